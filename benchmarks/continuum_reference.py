"""El Centro on the clay scene: a reference converged in time and mesh for the continuum's
histories, and each run's own error against it.

    python benchmarks/continuum_reference.py [--quick] [--out DIR] [--write]

The El Centro section of ``benchmarks/CONTINUUM.md`` measures the explicit route against the
implicit route on the same mesh, which is itself not converged in time (its θ history moves by
2.7 % and then 1.8 % of its peak when its step is halved, ``CONTINUUM_CONVERGENCE.md``). This
study holds the runs to a reference converged in time and in the mesh instead. Every run is 10 s
of El Centro 1940 N-S on the clay scene, built and run as in ``continuum_convergence.py``
(its ``run``; Tresca c_u = 50 kPa, frictionless unilateral contact, Q2 with 2×2 reduced
integration, 10B × 10B rigid box):

- the explicit route on 8, 16 and 32 across at its default step (set by stability: dt ∝ h,
  so each mesh halves the step with the element);
- the **reference**: the explicit route on 32 across at half its default step; its time error
  is bounded by the difference of the 32-across run at its default step from it;
- the implicit route on 16 across at its default step and Newton rtol 1e-6: the old accuracy
  reference of ``CONTINUUM.md``, now itself measured.

The mesh error comes from the three explicit meshes (``upliftlab.continuum.dynamics.mesh_error``:
for each quantity the observed order p = log₂(|f₁₆ − f₈| / |f₃₂ − f₁₆|), used only where both
differences have the same sign and p is in [0.5, 4]). Where the order holds, the 16-across
mesh's error is estimated as |f₃₂ − f₁₆| · 2^p / (2^p − 1) (its distance from the Richardson
extrapolation) and the 32-across mesh's as |f₃₂ − f₁₆| / (2^p − 1); where it does not, the plain
difference |f₃₂ − f₁₆| stands as a bound for both, flagged. Errors as in
``continuum_elcentro.compare``: peak |θ|, peak edge uplift, residual settlement (signed, over the
reference's value) and the largest difference of the θ and v − v(0) histories over their peaks;
the estimates are unsigned, over the reference's value as well.

Each run's histories are kept in ``<out>/rows/<label>.npz`` as soon as it ends (an interrupted
study resumes: a kept run is read, not run again; ``continuum_elcentro.py --reference`` reads
the reference from there). Writes ``CONTINUUM_REFERENCE.md`` to ``--out`` (default
``results/bench/continuum_reference``); ``--write`` also rewrites the committed
``benchmarks/CONTINUUM_REFERENCE.md`` once every run has completed. ``--quick`` (a smoke check,
never committed): 2 s of the record on 2, 4 and 8 across (the reference: 8 across at half its
step) and the implicit route on 4, rows kept in ``<out>/rows-quick``.

Cost model (the estimate printed before any work): a run recorded in the Runs table of the
committed ``CONTINUUM_REFERENCE.md`` costs its recorded wall time, any other
``continuum_convergence.cost`` (DOFs × steps × the rate of the route's finest El Centro row of
``CONTINUUM.md``).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import continuum_convergence as cc  # noqa: E402
import continuum_elcentro as ec  # noqa: E402
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, number, output_folder, run_sections, say, write_text)

from upliftlab.continuum.dynamics.mesh_error import mesh_error, richardson  # noqa: E402

NAME = "continuum_reference"
FILE = "CONTINUUM_REFERENCE.md"
#: Seconds of the record each run simulates (``--quick``: :data:`QUICK_DURATION`).
DURATION, QUICK_DURATION = 10.0, 2.0
#: (label, route, elements across, step as a fraction of the route's default, mass, Newton
#: rtol): ``continuum_convergence.run``'s arguments.
RUNS = (("explicit-8", "explicit", 8, 1.0, None, None),
        ("explicit-16", "explicit", 16, 1.0, None, None),
        ("explicit-32", "explicit", 32, 1.0, None, None),
        ("explicit-32-half", "explicit", 32, 0.5, None, None),
        ("implicit-16", "implicit", 16, 1.0, None, 1e-6))
QUICK_RUNS = (("explicit-2", "explicit", 2, 1.0, None, None),
              ("explicit-4", "explicit", 4, 1.0, None, None),
              ("explicit-8", "explicit", 8, 1.0, None, None),
              ("explicit-8-half", "explicit", 8, 0.5, None, None),
              ("implicit-4", "implicit", 4, 1.0, None, 1e-6))
#: The label of the converged reference in the full study: what ``continuum_elcentro.py
#: --reference`` reads.
REFERENCE = ec.CONVERGED
#: The quantities of :func:`continuum_elcentro.compare` with their ``mesh_error`` names.
QUANTITIES = dict(zip(ec.ERRORS, ("peak_theta", "peak_edge_uplift", "residual_settlement",
                                  "theta_history", "v_history")))


def roles(specs) -> dict:
    """The runs' roles: ``meshes`` (the explicit runs at the default step, coarsest first),
    ``reference`` (the finest mesh at half its step) and ``implicit``."""
    meshes = tuple(s[0] for s in specs if s[1] == "explicit" and s[3] == 1.0)
    return {"meshes": meshes, "across": tuple(s[2] for s in specs if s[0] in meshes),
            "reference": next(s[0] for s in specs if s[1] == "explicit" and s[3] != 1.0),
            "implicit": next(s[0] for s in specs if s[1] == "implicit")}


def summary(row: dict) -> dict:
    """The peaks of ``row`` that ``mesh_error`` reads (as ``dynamic_summary`` names them)."""
    return {"peak_theta": float(np.abs(row["theta"]).max()),
            "peak_edge_uplift": float(np.max(row["edge"])),
            "residual_settlement": float(row["v"][0] - row["v"][-1])}


def scale(row: dict) -> dict:
    """The reference's value of each quantity (its magnitude), by which every error is
    divided."""
    dv = np.asarray(row["v"]) - row["v"][0]
    return {**{k: abs(v) for k, v in summary(row).items()},
            "theta_history": float(np.abs(row["theta"]).max()),
            "v_history": float(np.abs(dv).max())}


def estimates(rows: dict, meshes, across, reference: dict) -> dict:
    """For each quantity (``compare``'s names): the Richardson estimate of the errors of the
    middle and the finest of ``meshes`` (three labels, coarsest first), over the reference's
    value, with the observed order (NaN where it does not hold) and the flag."""
    fine_first = [rows[m] for m in reversed(meshes)]
    found = mesh_error([summary(r) for r in fine_first], fine_first, tuple(reversed(across)),
                       tuple(float(r["dt"]) for r in fine_first))
    values = scale(reference)
    out = {}
    for name, key in QUANTITIES.items():
        q = found[key]
        d, p = q.differences[0], q.order
        middle = abs(d) + richardson(d, p) if math.isfinite(p) else abs(d)
        out[name] = {"middle": middle / values[key], "finest": q.estimate / values[key],
                     "order": p, "flag": q.flag,
                     "differences": tuple(x / values[key] for x in q.differences)}
    return out


def _cell(e: dict, which: str) -> str:
    if math.isfinite(e["order"]):
        return f"±{100 * e[which]:.3f} % (p = {e['order']:.2f})"
    return f"≤ {100 * e[which]:.3f} % (bound: {e['flag']})"


def _measured(errors: dict) -> str:
    return " | ".join(f"{100 * errors[k]:+.3f} %" if "history" not in k
                      else f"{100 * errors[k]:.3f} %" for k in ec.ERRORS)


def table(rows: dict, specs) -> str:
    """The errors against the reference (module docstring); rows whose runs are missing say
    so."""
    r = roles(specs)
    ref, (coarse, middle, fine), implicit = r["reference"], r["meshes"], r["implicit"]
    lines = ["| what | run | " + " | ".join(ec.ERRORS) + " |", "|" + "---|" * (2 + 5)]

    def measured(what, label):
        if label in rows and ref in rows:
            errors = ec.compare(rows[label], rows[ref])
            lines.append(f"| {what} | {label} | {_measured(errors)} |")
        else:
            lines.append(f"| {what} | {label} | – (missing: "
                         f"{' and '.join(x for x in (label, ref) if x not in rows)})"
                         + " | –" * 4 + " |")

    measured(f"{middle}: its own error (measured)", middle)
    found = None
    if all(m in rows for m in r["meshes"]) and ref in rows:
        found = estimates(rows, r["meshes"], r["across"], rows[ref])

    def estimated(what, label, which):
        if found is None:
            lines.append(f"| {what} | {label} | – (missing runs)" + " | –" * 4 + " |")
        else:
            lines.append(f"| {what} | {label} | "
                         + " | ".join(_cell(found[k], which) for k in ec.ERRORS) + " |")

    estimated(f"{middle}: Richardson estimate from {', '.join(r['meshes'])}", middle,
              "middle")
    measured(f"{fine}: time error (its step against half of it)", fine)
    estimated(f"{fine}: Richardson estimate of its mesh error", fine, "finest")
    measured(f"{implicit} (rtol 1e-6): the old accuracy reference, measured", implicit)
    measured(f"{coarse}: its own error (measured)", coarse)
    if middle in rows and implicit in rows:
        lines.append(f"| {middle} against {implicit}: the old error column | {middle} | "
                     f"{_measured(ec.compare(rows[middle], rows[implicit]))} |")
    return "\n".join(lines)


def orders(rows: dict, specs) -> str:
    """The values of each quantity on each mesh, the differences and the observed order."""
    r = roles(specs)
    if not all(m in rows for m in r["meshes"]) or r["reference"] not in rows:
        return "Not available: a mesh or the reference did not complete."
    found = estimates(rows, r["meshes"], r["across"], rows[r["reference"]])
    values = scale(rows[r["reference"]])
    a, b, c = r["across"]
    lines = [f"| quantity | reference value | f{b} − f{a} | f{c} − f{b} | observed order p | "
             "used |", "|---|---|---|---|---|---|"]
    for name, key in QUANTITIES.items():
        e = found[name]
        d_fine, d_coarse = e["differences"]
        p = f"{e['order']:.2f}" if math.isfinite(e["order"]) else "–"
        unit = "rad" if "theta" in name else "m"
        lines.append(f"| {name} | {values[key]:.4g} {unit} | {100 * d_coarse:+.3f} % | "
                     f"{100 * d_fine:+.3f} % | {p} | {e['flag']} |")
    return "\n".join(lines)


def document(rows: dict, missing: dict, specs, duration: float, quick: bool) -> str:
    """CONTINUUM_REFERENCE.md of the runs done so far."""
    r = roles(specs)
    return (f"# Continuum dynamics: a reference converged in time and mesh\n\n"
            f"`python benchmarks/continuum_reference.py{' --quick' if quick else ''}`, "
            f"{datetime.date.today()}, {platform.machine()}, Python "
            f"{platform.python_version()}.\n\n" + incomplete_note(missing)
            + (f"Quick run (a smoke check, not the study): {duration:g} s of the record, the "
               "runs listed at the end.\n\n" if quick else "")
            + __doc__.split("\n\n", 2)[2].split("\n\nEach run's histories")[0].strip()
            + f"\n\nEvery error is against `{r['reference']}`. Its own error is at most its "
            "mesh error (the Richardson estimate of the finest mesh) plus its time error "
            "(below the finest mesh's difference between its step and half of it).\n\n"
            + table(rows, specs) + "\n\n## Observed orders\n\nThe differences between "
            "successive meshes, over the reference's value (a history's value: its peak, "
            "|θ| or |v − v(0)|; its difference: the largest over the time axis, unsigned).\n\n" + orders(rows, specs)
            + "\n\n## Runs\n\n" + cc.runs_table(rows, specs, duration) + "\n")


def costs(specs, duration: float) -> dict:
    """The estimated wall time of each run (module docstring); None where the tables it
    reads are missing."""
    recorded = {(row["run"], number(row["simulated [s]"])): number(row["wall [s]"])
                for row in committed_tables(FILE).get("Runs", [])}
    try:
        elcentro, sizes = cc._elcentro_rows(), cc.mesh_sizes()
        return {s[0]: cc.cost(s, duration, recorded, sizes, elcentro) for s in specs}
    except (KeyError, ValueError, ZeroDivisionError):
        return {s[0]: recorded.get((s[0], duration)) for s in specs}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true",
                        help=f"{QUICK_DURATION:g} s on 2, 4 and 8 across (a smoke check)")
    add_output_arguments(parser, NAME)
    args = parser.parse_args(argv)
    out = output_folder(args, NAME)
    why = ec.unavailable()
    if why:
        say(f"{NAME}: error: {why}; nothing was run or written")
        return 2
    specs = QUICK_RUNS if args.quick else RUNS
    duration = QUICK_DURATION if args.quick else DURATION
    folder = out / ("rows-quick" if args.quick else "rows")
    estimate = costs(specs, duration)
    sections = [Section(s[0], lambda s=s: cc.kept(folder, s, duration),
                        None if (folder / f"{s[0]}.npz").exists() else estimate[s[0]])
                for s in specs]

    def publish(target: Path, done: dict, missing: dict) -> None:
        write_text(target / FILE, document(done, missing, specs, duration, args.quick))

    def commit(done: dict) -> None:
        publish(HERE, done, {})
        say(f"wrote {HERE / FILE}")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="DOFs × steps × the rates of benchmarks/CONTINUUM.md; kept "
                                "runs are read, not run")
    if status == 0:
        print(table(cc.kept_rows(folder, specs), specs))
        say(f"wrote {out / FILE}")
    return status


if __name__ == "__main__":
    sys.exit(main())
