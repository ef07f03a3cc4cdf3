"""Speed against error of the reduced model, per integrator, step and number of springs.

    python benchmarks/reduced_speed.py [--quick] [--out DIR | --write] [--repeats R]
                                       [--workers W] [--batch-scenes S]

Scene: the short-period masonry building on El Centro 1940 N-S, Case C (elasto-plastic Winkler
bed, 10 % dashpots, impact damper ε = 0.7), the whole 31.2 s record, on N = 2, 10, 40, 160
foundation springs. For every integrator (events, rk4, abm4, newmark, hht) at fixed steps
Δt = 0.02/2^k (error control off, energy guard relaxed so that every admissible step is
measured), and for the default — the event stepper under error control at rtol = 1e-3 … 1e-7,
1e-5 being the default — it prints the median CPU time of this process (one thread: the
run's own cost, which the load of other processes on a shared machine does not inflate as it
inflates wall time) of ``run(scene, integrator=..., dt=..., histories=False)`` over
the repeats (after one warm-up run, which also compiles or loads the numba cache), the kernel's
share of it, and the errors in peak u and in the peak uplift of the leftmost spring against two
references:

- **same N**: the event stepper at the finest step on the same bed (the time-integration error);
- **N = 640**: the event stepper at the finest step on 640 springs (the brief's reference: the
  time-integration error plus the error of the bed's discretisation).

The paper's impact damper (``foundation.impact_mass = "point"``, eq. 17 per spring) makes the
bed's total impact dissipation grow with N, so Case C has no limit as N grows and an N = 640
"reference" is just another model. The N = 640 errors are therefore also measured for
``impact_mass = "tributary"`` (each landing spring's share k_i/K_v of that mass; it converges in
N like Case B): the event stepper over the same steps and N, against its own N = 640 run.

Each reference is checked by halving its step. A step beyond a fixed-step explicit method's
stability limit is refused up front by ``run`` (``InputError``); the table says so, with the
limit. Then the batch API: ``run_batch`` on S scenes (default 10,000) of N = 20 springs with
varied yield multiple, foundation damping and structure period, at the event stepper's default
step and at Δt = 0.01 s (the stepper locates every switch inside its steps), against a loop of
single ``run`` calls on a subset, measured in the same process. The machine is shared: compare
ratios.

Sections (``bench_output``): the N = 640 reference, the runs of each N, the same with the
tributary impact mass, the bed's convergence and the batch; ``REDUCED.md`` and
``reduced_speed.png`` are rewritten in ``--out`` (default ``results/bench/reduced_speed``) as
each ends, and ``--write`` also rewrites the committed ones in ``benchmarks/`` (keeping the
OpenSees section that ``opensees_reduced.py`` writes there) once every section has completed.
``--quick`` (a smoke check, never committed): N = 2 and 40, a few steps, the reference on 160
springs, one timed repeat, 100 batch scenes.

Cost model (the estimate printed before any work; about 11 min for the default run from the
table committed on 2026-11-24): a point costs (1 + repeats) × the runtime the committed
``benchmarks/REDUCED.md`` records for the same N, integrator and step; a point it does not
record costs (record span / Δt) steps × the CPU time per step of that integrator, a + b·N fitted
by least squares to the table's measured rows (a reference or a bed run likewise, at its step);
the batch costs the recorded wall time per scene × scenes plus the recorded loop time per scene
× the loop's scenes.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import warnings  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, missing_section, number, output_folder, run_sections,
                          save_figure, say, write_text)
from upliftlab.checks import InputError  # noqa: E402
from upliftlab.reduced.batch import run_batch  # noqa: E402
from upliftlab.reduced.integrators import METHODS  # noqa: E402
from upliftlab.reduced.run import IntegrationError, ModelWarning, run  # noqa: E402
from upliftlab.scenes import load_scene  # noqa: E402

SCENE, CASE = "short_period_elcentro", "C"
INTEGRATORS = tuple(METHODS)
RECORD_DT = 0.02
# steps 0.02 / 2^k: the range of k per integrator (fixed-step explicit ones go finer, since
# their stability limits fall as 1/N; the implicit ones cost a Newton solve per step)
FULL = {"springs": (2, 10, 40, 160), "reference_n": 640, "reference_k": 9,
        "k": {"events": range(0, 8), "rk4": range(4, 11), "abm4": range(5, 11),
              "newmark": range(1, 9), "hht": range(1, 9)},
        "batch_scenes": 10_000, "loop_scenes": 200, "bed": (10, 40, 160, 640, 1280)}
QUICK = {"springs": (2, 40), "reference_n": 160, "reference_k": 8,
         "k": {"events": range(0, 6, 2), "rk4": range(7, 10), "abm4": range(8, 10),
               "newmark": range(5, 8, 2), "hht": range(5, 8, 2)},
         "batch_scenes": 100, "loop_scenes": 20, "bed": (10, 40, 160)}
NAME = "reduced_speed"
TARGET_N, TARGET_ERROR, TARGET_TIME = 40, 0.005, 0.020
BATCH_N, BATCH_TARGET = 20, 60.0


TRIBUTARY = ("foundation.impact_mass=tributary",)
#: The step sweep takes fixed steps (no error control) and measures each against the
#: references, so the energy guard is relaxed there: every step up to a method's limit for a
#: 100 % tolerance is measured. The default rows keep the scene's own settings.
FIXED = ("analysis.rtol=0", "analysis.energy_tolerance=1")
#: Tolerances of the event stepper's error control in the default rows (1e-5: the default).
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)


def scene(n: int, *extra: str, fixed: bool = True):
    """The scene on n springs; ``fixed``: the step sweep's fixed steps (:data:`FIXED`)."""
    return load_scene(SCENE, case=CASE, overrides=[f"foundation.springs={n}", *extra,
                                                   *(FIXED if fixed else ())])


# ---------------------------------------------------------------------------------------------
# Single runs
# ---------------------------------------------------------------------------------------------


def peaks_of(response) -> dict:
    pk = response.peaks
    return {"u": pk["u"], "uplift": pk["uplift_left"], "theta": pk["theta"]}


def measure(sc, integrator: str, dt: float | None, repeats: int) -> dict:
    """Warm-up, then ``repeats`` timed runs: medians of the call and of the kernel."""
    row = {"integrator": integrator, "dt": dt, "rtol": sc.analysis.rtol
           if integrator == "events" else 0.0}
    try:
        response = run(sc, integrator=integrator, dt=dt, histories=False)
    except InputError as exc:
        limit = _limit_in(str(exc))
        return {**row, "status": f"refused (limit {limit})"}
    except IntegrationError as exc:
        return {**row, "status": f"failed: {exc}"}
    calls, kernels = [], []
    for _ in range(repeats):
        start = time.process_time()  # this process's CPU: other processes' load aside
        response = run(sc, integrator=integrator, dt=dt, histories=False)
        calls.append(time.process_time() - start)
        kernels.append(response.info["wall_time_s"])
    counters = response.info["counters"]
    steps = (counters[2] // 4 if integrator == "events" else response.info["steps"])
    return {**row, "status": "ok", "steps": steps,
            "runtime": statistics.median(calls), "kernel": statistics.median(kernels),
            "peaks": peaks_of(response)}


def _limit_in(message: str) -> str:
    """The limit quoted in ``time_step``'s refusal: the stability limit of an explicit
    integrator, or the largest step that resolves the shortest period for an implicit one."""
    words = message.split("stability limit ")
    if len(words) > 1:
        return words[1].split()[0] + " s"
    words = message.split("valid range is (0, ")
    return (words[1].split("]")[0] + " s, resolution") if len(words) > 1 else "?"


def reference(n: int, k: int, extra: tuple[str, ...] = ()) -> dict:
    """Event stepper at 0.02/2^k on n springs, and the change on halving that step."""
    sc = scene(n, *extra)
    fine = peaks_of(run(sc, integrator="events", dt=RECORD_DT / 2 ** k, histories=False))
    finer = peaks_of(run(sc, integrator="events", dt=RECORD_DT / 2 ** (k + 1), histories=False))
    change = {key: finer[key] / fine[key] - 1.0 for key in fine}
    return {"n": n, "dt": RECORD_DT / 2 ** k, "peaks": fine, "halving": change}


def bed_convergence(ns, k: int) -> list[dict]:
    """Peaks of the event stepper at 0.02/2^k for Cases A, B, C (and C with the tributary
    impact mass) on each N: does the bed converge as N grows?"""
    out = []
    for case, extra in (("A", ()), ("B", ()), ("C", ()), ("C, tributary", TRIBUTARY)):
        for n in ns:
            sc = load_scene(SCENE, case=case[0], overrides=[f"foundation.springs={n}", *extra])
            peaks = peaks_of(run(sc, integrator="events", dt=RECORD_DT / 2 ** k,
                                 histories=False))
            out.append({"case": case, "n": n, **peaks})
    return out


def bed_text(items: list[dict]) -> str:
    lines = ["| case | N | peak u [in] | peak uplift, leftmost [in] | peak θ [rad] | "
             "u / u(largest N) − 1 |", "|" + "---|" * 6]
    for item in items:
        last = [i for i in items if i["case"] == item["case"]][-1]
        lines.append(f"| {item['case']} | {item['n']} | {item['u']:.6g} | {item['uplift']:.6g} "
                     f"| {item['theta']:.6g} | {_pct(item['u'] / last['u'] - 1.0)} |")
    return "\n".join(lines)


def add_errors(row: dict, own: dict, big: dict) -> dict:
    if row["status"] == "ok":
        for key in ("u", "uplift"):
            row[f"{key}_own"] = row["peaks"][key] / own["peaks"][key] - 1.0
            row[f"{key}_big"] = row["peaks"][key] / big["peaks"][key] - 1.0
    return row


def sweep(n: int, config: dict, repeats: int, big: dict, integrators=INTEGRATORS,
          extra: tuple[str, ...] = ()) -> tuple[dict, list[dict]]:
    """On n springs: the reference, every integrator at fixed steps 0.02/2^k, then the event
    stepper at its default settings under each tolerance of :data:`RTOLS` (no step given: the
    error control's)."""
    rows = []
    ref = reference(n, config["reference_k"], extra)
    sc = scene(n, *extra)
    for integrator in integrators:
        for k in config["k"][integrator]:
            row = measure(sc, integrator, RECORD_DT / 2 ** k, repeats)
            row["n"] = n
            rows.append(add_errors(row, ref, big))
            print(_line(row), file=sys.stderr, flush=True)
    for rtol in RTOLS:
        default = scene(n, *extra, f"analysis.rtol={rtol}", fixed=False)
        row = measure(default, "events", None, repeats)
        row["n"] = n
        rows.append(add_errors(row, ref, big))
        print(_line(row), file=sys.stderr, flush=True)
    return ref, rows


def _step(r: dict) -> str:
    """The step column: a fixed step, or the error control's tolerance."""
    if r["dt"] is None:
        default = " (default)" if r["rtol"] == 1e-5 else ""
        return f"rtol {r['rtol']:g}{default}"
    return f"{r['dt']:.4g}"


def _line(r: dict) -> str:
    head = f"N = {r['n']:4d} {r['integrator']:8s} {_step(r)}:"
    if r["status"] != "ok":
        return f"{head} {r['status']}"
    return (f"{head} {1e3 * r['runtime']:9.2f} ms, u {r['u_own']:+.2e} (N=640 "
            f"{r['u_big']:+.2e}), uplift {r['uplift_own']:+.2e} ({r['uplift_big']:+.2e})")


# ---------------------------------------------------------------------------------------------
# The batch
# ---------------------------------------------------------------------------------------------


def batch_scenes(count: int, seed: int = 0) -> list:
    """``count`` Case C scenes on N = 20 springs with varied yield multiple (2–5), foundation
    damping (5–40 % of critical) and fixed-base period (0.1–0.5 s), from a seeded generator."""
    rng = np.random.default_rng(seed)
    values = rng.uniform([2.0, 0.05, 0.1], [5.0, 0.40, 0.5], size=(count, 3))
    return [scene(BATCH_N, f"foundation.yield_multiple={y:.6g}",
                  f"foundation.damping_ratio={z:.6g}", f"structure.period={p:.6g}",
                  fixed=False) for y, z, p in values]


def batch(config: dict, workers: int) -> list[dict]:
    """Wall time of run_batch on every scene, and of a loop of run() on a subset."""
    start = time.perf_counter()
    scenes = batch_scenes(config["batch_scenes"])
    build = time.perf_counter() - start
    looser = [sc.with_overrides("analysis.rtol=1e-4") for sc in scenes]
    out = []
    for rtol, group in ((1e-5, scenes), (1e-4, looser)):
        dt = None
        result = run_batch(group, integrator="events", dt=dt, workers=workers)
        subset = group[:config["loop_scenes"]]
        start = time.perf_counter()
        for sc in subset:
            run(sc, integrator="events", dt=dt, histories=False)
        loop = (time.perf_counter() - start) / len(subset)
        check = np.array([run(sc, integrator="events", dt=dt, histories=False).peaks["u"]
                          for sc in group[:5]])
        agree = float(np.max(np.abs(result.u[:5] / check - 1.0)))
        out.append({"rtol": rtol, "scenes": len(scenes), "workers": workers, "build": build,
                    "wall": result.info["wall_time_s"], "failed": int(np.sum(~result.ok)),
                    "steps_dt": float(np.median(result.dt)), "loop": loop, "agree": agree,
                    "loop_scenes": len(subset)})
        print(f"batch rtol = {rtol:g}: {out[-1]['wall']:.1f} s for {len(scenes)} scenes",
              file=sys.stderr, flush=True)
    return out


# ---------------------------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------------------------


def _pct(x: float) -> str:
    return f"{100 * x:+.2e} %"


def table(rows: list[dict]) -> str:
    lines = ["| N | integrator | Δt [s] or tolerance | steps | runtime [ms] | kernel [ms] | "
             "err u (same N) | err uplift (same N) | err u (N = 640 ref) | "
             "err uplift (N = 640 ref) |", "|" + "---|" * 10]
    for r in rows:
        if r["status"] != "ok":
            lines.append(f"| {r['n']} | {r['integrator']} | {_step(r)} | – | "
                         f"{r['status']} | – | – | – | – | – |")
            continue
        lines.append(f"| {r['n']} | {r['integrator']} | {_step(r)} | {r['steps']} | "
                      f"{1e3 * r['runtime']:.2f} | {1e3 * r['kernel']:.2f} | "
                      f"{_pct(r['u_own'])} | {_pct(r['uplift_own'])} | {_pct(r['u_big'])} | "
                      f"{_pct(r['uplift_big'])} |")
    return "\n".join(lines)


def references_text(refs: dict, big: dict) -> str:
    lines = ["| N | Δt [s] | peak u [in] | peak uplift, leftmost [in] | peak θ [rad] | "
             "change of u on halving Δt | of uplift |", "|" + "---|" * 7]
    for ref in [*refs.values(), big]:
        p, h = ref["peaks"], ref["halving"]
        lines.append(f"| {ref['n']} | {ref['dt']:.4g} | {p['u']:.7g} | {p['uplift']:.7g} | "
                     f"{p['theta']:.6g} | {_pct(h['u'])} | {_pct(h['uplift'])} |")
    return "\n".join(lines)


def target_text(rows: list[dict], key: str, label: str, floor: float | None = None) -> str:
    """The fastest N = 40 run within 0.5 % in peak u against reference ``key``; ``floor`` is
    the converged N = 40 model's own error against that reference (the bed's discretisation)."""
    mine = [r for r in rows if r["n"] == TARGET_N and r["status"] == "ok"]
    good = [r for r in mine if abs(r[key]) <= TARGET_ERROR]
    if not mine:
        return f"- {label}: no N = {TARGET_N} rows in this run."
    if not good:
        best = min(mine, key=lambda r: abs(r[key]))
        why = (f" The converged N = {TARGET_N} model itself (event stepper, finest step) is "
               f"{_pct(floor)} off in peak u: that is the Winkler bed's discretisation, which "
               "no step removes; rows that land closer are unconverged runs whose time error "
               "happens to cancel it.") if floor is not None else ""
        return (f"- {label}: **not met** — no N = {TARGET_N} run is within 0.5 %; the closest "
                f"is {best['integrator']} {_step(best)} at {_pct(best[key])}.{why}")
    best = min(good, key=lambda r: r["runtime"])
    events = [r for r in mine if r["integrator"] == "events"]
    slowest = max(events, key=lambda r: r["runtime"]) if events else best
    verdict = "met" if best["runtime"] < TARGET_TIME else "not met"
    default = [r for r in mine if r["dt"] is None and r["rtol"] == 1e-5]
    said = (f" The default (error control, rtol 1e-5): {1e3 * default[0]['runtime']:.2f} ms, "
            f"error {_pct(default[0][key])}." if default else "")
    return (f"- {label}: **{verdict}** — fastest N = {TARGET_N} run within 0.5 %: "
            f"{best['integrator']} {_step(best)}, {1e3 * best['runtime']:.2f} ms "
            f"(median), error {_pct(best[key])}; that is {best['runtime'] / TARGET_TIME:.2f} × "
            f"the 20 ms budget, and {best['runtime'] / slowest['runtime']:.3f} × the finest "
            f"events run of this table ({1e3 * slowest['runtime']:.1f} ms, same process).{said}")


def _floor(refs: dict, big: dict) -> float | None:
    ref = refs.get(TARGET_N)
    return ref["peaks"]["u"] / big["peaks"]["u"] - 1.0 if ref else None


def batch_text(items: list[dict]) -> str:
    lines = ["| event stepper | scenes | workers | run_batch wall [s] | per scene [ms] | "
             "loop of run() per scene [ms] | batch / loop (per scene) | failed | "
             "extrapolated to 10,000 [s] | target < 60 s | max rel. diff. vs run() (5 scenes) |",
             "|" + "---|" * 11]
    note = (f"\n\nBuilding the {items[0]['scenes']} scenes (`load_scene` with overrides) took "
            f"{items[0]['build']:.1f} s, outside the batch's wall time. The batch's wall time "
            "includes checking every scene (model, step, stability limit) in the calling "
            "process, starting the pool and integrating; the loop runs the same scenes one by "
            "one with `run(..., histories=False)` in this process.") if items else ""
    for b in items:
        per = b["wall"] / b["scenes"]
        full = per * 10_000
        default = " (default)" if b["rtol"] == 1e-5 else ""
        lines.append(f"| error control, rtol {b['rtol']:g}{default} | "
                     f"{b['scenes']} | {b['workers']} | {b['wall']:.1f} | {1e3 * per:.2f} | "
                     f"{1e3 * b['loop']:.2f} | {per / b['loop']:.2f} | {b['failed']} | "
                     f"{full:.0f} | {'met' if full < BATCH_TARGET else 'not met'} | "
                     f"{b['agree']:.1e} |")
    return "\n".join(lines) + note


def figure(rows: list[dict], rows_t: list[dict], path: Path) -> Path:
    """Runtime against error: the paper's Case C against the same N (left) and, with the
    tributary impact mass whose bed converges in N, against N = 640 (right)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    markers = dict(zip(INTEGRATORS, "osD^v"))
    ns = sorted({r["n"] for r in rows})
    colours = dict(zip(ns, plt.cm.viridis(np.linspace(0.0, 0.85, len(ns)))))
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), sharey=False)
    for ax, key, title, points in (
            (axes[0], "u_own", "Case C: against the same N (time-integration error)", rows),
            (axes[1], "u_big", "Case C, tributary impact mass: against N = 640\n"
                               "(time + bed discretisation)", rows_t)):
        for r in points:
            if r["status"] == "ok":
                marker = "*" if r["dt"] is None else markers[r["integrator"]]
                ax.loglog(1e3 * r["runtime"], max(abs(r[key]), 1e-10), ls="none",
                          marker=marker, color=colours[r["n"]], ms=9 if r["dt"] is None else 6)
        ax.axhline(TARGET_ERROR, color="grey", lw=0.8, ls="--")
        ax.axvline(1e3 * TARGET_TIME, color="grey", lw=0.8, ls="--")
        ax.set_xlabel("runtime [ms] (median, 31.2 s of El Centro)")
        ax.set_ylabel("|relative error in peak u| (floor 1e-10)")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, which="both")
    handles = [plt.Line2D([], [], ls="none", marker=m, color="k", label=f"{i}, fixed Δt")
               for i, m in markers.items()]
    handles.append(plt.Line2D([], [], ls="none", marker="*", color="k", ms=9,
                              label="events, error control (rtol)"))
    handles += [plt.Line2D([], [], ls="none", marker="s", color=c, label=f"N = {n}")
                for n, c in colours.items()]
    axes[1].legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.suptitle("upliftlab reduced model, short-period building, Case C (dashed: 0.5 %, 20 ms)",
                 fontsize=10)
    fig.tight_layout()
    return save_figure(fig, path)


def kept_section(path: Path) -> str:
    """The OpenSees section that ``opensees_reduced.py`` wrote into ``path``, kept as it is."""
    begin, end = "<!-- opensees_reduced: begin -->", "<!-- opensees_reduced: end -->"
    old = path.read_text() if path.exists() else ""
    if begin not in old or end not in old:
        return ""
    return "\n" + begin + old.split(begin, 1)[1].split(end, 1)[0] + end + "\n"


def header(args, repeats: int, config: dict) -> str:
    return (f"# Reduced model: speed against error\n\n"
            f"`python benchmarks/reduced_speed.py{' --quick' if args.quick else ''}`, "
            f"{datetime.date.today().isoformat()}, "
            f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs (shared), "
            f"Python {platform.python_version()}, one thread. Scene `{SCENE}`, Case {CASE} "
            f"(elasto-plastic springs yielding at 3 F0, ζ_f = 10 %, impact damper ε = 0.7, "
            f"c* = 10 c_cr), El Centro 1940 N-S, 31.2 s. Runtime: median process CPU time of "
            f"{repeats} calls of "
            f"`run(scene, integrator, dt, histories=False)` after one warm-up call (model "
            f"build, step check and kernel); kernel: the integration alone, wall clock "
            f"(`info['wall_time_s']`). Errors are relative, in peak u (superstructure "
            f"deformation) and peak uplift of the leftmost spring, against the event stepper "
            f"at Δt = {RECORD_DT / 2 ** config['reference_k']:.4g} s on the same N and on "
            f"N = {config['reference_n']}. The machine is shared and noisy: compare ratios "
            f"within this file.\n\n")


def document(args, config: dict, done: dict, missing: dict) -> str:
    """REDUCED.md of the sections done so far (each missing one says so)."""
    def part(key: str, title: str, render) -> str:
        return render() if key in done else missing_section(title, key, missing)

    springs = config["springs"]
    big, big_t = done.get("reference"), done.get("tributary reference")
    refs = {n: done[f"runs N = {n}"][0] for n in springs if f"runs N = {n}" in done}
    rows = [r for n in springs if f"runs N = {n}" in done for r in done[f"runs N = {n}"][1]]
    refs_t = {n: done[f"tributary N = {n}"][0] for n in springs
              if f"tributary N = {n}" in done}
    rows_t = [r for n in springs if f"tributary N = {n}" in done
              for r in done[f"tributary N = {n}"][1]]
    ref_n = config["reference_n"]
    text = [header(args, args.repeats, config) + incomplete_note(missing),
            "## References\n\n" + (references_text(refs, big) if big else missing_section(
                "", "reference", missing).strip()),
            "## Runs\n\n" + table(rows) + "".join(
                f"\n\nN = {n}: not completed (section `runs N = {n}`: "
                f"{missing[f'runs N = {n}']})." for n in springs if f"runs N = {n}" in missing),
            "## Runs, tributary impact mass (event stepper; the bed converges in N)\n\n"
            + (references_text(refs_t, big_t) if big_t else missing_section(
                "", "tributary reference", missing).strip()) + "\n\n" + table(rows_t)
            + "".join(f"\n\nN = {n}: not completed (section `tributary N = {n}`: "
                      f"{missing[f'tributary N = {n}']})." for n in springs
                      if f"tributary N = {n}" in missing),
            "## Targets\n\n" + target_text(rows, "u_own", "N = 40 within 0.5 % of the same-N "
                                             "reference in peak u, under 20 ms")
            + "\n" + target_text(rows, "u_big", f"N = 40 within 0.5 % of the N = {ref_n} "
                                 "reference in peak u, under 20 ms (the paper's point impact "
                                 "mass)", _floor(refs, big) if big else None)
            + "\n" + target_text(rows_t, "u_big", f"N = 40 within 0.5 % of the N = {ref_n} "
                                 "reference in peak u, under 20 ms (tributary impact mass)",
                                 _floor(refs_t, big_t) if big_t else None),
            part("bed", "## Convergence of the bed in N (event stepper, Δt = 0.02/64 s)",
                 lambda: "## Convergence of the bed in N (event stepper, Δt = 0.02/64 s)\n\n"
                 + bed_text(done["bed"]) + "\n\nCase C with the paper's point impact mass "
                 "need not converge: each landing spring's damper removes (1 − ε²) of the "
                 "closing energy of the mass m_eff(x_i) behind it, so a landing of the whole "
                 "base removes more as N grows (Ewing's damper is defined per spring, not per "
                 "unit length). With the tributary mass (m_eff · k_i/K_v) the energy removed "
                 "per landing does not grow with N."),
            part("batch", "## Batch (`run_batch`, N = 20, Case C, varied yield multiple, ζ_f, "
                 "period)", lambda: "## Batch (`run_batch`, N = 20, Case C, varied yield "
                 "multiple, ζ_f, period)\n\n" + batch_text(done["batch"]))]
    return "\n\n".join(t.strip() for t in text) + "\n"


# ---------------------------------------------------------------------------------------------
# Cost model (module docstring)
# ---------------------------------------------------------------------------------------------


def step_rates(rows: list[dict]) -> dict[str, tuple[float, float]]:
    """Per integrator, (a, b) of CPU seconds per step = a + b·N, least squares over the
    measured rows of the committed Runs table."""
    points: dict[str, list[tuple[int, float]]] = {}
    for r in rows:
        steps = number(r.get("steps", ""))
        if np.isfinite(steps) and steps > 0:
            points.setdefault(r["integrator"], []).append(
                (int(r["N"]), number(r["runtime [ms]"]) / 1e3 / steps))
    rates = {}
    for name, pts in points.items():
        n, y = np.array(pts, dtype=float).T
        b, a = np.polyfit(n, y, 1) if len(set(n)) > 1 else (0.0, float(np.mean(y)))
        rates[name] = (float(a), float(b))
    return rates


def plan_costs(config: dict, repeats: int, span: float) -> dict[str, float | None]:
    """The estimated wall time (s) of each section (module docstring); None without the
    committed table."""
    tables = committed_tables("REDUCED.md")
    runs = tables.get("Runs", [])
    if not runs:
        return {}
    rates = step_rates(runs)
    recorded = {(r["N"], r["integrator"], r["Δt [s] or tolerance"]): number(r["runtime [ms]"])
                / 1e3 for r in runs if np.isfinite(number(r.get("steps", "")))}

    def run_cost(n: int, integrator: str, dt: float) -> float:
        a, b = rates.get(integrator, rates["events"])
        return span / dt * (a + b * n)

    def reference_cost(n: int) -> float:
        dt = RECORD_DT / 2 ** config["reference_k"]
        return run_cost(n, "events", dt) + run_cost(n, "events", dt / 2)

    def sweep_cost(n: int, integrators) -> float | None:
        total = reference_cost(n)
        for integrator in integrators:
            for k in config["k"][integrator]:
                step = _step({"dt": RECORD_DT / 2 ** k, "rtol": 0.0})
                seconds = recorded.get((str(n), integrator, step))
                total += (1 + repeats) * (seconds if seconds is not None
                                          else run_cost(n, integrator, RECORD_DT / 2 ** k))
        default = recorded.get((str(n), "events", _step({"dt": None, "rtol": 1e-5})))
        for rtol in RTOLS:  # a failed row records no time: the default's stands for it
            seconds = recorded.get((str(n), "events", _step({"dt": None, "rtol": rtol})),
                                   default)
            if seconds is None:
                return None
            total += (1 + repeats) * seconds
        return total

    out: dict[str, float | None] = {"reference": reference_cost(config["reference_n"]),
                                    "tributary reference": reference_cost(config["reference_n"])}
    for n in config["springs"]:
        out[f"runs N = {n}"] = sweep_cost(n, INTEGRATORS)
        out[f"tributary N = {n}"] = sweep_cost(n, ("events",))
    out["bed"] = 4 * sum(run_cost(n, "events", RECORD_DT / 64) for n in config["bed"])
    batch_rows = tables.get("Batch (`run_batch`, N = 20, Case C, varied yield multiple, ζ_f, "
                            "period)", [])
    out["batch"] = sum(number(b["per scene [ms]"]) / 1e3 * config["batch_scenes"]
                       + number(b["loop of run() per scene [ms]"]) / 1e3
                       * (config["loop_scenes"] + 5) for b in batch_rows) or None
    return out


def main(argv: list[str] | None = None) -> int:
    # Case C with the paper's damper on many springs warns that it does not converge in N:
    # this benchmark measures exactly that (its bed-convergence table)
    warnings.simplefilter("ignore", ModelWarning)
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true",
                        help="N = 2 and 40, a few steps, reference on 160 springs, one repeat, "
                             "100 scenes")
    add_output_arguments(parser, NAME)
    parser.add_argument("--repeats", type=int, default=None,
                        help="timed runs per point (5; 1 with --quick)")
    parser.add_argument("--workers", type=int, default=2, help="run_batch processes (2)")
    parser.add_argument("--batch-scenes", type=int, default=None,
                        help="scenes in the batch (10,000; 100 with --quick)")
    args = parser.parse_args(argv)
    out = output_folder(args, NAME)
    args.repeats = args.repeats or (1 if args.quick else 5)
    config = dict(QUICK if args.quick else FULL)
    if args.batch_scenes:
        config["batch_scenes"] = args.batch_scenes
    done: dict = {}  # the finished sections' results, which publish() keeps (the sweeps read
    # their reference from it)

    def big_reference(extra=()):
        ref = reference(config["reference_n"], config["reference_k"], extra)
        say(f"reference N = {ref['n']}{' (tributary)' if extra else ''}: {ref['peaks']}, "
            f"halving {ref['halving']}")
        return ref

    sections = [Section("reference", big_reference)]
    sections += [Section(f"runs N = {n}", lambda n=n: sweep(n, config, args.repeats,
                                                              done["reference"]))
                 for n in config["springs"]]
    sections.append(Section("tributary reference", lambda: big_reference(TRIBUTARY)))
    sections += [Section(f"tributary N = {n}", lambda n=n: sweep(
        n, config, args.repeats, done["tributary reference"], ("events",), TRIBUTARY))
        for n in config["springs"]]
    sections += [Section("bed", lambda: bed_convergence(config["bed"], 6)),
                 Section("batch", lambda: batch(config, args.workers))]
    span = scene(2).build_motion().duration
    cost = plan_costs(config, args.repeats, span)
    sections = [Section(s.key, s.compute, cost.get(s.key)) for s in sections]

    drawn = {}  # folder: the sections the figure there was last drawn from

    def publish(folder: Path, results: dict, missing: dict) -> None:
        """The table after every section; the figure when a section it draws has come."""
        done.clear()
        done.update(results)
        text = document(args, config, results, missing)
        write_text(folder / "REDUCED.md", text + kept_section(folder / "REDUCED.md"))
        rows = [r for n in config["springs"] if f"runs N = {n}" in results
                for r in results[f"runs N = {n}"][1]]
        rows_t = [r for n in config["springs"] if f"tributary N = {n}" in results
                  for r in results[f"tributary N = {n}"][1]]
        shown = tuple(k for k in results if k.startswith(("runs N = ", "tributary N = ")))
        if rows and drawn.get(folder) != shown:
            figure(rows, rows_t, folder / "reduced_speed.png")
            drawn[folder] = shown

    def commit(results: dict) -> None:
        publish(HERE, results, {})
        say(f"wrote {HERE / 'REDUCED.md'} and {HERE / 'reduced_speed.png'}")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="runtimes and per-step rates of benchmarks/REDUCED.md")
    if status == 0:
        say(f"wrote {out / 'REDUCED.md'} and {out / 'reduced_speed.png'}")
    return status


if __name__ == "__main__":
    sys.exit(main())
