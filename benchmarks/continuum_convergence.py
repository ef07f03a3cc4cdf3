"""El Centro on the clay scene: how converged is each dynamic route, in time and in the mesh?

    python benchmarks/continuum_convergence.py [--quick] [--out DIR] [--write]

The El Centro section of ``benchmarks/continuum_speed.py`` measures the explicit route against
the implicit one on the same mesh. The two differ by more than either changes when its own step
is halved, so this study asks where the difference comes from. Every run is 10 s of El Centro
1940 N-S on the clay scene (Tresca c_u = 50 kPa, frictionless unilateral contact, Q2 with 2×2
reduced integration, 10B × 10B box whose sides hold u_x: the scene's default, a rigid container),
built and run as in ``continuum_elcentro.py``:

- **time**: each route at its default step and at fractions of it, 8 elements across (the
  implicit route refuses steps below 0.21 h_min/V_s, so a quarter is its finest there), and
  the implicit route on 16 across at a half and a quarter of its step: is the implicit
  reference of the speed benchmark itself converged in time to the tolerance the explicit
  route is held to?
- **mass matrix**: the implicit route with the explicit route's row-sum lumped mass as well as
  its default consistent mass, so that the schemes and the mass matrices are told apart;
- **mesh**: the explicit route on 16 and 32 across and the implicit route on 16 across, each
  compared with the explicit route on 32 across;
- **sides**: both routes on 16 across with the box's sides a free-field column
  (``continuum.boundary = shear``) instead of the rigid container: do the routes agree better
  where the clay does not yield against the sides?
- **sensitivity**: each route with the record scaled by 1 + 1e-6 against the same route
  unscaled: how far the answer moves when the input moves by one part in a million, which no
  discretization can do better than (a history that moves by a percent here cannot be compared
  to a percent between two solvers).

Errors as in ``continuum_elcentro.compare``: peak |θ|, peak edge uplift, residual settlement and
the largest difference of the θ and v histories over their peaks. Each run is a section
(``bench_output``): its histories are kept in ``<out>/rows/<label>.npz`` as soon as it ends (an
interrupted study resumes where it stopped: a kept run is read, not run again) and the table is
rewritten, a pair whose runs are not both there marked as missing. Writes
``CONTINUUM_CONVERGENCE.md`` to ``--out`` (default ``results/bench/continuum_convergence``);
``--write`` also rewrites the committed ``benchmarks/CONTINUUM_CONVERGENCE.md`` once every run
has completed. ``--quick`` (a smoke check, never committed): 2 s of the record on 4 across (and
8 for the mesh pair), rows kept in ``<out>/rows-quick``.

Cost model (the estimate printed before any work: 2.3 h for the full study from the tables
committed on 2026-11-24): a run recorded in the committed table's runs list costs its recorded
wall time; any other costs DOFs × steps × a rate, the rate (s per step and DOF) of the route's
finest row of the El Centro table in the committed ``benchmarks/CONTINUUM.md`` (explicit: one
thread; implicit: rtol 1e-6), the DOFs and the step of each mesh from the same file (a mesh it
does not list: DOFs × (n/n₀)², step × n₀/n from its finest listed mesh n₀).
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
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import continuum_elcentro as ec  # noqa: E402
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, number, output_folder, run_sections, say, write_text)

NAME = "continuum_convergence"
#: Seconds of the record each run simulates (``--quick``: :data:`QUICK_DURATION`).
DURATION, QUICK_DURATION = 10.0, 2.0
#: The record's scale factor of the perturbed runs: how far a history moves when the input
#: moves by one part in a million tells how well posed a history comparison is at all.
PERTURBATION = 1.0 + 1e-6
#: (label, route, elements across, step as a fraction of the route's default, mass or None for
#: the route's own, Newton rtol of the implicit route[, scale of the record[, the box's sides,
#: continuum.boundary]])
RUNS = (("explicit-8", "explicit", 8, 1.0, None, None),
        ("explicit-8-half", "explicit", 8, 0.5, None, None),
        ("implicit-8", "implicit", 8, 1.0, None, 1e-6),
        ("implicit-8-half", "implicit", 8, 0.5, None, 1e-6),
        ("implicit-8-quarter", "implicit", 8, 0.25, None, 1e-6),
        ("implicit-lumped-8-half", "implicit", 8, 0.5, "lumped", 1e-6),
        ("implicit-lumped-8-quarter", "implicit", 8, 0.25, "lumped", 1e-6),
        ("explicit-16", "explicit", 16, 1.0, None, None),
        ("implicit-16", "implicit", 16, 1.0, None, 1e-6),
        ("implicit-16-half", "implicit", 16, 0.5, None, 1e-6),
        ("implicit-16-quarter", "implicit", 16, 0.25, None, 1e-6),
        ("explicit-32", "explicit", 32, 1.0, None, None),
        ("explicit-8-perturbed", "explicit", 8, 1.0, None, None, PERTURBATION),
        ("implicit-8-perturbed", "implicit", 8, 1.0, None, 1e-6, PERTURBATION),
        ("explicit-16-perturbed", "explicit", 16, 1.0, None, None, PERTURBATION),
        ("explicit-16-shear", "explicit", 16, 1.0, None, None, 1.0, "shear"),
        ("implicit-16-shear", "implicit", 16, 1.0, None, 1e-6, 1.0, "shear"))
#: (what the pair shows, run, reference)
PAIRS = (("time: explicit, step halved", "explicit-8", "explicit-8-half"),
         ("time: implicit, step halved", "implicit-8", "implicit-8-half"),
         ("time: implicit, step halved again", "implicit-8-half", "implicit-8-quarter"),
         ("time: implicit lumped, step halved", "implicit-lumped-8-half",
          "implicit-lumped-8-quarter"),
         ("mass: implicit consistent against lumped (quarter step)", "implicit-8-quarter",
          "implicit-lumped-8-quarter"),
         ("scheme: explicit against implicit, both lumped", "explicit-8",
          "implicit-lumped-8-quarter"),
         ("both: explicit against implicit consistent (quarter step)", "explicit-8",
          "implicit-8-quarter"),
         ("both: explicit against implicit consistent, 16 across", "explicit-16",
          "implicit-16"),
         ("time: implicit 16 across, step halved", "implicit-16", "implicit-16-half"),
         ("both: explicit against implicit consistent, 16 across, half step", "explicit-16",
          "implicit-16-half"),
         ("time: implicit 16 across, step halved again", "implicit-16-half",
          "implicit-16-quarter"),
         ("both: explicit against implicit consistent, 16 across, quarter step", "explicit-16",
          "implicit-16-quarter"),
         ("sides: explicit against implicit, 16 across, free-field column", "explicit-16-shear",
          "implicit-16-shear"),
         ("mesh: explicit 8 across against 32", "explicit-8", "explicit-32"),
         ("mesh: explicit 16 across against 32", "explicit-16", "explicit-32"),
         ("mesh: implicit 16 across against explicit 32", "implicit-16", "explicit-32"),
         ("sensitivity: explicit, record × (1 + 1e-6)", "explicit-8-perturbed", "explicit-8"),
         ("sensitivity: implicit, record × (1 + 1e-6)", "implicit-8-perturbed", "implicit-8"),
         ("sensitivity: explicit 16 across, record × (1 + 1e-6)", "explicit-16-perturbed",
          "explicit-16"))
#: ``--quick``: the same kinds of pair on 4 across (8 for the mesh), 2 s of the record.
QUICK_RUNS = (("explicit-4", "explicit", 4, 1.0, None, None),
              ("explicit-4-half", "explicit", 4, 0.5, None, None),
              ("implicit-4", "implicit", 4, 1.0, None, 1e-6),
              ("implicit-4-half", "implicit", 4, 0.5, None, 1e-6),
              ("explicit-8", "explicit", 8, 1.0, None, None),
              ("explicit-4-perturbed", "explicit", 4, 1.0, None, None, PERTURBATION))
QUICK_PAIRS = (("time: explicit, step halved", "explicit-4", "explicit-4-half"),
               ("time: implicit, step halved", "implicit-4", "implicit-4-half"),
               ("both: explicit against implicit consistent", "explicit-4", "implicit-4"),
               ("mesh: explicit 4 across against 8", "explicit-4", "explicit-8"),
               ("sensitivity: explicit, record × (1 + 1e-6)", "explicit-4-perturbed",
                "explicit-4"))
KEYS = ("time", "theta", "v", "edge")


def run(route: str, n: int, step: float, mass: str | None, rtol: float | None,
        scale: float = 1.0, boundary: str = "fixed", duration: float = DURATION) -> dict:
    """One run of ``duration`` s: its histories, step, steps and runtime (``scale``: the
    record's factor; ``boundary``: the box's sides, ``continuum.boundary``)."""
    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
    from upliftlab.motions import ELCENTRO
    from upliftlab.scenes import load_scene

    scene = load_scene("strip_footing_clay", motion=ELCENTRO, overrides=[
        f"continuum.elements_across={n}", f"continuum.dynamics={route}",
        f"analysis.duration={duration:g}", f"motion.scale={scale!r}",
        f"continuum.boundary={boundary}"])
    motion = scene.build_motion()
    started = time.perf_counter()
    model = build_model(scene)
    options = DynamicOptions(snapshots=0, mass=mass,
                             dt=step * ec.default_step(model, motion, route))
    if rtol is not None:
        options = replace(options, newton=replace(options.newton, rtol=rtol))
    result = run_dynamic(model, scene, motion, options)
    gap = np.asarray(result.gap)
    return {"time": np.asarray(result.time), "theta": np.asarray(result.footing)[:, 2],
            "v": np.asarray(result.footing)[:, 1], "edge": np.maximum(gap[:, 0], gap[:, -1]),
            "dt": float(result.metadata["dt"]), "steps": int(result.metadata["steps"]),
            "dofs": int(model.dofs), "wall": time.perf_counter() - started}


def kept(folder: Path, spec: tuple, duration: float) -> dict:
    """The run ``spec`` (a row of :data:`RUNS`), read from ``folder`` where an earlier
    invocation kept it, else run and kept there (atomically) before it is returned."""
    label, *args = spec
    path = folder / f"{label}.npz"
    if not path.exists():
        row = run(*args, duration=duration)
        folder.mkdir(parents=True, exist_ok=True)
        part = folder / f".{label}.part.npz"
        np.savez(part, **row)
        os.replace(part, path)
        say(f"{label}: {row['wall']:.1f} s, dt = {row['dt']:.3g} s")
        return row
    with np.load(path) as data:
        return {k: data[k] for k in data.files}


def table(rows: dict[str, dict], pairs) -> str:
    """The errors of each pair of ``pairs`` whose two runs are in ``rows`` (the others say
    which run is missing)."""
    names = ("peak theta", "peak edge uplift", "residual settlement", "theta history",
             "v history")
    lines = ["| what | run | reference | " + " | ".join(names) + " |",
             "|" + "---|" * (3 + len(names))]
    for what, a, b in pairs:
        if a not in rows or b not in rows:
            absent = " and ".join(x for x in (a, b) if x not in rows)
            lines.append(f"| {what} | {a} | {b} | " + " | ".join(
                f"– (missing: {absent})" if k == names[0] else "–" for k in names) + " |")
            continue
        errors = ec.compare(rows[a], rows[b])
        cells = " | ".join(f"{100 * errors[k]:+.3f} %" if "history" not in k
                           else f"{100 * errors[k]:.3f} %" for k in names)
        lines.append(f"| {what} | {a} (dt {rows[a]['dt']:.3g} s) | {b} "
                     f"(dt {rows[b]['dt']:.3g} s) | {cells} |")
    return "\n".join(lines)


def runs_table(rows: dict[str, dict], specs, duration: float) -> str:
    """Each run's mesh, step, steps and wall time (kept runs: as measured when they ran)."""
    lines = ["| run | route | n across | simulated [s] | dt [s] | steps | wall [s] |",
             "|---|---|---|---|---|---|---|"]
    for label, route, n, *_ in specs:
        if label in rows:
            r = rows[label]
            steps = int(r["steps"]) if "steps" in r else round(duration / float(r["dt"]))
            lines.append(f"| {label} | {route} | {n} | {duration:g} | {float(r['dt']):.3g} | "
                         f"{steps} | {float(r['wall']):.1f} |")
    return "\n".join(lines)


def document(rows: dict[str, dict], missing: dict, specs, pairs, duration: float,
             quick: bool) -> str:
    """CONTINUUM_CONVERGENCE.md of the runs done so far."""
    return (f"# Continuum dynamics: convergence in time, mass matrix and mesh\n\n"
            f"`python benchmarks/continuum_convergence.py{' --quick' if quick else ''}`, "
            f"{datetime.date.today()}, {platform.machine()}, Python "
            f"{platform.python_version()}.\n\n" + incomplete_note(missing)
            + (f"Quick run (a smoke check, not the study): {duration:g} s of the record on 4 "
               "and 8 across, the runs listed at the end.\n\n" if quick else "")
            + __doc__.split("\n\n", 2)[2].split("\n\nErrors as in")[0].strip() + "\n\n"
            + "Errors as in ``continuum_elcentro.compare``: peak |θ|, peak edge uplift, "
            "residual settlement and the largest difference of the θ and v histories over "
            "their peaks.\n\n" + table(rows, pairs) + "\n\n## Runs\n\n"
            + runs_table(rows, specs, duration) + "\n")


# ---------------------------------------------------------------------------------------------
# Cost model (module docstring)
# ---------------------------------------------------------------------------------------------


def _elcentro_rows() -> list[dict]:
    tables = committed_tables("CONTINUUM.md")
    return [r for head, rows in tables.items() if head.startswith("El Centro") for r in rows
            if "route" in r]


def mesh_sizes() -> dict[int, int]:
    """DOFs by elements across B (grading 1) in the committed CONTINUUM.md."""
    sizes = {}
    for rows in committed_tables("CONTINUUM.md").values():
        for r in rows:
            if r.get("grading", "1") == "1" and "DOFs" in r and r.get("n across", "").isdigit():
                sizes[int(r["n across"])] = int(number(r["DOFs"]))
    return sizes


def cost(spec: tuple, duration: float, recorded: dict, sizes: dict, elcentro: list) -> float:
    """Estimated wall time (s) of the run ``spec`` (module docstring)."""
    label, route, n, step, *_ = spec
    if (label, duration) in recorded:
        return recorded[label, duration]
    mine = [r for r in elcentro if r["route"] == route and r["threads"] == "1"
            and (route == "explicit" or r["rtol"] == "1e-06")]
    finest = max(mine, key=lambda r: int(r["n across"]))
    n0 = int(finest["n across"])
    rate = number(finest["wall [s]"]) / (number(finest["steps"]) * number(finest["DOFs"]))
    dts = {int(r["n across"]): number(r["dt [s]"]) for r in mine}
    dt = dts.get(n, dts[n0] * n0 / n) * step
    dofs = sizes.get(n, sizes.get(n0, number(finest["DOFs"])) * (n / n0) ** 2)
    return duration / dt * dofs * rate


def costs(specs, duration: float) -> dict[str, float | None]:
    """:func:`cost` of every run of ``specs``; None for all when the committed tables it reads
    are missing."""
    try:
        elcentro, sizes = _elcentro_rows(), mesh_sizes()
        recorded = {(r["run"], number(r["simulated [s]"])): number(r["wall [s]"])
                    for r in committed_tables("CONTINUUM_CONVERGENCE.md").get("Runs", [])}
        return {spec[0]: cost(spec, duration, recorded, sizes, elcentro) for spec in specs}
    except (KeyError, ValueError, ZeroDivisionError):
        return {spec[0]: None for spec in specs}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true",
                        help=f"{QUICK_DURATION:g} s on 4 across (a smoke check)")
    add_output_arguments(parser, NAME)
    args = parser.parse_args(argv)
    out = output_folder(args, NAME)
    why = ec.unavailable()
    if why:
        say(f"{NAME}: error: {why}; nothing was run or written")
        return 2
    specs, pairs = (QUICK_RUNS, QUICK_PAIRS) if args.quick else (RUNS, PAIRS)
    duration = QUICK_DURATION if args.quick else DURATION
    folder = out / ("rows-quick" if args.quick else "rows")
    estimate = costs(specs, duration)
    sections = [Section(spec[0], lambda spec=spec: kept(folder, spec, duration),
                        None if (folder / f"{spec[0]}.npz").exists() else estimate[spec[0]])
                for spec in specs]

    def publish(target: Path, done: dict, missing: dict) -> None:
        write_text(target / "CONTINUUM_CONVERGENCE.md",
                   document(done, missing, specs, pairs, duration, args.quick))

    def commit(done: dict) -> None:
        publish(HERE, done, {})
        say(f"wrote {HERE / 'CONTINUUM_CONVERGENCE.md'}")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="DOFs × steps × the rates of benchmarks/CONTINUUM.md; kept "
                                "runs are read, not run")
    if status == 0:
        print(table(kept_rows(folder, specs), pairs))
        say(f"wrote {out / 'CONTINUUM_CONVERGENCE.md'}")
    return status


def kept_rows(folder: Path, specs) -> dict[str, dict]:
    """Every kept run of ``specs`` in ``folder``."""
    rows = {}
    for label, *_ in specs:
        if (folder / f"{label}.npz").exists():
            with np.load(folder / f"{label}.npz") as data:
                rows[label] = {k: data[k] for k in data.files}
    return rows


if __name__ == "__main__":
    sys.exit(main())
