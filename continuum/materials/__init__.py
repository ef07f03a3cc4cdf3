"""Soil constitutive models for the plane-strain continuum model, as pure functions, one module
per model, found through one registry (:data:`SOIL_MODELS`).

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

The models, one module each, with the return regions each handles (:class:`Region`):

- :mod:`.elastic` (:func:`linear_elastic`): isotropic Hooke's law.
- :mod:`.von_mises` (undrained clay): q ≤ σ_y = √3 c_u + H ε̄p (plane-strain match: in plane
  strain the limit shear stress is c_u), radial return (SMOOTH).
- :mod:`.tresca`: σ1 − σ3 ≤ 2 c_u, multi-surface return in principal space: main plane (SMOOTH),
  triaxial-compression edge σ1 = σ2 (EDGE_COMPRESSION), triaxial-extension edge σ2 = σ3
  (EDGE_EXTENSION); spectral consistent tangent.
- :mod:`.mohr_coulomb`: (σ1 − σ3) + (σ1 + σ3) sin φ ≤ 2c cos φ with plastic potential
  (σ1 − σ3) + (σ1 + σ3) sin ψ (ψ ≤ φ): main plane, both edges and the apex σ = c cot φ 𝟏 (APEX).
  The return mapping follows de Souza Neto, Perić & Owen, *Computational Methods for
  Plasticity* (2008), ch. 8 (perfect plasticity: every region is closed form).
- :mod:`.drucker_prager`: √J2 + η p ≤ ξ c, potential √J2 + η̄ p (p = tr σ / 3): return to the
  cone (SMOOTH) and to the apex p = c cot φ (APEX). **Plane-strain match** to Mohr–Coulomb (the
  natural one for strip footings), see :class:`DruckerPrager`: for ψ = φ it is the textbook
  η = 3 tan φ / √(9 + 12 tan²φ), ξ = 3 / √(9 + 12 tan²φ).

σ1 ≥ σ2 ≥ σ3 are the principal stresses (tension positive, so σ3 is the most compressive).
Hardening (``hardening_modulus`` H) is implemented for von Mises only; the other plastic models
are perfectly plastic. ``State.equivalent_plastic_strain`` is ε̄p = ∫ √(2/3) ‖dεp‖ for every model
(von Mises' hardening variable; a diagnostic for the others).

Each model's module holds, side by side, its frozen parameter record (validated on construction
and callable: ``material(strain, state) -> (stress, tangent, new_state)``), its vectorised
return map and, for the explicit route, its compiled point return with the constants it reads
(:mod:`.compiled`; Drucker–Prager has none and runs through its vectorised map). Use
:func:`material_from_soil` to turn a :class:`upliftlab.scenes.Soil` into its record.

Shared pieces: :mod:`.base` (the records' base and input checks), :mod:`.returns` (state,
regions, tensor layouts), :mod:`.principal` (the principal-space return of Tresca and
Mohr–Coulomb), :mod:`.undrained` (Tresca's and von Mises' strength, which may grow with depth,
c_u + k z), :mod:`.compiled` (the point returns' shared helpers and dispatch) and
:mod:`.registry` (:data:`SOIL_MODELS`). Every name is importable from here.
"""

from __future__ import annotations

from .base import Elasticity, Frictional, check_elastic, check_frictional, check_undrained
from .compiled import point_return
from .drucker_prager import DruckerPrager, drucker_prager
from .elastic import Elastic, linear_elastic
from .mohr_coulomb import MohrCoulomb, mohr_coulomb
from .registry import (SOIL_MODELS, compiled_models, graded_models, hardening_models,
                       material_from_soil)
from .returns import (VOIGT, Region, State, initial_state, plane_strain, plane_strain_stress,
                      plane_strain_tangent)
from .tresca import Tresca, tresca
from .undrained import Undrained
from .von_mises import VonMises, von_mises

__all__ = [
    "SOIL_MODELS",
    "compiled_models",
    "hardening_models",
    "graded_models",
    "material_from_soil",
    "point_return",
    "Region",
    "State",
    "initial_state",
    "Elasticity",
    "Frictional",
    "Undrained",
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
    "check_elastic",
    "check_undrained",
    "check_frictional",
    "plane_strain",
    "plane_strain_tangent",
    "plane_strain_stress",
    "VOIGT",
]
