"""Compiled kernels of the explicit dynamics: the soil's internal force with the return map,
evaluated element by element in parallel (numba ``prange``).

An explicit step needs the stress at every quadrature point for the current displacement and
the nodal forces ∫ Bᵀ σ; no tangent, no assembly, no solve. These kernels do that in one pass
over the elements (strain from the element's DOFs, return map, Bᵀ σ dx into an element force
array) and a second pass over the DOFs that sums the element forces (a gather through a
precomputed DOF → element-entry map, so that no two threads write one entry).

**Layout** (:func:`layout`). The vector basis of scikit-fem interleaves the components: local
function 2a is u_x of node a, 2a + 1 its u_y, with the same scalar shape function N_a. The
kernels take the scalar gradients ``dNdx``, ``dNdy`` (nel, nqp, nnode), the quadrature weights
``dx`` (nel, nqp) and the global DOFs (nel, nnode, 2), which are (2k, 2k + 1) for the node k.
:func:`layout` checks all this against the discretisation and refuses a basis without it.

**Soil models.** The return map at a quadrature point is the soil model's compiled point
return (:mod:`~upliftlab.continuum.materials.compiled`), found by the type of the constants the
kernels are given (the record's ``kernel_constants()``, a named tuple whose class names the
return): numba compiles and caches one element loop per soil model, with the model's return
inlined; a strength that grows with depth enters as a per-point gain (nel, nqp) added to the
constants' c_u (:mod:`~upliftlab.continuum.materials.undrained`). Each is the same return map
as the model's vectorised one (plane strain: the strain's zz
component is the geostatic eigenstrain's, xz = yz = 0), written for one point and without the
tangent; a model without one (its record's ``Constants`` None) does not run here.

Plastic strain is stored as (xx, yy, zz, xy) (tensorial shear), stress as (xx, yy, zz, xy).
A point yields when f > 1e-12 × (strength + stress scale), as in the vectorised maps.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ...checks import InputError
from ..materials.compiled import point_return

__all__ = ["Layout", "layout", "internal_force", "compiled_pair", "soil_predict",
           "viscous_pair", "viscous_force"]

#: Element blocks of the parallel loop (each thread takes whole blocks; a scratch array each).
_BLOCKS = 64
#: Floating-point licences of the element loop: fused multiply-add and reassociation of its sums
#: (so that they vectorise), but NaN and infinity keep their meaning.
_FAST = {"contract", "reassoc", "nsz", "arcp"}


class Layout:
    """The arrays the kernels read (module docstring): ``dNdx``, ``dNdy`` (nel, nqp, nnode),
    ``dx`` (nel, nqp), ``dofs`` (nel, nnode, 2), ``nodes`` (nel, nnode) = dofs // 2, and the
    gather map ``ptr``/``entries`` (for DOF d, the flat element-force entries
    ptr[d]:ptr[d+1])."""

    def __init__(self, dNdx, dNdy, dx, dofs, ptr, entries, ndofs):
        self.dNdx, self.dNdy, self.dx, self.dofs = dNdx, dNdy, dx, dofs
        self.nodes = np.ascontiguousarray(dofs[:, :, 0] // 2)
        self.ptr, self.entries, self.ndofs = ptr, entries, ndofs

    @property
    def shape(self) -> tuple[int, int, int]:
        """(nel, nqp, nnode)."""
        return self.dNdx.shape


def layout(disc) -> Layout:
    """The kernel :class:`Layout` of a :class:`~upliftlab.continuum.assembly.Discretisation`."""
    B, dofs = disc.B, disc.dofs
    nloc = B.shape[1]
    x, y = slice(0, nloc, 2), slice(1, nloc, 2)
    pairs = dofs[y] == dofs[x] + 1
    ok = (nloc % 2 == 0 and disc.ndofs % 2 == 0 and pairs.all() and not np.any(dofs[x] % 2)
          and not np.any(B[1, x]) and not np.any(B[0, y])
          and np.array_equal(B[0, x], B[2, y]) and np.array_equal(B[1, y], B[2, x]))
    if not ok:
        raise InputError(f"continuum.element = {disc.element!r}: its vector basis does not "
                         "interleave (u_x, u_y) per node as DOFs (2k, 2k + 1); the explicit "
                         "kernels need it")
    dNdx = np.ascontiguousarray(B[0, x].transpose(1, 2, 0))
    dNdy = np.ascontiguousarray(B[1, y].transpose(1, 2, 0))
    local = np.ascontiguousarray(dofs.T.reshape(dofs.shape[1], nloc // 2, 2))
    flat = local.ravel()
    order = np.argsort(flat, kind="stable")
    ptr = np.concatenate(([0], np.cumsum(np.bincount(flat, minlength=disc.ndofs))))
    return Layout(dNdx, dNdy, np.ascontiguousarray(disc.dx), local.astype(np.int64),
                  ptr.astype(np.int64), order.astype(np.int64), disc.ndofs)


# ---------------------------------------------------------------------------------------------
# The internal force
# ---------------------------------------------------------------------------------------------


@nb.njit(cache=True, inline="always")
def _element_values(e, values2, nodes, out, fe):
    """Element ``e``'s nodal values (nn, 2) of ``values2`` into ``out``; its forces zeroed."""
    for a in range(out.shape[0]):
        out[a, 0], out[a, 1] = values2[nodes[e, a], 0], values2[nodes[e, a], 1]
        fe[e, a, 0] = 0.0
        fe[e, a, 1] = 0.0


@nb.njit(cache=True, inline="always")
def _point_strain(e, p, dNdx, dNdy, ue):
    """(ε_xx, ε_yy, γ_xy) at point ``p`` of element ``e`` from its nodal values ``ue``."""
    exx = eyy = gxy = 0.0
    for a in range(ue.shape[0]):
        bx, by = dNdx[e, p, a], dNdy[e, p, a]
        exx += bx * ue[a, 0]
        eyy += by * ue[a, 1]
        gxy += by * ue[a, 0] + bx * ue[a, 1]
    return exx, eyy, gxy


@nb.njit(cache=True, inline="always")
def _add_point_force(e, p, dNdx, dNdy, sxx, syy, sxy, fe):
    """Bᵀ σ of point ``p`` (the stress already times its weight) added to element ``e``."""
    for a in range(fe.shape[1]):
        bx, by = dNdx[e, p, a], dNdy[e, p, a]
        fe[e, a, 0] += bx * sxx + by * sxy
        fe[e, a, 1] += by * syy + bx * sxy


@nb.njit(cache=True, fastmath=_FAST)
def _elements(lo, hi, u2, nodes, dNdx, dNdy, dx, eig, plastic, ebar, constants, gain, stress,
              fe):
    """Elements lo:hi of :func:`internal_force`."""
    nel, nqp, nn = dNdx.shape
    ue = np.empty((nn, 2))
    for e in range(lo, hi):
        _element_values(e, u2, nodes, ue, fe)
        for p in range(nqp):
            exx, eyy, gxy = _point_strain(e, p, dNdx, dNdy, ue)
            sxx, syy, szz, sxy, d0, d1, d2, d3, db = point_return(
                constants, exx + eig[e, p, 0], eyy + eig[e, p, 1], eig[e, p, 2],
                0.5 * gxy + eig[e, p, 3], plastic[e, p, 0], plastic[e, p, 1],
                plastic[e, p, 2], plastic[e, p, 3], ebar[e, p], gain[e, p])
            if db != 0.0:
                plastic[e, p, 0] += d0
                plastic[e, p, 1] += d1
                plastic[e, p, 2] += d2
                plastic[e, p, 3] += d3
                ebar[e, p] += db
            stress[e, p, 0], stress[e, p, 1] = sxx, syy
            stress[e, p, 2], stress[e, p, 3] = szz, sxy
            w = dx[e, p]
            _add_point_force(e, p, dNdx, dNdy, sxx * w, syy * w, sxy * w, fe)


@nb.njit(cache=True, parallel=True)
def _elements_parallel(u2, nodes, dNdx, dNdy, dx, eig, plastic, ebar, constants, gain, stress,
                       fe):
    nel = dNdx.shape[0]
    blocks = min(nel, _BLOCKS)
    for b in nb.prange(blocks):
        _elements(b * nel // blocks, (b + 1) * nel // blocks, u2, nodes, dNdx, dNdy, dx, eig,
                  plastic, ebar, constants, gain, stress, fe)


@nb.njit(cache=True)
def _elements_serial(u2, nodes, dNdx, dNdy, dx, eig, plastic, ebar, constants, gain, stress,
                     fe):
    _elements(0, dNdx.shape[0], u2, nodes, dNdx, dNdy, dx, eig, plastic, ebar, constants, gain,
              stress, fe)


@nb.njit(cache=True)
def _gather_nodes(fe, nodes, ptr, entries, out):
    """The serial sum of element forces (the node-wise scatter; ``ptr``, ``entries`` unused:
    the signature of :func:`_gather_parallel`)."""
    _gather_serial(fe, nodes, out.reshape(-1, 2))


@nb.njit(cache=True, parallel=True)
def _gather_parallel(fe, nodes, ptr, entries, out):
    """The sum of element forces split among the threads by DOF (``nodes`` unused)."""
    flat = fe.ravel()
    for d in nb.prange(out.size):
        total = 0.0
        for j in range(ptr[d], ptr[d + 1]):
            total += flat[entries[j]]
        out[d] = total


@nb.njit(cache=True)
def _gather_serial(fe, nodes, out2):
    out2[:] = 0.0
    nel, nn, _ = fe.shape
    for e in range(nel):
        for a in range(nn):
            k = nodes[e, a]
            out2[k, 0] += fe[e, a, 0]
            out2[k, 1] += fe[e, a, 1]


def internal_force(lay: Layout, u, eigenstrain, plastic, ebar, constants, gain, stress, work,
                   out, parallel: bool | None = None) -> np.ndarray:
    """∫ Bᵀ σ (ndofs) into ``out`` for the displacement ``u``: the return map of the soil model
    whose ``constants`` these are (its record's ``kernel_constants()``) at every quadrature
    point, with the point's strength ``gain`` (nel, nqp; the record's ``strength_gain``, zeros
    for a uniform soil), from the state (``plastic`` (nel, nqp, 4), ``ebar`` (nel, nqp)),
    which is **updated in place** (an explicit step commits every evaluation), the stress
    written to ``stress`` (nel, nqp, 4).
    ``eigenstrain`` (nel, nqp, 4) is added to the strain of u (the geostatic stress); ``work``
    (nel, nnode, 2) is scratch. With more than one numba thread (``numba.get_num_threads()``)
    the elements and the DOFs are split among the threads, unless ``parallel`` is False."""
    if parallel is None:
        parallel = nb.get_num_threads() > 1
    elements, gather = compiled_pair(parallel)
    elements(u.reshape(-1, 2), lay.nodes, lay.dNdx, lay.dNdy, lay.dx, eigenstrain, plastic, ebar,
             constants, gain, stress, work)
    gather(work, lay.nodes, lay.ptr, lay.entries, out)
    return out


@nb.njit(cache=True, fastmath=_FAST)
def _viscous(lo, hi, v2, nodes, dNdx, dNdy, dx, D, arm, decay, fe):
    """Elements lo:hi of :func:`viscous_pair`'s kernels: the arm's stress
    σ_m ← a σ_m + (1 − a) D ε̇ at each point, ∫ Bᵀ σ_m into ``fe``."""
    nel, nqp, nn = dNdx.shape
    ve = np.empty((nn, 2))
    d00, d01, d02, d10, d11, d12, d20, d21, d22 = (D[0, 0], D[0, 1], D[0, 2], D[1, 0], D[1, 1],
                                                   D[1, 2], D[2, 0], D[2, 1], D[2, 2])
    fresh = 1.0 - decay
    for e in range(lo, hi):
        _element_values(e, v2, nodes, ve, fe)
        for p in range(nqp):
            rxx, ryy, rxy = _point_strain(e, p, dNdx, dNdy, ve)
            sxx = decay * arm[e, p, 0] + fresh * (d00 * rxx + d01 * ryy + d02 * rxy)
            syy = decay * arm[e, p, 1] + fresh * (d10 * rxx + d11 * ryy + d12 * rxy)
            sxy = decay * arm[e, p, 2] + fresh * (d20 * rxx + d21 * ryy + d22 * rxy)
            arm[e, p, 0], arm[e, p, 1], arm[e, p, 2] = sxx, syy, sxy
            w = dx[e, p]
            _add_point_force(e, p, dNdx, dNdy, sxx * w, syy * w, sxy * w, fe)


@nb.njit(cache=True, parallel=True)
def _viscous_parallel(v2, nodes, dNdx, dNdy, dx, D, arm, decay, fe):
    nel = dNdx.shape[0]
    blocks = min(nel, _BLOCKS)
    for b in nb.prange(blocks):
        _viscous(b * nel // blocks, (b + 1) * nel // blocks, v2, nodes, dNdx, dNdy, dx, D, arm,
                 decay, fe)


@nb.njit(cache=True)
def _viscous_serial(v2, nodes, dNdx, dNdy, dx, D, arm, decay, fe):
    _viscous(0, dNdx.shape[0], v2, nodes, dNdx, dNdy, dx, D, arm, decay, fe)


def viscous_pair(parallel: bool):
    """The element kernel of a viscous stress through a Maxwell arm (the Rayleigh β K₀ v with
    D = β D₀, :mod:`~upliftlab.continuum.dynamics.rayleigh`), serial or parallel:
    ``kernel(v2, nodes, dNdx, dNdy, dx, D, arm, decay, fe)`` updates the arm's stress ``arm``
    (nel, nqp, 3) on (xx, yy, xy) to a σ_m + (1 − a) D ε̇(v), a = ``decay``, and writes
    ∫ Bᵀ σ_m dx per element into ``fe`` (nel, nnode, 2), D the (3, 3) plane tangent on
    (ε̇xx, ε̇yy, γ̇xy); the gather of :func:`compiled_pair` sums it. With a = 0 the
    Kelvin–Voigt stress D ε̇: the same numbers as (β K₀) v, element by element."""
    return _viscous_parallel if parallel else _viscous_serial


def viscous_force(lay: Layout, v, D, arm, decay: float, work, out,
                  parallel: bool | None = None) -> np.ndarray:
    """∫ Bᵀ σ_m (ndofs) into ``out`` after one update of the arm's stress ``arm`` by
    ``decay`` (:func:`viscous_pair`; ``work`` (nel, nnode, 2) scratch), split among the threads
    as :func:`internal_force`."""
    if parallel is None:
        parallel = nb.get_num_threads() > 1
    _, gather = compiled_pair(parallel)
    viscous_pair(parallel)(v.reshape(-1, 2), lay.nodes, lay.dNdx, lay.dNdy, lay.dx, D, arm,
                           float(decay), work)
    gather(work, lay.nodes, lay.ptr, lay.entries, out)
    return out


def compiled_pair(parallel: bool):
    """(element forces, gather) kernels, serial or parallel; both pairs share a signature, so
    that a caller compiled for one never compiles the other."""
    return (_elements_parallel, _gather_parallel) if parallel else \
        (_elements_serial, _gather_nodes)


# ---------------------------------------------------------------------------------------------
# The diagonal update of one central-difference step
# ---------------------------------------------------------------------------------------------


@nb.njit(cache=True)
def soil_predict(u, u_prev, v, fint, viscous, datum, keep, ground, incident, ag,
                 incident_velocity, mass, damping, dt, first, R_prev, F_prev, u_out, v_out):
    """One step of the soil without contact forces (:mod:`~upliftlab.continuum.dynamics.explicit`):
    R = f_int − datum, F = ground a_g + incident v_inc, v_out = v_{n+½}, u_out = u_{n+1};
    a held DOF (``keep`` 0) stays put. ``damping`` the diagonal dashpots (the boundaries' and
    the Rayleigh α M) at the mean of v_{n±½}; ``viscous`` a force at v_{n−½} (the Rayleigh
    β K₀ v, :mod:`~upliftlab.continuum.dynamics.rayleigh`; zeros without it). Returns the
    increments of the strain work ½(R_{n−1} + R_n)·Δu, the input ½(F_{n−1} + F_n)·Δu and the
    damping work (c v_{n−½} + viscous)·Δu over the last step (Δu = u_n − u_{n−1}; zero on the
    ``first`` step), and stores R and F in ``R_prev`` and ``F_prev`` for the next step."""
    strain = work = dissipated = 0.0
    half = 0.5 * dt
    for i in range(u.size):
        if keep[i] == 0.0:
            u_out[i], v_out[i], R_prev[i], F_prev[i] = u[i], 0.0, 0.0, 0.0
            continue
        R = fint[i] - datum[i]
        F = ground[i] * ag + incident[i] * incident_velocity
        if first:
            vs = v[i] + half * (F - R - viscous[i] - damping[i] * v[i]) / mass[i]
        else:
            du = u[i] - u_prev[i]
            strain += 0.5 * (R_prev[i] + R) * du
            work += 0.5 * (F_prev[i] + F) * du
            dissipated += damping[i] * v[i] * du
            dissipated += viscous[i] * du
            vs = ((mass[i] - half * damping[i]) * v[i] + dt * (F - R - viscous[i])) \
                / (mass[i] + half * damping[i])
        v_out[i] = vs
        u_out[i] = u[i] + dt * vs
        R_prev[i], F_prev[i] = R, F
    return strain, work, dissipated
