"""The uplift mechanism: a rigid strip on a tensionless Winkler bed, in closed form, in series
with the elastic remainder of the footing's stiffness. Nonlinear elastic: it stores energy and
dissipates none.

A strip of half-width b = B/2 on a bed of modulus k (per unit length and width) with centre
settlement v and rotation θ presses the bed by w(x) = v + θ x; the bed carries p = k ⟨w⟩. In
full contact N = 2 k b v and M = (2/3) k b³ θ. With one edge lifted (θ > 0: the contact runs
from x₀ = −v/θ to b, of length a = b + v/θ < 2b) the pressure is a triangle:

    N = k θ a²/2,        M = N (b − a/3),

so that M = N b (1 − (2/3) √(θ_up/θ)) at constant N, θ_up = 2N/(k B²) the rotation at which
uplift starts (e = B/6). The tangent is symmetric: ∂N/∂v = k a, ∂N/∂θ = ∂M/∂v = k a (b − a/2),
∂M/∂θ = k (a³/3 − a² b + a b²); it equals the full-contact one at a = 2b and vanishes with a.

The footing's elastic stiffness (K_v, K_r) is this bed in series with a remainder of compliance
C_x = diag(1/K_v − 1/(k B), 1/K_r − 12/(k B³)) ≥ 0 (k is the softest such bed,
:attr:`~.params.MacroElement.winkler_modulus`): in full contact the two give K_v and K_r, and
as the contact narrows the bed softens the rotation as a tensionless contact does. Given the
footing's elastic displacement (v_e, θ_e), the forces (N, M) solve N, M = bed(d_e − C_x (N, M)),
found by Newton's method on that monotone system.
"""

from __future__ import annotations

import numpy as np

from . import compiled as cc
from .params import MacroElement, MacroStepError

__all__ = ["bed_forces", "bed_energy", "bed_displacement", "remainder_compliance",
           "vertical_rocking_forces", "vertical_rocking_displacement"]


def bed_forces(k: float, b: float, v: float, theta: float):
    """The tensionless bed's (N, M) and tangent ∂(N, M)/∂(v, θ) (2×2) at (v, θ)."""
    n, m, k11, k12, k22 = cc.bed(k, b, v, theta)
    return np.array([n, m]), np.array([[k11, k12], [k12, k22]])


def bed_energy(k: float, b: float, v: float, theta: float) -> float:
    """The bed's stored energy ∫ ½ k ⟨v + θ x⟩² dx (kN·m/m)."""
    return cc.bed_energy(k, b, v, theta)


def bed_displacement(k: float, b: float, n: float, m: float) -> np.ndarray:
    """The bed's (v, θ) under (N, M), N > 0 and |M| < N b: the inverse of
    :func:`bed_forces` (full contact while e = |M|/N ≤ b/3, else a = 3 (b − e),
    θ = 2N/(k a²), v = θ (a − b))."""
    return np.array(cc.bed_displacement(k, b, n, m))


def remainder_compliance(law: MacroElement) -> np.ndarray:
    """C_x = (1/K_v − 1/(k B), 1/K_r − 12/(k B³)), the elastic remainder in series with the
    bed (m/kN, rad/(kN·m)), each ≥ 0."""
    k, width = law.winkler_modulus, law.width
    # max(0, ·) only removes round-off: k is chosen so that both are ≥ 0
    return np.array([max(0.0, 1.0 / law.vertical_stiffness - 1.0 / (k * width)),
                     max(0.0, 1.0 / law.rocking_stiffness - 12.0 / (k * width ** 3))])


def vertical_rocking_displacement(law: MacroElement, n: float, m: float) -> np.ndarray:
    """The elastic (v, θ) at which the mechanism carries (N, M) (N > 0, |M| < N B/2)."""
    return (bed_displacement(law.winkler_modulus, 0.5 * law.width, n, m)
            + remainder_compliance(law) * [n, m])


def vertical_rocking_forces(law: MacroElement, v: float, theta: float, guess=None):
    """(N, M), their tangent ∂(N, M)/∂(v, θ) (2×2) and the stored energy of the bed and its
    remainder, at the elastic settlement v (m) and rotation θ (rad). ``guess``: a starting
    (N, M) (the last step's)."""
    g = (0.0, 0.0) if guess is None else guess
    n, m, t00, t01, t10, t11, energy, ok = cc.vertical_rocking(cc.pack(law), v, theta,
                                                               g[0], g[1])
    T = np.array([[t00, t01], [t10, t11]])
    if not ok:
        raise MacroStepError(f"macro uplift: the contact did not converge at v = {v:g}, "
                             f"θ = {theta:g} in {cc.MAX_NEWTON} iterations")
    return np.array([n, m]), T, energy
