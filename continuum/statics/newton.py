"""Newton's method for the soil, the rigid footing and its unilateral contact.

**Algorithm (one load step).** From the converged state n, with the quadrature-point history
of state n frozen for the whole step (each iteration calls the return map with the *same* old
state, as :mod:`~upliftlab.continuum.materials` requires):

1. Return map at the current displacement: stress, consistent tangent, residual
   R = f_int − f_body.
2. Factorise the tangent's free block once, the contact DOFs last, and condense onto them
   (S = K_cc − K_ci K_ii⁻¹ K_ic from the factors, r = R_c − K_ci K_ii⁻¹ R_i by one solve;
   :func:`~upliftlab.continuum.condensation.condensation`).
3. Solve the linearised contact problem **exactly** on that small dense system with the
   footing's equilibrium or prescribed motion (primal–dual active set,
   :func:`~upliftlab.continuum.contact.footing.solve_contact`): a sequential linear complementarity
   (Newton–Josephy) method, so the contact state follows the current soil tangent inside the
   plastic Newton loop.
4. Recover the interior increment Δu_i = −K_ii⁻¹(R_i + K_ic Δu_c) (one more solve).
5. Energy line search (:func:`_line_search`), the predictor included: near collapse the last
   converged tangent is nearly singular and its full step can overshoot (what the search saves:
   ``benchmarks/CONTINUUM_DESIGN.md``).

The first iteration of a step uses the tangent of the last converged state and imposes the whole
prescribed increment: the linearised (tangent) predictor, so the first iterate is already
consistent with the prescribed footing motion. Convergence is
‖R − f_c‖ ≤ ``rtol`` × (‖f_body‖ + ‖f_c‖ + E·B·1e-6) over the unconstrained DOFs. For elastic
soil the tangent is factorised once per model and each step is one small dense solve.

**Load path.** :func:`follow` walks a list of :class:`Control` targets and bisects a step that
fails (up to ``max_cuts`` times) before it raises :class:`ConvergenceError`, which names the
step, how far it got and the residual.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ...checks import InputError
from .anderson import Anderson
from ..contact.footing import OPEN, ContactError, ContactProblem, solve_contact
from ..materials import State
from ..model import evaluated

__all__ = ["Anderson", "NewtonOptions", "ConvergenceError", "ContinuumState", "Control",
           "FootingTerm", "SoilTerm", "equilibrium", "follow", "start_state", "footing_tangent"]


@dataclass(frozen=True)
class NewtonOptions:
    """``rtol`` relative residual tolerance; ``max_iterations`` per step; ``line_search``;
    ``max_cuts`` bisections of a load step before giving up; ``max_contact_iterations`` of the
    active set per Newton iteration; ``anderson`` the depth of the Anderson acceleration of the
    iterations (0: off; for a frozen iteration matrix, :class:`Anderson`)."""

    rtol: float = 1e-8
    max_iterations: int = 30
    line_search: bool = True
    max_cuts: int = 10
    max_contact_iterations: int = 100
    anderson: int = 0

    def __post_init__(self):
        if not 0.0 < self.rtol < 1e-2:
            raise InputError(f"NewtonOptions.rtol = {self.rtol:g}: valid range is (0, 0.01)")
        if not (isinstance(self.anderson, int) and 0 <= self.anderson <= 10):
            raise InputError(f"NewtonOptions.anderson = {self.anderson!r}: valid range is an "
                             "integer in [0, 10]")
        for name in ("max_iterations", "max_cuts", "max_contact_iterations"):
            value = getattr(self, name)
            if not (isinstance(value, int) and value >= 1):
                raise InputError(f"NewtonOptions.{name} = {value!r}: must be an integer >= 1")


class ConvergenceError(RuntimeError):
    """Newton gave up: ``step`` (index in the path), ``fraction`` of that step reached,
    ``residual`` (relative), ``iterations`` of the last attempt."""

    def __init__(self, message: str, *, step: int = -1, fraction: float = 0.0,
                 residual: float = math.nan, iterations: int = 0):
        super().__init__(message)
        self.step, self.fraction = step, fraction
        self.residual, self.iterations = residual, iterations


@dataclass(frozen=True, eq=False)
class ContinuumState:
    """A converged (or initial) state of soil and footing.

    ``u`` soil displacement (ndofs) from the geostatic state; ``q`` = (u, v, θ) of the footing;
    ``force`` the contact forces the footing applies to the soil at the contact DOFs (normal
    entries −P_i, then tangential T_i); ``status`` of each contact node (OPEN, STICK, SLIP_*);
    ``material`` the quadrature-point history; ``stress`` (3, 3, nelems, nqp) total stress
    (tension positive, geostatic included); ``eigenstrain`` C⁻¹σ0 of the geostatic stress (or
    None); ``reaction`` = Lᵀ f_c, the generalised force (H, −N, M) the contact carries;
    ``iterations`` Newton iterations of the step that produced it, ``cuts`` the bisections
    :func:`follow` needed to reach its target; ``tangent`` (3, 3, nelems,
    nqp) the consistent tangent of that step, which linearises the next step's predictor (or
    the function that computes it: :attr:`~upliftlab.continuum.model.Response.lazy_tangent`).
    """

    u: np.ndarray
    q: np.ndarray
    force: np.ndarray
    status: np.ndarray
    material: State
    stress: np.ndarray
    eigenstrain: np.ndarray | None
    reaction: np.ndarray
    iterations: int = 0
    cuts: int = 0
    tangent: object = field(default=None, repr=False)

    @property
    def H(self) -> float:
        """Horizontal force carried by the contact (+x), force/length."""
        return float(self.reaction[0])

    @property
    def N(self) -> float:
        """Vertical compression carried by the contact, force/length."""
        return float(-self.reaction[1])

    @property
    def M(self) -> float:
        """Moment of the contact forces about the base centre, + resisting +θ."""
        return float(self.reaction[2])


@dataclass(frozen=True)
class Control:
    """What one step imposes on the footing: for each of (u, v, θ), ``prescribed`` True imposes
    the total displacement ``target[k]``, False the generalised force ``target[k]`` of
    (H, −N, M)."""

    prescribed: tuple[bool, bool, bool]
    target: tuple[float, float, float]


@dataclass(frozen=True, eq=False)
class SoilTerm:
    """An affine soil term (e.g. Newmark inertia and Lysmer dashpots): it adds ``K u + offset``
    to the residual and ``K`` to the tangent. ``data`` is K in the model's CSR pattern
    (``model.disc.pattern``), ``offset`` (ndofs); ``matrix``, if given, is that CSR matrix
    already built (a time loop builds it once for all its steps, not once per residual)."""

    data: np.ndarray
    offset: np.ndarray
    matrix: object = None


@dataclass(frozen=True, eq=False)
class FootingTerm:
    """An affine footing term (e.g. a superstructure condensed onto the footing and its
    inertia): internal force ``K q + offset`` with ``K`` (3, 3), ``offset`` (3)."""

    K: np.ndarray
    offset: np.ndarray


def start_state(model, stress: np.ndarray | None, eigenstrain: np.ndarray | None
                ) -> ContinuumState:
    """The state with no displacement, the footing resting on the soil with no force, and the
    given initial ``stress`` (or zero)."""
    n, m = model.footing.nodes, model.blocks.contact.size
    if stress is None:
        stress = np.zeros((3, 3) + model.disc.qp_shape)
    return ContinuumState(u=np.zeros(model.disc.ndofs), q=np.zeros(3), force=np.zeros(m),
                          status=np.full(n, OPEN, dtype=np.int8),
                          material=model.initial_material_state(), stress=stress,
                          eigenstrain=eigenstrain, reaction=np.zeros(3))


# ---------------------------------------------------------------------------------------------
# One step
# ---------------------------------------------------------------------------------------------


def equilibrium(model, state: ContinuumState, control: Control,
                options: NewtonOptions = NewtonOptions(), *, frozen: bool = False,
                soil_term: SoilTerm | None = None,
                footing_term: FootingTerm | None = None,
                anderson: Anderson | None = None,
                start: tuple[np.ndarray, np.ndarray] | None = None) -> ContinuumState:
    """The converged state one step after ``state`` under ``control`` (module docstring).

    ``frozen`` keeps the contact status of ``state`` (no active-set update). ``anderson``
    carries the acceleration's pairs from step to step (default: a fresh
    :class:`Anderson` of depth ``options.anderson``). ``start`` (u, q): the first iterate, if
    not the state's own displacement (a dynamic step's predictor); the material history and
    the contact status still come from ``state``. Raises
    :class:`ConvergenceError` (or :class:`~upliftlab.continuum.contact.footing.ContactError`).
    """
    prescribed = np.asarray(control.prescribed, dtype=bool)
    target = np.asarray(control.target, dtype=float)
    _check_control(model, prescribed, target, footing_term)
    blocks, L = model.blocks, model.footing.kinematics
    slip0 = model.footing.slip(state.u, state.q)
    u, q, force, status = state.u, state.q, state.force, state.status
    if start is not None:
        u, q = start
    response = _respond(model, u, state, soil_term)
    scale = _scale(model)
    tangent = response.lazy_tangent if state.tangent is None else state.tangent
    smallest, merit = math.inf, math.inf
    if anderson is None:
        anderson = Anderson(options.anderson)
    anderson.new_step()
    for iteration in range(1, options.max_iterations + 1):
        cond = _condense(model, tangent, soil_term)
        R = response.residual
        z, r = cond.condense(R[blocks.interior], R[blocks.contact])
        Kq, rq = _footing_terms(footing_term, q)
        problem = ContactProblem(model.footing, cond.S, r, u[blocks.contact], q, slip0,
                                 prescribed, target, Kq, rq)
        sol, settled = _contact(problem, status, frozen, options)
        du = np.zeros_like(u)
        du[blocks.contact] = sol.duc
        du[blocks.interior] = cond.interior_increment(z, sol.duc)
        if not np.max(np.abs(du)) < model.width:  # NaN, or a node thrown a footing width
            relative = math.inf
            break
        mixed = anderson.mix(np.append(u, q), np.append(du, sol.dq), sol.force, sol.status,
                             cond)
        step = None if mixed is None else _mixed_step(model, state, soil_term, mixed, merit)
        if step is None:
            if mixed is not None:
                anderson.clear()  # the combination did not reduce the residual
            step = _line_search(model, state, soil_term, (u, q), (du, sol.dq, sol.force),
                                response, options.line_search)
        (u, q, force), response, merit = step
        status, tangent = sol.status, response.lazy_tangent
        relative = merit / (scale + np.linalg.norm(force))
        if relative <= options.rtol and settled:
            return ContinuumState(u=u, q=q, force=force, status=status,
                                  material=response.material, stress=response.stress,
                                  eigenstrain=state.eigenstrain, reaction=L.T @ force,
                                  iterations=iteration, tangent=response.lazy_tangent)
        smallest = min(smallest, relative)
        if not relative < min(1e3, 1e3 * smallest):  # diverging: the caller cuts the step
            break
    raise ConvergenceError(f"Newton did not converge in {iteration} iterations: relative "
                           f"residual {relative:.3e} > rtol {options.rtol:g}",
                           residual=relative, iterations=iteration)


def _mixed_step(model, state, soil_term, mixed, merit0):
    """The step to an accelerated iterate, or None if its residual is not below ``merit0``."""
    x, force = mixed
    n = model.disc.ndofs
    u, q = x[:n], x[n:]
    response = _respond(model, u, state, soil_term)
    merit = _merit(model, response, force)
    if not merit < merit0:
        return None
    return (u, q, force), response, merit


def _contact(problem, status, frozen, options):
    """The contact solution and whether its active set settled. If it does not settle at a
    poor iterate (a nearly singular plastic tangent), this iteration keeps the previous sets
    (a nested active-set step) and the next iteration tries again; a step only converges with
    settled sets."""
    try:
        return solve_contact(problem, status, frozen=frozen,
                             max_iterations=options.max_contact_iterations), True
    except ContactError:
        if frozen or not (status != OPEN).any():
            raise
        return solve_contact(problem, status, frozen=True), False


def _check_control(model, prescribed, target, footing_term=None) -> None:
    """Refuse a control the step cannot solve: a free u on a frictionless interface needs a
    horizontal stiffness of the footing term (a dynamic step's inertia, a tie), not the soil's."""
    if prescribed.shape != (3,) or target.shape != (3,) or not np.isfinite(target).all():
        raise InputError(f"control = {prescribed}, {target}: expected three flags and three "
                         "finite targets for (u, v, θ)")
    held = footing_term is not None and footing_term.K[0, 0] > 0.0
    if not model.footing.interface.tangential and not prescribed[0] and not held:
        raise InputError(f"control: H = {target[0]:g} on a frictionless interface: the footing "
                         "has no horizontal stiffness; prescribe u instead (H is then 0)")


def _scale(model) -> float:
    free = np.concatenate((model.blocks.interior, model.blocks.contact))
    floor = 1e-6 * model.soil.youngs_modulus * model.width
    return float(np.linalg.norm(model.body_force[free])) + floor


def _respond(model, u, state, soil_term):
    response = model.respond(u, state.material, state.eigenstrain)
    if soil_term is None:
        return response
    K = soil_term.matrix
    if K is None:
        K = model.disc.pattern.matrix(soil_term.data)
    return replace(response, residual=response.residual + K @ u + soil_term.offset)


def _condense(model, tangent, soil_term):
    """The tangent condensed onto the contact DOFs; a singular tangent (a perfectly plastic
    mechanism has one: the soil can no longer carry the prescribed load) is a Newton failure
    of this step, which the step cutting of :func:`follow` then retries smaller."""
    try:
        return model.condense(tangent, None if soil_term is None else soil_term.data)
    except RuntimeError as exc:
        if "singular" not in str(exc).lower():
            raise
        raise ConvergenceError(f"the tangent is singular ({exc}): the soil has reached a "
                               "mechanism under the prescribed loads") from exc


def _footing_terms(term: FootingTerm | None, q: np.ndarray):
    if term is None:
        return np.zeros((3, 3)), np.zeros(3)
    return np.asarray(term.K, dtype=float), np.asarray(term.K, dtype=float) @ q + term.offset


def _merit(model, response, force) -> float:
    """‖R − f_c‖ over the unconstrained DOFs."""
    R = response.residual
    rc = R[model.blocks.contact] - force
    return float(np.sqrt(np.sum(R[model.blocks.interior] ** 2) + np.sum(rc ** 2)))


def _line_search(model, state, soil_term, current, increment, response0, search: bool):
    """The step along (Δu, Δq) with the new contact forces: the full step if it does not
    increase the residual norm (or ``search`` is off); otherwise the energy line search of
    Crisfield (*Non-linear Finite Element Analysis of Solids and Structures* vol. 1, §9.3), a
    secant step on the slope s(α) = Δu · (R(u + α Δu) − f_c), then halvings, keeping the α
    (≥ 1/16) with the smallest residual."""
    (u, q), (du, dq, force) = current, increment
    response = _respond(model, u + du, state, soil_term)
    best = (1.0, response, _merit(model, response, force))
    merit0 = _merit(model, response0, force) if search else math.inf
    if best[2] > merit0:
        s0, s1 = _slope(model, response0, force, du), _slope(model, response, force, du)
        alpha = float(np.clip(s0 / (s0 - s1), 0.1, 0.5)) if s0 < 0.0 < s1 else 0.5
        while alpha >= 1.0 / 16.0 and best[2] > merit0:
            trial = _respond(model, u + alpha * du, state, soil_term)
            merit = _merit(model, trial, force)
            if merit < best[2]:
                best = (alpha, trial, merit)
            alpha *= 0.5
    alpha, response, merit = best
    return (u + alpha * du, q + alpha * dq, force), response, merit


def _slope(model, response, force, du) -> float:
    """Δu · (R − f_c) over the unconstrained DOFs."""
    b = model.blocks
    R = response.residual
    return float(du[b.interior] @ R[b.interior] + du[b.contact] @ (R[b.contact] - force))


def footing_tangent(model, state: ContinuumState, *, soil_term: SoilTerm | None = None,
                    footing_term: FootingTerm | None = None) -> np.ndarray:
    """dF/dq (3, 3): the consistent tangent of the generalised force (H, −N, M) the contact
    carries with respect to the footing motion (u, v, θ), at ``state`` with its contact status
    and its material history frozen (the tangent Newton uses). Columns are unit motions of
    u, v and θ; a frictionless footing's u column and row are zero."""
    tangent = evaluated(state.tangent)
    if tangent is None:
        tangent = _respond(model, state.u, state, soil_term).tangent
    S = _condense(model, tangent, soil_term).S
    m, n = S.shape[0], model.footing.nodes
    K = np.zeros((3, 3))
    for k in range(3):
        unit = np.eye(3)[k]
        problem = ContactProblem(model.footing, S, np.zeros(m), np.zeros(m), np.zeros(3),
                                 np.zeros(n), np.ones(3, dtype=bool), unit, np.zeros((3, 3)),
                                 np.zeros(3))
        sol = solve_contact(problem, state.status, frozen=True)
        K[:, k] = model.footing.kinematics.T @ (S @ sol.duc)
    if footing_term is not None:
        K += footing_term.K
    if not model.footing.interface.tangential:
        K[0, :] = K[:, 0] = 0.0
    return K


# ---------------------------------------------------------------------------------------------
# A load path with step cutting
# ---------------------------------------------------------------------------------------------


def follow(model, state: ContinuumState, controls, options: NewtonOptions = NewtonOptions(),
           **terms) -> list[ContinuumState]:
    """The converged state after each :class:`Control` in ``controls``, from ``state``.

    A step that fails is bisected (from the last converged state) up to ``options.max_cuts``
    times; the size then grows back. Raises :class:`ConvergenceError` naming the step.
    """
    states = []
    for index, control in enumerate(controls):
        state = _reach(model, state, control, options, index, terms)
        states.append(state)
    return states


def _reach(model, state, control, options, index, terms) -> ContinuumState:
    prescribed = np.asarray(control.prescribed, dtype=bool)
    goal = np.asarray(control.target, dtype=float)
    start = np.where(prescribed, state.q, state.reaction)
    done, size, error, cuts = 0.0, 1.0, None, 0
    while done < 1.0:
        size = min(size, 1.0 - done)
        target = start + (done + size) * (goal - start)
        try:
            state = equilibrium(model, state, Control(tuple(prescribed), tuple(target)),
                                options, **terms)
        except (ConvergenceError, ContactError, FloatingPointError) as exc:
            error, size, cuts = exc, 0.5 * size, cuts + 1
            if size < 0.5 ** options.max_cuts:
                raise _gave_up(index, done, goal, error) from exc
            continue
        done, size = done + size, 2.0 * size
    return replace(state, cuts=cuts)


def _gave_up(index, done, goal, error) -> ConvergenceError:
    residual = getattr(error, "residual", math.nan)
    iterations = getattr(error, "iterations", 0)
    return ConvergenceError(
        f"load step {index} (target {tuple(float(g) for g in goal)} for (u, v, θ) or "
        f"(H, -N, M)): gave up at {done:.4g} of the step after bisecting it; last error: "
        f"{error}", step=index, fraction=done, residual=residual, iterations=iterations)
