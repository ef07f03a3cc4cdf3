"""The continuum model of a scene: soil mesh, discretisation, material, footing and the DOF
blocks of the Newton solver.

Boundary conditions (statics): the bottom is fixed (a rigid base: the box bottom, or the rigid
base under ``soil.layer_depth``), the sides are rollers (ux = 0). The footing's contact DOFs c
(see :class:`~upliftlab.continuum.contact.footing.Footing`) are condensed; every other
unconstrained DOF
is interior (i).

Every input is checked before any mesh is built: each error is an :class:`InputError` naming the
field, its value and the valid range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import skfem

from .. import checks
from ..checks import InputError
from ..meshes import BOUNDARIES, SoilMesh, from_options
from ..scenes import ELEMENTS, ContinuumOptions, Scene, Soil
from . import assembly, setup_cache
from .condensation import (Blocks, Condensation, condensation, fill_reducing_order,  # noqa: F401
                           make_blocks, node_groups)
from .contact.footing import Footing, Interface, footing_on
from .materials import (State, material_from_soil, plane_strain, plane_strain_stress,
                        plane_strain_tangent)

__all__ = ["ContinuumModel", "Blocks", "Condensation", "Response", "build_model", "make_model",
           "default_k0", "validate", "make_blocks", "node_groups", "evaluated",
           "depth_below_surface"]


# ---------------------------------------------------------------------------------------------
# Validation (before any work)
# ---------------------------------------------------------------------------------------------


def validate(soil: Soil, options: ContinuumOptions, footing_width: float) -> None:
    """Refuse a soil, mesh options or footing that make no sense (InputError naming the field,
    the value and the valid range)."""
    checks.positive("foundation.half_width", 0.5 * footing_width)
    checks.one_of("continuum.element", options.element, ELEMENTS)
    checks.positive("soil.youngs_modulus", soil.youngs_modulus)
    nu = checks.finite("soil.poisson_ratio", soil.poisson_ratio)
    if not -1.0 < nu < 0.5:
        raise InputError(f"soil.poisson_ratio = {nu:g}: valid range is (-1, 0.5) with the "
                         f"displacement element {options.element} (ν = 0.5 is incompressible "
                         "and locks every displacement element)")
    checks.nonnegative("soil.density", soil.density)
    if soil.undrained and soil.undrained_strength is not None:
        checks.positive("soil.undrained_strength", soil.undrained_strength)
    checks.nonnegative("soil.undrained_strength_gradient", soil.undrained_strength_gradient)
    checks.in_range("soil.friction_angle", soil.friction_angle, 0.0, 60.0, high_open=True)
    if soil.k0 is not None:
        checks.in_range("soil.k0", soil.k0, 0.0, 10.0, low_open=True)
    if not options.domain_width > 1.0:
        raise InputError(f"continuum.domain_width = {options.domain_width:g}: the footing "
                         f"(B = {footing_width:g}) must be narrower than the domain; valid range "
                         "is (1, 1e4] footing widths")
    checks.in_range("continuum.domain_depth", options.domain_depth, 0.0, 1e4, low_open=True)
    if soil.layer_depth is not None:
        checks.positive("soil.layer_depth", soil.layer_depth)
    Interface(soil.interface, soil.interface_friction)
    material_from_soil(soil)  # names soil.* fields on anything else


def default_k0(soil: Soil) -> float:
    """K0 = σh/σv (total stress) of the geostatic stress when ``soil.k0`` is not given:
    ν/(1 − ν) for elastic soil (what an elastic gravity step under roller sides gives),
    1 for undrained Tresca/von Mises (isotropic total stress: gravity uses none of c_u),
    1 − sin φ (Jaky) for Mohr–Coulomb/Drucker–Prager."""
    if soil.k0 is not None:
        return float(soil.k0)
    if soil.strength is None:
        return soil.poisson_ratio / (1.0 - soil.poisson_ratio)
    if soil.undrained:
        return 1.0
    return 1.0 - math.sin(math.radians(soil.friction_angle))


# ---------------------------------------------------------------------------------------------
# The model
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Response:
    """The soil's response to a displacement ``u`` from a converged material ``state``:
    ``stress`` (3, 3, nelems, nqp), the plane consistent ``tangent`` (3, 3, nelems, nqp), the
    ``material`` state it would commit, and the out-of-balance force ``residual`` =
    f_int − f_body (ndofs).

    ``lazy_tangent`` is the tangent, or a function of no arguments that computes it: a
    response for an iteration with a frozen matrix
    (:mod:`~upliftlab.continuum.dynamics.kernel_response`)
    computes it only if asked. :attr:`tangent` always gives the array; a solver that may not
    need it passes ``lazy_tangent`` on (:func:`evaluated` turns either into the array)."""

    stress: np.ndarray
    lazy_tangent: object
    material: State
    residual: np.ndarray

    @property
    def tangent(self) -> np.ndarray:
        """The plane consistent tangent (3, 3, nelems, nqp), computed on first use."""
        tangent = evaluated(self.lazy_tangent)
        object.__setattr__(self, "lazy_tangent", tangent)
        return tangent


def evaluated(tangent):
    """A tangent given as an array or as a function that computes it (``lazy_tangent``), as
    the array (None stays None)."""
    return tangent() if callable(tangent) else tangent


@dataclass(frozen=True, eq=False)
class ContinuumModel:
    """A plane-strain soil domain under a rigid footing (build it with :func:`build_model` or
    :func:`make_model`).

    ``mesh`` (the linear skfem mesh with its named boundaries), ``mesh_parameters`` (what
    built it, for provenance), ``disc`` (B-matrices and pattern),
    ``material`` (callable record of :mod:`~upliftlab.continuum.materials`, at the quadrature
    points' depths: :meth:`~upliftlab.continuum.materials.Elasticity.at_points`), ``footing``,
    ``blocks``, ``body_force`` (the soil's weight as nodal forces), ``gravity`` g, ``k0``.
    """

    soil: Soil
    options: ContinuumOptions
    mesh: skfem.Mesh
    mesh_parameters: dict
    disc: assembly.Discretisation
    material: object
    footing: Footing
    blocks: Blocks
    body_force: np.ndarray
    gravity: float
    k0: float
    scene: Scene | None = None
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def width(self) -> float:
        """Footing width B (length)."""
        return self.footing.width

    @property
    def linear(self) -> bool:
        """True for elastic soil: one tangent, factorised once."""
        return self.material.linear

    @property
    def symmetric(self) -> bool:
        """True unless the flow rule is non-associated (ψ < φ)."""
        return self.material.symmetric

    @property
    def dofs(self) -> int:
        """Unconstrained soil DOFs (interior + contact)."""
        return self.blocks.interior.size + self.blocks.contact.size

    def respond(self, u: np.ndarray, state: State, eigenstrain: np.ndarray | None) -> Response:
        """Material update at every quadrature point for the total strain ε(u) + ``eigenstrain``
        (the geostatic stress enters as the eigenstrain C⁻¹σ0), from the converged ``state``."""
        strain = plane_strain(assembly.strain_tensor(assembly.strain(self.disc, u)))
        if eigenstrain is not None:
            strain = strain + eigenstrain
        stress, tangent, new_state = self.material(strain, state)
        residual = assembly.internal_force(self.disc, plane_strain_stress(stress)) \
            - self.body_force
        return Response(stress, plane_strain_tangent(tangent), new_state, residual)

    def condense(self, tangent, extra: np.ndarray | None = None) -> Condensation:
        """The :class:`Condensation` of a plane tangent (an array, or a function that computes
        it: :attr:`Response.lazy_tangent`) plus an ``extra`` matrix given by its CSR data in the
        model's pattern. For elastic soil the tangent is constant and the
        condensation is computed once per ``extra`` (cached)."""
        if not self.linear:
            return self._condense(evaluated(tangent), extra)
        key = None if extra is None else id(extra)
        cached = self._cache.get(key)
        if cached is None or cached[0] is not extra:
            if len(self._cache) > 4:
                self._cache.clear()
            elastic = self.material.at_surface()(np.zeros((3, 3, 1)))[1]
            D = plane_strain_tangent(elastic)[..., 0]
            cached = self._cache[key] = (extra, self._condense(D, extra, reused=True))
        return cached[1]

    def _condense(self, tangent: np.ndarray, extra: np.ndarray | None,
                  reused: bool = False, single: bool = False) -> Condensation:
        data = assembly.stiffness(self.disc, tangent).data
        if extra is not None:
            data = data + extra
        return condensation(self.blocks, data, self.symmetric, reused, single)

    def initial_material_state(self) -> State:
        return self.material.initial_state(self.disc.qp_shape)


def _dirichlet(basis: skfem.CellBasis) -> np.ndarray:
    """Fixed DOFs for statics: the bottom (both components), the sides (ux)."""
    return np.union1d(basis.get_dofs("bottom").all(), basis.get_dofs("sides").all("u^1"))


def _check_boundaries(mesh: skfem.Mesh) -> None:
    names = sorted((mesh.boundaries or {}).keys())
    missing = [name for name in BOUNDARIES if name not in names]
    if missing:
        raise InputError(f"mesh.boundaries = {names}: missing {', '.join(missing)}; a soil mesh "
                         f"needs the named boundaries {', '.join(BOUNDARIES)}")


def make_model(soil: Soil, footing_width: float, options: ContinuumOptions | None = None, *,
               gravity: float = 9.80665, mesh: SoilMesh | skfem.Mesh | None = None,
               scene: Scene | None = None) -> ContinuumModel:
    """A :class:`ContinuumModel` of ``soil`` under a footing of width ``footing_width``.

    ``options`` default to :class:`~upliftlab.scenes.ContinuumOptions` (10B × 10B, Q2, 16
    across). ``gravity`` g (length/s²) weighs soil of ``soil.density`` > 0. ``mesh`` replaces the
    generated mesh: a :class:`~upliftlab.meshes.SoilMesh`, or a linear skfem mesh (e.g. from
    :func:`~upliftlab.meshes.read_mesh`) used with ``options.element``; it must carry the named
    boundaries footing, surface, sides and bottom.
    """
    options = options or ContinuumOptions()
    validate(soil, options, footing_width)
    checks.nonnegative("gravity", gravity)
    if mesh is None:
        mesh = from_options(footing_width, options, layer_depth=soil.layer_depth,
                            lines=setup_cache.grid_lines(footing_width, options,
                                                         soil.layer_depth))
    if isinstance(mesh, SoilMesh):
        skmesh, element, parameters = mesh.mesh, mesh.element, mesh.parameters
    else:
        skmesh, element, parameters = mesh, options.element, {"element": options.element}
    _check_boundaries(skmesh)
    disc = assembly.discretise(skmesh, element, options.intorder)
    footing = footing_on(disc.basis, Interface(soil.interface, soil.interface_friction),
                         modulus=soil.youngs_modulus / (1.0 - soil.poisson_ratio ** 2))
    _check_footing(footing, footing_width, skmesh)
    fixed = _dirichlet(disc.basis)
    contact = footing.contact_dofs
    interior = np.setdiff1d(np.arange(disc.ndofs), np.union1d(fixed, contact))
    body = assembly.body_force(disc, (0.0, -soil.density * gravity))
    material = material_from_soil(soil).at_points(depth_below_surface(disc))
    return ContinuumModel(soil=soil, options=options, mesh=skmesh, mesh_parameters=parameters,
                          disc=disc, material=material, footing=footing,
                          blocks=make_blocks(disc.pattern, interior, contact, fixed,
                                         node_groups(disc.basis)),
                          body_force=body, gravity=gravity, k0=default_k0(soil), scene=scene)


def depth_below_surface(disc: assembly.Discretisation) -> np.ndarray:
    """The depth z (length) of every quadrature point below the ground surface, the footing's
    base level y = 0 of the mesh (nelems, nqp): −y, as the geostatic stress's."""
    return -np.minimum(disc.qp_coordinates[1], 0.0)


def _check_footing(footing: Footing, width: float, mesh: skfem.Mesh) -> None:
    if abs(footing.width - width) > 1e-9 * width or abs(footing.x[0] + 0.5 * width) > 1e-9 * width:
        raise InputError(f"foundation.half_width = {0.5 * width:g}: the mesh's footing boundary "
                         f"spans x = [{footing.x[0]:g}, {footing.x[-1]:g}]; valid is "
                         f"[-{0.5 * width:g}, {0.5 * width:g}]")
    span = float(np.ptp(mesh.p[0]))
    if not span > width:
        raise InputError(f"foundation.half_width = {0.5 * width:g}: the footing is as wide as "
                         f"or wider than the domain ({span:g}); valid range is < {0.5 * span:g}")


def build_model(scene: Scene, mesh: SoilMesh | None = None) -> ContinuumModel:
    """The :class:`ContinuumModel` of a scene with ``[soil]`` (and optionally ``[continuum]``)."""
    if scene.soil is None:
        raise InputError("soil is missing: the continuum model needs a [soil] table")
    return make_model(scene.soil, scene.foundation.width, scene.continuum or ContinuumOptions(),
                      gravity=scene.g, mesh=mesh, scene=scene)
