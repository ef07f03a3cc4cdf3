"""The study's summary, computed from its dataset alone (:func:`.workflow.compute`, or the
same read back by :func:`upliftlab.open_study`): the Markdown text (:func:`summarise`) and the
key numbers (:func:`key_numbers`, ``summary.json``). The wall time is the dataset's
``elapsed_s`` attribute (s), set when the study is written."""

from __future__ import annotations

import math

import numpy as np

from .analysis import Run, cheapest, converged, front, percent as _pct, runs, table_note
from .dataset import relative_to_reference
from .grid import FLOOR_FRACTION, INTEGRATORS, LABELS, QUANTITIES


def _point_dict(p: Run | None, reference_runtime: float) -> dict | None:
    if p is None:
        return None
    return {"model": p.model, "springs": p.springs, "integrator": p.integrator, "dt": p.dt,
            "runtime_s": p.runtime, "repeats": p.repeats,
            "errors": p.errors, "speedup_vs_reference": reference_runtime / p.runtime}


def context(ds) -> dict:
    """The measurement context of the runtimes (host, CPU, versions, threads, workers)."""
    return {k.removeprefix("context_"): v for k, v in ds.attrs.items()
            if k.startswith("context_")}


def _reference(ds, label: str) -> dict:
    one = ds.sel(scene=label)
    per_q = {name: dict(zip(QUANTITIES, (float(v) for v in one[name].values)))
             for name in ("reference", "change_half_springs", "change_double_dt", "floor")}
    return {"springs": reference_springs(ds), "dt": float(ds.attrs["grid_reference_dt"]),
            "values": per_q["reference"], "runtime_s": float(one.reference_runtime),
            "change_half_springs": per_q["change_half_springs"],
            "change_double_dt": per_q["change_double_dt"], "converged": converged(ds, label),
            "tolerance": float(ds.attrs["options_convergence_tolerance"]), "floors": per_q["floor"]}


def tolerances(ds) -> list[float]:
    """The error levels of the cheapest-run table (fractions)."""
    return [float(t) for t in _list(ds.attrs["options_tolerances"])]


def _list(value) -> list:
    return [value] if isinstance(value, (int, float)) else list(value)


def _elapsed(ds) -> float:
    """The study's wall time (s): the ``elapsed_s`` attribute the write step sets."""
    return float(ds.attrs.get("elapsed_s", math.nan))


def _scenes(ds) -> dict:
    """{scene label: its runs} of the dataset, in the panel's order."""
    return {label: runs(ds, label) for label in ds.scene.values.tolist()}


def summarise(ds) -> str:
    """The Markdown summary of the study's dataset ``ds``."""
    scenes = _scenes(ds)
    elapsed = _elapsed(ds)
    return summary_markdown(ds, scenes, summary_numbers(ds, scenes, elapsed), elapsed)


def key_numbers(ds) -> dict:
    """The key numbers of the study's dataset ``ds`` (``summary.json``)."""
    return summary_numbers(ds, _scenes(ds), _elapsed(ds))


def reference_springs(ds) -> int:
    """The springs of each scene's reference bed: the grid's largest."""
    return int(np.atleast_1d(ds.attrs["grid_springs"])[-1])


def summary_numbers(ds, scenes: dict, elapsed: float) -> dict:
    out = {}
    tally = {n: 0 for n in INTEGRATORS}
    for label, points in scenes.items():
        ref = _reference(ds, label)
        runtime = ref["runtime_s"]
        out[label] = {
            "scene": str(ds.scene_name.sel(scene=label).values),
            "reference": ref,
            "points": len(points),
            "refused": [f"{p.model} N={p.springs} {p.integrator}: {p.failure}"
                        for p in points if p.failure],
            "pareto": {q: [_point_dict(p, runtime) for p in front(points, q)]
                       for q in QUANTITIES},
            "cheapest": {q: {f"{t:g}": _point_dict(cheapest(points, q, t), runtime)
                             for t in tolerances(ds)} for q in QUANTITIES},
            "cheapest_note": {q: table_note(ds, label, points, q) for q in QUANTITIES}}
        for q in QUANTITIES:
            for p in front(points, q):
                tally[p.integrator] += 1
    return {"scenes": out, "pareto_points_by_integrator": tally,
            "measurement_context": context(ds),
            "measurement_sessions": int(ds.attrs["sessions"]),
            "runtimes": "stored with their measurement context (part of each point's key)",
            "continuum": str(ds.attrs["continuum"]), "elapsed_s": elapsed}


def short_label(p: Run) -> str:
    model = {"edges": "2 springs ±b", "equivalent": "2 springs ±b/√3",
             "continuum": f"continuum {p.springs} elements across"}.get(p.model,
                                                                          f"N = {p.springs}")
    step = (f"Δt = {p.dt:.3g} s" if math.isfinite(p.dt)
            else "Δt not recorded (the run was refused)")
    return f"{model}, {p.integrator}, {step}"


def _continuum_lines(ds, scenes: dict) -> list[str]:
    """The continuum meshes: values, error against the scene's (Winkler) reference, and the
    change of each mesh from the next finer one."""
    lines = []
    for label, points in scenes.items():
        pts = sorted((p for p in points if p.model == "continuum" and p.failure is None),
                     key=lambda p: p.springs)
        if not pts:
            continue
        floors = _reference(ds, label)["floors"]
        lines += [f"### {label} — continuum meshes against the Winkler reference", "",
                  "| elements across | runtime (s) | " + " | ".join(
                      f"{_head(q)} ({_units(ds, label).split(', ')[k]}; error and change to "
                      "next finer in %)" for k, q in enumerate(QUANTITIES))
                  + " |", "|---|---|" + "---|" * len(QUANTITIES)]
        for k, p in enumerate(pts):
            finer = pts[k + 1] if k + 1 < len(pts) else None
            cells = []
            for q in QUANTITIES:
                change = ("—" if finer is None else _pct(abs(relative_to_reference(
                    p.values[q], finer.values[q], floors[q]))))
                cells.append(f"{p.values[q]:.4g} ({_pct(p.abs_error(q))}; {change})")
            lines.append(f"| {p.springs} | {p.runtime:.3g} | " + " | ".join(cells) + " |")
        lines += ["", "The continuum is another model (soil continuum, plasticity, radiation), "
                  "so its error against the Winkler reference is model discrepancy plus mesh "
                  "error; the change to the next finer mesh is its own discretization error.",
                  ""]
    return lines


def summary_markdown(ds, scenes: dict, numbers: dict, elapsed: float) -> str:
    ctx = numbers["measurement_context"]
    fast = bool(ds.attrs.get("fast", 0))
    lines = [f"# Speed against error{' (fast)' if fast else ''}", "",
             f"{len(scenes)} scenes, {sum(len(p) for p in scenes.values())} runs "
             f"plus 3 reference runs each. Wall time {elapsed:.1f} s.", "",
             "Error = |value − reference| / max(|reference|, floor), floor = "
             f"{FLOOR_FRACTION:g} × the quantity's scale at the uplift threshold (u_up = "
             "(W b/3h)/k, θ_up = W/(K_v b), W/K_v for uplift and settlement). Peak edge uplift: "
             "the largest tracked spring gap plus (b − |x_i|)·θ_peak (a continuum mesh: the "
             "largest gap of its edge nodes); residual settlement: Σ k_i ε_p,i / Σ k_i at the "
             "end, zero for elastic springs (a continuum mesh: V(0) − V(end) of the footing "
             "centre, a different quantity, measured against the same reduced reference).", "",
             f"Runtimes: wall time of a whole reduced run in a single-threaded worker, median of "
             f"up to {int(ds.attrs['grid_repeats'])} repeats (fewer once "
             f"{float(ds.attrs['grid_repeat_budget']):g} s were spent), after a warm-up. They are "
             f"**stored with their measurement context** (in each point's key): {ctx['cpu']} on "
             f"host `{ctx['host']}`, {ctx['workers']} concurrent single-threaded workers on "
             f"{ctx['cpus']} CPUs, numba {ctx['numba']}; {numbers['measurement_sessions']} "
             "measurement session(s) (calls of the study that ran points) contributed. Compare "
             "runtimes as ratios within this table.", "",
             f"Continuum: {numbers['continuum']}.", "",
             "## References and their convergence", "",
             "| scene | reference | " + " | ".join(f"{_head(q)} (ΔN, Δdt in %)"
                                                 for q in QUANTITIES)
             + " | units of u, θ, uplift, settlement | ref. runtime (s) |",
             "|---|---|" + "---|" * len(QUANTITIES) + "---|---|"]
    for label in scenes:
        r = numbers["scenes"][label]["reference"]
        cells = [f"{r['values'][q]:.4g} ({_pct(r['change_half_springs'][q])}, "
                 f"{_pct(r['change_double_dt'][q])})"
                 + ("" if r["converged"][q] else " **not conv.**") for q in QUANTITIES]
        lines.append(f"| {label} | events, N = {r['springs']}, Δt = {r['dt']:g} s | "
                     + " | ".join(cells) + f" | {_units(ds, label)} | {r['runtime_s']:.3g} |")
    notconv = [(label, q) for label in scenes for q in QUANTITIES
               if not numbers["scenes"][label]["reference"]["converged"][q]]
    tolerance = float(ds.attrs["options_convergence_tolerance"])
    lines += ["", DEFINITIONS, "", f"Converged to {_pct(tolerance)} (change "
              f"from half the springs and from twice the step): "
              + (f"all but {len(notconv)}: " + ", ".join(f"{a} {LABELS[q]}" for a, q in notconv)
                 if notconv else "every scene and quantity") + ". Errors against an unconverged "
              "reference are at best as good as its change.", ""]
    levels = tolerances(ds)
    lines += ["## Cheapest discretization within each tolerance", "",
              "| scene | quantity | " + " | ".join(f"within {_pct(t)} (runtime in ms, error "
                                                  "in %)" for t in levels)
              + " |", "|---|---|" + "---|" * len(levels)]
    for label, points in scenes.items():
        runtime = numbers["scenes"][label]["reference"]["runtime_s"]
        for q in QUANTITIES:
            note = numbers["scenes"][label]["cheapest_note"][q]
            if note:
                lines.append(f"| {label} | {LABELS[q]} | " + " | ".join(
                    [note] * len(levels)) + " |")
                continue
            cells = []
            for t in levels:
                p = cheapest(points, q, t)
                cells.append("none" if p is None else
                             f"{short_label(p)}: {p.runtime * 1e3:.3g} ms, {_pct(p.abs_error(q))} "
                             f"(×{runtime / p.runtime:.3g} faster than ref.)")
            lines.append(f"| {label} | {LABELS[q]} | " + " | ".join(cells) + " |")
    tally = numbers["pareto_points_by_integrator"]
    lines += ["", "## Pareto fronts", "", "Points on the fronts (all scenes and quantities) by "
              "integrator: " + ", ".join(f"{n} {c}" for n, c in tally.items()) + ".", ""]
    for label, points in scenes.items():
        lines += [f"### {label} — peak u", "", r"| runtime (ms) | \|error\| | discretization |",
                  "|---|---|---|"]
        lines += [f"| {p.runtime * 1e3:.3g} | {_pct(p.abs_error('u'))} | {short_label(p)} |"
                  for p in front(points, "u")]
        lines.append("")
    lines += _continuum_lines(ds, scenes)
    refused = [(label, p) for label, points in scenes.items() for p in points if p.failure]
    lines += [f"Refused runs: {len(refused)}."]
    lines += [f"- {a}: {short_label(p)}: {p.failure}" for a, p in refused[:10]]
    return "\n".join(lines)


def _head(quantity: str) -> str:
    """A quantity's name for a table header: its label without the parenthesised definition
    (which :data:`DEFINITIONS` states under the table)."""
    return LABELS[quantity].split(" (")[0]


#: The definitions the table headers leave out.
DEFINITIONS = ("Peak edge uplift: reduced from the peaks, continuum the edge gap; residual "
               "settlement: reduced Σkε_p/Σk, continuum V(0) − V(end).")


def _units(ds, label: str) -> str:
    """The units of peak u, θ, uplift and settlement of scene ``label`` (its length unit; θ in
    rad)."""
    length = str(ds.length_unit.sel(scene=label).values)
    return f"{length}, rad, {length}, {length}"
