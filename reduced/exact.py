"""Independent reference solutions for the reduced model's tests.

* :func:`nigam_jennings` — the exact recurrence of a damped linear SDOF oscillator under
  piecewise-linear ground acceleration (Nigam & Jennings, BSSA 59(2), 1969). It is exact at
  the samples for any step, so it is the reference of the fixed-base test.
* :func:`housner_period` — Housner's linearised free-rocking period of a rigid block.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["nigam_jennings", "nigam_jennings_coefficients", "housner_period",
           "hermite_peak"]


def nigam_jennings_coefficients(omega: float, zeta: float, dt: float):
    """(A, B) with [u, v]ₖ₊₁ = A [u, v]ₖ + B [aₖ, aₖ₊₁] for ü + 2ζωu̇ + ω²u = −a(t).

    ω in rad/s, 0 ≤ ζ < 1, dt in s; a linear between samples (the classical closed form).
    """
    wd = omega * math.sqrt(1.0 - zeta**2)
    e = math.exp(-zeta * omega * dt)
    s, c = math.sin(wd * dt), math.cos(wd * dt)
    r = zeta / math.sqrt(1.0 - zeta**2)
    A = np.array([[e * (r * s + c), e * s / wd],
                  [-omega / math.sqrt(1.0 - zeta**2) * e * s, e * (c - r * s)]])
    k1 = (2 * zeta**2 - 1) / (omega**2 * dt)
    k2 = 2 * zeta / (omega**3 * dt)
    b11 = e * ((k1 + zeta / omega) * s / wd + (k2 + 1 / omega**2) * c) - k2
    b12 = -e * (k1 * s / wd + k2 * c) - 1 / omega**2 + k2
    b21 = (e * ((k1 + zeta / omega) * (c - r * s) - (k2 + 1 / omega**2) * (wd * s + zeta * omega * c))
           + 1 / (omega**2 * dt))
    b22 = -e * (k1 * (c - r * s) - k2 * (wd * s + zeta * omega * c)) - 1 / (omega**2 * dt)
    return A, np.array([[b11, b12], [b21, b22]])


def nigam_jennings(acceleration: np.ndarray, dt: float, omega: float, zeta: float,
                   u0: float = 0.0, v0: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Relative displacement and velocity at the samples of ``acceleration`` (length/s²).

    Exact for acceleration linear between samples: the recurrence is the analytical solution.
    """
    A, B = nigam_jennings_coefficients(omega, zeta, dt)
    a = np.asarray(acceleration, dtype=float)
    u = np.empty(a.size)
    v = np.empty(a.size)
    u[0], v[0] = u0, v0
    for k in range(a.size - 1):
        u[k + 1] = A[0, 0] * u[k] + A[0, 1] * v[k] + B[0, 0] * a[k] + B[0, 1] * a[k + 1]
        v[k + 1] = A[1, 0] * u[k] + A[1, 1] * v[k] + B[1, 0] * a[k] + B[1, 1] * a[k + 1]
    return u, v


def hermite_peak(values: np.ndarray, rates: np.ndarray, dt: float) -> float:
    """max |y(t)| of the cubic Hermite interpolant through samples (y, ẏ) every ``dt``."""
    peak = float(np.max(np.abs(values)))
    y0, y1, d0, d1 = values[:-1], values[1:], rates[:-1], rates[1:]
    turning = np.flatnonzero(d0 * d1 < 0)
    for k in turning:
        c = d0[k] * dt
        b = 6 * (y1[k] - y0[k]) - 4 * d0[k] * dt - 2 * d1[k] * dt
        a = -6 * (y1[k] - y0[k]) + 3 * (d0[k] + d1[k]) * dt
        roots = np.roots([a, b, c]) if abs(a) > 0 else np.array([-c / b])
        for s in roots.real[(np.abs(roots.imag) < 1e-12)]:
            if 0 < s < 1:
                y = ((2 * s**3 - 3 * s**2 + 1) * y0[k] + (s**3 - 2 * s**2 + s) * dt * d0[k]
                     + (-2 * s**3 + 3 * s**2) * y1[k] + (s**3 - s**2) * dt * d1[k])
                peak = max(peak, abs(y))
    return peak


def housner_period(theta0_over_alpha: float, half_width: float, height: float,
                   g: float = 9.81) -> float:
    """Linearised free-rocking period of a uniform rigid block released from rest at θ₀.

    T = (4/p) cosh⁻¹[1/(1 − θ₀/α)], p = √(3g/(4R)), R = √(b² + h²)
    (Housner 1963, for a rigid block on a rigid base).
    """
    R = math.hypot(half_width, height)
    p = math.sqrt(3.0 * g / (4.0 * R))
    return 4.0 / p * math.acosh(1.0 / (1.0 - theta0_over_alpha))
