"""Contact load cases after one factorisation (target: each under 10 ms).

    python benchmarks/contact_cases.py [--cases N] [--across N ...] [--quick] [--out DIR]

Elastic soil (the clay scene's E, ν; frictionless footing) on the default 10B box. The soil is
factorised and condensed onto the footing's contact DOFs once (K_ii = LU, S = K_cc − K_ci K_ii⁻¹
K_ic: the "one factorisation"). Each load case is then a pair (N, M) at the footing, from full
contact to large uplift (e = M/N from 0 to 0.45 B), solved exactly by the primal–dual active set
on the condensed system (:func:`upliftlab.continuum.contact.footing.solve_contact`), and,
separately,
with the back-substitution that recovers the whole displacement field from it.

For each mesh level it prints the DOFs, the one-off factorisation + condensation time, and the
median time per load case (contact alone; contact + field), with the active-set iterations, and
checks each case against the exact equilibrium it must satisfy: the contact forces resultant
equals (−N, M) to round-off, no tensile force, and no negative gap. Also the reference check of
Muskhelishvili's rigid punch: the full-contact rotation over M gives K_r = π G B²/(8(1 − ν))
(error printed).

Each mesh level is a section (``bench_output``): the table is printed and written to
``CONTACT_CASES.md`` in ``--out`` (default ``results/bench/contact_cases``) as each ends; it has
no committed table. ``--quick``: 4 and 8 across, 7 cases, 3 repeats (a few seconds).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import math  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from upliftlab.continuum import make_model  # noqa: E402
from upliftlab.continuum.contact.footing import OPEN, ContactProblem, solve_contact  # noqa: E402
from upliftlab.scenes import ContinuumOptions, load_scene  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (Section, add_output_arguments, incomplete_note,  # noqa: E402
                          output_folder, run_sections, write_text)

NAME = "contact_cases"


def elastic_soil():
    scene = load_scene("strip_footing_clay")
    soil = replace(scene.soil, model="elastic", density=0.0)
    return scene, soil


def level(across: int, cases: int, repeats: int) -> dict:
    scene, soil = elastic_soil()
    B = scene.foundation.width
    model = make_model(soil, B, replace(scene.continuum or ContinuumOptions(),
                                        elements_across=across), gravity=scene.g)
    blocks, footing = model.blocks, model.footing
    t0 = time.perf_counter()
    D = model.material(np.zeros((3, 3, 1)))[1]
    from upliftlab.continuum.materials import plane_strain_tangent
    cond = model._condense(plane_strain_tangent(D)[..., 0], None, reused=True)
    cond.X  # formed once with the factorisation: each field recovery is then a product
    factorise = time.perf_counter() - t0

    m = blocks.contact.size
    N = scene.structure.vertical_weight
    eccentricities = np.linspace(0.0, 0.45, cases) * B
    zero_m, zero_q = np.zeros(m), np.zeros(3)
    status0 = np.full(footing.nodes, OPEN, dtype=np.int8)
    prescribed = np.array([True, False, False])

    def problem(e):
        return ContactProblem(footing, cond.S, zero_m, zero_m, zero_q, np.zeros(footing.nodes),
                              prescribed, np.array([0.0, -N, N * e]), np.zeros((3, 3)),
                              zero_q)

    contact_times, field_times, iterations, worst = [], [], [], {"resultant": 0.0,
                                                                   "tension": 0.0, "gap": 0.0}
    L = footing.kinematics
    for e in eccentricities:
        p = problem(e)
        solve_contact(p, status0)  # warm-up
        tc, tf = [], []
        for _ in range(repeats):
            t = time.perf_counter()
            sol = solve_contact(p, status0)
            tc.append(time.perf_counter() - t)
            t = time.perf_counter()
            sol = solve_contact(p, status0)
            du = np.zeros(model.disc.ndofs)
            du[blocks.contact] = sol.duc
            du[blocks.interior] = -cond.times_x(sol.duc)
            tf.append(time.perf_counter() - t)
        contact_times.append(statistics.median(tc))
        field_times.append(statistics.median(tf))
        iterations.append(sol.iterations)
        reaction = L.T @ sol.force  # (H, -N, M) carried by the soil
        worst["resultant"] = max(worst["resultant"], abs(reaction[1] + N) / N,
                                 abs(reaction[2] - N * e) / (N * B))
        normal = -sol.force[:footing.nodes]  # compression > 0 (force on the soil is downward)
        worst["tension"] = max(worst["tension"], float(np.max(-normal)) / N)
        gap = footing.gap(du, sol.dq)
        worst["gap"] = max(worst["gap"], float(np.max(-gap)) / B)
    # the rigid punch: K_r in full contact, from a small moment
    G = soil.youngs_modulus / (2 * (1 + soil.poisson_ratio))
    kr_exact = math.pi * G * B ** 2 / (8 * (1 - soil.poisson_ratio))
    p = ContactProblem(footing, cond.S, zero_m, zero_m, zero_q, np.zeros(footing.nodes),
                       prescribed, np.array([0.0, -N, 1e-3 * N * B]), np.zeros((3, 3)), zero_q)
    full = solve_contact(p, status0)
    p0 = replace(p, target=np.array([0.0, -N, 0.0]))
    base = solve_contact(p0, status0)
    kr = 1e-3 * N * B / (full.dq[2] - base.dq[2])
    return {"across": across, "dofs": model.dofs, "contact_dofs": m, "factorise_s": factorise,
            "contact_ms": 1e3 * statistics.median(contact_times),
            "contact_max_ms": 1e3 * max(contact_times),
            "field_ms": 1e3 * statistics.median(field_times),
            "iterations_max": max(iterations), "kr_error": kr / kr_exact - 1.0, **worst}


def table(rows: list[dict]) -> str:
    lines = ["| elements across B | soil DOFs | contact DOFs | factorise + condense [s] | "
             "per case, contact [ms] (median / max) | per case, + field [ms] | active-set "
             "iterations (max) | resultant error | max tension / N | max overlap / B | "
             "K_r error (rigid punch) |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['across']} | {r['dofs']} | {r['contact_dofs']} | "
                     f"{r['factorise_s']:.2f} | {r['contact_ms']:.2f} / "
                     f"{r['contact_max_ms']:.2f} | {r['field_ms']:.2f} | "
                     f"{r['iterations_max']} | {r['resultant']:.1e} | {r['tension']:.1e} | "
                     f"{r['gap']:.1e} | {100 * r['kr_error']:+.3f} % |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=None,
                        help="load cases per level (19; 7 with --quick)")
    parser.add_argument("--repeats", type=int, default=5, help="timed repeats per case")
    parser.add_argument("--across", type=int, nargs="+", default=None,
                        help="elements across the footing, per level (8 16 32; 4 8 with "
                             "--quick)")
    parser.add_argument("--quick", action="store_true", help="4 and 8 across, 7 cases")
    add_output_arguments(parser, NAME, committed=False)
    args = parser.parse_args(argv)
    out = output_folder(args, NAME)
    across = args.across or ([4, 8] if args.quick else [8, 16, 32])
    cases = args.cases or (7 if args.quick else 19)
    rows: list[dict] = []

    def one(a: int) -> dict:
        rows.append(level(a, cases, args.repeats))
        return rows[-1]

    sections = [Section(f"{a} across", lambda a=a: one(a)) for a in across]

    def document(done: dict, missing: dict) -> str:
        command = " ".join(["python benchmarks/contact_cases.py", *(argv or sys.argv[1:])])
        return (f"# Contact load cases after one factorisation\n\n`{command}`; what is "
                "timed and checked: the script's docstring.\n\n" + incomplete_note(missing)
                + table(list(done.values())) + "\n")

    def publish(folder: Path, done: dict, missing: dict) -> None:
        write_text(folder / "CONTACT_CASES.md", document(done, missing))

    status = run_sections(NAME, sections, publish, out)
    if status == 0:
        print(document(dict(zip(across, rows)), {}))
    return status


if __name__ == "__main__":
    raise SystemExit(main())
