"""Compiled spring laws and time-stepping loops of the reduced model (numba, ``cache=True``).

Every parameter is passed as an argument; nothing is global. Each integrator is a plain Python
function compiled by numba, and its ``.py_func`` is the interpreted reference implementation
used by the tests. The spring laws live in this file, although :mod:`.springs` is where they
are documented and exported: numba's ``cache=True`` keys a cached function on its own source
file only, so a law edited in another file would leave stale compiled integrators.

Equation of motion (relative to the ground, Ewing eqs. 5–8):
``M q̈ = −A s(Aᵀq, Aᵀq̇) − K_G q + L a_g(t)``, with M diagonal, ``s`` the spring laws, ``K_G``
the optional P-Δ geometric stiffness and ``L = −M r`` the ground load. Each spring carries its
column of A in its record (``nnz`` entries ``a0…a2`` at DOFs ``i0…i2``): every spring touches
two or three DOFs, so e = Aᵀq and the nodal forces A s are gathered and scattered per spring.

Spring parameters are a structured array (:data:`SPRING_DTYPE`), one record per spring, and the
spring history another (:data:`HISTORY_DTYPE`). Records keep the laws readable (``p.k``,
``h.ep``) and fast: unlike array rows they carry no reference count.

Integrators
    ``events``  RK4 in which every spring keeps its mode through a step; a step that leaves a
                mode anywhere inside (contact, separation, yield, unloading, clipping, impact
                lock) is cut at the switch, located by re-integration, so no error comes from
                stepping over a kink.
    ``rk4``     classical Runge–Kutta (Nyström form), fixed step, trial laws with end-of-step
                return mapping.
    ``abm4``    Adams–Bashforth–Moulton predictor–corrector (PECE), RK4 start, fixed step.
    ``newmark`` / ``hht``  implicit Newmark average acceleration / HHT-α with Newton.

Energy (relative formulation) is integrated alongside the state: input ∫ a_g Lᵀq̇ dt, viscous,
impact and plastic dissipation. Kinetic, strain and gravity energy follow from the state.
Status codes: 0 ok, 1 too many switches in one step (chattering), 2 non-finite state,
3 Newton did not converge.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

try:  # numba's own switch for helpers that never allocate (numba.core.options.DefaultOptions)
    from numba.core.options import DefaultOptions as _DefaultOptions
    HOT = {"_nrt": False} if hasattr(_DefaultOptions, "_nrt") else {}
except ImportError:  # pragma: no cover
    HOT = {}

# ---------------------------------------------------------------------------------------------
# Spring parameters and state
# ---------------------------------------------------------------------------------------------

SPRING_DTYPE = np.dtype([
    ("kind", np.int64),   # STORY, UPLIFT or BONDED
    ("nnz", np.int64),    # how many DOFs the spring connects (its column of A): 2 or 3
    ("i0", np.int64), ("i1", np.int64), ("i2", np.int64),          # their indices in q
    ("a0", np.float64), ("a1", np.float64), ("a2", np.float64),    # and the entries of A
    ("k", np.float64),    # stiffness (story: its elastic-plastic part) (force/length)
    ("c", np.float64),    # parallel dashpot (force·s/length)
    ("cimp", np.float64),  # impact dashpot c* (force·s/length)
    ("f0", np.float64),   # static compression F0 (force)
    ("fy", np.float64),   # yield force (force; inf = elastic)
    ("kh", np.float64),   # parallel hardening stiffness of a story (force/length)
    ("dzf", np.float64),  # impact stroke per unit closing velocity, m_eff (1 − ε)/c* (s)
    ("x", np.float64),    # position under the base (length)
    ("imph", np.float64),  # largest stable RK4 step while the impact dashpot acts (s)
    ("d0", np.float64),   # derived: δ0 = F0/k (length)
    ("dy", np.float64),   # derived: Fy/k (length)
    ("gs", np.float64),   # derived: 1/F0 (story: 1/Fy; 0 if elastic) (1/force)
    ("gd", np.float64),   # derived: 1/δ0 (1/length)
    ("share", np.float64),  # derived: c*/(c + c*), the impact dashpot's share
    ("arm", np.float64),  # story: its height above the story below, the lever of its shear
], align=True)

HISTORY_DTYPE = np.dtype([
    ("ep", np.float64),   # plastic deformation: settlement, or plastic story drift (length)
    ("imp", np.float64),  # 1 while the impact dashpot acts, else 0
    ("e0", np.float64),   # deformation at the last recontact (length)
    ("dz", np.float64),   # impact stroke Δz of the last recontact (length)
], align=True)

STORY, UPLIFT, BONDED = 0, 1, 2
SEPARATED, CONTACT, YIELDING, CLIPPED = 0, 1, 2, 3  # foundation modes
ELASTIC, YIELD_POS, YIELD_NEG = 0, 1, 2  # story modes

# energy accumulators and output columns
E_INPUT, E_VISCOUS, E_IMPACT, E_PLASTIC = range(4)
N_ACC = 4
N_ENERGY = 7  # input, kinetic, strain, gravity, viscous, impact, plastic
# peaks: scalars, then two per spring. P_MOT the largest |overturning moment| Σ arm·shear of
# the stories; P_CMIN the least contact length of the base; P_ERES the largest |residual| of
# the energy balance, P_ESCALE its scale (the largest |input| and the initial energy) and
# P_ETOT0 the balance's value at the start (stored + dissipated − input)
P_UMIN, P_UMAX, P_THMIN, P_THMAX, P_VMIN, P_VMAX = range(6)
P_MOT, P_CMIN, P_ERES, P_ESCALE, P_ETOT0 = range(6, 11)
# toppling: the overturning ratio and time at the last accepted state, and the time at which
# the ratio reached 1 (interpolated linearly between the last two accepted states)
P_RPREV, P_TPREV, P_TOVER = range(11, 14)
N_PEAK_SCALARS = 14

# the frame: constants of the scene's geometry and kinematics that every integrator takes (one
# float array), and the pivot side of exact kinematics (the one entry that changes in a run)
F_B = 0        # half-width b of the base (0: no foundation, nothing to overturn)
F_ECHECK = 1   # steps between checks of the energy balance
F_EXACT = 2    # 1: exact rocking kinematics (q holds sin θ), 0: small rotations
F_WTOT = 3     # weight whose centre decides overturning: the stories' and the base's
F_MB = 4       # mass of the base body at O beyond the stories' (exact kinematics)
F_IB = 5       # rotary inertia of the base body about O (exact kinematics)
F_SIDE = 6     # exact kinematics: the edge the base rocks about, +1 or −1
F_ITH = 7      # index of θ (or sin θ) in q, −1 if the base is fixed
F_IV = 8       # index of V in q
F_NFLEX = 9    # story DOFs in q (0 for a rigid structure)
F_RTOL = 10    # event stepper: relative tolerance of its error control (0: fixed steps)
F_HMAX = 11    # event stepper: the largest step it takes (s)
F_H0 = 12      # event stepper: its first trial step under error control (s)
F_OUTDT = 13   # event stepper under error control: spacing of the stored states (s), which it
               # interpolates within its steps (0: every ``stride`` steps)
N_FRAME = 14

OK, CHATTER, NONFINITE, NO_CONVERGENCE, OVERTURNED, STEP_UNDERFLOW = 0, 1, 2, 3, 4, 5
# counters: [0] steps cut at a switch (events) or the failing step, [1] switches or halvings,
# [2] right-hand sides or Newton iterations, [3] impacts logged, [4] output rows written,
# [5] trial steps rejected by the error control
N_COUNTERS = 6
SWITCH_TOL = 1e-12
OVERSHOOT_TOL = 1e-6
# A condition is computed from e, which carries an absolute rounding error ~ eps·|e|: for a
# very stiff spring (δ0 of micrometres under a settlement of centimetres) that exceeds
# SWITCH_TOL once scaled by 1/δ0. ROUNDING · (the size of the condition's terms) is allowed on
# top of SWITCH_TOL, the same in the crossing search and in the switch, so the two never
# disagree about a spring that sits on its limit.
ROUNDING = 32.0 * 2.220446049250313e-16
N_SAMPLES = 4

# ---------------------------------------------------------------------------------------------
# Spring laws (documented in :mod:`.springs`)
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def force_in_mode(mode, p, e, ed, ep, imp):
    """Force conjugate to e in a mode, and where its work goes.

    Returns (force, viscous power, impact power, plastic power, dashpot force, impact share):
    the story shear, or the foundation force increment F − F0 over the static compression.
    """
    if p.kind == STORY:
        fd = p.c * ed
        if mode == ELASTIC:
            return p.kh * e + p.k * (e - ep) + fd, fd * ed, 0.0, 0.0, fd, 0.0
        fep = p.fy if mode == YIELD_POS else -p.fy
        return p.kh * e + fep + fd, fd * ed, 0.0, fep * ed, fd, 0.0
    if mode == SEPARATED:
        return -p.f0, 0.0, 0.0, 0.0, 0.0, 0.0
    plastic = 0.0
    if mode == YIELDING:
        fs = p.fy
        plastic = fs * ed
    else:
        fs = p.k * (p.d0 + e - ep)
    if mode == CLIPPED:
        fd = -fs
    else:
        fd = (p.c + p.cimp * imp) * ed
    power = fd * ed
    share = p.share * imp
    return fs + fd - p.f0, power * (1.0 - share), power * share, plastic, fd, share


@njit(cache=True)
def natural_mode(p, e, ed, ep, imp):
    """The mode a trial state (e, ė) with committed history falls in (return-map predictor)."""
    if p.kind == STORY:
        fep = p.k * (e - ep)
        if fep > p.fy:
            return YIELD_POS
        if fep < -p.fy:
            return YIELD_NEG
        return ELASTIC
    d = p.d0 + e - ep
    if p.kind == UPLIFT and d <= 0.0:
        return SEPARATED
    fs = p.k * d
    yielding = fs > p.fy
    if yielding:
        fs = p.fy
    if p.kind == UPLIFT and fs + (p.c + p.cimp * imp) * ed < 0.0:
        return CLIPPED
    return YIELDING if yielding else CONTACT


@njit(cache=True)
def validity(mode, p, e, ed, h):
    """How far a spring is inside its mode: ≥ 0 valid, < 0 means a switch was crossed.

    Force conditions are scaled by F0 (story: Fy), displacement conditions by δ0, so that the
    location tolerance means the same for every spring; velocity conditions (unloading from
    yield) are left in length/s, since only their sign matters.
    """
    if p.kind == STORY:
        if mode == ELASTIC:
            return 1.0 - abs(p.k * (e - h.ep)) * p.gs
        return ed if mode == YIELD_POS else -ed
    d = e + p.d0 - h.ep
    g = (h.dz - (e - h.e0)) * p.gd if h.imp > 0.0 else 1.0
    if mode == SEPARATED:
        return min(g, -d * p.gd)
    if mode == YIELDING:
        return min(g, ed)
    if p.kind == BONDED:
        return min(g, (p.fy - p.k * d) * p.gs)
    force = (p.k * d + (p.c + p.cimp * h.imp) * ed) * p.gs
    if mode == CLIPPED:
        return min(g, d * p.gd, -force)
    return min(g, d * p.gd, (p.fy - p.k * d) * p.gs, force)


@njit(cache=True)
def past_limit(mode, p, e, ed, h):
    """True if a spring has crossed a limit of its mode: one of its conditions α + β e + γ ė
    (:func:`condition`) below −SWITCH_TOL by more than its rounding, ROUNDING times the size
    of its terms. The crossing search (:func:`column_crossing`) allows the same."""
    for k in range(N_CONDITIONS):
        alpha, beta, gamma = condition(k, mode, p, h)
        value = alpha + beta * e + gamma * ed
        size = abs(alpha) + abs(beta * e) + abs(gamma * ed)
        if value + ROUNDING * size < -SWITCH_TOL:
            return True
    return False


@njit(cache=True)
def switch_mode(mode, p, e, ed, h):
    """Switch a spring whose mode was crossed; updates its history ``h``; returns the new mode.

    Called at the located switch time, so the state is continuous: only the law changes.
    Plastic deformation is committed so that the force is continuous, and the new mode is
    always valid for the state it leaves (a spring that grazed its yield force and turned within
    the location tolerance gets the infinitesimal plastic step that puts it back on the limit).
    """
    if p.kind == STORY:
        if mode == ELASTIC:
            if e - h.ep > 0.0:
                h.ep = e - p.dy
                return YIELD_POS
            h.ep = e + p.dy
            return YIELD_NEG
        h.ep = e - p.dy if mode == YIELD_POS else e + p.dy
        return ELASTIC
    if h.imp > 0.0 and e - h.e0 >= h.dz:
        h.imp = 0.0  # the impact damper has run its stroke: lock
    if mode == YIELDING:
        if ed >= 0.0:
            return YIELDING  # still loading: only the impact damper changed
        h.ep = e + p.d0 - p.dy  # unloading: commit the plastic settlement
    d = e + p.d0 - h.ep
    if p.kind == UPLIFT and d <= 0.0:
        h.imp = 0.0
        return SEPARATED
    if mode == SEPARATED and p.dzf > 0.0:
        h.imp = 1.0  # recontact: the impact damper acts for Δz = v₀·m_eff(1 − ε)/c*
        h.e0 = e
        h.dz = p.dzf * max(ed, 0.0)
    if p.k * d >= p.fy:
        h.ep = e + p.d0 - p.dy
        d = p.dy
        if ed > 0.0:
            return YIELDING
    if p.kind == UPLIFT and p.k * d + (p.c + p.cimp * h.imp) * ed < 0.0:
        return CLIPPED
    return CONTACT


@njit(cache=True)
def commit_step(p, e, ed, h, was_contact):
    """End-of-step update for fixed-step integrators: return mapping, recontact, impact lock.

    Returns (plastic work of the step, contact flag 0/1).
    """
    ep = h.ep
    if p.kind == STORY:
        fep = p.k * (e - ep)
        if fep > p.fy:
            h.ep = e - p.dy
        elif fep < -p.fy:
            h.ep = e + p.dy
        return (p.fy * abs(h.ep - ep) if h.ep != ep else 0.0), 1
    d = e + p.d0 - ep
    if p.kind == UPLIFT and d <= 0.0:
        h.imp = 0.0
        return 0.0, 0
    work = 0.0
    if p.k * d > p.fy:
        h.ep = e + p.d0 - p.dy
        work = p.fy * (h.ep - ep)
    if was_contact == 0 and p.dzf > 0.0:
        h.imp = 1.0
        h.e0 = ep - p.d0  # the deformation at which the spring touched the surface
        h.dz = p.dzf * max(ed, 0.0)
    elif h.imp > 0.0 and e - h.e0 >= h.dz:
        h.imp = 0.0
    return work, 1


@njit(cache=True)
def tangent(mode, p, imp):
    """Tangent stiffness and damping (dF/de, dF/dė) in a mode, for implicit integration."""
    if p.kind == STORY:
        return p.kh + (p.k if mode == ELASTIC else 0.0), p.c
    if mode == SEPARATED or mode == CLIPPED:
        return 0.0, 0.0
    return (0.0 if mode == YIELDING else p.k), p.c + p.cimp * imp


# ---------------------------------------------------------------------------------------------
# Equation of motion
# ---------------------------------------------------------------------------------------------
#
# Helpers that take arrays are inlined into their callers (``inline="always"``): an ordinary
# call reference-counts each array argument, which costs accelerations about 100 ns a call,
# almost as much as its arithmetic for 41 springs (140 ns). Helpers on records and scalars cost nothing
# to call and stay ordinary functions. e = aᵀq is gathered and −a f scattered inline.


@njit(cache=True, inline="always")
def ground_acceleration(t, ag, dtg):
    """a_g(t): linear between samples k·dtg; ``ag`` ends with an appended zero."""
    s = t / dtg
    i = int(math.floor(s))
    if i < 0:
        return ag[0]
    if i >= ag.size - 1:
        return 0.0
    w = s - i
    return ag[i] * (1.0 - w) + ag[i + 1] * w


@njit(cache=True, inline="always")
def deformations(q, qd, P, e, ed):
    """e = Aᵀq and ė = Aᵀq̇ (eq. 3), for the first e.size springs."""
    for j in range(e.size):
        p = P[j]
        e[j] = p.a0 * q[p.i0] + p.a1 * q[p.i1]
        ed[j] = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
        if p.nnz == 3:
            e[j] += p.a2 * q[p.i2]
            ed[j] += p.a2 * qd[p.i2]


@njit(cache=True, inline="always")
def rates(q, qd, qdd, P, e, ed, edd):
    """e = Aᵀq, ė = Aᵀq̇ and ë = Aᵀq̈, for the first e.size springs."""
    for j in range(e.size):
        p = P[j]
        e[j] = p.a0 * q[p.i0] + p.a1 * q[p.i1]
        ed[j] = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
        edd[j] = p.a0 * qdd[p.i0] + p.a1 * qdd[p.i1]
        if p.nnz == 3:
            e[j] += p.a2 * q[p.i2]
            ed[j] += p.a2 * qd[p.i2]
            edd[j] += p.a2 * qdd[p.i2]


@njit(cache=True, inline="always")
def accelerations(t, q, qd, natural, minv, P, KG, L, ag, dtg, modes, H, frame, story, Mw, qdd):
    """q̈ from the equation of motion; returns the powers (input, viscous, impact, plastic).

    ``natural``: each spring's mode is decided by its trial state (fixed-step methods, whose
    plastic work is counted at the return map instead; with exact kinematics the base pivots
    on the edge of θ's sign); otherwise modes are frozen. Springs on
    the same two DOFs as the last spring (the foundation bed, on θ and V) sum their forces
    locally instead of scattering each into q̈.
    """
    n = q.size
    a = ground_acceleration(t, ag, dtg)
    pin = 0.0
    for i in range(n):
        qdd[i] = L[i] * a
        pin += L[i] * a * qd[i]
        for k in range(KG.shape[1]):
            qdd[i] -= KG[i, k] * q[k]
    pv = 0.0
    pi = 0.0
    pp = 0.0
    b0, b1 = P[P.size - 1].i0, P[P.size - 1].i1
    qb0, qb1, vb0, vb1 = q[b0], q[b1], qd[b0], qd[b1]
    fb0 = 0.0
    fb1 = 0.0
    for j in range(P.size):
        p = P[j]
        h = H[j]
        base = p.nnz == 2 and p.i0 == b0 and p.i1 == b1
        if base:
            e = p.a0 * qb0 + p.a1 * qb1
            ed = p.a0 * vb0 + p.a1 * vb1
        else:
            e = p.a0 * q[p.i0] + p.a1 * q[p.i1]
            ed = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
            if p.nnz == 3:
                e += p.a2 * q[p.i2]
                ed += p.a2 * qd[p.i2]
        mode = natural_mode(p, e, ed, h.ep, h.imp) if natural else modes[j]
        f, v, im, pl, _, _ = force_in_mode(mode, p, e, ed, h.ep, h.imp)
        pv += v
        pi += im
        pp += pl
        if base:
            fb0 += p.a0 * f
            fb1 += p.a1 * f
        else:
            qdd[p.i0] -= p.a0 * f
            qdd[p.i1] -= p.a1 * f
            if p.nnz == 3:
                qdd[p.i2] -= p.a2 * f
    qdd[b0] -= fb0
    qdd[b1] -= fb1
    if natural and frame[F_EXACT] > 0.0 and q[int(frame[F_ITH])] != 0.0:
        frame[F_SIDE] = 1.0 if q[int(frame[F_ITH])] > 0.0 else -1.0
    pin += finish_accelerations(a, q, qd, minv, frame, story, Mw, qdd)
    return pin, pv, pi, 0.0 if natural else pp


@njit(cache=True)
def geometric_or_nothing(KG):
    """K_G, or a K_G with no columns when it is zero (no P-Δ, the usual case), so that the
    loops over it cost nothing."""
    for i in range(KG.shape[0]):
        for k in range(KG.shape[1]):
            if KG[i, k] != 0.0:
                return KG
    return np.zeros((KG.shape[0], 0))


# ---------------------------------------------------------------------------------------------
# Exact rocking kinematics
# ---------------------------------------------------------------------------------------------
#
# With ``structure.kinematics = "exact"`` the base rotation enters through s = sin θ, which
# keeps every spring deformation linear in q (foundation: e = x s − V; story: the drift
# w_j − w_{j−1} in the base's rotated frame), so the laws, their tables and the switch location
# are those of small rotations. The base rotates about the edge it leans towards (x = ±b, the
# pivot of a rigid block): its centre O moves by u_O = ±b (1 − cos θ) horizontally and V
# vertically, story mass j sits at X_j = u_O + w_j cos θ + h_j sin θ,
# Y_j = V + h_j (cos θ − 1) − w_j sin θ, and the base body (mass m_b at O, rotary inertia I_b
# about O) with it. Lagrange's equations in q give M(q) q̈ = Q − (velocity terms); gravity acts
# on the exact configuration (P-Δ exact). The static compressions carry the weight, so the
# springs' force increments and gravity's vertical part cancel at rest, as in small rotations.


@njit(cache=True, inline="always")
def pivot(s, frame):
    """cos θ, and the base centre's horizontal displacement u_O = side·b (1 − cos θ) with its
    first and second derivatives in s = sin θ."""
    c = math.sqrt(max(1.0 - s * s, 1e-300))
    sb = frame[F_SIDE] * frame[F_B]
    return c, sb * (1.0 - c), sb * s / c, sb / (c * c * c)


@njit(cache=True, inline="always")
def exact_dynamics(a, q, qd, frame, story, R, M):
    """Add to R (the springs' generalised forces) the inertia, gravity and ground terms of
    exact kinematics and fill the mass matrix M(q); returns the ground's input power.

    ``story`` rows are (h_j, m_j, W_j) of each story mass; ``a`` the ground acceleration."""
    n = q.size
    ith, iv, nflex = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    s, sd = q[ith], qd[ith]
    c, _, u1, u2 = pivot(s, frame)
    c3 = c * c * c
    for i in range(n):
        for k in range(n):
            M[i, k] = 0.0
    mb, ib = frame[F_MB], frame[F_IB]
    M[ith, ith] += mb * u1 * u1 + ib / (c * c)
    M[iv, iv] += mb
    R[ith] -= mb * u1 * u2 * sd * sd + ib * sd * sd * s / (c3 * c) + a * mb * u1
    pin = -a * mb * u1 * sd
    for j in range(story.shape[0]):
        h, m, W = story[j, 0], story[j, 1], story[j, 2]
        w = q[j] if j < nflex else 0.0
        wd = qd[j] if j < nflex else 0.0
        xs = u1 - w * s / c + h      # ∂X_j/∂s
        ys = -h * s / c - w          # ∂Y_j/∂s
        gx = (u2 - w / c3) * sd * sd - 2.0 * (s / c) * sd * wd   # the rest of Ẍ_j
        gy = -h / c3 * sd * sd - 2.0 * sd * wd                    # the rest of Ÿ_j
        M[ith, ith] += m * (xs * xs + ys * ys)
        M[ith, iv] += m * ys
        M[iv, ith] += m * ys
        M[iv, iv] += m
        R[ith] -= m * (xs * gx + ys * gy) + a * m * xs + W * ys
        R[iv] -= m * gy
        pin -= a * m * xs * sd
        if j < nflex:
            cross = m * (c * xs - s * ys)
            M[j, j] += m
            M[j, ith] += cross
            M[ith, j] += cross
            M[j, iv] -= m * s
            M[iv, j] -= m * s
            R[j] -= m * (c * gx - s * gy) + a * m * c - W * s
            pin -= a * m * c * wd
    return pin


@njit(cache=True, inline="always")
def solve_spd(M, r):
    """Solve M x = r for a small symmetric positive definite M by Cholesky, in place: M is
    overwritten by its factor and r by x."""
    n = r.size
    for k in range(n):
        d = M[k, k]
        for p in range(k):
            d -= M[k, p] * M[k, p]
        d = math.sqrt(d)
        M[k, k] = d
        for i in range(k + 1, n):
            v = M[i, k]
            for p in range(k):
                v -= M[i, p] * M[k, p]
            M[i, k] = v / d
    for i in range(n):
        v = r[i]
        for p in range(i):
            v -= M[i, p] * r[p]
        r[i] = v / M[i, i]
    for i in range(n - 1, -1, -1):
        v = r[i]
        for p in range(i + 1, n):
            v -= M[p, i] * r[p]
        r[i] = v / M[i, i]


@njit(cache=True, inline="always")
def finish_accelerations(a, q, qd, minv, frame, story, M, qdd):
    """Turn the generalised forces in qdd into accelerations: M⁻¹ for small rotations (M
    diagonal); the exact kinematics' terms and its M(q) otherwise. Returns the extra input
    power (exact kinematics: the ground's; small: none, L a q̇ is counted by the caller)."""
    if frame[F_EXACT] > 0.0:
        pin = exact_dynamics(a, q, qd, frame, story, qdd, M)
        solve_spd(M, qdd)
        return pin
    for i in range(q.size):
        qdd[i] *= minv[i]
    return 0.0


@njit(cache=True)
def exact_energy(q, qd, frame, story, weight):
    """(kinetic, gravity) energy of exact kinematics: ½ Σ m |Ẋ|² + ½ I_b θ̇², and
    W V + Σ W_j (h_j (cos θ − 1) − w_j sin θ) (W the weight on the foundation)."""
    ith, iv, nflex = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    s, sd, vd = q[ith], qd[ith], qd[iv]
    c, _, u1, _ = pivot(s, frame)
    mb, ib = frame[F_MB], frame[F_IB]
    kinetic = 0.5 * mb * ((u1 * sd) ** 2 + vd * vd) + 0.5 * ib * (sd / c) ** 2
    gravity = weight * q[iv]
    for j in range(story.shape[0]):
        h, m, W = story[j, 0], story[j, 1], story[j, 2]
        w = q[j] if j < nflex else 0.0
        wd = qd[j] if j < nflex else 0.0
        xd = c * wd + (u1 - w * s / c + h) * sd
        yd = -s * wd + (-h * s / c - w) * sd + vd
        kinetic += 0.5 * m * (xd * xd + yd * yd)
        gravity += W * (h * (c - 1.0) - w * s)
    return kinetic, gravity


@njit(cache=True)
def overturn_ratio(q, frame, story):
    """|x_G − x_O|/b, x_G the lateral position of the centre of the weight (the stories' and the
    base's) in the exact geometry of the state, and x_O the base centre's rest position. At 1
    the centre is over the edge the base rocks about: past the toppling angle (a rigid block:
    θ = α = atan(b/h)). Small rotations are judged on the same geometry, their state read as
    θ and deflections w_j = x_j − h_j θ: the model's own restoring moment vanishes only at
    θ = b/h, past the real structure's toppling."""
    b = frame[F_B]
    if b <= 0.0:
        return 0.0
    ith, nflex = int(frame[F_ITH]), int(frame[F_NFLEX])
    exact = frame[F_EXACT] > 0.0
    s = q[ith] if exact else math.sin(q[ith])
    c = math.sqrt(max(1.0 - s * s, 0.0))
    moment = frame[F_WTOT] * b * (1.0 - c) * (1.0 if s >= 0.0 else -1.0)  # u_O of every weight
    for j in range(story.shape[0]):
        h = story[j, 0]
        w = 0.0
        if j < nflex:
            w = q[j] if exact else q[j] - h * q[ith]
        moment += story[j, 2] * (w * c + h * s)
    return abs(moment / frame[F_WTOT]) / b


@njit(cache=True, inline="always")
def rk4_stage_state(stage, h, q, qd, k1, k2, k3, qs, qds):
    """The state at which classical RK4 (Nyström form, q̈ = f(t, q, q̇)) evaluates its stage
    2, 3 or 4, from the stages before it."""
    for i in range(q.size):
        if stage == 2:
            qs[i] = q[i] + 0.5 * h * qd[i]
            qds[i] = qd[i] + 0.5 * h * k1[i]
        elif stage == 3:
            qs[i] = q[i] + 0.5 * h * qd[i] + 0.25 * h * h * k1[i]
            qds[i] = qd[i] + 0.5 * h * k2[i]
        else:
            qs[i] = q[i] + h * qd[i] + 0.5 * h * h * k2[i]
            qds[i] = qd[i] + h * k3[i]


@njit(cache=True, inline="always")
def rk4_combine(h, q, qd, acc, k1, k2, k3, k4, p1, p2, p3, p4, q1, qd1, acc1):
    """The end of an RK4 step from its four stages; the energy accumulators ``acc`` ride along
    as extra components, with the powers p1…p4 as their rates."""
    for i in range(q.size):
        q1[i] = q[i] + h * qd[i] + h * h / 6.0 * (k1[i] + k2[i] + k3[i])
        qd1[i] = qd[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    for c in range(N_ACC):
        acc1[c] = acc[c] + h / 6.0 * (p1[c] + 2.0 * p2[c] + 2.0 * p3[c] + p4[c])


@njit(cache=True, **HOT)
def rk4_step(t, h, q, qd, acc, natural, minv, P, KG, L, ag, dtg, modes, H, frame, story, Mw,
             k1, k2, k3, k4, qs, qds, q1, qd1, acc1):
    """One classical RK4 step of size h with the laws of :func:`accelerations`."""
    p1 = accelerations(t, q, qd, natural, minv, P, KG, L, ag, dtg, modes, H, frame, story, Mw,
                       k1)
    rk4_stage_state(2, h, q, qd, k1, k2, k3, qs, qds)
    p2 = accelerations(t + 0.5 * h, qs, qds, natural, minv, P, KG, L, ag, dtg, modes, H, frame,
                       story, Mw, k2)
    rk4_stage_state(3, h, q, qd, k1, k2, k3, qs, qds)
    p3 = accelerations(t + 0.5 * h, qs, qds, natural, minv, P, KG, L, ag, dtg, modes, H, frame,
                       story, Mw, k3)
    rk4_stage_state(4, h, q, qd, k1, k2, k3, qs, qds)
    p4 = accelerations(t + h, qs, qds, natural, minv, P, KG, L, ag, dtg, modes, H, frame, story,
                       Mw, k4)
    rk4_combine(h, q, qd, acc, k1, k2, k3, k4, p1, p2, p3, p4, q1, qd1, acc1)


# ---------------------------------------------------------------------------------------------
# Laws tabulated by mode (event stepper)
# ---------------------------------------------------------------------------------------------
#
# While a spring keeps its mode its force is affine in (e, ė), its powers are quadratic and
# its validity conditions are affine. The event stepper keeps their coefficients in a table,
# one column per spring, rewritten only when the spring switches, so that its right-hand side
# and its switch screen are branch-free loops. The foundation bed (the springs on the same two
# DOFs as the last spring: θ and V) has a table of its own that those loops run through in SIMD
# lanes; the other springs (stories) are few and go one by one.

T_A0, T_A1 = 0, 1           # entries of A on the two shared DOFs (bed table only)
T_K, T_C, T_F = 2, 3, 4      # force conjugate to e: T_K e + T_C ė + T_F
T_V, T_I = 5, 8              # viscous, impact power: (T[r] + T[r + 1] e + T[r + 2] ė) ė
T_P = 11                     # plastic power: T_P ė
T_COND = 12                  # condition k (:func:`condition`): α, β, γ in rows T_COND + 3k
N_CONDITIONS = 4
T_GAP, T_KC, T_FY = 24, 25, 26  # foundation peaks: gap T_GAP − e, force min(T_KC d, T_FY)
N_ROWS = 27
FAST = {"reassoc", "contract"}  # lets the compiler regroup sums into SIMD lanes


@njit(cache=True)
def condition(k, mode, p, hist):
    """Condition k of a spring's mode as (α, β, γ): the spring stays in its mode while
    α + β e + γ ė ≥ 0. :func:`validity` is the least of them; a k the mode does not use gives
    the constant 1. Foundation condition 0 is the impact stroke; the others, by mode: gap
    (separated); loading rate (yielding); contact, yield, compression (contact); contact,
    tension of the clipped force (clipped). Story: the two yield limits, or the rate."""
    one = (1.0, 0.0, 0.0)
    if p.kind == STORY:
        if mode == ELASTIC:
            s = p.k * p.gs
            if k == 0:
                return 1.0 + s * hist.ep, -s, 0.0
            return (1.0 - s * hist.ep, s, 0.0) if k == 1 else one
        if k == 0:
            return 0.0, 0.0, (1.0 if mode == YIELD_POS else -1.0)
        return one
    if k == 0:
        return ((hist.dz + hist.e0) * p.gd, -p.gd, 0.0) if hist.imp > 0.0 else one
    r = p.d0 - hist.ep  # d = e + r
    cd = (p.c + p.cimp * hist.imp) * p.gs
    if mode == SEPARATED:
        return (-r * p.gd, -p.gd, 0.0) if k == 1 else one
    if mode == YIELDING:
        return (0.0, 0.0, 1.0) if k == 1 else one
    if p.kind == BONDED:
        return ((p.fy - p.k * r) * p.gs, -p.k * p.gs, 0.0) if k == 1 else one
    if k == 1:
        return r * p.gd, p.gd, 0.0
    if mode == CLIPPED:
        return (-p.k * r * p.gs, -p.k * p.gs, -cd) if k == 2 else one
    if k == 2:
        return (p.fy - p.k * r) * p.gs, -p.k * p.gs, 0.0
    return (p.k * r * p.gs, p.k * p.gs, cd) if k == 3 else one


@njit(cache=True)
def law(mode, p, hist):
    """A spring's law in a mode, in the affine form of :func:`force_in_mode`: (K, C, F) of the
    force K e + C ė + F; (a, b, c) of the viscous power (a + b e + c ė) ė; the same for the
    impact dashpot; P of the plastic power P ė."""
    if p.kind == STORY:
        if mode == ELASTIC:
            return p.kh + p.k, p.c, -p.k * hist.ep, 0.0, 0.0, p.c, 0.0, 0.0, 0.0, 0.0
        fep = p.fy if mode == YIELD_POS else -p.fy
        return p.kh, p.c, fep, 0.0, 0.0, p.c, 0.0, 0.0, 0.0, fep
    if mode == SEPARATED:
        return 0.0, 0.0, -p.f0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    share = p.share * hist.imp
    cd = p.c + p.cimp * hist.imp
    if mode == CLIPPED:  # the dashpot cancels the spring: its power is −k d ė
        kr = -p.k * (p.d0 - hist.ep)
        return (0.0, 0.0, -p.f0, kr * (1.0 - share), -p.k * (1.0 - share), 0.0, kr * share,
                -p.k * share, 0.0, 0.0)
    if mode == YIELDING:
        return 0.0, cd, p.fy - p.f0, 0.0, 0.0, cd * (1.0 - share), 0.0, 0.0, cd * share, p.fy
    return (p.k, cd, p.k * (p.d0 - hist.ep) - p.f0, 0.0, 0.0, cd * (1.0 - share), 0.0, 0.0,
            cd * share, 0.0)


@njit(cache=True, **HOT)
def write_column(T, col, mode, p, hist):
    """Tabulate a spring's law and conditions in its mode into column ``col`` of T."""
    coefficients = law(mode, p, hist)
    for r in range(10):
        T[T_K + r, col] = coefficients[r]
    for k in range(N_CONDITIONS):
        alpha, beta, gamma = condition(k, mode, p, hist)
        T[T_COND + 3 * k, col] = alpha
        T[T_COND + 3 * k + 1, col] = beta
        T[T_COND + 3 * k + 2, col] = gamma
    T[T_GAP, col] = hist.ep - p.d0
    T[T_KC, col] = p.k if (p.kind != STORY and mode != SEPARATED) else 0.0
    T[T_FY, col] = p.fy


@njit(cache=True, **HOT)
def tabulate(j, modes, P, H, Tg, Tb):
    """Rewrite spring j's column (its mode or history changed)."""
    first = Tg.shape[1]
    if j >= first:
        write_column(Tb, j - first, modes[j], P[j], H[j])
    else:
        write_column(Tg, j, modes[j], P[j], H[j])


@njit(cache=True)
def bed_start(P):
    """Index of the first spring of the bed: the trailing run of foundation springs that
    connect the same two DOFs (and only those) as the last spring."""
    last = P[P.size - 1]
    first = P.size
    while (first > 0 and P[first - 1].kind != STORY and P[first - 1].nnz == 2
           and P[first - 1].i0 == last.i0 and P[first - 1].i1 == last.i1):
        first -= 1
    return first


@njit(cache=True, inline="always")
def bed_state(P, q, qd, qdd):
    """Value, rate and second rate of the bed's two DOFs (those of the last spring)."""
    b0, b1 = P[P.size - 1].i0, P[P.size - 1].i1
    return (q[b0], qd[b0], qdd[b0]), (q[b1], qd[b1], qdd[b1])


@njit(cache=True, inline="always")
def bed_rates(a0, a1, x, y):
    """e, ė, ë of a bed spring (entries a0, a1 of A) from the state x, y of the bed's DOFs."""
    return (a0 * x[0] + a1 * y[0], a0 * x[1] + a1 * y[1], a0 * x[2] + a1 * y[2])


@njit(cache=True)
def law_tables(P, modes, H):
    """The tables of the springs off the bed (Tg, in spring order) and of the bed (Tb)."""
    first = bed_start(P)
    Tg = np.zeros((N_ROWS, first))
    Tb = np.zeros((N_ROWS, P.size - first))
    for k in range(P.size - first):
        Tb[T_A0, k] = P[first + k].a0
        Tb[T_A1, k] = P[first + k].a1
    for j in range(P.size):
        tabulate(j, modes, P, H, Tg, Tb)
    return Tg, Tb


@njit(cache=True, fastmath=FAST, **HOT)
def bed_forces(T, x, xd, y, yd):
    """Forces of the bed on its two DOFs (values x, y, rates ẋ, ẏ) and its viscous, impact and
    plastic powers."""
    fx = 0.0
    fy = 0.0
    pv = 0.0
    pi = 0.0
    pp = 0.0
    for k in range(T.shape[1]):
        a0 = T[T_A0, k]
        a1 = T[T_A1, k]
        e = a0 * x + a1 * y
        ed = a0 * xd + a1 * yd
        f = T[T_K, k] * e + T[T_C, k] * ed + T[T_F, k]
        pv += (T[T_V, k] + T[T_V + 1, k] * e + T[T_V + 2, k] * ed) * ed
        pi += (T[T_I, k] + T[T_I + 1, k] * e + T[T_I + 2, k] * ed) * ed
        pp += T[T_P, k] * ed
        fx += a0 * f
        fy += a1 * f
    return fx, fy, pv, pi, pp


@njit(cache=True, inline="always")
def frozen_accelerations(t, q, qd, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story, Mw, qdd):
    """q̈ with every spring held in its tabulated mode (event stepper); returns the powers
    (input, viscous, impact, plastic)."""
    n = q.size
    a = ground_acceleration(t, ag, dtg)
    pin = 0.0
    for i in range(n):
        qdd[i] = L[i] * a
        pin += L[i] * a * qd[i]
        for k in range(KG.shape[1]):
            qdd[i] -= KG[i, k] * q[k]
    pv = 0.0
    pi = 0.0
    pp = 0.0
    for j in range(Tg.shape[1]):
        p = P[j]
        e = p.a0 * q[p.i0] + p.a1 * q[p.i1]
        ed = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
        if p.nnz == 3:
            e += p.a2 * q[p.i2]
            ed += p.a2 * qd[p.i2]
        f = Tg[T_K, j] * e + Tg[T_C, j] * ed + Tg[T_F, j]
        pv += (Tg[T_V, j] + Tg[T_V + 1, j] * e + Tg[T_V + 2, j] * ed) * ed
        pi += (Tg[T_I, j] + Tg[T_I + 1, j] * e + Tg[T_I + 2, j] * ed) * ed
        pp += Tg[T_P, j] * ed
        qdd[p.i0] -= p.a0 * f
        qdd[p.i1] -= p.a1 * f
        if p.nnz == 3:
            qdd[p.i2] -= p.a2 * f
    if Tb.shape[1] > 0:
        b0, b1 = P[P.size - 1].i0, P[P.size - 1].i1
        fx, fy, bv, bi, bp = bed_forces(Tb, q[b0], qd[b0], q[b1], qd[b1])
        qdd[b0] -= fx
        qdd[b1] -= fy
        pv += bv
        pi += bi
        pp += bp
    pin += finish_accelerations(a, q, qd, minv, frame, story, Mw, qdd)
    return pin, pv, pi, pp


@njit(cache=True, **HOT)
def frozen_rk4_step(t, h, q, qd, acc, k1, p1, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story, Mw,
                    k2, k3, k4, qs, qds, q1, qd1, acc1):
    """RK4 step of the event stepper, every spring in its tabulated mode, from its first stage
    k1 (with its powers p1): the acceleration at the end of the step before (three
    right-hand sides a step, with the one at its end)."""
    rk4_stage_state(2, h, q, qd, k1, k2, k3, qs, qds)
    p2 = frozen_accelerations(t + 0.5 * h, qs, qds, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story,
                              Mw, k2)
    rk4_stage_state(3, h, q, qd, k1, k2, k3, qs, qds)
    p3 = frozen_accelerations(t + 0.5 * h, qs, qds, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story,
                              Mw, k3)
    rk4_stage_state(4, h, q, qd, k1, k2, k3, qs, qds)
    p4 = frozen_accelerations(t + h, qs, qds, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story, Mw,
                              k4)
    rk4_combine(h, q, qd, acc, k1, k2, k3, k4, p1, p2, p3, p4, q1, qd1, acc1)


# ---------------------------------------------------------------------------------------------
# Switch detection and location
# ---------------------------------------------------------------------------------------------
#
# Within a step of the event stepper every spring keeps its mode, so the trial step is a smooth
# solution of one set of laws. Its ends carry q, q̇ and q̈, and the quintic Hermite interpolant
# through them is a dense output of the step as accurate as the step itself (its error comes
# from the end values, O(h⁵)). A switch is located on that interpolant and the step is cut
# there, with the interpolated state: no re-integration. Each validity condition of a spring is
# affine in (e, ė), so along the step it is a quintic in s = (t − t₀)/h, bounded by its
# Bernstein coefficients (convex hull). A cheaper bound first screens out the springs that
# cannot switch; the Bernstein coefficients, on halved pieces, isolate the first crossing of
# the others.

MAX_DEPTH = 24      # subdivision depth of the crossing search (2⁻²⁴ of a step)
MAX_PIECES = 4096   # pieces it visits at most


@njit(cache=True, inline="always")
def finite(a, b):
    """True if every entry of a and b is finite (without the temporaries of np.isfinite)."""
    for i in range(a.size):
        if not (math.isfinite(a[i]) and math.isfinite(b[i])):
            return False
    return True


@njit(cache=True)
def hermite(s, h, y0, d0, y1, d1):
    """Cubic Hermite interpolant and its derivative at fraction s of a step of length h."""
    s2 = s * s
    s3 = s2 * s
    y = ((2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * y1
         + (s3 - s2) * h * d1)
    dy = ((6 * s2 - 6 * s) * (y0 - y1)) / h + (3 * s2 - 4 * s + 1) * d0 + (3 * s2 - 2 * s) * d1
    return y, dy


@njit(cache=True)
def hermite_stationary(h, y0, d0, y1, d1):
    """Fractions s in (0, 1) where the cubic Hermite interpolant is stationary (2.0 if none)."""
    c = d0 * h
    b = 6.0 * (y1 - y0) - 4.0 * d0 * h - 2.0 * d1 * h
    a = -6.0 * (y1 - y0) + 3.0 * (d0 + d1) * h
    r1 = r2 = 2.0
    if abs(a) > 1e-300:
        disc = b * b - 4.0 * a * c
        if disc >= 0.0:
            sq = math.sqrt(disc)
            r1 = (-b - sq) / (2.0 * a)
            r2 = (-b + sq) / (2.0 * a)
    elif b != 0.0:
        r1 = -c / b
    r1 = r1 if 0.0 < r1 < 1.0 else 2.0
    r2 = r2 if 0.0 < r2 < 1.0 else 2.0
    return min(r1, r2), max(r1, r2)


@njit(cache=True, inline="always")
def quintic(h, y0, d0, a0, y1, d1, a1):
    """Coefficients (m₀ … m₅) in s ∈ [0, 1] of the quintic Hermite interpolant that matches
    value, rate and second rate (per unit time) at both ends of a step of length h."""
    m1 = h * d0
    m2 = 0.5 * h * h * a0
    r0 = y1 - y0 - m1 - m2
    r1 = h * d1 - m1 - 2.0 * m2
    r2 = h * h * a1 - 2.0 * m2
    return (y0, m1, m2, 10.0 * r0 - 4.0 * r1 + 0.5 * r2, -15.0 * r0 + 7.0 * r1 - r2,
            6.0 * r0 - 3.0 * r1 + 0.5 * r2)


@njit(cache=True, inline="always")
def chord_deviation(m, h):
    """Bounds on how far a quintic's value and rate (per unit time) stray from their chords
    over the step: the largest distance of its Bernstein control points (value: degree 5;
    rate: degree 4) from those of the chord."""
    u = m[1] - (m[1] + m[2] + m[3] + m[4] + m[5])
    dev_e = max(abs(0.2 * u), abs(0.4 * u + 0.1 * m[2]), abs(0.6 * u + 0.3 * m[2] + 0.1 * m[3]),
                abs(0.8 * u + 0.6 * m[2] + 0.4 * m[3] + 0.2 * m[4]))
    n1, n2, n3 = 2.0 * m[2], 3.0 * m[3], 4.0 * m[4]
    dn = n1 + n2 + n3 + 5.0 * m[5]
    dev_ed = max(abs(n1 - dn) / 4.0, abs(0.5 * (n1 - dn) + n2 / 6.0),
                 abs(0.75 * (n1 - dn) + 0.5 * n2 + 0.25 * n3))
    return dev_e, dev_ed / h


@njit(cache=True)
def condition_polynomial(alpha, beta, gamma, m, h):
    """Coefficients in s of α + β e(s) + γ ė(s), e the quintic with coefficients m."""
    g = gamma / h
    return (alpha + beta * m[0] + g * m[1], beta * m[1] + 2.0 * g * m[2],
            beta * m[2] + 3.0 * g * m[3], beta * m[3] + 4.0 * g * m[4],
            beta * m[4] + 5.0 * g * m[5], beta * m[5])


@njit(cache=True)
def bernstein(c):
    """Bernstein coefficients on [0, 1] of the quintic with power coefficients c."""
    return (c[0], c[0] + 0.2 * c[1], c[0] + 0.4 * c[1] + 0.1 * c[2],
            c[0] + 0.6 * c[1] + 0.3 * c[2] + 0.1 * c[3],
            c[0] + 0.8 * c[1] + 0.6 * c[2] + 0.4 * c[3] + 0.2 * c[4],
            c[0] + c[1] + c[2] + c[3] + c[4] + c[5])


@njit(cache=True)
def restricted(c, a, w):
    """Power coefficients in u of the quintic c at s = a + w u (its piece on [a, a + w])."""
    d1 = c[1] + a * (2.0 * c[2] + a * (3.0 * c[3] + a * (4.0 * c[4] + a * 5.0 * c[5])))
    d2 = c[2] + a * (3.0 * c[3] + a * (6.0 * c[4] + a * 10.0 * c[5]))
    d3 = c[3] + a * (4.0 * c[4] + a * 10.0 * c[5])
    d4 = c[4] + a * 5.0 * c[5]
    d0 = c[0] + a * (c[1] + a * (c[2] + a * (c[3] + a * (c[4] + a * c[5]))))
    w2 = w * w
    return d0, w * d1, w2 * d2, w2 * w * d3, w2 * w2 * d4, w2 * w2 * w * c[5]


@njit(cache=True)
def polynomial_at(c, s):
    return c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))))


@njit(cache=True)
def place_switch(c, lo, hi, g_hi):
    """Where in (lo, hi] to put a switch of the condition c, which is above −SWITCH_TOL at lo
    and at g_hi below it at hi: the first point found at the target overshoot (half of
    OVERSHOOT_TOL, or halfway down to g_hi for a shallower dip), by Illinois."""
    level = -SWITCH_TOL
    target = max(-0.5 * OVERSHOOT_TOL, 0.5 * (level + g_hi))
    f_lo = polynomial_at(c, lo) - target
    f_hi = g_hi - target
    if f_hi >= 0.0 or f_lo < 0.0:
        return hi
    accept = 0.5 * (level - target)
    side = 0
    for _ in range(100):
        if hi - lo <= 1e-15:
            break
        s = hi - f_hi * (hi - lo) / (f_hi - f_lo)
        s = min(max(s, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
        f = polynomial_at(c, s) - target
        if f < 0.0:
            hi, f_hi = s, f
            if side == -1:
                f_lo *= 0.5
            side = -1
            if f > -accept:
                break
        else:
            lo, f_lo = s, f
            if side == 1:
                f_hi *= 0.5
            side = 1
    return hi


@njit(cache=True)
def condition_crossing(c, s_max):
    """Fraction s at which to switch for the first dip of condition c below −SWITCH_TOL before
    s_max (2.0 if none). Pieces of [0, 1] are visited left to right, halving those whose
    Bernstein coefficients do not clear the level, down to :data:`MAX_DEPTH`; a dip narrower
    and shallower than that resolves (a graze) is ignored."""
    level = -SWITCH_TOL
    b = bernstein(c)
    if min(b) >= level:
        return 2.0
    if b[0] < level:
        return 0.0
    depth, k = 0, 0
    for _ in range(MAX_PIECES):
        w = 0.5 ** depth
        a = k * w
        if a >= s_max:
            return 2.0
        b = bernstein(restricted(c, a, w)) if depth > 0 else b
        if min(b) < level:
            if b[5] < level:
                return place_switch(c, a, a + w, b[5])
            if depth < MAX_DEPTH:
                depth, k = depth + 1, 2 * k
                continue
            g_mid = polynomial_at(c, a + 0.5 * w)
            if g_mid < level:
                return place_switch(c, a, a + 0.5 * w, g_mid)
        while k % 2 == 1:  # this piece is clear: on to the next one
            depth, k = depth - 1, k // 2
        if depth == 0:
            return 2.0
        k += 1
    return 2.0


@njit(cache=True, **HOT)
def log_impact(t, j, was_imp, imp, ed, impacts, open_impact, counters):
    """Record spring j's impact damper switching on (recontact) or locking at time t."""
    if was_imp == imp:
        return
    if imp > 0.0:
        k = counters[3]
        if k < impacts.shape[0]:
            impacts[k, 0] = t
            impacts[k, 1] = j
            impacts[k, 2] = ed
            impacts[k, 3] = np.nan
            impacts[k, 4] = np.nan
            open_impact[j] = k
        counters[3] += 1
    elif open_impact[j] >= 0:
        impacts[open_impact[j], 3] = t
        impacts[open_impact[j], 4] = ed
        open_impact[j] = -1


@njit(cache=True, inline="always")
def impact_step_cap(P, H):
    """Largest step while impact dashpots act: 1/Σ(1/``imph``) over the active ones.

    Each ``imph`` is the cap for one dashpot alone; dashpots that act at once add up (the
    largest eigenvalue of M⁻¹C is at most its trace, the sum of each one's c*/m_eff), so their
    rates add.
    """
    rate = 0.0
    for j in range(H.size):
        if H[j].imp > 0.0:
            rate += 1.0 / P[j].imph
    return 1.0 / rate if rate > 0.0 else np.inf


@njit(cache=True, inline="always")
def condition_bound(alpha, beta, gamma, e0, ed0, e1, ed1, dev_e, dev_ed):
    """Lower bound over a step of the condition α + β e + γ ė: its smaller end value less how
    far e and ė can stray from their chords."""
    return (min(alpha + beta * e0 + gamma * ed0, alpha + beta * e1 + gamma * ed1)
            - abs(beta) * dev_e - abs(gamma) * dev_ed)


@njit(cache=True, inline="always")
def column_margin(T, col, h, e0, ed0, edd0, e1, ed1, edd1):
    """Lower bound of a spring's validity over a step (column ``col`` of its table; its e, ė, ë
    at both ends), the least :func:`condition_bound` of its conditions on the step's quintic.
    Below −SWITCH_TOL the spring may switch inside the step. (Written out again in
    :func:`bed_margins`, whose loop it would keep out of SIMD lanes.)"""
    dev_e, dev_ed = chord_deviation(quintic(h, e0, ed0, edd0, e1, ed1, edd1), h)
    low = np.inf
    for k in range(N_CONDITIONS):
        r = T_COND + 3 * k
        low = min(low, condition_bound(T[r, col], T[r + 1, col], T[r + 2, col], e0, ed0, e1,
                                       ed1, dev_e, dev_ed))
    return low


@njit(cache=True, fastmath=FAST, **HOT)
def bed_margins(T, h, x0, y0, x1, y1, margin):
    """:func:`column_margin` of every spring of the bed, from the state of its two DOFs at the
    start (x0, y0) and the end (x1, y1) of the step. (Written out: a helper that takes the
    table would keep this loop out of SIMD lanes.)"""
    for k in range(T.shape[1]):
        a0, a1 = T[T_A0, k], T[T_A1, k]
        e0, ed0, edd0 = bed_rates(a0, a1, x0, y0)
        e1, ed1, edd1 = bed_rates(a0, a1, x1, y1)
        dev_e, dev_ed = chord_deviation(quintic(h, e0, ed0, edd0, e1, ed1, edd1), h)
        low = np.inf
        for c in range(N_CONDITIONS):
            r = T_COND + 3 * c
            low = min(low, condition_bound(T[r, k], T[r + 1, k], T[r + 2, k], e0, ed0, e1, ed1,
                                           dev_e, dev_ed))
        margin[k] = low


@njit(cache=True, inline="always")
def column_crossing(T, col, m, h, s_max, shift):
    """Earliest switch fraction before s_max (2.0 if none) of the spring in column ``col``,
    whose e on the step is the quintic with coefficients m, its conditions raised by
    ``shift``."""
    best = 2.0
    for k in range(N_CONDITIONS):
        alpha = T[T_COND + 3 * k, col] + shift
        beta = T[T_COND + 3 * k + 1, col]
        gamma = T[T_COND + 3 * k + 2, col]
        if (beta == 0.0 and gamma == 0.0) or not math.isfinite(alpha):
            continue  # a constant, or a limit at infinity (elastic)
        e_end = m[0] + m[1] + m[2] + m[3] + m[4] + m[5]
        ed_end = (m[1] + 2.0 * m[2] + 3.0 * m[3] + 4.0 * m[4] + 5.0 * m[5]) / h
        size = (abs(T[T_COND + 3 * k, col]) + abs(beta) * max(abs(m[0]), abs(e_end))
                + abs(gamma) * max(abs(m[1] / h), abs(ed_end)))
        c = condition_polynomial(alpha + ROUNDING * size, beta, gamma, m, h)
        best = min(best, condition_crossing(c, min(best, s_max)))
    return best


@njit(cache=True, inline="always")
def spring_quintic(j, h, Tb, x0, y0, x1, y1, e0, ed0, edd0, e1, ed1, edd1):
    """Coefficients of spring j's e on a trial step (bed springs from their DOFs' state)."""
    ng = e0.size
    if j < ng:
        return quintic(h, e0[j], ed0[j], edd0[j], e1[j], ed1[j], edd1[j])
    a0, a1 = Tb[T_A0, j - ng], Tb[T_A1, j - ng]
    ea, eda, edda = bed_rates(a0, a1, x0, y0)
    eb, edb, eddb = bed_rates(a0, a1, x1, y1)
    return quintic(h, ea, eda, edda, eb, edb, eddb)


@njit(cache=True, inline="always")
def quintic_at(m, s, h):
    """Value and rate (per unit time) at fraction s of a quintic with coefficients m."""
    y = m[0] + s * (m[1] + s * (m[2] + s * (m[3] + s * (m[4] + s * m[5]))))
    dy = m[1] + s * (2.0 * m[2] + s * (3.0 * m[3] + s * (4.0 * m[4] + s * 5.0 * m[5])))
    return y, dy / h


@njit(cache=True, inline="always")
def deformation(p, q, qd):
    """e and ė of the spring with record p at the state (q, q̇)."""
    e = p.a0 * q[p.i0] + p.a1 * q[p.i1]
    ed = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
    if p.nnz == 3:
        e += p.a2 * q[p.i2]
        ed += p.a2 * qd[p.i2]
    return e, ed


@njit(cache=True, **HOT)
def relocate(j, s, m, h, P, modes, H, Tg, Tb, q, qd):
    """Where to cut again when the step re-integrated to fraction s fell short of spring j's
    switch (state q, q̇): on the trial's interpolant raised by what it missed there."""
    e, ed = deformation(P[j], q, qd)
    reached = validity(modes[j], P[j], e, ed, H[j])
    e, ed = quintic_at(m, s, h)
    shift = reached - validity(modes[j], P[j], e, ed, H[j])
    ng = Tg.shape[1]
    if j < ng:
        return column_crossing(Tg, j, m, h, 2.0, shift)
    return column_crossing(Tb, j - ng, m, h, 2.0, shift)


@njit(cache=True, **HOT)
def first_crossing(h, P, Tg, Tb, x0, y0, x1, y1, e0, ed0, edd0, e1, ed1, edd1, margin):
    """Earliest fraction s of a trial step at which a spring should switch, on the step's
    quintic interpolant, and that spring; (2.0, −1) when every spring keeps its mode.

    (e, ė, ë) of the springs off the bed at the start and the end of the step; the bed's follow
    from its DOFs' state at the start (x0, y0) and the end (x1, y1). ``margin`` is scratch.
    """
    level = -SWITCH_TOL
    best, spring = 2.0, -1
    for j in range(e0.size):
        if column_margin(Tg, j, h, e0[j], ed0[j], edd0[j], e1[j], ed1[j], edd1[j]) >= level:
            continue
        m = quintic(h, e0[j], ed0[j], edd0[j], e1[j], ed1[j], edd1[j])
        s = column_crossing(Tg, j, m, h, best, 0.0)
        if s < best:
            best, spring = s, j
    if Tb.shape[1] == 0:
        return best, spring
    bed_margins(Tb, h, x0, y0, x1, y1, margin)
    for k in range(Tb.shape[1]):
        if margin[k] >= level:
            continue
        a0, a1 = Tb[T_A0, k], Tb[T_A1, k]
        ea, eda, edda = bed_rates(a0, a1, x0, y0)
        eb, edb, eddb = bed_rates(a0, a1, x1, y1)
        s = column_crossing(Tb, k, quintic(h, ea, eda, edda, eb, edb, eddb), h, best, 0.0)
        if s < best:
            best, spring = s, e0.size + k
    return best, spring


@njit(cache=True, **HOT)
def apply_switches(t, P, modes, H, q, qd, Tg, Tb, impacts, open_impact, counters):
    """Switch every spring whose mode was crossed at the state (q, q̇), rewrite its column and
    log its impact damper; returns how many switches."""
    switches = 0
    for j in range(P.size):
        p = P[j]
        e, ed = deformation(p, q, qd)
        was_imp = H[j].imp
        switched = False
        for _ in range(4):
            if not past_limit(modes[j], p, e, ed, H[j]):
                break
            modes[j] = switch_mode(modes[j], p, e, ed, H[j])
            switches += 1
            switched = True
        if switched:
            tabulate(j, modes, P, H, Tg, Tb)
            log_impact(t, j, was_imp, H[j].imp, ed, impacts, open_impact, counters)
    return switches


# ---------------------------------------------------------------------------------------------
# Peaks, records and state bookkeeping
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def hermite_extreme(y0, d0, y1, d1, h, current, find_max):
    """Max (or min) of ``current`` and the cubic Hermite interpolant's interior extrema."""
    if d0 * d1 >= 0.0:
        return current
    best = current
    r1, r2 = hermite_stationary(h, y0, d0, y1, d1)
    for s in (r1, r2):
        if s < 1.0:
            y, _ = hermite(s, h, y0, d0, y1, d1)
            best = max(best, y) if find_max else min(best, y)
    return best


@njit(cache=True, **HOT)
def track_peaks(h, q0, qd0, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv, peaks):
    """Update peaks over a step [t, t+h], refining interior extrema by Hermite interpolation.

    Scalars: top deformation u (sum of story drifts), θ, V, and at the step's end the
    overturning moment Σ arm·shear of the stories. Per spring j: slot A = max opening
    (foundation: gap −d; story: |drift|), slot B = max |force| at the step ends (foundation:
    spring compression; story: its shear, dashpot included, so story 0 gives the base shear).
    """
    if n_story > 0:
        u0 = ud0 = u1 = ud1 = 0.0
        for j in range(n_story):
            u0 += e0[j]
            ud0 += ed0[j]
            u1 += e1[j]
            ud1 += ed1[j]
        peaks[P_UMIN] = hermite_extreme(u0, ud0, u1, ud1, h, min(peaks[P_UMIN], u1), False)
        peaks[P_UMAX] = hermite_extreme(u0, ud0, u1, ud1, h, max(peaks[P_UMAX], u1), True)
    if ith >= 0:
        a, b, c, d = q0[ith], qd0[ith], q1[ith], qd1[ith]
        peaks[P_THMIN] = hermite_extreme(a, b, c, d, h, min(peaks[P_THMIN], c), False)
        peaks[P_THMAX] = hermite_extreme(a, b, c, d, h, max(peaks[P_THMAX], c), True)
        a, b, c, d = q0[iv], qd0[iv], q1[iv], qd1[iv]
        peaks[P_VMIN] = hermite_extreme(a, b, c, d, h, min(peaks[P_VMIN], c), False)
        peaks[P_VMAX] = hermite_extreme(a, b, c, d, h, max(peaks[P_VMAX], c), True)
    moment = 0.0
    for j in range(e0.size):
        p = P[j]
        a = N_PEAK_SCALARS + 2 * j
        if p.kind == STORY:
            top = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h, max(e1[j], peaks[a]), True)
            low = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h, min(e1[j], -peaks[a]), False)
            peaks[a] = max(top, -low)
            fep = min(max(p.k * (e1[j] - H[j].ep), -p.fy), p.fy)  # after the return map
            shear = p.kh * e1[j] + fep + p.c * ed1[j]
            peaks[a + 1] = max(peaks[a + 1], abs(shear))
            moment += p.arm * shear
        else:
            # gap = −d = (ep − δ0) − e, largest where e is smallest
            offset = H[j].ep - p.d0
            e_min = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h,
                                    min(e1[j], offset - peaks[a]), False)
            peaks[a] = max(peaks[a], offset - e_min)
            if modes[j] != SEPARATED:
                d1 = p.d0 + e1[j] - H[j].ep
                peaks[a + 1] = max(peaks[a + 1], min(p.k * max(d1, 0.0), p.fy))
    peaks[P_MOT] = max(peaks[P_MOT], abs(moment))


@njit(cache=True, **HOT)
def story_peaks(h, T, P, e0, ed0, edd0, e1, ed1, edd1, peaks):
    """Refine the story shears' and the overturning moment's peaks inside an event-stepper
    step, where every story keeps its tabulated law f = K e + C ė + F: the extremes of the
    cubic through f and ḟ = K ė + C ë at the step's ends (:func:`track_peaks` has the ends)."""
    m0 = md0 = m1 = md1 = 0.0
    for j in range(T.shape[1]):
        if P[j].kind != STORY:
            continue
        f0 = T[T_K, j] * e0[j] + T[T_C, j] * ed0[j] + T[T_F, j]
        f1 = T[T_K, j] * e1[j] + T[T_C, j] * ed1[j] + T[T_F, j]
        fd0 = T[T_K, j] * ed0[j] + T[T_C, j] * edd0[j]
        fd1 = T[T_K, j] * ed1[j] + T[T_C, j] * edd1[j]
        a = N_PEAK_SCALARS + 2 * j + 1
        top = hermite_extreme(f0, fd0, f1, fd1, h, peaks[a], True)
        low = hermite_extreme(f0, fd0, f1, fd1, h, -peaks[a], False)
        peaks[a] = max(top, -low)
        arm = P[j].arm
        m0 += arm * f0
        m1 += arm * f1
        md0 += arm * fd0
        md1 += arm * fd1
    top = hermite_extreme(m0, md0, m1, md1, h, peaks[P_MOT], True)
    low = hermite_extreme(m0, md0, m1, md1, h, -peaks[P_MOT], False)
    peaks[P_MOT] = max(top, -low)


@njit(cache=True, fastmath=FAST, **HOT)
def bed_peaks(T, h, x0, y0, x1, y1, peaks):
    """:func:`track_peaks` for the springs of the bed (its slots: ``peaks[k, 0]`` the gap,
    ``peaks[k, 1]`` the compression), from the state of its two DOFs at the step's ends."""
    for k in range(T.shape[1]):
        a0, a1 = T[T_A0, k], T[T_A1, k]
        e0, ed0, _ = bed_rates(a0, a1, x0, y0)
        e1, ed1, _ = bed_rates(a0, a1, x1, y1)
        offset = T[T_GAP, k]
        e_min = hermite_extreme(e0, ed0, e1, ed1, h, min(e1, offset - peaks[k, 0]), False)
        peaks[k, 0] = max(peaks[k, 0], offset - e_min)
        peaks[k, 1] = max(peaks[k, 1], min(T[T_KC, k] * max(e1 - offset, 0.0), T[T_FY, k]))


@njit(cache=True)
def current_plastic(mode, p, e, ep):
    """Plastic deformation now: while yielding, the committed value lags and e sets it."""
    if p.kind == STORY:
        if mode == YIELD_POS:
            return e - p.dy
        if mode == YIELD_NEG:
            return e + p.dy
        return ep
    if mode == YIELDING:
        return e + p.d0 - p.dy
    return ep


@njit(cache=True, **HOT)
def spring_state(j, p, mode, h, e):
    """(plastic deformation now, spring force without its dashpot, strain energy) of spring j
    (foundation: total compression k d and ½ k d² while in contact)."""
    ep = current_plastic(mode, p, e, h.ep)
    if p.kind == STORY:
        fep = p.k * (e - ep)
        return ep, p.kh * e + fep, 0.5 * p.kh * e * e + 0.5 * fep * (e - ep)
    d = p.d0 + e - ep
    if mode == SEPARATED or (p.kind == UPLIFT and d <= 0.0):
        return ep, 0.0, 0.0
    return ep, p.k * d, 0.5 * p.k * d * d


@njit(cache=True)
def kinetic_gravity(q, qd, minv, KG, weight, frame, story):
    """(kinetic, gravity) energy: ½ q̇ᵀ M q̇ and W V + ½ qᵀ K_G q, or exact kinematics'."""
    if frame[F_EXACT] > 0.0:
        return exact_energy(q, qd, frame, story, weight)
    kinetic = 0.0
    for i in range(q.size):
        kinetic += 0.5 * qd[i] * qd[i] / minv[i]
    iv = int(frame[F_IV])
    gravity = weight * q[iv] if iv >= 0 else 0.0
    for i in range(q.size):
        for m in range(KG.shape[1]):
            gravity += 0.5 * q[i] * KG[i, m] * q[m]
    return kinetic, gravity


@njit(cache=True, **HOT)
def record(k, t, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story, out_t,
           out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy):
    """Store the state at output index k."""
    n = q.size
    deformations(q, qd, P, e, ed)
    out_t[k] = t
    for i in range(n):
        out_q[k, i] = q[i]
        out_qd[k, i] = qd[i]
    strain = 0.0
    for j in range(e.size):
        ep, f, w = spring_state(j, P[j], modes[j], H[j], e[j])
        out_e[k, j] = e[j]
        out_mode[k, j] = modes[j]
        out_ep[k, j] = ep
        out_f[k, j] = f
        strain += w
    kinetic, gravity = kinetic_gravity(q, qd, minv, KG, weight, frame, story)
    out_energy[k, 0] = acc[E_INPUT]
    out_energy[k, 1] = kinetic
    out_energy[k, 2] = strain - e_ref
    out_energy[k, 3] = gravity
    out_energy[k, 4] = acc[E_VISCOUS]
    out_energy[k, 5] = acc[E_IMPACT]
    out_energy[k, 6] = acc[E_PLASTIC]


@njit(cache=True, **HOT)
def energy_balance(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story):
    """Stored + dissipated − input energy at a state: constant for an exact integration."""
    deformations(q, qd, P, e, ed)
    strain = 0.0
    for j in range(e.size):
        strain += spring_state(j, P[j], modes[j], H[j], e[j])[2]
    kinetic, gravity = kinetic_gravity(q, qd, minv, KG, weight, frame, story)
    return (kinetic + strain - e_ref + gravity + acc[E_VISCOUS] + acc[E_IMPACT] + acc[E_PLASTIC]
            - acc[E_INPUT])


@njit(cache=True, **HOT)
def check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story, peaks):
    """Update the largest residual of the energy balance and its scale (the largest |input|)."""
    total = energy_balance(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story)
    peaks[P_ERES] = max(peaks[P_ERES], abs(total - peaks[P_ETOT0]))
    peaks[P_ESCALE] = max(peaks[P_ESCALE], abs(acc[E_INPUT]))


@njit(cache=True, **HOT)
def start_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story, peaks):
    """The balance's datum at the start, and its scale: the initial stored energy."""
    total = energy_balance(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story)
    peaks[P_ETOT0] = total
    peaks[P_ESCALE] = max(peaks[P_ESCALE], abs(total))


@njit(cache=True, inline="always")
def segment_contact(x0, x1, d0, d1):
    """Length in contact of a piece of base between two springs, d linear between them."""
    if d0 > 0.0 and d1 > 0.0:
        return x1 - x0
    if d0 > 0.0 or d1 > 0.0:
        return max(d0, d1) / (abs(d0) + abs(d1)) * (x1 - x0)
    return 0.0


@njit(cache=True, **HOT)
def bed_contact_length(T, x, y, b):
    """Contact length of the bed (its springs by increasing x): where d = e − T_GAP > 0, d
    linear between springs and constant beyond the outer ones to the edges ±b."""
    total = 0.0
    x_prev, d_prev = -b, 0.0
    for k in range(T.shape[1]):
        xk = T[T_A0, k]
        dk = T[T_A0, k] * x + T[T_A1, k] * y - T[T_GAP, k]
        if k == 0:
            d_prev = dk
        total += segment_contact(x_prev, xk, d_prev, dk)
        x_prev, d_prev = xk, dk
    return total + segment_contact(x_prev, b, d_prev, d_prev)


@njit(cache=True, **HOT)
def springs_contact_length(P, H, e, first, b):
    """:func:`bed_contact_length` from the springs' records (foundation springs from
    ``first`` on, by increasing x) and their deformations e."""
    total = 0.0
    x_prev, d_prev = -b, 0.0
    for j in range(first, P.size):
        dk = P[j].d0 + e[j] - H[j].ep
        if j == first:
            d_prev = dk
        total += segment_contact(x_prev, P[j].x, d_prev, dk)
        x_prev, d_prev = P[j].x, dk
    return total + segment_contact(x_prev, b, d_prev, d_prev)


@njit(cache=True, **HOT)
def static_strain_energy(P):
    """Σ ½ k δ0² of the foundation springs at static equilibrium (the energy datum)."""
    total = 0.0
    for j in range(P.size):
        if P[j].kind != STORY:
            total += 0.5 * P[j].f0 * P[j].d0
    return total


@njit(cache=True, **HOT)
def initial_modes(P, H, modes, e, ed):
    for j in range(e.size):
        modes[j] = natural_mode(P[j], e[j], ed[j], H[j].ep, H[j].imp)


@njit(cache=True, **HOT)
def commit_all(P, modes, H, contact, e, ed):
    """End-of-step return mapping of every spring (fixed-step methods); returns plastic work."""
    work = 0.0
    for j in range(e.size):
        w, contact[j] = commit_step(P[j], e[j], ed[j], H[j], contact[j])
        work += w
        modes[j] = natural_mode(P[j], e[j], ed[j], H[j].ep, H[j].imp)
    return work


# ---------------------------------------------------------------------------------------------
# Explicit integrators
# ---------------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def copy(a, b):
    """a[:] = b, without the temporary numba may make when the two could overlap."""
    for i in range(a.size):
        a[i] = b[i]


@njit(cache=True, inline="always")
def advance(q, qd, a, acc, e, ed, edd, q1, qd1, a1, acc1, e1, ed1, edd1):
    """Make the end of an accepted step the start of the next."""
    for i in range(q.size):
        q[i] = q1[i]
        qd[i] = qd1[i]
        a[i] = a1[i]
    for c in range(N_ACC):
        acc[c] = acc1[c]
    for j in range(e.size):
        e[j] = e1[j]
        ed[j] = ed1[j]
        edd[j] = edd1[j]


@njit(cache=True, inline="always")
def error_ratio(h, q, qd, q1, qd1, k3, k4, a1, floor, qpeak, rtol):
    """The trial step's local error over its tolerance (≤ 1: accept). RK4 and its embedded
    third-order companion that replaces the last stage by the acceleration at the step's end
    (first same as last) differ by y₁ − y₁* = h/6 (F₄ − F₅): h/6 (q̇ + h k₃ − q̇₁) in q and
    h/6 (k₄ − q̈₁) in q̇. Each component is measured against ``rtol`` times the largest
    magnitude it has had in the run (or its floor, the scene's static scale)."""
    n = q.size
    worst = 0.0
    for i in range(n):
        eq = h / 6.0 * abs(qd[i] + h * k3[i] - qd1[i])
        ev = h / 6.0 * abs(k4[i] - a1[i])
        sq = rtol * max(abs(q1[i]), qpeak[i], floor[i])
        sv = rtol * max(abs(qd1[i]), qpeak[n + i], floor[n + i])
        worst = max(worst, eq / sq, ev / sv)
    return worst


@njit(cache=True, inline="always")
def note_magnitudes(q, qd, qpeak):
    """Largest |q| and |q̇| so far, per component (the error control's scale)."""
    n = q.size
    for i in range(n):
        qpeak[i] = max(qpeak[i], abs(q[i]))
        qpeak[n + i] = max(qpeak[n + i], abs(qd[i]))


@njit(cache=True, inline="always")
def output_row(step, stride):
    """Output row of the state after step ``step``: every ``stride`` steps, and the last state
    in the row after them when ``stride`` does not divide the run."""
    return (step + 1) // stride + (0 if (step + 1) % stride == 0 else 1)


@njit(cache=True, inline="always")
def stop_row(step, stride):
    """Output row for a state that ends the run inside macro step ``step``: the next row."""
    return step // stride + 1


@njit(cache=True, **HOT)
def record_between(row, t_out, t, h, q, qd, a0, q1, qd1, a1, acc, acc1, p0, p1, qs, qds, acc_s,
                   P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story, out_t, out_q,
                   out_qd, out_e, out_f, out_mode, out_ep, out_energy):
    """Store the state at time t_out inside the accepted step [t, t + h], in which every spring
    kept its mode: q and q̇ on the step's quintic interpolant (q, q̇, q̈ at both ends), the
    energy accumulators on the cubic through their values and rates (the powers p0, p1)."""
    s = (t_out - t) / h
    for i in range(q.size):
        m = quintic(h, q[i], qd[i], a0[i], q1[i], qd1[i], a1[i])
        qs[i], qds[i] = quintic_at(m, s, h)
    for c in range(N_ACC):
        acc_s[c] = hermite(s, h, acc[c], p0[c], acc1[c], p1[c])[0]
    record(row, t_out, qs, qds, acc_s, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story,
           out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)


@njit(cache=True)
def integrate_events(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, frame,
                     story, floor, max_switches, out_t, out_q, out_qd, out_e, out_f, out_mode,
                     out_ep, out_energy, peaks, counters, impacts, H):
    """RK4 with switch location and, when ``frame[F_RTOL]`` > 0, error control.
    ``counters`` (:data:`N_COUNTERS`): steps cut at a switch, springs switched, rhs calls,
    impacts logged, output rows written, trial steps rejected. ``H`` is the spring history
    (:data:`HISTORY_DTYPE`, zeros at rest); it holds the final history on return, as in every
    integrator here. ``floor`` (2n) are the error control's smallest scales of q and q̇.

    ``impacts`` (rows × 5) logs each activation of an impact damper: time of recontact, spring,
    closing velocity v₀, and time and closing velocity when the damper locked (NaN if it never
    did: the spring separated first, or the run ended).

    Within a step every spring keeps its mode (its law tabulated, :func:`law_tables`), so the
    right-hand side is smooth and RK4 keeps its order. A trial step in which a spring leaves
    its mode (:func:`first_crossing`, on the trial's quintic interpolant) is re-integrated from
    its start up to that switch, where every spring past its limit is switched. A cut that falls
    short of the switch is tried once more on the interpolant raised by what it missed
    (:func:`relocate`); if that too falls short, it ends a step without a switch, and the next
    trial finds the switch at its start. With exact kinematics the base's change of pivot
    (sin θ changing sign) is located the same way. Steps meet every multiple of ``dt`` (the
    record's samples and the outputs); between them, under error control, a trial whose local
    error (:func:`error_ratio`) exceeds the tolerance is retried shorter, and the next trial
    grows or shrinks with (tolerance/error)^¼. While impact dashpots act, steps are capped at
    their stable length. The springs off the bed keep (e, ė, ë) in arrays; the bed's follow
    from the state of its two DOFs.
    """
    ns, n = P.size, q0.size
    KG = geometric_or_nothing(KG)
    modes = np.zeros(ns, dtype=np.int64)
    e_all, ed_all = np.zeros(ns), np.zeros(ns)
    deformations(q0, qd0, P, e_all, ed_all)
    initial_modes(P, H, modes, e_all, ed_all)
    Tg, Tb = law_tables(P, modes, H)
    ng = Tg.shape[1]  # springs off the bed: 0 … ng − 1
    e0, ed0, edd0 = np.zeros(ng), np.zeros(ng), np.zeros(ng)
    e1, ed1, edd1 = np.zeros(ng), np.zeros(ng), np.zeros(ng)
    margin = np.zeros(Tb.shape[1])
    bed = peaks[N_PEAK_SCALARS + 2 * ng:].reshape((Tb.shape[1], 2))  # the bed's peak slots
    open_impact = np.full(ns, -1, dtype=np.int64)
    a0, a1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    Mw, qpeak = np.zeros((n, n)), np.zeros(2 * n)
    q, qd = q0.copy(), qd0.copy()
    acc, acc1, acc_s = np.zeros(N_ACC), np.zeros(N_ACC), np.zeros(N_ACC)
    e_ref = static_strain_energy(P)
    start_side(q, qd, frame)
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e_all, ed_all, frame, story,
           out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    counters[4] = 1
    start_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e_all, ed_all, frame, story,
                 peaks)
    return march_events(q, qd, acc, modes, H, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight,
                        frame, story, floor, max_switches, e_ref, Tg, Tb, e0, ed0, edd0, e1, ed1,
                        edd1, e_all, ed_all, margin, bed, a0, a1, k2, k3, k4, qs, qds, q1, qd1,
                        acc1, acc_s, Mw, qpeak, out_t, out_q, out_qd, out_e, out_f, out_mode,
                        out_ep, out_energy, peaks, counters, impacts, open_impact)


@njit(cache=True, **HOT)
def start_side(q, qd, frame):
    """Exact kinematics: the edge the base starts rocking about, from the sign of θ (or θ̇)."""
    if frame[F_EXACT] > 0.0:
        ith = int(frame[F_ITH])
        lean = q[ith] if q[ith] != 0.0 else qd[ith]
        frame[F_SIDE] = -1.0 if lean < 0.0 else 1.0


@njit(cache=True, **HOT)
def toppled(t, q, frame, story, peaks):
    """True if the state at time t is past the toppling angle (:func:`overturn_ratio` ≥ 1),
    with the time it got there, interpolated from the last accepted state, in P_TOVER."""
    ratio = overturn_ratio(q, frame, story)
    if ratio >= 1.0:
        r0, t0 = peaks[P_RPREV], peaks[P_TPREV]
        peaks[P_TOVER] = t0 + (1.0 - r0) / (ratio - r0) * (t - t0) if ratio > r0 else t
        return True
    peaks[P_RPREV], peaks[P_TPREV] = ratio, t
    return False


@njit(cache=True, **HOT)
def after_step(t, q, P, Tb, frame, story, peaks):
    """Contact length of the bed at an accepted state at time t, into its least; True if the
    state is past the toppling angle (:func:`toppled`)."""
    b = frame[F_B]
    if b <= 0.0:
        return False
    if Tb.shape[1] > 0:
        last = P[P.size - 1]
        peaks[P_CMIN] = min(peaks[P_CMIN], bed_contact_length(Tb, q[last.i0], q[last.i1], b))
    return toppled(t, q, frame, story, peaks)


@njit(cache=True, **HOT)
def march_events(q, qd, acc, modes, H, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight,
                 frame, story, floor, max_switches, e_ref, Tg, Tb, e0, ed0, edd0, e1, ed1, edd1,
                 e_all, ed_all, margin, bed, a0, a1, k2, k3, k4, qs, qds, q1, qd1, acc1, acc_s,
                 Mw, qpeak, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy,
                 peaks, counters, impacts, open_impact):
    """The time loop of :func:`integrate_events`, in the workspace it allocated; every helper
    is inlined and nothing is reference-counted (the loop never allocates). Under error
    control the stored states are interpolated within the steps every ``frame[F_OUTDT]``
    (:func:`record_between`), so that what is stored does not change the steps taken."""
    t = 0.0
    out_dt = frame[F_OUTDT]
    dense = out_dt > 0.0
    row = 1  # the next stored state
    ith, iv, n_story = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    exact = frame[F_EXACT] > 0.0
    rtol, hmax = frame[F_RTOL], frame[F_HMAX]
    h_adapt = frame[F_H0] if rtol > 0.0 else np.inf
    echeck = max(1, int(frame[F_ECHECK]))
    p0 = frozen_accelerations(t, q, qd, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story, Mw, a0)
    counters[2] += 1
    rates(q, qd, a0, P, e0, ed0, edd0)
    note_magnitudes(q, qd, qpeak)
    if after_step(0.0, q, P, Tb, frame, story, peaks):
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    for step in range(nsteps):
        t_end = (step + 1) * dt
        t_tol = 1e-10 * dt + 8.0 * np.finfo(np.float64).eps * t_end
        switches = 0
        while t_end - t > t_tol:
            h = min(t_end - t, impact_step_cap(P, H), h_adapt, hmax)
            t1 = t + h if t_end - (t + h) > t_tol else t_end
            frozen_rk4_step(t, h, q, qd, acc, a0, p0, minv, P, KG, L, ag, dtg, Tg, Tb, frame,
                            story, Mw, k2, k3, k4, qs, qds, q1, qd1, acc1)
            p1 = frozen_accelerations(t1, q1, qd1, minv, P, KG, L, ag, dtg, Tg, Tb, frame, story,
                                      Mw, a1)
            counters[2] += 4
            good = finite(q1, qd1) and finite(a1, a1)
            if rtol > 0.0:
                ratio = error_ratio(h, q, qd, q1, qd1, k3, k4, a1, floor, qpeak, rtol) \
                    if good else np.inf
                if ratio > 1.0:
                    counters[5] += 1
                    h_adapt = h * (max(0.1, 0.9 * ratio ** -0.25) if good else 0.1)
                    if h_adapt <= 1e-12 * max(dt, t_end):
                        counters[0] = step
                        return STEP_UNDERFLOW
                    continue
                grown = h * (min(4.0, 0.9 * ratio ** -0.25) if ratio > 0.0 else 4.0)
                h_adapt = grown if h >= h_adapt else max(h_adapt, grown)
            if not good:
                counters[0] = step
                return NONFINITE
            rates(q1, qd1, a1, P, e1, ed1, edd1)
            x0, y0 = bed_state(P, q, qd, a0)
            x1, y1 = bed_state(P, q1, qd1, a1)
            s, spring = first_crossing(h, P, Tg, Tb, x0, y0, x1, y1, e0, ed0, edd0, e1, ed1,
                                       edd1, margin)
            flip = False
            if exact:  # the base changes pivot where sin θ changes sign
                m = quintic(h, q[ith], qd[ith], a0[ith], q1[ith], qd1[ith], a1[ith])
                c = condition_polynomial(0.0, frame[F_SIDE], 0.0, m, h)
                sp = condition_crossing(c, s)
                if sp < s:
                    s, spring, flip = sp, -1, True
            if spring >= 0 or flip:  # re-integrate up to the switch
                if spring >= 0:
                    m = spring_quintic(spring, h, Tb, x0, y0, x1, y1, e0, ed0, edd0, e1, ed1,
                                       edd1)
                tau = min(max(s * h, t_tol), h)
                frozen_rk4_step(t, tau, q, qd, acc, a0, p0, minv, P, KG, L, ag, dtg, Tg, Tb,
                                frame, story, Mw, k2, k3, k4, qs, qds, q1, qd1, acc1)
                counters[2] += 3
                if spring >= 0:
                    e, ed = deformation(P[spring], q1, qd1)
                    if not past_limit(modes[spring], P[spring], e, ed, H[spring]):
                        s = relocate(spring, tau / h, m, h, P, modes, H, Tg, Tb, q1, qd1)
                        if s < 1.0:  # once more, on the interpolant raised by what it missed
                            tau = min(max(s * h, t_tol), h)
                            frozen_rk4_step(t, tau, q, qd, acc, a0, p0, minv, P, KG, L, ag, dtg,
                                            Tg, Tb, frame, story, Mw, k2, k3, k4, qs, qds, q1,
                                            qd1, acc1)
                            counters[2] += 3
                h = tau
                t1 = t + h if t_end - (t + h) > t_tol else t_end
                # q̈ at the cut, in the modes of the step: its end for the peaks and outputs
                p1 = frozen_accelerations(t1, q1, qd1, minv, P, KG, L, ag, dtg, Tg, Tb, frame,
                                          story, Mw, a1)
                counters[2] += 1
                rates(q1, qd1, a1, P, e1, ed1, edd1)
                x1, y1 = bed_state(P, q1, qd1, a1)
            track_peaks(h, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv,
                        peaks)
            story_peaks(h, Tg, P, e0, ed0, edd0, e1, ed1, edd1, peaks)
            bed_peaks(Tb, h, x0, y0, x1, y1, bed)
            if dense and row < out_t.size and row * out_dt <= t1 + t_tol:
                while row < out_t.size and row * out_dt <= t1 + t_tol:
                    record_between(row, min(row * out_dt, t1), t, h, q, qd, a0, q1, qd1, a1, acc,
                                   acc1, p0, p1, qs, qds, acc_s, P, modes, H, minv, KG, weight,
                                   e_ref, e_all, ed_all, frame, story, out_t, out_q, out_qd,
                                   out_e, out_f, out_mode, out_ep, out_energy)
                    row += 1
                counters[4] = row
            t = t1
            if spring < 0 and not flip:  # the whole step, without a switch
                advance(q, qd, a0, acc, e0, ed0, edd0, q1, qd1, a1, acc1, e1, ed1, edd1)
                p0 = p1
            else:
                copy(q, q1)
                copy(qd, qd1)
                copy(acc, acc1)
                if flip:
                    frame[F_SIDE] = -frame[F_SIDE]
                switched = apply_switches(t, P, modes, H, q, qd, Tg, Tb, impacts, open_impact,
                                          counters)
                counters[0] += 1
                counters[1] += switched
                switches += max(switched, 1)
                if switches > max_switches:
                    counters[1] = step
                    return CHATTER
                p0 = frozen_accelerations(t, q, qd, minv, P, KG, L, ag, dtg, Tg, Tb, frame,
                                          story, Mw, a0)
                counters[2] += 1
                rates(q, qd, a0, P, e0, ed0, edd0)
            note_magnitudes(q, qd, qpeak)
            if after_step(t, q, P, Tb, frame, story, peaks):
                last = row if dense else stop_row(step, stride)
                if last < out_t.size:
                    record(last, t, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e_all,
                           ed_all, frame, story, out_t, out_q, out_qd, out_e, out_f, out_mode,
                           out_ep, out_energy)
                    counters[4] = last + 1
                check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e_all, ed_all,
                             frame, story, peaks)
                return OVERTURNED
        if not dense and ((step + 1) % stride == 0 or step == nsteps - 1):
            row = output_row(step, stride)
            record(row, t_end, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e_all, ed_all,
                   frame, story, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep,
                   out_energy)
            counters[4] = row + 1
        if (step + 1) % echeck == 0 or step == nsteps - 1:
            check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e_all, ed_all, frame,
                         story, peaks)
    return OK


@njit(cache=True, **HOT)
def after_fixed_step(t, q, P, H, e, frame, story, peaks):
    """:func:`after_step` for the fixed-step integrators, whose springs keep e in an array."""
    b = frame[F_B]
    if b <= 0.0:
        return False
    first = P.size
    while first > 0 and P[first - 1].kind != STORY:
        first -= 1
    if first < P.size:
        peaks[P_CMIN] = min(peaks[P_CMIN], springs_contact_length(P, H, e, first, b))
    return toppled(t, q, frame, story, peaks)


@njit(cache=True)
def integrate_rk4(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, frame, story,
                  out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy, peaks,
                  counters, H):
    """Classical RK4 with trial spring laws and end-of-step return mapping."""
    ns, n = P.size, q0.size
    KG = geometric_or_nothing(KG)
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    k1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    Mw = np.zeros((n, n))
    q, qd = q0.copy(), qd0.copy()
    acc, acc1 = np.zeros(N_ACC), np.zeros(N_ACC)
    modes = np.zeros(ns, dtype=np.int64)
    contact = np.ones(ns, dtype=np.int64)
    deformations(q, qd, P, e0, ed0)
    initial_modes(P, H, modes, e0, ed0)
    e_ref = static_strain_energy(P)
    start_side(q, qd, frame)
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story,
           out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    counters[4] = 1
    start_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story, peaks)
    deformations(q, qd, P, e0, ed0)
    if after_fixed_step(0.0, q, P, H, e0, frame, story, peaks):
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    return march_rk4(q, qd, acc, modes, contact, H, dt, nsteps, stride, minv, P, KG, L, ag, dtg,
                     weight, frame, story, Mw, e_ref, e0, ed0, e1, ed1, k1, k2, k3, k4, qs, qds,
                     q1, qd1, acc1, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep,
                     out_energy, peaks, counters)


@njit(cache=True, **HOT)
def end_fixed_step(step, t, nsteps, stride, q, qd, acc, modes, H, minv, P, KG, weight, frame,
                   story, e_ref, e0, e1, ed1, out_t, out_q, out_qd, out_e, out_f, out_mode,
                   out_ep, out_energy, peaks, counters):
    """After a fixed step (committed): contact length, overturning, outputs and the energy
    check. Returns OVERTURNED if the run ends here, else OK."""
    if after_fixed_step(t, q, P, H, e0, frame, story, peaks):
        row = stop_row(step, stride)
        record(row, t, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story,
               out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
        counters[4] = row + 1
        check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story,
                     peaks)
        return OVERTURNED
    if (step + 1) % stride == 0 or step == nsteps - 1:
        row = output_row(step, stride)
        record(row, t, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story,
               out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
        counters[4] = row + 1
    if (step + 1) % max(1, int(frame[F_ECHECK])) == 0:
        check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story,
                     peaks)
    return OK


@njit(cache=True, **HOT)
def march_rk4(q, qd, acc, modes, contact, H, dt, nsteps, stride, minv, P, KG, L, ag, dtg,
              weight, frame, story, Mw, e_ref, e0, ed0, e1, ed1, k1, k2, k3, k4, qs, qds, q1,
              qd1, acc1, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy,
              peaks, counters):
    """The time loop of :func:`integrate_rk4`, in the workspace it allocated."""
    ith, iv, n_story = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    for step in range(nsteps):
        rk4_step(step * dt, dt, q, qd, acc, True, minv, P, KG, L, ag, dtg, modes, H, frame, story,
                 Mw, k1, k2, k3, k4, qs, qds, q1, qd1, acc1)
        counters[2] += 4
        if not finite(q1, qd1):
            counters[0] = step
            return NONFINITE
        deformations(q1, qd1, P, e1, ed1)
        track_peaks(dt, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv, peaks)
        copy(q, q1)
        copy(qd, qd1)
        copy(acc, acc1)
        copy(e0, e1)
        copy(ed0, ed1)
        acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
        if end_fixed_step(step, (step + 1) * dt, nsteps, stride, q, qd, acc, modes, H, minv, P,
                          KG, weight, frame, story, e_ref, e0, e1, ed1, out_t, out_q, out_qd,
                          out_e, out_f, out_mode, out_ep, out_energy, peaks, counters) != OK:
            return OVERTURNED
    check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story, peaks)
    return OK


@njit(cache=True)
def integrate_abm4(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, frame, story,
                   out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy, peaks,
                   counters, H):
    """Adams–Bashforth–Moulton 4 (PECE) on y = (q, q̇, energy), started by three RK4 steps.

    Predictor AB4: y* = yₙ + h/24 (55fₙ − 59fₙ₋₁ + 37fₙ₋₂ − 9fₙ₋₃).
    Corrector AM4: yₙ₊₁ = yₙ + h/24 (9f* + 19fₙ − 5fₙ₋₁ + fₙ₋₂).
    """
    ns, n = P.size, q0.size
    KG = geometric_or_nothing(KG)
    m = 2 * n + N_ACC
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    k1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    Mw = np.zeros((n, n))
    q, qd = q0.copy(), qd0.copy()
    acc, acc1 = np.zeros(N_ACC), np.zeros(N_ACC)
    F = np.zeros((4, m))  # derivative history, F[0] newest
    ystar = np.zeros(m)
    fstar = np.zeros(m)
    modes = np.zeros(ns, dtype=np.int64)
    contact = np.ones(ns, dtype=np.int64)
    deformations(q, qd, P, e0, ed0)
    initial_modes(P, H, modes, e0, ed0)
    e_ref = static_strain_energy(P)
    start_side(q, qd, frame)
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story,
           out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    counters[4] = 1
    start_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story, peaks)
    deformations(q, qd, P, e0, ed0)
    if after_fixed_step(0.0, q, P, H, e0, frame, story, peaks):
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    return march_abm4(q, qd, acc, modes, contact, H, dt, nsteps, stride, minv, P, KG, L, ag, dtg,
                      weight, frame, story, Mw, e_ref, e0, ed0, e1, ed1, k1, k2, k3, k4, qs, qds,
                      q1, qd1, acc1, F, ystar, fstar, out_t, out_q, out_qd, out_e, out_f,
                      out_mode, out_ep, out_energy, peaks, counters)


@njit(cache=True, **HOT)
def march_abm4(q, qd, acc, modes, contact, H, dt, nsteps, stride, minv, P, KG, L, ag, dtg,
               weight, frame, story, Mw, e_ref, e0, ed0, e1, ed1, k1, k2, k3, k4, qs, qds, q1,
               qd1, acc1, F, ystar, fstar, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep,
               out_energy, peaks, counters):
    """The time loop of :func:`integrate_abm4`, in the workspace it allocated."""
    n, m = q.size, F.shape[1]
    ith, iv, n_story = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    for step in range(nsteps):
        t = step * dt
        pw = accelerations(t, q, qd, True, minv, P, KG, L, ag, dtg, modes, H, frame, story, Mw,
                           k1)
        counters[2] += 1
        for r in range(3, 0, -1):
            for c in range(m):
                F[r, c] = F[r - 1, c]
        for i in range(n):
            F[0, i] = qd[i]
            F[0, n + i] = k1[i]
        for c in range(N_ACC):
            F[0, 2 * n + c] = pw[c]
        if step < 3:
            rk4_step(t, dt, q, qd, acc, True, minv, P, KG, L, ag, dtg, modes, H, frame, story,
                     Mw, k1, k2, k3, k4, qs, qds, q1, qd1, acc1)
            counters[2] += 4
        else:
            for c in range(m):
                y = q[c] if c < n else (qd[c - n] if c < 2 * n else acc[c - 2 * n])
                ystar[c] = y + dt / 24.0 * (55 * F[0, c] - 59 * F[1, c] + 37 * F[2, c]
                                            - 9 * F[3, c])
            for i in range(n):
                qs[i] = ystar[i]
                qds[i] = ystar[n + i]
            pw = accelerations(t + dt, qs, qds, True, minv, P, KG, L, ag, dtg, modes, H, frame,
                               story, Mw, k2)
            counters[2] += 1
            for i in range(n):
                fstar[i] = qds[i]
                fstar[n + i] = k2[i]
            for c in range(N_ACC):
                fstar[2 * n + c] = pw[c]
            for c in range(m):
                incr = dt / 24.0 * (9 * fstar[c] + 19 * F[0, c] - 5 * F[1, c] + F[2, c])
                if c < n:
                    q1[c] = q[c] + incr
                elif c < 2 * n:
                    qd1[c - n] = qd[c - n] + incr
                else:
                    acc1[c - 2 * n] = acc[c - 2 * n] + incr
        if not finite(q1, qd1):
            counters[0] = step
            return NONFINITE
        deformations(q1, qd1, P, e1, ed1)
        track_peaks(dt, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv, peaks)
        copy(q, q1)
        copy(qd, qd1)
        copy(acc, acc1)
        copy(e0, e1)
        copy(ed0, ed1)
        acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
        if end_fixed_step(step, (step + 1) * dt, nsteps, stride, q, qd, acc, modes, H, minv, P,
                          KG, weight, frame, story, e_ref, e0, e1, ed1, out_t, out_q, out_qd,
                          out_e, out_f, out_mode, out_ep, out_energy, peaks, counters) != OK:
            return OVERTURNED
    check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e1, ed1, frame, story, peaks)
    return OK


# ---------------------------------------------------------------------------------------------
# Implicit integrator
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def internal_force(q, qd, P, KG, H, e, ed, fint, kt, ct, modes, fd, fimp):
    """Internal force A s + K_G q, spring tangents and trial modes (natural laws).

    Also fills ``fd`` (dashpot force of each spring) and ``fimp`` (the impact dashpot's share).
    Returns (viscous power, impact power).
    """
    n = q.size
    deformations(q, qd, P, e, ed)
    for i in range(n):
        fint[i] = 0.0
        for k in range(n):
            fint[i] += KG[i, k] * q[k]
    pv = 0.0
    pi = 0.0
    for j in range(e.size):
        p = P[j]
        h = H[j]
        mode = natural_mode(p, e[j], ed[j], h.ep, h.imp)
        modes[j] = mode
        f, v, im, _, fd[j], fimp[j] = force_in_mode(mode, p, e[j], ed[j], h.ep, h.imp)
        pv += v
        pi += im
        kt[j], ct[j] = tangent(mode, p, h.imp)
        fint[p.i0] += p.a0 * f
        fint[p.i1] += p.a1 * f
        if p.nnz == 3:
            fint[p.i2] += p.a2 * f
    return pv, pi


@njit(cache=True)
def newmark_residual(t, h, q, qd, qdd, fint0, alpha, beta, gamma, minv, P, KG, L, ag,
                     dtg, H, modes, e, ed, kt, ct, fd, fimp, q1, qd1, qdd1, fint1, R):
    """Residual of the HHT-α step at trial q₁ (fills q̇₁, q̈₁, f₁); returns (|R|∞, force scale)."""
    n = q.size
    a0 = ground_acceleration(t, ag, dtg)
    a1 = ground_acceleration(t + h, ag, dtg)
    for i in range(n):
        qdd1[i] = (q1[i] - q[i] - h * qd[i]) / (beta * h * h) - (0.5 / beta - 1.0) * qdd[i]
        qd1[i] = qd[i] + h * ((1.0 - gamma) * qdd[i] + gamma * qdd1[i])
    internal_force(q1, qd1, P, KG, H, e, ed, fint1, kt, ct, modes, fd, fimp)
    rnorm = 0.0
    scale = 0.0
    for i in range(n):
        inertia = qdd1[i] / minv[i]
        R[i] = (inertia + (1 + alpha) * fint1[i] - alpha * fint0[i]
                - (1 + alpha) * L[i] * a1 + alpha * L[i] * a0)
        rnorm = max(rnorm, abs(R[i]))
        scale = max(scale, abs(inertia), abs(fint1[i]), abs(L[i] * a1))
    return rnorm, scale


@njit(cache=True)
def newmark_jacobian(h, alpha, beta, gamma, minv, P, KG, kt, ct, J):
    """J = M/(βh²) + (1+α)(A diag(k_t + γ c_t/(βh)) Aᵀ + K_G)."""
    n = minv.size
    for i in range(n):
        for k in range(n):
            J[i, k] = (1 + alpha) * KG[i, k]
        J[i, i] += 1.0 / (minv[i] * beta * h * h)
    for j in range(P.size):
        stiff = (1 + alpha) * (kt[j] + gamma / (beta * h) * ct[j])
        if stiff == 0.0:
            continue
        p = P[j]
        idx = (p.i0, p.i1, p.i2)
        val = (p.a0, p.a1, p.a2)
        for a in range(p.nnz):
            for b in range(p.nnz):
                J[idx[a], idx[b]] += val[a] * val[b] * stiff


@njit(cache=True)
def newmark_substep(t, h, q, qd, qdd, fint0, alpha, beta, gamma, minv, P, KG, L, ag, dtg,
                    H, modes, e, ed, kt, ct, fd, fimp, tol, fscale, max_iter, q1, qd1, qdd1,
                    fint1):
    """One HHT-α step (α = 0: Newmark average acceleration) by Newton. Returns iterations or −1.

    Residual: M q̈₁ + (1+α) f(q₁, q̇₁) − α f(q₀, q̇₀) − (1+α) L a_g(t₁) + α L a_g(t₀) = 0,
    converged when its largest entry is below ``tol`` times the larger of ``fscale`` (the
    weights, m g) and the forces in play, or when the Newton update is at round-off. A
    backtracking line search on |R| stops the active set of the springs from cycling.
    """
    n = q.size
    R = np.zeros(n)
    J = np.zeros((n, n))
    trial = np.zeros(n)
    qscale = 1e-300
    for i in range(n):
        q1[i] = q[i] + h * qd[i] + h * h * (0.5 - beta) * qdd[i]
        qscale = max(qscale, abs(q[i]), abs(q1[i]))
    rnorm, scale = newmark_residual(t, h, q, qd, qdd, fint0, alpha, beta, gamma, minv, P,
                                    KG, L, ag, dtg, H, modes, e, ed, kt, ct, fd, fimp, q1, qd1,
                                    qdd1, fint1, R)
    for it in range(1, max_iter + 1):
        newmark_jacobian(h, alpha, beta, gamma, minv, P, KG, kt, ct, J)
        dq = np.linalg.solve(J, R)
        step = 1.0
        trial[:] = q1
        for _ in range(8):
            for i in range(n):
                q1[i] = trial[i] - step * dq[i]
            new_norm, scale = newmark_residual(t, h, q, qd, qdd, fint0, alpha, beta, gamma, minv,
                                               P, KG, L, ag, dtg, H, modes, e, ed, kt, ct,
                                               fd, fimp, q1, qd1, qdd1, fint1, R)
            if new_norm <= rnorm or new_norm <= tol * max(scale, fscale):
                break
            step *= 0.5
        rnorm = new_norm
        update = 0.0
        for i in range(n):
            update = max(update, abs(step * dq[i]))
        if rnorm <= tol * max(scale, fscale) or update <= 1e-13 * qscale:
            return it
    return -1


@njit(cache=True)
def integrate_newmark(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, frame,
                      story, alpha, tol, fscale, max_iter, max_halvings, out_t, out_q,
                      out_qd, out_e, out_f, out_mode, out_ep, out_energy, peaks, counters, H):
    """HHT-α (α in [−1/3, 0]; α = 0 is Newmark average acceleration), Newton, step halving.

    β = (1 − α)²/4, γ = 1/2 − α. A step whose Newton iteration fails is split in halves, up to
    ``max_halvings`` times. ``counters`` = [step of failure, halvings, Newton iterations].
    Energy follows the scheme's own identity: the work of each force is the trapezoid
    ½(f₀ + f₁)·Δe over the step, so the balance of Newmark closes to the Newton tolerance away
    from switches; HHT's own numerical dissipation is what its balance leaves open.
    """
    ns, n = P.size, q0.size
    ith, iv, n_story = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    beta = (1.0 - alpha) ** 2 / 4.0
    gamma = 0.5 - alpha
    e, ed = np.zeros(ns), np.zeros(ns)
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    kt, ct = np.zeros(ns), np.zeros(ns)
    fd0, fimp0, fd1, fimp1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    q, qd = q0.copy(), qd0.copy()
    q1, qd1, qdd, qdd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    fint0, fint1 = np.zeros(n), np.zeros(n)
    acc = np.zeros(N_ACC)
    modes = np.zeros(ns, dtype=np.int64)
    contact = np.ones(ns, dtype=np.int64)
    internal_force(q, qd, P, KG, H, e0, ed0, fint0, kt, ct, modes, fd0, fimp0)
    a0 = ground_acceleration(0.0, ag, dtg)
    for i in range(n):
        qdd[i] = (L[i] * a0 - fint0[i]) * minv[i]
    e_ref = static_strain_energy(P)
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story,
           out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    counters[4] = 1
    start_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story, peaks)
    if after_fixed_step(0.0, q, P, H, e0, frame, story, peaks):
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    for step in range(nsteps):
        t = step * dt
        t_end = (step + 1) * dt
        level = 0
        t_tol = 1e-9 * dt + 8.0 * np.finfo(np.float64).eps * t_end
        while t_end - t > t_tol:
            h = min(dt / 2.0**level, t_end - t)
            if t_end - (t + h) <= t_tol:
                h = t_end - t
            its = newmark_substep(t, h, q, qd, qdd, fint0, alpha, beta, gamma, minv, P,
                                  KG, L, ag, dtg, H, modes, e, ed, kt, ct, fd1, fimp1, tol,
                                  fscale, max_iter, q1, qd1, qdd1, fint1)
            if its < 0:
                level += 1
                counters[1] += 1
                if level > max_halvings:
                    counters[0] = step
                    return NO_CONVERGENCE
                continue
            counters[2] += its
            deformations(q1, qd1, P, e1, ed1)
            track_peaks(h, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv,
                        peaks)
            ga0 = ground_acceleration(t, ag, dtg)
            ga1 = ground_acceleration(t + h, ag, dtg)
            for i in range(n):
                acc[E_INPUT] += 0.5 * (ga0 + ga1) * L[i] * (q1[i] - q[i])
            for j in range(ns):
                work = 0.5 * (fd0[j] + fd1[j]) * (e1[j] - e0[j])
                share = 0.5 * (fimp0[j] + fimp1[j])
                acc[E_VISCOUS] += work * (1.0 - share)
                acc[E_IMPACT] += work * share
            q[:] = q1
            qd[:] = qd1
            qdd[:] = qdd1
            e0[:] = e1
            ed0[:] = ed1
            # the next step starts from the forces this step converged with (pre-commit), as the
            # acceleration it carries does; the commit changes history, not these forces
            fint0[:] = fint1
            fd0[:] = fd1
            fimp0[:] = fimp1
            acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
            t = t + h if t_end - (t + h) > t_tol else t_end
        if not finite(q, qd):
            counters[0] = step
            return NONFINITE
        if end_fixed_step(step, t_end, nsteps, stride, q, qd, acc, modes, H, minv, P, KG, weight,
                          frame, story, e_ref, e0, e, ed, out_t, out_q, out_qd, out_e, out_f,
                          out_mode, out_ep, out_energy, peaks, counters) != OK:
            return OVERTURNED
    check_energy(q, qd, acc, P, modes, H, minv, KG, weight, e_ref, e, ed, frame, story, peaks)
    return OK
