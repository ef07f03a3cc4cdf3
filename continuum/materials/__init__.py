"""Soil constitutive models for the plane-strain continuum model, as pure functions.

Each model is one pure function ``update(strain, state, params) -> (stress, tangent, new_state)``
in the style of FElupe, evaluated at every quadrature point at once:

- ``strain``: the **total** small strain ε_{n+1}, a tensor of shape ``(3, 3, *batch)``
  (tensorial shear, ε_xy = γ_xy/2). It is symmetrised on entry. Plane strain is the special case
  ε_zz = ε_xz = ε_yz = 0 (:func:`plane_strain` embeds a 2×2 strain). ``batch`` is any shape,
  e.g. scikit-fem's ``(nelems, nqp)``.
- ``state``: the converged :class:`State` of step n (``None`` for a virgin material). It is never
  modified. Newton iterations call the update again with the new total strain and the *same* old
  state; only the converged ``new_state`` of a step is kept.
- ``stress``: σ_{n+1}, shape ``(3, 3, *batch)``. **Tension positive.**
- ``tangent``: the consistent (algorithmic) tangent dσ_{n+1}/dε_{n+1}, a 6×6 Voigt matrix per
  point, shape ``(6, 6, *batch)``, in the order (xx, yy, zz, xy, xz, yz), mapping **engineering**
  shear strains (γ_xy = 2ε_xy) to tensorial shear stresses (σ_xy):
  ``dσ_I = D[I, J] dε̂_J`` with ε̂ = (ε_xx, ε_yy, ε_zz, γ_xy, γ_xz, γ_yz).
  :func:`plane_strain_tangent` keeps rows and columns (xx, yy, xy): the 3×3 matrix D for the 2D
  B-matrix assembly Bᵀ D B with B rows (∂u/∂x, ∂v/∂y, ∂u/∂y + ∂v/∂x). The tangent is not
  symmetric for non-associated flow (ψ < φ).

The models, with the return regions each handles (:class:`Region`):

- :func:`linear_elastic`: isotropic Hooke's law.
- :func:`von_mises` (undrained clay): q ≤ σ_y = √3 c_u + H ε̄p (plane-strain match: in plane
  strain the limit shear stress is c_u), radial return (SMOOTH).
- :func:`tresca`: σ1 − σ3 ≤ 2 c_u, multi-surface return in principal space: main plane (SMOOTH),
  triaxial-compression edge σ1 = σ2 (EDGE_COMPRESSION), triaxial-extension edge σ2 = σ3
  (EDGE_EXTENSION); spectral consistent tangent.
- :func:`mohr_coulomb`: (σ1 − σ3) + (σ1 + σ3) sin φ ≤ 2c cos φ with plastic potential
  (σ1 − σ3) + (σ1 + σ3) sin ψ (ψ ≤ φ): main plane, both edges and the apex σ = c cot φ 𝟏 (APEX).
  The return mapping follows de Souza Neto, Perić & Owen, *Computational Methods for
  Plasticity* (2008), ch. 8 (perfect plasticity: every region is closed form).
- :func:`drucker_prager`: √J2 + η p ≤ ξ c, potential √J2 + η̄ p (p = tr σ / 3): return to the cone
  (SMOOTH) and to the apex p = c cot φ (APEX). **Plane-strain match** to Mohr–Coulomb (the natural
  one for strip footings), see :class:`DruckerPrager`: for ψ = φ it is the textbook
  η = 3 tan φ / √(9 + 12 tan²φ), ξ = 3 / √(9 + 12 tan²φ).

σ1 ≥ σ2 ≥ σ3 are the principal stresses (tension positive, so σ3 is the most compressive).
Hardening (``hardening_modulus`` H) is implemented for von Mises only; the other plastic models
are perfectly plastic. ``State.equivalent_plastic_strain`` is ε̄p = ∫ √(2/3) ‖dεp‖ for every model
(von Mises' hardening variable; a diagnostic for the others).

Use :func:`material_from_soil` to turn a :class:`upliftlab.scenes.Soil` into a callable,
validated parameter record: ``material(strain, state) -> (stress, tangent, new_state)``.

The pieces: :mod:`~upliftlab.continuum.materials.returns` (state, regions, tensor layouts),
:mod:`~upliftlab.continuum.materials.params` (the parameter records),
:mod:`~upliftlab.continuum.materials.smooth` (elastic, von Mises, Drucker–Prager) and
:mod:`~upliftlab.continuum.materials.principal` (Tresca, Mohr–Coulomb). Every name is importable
from here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ... import checks
from ...checks import InputError
from .params import (DruckerPrager, Elastic, MohrCoulomb, Tresca, VonMises, check_elastic,
                     check_frictional, check_undrained)
from .principal import mohr_coulomb, tresca
from .returns import (VOIGT, Region, State, initial_state, plane_strain, plane_strain_stress,
                      plane_strain_tangent)
from .smooth import drucker_prager, linear_elastic, von_mises

if TYPE_CHECKING:  # pragma: no cover
    from ...scenes import Soil

__all__ = [
    "Region",
    "State",
    "initial_state",
    "Elastic",
    "VonMises",
    "Tresca",
    "DruckerPrager",
    "MohrCoulomb",
    "linear_elastic",
    "von_mises",
    "tresca",
    "drucker_prager",
    "mohr_coulomb",
    "material_from_soil",
    "plane_strain",
    "plane_strain_tangent",
    "plane_strain_stress",
    "VOIGT",
]

Elastic.update = staticmethod(linear_elastic)
VonMises.update = staticmethod(von_mises)
Tresca.update = staticmethod(tresca)
DruckerPrager.update = staticmethod(drucker_prager)
MohrCoulomb.update = staticmethod(mohr_coulomb)


def material_from_soil(soil: Soil):
    """The validated, callable parameter record for ``soil.model``.

    ``material(strain, state) -> (stress, tangent, new_state)``. Raises :class:`InputError`
    naming the ``soil.*`` field, its value and the valid range.
    """
    model = checks.one_of("soil.model", soil.model,
                          ("elastic", "tresca", "von_mises", "drucker_prager", "mohr_coulomb"))
    check_elastic("soil.", soil.youngs_modulus, soil.poisson_ratio)
    hardening = checks.nonnegative("soil.hardening_modulus", soil.hardening_modulus)
    if hardening > 0.0 and model != "von_mises":
        raise InputError(f"soil.hardening_modulus = {hardening:g}: model {model!r} is perfectly "
                         "plastic here, valid range is [0, 0] (hardening is implemented for "
                         "von_mises only)")
    elastic = dict(youngs_modulus=float(soil.youngs_modulus),
                   poisson_ratio=float(soil.poisson_ratio))
    if model == "elastic":
        return Elastic(**elastic)
    if model in ("tresca", "von_mises"):
        check_undrained("soil.", model, soil.undrained_strength)
        if model == "tresca":
            return Tresca(**elastic, undrained_strength=float(soil.undrained_strength))
        return VonMises(**elastic, undrained_strength=float(soil.undrained_strength),
                        hardening_modulus=hardening)
    check_frictional("soil.", soil.cohesion, soil.friction_angle, soil.dilation_angle)
    cls = MohrCoulomb if model == "mohr_coulomb" else DruckerPrager
    return cls(**elastic, cohesion=float(soil.cohesion), friction_angle=float(soil.friction_angle),
               dilation_angle=float(soil.dilation_angle))

