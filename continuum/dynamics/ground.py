"""How a ground motion enters the soil domain of a dynamic run: the boundary conditions of
either route, the start from the gravity state, the rigid-body load and the ground velocity.

**Boundaries.** ``base = "rigid"`` (the scene's ``continuum.base``): the bottom moves with the
ground; the relative formulation loads every DOF with −M r a_g (r the unit horizontal rigid
motion, :func:`x_dofs`). ``base = "compliant"``: an absolute formulation on an elastic
half-space, the bottom carrying dashpots and the incident wave
(:mod:`~upliftlab.continuum.dynamics.waves`),
with u̇_inc = v_g/2 (:func:`ground_velocity`): the record is taken as the *outcrop* motion of the
underlying rock, twice the incident wave. ``sides``: ``rollers`` (u_x = 0, statics' condition),
``shear`` (u_y = 0, u_x free: exact for a vertically incident S wave in a layered column) or
``lysmer`` (free, with dashpots).

**Horizontal tie** (``continuum.horizontal_tie`` K_t, compliant base): a footing on a frictionless
interface takes no horizontal force from the soil, so on a compliant base a spring K_t holds it
to the free field's surface displacement u_ff(t) (:func:`free_field_motion`), with a parallel
dashpot C_t (``continuum.horizontal_tie_damping``): the footing feels −K_t (u − u_ff) −
C_t (u̇ − v_ff), the force a sway spring and dashpot of a bed on the moving ground give. On a rigid
base the footing's u is prescribed to the base's instead, which ties the footing to the rock at
the box's depth. DOFs released for dynamics (held in statics,
:func:`static_fixed`) carry their static reaction as a constant load, so the gravity state stays
in equilibrium at t = 0.

**Gravity first.** :func:`gravity_state`: the geostatic state, then the weight
``vertical_weight`` ramped on the footing in ``load_steps`` statics steps (θ held, then
released), under the static boundary conditions; the motion starts from that state at rest.
It depends only on the model and a few options, and a fresh process reads it from the set-up
cache (:mod:`~upliftlab.continuum.setup_cache`) when an earlier one has made it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ...checks import InputError
from .. import setup_cache
from ..materials import State
from ..model import evaluated
from ..statics.newton import ContinuumState, Control, follow
from ..statics.analyses import geostatic
from .waves import DomainWaves, domain_waves, wave_speeds

__all__ = ["Ground", "dynamic_ground", "boundaries", "free_field_motion", "held_horizontally", "dynamic_fixed",
           "static_fixed", "x_dofs", "ground_velocity", "gravity_state", "state_arrays",
           "state_of", "GRAVITY_SOURCES"]


@dataclass(frozen=True, eq=False)
class Ground:
    """How the ground motion enters a dynamic run's domain, decided once before either route
    sets up (:func:`dynamic_ground`): the ``base`` and ``sides`` (:func:`boundaries`); the
    DOFs ``fixed`` in the run (:func:`dynamic_fixed`) and those ``released`` from the statics'
    (:func:`static_fixed`), which carry their static reaction as a constant load; ``x``, every
    u_x DOF (the rigid-body vector r of a rigid base, :func:`x_dofs`); whether the footing's u
    is prescribed (``prescribe_u``, :func:`held_horizontally`); and the ``waves`` of the
    domain, the dashpots on its absorbing boundaries and the incident load of a compliant base
    among them (:class:`~upliftlab.continuum.dynamics.waves.DomainWaves`)."""

    base: str
    sides: str
    fixed: np.ndarray
    released: np.ndarray
    x: np.ndarray
    prescribe_u: bool
    waves: DomainWaves


def dynamic_ground(model, options) -> Ground:
    """The :class:`Ground` of a dynamic run of ``model`` with ``options`` (a
    :class:`~upliftlab.continuum.dynamics.options.DynamicOptions`), checked before any work."""

    base, sides = boundaries(model, options)
    fixed = dynamic_fixed(model, base, sides)
    released, x = np.setdiff1d(static_fixed(model), fixed), x_dofs(model)
    held = held_horizontally(model)
    dashpots = (("sides",) if sides == "lysmer" else ()) + (
        ("bottom",) if base == "compliant" else ())
    waves = domain_waves(model, dashpots, options.wave if base == "compliant" else None)
    return Ground(base, sides, fixed, released, x, held, waves)


def boundaries(model, options) -> tuple[str, str]:
    """(base, sides) of a dynamic run (``options``, a
    :class:`~upliftlab.continuum.dynamics.options.DynamicOptions`, else the scene's
    ``continuum.base`` and ``continuum.boundary``), checked against the interface."""
    cont = model.options
    base = options.base or cont.base
    sides = options.sides or ("lysmer" if cont.boundary == "lysmer" else
                              "rollers" if base == "rigid" and cont.boundary == "fixed" else
                              "shear")
    tangential = model.footing.interface.tangential
    tie = cont.horizontal_tie
    if base == "compliant" and not tangential and tie is None:
        raise InputError("soil.interface = 'frictionless' with base = 'compliant': a frictionless "
                         "footing cannot follow the horizontal ground; valid: bonded or coulomb, "
                         "continuum.horizontal_tie > 0 (a spring to the free field), or "
                         "base = 'rigid'")
    if tie is not None and base != "compliant":
        raise InputError(f"continuum.horizontal_tie = {tie:g}: the tie holds a footing on a "
                         f"compliant base, and base = {base!r} holds it already; valid: "
                         "base = 'compliant', or no horizontal_tie")
    if base == "compliant" and model.soil.density <= 0.0:
        raise InputError(f"soil.density = {model.soil.density:g}: a compliant base radiates "
                         "through ρV; valid range is > 0")
    return base, sides


def free_field_motion(model, velocity: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """(u_ff, v_ff) (length, length/s) at t_k = k dt: the surface displacement and velocity
    of the free field of a homogeneous elastic half-plane under the vertically incident S
    wave that enters the compliant base, ``velocity`` (length/s at t_k) being the outcrop
    motion (twice the incident wave, :func:`ground_velocity` times g). At the surface the
    incident and the reflected wave add up to the outcrop motion, delayed by the travel time
    D/V_s from the base at depth D: v_ff(t) = v(t − D/V_s), u_ff(t) = ∫₀^{t − D/V_s} v dt
    (trapezoidal rule on the step; 0 before the wave arrives). Exact while the free field
    stays elastic."""

    y = model.mesh.p[1]
    delay = float(y.max() - y.min()) / wave_speeds(model.soil)[1]
    v = np.asarray(velocity, dtype=float)
    u = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)))
    t = np.arange(v.size) * dt
    return np.interp(t - delay, t, u, left=0.0), np.interp(t - delay, t, v, left=0.0)


def held_horizontally(model) -> bool:
    """Whether a dynamic run prescribes the footing's u (to the rigid base's): a frictionless
    interface without a horizontal tie. The gravity state holds it for every frictionless
    footing, which the tie, at rest, does not change."""
    return not model.footing.interface.tangential and model.options.horizontal_tie is None


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


def static_fixed(model) -> np.ndarray:
    """The statics model's fixed DOFs (bottom, sides u_x)."""
    basis = model.disc.basis
    return np.union1d(basis.get_dofs("bottom").all(), basis.get_dofs("sides").all("u^1"))


def x_dofs(model) -> np.ndarray:
    """Every u_x DOF of the vector basis (the first row of each DOF table)."""
    b = model.disc.basis
    tables = (b.nodal_dofs, b.facet_dofs, b.edge_dofs, b.interior_dofs)
    return np.concatenate([np.asarray(t[0]).ravel() for t in tables if np.size(t)])


def ground_velocity(motion, dt: float, steps: int) -> np.ndarray:
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


#: The sources of the gravity state (as :func:`upliftlab.provenance.code_digest` names them).
GRAVITY_SOURCES = setup_cache.MODEL_SOURCES + ("upliftlab.continuum/statics/",
                                               "upliftlab.continuum/dynamics/ground.py")
#: The arrays of a :class:`ContinuumState` in the set-up cache, beside its material history.
_STATE_ARRAYS = ("u", "q", "force", "status", "stress", "reaction")


def gravity_state(model, scene, options, prescribe_u: bool) -> ContinuumState:
    """Geostatic state, then the footing's weight ramped with θ held in ``options.load_steps``
    steps (:class:`~upliftlab.continuum.dynamics.options.DynamicOptions`), then θ released;
    ``prescribe_u``: the footing's u is held (a frictionless interface). Read from the set-up
    cache when a process has made it for the same model and options (module docstring)."""
    inputs = {**setup_cache.model_inputs(model), "weight": scene.structure.vertical_weight,
              "load_steps": options.load_steps, "prescribe_u": bool(prescribe_u),
              "newton": dataclasses.asdict(options.newton)}
    made = []

    def build():
        made.append(_gravity_state(model, scene.structure.vertical_weight, options,
                                   prescribe_u))
        return state_arrays(made[0])
    arrays, _ = setup_cache.cached("gravity", inputs, GRAVITY_SOURCES, build)
    return made[0] if made else state_of(arrays)


def _gravity_state(model, weight: float, options, prescribe_u: bool) -> ContinuumState:
    state = geostatic(model)
    loads = weight * np.arange(1, options.load_steps + 1) / options.load_steps
    controls = [Control((prescribe_u, False, True), (0.0, -n, 0.0)) for n in loads]
    controls.append(Control((prescribe_u, False, False), (0.0, -weight, 0.0)))
    return follow(model, state, controls, options.newton)[-1]


def state_arrays(state: ContinuumState) -> dict[str, np.ndarray]:
    """The arrays of a converged ``state`` (its tangent evaluated), as the set-up cache keeps
    them; :func:`state_of` makes the state again."""
    arrays = {name: np.asarray(getattr(state, name)) for name in _STATE_ARRAYS}
    arrays.update(plastic_strain=state.material.plastic_strain,
                  equivalent_plastic_strain=state.material.equivalent_plastic_strain,
                  region=state.material.region,
                  counts=np.array([state.iterations, state.cuts]))
    for name in ("eigenstrain", "tangent"):
        value = evaluated(getattr(state, name))
        if value is not None:
            arrays[name] = np.asarray(value)
    return arrays


def state_of(arrays: dict[str, np.ndarray]) -> ContinuumState:
    """The :class:`ContinuumState` of :func:`state_arrays`."""
    material = State(arrays["plastic_strain"], arrays["equivalent_plastic_strain"],
                     arrays["region"])
    iterations, cuts = (int(n) for n in arrays["counts"])
    return ContinuumState(**{name: arrays[name] for name in _STATE_ARRAYS}, material=material,
                          eigenstrain=arrays.get("eigenstrain"), tangent=arrays.get("tangent"),
                          iterations=iterations, cuts=cuts)
