"""The reduced model against OpenSeesPy: the short-period building on El Centro, side by side.

    python benchmarks/opensees_reduced.py [--springs N ...] [--dt DT ...] [--case A|B ...]
                                          [--timeout S] [--quick] [--out DIR | --write]

The same scene (``short_period_elcentro``, N Winkler springs, the whole 31.2 s record) is built
once by upliftlab (:func:`upliftlab.reduced.model.build_model`), and its numbers — masses,
heights, spring positions, stiffnesses, dashpots, yield forces, the record — are handed as JSON
to an OpenSeesPy model that runs in a subprocess (with a timeout; without openseespy the script
stops before any work, naming the extra to install). The OpenSees model, 2D, three DOFs per
node:

- base node O at the origin: u_x fixed, vertical mass W_v/g and rotary inertia I₀ (the
  foundation carries W_v); a node at height h tied to O by ``rigidLink beam`` (Lagrange
  constraints: OpenSees 3.7.1's Transformation handler reported O's vertical displacement as
  the sum of the load steps' totals in a 10-step gravity analysis, while the tied nodes were
  right); the lateral mass m on its own node, joined to it by a ``zeroLength`` shear
  spring ``Elastic(k_s, eta = c_s)`` (k_s = m ω², c_s = 2 ζ_s k_s/ω: upliftlab's story spring);
- per foundation spring i: a fixed ground node and a node tied to O by ``rigidLink beam``, both
  at (x_i, 0), joined by a ``zeroLength`` in the vertical direction: Case A ``ENT(k_i)``
  (elastic, no tension), Case B ``ElasticPPGap(k_i, −3 F0_i, gap 0, 0, 'damage')`` (elasto-plastic
  in compression, open in tension, plastic settlement kept so that it shifts separation);
- foundation dashpots, in one of two ways (``--dashpots``): ``detaching`` — stiffness-
  proportional Rayleigh damping on the *current* tangent of each spring element
  (``region -rayleigh 0 β 0 0`` with ``-doRayleigh 1``, β = c_i/k_i = 2 ζ_f/ω_v, the same for
  every spring as upliftlab takes c_i = ζ_f·2√(K_v m_v)·k_i/K_v), so that a dashpot acts only
  while its spring is in contact (and, for Case B, not while it yields); or ``parallel`` — a
  ``Viscous(c_i)`` in parallel (``Parallel`` material), which stays attached while the spring is
  open and can pull;
- gravity first (−W_v on O, 10 load steps, ``loadConst -time 0``), then
  ``UniformExcitation`` in x with the record (``Path -dt 0.02``, linear between samples, as
  upliftlab's kernels), ``Newmark 0.5 0.25``, ``Newton`` (line search, then modified Newton and
  step halving when a step fails), ``NormDispIncr 1e-10``, one ``analyze(1, dt)`` per step and
  the peaks read after each.

upliftlab's foundation dashpot detaches with its spring and never pulls: the total force
k d + c ḋ of a spring in contact is clipped at zero while it opens (``reduced/springs.py``). The
``detaching`` OpenSees variant matches it except for that clip (an OpenSees spring in contact
may pull through its dashpot for the instant before it separates); ``parallel`` differs more.
upliftlab runs, in this process and in the same run: the event stepper at its default step and
converged (Δt = 0.02/1024 s), and its Newmark (average acceleration, Newton) at each OpenSees Δt.
Times: OpenSees's is the analysis loop in the child (model build and gravity excluded, and
reported apart); upliftlab's is the median of 3 calls of ``run(..., histories=False)``.
Prints Markdown tables and puts them in their own section of ``REDUCED.md`` in ``--out``
(default ``results/bench/opensees_reduced``), or of the committed ``benchmarks/REDUCED.md`` with
``--write`` (between markers that ``reduced_speed.py`` keeps when it rewrites the file).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from bench_output import add_output_arguments, output_folder, require

SCENE = "short_period_elcentro"


# ---------------------------------------------------------------------------------------------
# Child: the OpenSees model (needs only openseespy and the JSON on stdin)
# ---------------------------------------------------------------------------------------------


def build_opensees(ops, spec: dict) -> dict:
    """Nodes, elements and materials of the OpenSees model; returns the tags to read."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    h, base, top_rigid, top = spec["height"], 1, 2, 3
    ops.node(base, 0.0, 0.0)
    ops.fix(base, 1, 0, 0)
    ops.mass(base, 0.0, spec["vertical_mass"], spec["rotary_inertia"])
    ops.node(top_rigid, 0.0, h)
    ops.rigidLink("beam", base, top_rigid)
    ops.node(top, 0.0, h)
    ops.fix(top, 0, 1, 1)
    ops.mass(top, spec["story_mass"], 0.0, 0.0)
    ops.uniaxialMaterial("Elastic", 1, spec["story_k"], spec["story_c"])
    ops.element("zeroLength", 1, top_rigid, top, "-mat", 1, "-dir", 1)
    springs = []
    for i, (x, k, c, f0) in enumerate(zip(spec["x"], spec["k"], spec["c"], spec["f0"])):
        ground, on_base, ele = 1000 + i, 2000 + i, 100 + i
        ops.node(ground, x, 0.0)
        ops.fix(ground, 1, 1, 1)
        ops.node(on_base, x, 0.0)
        ops.rigidLink("beam", base, on_base)
        mat = foundation_material(ops, 10 + 3 * i, spec, k, c, f0)
        flags = ["-doRayleigh", 1] if spec["dashpots"] == "detaching" else []
        ops.element("zeroLength", ele, ground, on_base, "-mat", mat, "-dir", 2, *flags)
        springs.append(ele)
    if spec["dashpots"] == "detaching":
        ops.region(1, "-ele", *springs, "-rayleigh", 0.0, spec["beta"], 0.0, 0.0)
    i = min(range(len(spec["x"])), key=lambda j: spec["x"][j])
    return {"base": base, "top_rigid": top_rigid, "top": top, "left": 2000 + i,
            "left_element": 100 + i, "left_k": spec["k"][i],
            "left_c": spec["c"][i] if spec["dashpots"] == "parallel" else 0.0}


def foundation_material(ops, tag: int, spec: dict, k: float, c: float, f0: float) -> int:
    """ENT (Case A) or ElasticPPGap with damage (Case B); a Viscous in parallel if asked."""
    if spec["law"] == "elastic":
        ops.uniaxialMaterial("ENT", tag, k)
    else:
        ops.uniaxialMaterial("ElasticPPGap", tag, k, -spec["yield_multiple"] * f0, 0.0, 0.0,
                             "damage")
    if spec["dashpots"] != "parallel":
        return tag
    ops.uniaxialMaterial("Viscous", tag + 1, c, 1.0)
    ops.uniaxialMaterial("Parallel", tag + 2, tag, tag + 1)
    return tag + 2


def gravity(ops, tags: dict, weight: float) -> None:
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(tags["base"], 0.0, -weight, 0.0)
    analysis(ops)
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    if ops.analyze(10) != 0:
        raise RuntimeError("gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def analysis(ops) -> None:
    ops.constraints("Lagrange")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", 1e-10, 50)
    ops.algorithm("Newton")


def step(ops, dt: float, depth: int = 0) -> int:
    """One step; on failure line search, modified Newton, then halving (returns 0 when done)."""
    if ops.analyze(1, dt) == 0:
        return 0
    for algorithm in (("NewtonLineSearch", 0.8), ("ModifiedNewton", "-initial")):
        ops.algorithm(*algorithm)
        ok = ops.analyze(1, dt)
        ops.algorithm("Newton")
        if ok == 0:
            return 0
    if depth >= 8:
        return -1
    return step(ops, dt / 2, depth + 1) or step(ops, dt / 2, depth + 1)


def child(spec: dict) -> dict:
    import openseespy.opensees as ops

    start = time.perf_counter()
    tags = build_opensees(ops, spec)
    gravity(ops, tags, spec["vertical_weight"])
    values = [a * spec["g"] for a in spec["acceleration"]] + [0.0]
    ops.timeSeries("Path", 2, "-dt", spec["record_dt"], "-values", *values)
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    analysis(ops)
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    setup = time.perf_counter() - start
    start = time.perf_counter()
    peaks = march(ops, tags, spec)
    peaks.update(runtime=time.perf_counter() - start, setup=setup)
    ops.wipe()
    return peaks


def march(ops, tags: dict, spec: dict) -> dict:
    dt, h = spec["dt"], spec["height"]
    steps = int(round(spec["duration"] / dt))
    u = theta = uplift = surface = 0.0
    for n in range(steps):
        if step(ops, dt) != 0:
            return {"status": f"failed at t = {ops.getTime():.4f} s", "steps": n}
        x = ops.nodeDisp(tags["top"], 1) - ops.nodeDisp(tags["top_rigid"], 1)
        u = max(u, abs(x))
        theta = max(theta, abs(ops.nodeDisp(tags["base"], 3)))
        # the gap is measured from the (settled) surface, as upliftlab's: while the spring
        # pushes (F < 0), its surface is where its force would vanish, δ − F/k (F without a
        # parallel Viscous; Rayleigh damping is not in the element's basic force)
        delta = ops.nodeDisp(tags["left"], 2)
        force = (ops.eleResponse(tags["left_element"], "basicForce")[0]
                 - tags["left_c"] * ops.nodeVel(tags["left"], 2))
        if force < 0.0:
            surface = delta - force / tags["left_k"]
        uplift = max(uplift, delta - surface)
    return {"status": "ok", "steps": steps, "u": u, "theta": theta, "uplift": uplift}


# ---------------------------------------------------------------------------------------------
# Parent: build the spec from upliftlab, run the child, run upliftlab, compare
# ---------------------------------------------------------------------------------------------


def opensees_environment() -> dict | None:
    """The child's environment, or None without openseespy. The Linux wheel ships its BLAS and
    LAPACK in ``openseespylinux/lib`` but its library does not find them unless that folder is
    on LD_LIBRARY_PATH (a machine without libblas3 fails to import it otherwise)."""
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


def spec_of(case: str, springs: int, dt: float, dashpots: str, extra=()) -> dict:
    """Everything the OpenSees model takes, from upliftlab's own model of the scene."""
    from upliftlab.reduced.model import build_model
    from upliftlab.scenes import load_scene

    scene = load_scene(SCENE, case=case, overrides=[f"foundation.springs={springs}", *extra])
    model, motion = build_model(scene), scene.build_motion()
    d, p = model.dofs, model.params
    found = p[model.foundation_slice]
    beta = found["c"] / found["k"]
    return {"case": case, "springs": springs, "dt": dt, "dashpots": dashpots,
            "law": scene.foundation.law, "yield_multiple": scene.foundation.yield_multiple,
            "height": float(model.heights[0]), "story_mass": float(model.mass[d.stories[0]]),
            "story_k": float(p["k"][0] + p["kh"][0]), "story_c": float(p["c"][0]),
            "vertical_mass": float(model.mass[d.v]), "rotary_inertia": float(model.mass[d.theta]),
            "vertical_weight": float(model.weight), "x": found["x"].tolist(),
            "k": found["k"].tolist(), "c": found["c"].tolist(), "f0": found["f0"].tolist(),
            "beta": float(beta[0]),
            "g": model.g, "record_dt": motion.dt, "acceleration": motion.acceleration.tolist(),
            "duration": scene.analysis.duration or motion.duration}


def run_child(spec: dict, env: dict, timeout: float) -> dict:
    start = time.perf_counter()
    try:
        done = subprocess.run([sys.executable, __file__, "--child"], input=json.dumps(spec),
                              env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": f"timed out after {timeout:g} s"}
    wall = time.perf_counter() - start
    if done.returncode != 0:
        return {"status": "error: " + done.stderr.strip().splitlines()[-1][:200]}
    result = json.loads(done.stdout.strip().splitlines()[-1])
    result["wall"] = wall
    return result


def upliftlab_run(case: str, springs: int, integrator: str, dt: float | None, repeats: int = 3,
                  extra=()):
    from upliftlab.reduced.run import run
    from upliftlab.scenes import load_scene

    scene = load_scene(SCENE, case=case, overrides=[f"foundation.springs={springs}", *extra])
    response = run(scene, integrator=integrator, dt=dt, histories=False)  # warm-up
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        response = run(scene, integrator=integrator, dt=dt, histories=False)
        times.append(time.perf_counter() - start)
    pk = response.peaks
    return {"status": "ok", "u": pk["u"], "theta": pk["theta"], "uplift": pk["uplift_left"],
            "runtime": statistics.median(times), "dt": response.info["dt"]}


def row(label: str, r: dict, ref: dict, ratio_to: float | None) -> str:
    if r.get("status") != "ok":
        return f"| {label} | – | {r.get('status')} | – | – | – | – |"
    err = {k: r[k] / ref[k] - 1.0 for k in ("u", "theta", "uplift")}
    ratio = f"{r['runtime'] / ratio_to:.3g}" if ratio_to else "–"
    return (f"| {label} | {1e3 * r['runtime']:.1f} | {ratio} | {r['u']:.5g} ({err['u']:+.2%}) "
            f"| {r['theta']:.5g} ({err['theta']:+.2%}) | {r['uplift']:.5g} "
            f"({err['uplift']:+.2%}) | {r.get('note', '')} |")


def compare(case: str, springs: int, dts: list[float], dashpots: list[str], env: dict | None,
            timeout: float, extra=()) -> str:
    ref = upliftlab_run(case, springs, "events", 0.02 / 1024, repeats=1, extra=extra)
    events = upliftlab_run(case, springs, "events", None, extra=extra)
    title = f"### Case {case}, N = {springs}" + (f", {', '.join(extra)}" if extra else "")
    lines = [title + "\n",
             "| model | runtime [ms] | runtime / upliftlab events (default Δt) | peak u [in] "
             "| peak θ [rad] | peak uplift, leftmost [in] | note |", "|" + "---|" * 7,
             row("upliftlab events, Δt = 0.02/1024 s (reference)", ref, ref, events["runtime"]),
             row(f"upliftlab events, default Δt = {events['dt']:.3g} s", events, ref,
                 events["runtime"])]
    for dt in dts:
        mine = upliftlab_run(case, springs, "newmark", dt, extra=extra)
        lines.append(row(f"upliftlab newmark, Δt = {dt:g} s", mine, ref, events["runtime"]))
        for kind in dashpots if extra != ("foundation.damping_ratio=0",) else dashpots[:1]:
            if env is None:
                lines.append(f"| OpenSees {kind}, Δt = {dt:g} s | – | skipped: openseespy is "
                             "not importable | – | – | – | – |")
                continue
            spec = spec_of(case, springs, dt, kind, extra)
            result = run_child(spec, env, timeout)
            if result.get("status") == "ok":
                result["note"] = (f"Newton, {result['steps']} steps; setup {result['setup']:.2f}"
                                  f" s; {result['runtime'] / mine['runtime']:.1f} × upliftlab "
                                  f"newmark at this Δt")
            lines.append(row(f"OpenSees {kind} dashpots, Δt = {dt:g} s", result, ref,
                             events["runtime"]))
            print(lines[-1], file=sys.stderr, flush=True)
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--case", nargs="+", default=["A", "B"])
    parser.add_argument("--springs", nargs="+", type=int, default=[12],
                        help="foundation springs (default 12, the scene's own, Fig. 1b)")
    parser.add_argument("--dt", nargs="+", type=float, default=[0.002, 0.001, 0.0005])
    parser.add_argument("--dashpots", nargs="+", default=["detaching", "parallel"],
                        choices=["detaching", "parallel"])
    parser.add_argument("--timeout", type=float, default=900.0, help="per OpenSees run (s)")
    parser.add_argument("--quick", action="store_true", help="Case A, N = 12, Δt = 0.002 s")
    parser.add_argument("--check", nargs="*", type=float, default=[0.0, 0.1],
                        help="also Case A with these foundation damping ratios ζ_f (default 0 "
                             "and 0.1): 0 checks the mapping of the model free of any dashpot "
                             "definition; the others show how the difference grows with ζ_f")
    add_output_arguments(parser, "opensees_reduced")
    args = parser.parse_args(argv)
    if args.child:
        print(json.dumps(child(json.loads(sys.stdin.read()))))
        return 0
    require("openseespy", "opensees", "opensees_reduced")
    out = output_folder(args, "opensees_reduced") / "REDUCED.md"
    if args.quick:
        args.case, args.springs, args.dt, args.check = ["A"], [12], [0.002], [0.0]
    env = opensees_environment()
    if env is None:
        print("opensees_reduced: error: openseespy does not run in a subprocess here (pip "
              "install 'upliftlab[opensees]'); nothing was written", file=sys.stderr)
        return 2
    runs = [("A", (f"foundation.damping_ratio={z:g}",)) for z in args.check]
    runs += [(case, ()) for case in args.case]
    parts = [compare(case, n, args.dt, args.dashpots, env, args.timeout, extra)
             for case, extra in runs for n in args.springs]
    text = "\n\n".join(parts)
    print(text)
    write_section(out, SECTION_HEAD + text)
    print(f"opensees_reduced: wrote the OpenSees section of {out}", file=sys.stderr)
    return 0


MARK_BEGIN, MARK_END = "<!-- opensees_reduced: begin -->", "<!-- opensees_reduced: end -->"
SECTION_HEAD = """## OpenSees comparison (`python benchmarks/opensees_reduced.py`)

Short-period building on El Centro, N springs, upliftlab's own numbers handed to an OpenSeesPy
model in a subprocess (zeroLength springs: ENT for Case A, ElasticPPGap with damage for Case B;
rigid base by rigidLink beam with Lagrange constraints; Newmark 0.5/0.25 with Newton). Errors in
brackets are against upliftlab's converged event stepper. "detaching" dashpots: stiffness-
proportional Rayleigh damping on each spring element's current tangent (β = c_i/k_i), acting
only in contact; "parallel": a Viscous material in parallel with the spring, always attached.
upliftlab's dashpot detaches with its spring and its total force is clipped at zero while it
opens (never pulls): neither OpenSees variant has that clip. In Case B the "detaching" dashpot
also stops while its spring yields (tangent 0); upliftlab's keeps acting. The uplift is the gap
under the leftmost spring from its settled surface in both. OpenSees runtimes are the time-step
loop in the child; upliftlab's the median of 3 `run(..., histories=False)` calls in the parent,
the same run.

"""


def write_section(path: Path, text: str) -> None:
    """Put ``text`` between this script's markers in ``path`` (appended if absent)."""
    from upliftlab.results import write_text

    old = path.read_text() if path.exists() else ""
    block = f"{MARK_BEGIN}\n{text}\n{MARK_END}"
    if MARK_BEGIN in old and MARK_END in old:
        head, rest = old.split(MARK_BEGIN, 1)
        new = head + block + rest.split(MARK_END, 1)[1]
    else:
        new = old.rstrip("\n") + ("\n\n" if old else "") + block + "\n"
    write_text(path, new)


if __name__ == "__main__":
    sys.exit(main())
