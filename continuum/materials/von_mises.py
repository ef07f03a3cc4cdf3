"""von Mises (J2) plasticity with linear isotropic hardening, for undrained clay: the record
:class:`VonMises`, its vectorised map :func:`von_mises` and its compiled point return
:func:`von_mises_point`.

q = √(3 J2) ≤ σ_y = √3 c_u + H ε̄p, radial return (exact for linear hardening) and its
consistent tangent (de Souza Neto, Perić & Owen, *Computational Methods for Plasticity*, 2008,
ch. 7). σ_y = √3 c_u is the plane-strain match: at the plane-strain limit s_zz = 0, so the
in-plane shear strength is c_u (Tresca's, in plane strain).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numba as nb
import numpy as np

from ... import checks
from .base import Elasticity, check_elastic, check_undrained
from .compiled import RTOL as POINT_RTOL
from .compiled import elastic_trial
from .returns import (EYE3, IDEV6, ONE_ONE6, RTOL, Region, State, deviator, finish,
                      frobenius_norm, mandel, prepare)
from .undrained import Undrained, check_gradient

__all__ = ["VonMises", "VonMisesConstants", "von_mises", "von_mises_point"]

_SQRT32 = math.sqrt(1.5)


def von_mises(strain, state: State | None, params: VonMises):
    """von Mises with linear isotropic hardening: radial return (exact for linear hardening) and
    its consistent tangent (de Souza Neto et al. 2008, ch. 7)."""
    eps, eps_p, ebar, batch = prepare(strain, state)
    K, G, H = params.bulk_modulus, params.shear_modulus, params.hardening_modulus
    dev, vol = deviator(eps - eps_p)
    s_trial = 2.0 * G * dev
    norm = frobenius_norm(s_trial)
    q_trial = math.sqrt(1.5) * norm
    yield_stress = math.sqrt(3.0) * params.strength(batch) + H * ebar
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


@nb.njit(cache=True, inline="always")
def von_mises_point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain=0.0):
    """The radial return at one point (:mod:`.compiled`) with c_u + ``gain`` (kPa: the
    point's k z, :mod:`.undrained`), the same closed form as :func:`von_mises`."""
    lam, G = constants.lame, constants.shear_modulus
    exx, eyy, ezz, exy, tr, sxx, syy, szz, sxy = elastic_trial(
        lam, G, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy)
    mean = tr / 3.0
    dxx, dyy, dzz = 2.0 * G * (exx - mean), 2.0 * G * (eyy - mean), 2.0 * G * (ezz - mean)
    norm = math.sqrt(dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * sxy * sxy)
    q = _SQRT32 * norm
    H = constants.hardening_modulus
    sy = math.sqrt(3.0) * (constants.undrained_strength + gain) + H * ebar
    f = q - sy
    if not f > POINT_RTOL * sy:
        return sxx, syy, szz, sxy, 0.0, 0.0, 0.0, 0.0, 0.0
    dgamma = f / (3.0 * G + H)
    keep = 1.0 - 3.0 * G * dgamma / q
    K = lam + 2.0 * G / 3.0
    p = K * tr
    scale = _SQRT32 * dgamma / norm
    return (dxx * keep + p, dyy * keep + p, dzz * keep + p, sxy * keep,
            scale * dxx, scale * dyy, scale * dzz, scale * sxy, dgamma)


class VonMisesConstants(NamedTuple):
    """What :func:`von_mises_point` reads: λ, G, c_u (kPa) at the surface and H (kPa)
    (``graded``: the point return takes the point's strength gain)."""

    lame: float
    shear_modulus: float
    undrained_strength: float
    hardening_modulus: float
    point = von_mises_point
    graded = True


@dataclass(frozen=True)
class VonMises(Undrained, Elasticity):
    """von Mises (J2) plasticity for undrained clay: q = √(3 J2) ≤ σ_y = √3 c_u + H ε̄p.

    σ_y = √3 c_u is the plane-strain match: at the plane-strain limit s_zz = 0, so the in-plane
    shear strength is c_u (Tresca's, in plane strain). H is dσ_y/dε̄p with ε̄p = ∫√(2/3)‖dεp‖;
    in plane-strain simple shear τ = c_u + H γp/3. c_u = ``undrained_strength`` +
    ``undrained_strength_gradient`` × depth (:mod:`.undrained`).
    """

    youngs_modulus: float
    poisson_ratio: float
    undrained_strength: float
    hardening_modulus: float = 0.0
    undrained_strength_gradient: float = 0.0
    depth: np.ndarray | None = field(default=None, repr=False, compare=False)
    name = "von_mises"
    update = staticmethod(von_mises)
    Constants = VonMisesConstants

    def __post_init__(self):
        check_elastic("VonMises.", self.youngs_modulus, self.poisson_ratio)
        check_undrained("VonMises.", "von_mises", self.undrained_strength)
        checks.nonnegative("VonMises.hardening_modulus", self.hardening_modulus)
        check_gradient("VonMises.", self.undrained_strength_gradient)

    @classmethod
    def from_soil(cls, soil):
        check_undrained("soil.", cls.name, soil.undrained_strength)
        return cls(youngs_modulus=float(soil.youngs_modulus),
                   poisson_ratio=float(soil.poisson_ratio),
                   undrained_strength=float(soil.undrained_strength),
                   hardening_modulus=float(soil.hardening_modulus),
                   undrained_strength_gradient=float(soil.undrained_strength_gradient))
