"""Speed against error of the continuum model, per mesh level.

    python benchmarks/continuum_speed.py [--quick] [--only static|elcentro] [--out DIR]
                                         [--repeats R] [--write]

For each case and mesh level (elements across the footing B and the grading towards its
edges, the centre-to-edge element size ratio; Q2 with 2×2 reduced integration, 10B × 10B box)
it prints the DOFs, the runtime (median of the repeats), the time in
tangent assembly, in residuals (return map and internal force), in linear solves (factorisation,
Schur condensation, the contact active set and back-substitution), the Newton iterations, and
the error against the reference:

- ``rocking``: elastic rocking stiffness K_r of a frictionless strip in full contact
  (``footing_stiffness``) against π G B²/(8(1 − ν)) (Muskhelishvili's rigid punch);
- ``prandtl``: capacity of a rough (bonded) strip on Tresca clay, settlement pushed to 0.05 B
  in 10 steps, against Prandtl's (2 + π) c_u B; uniform (grading 1) and graded (16) meshes.
  ``prandtl-richardson`` rows extrapolate two measured rows of one grading, n and 2n, to
  h → 0 for the O(h) convergence of the footing-edge singularity (2 q(2n) − q(n)); their
  runtime is the sum of both runs, their DOFs those of both;
- ``uplift``: rotation pushover of a frictionless strip on elastic soil at N = 171.39 kN/m to
  10 θ_on in 40 steps: the uplift-onset eccentricity against the half-plane B/4, and (second
  error) the largest |c/B − θ_on/θ| after uplift (tests/test_continuum_contact.py);
- ``elcentro``: El Centro 1940 N-S on the clay scene, the explicit and the implicit route in
  the same invocation (``benchmarks/continuum_elcentro.py``: runtime, speed-up, and the errors
  of peak θ, peak edge uplift, residual settlement and the θ and v histories against the
  converged reference kept by ``benchmarks/continuum_reference.py``, ``--reference DIR``,
  default ``results/bench/continuum_reference/rows``; without it against the implicit route at
  rtol 1e-6 on the same mesh, and the section's text says which). It needs the record on
  ``UPLIFTLAB_MOTIONS``; without it the section is skipped with a message.

Soil: E = 50 MPa, ν = 0.3, ρ = 1.8 t/m³, c_u = 50 kPa, B = 2 m (the clay scene). The timers wrap
the solver's functions for the duration of a run and change no result. One thread per solve
(``OMP_NUM_THREADS=1``). Each static row and each El Centro run is a section (``bench_output``):
``CONTINUUM.md`` (the tables) and ``continuum_speed.png`` (runtime against error of the static
cases) are rewritten in ``--out`` (default ``results/bench/continuum_speed``) as each ends;
``--write`` also rewrites the committed ``benchmarks/CONTINUUM.md`` and
``benchmarks/continuum_speed.png`` once every section has completed (never with ``--quick`` or
``--only``). ``--quick``: the coarse levels, one repeat, El Centro on 4 across (about a minute).

Cost model (the estimate printed before any work; about 45 min in all, most of it the implicit El
Centro runs): each static row costs the runtime recorded for the same case and level in the
committed ``benchmarks/CONTINUUM.md`` times its repeats, each El Centro run the wall time
recorded there (``continuum_elcentro.cost``); a row not recorded there has no estimate.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import contextlib  # noqa: E402
import datetime  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from upliftlab.continuum import (OPEN, footing_stiffness, make_model,  # noqa: E402
                                 rotation_pushover, uplift_onset, vertical_pushover)
from upliftlab.scenes import ContinuumOptions, Soil  # noqa: E402
from upliftlab.anchors import prandtl_capacity  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, missing_section, number, output_folder, run_sections,
                          save_figure, say, write_text)

E, NU, RHO, CU, B, N = 50e3, 0.3, 1.8, 50.0, 2.0, 171.39
G = E / (2 * (1 + NU))
K_R = math.pi * G * B ** 2 / (8 * (1 - NU))
Q_U = prandtl_capacity(CU, B)
THETA_ON = 2 * N * (1 - NU) / (math.pi * G * B)
ELASTIC = Soil(youngs_modulus=E, poisson_ratio=NU, density=RHO, model="elastic")
CLAY = Soil(youngs_modulus=E, poisson_ratio=NU, density=RHO, model="tresca",
            undrained_strength=CU, interface="bonded")

#: Mesh levels per case: (elements across B, grading towards the footing edges).
LEVELS = {"rocking": ((4, 1.0), (8, 1.0), (16, 1.0), (32, 1.0)),
          "prandtl": ((4, 1.0), (8, 1.0), (16, 1.0), (8, 16.0), (10, 16.0), (16, 16.0)),
          "uplift": ((8, 1.0), (16, 1.0), (32, 1.0))}
QUICK = {"rocking": ((4, 1.0), (8, 1.0)), "prandtl": ((4, 1.0), (8, 1.0), (8, 16.0)),
         "uplift": ((4, 1.0), (8, 1.0))}

NAME = "continuum_speed"
#: The issue's targets: (case, |error| bound, runtime bound [s], smallest DOFs).
TARGETS = (("rocking", 0.01, 2.0, 0), ("prandtl", 0.01, 15.0, 0), ("prandtl", 0.005, 60.0, 0))


# ---------------------------------------------------------------------------------------------
# Timers around the solver's leaves
# ---------------------------------------------------------------------------------------------


class Timers:
    """Seconds and calls spent in the wrapped functions, by category."""

    def __init__(self):
        self.seconds = {"assembly": 0.0, "residual": 0.0, "solve": 0.0}
        self.calls = {"newton": 0}

    def wrap(self, function, category: str | None, count: str | None = None):
        def timed(*args, **kwargs):
            if count:
                self.calls[count] += 1
            if category is None:
                return function(*args, **kwargs)
            start = time.perf_counter()
            try:
                return function(*args, **kwargs)
            finally:
                self.seconds[category] += time.perf_counter() - start
        return timed


@contextlib.contextmanager
def instrumented():
    """Patch the solver's leaf functions with timers (restored on exit): tangent assembly
    (``assembly.stiffness``), residuals (``ContinuumModel.respond``), solves (``condensation``,
    ``Condensation.condense``, ``solve_contact``); Newton iterations count the condensations
    each iteration asks for (``newton._condense``)."""
    from upliftlab.continuum import assembly, model
    from upliftlab.continuum.statics import newton

    timers = Timers()
    patches = [(assembly, "stiffness", "assembly", None),
               (model.ContinuumModel, "respond", "residual", None),
               (model, "condensation", "solve", None),
               (model.Condensation, "condense", "solve", None),
               (newton, "solve_contact", "solve", None),
               (newton, "_condense", None, "newton")]
    saved = []
    try:
        for owner, name, category, count in patches:
            original = owner.__dict__[name] if isinstance(owner, type) else getattr(owner, name)
            saved.append((owner, name, original))
            setattr(owner, name, timers.wrap(original, category, count))
        yield timers
    finally:
        for owner, name, original in reversed(saved):
            setattr(owner, name, original)


# ---------------------------------------------------------------------------------------------
# Cases: each returns (model, errors dict) after one run
# ---------------------------------------------------------------------------------------------


def rocking(n: int, grading: float = 1.0):
    model = make_model(ELASTIC, B, ContinuumOptions(elements_across=n, grading=grading))
    return model, {"K_r / closed form - 1": footing_stiffness(model).rocking / K_R - 1.0}


def prandtl(n: int, grading: float = 1.0):
    model = make_model(CLAY, B, ContinuumOptions(elements_across=n, grading=grading))
    path = vertical_pushover(model, np.linspace(0.0, 0.05 * B, 11)[1:])
    return model, {"N_max / (2+pi) c_u B - 1": path.capacity / Q_U - 1.0}


def uplift(n: int, grading: float = 1.0):
    model = make_model(ELASTIC, B, ContinuumOptions(elements_across=n, grading=grading))
    path = rotation_pushover(model, N, np.linspace(0.0, 10 * THETA_ON, 41)[1:])
    onset = uplift_onset(path)
    lifted = (path.status == OPEN).any(axis=1)
    contact = np.max(np.abs(path.contact_fraction[lifted] - onset.theta / path.theta[lifted]))
    return model, {"e_on / (B/4) - 1": onset.e / (0.25 * B) - 1.0,
                   "max |c/B - theta_on/theta|": contact}


CASES = {"rocking": rocking, "prandtl": prandtl, "uplift": uplift}


# ---------------------------------------------------------------------------------------------
# Measuring
# ---------------------------------------------------------------------------------------------


def measure(case: str, level: tuple[int, float], repeats: int) -> dict:
    """Run a case ``repeats`` times; medians of the times, the errors of the last run."""
    n, grading = level
    runs = []
    for _ in range(repeats):
        with instrumented() as timers:
            start = time.perf_counter()
            model, errors = CASES[case](n, grading)
            total = time.perf_counter() - start
        runs.append((total, dict(timers.seconds), timers.calls["newton"]))
    return {"case": case, "n": n, "grading": grading, "dofs": model.dofs, "repeats": repeats,
            "runtime": statistics.median(r[0] for r in runs),
            "assembly": statistics.median(r[1]["assembly"] for r in runs),
            "residual": statistics.median(r[1]["residual"] for r in runs),
            "solve": statistics.median(r[1]["solve"] for r in runs),
            "newton": runs[-1][2], "errors": errors}


def richardson(rows: list[dict]) -> list[dict]:
    """``prandtl-richardson`` rows: 2 q(2n) − q(n) from each measured pair of one grading."""
    prandtl = {(r["n"], r["grading"]): r for r in rows if r["case"] == "prandtl"}
    name = "N_max / (2+pi) c_u B - 1"
    out = []
    for (n, grading), coarse in sorted(prandtl.items()):
        fine = prandtl.get((2 * n, grading))
        if fine is None:
            continue
        error = 2.0 * fine["errors"][name] - coarse["errors"][name]
        out.append({"case": "prandtl-richardson", "n": f"{n}+{2 * n}", "grading": grading,
                    "dofs": f"{coarse['dofs']}+{fine['dofs']}",
                    "dofs_total": coarse["dofs"] + fine["dofs"],
                    **{k: coarse[k] + fine[k] for k in ("runtime", "assembly", "residual",
                                                          "solve", "newton")},
                    "errors": {name: error}, "note": "2 q(2n) − q(n)"})
    return out


def targets(rows: list[dict]) -> str:
    """Each target of :data:`TARGETS` with the fastest row that meets it (a raw mesh before a
    Richardson pair), or the nearest row if none does."""
    lines = ["| target | met | fastest row that meets it |", "|---|---|---|"]
    for case, bound, seconds, dofs in TARGETS:
        family = [r for r in rows if r["case"].startswith(case) and _size(r) >= dofs]
        what = (f"{case}: error within {bound:.1%} in under {seconds:g} s"
                if math.isfinite(bound) else f"{case}: {dofs}+ DOFs in under {seconds:g} s")
        ok = [r for r in family if r["runtime"] <= seconds and abs(_error(r)) <= bound]
        raw = [r for r in ok if "richardson" not in r["case"]]
        if ok:
            best = min(raw or ok, key=lambda r: r["runtime"])
            lines.append(f"| {what} | yes{'' if raw else ' (Richardson only)'} | "
                         f"{_label(best)} |")
        else:
            near = f"nearest: {_label(min(family, key=_size))}" if family else "no row"
            lines.append(f"| {what} | no | {near} |")
    return "\n".join(lines)


def _size(row: dict) -> int:
    return row.get("dofs_total", row["dofs"])


def _error(row: dict) -> float:
    return next(iter(row["errors"].values()))


def _label(r: dict) -> str:
    return (f"{r['case']}, n = {r['n']}, grading {r['grading']:g}: {r['dofs']} DOFs, "
            f"{r['runtime']:.2f} s, error {_error(r):+.3%}")


def _fmt_errors(errors: dict) -> str:
    """Relative errors (names ending in ``- 1``) in percent (below 0.001 %: two significant
    digits, so that a small error does not print as zero), others as numbers."""
    def percent(value: float) -> str:
        if value != 0.0 and abs(value) < 1e-5:
            return f"{100.0 * value:+.2g}%"
        return f"{value:+.3%}"
    return "; ".join(f"{name} = {percent(value)}" if name.endswith("- 1") else
                     f"{name} = {value:.4f}" for name, value in errors.items())


def table(rows: list[dict], skipped: dict[str, str]) -> str:
    head = ("| case | n across | grading | DOFs | runtime [s] | assembly [s] | residual [s] "
            "| solve [s] | Newton its | error |")
    lines = [head, "|" + "---|" * 10]
    for r in rows:
        note = f" ({r['note']})" if r.get("note") else ""
        lines.append(f"| {r['case']} | {r['n']} | {r['grading']:g} | {r['dofs']} | "
                     f"{r['runtime']:.3f} | "
                     f"{r['assembly']:.3f} | {r['residual']:.3f} | {r['solve']:.3f} | "
                     f"{r['newton'] or '–'} | {_fmt_errors(r['errors'])}{note} |")
    for case, why in skipped.items():
        lines.append(f"| {case} | – | – | – | – | – | – | – | – | skipped: {why} |")
    return "\n".join(lines)


def figure(rows: list[dict], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    markers = {"rocking": "o", "prandtl": "s", "prandtl-richardson": "x", "uplift": "^"}
    for case, grading in sorted({(r["case"], r["grading"]) for r in rows},
                                key=lambda cg: (list(markers).index(cg[0]), cg[1])):
        mine = [r for r in rows if r["case"] == case and r["grading"] == grading]
        names = list(mine[0]["errors"]) if mine else []
        for k, name in enumerate(names):
            points = [(r["runtime"], abs(r["errors"][name]), f"{r['n']}/{r['grading']:g}")
                      for r in mine]
            points = [p for p in points if p[1] > 0.0]
            if not points:
                continue
            ax.loglog([p[0] for p in points], [p[1] for p in points], marker=markers[case],
                      ls="-" if k == 0 else "--",
                      label=f"{case}" + (f" (grading {grading:g})" if grading != 1.0 else "")
                      + f": |{name}|")
            for t, e, n in points:
                ax.annotate(f"{n}", (t, e), textcoords="offset points", xytext=(4, 4),
                            fontsize=8)
    ax.set_xlabel("runtime [s] (median)")
    ax.set_ylabel("error against the reference (relative; c/B in B)")
    ax.set_title("upliftlab continuum: runtime against error (labels: n across B / grading)",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
    fig.tight_layout()
    return save_figure(fig, path, dpi=100)


def static_cost(case: str, level: tuple[int, float], repeats: int) -> float | None:
    """The runtime the committed CONTINUUM.md records for ``case`` on ``level``, times
    ``repeats`` (None if it records none)."""
    for rows in committed_tables("CONTINUUM.md").values():
        for r in rows:
            if r.get("case") == case and r.get("n across") == str(level[0]) \
                    and number(r.get("grading", "")) == level[1]:
                return number(r["runtime [s]"]) * repeats
    return None


def static_sections(levels: dict, repeats: int, rows: list[dict]) -> list[Section]:
    """One section per static case and level: measures it and appends its row to ``rows``."""
    def one(case, level, reps):
        row = measure(case, level, reps)
        rows.append(row)
        say(f"{case:8s} n = {level[0]:3d}, grading {level[1]:4g}: {row['dofs']:7d} "
            f"DOFs, {row['runtime']:8.3f} s, {_fmt_errors(row['errors'])}")
        return row
    out = []
    for case, ns in levels.items():
        # one run of the plastic cases; the elastic ones are repeated
        reps = repeats if case in ("rocking", "uplift") else 1
        for level in ns:
            out.append(Section(f"{case} {level[0]} across, grading {level[1]:g}",
                               lambda c=case, lv=level, k=reps: one(c, lv, k),
                               static_cost(case, level, reps)))
    return out


def header(args, repeats: int) -> str:
    return (f"# Continuum speed against error\n\n"
            f"`python benchmarks/continuum_speed.py{' --quick' if args.quick else ''}"
            f"{f' --only {args.only}' if args.only else ''}`, "
            f"{datetime.date.today().isoformat()}, {platform.processor() or platform.machine()}"
            f", Python {platform.python_version()}, one BLAS thread per solve "
            f"(OMP_NUM_THREADS={os.environ['OMP_NUM_THREADS']}). Static cases: runtime is the "
            f"median of {repeats} runs for the elastic cases (rocking, uplift) and one run "
            "otherwise; assembly is the tangent stiffness, residual the return map and "
            "internal force, solve the factorisation, Schur condensation, contact active set "
            "and back-substitution; the rest (meshing, basis, bookkeeping) is runtime minus "
            "these. Newton iterations include those of cut steps. The machine is shared: "
            "compare ratios measured in one invocation (the dynamic rows also give the "
            "process's CPU time, which the other processes' load does not inflate).\n\n"
            "Q2 with 2×2 reduced integration, 10B × 10B box, grading as listed (the ratio of "
            "the centre element to the edge element across B); B = 2 m, E = 50 MPa, "
            "ν = 0.3, c_u = 50 kPa. References: rocking π G B²/(8(1 − ν)); prandtl "
            "(2 + π) c_u B (rough, Tresca, settlement 0.05 B); uplift: onset e = B/4 and "
            "c/B = θ_on/θ of the elastic half-plane (the 10B box is −0.36 % on e). The "
            "Richardson rows are named extrapolations of two measured rows, not raw "
            "meshes.\n\n")


def document(args, repeats: int, statics: list[dict], dynamic: list[dict], skipped: str,
             missing: dict) -> str:
    """CONTINUUM.md of the rows so far: the statics and their targets, El Centro and its."""
    import continuum_elcentro as ec

    parts = [header(args, repeats) + incomplete_note(missing).strip()]
    if args.only != "elcentro":
        rows = statics + richardson(statics)
        parts.append("## Statics\n\n" + table(rows, {}) + "\n\n### Targets: the statics' "
                     "speed against error\n\n" + targets(rows) if rows else
                     missing_section("## Statics", next(iter(missing)), missing).strip())
    if args.only != "static":
        if skipped:
            parts.append(f"## El Centro\n\nskipped: {skipped}")
        elif dynamic:
            converged = ec.converged_reference(args.reference)
            done = ec.finish(dynamic, converged)
            parts.append("## El Centro: explicit and implicit dynamics\n\n" + ec.description()
                         + "\n\n" + ec.reference_note(converged, args.reference) + "\n\n"
                         + ec.table(done) + "\n\n### Targets: 8x faster at the "
                         "same accuracy\n\n" + ec.targets(done))
        else:
            key = [k for k in missing if k.startswith("elcentro")][0]
            parts.append(missing_section("## El Centro: explicit and implicit dynamics", key,
                                         missing).strip())
    return "\n\n".join(p for p in parts if p) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="coarse levels, one repeat")
    parser.add_argument("--only", choices=("static", "elcentro"),
                        help="run only the static cases or only El Centro")
    add_output_arguments(parser, NAME)
    parser.add_argument("--reference", default=str(Path("results") / "bench" /
                                                   "continuum_reference" / "rows"),
                        help="the rows kept by benchmarks/continuum_reference.py: El Centro's "
                             "errors against its converged reference (absent: against the "
                             "implicit route at rtol 1e-6)")
    parser.add_argument("--repeats", type=int, default=None,
                        help="repeats of the cheap runs (default 3; 1 with --quick)")
    args = parser.parse_args(argv)
    if args.write and args.only:
        parser.error("--write rewrites the committed tables: run every case (no --only)")
    out = output_folder(args, NAME)
    import continuum_elcentro as ec

    repeats = args.repeats or (1 if args.quick else 3)
    statics: list[dict] = []
    dynamic: list[dict] = []
    sections = []
    if args.only != "elcentro":
        sections += static_sections(QUICK if args.quick else LEVELS, repeats, statics)
    skipped = ec.unavailable() if args.only != "static" else None
    if skipped:
        if args.write:
            say(f"{NAME}: error: --write needs the El Centro record: {skipped}; nothing was "
                "run or written")
            return 2
        say(f"elcentro: skipped: {skipped}")
    elif args.only != "static":
        sections += ec.sections(ec.QUICK if args.quick else ec.RUNS, dynamic)

    def publish(folder: Path, done: dict, missing: dict) -> None:
        write_text(folder / "CONTINUUM.md",
                   document(args, repeats, statics, dynamic, skipped or "", missing))
        if statics:
            figure(statics + richardson(statics), folder / "continuum_speed.png")

    def commit(done: dict) -> None:
        publish(HERE, done, {})
        say(f"wrote {HERE / 'CONTINUUM.md'} and {HERE / 'continuum_speed.png'}")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="runtimes recorded in benchmarks/CONTINUUM.md")
    if status == 0:
        say(f"wrote {out / 'CONTINUUM.md'}")
    return status


if __name__ == "__main__":
    sys.exit(main())
