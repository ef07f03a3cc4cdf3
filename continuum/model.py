"""The continuum model of a scene: soil mesh, discretisation, material, footing and the DOF
blocks of the Newton solver.

Boundary conditions (statics): the bottom is fixed (a rigid base: the box bottom, or the rigid
base under ``soil.layer_depth``), the sides are rollers (ux = 0). The footing's contact DOFs c
(see :class:`~upliftlab.continuum.footing.Footing`) are condensed; every other unconstrained DOF
is interior (i).

Every input is checked before any mesh is built: each error is an :class:`InputError` naming the
field, its value and the valid range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import skfem
from scipy import sparse
from scipy.sparse.linalg import splu

from .. import checks
from ..checks import InputError
from ..meshes import BOUNDARIES, SoilMesh, from_options
from ..scenes import ELEMENTS, ContinuumOptions, Scene, Soil
from . import assembly
from .footing import Footing, Interface, footing_on
from .materials import (DruckerPrager, Elastic, MohrCoulomb, State, material_from_soil,
                        plane_strain, plane_strain_stress, plane_strain_tangent)

__all__ = ["ContinuumModel", "Blocks", "Condensation", "Response", "build_model", "make_model",
           "default_k0", "validate", "make_blocks", "node_groups"]


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
    if soil.model in ("tresca", "von_mises") and soil.undrained_strength is not None:
        checks.positive("soil.undrained_strength", soil.undrained_strength)
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
    if soil.model == "elastic":
        return soil.poisson_ratio / (1.0 - soil.poisson_ratio)
    if soil.model in ("tresca", "von_mises"):
        return 1.0
    return 1.0 - math.sin(math.radians(soil.friction_angle))


# ---------------------------------------------------------------------------------------------
# DOF blocks and condensation
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class _Gather:
    """A sub-matrix of the full CSR pattern: ``take`` indexes the full data array."""

    take: np.ndarray
    indices: np.ndarray
    indptr: np.ndarray
    shape: tuple[int, int]

    def matrix(self, data: np.ndarray) -> sparse.csc_matrix:
        return sparse.csc_matrix((data[self.take], self.indices, self.indptr), shape=self.shape)


def _gather(marked: sparse.csr_matrix, dofs: np.ndarray) -> _Gather:
    """Where the block (dofs, dofs) of a matrix lives in its CSR data, as a CSC matrix, from
    ``marked`` whose data are 1, 2, …, nnz (never zero, so slicing keeps every entry)."""
    sub = marked[dofs][:, dofs].tocsc()
    sub.sort_indices()
    return _Gather(take=sub.data.astype(np.int64) - 1, indices=sub.indices.copy(),
                   indptr=sub.indptr.copy(), shape=sub.shape)


def fill_reducing_order(pattern: assembly.Pattern, dofs: np.ndarray,
                        groups: np.ndarray | None = None) -> np.ndarray:
    """``dofs`` reordered to keep the fill of a factorisation of their block small: SuperLU's
    minimum degree on AᵀA + A, computed once on the graph of the DOF ``groups`` (the DOFs
    sharing a node: one group per node, so the graph is a quarter of the matrix's size) and
    expanded to the DOFs, each group's DOFs kept together in their given order."""
    dofs = np.asarray(dofs)
    if dofs.size < 3:
        return dofs
    groups = np.arange(pattern.size) if groups is None else np.asarray(groups)
    labels, local = np.unique(groups[dofs], return_inverse=True)
    Q = sparse.csr_matrix((np.ones(dofs.size), (np.arange(dofs.size), local)),
                          shape=(dofs.size, labels.size))
    A = pattern.matrix(np.ones(pattern.nnz))[dofs][:, dofs]
    graph = (Q.T @ A @ Q).tocsr()
    graph.data[:] = -1.0
    degree = np.diff(graph.indptr).astype(float)
    graph = (graph + sparse.diags(2.0 * degree + 1.0)).tocsc()  # diagonally dominant: no pivots
    lu = splu(graph, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options=dict(SymmetricMode=True))
    rank = np.argsort(lu.perm_c)  # elimination position -> group
    position = np.empty(labels.size, dtype=np.int64)
    position[rank] = np.arange(labels.size)
    return dofs[np.argsort(position[local], kind="stable")]


@dataclass(frozen=True, eq=False)
class Blocks:
    """Interior (i), contact (c) and fixed DOFs, and a gather from the full CSR data array into
    the free block F = [[K_ii, K_ic], [K_ci, K_cc]] (CSC, for the factorisation). ``interior``
    is in fill-reducing order (:func:`fill_reducing_order`) and the contact DOFs come last, so
    that the trailing block of F's LU factors is the Schur complement on the contact DOFs."""

    interior: np.ndarray
    contact: np.ndarray
    fixed: np.ndarray
    free: _Gather = field(repr=False)
    contact_diagonal: np.ndarray = field(repr=False)

    def matrix(self, data: np.ndarray) -> sparse.csc_matrix:
        """F of the full matrix with CSR ``data``."""
        return self.free.matrix(data)


def make_blocks(pattern: assembly.Pattern, interior, contact, fixed, groups=None) -> Blocks:
    """The :class:`Blocks` of ``pattern`` with these ``interior``, ``contact`` and ``fixed``
    DOFs; the interior in a fill-reducing order (node ``groups`` kept together)."""
    interior = fill_reducing_order(pattern, interior, groups)
    marked = pattern.matrix(np.arange(1.0, pattern.nnz + 1.0))
    free = _gather(marked, np.concatenate((interior, contact)))
    return Blocks(interior=interior, contact=contact, fixed=fixed, free=free,
                  contact_diagonal=_diagonal_positions(free, interior.size))


def _diagonal_positions(gather: _Gather, start: int) -> np.ndarray:
    """Positions in the CSC data of the diagonal entries (j, j), j >= ``start``."""
    positions = []
    for j in range(start, gather.shape[1]):
        lo, hi = gather.indptr[j], gather.indptr[j + 1]
        positions.append(lo + np.searchsorted(gather.indices[lo:hi], j))
    return np.asarray(positions, dtype=np.int64)


def node_groups(basis: skfem.CellBasis) -> np.ndarray:
    """Group label of each DOF of a vector ``basis``: the DOFs at one location share it."""
    _, groups = np.unique(np.round(basis.doflocs.T, 12), axis=0, return_inverse=True)
    return groups.ravel()


@dataclass(frozen=True, eq=False)
class Condensation:
    """A tangent condensed onto the contact DOFs: S = K_cc − K_ci K_ii⁻¹ K_ic.

    The factorisation is of F_σ, F with ``shift`` σ added to the contact diagonal, and
    ``solve`` is its F_σ⁻¹ on free vectors (interior then contact). Its Schur complement
    S_σ = S + σ I (``S_shifted``) is the trailing block of the LU factors (no solves), and it
    stays well conditioned when S itself becomes singular at collapse (the footing's vertical
    stiffness vanishes), so that r = S_σ z_c keeps its precision. The shift changes neither
    K_ii⁻¹ nor X, and S = S_σ − σ I.

    ``reused``: the condensation serves many Newton iterations (elastic soil, a frozen tangent):
    X = K_ii⁻¹ K_ic is then formed once (m solves) and every recovery is a product. Otherwise
    each recovery costs one solve."""

    solve: object
    S_shifted: np.ndarray
    shift: float
    interior: int
    reused: bool = False

    @cached_property
    def S(self) -> np.ndarray:
        """K_cc − K_ci K_ii⁻¹ K_ic (m, m)."""
        return self.S_shifted - self.shift * np.eye(self.S_shifted.shape[0])

    def condense(self, R_i: np.ndarray, R_c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(z, r): z = F_σ⁻¹ R and the condensed residual r = R_c − K_ci K_ii⁻¹ R_i = S_σ z_c."""
        z = self.solve(np.concatenate((R_i, R_c)))
        return z, self.S_shifted @ z[self.interior:]

    def interior_increment(self, z: np.ndarray, duc: np.ndarray) -> np.ndarray:
        """Δu_i = −K_ii⁻¹ (R_i + K_ic Δu_c) from the ``z`` of :meth:`condense`: the first
        block row of F z = R gives K_ii⁻¹ R_i = z_i + X z_c."""
        return -z[:self.interior] - self.times_x(z[self.interior:] + duc)

    def times_x(self, w: np.ndarray) -> np.ndarray:
        """X w = K_ii⁻¹ K_ic w: from X if formed, else one solve, F_σ⁻¹ [0; S_σ w] =
        [−X w; w]."""
        if self.reused or "X" in self.__dict__:
            return self.X @ w
        rhs = np.concatenate((np.zeros(self.interior), self.S_shifted @ w))
        return -self.solve(rhs)[:self.interior]

    @cached_property
    def X(self) -> np.ndarray:
        """K_ii⁻¹ K_ic (n_i, m), from F_σ⁻¹ [0; S_σ] = [−X; I]."""
        m = self.S_shifted.shape[0]
        rhs = np.zeros((self.interior + m, m), order="F")
        rhs[self.interior:] = self.S_shifted
        return -self.solve(rhs)[:self.interior]


def condensation(blocks: Blocks, data: np.ndarray, symmetric: bool,
                 reused: bool = False, single: bool = False) -> Condensation:
    """Factorise F of the matrix with CSR ``data`` once and condense it onto the contact DOFs.

    The fill-reducing order of :class:`Blocks` is kept (no column permutation) and pivots stay
    on the diagonal (a non-symmetric tangent may pivot with threshold 0.1). The contact
    diagonal is shifted by σ = the mean |K_cc| diagonal (:class:`Condensation`). S_σ is then
    L_cc U_cc; if pivoting moved a contact row, it is recovered as ((F_σ⁻¹)_cc)⁻¹ instead.

    ``single`` factorises in single precision: half the bytes of every back-substitution
    (timed in ``benchmarks/CONTINUUM_DESIGN.md``), for an *iteration matrix* only
    (modified Newton), whose residuals stay double; its relative error (about 1e-3 on the
    static tangent) is far below the elastic-for-plastic mismatch such a matrix already has."""
    F = blocks.matrix(data)
    shift = float(np.mean(np.abs(F.data[blocks.contact_diagonal])))
    F.data[blocks.contact_diagonal] += shift
    if single:
        F = F.astype(np.float32)
    lu = splu(F, permc_spec="NATURAL", diag_pivot_thresh=0.0 if symmetric else 0.1,
              options=dict(SymmetricMode=True))
    ni, n = blocks.interior.size, F.shape[0]
    trailing = np.arange(ni, n)
    solve = _single_solve(lu) if single else lu.solve
    if np.array_equal(lu.perm_r[ni:], trailing) and np.array_equal(lu.perm_c[ni:], trailing):
        S = (lu.L[ni:, ni:].astype(float) @ lu.U[ni:, ni:].astype(float)).toarray()
    else:
        unit = np.zeros((n, n - ni), order="F")
        unit[ni:] = np.eye(n - ni)
        S = np.linalg.inv(solve(unit)[ni:])
    return Condensation(solve=solve, S_shifted=S, shift=shift, interior=ni, reused=reused)


def _single_solve(lu):
    """F⁻¹ b (double in, double out) with single-precision factors ``lu``."""
    def solve(b: np.ndarray) -> np.ndarray:
        return lu.solve(np.asarray(b, dtype=np.float32)).astype(float)
    return solve


# ---------------------------------------------------------------------------------------------
# The model
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Response:
    """The soil's response to a displacement ``u`` from a converged material ``state``:
    ``stress`` (3, 3, nelems, nqp), plane ``tangent`` (3, 3, nelems, nqp), the ``material``
    state it would commit, and the out-of-balance force ``residual`` = f_int − f_body (ndofs)."""

    stress: np.ndarray
    tangent: np.ndarray
    material: State
    residual: np.ndarray


@dataclass(frozen=True, eq=False)
class ContinuumModel:
    """A plane-strain soil domain under a rigid footing (build it with :func:`build_model` or
    :func:`make_model`).

    ``mesh`` (the linear skfem mesh with its named boundaries), ``mesh_parameters`` (what
    built it, for provenance), ``disc`` (B-matrices and pattern),
    ``material`` (callable record of :mod:`~upliftlab.continuum.materials`), ``footing``,
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
        return isinstance(self.material, Elastic)

    @property
    def symmetric(self) -> bool:
        """True unless the flow rule is non-associated (ψ < φ)."""
        m = self.material
        return not (isinstance(m, (MohrCoulomb, DruckerPrager))
                    and m.dilation_angle < m.friction_angle)

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

    def condense(self, tangent: np.ndarray, extra: np.ndarray | None = None) -> Condensation:
        """The :class:`Condensation` of a plane tangent plus an ``extra`` matrix given by its
        CSR data in the model's pattern. For elastic soil the tangent is constant and the
        condensation is computed once per ``extra`` (cached)."""
        if not self.linear:
            return self._condense(tangent, extra)
        key = None if extra is None else id(extra)
        cached = self._cache.get(key)
        if cached is None or cached[0] is not extra:
            if len(self._cache) > 4:
                self._cache.clear()
            D = plane_strain_tangent(self.material(np.zeros((3, 3, 1)))[1])[..., 0]
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
        mesh = from_options(footing_width, options, layer_depth=soil.layer_depth)
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
    return ContinuumModel(soil=soil, options=options, mesh=skmesh, mesh_parameters=parameters,
                          disc=disc, material=material_from_soil(soil), footing=footing,
                          blocks=make_blocks(disc.pattern, interior, contact, fixed,
                                         node_groups(disc.basis)),
                          body_force=body, gravity=gravity, k0=default_k0(soil), scene=scene)


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
