"""The strip's capacity under combined load: the failure surface of the macro-element.

**Vertical load and moment: Meyerhof's effective width.** A load V at eccentricity e = |M|/V
bears on B′ = B − 2e centred under it, so the strip carries V = B′ c N_c + B′² ½ γ N_γ (each
term times its factor): the moment capacity M_max(V) = V (B − B′)/2 with B′ the root of that
quadratic. Under N = V_ult/FS_v it is N B/2 (1 − 1/FS_v) on a Tresca clay and
N B/2 (1 − 1/√FS_v) with the N_γ term alone: a narrowing contact carries less on a frictional
soil.

**Horizontal load: a parabola,** H_max(V) = t_h V (1 − V/V_ult) (Butterfield and Gottardi 1994
give this shape for strips and pads on sand; ``sliding_ratio`` t_h). The default t_h = 4/(2 + π)
puts its peak on Green's (1954) solution for a bonded strip on Tresca clay, H = c B at
V = c B (1 + π/2) = V_ult/2.

**Combined:** elliptic sections, (H/H_max)² + (M/M_max)² ≤ 1, written as the moment-sized
function

    F = [√((r H)² + M²) − M_max(V)] / (B V_ult),        r = M_max(V)/H_max(V),

< 0 inside, 0 on the surface, continued beyond V = 0 and V = ζ V_ult (where M_max vanishes) by
the distance in V, so that F is continuous everywhere and closes the surface at its two apexes.
The bounding surface of :mod:`.plastic` is this surface with V_ult scaled by its size ζ.

F takes complex arguments, and its gradient is the complex step's (Squire and Trapp 1998):
exact to round-off, with no step to choose. Its ridges at H = M = 0 (the apexes' cones) are
rounded over :data:`RIDGE`.
"""

from __future__ import annotations

import numpy as np

from .params import MacroElement

__all__ = ["RIDGE", "failure_function", "failure_gradient", "failure_size_derivative",
           "moment_capacity", "horizontal_capacity"]

#: The rounding of the surface's cone at H = M = 0, as a fraction of B V_ult: the normal there
#: is along V (no sway or rotation flows from a vertical load alone), and the capacity moves
#: by a part in 10¹².
RIDGE = 1e-12

_STEP = 1e-30  # the complex step: far below round-off of any force


def moment_capacity(law: MacroElement, V, size: float = 1.0):
    """M_max(V) (kN·m/m) with H = 0 and the capacity scaled by ``size`` ζ: V (B − B′)/2 with
    V = ζ (B′ c N_c + B′² ½ γ N_γ); 0 outside 0 < V < ζ V_ult. Complex V passes through."""
    if V.real <= 0.0 or V.real >= np.real(size) * law.ultimate_load:
        return 0.0 * V * size
    a1, a2 = size * law.cohesive_pressure, size * law.frictional_modulus
    if law.frictional_modulus > 0.0:
        width = 2.0 * V / (a1 + np.sqrt(a1 * a1 + 4.0 * a2 * V))
    else:
        width = V / a1
    return 0.5 * V * (law.width - width)


def horizontal_capacity(law: MacroElement, V, size: float = 1.0):
    """H_max(V) = t_h V (1 − V/(ζ V_ult)) (kN/m); 0 outside 0 < V < ζ V_ult."""
    if V.real <= 0.0 or V.real >= np.real(size) * law.ultimate_load:
        return 0.0 * V * size
    return law.sliding_ratio * V * (1.0 - V / (size * law.ultimate_load))


def _ratio(law: MacroElement, V, size: float):
    """r(V) = M_max/H_max (m), continued by its limits at the apexes."""
    top = np.real(size) * law.ultimate_load
    v = min(max(V.real, 1e-9 * top), (1.0 - 1e-9) * top) + (V - V.real)
    return moment_capacity(law, v, size) / horizontal_capacity(law, v, size)


def failure_function(law: MacroElement, Q, size: float = 1.0):
    """F at forces Q = (V, H, M) (kN/m, kN/m, kN·m/m) with the capacity scaled by ``size`` ζ:
    < 0 inside, 0 on the surface, > 0 beyond it (dimensionless, a moment over B V_ult)."""
    V, H, M = Q
    scale = law.width * law.ultimate_load
    ridge = RIDGE * scale
    radius = np.sqrt((_ratio(law, V, size) * H) ** 2 + M * M + ridge * ridge) - ridge
    top = size * law.ultimate_load
    if V.real <= 0.0:
        beyond = -V * law.width
    elif V.real >= np.real(top):
        beyond = (V - top) * law.width
    else:
        beyond = -moment_capacity(law, V, size)
    return (radius + beyond) / scale


def failure_gradient(law: MacroElement, Q, size: float = 1.0) -> np.ndarray:
    """∂F/∂Q at Q (1/kN, 1/kN, 1/(kN·m)), by the complex step."""
    Q = np.asarray(Q, dtype=float)
    grad = np.empty(3)
    for i in range(3):
        z = Q.astype(complex)
        z[i] += 1j * _STEP
        grad[i] = np.imag(failure_function(law, z, size)) / _STEP
    return grad


def failure_size_derivative(law: MacroElement, Q, size: float) -> float:
    """∂F/∂ζ at Q (< 0 on the surface: a larger surface leaves the load inside), by the
    complex step."""
    Q = np.asarray(Q, dtype=complex)
    return float(np.imag(failure_function(law, Q, size + 1j * _STEP)) / _STEP)
