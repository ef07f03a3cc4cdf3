"""The macro-element's uplift mechanism, compiled: the tensionless Winkler bed on a surface
rounded by ρ in closed form (its contact, forces, tangent, energy and rounding force), in series
with the elastic remainder, and the elastic-and-uplift mechanism's forces and tangent
(:mod:`.uplift` is its readable entry point; the equations are there).
"""

from __future__ import annotations

import math

from numba import njit

from ..spring import HOT
from .slots import MAX_NEWTON, P_B, P_CXT, P_CXV, P_KH, P_KV, P_KW

__all__ = ["contact", "bed_moments", "bed", "bed_energy", "rounding_force",
           "rounding_sensitivity", "flat_bed_displacement", "bed_length", "solve2",
           "series_tangent", "vertical_rocking", "elastic"]


@njit(cache=True, **HOT)
def contact(b, A, C, R):
    """The contact interval [lo, hi] ⊂ [−b, b] where w(x) = A + C x − R x² > 0 (R ≥ 0), and
    whether there is one; the roots in their stable form (no cancellation as R → 0)."""
    if R <= 0.0:
        if C == 0.0:
            return -b, b, A > 0.0
        root = -A / C
        lo, hi = (max(-b, root), b) if C > 0.0 else (-b, min(b, root))
        return lo, hi, hi > lo
    disc = C * C + 4.0 * R * A
    if disc <= 0.0:
        return 0.0, 0.0, False
    q = 0.5 * (C + math.copysign(math.sqrt(disc), C))
    if q == 0.0:
        return 0.0, 0.0, False
    r1, r2 = q / R, -A / q
    lo, hi = max(-b, min(r1, r2)), min(b, max(r1, r2))
    return lo, hi, hi > lo


@njit(cache=True, **HOT)
def bed_moments(b, v, theta, rho):
    """(w's coefficients A, C, R and the contact's moments I0…I4, ∫ xʲ dx over it) of the bed
    at (v, θ) on a surface rounded by ρ: w(x) = v + θ x − ρ (x²/b² − 1/3) (:mod:`.uplift`)."""
    A, C, R = v + rho / 3.0, theta, rho / (b * b)
    lo, hi, found = contact(b, A, C, R)
    if not found:
        return A, C, R, 0.0, 0.0, 0.0, 0.0, 0.0
    return (A, C, R, hi - lo, (hi ** 2 - lo ** 2) / 2.0, (hi ** 3 - lo ** 3) / 3.0,
            (hi ** 4 - lo ** 4) / 4.0, (hi ** 5 - lo ** 5) / 5.0)


@njit(cache=True, **HOT)
def bed(k, b, v, theta, rho):
    """The tensionless bed's (N, M) and tangent (k11, k12, k22) at (v, θ) on a surface
    rounded by ρ: k ∫ w, k ∫ x w, and k times the contact's moments (:mod:`.uplift`)."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(b, v, theta, rho)
    return (k * (A * I0 + C * I1 - R * I2), k * (A * I1 + C * I2 - R * I3),
            k * I0, k * I1, k * I2)


@njit(cache=True, **HOT)
def bed_energy(k, b, v, theta, rho):
    """The bed's stored energy ½ k ∫ ⟨w⟩² dx."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(b, v, theta, rho)
    return 0.5 * k * (A * A * I0 + 2.0 * A * C * I1 + (C * C - 2.0 * A * R) * I2
                      - 2.0 * C * R * I3 + R * R * I4)


@njit(cache=True, **HOT)
def rounding_force(k, b, v, theta, rho):
    """F_ρ = −∂U/∂ρ at fixed (v, θ) = k ∫ ⟨w⟩ (x²/b² − 1/3) dx: the work per unit rounding
    (> 0 when the bed presses its edges more than its middle)."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(b, v, theta, rho)
    n = k * (A * I0 + C * I1 - R * I2)
    return k * (A * I2 + C * I3 - R * I4) / (b * b) - n / 3.0


@njit(cache=True, **HOT)
def rounding_sensitivity(k, b, v, theta, rho):
    """∂(N, M)/∂ρ of the bed at fixed (v, θ): k ∫ (1/3 − x²/b²) (1, x) dx over the contact."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(b, v, theta, rho)
    return k * (I0 / 3.0 - I2 / (b * b)), k * (I1 / 3.0 - I3 / (b * b))


@njit(cache=True, **HOT)
def flat_bed_displacement(k, b, n, m):
    """The flat bed's (v, θ) under (N, M), N > 0, |M| < N b, in closed form: full contact
    while e = |M|/N ≤ b/3, else a = 3 (b − e), θ = 2N/(k a²), v = θ (a − b)."""
    e = abs(m) / n
    if e <= b / 3.0:
        return n / (2.0 * k * b), 1.5 * m / (k * b ** 3)
    a = 3.0 * (b - e)
    t = 2.0 * n / (k * a * a)
    return t * (a - b), (t if m >= 0.0 else -t)


@njit(cache=True, **HOT)
def bed_length(k, b, v, theta, rho):
    """The contact length (length)."""
    return bed_moments(b, v, theta, rho)[3]


@njit(cache=True, **HOT)
def solve2(a11, a12, a21, a22, r0, r1):
    """(x0, x1) solving [[a11, a12], [a21, a22]] x = r by Cramer's rule (the caller keeps the
    determinant away from zero)."""
    det = a11 * a22 - a12 * a21
    return (a22 * r0 - a12 * r1) / det, (a11 * r1 - a21 * r0) / det


@njit(cache=True, **HOT)
def series_tangent(k11, k12, k22, cv, ct):
    """(I + K_b C_x)⁻¹ K_b: the bed in series with the remainder, column by column."""
    j11, j12, j21, j22 = 1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct
    t00, t10 = solve2(j11, j12, j21, j22, k11, k12)
    t01, t11 = solve2(j11, j12, j21, j22, k12, k22)
    return t00, t01, t10, t11


@njit(cache=True, **HOT)
def vertical_rocking(P, v, theta, n, m, rho):
    """(N, M, ∂N/∂v, ∂N/∂θ, ∂M/∂v, ∂M/∂θ, energy, converged) at elastic (v, θ), from the guess
    (n, m), on a surface rounded by ρ: the bed in series with the remainder C_x
    (:mod:`.uplift`), by Newton's method."""
    k, b, cv, ct = P[P_KW], 0.5 * P[P_B], P[P_CXV], P[P_CXT]
    scale = P[P_KV] * (abs(v) + b * abs(theta) + rho) + 1e-300  # the forces' size
    ok = False
    f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m, rho)
    r0, r1 = n - f0, m - f1
    for _ in range(MAX_NEWTON):
        size0 = max(abs(r0), abs(r1) / b)
        if size0 <= 1e-13 * scale:
            ok = True
            break
        d0, d1 = solve2(1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct, r0, r1)
        n0, m0, step = n, m, 1.0
        for _ in range(40):  # halved while the residual does not fall
            n, m = n0 - step * d0, m0 - step * d1
            f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m, rho)
            r0, r1 = n - f0, m - f1
            if max(abs(r0), abs(r1) / b) < size0:
                break
            step *= 0.5
    f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m, rho)
    t00, t01, t10, t11 = series_tangent(k11, k12, k22, cv, ct)
    energy = (bed_energy(k, b, v - cv * f0, theta - ct * f1, rho)
              + 0.5 * (cv * f0 * f0 + ct * f1 * f1))
    return f0, f1, t00, t01, t10, t11, energy, ok


@njit(cache=True, **HOT)
def elastic(P, de, guess, Q, D, rho):
    """Forces Q (3) and tangent D (3×3) of the elastic-and-uplift mechanism at elastic
    displacement ``de`` (v, u, θ) on a surface rounded by ρ, from the forces ``guess`` (Q may
    be ``guess``); returns (energy, converged)."""
    n, m, t00, t01, t10, t11, energy, ok = vertical_rocking(P, de[0], de[2], guess[0], guess[2],
                                                            rho)
    Q[0], Q[1], Q[2] = n, P[P_KH] * de[1], m
    for i in range(3):
        for j in range(3):
            D[i, j] = 0.0
    D[0, 0], D[0, 2], D[2, 0], D[2, 2] = t00, t01, t10, t11
    D[1, 1] = P[P_KH]
    return energy + 0.5 * P[P_KH] * de[1] * de[1], ok
