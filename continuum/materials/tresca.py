"""Tresca plasticity (perfectly plastic), for undrained clay: the record :class:`Tresca`, its
vectorised map :func:`tresca` and its compiled point return :func:`tresca_point`.

σ1 − σ3 ≤ 2 c_u, a multi-surface return in principal space: the main plane (SMOOTH), the
triaxial-compression edge σ1 = σ2 (EDGE_COMPRESSION) or the triaxial-extension edge σ2 = σ3
(EDGE_EXTENSION); Mohr–Coulomb with φ = ψ = 0 and c = c_u (:mod:`.principal`). In plane
strain the principal directions are the in-plane pair and z, so the point return rotates back
in the xy plane.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numba as nb
import numpy as np

from .base import Elasticity, check_elastic, check_undrained
from .compiled import RTOL, SQRT23, elastic_trial, rotate_back, sorted_principal
from .principal import principal_return
from .returns import State
from .undrained import Undrained, check_gradient

__all__ = ["Tresca", "TrescaConstants", "tresca", "tresca_point"]


def tresca(strain, state: State | None, params: Tresca):
    """Tresca (perfectly plastic): principal-space return to the main plane or an edge, spectral
    consistent tangent. Mohr–Coulomb with φ = ψ = 0 and c = c_u (at each point's depth:
    :mod:`.undrained`)."""
    return principal_return(strain, state, params, 0.0, 1.0, 0.0,
                            params.strength(np.shape(strain)[2:]))


@nb.njit(cache=True, inline="always")
def _principal_tresca(sxx, syy, szz, sxy, k):
    """Tresca return of the trial stress with σ1 − σ3 ≤ ``k`` = 2 c_u; the stress (xx, yy, zz,
    xy). Main plane: σ1 and σ3 move by f/2; an edge: two planes, closed form."""
    case, s1, s2, s3, cos2, sin2 = sorted_principal(sxx, syy, szz, sxy)
    f = (s1 - s3) - k
    if not f > RTOL * (k + max(abs(s1), abs(s3))):
        return sxx, syy, szz, sxy
    n1, n2, n3 = s1 - 0.5 * f, s2, s3 + 0.5 * f
    if not (n1 >= n2 and n2 >= n3):
        if s1 - 2.0 * s2 + s3 > 0.0:  # extension edge: s2 = s3
            f1, f2 = s1 - s3 - k, s1 - s2 - k
            n1 = s1 - (f1 + f2) / 3.0
            n2 = s2 + (2.0 * f2 - f1) / 3.0
            n3 = s3 + (2.0 * f1 - f2) / 3.0
            n2 = n3 = 0.5 * (n2 + n3)
        else:  # compression edge: s1 = s2
            f1, f2 = s1 - s3 - k, s2 - s3 - k
            n1 = s1 - (2.0 * f1 - f2) / 3.0
            n2 = s2 - (2.0 * f2 - f1) / 3.0
            n3 = s3 + (f1 + f2) / 3.0
            n1 = n2 = 0.5 * (n1 + n2)
    return rotate_back(case, n1, n2, n3, cos2, sin2)


@nb.njit(cache=True, inline="always")
def tresca_point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar, gain=0.0):
    """The Tresca return at one point (:mod:`.compiled`) with c_u + ``gain`` (kPa: the
    point's k z, :mod:`.undrained`); the plastic strain increment is (σ_trial − σ)/(2G),
    deviatoric (Tresca's flow is isochoric)."""
    G = constants.shear_modulus
    _, _, _, _, _, sxx, syy, szz, sxy = elastic_trial(
        constants.lame, G, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy)
    nxx, nyy, nzz, nxy = _principal_tresca(sxx, syy, szz, sxy,
                                           2.0 * (constants.undrained_strength + gain))
    a, b, c, d = (sxx - nxx) / (2.0 * G), (syy - nyy) / (2.0 * G), \
        (szz - nzz) / (2.0 * G), (sxy - nxy) / (2.0 * G)
    dbar = SQRT23 * math.sqrt(a * a + b * b + c * c + 2.0 * d * d)
    return nxx, nyy, nzz, nxy, a, b, c, d, dbar


class TrescaConstants(NamedTuple):
    """What :func:`tresca_point` reads: λ, G and c_u (kPa) at the surface (``graded``: the
    point return takes the point's strength gain)."""

    lame: float
    shear_modulus: float
    undrained_strength: float
    point = tresca_point
    graded = True


@dataclass(frozen=True)
class Tresca(Undrained, Elasticity):
    """Tresca plasticity (perfectly plastic): σ1 − σ3 ≤ 2 c_u, c_u = ``undrained_strength`` +
    ``undrained_strength_gradient`` × depth (:mod:`.undrained`; ``depth`` set by
    :meth:`~.undrained.Undrained.at_points`)."""

    youngs_modulus: float
    poisson_ratio: float
    undrained_strength: float
    undrained_strength_gradient: float = 0.0
    depth: np.ndarray | None = field(default=None, repr=False, compare=False)
    name = "tresca"
    update = staticmethod(tresca)
    Constants = TrescaConstants

    def __post_init__(self):
        check_elastic("Tresca.", self.youngs_modulus, self.poisson_ratio)
        check_undrained("Tresca.", "tresca", self.undrained_strength)
        check_gradient("Tresca.", self.undrained_strength_gradient)

    @classmethod
    def from_soil(cls, soil):
        check_undrained("soil.", cls.name, soil.undrained_strength)
        return cls(youngs_modulus=float(soil.youngs_modulus),
                   poisson_ratio=float(soil.poisson_ratio),
                   undrained_strength=float(soil.undrained_strength),
                   undrained_strength_gradient=float(soil.undrained_strength_gradient))
