"""The compiled Mohr–Coulomb return map at one plane-strain point, for the explicit route's
kernels (:mod:`~upliftlab.continuum.dynamics.kernels`, kind ``MOHR_COULOMB``).

The same closed-form principal-space return as the vectorised
:func:`~upliftlab.continuum.materials.principal.mohr_coulomb` (de Souza Neto, Perić & Owen,
*Computational Methods for Plasticity*, 2008, ch. 8), written for one point, without the
tangent (an explicit step needs none), so that a frictional soil runs in the compiled time loop
instead of the Python fallback.

Perfectly plastic and non-associated: yield f = (σ1 − σ3) + (σ1 + σ3) sin φ − 2c cos φ ≤ 0
(tension positive, σ1 ≥ σ2 ≥ σ3), plastic potential with sin ψ in place of sin φ. A planar
face (i, j) has the gradient a_ij = (1 + sin φ) e_i − (1 − sin φ) e_j and the flow vector
b_ij, the same with sin ψ; with the principal elasticity Ce = λ 𝟏𝟏ᵀ + 2G I the products are
a_pq·Ce·b_rs = 4λ sin φ sin ψ + 2G a_pq·b_rs. The trial stress returns

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

import numba as nb

__all__ = ["mohr_coulomb_point"]

_RTOL = 1e-12
_SQRT23 = math.sqrt(2.0 / 3.0)


@nb.njit(cache=True, inline="always")
def sorted_principal(sxx, syy, szz, sxy):
    """The plane-strain stress (xx, yy, zz, xy) in principal values, sorted: (``case``, s1 ≥
    s2 ≥ s3, cos 2α, sin 2α) with z at position ``case`` (0 first, 1 middle, 2 last) and α
    the in-plane principal axis; :func:`rotate_back` undoes it. Shared by the Tresca and
    Mohr–Coulomb returns."""
    centre = 0.5 * (sxx + syy)
    half = 0.5 * (sxx - syy)
    r = math.sqrt(half * half + sxy * sxy)
    if r > 0.0:
        cos2, sin2 = half / r, sxy / r
    else:
        cos2, sin2 = 1.0, 0.0
    pa, pb = centre + r, centre - r  # in-plane principal values, pa >= pb
    if szz >= pa:
        return 0, szz, pa, pb, cos2, sin2
    if szz >= pb:
        return 1, pa, szz, pb, cos2, sin2
    return 2, pa, pb, szz, cos2, sin2


@nb.njit(cache=True, inline="always")
def rotate_back(case, v1, v2, v3, cos2, sin2):
    """(xx, yy, zz, xy) of the principal values v1 ≥ v2 ≥ v3 (of the trial's order) with z at
    position ``case`` (0 first, 1 middle, 2 last) and the in-plane pair at the others, the
    in-plane principal axis at the angle whose (cos 2α, sin 2α) = (``cos2``, ``sin2``)."""
    if case == 0:
        vz, va, vb = v1, v2, v3
    elif case == 1:
        va, vz, vb = v1, v2, v3
    else:
        va, vb, vz = v1, v2, v3
    centre, radius = 0.5 * (va + vb), 0.5 * (va - vb)
    return centre + radius * cos2, centre - radius * cos2, vz, radius * sin2


@nb.njit(cache=True, inline="always")
def mohr_coulomb_point(sxx, syy, szz, sxy, lam, G, cohesion, sin_phi, cos_phi, sin_psi):
    """Mohr–Coulomb return of the plane-strain trial stress (xx, yy, zz, xy) (module
    docstring; λ, G in kPa, c in kPa) -> (stress xx, yy, zz, xy, plastic strain increment xx,
    yy, zz, xy (tensorial shear), Δε̄p)."""
    case, s1, s2, s3, cos2, sin2 = sorted_principal(sxx, syy, szz, sxy)
    k = 2.0 * cohesion * cos_phi
    f = (s1 - s3) + (s1 + s3) * sin_phi - k
    if not f > _RTOL * (k + max(abs(s1), abs(s3))):
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
            _SQRT23 * math.sqrt(e1 * e1 + e2 * e2 + e3 * e3))
