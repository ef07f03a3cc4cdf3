"""Scenes: TOML files that describe a structure, its foundation, a motion and an analysis.

A scene is read, merged with one of its ``[cases.X]`` tables, patched with ``--set`` overrides
(dotted TOML keys), and validated into immutable dataclasses. Unknown keys are errors, and every
error names the field, the value and the valid range before any work starts.

The same scene runs in the reduced model and (with ``[soil]`` and ``[continuum]``) in the
continuum model. Units are declared by ``units`` and g follows from them.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import tomllib
from dataclasses import InitVar, dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from . import bounds, checks
from .checks import InputError
from .motions import (Motion, cosine_pulse, free_vibration, harmonic, load_motion, ricker_pulse,
                      sine_pulse)
from .units import UNIT_SYSTEMS, UnitSystem, unit_system

__all__ = [
    "SCHEMA_VERSION",
    "Story",
    "Structure",
    "Foundation",
    "MotionSpec",
    "Analysis",
    "Soil",
    "ContinuumOptions",
    "Scene",
    "load_scene",
    "scene_from_dict",
    "find_scene",
    "packaged_scenes",
    "apply_override",
    "build_motion",
]

SCHEMA_VERSION = 1
_MISSING = object()
#: Default budget of a run (``analysis.max_steps``, ``analysis.max_memory`` in GiB).
DEFAULT_MAX_STEPS, DEFAULT_MAX_MEMORY = 10_000_000, 4.0

SUPPORTS = ("uplift", "bonded", "fixed")
LAYOUTS = ("winkler", "edges", "equivalent", "end_stiffened", "custom")
LAWS = ("elastic", "elastoplastic")
IMPACT_MASSES = ("point", "tributary")
MOTION_TYPES = ("record", "free", "sine", "cosine", "ricker", "harmonic")
INTEGRATORS = ("events", "rk4", "abm4", "newmark", "hht")
KINEMATICS = ("small", "exact")
#: Default relative tolerance of the event stepper's error control (``analysis.rtol``).
DEFAULT_RTOL = 1e-5
#: Default largest relative error of a run's energy balance (``analysis.energy_tolerance``).
DEFAULT_ENERGY_TOLERANCE = 1e-3


class _Table:
    """A TOML table read key by key; :meth:`done` refuses keys nobody asked for."""

    def __init__(self, data: Any, path: str):
        if not isinstance(data, dict):
            raise InputError(f"{path} = {data!r}: expected a table")
        self.data, self.path, self.used = data, path, set()

    def get(self, key: str, check=None, default=_MISSING):
        self.used.add(key)
        name = f"{self.path}.{key}" if self.path else key
        if key not in self.data:
            if default is _MISSING:
                raise InputError(f"{name} is missing")
            return default
        value = self.data[key]
        return check(name, value) if check else value

    def has(self, key: str) -> bool:
        return key in self.data

    def done(self) -> None:
        unknown = sorted(set(self.data) - self.used)
        if unknown:
            where = f"{self.path}." if self.path else ""
            valid = ", ".join(sorted(self.used))
            raise InputError(f"{where}{unknown[0]}: unknown key (valid keys here: {valid})")


def _string(name: str, value) -> str:
    if not isinstance(value, str):
        raise InputError(f"{name} = {value!r}: expected a string")
    return value


def _choice(choices):
    return lambda name, value: checks.one_of(name, value, choices)


def _range(low, high, low_open=False, high_open=False):
    return lambda name, value: checks.in_range(name, value, low, high,
                                               low_open=low_open, high_open=high_open)


def _numbers(name: str, value) -> tuple[float, ...]:
    if not isinstance(value, list) or not value:
        raise InputError(f"{name} = {value!r}: expected a non-empty list of numbers")
    return tuple(checks.finite(f"{name}[{i}]", v) for i, v in enumerate(value))


# ---------------------------------------------------------------------------------------------
# Structure
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Story:
    """One story of a shear building: a lumped mass on a story spring.

    ``weight`` (force) at ``height`` (length, above the base centre O); ``stiffness`` of the story
    spring below it (force/length); ``yield_force`` (force; inf = elastic) with a bilinear
    ``post_yield_ratio``; ``damping_ratio`` of its parallel dashpot, as a fraction of critical
    for the fixed-base first mode (None: the structure's ratio).
    """

    weight: float
    height: float
    stiffness: float
    yield_force: float = math.inf
    post_yield_ratio: float = 0.0
    damping_ratio: float | None = None


@dataclass(frozen=True)
class Structure:
    """The superstructure (Ewing eqs. 6–8): one story (SDOF) or a shear building (MDOF).

    ``rotary_inertia`` is I₀, the mass moment of inertia of the rocking base body about O
    (mass·length²), excluding the story masses, which enter through their lateral DOFs.
    ``vertical_weight`` (force) is carried by the foundation and gives the vertical mass.
    ``rigid`` ties every story to the base rotation (u = 0). ``p_delta`` adds the P-Δ effect of
    the story weights: about the rocking base and on the story drifts. ``kinematics`` is
    ``small`` (the paper's small rotations) or ``exact``: the base rotates about the edge it
    leans towards, every mass moves on its exact path and gravity acts on the exact
    configuration (P-Δ exact, so ``p_delta`` is true).
    """

    stories: tuple[Story, ...]
    damping_ratio: float
    rotary_inertia: float
    vertical_weight: float
    rigid: bool = False
    p_delta: bool = False
    kinematics: str = "small"

    @property
    def weight(self) -> float:
        return sum(s.weight for s in self.stories)

    @property
    def height(self) -> float:
        """Height of the top mass (length)."""
        return self.stories[-1].height


def _story(table: _Table, sdof: bool, units: UnitSystem) -> Story:
    weight = table.get("weight", bounds.checker("force", units))
    height = table.get("height", bounds.checker("length", units))
    if table.has("stiffness") and table.has("period"):
        raise InputError(f"{table.path}: give stiffness or period, not both")
    if table.has("period") and sdof:
        period = table.get("period", bounds.checker("period", units))
        stiffness = (weight / units.gravity) * (2.0 * math.pi / period) ** 2
    else:
        stiffness = table.get("stiffness", bounds.checker("stiffness", units))
    yield_force = table.get("yield_force", lambda n, v: _force_or_inf(n, v, units), math.inf)
    ratio = table.get("post_yield_ratio", _range(0.0, 1.0, high_open=True), 0.0)
    damping = None if sdof else table.get("damping_ratio", _range(0.0, 1.0), None)
    return Story(weight, height, stiffness, yield_force, ratio, damping)


def _force_or_inf(name: str, value, units: UnitSystem) -> float:
    """A force within the physical range, or inf (no yield)."""
    value = checks.positive(name, value, allow_inf=True)
    return value if math.isinf(value) else bounds.check(name, value, "force", units)


def _structure(data, units: UnitSystem) -> Structure:
    table = _Table(data, "structure")
    if table.has("story"):
        stories_data = table.get("story")
        if not isinstance(stories_data, list) or not stories_data:
            raise InputError("structure.story: expected a list of story tables")
        stories = []
        for i, item in enumerate(stories_data):
            sub = _Table(item, f"structure.story.{i}")
            stories.append(_story(sub, sdof=False, units=units))
            sub.done()
        stories = tuple(stories)
    else:
        stories = (_story(table, sdof=True, units=units),)
    heights = [s.height for s in stories]
    for i in range(1, len(heights)):
        if heights[i] <= heights[i - 1]:
            raise InputError(f"structure.story.{i}.height = {heights[i]:g}: must exceed the "
                             f"story below ({heights[i - 1]:g})")
    rigid = table.get("rigid", checks.boolean, False)
    kinematics = table.get("kinematics", _choice(KINEMATICS), "small")
    p_delta = table.get("p_delta", checks.boolean, kinematics == "exact")
    if kinematics == "exact" and not p_delta:
        raise InputError("structure.p_delta = false with structure.kinematics = 'exact': exact "
                         "kinematics carries the weight's P-Δ exactly; valid: true (or remove it)")
    structure = Structure(
        stories=stories,
        damping_ratio=table.get("damping_ratio", _range(0.0, 1.0), 0.0),
        rotary_inertia=table.get("rotary_inertia", bounds.checker("rotary_inertia", units)),
        vertical_weight=table.get("vertical_weight", bounds.checker("force", units),
                                  sum(s.weight for s in stories)),
        rigid=rigid,
        p_delta=p_delta,
        kinematics=kinematics,
    )
    table.done()
    if kinematics == "exact" and structure.vertical_weight < structure.weight * (1 - 1e-12):
        raise InputError(f"structure.vertical_weight = {structure.vertical_weight:g}: with exact "
                         f"kinematics the story weights ride on the base; valid range is >= "
                         f"their sum {structure.weight:g}")
    return structure


# ---------------------------------------------------------------------------------------------
# Foundation
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Foundation:
    """The foundation under the base (Ewing eqs. 3, 9; Figs. 1, 6).

    ``support``: ``uplift`` (compression-only springs), ``bonded`` (springs also carry tension)
    or ``fixed`` (θ and V locked). ``half_width`` b (length). ``layout`` and ``springs`` (N) place
    the springs; ``stiffness`` is their total K_v (force/length). ``law`` is ``elastic`` or
    ``elastoplastic`` (yield at ``yield_multiple`` times the static compression). Dashpots in
    parallel carry ``damping_ratio`` of critical for the bonded vertical mode. ``restitution`` ε
    < 1 adds Ewing's impact damper with c* = ``impact_multiple`` · c_cr. ``impact_mass``: the
    mass behind a landing spring in c_cr and Δz — ``point`` (the paper's eq. 17: the structure's
    effective mass at the spring's position, so each landing spring removes (1 − ε²) of that
    mass's closing energy and a bed of N springs removes N times as much) or ``tributary``
    (that mass times the spring's share k_i/K_v of the bed, so the energy removed per landing
    of the whole base does not grow with N).
    """

    support: str
    half_width: float
    layout: str
    springs: int
    stiffness: float
    law: str = "elastic"
    yield_multiple: float = 3.0
    damping_ratio: float = 0.0
    restitution: float = 1.0
    impact_multiple: float = 10.0
    impact_mass: str = "point"
    end_stiffness_ratio: float = 1.0
    end_length: float = 0.0
    positions: tuple[float, ...] = ()
    stiffnesses: tuple[float, ...] = ()

    @property
    def width(self) -> float:
        """Full base width B = 2b (length)."""
        return 2.0 * self.half_width


#: Most springs a foundation may have: a bed finer than b/50000 resolves nothing more, and its
#: histories outgrow any memory (the run's memory is estimated by :mod:`upliftlab.budget`).
MAX_SPRINGS = 100_000


def _spring_count(name: str, value) -> int:
    count = checks.integer_at_least(name, value, 2)
    if count > MAX_SPRINGS:
        shown = f"{count:.3g}" if count > 10**12 else str(count)
        raise InputError(f"{name} = {shown}: valid range is [2, {MAX_SPRINGS}]")
    return count


def _foundation(data, vertical_mass: float, units: UnitSystem) -> Foundation:
    table = _Table(data, "foundation")
    support = table.get("support", _choice(SUPPORTS), "uplift")
    half_width = table.get("half_width", bounds.checker("length", units))
    layout = table.get("layout", _choice(LAYOUTS), "winkler")
    positions, stiffnesses = (), ()
    if layout == "custom":
        positions = table.get("positions", _numbers)
        stiffnesses = table.get("stiffnesses", _numbers)
        if len(positions) != len(stiffnesses):
            raise InputError(f"foundation.stiffnesses has {len(stiffnesses)} entries but "
                             f"foundation.positions has {len(positions)}: give one per spring")
        for i, (x, k) in enumerate(zip(positions, stiffnesses)):
            checks.in_range(f"foundation.positions[{i}]", x, -half_width, half_width)
            bounds.check(f"foundation.stiffnesses[{i}]", k, "stiffness", units)
        springs, stiffness = len(positions), float(sum(stiffnesses))
        _spring_count("foundation.springs (number of custom positions)", springs)
        given = table.get("springs", None, springs)
        if given != springs:
            raise InputError(f"foundation.springs = {given!r}: a custom layout has one spring "
                             f"per position ({springs}); set it to {springs} or remove it")
        for key in ("stiffness", "vertical_period"):
            if table.get(key, None, None) is not None:
                raise InputError(f"foundation.{key}: a custom layout takes its stiffness from "
                                 f"foundation.stiffnesses; remove foundation.{key} "
                                 f"(--set foundation.{key}= removes a key)")
    else:
        default_n = 2 if layout in ("edges", "equivalent") else _MISSING
        springs = table.get("springs", _spring_count, default_n)
        if layout in ("edges", "equivalent") and springs != 2:
            raise InputError(f"foundation.springs = {springs}: layout {layout!r} has exactly 2 "
                             "springs; set foundation.springs = 2 or remove it")
        if table.has("stiffness") and table.has("vertical_period"):
            raise InputError("foundation: give stiffness or vertical_period, not both")
        if table.has("vertical_period"):
            period = table.get("vertical_period", bounds.checker("period", units))
            stiffness = vertical_mass * (2.0 * math.pi / period) ** 2
        else:
            stiffness = table.get("stiffness", bounds.checker("stiffness", units))
    end_ratio, end_length = 1.0, 0.0
    if layout == "end_stiffened":
        end_ratio = table.get("end_stiffness_ratio", _range(1.0, 1e6))
        end_length = table.get("end_length", _range(0.0, 1.0, low_open=True, high_open=True))
    foundation = Foundation(
        support=support,
        half_width=half_width,
        layout=layout,
        springs=springs,
        stiffness=stiffness,
        law=table.get("law", _choice(LAWS), "elastic"),
        yield_multiple=table.get("yield_multiple", _range(1.0, 1e6, low_open=True), 3.0),
        damping_ratio=table.get("damping_ratio", _range(0.0, 2.0), 0.0),
        restitution=table.get("restitution", _range(0.0, 1.0), 1.0),
        impact_multiple=table.get("impact_multiple", _range(0.1, 1e4), 10.0),
        impact_mass=table.get("impact_mass", _choice(IMPACT_MASSES), "point"),
        end_stiffness_ratio=end_ratio,
        end_length=end_length,
        positions=positions,
        stiffnesses=stiffnesses,
    )
    table.done()
    return foundation


# ---------------------------------------------------------------------------------------------
# Motion and analysis
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class MotionSpec:
    """What motion drives the scene. Built into a :class:`~upliftlab.motions.Motion` on demand.

    ``record``: ``name`` (a name on ``UPLIFTLAB_MOTIONS`` or a path), optional ``dt`` for one
    column files, ``scale`` or ``pga`` (g). ``free``: ``velocity`` (length/s), ``displacement``
    (length), ``rotation`` (rad). Pulses: ``amplitude`` (g), ``period`` (s), ``cycles``, ``delay``.
    ``duration`` (s) extends or sets the length.
    """

    type: str
    name: str = ""
    dt: float | None = None
    scale: float = 1.0
    pga: float | None = None
    duration: float | None = None
    velocity: float = 0.0
    displacement: float = 0.0
    rotation: float = 0.0
    amplitude: float = 0.0
    period: float = 0.0
    cycles: float = 1.0
    delay: float | None = None


#: Largest factor a record may be scaled by (its PGA is then checked against 100 g).
MAX_SCALE = 1e4


def _motion_spec(data, units: UnitSystem) -> MotionSpec:
    table = _Table(data, "motion")
    kind = table.get("type", _choice(MOTION_TYPES))
    spec: dict[str, Any] = {"type": kind,
                            "duration": table.get("duration", bounds.checker("duration", units),
                                                  None),
                            "dt": table.get("dt", bounds.checker("step", units), None)}
    if kind == "record":
        spec["name"] = table.get("name", _record_name)
        if table.has("scale") and table.has("pga"):
            raise InputError("motion: give scale or pga, not both")
        spec["scale"] = table.get("scale", _range(-MAX_SCALE, MAX_SCALE), 1.0)
        spec["pga"] = table.get("pga", _positive_g(units), None)
    elif kind == "free":
        kinds = {"velocity": "velocity", "displacement": "displacement", "rotation": "rotation"}
        for key in ("velocity", "displacement", "rotation"):
            spec[key] = table.get(key, bounds.checker(kinds[key], units), 0.0)
        if not any(spec[k] for k in ("velocity", "displacement", "rotation")):
            raise InputError("motion.type = 'free' needs a nonzero motion.velocity, "
                             "motion.displacement or motion.rotation")
        if spec["duration"] is None:
            raise InputError("motion.duration is missing: free vibration needs a duration (s)")
    else:
        spec["amplitude"] = table.get("amplitude", bounds.checker("acceleration_g", units))
        spec["period"] = table.get("period", bounds.checker("period", units))
        if kind in ("sine", "cosine"):
            spec["cycles"] = table.get("cycles", _range(0.0, 1e4, low_open=True), 1.0)
        if kind == "ricker":
            spec["delay"] = table.get("delay", _range(0.0, 1e6), None)
        if kind == "harmonic" and spec["duration"] is None:
            raise InputError("motion.duration is missing: a harmonic motion needs a duration (s)")
    table.done()
    return MotionSpec(**spec)


def _record_name(name: str, value) -> str:
    value = _string(name, value)
    if not value.strip():
        raise InputError(f"{name} = {value!r}: expected a record name on UPLIFTLAB_MOTIONS or "
                         "a file path")
    return value


def _positive_g(units: UnitSystem):
    def check(name, value):
        return bounds.check(name, checks.positive(name, value), "acceleration_g", units)
    return check


def _default_step(duration: float | None, step: float) -> float:
    """The default sample step of a built-in motion: ``step``, or the nearest smaller one that
    divides ``duration`` into whole steps (so that the motion lasts exactly ``duration``)."""
    if duration is None:
        return step
    return duration / max(1, math.ceil(duration / step - 1e-9))


def build_motion(spec: MotionSpec) -> Motion:
    """The :class:`Motion` a spec describes (reads the record file if it names one).

    ``duration`` is the motion's length: a record or pulse is cut or padded with zero
    acceleration to it. It must be a whole number of the motion's steps: of the file's step for
    a record, of ``dt`` when given, else the default step (0.01 s for free vibration, 0.005 s
    for pulses) is shortened to divide it. A scaled record whose PGA exceeds 100 g is refused.
    """
    dt = spec.dt
    if spec.type == "record":
        motion = load_motion(spec.name, dt=dt)
        motion = motion.scaled_to_pga(spec.pga) if spec.pga is not None else motion.scaled(spec.scale)
        if motion.pga > 100.0:
            which = (f"motion.pga = {spec.pga:g}" if spec.pga is not None
                     else f"motion.scale = {spec.scale:g}")
            raise InputError(f"{which}: the scaled record's PGA would be {motion.pga:.3g} g; "
                             "valid: a PGA up to 100 g")
    elif spec.type == "free":
        motion = free_vibration(spec.duration, dt or _default_step(spec.duration, 0.01),
                                velocity=spec.velocity, displacement=spec.displacement,
                                rotation=spec.rotation)
    elif spec.type == "harmonic":
        motion = harmonic(spec.amplitude, spec.period, spec.duration,
                          dt=dt or _default_step(spec.duration, 0.005))
    elif spec.type == "ricker":
        motion = ricker_pulse(spec.amplitude, spec.period,
                              dt=dt or _default_step(spec.duration, 0.005), delay=spec.delay)
    else:
        pulse = sine_pulse if spec.type == "sine" else cosine_pulse
        motion = pulse(spec.amplitude, spec.period, spec.cycles,
                       dt=dt or _default_step(spec.duration, 0.005))
    if spec.duration is not None:
        motion = motion.with_duration(spec.duration)
    return motion


@dataclass(frozen=True)
class Analysis:
    """How to integrate: ``integrator``, time step ``dt`` (s; None = automatic; for the event
    stepper under error control the longest step), ``subcycle`` (split a step beyond the
    stability limit instead of refusing it), ``duration`` (s; None = the motion's),
    ``output_dt`` (s; None = automatic), ``hht_alpha`` in [−1/3, 0] for ``hht``. ``rtol`` is
    the event stepper's relative tolerance per step (0: fixed steps of ``dt``);
    ``energy_tolerance`` the largest relative error of the energy balance a run may end with
    before it is reported as failed.

    The run's budget (:mod:`upliftlab.budget`): a run that needs more than ``max_steps`` time
    or load steps, or more than ``max_memory`` GiB for its arrays, is refused before it starts
    with what it would cost; raise them to run it anyway.
    """

    integrator: str = "events"
    dt: float | None = None
    subcycle: bool = False
    duration: float | None = None
    output_dt: float | None = None
    hht_alpha: float = -0.1
    rtol: float = DEFAULT_RTOL
    energy_tolerance: float = DEFAULT_ENERGY_TOLERANCE
    max_steps: int = DEFAULT_MAX_STEPS
    max_memory: float = DEFAULT_MAX_MEMORY


def _analysis(data, units: UnitSystem) -> Analysis:
    table = _Table(data, "analysis")
    step = bounds.checker("step", units)
    analysis = Analysis(
        integrator=table.get("integrator", _choice(INTEGRATORS), "events"),
        dt=table.get("dt", step, None),
        subcycle=table.get("subcycle", checks.boolean, False),
        duration=table.get("duration", bounds.checker("duration", units), None),
        output_dt=table.get("output_dt", step, None),
        hht_alpha=table.get("hht_alpha", _range(-1.0 / 3.0, 0.0), -0.1),
        rtol=table.get("rtol", _range(0.0, 1e-2), DEFAULT_RTOL),
        energy_tolerance=table.get("energy_tolerance", _range(1e-12, 1.0),
                                   DEFAULT_ENERGY_TOLERANCE),
        max_steps=table.get("max_steps", lambda n, v: checks.integer_at_least(n, v, 1),
                            DEFAULT_MAX_STEPS),
        max_memory=table.get("max_memory", _range(0.0, 1e6, low_open=True),
                             DEFAULT_MAX_MEMORY),
    )
    table.done()
    return analysis


# ---------------------------------------------------------------------------------------------
# Continuum sections (used by upliftlab.continuum; the reduced model ignores them)
# ---------------------------------------------------------------------------------------------

SOIL_MODELS = ("elastic", "tresca", "von_mises", "drucker_prager", "mohr_coulomb")
INTERFACES = ("frictionless", "bonded", "coulomb")
ELEMENTS = ("P1", "P2", "Q1", "Q2")
DYNAMICS = ("explicit", "implicit")


@dataclass(frozen=True)
class Soil:
    """Plane-strain soil under the footing.

    ``youngs_modulus`` E (force/length²), ``poisson_ratio`` ν, ``density`` ρ (mass/length³).
    ``model``: elastic, tresca / von_mises (``undrained_strength`` c_u, force/length²), or
    drucker_prager / mohr_coulomb (``cohesion`` c, ``friction_angle`` φ and ``dilation_angle`` ψ
    in degrees). ``layer_depth`` (length) puts a rigid base at that depth (None: the box bottom).
    ``interface`` under the footing: frictionless, bonded, or coulomb with ``interface_friction``.
    ``k0`` the geostatic ratio σh/σv (None: the continuum model's default for ``model``).
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float = 0.0
    model: str = "elastic"
    undrained_strength: float | None = None
    cohesion: float = 0.0
    friction_angle: float = 0.0
    dilation_angle: float = 0.0
    hardening_modulus: float = 0.0
    layer_depth: float | None = None
    interface: str = "frictionless"
    interface_friction: float = 0.0
    k0: float | None = None

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


def _positive_strength(units: UnitSystem):
    def check(name, value):
        return bounds.check(name, checks.positive(name, value), "strength", units)
    return check


def _soil(data, units: UnitSystem) -> Soil:
    table = _Table(data, "soil")
    model = table.get("model", _choice(SOIL_MODELS), "elastic")
    strength = bounds.checker("strength", units)
    soil = Soil(
        youngs_modulus=table.get("youngs_modulus", bounds.checker("modulus", units)),
        poisson_ratio=table.get("poisson_ratio", _range(-1.0, 0.5, low_open=True, high_open=True)),
        density=table.get("density", bounds.checker("density", units), 0.0),
        model=model,
        undrained_strength=table.get("undrained_strength", _positive_strength(units),
                                     _MISSING if model in ("tresca", "von_mises") else None),
        cohesion=table.get("cohesion", strength, 0.0),
        friction_angle=table.get("friction_angle", _range(0.0, 60.0, high_open=True), 0.0),
        dilation_angle=table.get("dilation_angle", _range(0.0, 60.0, high_open=True), 0.0),
        hardening_modulus=table.get("hardening_modulus", bounds.checker("hardening", units),
                                    0.0),
        layer_depth=table.get("layer_depth", bounds.checker("length", units), None),
        interface=table.get("interface", _choice(INTERFACES), "frictionless"),
        interface_friction=table.get("interface_friction", _range(0.0, 10.0), 0.0),
        k0=table.get("k0", _range(0.0, 10.0, low_open=True), None),
    )
    if soil.dilation_angle > soil.friction_angle:
        raise InputError(f"soil.dilation_angle = {soil.dilation_angle:g}: valid range is "
                         f"[0, friction_angle = {soil.friction_angle:g}]")
    table.done()
    return soil


@dataclass(frozen=True)
class ContinuumOptions:
    """Continuum domain and mesh: a box ``domain_width`` × ``domain_depth`` (multiples of the
    footing width B), ``element`` type, ``elements_across`` the footing, ``grading`` towards the
    footing edges, ``base`` (rigid or compliant) and side/bottom ``boundary`` (fixed or lysmer).
    ``intorder`` is the quadrature order (None: the element's default, Q2 2×2 reduced).
    ``dynamics``: the time integration of a dynamic run, ``explicit`` (central differences,
    lumped mass; the default) or ``implicit`` (HHT-α with Newton). ``energy_tolerance``: the
    largest energy balance error (fraction of the input energy) a dynamic run may have before
    it counts as failed, in (0, 1].
    """

    domain_width: float = 10.0
    domain_depth: float = 10.0
    element: str = "Q2"
    elements_across: int = 16
    grading: float = 1.0
    base: str = "rigid"
    boundary: str = "fixed"
    intorder: int | None = None
    dynamics: str = "explicit"
    energy_tolerance: float = 0.05


#: Most elements across the footing: 1024 gives about 10⁸ DOFs (the run's memory is estimated
#: and refused above its budget well before that; this bound keeps the estimate itself cheap).
MAX_ELEMENTS_ACROSS = 1024


def _integer(low: int, high: int):
    def check(name, value):
        value = checks.integer_at_least(name, value, low)
        if value > high:
            raise InputError(f"{name} = {value}: valid range is [{low}, {high}]")
        return value
    return check


def _continuum(data) -> ContinuumOptions:
    table = _Table(data, "continuum")
    options = ContinuumOptions(
        domain_width=table.get("domain_width", _range(1.0, 1e4, low_open=True), 10.0),
        domain_depth=table.get("domain_depth", _range(0.25, 1e4), 10.0),
        element=table.get("element", _choice(ELEMENTS), "Q2"),
        elements_across=table.get("elements_across", _integer(2, MAX_ELEMENTS_ACROSS), 16),
        grading=table.get("grading", _range(1.0, 100.0), 1.0),
        base=table.get("base", _choice(("rigid", "compliant")), "rigid"),
        boundary=table.get("boundary", _choice(("fixed", "lysmer")), "fixed"),
        intorder=table.get("intorder", _integer(1, 10), None),
        dynamics=table.get("dynamics", _choice(DYNAMICS), "explicit"),
        energy_tolerance=table.get("energy_tolerance", _range(0.0, 1.0, low_open=True), 0.05),
    )
    table.done()
    return options


# ---------------------------------------------------------------------------------------------
# Scene
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Scene:
    """A validated scene. ``data`` is the merged table it came from (for provenance).

    The fields are the scene; ``data``, :attr:`digest` and :attr:`table` describe them. A scene
    made otherwise than by :func:`scene_from_dict` (``dataclasses.replace``, or the typed
    :meth:`replace`) is validated again from its fields, with the same checks and messages as
    a file; if its fields no longer match ``data``, ``data`` becomes the fields' own table and
    the changes are added to ``overrides``, so that the provenance of a run always describes
    the scene that ran (:mod:`upliftlab.scene_edit`).
    """

    title: str
    units: UnitSystem
    structure: Structure
    foundation: Foundation
    motion: MotionSpec
    analysis: Analysis
    soil: Soil | None = None
    continuum: ContinuumOptions | None = None
    description: str = ""
    reference: str = ""
    cases: tuple[str, ...] = ()
    case: str | None = None
    source: str = ""
    overrides: tuple[str, ...] = ()
    data: dict = field(default_factory=dict, repr=False, compare=False)
    validated: InitVar[bool] = False

    def __post_init__(self, validated: bool) -> None:
        if not validated:
            from .scene_edit import revalidate
            revalidate(self)

    @property
    def g(self) -> float:
        """Acceleration of gravity in the scene's units (length/s²)."""
        return self.units.gravity

    @property
    def name(self) -> str:
        stem = Path(self.source).stem if self.source else "scene"
        return f"{stem}-{self.case}" if self.case else stem

    @property
    def table(self) -> dict:
        """The scene's own table, derived from its fields: every value explicit (defaults
        and derived stiffnesses included), in the scene's units; validating it gives back
        this scene."""
        from .scene_edit import scene_table
        return scene_table(self)

    @property
    def digest(self) -> str:
        """SHA-256 of :attr:`table`: equal digests mean equal inputs, however the scene was
        written or changed."""
        text = json.dumps(self.table, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()

    def build_motion(self) -> Motion:
        return build_motion(self.motion)

    def with_overrides(self, *overrides: str) -> Scene:
        """This scene with more ``key=value`` overrides (dotted TOML keys)."""
        data = copy.deepcopy(self.data)
        _apply_overrides(data, overrides)
        return scene_from_dict(data, source=self.source, case=self.case,
                               overrides=self.overrides + tuple(overrides), merged=True)

    def replace(self, table: str, **fields) -> Scene:
        """This scene with ``fields`` of one record changed, validated as a file would be:
        ``scene.replace("foundation", springs=40)``. ``table`` is ``structure``, ``story``
        (the one story of an SDOF; ``story.1`` for a story of a building), ``foundation``,
        ``motion``, ``analysis``, ``soil`` or ``continuum``; each field is a field of that
        record, in the scene's units. The change is recorded in ``overrides``."""
        from .scene_edit import replace_fields
        return replace_fields(self, table, fields)


def scene_from_dict(data: dict, *, source: str = "", case: str | None = None,
                    overrides: tuple[str, ...] = (), merged: bool = False,
                    motion: str | None = None) -> Scene:
    """Validate a scene table (as parsed from TOML) into a :class:`Scene`.

    Unless ``merged``, the ``[cases.<case>]`` table is merged in, the motion replaced by the
    record ``motion`` (a name on UPLIFTLAB_MOTIONS or a path) if given, and ``overrides``
    applied, in that order.
    """
    data = copy.deepcopy(data)
    if not merged:
        in_cases = [o for o in overrides if _override_key(o).split(".")[0] == "cases"]
        for item in in_cases:  # edit the case table itself, before it is merged
            _check_case_override(item, case, data.get("cases"))
            apply_override(data, item)
        cases_table = data.get("cases", {})
        data = _merge_case(data, case)
        if motion is not None:
            data["motion"] = {"type": "record", "name": str(motion)}
        _apply_overrides(data, [o for o in overrides if o not in in_cases])
    cases_table = data.get("cases", {}) if merged else cases_table
    table = _Table(data, "")
    schema = table.get("schema", lambda n, v: checks.integer_at_least(n, v, 1))
    if schema != SCHEMA_VERSION:
        raise InputError(f"schema = {schema}: this upliftlab reads schema {SCHEMA_VERSION}")
    units = unit_system(table.get("units", _string))
    g = units.gravity
    structure = _structure(table.get("structure"), units)
    vertical_mass = structure.vertical_weight / g
    scene = Scene(
        title=table.get("title", _string, ""),
        description=table.get("description", _string, ""),
        reference=table.get("reference", _string, ""),
        units=units,
        structure=structure,
        foundation=_foundation(table.get("foundation"), vertical_mass, units),
        motion=_motion_spec(table.get("motion"), units),
        analysis=_analysis(table.get("analysis", None, {}), units),
        soil=_soil(table.get("soil"), units) if table.has("soil") else None,
        continuum=_continuum(table.get("continuum")) if table.has("continuum") else None,
        cases=tuple(cases_table) if isinstance(cases_table, dict) else (),
        case=case,
        source=source,
        overrides=tuple(overrides),
        data=data,
        validated=True,
    )
    table.get("cases", None, None)
    table.done()
    _check_consistency(scene)
    return scene


def _check_consistency(scene: Scene) -> None:
    s, f = scene.structure, scene.foundation
    if s.rigid and f.support == "fixed":
        raise InputError("structure.rigid = true with foundation.support = 'fixed': "
                         "a rigid structure on a fixed base has no motion")
    if s.rotary_inertia == 0.0 and not s.rigid and f.support != "fixed":
        raise InputError("structure.rotary_inertia = 0: the rocking base needs a mass moment of "
                         "inertia > 0 (mass·length²) unless structure.rigid = true")


def _merge_case(data: dict, case: str | None) -> dict:
    cases = data.pop("cases", {})
    if case is None:
        return data
    if not isinstance(cases, dict) or case not in cases:
        valid = ", ".join(map(repr, cases)) if isinstance(cases, dict) and cases else "none"
        raise InputError(f"case = {case!r}: not defined in this scene (cases: {valid})")
    _deep_merge(data, cases[case], f"cases.{case}")
    return data


def _deep_merge(base: dict, patch: dict, path: str) -> None:
    if not isinstance(patch, dict):
        raise InputError(f"{path} = {patch!r}: expected a table")
    for key, value in patch.items():
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            _deep_merge(base[key], value, f"{path}.{key}")
        else:
            base[key] = copy.deepcopy(value)


def _override_key(item: str) -> str:
    return item.split("=", 1)[0].strip()


def _check_case_override(item: str, case: str | None, cases) -> None:
    """An override of ``cases.X...`` only means something for the case that runs."""
    parts = [p for p in _override_key(item).split(".") if p]
    if len(parts) < 3 or parts[1] != case:
        running = f"case {case!r}" if case is not None else "no case (--case is not given)"
        raise InputError(f"--set {item!r}: has no effect: this run uses {running}; "
                         f"override the scene's fields directly (e.g. --set "
                         f"{'.'.join(parts[2:]) or 'foundation.restitution'}=...), or select "
                         f"the case with --case {parts[1] if len(parts) > 1 else 'X'}")
    if not isinstance(cases, dict) or not isinstance(cases.get(case), dict):
        raise InputError(f"--set {item!r}: the scene has no table cases.{case}")


def _apply_overrides(data: dict, overrides) -> None:
    """Apply ``overrides`` in order; refuse one that changes the unit system, which would
    reinterpret every number of the scene in other units."""
    declared = data.get("units")
    for item in overrides:
        if _override_key(item).split(".")[0] == "cases":
            raise InputError(f"--set {item!r}: has no effect: the scene's case is already "
                             "merged; override the scene's fields directly")
        apply_override(data, item)
    new = data.get("units")
    if declared is not None and isinstance(new, str) and new != declared and new in UNIT_SYSTEMS:
        raise InputError(f"units = {data.get('units')!r}: every number of this scene is in "
                         f"{declared!r}; an override cannot convert them. Write the values in "
                         f"{data.get('units')!r} in a scene file of its own")


def _parse_value(text: str):
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def apply_override(data: dict, item: str) -> None:
    """Apply one ``dotted.key=value`` override in place. The value is read as TOML, else text.

    List entries are addressed by index: ``structure.story.1.stiffness=300``. An empty value
    removes the key: ``foundation.vertical_period=``.
    """
    if "=" not in item:
        raise InputError(f"--set {item!r}: expected KEY=VALUE with a dotted TOML key")
    key, text = item.split("=", 1)
    parts = [p for p in key.strip().split(".") if p]
    if not parts:
        raise InputError(f"--set {item!r}: empty key")
    node = data
    for depth, part in enumerate(parts[:-1]):
        where = ".".join(parts[: depth + 1])
        if isinstance(node, list):
            node = node[_index(part, node, where)]
        else:
            node = node.setdefault(part, {})
        if not isinstance(node, (dict, list)):
            raise InputError(f"--set {item!r}: {where} is a value, not a table")
    last = parts[-1]
    if isinstance(node, list):
        node[_index(last, node, key)] = _parse_value(text.strip())
    elif not text.strip():
        node.pop(last, None)
    else:
        node[last] = _parse_value(text.strip())


def _index(part: str, node: list, where: str) -> int:
    if not part.isdigit() or int(part) >= len(node):
        raise InputError(f"--set {where}: index {part!r} is not in 0..{len(node) - 1}")
    return int(part)


def packaged_scenes() -> dict[str, Path]:
    """The scene files shipped with upliftlab, by name (in a source checkout imported as it is,
    the ``scenes/`` folder beside the package)."""
    try:
        root = resources.files("upliftlab.scene_files")
    except ModuleNotFoundError:
        root = Path(__file__).resolve().parent.parent / "scenes"
    return {Path(p.name).stem: Path(str(p)) for p in root.iterdir() if p.name.endswith(".toml")}


#: Largest scene file read (bytes).
MAX_SCENE_BYTES = 16 * 2**20


def find_scene(name_or_path: str) -> Path:
    """A scene file given by a path, or the packaged scene of that name."""
    path = Path(name_or_path).expanduser()
    if path.is_file():
        return path
    scenes = packaged_scenes()
    stem = path.stem if path.suffix == ".toml" else name_or_path
    if stem in scenes:
        return scenes[stem]
    raise InputError(f"scene {name_or_path!r}: no such file, and no packaged scene of that name "
                     f"(packaged: {', '.join(sorted(scenes))})")


def load_scene(name_or_path: str, case: str | None = None,
               overrides: tuple[str, ...] | list[str] = (), motion: str | None = None) -> Scene:
    """Read, merge, override and validate a scene file (see :func:`scene_from_dict`)."""
    path = find_scene(str(name_or_path))
    try:
        size = path.stat().st_size
        if size > MAX_SCENE_BYTES:
            raise InputError(f"scene {str(path)!r}: {size / 2**20:.0f} MiB; a scene file may "
                             f"hold at most {MAX_SCENE_BYTES // 2**20} MiB of TOML")
        data = tomllib.loads(path.read_bytes().decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise InputError(f"scene {str(path)!r}: not UTF-8 text (byte {exc.start}); a scene is "
                         "a TOML file") from None
    except OSError as exc:
        raise InputError(f"scene {str(path)!r}: cannot read it ({exc.strerror})") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"scene {str(path)!r}: not valid TOML ({exc})") from None
    return scene_from_dict(data, source=str(path), case=case, overrides=tuple(overrides),
                           motion=motion)

