"""Where the macro-element's settlement departs from the continuum's on the half-plane map,
and what one of its runs costs against the continuum's, both timed in this process (issue 36
§1 and §3).

    python benchmarks/macro_diagnosis.py [--quick] [--out DIR] [--write]

The points: pulse points of the half-plane map's slice h/B 1.5, T 0.5 s (clay and sand, FS_v
3 and 5, the Ricker pulse of 0.6 s at 1.5 and 3 times the uplift acceleration; ``--quick``:
clay, FS_v 3, 1.5 a_up only). At each, built exactly as the map builds them from the kept
store ``benchmarks/winkler_map_halfplane_store`` (its statics, rotation pushovers and the
soil's macro-element fit; nothing is fitted here):

- the **continuum**, run live in this process (explicit route, 16 across, kernels compiled
  before the clock starts, as the map's own runs are timed), with its settlement history;
- the **macro-element** as the map runs it (Newmark at 0.25 ms, the fit's law, the point's K_v
  and K_r, the tie's sway spring, the soil's β K_v), with its settlement history; then the
  same run at the scene's coarsest sub-step (``force_step`` 0.1 of the weight: about one
  sub-step an iteration), the floor of what the element's update costs at this time step;
- the element without revision 3's memory (μ = 0: the interior modulus no longer grows with the
  largest mobilisation a side has carried; revision 2's law with revision 3's other parameters),
  and the element with revision 1's flow (δ = 1, ε = 0: associated in V, the coupling alike
  inside the surface and on it) and the fit's other parameters;
- three variants of the element that each remove one way it can settle: no settlement
  coupling (χ = 0: no settlement from flow in rotation or sway), a horizontal capacity 5.1
  times the fit's (the sliding ratio t_h at the scene's largest, 4, from the fit's 0.778: the
  base shear nearly out of the failure surface and its flow), and a stiffer interior
  (h0 × 100: the small cycles inside the bounding surface nearly elastic); and one more that
  keeps the soil's surface flat (λ_ρ = 0: no rounding under the edges). A variant that the
  reduced model's own checks refuse (its energy balance, its plastic work) is reported as
  refused, with the check's words; the map's own run is never excused.

The table gives, per point, the residual settlement (the map's measure: the settlement when
the footing is flattest) of each, and the same measure taken in the period after the pulse's
end (:func:`at_pulse_end`) as a share of the residual, which says whether the extra settlement
comes with the strong cycles or after them; then both models' wall times and their ratio,
measured in one run. Nothing here is tuned: the variants are diagnoses, not candidates.

Cost model: a continuum pulse run about 20 s on this machine (the store's median for these
points, 11 s, on an idle machine), an element run about 1.2 s at 0.25 ms; the whole about 5 min
(``--quick`` 30 s), and the element's update alone, timed on its own (5 s). Writes
``MACRO_DIAGNOSIS.md`` to ``--out`` (default
``results/bench/macro_diagnosis``); ``--write`` also the committed copy in ``benchmarks/``.
"""

from __future__ import annotations

import argparse
import copy
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, output_folder,  # noqa: E402
                          run_sections, write_text)

NAME = "macro_diagnosis"
STORE = HERE / "winkler_map_halfplane_store"
POINTS = [(soil, fs, intensity) for soil in ("clay", "sand") for fs in (3.0, 5.0)
          for intensity in (1.5, 3.0)]
QUICK = [("clay", 3.0, 1.5)]
PULSE = 0.6  # s, the map's longer Ricker pulse
VARIANTS = {"map": {}, "μ = 0": {"memory_modulus": 0.0},
            "δ = 1, ε = 0": {"flow_dilatancy": 1.0, "coupling_exponent": 0.0},
            "χ = 0": {"settlement_coupling": 0.0},
            "t_h = 4": {"sliding_ratio": 4.0}, "h0 × 100": {"interior_modulus": 100.0},
            "λ_ρ = 0": {"rounding_ratio": 0.0}}
#: Variants that multiply a key of the element's table rather than set it.
SCALED = {"interior_modulus"}
_WARM: list = []


def _map_inputs(soil: str, fs: float, intensity: float) -> tuple:
    """(the map's dynamic point, its bed reference, the map's options) at one coordinate of the
    slice."""
    import upliftlab.comparisons.studies.winkler_map as wm
    from upliftlab.comparisons.beds import BASE_SCENE, base_table
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies.winkler_map.maps import calibration_inputs
    from upliftlab.comparisons.studies.winkler_map.plan import (dynamic_points, reference,
                                                                scene_of)
    from upliftlab.scenes import load_scene

    grid = replace(wm.FULL_GRID, soils=(soil,), fs_v=(fs,), h_over_B=(1.5,), periods=(0.5,),
                   intensities=(intensity,), pulse_periods=(PULSE,), elcentro=False,
                   fema_components=0)
    options = replace(wm.FULL_OPTIONS, reference="half_plane")
    statics, impedances, pushovers = calibration_inputs(grid, options, ("macro",),
                                                        Store(STORE))
    st = statics[soil]
    motions = wm.study_motions(grid, options, Path("."))
    point = dynamic_points(grid, options, motions, base_table(), load_scene(BASE_SCENE).g,
                           {soil: st.V_ult})[0]
    ref = reference(st, scene_of(point["scene"]), point["scene"]["structure"],
                    impedances.get(soil), pushovers[soil, fs], options.bed_stiffness)
    return point, ref, options


def _continuum(point: dict) -> dict:
    """The continuum's run of ``point`` as the map makes it: measures, settlement history,
    wall time (kernels compiled before)."""
    from upliftlab.comparisons.studies.winkler_map.points import (_timed_run, _warm_kernels,
                                                                  continuum_measures,
                                                                  point_scene)

    _warm_kernels(point)
    scene = point_scene(point)
    _, result, wall = _timed_run(scene)
    t, theta, settlement, *_, measures = continuum_measures(scene, result)
    return {"t": t, "theta": theta, "settlement": settlement, "measures": measures,
            "wall": wall}


def _element(point: dict, foundation: dict, options, force_step: float | None = None) -> dict:
    """The element's run of ``point`` on the map's integrator and step (``force_step``: the
    element's sub-step, of the weight; None: the scene's default)."""
    from upliftlab.comparisons.studies.winkler_map.bed_runs import (_resolved, bed_scene,
                                                                    element_analysis,
                                                                    reduced_measures)
    from upliftlab.reduced import run

    table = dict(foundation) if force_step is None else {**foundation, "force_step": force_step}
    scene = _resolved(bed_scene(point, table, element_analysis(options)))
    if not _WARM:  # the reduced model's kernels compiled (or loaded) before the clock starts
        run(scene)
        _WARM.append(True)
    started = time.perf_counter()
    response = run(scene)
    wall = time.perf_counter() - started
    t = np.asarray(response.time, dtype=float)
    return {"t": t - t[0], "theta": np.asarray(response.theta, dtype=float),
            "settlement": np.asarray(response.settlement, dtype=float),
            "measures": reduced_measures(response), "wall": wall,
            "plastic_settlement": np.asarray(response.base[:, 3], dtype=float),
            "plastic_rotation": np.asarray(response.base[:, 5], dtype=float),
            "moment": np.asarray(response.base[:, 2], dtype=float),
            "vertical": np.asarray(response.base[:, 0], dtype=float),
            "width": 2.0 * scene.foundation.half_width,
            "steps": int(response.info["steps"])}


def at_pulse_end(run: dict) -> float:
    """The settlement (m) after the pulse, where the footing is flattest in the period that
    follows its end (its centre, 1.5 periods in (:func:`upliftlab.motions.ricker_pulse`'s
    delay), plus one period): the map's residual measure taken then, not at the run's end."""
    window = np.flatnonzero((run["t"] >= 2.5 * PULSE) & (run["t"] <= 3.5 * PULSE))
    flat = window[int(np.argmin(np.abs(run["theta"][window])))]
    return float(run["settlement"][flat])


def compute_point(soil: str, fs: float, intensity: float) -> dict:
    """Every run of one point (module docstring)."""
    from upliftlab.comparisons.beds import bed_foundation
    from upliftlab.reduced import IntegrationError

    point, ref, options = _map_inputs(soil, fs, intensity)
    foundation = bed_foundation("macro", ref, options)
    runs, refused = {"continuum": _continuum(point)}, {}
    for label, change in VARIANTS.items():
        table = copy.deepcopy(foundation)
        for key, value in change.items():
            table[key] = table[key] * value if key in SCALED else value
        try:
            runs[label] = _element(point, table, options)
        except IntegrationError as error:  # a variant's own check refused it: say so
            if label == "map":
                raise
            refused[label] = str(error).split(": ", 1)[-1].split(" (")[0]
    runs["coarsest sub-step"] = _element(point, foundation, options, force_step=0.1)
    return {"runs": runs, "refused": refused}


def update_cost(repeats: int = 20_000) -> float:
    """The element's update alone (µs a sub-step): the clay's fitted law (the store's fit)
    stepped along a random walk of the footing that loads it to its capacity, in this process,
    compiled, median of three."""
    from upliftlab.comparisons.beds import bed_foundation
    from upliftlab.comparisons.beds.macro_bed import element_of
    from upliftlab.reduced.laws.macro import at_rest, compiled as cc

    _, ref, options = _map_inputs("clay", 3.0, 1.5)

    law = element_of(bed_foundation("macro", ref, options), ref.N)
    P, D, W = cc.pack(law), np.empty((3, 3)), np.empty(cc.W_COUNT)
    start = at_rest(law, ref.N)
    v0 = start.displacement[0]
    rng = np.random.default_rng(1)
    walk = np.cumsum(rng.normal(0, 1, (200, 3)) * [0.3 * v0, 0.5 * v0, 0.6 * v0 / law.width],
                     axis=0) + [v0, 0, 0]
    count = max(1, repeats // walk.shape[0])
    times = []
    for _ in range(3):
        S = start.packed()
        began = time.perf_counter()
        for d in walk:
            if cc.step_into(P, S, d, 1.0, count, D, W) != cc.STEP_OK:
                raise RuntimeError("the random walk left the element's range")
        times.append((time.perf_counter() - began) / (count * walk.shape[0]))
    return 1e6 * float(np.median(times))


def _label(key: tuple) -> str:
    soil, fs, intensity = key
    return f"{soil}, FS_v {fs:g}, {intensity:g} a_up"


def _settlement_table(points: dict) -> list[str]:
    lines = ["## Residual settlement", "",
             "| point | continuum | element (map) | at the pulse's end: continuum | element | "
             + " | ".join(f"element, {v}" for v in list(VARIANTS)[1:]) + " |",
             "|" + "---|" * (5 + len(VARIANTS) - 1)]
    for key, r in points.items():
        runs = r["runs"]
        res = {k: v["measures"]["residual_settlement"] for k, v in runs.items()}
        c, e = res["continuum"], res["map"]
        cells = [key, f"{1e3 * c:.2f}", f"{1e3 * e:.2f} ({e / c - 1:+.0%})",
                 f"{at_pulse_end(runs['continuum']) / c:.0%}",
                 f"{at_pulse_end(runs['map']) / e:.0%}"]
        cells += [f"{1e3 * res[v]:.2f} ({res[v] / c - 1:+.0%})" if v in res
                  else f"refused ({r['refused'][v]})" for v in list(VARIANTS)[1:]]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _accrual_table(points: dict) -> list[str]:
    lines = ["## Where the element's plastic settlement accrues", "",
             "The element's plastic settlement v_p (mm, down; the map's run, at its recorded "
             "steps): at the pulse's end (its centre plus one period), at the run's end, and "
             "the sums of its downward and upward changes.", "",
             "| point | v_p at the pulse's end | v_p at the end | down | up |",
             "|---|---|---|---|---|"]
    for key, r in points.items():
        e = r["runs"]["map"]
        vp = e["plastic_settlement"]
        change = np.diff(vp)
        end = float(np.interp(2.5 * PULSE, e["t"], vp))
        lines.append(f"| {key} | {1e3 * end:.2f} | {1e3 * vp[-1]:.2f} | "
                     f"{1e3 * change[change > 0].sum():.2f} | "
                     f"{1e3 * change[change < 0].sum():.2f} |")
    return lines


def _rotation_table(points: dict) -> list[str]:
    lines = ["## Residual rotation", "",
             "The tilt left at the end (mrad, the map's measure: θ's mean over the run's last "
             "quarter) of both models, and the element's plastic rotation θ_p and its moment "
             "M/(V B) at the step where the map reads the residual settlement (the flattest "
             "of the last quarter): a tilt that the element keeps and the continuum does not "
             "is swung back there against the element's moment, which lifts its centre.", "",
             "| point | continuum | element | element's θ_p when flattest | its M/(V B) then |",
             "|---|---|---|---|---|"]
    from upliftlab.comparisons.framework.measures import settlement_when_flattest as flattest

    for key, r in points.items():
        c, e = r["runs"]["continuum"], r["runs"]["map"]
        theta_p, M, V = (flattest(e["t"], e["theta"], e[name])
                         for name in ("plastic_rotation", "moment", "vertical"))
        lines.append(f"| {key} | {1e3 * c['measures']['residual_rotation']:.2f} | "
                     f"{1e3 * e['measures']['residual_rotation']:.2f} | "
                     f"{1e3 * theta_p:.2f} | {M / (V * e['width']):+.3f} |")
    return lines


def _cost_table(points: dict, update: float | None) -> list[str]:
    lines = ["## Cost, both models timed in this process", "",
             "| point | continuum (s) | element (s) | ratio | element at the coarsest "
             "sub-step (s) | ratio | its θ error | its settlement error | element steps |",
             "|---|---|---|---|---|---|---|---|---|"]
    for key, r in points.items():
        runs = r["runs"]
        c, e, f = runs["continuum"], runs["map"], runs["coarsest sub-step"]
        em, fm = e["measures"], f["measures"]
        lines.append(f"| {key} | {c['wall']:.1f} | {e['wall']:.3f} | "
                     f"{c['wall'] / e['wall']:.0f}× | {f['wall']:.3f} | "
                     f"{c['wall'] / f['wall']:.0f}× | {fm['theta'] / em['theta'] - 1:+.1%} | "
                     f"{fm['residual_settlement'] / em['residual_settlement'] - 1:+.1%} | "
                     f"{e['steps']} |")
    if update is not None and points:
        slowest = max(r["runs"]["coarsest sub-step"]["wall"] / r["runs"]["map"]["steps"]
                      for r in points.values())
        lines += ["", f"The element's update alone: {update:.2f} µs a sub-step (the "
                  "clay's law, a random walk to its capacity). The coarsest sub-step's run "
                  f"costs up to {1e6 * slowest:.0f} µs a time step (Newton's iterations, the "
                  "structure, the outputs)."]
    return lines


def publish(folder: Path, done: dict, missing: dict) -> None:
    points = {k: r for k, r in done.items() if k != "update"}
    lines = ["# Where the macro-element's settlement departs from the continuum's, and what its "
             "run costs",
             "", "Command `python benchmarks/macro_diagnosis.py`; what is run: the script's "
             "docstring. Settlements in mm (down); \"at the pulse's end\" is the share of the "
             "residual settlement already there one period after the pulse (the footing's "
             "settlement when flattest in the period after the pulse's centre plus one "
             "period).", ""]
    for table in (_settlement_table, _accrual_table, _rotation_table):
        lines += table(points) + [""]
    lines += _cost_table(points, done.get("update"))
    if missing:
        lines += ["", "Not measured: " + "; ".join(f"{k}: {v}" for k, v in missing.items())]
    write_text(folder / "MACRO_DIAGNOSIS.md", "\n".join(lines) + "\n")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--quick", action="store_true", help="one point (docstring)")
    args = parser.parse_args(argv)
    folder = output_folder(args, NAME)
    sections = [Section(_label(key), (lambda key=key: compute_point(*key)), 30.0)
                for key in (QUICK if args.quick else POINTS)]
    sections.append(Section("update", update_cost, 5.0))

    def commit(done):
        write_text(HERE / "MACRO_DIAGNOSIS.md", (folder / "MACRO_DIAGNOSIS.md").read_text())

    return run_sections(NAME, sections, publish, folder,
                        commit=commit if args.write else None,
                        model="a continuum pulse run 20 s, the element's eight runs 10 s")


if __name__ == "__main__":
    raise SystemExit(main())
