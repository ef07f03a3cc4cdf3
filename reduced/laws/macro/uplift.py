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

**Rounding.** Rocking that yields the soil under the edges by turns leaves its surface rounded:
the footing then rests on its middle and rocks on it, with a pinched M–θ loop (the continuum's
contact at θ = 0 after three cycles at FS_v = 2 on the clay is 1.19 m of B = 2 m). The bed's
surface is the parabola s(x) = ρ (x²/b² − 1/3) below the footing's plastic position (mean zero:
ρ does not move the mean settlement), so that w(x) = v + θ x − s(x): the contact is where this
quadratic is positive, and N, M, the tangent (k ∫ 1, x, x² over the contact: Leibniz's rule,
w vanishing at the contact's ends) and the energy are polynomial integrals over it. ρ grows
with the plastic rotation (:mod:`.plastic`); the work it absorbs is F_ρ dρ, with
F_ρ = −∂U/∂ρ = k ∫ ⟨w⟩ (x²/b² − 1/3) dx.
"""

from __future__ import annotations

import numpy as np

from . import compiled as cc
from .params import MacroElement, MacroStepError

__all__ = ["bed_forces", "bed_energy", "rounding_force", "remainder_compliance",
           "vertical_rocking_forces"]


def bed_forces(k: float, b: float, v: float, theta: float, rho: float = 0.0):
    """The tensionless bed's (N, M) and tangent ∂(N, M)/∂(v, θ) (2×2) at (v, θ), its surface
    rounded by ρ (m)."""
    n, m, k11, k12, k22 = cc.bed(k, b, v, theta, rho)
    return np.array([n, m]), np.array([[k11, k12], [k12, k22]])


def bed_energy(k: float, b: float, v: float, theta: float, rho: float = 0.0) -> float:
    """The bed's stored energy ½ k ∫ ⟨w⟩² dx (kN·m/m)."""
    return cc.bed_energy(k, b, v, theta, rho)


def rounding_force(k: float, b: float, v: float, theta: float, rho: float) -> float:
    """F_ρ = −∂U/∂ρ at fixed (v, θ) (kN/m): the work per unit rounding."""
    return cc.rounding_force(k, b, v, theta, rho)


def remainder_compliance(law: MacroElement) -> np.ndarray:
    """C_x = (1/K_v − 1/(k B), 1/K_r − 12/(k B³)), the elastic remainder in series with the
    bed (m/kN, rad/(kN·m)), each ≥ 0 (:attr:`~.params.MacroElement.remainder_compliance`)."""
    return np.array(law.remainder_compliance)


def vertical_rocking_forces(law: MacroElement, v: float, theta: float, guess=None,
                            rounding: float = 0.0):
    """(N, M), their tangent ∂(N, M)/∂(v, θ) (2×2) and the stored energy of the bed and its
    remainder, at the elastic settlement v (m) and rotation θ (rad), the surface rounded by
    ``rounding`` ρ (m). ``guess``: a starting (N, M) (the last step's)."""
    g = (0.0, 0.0) if guess is None else guess
    n, m, t00, t01, t10, t11, energy, ok = cc.vertical_rocking(cc.pack(law), v, theta,
                                                               g[0], g[1], rounding)
    T = np.array([[t00, t01], [t10, t11]])
    if not ok:
        raise MacroStepError(f"macro uplift: the contact did not converge at v = {v:g}, "
                             f"θ = {theta:g} in {cc.MAX_NEWTON} iterations")
    return np.array([n, m]), T, energy
