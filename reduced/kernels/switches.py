"""Switch location of the event stepper: which spring leaves its mode first within a trial
step, and where (:func:`first_crossing`); the switches at the cut (:func:`apply_switches`) and
the impact log. A cheap bound (:func:`column_margin`) first screens out the springs that cannot
switch; the others go through the crossing search of :mod:`.crossing`. The step is cut at the
switch, with the interpolated state.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .codes import FAST, HOT, N_CONDITIONS, ROUNDING, SWITCH_TOL, T_A0, T_A1, T_COND
from .crossing import condition_crossing, condition_polynomial
from .interpolants import chord_deviation, quintic, quintic_at
from .laws import past_limit, switch_mode, validity
from .motion import deformation
from .tables import bed_rates, tabulate


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
def spring_quintic(j, h, Tb, x0, y0, x1, y1, start, end):
    """Coefficients of spring j's e on a trial step (bed springs from their DOFs' state;
    ``start``, ``end``: (e, ė, ë) of the springs off the bed)."""
    e0, ed0, edd0 = start
    e1, ed1, edd1 = end
    ng = e0.size
    if j < ng:
        return quintic(h, e0[j], ed0[j], edd0[j], e1[j], ed1[j], edd1[j])
    a0, a1 = Tb[T_A0, j - ng], Tb[T_A1, j - ng]
    ea, eda, edda = bed_rates(a0, a1, x0, y0)
    eb, edb, eddb = bed_rates(a0, a1, x1, y1)
    return quintic(h, ea, eda, edda, eb, edb, eddb)


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
def first_crossing(h, P, Tg, Tb, x0, y0, x1, y1, start, end, margin):
    """Earliest fraction s of a trial step at which a spring should switch, on the step's
    quintic interpolant, and that spring; (2.0, −1) when every spring keeps its mode.

    ``start``, ``end``: (e, ė, ë) of the springs off the bed at the start and the end of the
    step; the bed's follow from its DOFs' state at the start (x0, y0) and the end (x1, y1).
    ``margin`` is scratch.
    """
    e0, ed0, edd0 = start
    e1, ed1, edd1 = end
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
