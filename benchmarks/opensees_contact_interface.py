"""What a user of OpenSees gets: Gajan and Kutter's contact interface model beside upliftlab's
macro-element and the map's best bed, on pulse points of the half-plane map (issue 36 §4).

    python benchmarks/opensees_contact_interface.py --opensees TREE [--quick] [--out DIR]
                                                    [--write]

``--opensees``: an OpenSees source tree (a clone of github.com/OpenSees/OpenSees; the
commit is written with the table). Its ``soilFootingSection2d`` is compiled and driven by the
model that ``upliftlab opensees`` writes for Tcl OpenSees (:mod:`contact_interface`: the
section's own C++, OpenSees's order of calls; openseespy has no such section).

The points: the half-plane map's slice h/B 1.5, T 0.5 s, clay and sand, FS_v 3, 5 and 10, both
Ricker pulses (0.25 and 0.6 s) at 1.5 and 3 times the uplift acceleration (24 points;
``--quick``: clay, FS_v 5, the 0.6 s pulse at 1.5 a_up). At each, from the kept store
``benchmarks/winkler_map_halfplane_store`` (nothing of the continuum is run here):

- the **continuum**'s stored run (its measures);
- **ES-f-I**, the map's best bed, and the **macro-element** (the soil's stored fit), each run as
  the map runs it (:func:`~upliftlab.comparisons.studies.winkler_map.bed_runs.run_bed`);
- the **contact interface model** (CIM) on the numbers that ``upliftlab opensees`` writes for
  the macro-element's scene of the point (:func:`upliftlab.comparisons.opensees.tcl.
  tcl_numbers`: FS, V_ult, L = B, Kv = 12 K_r/L² (the section's rocking at its uplift onset
  the element's K_r), K_h of the element, R_v = 0.1, dL = L/40, the tie's sway dashpot, the
  structure and the motion at the element's step of 0.25 ms), and again with Kv = K_v (the
  section's vertical stiffness the element's, its rocking then a uniform bed's, 0.21 K_r on
  these points), measured as the map measures a bed:
  peak |θ|, the larger gap under its edges (the section's own footing and soil surface),
  the settlement from its static position when the footing is flattest in the last quarter,
  peak story deformation and story shear.

Errors are the map's, (model − continuum)/max(|continuum|, floor) with the map's floors. The
table gives each point's errors and, per soil and together, the share of the compared points
within 10 % in both peak θ and edge uplift, within 20 % in residual settlement and 10 % in peak
u, and the median absolute errors; points where the continuum failed in bearing or ran beyond
small strain are listed and not compared (as the map does). A run of the section that stops
(a step that does not converge in 50 Newton iterations, as the Tcl script stops) is counted as
such. Then the section alone (:func:`section_checks`), one ulp of its Kv, and its Rv at 0.1,
0.5 and 1 at one point (:func:`rebound`).

Cost: about 3 s a point (the section's two runs and the two beds'), about
65 s in all on this machine (``--quick`` about 10 s). Writes ``OPENSEES_CONTACT_INTERFACE.md``
to ``--out`` (default ``results/bench/opensees_contact_interface``); ``--write`` also the
committed copy.
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import HERE, add_output_arguments, output_folder, write_text  # noqa: E402
from contact_interface import (ContactInterfaceError, compile_section,  # noqa: E402
                               rotation_pushover, run_numbers)

NAME = "opensees_contact_interface"
STORE = HERE / "winkler_map_halfplane_store"
FS_V = (3.0, 5.0, 10.0)
MODELS = ("ES-f-I", "macro", "CIM, Kv = K_v", "CIM, Kv = 12 K_r/L²")
#: The map's name of ES-f-I, its best bed.
BEST_BED = "end_stiffened_fitted_impedance"
_WARMED: set[str] = set()
SHOWN = ("theta", "uplift", "residual_settlement", "u")


def _slice(soil: str, quick: bool):
    """(grid, options, points with their (fs, intensity, motion name), bed references)."""
    import upliftlab.comparisons.studies.winkler_map as wm
    from upliftlab.comparisons.beds import BASE_SCENE, base_table
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies.winkler_map.maps import calibration_inputs
    from upliftlab.comparisons.studies.winkler_map.plan import (cells, dynamic_points,
                                                                reference, scene_of)
    from upliftlab.scenes import load_scene

    grid = replace(wm.FULL_GRID, soils=(soil,), fs_v=(5.0,) if quick else FS_V,
                   h_over_B=(1.5,), periods=(0.5,), intensities=(1.5,) if quick else (1.5, 3.0),
                   pulse_periods=(0.6,) if quick else (0.25, 0.6), elcentro=False,
                   fema_components=0)
    options = replace(wm.FULL_OPTIONS, reference="half_plane")
    store = Store(STORE)
    statics, impedances, pushovers = calibration_inputs(grid, options, ("macro", BEST_BED),
                                                        store)
    st = statics[soil]
    motions = wm.study_motions(grid, options, Path("."))
    points = dynamic_points(grid, options, motions, base_table(), load_scene(BASE_SCENE).g,
                            {soil: st.V_ult})
    rows, it = [], iter(points)
    for _, (_, fs, _, _, intensity) in cells(grid):
        for motion in motions:
            point = next(it)
            ref = reference(st, scene_of(point["scene"]), point["scene"]["structure"],
                            impedances.get(soil), pushovers[soil, fs], options.bed_stiffness)
            rows.append({"soil": soil, "fs": fs, "intensity": intensity,
                         "motion": motion["name"], "point": point, "ref": ref,
                         "options": options, "store": store})
    return rows


def _section_measures(library: Path, scene, numbers: dict) -> dict:
    """The section's run of the element's ``scene`` measured as the map measures a bed."""
    from upliftlab.comparisons.framework.measures import peak_story_shear
    from upliftlab.comparisons.studies.winkler_map.points import measured

    accel = np.asarray(scene.build_motion().acceleration, dtype=float)
    started = time.perf_counter()
    h = run_numbers(library, numbers, accel)
    wall = time.perf_counter() - started
    if "failed_at" in h:
        return {"stopped": f"step at t = {h['failed_at']:.3f} s did not converge", "wall": wall}
    settlement = -(h["v"] - h["static"][1])
    uplift = float(np.max(np.maximum(h["gap_left"], h["gap_right"])))
    k = numbers["story_stiffness"]
    shear = peak_story_shear(h["s"], h["s_rate"], k, numbers["story_damping_beta"] * k)
    return {"measures": measured(h["t"], h["theta"], uplift, settlement,
                                 float(np.max(np.abs(h["s"]))), shear), "wall": wall}


def _ulp_numbers(row: dict) -> list[dict]:
    from upliftlab.reduced import build_model

    numbers = done_numbers(row)
    scene = _element_scene(row)
    K_v = float(build_model(scene).base.law.vertical_stiffness)
    return [{**numbers, "Kv": K_v}, {**numbers, "Kv": float(np.nextafter(K_v, 0.0))}]


def _outcome(library: Path, row: dict, numbers: dict) -> str:
    try:
        run = _section_measures(library, _element_scene(row), numbers)
    except ContactInterfaceError as exc:
        return str(exc)
    if "stopped" in run:
        return run["stopped"]
    return f"peak θ {run['measures']['theta']:.4g} rad"


def compute_point(row: dict, library: Path) -> dict:
    """The continuum's stored run and the three models' runs of one point (module docstring)."""
    from upliftlab.comparisons.beds import bed_foundation
    from upliftlab.comparisons.framework.study import relative_error
    from upliftlab.comparisons.opensees.tcl import tcl_numbers
    from upliftlab.comparisons.studies.winkler_map.bed_runs import (element_analysis, run_bed)
    from upliftlab.reduced import build_model
    from upliftlab.comparisons.studies.winkler_map.grid import FLOOR_FRACTION
    from upliftlab.comparisons.studies.winkler_map.plan import point_key_of, scene_of
    from upliftlab.comparisons.studies.winkler_map.points import (evaluate_dynamic, scales,
                                                                  story_constants)

    point, ref, options = row["point"], row["ref"], row["options"]
    record = row["store"].get(point_key_of(point, evaluate_dynamic))
    if record is None:
        return {"skipped": "not in the store"}
    if row.get("ulp"):  # the section's sensitivity: Kv = K_v and one ulp below it
        return {"ulp": [_outcome(library, row, n) for n in _ulp_numbers(row)]}
    if "error" in record:
        return {"skipped": "bearing failure" if record.get("failure") == "bearing"
                else record["error"][:60]}
    if record.get("validity") == "beyond":
        return {"skipped": "beyond the small-strain reference"}
    scene = scene_of(point["scene"])
    k_story, _ = story_constants(scene)
    scl = scales(ref.N, scene.foundation.width, scene.structure.height, ref.K_v, ref.K_r,
                 k_story)
    runs = {}
    for name, bed_name in (("ES-f-I", BEST_BED), ("macro", "macro")):
        foundation = bed_foundation(bed_name, ref, options)
        analysis = element_analysis(options) if name == "macro" else None
        if name not in _WARMED:  # the first run compiles the kernels: not timed
            run_bed(point, foundation, analysis)
            _WARMED.add(name)
        bed = run_bed(point, foundation, analysis)
        runs[name] = ({"stopped": bed["refused"]} if "refused" in bed else
                      {"measures": bed["measures"], "wall": bed["wall_time_s"]})
    element_scene = _element_scene(row)
    numbers = tcl_numbers(element_scene)  # Kv = 12 K_r/L², as written for Tcl OpenSees
    law = build_model(element_scene).base.law
    vertical = {**numbers, "Kv": float(law.vertical_stiffness)}  # the element's own K_v
    for name, n in ((MODELS[2], vertical), (MODELS[3], numbers)):
        try:
            runs[name] = _section_measures(library, element_scene, n)
        except ContactInterfaceError as exc:
            runs[name] = {"stopped": str(exc), "wall": math.nan}
    continuum = record["measures"]
    for run in runs.values():
        if "measures" in run:
            run["errors"] = {q: relative_error(run["measures"][q], continuum[q],
                                               FLOOR_FRACTION * scl[q]) for q in SHOWN}
    return {"continuum": continuum, "runs": runs}


def section_checks(library: Path, numbers: dict) -> list[dict]:
    """The section alone at each FS_v of the map (its numbers ``numbers`` otherwise): its
    largest moment in a rotation pushover to 100 θ_on at constant V (θ_on = 2 V/(Kv L), 200
    geometric steps from θ_on/100) over V L/2, beside Tresca's 1 − V/Vult and the frictional
    soil's 1 − √(V/Vult) (closed forms of the effective-width rule); its secant M/θ at
    θ_on/100, θ_on/10 and θ_on over a uniform bed's Kv L²/12; the V–θ and M–v entries of its
    tangent at the first θ; the largest entry of its initial tangent."""
    out = []
    for fs in FS_V:
        n = {**numbers, "FS": fs}
        V = n["Vult"] / fs
        theta_on = 2.0 * V / (n["Kv"] * n["L"])
        thetas = theta_on * np.geomspace(0.01, 100.0, 201)
        r = rotation_pushover(library, n, thetas)
        bed = n["Kv"] * n["L"] ** 2 / 12.0
        out.append({"fs": fs, "capacity": float(np.max(r["M"]) / (V * n["L"] / 2)),
                    "tresca": 1.0 - 1.0 / fs, "frictional": 1.0 - 1.0 / math.sqrt(fs),
                    "secant": [float(r["M"][i] / thetas[i] / bed) for i in (0, 50, 100)],
                    "k_v_theta": float(r["tangent"][0, 2]), "k_m_v": float(r["tangent"][2, 0]),
                    "initial": float(np.max(np.abs(r["initial_tangent"])))})
    return out


def compute(args) -> dict:
    library = compile_section(Path(args.opensees), output_folder(args, NAME) / "build")
    commit = subprocess.run(["git", "-C", str(args.opensees), "rev-parse", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    rows = [r for soil in (("clay",) if args.quick else ("clay", "sand"))
            for r in _slice(soil, args.quick)]
    print(f"{NAME}: {len(rows)} points, each the continuum's stored run and four live runs "
          f"(about 3 s a point here): about {3 * len(rows) + 10} s", file=sys.stderr,
          flush=True)
    done = []
    started = time.perf_counter()
    for i, row in enumerate(rows, 1):
        done.append({**{k: row[k] for k in ("soil", "fs", "intensity", "motion")},
                     **compute_point(row, library)})
        left = (time.perf_counter() - started) / i * (len(rows) - i)
        print(f"{NAME}: {i}/{len(rows)} points, {time.perf_counter() - started:.0f} s, "
              f"about {left:.0f} s left", file=sys.stderr, flush=True)
    checks = section_checks(library, done_numbers(rows[0]))
    ulp = compute_point({**rows[0], "ulp": True}, library)["ulp"]
    return {"rows": done, "commit": commit, "checks": checks, "ulp": ulp,
            "rebound": rebound(library, rows[min(1, len(rows) - 1)])}


#: The section's Rv (the share of its soil's compression that rebounds) tried beside the
#: bridge's :data:`~upliftlab.comparisons.opensees.tcl.REBOUND`.
REBOUNDS = (0.1, 0.5, 1.0)


def rebound(library: Path, row: dict) -> dict:
    """The section's residual settlement (m) at one point with each of :data:`REBOUNDS` (or
    why its run stopped), and the continuum's."""
    from upliftlab.comparisons.studies.winkler_map.plan import point_key_of
    from upliftlab.comparisons.studies.winkler_map.points import evaluate_dynamic

    scene, numbers = _element_scene(row), done_numbers(row)
    out = {}
    for rv in REBOUNDS:
        run = _section_measures(library, scene, {**numbers, "Rv": rv})
        out[rv] = run.get("stopped") or run["measures"]["residual_settlement"]
    record = row["store"].get(point_key_of(row["point"], evaluate_dynamic))
    where = f"{row['soil']}, FS_v {row['fs']:g}, {row['intensity']:g} a_up, {row['motion']}"
    return {"where": where, "section": out,
            "continuum": record["measures"]["residual_settlement"]}


def _element_scene(row: dict):
    """The macro-element's scene of ``row`` as the map runs it."""
    from upliftlab.comparisons.beds import bed_foundation
    from upliftlab.comparisons.studies.winkler_map.bed_runs import (_resolved, bed_scene,
                                                                    element_analysis)

    foundation = bed_foundation("macro", row["ref"], row["options"])
    return _resolved(bed_scene(row["point"], foundation, element_analysis(row["options"])))


def done_numbers(row: dict) -> dict:
    """The numbers ``upliftlab opensees`` writes for the macro-element's scene of ``row``."""
    from upliftlab.comparisons.opensees.tcl import tcl_numbers

    return tcl_numbers(_element_scene(row))


def _pct(x: float) -> str:
    return "—" if not np.isfinite(x) else f"{100 * x:+.0f}%"


def _summary(rows: list, soil: str | None) -> list[str]:
    chosen = [r for r in rows if "runs" in r and (soil is None or r["soil"] == soil)]
    out = []
    for name in MODELS:
        runs = [r["runs"][name] for r in chosen]
        errs = [r["errors"] for r in runs if "errors" in r]
        n, stopped = len(runs), sum(1 for r in runs if "stopped" in r)
        if not n:
            continue

        def share(ok):
            return f"{sum(1 for e in errs if ok(e))}/{n}"
        med = [np.median([abs(e[q]) for e in errs]) if errs else math.nan for q in SHOWN]
        out.append(f"| {soil or 'both'} | {name} | "
                   f"{share(lambda e: abs(e['theta']) <= .1 and abs(e['uplift']) <= .1)} | "
                   f"{share(lambda e: abs(e['residual_settlement']) <= .2)} | "
                   f"{share(lambda e: abs(e['u']) <= .1)} | {stopped} | "
                   + " / ".join(f"{100 * m:.0f}%" for m in med) + " |")
    return out


def publish(folder: Path, result: dict, write: bool) -> None:
    rows = result["rows"]
    lines = ["# What a user of OpenSees gets: the contact interface model beside the "
             "macro-element and ES-f-I", "",
             f"Command `python benchmarks/{NAME}.py --opensees TREE`; OpenSees commit "
             f"`{result['commit']}`; what is run and measured: the script's docstring. Errors "
             "against the half-plane continuum's stored runs (the map's relative errors and "
             "floors).", "", "## Shares of the compared points", "",
             "| soil | model | θ and uplift within 10 % | settlement within 20 % | u within "
             "10 % | runs stopped | median abs. error θ / uplift / settlement / u |",
             "|---|---|---|---|---|---|---|"]
    for soil in ("clay", "sand", None):
        lines += _summary(rows, soil)
    lines += ["", "## Per point", "", "Errors in peak θ / edge uplift / residual settlement / "
              "peak u.", "", "| soil | FS_v | a/a_up | motion | " + " | ".join(MODELS) + " |",
              "|---|---|---|---|" + "---|" * len(MODELS)]
    for r in rows:
        head = f"| {r['soil']} | {r['fs']:g} | {r['intensity']:g} | {r['motion']} | "
        if "skipped" in r:
            lines.append(head + f"not compared: {r['skipped']} |" + " |" * (len(MODELS) - 1))
            continue
        cells = []
        for name in MODELS:
            run = r["runs"][name]
            cells.append(run["stopped"] if "stopped" in run else
                         " / ".join(_pct(run["errors"][q]) for q in SHOWN))
        lines.append(head + " | ".join(cells) + " |")
    c = result["checks"]
    lines += ["", "## The section alone", "", "At the numbers written for the first point "
              "(its Kv = 12 K_r/L²), at each FS_v: the largest moment of a rotation pushover at "
              "constant V to 100 θ_on over V L/2, beside the closed forms of the effective-width "
              "rule; the secant M/θ over a uniform bed's Kv L²/12 at θ_on/100, θ_on/10 and θ_on; "
              "the tangent's V–θ and M–v entries at θ_on/100; the largest entry of its initial "
              "tangent.", "",
              "| FS_v | M_max/(V L/2) | Tresca 1 − 1/FS_v | frictional 1 − 1/√FS_v | secant at "
              "θ_on/100, θ_on/10, θ_on | ∂V/∂θ | ∂M/∂v | initial tangent, largest |",
              "|---|---|---|---|---|---|---|---|"]
    for r in c:
        lines.append(f"| {r['fs']:g} | {r['capacity']:.3f} | {r['tresca']:.3f} | "
                     f"{r['frictional']:.3f} | "
                     + ", ".join(f"{x:.2f}" for x in r["secant"])
                     + f" | {r['k_v_theta']:.4g} | {r['k_m_v']:.4g} | {r['initial']:.3g} |")
    first = rows[0]
    lines += ["", f"One ulp of Kv (the first point, {first['soil']}, FS_v {first['fs']:g}, "
              f"{first['intensity']:g} a_up, {first['motion']}, Kv = K_v): with K_v, "
              f"{result['ulp'][0]}; with the next float below it, {result['ulp'][1]}."]
    rb = result["rebound"]
    cells = [f"Rv = {rv:g}: " + (f"{1e3 * v:.2f} mm" if isinstance(v, float) else v)
             for rv, v in rb["section"].items()]
    lines += ["", f"The section's Rv ({rb['where']}): residual settlement " + "; ".join(cells)
              + f" (the continuum's {1e3 * rb['continuum']:.2f} mm)."]
    text = "\n".join(lines) + "\n"
    write_text(folder / "OPENSEES_CONTACT_INTERFACE.md", text)
    if write:
        write_text(HERE / "OPENSEES_CONTACT_INTERFACE.md", text)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--opensees", required=True, help="an OpenSees source tree")
    parser.add_argument("--quick", action="store_true")
    add_output_arguments(parser, NAME)
    args = parser.parse_args()
    result = compute(args)
    publish(output_folder(args, NAME), result, args.write)


if __name__ == "__main__":
    main()
