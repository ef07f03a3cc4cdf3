"""El Centro on the clay scene: how converged is each dynamic route, in time and in the mesh?

    python benchmarks/continuum_convergence.py [--out DIR] [--write]

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
the largest difference of the θ and v histories over their peaks. Each run's histories are kept
in ``<out>/rows/<label>.npz`` as soon as it ends: an interrupted study resumes where it stopped.
Writes ``CONTINUUM_CONVERGENCE.md`` to ``--out`` (default ``results/bench/continuum_convergence``);
``--write`` rewrites the committed ``benchmarks/CONTINUUM_CONVERGENCE.md`` instead.
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

OUT = Path("results/bench/continuum_convergence")
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
KEYS = ("time", "theta", "v", "edge")


def run(route: str, n: int, step: float, mass: str | None, rtol: float | None,
        scale: float = 1.0, boundary: str = "fixed") -> dict:
    """One run of 10 s: its histories, step and runtime (``scale``: the record's factor;
    ``boundary``: the box's sides, ``continuum.boundary``)."""
    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics import DynamicOptions, run_dynamic
    from upliftlab.motions import ELCENTRO
    from upliftlab.scenes import load_scene

    scene = load_scene("strip_footing_clay", motion=ELCENTRO, overrides=[
        f"continuum.elements_across={n}", f"continuum.dynamics={route}", "analysis.duration=10",
        f"motion.scale={scale!r}", f"continuum.boundary={boundary}"])
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
            "dt": float(result.metadata["dt"]), "wall": time.perf_counter() - started}


def measure(folder: Path, say) -> dict[str, dict]:
    """Every run of :data:`RUNS`, read from ``folder`` where an earlier invocation kept it."""
    folder.mkdir(parents=True, exist_ok=True)
    rows, started = {}, time.perf_counter()
    todo = [spec for spec in RUNS if not (folder / f"{spec[0]}.npz").exists()]
    for done, (label, *spec) in enumerate(todo):
        say(f"{label}: running ({done + 1} of {len(todo)} left to run; elapsed "
            f"{time.perf_counter() - started:.0f} s)")
        row = run(*spec)
        np.savez(folder / f".{label}.part.npz", **row)
        os.replace(folder / f".{label}.part.npz", folder / f"{label}.npz")
        say(f"{label}: {row['wall']:.1f} s, dt = {row['dt']:.3g} s")
    for label, *_ in RUNS:
        with np.load(folder / f"{label}.npz") as data:
            rows[label] = {k: data[k] for k in data.files}
    return rows


def table(rows: dict[str, dict]) -> str:
    names = ("peak theta", "peak edge uplift", "residual settlement", "theta history",
             "v history")
    lines = ["| what | run | reference | " + " | ".join(names) + " |",
             "|" + "---|" * (3 + len(names))]
    for what, a, b in PAIRS:
        errors = ec.compare(rows[a], rows[b])
        cells = " | ".join(f"{100 * errors[k]:+.3f} %" if "history" not in k
                           else f"{100 * errors[k]:.3f} %" for k in names)
        lines.append(f"| {what} | {a} (dt {rows[a]['dt']:.3g} s) | {b} "
                     f"(dt {rows[b]['dt']:.3g} s) | {cells} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(OUT), help=f"output folder (default {OUT})")
    parser.add_argument("--write", action="store_true",
                        help="write CONTINUUM_CONVERGENCE.md into benchmarks/")
    args = parser.parse_args(argv)
    why = ec.unavailable()
    if why:
        print(f"continuum_convergence: {why}", file=sys.stderr)
        return 1
    out = Path(args.out)
    rows = measure(out / "rows", lambda m: print(m, file=sys.stderr, flush=True))
    text = (f"# Continuum dynamics: convergence in time, mass matrix and mesh\n\n"
            f"`python benchmarks/continuum_convergence.py`, {datetime.date.today()}, "
            f"{platform.machine()}, Python {platform.python_version()}.\n\n"
            + __doc__.split("\n\n", 2)[2].strip() + "\n\n" + table(rows) + "\n")
    target = Path(__file__).resolve().parent if args.write else out
    target.mkdir(parents=True, exist_ok=True)
    (target / "CONTINUUM_CONVERGENCE.md").write_text(text)
    print(table(rows))
    print(f"wrote {target / 'CONTINUUM_CONVERGENCE.md'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
