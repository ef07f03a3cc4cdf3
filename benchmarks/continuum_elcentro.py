"""El Centro on the clay scene: the continuum dynamics' two routes, runtime against error.

Used by ``benchmarks/continuum_speed.py`` (its ``elcentro`` sections); runnable alone:

    python benchmarks/continuum_elcentro.py [--quick] [--out DIR] [--reference DIR]

Alone it writes ``ELCENTRO.md`` to ``--out`` (default ``results/bench/continuum_elcentro``),
rewritten as each run ends (``bench_output``); its committed table is the El Centro section of
``benchmarks/CONTINUUM.md``, which ``continuum_speed.py --write`` rewrites. ``--quick``: the
runs on 4 across over 2 s (about a minute).

Every run: the clay scene (Tresca c_u = 50 kPa, frictionless unilateral contact, Q2 with 2×2
reduced integration, 10B × 10B box) under El Centro 1940 N-S, built and run in this process
(mesh, gravity and time loop timed together, wall clock and process CPU time). The rows:

- ``implicit`` at the Newton tolerance rtol = 1e-6: the accuracy reference of its mesh where
  the converged reference (below) is absent;
- ``implicit`` at the default rtol = 1e-5: the **runtime reference** (today's solver);
- ``implicit`` at half its default step: how far the reference itself is from its own
  time-converged solution (the implicit route's time-discretisation error);
- ``explicit`` (the default route) with one and two numba threads, over the first 10 s and over
  the whole record (31.2 s), and on coarser meshes.

Errors against the reference over the reference's 10 s (a whole-record row is compared on its
first 10 s): peak |θ|, peak edge uplift (the larger gap at x = ±B/2), residual settlement
(v(0) − v(10 s)), and the largest difference of the θ and v − v(0) histories (on the
reference's time grid) over their peaks. The reference is the **converged reference** of
``benchmarks/continuum_reference.py`` (the explicit route on 32 across at half its step, its
time and mesh errors stated in ``benchmarks/CONTINUUM_REFERENCE.md``), read from the rows that
benchmark kept (``--reference DIR``, default ``results/bench/continuum_reference/rows``), for
every row that covers its span; without it (or for a shorter row) the implicit route at rtol
1e-6 on the row's mesh (else the finest mesh's), which is not converged in time itself. The
table's text and its last column say which reference each row was compared with.

Cost model (the estimate printed before any work): each run costs the wall time recorded for
the same run (route, mesh, span, threads, rtol, step) in the El Centro table of the committed
``benchmarks/CONTINUUM.md``; a run that table does not record has no estimate.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, number, output_folder, run_sections, say, write_text)

NAME = "continuum_elcentro"

#: (route, elements across, duration [s] or None for the whole record, rtol or None, threads,
#: step as a fraction of the default)
RUNS = (("implicit", 16, 10.0, 1e-6, 1, 1.0), ("implicit", 16, 10.0, None, 1, 1.0),
        ("explicit", 16, 10.0, None, 1, 1.0), ("explicit", 16, 10.0, None, 2, 1.0),
        ("explicit", 16, None, None, 1, 1.0), ("explicit", 16, None, None, 2, 1.0),
        ("explicit", 8, 10.0, None, 1, 1.0), ("explicit", 4, 10.0, None, 1, 1.0),
        ("implicit", 16, 10.0, 1e-6, 1, 0.5))
#: ``--quick``: the same kinds of row on 4 across, over 2 s (the whole-record row: 31.2 s)
QUICK = (("implicit", 4, 2.0, 1e-6, 1, 1.0), ("implicit", 4, 2.0, None, 1, 1.0),
         ("explicit", 4, 2.0, None, 1, 1.0), ("explicit", 4, 2.0, None, 2, 1.0),
         ("explicit", 4, None, None, 1, 1.0), ("implicit", 4, 2.0, 1e-6, 1, 0.5))
#: Targets: explicit 10 s on 16 across within 60 s and 8 times faster than the
#: implicit run of the same invocation; the whole record within 180 s; peaks and residual
#: settlement within 0.5 %, histories within 1 % of their peaks.
TARGET_10S, TARGET_FULL, TARGET_SPEEDUP, TARGET_PEAKS, TARGET_HISTORY = 60.0, 180.0, 8.0, \
    0.005, 0.01
#: Where ``benchmarks/continuum_reference.py`` keeps its runs (relative to the working folder),
#: and the label of its converged reference there.
REFERENCE_ROWS, CONVERGED = Path("results") / "bench" / "continuum_reference" / "rows", \
    "explicit-32-half"


def unavailable() -> str | None:
    """Why El Centro cannot run here (None if it can)."""
    from upliftlab.checks import InputError
    from upliftlab.motions import ELCENTRO, find_motion
    try:
        find_motion(ELCENTRO)
    except InputError as exc:
        return str(exc)
    return None


def run(route: str, n: int, duration: float | None, rtol: float | None, threads: int,
        step: float = 1.0) -> dict:
    """One timed run: its histories and settings (``step``: the time step as a fraction of the
    route's default)."""
    from dataclasses import replace

    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
    from upliftlab.motions import ELCENTRO
    from upliftlab.scenes import load_scene

    overrides = [f"continuum.elements_across={n}", f"continuum.dynamics={route}"]
    if duration is not None:
        overrides.append(f"analysis.duration={duration}")
    scene = load_scene("strip_footing_clay", motion=ELCENTRO, overrides=overrides)
    motion = scene.build_motion()
    options = DynamicOptions(snapshots=0, threads=threads)
    if rtol is not None:
        options = replace(options, newton=replace(options.newton, rtol=rtol))
    wall, cpu = time.perf_counter(), time.process_time()
    model = build_model(scene)
    if step != 1.0:
        options = replace(options, dt=step * default_step(model, motion, route))
    result = run_dynamic(model, scene, motion, options)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    gap = np.asarray(result.gap)
    return {"route": route, "n": n, "duration": float(result.time[-1]), "threads": threads,
            "step": step,
            "rtol": rtol if rtol is not None else options.newton.rtol, "dofs": model.dofs,
            "wall": wall, "cpu": cpu, "steps": int(result.metadata["steps"]),
            "dt": float(result.metadata["dt"]), "energy": result.energy_balance_error,
            "time": np.asarray(result.time), "theta": np.asarray(result.footing)[:, 2],
            "v": np.asarray(result.footing)[:, 1],
            "edge": np.maximum(gap[:, 0], gap[:, -1])}


def default_step(model, motion, route: str) -> float:
    """The route's automatic step on this mesh and record (s)."""
    from upliftlab.continuum.dynamics import explicit
    from upliftlab.continuum.dynamics.run import dynamic_fixed, time_step_limit

    if route == "implicit":
        limit = time_step_limit(model)
    else:
        free = np.setdiff1d(np.arange(model.disc.ndofs),
                            dynamic_fixed(model, "rigid", "rollers"))
        limit = explicit.STABILITY_FRACTION * explicit.critical_step(
            model, explicit.lumped_mass(model), free)[0]
    return motion.dt / max(1, math.ceil(motion.dt / limit * (1.0 - 1e-12)))


def _window(row: dict, end: float) -> dict:
    keep = row["time"] <= end * (1.0 + 1e-9)
    return {k: row[k][keep] for k in ("time", "theta", "v", "edge")}


#: The errors of :func:`compare`, in its order.
ERRORS = ("peak theta", "peak edge uplift", "residual settlement", "theta history",
          "v history")


def compare(row: dict, reference: dict) -> dict:
    """Errors of ``row`` against ``reference`` over the reference's span (module docstring)."""
    ref = _window(reference, reference["time"][-1])
    mine = _window(row, reference["time"][-1])
    peak_theta = np.abs(ref["theta"]).max()
    dv_ref = ref["v"] - ref["v"][0]
    dv = np.interp(ref["time"], mine["time"], mine["v"] - mine["v"][0])
    theta = np.interp(ref["time"], mine["time"], mine["theta"])
    end = mine["time"][-1]
    return {
        "peak theta": np.abs(mine["theta"]).max() / peak_theta - 1.0,
        "peak edge uplift": mine["edge"].max() / ref["edge"].max() - 1.0,
        "residual settlement": (mine["v"][0] - np.interp(end, mine["time"], mine["v"]))
        / (ref["v"][0] - ref["v"][-1]) - 1.0,
        "theta history": np.abs(theta - ref["theta"]).max() / peak_theta,
        "v history": np.abs(dv - dv_ref).max() / np.abs(dv_ref).max(),
    }


def description() -> str:
    """The module docstring's account of the rows and errors (for the tables' text)."""
    paragraphs = __doc__.split("\n\n")
    start = next(i for i, p in enumerate(paragraphs) if p.startswith("Every run:"))
    end = next(i for i, p in enumerate(paragraphs) if p.startswith("Cost model"))
    return "\n\n".join(paragraphs[start:end]).strip()


def describe(row: dict) -> str:
    """One progress line of a finished run."""
    return (f"elcentro {row['route']:8s} n = {row['n']:2d}, {row['duration']:5.1f} s, "
            f"rtol {row['rtol']:g}, threads {row['threads']}, step × {row['step']:g}: "
            f"{row['wall']:8.1f} s wall, {row['cpu']:8.1f} s CPU, {row['steps']} steps, "
            f"energy {row['energy']:.2g}")


def converged_reference(folder: str | os.PathLike | None = REFERENCE_ROWS) -> dict | None:
    """The converged reference kept in ``folder`` (``<folder>/explicit-32-half.npz``, written
    by ``benchmarks/continuum_reference.py``) with its ``source`` path, or None if absent."""
    path = Path(folder) / f"{CONVERGED}.npz" if folder is not None else None
    if path is None or not path.is_file():
        return None
    with np.load(path) as data:
        row = {k: data[k] for k in data.files}
    return {**row, "source": str(path)}


def reference_note(converged: dict | None, folder=REFERENCE_ROWS) -> str:
    """The sentence of the table's text saying which reference the errors are against."""
    if converged is not None:
        return (f"Errors against the converged reference, the explicit route on 32 across at "
                f"half its step ({float(converged['time'][-1]):g} s, dt "
                f"{float(converged['dt']):.3g} s), read from `{converged['source']}` "
                "(`benchmarks/continuum_reference.py`); a row shorter than it is compared with "
                "the implicit route at rtol 1e-6, as its last column says.")
    return (f"No converged reference was found (`{Path(folder) / (CONVERGED + '.npz')}`: run "
            "`benchmarks/continuum_reference.py`): the errors are against the implicit route "
            "at rtol 1e-6, which is not converged in time itself (its θ history moves by "
            "2.7 % of its peak when its step is halved, `CONTINUUM_CONVERGENCE.md`).")


def finish(rows: list[dict], converged: dict | None = None) -> list[dict]:
    """``rows`` (finished runs) with their errors against the ``converged`` reference
    (:func:`converged_reference`) where given and the row covers its span, else against the
    implicit rtol 1e-6 run of their mesh (else the finest mesh's; NaN without one), and their
    speed-up over the implicit runtime reference of the same mesh and span."""
    finest = max(r["n"] for r in rows)
    reference = {r["n"]: r for r in rows if r["route"] == "implicit" and r["rtol"] < 1e-5
                 and r["step"] == 1.0}
    runtime = {r["n"]: r for r in rows if r["route"] == "implicit" and r["rtol"] >= 1e-5}
    out = []
    for r in rows:
        ref = reference.get(r["n"]) or reference.get(finest)
        r = dict(r)
        if converged is not None and \
                r["time"][-1] >= float(converged["time"][-1]) * (1.0 - 1e-9):
            r["reference"] = "converged: explicit 32 across, half step"
            r["errors"] = compare(r, converged)
        elif ref is None:
            r["reference"] = "missing: no implicit rtol 1e-6 run"
            r["errors"] = dict.fromkeys(ERRORS, math.nan)
        else:
            r["reference"] = f"implicit rtol 1e-6, {ref['n']} across"
            r["errors"] = compare(r, ref)
        base = runtime.get(r["n"])  # the implicit run of the same mesh and span
        same = base is not None and abs(base["duration"] - r["duration"]) < 1e-9
        r["speedup"] = base["wall"] / r["wall"] if same else math.nan
        out.append(r)
    return out


def measure(quick: bool = False, say=print) -> list[dict]:
    """Every run of :data:`RUNS` (or :data:`QUICK`), with errors and speed-ups."""
    rows = []
    for spec in (QUICK if quick else RUNS):
        rows.append(run(*spec))
        say(describe(rows[-1]))
    return finish(rows)


def cost(spec: tuple) -> float | None:
    """The wall time (s) the committed CONTINUUM.md records for the run ``spec`` (a row of
    :data:`RUNS`), or None."""
    route, n, duration, rtol, threads, step = spec
    label = route + (f", step × {step:g}" if step != 1.0 else "")
    rows = [r for head, rows in committed_tables("CONTINUUM.md").items()
            if head.startswith("El Centro") for r in rows if "route" in r]
    for r in rows:
        span = number(r["simulated [s]"])
        if (r["route"] == label and r["n across"] == str(n) and r["threads"] == str(threads)
                and (span <= 10.0 + 1e-9) == (duration is not None)
                and (route == "explicit" or number(r["rtol"]) == (rtol or 1e-5))):
            return number(r["wall [s]"])
    return None


def sections(specs, rows: list[dict]) -> list[Section]:
    """One section per run of ``specs``: it runs, appends to ``rows`` and returns the row."""
    def one(spec):
        rows.append(run(*spec))
        say(describe(rows[-1]))
        return rows[-1]
    return [Section(f"elcentro {i + 1}: {spec[0]} {spec[1]} across"
                    f"{'' if spec[2] is None else f', {spec[2]:g} s'}"
                    f"{'' if spec[3] is None else f', rtol {spec[3]:g}'}, {spec[4]} thread(s)"
                    f"{'' if spec[5] == 1.0 else f', step × {spec[5]:g}'}",
                    lambda spec=spec: one(spec), cost(spec)) for i, spec in enumerate(specs)]


def table(rows: list[dict]) -> str:
    names = list(rows[0]["errors"])
    lines = ["| route | n across | DOFs | simulated [s] | threads | rtol | steps | dt [s] | "
             "wall [s] | CPU [s] | speed-up vs implicit | "
             + " | ".join(names) + " | energy balance | compared with |",
             "|" + "---|" * (13 + len(names))]
    for r in rows:
        e = " | ".join(f"{100 * r['errors'][k]:+.3f} %" if "history" not in k
                       else f"{100 * r['errors'][k]:.3f} %" for k in names)
        rtol = f"{r['rtol']:g}" if r["route"] == "implicit" else "–"
        speed = f"{r['speedup']:.1f}×" if math.isfinite(r["speedup"]) else "–"
        route = r["route"] + (f", step × {r['step']:g}" if r["step"] != 1.0 else "")
        lines.append(f"| {route} | {r['n']} | {r['dofs']} | {r['duration']:.1f} | "
                     f"{r['threads']} | {rtol} | {r['steps']} | {r['dt']:.3g} | "
                     f"{r['wall']:.1f} | {r['cpu']:.1f} | {speed} | {e} | {r['energy']:.1g} | "
                     f"{r['reference']} |")
    return "\n".join(lines)


def targets(rows: list[dict]) -> str:
    """The issue's targets with the rows that decide them."""
    finest = max(r["n"] for r in rows)
    ex10 = [r for r in rows if r["route"] == "explicit" and r["n"] == finest
            and r["duration"] <= 10.0 + 1e-9]
    full = [r for r in rows if r["route"] == "explicit" and r["n"] == finest
            and r["duration"] > 10.0 + 1e-9]
    lines = ["| target | met | measured |", "|---|---|---|"]

    def line(what, ok, measured):
        lines.append(f"| {what} | {'yes' if ok else 'no'} | {measured} |")

    if ex10:
        best = min(ex10, key=lambda r: r["wall"])
        line(f"{best['duration']:g} s on {finest} across within {TARGET_10S:g} s",
             best["wall"] <= TARGET_10S,
             f"{best['wall']:.1f} s ({best['threads']} thread(s); CPU {best['cpu']:.1f} s)")
        line(f"at least {TARGET_SPEEDUP:g}× the implicit run of this invocation",
             best["speedup"] >= TARGET_SPEEDUP, f"{best['speedup']:.1f}×")
        worst = {k: max(abs(r["errors"][k]) for r in ex10) for k in best["errors"]}
        peaks = max(worst[k] for k in worst if "history" not in k)
        history = max(worst[k] for k in worst if "history" in k)
        against = "; ".join(sorted({r["reference"] for r in ex10}))
        line(f"peaks and residual settlement within {100 * TARGET_PEAKS:g} % of the reference "
             f"({against})", peaks <= TARGET_PEAKS, f"worst {100 * peaks:.3f} %")
        line(f"θ and v histories within {100 * TARGET_HISTORY:g} % of their peaks",
             history <= TARGET_HISTORY, f"worst {100 * history:.3f} %")
    if full:
        best = min(full, key=lambda r: r["wall"])
        line(f"the whole record ({best['duration']:.1f} s) on {finest} across within "
             f"{TARGET_FULL:g} s", best["wall"] <= TARGET_FULL,
             f"{best['wall']:.1f} s ({best['threads']} thread(s); CPU {best['cpu']:.1f} s)")
    return "\n".join(lines)


def document(rows: list[dict], missing: dict, quick: bool, converged: dict | None = None,
             folder=REFERENCE_ROWS) -> str:
    """ELCENTRO.md: the runs so far, their errors (against ``converged`` where given, else the
    implicit route) and the targets."""
    text = (f"# El Centro: explicit and implicit dynamics\n\n`python benchmarks/"
            f"continuum_elcentro.py{' --quick' if quick else ''}`.\n\n"
            + incomplete_note(missing) + description() + "\n\n"
            + reference_note(converged, folder) + "\n\n")
    if rows:
        done = finish(rows, converged)
        text += table(done) + "\n\n## Targets\n\n" + targets(done) + "\n"
    return text


def main(argv=None) -> int:
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="4 across instead of 16")
    parser.add_argument("--reference", default=str(REFERENCE_ROWS),
                        help="the rows kept by benchmarks/continuum_reference.py, whose "
                             f"{CONVERGED}.npz is the converged reference (default "
                             f"{REFERENCE_ROWS}; absent: the implicit route at rtol 1e-6)")
    add_output_arguments(parser, NAME, committed=False)
    args = parser.parse_args(argv)
    out = output_folder(args, NAME)
    why = unavailable()
    if why:
        say(f"{NAME}: error: {why}; nothing was run or written")
        return 2
    converged = converged_reference(args.reference)
    say(reference_note(converged, args.reference))
    rows: list[dict] = []

    def publish(folder, done, missing):
        write_text(folder / "ELCENTRO.md",
                   document(rows, missing, args.quick, converged, args.reference))

    status = run_sections(NAME, sections(QUICK if args.quick else RUNS, rows), publish, out,
                          model="wall times recorded in benchmarks/CONTINUUM.md")
    if status == 0:
        done = finish(rows, converged)
        print(reference_note(converged, args.reference) + "\n\n" + table(done) + "\n\n"
              + targets(done))
        say(f"wrote {out / 'ELCENTRO.md'}")
    return status


if __name__ == "__main__":
    sys.exit(main())
