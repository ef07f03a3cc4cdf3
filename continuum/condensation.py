"""The DOF blocks of the Newton solver and the condensation of the soil onto the footing's
contact DOFs.

The unconstrained DOFs split into the interior i (in a fill-reducing order, the nodes of a
group kept together) and the contact DOFs c last, so that one sparse LU of the free block F
gives both the Schur complement S = K_cc − K_ci K_ii⁻¹ K_ic (from the factors' last rows) and
the interior solves. :class:`Blocks` gathers a matrix's free block from its CSR data without
re-indexing; :func:`condensation` factorises it once and condenses it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import skfem
from scipy import sparse
from scipy.sparse.linalg import splu

from . import assembly

__all__ = ["Blocks", "Condensation", "make_blocks", "node_groups", "fill_reducing_order",
           "condensation"]


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
