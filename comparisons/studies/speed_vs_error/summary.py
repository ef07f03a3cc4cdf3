"""The study's summary: key numbers and the Markdown text computed from them."""

from __future__ import annotations

import math

from .analysis import Point, Reference, SceneResult, SpeedVsError, relative_to_reference
from .grid import FLOOR_FRACTION, INTEGRATORS, LABELS, QUANTITIES


def _point_dict(p: Point | None, ref: Reference) -> dict | None:
    if p is None:
        return None
    return {"model": p.model, "springs": p.springs, "integrator": p.integrator, "dt": p.dt,
            "runtime_s": p.runtime, "repeats": p.repeats,
            "errors": p.errors, "speedup_vs_reference": ref.runtime / p.runtime}


def summary_numbers(result: SpeedVsError, elapsed: float) -> dict:
    scenes = {}
    tally = {n: 0 for n in INTEGRATORS}
    for s in result.scenes:
        ref = s.reference
        scenes[s.label] = {
            "scene": s.name,
            "reference": {"springs": ref.springs, "dt": ref.dt, "values": ref.values,
                          "runtime_s": ref.runtime, "change_half_springs": ref.change_springs,
                          "change_double_dt": ref.change_dt, "converged": ref.converged,
                          "tolerance": ref.tolerance, "floors": ref.floors},
            "points": len(s.points),
            "refused": [f"{p.model} N={p.springs} {p.integrator}: {p.failure}"
                        for p in s.points if p.failure],
            "pareto": {q: [_point_dict(p, ref) for p in s.front(q)] for q in QUANTITIES},
            "cheapest": {q: {f"{t:g}": _point_dict(s.cheapest(q, t), ref)
                             for t in result.options.tolerances} for q in QUANTITIES},
            "cheapest_note": {q: table_note(s, q) for q in QUANTITIES}}
        for q in QUANTITIES:
            for p in s.front(q):
                tally[p.integrator] += 1
    return {"scenes": scenes, "pareto_points_by_integrator": tally,
            "measurement_context": result.context, "measurement_sessions": result.sessions,
            "runtimes": "stored with their measurement context (part of each point's key)",
            "continuum": result.continuum, "elapsed_s": elapsed}


def _pct(v: float) -> str:
    if not math.isfinite(v):
        return "n/a"
    return f"{100 * v:.2g} %" if v < 0.01 else f"{100 * v:.1f} %"


def short_label(p: Point) -> str:
    model = {"edges": "2 springs ±b", "equivalent": "2 springs ±b/√3",
             "continuum": f"continuum {p.springs} elements across"}.get(p.model,
                                                                          f"N = {p.springs}")
    return f"{model}, {p.integrator}, Δt = {p.dt:.3g} s"


def _continuum_lines(result: SpeedVsError) -> list[str]:
    """The continuum meshes: values, error against the scene's (Winkler) reference, and the
    change of each mesh from the next finer one."""
    lines = []
    for s in result.scenes:
        pts = sorted((p for p in s.points if p.model == "continuum" and p.failure is None),
                     key=lambda p: p.springs)
        if not pts:
            continue
        lines += [f"### {s.label} — continuum meshes against the Winkler reference", "",
                  "| elements across | runtime (s) | " + " | ".join(
                      f"{_head(q)} ({_units(result, s).split(', ')[k]}; error and change to "
                      "next finer in %)" for k, q in enumerate(QUANTITIES))
                  + " |", "|---|---|" + "---|" * len(QUANTITIES)]
        for k, p in enumerate(pts):
            finer = pts[k + 1] if k + 1 < len(pts) else None
            cells = []
            for q in QUANTITIES:
                change = ("—" if finer is None else _pct(abs(relative_to_reference(
                    p.values[q], finer.values[q], s.reference.floors[q]))))
                cells.append(f"{p.values[q]:.4g} ({_pct(p.abs_error(q))}; {change})")
            lines.append(f"| {p.springs} | {p.runtime:.3g} | " + " | ".join(cells) + " |")
        lines += ["", "The continuum is another model (soil continuum, plasticity, radiation), "
                  "so its error against the Winkler reference is model discrepancy plus mesh "
                  "error; the change to the next finer mesh is its own discretization error.",
                  ""]
    return lines


def table_note(s: SceneResult, q: str) -> str:
    """Why the cheapest-within-tolerance cells of (scene, quantity) say nothing, or ''."""
    ref = s.reference
    if not ref.converged[q]:
        change = max(ref.change_springs[q], ref.change_dt[q])
        return f"n/a: reference not converged (changes {_pct(change)})"
    if ref.values[q] == 0.0 and all(p.values[q] == 0.0 for p in s.points if not p.failure):
        return "0 for every model (elastic springs)"
    return ""


def summary_markdown(result: SpeedVsError, fast: bool, elapsed: float) -> str:
    ctx, opt = result.context, result.options
    lines = [f"# Speed against error{' (fast)' if fast else ''}", "",
             f"{len(result.scenes)} scenes, {sum(len(s.points) for s in result.scenes)} runs "
             f"plus 3 reference runs each. Wall time {elapsed:.1f} s.", "",
             "Error = |value − reference| / max(|reference|, floor), floor = "
             f"{FLOOR_FRACTION:g} × the quantity's scale at the uplift threshold (u_up = "
             "(W b/3h)/k, θ_up = W/(K_v b), W/K_v for uplift and settlement). Peak edge uplift: "
             "the largest tracked spring gap plus (b − |x_i|)·θ_peak (a continuum mesh: the "
             "largest gap of its edge nodes); residual settlement: Σ k_i ε_p,i / Σ k_i at the "
             "end, zero for elastic springs (a continuum mesh: V(0) − V(end) of the footing "
             "centre, a different quantity, measured against the same reduced reference).", "",
             f"Runtimes: wall time of a whole reduced run in a single-threaded worker, median of "
             f"up to {result.grid.repeats} repeats (fewer once {result.grid.repeat_budget:g} s "
             f"were spent), after a warm-up. They are **stored with their measurement context** "
             f"(in each point's key): {ctx['cpu']} on host `{ctx['host']}`, {ctx['workers']} "
             f"concurrent single-threaded workers on {ctx['cpus']} CPUs, numba {ctx['numba']}; "
             f"{result.sessions} measurement session(s) (calls of the study that ran points) "
             "contributed. Compare runtimes as ratios within this table.", "",
             f"Continuum: {result.continuum}.", "",
             "## References and their convergence", "",
             "| scene | reference | " + " | ".join(f"{_head(q)} (ΔN, Δdt in %)"
                                                 for q in QUANTITIES)
             + " | units of u, θ, uplift, settlement | ref. runtime (s) |",
             "|---|---|" + "---|" * len(QUANTITIES) + "---|---|"]
    for s in result.scenes:
        r = s.reference
        cells = [f"{r.values[q]:.4g} ({_pct(r.change_springs[q])}, {_pct(r.change_dt[q])})"
                 + ("" if r.converged[q] else " **not conv.**") for q in QUANTITIES]
        lines.append(f"| {s.label} | events, N = {r.springs}, Δt = {r.dt:g} s | "
                     + " | ".join(cells) + f" | {_units(result, s)} | {r.runtime:.3g} |")
    notconv = [(s.label, q) for s in result.scenes for q in QUANTITIES
               if not s.reference.converged[q]]
    lines += ["", DEFINITIONS, "", f"Converged to {_pct(opt.convergence_tolerance)} (change "
              f"from half the springs and from twice the step): "
              + (f"all but {len(notconv)}: " + ", ".join(f"{a} {LABELS[q]}" for a, q in notconv)
                 if notconv else "every scene and quantity") + ". Errors against an unconverged "
              "reference are at best as good as its change.", ""]
    lines += ["## Cheapest discretization within each tolerance", "",
              "| scene | quantity | " + " | ".join(f"within {_pct(t)} (runtime in ms, error "
                                                  "in %)" for t in opt.tolerances)
              + " |", "|---|---|" + "---|" * len(opt.tolerances)]
    for s in result.scenes:
        for q in QUANTITIES:
            note = table_note(s, q)
            if note:
                lines.append(f"| {s.label} | {LABELS[q]} | " + " | ".join(
                    [note] * len(opt.tolerances)) + " |")
                continue
            cells = []
            for t in opt.tolerances:
                p = s.cheapest(q, t)
                cells.append("none" if p is None else
                             f"{short_label(p)}: {p.runtime * 1e3:.3g} ms, {_pct(p.abs_error(q))} "
                             f"(×{s.reference.runtime / p.runtime:.3g} faster than ref.)")
            lines.append(f"| {s.label} | {LABELS[q]} | " + " | ".join(cells) + " |")
    tally = summary_numbers(result, elapsed)["pareto_points_by_integrator"]
    lines += ["", "## Pareto fronts", "", "Points on the fronts (all scenes and quantities) by "
              "integrator: " + ", ".join(f"{n} {c}" for n, c in tally.items()) + ".", ""]
    for s in result.scenes:
        lines += [f"### {s.label} — peak u", "", "| runtime (ms) | |error| | discretization |",
                  "|---|---|---|"]
        lines += [f"| {p.runtime * 1e3:.3g} | {_pct(p.abs_error('u'))} | {short_label(p)} |"
                  for p in s.front("u")]
        lines.append("")
    lines += _continuum_lines(result)
    refused = [(s.label, p) for s in result.scenes for p in s.points if p.failure]
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


def _units(result: SpeedVsError, s) -> str:
    """The units of peak u, θ, uplift and settlement of scene result ``s`` (its packaged
    scene's length unit; θ in rad)."""
    from ....scenes import load_scene

    spec = next(sp for sp in result.grid.scenes if sp.label == s.label)
    length = load_scene(spec.scene).units.length
    return f"{length}, rad, {length}, {length}"
