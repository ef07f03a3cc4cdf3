"""The macro-element's compiled forms (numba, ``cache=True``): every function of the law on
plain arrays, so that the reduced model's kernels can call it; :mod:`.capacity`, :mod:`.uplift`
and :mod:`.plastic` are its readable entry points, and each function's ``.py_func`` is its
interpreted reference.

The parameters are one float array (:func:`pack`, slots ``P_…``), the state another
(``S_…``): displacement (v, u, θ), plastic displacement, forces (V, H, M), projection centre,
accumulated plastic settlement κ and dissipated energy. The equations are those of the modules
named above. A step that cannot be completed returns a status (``STEP_…``), never a number.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
from numba import njit

__all__ = ["pack", "P_COUNT", "S_COUNT", "STEP_OK", "STEP_CONTACT", "STEP_SURFACE",
           "STEP_SUBSTEPS", "RIDGE", "MAX_NEWTON", "MAX_SUBSTEPS"]

(P_B, P_KV, P_KH, P_KR, P_KW, P_CXV, P_CXT, P_A1, P_A2, P_VU, P_TH, P_Z0, P_KREF, P_H0,
 P_GEXP, P_CHI) = range(16)
P_COUNT = 16
S_D, S_P, S_Q, S_C, S_KAPPA, S_W = 0, 3, 6, 9, 12, 13
S_COUNT = 14
STEP_OK, STEP_CONTACT, STEP_SURFACE, STEP_SUBSTEPS = 0, 1, 2, 3

#: The rounding of the surface's cone at H = M = 0, as a fraction of B V_ult (:mod:`.capacity`).
RIDGE = 1e-12
MAX_NEWTON = 60
MAX_SUBSTEPS = 200_000
_STEP = 1e-30  # the complex step


def pack(law) -> np.ndarray:
    """The parameter array of a :class:`~.params.MacroElement`."""
    from .uplift import remainder_compliance

    P = np.zeros(P_COUNT)
    P[[P_B, P_KV, P_KH, P_KR, P_KW]] = (law.width, law.vertical_stiffness,
                                        law.horizontal_stiffness, law.rocking_stiffness,
                                        law.winkler_modulus)
    P[[P_CXV, P_CXT]] = remainder_compliance(law)
    P[[P_A1, P_A2, P_VU, P_TH]] = (law.cohesive_pressure, law.frictional_modulus,
                                   law.ultimate_load, law.sliding_ratio)
    P[[P_Z0, P_KREF, P_H0, P_GEXP, P_CHI]] = (law.initial_size, law.hardening_settlement,
                                              law.interior_modulus, law.interior_exponent,
                                              law.settlement_coupling)
    return P


# -- the uplift mechanism -----------------------------------------------------------------


@njit(cache=True)
def bed(k, b, v, theta):
    """The tensionless bed's (N, M) and tangent (k11, k12, k22) at (v, θ) (:mod:`.uplift`)."""
    sign = 1.0 if theta >= 0.0 else -1.0
    t = abs(theta)
    if v - t * b >= 0.0:
        return 2.0 * k * b * v, 2.0 / 3.0 * k * b ** 3 * theta, 2.0 * k * b, 0.0, \
            2.0 / 3.0 * k * b ** 3
    if v + t * b <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    a = b + v / t
    n = 0.5 * k * t * a * a
    return n, sign * n * (b - a / 3.0), k * a, sign * k * a * (b - 0.5 * a), \
        k * (a ** 3 / 3.0 - a * a * b + a * b * b)


@njit(cache=True)
def bed_energy(k, b, v, theta):
    """The bed's stored energy ∫ ½ k ⟨v + θ x⟩² dx."""
    t = abs(theta)
    if v - t * b >= 0.0:
        return k * b * v * v + k * b ** 3 * theta * theta / 3.0
    if v + t * b <= 0.0:
        return 0.0
    a = b + v / t
    return k * t * t * a ** 3 / 6.0


@njit(cache=True)
def bed_displacement(k, b, n, m):
    """The bed's (v, θ) under (N, M), N > 0, |M| < N b."""
    e = abs(m) / n
    if e <= b / 3.0:
        return n / (2.0 * k * b), 1.5 * m / (k * b ** 3)
    a = 3.0 * (b - e)
    t = 2.0 * n / (k * a * a)
    return t * (a - b), (t if m >= 0.0 else -t)


@njit(cache=True)
def vertical_rocking(P, v, theta, n, m, T):
    """(N, M, energy, converged) at elastic (v, θ), from the guess (n, m); T (2×2) is set
    to ∂(N, M)/∂(v, θ). The bed in series with the remainder C_x (:mod:`.uplift`)."""
    k, b, cv, ct = P[P_KW], 0.5 * P[P_B], P[P_CXV], P[P_CXT]
    scale = P[P_KV] * (abs(v) + b * abs(theta)) + 1e-300
    ok = False
    for _ in range(MAX_NEWTON):
        f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m)
        r0, r1 = n - f0, m - f1
        if max(abs(r0), abs(r1)) <= 1e-13 * scale:
            ok = True
            break
        j11, j12, j21, j22 = 1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct
        det = j11 * j22 - j12 * j21
        n -= (j22 * r0 - j12 * r1) / det
        m -= (j11 * r1 - j21 * r0) / det
    f0, f1, k11, k12, k22 = bed(k, b, v - cv * n, theta - ct * m)
    j11, j12, j21, j22 = 1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct
    det = j11 * j22 - j12 * j21
    T[0, 0] = (j22 * k11 - j12 * k12) / det
    T[0, 1] = (j22 * k12 - j12 * k22) / det
    T[1, 0] = (j11 * k12 - j21 * k11) / det
    T[1, 1] = (j11 * k22 - j21 * k12) / det
    energy = bed_energy(k, b, v - cv * f0, theta - ct * f1) + 0.5 * (cv * f0 * f0 + ct * f1 * f1)
    return f0, f1, energy, ok


@njit(cache=True)
def elastic(P, de, guess, Q, D):
    """Forces Q and tangent D (3×3) of the elastic-and-uplift mechanism at elastic
    displacement ``de`` (v, u, θ), from the forces ``guess``; returns (energy, converged)."""
    T = np.empty((2, 2))
    n, m, energy, ok = vertical_rocking(P, de[0], de[2], guess[0], guess[2], T)
    Q[0], Q[1], Q[2] = n, P[P_KH] * de[1], m
    D[:, :] = 0.0
    D[0, 0], D[0, 2], D[2, 0], D[2, 2] = T[0, 0], T[0, 1], T[1, 0], T[1, 1]
    D[1, 1] = P[P_KH]
    return energy + 0.5 * P[P_KH] * de[1] * de[1], ok


# -- the failure surface ------------------------------------------------------------------


@njit(cache=True)
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


@njit(cache=True)
def horizontal_capacity(P, V, zeta):
    """H_max(V) = t_h V (1 − V/(ζ V_ult)); 0 outside 0 < V < ζ V_ult."""
    if V.real <= 0.0 or V.real >= zeta.real * P[P_VU]:
        return 0.0 * V * zeta
    return P[P_TH] * V * (1.0 - V / (zeta * P[P_VU]))


@njit(cache=True)
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


@njit(cache=True)
def failure_value(P, Q, zeta):
    """F at forces Q (real)."""
    return failure(P, Q[0] + 0j, Q[1] + 0j, Q[2] + 0j, zeta + 0j).real


@njit(cache=True)
def failure_gradient(P, Q, zeta, n):
    """∂F/∂Q at Q into ``n``, by the complex step."""
    z = zeta + 0j
    n[0] = failure(P, Q[0] + 1j * _STEP, Q[1] + 0j, Q[2] + 0j, z).imag / _STEP
    n[1] = failure(P, Q[0] + 0j, Q[1] + 1j * _STEP, Q[2] + 0j, z).imag / _STEP
    n[2] = failure(P, Q[0] + 0j, Q[1] + 0j, Q[2] + 1j * _STEP, z).imag / _STEP


@njit(cache=True)
def failure_size_derivative(P, Q, zeta):
    """∂F/∂ζ at Q, by the complex step."""
    return failure(P, Q[0] + 0j, Q[1] + 0j, Q[2] + 0j, zeta + 1j * _STEP).imag / _STEP


# -- the bounding-surface update ----------------------------------------------------------


@njit(cache=True)
def size(P, kappa):
    """ζ(κ) = 1 − (1 − ζ0) exp(−κ/κ_ref)."""
    return 1.0 - (1.0 - P[P_Z0]) * math.exp(-kappa / P[P_KREF])


@njit(cache=True)
def image(P, centre, direction, zeta):
    """(t, found): the distance in units of ``direction`` from ``centre`` to the surface."""
    far = 0.0
    far = max(far, abs(direction[0]) / P[P_VU], abs(direction[1]) / P[P_VU],
              abs(direction[2]) / (P[P_B] * P[P_VU]))
    reach = 10.0 / max(far, 1e-300)
    probe = np.empty(3)
    high = min(1.0, reach)
    while True:
        for i in range(3):
            probe[i] = centre[i] + high * direction[i]
        if failure_value(P, probe, zeta) > 0.0:
            break
        high *= 2.0
        if high > reach:
            return 0.0, False
    low = 0.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        for i in range(3):
            probe[i] = centre[i] + mid * direction[i]
        if failure_value(P, probe, zeta) <= 0.0:
            low = mid
        else:
            high = mid
        if high - low <= 1e-15 * high:
            break
    return low, True


@njit(cache=True)
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


@njit(cache=True)
def _scaled_norm(P, x):
    vu = P[P_VU]
    return math.sqrt((x[0] / vu) ** 2 + (x[1] / vu) ** 2 + (x[2] / (P[P_B] * vu)) ** 2)


@njit(cache=True)
def substep(P, S, target, D):
    """One sub-step of state S (in place) to total displacement ``target``; D is set to the
    tangent. Returns a status."""
    Q0 = S[S_Q:S_Q + 3].copy()
    de = target - S[S_P:S_P + 3]
    trial = np.empty(3)
    _, ok = elastic(P, de, Q0, trial, D)
    if not ok:
        return STEP_CONTACT
    S[S_D:S_D + 3] = target
    if trial[0] <= 0.0:  # lifted off: no load, and the footing's sway is free
        S[S_P + 1] = target[1]
        S[S_Q:S_Q + 3] = 0.0
        D[:, :] = 0.0
        return STEP_OK
    zeta = size(P, S[S_KAPPA])
    centre = S[S_C:S_C + 3].copy()
    direction = trial - centre
    if _scaled_norm(P, direction) <= 1e-13:
        S[S_Q:S_Q + 3] = trial
        return STEP_OK
    t, found = image(P, centre, direction, zeta)
    if not found:
        return STEP_SURFACE
    normal = np.empty(3)
    failure_gradient(P, centre + t * direction, zeta, normal)
    if normal @ (trial - Q0) < 0.0:  # a reversal: the centre moves to the present load
        centre = Q0.copy()
        direction = trial - centre
        t, found = image(P, centre, direction, zeta)
        if not found:
            return STEP_SURFACE
        failure_gradient(P, centre + t * direction, zeta, normal)
    image_point = centre + t * direction
    S[S_C:S_C + 3] = centre
    s = min(_scaled_norm(P, Q0 - centre) / max(t * _scaled_norm(P, direction), 1e-300), 1.0)
    flow = normal.copy()  # χ |(n_H, n_M)| added to n_V, in V_ult-scaled forces
    flow[0] += P[P_CHI] * math.hypot(normal[1], normal[2] * P[P_B])
    modulus = plastic_modulus(P, S[S_KAPPA], image_point, flow[0], s, zeta)
    loading = normal @ (trial - Q0)
    if not math.isfinite(modulus) or loading <= 0.0:
        S[S_Q:S_Q + 3] = trial
        return STEP_OK
    lam = loading / (modulus + normal @ (D @ flow))
    plastic = S[S_P:S_P + 3] + lam * flow
    Q = np.empty(3)
    _, ok = elastic(P, target - plastic, trial, Q, D)
    if not ok:
        return STEP_CONTACT
    kappa = S[S_KAPPA] + max(lam * flow[0], 0.0)
    zeta1 = size(P, kappa)
    if failure_value(P, Q, zeta1) > 0.0:  # drift: returned radially onto the surface
        inner = np.array([0.5 * zeta1 * P[P_VU], 0.0, 0.0])
        t, found = image(P, inner, Q - inner, zeta1)
        if not found:
            return STEP_SURFACE
        Q = inner + t * (Q - inner)
        v, theta = bed_displacement(P[P_KW], 0.5 * P[P_B], Q[0], Q[2])
        before = plastic[0]
        plastic = target - np.array([v + P[P_CXV] * Q[0], Q[1] / P[P_KH],
                                     theta + P[P_CXT] * Q[2]])
        kappa += max(plastic[0] - before, 0.0)
        _, ok = elastic(P, target - plastic, Q, Q, D)
        if not ok:
            return STEP_CONTACT
    S[S_W] += 0.5 * (Q0 + Q) @ (plastic - S[S_P:S_P + 3])
    S[S_P:S_P + 3] = plastic
    S[S_Q:S_Q + 3] = Q
    S[S_KAPPA] = kappa
    Dm = D @ flow
    nD = normal @ D
    denominator = modulus + normal @ Dm
    for i in range(3):
        for j in range(3):
            D[i, j] -= Dm[i] * nD[j] / denominator
    return STEP_OK


@njit(cache=True)
def step(P, S, target, max_force_step, D):
    """State S (in place) moved to total displacement ``target`` in sub-steps of at most
    ``max_force_step`` trial force (V_ult-scaled); D is set to the tangent. Returns a
    status."""
    trial = np.empty(3)
    _, ok = elastic(P, target - S[S_P:S_P + 3], S[S_Q:S_Q + 3], trial, D)
    if not ok:
        return STEP_CONTACT
    change = trial - S[S_Q:S_Q + 3]
    largest = max(abs(change[0]) / P[P_VU], abs(change[1]) / P[P_VU],
                  abs(change[2]) / (P[P_B] * P[P_VU]))
    count = max(1, int(math.ceil(largest / max_force_step)))
    if count > MAX_SUBSTEPS:
        return STEP_SUBSTEPS
    start = S[S_D:S_D + 3].copy()
    for i in range(1, count + 1):
        status = substep(P, S, start + (target - start) * (i / count), D)
        if status != STEP_OK:
            return status
    return STEP_OK
