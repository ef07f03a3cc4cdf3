"""Mohr–Coulomb plasticity (perfectly plastic, non-associated): the record
:class:`MohrCoulomb`, its vectorised map :func:`mohr_coulomb` and its compiled point return
:func:`mohr_coulomb_point`.

Yield f = (σ1 − σ3) + (σ1 + σ3) sin φ − 2c cos φ ≤ 0 (tension positive, σ1 ≥ σ2 ≥ σ3), plastic
potential with sin ψ in place of sin φ (ψ ≤ φ). The vectorised map is the principal-space return
of :mod:`.principal` (de Souza Neto, Perić & Owen, *Computational Methods for Plasticity*, 2008,
ch. 8: main plane, either edge or the apex σ = c cot φ 𝟏, all closed form, spectral consistent
tangent).

The point return is the same closed form written for one plane-strain point, without the
tangent. A planar face (i, j) has the gradient a_ij = (1 + sin φ) e_i − (1 − sin φ) e_j and the
flow vector b_ij, the same with sin ψ; with the principal elasticity Ce = λ 𝟏𝟏ᵀ + 2G I the
products are a_pq·Ce·b_rs = 4λ sin φ sin ψ + 2G a_pq·b_rs. The trial stress returns

- to the main plane (0, 2), if the result keeps σ1 ≥ σ2 ≥ σ3: Δγ = f / (a·Ce·b);
- else to the edge of the main plane with (0, 1) (extension, σ2 = σ3) when
  (1 − sin ψ) σ1 − 2σ2 + (1 + sin ψ) σ3 > 0, else with (1, 2) (compression, σ1 = σ2): two
  multipliers from the symmetric 2×2 system; the two equal values are set to their mean, so
  that the tie is exact;
- else (the edge return gives σ1 < σ3, only for φ > 0) to the apex σ = c cos φ / sin φ 𝟏.

In plane strain (σxz = σyz = 0) the principal directions are the in-plane pair and z, so the
return rotates back in the xy plane. The plastic strain increment is Ce⁻¹(σ_trial − σ) in
principal space, rotated back; Δε̄p = √(2/3)‖Δεp‖. A point yields when
f > 1e-12 × (2c cos φ + max(|σ1|, |σ3|)), as in the vectorised map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numba as nb

from .base import Frictional
from .compiled import RTOL, SQRT23, elastic_trial, rotate_back, sorted_principal
from .principal import principal_return
from .returns import State

__all__ = ["MohrCoulomb", "MohrCoulombConstants", "mohr_coulomb", "mohr_coulomb_point"]


def mohr_coulomb(strain, state: State | None, params: MohrCoulomb):
    """Mohr–Coulomb (perfectly plastic, non-associated): principal-space return to the main
    plane, either edge or the apex (de Souza Neto et al. 2008, ch. 8), spectral consistent
    tangent."""
    return principal_return(strain, state, params, params.sin_phi, params.cos_phi,
                            params.sin_psi, params.cohesion)


@nb.njit(cache=True, inline="always")
def _principal_mohr_coulomb(sxx, syy, szz, sxy, lam, G, cohesion, sin_phi, cos_phi, sin_psi):
    """Mohr–Coulomb return of the plane-strain trial stress (xx, yy, zz, xy) (module
    docstring; λ, G and c in kPa) -> (stress xx, yy, zz, xy, plastic strain increment xx,
    yy, zz, xy (tensorial shear), Δε̄p)."""
    case, s1, s2, s3, cos2, sin2 = sorted_principal(sxx, syy, szz, sxy)
    k = 2.0 * cohesion * cos_phi
    f = (s1 - s3) + (s1 + s3) * sin_phi - k
    if not f > RTOL * (k + max(abs(s1), abs(s3))):
        return sxx, syy, szz, sxy, 0.0, 0.0, 0.0, 0.0, 0.0
    # Ce·b of a face: 2λ sin ψ on every component, plus 2G (1 + sin ψ) at its i and
    # −2G (1 − sin ψ) at its j
    common = 2.0 * lam * sin_psi
    up = common + 2.0 * G * (1.0 + sin_psi)
    down = common - 2.0 * G * (1.0 - sin_psi)
    friction = 4.0 * lam * sin_phi * sin_psi
    diagonal = friction + 4.0 * G * (1.0 + sin_phi * sin_psi)  # a_ij·Ce·b_ij
    dgamma = f / diagonal
    n1, n2, n3 = s1 - dgamma * up, s2 - dgamma * common, s3 - dgamma * down
    if not (n1 >= n2 and n2 >= n3):
        if (1.0 - sin_psi) * s1 - 2.0 * s2 + (1.0 + sin_psi) * s3 > 0.0:
            # extension edge: faces (0, 2) and (0, 1), σ2 = σ3
            f2 = (s1 - s2) + (s1 + s2) * sin_phi - k
            off = friction + 2.0 * G * (1.0 + sin_phi) * (1.0 + sin_psi)
            det = diagonal * diagonal - off * off
            g1 = (diagonal * f - off * f2) / det
            g2 = (diagonal * f2 - off * f) / det
            n1 = s1 - (g1 + g2) * up
            n2 = s2 - g1 * common - g2 * down
            n3 = s3 - g1 * down - g2 * common
            n2 = n3 = 0.5 * (n2 + n3)
        else:
            # compression edge: faces (0, 2) and (1, 2), σ1 = σ2
            f2 = (s2 - s3) + (s2 + s3) * sin_phi - k
            off = friction + 2.0 * G * (1.0 - sin_phi) * (1.0 - sin_psi)
            det = diagonal * diagonal - off * off
            g1 = (diagonal * f - off * f2) / det
            g2 = (diagonal * f2 - off * f) / det
            n1 = s1 - g1 * up - g2 * common
            n2 = s2 - g1 * common - g2 * up
            n3 = s3 - (g1 + g2) * down
            n1 = n2 = 0.5 * (n1 + n2)
        if not (n1 >= n3 or sin_phi == 0.0):  # beyond the edge: the apex
            n1 = n2 = n3 = cohesion * cos_phi / sin_phi
    d1, d2, d3 = s1 - n1, s2 - n2, s3 - n3
    shift = lam / (3.0 * lam + 2.0 * G) * (d1 + d2 + d3)
    e1, e2, e3 = (d1 - shift) / (2.0 * G), (d2 - shift) / (2.0 * G), (d3 - shift) / (2.0 * G)
    nxx, nyy, nzz, nxy = rotate_back(case, n1, n2, n3, cos2, sin2)
    pxx, pyy, pzz, pxy = rotate_back(case, e1, e2, e3, cos2, sin2)
    return (nxx, nyy, nzz, nxy, pxx, pyy, pzz, pxy,
            SQRT23 * math.sqrt(e1 * e1 + e2 * e2 + e3 * e3))


@nb.njit(cache=True, inline="always")
def mohr_coulomb_point(constants, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy, ebar):
    """The Mohr–Coulomb return at one point (:mod:`.compiled`; module docstring)."""
    lam, G = constants.lame, constants.shear_modulus
    _, _, _, _, _, sxx, syy, szz, sxy = elastic_trial(
        lam, G, exx, eyy, ezz, exy, pxx, pyy, pzz, pxy)
    return _principal_mohr_coulomb(sxx, syy, szz, sxy, lam, G, constants.cohesion,
                                   constants.sin_phi, constants.cos_phi, constants.sin_psi)


class MohrCoulombConstants(NamedTuple):
    """What :func:`mohr_coulomb_point` reads: λ, G, c (kPa), sin φ, cos φ and sin ψ."""

    lame: float
    shear_modulus: float
    cohesion: float
    sin_phi: float
    cos_phi: float
    sin_psi: float
    point = mohr_coulomb_point


@dataclass(frozen=True)
class MohrCoulomb(Frictional):
    """Mohr–Coulomb, perfectly plastic, non-associated (dilation angle ψ ≤ φ), angles in degrees.

    Yield (σ1 − σ3) + (σ1 + σ3) sin φ − 2 c cos φ ≤ 0, potential (σ1 − σ3) + (σ1 + σ3) sin ψ.
    """

    name = "mohr_coulomb"
    update = staticmethod(mohr_coulomb)
    Constants = MohrCoulombConstants
