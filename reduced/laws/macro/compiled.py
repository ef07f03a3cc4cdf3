"""The macro-element's compiled forms (numba, ``cache=True``): every function of the law on
plain arrays, so that the reduced model's kernels can call it; :mod:`.capacity`, :mod:`.uplift`
and :mod:`.plastic` are its readable entry points, and each function's ``.py_func`` is its
interpreted reference.

The parameters are one float array (:func:`pack`, slots ``P_…``), the state another
(``S_…``): displacement (v, u, θ), plastic displacement, forces (V, H, M), projection
centre, accumulated plastic settlement κ, dissipated energy and the rounding ρ of the soil's
surface. The equations are those of the modules
named above. A step that cannot be completed returns a status (``STEP_…``), never a number.

The update (:func:`step_into`) allocates nothing: its vectors are slots of a scratch array
(``W_COUNT`` floats), so that the reduced model's compiled loops, which never allocate, can
call it. :func:`step` is the allocating entry point for everything else.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
from numba import njit

from ..spring import HOT

__all__ = ["pack", "P_COUNT", "S_COUNT", "W_COUNT", "STEP_OK", "STEP_CONTACT",
           "STEP_SURFACE", "STEP_SUBSTEPS", "STEP_FLOW", "RIDGE", "MAX_NEWTON", "MAX_SUBSTEPS",
           "step", "step_into"]

(P_B, P_KV, P_KH, P_KR, P_KW, P_CXV, P_CXT, P_A1, P_A2, P_VU, P_TH, P_Z0, P_KREF, P_H0,
 P_GEXP, P_CHI, P_RHO) = range(17)
P_COUNT = 17
S_D, S_P, S_Q, S_C, S_KAPPA, S_W, S_ROUND = 0, 3, 6, 9, 12, 13, 14
S_COUNT = 15
# the scratch array: the update's vectors, three floats each
(W_Q0, W_TRIAL, W_CENTRE, W_DIR, W_NORMAL, W_FLOW, W_PLASTIC, W_Q, W_START, W_TARGET, W_DE,
 W_DE0, W_G) = range(0, 39, 3)
W_COUNT = 39
STEP_OK, STEP_CONTACT, STEP_SURFACE, STEP_SUBSTEPS, STEP_FLOW = 0, 1, 2, 3, 4

#: The rounding of the surface's cone at H = M = 0, as a fraction of B V_ult (:mod:`.capacity`).
RIDGE = 1e-12
MAX_NEWTON = 100
MAX_SUBSTEPS = 200_000
_STEP = 1e-30  # the complex step


def pack(law) -> np.ndarray:
    """The parameter array of a :class:`~.params.MacroElement`."""
    P = np.zeros(P_COUNT)
    P[[P_B, P_KV, P_KH, P_KR, P_KW]] = (law.width, law.vertical_stiffness,
                                        law.horizontal_stiffness, law.rocking_stiffness,
                                        law.winkler_modulus)
    P[[P_CXV, P_CXT]] = law.remainder_compliance
    P[[P_A1, P_A2, P_VU, P_TH]] = (law.cohesive_pressure, law.frictional_modulus,
                                   law.ultimate_load, law.sliding_ratio)
    P[[P_Z0, P_KREF, P_H0, P_GEXP, P_CHI, P_RHO]] = (
        law.initial_size, law.hardening_settlement, law.interior_modulus,
        law.interior_exponent, law.settlement_coupling, law.rounding_ratio)
    return P


# -- the uplift mechanism -----------------------------------------------------------------


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
def bed_moments(k, b, v, theta, rho):
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
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(k, b, v, theta, rho)
    return (k * (A * I0 + C * I1 - R * I2), k * (A * I1 + C * I2 - R * I3),
            k * I0, k * I1, k * I2)


@njit(cache=True, **HOT)
def bed_energy(k, b, v, theta, rho):
    """The bed's stored energy ½ k ∫ ⟨w⟩² dx."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(k, b, v, theta, rho)
    return 0.5 * k * (A * A * I0 + 2.0 * A * C * I1 + (C * C - 2.0 * A * R) * I2
                      - 2.0 * C * R * I3 + R * R * I4)


@njit(cache=True, **HOT)
def rounding_force(k, b, v, theta, rho):
    """F_ρ = −∂U/∂ρ at fixed (v, θ) = k ∫ ⟨w⟩ (x²/b² − 1/3) dx: the work per unit rounding
    (> 0 when the bed presses its edges more than its middle)."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(k, b, v, theta, rho)
    n = k * (A * I0 + C * I1 - R * I2)
    return k * (A * I2 + C * I3 - R * I4) / (b * b) - n / 3.0


@njit(cache=True, **HOT)
def rounding_sensitivity(k, b, v, theta, rho):
    """∂(N, M)/∂ρ of the bed at fixed (v, θ): k ∫ (1/3 − x²/b²) (1, x) dx over the contact."""
    A, C, R, I0, I1, I2, I3, I4 = bed_moments(k, b, v, theta, rho)
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
    return bed_moments(k, b, v, theta, rho)[3]


@njit(cache=True, **HOT)
def _series_tangent(k11, k12, k22, cv, ct):
    """(I + K_b C_x)⁻¹ K_b: the bed in series with the remainder, and det(I + K_b C_x)."""
    j11, j12, j21, j22 = 1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct
    det = j11 * j22 - j12 * j21
    return ((j22 * k11 - j12 * k12) / det, (j22 * k12 - j12 * k22) / det,
            (j11 * k12 - j21 * k11) / det, (j11 * k22 - j21 * k12) / det)


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
        j11, j12, j21, j22 = 1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct
        det = j11 * j22 - j12 * j21
        d0, d1 = (j22 * r0 - j12 * r1) / det, (j11 * r1 - j21 * r0) / det
        n0, m0, step = n, m, 1.0
        for _ in range(40):  # halved while the residual does not fall
            n, m = n0 - step * d0, m0 - step * d1
            f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m, rho)
            r0, r1 = n - f0, m - f1
            if max(abs(r0), abs(r1) / b) < size0:
                break
            step *= 0.5
    f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m, rho)
    t00, t01, t10, t11 = _series_tangent(k11, k12, k22, cv, ct)
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


# -- the failure surface ------------------------------------------------------------------


@njit(cache=True, **HOT)
def moment_capacity(P, V, zeta):
    """M_max(V) with H = 0 and size ζ (complex V and ζ pass through) (:mod:`.capacity`)."""
    if V.real <= 0.0 or V.real >= zeta.real * P[P_VU]:
        return 0.0 * V * zeta
    a1, a2 = zeta * P[P_A1], zeta * P[P_A2]
    if P[P_A2] > 0.0:
        width = 2.0 * V / (a1 + cmath.sqrt(a1 * a1 + 4.0 * a2 * V))
    else:
        width = V / a1
    return 0.5 * V * (P[P_B] - width)


@njit(cache=True, **HOT)
def horizontal_capacity(P, V, zeta):
    """H_max(V) = t_h V (1 − V/(ζ V_ult)); 0 outside 0 < V < ζ V_ult."""
    if V.real <= 0.0 or V.real >= zeta.real * P[P_VU]:
        return 0.0 * V * zeta
    return P[P_TH] * V * (1.0 - V / (zeta * P[P_VU]))


@njit(cache=True, **HOT)
def failure(P, V, H, M, zeta):
    """F at (V, H, M) with size ζ, complex (:mod:`.capacity`)."""
    scale = P[P_B] * P[P_VU]
    ridge = RIDGE * scale
    top = zeta.real * P[P_VU]
    vr = min(max(V.real, 1e-9 * top), (1.0 - 1e-9) * top) + 1j * V.imag
    ratio = moment_capacity(P, vr, zeta) / horizontal_capacity(P, vr, zeta)
    radius = cmath.sqrt((ratio * H) ** 2 + M * M + ridge * ridge) - ridge
    if V.real <= 0.0:
        beyond = -V * P[P_B]
    elif V.real >= top:
        beyond = (V - zeta * P[P_VU]) * P[P_B]
    else:
        beyond = -moment_capacity(P, V, zeta)
    return (radius + beyond) / scale


@njit(cache=True, **HOT)
def failure_at(P, V, H, M, zeta):
    """F at real forces (V, H, M)."""
    return failure(P, V + 0j, H + 0j, M + 0j, zeta + 0j).real


@njit(cache=True, **HOT)
def failure_value(P, Q, zeta):
    """F at forces Q (3, real)."""
    return failure_at(P, Q[0], Q[1], Q[2], zeta)


@njit(cache=True, **HOT)
def failure_gradient(P, Q, zeta, n):
    """∂F/∂Q at Q into ``n``, by the complex step."""
    z = zeta + 0j
    n[0] = failure(P, Q[0] + 1j * _STEP, Q[1] + 0j, Q[2] + 0j, z).imag / _STEP
    n[1] = failure(P, Q[0] + 0j, Q[1] + 1j * _STEP, Q[2] + 0j, z).imag / _STEP
    n[2] = failure(P, Q[0] + 0j, Q[1] + 0j, Q[2] + 1j * _STEP, z).imag / _STEP


@njit(cache=True, **HOT)
def failure_size_derivative(P, Q, zeta):
    """∂F/∂ζ at Q, by the complex step."""
    return failure(P, Q[0] + 0j, Q[1] + 0j, Q[2] + 0j, zeta + 1j * _STEP).imag / _STEP


# -- the bounding-surface update ----------------------------------------------------------


@njit(cache=True, **HOT)
def size(P, kappa):
    """ζ(κ) = 1 − (1 − ζ0) exp(−κ/κ_ref)."""
    return 1.0 - (1.0 - P[P_Z0]) * math.exp(-kappa / P[P_KREF])


@njit(cache=True, **HOT)
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, **HOT)
def _scaled_norm(P, x):
    vu = P[P_VU]
    return math.sqrt((x[0] / vu) ** 2 + (x[1] / vu) ** 2 + (x[2] / (P[P_B] * vu)) ** 2)


@njit(cache=True, **HOT)
def image(P, centre, direction, zeta):
    """(t, found): the distance in units of ``direction`` from ``centre`` to the surface."""
    far = max(abs(direction[0]) / P[P_VU], abs(direction[1]) / P[P_VU],
              abs(direction[2]) / (P[P_B] * P[P_VU]))
    reach = 10.0 / max(far, 1e-300)
    high = min(1.0, reach)
    while failure_at(P, centre[0] + high * direction[0], centre[1] + high * direction[1],
                     centre[2] + high * direction[2], zeta) <= 0.0:
        high *= 2.0
        if high > reach:
            return 0.0, False
    low = 0.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        if failure_at(P, centre[0] + mid * direction[0], centre[1] + mid * direction[1],
                      centre[2] + mid * direction[2], zeta) <= 0.0:
            low = mid
        else:
            high = mid
        if high - low <= 1e-15 * high:
            break
    return low, True


@njit(cache=True, **HOT)
def plastic_modulus(P, kappa, image_point, flow_v, s, zeta):
    """K_p at distance ratio s: the bounding surface's K_b plus the interior term."""
    grow = (1.0 - P[P_Z0]) / P[P_KREF] * math.exp(-kappa / P[P_KREF])
    bound = -failure_size_derivative(P, image_point, zeta) * grow * max(flow_v, 0.0)
    if s <= 0.0:
        return math.inf
    if s >= 1.0:
        return bound
    interior = P[P_H0] * P[P_KV] / P[P_VU] ** 2
    return bound + interior * ((1.0 - s) / s) ** P[P_GEXP]


@njit(cache=True, **HOT)
def _image_normal(P, W, zeta):
    """The image along W_DIR from W_CENTRE and the normal there (into W_NORMAL, the image
    point into W_Q): (t, found)."""
    centre, direction = W[W_CENTRE:W_CENTRE + 3], W[W_DIR:W_DIR + 3]
    t, found = image(P, centre, direction, zeta)
    for i in range(3):
        W[W_Q + i] = centre[i] + t * direction[i]
    failure_gradient(P, W[W_Q:W_Q + 3], zeta, W[W_NORMAL:W_NORMAL + 3])
    return t, found


@njit(cache=True, **HOT)
def _rounding_force(P, de, Q, rho):
    """F_ρ of the bed at elastic displacement ``de`` carrying ``Q`` (the bed's own displacement
    is de less the remainder's C_x Q)."""
    return rounding_force(P[P_KW], 0.5 * P[P_B], de[0] - P[P_CXV] * Q[0],
                          de[2] - P[P_CXT] * Q[2], rho)


@njit(cache=True, **HOT)
def _rounding_forces(P, de, Q, rho, g):
    """∂Q/∂ρ at fixed elastic displacement ``de`` (carrying Q) into ``g``: the bed's own,
    through the series with the remainder, (I + K_b C_x)⁻¹ ∂(N, M)_bed/∂ρ."""
    k, b, cv, ct = P[P_KW], 0.5 * P[P_B], P[P_CXV], P[P_CXT]
    v, theta = de[0] - cv * Q[0], de[2] - ct * Q[2]
    _, _, k11, k12, k22 = bed(k, b, v, theta, rho)
    h0, h2 = rounding_sensitivity(k, b, v, theta, rho)
    j11, j12, j21, j22 = 1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct
    det = j11 * j22 - j12 * j21
    g[0], g[1], g[2] = (j22 * h0 - j12 * h2) / det, 0.0, (j11 * h2 - j21 * h0) / det


@njit(cache=True, **HOT)
def _invert(P, W, de, rho):
    """The elastic (v, θ) in ``de`` (from its value) at which the mechanism on a surface
    rounded by ρ carries W_Q's (V, M): Newton's method, each step halved until the residual
    falls with the bed still in contact. Returns whether it converged."""
    target_n, target_m, scale = W[W_Q], W[W_Q + 2], P[P_VU]
    n, m, t00, t01, t10, t11, _, ok = vertical_rocking(P, de[0], de[2], target_n, target_m, rho)
    for _ in range(MAX_NEWTON):  # from the flat bed's answer, settle until the rounded one bears
        if not ok or t00 * t11 - t01 * t10 > 0.0:
            break
        de[0] += rho
        n, m, t00, t01, t10, t11, _, ok = vertical_rocking(P, de[0], de[2], n, m, rho)
    r0, r1 = n - target_n, (m - target_m) / P[P_B]
    for _ in range(MAX_NEWTON):
        size0 = abs(r0) + abs(r1)
        if ok and size0 <= 1e-12 * scale:
            return True
        det = t00 * t11 - t01 * t10
        if not ok or det <= 0.0:
            return False
        d0 = (t11 * r0 - t01 * r1 * P[P_B]) / det
        d2 = (t00 * r1 * P[P_B] - t10 * r0) / det
        v0, th0, step = de[0], de[2], 1.0
        for _ in range(40):
            de[0], de[2] = v0 - step * d0, th0 - step * d2
            n, m, t00, t01, t10, t11, _, ok = vertical_rocking(P, de[0], de[2], n, m, rho)
            r0, r1 = n - target_n, (m - target_m) / P[P_B]
            if ok and abs(r0) + abs(r1) < size0 and t00 * t11 - t01 * t10 > 0.0:
                break  # smaller, and still in contact (the load is carried somewhere)
            step *= 0.5
    return False


@njit(cache=True, **HOT)
def _return_to_surface(P, W, target, zeta, D, rho):
    """The forces W_Q beyond the surface returned radially towards (ζ V_ult/2, 0, 0), and the
    plastic displacement W_PLASTIC that leaves the elastic part carrying them (the mechanism
    inverted in closed form on a flat surface, by :func:`_invert` on a rounded one). Returns
    the status."""
    inner = 0.5 * zeta * P[P_VU]
    for i in range(3):
        W[W_DIR + i] = W[W_Q + i] - (inner if i == 0 else 0.0)
        W[W_TRIAL + i] = inner if i == 0 else 0.0  # W_TRIAL holds the inner point here
    t, found = image(P, W[W_TRIAL:W_TRIAL + 3], W[W_DIR:W_DIR + 3], zeta)
    if not found:
        return STEP_SURFACE
    for i in range(3):
        W[W_Q + i] = W[W_TRIAL + i] + t * W[W_DIR + i]
    de = W[W_DE:W_DE + 3]
    de[1] = W[W_Q + 1] / P[P_KH]
    k, b = P[P_KW], 0.5 * P[P_B]
    v, theta = flat_bed_displacement(k, b, W[W_Q], W[W_Q + 2])  # exact for a flat surface
    de[0], de[2] = v + P[P_CXV] * W[W_Q], theta + P[P_CXT] * W[W_Q + 2]
    if rho > 0.0 and not _invert(P, W, de, rho):
        return STEP_CONTACT
    for i in range(3):
        W[W_PLASTIC + i] = target[i] - de[i]
    _, ok = elastic(P, de, W[W_Q:W_Q + 3], W[W_Q:W_Q + 3], D, rho)
    return STEP_OK if ok else STEP_CONTACT


@njit(cache=True, **HOT)
def substep(P, S, target, D, W):
    """One sub-step of state S (in place) to total displacement ``target``; D is set to the
    tangent; W is scratch (``W_COUNT``). Returns a status."""
    Q0, trial = W[W_Q0:W_Q0 + 3], W[W_TRIAL:W_TRIAL + 3]
    centre, direction = W[W_CENTRE:W_CENTRE + 3], W[W_DIR:W_DIR + 3]
    normal, flow = W[W_NORMAL:W_NORMAL + 3], W[W_FLOW:W_FLOW + 3]
    plastic, Q, de = W[W_PLASTIC:W_PLASTIC + 3], W[W_Q:W_Q + 3], W[W_DE:W_DE + 3]
    de0, g = W[W_DE0:W_DE0 + 3], W[W_G:W_G + 3]
    rho = S[S_ROUND]
    for i in range(3):
        Q0[i] = S[S_Q + i]
        de0[i] = S[S_D + i] - S[S_P + i]  # the start's elastic displacement
        de[i] = target[i] - S[S_P + i]
        plastic[i] = S[S_P + i]
    _, ok = elastic(P, de, Q0, trial, D, rho)
    if not ok:
        return STEP_CONTACT
    for i in range(3):
        S[S_D + i] = target[i]
    if trial[0] <= 0.0:  # lifted off: no load, the sway free; what it stored is not returned
        stored, _ = elastic(P, de0, Q0, g, D, rho)
        work = stored
        for i in range(3):  # the work done on it over the sub-step, its force falling to 0
            work += 0.5 * Q0[i] * (target[i] - de0[i] - S[S_P + i])
        S[S_W] += work
        S[S_P + 1] = target[1]
        for i in range(3):
            S[S_Q + i] = 0.0
            for j in range(3):
                D[i, j] = 0.0
        return STEP_OK
    zeta = size(P, S[S_KAPPA])
    kappa = S[S_KAPPA]
    for i in range(3):
        centre[i] = S[S_C + i]
        direction[i] = trial[i] - centre[i]
        Q[i] = trial[i]
    modulus, lam, rate = math.inf, 0.0, 0.0
    if _scaled_norm(P, direction) > 1e-13:
        t, found = _image_normal(P, W, zeta)
        if not found:
            return STEP_SURFACE
        if normal[0] * (trial[0] - Q0[0]) + normal[1] * (trial[1] - Q0[1]) \
                + normal[2] * (trial[2] - Q0[2]) < 0.0:  # a reversal: the centre moves here
            for i in range(3):
                centre[i] = Q0[i]
                direction[i] = trial[i] - centre[i]
            t, found = _image_normal(P, W, zeta)
            if not found:
                return STEP_SURFACE
        for i in range(3):
            S[S_C + i] = centre[i]
            Q[i] = Q0[i] - centre[i]  # Q holds Q0 − centre for the distance ratio
        s = min(_scaled_norm(P, Q) / max(t * _scaled_norm(P, direction), 1e-300), 1.0)
        for i in range(3):
            Q[i] = centre[i] + t * direction[i]  # the image point
            flow[i] = normal[i]
        flow[0] += P[P_CHI] * math.hypot(normal[1], normal[2] * P[P_B])
        modulus = plastic_modulus(P, kappa, Q, flow[0], s, zeta)
        loading = normal[0] * (trial[0] - Q0[0]) + normal[1] * (trial[1] - Q0[1]) \
            + normal[2] * (trial[2] - Q0[2])
        for i in range(3):
            Q[i] = trial[i]
        if math.isfinite(modulus) and loading > 0.0:
            nDm = 0.0
            for i in range(3):
                for j in range(3):
                    nDm += normal[i] * D[i, j] * flow[j]
            if not modulus + nDm > 0.0:  # no stiffness along the flow: no multiplier
                return STEP_FLOW
            lam = loading / (modulus + nDm)
            force0 = _rounding_force(P, de0, Q0, rho)
            if force0 > 0.0:  # the edges pressed harder than the middle: the surface rounds
                rate = P[P_RHO] * 0.5 * P[P_B] * abs(flow[2])
            for i in range(3):
                plastic[i] = S[S_P + i] + lam * flow[i]
                de[i] = target[i] - plastic[i]
            rho += rate * lam
            _, ok = elastic(P, de, trial, Q, D, rho)
            if not ok:
                return STEP_CONTACT
            kappa += max(lam * flow[0], 0.0)
            zeta = size(P, kappa)
    if failure_value(P, Q, zeta) > 0.0:  # beyond the surface: returned radially onto it
        before = plastic[0]
        status = _return_to_surface(P, W, target, zeta, D, rho)
        if status != STEP_OK:
            return status
        kappa += max(plastic[0] - before, 0.0)
    work = 0.0
    if rho != S[S_ROUND]:
        work = 0.5 * (_rounding_force(P, de0, Q0, S[S_ROUND]) + _rounding_force(P, de, Q, rho)) \
            * (rho - S[S_ROUND])
    for i in range(3):
        work += 0.5 * (Q0[i] + Q[i]) * (plastic[i] - S[S_P + i])
    S[S_W] += work
    for i in range(3):
        S[S_P + i] = plastic[i]
        S[S_Q + i] = Q[i]
    S[S_KAPPA] = kappa
    S[S_ROUND] = rho
    if lam > 0.0 and math.isfinite(modulus):
        _rounding_forces(P, de, Q, rho, g)
        _plastic_tangent(D, normal, flow, modulus, g, rate)
    return STEP_OK


@njit(cache=True, **HOT)
def _plastic_tangent(D, normal, flow, modulus, g, rate):
    """The update's tangent, in place: D − (D m − r g) nᵀ D / (K_p + nᵀ D m), r g the
    rounding's share (dρ = r dλ, g = ∂Q/∂ρ at fixed elastic displacement); D left as it is
    where the denominator vanishes (the contact lost, the load perfectly plastic)."""
    a0 = D[0, 0] * flow[0] + D[0, 1] * flow[1] + D[0, 2] * flow[2]
    a1 = D[1, 0] * flow[0] + D[1, 1] * flow[1] + D[1, 2] * flow[2]
    a2 = D[2, 0] * flow[0] + D[2, 1] * flow[1] + D[2, 2] * flow[2]
    denominator = modulus + normal[0] * a0 + normal[1] * a1 + normal[2] * a2
    if not denominator > 0.0:
        return
    a0, a1, a2 = a0 - rate * g[0], a1 - rate * g[1], a2 - rate * g[2]
    nD0 = normal[0] * D[0, 0] + normal[1] * D[1, 0] + normal[2] * D[2, 0]
    nD1 = normal[0] * D[0, 1] + normal[1] * D[1, 1] + normal[2] * D[2, 1]
    nD2 = normal[0] * D[0, 2] + normal[1] * D[1, 2] + normal[2] * D[2, 2]
    D[0, 0] -= a0 * nD0 / denominator
    D[0, 1] -= a0 * nD1 / denominator
    D[0, 2] -= a0 * nD2 / denominator
    D[1, 0] -= a1 * nD0 / denominator
    D[1, 1] -= a1 * nD1 / denominator
    D[1, 2] -= a1 * nD2 / denominator
    D[2, 0] -= a2 * nD0 / denominator
    D[2, 1] -= a2 * nD1 / denominator
    D[2, 2] -= a2 * nD2 / denominator


@njit(cache=True, **HOT)
def substeps(P, S, target, max_force_step, D, W):
    """How many sub-steps a step of S to ``target`` takes (≥ 1; 0 if its elastic trial
    fails), so that none changes the trial force by more than ``max_force_step``
    (V_ult-scaled)."""
    for i in range(3):
        W[W_DE + i] = target[i] - S[S_P + i]
    _, ok = elastic(P, W[W_DE:W_DE + 3], S[S_Q:S_Q + 3], W[W_TRIAL:W_TRIAL + 3], D,
                    S[S_ROUND])
    if not ok:
        return 0
    vu = P[P_VU]
    largest = max(abs(W[W_TRIAL] - S[S_Q]) / vu, abs(W[W_TRIAL + 1] - S[S_Q + 1]) / vu,
                  abs(W[W_TRIAL + 2] - S[S_Q + 2]) / (P[P_B] * vu))
    return max(1, int(math.ceil(min(largest / max_force_step, 1e18))))


@njit(cache=True, **HOT)
def step_into(P, S, target, max_force_step, count, D, W):
    """State S (in place) moved to total displacement ``target`` in ``count`` equal sub-steps
    (0: as many as keep each within ``max_force_step`` of trial force, V_ult-scaled); D is
    set to the tangent; W is scratch (``W_COUNT``). Returns a status. Allocates nothing."""
    if count <= 0:
        count = substeps(P, S, target, max_force_step, D, W)
        if count == 0:
            return STEP_CONTACT
    if count > MAX_SUBSTEPS:
        return STEP_SUBSTEPS
    for i in range(3):
        W[W_START + i] = S[S_D + i]
    for k in range(1, count + 1):
        for i in range(3):
            W[W_TARGET + i] = W[W_START + i] + (target[i] - W[W_START + i]) * (k / count)
        status = substep(P, S, W[W_TARGET:W_TARGET + 3], D, W)
        if status != STEP_OK:
            return status
    return STEP_OK


@njit(cache=True)
def step(P, S, target, max_force_step, D):
    """:func:`step_into` with its own scratch and the automatic sub-step count."""
    return step_into(P, S, target, max_force_step, 0, D, np.empty(W_COUNT))
