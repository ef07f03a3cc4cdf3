"""The Winkler-against-continuum study's options, and the checks of its options and scene."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ....anchors import (HALF_PLANE_ONSET_ECCENTRICITY, WINKLER_ONSET_ECCENTRICITY,
                         undrained_capacity)
from .... import checks
from ....checks import InputError
from ....scenes import Scene


STUDY = "winkler_vs_continuum"
DYNAMIC_MISSING = "dynamic comparison not run: continuum dynamics unavailable"
ONSET_ANCHOR = HALF_PLANE_ONSET_ECCENTRICITY  # e/B, rigid strip on an elastic half-plane
WINKLER_ONSET = WINKLER_ONSET_ECCENTRICITY  # e/B of a uniform tensionless Winkler bed
STATIC_MOTION = {"type": "free", "velocity": 1.0, "duration": 1.0}  # unused by the statics


# ---------------------------------------------------------------------------------------------
# Options
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Options:
    """What the study computes.

    ``springs`` of each bed (a multiple of 6 puts the default end zones on strip edges);
    ``end_length`` R_e of the end-stiffened bed, a fraction of the half-width b (NIST
    convention; 1/3 is ATC-40's B/6 per end); ``max_end_stiffness_ratio`` the largest R_k it may
    take. ``theta_ratios``: rotations θ/θ_on at which M, c and settlement are compared (θ_on =
    2N(1 − ν)/(π G B), the elastic half-plane's uplift rotation); ``monotonic_steps``
    geometric steps of the monotonic pushover beyond 1.5 θ_on. ``cycle_ratios``: amplitudes
    θ/θ_on of the cyclic path (one full cycle each), ``cycle_steps`` per quarter cycle.
    ``settlement_ratio``: the vertical pushover goes to this × B in ``vertical_steps``.
    ``fast_overrides``: scene overrides (``--set`` style) applied in fast mode (a coarse mesh);
    ``dynamic_overrides`` for the continuum's dynamic runs in either mode, and
    ``fast_dynamic_overrides`` on top of them in fast mode. (Full mode runs its dynamics on 8
    elements across B, 5184 DOFs: on 10 s of El Centro its peak θ is 1.1 % below the 16-across
    mesh's in an eighth of the time, benchmarks/CONTINUUM.md; 16 across takes about 8 minutes
    per record, which would take the full report near its 30-minute budget.)
    ``adequate``: the error within which the recommendation calls a calibration adequate.
    ``dynamic``: run the dynamic comparison when the continuum dynamics is available: the
    scene's pulse (cut to ``pulse_duration`` s if given) and, in full mode, the ``records``
    (names on ``UPLIFTLAB_MOTIONS``, cut to ``record_duration`` s if given); histories are kept
    every ``history_dt`` s. ``figures``: write PNGs.
    """

    springs: int = 48
    end_length: float = 1.0 / 3.0
    max_end_stiffness_ratio: float = 10.0
    theta_ratios: tuple[float, ...] = (2.0, 5.0, 10.0, 30.0)
    monotonic_steps: int = 14
    cycle_ratios: tuple[float, ...] = (2.0, 5.0, 10.0)
    cycle_steps: int = 4
    settlement_ratio: float = 0.05
    vertical_steps: int = 10
    fast_overrides: tuple[str, ...] = ("continuum.elements_across=8",)
    dynamic_overrides: tuple[str, ...] = ()
    fast_dynamic_overrides: tuple[str, ...] = ("continuum.elements_across=4",)
    adequate: float = 0.10
    dynamic: bool = True
    pulse_duration: float | None = None
    records: tuple[str, ...] = ("elcentro_1940_ns",)
    record_duration: float | None = None
    history_dt: float = 0.01
    figures: bool = True


FULL_OPTIONS = Options(pulse_duration=3.0, record_duration=10.0,
                       dynamic_overrides=("continuum.elements_across=8",))
FAST_OPTIONS = Options(monotonic_steps=8, cycle_ratios=(2.0, 6.0), cycle_steps=2,
                       vertical_steps=8, pulse_duration=2.0, records=())


def check_options(options: Options) -> Options:
    """Validate the options; an :class:`InputError` names the field, value and valid range."""
    if not isinstance(options, Options):
        raise InputError(f"options = {options!r}: expected a winkler_vs_continuum.Options")
    checks.integer_at_least("options.springs", options.springs, 6)
    checks.in_range("options.end_length", options.end_length, 0.0, 1.0, low_open=True,
                    high_open=True)
    checks.in_range("options.max_end_stiffness_ratio", options.max_end_stiffness_ratio, 1.0,
                    1e4, low_open=True)
    checks.ascending("options.theta_ratios", options.theta_ratios, 1.0, 1000.0, low_open=True)
    checks.integer_at_least("options.monotonic_steps", options.monotonic_steps, 2)
    checks.ascending("options.cycle_ratios", options.cycle_ratios, 0.0, 1000.0, low_open=True)
    checks.integer_at_least("options.cycle_steps", options.cycle_steps, 1)
    checks.in_range("options.settlement_ratio", options.settlement_ratio, 0.0, 0.5,
                    low_open=True)
    checks.integer_at_least("options.vertical_steps", options.vertical_steps, 2)
    for name in ("fast_overrides", "dynamic_overrides", "fast_dynamic_overrides"):
        value = getattr(options, name)
        if isinstance(value, str) or not all(isinstance(s, str) and "=" in s for s in value):
            raise InputError(f"options.{name} = {value!r}: expected a list of "
                             "'dotted.key=value' scene overrides")
    checks.in_range("options.adequate", options.adequate, 0.0, 10.0, low_open=True)
    checks.boolean("options.dynamic", options.dynamic)
    for name in ("pulse_duration", "record_duration"):
        if getattr(options, name) is not None:
            checks.in_range(f"options.{name}", getattr(options, name), 0.0, 1e4, low_open=True)
    if isinstance(options.records, str) or not all(isinstance(r, str) and r
                                                   for r in options.records):
        raise InputError(f"options.records = {options.records!r}: expected a list of motion "
                         "names (on UPLIFTLAB_MOTIONS)")
    checks.in_range("options.history_dt", options.history_dt, 0.0, 1.0, low_open=True)
    checks.boolean("options.figures", options.figures)
    return options


def check_scene(scene: Scene) -> None:
    """Refuse a scene the study cannot compare (before any work)."""
    if scene.soil is None:
        raise InputError(f"scene {scene.name!r}: soil is missing; the study needs a [soil] "
                         "table for the continuum reference")
    if scene.foundation.support != "uplift":
        raise InputError(f"scene {scene.name!r}: foundation.support = "
                         f"{scene.foundation.support!r}; the study needs 'uplift'")
    soil, N, B = scene.soil, scene.structure.vertical_weight, scene.foundation.width
    if soil.undrained and soil.undrained_strength is not None:
        capacity = undrained_capacity(soil.undrained_strength, soil.undrained_strength_gradient,
                                      B, rough=soil.interface == "bonded")
        if not N < capacity:
            rule = "Prandtl (2 + π) c_u B" if soil.undrained_strength_gradient == 0.0 else \
                "Davis & Booker F [(2 + π) c_u + k B/4] B"
            raise InputError(f"structure.vertical_weight = {N:g}: the footing cannot carry it; "
                             f"valid range is (0, {capacity:g}) ({rule})")


def finite_or_none(value: float):
    return float(value) if math.isfinite(value) else None
