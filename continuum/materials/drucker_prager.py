"""Drucker–Prager plasticity (perfectly plastic, non-associated), matched to Mohr–Coulomb in plane
strain: the record :class:`DruckerPrager` and its vectorised map :func:`drucker_prager`.

√J2 + η p ≤ ξ c, potential √J2 + η̄ p (p = tr σ / 3, tension positive): a closed-form return
to the cone (SMOOTH) or to the apex p = c cot φ (APEX). The plane-strain match to Mohr–Coulomb
(c, φ, ψ) is the record's (:class:`DruckerPrager`); for ψ = φ it is the textbook
η = 3 tan φ / √(9 + 12 tan²φ), ξ = 3 / √(9 + 12 tan²φ).

No compiled point return: the explicit route runs it through :func:`drucker_prager` and the
sparse assembly (the same numbers, slower; ``Constants`` is None).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .base import Frictional
from .returns import (EYE3, IDEV6, ONE6, ONE_ONE6, RTOL, SQ2, Region, State, deviator,
                      finish, frobenius_norm, mandel, prepare)

__all__ = ["DruckerPrager", "drucker_prager"]


def drucker_prager(strain, state: State | None, params: DruckerPrager):
    """Drucker–Prager (perfectly plastic, non-associated): closed-form return to the cone or to
    the apex, consistent tangent (cf. de Souza Neto et al. 2008, ch. 8; derived here for this
    parametrisation and checked by finite differences in the tests)."""
    eps, eps_p, ebar, batch = prepare(strain, state)
    K, G = params.bulk_modulus, params.shear_modulus
    eta, eta_bar, xi, c = params.eta, params.eta_bar, params.xi, params.cohesion
    e_trial = eps - eps_p
    dev, vol = deviator(e_trial)
    s_trial = 2.0 * G * dev
    norm = frobenius_norm(s_trial)
    j_trial = norm / SQ2  # √J2
    p_trial = K * vol
    f_trial = j_trial + eta * p_trial - xi * c
    plastic = f_trial > RTOL * (xi * c + j_trial + abs(eta * p_trial))
    a = 1.0 / (G + K * eta * eta_bar)
    dgamma = np.where(plastic, f_trial * a, 0.0)
    apex = plastic & (j_trial - G * dgamma < 0.0) & (eta > 0.0)
    cone = plastic & ~apex
    dgamma = np.where(cone, dgamma, 0.0)
    j_safe = np.where(cone, j_trial, 1.0)
    unit = s_trial / np.where(norm > 0.0, norm, 1.0)[:, None, None]
    shrink = np.where(apex, 1.0, G * dgamma / j_safe)
    p_apex = xi * c / eta if eta > 0.0 else 0.0
    p = np.where(apex, p_apex, p_trial - K * eta_bar * dgamma)
    stress = s_trial * (1.0 - shrink)[:, None, None] + p[:, None, None] * EYE3
    d_eps_p = dgamma[:, None, None] * (unit / SQ2 + eta_bar / 3.0 * EYE3)
    d_eps_p = np.where(apex[:, None, None],
                       e_trial - (p_apex / (3.0 * K)) * EYE3, d_eps_p)
    n6 = mandel(unit)
    c1 = np.where(cone, 2.0 * G * G * (dgamma / j_safe - a), 0.0)[:, None, None]
    c2 = np.where(cone, SQ2 * G * a * K, 0.0)[:, None, None]
    c3 = np.where(cone, K * K * eta * eta_bar * a, 0.0)[:, None, None]
    tangent = ((2.0 * G * (1.0 - shrink))[:, None, None] * IDEV6
               + c1 * n6[:, :, None] * n6[:, None, :]
               - c2 * (eta * n6[:, :, None] * ONE6 + eta_bar * ONE6[:, None] * n6[:, None, :])
               + (K - c3) * ONE_ONE6)
    tangent = np.where(apex[:, None, None], 0.0, tangent)
    region = np.select([apex, cone], [Region.APEX, Region.SMOOTH], Region.ELASTIC)
    d_ebar = math.sqrt(2.0 / 3.0) * frobenius_norm(d_eps_p)
    return finish(batch, stress, tangent, eps_p + d_eps_p, ebar + d_ebar, region)


@dataclass(frozen=True)
class DruckerPrager(Frictional):
    """Drucker–Prager, perfectly plastic, matched to Mohr–Coulomb (c, φ, ψ) in plane strain.

    Yield √J2 + η p − ξ c ≤ 0, potential √J2 + η̄ p, p = tr σ / 3 (tension positive).

    Plane-strain match: at the plane-strain limit (ε̇p_zz = 0) the DP cone gives exactly the
    Mohr–Coulomb limit (σ1 − σ3)/2 = c cos φ − (σ1 + σ3)/2 sin φ, and the plastic dilatancy ratio
    ε̇p_v / (ε̇p_1 − ε̇p_3) equals Mohr–Coulomb's sin ψ:

        η̄ = 3 tan ψ / √(9 + 12 tan²ψ),  r = √(1 − η̄²/3),
        η = sin φ / (r + η̄ sin φ / 3),  ξ = cos φ / (r + η̄ sin φ / 3).

    For ψ = φ this is the textbook associated match η = 3 tan φ / √(9 + 12 tan²φ),
    ξ = 3 / √(9 + 12 tan²φ); for ψ = 0 it is η = sin φ, ξ = cos φ. The apex is
    p = ξ c / η = c cot φ.
    """

    name = "drucker_prager"
    update = staticmethod(drucker_prager)

    @property
    def eta_bar(self) -> float:
        t = math.tan(math.radians(self.dilation_angle))
        return 3.0 * t / math.sqrt(9.0 + 12.0 * t * t)

    @property
    def _denominator(self) -> float:
        eb = self.eta_bar
        return math.sqrt(1.0 - eb * eb / 3.0) + eb * self.sin_phi / 3.0

    @property
    def eta(self) -> float:
        return self.sin_phi / self._denominator

    @property
    def xi(self) -> float:
        return self.cos_phi / self._denominator
