"""Interpolants of a step from its end values: the cubic Hermite interpolant (value and
rate), its stationary points and extremes (peaks between steps), and the quintic Hermite
interpolant (value, rate and second rate), the event stepper's dense output.
"""

from __future__ import annotations

import math

from numba import njit


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


@njit(cache=True, inline="always")
def quintic_at(m, s, h):
    """Value and rate (per unit time) at fraction s of a quintic with coefficients m."""
    y = m[0] + s * (m[1] + s * (m[2] + s * (m[3] + s * (m[4] + s * m[5]))))
    dy = m[1] + s * (2.0 * m[2] + s * (3.0 * m[3] + s * (4.0 * m[4] + s * 5.0 * m[5])))
    return y, dy / h


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
