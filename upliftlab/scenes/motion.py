"""The motion and the analysis of a scene: their records, how they are read from the scene's
``[motion]`` and ``[analysis]`` tables, and the motion a spec describes (:func:`build_motion`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .. import bounds, checks
from ..checks import InputError
from ..motions import (Motion, cosine_pulse, free_vibration, harmonic, load_motion, ricker_pulse,
                       sample_line, sine_pulse)
from .table import Table, choice, in_range, string
from ..units import UnitSystem

__all__ = ["MOTION_TYPES", "INTEGRATORS", "DEFAULT_RTOL", "DEFAULT_ENERGY_TOLERANCE",
           "DEFAULT_MAX_STEPS", "DEFAULT_MAX_MEMORY", "MAX_SCALE", "MotionSpec", "Analysis",
           "read_motion", "read_analysis", "build_motion"]

MOTION_TYPES = ("record", "free", "sine", "cosine", "ricker", "harmonic")
#: The reduced model's integrators by name (the scene and the command line check a name here;
#: the registry of what each is, ``upliftlab.reduced.integrators.METHODS``, has exactly these).
INTEGRATORS = ("events", "rk4", "abm4", "newmark", "hht")
#: Default budget of a run (``analysis.max_steps``, ``analysis.max_memory`` in GiB).
DEFAULT_MAX_STEPS, DEFAULT_MAX_MEMORY = 10_000_000, 4.0
#: Default relative tolerance of the event stepper's error control (``analysis.rtol``).
DEFAULT_RTOL = 1e-5
#: Default largest relative error of a run's energy balance (``analysis.energy_tolerance``).
DEFAULT_ENERGY_TOLERANCE = 1e-3


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


def read_motion(data, units: UnitSystem) -> MotionSpec:
    """The :class:`MotionSpec` of a ``[motion]`` table."""
    table = Table(data, "motion")
    kind = table.get("type", choice(MOTION_TYPES))
    spec: dict[str, Any] = {"type": kind,
                            "duration": table.get("duration", bounds.checker("duration", units),
                                                  None),
                            "dt": table.get("dt", bounds.checker("step", units), None)}
    if kind == "record":
        spec["name"] = table.get("name", _record_name)
        if table.has("scale") and table.has("pga"):
            raise InputError("motion: give scale or pga, not both")
        spec["scale"] = table.get("scale", in_range(-MAX_SCALE, MAX_SCALE), 1.0)
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
            spec["cycles"] = table.get("cycles", in_range(0.0, 1e4, low_open=True), 1.0)
        if kind == "ricker":
            spec["delay"] = table.get("delay", in_range(0.0, 1e6), None)
        if kind == "harmonic" and spec["duration"] is None:
            raise InputError("motion.duration is missing: a harmonic motion needs a duration (s)")
    table.done()
    return MotionSpec(**spec)


def _record_name(name: str, value) -> str:
    value = string(name, value)
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


def _refuse_a_record_beyond_100_g(record: Motion, scale: float) -> None:
    """Refuse a record whose PGA times ``scale`` would exceed 100 g (before it is scaled: the
    product may overflow) by naming the file and the line of its largest value when the file's
    own PGA is already beyond 100 g (the file is at fault, not ``motion.scale``); else
    ``motion.scale``."""
    if not abs(scale) * record.pga > 100.0:
        return
    if record.pga > 100.0:
        peak = int(abs(record.acceleration).argmax())
        line = sample_line(record, peak)
        where = f"motion file {record.source!r}" + (f" line {line}" if line else "")
        raise InputError(f"{where}: acceleration {record.acceleration[peak]:.3g} g, the "
                         "record's peak; valid: a PGA up to 100 g (a record in g; scale it "
                         "with motion.pga or motion.scale)")
    raise InputError(f"motion.scale = {scale:g}: the scaled record's PGA would be "
                     f"{abs(scale) * record.pga:.3g} g; valid: a PGA up to 100 g")


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
        if spec.pga is None:
            _refuse_a_record_beyond_100_g(motion, spec.scale)
        motion = (motion.scaled_to_pga(spec.pga) if spec.pga is not None
                  else motion.scaled(spec.scale))
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


def read_analysis(data, units: UnitSystem) -> Analysis:
    """The :class:`Analysis` of an ``[analysis]`` table."""
    table = Table(data, "analysis")
    step = bounds.checker("step", units)
    analysis = Analysis(
        integrator=table.get("integrator", choice(INTEGRATORS), "events"),
        dt=table.get("dt", step, None),
        subcycle=table.get("subcycle", checks.boolean, False),
        duration=table.get("duration", bounds.checker("duration", units), None),
        output_dt=table.get("output_dt", step, None),
        hht_alpha=table.get("hht_alpha", in_range(-1.0 / 3.0, 0.0), -0.1),
        rtol=table.get("rtol", in_range(0.0, 1e-2), DEFAULT_RTOL),
        energy_tolerance=table.get("energy_tolerance", in_range(1e-12, 1.0),
                                   DEFAULT_ENERGY_TOLERANCE),
        max_steps=table.get("max_steps", lambda n, v: checks.integer_at_least(n, v, 1),
                            DEFAULT_MAX_STEPS),
        max_memory=table.get("max_memory", in_range(0.0, 1e6, low_open=True),
                             DEFAULT_MAX_MEMORY),
    )
    table.done()
    return analysis
