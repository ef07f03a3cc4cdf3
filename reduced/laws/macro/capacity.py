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

F (:mod:`.compiled`) takes complex arguments, and its gradient is the complex step's (Squire
and Trapp 1998): exact to round-off, with no step to choose. Its ridges at H = M = 0 (the
apexes' cones) are rounded over :data:`RIDGE`.
"""

from __future__ import annotations

import numpy as np

from . import compiled as cc
from .compiled import RIDGE
from .params import MacroElement

__all__ = ["RIDGE", "failure_function", "failure_gradient", "failure_size_derivative",
           "moment_capacity", "horizontal_capacity"]


def moment_capacity(law: MacroElement, V: float, size: float = 1.0) -> float:
    """M_max(V) (kN·m/m) with H = 0 and the capacity scaled by ``size`` ζ: V (B − B′)/2 with
    V = ζ (B′ c N_c + B′² ½ γ N_γ); 0 outside 0 < V < ζ V_ult."""
    return cc.moment_capacity(cc.pack(law), complex(V), complex(size)).real


def horizontal_capacity(law: MacroElement, V: float, size: float = 1.0) -> float:
    """H_max(V) = t_h V (1 − V/(ζ V_ult)) (kN/m); 0 outside 0 < V < ζ V_ult."""
    return cc.horizontal_capacity(cc.pack(law), complex(V), complex(size)).real


def failure_function(law: MacroElement, Q, size: float = 1.0) -> float:
    """F at forces Q = (V, H, M) (kN/m, kN/m, kN·m/m) with the capacity scaled by ``size`` ζ:
    < 0 inside, 0 on the surface (and at Q = 0, a footing lifted off), > 0 beyond it
    (dimensionless, a moment over B V_ult)."""
    return cc.failure_value(cc.pack(law), np.asarray(Q, dtype=float), float(size))


def failure_gradient(law: MacroElement, Q, size: float = 1.0) -> np.ndarray:
    """∂F/∂Q at Q (1/kN, 1/kN, 1/(kN·m)), by the complex step."""
    n = np.empty(3)
    cc.failure_gradient(cc.pack(law), np.asarray(Q, dtype=float), float(size), n)
    return n


def failure_size_derivative(law: MacroElement, Q, size: float) -> float:
    """∂F/∂ζ at Q (< 0 on the surface: a larger surface leaves the load inside), by the
    complex step."""
    return cc.failure_size_derivative(cc.pack(law), np.asarray(Q, dtype=float), float(size))
