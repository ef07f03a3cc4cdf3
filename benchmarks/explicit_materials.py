"""Per-step cost of the explicit route by soil model: compiled Tresca, compiled Mohr–Coulomb and
the Mohr–Coulomb fallback (the Python loop with the vectorised return map), side by side.

    python benchmarks/explicit_materials.py [--quick] [--steps S] [--repeats R] [--out DIR]
                                            [--write]

Every run: the clay scene's footing and structure (B = 2 m, N = 171.39 kN/m, frictionless
unilateral contact, Q2 with 2×2 reduced integration, 10B × 10B box, rigid base, one numba
thread) on either the clay (Tresca, c_u = 50 kPa) or the Winkler map's frictional soil
(Mohr–Coulomb, c = 5 kPa, φ = ψ = 30°, comparisons/studies/winkler_map/grid.py ``SOILS["sand"]``),
under
a 0.6 g Ricker pulse of 0.4 s centred at t = 0 (so that the soil is loaded from the first
step), for about ``--steps`` steps (default 300) on 8 and 16 elements across B.

The time per step is the wall time (and the process's CPU time, less disturbed by the other
processes of a shared machine) between the first and the last recorded row (the progress
callback's calls) over the steps between them: it leaves out the mesh, the stable step, the
gravity state and the compilation (a warm-up run compiles the kernels first), which the
``fixed`` column holds (mesh to the first row). Every case runs ``--repeats`` times (default
3), the cases interleaved so that a change in the machine's load falls on all of them; the
tables give the medians. Ratios are of runs of the same invocation.
The error column compares the compiled Mohr–Coulomb run with the fallback of the same mesh
(largest difference of the footing history (u, v, θ) and of the element ε̄p snapshots, over
their peaks); ``yielded`` is the share of elements whose average ε̄p grew during the motion.

Each round of repeats (every case once) is a section (``bench_output``): ``EXPLICIT_MATERIALS.md``
is rewritten in ``--out`` (default ``results/bench/explicit_materials``) as each ends, with the
medians of the rounds so far; ``--write`` also rewrites the committed
``benchmarks/EXPLICIT_MATERIALS.md`` once every round has completed (never with ``--quick``: 4
and 8 across, 100 steps, one round).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, incomplete_note,  # noqa: E402
                          output_folder, run_sections, say, write_text)

NAME = "explicit_materials"
#: The soils: the clay scene's Tresca clay and the Winkler map's frictional soil.
SOILS = {"tresca": [],
         "mohr_coulomb": ["soil.model=mohr_coulomb", "soil.cohesion=5",
                          "soil.friction_angle=30", "soil.dilation_angle=30"]}
#: (soil, route) of the rows of each mesh.
CASES = (("tresca", "compiled"), ("mohr_coulomb", "compiled"), ("mohr_coulomb", "fallback"))
MOTION = ["motion.amplitude=0.6", "motion.period=0.4", "motion.delay=0"]
MESHES, QUICK_MESHES = (8, 16), (4, 8)
#: The stable step of each mesh (s), to size the runs (benchmarks/CONTINUUM.md: 16 across
#: 0.000235 s, 8 across 0.000465 s, 4 across 0.000952 s); the runs take their own step.
STEP = {4: 0.000952, 8: 0.000465, 16: 0.000235}


def run(soil: str, route: str, n: int, steps: int) -> dict:
    """One run of ``soil`` on ``n`` across through the ``route`` (compiled or fallback)."""
    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
    from upliftlab.continuum.materials import MohrCoulomb
    from upliftlab.scenes import load_scene

    duration = steps * STEP[n]
    overrides = SOILS[soil] + MOTION + [f"continuum.elements_across={n}",
                                        f"motion.duration={duration:.6g}"]
    rows = []
    compiled = MohrCoulomb.Constants
    if route == "fallback":  # no compiled point return: the vectorised fallback
        MohrCoulomb.Constants = None
    try:
        start = time.perf_counter()
        scene = load_scene("strip_footing_clay", overrides=overrides)
        model = build_model(scene)
        result = run_dynamic(model, scene, scene.build_motion(),
                             DynamicOptions(method="explicit", snapshots=2, threads=1),
                             progress=lambda k, total, state: rows.append(
                                 (k, time.perf_counter(), time.process_time())))
    finally:
        MohrCoulomb.Constants = compiled
    assert result.metadata["compiled"] == (route == "compiled")
    (k0, t0, c0), (k1, t1, c1) = rows[0], rows[-1]
    return {"soil": soil, "route": route, "n": n, "dofs": model.dofs, "steps": k1 - k0,
            "per_step": (t1 - t0) / (k1 - k0), "cpu_per_step": (c1 - c0) / (k1 - k0),
            "fixed": t0 - start,
            "energy": result.energy_balance_error, "footing": np.asarray(result.footing),
            "eps": np.asarray(result.plastic_strain)}


def median(rows: list[dict]) -> dict:
    """The first of ``rows`` (repeats of one case: the same histories) with the medians of
    their times."""
    return {**rows[0], **{key: float(np.median([r[key] for r in rows]))
                          for key in ("per_step", "cpu_per_step", "fixed")}}


def yielded(row: dict) -> float:
    """Share of elements whose average ε̄p grew between the first and the last snapshot."""
    return float(np.mean(row["eps"][-1] > row["eps"][0]))


def error(row: dict, reference: dict) -> str:
    """The largest difference of the footing history and of the ε̄p snapshots, over their
    peaks, of ``row`` against ``reference``."""
    foot = np.abs(row["footing"] - reference["footing"]).max() / np.abs(
        reference["footing"]).max()
    eps = np.abs(row["eps"] - reference["eps"]).max() / np.abs(reference["eps"]).max()
    return f"footing {foot:.1e}, ε̄p {eps:.1e}"


def table(results: list[dict]) -> list[str]:
    lines = ["| n across | DOFs | soil | route | steps | per step [ms] | CPU per step [ms] | "
             "per step and DOF [s] | × compiled Tresca | fixed [s] | yielded | energy balance | "
             "against the fallback |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for n in sorted({r["n"] for r in results}):
        mesh = [r for r in results if r["n"] == n]
        tresca = next(r for r in mesh if r["soil"] == "tresca")
        fallback = next(r for r in mesh if r["route"] == "fallback")
        for r in mesh:
            against = error(r, fallback) if r["soil"] == "mohr_coulomb" and r is not fallback \
                else "–"
            lines.append(
                f"| {n} | {r['dofs']} | {r['soil']} | {r['route']} | {r['steps']} | "
                f"{1e3 * r['per_step']:.3g} | {1e3 * r['cpu_per_step']:.3g} | "
                f"{r['per_step'] / r['dofs']:.2e} | "
                f"{r['per_step'] / tresca['per_step']:.2f} | {r['fixed']:.2f} | "
                f"{100 * yielded(r):.0f} % | {r['energy']:.1e} | {against} |")
    return lines


def ratios(results: list[dict]) -> list[str]:
    lines = ["| n across | time | fallback / compiled Mohr–Coulomb | "
             "compiled Mohr–Coulomb / Tresca |", "|---|---|---|---|"]
    for n in sorted({r["n"] for r in results}):
        for key, label in (("per_step", "wall"), ("cpu_per_step", "CPU")):
            by = {(r["soil"], r["route"]): r[key] for r in results if r["n"] == n}
            mc = by["mohr_coulomb", "compiled"]
            lines.append(f"| {n} | {label} | {by['mohr_coulomb', 'fallback'] / mc:.1f} | "
                         f"{mc / by['tresca', 'compiled']:.2f} |")
    return lines


def document(args, rounds: list[list[dict]], missing: dict) -> str:
    """EXPLICIT_MATERIALS.md: the medians over the rounds done so far."""
    runs: dict[tuple, list[dict]] = {}
    for row in (r for done in rounds for r in done):
        runs.setdefault((row["n"], row["soil"], row["route"]), []).append(row)
    results = [median(rows) for rows in runs.values()]
    text = ["# Explicit route: per-step cost by soil model", "",
            f"Measured {datetime.date.today().isoformat()} on {platform.machine()} "
            f"({os.cpu_count()} cores, shared), Python {platform.python_version()}, one numba "
            f"thread; command `python benchmarks/explicit_materials.py"
            f"{' --quick' if args.quick else ''} --steps {args.steps} --repeats {args.repeats}`"
            f", medians of {len(rounds)} repeat(s). "
            "What is timed and compared: the script's docstring.", ""]
    if missing:
        text += [incomplete_note(missing).strip(), ""]
    if results:
        text += [*table(results), "", "Ratios of the time per step (same invocation):", "",
                 *ratios(results)]
    return "\n".join(text) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="4 and 8 across, 100 steps, one round (a smoke check)")
    parser.add_argument("--steps", type=int, default=None,
                        help="steps per run (default 300; 100 with --quick)")
    parser.add_argument("--repeats", type=int, default=None,
                        help="runs per case (default 3; 1 with --quick)")
    add_output_arguments(parser, NAME)
    args = parser.parse_args(argv)
    args.steps = args.steps or (100 if args.quick else 300)
    args.repeats = args.repeats or (1 if args.quick else 3)
    if args.steps < 10:
        parser.error(f"--steps = {args.steps}: valid range is >= 10")
    if args.repeats < 1:
        parser.error(f"--repeats = {args.repeats}: valid range is >= 1")
    folder = output_folder(args, NAME)
    meshes = QUICK_MESHES if args.quick else MESHES
    rounds: list[list[dict]] = []

    def one_round(k: int) -> list[dict]:
        """Every case once, the cases interleaved (module docstring)."""
        done = []
        for n in meshes:
            for soil, route in CASES:
                done.append(run(soil, route, n, args.steps))
                say(f"round {k + 1}/{args.repeats}: {soil} {route} {n} across: "
                    f"{1e3 * done[-1]['per_step']:.3g} ms per step")
        rounds.append(done)
        return done

    sections = [Section("warm-up", lambda: run("tresca", "compiled", 4, 20))]  # compiles
    sections += [Section(f"round {k + 1}", lambda k=k: one_round(k))
                 for k in range(args.repeats)]

    def publish(target: Path, done: dict, missing: dict) -> None:
        write_text(target / "EXPLICIT_MATERIALS.md", document(args, rounds, missing))

    def commit(done: dict) -> None:
        publish(HERE, done, {})
        say(f"wrote {HERE / 'EXPLICIT_MATERIALS.md'}")

    status = run_sections(NAME, sections, publish, folder,
                          commit=commit if args.write else None)
    if status == 0:
        print(document(args, rounds, {}))
        say(f"wrote {folder / 'EXPLICIT_MATERIALS.md'}")
    return status


if __name__ == "__main__":
    raise SystemExit(main())
