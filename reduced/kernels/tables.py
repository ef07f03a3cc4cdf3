"""Laws tabulated by mode, for the event stepper.

While a spring keeps its mode its force is affine in (e, ė), its powers are quadratic and its
validity conditions are affine. The event stepper keeps their coefficients in a table (rows
``T_*`` of :mod:`.codes`), one column per spring, rewritten only when the spring switches, so
that its right-hand side and its switch screen are branch-free loops. The foundation bed (the
springs on the same two DOFs as the last spring: θ and V) has a table of its own that those
loops run through in SIMD lanes; the other springs (stories) are few and go one by one.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .codes import (FAST, HOT, N_CONDITIONS, N_ROWS, SEPARATED, STORY, T_A0, T_A1, T_C, T_COND,
                    T_F, T_FY, T_GAP, T_I, T_K, T_KC, T_P, T_V)
from .laws import condition, law
from .motion import ground_acceleration
from .rocking import finish_accelerations


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
def frozen_accelerations(t, q, qd, system, Tg, Tb, Mw, qdd):
    """q̈ with every spring held in its tabulated mode (event stepper); returns the powers
    (input, viscous, impact, plastic)."""
    minv, P, KG, L, ag, dtg, _, frame, story, _ = system
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
