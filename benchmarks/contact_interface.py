"""Gajan and Kutter's contact interface model (OpenSees ``soilFootingSection2d``) compiled from
an OpenSees source tree and driven here by the model that upliftlab's ``model.tcl`` builds, for
the comparison of :mod:`opensees_contact_interface` (issue 36 §4).

openseespy has no ``soilFootingSection2d`` and this machine no Tcl OpenSees, so the section's
own C++ (``SRC/material/section/yieldSurface/SoilFootingSection2d.cpp`` of the tree given) is
compiled with ``g++`` against upliftlab's stand-ins for the few OpenSees classes it uses
(``contact_interface/shim``: a vector, a matrix, an ID, a stream, the section's base) and a C
interface (``contact_interface/capi.cpp``), and called through :mod:`ctypes`. Nothing of the
section is rewritten: its numbers are OpenSees's.

:func:`run_numbers` is ``model.tcl`` (``comparisons/opensees/soil_footing.tcl``) step by step,
from the same ``model_numbers.txt`` numbers (:func:`upliftlab.comparisons.opensees.tcl.
tcl_numbers`): node 2 the footing centre on the section (local x down: the section's
deformation is (−v, u, θ) and its force (V, H, M) acts on the footing as (H, −V, M)), beside the
sway dashpot; node 3 the story mass on an elastic column (E = 1, I = k h³/12, A = 10⁶ K_v h)
whose top rotation is the footing's (equalDOF 2 3 3), with the column's stiffness-proportional
dashpot β K; the footing's horizontal mass, the whole vertical mass and the rotary inertia at
node 2, the story's horizontal mass at node 3. Gravity in ``gravity_steps`` load steps, a
horizontal load of 10⁻⁶ of the story weight put on and taken off, then the ground acceleration
as a uniform excitation (−m a_g on each horizontal mass), Newmark (γ = ½, β = ¼) with Newton at
``dt``, the norm of the displacement increment within ``tolerance`` in at most 50 iterations,
OpenSees's order of calls: the trial deformation set once after each correction (and once at
the step's predictor), the section's tangent of its last trial used for the next correction,
the section committed at the step's end. A step that does not converge ends the run, as it
ends the Tcl script. P-Δ is refused (the map's points have none).
"""

from __future__ import annotations

import ctypes
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent / "contact_interface"
SECTION = Path("SRC/material/section/yieldSurface")
MAX_ITERATIONS = 50
#: The displacement DOFs: u2, v2, θ2 (the footing centre), u3, v3 (the story; θ3 = θ2).
DOFS = 5


class ContactInterfaceError(RuntimeError):
    """A run of the section that OpenSees would stop (a step that does not converge)."""


def compile_section(opensees: Path, out: Path) -> Path:
    """Compile the section of the OpenSees tree ``opensees`` with the stand-ins into
    ``out/libcontact_interface.so``; refuse, in one line, a tree without the section."""
    source = Path(opensees) / SECTION
    cpp, header = source / "SoilFootingSection2d.cpp", source / "SoilFootingSection2d.h"
    for path in (cpp, header):
        if not path.is_file():
            raise SystemExit(f"contact_interface: --opensees: {path} is not a file (an OpenSees "
                             "source tree holds it)")
    if shutil.which("g++") is None:
        raise SystemExit("contact_interface: g++ is not installed (Debian/Ubuntu: apt-get "
                         "install g++); it compiles the section")
    out.mkdir(parents=True, exist_ok=True)
    library = out / "libcontact_interface.so"
    command = ["g++", "-O2", "-fPIC", "-shared", "-w", "-I", str(HERE / "shim"), "-I",
               str(source), str(cpp), str(HERE / "capi.cpp"), "-o", str(library)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        errors = [line for line in done.stderr.splitlines() if "error" in line] or [""]
        raise SystemExit(f"contact_interface: g++ failed ({done.returncode}): {errors[0]}")
    return library


class Section:
    """One ``soilFootingSection2d`` (the compiled library's object)."""

    def __init__(self, library: Path, n: dict):
        lib = ctypes.CDLL(str(library))
        p, d = ctypes.c_void_p, ctypes.c_double
        lib.cim_new.restype, lib.cim_new.argtypes = p, [d] * 7
        lib.cim_delete.argtypes = [p]
        arr = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")
        lib.cim_trial.restype, lib.cim_trial.argtypes = ctypes.c_int, [p, arr, arr, arr]
        lib.cim_commit.restype, lib.cim_commit.argtypes = ctypes.c_int, [p]
        lib.cim_points.restype, lib.cim_points.argtypes = ctypes.c_int, [p]
        lib.cim_contact.argtypes = [p, arr, arr]
        lib.cim_initial_tangent.argtypes = [p, arr]
        self._lib = lib
        self._h = lib.cim_new(*(float(n[k]) for k in ("FS", "Vult", "L", "Kv", "Kh", "Rv", "dL")))
        if not self._h:
            raise MemoryError("contact_interface: the section could not be allocated")
        self.force, self.tangent = np.zeros(3), np.zeros(9)
        points = lib.cim_points(self._h)
        self._foot, self._surface = np.zeros(points), np.zeros(points)

    def trial(self, deformation: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The section's (V, H, M) and 3 × 3 tangent at the trial ``deformation`` (−v, u, θ)."""
        self._lib.cim_trial(self._h, np.ascontiguousarray(deformation, dtype=float),
                            self.force, self.tangent)
        return self.force.copy(), self.tangent.reshape(3, 3).copy()

    def initial_tangent(self) -> np.ndarray:
        """The section's own initial tangent (3 × 3)."""
        out = np.zeros(9)
        self._lib.cim_initial_tangent(self._h, out)
        return out.reshape(3, 3)

    def commit(self) -> None:
        self._lib.cim_commit(self._h)

    def edge_gaps(self) -> tuple[float, float]:
        """The gaps (length) between the footing and the soil's surface at both ends, at the
        last trial: the section's own record of where the footing lifted off."""
        self._lib.cim_contact(self._h, self._foot, self._surface)
        gap = np.maximum(self._surface - self._foot, 0.0)
        return float(gap[0]), float(gap[-1])

    def __del__(self):
        if getattr(self, "_h", None):
            self._lib.cim_delete(self._h)
            self._h = None


def rotation_pushover(library: Path, n: dict, thetas) -> dict:
    """The section alone, loaded by its vertical load V = Vult/FS in ``gravity_steps`` steps of
    v, then rotated through ``thetas`` (rad, committed one by one) with V held (v found by the
    secant method from a step of V/Kv, within 1e-9 V in at most 50 trials: the section's own
    ks(0,0) is a secant of the step that can read 1 and stall a Newton iteration): M
    (force · length/length) at each θ, and the tangent at the first θ and the initial
    tangent."""
    section = Section(library, n)
    V = n["Vult"] / n["FS"]
    steps = int(n["gravity_steps"])
    for i in range(1, steps + 1):
        section.trial(np.array([V / n["Kv"] * i / steps, 0.0, 0.0]))
        section.commit()
    v, moments, first = V / n["Kv"], [], None
    for theta in thetas:
        force, tangent = section.trial(np.array([v, 0.0, theta]))
        v_old, V_old = v, force[0]
        v = v + (V - force[0]) / n["Kv"]
        for _ in range(MAX_ITERATIONS):
            force, tangent = section.trial(np.array([v, 0.0, theta]))
            if abs(force[0] - V) <= 1e-9 * V:
                break
            slope = (force[0] - V_old) / (v - v_old) if v != v_old else n["Kv"]
            v_old, V_old = v, force[0]
            v = v + (V - force[0]) / (slope if slope > 0 else n["Kv"])
        else:
            raise ContactInterfaceError(f"V not held at θ = {theta:g}")
        first = tangent if first is None else first
        section.commit()
        moments.append(force[2])
    return {"M": np.array(moments), "tangent": first,
            "initial_tangent": section.initial_tangent()}


def _column(n: dict) -> np.ndarray:
    """The elastic column's 5 × 5 stiffness on (u2, v2, θ2, u3, v3), its top rotation θ2."""
    h, E = n["height"], 1.0
    I = n["story_stiffness"] * h ** 3 / (12.0 * E)
    A = 1.0e6 * n["Kv"] * h / E
    a, b, c, d = E * A / h, 12 * E * I / h ** 3, 6 * E * I / h ** 2, E * I / h
    local = np.array([[a, 0, 0, -a, 0, 0], [0, b, c, 0, -b, c], [0, c, 4 * d, 0, -c, 2 * d],
                      [-a, 0, 0, a, 0, 0], [0, -b, -c, 0, b, -c], [0, c, 2 * d, 0, -c, 4 * d]])
    # local x along the column (global +y), local y = global −x
    T = np.zeros((6, DOFS))
    T[0, 1], T[1, 0], T[2, 2], T[3, 4], T[4, 3], T[5, 2] = 1, -1, 1, 1, -1, 1
    return T.T @ local @ T


#: The section's deformation (−v2, u2, θ2) from the DOFs.
SECTION_MAP = np.zeros((3, DOFS))
SECTION_MAP[0, 1], SECTION_MAP[1, 0], SECTION_MAP[2, 2] = -1.0, 1.0, 1.0


def _newton(section, d, residual_tangent, tolerance):
    """OpenSees's Newton with the norm of the displacement increment (module docstring):
    ``d`` corrected in place; the section's trial set after each correction."""
    force, tangent = section.trial(SECTION_MAP @ d)
    for _ in range(MAX_ITERATIONS):
        R, K = residual_tangent(d, force, tangent)
        dd = np.linalg.solve(K, R)
        if not np.all(np.isfinite(dd)):
            return False
        d += dd
        force, tangent = section.trial(SECTION_MAP @ d)
        if math.sqrt(float(dd @ dd)) <= tolerance:
            return np.all(np.isfinite(force))
    return False


def run_numbers(library: Path, n: dict, accel_g: np.ndarray) -> dict:
    """The Tcl model's run (module docstring) of the numbers ``n`` under the ground
    acceleration ``accel_g`` (g, at ``n["motion_dt"]``): histories of time t (s, from the
    motion's start), the footing centre's u, v, θ, the story deformation s = u3 − u2 + h θ
    and its rate, the section's force and its edge gaps."""
    if n["p_delta"] > 0.5:
        raise SystemExit("contact_interface: p_delta: the driver has no P-Δ column")
    section = Section(library, n)
    K_col = _column(n)
    g, W_s, W_v = n["g"], n["story_weight"], n["vertical_weight"]
    mass = np.diag([(W_v - W_s) / g, W_v / g, n["rotary_inertia"], W_s / g, 0.0])
    C = n["story_damping_beta"] * K_col
    C[0, 0] += n["sway_damping"]
    gravity = np.array([0.0, W_s - W_v, 0.0, 0.0, -W_s])
    tol = n["tolerance"]
    d = np.zeros(DOFS)

    def static(load):
        def residual_tangent(d, force, tangent):
            return (load - SECTION_MAP.T @ force - K_col @ d,
                    K_col + SECTION_MAP.T @ tangent @ SECTION_MAP)
        if not _newton(section, d, residual_tangent, tol):
            raise ContactInterfaceError("a static step did not converge")
        section.commit()

    steps = int(n["gravity_steps"])
    for i in range(1, steps + 1):
        static(gravity * i / steps)
    nudge = np.array([0.0, 0.0, 0.0, 1.0e-6 * W_s, 0.0])
    static(gravity + nudge)
    static(gravity)
    d_static = d.copy()

    dt, beta, gamma = n["dt"], 0.25, 0.5
    t_motion = np.arange(accel_g.size) * n["motion_dt"]
    horizontal = np.array([1.0, 0.0, 0.0, 1.0, 0.0])
    count = int(n["steps"])
    v, a = np.zeros(DOFS), np.zeros(DOFS)
    out = {k: np.zeros(count + 1) for k in ("t", "u", "v", "theta", "s", "s_rate", "V", "H",
                                             "M", "gap_left", "gap_right")}

    def record(i, t, force):
        out["t"][i], out["u"][i], out["v"][i], out["theta"][i] = t, d[0], d[1], d[2]
        out["s"][i] = d[3] - d[0] + n["height"] * d[2]
        out["s_rate"][i] = v[3] - v[0] + n["height"] * v[2]
        out["V"][i], out["H"][i], out["M"][i] = force
        out["gap_left"][i], out["gap_right"][i] = section.edge_gaps()

    force, _ = section.trial(SECTION_MAP @ d)
    record(0, 0.0, force)
    c1, c2 = gamma / (beta * dt), 1.0 / (beta * dt * dt)
    K_dyn = K_col + c1 * C + c2 * mass
    for i in range(1, count + 1):
        t = i * dt
        ag = g * float(np.interp(t, t_motion, accel_g, right=0.0))
        load = gravity - mass @ horizontal * ag
        v_n, a_n, d_n = v, a, d.copy()

        def residual_tangent(d, force, tangent):
            dd = d - d_n
            vel = (1 - gamma / beta) * v_n + dt * (1 - gamma / (2 * beta)) * a_n + c1 * dd
            acc = -v_n / (beta * dt) + (1 - 1 / (2 * beta)) * a_n + c2 * dd
            R = load - SECTION_MAP.T @ force - K_col @ d - C @ vel - mass @ acc
            return R, K_dyn + SECTION_MAP.T @ tangent @ SECTION_MAP
        if not _newton(section, d, residual_tangent, tol):
            out = {k: x[:i] for k, x in out.items()}
            out["failed_at"] = t
            return {**out, "static": d_static}
        dd = d - d_n
        v = (1 - gamma / beta) * v_n + dt * (1 - gamma / (2 * beta)) * a_n + c1 * dd
        a = -v_n / (beta * dt) + (1 - 1 / (2 * beta)) * a_n + c2 * dd
        section.commit()
        record(i, t, section.force)
    return {**out, "static": d_static}
