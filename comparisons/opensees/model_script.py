#!/usr/bin/env python3
"""An OpenSeesPy model of an upliftlab scene: a BNWF model of upliftlab's reduced model.

Standalone: it needs Python 3 and openseespy only (pip install openseespy; on Linux the wheel
also needs libblas.so.3, which this script finds inside the wheel when the system has none).
upliftlab writes it unchanged (``upliftlab opensees SCENE``), with the scene's numbers in
``model.json`` beside it, and the ground motion, if any, in ``motion.txt``: this script holds
no number and no text of the scene, only the model's code. Run it with ``python model.py``: it
prints the scene's modelling notes (how each part compares with upliftlab's reduced model),
runs gravity and the motion, writes ``opensees_histories.csv`` (time, u, theta, V, the
leftmost spring's compression from rest, base shear) and ``opensees_summary.json`` (the peaks)
beside itself, each whole or not at all, and prints the summary. Exit 0 when the run completed,
1 when it did not, 3 (one line naming the file) when its results found no room on the disk.

2D, three DOFs per node, in the scene's consistent units (``model.json``: ``units``, ``g``).
"""

import errno
import json
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# The scene's numbers, read from model.json by load_scene_numbers() before anything runs:
WRITTEN_BY = SCENE = TITLE = COMMAND = UNITS = None  # who wrote this model, and from what
G = None  # length/s²
SUPPORT = None  # uplift: springs carry no tension; bonded: they do; fixed: no springs
DASHPOTS = None  # foundation dashpots: clipped, detaching or parallel
RIGID = P_DELTA = None  # the stories tied to the footing; the story weights' P-Δ
VERTICAL_WEIGHT = None  # force: W_v, carried by the footing (mass W_v/G)
ROTARY_INERTIA = None  # force·length·s²: I0 of the footing body about O
FOUNDATION = None  # springs, left to right: (x, k, c, F0, Fy); Fy inf: elastic
STORIES = None  # bottom to top: (height above O, weight, k, c, Fy, post-yield ratio α)
DT = DURATION = None  # s: the Newmark step and the run's length
MOTION_FILE = None  # the ground acceleration beside this script ("" for none)
INITIAL_VELOCITY = None  # length/s, of the top mass relative to the ground
TOLERANCE = None  # length: Newton's displacement increment
TIE_STIFFNESS = None  # force·length/rad: ties a floor's rotation to the footing's
QZ = ()  # a q–z bed: per spring the QzSimple2 (type, q_ult, z50, suction, c); () otherwise
NOTES = ()  # one sentence per modelling choice


def load_scene_numbers(path=None):
    """Set the constants above from ``model.json`` (written by upliftlab beside this script):
    numbers and the scene's names, never code."""
    with open(path or os.path.join(HERE, "model.json"), encoding="utf-8") as f:
        numbers = json.load(f)
    for name in ("FOUNDATION", "STORIES", "QZ"):
        numbers[name] = [tuple(row) for row in numbers.get(name, ())]
    numbers["NOTES"] = tuple(numbers["NOTES"])
    unknown = set(numbers) - {n for n in globals() if n.isupper()}
    if unknown:
        sys.exit(f"model.json names what this script does not have: {sorted(unknown)}")
    globals().update(numbers)
# =============================================================================================
# The model. Node and element numbers:
#   1            the footing's centre O: vertical displacement V and rotation (x is held)
#   1000 + i     a fixed soil node under foundation spring i (i = 1 … N, left to right)
#   2000 + i     the footing's node above it, tied to node 1 by a rigid link
#   100 + j      the mass of story j (j = 1 at the bottom)
#   200 + j      the point at the height of mass j carried rigidly by the floor below (by the
#                footing for j = 1): the story spring j joins it to mass j
# Elements: 1000 + i foundation spring i, 100 + j story spring j, 800 + j the rotational tie
# of mass j to the footing, 300 + j, 400 + j, 450 + j and 500 the P-Δ springs.
# Sign: OpenSees' rotation is counter-clockwise; upliftlab's θ is positive when it moves the
# top by +hθ (clockwise here), so θ = −(node 1's rotation).
# =============================================================================================

BASE = 1


def soil_node(i):
    return 1000 + i


def footing_node(i):
    return 2000 + i


def mass_node(j):
    return 100 + j


def below_node(j):
    return 200 + j


def import_opensees():
    """openseespy. The Linux wheel (openseespylinux) ships BLAS and LAPACK in its lib/ folder,
    but its LAPACK does not find the BLAS beside it unless the system has libblas.so.3
    (Debian/Ubuntu: apt-get install libblas3): load that BLAS first when the plain import
    fails."""
    try:
        import openseespy.opensees as ops
        return ops
    except Exception:
        pass
    import ctypes
    import importlib.util
    found = importlib.util.find_spec("openseespylinux")
    if found is None or not found.submodule_search_locations:
        sys.exit("openseespy is not installed (pip install openseespy)")
    lib = os.path.join(list(found.submodule_search_locations)[0], "lib", "libblas.so.3")
    if os.path.exists(lib):
        ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops
    return ops


def foundation_material(ops, tag, k, c, fy):
    """The material of one foundation spring; returns its tag.

    The element's nodes are ordered (footing, soil), so its deformation is the soil's
    compression, positive. The spring alone carries no tension: elastic (``Elastic`` with no
    stiffness in tension) or elastic-perfectly-plastic in compression (``ElasticPPGap`` with
    'damage': yield at Fy, the plastic settlement kept, so the spring separates from its
    settled surface). Its dashpot c, by DASHPOTS: "clipped" puts spring and dashpot inside
    ``TensionOnly``, which keeps the positive part of their sum, so the dashpot detaches with
    its spring and never pulls; the spring inside is then one that pulls while open
    (``Elastic``, ``ElasticPP``), so that the dashpot cannot push long before the footing
    lands. TensionOnly scales a negative force by 1e-4 instead of zeroing it: wrapped twice,
    the pull of an open spring is 1e-8 k·gap (once, 1e-4 k·gap changed the peak rotation of
    an uplifting wall by 1 %). "parallel": a ``Viscous`` beside the spring,
    attached even while it is open. "detaching": Rayleigh damping (below).
    """
    if SUPPORT == "bonded":  # springs that also carry tension: spring and dashpot side by side
        if math.isinf(fy):
            ops.uniaxialMaterial("Elastic", tag + 1, k)
        else:
            ops.uniaxialMaterial("ElasticPP", tag + 1, k, fy / k, -1.0e10)
        if c == 0.0:
            return tag + 1
        ops.uniaxialMaterial("Viscous", tag + 2, c, 1.0)
        ops.uniaxialMaterial("Parallel", tag, tag + 1, tag + 2)
        return tag
    if math.isinf(fy):
        ops.uniaxialMaterial("Elastic", tag + 1, k, 0.0, 0.0)  # E in compression, 0 in tension
    else:
        ops.uniaxialMaterial("ElasticPPGap", tag + 1, k, fy, 0.0, 0.0, "damage")
    if c == 0.0 or DASHPOTS == "detaching":
        return tag + 1
    ops.uniaxialMaterial("Viscous", tag + 2, c, 1.0)
    if DASHPOTS == "parallel":
        ops.uniaxialMaterial("Parallel", tag, tag + 1, tag + 2)
        return tag
    if math.isinf(fy):  # "clipped"
        ops.uniaxialMaterial("Elastic", tag + 3, k)
    else:
        ops.uniaxialMaterial("ElasticPP", tag + 3, k, fy / k, -1.0e10)  # no yield in tension
    ops.uniaxialMaterial("Parallel", tag + 4, tag + 3, tag + 2)
    ops.uniaxialMaterial("TensionOnly", tag + 5, tag + 4)
    ops.uniaxialMaterial("TensionOnly", tag, tag + 5)  # twice: the leak is then 1e-8
    return tag


def story_material(ops, tag, k, c, fy, alpha):
    """A story spring: elastic, or bilinear with kinematic hardening as an elastic-perfectly-
    plastic part (1 − α)k yielding at (1 − α)Fy beside an elastic αk; plus its dashpot c."""
    parts = []
    if math.isinf(fy):
        ops.uniaxialMaterial("Elastic", tag + 1, k)
        parts.append(tag + 1)
    else:
        ops.uniaxialMaterial("ElasticPP", tag + 1, (1.0 - alpha) * k, fy / k)
        parts.append(tag + 1)
        if alpha > 0.0:
            ops.uniaxialMaterial("Elastic", tag + 2, alpha * k)
            parts.append(tag + 2)
    if c > 0.0:
        ops.uniaxialMaterial("Viscous", tag + 3, c, 1.0)
        parts.append(tag + 3)
    ops.uniaxialMaterial("Parallel", tag, *parts)
    return tag


def build_model(ops):
    """Nodes, masses, constraints and springs of the BNWF model."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(BASE, 0.0, 0.0)
    if SUPPORT == "fixed":
        ops.fix(BASE, 1, 1, 1)
    else:
        ops.fix(BASE, 1, 0, 0)  # no sliding: the footing settles, lifts and rotates
        ops.mass(BASE, 0.0, VERTICAL_WEIGHT / G, ROTARY_INERTIA)
    springs = []
    for i, (x, k, c, f0, fy) in enumerate(FOUNDATION, start=1):
        ops.node(soil_node(i), x, 0.0)
        ops.fix(soil_node(i), 1, 1, 1)
        ops.node(footing_node(i), x, 0.0)
        ops.rigidLink("beam", BASE, footing_node(i))
        if QZ:  # QzSimple2: compression negative, so the element runs from soil to footing
            qz_type, qult, z50, suction, dashpot = QZ[i - 1]
            ops.uniaxialMaterial("QzSimple2", 10 * (1000 + i), int(qz_type), qult, z50,
                                 suction, dashpot)
            ops.element("zeroLength", 1000 + i, soil_node(i), footing_node(i), "-mat",
                        10 * (1000 + i), "-dir", 2)
            springs.append(1000 + i)
            continue
        mat = foundation_material(ops, 10 * (1000 + i), k, c, fy)
        rayleigh = ["-doRayleigh", 1] if DASHPOTS == "detaching" and c > 0.0 else []
        ops.element("zeroLength", 1000 + i, footing_node(i), soil_node(i), "-mat", mat,
                    "-dir", 2, *rayleigh)
        springs.append(1000 + i)
    if DASHPOTS == "detaching" and not QZ and any(c > 0.0 for _, _, c, _, _ in FOUNDATION):
        # stiffness-proportional damping on each spring's current tangent, β = c_i/k_i: zero
        # while the spring is open (and while it yields), never clipped
        beta = FOUNDATION[0][2] / FOUNDATION[0][1]
        ops.region(1, "-ele", *springs, "-rayleigh", 0.0, beta, 0.0, 0.0)
    for j, (h, w, k, c, fy, alpha) in enumerate(STORIES, start=1):
        ops.node(mass_node(j), 0.0, h)
        ops.mass(mass_node(j), w / G, 0.0, 0.0)  # lateral mass only: W_v/G on node 1 carries it
        if RIGID:
            ops.rigidLink("beam", BASE, mass_node(j))
            continue
        below = BASE if j == 1 else mass_node(j - 1)
        ops.node(below_node(j), 0.0, h)
        ops.rigidLink("beam", below, below_node(j))
        # story drift relative to the rotated footing: x_j − x_(j−1) − (h_j − h_(j−1))θ
        ops.element("zeroLength", 100 + j, below_node(j), mass_node(j), "-mat",
                    story_material(ops, 10 * (100 + j), k, c, fy, alpha), "-dir", 1)
        # the mass moves laterally; its vertical displacement is not used (small rotations, no
        # vertical mass here) and is held; its rotation carries the floor above, so it follows
        # the footing's through a stiff rotational spring (OpenSees 3.7's Lagrange handler
        # exits on an equalDOF that ties only some DOFs of a node)
        if j == len(STORIES) or SUPPORT == "fixed":
            ops.fix(mass_node(j), 0, 1, 1)
        else:
            ops.fix(mass_node(j), 0, 1, 0)
            ops.node(800 + j, 0.0, h)
            ops.rigidLink("beam", BASE, 800 + j)
            ops.uniaxialMaterial("Elastic", 8000 + j, TIE_STIFFNESS)
            ops.element("zeroLength", 800 + j, 800 + j, mass_node(j), "-mat", 8000 + j,
                        "-dir", 3)
    if P_DELTA:
        p_delta_springs(ops)


def p_delta_springs(ops):
    """The linearised P-Δ of the story weights, as upliftlab's (small rotations), by springs of
    negative stiffness. Rigid structure: −Σ W_j h_j on the footing's rotation. Shear building:
    −P_k/Δh_k beside each story (P_k the weight above story k), and for each mass W_j/h_j on its
    displacement relative to the rotated footing with −W_j/h_j on its displacement relative to
    the ground (together W_j h_j θ²/2 − W_j x_j θ, the weight's work about the rocking base)."""
    if RIGID:
        ops.node(500, 0.0, 0.0)
        ops.fix(500, 1, 1, 1)
        ops.uniaxialMaterial("Elastic", 5000, -sum(w * h for h, w, *_ in STORIES))
        ops.element("zeroLength", 500, 500, BASE, "-mat", 5000, "-dir", 3)
        return
    lower = 0.0
    for j, (h, w, *_) in enumerate(STORIES, start=1):
        above = sum(s[1] for s in STORIES[j - 1:])
        ops.uniaxialMaterial("Elastic", 3000 + j, -above / (h - lower))
        ops.element("zeroLength", 300 + j, below_node(j), mass_node(j), "-mat", 3000 + j,
                    "-dir", 1)
        lower = h
        if SUPPORT == "fixed":
            continue
        ops.node(600 + j, 0.0, h)  # a point at height h_j on the footing
        ops.rigidLink("beam", BASE, 600 + j)
        ops.node(700 + j, 0.0, h)  # a fixed point at height h_j
        ops.fix(700 + j, 1, 1, 1)
        ops.uniaxialMaterial("Elastic", 4000 + j, w / h)
        ops.uniaxialMaterial("Elastic", 4500 + j, -w / h)
        ops.element("zeroLength", 400 + j, 600 + j, mass_node(j), "-mat", 4000 + j, "-dir", 1)
        ops.element("zeroLength", 450 + j, 700 + j, mass_node(j), "-mat", 4500 + j, "-dir", 1)


def set_analysis(ops):
    """Lagrange multipliers for the rigid links, Newton on the displacement increment."""
    ops.constraints("Lagrange")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", TOLERANCE, 50)
    ops.algorithm("Newton")


def apply_gravity(ops):
    """The weight W_v on the footing in 10 load steps, then held (loadConst)."""
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(BASE, 0.0, -VERTICAL_WEIGHT, 0.0)
    set_analysis(ops)
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    if ops.analyze(10) != 0:
        sys.exit("gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def read_motion(path):
    """(dt, accelerations in g) of a two-column file 'time [s]  acceleration [g]'."""
    times, values = [], []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                t, a = line.split()
                times.append(float(t))
                values.append(float(a))
    dt = times[1] - times[0]
    for k in range(1, len(times)):
        if abs(times[k] - times[0] - k * dt) > 1e-6 * dt * k:
            sys.exit(f"{path}: the time step is not uniform at line {k + 1}")
    return dt, values


def apply_motion(ops):
    """The ground acceleration in x (linear between samples, zero after the last), or the
    initial velocity of the top mass relative to the ground."""
    if MOTION_FILE:
        dt, values = read_motion(os.path.join(HERE, MOTION_FILE))
        ops.timeSeries("Path", 2, "-dt", dt, "-values", *[a * G for a in values], 0.0)
        ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    if INITIAL_VELOCITY:
        if RIGID:  # the rigid structure turns about O, and every node tied to the footing with it
            rate = -INITIAL_VELOCITY / STORIES[-1][0]
            tied = [BASE] + [footing_node(i) for i in range(1, len(FOUNDATION) + 1)] \
                + [mass_node(j) for j in range(1, len(STORIES) + 1)]
            for node in tied:
                x, y = ops.nodeCoord(node)
                ops.setNodeVel(node, 1, -y * rate, "-commit")
                ops.setNodeVel(node, 2, x * rate, "-commit")
                ops.setNodeVel(node, 3, rate, "-commit")
        else:
            ops.setNodeVel(mass_node(len(STORIES)), 1, INITIAL_VELOCITY, "-commit")


def step(ops, dt, depth=0):
    """One step of dt; if Newton fails, Newton with line search, then modified Newton from the
    initial tangent, then two half steps (at most 8 halvings). Returns 0 when done."""
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


def hermite_extreme(y0, v0, y1, v1, h, largest):
    """The largest (or, with largest=False, the smallest) value over a step of the cubic
    through (y0, v0) and (y1, v1), the end values included: peaks between steps, as upliftlab
    takes them."""
    best = max(y0, y1) if largest else min(y0, y1)
    a = 6 * (y0 - y1) / h ** 3 + 3 * (v0 + v1) / h ** 2   # y'(s) = a s² + b s + v0
    b = -6 * (y0 - y1) / h ** 2 - 2 * (2 * v0 + v1) / h
    roots = []
    if abs(a) > 1e-300:
        disc = b * b - 4 * a * v0
        if disc >= 0:
            roots = [(-b + sgn * math.sqrt(disc)) / (2 * a) for sgn in (1, -1)]
    elif abs(b) > 1e-300:
        roots = [-v0 / b]
    for s in roots:
        if 0.0 < s < h:
            y = y0 + v0 * s + (b / 2) * s * s + (a / 3) * s ** 3
            best = max(best, y) if largest else min(best, y)
    return best


class Observer:
    """Reads the state after each step: u, θ, V, the leftmost spring, the base shear."""

    def __init__(self, ops):
        self.ops = ops
        self.left = min(range(len(FOUNDATION)), key=lambda i: FOUNDATION[i][0]) + 1 \
            if FOUNDATION else 0
        self.rest = self.raw()
        self.plastic = 0.0  # plastic settlement of the leftmost spring: largest ε − Fy/k
        self.rows = []
        self.peak = {"u": 0.0, "theta": 0.0, "uplift": 0.0, "shear": 0.0}
        self.prev = None

    def raw(self):
        """(u, u', θ, θ', V, ε, ε'): u the top's deformation relative to the rotated footing
        (the sum of the story drifts), ε the leftmost spring's compression from unloaded."""
        ops = self.ops
        u = ud = 0.0
        if not RIGID:
            for j in range(1, len(STORIES) + 1):
                u += ops.nodeDisp(mass_node(j), 1) - ops.nodeDisp(below_node(j), 1)
                ud += ops.nodeVel(mass_node(j), 1) - ops.nodeVel(below_node(j), 1)
        theta, thetad = -ops.nodeDisp(BASE, 3), -ops.nodeVel(BASE, 3)
        eps = epsd = 0.0
        if self.left_node():
            eps, epsd = -ops.nodeDisp(self.left_node(), 2), -ops.nodeVel(self.left_node(), 2)
        return [u, ud, theta, thetad, ops.nodeDisp(BASE, 2), eps, epsd]

    def left_node(self):
        return footing_node(self.left) if self.left else 0

    def shear(self):
        if RIGID or not STORIES:
            return 0.0
        return abs(self.ops.eleResponse(101, "force")[3])

    def observe(self, t, h):
        u, ud, th, thd, v, eps, epsd = self.raw()
        u, th, v = u - self.rest[0], th - self.rest[2], v - self.rest[4]
        if self.left:
            fy, k = FOUNDATION[self.left - 1][4], FOUNDATION[self.left - 1][1]
            if not math.isinf(fy):
                self.plastic = max(self.plastic, eps - fy / k)
        gap, gapd = self.plastic - eps, -epsd
        shear = self.shear()
        if self.prev is not None:
            u0, ud0, th0, thd0, gap0, gapd0 = self.prev
            pk = self.peak
            pk["u"] = max(pk["u"], hermite_extreme(u0, ud0, u, ud, h, True),
                          -hermite_extreme(u0, ud0, u, ud, h, False))
            pk["theta"] = max(pk["theta"], hermite_extreme(th0, thd0, th, thd, h, True),
                              -hermite_extreme(th0, thd0, th, thd, h, False))
            if self.left:
                pk["uplift"] = max(pk["uplift"], hermite_extreme(gap0, gapd0, gap, gapd, h, True))
        self.peak["shear"] = max(self.peak["shear"], shear)
        self.prev = (u, ud, th, thd, gap, gapd)
        self.rows.append((t, u, th, v, eps - self.rest[5], shear))


#: The errors of a write that found no room (a full disk, a quota, a file-size limit), and
#: the exit code that says so (as upliftlab's own: 3), after one line naming the file.
NO_SPACE = (errno.ENOSPC, errno.EDQUOT, errno.EFBIG)
NO_SPACE_EXIT = 3


def write_whole(name, write):
    """Write the file ``name`` beside this script with ``write(file)``, whole or not at all: into
    a temporary file first, moved to its name once written and flushed to the disk (a full disk
    leaves no half of it, and no temporary file)."""
    path = os.path.join(HERE, name)
    # named as upliftlab's own temporaries (.<name>.upliftlab-<pid>-<tag>.part): one that a
    # killed run leaves is removed by the next run through upliftlab
    part = os.path.join(HERE, f".{name}.upliftlab-{os.getpid()}-opensees.part")
    try:
        with open(part, "w") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(part, path)
    except BaseException as exc:
        if os.path.exists(part):
            os.remove(part)
        if isinstance(exc, OSError) and exc.filename is None:  # a write names no file
            raise OSError(exc.errno, exc.strerror, path) from None
        raise


def write_outputs(observer, status, runtime, setup, steps):
    """opensees_histories.csv and opensees_summary.json beside this script (the summary last:
    it says the run is complete)."""
    summary_path = os.path.join(HERE, "opensees_summary.json")
    if os.path.exists(summary_path):  # an earlier run's: never beside this run's histories
        os.remove(summary_path)
    names = "time,u,theta,V,left_spring_displacement,base_shear"
    header = (f"{TITLE}: OpenSees histories; units {UNITS}; theta as upliftlab's; "
              "left_spring_displacement is the compression from rest")

    def histories(f):
        # every line of the header a comment, a title's line breaks included (as upliftlab's
        # own CSV): no line of the title can become a row of numbers
        f.write("".join(f"# {line}\n" for line in header.splitlines()) + names + "\n")
        for row in observer.rows:
            f.write(",".join(f"{value:.10g}" for value in row) + "\n")

    write_whole("opensees_histories.csv", histories)
    pk, last = observer.peak, observer.rows[-1]
    summary = {"scene": SCENE, "verdict": status, "integrator": "opensees newmark",
               "dt": DT, "units": UNITS, "steps": steps, "runtime_s": runtime,
               "setup_s": setup, "peak_u": pk["u"], "peak_theta": pk["theta"],
               "peak_base_shear": pk["shear"]}
    if FOUNDATION:
        summary["peak_uplift_left"] = max(pk["uplift"], 0.0)
        summary["final_vertical_position"] = last[3]  # V at the end, up positive
    bad = [key for key, value in summary.items()
           if isinstance(value, float) and not math.isfinite(value)]
    if bad:
        summary["verdict"] = f"failed: non-finite {', '.join(bad)}"
        for key in bad:
            summary[key] = None
    write_whole("opensees_summary.json", lambda f: json.dump(summary, f, indent=1))
    return summary


def printable(text):
    """``text`` with each character that is not printable (a line break, a terminal escape)
    written as its Python escape (``\\n``, ``\\x1b``): a scene's title reaches the terminal as
    text, never as control codes."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(text))


def announce():
    """The scene and its modelling notes, on stderr, one line each."""
    print(printable(f"OpenSees model of {SCENE}: {TITLE} ({UNITS})"), file=sys.stderr)
    for note in NOTES:
        print(printable(f"- {note}"), file=sys.stderr)


def main():
    load_scene_numbers()
    announce()
    ops = import_opensees()
    start = time.perf_counter()
    build_model(ops)
    apply_gravity(ops)
    observer = Observer(ops)
    apply_motion(ops)
    set_analysis(ops)
    ops.integrator("Newmark", 0.5, 0.25)  # average acceleration, as upliftlab's "newmark"
    ops.analysis("Transient")
    setup = time.perf_counter() - start
    steps = int(round(DURATION / DT))
    observer.observe(0.0, DT)
    status, start, report = "completed", time.perf_counter(), max(1, steps // 20)
    for n in range(1, steps + 1):
        if n == 1 and INITIAL_VELOCITY:
            # OpenSees' Newmark starts from zero acceleration, not from the one in equilibrium
            # with the initial velocity (the story dashpot's force c·v0): the first step's
            # velocity is then off by Δt/2 times that acceleration. Splitting the first step
            # into 100 makes it 100 times smaller (upliftlab starts from equilibrium).
            ok = all(step(ops, DT / 100) == 0 for _ in range(100))
        else:
            ok = step(ops, DT) == 0
        if not ok:
            status = f"failed: no convergence at t = {ops.getTime():.5g} s"
            break
        observer.observe(n * DT, DT)
        if n % report == 0 or n == steps:
            elapsed = time.perf_counter() - start
            print(f"opensees: t = {n * DT:.3f}/{DURATION:g} s, {elapsed:.1f} s elapsed, "
                  f"ETA {elapsed * (steps - n) / n:.0f} s", file=sys.stderr, flush=True)
    runtime = time.perf_counter() - start
    try:
        summary = write_outputs(observer, status, runtime, setup, steps)
    except OSError as exc:
        if exc.errno not in NO_SPACE:
            raise
        print(f"opensees: no space left on device writing {exc.filename or HERE} "
              f"(errno {exc.errno}: {exc.strerror})", file=sys.stderr, flush=True)
        return NO_SPACE_EXIT
    ops.wipe()
    print(json.dumps(summary))
    return 0 if summary["verdict"] == "completed" else 1


if __name__ == "__main__":
    sys.exit(main())
