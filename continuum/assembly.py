"""Vectorised plane-strain assembly on scikit-fem bases.

The soil's tangent changes at every Newton iteration, so the stiffness is not assembled through
``skfem.BilinearForm`` but as one ``np.einsum`` of Bᵀ D B over (element, quadrature point),
scattered into a CSR pattern that is built once per mesh, so each assembly is one product and one
scatter.

Conventions (per unit out-of-plane length):

- DOFs are those of ``skfem.ElementVector(element)``: ``u^1`` = ux, ``u^2`` = uy.
- Strains and stresses at quadrature points are plane vectors ``(3, nelems, nqp)`` in the order
  (xx, yy, xy). Strains carry the **engineering** shear γ_xy = ∂ux/∂y + ∂uy/∂x, stresses the
  tensorial σ_xy, so that the 3×3 tangent D of
  :func:`~upliftlab.continuum.materials.plane_strain_tangent` gives dσ = D dε and the
  stiffness is ∫ Bᵀ D B.
- ``intorder`` is explicit (:data:`DEFAULT_INTORDER`). Q2 defaults to 2×2 Gauss points: reduced
  integration, which keeps the element free of volumetric locking under plastic flow.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import skfem
from scipy import sparse

from ..checks import InputError

__all__ = ["DEFAULT_INTORDER", "ELEMENT_TYPES", "Pattern", "Discretisation", "discretise",
           "strain", "strain_tensor", "stiffness", "internal_force", "body_force",
           "element_name"]

#: Quadrature order per element: P1 3 points (degree 1 is exact), P2 3 points (exact for an
#: affine stiffness), Q1 2×2 (full), Q2 2×2 (reduced; full would be 3×3).
DEFAULT_INTORDER = {"P1": 1, "P2": 2, "Q1": 2, "Q2": 2}

#: Element name -> (skfem mesh type, skfem scalar element type).
ELEMENT_TYPES = {
    "P1": (skfem.MeshTri1, skfem.ElementTriP1),
    "P2": (skfem.MeshTri1, skfem.ElementTriP2),
    "Q1": (skfem.MeshQuad1, skfem.ElementQuad1),
    "Q2": (skfem.MeshQuad1, skfem.ElementQuad2),
}


@dataclass(frozen=True, eq=False)
class Pattern:
    """A CSR sparsity pattern and where each element-matrix entry lands in its data array.

    ``scatter[k]`` is the data index of entry k of the element matrices flattened in the order
    (element, row, column).
    """

    indptr: np.ndarray
    indices: np.ndarray
    scatter: np.ndarray
    size: int

    @property
    def nnz(self) -> int:
        return self.indices.size

    def data(self, element_matrices: np.ndarray) -> np.ndarray:
        """Sum element matrices ``(nelems, nloc, nloc)`` into the CSR data array."""
        return np.bincount(self.scatter, weights=element_matrices.ravel(), minlength=self.nnz)

    def matrix(self, data: np.ndarray) -> sparse.csr_matrix:
        """The CSR matrix with this pattern and ``data`` (not copied)."""
        return sparse.csr_matrix((data, self.indices, self.indptr), shape=(self.size,) * 2)

    def gather(self, matrix) -> np.ndarray:
        """The data array, in this pattern, of a sparse ``matrix`` on the same DOFs (e.g. a
        mass or boundary-dashpot matrix assembled by scikit-fem). Entries outside the pattern
        are refused."""
        matrix = sparse.csr_matrix(matrix)
        rows = np.repeat(np.arange(self.size), np.diff(self.indptr))
        data = np.asarray(matrix[rows, self.indices]).ravel()
        if abs(matrix - self.matrix(data)).max() > 0.0:
            raise InputError("matrix: has entries outside the sparsity pattern of the basis")
        return data


def _pattern(dofs: np.ndarray, size: int) -> Pattern:
    """The CSR pattern of element DOF tables ``dofs`` (nloc, nelems), rows sorted."""
    nloc = dofs.shape[0]
    rows = np.repeat(dofs.T, nloc, axis=1).ravel()
    cols = np.tile(dofs.T, (1, nloc)).ravel()
    keys, scatter = np.unique(rows.astype(np.int64) * size + cols, return_inverse=True)
    counts = np.bincount(keys // size, minlength=size)
    indptr = np.concatenate(([0], np.cumsum(counts)))
    return Pattern(indptr=indptr, indices=(keys % size).astype(np.int32), scatter=scatter.ravel(),
                   size=size)


@dataclass(frozen=True, eq=False)
class Discretisation:
    """A vector basis with its B-matrices at the quadrature points and its CSR pattern.

    ``B`` (3, nloc, nelems, nqp): rows (∂ux/∂x, ∂uy/∂y, ∂ux/∂y + ∂uy/∂x) of each local basis
    function; ``dx`` (nelems, nqp): quadrature weights times Jacobians (area); ``dofs``
    (nloc, nelems): global DOF of each local function. ``gradient`` (3·nelems·nqp, ndofs) is B
    as one sparse matrix (strains of a DOF vector by one product) and ``divergence`` its
    transpose (CSR), which sums Bᵀ σ into nodal forces.
    """

    basis: skfem.CellBasis
    element: str
    intorder: int
    B: np.ndarray
    dx: np.ndarray
    dofs: np.ndarray
    pattern: Pattern
    gradient: sparse.csr_matrix = field(repr=False)
    divergence: sparse.csr_matrix = field(repr=False)

    @property
    def ndofs(self) -> int:
        return self.basis.N

    @property
    def qp_shape(self) -> tuple[int, int]:
        """(nelems, nqp): the batch shape of quadrature-point fields."""
        return self.dx.shape

    @property
    def qp_coordinates(self) -> np.ndarray:
        """Global (x, y) of every quadrature point, (2, nelems, nqp)."""
        return np.asarray(self.basis.mapping.F(self.basis.X))


def element_name(mesh: skfem.Mesh, element: str) -> str:
    """``element`` validated against the mesh type (P* on triangles, Q* on quads)."""
    if element not in ELEMENT_TYPES:
        raise InputError(f"element = {element!r}: must be one of "
                         f"{', '.join(map(repr, ELEMENT_TYPES))}")
    mesh_type = ELEMENT_TYPES[element][0]
    if type(mesh) is not mesh_type:
        raise InputError(f"element = {element!r}: needs a {mesh_type.__name__} mesh, "
                         f"got {type(mesh).__name__}")
    return element


def discretise(mesh: skfem.Mesh, element: str, intorder: int | None = None) -> Discretisation:
    """The :class:`Discretisation` of ``element`` (P1, P2, Q1, Q2) on a linear skfem mesh.

    ``intorder`` defaults to :data:`DEFAULT_INTORDER` (Q2: 2×2 reduced integration).
    """
    element = element_name(mesh, element)
    intorder = DEFAULT_INTORDER[element] if intorder is None else intorder
    if isinstance(intorder, bool) or not isinstance(intorder, int) or not 1 <= intorder <= 10:
        raise InputError(f"intorder = {intorder!r}: valid range is an integer in [1, 10]")
    basis = skfem.Basis(mesh, skfem.ElementVector(ELEMENT_TYPES[element][1]()), intorder=intorder)
    B = np.stack([_b_rows(phi[0].grad) for phi in basis.basis], axis=1)
    dofs = np.asarray(basis.element_dofs)
    gradient = _gradient(B, dofs, basis.N)
    return Discretisation(basis=basis, element=element, intorder=intorder, B=B,
                          dx=np.asarray(basis.dx), dofs=dofs, pattern=_pattern(dofs, basis.N),
                          gradient=gradient, divergence=gradient.T.tocsr())


def _gradient(B: np.ndarray, dofs: np.ndarray, ndofs: int) -> sparse.csr_matrix:
    """B (3, nloc, nelems, nqp) as a sparse matrix: row (a, e, p), column dofs[i, e]."""
    ncomp, nloc, nelems, nqp = B.shape
    rows = np.broadcast_to(np.arange(ncomp * nelems * nqp).reshape(ncomp, 1, nelems, nqp),
                           B.shape)
    cols = np.broadcast_to(dofs[None, :, :, None], B.shape)
    return sparse.csr_matrix((B.ravel(), (rows.ravel(), cols.ravel())),
                             shape=(ncomp * nelems * nqp, ndofs))


def _b_rows(grad: np.ndarray) -> np.ndarray:
    """(εxx, εyy, γxy) of one vector basis function from its gradient (2, 2, nelems, nqp)."""
    return np.stack((grad[0, 0], grad[1, 1], grad[0, 1] + grad[1, 0]))


def strain(disc: Discretisation, u: np.ndarray) -> np.ndarray:
    """Plane strain (εxx, εyy, γxy) of the DOF vector ``u`` at the quadrature points."""
    return (disc.gradient @ u).reshape(3, *disc.dx.shape)


def strain_tensor(eps: np.ndarray) -> np.ndarray:
    """The 2×2 tensor (2, 2, …) of plane strains (εxx, εyy, γxy) (3, …)."""
    half = 0.5 * eps[2]
    return np.array([[eps[0], half], [half, eps[1]]])


def stiffness(disc: Discretisation, D: np.ndarray) -> sparse.csr_matrix:
    """∫ Bᵀ D B with the plane tangent ``D`` (3, 3, nelems, nqp) or one constant (3, 3)."""
    D = np.asarray(D, dtype=float)
    if D.ndim == 2:
        DB = np.einsum("ab,bjep->ajep", D, disc.B, optimize=True)
    else:
        DB = np.einsum("abep,bjep->ajep", D, disc.B, optimize=True)
    Ke = np.einsum("aiep,ajep->eij", disc.B, DB * disc.dx, optimize=True)
    return disc.pattern.matrix(disc.pattern.data(Ke))


def internal_force(disc: Discretisation, stress: np.ndarray) -> np.ndarray:
    """∫ Bᵀ σ for the plane stress (σxx, σyy, σxy) ``(3, nelems, nqp)``."""
    return disc.divergence @ (stress * disc.dx).ravel()


def body_force(disc: Discretisation, force_density) -> np.ndarray:
    """∫ Nᵀ b for a constant body force ``(bx, by)`` (force per volume)."""
    b = np.asarray(force_density, dtype=float)
    form = skfem.LinearForm(lambda v, w: b[0] * v[0] + b[1] * v[1])
    return form.assemble(disc.basis)
