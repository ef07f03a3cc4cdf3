"""The rigid footing: its kinematics, its contact with the soil, and the contact solver.

**Kinematics.** The footing has three DOFs q = (u, v, θ) at the centre of its base (x = 0,
y = 0): u horizontal (+x), v vertical (up), θ positive when it moves the top of the structure by
+hθ. A base point at x moves by (u, v − x θ) (small rotation, base on y = 0): the right edge goes
down for θ > 0. The work-conjugate generalised force is (H, −N, M): H horizontal (+x), N the
vertical compression (downwards, positive), M the moment about the base centre, positive driving
+θ, which in equilibrium equals the soil's resisting moment Σ x_i P_i (right edge compressed).

**Contact.** Every soil DOF location on the footing base (mesh nodes and, for P2/Q2, facet
midpoints) is a contact node i at x_i. Its normal force P_i ≥ 0 (compression; the soil receives
−P_i in y), its gap g_i = (v − x_i θ) − uy_i ≥ 0, and P_i g_i = 0, solved exactly (no penalty).
Its pressure is p_i = P_i / w_i with w_i = ∫ φ_i ds the node's weight on the base (the nodal
force of a unit pressure). Tangentially the interface is frictionless (no tangential force),
Coulomb (|T_i| ≤ μ P_i; a slipping node's T_i opposes the soil's slip relative to the footing,
measured from the start of the step) or bonded (rough: no slip while in contact). Bonded is
Coulomb with μ = :data:`ROUGH_FRICTION` (1000): identical to a tie wherever |T| < 1000 P, and
solvable at the node where contact ends, where an infinite μ has no solution.

**Solver.** The soil's linearisation is condensed onto the contact DOFs c (a flexibility
formulation: only the contact DOFs enter the contact problem): f_c = r + S Δu_c, with S the Schur
complement of the current tangent and f_c the forces the footing applies to the soil.
:func:`solve_contact` then solves this small dense problem together with the footing's equilibrium
or prescribed motion and the contact conditions by a primal–dual active set (semismooth Newton on
the complementarity function P − c g): guess the closed/stick/slip sets, solve the linear system
they define, update the sets from the solution, and stop when they no longer change. Each solve is
exact for its sets, so the converged answer satisfies P ≥ 0, g ≥ 0, P g = 0 to round-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np
import skfem

from ...checks import InputError, nonnegative, one_of
from ...scenes import INTERFACES

__all__ = ["OPEN", "STICK", "SLIP_POSITIVE", "SLIP_NEGATIVE", "Interface", "Footing",
           "footing_on", "separation_fraction", "ContactProblem", "ContactSolution",
           "ContactError", "solve_contact"]

#: Relative round-off allowance of the contact conditions: P ≥ −tol and g ≥ −tol/c with
#: tol = RTOL_CONTACT × the largest contact force.
RTOL_CONTACT = 1e-9

#: Friction coefficient that stands for "bonded" (rough, tied while in contact). A tie with
#: μ = ∞ has no solution at a node where contact ends under plastic flow (sticking pulls it,
#: opening lets it penetrate); with this μ such a node slips with T = μP, P ≈ 0+, and every
#: node with |T| < 1000 P sticks exactly as a tie would.
ROUGH_FRICTION = 1e3

#: Contact status of a node: open (separated), closed and sticking (or closed, frictionless),
#: closed and slipping with the tangential force on the soil +μP or −μP.
OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = 0, 1, 2, 3


class ContactError(RuntimeError):
    """The contact problem of one Newton iteration has no solution (the footing lost all
    contact under a prescribed force) or its active set did not settle."""


@dataclass(frozen=True)
class Interface:
    """Tangential law of the footing–soil interface: ``frictionless``, ``bonded`` (rough: no
    slip while in contact) or ``coulomb`` with friction coefficient ``friction`` μ > 0. The
    normal law is always unilateral (tensionless)."""

    kind: str = "frictionless"
    friction: float = 0.0

    def __post_init__(self):
        one_of("soil.interface", self.kind, INTERFACES)
        nonnegative("soil.interface_friction", self.friction)
        if self.kind == "coulomb" and not self.friction > 0.0:
            raise InputError(f"soil.interface_friction = {self.friction:g}: a coulomb interface "
                             "needs a friction coefficient > 0 (use interface = 'frictionless' "
                             "for none)")

    @property
    def tangential(self) -> bool:
        """True if the interface carries tangential force (bonded or coulomb)."""
        return self.kind != "frictionless"

    @property
    def mu(self) -> float:
        """Friction coefficient of the contact solver: 0 frictionless, :data:`ROUGH_FRICTION`
        bonded, ``friction`` for coulomb."""
        return {"frictionless": 0.0, "bonded": ROUGH_FRICTION}.get(self.kind, self.friction)


@dataclass(frozen=True, eq=False)
class Footing:
    """The contact nodes of the footing base, sorted by x.

    ``x`` (length), soil DOFs ``ux`` and ``uy``, weights ``weight`` = ∫ φ_i ds (length; they
    sum to B), footing ``width`` B, the ``interface``, and the soil's plane-strain modulus
    ``modulus`` E* = E/(1 − ν²) (force/length²; locates the ends of contact patches). The
    contact DOFs c are ``uy`` then, for a tangential interface, ``ux``.
    """

    x: np.ndarray
    ux: np.ndarray
    uy: np.ndarray
    weight: np.ndarray
    width: float
    interface: Interface
    modulus: float = math.nan

    @property
    def nodes(self) -> int:
        return self.x.size

    @property
    def contact_dofs(self) -> np.ndarray:
        """Soil DOFs condensed for contact: ``uy`` (and ``ux`` if tangential)."""
        return np.concatenate((self.uy, self.ux)) if self.interface.tangential else self.uy

    @property
    def kinematics(self) -> np.ndarray:
        """L (m, 3): footing displacement at the contact DOFs per unit (u, v, θ)."""
        normal = np.column_stack((np.zeros(self.nodes), np.ones(self.nodes), -self.x))
        if not self.interface.tangential:
            return normal
        tangential = np.column_stack((np.ones(self.nodes), np.zeros((self.nodes, 2))))
        return np.vstack((normal, tangential))

    def gap(self, u: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Gap g_i = (v − x_i θ) − uy_i (length) of soil displacement ``u``, footing ``q``."""
        return (q[1] - self.x * q[2]) - u[self.uy]

    def slip(self, u: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Tangential displacement of the soil relative to the footing, ux_i − u (length)."""
        return u[self.ux] - q[0]

    def contact_length(self, closed: np.ndarray, pressure: np.ndarray | None = None,
                       gap: np.ndarray | None = None) -> float:
        """Length of the base in contact (length) of one state: :meth:`contact_lengths` of one
        row."""
        rows = [None if a is None else np.asarray(a)[None, :] for a in (pressure, gap)]
        return float(self.contact_lengths(np.asarray(closed)[None, :], *rows)[0])

    def contact_lengths(self, closed: np.ndarray, pressure: np.ndarray | None = None,
                        gap: np.ndarray | None = None) -> np.ndarray:
        """Length of the base in contact (length) of each row of ``closed`` (rows, nodes): the
        sum over the row's contact patches (runs of closed nodes) of the distance between their
        two ends. A patch ending at a footing edge ends there; elsewhere it ends at the
        separation point between its last closed node i and the first open one j,
        :func:`separation_fraction` of the way from x_i to x_j, interpolated from the closed
        node's ``pressure`` p_i and the open node's ``gap`` g_j (rows, nodes). Without
        ``pressure`` and ``gap`` each patch ends half-way (the midpoint rule: off by up to about
        one node spacing however fine the mesh). All rows at once: a dynamic run measures its
        recorded rows when it ends, not one by one."""
        closed = np.asarray(closed, dtype=bool)
        x, n = self.x, self.nodes
        before = np.zeros_like(closed)
        before[:, 1:] = closed[:, :-1]
        after = np.zeros_like(closed)
        after[:, :-1] = closed[:, 1:]
        row, starts = np.nonzero(closed & ~before)  # row-major: the k-th start and the
        ends = np.nonzero(closed & ~after)[1]  # k-th end bound one patch of one row
        left = np.where(starts == 0, x[0], x[np.maximum(starts, 1)])
        right = np.where(ends == n - 1, x[-1], x[np.minimum(ends, n - 2)])
        for inner, i, j, side in ((starts > 0, starts, starts - 1, left),
                                  (ends < n - 1, ends, ends + 1, right)):
            if not inner.any():
                continue
            r, i, j = row[inner], i[inner], j[inner]
            if pressure is None or gap is None:
                t = np.full(i.size, 0.5)
            else:
                t = separation_fraction(np.asarray(pressure)[r, i], np.asarray(gap)[r, j],
                                        np.abs(x[j] - x[i]), self.modulus)
            side[inner] = x[i] + t * (x[j] - x[i])
        return np.bincount(row, weights=right - left, minlength=closed.shape[0])


def separation_fraction(pressure, gap, spacing, modulus) -> np.ndarray:
    """Where contact ends between a closed node (``pressure`` p ≥ 0, force/length²) and the next
    open one (``gap`` g ≥ 0, length) a ``spacing`` h apart, as the fraction t = d/h of the way
    from the closed node, for soil of plane-strain modulus E* = ``modulus``.

    On the elastic half-plane the pressure vanishes at a smooth separation point as p = α√d at
    a distance d inside the contact, and the gap opens as g = (4α/(3E*)) e^{3/2} at a distance e
    outside (the surface displacement's second derivative is the Hilbert transform of p″,
    α/(E*√e)). With d = t h and e = (1 − t) h the two nodal values give
    (1 − t)^{3/2}/√t = 3E* g/(4 p h), monotonic in t ∈ [0, 1]: solved by bisection (60
    halvings, to the last bit), compiled (:func:`_fraction`): a dynamic run calls this on all
    its recorded rows at once. p = 0 puts the end at the closed node (t = 0), g = 0 at the open
    one (t = 1)."""
    p, g, h = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (pressure, gap, spacing)))
    out = np.empty(p.shape)
    _fractions(p.ravel(), g.ravel(), h.ravel(), float(modulus), out.reshape(-1))
    return out


@nb.njit(cache=True)
def _fractions(p, g, h, modulus, out):
    for i in range(p.size):
        out[i] = _fraction(p[i], g[i], h[i], modulus)


@nb.njit(cache=True)
def _fraction(p, g, h, modulus):
    """:func:`separation_fraction` at one pair of nodes: (1 − t)³ − r² t is decreasing on
    [0, 1], r = 3E* g/(4 p h)."""
    if not p > 0.0:
        return 0.0
    if not g > 0.0:
        return 1.0
    r = 3.0 * modulus * g / (4.0 * p * h)
    r2 = r * r
    lo, hi = 0.0, 1.0
    for _ in range(60):
        t = 0.5 * (lo + hi)
        s = 1.0 - t
        if s * s * s - r2 * t > 0.0:
            lo = t
        else:
            hi = t
    return 0.5 * (lo + hi)


def footing_on(basis: skfem.CellBasis, interface: Interface,
               modulus: float = math.nan) -> Footing:
    """The :class:`Footing` on the ``footing`` boundary of a two-component vector ``basis``,
    on soil of plane-strain modulus ``modulus`` E*."""
    from ...meshes import footing_dofs

    dofs = footing_dofs(basis)
    facets = basis.mesh.boundaries["footing"]
    order = 2 * max(basis.elem.elem.maxdeg, 1)
    facet_basis = skfem.FacetBasis(basis.mesh, basis.elem, facets=facets, intorder=order)
    weight = skfem.LinearForm(lambda v, w: v[1]).assemble(facet_basis)[dofs.uy]
    return Footing(x=dofs.x, ux=dofs.ux, uy=dofs.uy, weight=weight,
                   width=float(dofs.x[-1] - dofs.x[0]), interface=interface, modulus=modulus)


@dataclass(frozen=True, eq=False)
class ContactProblem:
    """One linearised footing–soil problem (all arrays in the contact-DOF order of
    :attr:`Footing.contact_dofs`).

    - ``S`` (m, m), ``r`` (m): condensed soil, f_c = r + S Δu_c (force on the soil).
    - ``uc`` (m), ``q`` (3): current soil displacement at c and footing displacement.
    - ``slip0`` (nodes): soil–footing tangential displacement at the start of the step.
    - ``prescribed`` (3 bool) and ``target`` (3): for a prescribed component the total footing
      displacement, otherwise the generalised force (H, −N, M) it must carry.
    - ``Kq`` (3, 3), ``rq`` (3): stiffness and force of anything else attached to the footing
      (zero in statics; the superstructure and inertia in dynamics): its internal force is
      rq + Kq Δq.
    """

    footing: Footing
    S: np.ndarray
    r: np.ndarray
    uc: np.ndarray
    q: np.ndarray
    slip0: np.ndarray
    prescribed: np.ndarray
    target: np.ndarray
    Kq: np.ndarray
    rq: np.ndarray


@dataclass(frozen=True, eq=False)
class ContactSolution:
    """Increments ``duc`` (m) and ``dq`` (3), contact forces ``force`` on the soil (m), the
    node ``status`` and the number of active-set ``iterations``."""

    duc: np.ndarray
    dq: np.ndarray
    force: np.ndarray
    status: np.ndarray
    iterations: int


def solve_contact(problem: ContactProblem, status: np.ndarray, *, frozen: bool = False,
                  max_iterations: int = 100) -> ContactSolution:
    """Solve ``problem`` by a primal–dual active set from the guess ``status`` (module docstring).

    The active set updates every node at once; if the sets cycle (possible when the plastic
    tangent makes S nearly singular) it switches to Murty's least-index rule, which changes one
    node at a time and terminates for the P-matrix contact problems of a stable soil.
    ``frozen`` keeps ``status`` fixed (one linear solve). Raises :class:`ContactError` if the
    sets do not settle in ``max_iterations``, or the system is singular.
    """
    status = np.asarray(status, dtype=np.int8).copy()
    if not frozen and not (status != OPEN).any():
        status[:] = STICK  # start from full contact: the sets then shrink monotonically
    seen, least_index = set(), False
    for iteration in range(1, max_iterations + 1):
        duc, dq = _solve_sets(problem, status)
        force = problem.r + problem.S @ duc
        if frozen:
            return ContactSolution(duc, dq, force, status, iteration)
        new = _update_sets(problem, duc, dq, force)
        changed = np.flatnonzero(new != status)
        if changed.size == 0:
            return ContactSolution(duc, dq, force, status, iteration)
        least_index = least_index or new.tobytes() in seen
        seen.add(new.tobytes())
        if least_index:
            status[changed[0]] = new[changed[0]]
        else:
            status = new
    raise ContactError(f"contact active set did not settle in {max_iterations} iterations "
                       f"({int(np.count_nonzero(status))} of {status.size} nodes closed)")


def _solve_sets(p: ContactProblem, status: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The increments (Δu_c, Δq) that the sets ``status`` define (module docstring)."""
    A, b = _system(p, status)
    try:
        z = np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        z = np.full(b.size, np.nan)
    if not np.isfinite(z).all():
        closed = int(np.count_nonzero(status != OPEN))
        raise ContactError(f"contact system is singular with {closed} of {status.size} nodes "
                           "closed: the footing cannot carry the prescribed force "
                           f"(H, -N, M) = {tuple(np.round(p.target, 6))} in this contact state")
    m = p.S.shape[0]
    return z[:m], z[m:]


def _system(p: ContactProblem, status: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    f, m = p.footing, p.S.shape[0]
    L = f.kinematics
    A, b = np.zeros((m + 3, m + 3)), np.zeros(m + 3)
    closed, opened = np.flatnonzero(status != OPEN), np.flatnonzero(status == OPEN)
    # normal rows: closed -> zero gap after the step; open -> zero normal force
    A[closed, closed] = 1.0
    A[closed, m:] = -L[closed]
    b[closed] = L[closed] @ p.q - p.uc[closed]
    A[opened, :m] = p.S[opened]
    b[opened] = -p.r[opened]
    if f.interface.tangential:
        _tangential_rows(p, status, A, b, L)
    for k in range(3):
        row = m + k
        if p.prescribed[k]:
            A[row, row] = 1.0
            b[row] = p.target[k] - p.q[k]
        else:
            A[row, :m] = L[:, k] @ p.S
            A[row, m:] += p.Kq[k]
            b[row] = p.target[k] - p.rq[k] - L[:, k] @ p.r
    return A, b


def _tangential_rows(p: ContactProblem, status, A, b, L) -> None:
    n, m = p.footing.nodes, p.S.shape[0]
    rows, normal = n + np.arange(n), np.arange(n)
    stick, slip = status == STICK, (status == SLIP_POSITIVE) | (status == SLIP_NEGATIVE)
    free = status == OPEN
    A[rows[free], :m] = p.S[rows[free]]
    b[rows[free]] = -p.r[rows[free]]
    A[rows[stick], rows[stick]] = 1.0
    A[rows[stick], m:] = -L[rows[stick]]
    b[rows[stick]] = p.slip0[stick] - (p.uc[rows[stick]] - p.q[0])
    # slip: T = μ P σ with T = f_x and P = -f_y, i.e. f_x + μ σ f_y = 0
    sign = np.where(status == SLIP_POSITIVE, 1.0, -1.0)[slip]
    mu = p.footing.interface.mu
    A[rows[slip], :m] = p.S[rows[slip]] + (mu * sign)[:, None] * p.S[normal[slip]]
    b[rows[slip]] = -(p.r[rows[slip]] + mu * sign * p.r[normal[slip]])


def _update_sets(p: ContactProblem, duc, dq, force) -> np.ndarray:
    """New sets from a solution: closed where P − c g ≥ −tol; stick or slip by the trial
    tangential force T − c_t Δs against μ P."""
    f, n = p.footing, p.footing.nodes
    diag = np.abs(np.diag(p.S))
    c_n = float(diag[:n].mean())
    # round-off allowance: a node with P ≈ 0 and g ≈ 0 (where contact ends) must not flip
    tol = RTOL_CONTACT * max(np.abs(force).max(), np.abs(p.r).max(), 1e-6 * c_n * f.width)
    uc, q = p.uc + duc, p.q + dq
    pressure = -force[:n]
    gap = f.kinematics[:n] @ q - uc[:n]
    closed = pressure - c_n * gap >= -tol
    status = np.where(closed, STICK, OPEN).astype(np.int8)
    mu = f.interface.mu
    if f.interface.tangential:
        c_t = float(diag[n:].mean())
        trial = force[n:] - c_t * ((uc[n:] - q[0]) - p.slip0)
        slipping = closed & (np.abs(trial) > mu * pressure + tol)
        status[slipping] = np.where(trial[slipping] > 0.0, SLIP_POSITIVE, SLIP_NEGATIVE)
    return status
