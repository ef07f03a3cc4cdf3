"""What the OpenSees model of a scene takes: the reduced model's numbers, checked to be
representable in OpenSees.

:func:`opensees_spec` reads a scene through :func:`upliftlab.reduced.build_model`, so that the
OpenSees script gets exactly the masses, spring positions, stiffnesses, static compressions,
dashpots and yield forces upliftlab integrates, and refuses (:class:`~upliftlab.checks.InputError`)
what OpenSees has no equivalent for: Ewing's impact damper (Case C), exact rocking kinematics,
and initial states that are a static push.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checks import InputError
from ...motions import Motion
from ...reduced import build_model
from ...scenes import Scene
from .qz import QzSimple2Spring, qzsimple2_springs

__all__ = ["DASHPOT_MODELS", "POINTS_PER_PERIOD", "FoundationSpring", "Story", "OpenSeesSpec",
           "check_representable", "check_step_count", "default_step", "opensees_spec"]

#: How the foundation dashpots are modelled in OpenSees (``--dashpots``): ``clipped`` (the
#: default) wraps spring and dashpot in ``TensionOnly`` so that their sum never pulls, as
#: upliftlab's; ``detaching`` is stiffness-proportional Rayleigh damping on each spring's
#: current tangent (acts only in contact, never clipped); ``parallel`` is a ``Viscous``
#: material beside the compression-only spring (attached even while the spring is open).
DASHPOT_MODELS = ("clipped", "detaching", "parallel")
#: Default step of the OpenSees Newmark run: the largest divisor of the record step with this
#: many steps per shortest bonded period (average acceleration then lengthens that period by
#: about 0.1 %).
POINTS_PER_PERIOD = 60


@dataclass(frozen=True)
class FoundationSpring:
    """One foundation spring: position ``x`` from O (length), stiffness ``k`` (force/length),
    dashpot ``c`` (force·s/length), static compression ``f0`` and yield force ``fy`` (force; inf
    for an elastic spring)."""

    x: float
    k: float
    c: float
    f0: float
    fy: float


@dataclass(frozen=True)
class Story:
    """One story: ``height`` of its mass above O (length), ``weight`` (force), ``stiffness`` of
    the story spring below it (force/length), ``damping`` of its dashpot (force·s/length),
    ``yield_force`` (force, inf: elastic) and ``post_yield_ratio`` of the bilinear spring."""

    height: float
    weight: float
    stiffness: float
    damping: float
    yield_force: float
    post_yield_ratio: float


@dataclass(frozen=True)
class OpenSeesSpec:
    """Everything the standalone OpenSees script holds, in the scene's units.

    ``support`` uplift, bonded or fixed; ``rigid`` superstructure; ``p_delta``; the base body's
    ``vertical_weight`` W_v and ``rotary_inertia`` I₀ about O; ``springs`` and ``stories``;
    ``dashpots`` one of :data:`DASHPOT_MODELS`; ``dt`` the Newmark step and ``duration`` (s);
    the ground ``motion`` (accelerations in g every ``motion.dt``) and the top mass's
    ``initial_velocity`` (length/s); ``qz`` the QzSimple2 springs of a q–z bed (:mod:`.qz`),
    in the order of ``springs`` (empty for the other laws).
    """

    scene_name: str
    title: str
    case: str | None
    overrides: tuple[str, ...]
    units: str
    length: str
    force: str
    g: float
    support: str
    law: str
    rigid: bool
    p_delta: bool
    vertical_weight: float
    rotary_inertia: float
    springs: tuple[FoundationSpring, ...]
    stories: tuple[Story, ...]
    dashpots: str
    damping_ratio: float
    dt: float
    duration: float
    motion: Motion
    initial_velocity: float
    qz: tuple[QzSimple2Spring, ...] = ()

    @property
    def has_foundation(self) -> bool:
        return bool(self.springs)

    @property
    def has_dashpots(self) -> bool:
        return any(s.c > 0.0 for s in self.springs)

    @property
    def steps(self) -> int:
        return int(round(self.duration / self.dt))

    @property
    def dashpot_time(self) -> float:
        """β = c_i/k_i = 2ζ_f/ω_v (s), the same for every spring: how long the clipped dashpot
        acts ahead of a landing (a gap β·v closing at v)."""
        return self.springs[0].c / self.springs[0].k if self.has_foundation else 0.0


def check_representable(scene: Scene) -> None:
    """Refuse, with one line naming the field, what the OpenSees bridge cannot represent."""
    s, f, m = scene.structure, scene.foundation, scene.motion
    if f.law.name == "macro":
        raise InputError(
            "foundation.law = 'macro': the OpenSees script writes a bed of zeroLength springs, "
            "and OpenSeesPy has no section for one element under the base; valid: 'elastic', "
            "'elastoplastic', 'qz'")
    if f.support == "uplift" and f.restitution < 1.0:
        raise InputError(
            f"foundation.restitution = {f.restitution:g}: Ewing's impact damper (Case C) has "
            "no equivalent in OpenSees (no material adds a dashpot on recontact for a stroke "
            "set by the closing velocity and then locks); valid: 1 (Cases A and B)")
    if f.sways:
        raise InputError(
            f"foundation.sway_stiffness = {f.sway_stiffness:g}: the OpenSees script has no sway "
            "spring under the footing (its footing node is fixed horizontally); remove it")
    if f.dashpots is not None:
        raise InputError(
            "foundation.dashpots: the OpenSees script sizes every dashpot from "
            "foundation.damping_ratio (c_i proportional to k_i); remove foundation.dashpots")
    if f.law.name == "elastoplastic" and f.law.yield_multiple is None:
        key = "yield_forces" if f.law.yield_forces is not None else "capacity_multiple"
        raise InputError(
            f"foundation.{key}: the OpenSees script yields each spring at yield_multiple x F0, "
            "its elastic static force; a bed whose springs yield at other forces (some at rest) "
            "is not written; remove it and give foundation.yield_multiple")
    if s.kinematics != "small":
        raise InputError(
            f"structure.kinematics = {s.kinematics!r}: the OpenSees model (zeroLength springs "
            "and rigid links) is in small rotations, as the paper's; valid: 'small'")
    if m.type == "free" and (m.displacement or m.rotation):
        key = "displacement" if m.displacement else "rotation"
        raise InputError(
            f"motion.{key} = {getattr(m, key):g}: an initial {key} is upliftlab's static push, "
            "which the OpenSees script does not reproduce; valid: 0 (use motion.velocity or "
            "a ground motion)")


def check_step_count(scene: Scene, step: float, duration: float) -> float:
    """The Newmark steps of the OpenSees run, ``duration`` / ``step`` (both s); refused (before
    any file is written) above the scene's ``analysis.max_steps``, the limit every upliftlab
    run is held to: a step of 1e-12 s would otherwise write a script of 10¹³ steps."""
    steps = duration / step  # a float: a step of 5e-324 s makes it inf, not an overflow
    limit = scene.analysis.max_steps
    if steps >= limit + 0.5:  # the script takes round(duration / step) steps
        about = (f"the OpenSees run would take {steps:.4g} Newmark steps of {step:.3g} s "
                 f"({duration:g} s)")
        raise InputError(f"analysis.max_steps = {limit}: {about}; raise it (--set "
                         f"analysis.max_steps={math.ceil(steps)}) to write it anyway, or take "
                         "a larger step (--dt) or a shorter duration" if steps < 1e15 else
                         f"analysis.max_steps = {limit}: {about}; take a larger step (--dt) "
                         "or a shorter duration")
    return steps


def default_step(scene: Scene, motion: Motion) -> float:
    """``analysis.dt`` if the scene sets it, else the largest record step / n with
    :data:`POINTS_PER_PERIOD` steps per shortest bonded period (s)."""
    if scene.analysis.dt is not None:
        return scene.analysis.dt
    shortest = float(build_model(scene).bonded_periods()[-1])
    n = max(1, math.ceil(motion.dt * POINTS_PER_PERIOD / shortest - 1e-9))
    return motion.dt / n


def opensees_spec(scene: Scene, *, dt: float | None = None,
                  dashpots: str = "clipped") -> OpenSeesSpec:
    """The :class:`OpenSeesSpec` of ``scene`` (its motion is read here)."""
    check_representable(scene)
    if dashpots not in DASHPOT_MODELS:
        raise InputError(f"--dashpots = {dashpots!r}: valid: {', '.join(DASHPOT_MODELS)}")
    if scene.foundation.law.name == "qz" and dashpots != "clipped":
        raise InputError(f"--dashpots = {dashpots!r}: a q–z bed's dashpot is QzSimple2's own "
                         "(on its far field); valid: the default")
    model = build_model(scene)
    if scene.structure.p_delta and abs(model.static_rotation) > 1e-12:
        raise InputError(
            f"structure.p_delta = true with a foundation that tilts at rest (static rotation "
            f"{model.static_rotation:.3g} rad): upliftlab linearises P-Δ about the tilted rest "
            "state, which the OpenSees script does not; valid: a layout symmetric about O, or "
            "structure.p_delta = false")
    motion = scene.build_motion()
    duration = scene.analysis.duration or motion.duration
    motion = motion.extended(duration)
    step = default_step(scene, motion) if dt is None else dt
    if not (math.isfinite(step) and step > 0.0):
        raise InputError(f"--dt = {step:g}: must be a finite number > 0 (s)")
    if step > duration:
        raise InputError(f"--dt = {step:g}: longer than the run ({duration:g} s)")
    check_step_count(scene, step, duration)
    p = model.params
    found = p[model.foundation_slice]
    springs = tuple(FoundationSpring(float(r["x"]), float(r["k"]), float(r["c"]),
                                     float(r["f0"]), float(r["fy"])) for r in found)
    s = scene.structure
    story_c = p["c"][:model.story_count] if model.story_count else np.zeros(len(s.stories))
    stories = tuple(Story(st.height, st.weight, st.stiffness, float(c),
                          st.yield_force, st.post_yield_ratio if math.isfinite(st.yield_force)
                          else 0.0)
                    for st, c in zip(s.stories, story_c))
    u = scene.units
    return OpenSeesSpec(
        scene_name=scene.name, title=scene.title, case=scene.case,
        overrides=tuple(scene.overrides), units=u.name, length=u.length, force=u.force,
        g=scene.g, support=scene.foundation.support, law=scene.foundation.law.name,
        rigid=s.rigid,
        p_delta=s.p_delta, vertical_weight=s.vertical_weight, rotary_inertia=s.rotary_inertia,
        springs=springs, stories=stories, dashpots=dashpots,
        damping_ratio=scene.foundation.damping_ratio, dt=step, duration=duration,
        motion=motion, initial_velocity=motion.initial_velocity,
        qz=qzsimple2_springs(found) if scene.foundation.law.name == "qz" else ())
