"""The one list of the continuum's soil models: :data:`SOIL_MODELS`, each model's parameter
record by its ``[soil] model`` name, and :func:`material_from_soil`, which builds a scene's.

A model is one module of this package (its record, its vectorised return map, its compiled point
return side by side; :mod:`.base`). Adding one touches its module, its lines here (its import
and its place in :data:`SOIL_MODELS`), its line in the scene's list of names
(:data:`upliftlab.scenes.soil.SOIL_MODELS`, which the core reads without the continuum
installed, with the strength the model reads from ``[soil]``) and its tests; a test holds this
list and the scene's to the same names, in the same order, and each record to its strength.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ... import checks
from ...checks import InputError
from .base import Elasticity, check_elastic
from .drucker_prager import DruckerPrager
from .elastic import Elastic
from .mohr_coulomb import MohrCoulomb
from .tresca import Tresca
from .von_mises import VonMises

if TYPE_CHECKING:  # pragma: no cover
    from ...scenes import Soil

__all__ = ["SOIL_MODELS", "material_from_soil", "hardening_models", "graded_models",
           "compiled_models"]

#: Every soil model's parameter record by its name, in the scene's order.
SOIL_MODELS: dict[str, type[Elasticity]] = {
    record.name: record for record in (Elastic, Tresca, VonMises, DruckerPrager, MohrCoulomb)}


def hardening_models() -> tuple[str, ...]:
    """The names of the models that read ``soil.hardening_modulus`` (a field of the record)."""
    return tuple(name for name, record in SOIL_MODELS.items()
                 if "hardening_modulus" in record.__dataclass_fields__)


def graded_models() -> tuple[str, ...]:
    """The names of the models whose undrained strength may grow with depth (a field
    ``undrained_strength_gradient`` of the record)."""
    return tuple(name for name, record in SOIL_MODELS.items()
                 if "undrained_strength_gradient" in record.__dataclass_fields__)


def compiled_models() -> tuple[str, ...]:
    """The names of the models with a compiled point return (the explicit route's compiled
    loop); the others run through their vectorised map."""
    return tuple(name for name, record in SOIL_MODELS.items() if record.Constants is not None)


def material_from_soil(soil: Soil) -> Elasticity:
    """The validated, callable parameter record for ``soil.model``.

    ``material(strain, state) -> (stress, tangent, new_state)``. Raises :class:`InputError`
    naming the ``soil.*`` field, its value and the valid range.
    """
    model = checks.one_of("soil.model", soil.model, SOIL_MODELS)
    check_elastic("soil.", soil.youngs_modulus, soil.poisson_ratio)
    hardening = checks.nonnegative("soil.hardening_modulus", soil.hardening_modulus)
    hardens = hardening_models()
    if hardening > 0.0 and model not in hardens:
        raise InputError(f"soil.hardening_modulus = {hardening:g}: model {model!r} is perfectly "
                         "plastic here, valid range is [0, 0] (hardening is implemented for "
                         f"{' and '.join(hardens)} only)")
    gradient = checks.nonnegative("soil.undrained_strength_gradient",
                                  getattr(soil, "undrained_strength_gradient", 0.0))
    graded = graded_models()
    if gradient > 0.0 and model not in graded:
        raise InputError(f"soil.undrained_strength_gradient = {gradient:g}: model {model!r} "
                         "reads no undrained strength, valid range is [0, 0] (a strength that "
                         f"grows with depth is implemented for {' and '.join(graded)} only)")
    return SOIL_MODELS[model].from_soil(soil)
