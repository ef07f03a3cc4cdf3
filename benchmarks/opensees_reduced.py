"""The reduced model against OpenSeesPy: the short-period building on El Centro, side by side.

    python benchmarks/opensees_reduced.py [--case A|B ...] [--springs N ...] [--dt DT ...]
                                          [--dashpots clipped|detaching|parallel ...]
                                          [--check ZETA ...] [--timeout S] [--quick]
                                          [--out DIR] [--write]

The same scene (``short_period_elcentro``, N Winkler springs, the whole 31.2 s record) in both
models. The OpenSees model is the one ``upliftlab opensees`` writes (the bridge in
``upliftlab.comparisons.opensees``: upliftlab's own numbers in a standalone OpenSeesPy script,
zeroLength springs under a rigid footing, Newmark average acceleration with Newton, run in a
subprocess with a timeout; without openseespy the OpenSees rows say so). Its foundation
dashpots in three ways (``--dashpots``): ``clipped`` — spring and dashpot inside TensionOnly, so
that they detach together and their sum never pulls, as upliftlab's (it differs before a
landing: the dashpot pushes once the gap is below β·v, β = c_i/k_i); ``detaching`` —
stiffness-proportional Rayleigh damping on each spring's current tangent (acts only in contact,
never clipped); ``parallel`` — a Viscous beside the spring, attached even while it is open.
upliftlab runs in this process, in the same run: the event stepper converged (Δt = 0.02/1024 s,
the reference of the errors in brackets) and at its default settings, and its Newmark at each
OpenSees Δt. Times: OpenSees' is the time-step loop in the child (model and gravity excluded);
upliftlab's the median of 3 ``run(..., histories=False)`` calls. ``--check`` adds Case A with
those foundation damping ratios (0: no dashpot, the models are the same).

Each scene is a section (``bench_output``): ``OPENSEES_REDUCED.md`` (and the scripts of every
run) are written to ``--out`` (default ``results/bench/opensees_reduced``) as each ends;
``--write`` also replaces the OpenSees section of the committed ``benchmarks/REDUCED.md``
(between markers that ``reduced_speed.py`` keeps) once every scene has completed. ``--quick`` (a
smoke check, never committed): Case A without foundation dashpots (ζ_f = 0, where the two models
are the same), N = 12, Δt = 0.002 s, one OpenSees run.

Cost model (the estimate printed before any work; about 20 min for the default run): each
OpenSees run costs (record span / Δt) steps × the median time per step of the OpenSees rows of
the committed ``benchmarks/REDUCED.md``, and each scene the median runtime of its upliftlab
reference rows there.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import shlex  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, number, output_folder, run_sections, say, write_text)

NAME = "opensees_reduced"
SCENE = "short_period_elcentro"
MARK_BEGIN, MARK_END = "<!-- opensees_reduced: begin -->", "<!-- opensees_reduced: end -->"


def _scene(case: str, springs: int, extra=()):
    from upliftlab.scenes import load_scene

    return load_scene(SCENE, case=case, overrides=[f"foundation.springs={springs}", *extra])


def upliftlab_run(scene, integrator: str, dt: float | None, repeats: int = 3) -> dict:
    from upliftlab.reduced import IntegrationError, run

    try:
        response = run(scene, integrator=integrator, dt=dt, histories=False)  # warm-up
    except IntegrationError as exc:  # e.g. an energy balance beyond analysis.energy_tolerance
        return {"status": f"refused: {str(exc).split(': ', 1)[-1][:120]}"}
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        response = run(scene, integrator=integrator, dt=dt, histories=False)
        times.append(time.perf_counter() - start)
    pk = response.peaks
    return {"status": "ok", "u": pk["u"], "theta": pk["theta"], "uplift": pk["uplift_left"],
            "runtime": statistics.median(times), "dt": response.info["dt"]}


def opensees_run(scene, dt: float, dashpots: str, out: Path, timeout: float) -> dict:
    """Write the bridge's script of ``scene`` into ``out`` and run it."""
    from upliftlab.comparisons.opensees import (OpenSeesError, opensees_spec, run_script,
                                                write_script)

    files = write_script(opensees_spec(scene, dt=dt, dashpots=dashpots), out)
    try:
        result = run_script(files.script, timeout=timeout, echo=False)
    except OpenSeesError as exc:
        return {"status": str(exc)[:200]}
    s = result.summary
    return {"status": "ok", "u": s["peak_u"], "theta": s["peak_theta"],
            "uplift": s["peak_uplift_left"], "runtime": s["runtime_s"], "steps": s["steps"],
            "setup": s["setup_s"]}


def row(label: str, r: dict, ref: dict, ratio_to: float | None) -> str:
    if r.get("status") != "ok":
        return f"| {label} | – | {r.get('status')} | – | – | – | – |"
    err = {k: r[k] / ref[k] - 1.0 for k in ("u", "theta", "uplift")}
    ratio = f"{r['runtime'] / ratio_to:.3g}" if ratio_to else "–"
    return (f"| {label} | {1e3 * r['runtime']:.1f} | {ratio} | {r['u']:.5g} ({err['u']:+.2%}) "
            f"| {r['theta']:.5g} ({err['theta']:+.2%}) | {r['uplift']:.5g} "
            f"({err['uplift']:+.2%}) | {r.get('note', '')} |")


def compare(case: str, springs: int, dts: list[float], dashpots: list[str], available: bool,
            timeout: float, out: Path, extra=()) -> str:
    scene = _scene(case, springs, extra)
    ref = upliftlab_run(scene, "events", 0.02 / 1024, repeats=1)
    events = upliftlab_run(scene, "events", None)
    title = f"### Case {case}, N = {springs}" + (f", {', '.join(extra)}" if extra else "")
    lines = [title + "\n",
             "| model | runtime [ms] | runtime / upliftlab events (default Δt) | peak u [in] "
             "| peak θ [rad] | peak uplift, leftmost [in] | note |", "|" + "---|" * 7,
             row("upliftlab events, Δt = 0.02/1024 s (reference)", ref, ref, events["runtime"]),
             row(f"upliftlab events, default Δt = {events['dt']:.3g} s", events, ref,
                 events["runtime"])]
    no_dashpots = scene.foundation.damping_ratio == 0.0
    for dt in dts:
        mine = upliftlab_run(scene, "newmark", dt)
        lines.append(row(f"upliftlab newmark, Δt = {dt:g} s", mine, ref, events["runtime"]))
        for kind in dashpots[:1] if no_dashpots else dashpots:
            label = "OpenSees" if no_dashpots else f"OpenSees {kind} dashpots"
            if not available:
                lines.append(f"| {label}, Δt = {dt:g} s | – | skipped: openseespy is not "
                             "importable | – | – | – | – |")
                continue
            folder = (out / f"case{case}-N{springs}-zeta{scene.foundation.damping_ratio:g}-"
                            f"{kind}-dt{dt:g}")
            result = opensees_run(scene, dt, kind, folder, timeout)
            if result.get("status") == "ok":
                result["note"] = f"{result['steps']} steps; setup {result['setup']:.2f} s"
                if mine.get("status") == "ok":
                    result["note"] += (f"; {result['runtime'] / mine['runtime']:.0f} × "
                                       "upliftlab newmark at this Δt")
            lines.append(row(f"{label}, Δt = {dt:g} s", result, ref, events["runtime"]))
            print(lines[-1], file=sys.stderr, flush=True)
    return "\n".join(lines)


SECTION_HEAD = """## OpenSees comparison (`python benchmarks/opensees_reduced.py`)

Short-period building on El Centro, N springs: the OpenSeesPy model that `upliftlab opensees`
writes (upliftlab's own numbers; zeroLength springs under a rigid footing — Elastic without
tension stiffness for Case A, ElasticPPGap with damage for Case B; rigid links with Lagrange
constraints; Newmark 0.5/0.25 with Newton), run in a subprocess. Errors in brackets are against
upliftlab's converged event stepper. Foundation dashpots: "clipped" — spring and dashpot inside
TensionOnly (twice), so they detach together and their sum never pulls, as upliftlab's, but the
dashpot starts to push before a landing, once the gap is below β·v (β = c_i/k_i = 2ζ_f/ω_v:
7.6 ms for Case A's 40 %, 1.9 ms for B's 10 %), where upliftlab's starts at contact;
"detaching" — stiffness-proportional Rayleigh damping on each spring's current tangent
(β = c_i/k_i), acting only in contact, never clipped (and not while a spring yields);
"parallel" — a Viscous material beside the spring, attached even while it is open. The uplift
is the gap under the leftmost spring from its settled surface in both. OpenSees runtimes are
the time-step loop in the child; upliftlab's the median of 3 `run(..., histories=False)` calls
in the parent, the same run. Command: `{command}`.

"""


def write_section(path: Path, text: str) -> None:
    """Put ``text`` between this script's markers in ``path`` (appended if absent)."""
    old = path.read_text() if path.exists() else ""
    block = f"{MARK_BEGIN}\n{text}\n{MARK_END}"
    if MARK_BEGIN in old and MARK_END in old:
        head, rest = old.split(MARK_BEGIN, 1)
        new = head + block + rest.split(MARK_END, 1)[1]
    else:
        new = old.rstrip("\n") + ("\n\n" if old else "") + block + "\n"
    write_text(path, new)


def scene_cost(dts: list[float], kinds: int, span: float) -> float | None:
    """Estimated wall time (s) of one scene (module docstring); None without the committed
    OpenSees rows."""
    rows = [r for head, table in committed_tables("REDUCED.md").items()
            if head.startswith("Case ") for r in table]
    per_step = [number(r["runtime [ms]"]) / 1e3 / number(r["note"].split(" steps")[0])
                for r in rows if r["model"].startswith("OpenSees") and " steps" in r["note"]]
    reference = [number(r["runtime [ms]"]) / 1e3 for r in rows if "(reference)" in r["model"]]
    if not per_step or not reference:
        return None
    return float(np.median(reference)) + kinds * sum(span / dt for dt in dts) \
        * float(np.median(per_step))


def main(argv: list[str] | None = None) -> int:
    from upliftlab.comparisons.opensees import opensees_available

    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", nargs="+", default=["A", "B"])
    parser.add_argument("--springs", nargs="+", type=int, default=[12],
                        help="foundation springs (default 12, the scene's own, Fig. 1b)")
    parser.add_argument("--dt", nargs="+", type=float, default=[0.002, 0.001, 0.0005])
    parser.add_argument("--dashpots", nargs="+", default=["clipped", "detaching", "parallel"],
                        choices=["clipped", "detaching", "parallel"])
    parser.add_argument("--timeout", type=float, default=900.0, help="per OpenSees run (s)")
    parser.add_argument("--quick", action="store_true",
                        help="Case A with ζ_f = 0, N = 12, Δt = 0.002 s (a smoke check)")
    parser.add_argument("--check", nargs="*", type=float, default=[0.0, 0.1],
                        help="also Case A with these foundation damping ratios ζ_f (default 0 "
                             "and 0.1): 0 checks the mapping of the model free of any dashpot "
                             "definition; the others show how the difference grows with ζ_f")
    add_output_arguments(parser, NAME)
    args = parser.parse_args(argv)
    out = output_folder(args, NAME)
    if args.quick:
        args.case, args.springs, args.dt, args.check = [], [12], [0.002], [0.0]
    available = opensees_available()
    if not available:
        if args.write:
            say(f"{NAME}: error: --write needs openseespy (pip install "
                "'upliftlab[opensees]'); nothing was run or written")
            return 2
        say("openseespy is not importable (pip install 'upliftlab[opensees]'): the OpenSees "
            "runs are skipped")
    runs = [("A", (f"foundation.damping_ratio={z:g}",)) for z in args.check]
    runs += [(case, ()) for case in args.case]
    span = _scene("A", args.springs[0]).build_motion().duration
    parts: dict[str, str] = {}

    def one(case, n, extra) -> str:
        return compare(case, n, args.dt, args.dashpots, available, args.timeout, out, extra)

    sections = []
    for case, extra in runs:
        for n in args.springs:
            kinds = 1 if extra == ("foundation.damping_ratio=0",) else len(args.dashpots)
            sections.append(Section(f"Case {case}, N = {n}" + (f", {', '.join(extra)}"
                                                                if extra else ""),
                                    lambda c=case, k=n, e=extra: one(c, k, e),
                                    scene_cost(args.dt, kinds if available else 0, span)))
    command = "python benchmarks/opensees_reduced.py " + " ".join(
        shlex.quote(a) for a in (argv if argv is not None else sys.argv[1:]))

    def document(done: dict, missing: dict) -> str:
        return (SECTION_HEAD.format(command=command.strip()) + incomplete_note(missing)
                + "\n\n".join(done.values()))

    def publish(folder: Path, done: dict, missing: dict) -> None:
        parts.clear()
        parts.update(done)
        write_text(folder / "OPENSEES_REDUCED.md", document(done, missing) + "\n")

    def commit(done: dict) -> None:
        write_section(HERE / "REDUCED.md", document(done, {}))
        say(f"wrote the OpenSees section of {HERE / 'REDUCED.md'}")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="per-step times of the OpenSees rows in benchmarks/REDUCED.md")
    if status == 0:
        print(document(parts, {}))
    return status


if __name__ == "__main__":
    sys.exit(main())
