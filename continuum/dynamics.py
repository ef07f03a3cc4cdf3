"""Time histories of the soil, the rigid footing and the superstructure under a ground motion.

Two routes share this module's unknowns, loads, gravity state, results and energy account:
the explicit one (:mod:`~upliftlab.continuum.explicit`, central differences with a lumped mass,
the default) and the implicit one described here (HHT-α with Newton), chosen by the scene's
``continuum.dynamics`` or :attr:`DynamicOptions.method`. Every run's energy balance error is
checked against ``continuum.energy_tolerance`` (:mod:`~upliftlab.continuum.run_control`).

**Unknowns.** The soil DOF vector u (from the geostatic state), the footing q = (u, v, θ) and the
deformation s of the superstructure's story spring (the reduced model's u = X − Xg − hθ: the
story's lateral position less the ground's and the footing's rigid rotation). The story mass
m = W/g sits at height h on a shear spring k with a dashpot c = 2 ζ_s √(k m) (ζ_s of the
fixed-base mode, as in :mod:`upliftlab.reduced`); its lateral position is u + h θ + s. The
footing carries the vertical mass ``vertical_weight``/g, the rotary inertia I₀
(``structure.rotary_inertia``, about O, story mass excluded) and, horizontally, the base's own
mass ``vertical_weight``/g − m (zero when the structure's weight is all in the story). P-Δ is off.

**Time stepping.** HHT-α (Hilber, Hughes & Taylor 1977) with β = (1 − α)²/4, γ = 1/2 − α;
α = 0 is Newmark's average acceleration (``scheme = "newmark"``), which conserves the energy of a
linear undamped system exactly. Stiffness, damping, contact and external forces are weighted
(1 + α) at n+1 and −α at n; inertia at n+1. Each step is one call of
:func:`~upliftlab.continuum.newton.equilibrium`: the inertia, the dashpots and the α terms of the
soil enter as a :class:`~upliftlab.continuum.newton.SoilTerm` (a0 M/(1+α) + c0 C and an offset),
the superstructure and the footing's inertia as a :class:`~upliftlab.continuum.newton.FootingTerm`
(the story DOF s is eliminated exactly: its equation is linear), so the existing exact contact
solver does the rest. No second contact solver.

**Mass.** Consistent (``mass = "consistent"``, the default), integrated exactly (Q2: 3×3 points,
not the stiffness's reduced 2×2, which would make the element mass rank deficient). An implicit
scheme never inverts M, so the consistent mass costs nothing (the stiffness's pattern), and its
overestimate of the high frequencies partly cancels the period elongation of the trapezoidal rule.
``"lumped"`` (row sums; positive for Q2/P1/Q1) is offered for comparison.

**Boundaries.** ``base = "rigid"`` (default: the scene's ``continuum.base``): the bottom moves with
the ground; the relative formulation loads every DOF with −M r a_g (r the unit horizontal rigid
motion), the footing and structure with −M_z r_z a_g. ``base = "compliant"``: an absolute
formulation on an elastic half-space; the bottom carries Lysmer–Kuhlemeyer dashpots (normal
ρ V_p, tangential ρ V_s: they absorb a normally incident plane wave exactly) and the
vertically incident wave enters as the traction 2 ρ V u̇_inc (V = V_s for an S wave, V_p for a P
wave), with u̇_inc = v_g/2: the record is taken as the *outcrop* motion of the underlying rock,
twice the incident wave. ``sides``: ``rollers`` (u_x = 0, statics' condition), ``shear``
(u_y = 0, u_x free: exact for a vertically incident S wave in a layered column) or ``lysmer``
(free, with dashpots ρ V_p normal, ρ V_s tangential). There are no free-field columns: on a
compliant base (absolute motion) lysmer sides also damp the free field itself, so use
``shear`` sides there; on a rigid base they act on the motion relative to the base, the usual
approximation. Dashpot matrices are assembled on the facets (consistent). DOFs released for
dynamics carry their static reaction as a constant load, so the gravity state stays in
equilibrium at t = 0.

**Gravity first.** The geostatic state (:func:`~upliftlab.continuum.statics.geostatic`), then the
weight ``vertical_weight`` ramped on the footing in ``load_steps`` statics steps (θ held, then
released), under the static boundary conditions; the motion starts from that state at rest.

**Contact switching.** The contact conditions are enforced exactly at the end-of-step
configuration (gap_{n+1} ≥ 0, P_{n+1} ≥ 0, P g = 0) by the primal–dual active set that
:func:`~upliftlab.continuum.newton.equilibrium` solves at every Newton iteration, warm-started from
the last converged set; a step converges only with a settled set. A landing is an inelastic
impact of the footing's nodes, absorbed by the implicit scheme in the step where the gap closes
(no penalty, no restitution law, no velocity-jump rule, no set held from step to step). The HHT
dissipation (α < 0, the default: the scene's ``analysis.hht_alpha``) removes the spurious
high-frequency ringing after an impact that makes a node reopen and close again; Newmark's
average acceleration (α = 0) does not, and chatters. A bonded interface whose edge lifts off can
make the active set cycle at a node where P and g both vanish; such a step raises
:class:`ConvergenceError` rather than guess a set.

**Newton.** Elastic soil: the tangent (with a0 M/(1+α) + c0 C) is factorised once per run
(constant dt), so each step is one back-substitution per iteration, usually one iteration.
Plastic soil: modified Newton (:class:`_FrozenTangent`), accelerated by Anderson mixing
(:class:`~upliftlab.continuum.newton.Anderson`, depth ``NewtonOptions.anderson`` = 4) whose
secant pairs are carried from step to step (the map's Jacobian changes little in one dt);
each step's first iteration is the plain predictor. The iteration starts from the
constant-acceleration extrapolation d + dt v + dt² a/2 of the soil and the footing
(``DynamicOptions.predict``), not from the last converged state. The elastic iteration matrix
of plastic soil is factorised in single precision (:data:`SINGLE`; residuals stay double, so the
converged state is the same), which halves the bytes of its back-substitution, the largest cost
of an iteration. The default tolerance is rtol = 1e-5. Every step starts with that elastic
factorisation; a step still unconverged after ``_FrozenTangent.SWITCH`` = 20 iterations
refactorises once at its current consistent tangent and finishes with it. A step that still
fails is retried with the consistent tangent refactorised at every iteration. ``refactored``
records the steps that refactorised. What each of these choices saves is measured in
``benchmarks/CONTINUUM_DESIGN.md``.

**Time step.** The fastest wave must not cross more than :data:`COURANT_LIMIT` = 2 of the mesh's
smallest elements per step: dt ≤ 2 h_min/V_p. At ν = 0.3, V_p ≈ 1.87 V_s, so this is a shear-wave
Courant number ≤ 1.07: the shear waves that carry the input and the rocking radiation advance about
one element per step, and the implicit scheme (unconditionally stable) only smooths the faster P
waves in the fine elements under the footing. h_min is the shortest element edge. The default dt is
the largest divisor of the record's step below that limit. A step in which the waves cross several
elements is what the rule exists to refuse.

**A smallest step.** The step must not fall below :data:`MIN_SHEAR_COURANT` h_min/V_s either. Below
it the end-of-step contact resolves the footing nodes' own ringing after a landing (their period is
set by the shear stiffness of the locking-free element), the HHT dissipation no longer removes it,
the nodes chatter and the contact pumps energy into the system. This is what made nearly
incompressible soil gain energy: the P-wave rule shrinks the step as V_p/V_s grows. The bound,
0.21, lies above every case measured to fail and admits ν = 0.49. The two rules leave no step once
V_p/V_s > 2/:data:`MIN_SHEAR_COURANT` = 9.5, i.e. ν > 0.494 (somewhat less where the step is
rounded down to a divisor of the record's): such soil is refused here (InputError naming ν) and
runs on the explicit route (:mod:`~upliftlab.continuum.explicit`), whose contact only dissipates.

**Results.** :class:`DynamicResult` (a :class:`~upliftlab.continuum.output.FieldHistory`): per
step the footing motion, structure deformation, contact forces and status, Newton iterations and
an energy account; soil fields at ``snapshots`` evenly spaced steps.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

import numpy as np
import skfem

from .. import checks
from ..checks import InputError
from ..results import write_netcdf
from . import assembly
from .footing import OPEN, ContactError
from .materials import plane_strain_stress
from .model import ContinuumModel, _blocks, node_groups
from .newton import (Anderson, ContinuumState, Control, ConvergenceError, FootingTerm,
                     NewtonOptions, SoilTerm, equilibrium, follow)
from .run_control import Interrupted, check_energy, energy_floor
from .statics import _metadata, element_average, geostatic, max_shear_stress

__all__ = ["DynamicOptions", "DynamicResult", "run_dynamic", "COURANT_LIMIT", "SCHEMES",
           "mass_data", "dashpot_data", "incident_load", "wave_speeds", "smallest_element",
           "time_step_limit", "newmark_parameters", "structure_matrices"]

#: Largest P-wave Courant number V_p dt / h_min (module docstring).
COURANT_LIMIT = 2.0
#: Smallest shear-wave Courant number V_s dt / h_min of the implicit route (module docstring).
MIN_SHEAR_COURANT = 0.21
#: Factorise the elastic iteration matrix of plastic soil in single precision (module docstring).
SINGLE = True
SCHEMES = ("newmark", "hht")
BASES = ("rigid", "compliant")
SIDES = ("rollers", "shear", "lysmer")
WAVES = ("S", "P")
MASSES = ("consistent", "lumped")
METHODS = ("explicit", "implicit")


# ---------------------------------------------------------------------------------------------
# Options
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class DynamicOptions:
    """Options of :func:`run_dynamic`.

    ``scheme`` newmark (average acceleration) or hht; ``alpha`` HHT α in [−1/3, 0] (None: the
    scene's ``analysis.hht_alpha``; newmark is α = 0); ``dt`` (s; None: automatic, module
    docstring); ``duration`` (s; None: the scene's ``analysis.duration``, else the motion's);
    ``base`` rigid or compliant and ``sides`` rollers, shear or lysmer (None: from the scene's
    ``continuum.base`` and ``continuum.boundary``: lysmer -> lysmer; fixed -> rollers on a
    rigid base, shear on a compliant one, where rollers would block the S wave);
    ``wave`` S or P (compliant base: the incident wave); ``mass`` consistent or lumped (None:
    consistent for the implicit route, lumped for the explicit one, which needs it);
    ``snapshots`` soil-field snapshots, evenly spaced (0: none); ``energy`` records the energy
    account (implicit: one internal-force assembly per step; the explicit route always keeps
    it, at no cost); ``load_steps`` of the gravity ramp;
    ``predict`` starts each step's Newton iteration from the constant-acceleration
    extrapolation d + dt v + dt² a/2 instead of the last converged state (module docstring);
    ``newton`` the Newton options of each step. ``method`` explicit (central differences,
    :mod:`~upliftlab.continuum.explicit`) or implicit (this module's HHT-α); None: the scene's
    ``continuum.dynamics``. ``record_every`` (explicit route): steps per recorded row (None:
    the implicit route's step). ``energy_tolerance``: the largest admissible energy balance
    error (:func:`~upliftlab.continuum.run_control.balance_error`; None: the scene's
    ``continuum.energy_tolerance``); a run beyond it raises
    :class:`~upliftlab.continuum.run_control.EnergyBalanceError`. ``threads`` (explicit route):
    numba threads of the internal-force kernels (1: serial; more split the elements, which
    pays only on an otherwise idle machine; at most numba's ``NUMBA_NUM_THREADS``).
    """

    scheme: str = "hht"
    alpha: float | None = None
    dt: float | None = None
    duration: float | None = None
    base: str | None = None
    sides: str | None = None
    wave: str = "S"
    mass: str | None = None
    snapshots: int = 41
    energy: bool = True
    load_steps: int = 4
    predict: bool = True
    newton: NewtonOptions = NewtonOptions(rtol=1e-5, max_iterations=60, anderson=4)
    method: str | None = None
    record_every: int | None = None
    energy_tolerance: float | None = None
    threads: int = 1

    def __post_init__(self):
        checks.one_of("DynamicOptions.scheme", self.scheme, SCHEMES)
        if self.alpha is not None:
            alpha = checks.finite("DynamicOptions.alpha", self.alpha)
            if not -1.0 / 3.0 <= alpha <= 0.0:
                raise InputError(f"DynamicOptions.alpha = {alpha:g}: HHT α must lie in "
                                 "[-1/3, 0] (0 is Newmark's average acceleration)")
            if self.scheme == "newmark" and alpha != 0.0:
                raise InputError(f"DynamicOptions.alpha = {alpha:g}: scheme 'newmark' is α = 0; "
                                 "use scheme = 'hht' for α in [-1/3, 0)")
        for name in ("dt", "duration"):
            value = getattr(self, name)
            if value is not None:
                value = checks.finite(f"DynamicOptions.{name}", value)
                if not value > 0.0:
                    raise InputError(f"DynamicOptions.{name} = {value:g} s: must be > 0")
        if self.base is not None:
            checks.one_of("DynamicOptions.base", self.base, BASES)
        if self.sides is not None:
            checks.one_of("DynamicOptions.sides", self.sides, SIDES)
        checks.one_of("DynamicOptions.wave", self.wave, WAVES)
        if self.mass is not None:
            checks.one_of("DynamicOptions.mass", self.mass, MASSES)
        if self.method is not None:
            checks.one_of("DynamicOptions.method", self.method, METHODS)
        if self.record_every is not None:
            checks.integer_at_least("DynamicOptions.record_every", self.record_every, 1)
        if self.energy_tolerance is not None:
            checks.in_range("DynamicOptions.energy_tolerance", self.energy_tolerance, 0.0, 1.0,
                            low_open=True)
        checks.integer_at_least("DynamicOptions.threads", self.threads, 1)
        checks.integer_at_least("DynamicOptions.snapshots", self.snapshots, 0)
        checks.integer_at_least("DynamicOptions.load_steps", self.load_steps, 1)
        if not isinstance(self.predict, bool):
            raise InputError(f"DynamicOptions.predict = {self.predict!r}: must be true or false")


# ---------------------------------------------------------------------------------------------
# Small pure pieces
# ---------------------------------------------------------------------------------------------


def newmark_parameters(alpha: float, dt: float) -> dict:
    """HHT-α constants for step ``dt`` (s): β = (1−α)²/4, γ = 1/2 − α, and the Newmark
    coefficients a0 = 1/(β dt²), a1 = 1/(β dt), a2 = 1/(2β) − 1, c0 = γ/(β dt)."""
    beta, gamma = 0.25 * (1.0 - alpha) ** 2, 0.5 - alpha
    return {"alpha": alpha, "beta": beta, "gamma": gamma, "dt": dt,
            "a0": 1.0 / (beta * dt * dt), "a1": 1.0 / (beta * dt), "a2": 0.5 / beta - 1.0,
            "c0": gamma / (beta * dt), "c1": 1.0 - gamma / beta,
            "c2": dt * (1.0 - 0.5 * gamma / beta)}


def wave_speeds(soil) -> tuple[float, float]:
    """(V_p, V_s) (length/s) of the soil; (inf, inf) for massless soil."""
    if soil.density <= 0.0:
        return math.inf, math.inf
    G, nu = soil.shear_modulus, soil.poisson_ratio
    vs = math.sqrt(G / soil.density)
    return vs * math.sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu)), vs


def smallest_element(model) -> float:
    """The shortest element edge of the linear mesh (length)."""
    p, t = model.mesh.p, model.mesh.t
    edges = p[:, np.roll(t, -1, axis=0)] - p[:, t]
    return float(np.sqrt((edges ** 2).sum(axis=0)).min())


def time_step_limit(model) -> float:
    """The largest admissible dt (s): :data:`COURANT_LIMIT` h_min / V_p."""
    return COURANT_LIMIT * smallest_element(model) / wave_speeds(model.soil)[0]


def _full_basis(model) -> skfem.CellBasis:
    """The model's element with quadrature exact for the mass (twice the degree)."""
    basis = model.disc.basis
    order = 2 * max(basis.elem.elem.maxdeg, 1)
    return skfem.Basis(model.mesh, basis.elem, intorder=order)


def mass_data(model, kind: str = "consistent") -> np.ndarray:
    """The soil mass matrix ∫ ρ u·v (mass/length per length²) as CSR data in the model's pattern,
    ``consistent`` or ``lumped`` (row sums on the diagonal)."""
    rho = model.soil.density
    M = skfem.BilinearForm(lambda u, v, w: rho * (u[0] * v[0] + u[1] * v[1])).assemble(
        _full_basis(model))
    if kind == "lumped":
        from scipy import sparse
        M = sparse.diags(np.asarray(M.sum(axis=1)).ravel())
    return model.disc.pattern.gather(M)


def _facet_basis(model, names) -> skfem.FacetBasis | None:
    facets = np.concatenate([model.mesh.boundaries[n] for n in names]) if names else []
    if len(facets) == 0:
        return None
    basis = model.disc.basis
    return skfem.FacetBasis(model.mesh, basis.elem, facets=np.asarray(facets),
                            intorder=2 * max(basis.elem.elem.maxdeg, 1))


def dashpot_data(model, boundaries) -> np.ndarray:
    """Lysmer–Kuhlemeyer dashpots ∫ (ρ V_p u_n v_n + ρ V_s u_t v_t) ds on the named
    ``boundaries`` (force·s/length per length²) as CSR data in the model's pattern."""
    vp, vs = wave_speeds(model.soil)
    rho = model.soil.density
    fb = _facet_basis(model, list(boundaries))
    if fb is None or rho == 0.0:
        return np.zeros(model.disc.pattern.nnz)

    def form(u, v, w):
        n = w.n
        un, vn = u[0] * n[0] + u[1] * n[1], v[0] * n[0] + v[1] * n[1]
        return rho * (vp * un * vn + vs * (u[0] * v[0] + u[1] * v[1] - un * vn))

    return model.disc.pattern.gather(skfem.BilinearForm(form).assemble(fb))


def incident_load(model, wave: str = "S") -> np.ndarray:
    """The bottom's nodal force per unit incident velocity of a vertically incident ``wave``:
    2 ρ V ∫ v_k ds (k = x for S, y for P), force per (length/s)."""
    vp, vs = wave_speeds(model.soil)
    fb = _facet_basis(model, ["bottom"])
    k, speed = (0, vs) if wave == "S" else (1, vp)
    scale = 2.0 * model.soil.density * speed
    return skfem.LinearForm(lambda v, w: scale * v[k]).assemble(fb)


@dataclass(frozen=True)
class StructureMatrices:
    """Mass, damping, stiffness (4, 4) of z = (u, v, θ, s), the ground influence vector
    ``r`` (4) and the gravity load ``gravity`` (4) (force; −W on v)."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    r: np.ndarray
    gravity: np.ndarray
    story_mass: float
    height: float


def structure_matrices(scene) -> StructureMatrices:
    """The superstructure and footing of ``scene`` on z = (u, v, θ, s) (module docstring)."""
    s = scene.structure
    story = s.stories[0]
    m, k, h = story.weight / scene.g, story.stiffness, story.height
    c = 2.0 * s.damping_ratio * math.sqrt(k * m)
    mv = s.vertical_weight / scene.g
    a = np.array([1.0, 0.0, h, 1.0])
    M = np.diag([max(mv - m, 0.0), mv, s.rotary_inertia, 0.0]) + m * np.outer(a, a)
    return StructureMatrices(M=M, C=np.diag([0.0, 0.0, 0.0, c]), K=np.diag([0.0, 0.0, 0.0, k]),
                             r=np.array([1.0, 0.0, 0.0, 0.0]),
                             gravity=np.array([0.0, -s.vertical_weight, 0.0, 0.0]),
                             story_mass=m, height=h)


# ---------------------------------------------------------------------------------------------
# Settings checked before any work
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Settings:
    alpha: float
    dt: float
    steps: int
    base: str
    sides: str
    prescribe_u: bool
    limit: float


def _check_scene(scene, motion) -> None:
    s = scene.structure
    if len(s.stories) != 1:
        raise InputError(f"structure.story: {len(s.stories)} stories; the continuum dynamics "
                         "carries one story (an SDOF superstructure); valid: 1")
    if s.rigid:
        raise InputError("structure.rigid = true: the continuum dynamics needs the story spring; "
                         "valid: false")
    if s.p_delta:
        raise InputError("structure.p_delta = true: P-Δ is not in the continuum dynamics; "
                         "valid: false")
    for name in ("initial_displacement", "initial_rotation"):
        if getattr(motion, name):
            raise InputError(f"motion.{name} = {getattr(motion, name):g}: the continuum dynamics "
                             "starts from the static state; valid: 0 (initial_velocity is "
                             "supported)")


def boundaries(model, options: DynamicOptions) -> tuple[str, str]:
    """(base, sides) of a dynamic run (:class:`DynamicOptions`, else the scene's
    ``continuum.base`` and ``continuum.boundary``), checked against the interface."""
    cont = model.options
    base = options.base or cont.base
    sides = options.sides or ("lysmer" if cont.boundary == "lysmer" else
                              "rollers" if base == "rigid" else "shear")
    tangential = model.footing.interface.tangential
    if base == "compliant" and not tangential:
        raise InputError("soil.interface = 'frictionless' with base = 'compliant': a frictionless "
                         "footing cannot follow the horizontal ground; valid: bonded or coulomb, "
                         "or base = 'rigid'")
    if base == "compliant" and model.soil.density <= 0.0:
        raise InputError(f"soil.density = {model.soil.density:g}: a compliant base radiates "
                         "through ρV; valid range is > 0")
    return base, sides


def _settings(model, scene, motion, options: DynamicOptions) -> _Settings:
    _check_scene(scene, motion)
    base, sides = boundaries(model, options)
    tangential = model.footing.interface.tangential
    alpha = 0.0 if options.scheme == "newmark" else (
        scene.analysis.hht_alpha if options.alpha is None else options.alpha)
    if not -1.0 / 3.0 <= alpha <= 0.0:
        raise InputError(f"analysis.hht_alpha = {alpha:g}: valid range is [-1/3, 0]")
    limit = time_step_limit(model)
    if options.dt is None:
        dt = motion.dt / max(1, math.ceil(motion.dt / limit * (1.0 - 1e-12)))
    else:
        dt = options.dt
        if dt > limit:
            vp = wave_speeds(model.soil)[0]
            raise InputError(
                f"DynamicOptions.dt = {dt:g} s: too coarse for the mesh's shortest wave transit "
                f"(h_min = {smallest_element(model):.4g}, V_p = {vp:.4g}, h_min/V_p = "
                f"{limit / COURANT_LIMIT:.4g} s); valid range is (0, {limit:.4g}] s "
                f"(V_p dt/h_min ≤ {COURANT_LIMIT:g})")
    _check_smallest_step(model, dt, limit, automatic=options.dt is None)
    duration = options.duration or scene.analysis.duration or motion.duration
    steps = max(1, int(round(duration / dt)))
    return _Settings(alpha=alpha, dt=dt, steps=steps, base=base, sides=sides,
                     prescribe_u=not tangential, limit=limit)


def _check_smallest_step(model, dt: float, limit: float, automatic: bool) -> None:
    """Refuse a step below :data:`MIN_SHEAR_COURANT` h_min/V_s (module docstring): naming ν
    when the P-wave rule forced it, else the step."""
    vp, vs = wave_speeds(model.soil)
    floor = MIN_SHEAR_COURANT * smallest_element(model) / vs
    if dt >= floor * (1.0 - 1e-12):
        return
    why = (f"below {floor:.4g} s = {MIN_SHEAR_COURANT:g} h_min/V_s the implicit route's "
           "end-of-step contact chatters and gains energy")
    if automatic:
        nu = model.soil.poisson_ratio
        raise InputError(
            f"soil.poisson_ratio = {nu:g}: the implicit step follows the P wave (dt = {dt:.4g} "
            f"s ≤ {limit:.4g} s, V_p/V_s = {vp / vs:.3g}) and {why}; valid range for "
            f"continuum.dynamics = 'implicit' is V_p/V_s ≤ {2.0 / MIN_SHEAR_COURANT:.3g} "
            "(ν ≤ 0.494, less where the step rounds down to the record's); use "
            "continuum.dynamics = 'explicit'")
    valid = (f"[{floor:.4g}, {limit:.4g}] s" if floor <= limit else
             "empty for this soil (use continuum.dynamics = 'explicit')")
    raise InputError(f"DynamicOptions.dt = {dt:g} s: {why}; valid range is {valid}")


# ---------------------------------------------------------------------------------------------
# Dynamic model: blocks and the iteration matrix
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class _FrozenTangent(ContinuumModel):
    """The model with a frozen iteration matrix (modified Newton for plastic soil).

    Each step starts with the elastic tangent plus the dynamic terms, factorised once per run.
    A step still unconverged after :attr:`SWITCH` iterations refactorises once, at the
    consistent tangent of its current iterate, and finishes with it (nearly Newton's quadratic
    rate); the next step starts from the elastic factorisation again, which contracts for any
    mix of yielding and unloading points. Residuals use the true return map, so the converged
    state is the same as full Newton's."""

    #: Iterations before a slow step refactorises: a refactorisation and Schur condensation
    #: costs tens of iterations (``benchmarks/CONTINUUM_DESIGN.md``), so the elastic matrix is
    #: kept for many iterations.
    SWITCH = 20

    def condense(self, tangent, extra=None):
        cache = self._cache
        cache["calls"] = cache.get("calls", 0) + 1
        if cache["calls"] > self.SWITCH and tangent is not None and not cache.get("fresh"):
            cache["fresh"] = (extra, self._condense(tangent, extra, reused=True))
        if cache.get("fresh") and cache["fresh"][0] is extra:
            return cache["fresh"][1]
        hit = cache.get("elastic")
        if hit is None or hit[0] is not extra:
            hit = cache["elastic"] = (extra, self._condense(_elastic_tangent(self), extra,
                                                            reused=True, single=SINGLE))
        return hit[1]

    def new_step(self) -> bool:
        """Start a step; True if the last step refactorised."""
        fresh = bool(self._cache.pop("fresh", None))
        self._cache["calls"] = 0
        return fresh


def _elastic_tangent(model) -> np.ndarray:
    from .materials import plane_strain_tangent
    D = plane_strain_tangent(model.material(np.zeros((3, 3, 1)))[1])[..., 0]
    return np.ascontiguousarray(np.broadcast_to(D[..., None, None], (3, 3) + model.disc.qp_shape))


def dynamic_fixed(model, base: str, sides: str) -> np.ndarray:
    """The DOFs held in a dynamic run: the bottom on a rigid ``base``; u_x of the sides for
    ``rollers``, u_y for ``shear`` (none for ``lysmer``); never a contact DOF."""
    basis = model.disc.basis
    fixed = [basis.get_dofs("bottom").all()] if base == "rigid" else []
    if sides == "rollers":
        fixed.append(basis.get_dofs("sides").all("u^1"))
    elif sides == "shear":
        fixed.append(basis.get_dofs("sides").all("u^2"))
    fixed = np.unique(np.concatenate(fixed)) if fixed else np.zeros(0, dtype=np.int64)
    return np.setdiff1d(fixed, model.footing.contact_dofs)


def _dynamic_model(model, settings: _Settings, cls=ContinuumModel):
    fixed = dynamic_fixed(model, settings.base, settings.sides)
    contact = model.footing.contact_dofs
    basis = model.disc.basis
    interior = np.setdiff1d(np.arange(model.disc.ndofs), np.union1d(fixed, contact))
    values = {f.name: getattr(model, f.name) for f in fields(model) if f.init}
    values.update(blocks=_blocks(model.disc.pattern, interior, contact, fixed,
                                 node_groups(basis)), _cache={})
    return cls(**values)


def _residual(model, stress) -> np.ndarray:
    """f_int − f_body of a total stress field."""
    return assembly.internal_force(model.disc, plane_strain_stress(stress)) - model.body_force


# ---------------------------------------------------------------------------------------------
# Gravity
# ---------------------------------------------------------------------------------------------


def _gravity(model, scene, options: DynamicOptions, prescribe_u: bool) -> ContinuumState:
    """Geostatic state, then the footing's weight ramped with θ held, then θ released."""
    state = geostatic(model)
    N = scene.structure.vertical_weight
    loads = N * np.arange(1, options.load_steps + 1) / options.load_steps
    controls = [Control((prescribe_u, False, True), (0.0, -n, 0.0)) for n in loads]
    controls.append(Control((prescribe_u, False, False), (0.0, -N, 0.0)))
    return follow(model, state, controls, options.newton)[-1]


# ---------------------------------------------------------------------------------------------
# Result
# ---------------------------------------------------------------------------------------------

ENERGY = ("kinetic", "strain", "damping", "input", "contact")


@dataclass(frozen=True, eq=False)
class DynamicResult:
    """Histories of a dynamic run, one row per step (row 0: the static state at t = 0).

    ``time`` (s); ``footing`` (nt, 3) u, v (up), θ (rad) relative to the base (rigid base) or
    absolute (compliant base); ``structure_u`` (nt) the story deformation s (length) and
    ``structure_velocity`` (length/s); ``ground_acceleration`` (nt, length/s²); ``H``, ``N``
    (compression), ``M`` (force/length); ``contact_length`` (length); per contact node at ``x``:
    ``pressure`` (force/length², compression +), ``gap`` (length), ``status``; ``iterations``
    Newton iterations per step (explicit route: contact active-set iterations since the last
    row), ``refactored`` (bool) the steps that refactorised the iteration matrix (plastic soil:
    a slow step, or a retry with the consistent tangent; never on the explicit route);
    ``energy`` (nt, 5): kinetic, strain (soil work ∫(f_int − f_body)·du, story spring, footing
    weight), damping (dissipated by dashpots), input (work of the ground loads), contact (the
    energy the contact forces took out of the soil and the footing), all cumulative from the
    static state by the trapezoidal rule (force·length/length; with ``energy`` off: NaN). For
    Newmark (α = 0), kinetic + strain + damping + contact − input is constant to the Newton
    tolerance; HHT's dissipation and central differences' O(dt²) make it drift
    (:attr:`energy_balance_error`).
    Soil fields at ``snapshot_step``: ``displacement`` (nk, ndofs), ``plastic_strain`` and
    ``max_shear_stress`` (nk, nelems) element averages. ``width`` B; ``metadata`` provenance.
    """

    time: np.ndarray
    footing: np.ndarray
    structure_u: np.ndarray
    structure_velocity: np.ndarray
    ground_acceleration: np.ndarray
    H: np.ndarray
    N: np.ndarray
    M: np.ndarray
    contact_length: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    status: np.ndarray
    iterations: np.ndarray
    refactored: np.ndarray
    energy: np.ndarray
    width: float
    snapshot_step: np.ndarray
    displacement: np.ndarray = field(repr=False)
    plastic_strain: np.ndarray = field(repr=False)
    max_shear_stress: np.ndarray = field(repr=False)
    metadata: dict = field(default_factory=dict, repr=False)
    kind: str = "dynamic"

    @property
    def snapshot_time(self) -> np.ndarray:
        return self.time[self.snapshot_step]

    @property
    def theta(self) -> np.ndarray:
        return self.footing[:, 2]

    @property
    def total_energy(self) -> np.ndarray:
        """kinetic + strain + damping + contact − input (constant for an exact balance)."""
        e = self.energy
        return e[:, 0] + e[:, 1] + e[:, 2] + e[:, 4] - e[:, 3]

    @property
    def energy_balance_error(self) -> float:
        """The balance's relative error (:func:`~upliftlab.continuum.run_control.balance_error`;
        NaN without an energy account)."""
        from .run_control import balance_error
        return balance_error(self.energy, self.metadata.get("energy_floor", 0.0))

    def switches(self) -> np.ndarray:
        """Open/closed status changes per node over the run (nc)."""
        closed = self.status != OPEN
        return np.sum(closed[1:] != closed[:-1], axis=0)

    def save(self, path) -> Path:
        """Write the histories and soil fields to NetCDF (atomically), with provenance."""
        units = self.metadata.get("units", {})
        length, force = units.get("length", ""), units.get("force/length", "")
        t, node, snap = ("time",), ("time", "node"), ("snapshot",)
        variables = {
            "time": (t, self.time, {"units": "s"}),
            "u": (t, self.footing[:, 0], {"units": length}),
            "v": (t, self.footing[:, 1], {"units": length, "positive": "up"}),
            "theta": (t, self.footing[:, 2], {"units": "rad"}),
            "structure_u": (t, self.structure_u, {"units": length}),
            "structure_velocity": (t, self.structure_velocity, {"units": f"{length}/s"}),
            "ground_acceleration": (t, self.ground_acceleration, {"units": f"{length}/s^2"}),
            "H": (t, self.H, {"units": force}),
            "N": (t, self.N, {"units": force, "positive": "compression"}),
            "M": (t, self.M, {"units": units.get("moment/length", "")}),
            "contact_length": (t, self.contact_length, {"units": length}),
            "x": (("node",), self.x, {"units": length}),
            "pressure": (node, self.pressure, {"positive": "compression"}),
            "gap": (node, self.gap, {"units": length}),
            "status": (node, self.status, {"values": "0 open, 1 stick, 2/3 slip +/-"}),
            "iterations": (t, self.iterations, {}),
            "refactored": (t, self.refactored.astype(np.int8), {}),
            "energy": (t + ("term",), self.energy, {"terms": " ".join(ENERGY)}),
            "snapshot_step": (snap, self.snapshot_step, {}),
            "snapshot_time": (snap, self.snapshot_time, {"units": "s"}),
            "displacement": (snap + ("dof",), self.displacement,
                             {"units": length, "meaning": "soil DOF vector, model basis ordering"}),
            "plastic_strain": (snap + ("element",), self.plastic_strain, {}),
            "max_shear_stress": (snap + ("element",), self.max_shear_stress,
                                 {"units": units.get("stress", "")}),
        }
        return write_netcdf(path, variables, attrs={"kind": self.kind, "width": self.width,
                                                    **self.metadata})


# ---------------------------------------------------------------------------------------------
# The run
# ---------------------------------------------------------------------------------------------


@dataclass(eq=False)
class _Kinematics:
    """Displacement, velocity, acceleration of a set of DOFs (mutable loop state)."""

    d: np.ndarray
    v: np.ndarray
    a: np.ndarray

    def advance(self, new: np.ndarray, c: dict) -> None:
        a = c["a0"] * (new - self.d) - c["a1"] * self.v - c["a2"] * self.a
        self.v = self.v + c["dt"] * ((1.0 - c["gamma"]) * self.a + c["gamma"] * a)
        self.d, self.a = new, a

    def predict(self, dt: float) -> np.ndarray:
        """The displacement one step ``dt`` ahead at constant acceleration, d + dt v + dt² a/2:
        the first Newton iterate of the step (module docstring)."""
        return self.d + dt * self.v + (0.5 * dt * dt) * self.a

    def history(self, c: dict) -> np.ndarray:
        """The part of (M/(1+α)) ü + C u̇ at n+1 that does not depend on the new d, per matrix:
        (mass vector, damping vector) to multiply."""
        return (-c["a0"] * self.d - c["a1"] * self.v - c["a2"] * self.a,
                -c["c0"] * self.d + c["c1"] * self.v + c["c2"] * self.a)


def run_dynamic(model, scene, motion, options: DynamicOptions = DynamicOptions(), *,
                progress=None) -> DynamicResult:
    """Gravity, then ``motion`` on ``model`` (built from ``scene``): see the module docstring.

    ``options.method`` (else the scene's ``continuum.dynamics``) chooses the explicit route
    (:func:`~upliftlab.continuum.explicit.run_explicit`) or this module's implicit one. Every
    input is checked before any work (InputError naming the field, the value and the valid
    range). ``progress(k, n, state)`` is called after each step (explicit: each recorded row)
    if given. Raises :class:`~upliftlab.continuum.newton.ConvergenceError` naming the time if a
    step fails, :class:`~upliftlab.continuum.run_control.EnergyBalanceError` if the energy
    balance error exceeds the tolerance, and
    :class:`~upliftlab.continuum.run_control.Interrupted` (with the partial result) on a
    KeyboardInterrupt.
    """
    method = options.method or model.options.dynamics
    tolerance = options.energy_tolerance or model.options.energy_tolerance
    if method == "explicit" and (options.scheme != "hht" or options.alpha is not None):
        raise InputError(f"DynamicOptions.scheme = {options.scheme!r}, alpha = {options.alpha}: "
                         "the scheme and α are the implicit route's; valid with the explicit "
                         "route: scheme 'hht', alpha None (or method = 'implicit')")
    if method == "explicit":
        from .explicit import run_explicit
        result = run_explicit(model, scene, motion, options, progress=progress)
    else:
        settings = _settings(model, scene, motion, options)
        started = _time.perf_counter()
        static = _gravity(model, scene, options, settings.prescribe_u)
        dyn = _dynamic_model(model, settings)
        frozen = dyn if model.linear else _dynamic_model(model, settings, _FrozenTangent)
        run = _Run(dyn, frozen, scene, motion, options, settings, static)
        result = run.loop(progress)
        result.metadata["wall_time_s"] = _time.perf_counter() - started
    check_energy(result, tolerance, energy_floor(scene, model.width))
    return result


class _Run:
    """The time loop's constant pieces and its mutable state."""

    def __init__(self, dyn, frozen, scene, motion, options, settings, static):
        self.dyn, self.frozen, self.scene, self.motion = dyn, frozen, scene, motion
        self.options, self.settings = options, settings
        self.c = newmark_parameters(settings.alpha, settings.dt)
        c, alpha = self.c, settings.alpha
        pattern = dyn.disc.pattern
        self.M = pattern.matrix(mass_data(dyn, options.mass or "consistent"))
        boundaries = (["sides"] if settings.sides == "lysmer" else []) + (
            ["bottom"] if settings.base == "compliant" else [])
        self.C = pattern.matrix(dashpot_data(dyn, boundaries))
        self.soil_data = c["a0"] / (1.0 + alpha) * self.M.data + c["c0"] * self.C.data
        self.soil_matrix = pattern.matrix(self.soil_data)
        released = np.setdiff1d(_static_fixed(dyn), dyn.blocks.fixed)
        R0 = _residual(dyn, static.stress)
        self.release = np.zeros(dyn.disc.ndofs)
        self.release[released] = R0[released]
        if settings.base == "rigid":
            r = np.zeros(dyn.disc.ndofs)
            r[_x_dofs(dyn)] = 1.0
            self.ground_soil = -(self.M @ r)       # per unit a_g (length/s²)
            self.incident = np.zeros(dyn.disc.ndofs)
        else:
            self.ground_soil = np.zeros(dyn.disc.ndofs)
            self.incident = incident_load(dyn, options.wave)  # per unit incident velocity
        self.z = structure_matrices(scene)
        self.ground_z = -(self.z.M @ self.z.r) if settings.base == "rigid" else np.zeros(4)
        self.g = scene.g
        self.vg = _ground_velocity(motion, settings.dt, settings.steps)
        self.static = static
        self.need_R = alpha != 0.0 or options.energy
        self.anderson = Anderson(options.newton.anderson)  # its pairs serve the whole run

    def load(self, k: int):
        """(soil load, footing load) of the ground at step k (time k dt)."""
        t = k * self.settings.dt
        ag = float(self.motion.acceleration_at(t)) * self.g
        soil = self.ground_soil * ag + self.incident * (0.5 * self.vg[k] * self.g)
        return soil, self.ground_z * ag + self.z.gravity, ag

    def contact_vector(self, state) -> np.ndarray:
        f = np.zeros(self.dyn.disc.ndofs)
        f[self.dyn.blocks.contact] = state.force
        return f

    def loop(self, progress) -> DynamicResult:
        dyn, st, opts = self.dyn, self.settings, self.options
        n = st.steps
        state = self.static
        soil = _Kinematics(state.u.copy(), np.zeros_like(state.u), np.zeros_like(state.u))
        z0 = np.append(state.q, 0.0)
        zv = np.zeros(4)
        zv[3] = self.motion.initial_velocity
        za = np.zeros(4)
        za[3] = -self.z.C[3, 3] * zv[3] / self.z.story_mass
        zk = _Kinematics(z0, zv, za)
        ag = self.load(0)[2]
        R = _residual(dyn, state.stress) if self.need_R else None
        rec = _Recorder(dyn, n, opts.snapshots)
        energy = np.zeros(5) if opts.energy else np.full(5, np.nan)
        rec.record(0, 0.0, state, zk, ag, energy, 0, False,
                   kinetic=self.kinetic(soil.v, zk.v) if opts.energy else math.nan)
        soil_term_data = self.soil_data
        control = Control((st.prescribe_u, False, False), (0.0, 0.0, 0.0))
        try:
            self.steps(rec, state, soil, zk, R, energy, soil_term_data, control, progress)
        except KeyboardInterrupt:
            raise Interrupted(rec.result(dyn, self.motion, self.metadata(), rows=rec.rows)) \
                from None
        return rec.result(dyn, self.motion, self.metadata())

    def metadata(self) -> dict:
        """The run's settings for the result's metadata."""
        st, options = self.settings, self.options
        return {"method": "implicit", "scheme": options.scheme, "alpha": st.alpha,
                "dt": st.dt, "steps": st.steps, "base": st.base, "sides": st.sides,
                "wave": options.wave, "mass": options.mass or "consistent",
                "dt_limit": st.limit, "courant_limit": COURANT_LIMIT,
                "newton_rtol": options.newton.rtol}

    def steps(self, rec, state, soil, zk, R, energy, soil_term_data, control, progress):
        """Steps 1…n, recorded into ``rec``."""
        dyn, c, st, opts = self.dyn, self.c, self.settings, self.options
        alpha = st.alpha
        w = alpha / (1.0 + alpha)
        n = st.steps
        F_soil, F_z, _ = self.load(0)
        for k in range(1, n + 1):
            F1_soil, F1_z, ag = self.load(k)
            fc = self.contact_vector(state)
            mh, ch = soil.history(c)
            offset = (self.M @ mh) / (1.0 + alpha) + self.C @ ch - self.release - F1_soil
            if alpha != 0.0:
                Xn = self.C @ soil.v + R - self.release - fc - F_soil
                offset = offset - w * Xn
            term = SoilTerm(soil_term_data, offset, self.soil_matrix)
            A, b = self.footing_affine(zk, state, F1_z, F_z)
            fterm = FootingTerm(A[:3, :3] - np.outer(A[:3, 3], A[3, :3]) / A[3, 3],
                                b[:3] - A[:3, 3] * b[3] / A[3, 3])
            if self.frozen is not self.dyn:
                self.frozen.new_step()
            start = (soil.predict(st.dt), zk.predict(st.dt)[:3]) if opts.predict else None
            new, refactored = self.step(state, control, term, fterm, k, start)
            if self.frozen is not self.dyn and self.frozen._cache.get("fresh"):
                refactored = True
            q = new.q
            s = -(A[3, :3] @ q + b[3]) / A[3, 3]
            z_old, u_old, v_old, zv_old = zk.d, soil.d, soil.v, zk.v
            soil.advance(new.u, c)
            zk.advance(np.append(q, s), c)
            if self.need_R:
                R1 = _residual(dyn, new.stress)
                if opts.energy:
                    energy += self.energy_increment(R, R1, new.u - u_old, v_old, soil.v,
                                                    (z_old, zk.d), zv_old, zk.v,
                                                    F_soil, F1_soil, F_z, F1_z,
                                                    (state.force, new.force))
                R = R1
            state, F_soil, F_z = new, F1_soil, F1_z
            rec.record(k, k * st.dt, state, zk, ag, energy, new.iterations, refactored,
                       kinetic=self.kinetic(soil.v, zk.v) if opts.energy else math.nan)
            if progress is not None:
                progress(k, n, state)

    def footing_affine(self, zk, state, F1, F0):
        """(A, b): A z_{n+1} + b + [Lᵀ f_c; 0] = 0, the footing and story equations."""
        c, z, alpha = self.c, self.z, self.settings.alpha
        A = c["a0"] / (1.0 + alpha) * z.M + c["c0"] * z.C + z.K
        mh, ch = zk.history(c)
        b = z.M @ mh / (1.0 + alpha) + z.C @ ch - F1
        if alpha != 0.0:
            reaction = np.append(state.reaction, 0.0)
            Xn = z.C @ zk.v + z.K @ zk.d + reaction - F0
            b = b - alpha / (1.0 + alpha) * Xn
        return A, b

    def step(self, state, control, term, fterm, k, start=None):
        """One step: modified Newton (for elastic soil the exact tangent), then, for plastic
        soil, the consistent tangent refactorised each iteration. Returns (state, refactored).
        A step that fails both raises :class:`ConvergenceError` naming the time: a contact set
        is never held or guessed."""
        opts, errors = self.options.newton, []
        attempts = [self.frozen] + ([self.dyn] if self.frozen is not self.dyn else [])
        for model in attempts:
            memory = self.anderson if model is self.frozen else None
            if model is self.dyn and self.frozen is not self.dyn:
                opts = replace(opts, anderson=0)  # Newton's own rate needs no acceleration
            try:
                return equilibrium(model, state, control, opts, soil_term=term,
                                   footing_term=fterm, anderson=memory,
                                   start=start if model is self.frozen else None), \
                    model is not self.frozen
            except (ConvergenceError, ContactError, FloatingPointError) as exc:
                errors.append(str(exc))
        raise ConvergenceError(f"time step {k} (t = {k * self.settings.dt:.6g} s): "
                               f"{'; then '.join(errors)}", step=k)

    def kinetic(self, v, zv) -> float:
        return 0.5 * float(v @ (self.M @ v)) + 0.5 * float(zv @ self.z.M @ zv)

    def energy_increment(self, R0, R1, du, v0, v1, zz, zv0, zv1, Fs0, Fs1, Fz0, Fz1, forces):
        """(0, strain, damping, input, contact) increments by the trapezoidal rule over the
        free DOFs: soil work of f_int − f_body (less the released reactions), story spring,
        footing weight; dashpot dissipation; work of the ground loads; the work the contact
        forces (``forces`` at both ends, on the soil) take out of the soil and the footing."""
        free = np.concatenate((self.dyn.blocks.interior, self.dyn.blocks.contact))
        d = du[free]
        z = self.z
        dz = zz[1] - zz[0]
        strain = 0.5 * float((R0 + R1)[free] @ d) - float(self.release[free] @ d)
        strain += 0.5 * float((z.K @ (zz[0] + zz[1])) @ dz) - float(z.gravity @ dz)
        damping = 0.5 * float((self.C @ (v0 + v1))[free] @ d) + 0.5 * float(
            (z.C @ (zv0 + zv1)) @ dz)
        inputs = 0.5 * float((Fs0 + Fs1)[free] @ d) + 0.5 * float(
            (Fz0 + Fz1 - 2.0 * z.gravity) @ dz)
        mean = 0.5 * (forces[0] + forces[1])
        L = self.dyn.footing.kinematics
        contact = -(float(mean @ du[self.dyn.blocks.contact]) - float((L.T @ mean) @ dz[:3]))
        return np.array([0.0, strain, damping, inputs, contact])


def _static_fixed(model) -> np.ndarray:
    """The statics model's fixed DOFs (bottom, sides u_x)."""
    basis = model.disc.basis
    return np.union1d(basis.get_dofs("bottom").all(), basis.get_dofs("sides").all("u^1"))


def _x_dofs(model) -> np.ndarray:
    """Every u_x DOF of the vector basis (the first row of each DOF table)."""
    b = model.disc.basis
    tables = (b.nodal_dofs, b.facet_dofs, b.edge_dofs, b.interior_dofs)
    return np.concatenate([np.asarray(t[0]).ravel() for t in tables if np.size(t)])


def _ground_velocity(motion, dt: float, steps: int) -> np.ndarray:
    """Ground velocity (in g·s) at t = k dt, k = 0…steps: the exact integral of the
    piecewise-linear record."""
    n = motion.acceleration.size
    times = np.arange(n + 1) * motion.dt
    acc = np.append(motion.acceleration, 0.0)
    vel = np.concatenate(([0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * motion.dt)))
    t = np.arange(steps + 1) * dt
    k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, n)
    tau = t - times[k]
    a0 = acc[k]
    a1 = np.where(k < n, acc[np.minimum(k + 1, n)], 0.0)
    slope = (a1 - a0) / motion.dt
    inside = k < n
    return np.where(inside, vel[k] + a0 * tau + 0.5 * slope * tau ** 2, vel[n])


class _Recorder:
    """Per-step histories and the snapshots."""

    def __init__(self, model, steps: int, snapshots: int):
        f = model.footing
        nt, nc = steps + 1, f.nodes
        self.model, self.f = model, f
        self.time, self.q = np.zeros(nt), np.zeros((nt, 3))
        self.s, self.sv, self.ag = np.zeros(nt), np.zeros(nt), np.zeros(nt)
        self.reaction = np.zeros((nt, 3))
        self.pressure, self.gap = np.zeros((nt, nc)), np.zeros((nt, nc))
        self.status = np.zeros((nt, nc), dtype=np.int8)
        self.length = np.zeros(nt)
        self.iterations = np.zeros(nt, dtype=np.int64)
        self.refactored = np.zeros(nt, dtype=bool)
        self.energy = np.zeros((nt, len(ENERGY)))
        chosen = np.unique(np.round(np.linspace(0, steps, snapshots)).astype(np.int64)) \
            if snapshots else np.zeros(0, dtype=np.int64)
        self.snap_steps = chosen
        self.rows = 0
        self.snap_index = {int(k): i for i, k in enumerate(chosen)}
        ne = model.mesh.nelements
        self.disp = np.zeros((chosen.size, model.disc.ndofs))
        self.eps = np.zeros((chosen.size, ne))
        self.shear = np.zeros((chosen.size, ne))

    def record(self, k, t, state, zk, ag, energy, iterations, refactored, kinetic=0.0):
        f = self.f
        self.rows = k + 1
        self.time[k], self.q[k] = t, state.q
        self.s[k], self.sv[k], self.ag[k] = zk.d[3], zk.v[3], ag
        self.reaction[k] = state.reaction
        self.pressure[k] = -state.force[:f.nodes] / f.weight
        self.gap[k] = f.gap(state.u, state.q)
        self.status[k] = state.status
        self.length[k] = f.contact_length(state.status != OPEN, self.pressure[k], self.gap[k])
        self.iterations[k], self.refactored[k] = iterations, refactored
        self.energy[k] = energy
        self.energy[k, 0] = kinetic
        i = self.snap_index.get(int(k))
        if i is not None:
            self.disp[i] = state.u
            self.eps[i] = element_average(self.model, state.material.equivalent_plastic_strain)
            self.shear[i] = element_average(self.model, max_shear_stress(state.stress))

    def result(self, model, motion, extra: dict, rows: int | None = None) -> DynamicResult:
        """The :class:`DynamicResult` with ``extra`` metadata; ``rows``: only the first rows
        were recorded (an interrupted run), marked ``incomplete`` with ``completed_until``."""
        n = self.time.size if rows is None else rows
        extra = {**extra, "motion": motion.name, "motion_source": motion.source,
                 "width": model.width}
        if n < self.time.size:
            extra.update(incomplete=True, completed_until=float(self.time[n - 1]))
        snaps = self.snap_steps < n
        return DynamicResult(
            time=self.time[:n], footing=self.q[:n], structure_u=self.s[:n],
            structure_velocity=self.sv[:n], ground_acceleration=self.ag[:n],
            H=self.reaction[:n, 0], N=-self.reaction[:n, 1], M=self.reaction[:n, 2],
            contact_length=self.length[:n], x=self.f.x, pressure=self.pressure[:n],
            gap=self.gap[:n], status=self.status[:n], iterations=self.iterations[:n],
            refactored=self.refactored[:n], energy=self.energy[:n], width=model.width,
            snapshot_step=self.snap_steps[snaps], displacement=self.disp[snaps],
            plastic_strain=self.eps[snaps], max_shear_stress=self.shear[snaps],
            metadata=_metadata(model, "dynamic", extra))
