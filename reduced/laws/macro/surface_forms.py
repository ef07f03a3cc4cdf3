"""The macro-element's failure surface, compiled: the capacity under (V, H, M) scaled by the
bounding surface's size ζ (:mod:`.capacity` is its readable entry point), its gradients by the
complex step, the size's growth with the plastic settlement and the distance to the surface
along a line of load.
"""

from __future__ import annotations

import cmath
import math

from numba import njit

from ..spring import HOT
from .slots import P_A1, P_A2, P_B, P_KREF, P_TH, P_VU, P_Z0

__all__ = ["RIDGE", "moment_capacity", "horizontal_capacity", "failure", "failure_at",
           "failure_value", "failure_gradient", "failure_size_derivative", "size", "image",
           "mobilisation"]

#: The rounding of the surface's cone at H = M = 0, as a fraction of B V_ult (:mod:`.capacity`).
RIDGE = 1e-12
_STEP = 1e-30  # the complex step


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


@njit(cache=True, **HOT)
def size(P, kappa):
    """ζ(κ) = 1 − (1 − ζ0) exp(−κ/κ_ref)."""
    return 1.0 - (1.0 - P[P_Z0]) * math.exp(-kappa / P[P_KREF])


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
def mobilisation(P, Q, zeta):
    """The size ζ_Q ≤ ζ of the surface through the load Q (3): how far the soil's strength is
    mobilised, by bisection (F falls as the size grows: both capacities grow with it). A
    central vertical load V is at V/V_ult; on a footing lifting off, a load at eccentricity
    b − a/3 (contact a) is at 3V/(2 a q) on a Tresca clay: the pressure under the contact, not
    the load's nearness to the overturning limit M = V b. ζ when Q is on or beyond the surface
    of size ζ; 0 when V ≤ 0 (no load, nothing mobilised)."""
    V = Q[0]
    if V <= 0.0:
        return 0.0
    if failure_at(P, V, Q[1], Q[2], zeta) >= 0.0:
        return zeta
    low = V / P[P_VU]  # at this size the surface's top apex is the load's V
    high = zeta
    for _ in range(200):
        mid = 0.5 * (low + high)
        if failure_at(P, V, Q[1], Q[2], mid) > 0.0:
            low = mid
        else:
            high = mid
        if high - low <= 1e-13 * high:
            break
    return high
