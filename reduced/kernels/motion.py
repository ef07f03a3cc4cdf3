"""The equation of motion (relative to the ground, Ewing eqs. 5–8):
``M q̈ = −A s(Aᵀq, Aᵀq̇) − K_G q + L a_g(t)``, with M diagonal (small rotations), ``s`` the
spring laws, ``K_G`` the optional P-Δ geometric stiffness and ``L = −M r`` the ground load.

Helpers that take arrays are inlined into their callers (``inline="always"``): an ordinary call
reference-counts each array argument, which costs about as much as the arithmetic of a small
bed. Helpers on records and scalars are ordinary functions. e = aᵀq is gathered and −a f
scattered inline.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .base import base_force
from .codes import F_EXACT, F_ITH, F_SIDE
from .laws import force_in_mode, from_history, natural_mode, trial_force
from .rocking import finish_accelerations


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
def accelerations(t, q, qd, natural, system, modes, H, Mw, qdd):
    """q̈ from the equation of motion; returns the powers (input, viscous, impact, plastic).
    ``system`` is the scene's record (:data:`~.codes.SYSTEM`), ``Mw`` scratch for the mass
    matrix of exact kinematics.

    ``natural``: each spring's mode is decided by its trial state (fixed-step methods, whose
    plastic work is counted at the return map instead; with exact kinematics the base pivots
    on the edge of θ's sign); otherwise modes are frozen. Springs on
    the same two DOFs as the last spring (the foundation bed, on θ and V) sum their forces
    locally instead of scattering each into q̈. A base element (:mod:`.base`) adds its own,
    from a trial copy of its committed state.
    """
    minv, P, KG, L, ag, dtg, _, frame, story, element = system
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
    b0, b1 = (P[P.size - 1].i0, P[P.size - 1].i1) if P.size else (0, 0)  # none: a base element
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
        if from_history(p):  # q–z: its trial from its history (fixed-step and implicit only)
            f, v, _, _, _, _ = trial_force(p, h, e, ed)
            im, pl = 0.0, 0.0
        else:
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
    pv += base_force(q, qd, element, qdd)
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


@njit(cache=True, inline="always")
def deformation(p, q, qd):
    """e and ė of the spring with record p at the state (q, q̇)."""
    e = p.a0 * q[p.i0] + p.a1 * q[p.i1]
    ed = p.a0 * qd[p.i0] + p.a1 * qd[p.i1]
    if p.nnz == 3:
        e += p.a2 * q[p.i2]
        ed += p.a2 * qd[p.i2]
    return e, ed
