"""The soil's initial state: the geostatic stress, and the elastic law it and the footing's
stiffness use.

:func:`geostatic` uses the K0 procedure by default: σ_yy = ρ g y (y ≤ 0), σ_xx = σ_zz = K0 σ_yy,
σ_xy = 0 (:func:`~upliftlab.continuum.model.default_k0`). On a flat surface with roller sides
this is in exact equilibrium with the soil's weight, so the displacements start at zero.
``method="elastic"`` instead solves one elastic gravity step (soil alone, no footing) and keeps
its stress, resetting the displacement to zero; under roller sides it gives K0 = ν/(1 − ν),
which the tests use to cross-check the two routes. The stress enters the material as an
eigenstrain C⁻¹σ, so that the return map sees the total stress.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse.linalg import splu

from ... import checks
from ...checks import InputError
from .. import assembly
from ..materials import Elastic, Region, plane_strain, plane_strain_tangent
from .newton import ContinuumState, start_state

__all__ = ["geostatic", "k0_stress", "elastic_gravity_stress", "elastic_law", "elastic_tangent",
           "compliance"]


def k0_stress(model) -> np.ndarray:
    """The K0 stress (3, 3, nelems, nqp) at the quadrature points (module docstring)."""
    y = model.disc.qp_coordinates[1]
    vertical = model.soil.density * model.gravity * np.minimum(y, 0.0)
    stress = np.zeros((3, 3) + y.shape)
    stress[0, 0] = stress[2, 2] = model.k0 * vertical
    stress[1, 1] = vertical
    return stress


def elastic_gravity_stress(model) -> np.ndarray:
    """The stress (3, 3, nelems, nqp) of one elastic gravity step: the soil alone (free surface,
    roller sides, fixed bottom) under its weight."""
    D = plane_strain_tangent(elastic_tangent(model))
    K = assembly.stiffness(model.disc, D)
    free = np.setdiff1d(np.arange(model.disc.ndofs), model.blocks.fixed)
    u = np.zeros(model.disc.ndofs)
    u[free] = splu(K[free][:, free].tocsc()).solve(model.body_force[free])
    strain = plane_strain(assembly.strain_tensor(assembly.strain(model.disc, u)))
    return elastic_law(model)(strain)[0]


def elastic_law(model) -> Elastic:
    """The soil's elasticity (E, ν) as a material."""
    return Elastic(model.soil.youngs_modulus, model.soil.poisson_ratio)


def elastic_tangent(model) -> np.ndarray:
    """The 6×6 elastic tangent of the soil."""
    return elastic_law(model)(np.zeros((3, 3, 1)))[1][..., 0]


def compliance(model, stress: np.ndarray) -> np.ndarray:
    """Elastic strain C⁻¹σ of a stress field."""
    E, nu = model.soil.youngs_modulus, model.soil.poisson_ratio
    trace = np.einsum("ii...->...", stress)
    eye = np.eye(3).reshape(3, 3, *([1] * trace.ndim))
    return ((1 + nu) * stress - nu * trace * eye) / E


def geostatic(model, method: str = "k0") -> ContinuumState:
    """The initial state: geostatic stress (``k0`` or ``elastic``, module docstring), zero
    displacement, the footing resting on the surface with no load.

    Raises :class:`InputError` if the geostatic stress violates the yield criterion somewhere.
    """
    checks.one_of("geostatic method", method, ("k0", "elastic"))
    if model.soil.density == 0.0:
        return start_state(model, None, None)
    stress = k0_stress(model) if method == "k0" else elastic_gravity_stress(model)
    eigenstrain = compliance(model, stress)
    _, _, trial = model.material(eigenstrain, model.initial_material_state())
    plastic = np.asarray(trial.region) != Region.ELASTIC
    if plastic.any():
        depth = -model.disc.qp_coordinates[1][plastic]
        field = f"soil.k0 = {model.k0:g}" if method == "k0" else "geostatic method = 'elastic'"
        raise InputError(f"{field}: the geostatic stress violates the yield criterion of "
                         f"soil.model = {model.soil.model!r} at depths {depth.min():.3g} to "
                         f"{depth.max():.3g}; choose a K0 inside the yield surface")
    return start_state(model, stress, eigenstrain)


