"""Repeated small rocking cycles, and what the macro-element's settlement under records is
sensitive to: the first of three measured causes of its error (issue 36 §3: it settles in every
small cycle of a record, ``MACRO_DIAGNOSIS.md``).

    python benchmarks/macro_small_cycles.py [--quick] [--out DIR] [--write]

**Cycles.** The continuum's rotation pushover of six full cycles at 2 θ_on (θ_on = 2N(1 − ν)/
(π G B); each cycle four steps to +2 θ_on, four to −2 θ_on and four back to 0) at N =
V_ult/FS_v, on the half-plane reference's soil and mesh (16 across), clay and sand, FS_v 3 and
5: points of the beds' continuum point function
(``evaluate_continuum``) in the kept store ``benchmarks/winkler_map_halfplane_store``, made
here when missing (on this process, 10 s to 2 minutes each). Their first cycle is the map's own
cyclic pushover's first cycle. Beside each, the macro-element on the same rotations at the same
N, as the map's statics rows push it over (the soil's stored fit, the point's K_v and K_r:
:func:`upliftlab.comparisons.beds.macro_bed.macro_rocking`). The table gives the settlement
(mm, down) at the end of each cycle, both models, and the last cycle's increment over the
first's: whether the footing shakes down and whether the element does. ``--quick``: the clay at
FS_v 5 on the map's own stored cyclic pushover (one cycle each at 2, 5 and 10 θ_on: its first
cycle only, nothing is run), the element beside it.

**Sensitivities under records.** The element's error against the continuum's stored runs on
the record points of the half-plane map's slice h/B 1.5, T 0.5 s at 1.5 a_up, FS_v 3 and 5
(El Centro and the ten FEMA P695 records; the points whose continuum run is compared, as the
map compares them), built and run as the map runs the element, then with one thing changed:
the coupling exponent ε at 1, 2 and 4 (the fit's other parameters kept; the fit put ε at 0 on
the clay and the sand's χ is 0, so it acts there on nothing), and a radiation dashpot density
from the continuum's impedance at the structure's rocking frequency added to the soil's β K_v/B
(:func:`upliftlab.comparisons.beds.dashpots.impedance_dashpots_of`, the dashpots of the map's
impedance beds): C_v/B (a uniform density with the impedance's vertical dashpot) or 12 C_r/B³
(with its rocking dashpot). These are diagnoses, not candidates: nothing here is fitted, and
no choice is made from them. Per soil and change: the median signed error in residual
settlement, the median absolute error in θ and the shares within 10 % in θ and uplift and
within 20 % in settlement. Not in ``--quick``.

Writes ``MACRO_SMALL_CYCLES.md`` to ``--out`` (default ``results/bench/macro_small_cycles``)
section by section; ``--write`` also the committed copy.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import copy
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, output_folder,  # noqa: E402
                          run_sections, say, write_text)

NAME = "macro_small_cycles"
STORE = HERE / "winkler_map_halfplane_store"
CELLS = [(soil, fs) for soil in ("clay", "sand") for fs in (3.0, 5.0)]
QUICK = [("clay", 5.0)]
CYCLES, AMPLITUDE = 6, 2.0
VARIANTS = ("map", "ε = 1", "ε = 2", "ε = 4", "+ C_v/B", "+ 12 C_r/B³")
BEST_BED = "end_stiffened_fitted_impedance"


def _inputs(soil: str, fs_values, record_points: bool):
    """(grid, options, statics, impedances, pushovers, store) of the slice h/B 1.5, T 0.5 s."""
    import upliftlab.comparisons.studies.winkler_map as wm
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies.winkler_map.maps import calibration_inputs

    grid = replace(wm.FULL_GRID, soils=(soil,), fs_v=tuple(fs_values), h_over_B=(1.5,),
                   periods=(0.5,), intensities=(1.5,), pulse_periods=(),
                   elcentro=record_points, fema_components=10 if record_points else 0)
    options = replace(wm.FULL_OPTIONS, reference="half_plane")
    store = Store(STORE)
    statics, impedances, pushovers = calibration_inputs(grid, options, ("macro", BEST_BED),
                                                        store)
    return grid, options, statics, impedances, pushovers, store


def _cycle_ends(theta: np.ndarray, settlement: np.ndarray, steps: int) -> list[float]:
    """The settlement at the path's start (θ = 0, under N) and at the end of each full cycle,
    ``steps`` steps a cycle."""
    return [float(settlement[k]) for k in range(0, theta.size, steps)]


def compute_cycles(soil: str, fs: float, quick: bool) -> dict:
    """The continuum's repeated cycles (stored; made when missing) and the element's."""
    from upliftlab.comparisons.beds import BASE_SCENE, base_table, bed_foundation
    from upliftlab.comparisons.beds.continuum_points import evaluate_continuum
    from upliftlab.comparisons.beds.macro_bed import macro_rocking
    from upliftlab.comparisons.beds.pushover import repeated_cycles
    from upliftlab.comparisons.framework.sweep import run_sweep
    from upliftlab.comparisons.studies.winkler_map.grid import STUDY
    from upliftlab.comparisons.studies.winkler_map.plan import point_key_of, reference, scene_of
    from upliftlab.comparisons.studies.winkler_map.points import point_table
    from upliftlab.comparisons.studies.winkler_map.rocking import rocking_points
    from upliftlab.scenes import load_scene

    grid, options, statics, impedances, pushovers, store = _inputs(soil, (fs,), False)
    st, base = statics[soil], base_table()
    N = st.V_ult / fs
    path_options = options if quick else repeated_cycles(options, AMPLITUDE, CYCLES)
    point = rocking_points(base, soil, N, path_options)[0]
    if quick:
        record = store.get(point_key_of(point, evaluate_continuum))
        if record is None:
            raise RuntimeError("the map's cyclic pushover is not in the kept store")
    else:
        with cf.ThreadPoolExecutor(1) as executor:
            record = run_sweep(evaluate_continuum, [point], store, study=STUDY,
                               executor=executor, chunk=1)[0]
    if "error" in record:
        raise RuntimeError(f"the continuum's path stopped: {record['error']}")
    g = load_scene(BASE_SCENE).g
    table = point_table(base, soil, options.elements_across, N, 1.5, 0.5, g, options.reference)
    ref = reference(st, scene_of(table), table["structure"], impedances.get(soil),
                    pushovers[soil, fs], options.bed_stiffness)
    theta = np.asarray(record["theta"], dtype=float)
    element = macro_rocking(N, bed_foundation("macro", ref, options), theta,
                            theta[:2])["cyclic"]
    steps = 3 * options.cycle_steps  # cyclic_path: n steps to +a, n to −a, n back to 0
    cycles = 1 if quick else CYCLES
    return {"continuum": _cycle_ends(theta, np.asarray(record["settlement"]), steps)[:cycles + 1],
            "element": _cycle_ends(theta, np.asarray(element["settlement"]), steps)[:cycles + 1],
            "N": N}


def _variant_table(foundation: dict, label: str, dashpots, B: float) -> tuple[dict, float]:
    """The element's ``[foundation]`` table of one variant and the dashpot density it adds."""
    table = copy.deepcopy(foundation)
    if label.startswith("ε"):
        table["coupling_exponent"] = float(label.split("=")[1])
    if label == "+ C_v/B":
        return table, dashpots.C_v / B
    if label == "+ 12 C_r/B³":
        return table, 12.0 * dashpots.C_r / B ** 3
    return table, 0.0


def compute_records(soil: str) -> list[dict]:
    """Every variant's errors at the slice's compared record points of ``soil``."""
    import upliftlab.comparisons.studies.winkler_map as wm
    from upliftlab.comparisons.beds import BASE_SCENE, base_table, bed_foundation
    from upliftlab.comparisons.beds.dashpots import impedance_dashpots_of
    from upliftlab.comparisons.framework.study import relative_error
    from upliftlab.comparisons.studies.winkler_map.bed_runs import (_resolved, bed_scene,
                                                                    element_analysis,
                                                                    reduced_measures)
    from upliftlab.comparisons.studies.winkler_map.grid import FLOOR_FRACTION
    from upliftlab.comparisons.studies.winkler_map.plan import (cells, dynamic_points,
                                                                point_key_of, reference,
                                                                scene_of)
    from upliftlab.comparisons.studies.winkler_map.points import (evaluate_dynamic, scales,
                                                                  story_constants)
    from upliftlab.reduced import IntegrationError, run
    from upliftlab.scenes import load_scene, scene_from_dict

    grid, options, statics, impedances, pushovers, store = _inputs(soil, (3.0, 5.0), True)
    st = statics[soil]
    motions = wm.study_motions(grid, options, Path("."))
    points = iter(dynamic_points(grid, options, motions, base_table(),
                                 load_scene(BASE_SCENE).g, {soil: st.V_ult}))
    rows, started, total, seen = [], time.perf_counter(), 2 * len(motions), 0
    for _, (_, fs, _, _, _) in cells(grid):
        for _ in motions:
            point = next(points)
            seen += 1
            elapsed = time.perf_counter() - started
            say(f"{NAME}: records, {soil}: point {seen}/{total}, {elapsed:.0f} s, about "
                f"{elapsed / max(seen - 1, 1) * (total - seen + 1):.0f} s left")
            record = store.get(point_key_of(point, evaluate_dynamic))
            if record is None or "error" in record or record.get("validity") == "beyond":
                continue
            ref = reference(st, scene_of(point["scene"]), point["scene"]["structure"],
                            impedances.get(soil), pushovers[soil, fs], options.bed_stiffness)
            scene = scene_of(point["scene"])
            k_story, _ = story_constants(scene)
            scl = scales(ref.N, scene.foundation.width, scene.structure.height, ref.K_v,
                         ref.K_r, k_story)
            foundation = bed_foundation("macro", ref, options)
            dashpots = impedance_dashpots_of(ref, options)
            errors = {}
            for label in VARIANTS:
                table, density = _variant_table(foundation, label, dashpots, ref.B)
                element = _resolved(bed_scene(point, table, element_analysis(options)))
                data = copy.deepcopy(element.data)
                unit = 2.0 * math.sqrt(element.foundation.stiffness
                                       * element.structure.vertical_weight / element.g) / ref.B
                data["foundation"]["damping_ratio"] = (data["foundation"].get("damping_ratio",
                                                                              0.0)
                                                       + density / unit)
                try:
                    measures = reduced_measures(run(scene_from_dict(data, merged=True)))
                except IntegrationError as exc:
                    errors[label] = {"refused": str(exc)}
                    continue
                errors[label] = {q: relative_error(measures[q], record["measures"][q],
                                                   FLOOR_FRACTION * scl[q])
                                 for q in ("theta", "uplift", "residual_settlement")}
            rows.append({"fs": fs, "errors": errors})
    return rows


def _cycles_lines(done: dict) -> list[str]:
    lines = ["## Cycles", "", "Settlement (mm, down) under N at the path's start and its "
             f"increase in each full cycle at {AMPLITUDE:g} θ_on; the last column is the last "
             "cycle's increase over the first's.", "",
             "| soil, FS_v | model | under N | " + " | ".join(f"cycle {i}" for i in
                                                          range(1, CYCLES + 1))
             + " | last/first |", "|---|---|---|" + "---|" * (CYCLES + 1)]
    for key, r in done.items():
        if not key.startswith("cycles"):
            continue
        for model in ("continuum", "element"):
            s = np.asarray(r[model])
            rise = np.diff(s)
            cells = ([f"{1e3 * s[0]:.3f}"] + [f"{1e3 * v:+.3f}" for v in rise]
                     + [""] * (CYCLES - rise.size))
            ratio = rise[-1] / rise[0] if rise.size > 1 and rise[0] else math.nan
            lines.append(f"| {key[len('cycles: '):]} | {model} | " + " | ".join(cells)
                         + f" | {ratio:.2f} |")
    return lines


def _records_lines(done: dict) -> list[str]:
    lines = ["", "## Sensitivities under records", "",
             "| soil | change | points | median signed settlement error | median abs. θ error "
             "| θ and uplift within 10 % | settlement within 20 % |",
             "|---|---|---|---|---|---|---|"]
    for key, rows in done.items():
        if not key.startswith("records"):
            continue
        soil = key.split(": ")[1]
        for label in VARIANTS:
            runs = [r["errors"][label] for r in rows if "refused" not in r["errors"][label]]
            if not runs:
                continue
            s = [e["residual_settlement"] for e in runs]
            th = [abs(e["theta"]) for e in runs]
            both = sum(1 for e in runs if abs(e["theta"]) <= 0.1 and abs(e["uplift"]) <= 0.1)
            within = sum(1 for v in s if abs(v) <= 0.2)
            lines.append(f"| {soil} | {label} | {len(runs)} | {np.median(s):+.0%} | "
                         f"{np.median(th):.0%} | {both} | {within} |")
    return lines


def publish(folder: Path, done: dict, missing: dict) -> None:
    lines = ["# Repeated small rocking cycles, and the macro-element's sensitivities under "
             "records", "", "Command `python benchmarks/macro_small_cycles.py`; what is run: "
             "the script's docstring.", ""]
    lines += _cycles_lines(done) + _records_lines(done)
    if missing:
        lines += ["", "Not measured: " + "; ".join(f"{k}: {v}" for k, v in missing.items())]
    write_text(folder / "MACRO_SMALL_CYCLES.md", "\n".join(lines) + "\n")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--quick", action="store_true", help="one stored cycle (docstring)")
    args = parser.parse_args(argv)
    folder = output_folder(args, NAME)
    sections = [Section(f"cycles: {soil}, {fs:g}",
                        (lambda soil=soil, fs=fs: compute_cycles(soil, fs, args.quick)),
                        10.0 if args.quick else 60.0)
                for soil, fs in (QUICK if args.quick else CELLS)]
    if not args.quick:
        sections += [Section(f"records: {soil}", (lambda soil=soil: compute_records(soil)),
                             250.0) for soil in ("clay", "sand")]

    def commit(done):
        write_text(HERE / "MACRO_SMALL_CYCLES.md", (folder / "MACRO_SMALL_CYCLES.md").read_text())

    return run_sections(NAME, sections, publish, folder,
                        commit=commit if args.write else None,
                        model="a continuum cycle pushover about 1 min when not stored, an "
                              "element record run about 1 s")


if __name__ == "__main__":
    raise SystemExit(main())
