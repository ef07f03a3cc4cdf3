"""Prandtl's strip-footing capacity with OpenSeesPy quads against upliftlab's continuum model.

    python benchmarks/opensees_bearing.py [--levels M ...] [--elements E ...] [--upliftlab N ...]
                                          [--timeout S] [--quick] [--out DIR | --write]

The bearing problem of ``scenes/strip_footing_clay.toml``: a rough rigid strip
B = 2 m on weightless undrained clay, E = 50 MPa, ν = 0.3, c_u = 50 kPa, in a 10B × 10B box
(sides on rollers, base fixed), the footing pushed down uniformly to 0.05 B in 10 equal steps;
the capacity is the largest total footing reaction, against Prandtl's (2 + π) c_u B =
514.16 kN/m.

OpenSees (in a subprocess with a timeout; without openseespy the script stops before any work,
naming the extra to install): plane
strain, ``nDMaterial J2Plasticity`` with K, G of (E, ν) and a von Mises yield stress
σ_y = √3 c_u (the von Mises surface through Tresca's in plane-strain shear: k = c_u), perfectly
plastic; elements ``bbarQuad`` (B-bar, 2×2), ``SSPquad`` (stabilised single point), ``quad``
(plain 2×2, which locks once the flow is isochoric) and ``quad9n`` (9-node, 3×3); footing nodes
fixed in x (rough) and their u_y tied (``equalDOF``) so that the footing settles uniformly,
pushed by ``DisplacementControl`` in 10 steps of 0.005 B (the footing load is the load factor on
a unit load), ``Plain`` constraints, ``Newton`` with ``NormDispIncr 1e-8`` m and step halving,
``UmfPack``.
The mesh has the grid lines of upliftlab's own soil mesh (``upliftlab.meshes.soil_mesh``,
grading 1): M bilinear elements across B have the node spacing of upliftlab's Q2 mesh with
M/2 across (``quad9n`` with M/2 across has the same nodes). Also runs upliftlab's continuum
model on the same problem in this process (``benchmarks/continuum_speed.py``'s ``prandtl``
case: Q2 with 2×2 reduced integration, Tresca, the same pushover), so that the runtimes are
measured in one run: compare ratios. Each row is a section (``bench_output``):
``OPENSEES_BEARING.md`` is rewritten in ``--out`` (default ``results/bench/opensees_bearing``)
as each ends, and ``--write`` also rewrites the committed one in ``benchmarks/`` once every row
has completed (never with ``--quick``: bbarQuad on 8 and 16 across, upliftlab on 4 and 8).

Cost model (the estimate printed before any work): each row costs the runtime the committed
``benchmarks/OPENSEES_BEARING.md`` records for the same model and level (OpenSees: the load
steps, its model build apart); a row it does not record has no estimate.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, number, output_folder, require, run_sections, say,
                          write_text)
from upliftlab.anchors import prandtl_capacity  # noqa: E402

E, NU, CU, B = 50e3, 0.3, 50.0, 2.0  # kPa, -, kPa, m
Q_U = prandtl_capacity(CU, B)          # kN/m
SETTLEMENT, STEPS = 0.05 * B, 10
NAME = "opensees_bearing"

# ---------------------------------------------------------------------------------------------
# Child: the OpenSees model (openseespy and the JSON on stdin only)
# ---------------------------------------------------------------------------------------------


def build(ops, spec: dict) -> list[int]:
    """Nodes on the grid, elements, supports; returns the footing nodes."""
    x, y, quadratic = spec["x"], spec["y"], spec["element"] == "quad9n"
    nx = len(x)
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 2)
    for j, yj in enumerate(y):
        for i, xi in enumerate(x):
            ops.node(1 + i + nx * j, xi, yj)
    k = spec["nu_bulk"]
    ops.nDMaterial("J2Plasticity", 1, k["K"], k["G"], spec["sigma_y"], spec["sigma_y"], 0.0, 0.0)
    step = 2 if quadratic else 1
    tag = 0
    for j in range(0, len(y) - 1, step):
        for i in range(0, nx - 1, step):
            tag += 1
            element(ops, spec["element"], tag, i, j, nx)
    footing, fixed = [], 0
    for j, yj in enumerate(y):
        for i, xi in enumerate(x):
            n = 1 + i + nx * j
            if j == 0:
                ops.fix(n, 1, 1)
                fixed += 2
            elif i in (0, nx - 1):
                ops.fix(n, 1, 0)
                fixed += 1
            elif yj == 0.0 and abs(xi) <= 0.5 * spec["width"] + 1e-12:
                ops.fix(n, 1, 0)
                footing.append(n)
                fixed += 2  # u_x fixed, u_y prescribed
    return footing, 2 * nx * len(y) - fixed


def element(ops, kind: str, tag: int, i: int, j: int, nx: int) -> None:
    def n(di, dj):
        return 1 + (i + di) + nx * (j + dj)

    corners = (n(0, 0), n(1, 0), n(1, 1), n(0, 1))
    if kind == "bbarQuad":
        ops.element("bbarQuad", tag, *corners, 1.0, 1)
    elif kind == "SSPquad":
        ops.element("SSPquad", tag, *corners, 1, "PlaneStrain", 1.0)
    elif kind == "quad":
        ops.element("quad", tag, *corners, 1.0, "PlaneStrain", 1)
    else:  # quad9n: corners, mid-sides, centre, counter-clockwise
        nodes = (n(0, 0), n(2, 0), n(2, 2), n(0, 2), n(1, 0), n(2, 1), n(1, 2), n(0, 1), n(1, 1))
        ops.element("quad9n", tag, *nodes, 1.0, "PlaneStrain", 1)


def child(spec: dict) -> dict:
    import openseespy.opensees as ops

    start = time.perf_counter()
    footing, dofs = build(ops, spec)
    dofs -= len(footing) - 1  # the footing nodes' u_y are tied to one
    lead = footing[len(footing) // 2]
    for n in footing:
        if n != lead:
            ops.equalDOF(lead, n, 2)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(lead, 0.0, -1.0)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system(spec.get("system", "UmfPack"))
    ops.test("NormDispIncr", spec.get("tolerance", 1e-8), 30)
    ops.algorithm("Newton")
    setup = time.perf_counter() - start
    start = time.perf_counter()
    loads, iterations = [], 0
    for k in range(spec["steps"]):
        ok, its = advance(ops, spec["settlement"] / spec["steps"], 0, lead)
        iterations += its
        if ok != 0:
            return {"status": f"failed in step {k + 1}", "runtime": time.perf_counter() - start}
        loads.append(ops.getLoadFactor(1))  # the footing load: λ times a unit load down
    runtime = time.perf_counter() - start
    ops.wipe()
    return {"status": "ok", "capacity": max(loads), "loads": loads, "runtime": runtime,
            "setup": setup, "iterations": iterations, "nodes": len(spec["x"]) * len(spec["y"]),
            "dofs": dofs}


def advance(ops, increment: float, depth: int = 0, lead: int = 0) -> tuple[int, int]:
    """One settlement step of ``increment`` (down) of node ``lead``, halved (up to 6 times)
    when Newton fails; (status, Newton iterations)."""
    ops.integrator("DisplacementControl", lead, 2, -increment)
    ops.analysis("Static")
    ok = ops.analyze(1)
    its = ops.testIter()
    if ok == 0 or depth >= 6:
        return ok, its
    first, a = advance(ops, 0.5 * increment, depth + 1, lead)
    if first != 0:
        return first, its + a
    second, b = advance(ops, 0.5 * increment, depth + 1, lead)
    return second, its + a + b


# ---------------------------------------------------------------------------------------------
# Parent
# ---------------------------------------------------------------------------------------------


def opensees_environment() -> dict | None:
    """The child's environment (the wheel's bundled BLAS/LAPACK on LD_LIBRARY_PATH), or None
    when openseespy cannot be imported."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    found = importlib.util.find_spec("openseespylinux")
    if found is not None and found.submodule_search_locations:
        lib = Path(list(found.submodule_search_locations)[0]) / "lib"
        if lib.is_dir():
            env["LD_LIBRARY_PATH"] = os.pathsep.join(
                p for p in (str(lib), env.get("LD_LIBRARY_PATH", "")) if p)
    probe = subprocess.run([sys.executable, "-c", "import openseespy.opensees"], env=env,
                           capture_output=True, text=True, timeout=120)
    return env if probe.returncode == 0 else None


def grid(across: int) -> tuple[list[float], list[float]]:
    """x and y grid lines of upliftlab's Q1 soil mesh with ``across`` elements across B."""
    import numpy as np

    from upliftlab.meshes import soil_mesh

    mesh = soil_mesh(B, element="Q1", elements_across=across).mesh
    return np.unique(mesh.p[0]).tolist(), np.unique(mesh.p[1]).tolist()


def spec_of(element: str, level: int, nu: float, system: str = "UmfPack") -> dict:
    """``level``: bilinear elements across B. quad9n: level/2 nine-node elements on the grid
    of upliftlab's Q2 mesh with level/2 across, mid-side lines added (the Q2 nodes)."""
    if element == "quad9n":
        x, y = (_with_midpoints(lines) for lines in grid(level // 2))
    else:
        x, y = grid(level)
    K, G = E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))
    return {"element": element, "level": level, "x": x, "y": y, "width": B,
            "nu_bulk": {"K": K, "G": G}, "nu": nu, "sigma_y": math.sqrt(3.0) * CU,
            "settlement": SETTLEMENT, "steps": STEPS, "system": system}


def _with_midpoints(lines: list[float]) -> list[float]:
    out = [lines[0]]
    for a, b in zip(lines[:-1], lines[1:]):
        out += [0.5 * (a + b), b]
    return out


def run_child(spec: dict, env: dict, timeout: float) -> dict:
    start = time.perf_counter()
    try:
        done = subprocess.run([sys.executable, __file__, "--child"], input=json.dumps(spec),
                              env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": f"timed out after {timeout:g} s"}
    if done.returncode != 0 or not done.stdout.strip():
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return {"status": f"error: {tail[:200]}"}
    result = json.loads(done.stdout.strip().splitlines()[-1])
    result["wall"] = time.perf_counter() - start
    return result


UNIFORM = "upliftlab Q2 (2×2 reduced), Tresca"
GRADING = 16.0
GRADED = f"upliftlab Q2 (2×2 reduced), Tresca, graded ×{GRADING:g}"


def upliftlab_prandtl(n: int, grading: float = 1.0) -> dict:
    """upliftlab's own Prandtl run, through continuum_speed.py's ``prandtl`` case."""
    path = HERE / "continuum_speed.py"
    module_spec = importlib.util.spec_from_file_location("continuum_speed", path)
    bench = importlib.util.module_from_spec(module_spec)
    module_spec.loader.exec_module(bench)
    row = bench.measure("prandtl", (n, grading), 1)
    error = row["errors"]["N_max / (2+pi) c_u B - 1"]
    return {"status": "ok", "capacity": Q_U * (1 + error), "runtime": row["runtime"],
            "dofs": row["dofs"], "iterations": row["newton"]}


def line(label: str, level: str, r: dict, base: float | None) -> str:
    if r.get("status") != "ok":
        return f"| {label} | {level} | – | – | {r.get('status')} | – | – | – |"
    ratio = f"{r['runtime'] / base:.2f}" if base else "–"
    return (f"| {label} | {level} | {r['dofs']} | {r['iterations']} | {r['runtime']:.2f} | "
            f"{ratio} | {r['capacity']:.2f} | {r['capacity'] / Q_U - 1:+.2%} |")


def table(rows: list[tuple[str, str, dict]], base: float | None) -> str:
    out = ["| model | level | DOFs | Newton its | runtime [s] | runtime / upliftlab Q2 "
           "(finest) | capacity [kN/m] | error vs (2+π) c_u B |", "|" + "---|" * 8]
    out += [line(label, level, r, base) for label, level, r in rows]
    return "\n".join(out)


NOTES = """\
Notes. Plain `quad` (2×2) and `quad9n` (3×3) are fully integrated: they lock once the plastic
flow is isochoric, which shows as a capacity far above Prandtl's that falls slowly with h.
`SSPquad` (one point, stabilised) is stabilised with the full elastic stiffness. `bbarQuad`
removes volumetric locking. The graded upliftlab rows put smaller elements at the footing
edges, where the error is O(h) (a singular pressure); OpenSees keeps the uniform grid lines, so
those rows compare methods as a user would run them, not the same mesh. The limit load does not
depend on the elastic constants, so the ν = 0.49 rows show what near-incompressibility changes
in convergence and cost only. The issue's figures (scikit-fem Q2 + CHOLMOD 0.7 % in 13 s;
bbarQuad 5.1 % in 5 s; quad9n 5.7 % in 114 s) were measured elsewhere, on other meshes and
machines; only the ratios within this file are comparable."""


def summary(rows: list[tuple[str, str, dict]]) -> str:
    """Each OpenSees element at the DOF count nearest upliftlab's finest level, as ratios."""
    ok = [(label, level, r) for label, level, r in rows if r.get("status") == "ok"]
    ours = [row for row in ok if row[0] == UNIFORM]
    if not ours:
        return ""
    label, level, ref = ours[-1]
    err = ref["capacity"] / Q_U - 1
    lines = [f"upliftlab Q2, {level}: {err:+.2%} in {ref['runtime']:.1f} s ({ref['dofs']} DOFs)."
             " OpenSees at the nearest DOF count, same run:", ""]
    for name in dict.fromkeys(row[0] for row in ok if not row[0].startswith("upliftlab")):
        mine = [row for row in ok if row[0] == name]
        lab, lev, r = min(mine, key=lambda row: abs(row[2]["dofs"] / ref["dofs"] - 1))
        e = r["capacity"] / Q_U - 1
        lines.append(f"- {lab}, {lev} ({r['dofs']} DOFs): {e:+.2%}, {abs(e / err):.1f} × "
                     f"upliftlab's error, in {r['runtime'] / ref['runtime']:.2f} × its time.")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--levels", nargs="+", type=int, default=[8, 16, 32],
                        help="bilinear elements across B (quad9n: half as many)")
    parser.add_argument("--elements", nargs="+", default=["bbarQuad", "SSPquad", "quad",
                                                          "quad9n"])
    parser.add_argument("--nu", nargs="+", type=float, default=[NU, 0.49],
                        help="Poisson's ratios (the first for every element, the others for "
                             "bbarQuad only)")
    parser.add_argument("--upliftlab", nargs="*", type=int, default=[4, 8, 16],
                        help="upliftlab Q2 elements across B (continuum_speed's prandtl)")
    parser.add_argument("--graded", nargs="*", type=int, default=[8, 16],
                        help="upliftlab Q2 elements across B on meshes graded ×16 towards the "
                             "footing edges (OpenSees keeps the uniform grid lines)")
    parser.add_argument("--timeout", type=float, default=900.0)
    parser.add_argument("--system", default="UmfPack", help="OpenSees linear solver")
    parser.add_argument("--quick", action="store_true", help="levels 8 and 16, bbarQuad, "
                        "upliftlab 4 and 8")
    add_output_arguments(parser, "opensees_bearing")
    args = parser.parse_args(argv)
    if args.child:
        print(json.dumps(child(json.loads(sys.stdin.read()))))
        return 0
    require("openseespy", "opensees", NAME)
    out = output_folder(args, NAME)
    env = opensees_environment()
    if env is None:
        say(f"{NAME}: error: openseespy does not run in a subprocess here (pip install "
            "'upliftlab[opensees]'); nothing was run or written")
        return 2
    if args.quick:
        args.levels, args.elements, args.nu, args.upliftlab = [8, 16], ["bbarQuad"], [NU], [4, 8]
        args.graded = [8]
    rows: list[tuple[str, str, dict]] = []
    recorded = {(r["model"], r["level"]): number(r["runtime [s]"])
                for table_rows in committed_tables("OPENSEES_BEARING.md").values()
                for r in table_rows if "model" in r}

    def section(label: str, size: str, compute) -> Section:
        def one():
            rows.append((label, size, compute()))
            say(line(*rows[-1], None))
            return rows[-1]
        cost = recorded.get((label, size))
        return Section(f"{label}, {size}", one, cost if cost == cost else None)

    sections = []
    for label, grading, levels in ((UNIFORM, 1.0, args.upliftlab),
                                   (GRADED, GRADING, args.graded)):
        sections += [section(label, f"{n} across (≈ {2 * n} bilinear)",
                             lambda n=n, g=grading: upliftlab_prandtl(n, g)) for n in levels]
    for element in args.elements:
        for nu in args.nu if element == "bbarQuad" else args.nu[:1]:
            for level in args.levels:
                size = f"{level // 2} nine-node across" if element == "quad9n" else \
                    f"{level} across"
                sections.append(section(
                    f"OpenSees {element}, J2, ν = {nu:g}", size,
                    lambda e=element, lv=level, v=nu: run_child(spec_of(e, lv, v, args.system),
                                                                env, args.timeout)))

    def publish(folder: Path, done: dict, missing: dict) -> None:
        write_text(folder / "OPENSEES_BEARING.md", document(args, rows, missing))

    def commit(done: dict) -> None:
        publish(HERE, done, {})
        say(f"wrote {HERE / 'OPENSEES_BEARING.md'}")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="runtimes recorded in benchmarks/OPENSEES_BEARING.md")
    if status == 0:
        print(table(rows, _base(rows)))
        say(f"{NAME}: wrote {out / 'OPENSEES_BEARING.md'}")
    return status


def _base(rows) -> float | None:
    """The runtime of upliftlab's finest uniform row, the table's unit of time."""
    ours = [r for label, _, r in rows if label == UNIFORM and r.get("status") == "ok"]
    return ours[-1]["runtime"] if ours else None


def document(args, rows, missing: dict) -> str:
    """OPENSEES_BEARING.md of the rows so far."""
    header = (f"# Prandtl bearing capacity: OpenSees quads against upliftlab\n\n"
              f"`python benchmarks/opensees_bearing.py{' --quick' if args.quick else ''}`, "
              f"{datetime.date.today().isoformat()}, {platform.processor() or platform.machine()}"
              f", Python {platform.python_version()}, one thread. Rough rigid strip B = 2 m, "
              "weightless Tresca clay (OpenSees: von Mises J2Plasticity with σ_y = √3 c_u, "
              "perfectly plastic), E = 50 MPa, c_u = 50 kPa, 10B × 10B box on upliftlab's "
              "graded grid lines, uniform settlement to 0.05 B in 10 steps; capacity = largest "
              "footing reaction; reference (2 + π) c_u B = 514.16 kN/m. OpenSees runtime: the "
              "10 load steps in the child (model build apart); upliftlab's: the whole pushover "
              "including meshing. The machine is shared: compare the ratios.\n\n")
    return (header + incomplete_note(missing) + table(rows, _base(rows)) + "\n\n"
            + summary(rows) + "\n\n" + NOTES + "\n")


if __name__ == "__main__":
    sys.exit(main())
