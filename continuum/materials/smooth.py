"""Return maps whose yield surface is smooth (away from an apex): linear elasticity, von Mises
(radial return) and Drucker–Prager (return to the cone or its apex), all in closed form."""

from __future__ import annotations

import math

import numpy as np

from .params import DruckerPrager, Elastic, VonMises
from .returns import (EYE3, IDEV6, ONE6, ONE_ONE6, RTOL, SQ2, Region, State, deviator,
                      elastic_mandel, elastic_stress, finish, frobenius_norm, mandel, prepare)

__all__ = ["linear_elastic", "von_mises", "drucker_prager"]


def linear_elastic(strain, state: State | None, params: Elastic):
    """Hooke's law σ = λ tr(εe) 𝟏 + 2G εe with εe = ε − εp (εp of ``state``, normally zero)."""
    eps, eps_p, ebar, batch = prepare(strain, state)
    stress = elastic_stress(eps - eps_p, params)
    tangent = np.broadcast_to(elastic_mandel(params), (len(eps), 6, 6))
    return finish(batch, stress, tangent, eps_p.copy(), ebar.copy(),
                   np.zeros(len(eps), dtype=np.int8))


def von_mises(strain, state: State | None, params: VonMises):
    """von Mises with linear isotropic hardening: radial return (exact for linear hardening) and
    its consistent tangent (de Souza Neto et al. 2008, ch. 7)."""
    eps, eps_p, ebar, batch = prepare(strain, state)
    K, G, H = params.bulk_modulus, params.shear_modulus, params.hardening_modulus
    dev, vol = deviator(eps - eps_p)
    s_trial = 2.0 * G * dev
    norm = frobenius_norm(s_trial)
    q_trial = math.sqrt(1.5) * norm
    yield_stress = math.sqrt(3.0) * params.undrained_strength + H * ebar
    f_trial = q_trial - yield_stress
    plastic = f_trial > RTOL * yield_stress
    q_safe = np.where(plastic, q_trial, 1.0)
    dgamma = np.where(plastic, f_trial / (3.0 * G + H), 0.0)
    unit = s_trial / np.where(norm > 0.0, norm, 1.0)[:, None, None]
    shrink = 3.0 * G * dgamma / q_safe  # 0 where elastic
    stress = s_trial * (1.0 - shrink)[:, None, None] + (K * vol)[:, None, None] * EYE3
    d_eps_p = (math.sqrt(1.5) * dgamma)[:, None, None] * unit
    n6 = mandel(unit)
    b = np.where(plastic, 6.0 * G * G * (dgamma / q_safe - 1.0 / (3.0 * G + H)), 0.0)
    tangent = (K * ONE_ONE6 + (2.0 * G * (1.0 - shrink))[:, None, None] * IDEV6
               + b[:, None, None] * n6[:, :, None] * n6[:, None, :])
    region = np.where(plastic, Region.SMOOTH, Region.ELASTIC)
    return finish(batch, stress, tangent, eps_p + d_eps_p, ebar + dgamma, region)


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
