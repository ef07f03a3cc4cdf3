"""Where a condition of a spring's mode crosses its limit within a step.

Within a step of the event stepper every spring keeps its mode, so the trial step is a smooth
solution of one set of laws. Its ends carry q, q̇ and q̈, and the quintic Hermite interpolant
through them is a dense output of the step as accurate as the step itself (its error comes from
the end values, O(h⁵)). Each validity condition of a spring is affine in (e, ė), so along the
step it is a quintic in s = (t − t₀)/h, bounded by its Bernstein coefficients (convex hull); the
Bernstein coefficients, on halved pieces, isolate its first crossing.
"""

from __future__ import annotations

from numba import njit

from .codes import MAX_DEPTH, MAX_PIECES, OVERSHOOT_TOL, SWITCH_TOL


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
