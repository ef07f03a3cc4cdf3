"""Linear isotropic elasticity: the record :class:`Elastic`, its vectorised map
:func:`linear_elastic` and its compiled point return :func:`elastic_point`.

σ = λ tr(ε − εp) 𝟏 + 2G (ε − εp), with εp the state's plastic strain (normally zero).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numba as nb
import numpy as np

from .base import Elasticity, check_elastic
from .compiled import elastic_trial
from .returns import State, elastic_mandel, elastic_stress, finish, prepare

__all__ = ["Elastic", "ElasticConstants", "linear_elastic", "elastic_point"]


def linear_elastic(strain, state: State | None, params: Elastic):
    """Hooke's law σ = λ tr(εe) 𝟏 + 2G εe with εe = ε − εp (εp of ``state``, normally zero)."""
    eps, eps_p, ebar, batch = prepare(strain, state)
    stress = elastic_stress(eps - eps_p, params)
    tangent = np.broadcast_to(elastic_mandel(params), (len(eps), 6, 6))
    return finish(batch, stress, tangent, eps_p.copy(), ebar.copy(),
                  np.zeros(len(eps), dtype=np.int8))


@nb.njit(cache=True, inline="always")
def elastic_point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar):
    """Hooke's law at one point (:mod:`.compiled`): the trial stress, no plastic increment."""
    _, _, _, _, _, sxx, syy, szz, sxy = elastic_trial(
        constants.lame, constants.shear_modulus, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy)
    return sxx, syy, szz, sxy, 0.0, 0.0, 0.0, 0.0, 0.0


class ElasticConstants(NamedTuple):
    """What :func:`elastic_point` reads: λ and G (kPa)."""

    lame: float
    shear_modulus: float
    point = elastic_point


@dataclass(frozen=True)
class Elastic(Elasticity):
    """Linear isotropic elasticity: E > 0, −1 < ν < 0.5."""

    youngs_modulus: float
    poisson_ratio: float
    name = "elastic"
    update = staticmethod(linear_elastic)
    Constants = ElasticConstants
    linear = True

    def __post_init__(self):
        check_elastic("Elastic.", self.youngs_modulus, self.poisson_ratio)
