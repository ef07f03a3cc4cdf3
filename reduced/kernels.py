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
# peaks: six scalars, then two per spring
P_UMIN, P_UMAX, P_THMIN, P_THMAX, P_VMIN, P_VMAX = range(6)
N_PEAK_SCALARS = 6

OK, CHATTER, NONFINITE, NO_CONVERGENCE = 0, 1, 2, 3
SWITCH_TOL = 1e-12
OVERSHOOT_TOL = 1e-6
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


@njit(cache=True)
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


# The hot loops below gather e = aᵀq and scatter −a f inline: a helper that takes arrays is
# reference-counted at every call (about 20 ns, ten times the arithmetic), one on records and
# scalars is not.


@njit(cache=True)
def deformations(q, qd, P, e, ed):
    """e = Aᵀq and ė = Aᵀq̇ (eq. 3)."""
    for j in range(P.size):
        p = P[j]
        e[j] = p.a0 * q[p.i0] + p.a1 * q[p.i1]
        ed[j] = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
        if p.nnz == 3:
            e[j] += p.a2 * q[p.i2]
            ed[j] += p.a2 * qd[p.i2]


@njit(cache=True)
def accelerations(t, q, qd, natural, minv, P, KG, L, ag, dtg, modes, H, qdd):
    """q̈ from the equation of motion; returns the powers (input, viscous, impact, plastic).

    ``natural``: each spring's mode is decided by its trial state (fixed-step methods, whose
    plastic work is counted at the return map instead); otherwise modes are frozen.
    """
    n = q.size
    a = ground_acceleration(t, ag, dtg)
    pin = 0.0
    for i in range(n):
        qdd[i] = L[i] * a
        pin += L[i] * a * qd[i]
        for k in range(n):
            qdd[i] -= KG[i, k] * q[k]
    pv = 0.0
    pi = 0.0
    pp = 0.0
    for j in range(P.size):
        p = P[j]
        h = H[j]
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
        qdd[p.i0] -= p.a0 * f
        qdd[p.i1] -= p.a1 * f
        if p.nnz == 3:
            qdd[p.i2] -= p.a2 * f
    for i in range(n):
        qdd[i] *= minv[i]
    return pin, pv, pi, 0.0 if natural else pp


@njit(cache=True)
def rk4_step(t, h, q, qd, acc, natural, minv, P, KG, L, ag, dtg, modes, H, k1, k2, k3, k4, qs,
             qds, q1, qd1, acc1):
    """One classical RK4 step of size h in Nyström form (for q̈ = f(t, q, q̇)).

    The energy accumulators ``acc`` ride along as extra RK4 components.
    """
    n = q.size
    p1 = accelerations(t, q, qd, natural, minv, P, KG, L, ag, dtg, modes, H, k1)
    for i in range(n):
        qs[i] = q[i] + 0.5 * h * qd[i]
        qds[i] = qd[i] + 0.5 * h * k1[i]
    p2 = accelerations(t + 0.5 * h, qs, qds, natural, minv, P, KG, L, ag, dtg, modes,
                       H, k2)
    for i in range(n):
        qs[i] = q[i] + 0.5 * h * qd[i] + 0.25 * h * h * k1[i]
        qds[i] = qd[i] + 0.5 * h * k2[i]
    p3 = accelerations(t + 0.5 * h, qs, qds, natural, minv, P, KG, L, ag, dtg, modes,
                       H, k3)
    for i in range(n):
        qs[i] = q[i] + h * qd[i] + 0.5 * h * h * k2[i]
        qds[i] = qd[i] + h * k3[i]
    p4 = accelerations(t + h, qs, qds, natural, minv, P, KG, L, ag, dtg, modes, H, k4)
    for i in range(n):
        q1[i] = q[i] + h * qd[i] + h * h / 6.0 * (k1[i] + k2[i] + k3[i])
        qd1[i] = qd[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    for c in range(N_ACC):
        acc1[c] = acc[c] + h / 6.0 * (p1[c] + 2.0 * p2[c] + 2.0 * p3[c] + p4[c])


# ---------------------------------------------------------------------------------------------
# Switch detection and location
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def min_validity(P, modes, H, e, ed):
    """Smallest validity over all springs at deformations (e, ė)."""
    g = np.inf
    for j in range(e.size):
        v = validity(modes[j], P[j], e[j], ed[j], H[j])
        if v < g:
            g = v
    return g


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
    """Fractions s in (0, 1) where the Hermite interpolant is stationary (2.0 if none)."""
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


@njit(cache=True)
def validity_between(s, h, mode, p, hist, e0, ed0, e1, ed1):
    """Validity of a spring at fraction s of the step, on the Hermite interpolant of its e."""
    e, ed = hermite(s, h, e0, ed0, e1, ed1)
    return validity(mode, p, e, ed, hist)


@njit(cache=True)
def dip_bound(p, h, e0, ed0, e1, ed1, imp):
    """Most any validity condition of a spring can fall below the straight line between its
    end values on the step's interpolant (validity units).

    On the cubic Hermite e(s), e deviates from its chord by at most (4/27)·h·(|ė₀ − m| +
    |ė₁ − m|) and ė from its chord by at most 1.5·|m − (ė₀ + ė₁)/2|, m = (e₁ − e₀)/h; each
    condition is a combination of e and ė with the coefficients below.
    """
    m = (e1 - e0) / h
    dev_e = 4.0 / 27.0 * h * (abs(ed0 - m) + abs(ed1 - m))
    dev_ed = 1.5 * abs(m - 0.5 * (ed0 + ed1))
    if p.kind == STORY:
        return p.k * p.gs * dev_e + dev_ed
    return max(p.gd, p.k * p.gs) * dev_e + max((p.c + p.cimp * imp) * p.gs, 1.0) * dev_ed


@njit(cache=True)
def first_crossing(h, P, modes, H, e0, ed0, e1, ed1, g0):
    """Earliest fraction s of the step at which a spring leaves its mode, on the interpolant.

    Every condition is linear in (e, ė), and e is a cubic on the step. A spring whose smaller
    end validity exceeds :func:`dip_bound` cannot switch inside the step. Any other is checked
    where a dip below zero and back (a brief touch-down or yield, which a check at the step end
    would step over) can hide: mid-step, at the stationary points of e and of ė, and at the end.
    The earliest crossing is refined on the interpolant to a point just past it (by half the
    overshoot tolerance). ``g0`` holds each spring's validity at the step start and receives it
    at the step end. Returns (estimate, a fraction known to be past it, spring), or (2, 2, −1)
    when every spring stays in its mode.
    """
    best, beyond, spring = 2.0, 2.0, -1
    for j in range(e0.size):
        g_end = validity(modes[j], P[j], e1[j], ed1[j], H[j])
        g_start = g0[j]
        g0[j] = g_end
        if min(g_start, g_end) > dip_bound(P[j], h, e0[j], ed0[j], e1[j], ed1[j], H[j].imp):
            continue
        s_neg, g_neg = (1.0, g_end) if g_end < -SWITCH_TOL else (2.0, 0.0)
        r1, r2 = hermite_stationary(h, e0[j], ed0[j], e1[j], ed1[j])
        # ė is quadratic in s; it is stationary where the cubic's second derivative vanishes
        a = -6.0 * (e1[j] - e0[j]) + 3.0 * (ed0[j] + ed1[j]) * h
        b = 6.0 * (e1[j] - e0[j]) - 4.0 * ed0[j] * h - 2.0 * ed1[j] * h
        r3 = -b / (3.0 * a) if abs(a) > 1e-300 else 2.0
        for s in (0.5, r1, r2, r3):
            if 0.0 < s < min(s_neg, best):
                g = validity_between(s, h, modes[j], P[j], H[j], e0[j], ed0[j], e1[j], ed1[j])
                if g < -SWITCH_TOL:
                    s_neg, g_neg = s, g
        if s_neg >= best:
            continue
        lo = 0.0  # the latest checked point before s_neg that is still valid
        for s in (0.5, r1, r2, r3):
            if lo < s < s_neg:
                lo = s
        best = interpolant_root(lo, s_neg, max(-0.5 * OVERSHOOT_TOL, 0.5 * g_neg), 0.0, h,
                                modes[j], P[j], H[j], e0[j], ed0[j], e1[j], ed1[j])
        beyond, spring = s_neg, j
    return best, beyond, spring


@njit(cache=True)
def interpolant_root(lo, hi, target, shift, h, mode, p, hist, e0, ed0, e1, ed1):
    """Fraction s in (lo, hi] where a spring's interpolated validity, plus ``shift``, drops
    below ``target``: Illinois on the interpolant to 1e-9 of the step, ending on the far side
    (``hi`` if it does not drop within the bracket)."""
    f_lo = validity_between(lo, h, mode, p, hist, e0, ed0, e1, ed1) + shift - target
    f_hi = validity_between(hi, h, mode, p, hist, e0, ed0, e1, ed1) + shift - target
    if f_hi >= 0.0 or f_lo < 0.0:
        return hi
    side = 0
    for _ in range(60):
        if hi - lo <= 1e-9:
            break
        s = hi - f_hi * (hi - lo) / (f_hi - f_lo)
        s = min(max(s, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
        f = validity_between(s, h, mode, p, hist, e0, ed0, e1, ed1) + shift - target
        if f < 0.0:
            hi, f_hi = s, f
            if side == -1:
                f_lo *= 0.5
            side = -1
        else:
            lo, f_lo = s, f
            if side == 1:
                f_hi *= 0.5
            side = 1
        if abs(f) < 0.25 * OVERSHOOT_TOL and f < 0.0:
            break
    return hi


@njit(cache=True)
def locate_switch(t, h, s_est, s_past, spring, q, qd, acc, minv, P, KG, L, ag, dtg,
                  modes, H, e0, ed0, e1, ed1, e, ed, k1, k2, k3, k4, qs, qds, q1, qd1, acc1,
                  t_tol, counters):
    """Shortest step that crosses a switch, re-integrated by RK4 from the step start.

    Root-finds on the validity of the spring predicted to switch first. Each try is
    re-integrated; the next one is taken on the step's interpolant (``e0, ed0, e1, ed1``)
    shifted by the error seen at the try — a Newton step with the interpolant's slope — until
    the crossing is overshot by at most :data:`OVERSHOOT_TOL` (validity units: δ0, F0) or the
    bracket is shorter than ``t_tol``. If another spring turns out to have crossed first, it is
    located in turn. Leaves the state at the returned step length in (q1, q̇1, acc1) and returns
    it, or −1 (with the full step in q1) when no spring leaves its mode after all.
    """
    target = -0.5 * OVERSHOOT_TOL
    j = spring
    lo, hi = 0.0, (s_past * h if s_past <= 1.0 else h)
    known_hi = False
    tau = min(max(s_est * h, t_tol), h)
    for _ in range(60):
        rk4_step(t, tau, q, qd, acc, False, minv, P, KG, L, ag, dtg, modes, H, k1,
                 k2, k3, k4, qs, qds, q1, qd1, acc1)
        counters[1] += 1
        counters[2] += 4
        deformations(q1, qd1, P, e, ed)
        g = validity(modes[j], P[j], e[j], ed[j], H[j])
        g_all = min_validity(P, modes, H, e, ed)
        if g_all < -OVERSHOOT_TOL and g >= -OVERSHOOT_TOL:
            for k in range(e.size):  # another spring crossed first: locate it instead
                if validity(modes[k], P[k], e[k], ed[k], H[k]) == g_all:
                    j = k
                    break
            g = g_all
        if -OVERSHOOT_TOL <= g < -SWITCH_TOL:
            return tau
        if g < -SWITCH_TOL:
            hi, known_hi = tau, True
        else:
            lo = tau
        if hi - lo <= t_tol:
            if known_hi:
                break
            return -1.0
        shift = g - validity_between(tau / h, h, modes[j], P[j], H[j], e0[j], ed0[j], e1[j], ed1[j])
        s_new = interpolant_root(lo / h, hi / h, target, shift, h, modes[j], P[j], H[j], e0[j],
                                 ed0[j], e1[j], ed1[j])
        tau = s_new * h
        if not lo < tau < hi or (tau == hi and known_hi):
            tau = 0.5 * (lo + hi)  # the corrected interpolant gives nothing better: bisect
    rk4_step(t, hi, q, qd, acc, False, minv, P, KG, L, ag, dtg, modes, H, k1, k2,
             k3, k4, qs, qds, q1, qd1, acc1)
    counters[2] += 4
    return hi


@njit(cache=True)
def apply_switches(P, modes, H, e, ed):
    """Switch every spring whose mode was crossed, at deformations (e, ė); returns how many."""
    count = 0
    for j in range(e.size):
        for _ in range(4):
            if validity(modes[j], P[j], e[j], ed[j], H[j]) >= -SWITCH_TOL:
                break
            modes[j] = switch_mode(modes[j], P[j], e[j], ed[j], H[j])
            count += 1
    return count


@njit(cache=True)
def log_impacts(t, H, was_imp, ed, impacts, open_impact, counters):
    """Record impact dampers that switched on (recontact) or locked at time t."""
    for j in range(H.size):
        if was_imp[j] == H[j].imp:
            continue
        if H[j].imp > 0.0:
            k = counters[3]
            if k < impacts.shape[0]:
                impacts[k, 0] = t
                impacts[k, 1] = j
                impacts[k, 2] = ed[j]
                impacts[k, 3] = np.nan
                impacts[k, 4] = np.nan
                open_impact[j] = k
            counters[3] += 1
        elif open_impact[j] >= 0:
            impacts[open_impact[j], 3] = t
            impacts[open_impact[j], 4] = ed[j]
            open_impact[j] = -1


@njit(cache=True)
def impact_step_cap(P, H):
    """Largest step while impact dashpots act: the smallest ``imph`` of the active ones."""
    cap = np.inf
    for j in range(H.size):
        if H[j].imp > 0.0 and P[j].imph < cap:
            cap = P[j].imph
    return cap


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


@njit(cache=True)
def track_peaks(h, q0, qd0, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv, peaks):
    """Update peaks over a step [t, t+h], refining interior extrema by Hermite interpolation.

    Scalars: top deformation u (sum of story drifts), θ, V. Per spring j: slot A = max opening
    (foundation: gap −d; story: |drift|), slot B = max |force| (foundation: spring compression).
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
    for j in range(e0.size):
        p = P[j]
        a = N_PEAK_SCALARS + 2 * j
        if p.kind == STORY:
            top = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h, max(e1[j], peaks[a]), True)
            low = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h, min(e1[j], -peaks[a]), False)
            peaks[a] = max(top, -low)
            if modes[j] == ELASTIC:
                fep = p.k * (e1[j] - H[j].ep)
            else:
                fep = p.fy if modes[j] == YIELD_POS else -p.fy
            peaks[a + 1] = max(peaks[a + 1], abs(p.kh * e1[j] + fep))
        else:
            # gap = −d = (ep − δ0) − e, largest where e is smallest
            offset = H[j].ep - p.d0
            e_min = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h,
                                    min(e1[j], offset - peaks[a]), False)
            peaks[a] = max(peaks[a], offset - e_min)
            if modes[j] != SEPARATED:
                d1 = p.d0 + e1[j] - H[j].ep
                peaks[a + 1] = max(peaks[a + 1], min(p.k * max(d1, 0.0), p.fy))


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


@njit(cache=True)
def record(k, t, q, qd, acc, P, modes, H, minv, KG, weight, iv, e_ref, e, ed, out_t,
           out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy):
    """Store the state at output index k."""
    n = q.size
    deformations(q, qd, P, e, ed)
    out_t[k] = t
    kinetic = 0.0
    for i in range(n):
        out_q[k, i] = q[i]
        out_qd[k, i] = qd[i]
        kinetic += 0.5 * qd[i] * qd[i] / minv[i]
    strain = 0.0
    for j in range(e.size):
        p = P[j]
        ep = current_plastic(modes[j], p, e[j], H[j].ep)
        out_e[k, j] = e[j]
        out_mode[k, j] = modes[j]
        out_ep[k, j] = ep
        if p.kind == STORY:
            fep = p.k * (e[j] - ep)
            out_f[k, j] = p.kh * e[j] + fep
            strain += 0.5 * p.kh * e[j] * e[j] + 0.5 * fep * (e[j] - ep)
        else:
            d = p.d0 + e[j] - ep
            if modes[j] == SEPARATED or (p.kind == UPLIFT and d <= 0.0):
                out_f[k, j] = 0.0
            else:
                out_f[k, j] = p.k * d
                strain += 0.5 * p.k * d * d
    gravity = weight * q[iv] if iv >= 0 else 0.0
    for i in range(n):
        for m in range(n):
            gravity += 0.5 * q[i] * KG[i, m] * q[m]
    out_energy[k, 0] = acc[E_INPUT]
    out_energy[k, 1] = kinetic
    out_energy[k, 2] = strain - e_ref
    out_energy[k, 3] = gravity
    out_energy[k, 4] = acc[E_VISCOUS]
    out_energy[k, 5] = acc[E_IMPACT]
    out_energy[k, 6] = acc[E_PLASTIC]


@njit(cache=True)
def static_strain_energy(P):
    """Σ ½ k δ0² of the foundation springs at static equilibrium (the energy datum)."""
    total = 0.0
    for j in range(P.size):
        if P[j].kind != STORY:
            total += 0.5 * P[j].f0 * P[j].d0
    return total


@njit(cache=True)
def initial_modes(P, H, modes, e, ed):
    for j in range(e.size):
        modes[j] = natural_mode(P[j], e[j], ed[j], H[j].ep, H[j].imp)


@njit(cache=True)
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


@njit(cache=True)
def integrate_events(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, ith,
                     iv, n_story, max_switches, out_t, out_q, out_qd, out_e, out_f, out_mode,
                     out_ep, out_energy, peaks, counters, impacts, H):
    """RK4 with switch location. ``counters`` = [switches, trial steps spent locating, rhs calls,
    impacts logged]. ``H`` is the spring history (:data:`HISTORY_DTYPE`, zeros at rest); it holds
    the final history on return, as in every integrator here.

    ``impacts`` (rows × 5) logs each activation of an impact damper: time of recontact, spring,
    closing velocity v₀, and time and closing velocity when the damper locked (NaN if it never
    did: the spring separated first, or the run ended).

    Within a step every spring keeps its mode, so the right-hand side is smooth and RK4 keeps
    its order. A trial step that leaves a mode anywhere inside (:func:`first_crossing`) is cut
    at the switch (:func:`locate_switch`); the spring is switched there and the step goes on.
    While impact dashpots act, steps are capped at their stable length.
    """
    ns, n = P.size, q0.size
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    es, eds = np.zeros(ns), np.zeros(ns)
    g_start, gv = np.zeros(ns), np.zeros(ns)  # validity at the step start; scratch
    was_imp = np.zeros(ns)
    open_impact = np.full(ns, -1, dtype=np.int64)
    k1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    q, qd = q0.copy(), qd0.copy()
    acc, acc1 = np.zeros(N_ACC), np.zeros(N_ACC)
    modes = np.zeros(ns, dtype=np.int64)
    deformations(q, qd, P, e0, ed0)
    initial_modes(P, H, modes, e0, ed0)
    for j in range(ns):
        g_start[j] = validity(modes[j], P[j], e0[j], ed0[j], H[j])
    e_ref = static_strain_energy(P)
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, iv, e_ref, e1, ed1, out_t,
           out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    for step in range(nsteps):
        t = step * dt
        t_end = (step + 1) * dt
        t_tol = 1e-10 * dt + 8.0 * np.finfo(np.float64).eps * t_end
        switches = 0
        while t_end - t > t_tol:
            h = min(t_end - t, impact_step_cap(P, H))
            rk4_step(t, h, q, qd, acc, False, minv, P, KG, L, ag, dtg, modes, H,
                     k1, k2, k3, k4, qs, qds, q1, qd1, acc1)
            counters[2] += 4
            deformations(q1, qd1, P, e1, ed1)
            gv[:] = g_start
            s_est, s_past, spring = first_crossing(h, P, modes, H, e0, ed0, e1, ed1, gv)
            crossed = False
            if spring >= 0:
                h_cross = locate_switch(t, h, s_est, s_past, spring, q, qd, acc, minv, P,
                                        KG, L, ag, dtg, modes, H, e0, ed0, e1, ed1, es, eds, k1,
                                        k2, k3, k4, qs, qds, q1, qd1, acc1, t_tol, counters)
                if h_cross > 0.0:
                    h = h_cross
                    crossed = True
                deformations(q1, qd1, P, e1, ed1)
            if not (np.all(np.isfinite(q1)) and np.all(np.isfinite(qd1))):
                counters[0] = step
                return NONFINITE
            track_peaks(h, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv,
                        peaks)
            q[:] = q1
            qd[:] = qd1
            acc[:] = acc1
            e0[:] = e1
            ed0[:] = ed1
            t = t + h if t_end - (t + h) > t_tol else t_end
            if crossed:
                for j in range(ns):
                    was_imp[j] = H[j].imp
                switches += apply_switches(P, modes, H, e0, ed0)
                log_impacts(t, H, was_imp, ed0, impacts, open_impact, counters)
                counters[0] += 1
                if switches > max_switches:
                    counters[1] = step
                    return CHATTER
                for j in range(ns):
                    g_start[j] = validity(modes[j], P[j], e0[j], ed0[j], H[j])
            else:
                g_start[:] = gv
        if (step + 1) % stride == 0:
            record((step + 1) // stride, t_end, q, qd, acc, P, modes, H, minv, KG,
                   weight, iv, e_ref, e1, ed1, out_t, out_q, out_qd, out_e, out_f, out_mode,
                   out_ep, out_energy)
    return OK


@njit(cache=True)
def integrate_rk4(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, ith, iv,
                  n_story, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy,
                  peaks, counters, H):
    """Classical RK4 with trial spring laws and end-of-step return mapping."""
    ns, n = P.size, q0.size
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    k1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    q, qd = q0.copy(), qd0.copy()
    acc, acc1 = np.zeros(N_ACC), np.zeros(N_ACC)
    modes = np.zeros(ns, dtype=np.int64)
    contact = np.ones(ns, dtype=np.int64)
    deformations(q, qd, P, e0, ed0)
    initial_modes(P, H, modes, e0, ed0)
    e_ref = static_strain_energy(P)
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, iv, e_ref, e1, ed1, out_t,
           out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    for step in range(nsteps):
        rk4_step(step * dt, dt, q, qd, acc, True, minv, P, KG, L, ag, dtg, modes, H, k1, k2, k3,
                 k4, qs, qds, q1, qd1, acc1)
        counters[2] += 4
        if not (np.all(np.isfinite(q1)) and np.all(np.isfinite(qd1))):
            counters[0] = step
            return NONFINITE
        deformations(q1, qd1, P, e1, ed1)
        track_peaks(dt, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv, peaks)
        q[:] = q1
        qd[:] = qd1
        acc[:] = acc1
        e0[:] = e1
        ed0[:] = ed1
        acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
        if (step + 1) % stride == 0:
            record((step + 1) // stride, (step + 1) * dt, q, qd, acc, P, modes, H, minv,
                   KG, weight, iv, e_ref, e1, ed1, out_t, out_q, out_qd, out_e, out_f, out_mode,
                   out_ep, out_energy)
    return OK


@njit(cache=True)
def integrate_abm4(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, ith, iv,
                   n_story, out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy,
                   peaks, counters, H):
    """Adams–Bashforth–Moulton 4 (PECE) on y = (q, q̇, energy), started by three RK4 steps.

    Predictor AB4: y* = yₙ + h/24 (55fₙ − 59fₙ₋₁ + 37fₙ₋₂ − 9fₙ₋₃).
    Corrector AM4: yₙ₊₁ = yₙ + h/24 (9f* + 19fₙ − 5fₙ₋₁ + fₙ₋₂).
    """
    ns, n = P.size, q0.size
    m = 2 * n + N_ACC
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    k1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
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
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, iv, e_ref, e1, ed1, out_t,
           out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
    for step in range(nsteps):
        t = step * dt
        pw = accelerations(t, q, qd, True, minv, P, KG, L, ag, dtg, modes, H, k1)
        counters[2] += 1
        for r in range(3, 0, -1):
            F[r, :] = F[r - 1, :]
        for i in range(n):
            F[0, i] = qd[i]
            F[0, n + i] = k1[i]
        for c in range(N_ACC):
            F[0, 2 * n + c] = pw[c]
        if step < 3:
            rk4_step(t, dt, q, qd, acc, True, minv, P, KG, L, ag, dtg, modes, H, k1, k2, k3, k4,
                     qs, qds, q1, qd1, acc1)
            counters[2] += 4
        else:
            for c in range(m):
                y = q[c] if c < n else (qd[c - n] if c < 2 * n else acc[c - 2 * n])
                ystar[c] = y + dt / 24.0 * (55 * F[0, c] - 59 * F[1, c] + 37 * F[2, c]
                                            - 9 * F[3, c])
            for i in range(n):
                qs[i] = ystar[i]
                qds[i] = ystar[n + i]
            pw = accelerations(t + dt, qs, qds, True, minv, P, KG, L, ag, dtg, modes, H, k2)
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
        if not (np.all(np.isfinite(q1)) and np.all(np.isfinite(qd1))):
            counters[0] = step
            return NONFINITE
        deformations(q1, qd1, P, e1, ed1)
        track_peaks(dt, q, qd, q1, qd1, e0, ed0, e1, ed1, P, modes, H, n_story, ith, iv, peaks)
        q[:] = q1
        qd[:] = qd1
        acc[:] = acc1
        e0[:] = e1
        ed0[:] = ed1
        acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
        if (step + 1) % stride == 0:
            record((step + 1) // stride, (step + 1) * dt, q, qd, acc, P, modes, H, minv,
                   KG, weight, iv, e_ref, e1, ed1, out_t, out_q, out_qd, out_e, out_f, out_mode,
                   out_ep, out_energy)
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
def integrate_newmark(q0, qd0, dt, nsteps, stride, minv, P, KG, L, ag, dtg, weight, ith,
                      iv, n_story, alpha, tol, fscale, max_iter, max_halvings, out_t, out_q,
                      out_qd, out_e, out_f, out_mode, out_ep, out_energy, peaks, counters, H):
    """HHT-α (α in [−1/3, 0]; α = 0 is Newmark average acceleration), Newton, step halving.

    β = (1 − α)²/4, γ = 1/2 − α. A step whose Newton iteration fails is split in halves, up to
    ``max_halvings`` times. ``counters`` = [step of failure, halvings, Newton iterations].
    Energy follows the scheme's own identity: the work of each force is the trapezoid
    ½(f₀ + f₁)·Δe over the step, so the balance of Newmark closes to the Newton tolerance away
    from switches; HHT's own numerical dissipation is what its balance leaves open.
    """
    ns, n = P.size, q0.size
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
    record(0, 0.0, q, qd, acc, P, modes, H, minv, KG, weight, iv, e_ref, e, ed, out_t,
           out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy)
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
        if not np.all(np.isfinite(q)):
            counters[0] = step
            return NONFINITE
        if (step + 1) % stride == 0:
            record((step + 1) // stride, t_end, q, qd, acc, P, modes, H, minv, KG,
                   weight, iv, e_ref, e, ed, out_t, out_q, out_qd, out_e, out_f, out_mode,
                   out_ep, out_energy)
    return OK
