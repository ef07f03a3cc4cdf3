"""How well does a Winkler bed match the continuum? Calibrate beds from the continuum, compare.

The continuum (a plane-strain soil domain under a rigid footing, :mod:`upliftlab.continuum`) is
the reference. From it the study calibrates Winkler beds of compression-only springs
(:mod:`upliftlab.reduced`), under the same footing width B, vertical load N and height h:

* ``uniform``: a uniform bed whose bonded rocking stiffness Σ k_i x_i² equals the continuum's
  K_r (anchors §4: calibrate Winkler moduli to K_r);
* ``end_stiffened``: a bed with stiffer end zones (OpenSees ``ShallowFoundationGen`` /
  Harden–Hutchinson / ATC-40 practice) of a given end length R_e (a fraction of the half-width
  b; the default 1/3 is ATC-40's B/6 at each end), whose end-stiffness ratio R_k and total
  stiffness are solved so that the bed has both the continuum's K_r and the domain's K_v.
  K_v of a strip in 2D depends on the domain size (anchors §4), and no bed under the footing has
  K_θ/K_v > b²: when the target K_r/K_v lies outside what R_k ∈ [1, R_k,max] reaches, the bed
  keeps K_r exactly, takes the nearest R_k, and the K_v it then misses is reported;
* ``uniform_plastic``, ``end_stiffened_plastic``: the same beds with elasto-plastic springs that
  yield at FS_v times their static compression, FS_v = q_ult B/N with q_ult from the
  continuum's vertical pushover to failure.

**Compared** (bed against continuum, same N, B, h): K_r and K_v, the uplift-onset moment, the
monotonic M–θ (moment, contact length and settlement at several θ, the largest moment), a
cyclic M–θ path (peak moments, dissipated energy, settlement accumulated), the vertical
capacity, and, when :mod:`upliftlab.continuum.dynamics` is available, dynamic responses (peak
u, θ, edge uplift, residual settlement; histories overlaid) to the scene's pulse and, in full
mode, the first 10 s of El Centro; otherwise the summary says that the dynamic comparison was
not run. Fast mode puts the statics on a mesh of 8 elements across B and the dynamic pulse on
4 (seconds); full mode uses the scene's mesh (minutes for the statics, hours for El Centro).
Anchors checked on the way: K_r against π G B²/(8(1 − ν)), the
elastic half-plane's onset e/B = 1/4 against Winkler's 1/6 (anchors §3–4), the uniform bed's
M/M_up = 3 − 2√(θ_up/θ), and the capacity against Prandtl's (2 + π) c_u.

Each continuum analysis is one point of :func:`.sweep.run_sweep` in a content-addressed
:class:`.store.Store`: running the study again with the same inputs recomputes nothing. The
error table, the recommendation (the calibration with the smallest error per quantity and per
question) and every statement of ``summary.md`` are computed from the data.

Run it with ``python -m upliftlab.comparisons.winkler_vs_continuum [--fast] [--out DIR]``.
"""

from __future__ import annotations

import contextlib
import copy
import importlib.util
import math
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from .. import checks
from ..checks import InputError
from ..results import provenance, write_csv, write_netcdf
from ..scenes import Scene, load_scene, scene_from_dict
from ..reduced import build_model as build_reduced, rocking_pushover, uplift_onset_force
from ..reduced.compatibility import end_stiffened_bed, winkler_bed
from .protocol import Context, Study, main_for, run_study
from .store import Store
from .study import StudyResult, ascii_text, relative_error, require_matplotlib, write_figure, \
    write_summary
from .sweep import run_sweep, sweep_executor

__all__ = ["STUDY", "CALIBRATIONS", "Options", "FULL_OPTIONS", "FAST_OPTIONS", "check_options",
           "Calibration", "EndStiffening", "end_stiffening", "calibrate", "ContinuumReference",
           "BedResponse", "ErrorTable", "Recommendation", "DynamicComparison",
           "WinklerVsContinuum", "evaluate_continuum", "rotation_path", "cyclic_path",
           "error_table", "recommend", "DEFINITION", "compute", "write", "run", "main",
           "DYNAMIC_MISSING"]

STUDY = "winkler_vs_continuum"
CALIBRATIONS = ("uniform", "end_stiffened", "uniform_plastic", "end_stiffened_plastic")
LABELS = {"uniform": "uniform bed (K_r)", "end_stiffened": "end-stiffened bed (K_r, K_v)",
          "uniform_plastic": "uniform bed, elasto-plastic (K_r, q_ult)",
          "end_stiffened_plastic": "end-stiffened bed, elasto-plastic (K_r, K_v, q_ult)"}
DYNAMIC_MISSING = "dynamic comparison not run: continuum dynamics unavailable"
ONSET_ANCHOR = 0.25  # e/B of a rigid strip on an elastic half-plane (anchors §4)
WINKLER_ONSET = 1.0 / 6.0  # e/B of a uniform tensionless Winkler bed (anchors §3)
# Error floors: a reference smaller than this is measured against the floor instead.
FLOORS = {"moment": 0.01, "contact": 0.05, "settlement": 0.1, "energy": 0.01}
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


def _ascending(name: str, values, low: float, high: float) -> tuple[float, ...]:
    if isinstance(values, (str, bytes)) or not isinstance(values, Sequence) or not values:
        raise InputError(f"{name} = {values!r}: expected a non-empty list of numbers in "
                         f"({low:g}, {high:g}]")
    out = tuple(checks.in_range(f"{name}[{i}]", v, low, high, low_open=True)
                for i, v in enumerate(values))
    if any(b <= a for a, b in zip(out, out[1:])):
        raise InputError(f"{name} = {list(values)!r}: values must strictly ascend")
    return out


def check_options(options: Options) -> Options:
    """Validate the options; an :class:`InputError` names the field, value and valid range."""
    if not isinstance(options, Options):
        raise InputError(f"options = {options!r}: expected a winkler_vs_continuum.Options")
    checks.integer_at_least("options.springs", options.springs, 6)
    checks.in_range("options.end_length", options.end_length, 0.0, 1.0, low_open=True,
                    high_open=True)
    checks.in_range("options.max_end_stiffness_ratio", options.max_end_stiffness_ratio, 1.0,
                    1e4, low_open=True)
    _ascending("options.theta_ratios", options.theta_ratios, 1.0, 1000.0)
    checks.integer_at_least("options.monotonic_steps", options.monotonic_steps, 2)
    _ascending("options.cycle_ratios", options.cycle_ratios, 0.0, 1000.0)
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


def _check_scene(scene: Scene) -> None:
    """Refuse a scene the study cannot compare (before any work)."""
    if scene.soil is None:
        raise InputError(f"scene {scene.name!r}: soil is missing; the study needs a [soil] "
                         "table for the continuum reference")
    if scene.foundation.support != "uplift":
        raise InputError(f"scene {scene.name!r}: foundation.support = "
                         f"{scene.foundation.support!r}; the study needs 'uplift'")
    soil, N, B = scene.soil, scene.structure.vertical_weight, scene.foundation.width
    if soil.model in ("tresca", "von_mises") and soil.undrained_strength is not None:
        prandtl = (2.0 + math.pi) * soil.undrained_strength * B
        if not N < prandtl:
            raise InputError(f"structure.vertical_weight = {N:g}: the footing cannot carry it; "
                             f"valid range is (0, {prandtl:g}) (Prandtl (2 + π) c_u B)")


# ---------------------------------------------------------------------------------------------
# Continuum points (evaluated by run_sweep, stored by content)
# ---------------------------------------------------------------------------------------------


def _point_scene(point: Mapping) -> Scene:
    scene = scene_from_dict(copy.deepcopy(point["scene"]), merged=True)
    if point.get("soil") == "elastic":
        scene = scene.with_overrides("soil.model='elastic'", "soil.undrained_strength=")
    return scene


def _floats(values) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def evaluate_continuum(point: Mapping) -> dict:
    """One continuum analysis of a point: ``stiffness`` (K_v, K_r in full contact),
    ``rotation`` (a rotation pushover at ``N`` through ``rotations``), ``vertical`` (a vertical
    pushover through ``settlements``) or ``dynamic`` (:func:`evaluate_dynamic`). ``soil`` =
    ``elastic`` swaps the scene's soil for an elastic one of the same E and ν. Returns JSON values (units of the scene)."""
    from ..continuum import (build_model, footing_stiffness, rotation_pushover, uplift_onset,
                             vertical_pushover)
    from ..continuum.footing import OPEN

    kind = point["analysis"]
    if kind == "dynamic":
        return evaluate_dynamic(point)
    model = build_model(_point_scene(point))
    if kind == "stiffness":
        k = footing_stiffness(model)
        return {"K_v": k.vertical, "K_r": k.rocking, "dofs": int(model.dofs)}
    if kind == "vertical":
        path = vertical_pushover(model, point["settlements"])
        return {"settlement": _floats(path.settlement), "N": _floats(path.N),
                "capacity": path.capacity, "dofs": int(model.dofs)}
    path = rotation_pushover(model, point["N"], point["rotations"])
    try:
        onset = uplift_onset(path)
        onset = {"theta": onset.theta, "M": onset.M, "e": onset.e}
    except InputError as exc:
        onset = {"error": str(exc)}
    return {"theta": _floats(path.theta), "M": _floats(path.M), "N": _floats(path.N),
            "settlement": _floats(path.settlement), "contact": _floats(path.contact_length),
            "lifted": [bool(v) for v in (path.status == OPEN).any(axis=1)], "onset": onset,
            "cuts": int(np.sum(path.cuts)), "dofs": int(model.dofs)}


def rotation_path(theta_on: float, options: Options) -> np.ndarray:
    """Monotonic rotations (rad): 0, fine steps through the half-plane onset θ_on (so that the
    onset has full-contact steps to extrapolate from, elastic or plastic), then
    ``monotonic_steps`` geometric steps to the largest of ``theta_ratios`` × θ_on, which are all
    on the path."""
    top = max(options.theta_ratios)
    ratios = [0.0, 0.3, 0.6, 0.8, 0.9, 1.0, 1.1, 1.25]
    ratios += list(np.geomspace(1.5, top, options.monotonic_steps)) + list(options.theta_ratios)
    ratios = np.unique(np.round(ratios, 10))
    return theta_on * ratios


def cyclic_path(theta_on: float, options: Options) -> np.ndarray:
    """One full cycle 0 → +a → −a → 0 per amplitude a ∈ ``cycle_ratios`` × θ_on, with
    ``cycle_steps`` steps per quarter cycle (rad); starts at 0."""
    n = options.cycle_steps
    path = [0.0]
    for a in options.cycle_ratios:
        quarter = np.arange(1, n + 1) / n
        path += list(a * quarter) + list(a * (1 - 2 * quarter)) + list(-a * (1 - quarter))
    return theta_on * np.array(path)


# ---------------------------------------------------------------------------------------------
# The continuum reference
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ContinuumReference:
    """The continuum results the beds are calibrated from and compared with.

    ``K_v``, ``K_r`` (full contact, the scene's box); ``theta_on`` the half-plane onset
    rotation; ``monotonic``, ``cyclic`` and ``elastic`` (elastic soil, the onset anchor) rotation
    pushover records; ``vertical`` the vertical pushover; ``N_ult`` its capacity (force/length),
    ``q_ult`` = N_ult/B. ``dofs`` of the mesh.
    """

    N: float
    B: float
    h: float
    G: float
    nu: float
    cu: float | None
    K_v: float
    K_r: float
    theta_on: float
    monotonic: dict = field(repr=False)
    cyclic: dict = field(repr=False)
    elastic: dict = field(repr=False)
    vertical: dict = field(repr=False)
    dofs: int = 0

    @property
    def N_ult(self) -> float:
        return float(self.vertical["capacity"])

    @property
    def q_ult(self) -> float:
        return self.N_ult / self.B

    @property
    def K_r_closed_form(self) -> float:
        """π G B²/(8(1 − ν)) (anchors §4)."""
        return math.pi * self.G * self.B ** 2 / (8.0 * (1.0 - self.nu))

    def onset(self, which: str = "monotonic") -> dict:
        return getattr(self, which)["onset"]


def _continuum_points(scene: Scene, options: Options) -> tuple[list[dict], float]:
    soil, B = scene.soil, scene.foundation.width
    N = scene.structure.vertical_weight
    theta_on = 2.0 * N * (1.0 - soil.poisson_ratio) / (math.pi * soil.shear_modulus * B)
    table = {**copy.deepcopy(scene.data), "motion": STATIC_MOTION}  # keys free of the motion
    rotations = _floats(rotation_path(theta_on, options))
    points = [
        {"scene": table, "soil": "scene", "analysis": "rotation", "N": N,
         "rotations": _floats(cyclic_path(theta_on, options))},
        {"scene": table, "soil": "scene", "analysis": "rotation", "N": N, "rotations": rotations},
        {"scene": table, "soil": "scene", "analysis": "vertical",
         "settlements": _floats(np.linspace(0.0, options.settlement_ratio * B,
                                            options.vertical_steps + 1)[1:])},
        {"scene": table, "soil": "elastic", "analysis": "rotation", "N": N,
         "rotations": rotations},
        {"scene": table, "soil": "scene", "analysis": "stiffness"},
    ]
    return points, theta_on


def continuum_reference(scene: Scene, theta_on: float, records: Sequence[dict]
                        ) -> ContinuumReference:
    """The reference from the records of the :func:`_continuum_points` (in their order)."""
    cyclic, monotonic, vertical, elastic, stiffness = records
    soil = scene.soil
    cu = soil.undrained_strength if soil.model in ("tresca", "von_mises") else None
    return ContinuumReference(N=scene.structure.vertical_weight, B=scene.foundation.width,
                              h=scene.structure.height, G=soil.shear_modulus,
                              nu=soil.poisson_ratio, cu=cu, K_v=stiffness["K_v"],
                              K_r=stiffness["K_r"], theta_on=theta_on, monotonic=monotonic,
                              cyclic=cyclic, elastic=elastic, vertical=vertical,
                              dofs=stiffness["dofs"])


# ---------------------------------------------------------------------------------------------
# Calibration
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class EndStiffening:
    """R_k solving K_θ/K_v = ``target`` (length²) for a bed of ``springs`` with end length R_e:
    ``ratio`` the R_k used, ``exact`` the unbounded solution (inf or negative when no R_k
    exists), ``reachable`` the (low, high) K_θ/K_v over R_k ∈ [1, R_k,max], ``feasible``
    whether ``target`` lies in it."""

    target: float
    ratio: float
    exact: float
    reachable: tuple[float, float]
    supremum: float
    feasible: bool


def _moment_ratio(half_width: float, springs: int, ratio: float, end_length: float) -> float:
    """K_θ/K_v (length²) of the end-stiffened bed of :mod:`upliftlab.reduced.compatibility`."""
    bed = end_stiffened_bed(half_width, 1.0, springs, ratio, end_length)
    return bed.rocking_stiffness / bed.vertical_stiffness


def end_zone(half_width: float, springs: int, end_length: float) -> np.ndarray:
    """Which springs of the end-stiffened bed are end springs (its own rule, probed); an
    :class:`InputError` if none or all are."""
    unit = winkler_bed(half_width, 1.0, springs)
    probe = end_stiffened_bed(half_width, 1.0, springs, 2.0, end_length)
    end = probe.stiffnesses > unit.stiffnesses * (1.0 + 1e-9)
    if not end.any() or end.all() or (end != end[::-1]).any():
        raise InputError(f"options.end_length = {end_length:g}: with options.springs = "
                         f"{springs} the end zones hold {int(end.sum()) or '0 (or all)'} of "
                         f"{springs} springs; "
                         "valid is a length whose end zones each hold the same number (≥ 1) of "
                         f"strip centres and leave one between, within [{2 / springs:g}, "
                         f"{1 - 2 / springs:g}] away from a strip centre (strips of "
                         f"{2 / springs:g} b)")
    return end


def end_stiffening(target: float, half_width: float, springs: int, end_length: float,
                   max_ratio: float) -> EndStiffening:
    """Solve for the end-stiffness ratio R_k whose bed has K_θ/K_v = ``target``.

    K_θ/K_v = (R_k A_e + A_m)/(R_k W_e + W_m), with W and A the summed strip widths and
    width·x² of the end (e) and middle (m) springs, so R_k = (A_m − ρ W_m)/(ρ W_e − A_e) in
    closed form; R_k → ∞ reaches A_e/W_e < b² at most. Outside [1, ``max_ratio``] the nearest
    bound is used and ``feasible`` is False. The bed is built by
    :func:`~upliftlab.reduced.compatibility.end_stiffened_bed` (its end-zone rule).
    """
    checks.positive("target K_r/K_v", target)
    unit = winkler_bed(half_width, 1.0, springs)
    end = end_zone(half_width, springs, end_length)
    w, x2 = unit.widths, unit.positions ** 2
    W_e, W_m, A_e, A_m = w[end].sum(), w[~end].sum(), (w * x2)[end].sum(), (w * x2)[~end].sum()
    denominator = target * W_e - A_e
    exact = (A_m - target * W_m) / denominator if denominator < 0 else math.inf
    low = _moment_ratio(half_width, springs, 1.0, end_length)
    high = _moment_ratio(half_width, springs, max_ratio, end_length)
    feasible = bool(low <= target <= high)
    ratio = float(min(max(exact, 1.0), max_ratio))
    if feasible:
        got = _moment_ratio(half_width, springs, ratio, end_length)
        if abs(got / target - 1.0) > 1e-9:
            raise RuntimeError(f"end stiffening: R_k = {ratio:g} gives K_θ/K_v = {got:.12g}, "
                               f"not {target:.12g}")
    return EndStiffening(float(target), ratio, float(exact), (low, high), float(A_e / W_e),
                         feasible)


@dataclass(frozen=True)
class Calibration:
    """A bed calibrated from the continuum: ``layout`` (``winkler`` or ``end_stiffened``),
    ``law``, total ``vertical_stiffness`` K_v and bonded ``rocking_stiffness`` K_θ of the bed
    (as built), ``end_stiffness_ratio`` R_k and ``end_length`` R_e (fraction of b),
    ``yield_multiple`` FS_v (elasto-plastic), ``matches`` the continuum quantities it was
    calibrated to, and ``note`` (e.g. why K_v is missed)."""

    name: str
    label: str
    layout: str
    law: str
    springs: int
    half_width: float
    vertical_stiffness: float
    rocking_stiffness: float
    end_stiffness_ratio: float = 1.0
    end_length: float = 0.0
    yield_multiple: float = 3.0
    matches: tuple[str, ...] = ()
    note: str = ""
    stiffening: EndStiffening | None = None

    def foundation_table(self) -> dict:
        """The reduced model's ``[foundation]`` table of this bed."""
        table = {"support": "uplift", "half_width": self.half_width, "layout": self.layout,
                 "springs": self.springs, "stiffness": self.vertical_stiffness,
                 "law": self.law, "yield_multiple": self.yield_multiple}
        if self.layout == "end_stiffened":
            table.update(end_stiffness_ratio=self.end_stiffness_ratio,
                         end_length=self.end_length)
        return table


def _bed_stiffnesses(layout: str, b: float, springs: int, K_v: float, R_k: float,
                     R_e: float) -> tuple[float, float]:
    bed = (winkler_bed(b, K_v, springs) if layout == "winkler"
           else end_stiffened_bed(b, K_v, springs, R_k, R_e))
    return bed.vertical_stiffness, bed.rocking_stiffness


def calibrate(ref: ContinuumReference, options: Options) -> tuple[Calibration, ...]:
    """The four calibrations of the module docstring, from the continuum reference."""
    b, n = 0.5 * ref.B, options.springs
    uniform = winkler_bed(b, 1.0, n)
    Kv_uniform = ref.K_r / uniform.rocking_stiffness
    fs = ref.N_ult / ref.N
    stiff = end_stiffening(ref.K_r / ref.K_v, b, n, options.end_length,
                           options.max_end_stiffness_ratio)
    Kv_end = ref.K_r / _moment_ratio(b, n, stiff.ratio, options.end_length)
    if stiff.feasible:
        note, end_matches = "", ("K_r", "K_v")
    else:
        note = (f"no R_k in [1, {options.max_end_stiffness_ratio:g}] reaches K_r/K_v = "
                f"{stiff.target:.4g} (reachable {stiff.reachable[0]:.4g} to "
                f"{stiff.reachable[1]:.4g}; R_k → ∞ gives {stiff.supremum:.4g}, and no bed under "
                f"the footing exceeds b² = {b * b:.4g}): R_k = {stiff.ratio:g} is used, K_r is "
                f"matched and K_v is {Kv_end / ref.K_v:.3g} × the domain's")
        end_matches = ("K_r",)
    rows = []
    for name, layout, Kv, R_k, matches in (
            ("uniform", "winkler", Kv_uniform, 1.0, ("K_r",)),
            ("end_stiffened", "end_stiffened", Kv_end, stiff.ratio, end_matches)):
        for plastic in (False, True):
            kv, kr = _bed_stiffnesses(layout, b, n, Kv, R_k, options.end_length)
            key = f"{name}_plastic" if plastic else name
            rows.append(Calibration(
                key, LABELS[key], layout, "elastoplastic" if plastic else "elastic", n, b, kv,
                kr, R_k, options.end_length if layout == "end_stiffened" else 0.0,
                fs if plastic else 3.0, matches + (("N_ult",) if plastic else ()),
                note if layout == "end_stiffened" else "",
                stiff if layout == "end_stiffened" else None))
    return tuple(sorted(rows, key=lambda c: CALIBRATIONS.index(c.name)))


# ---------------------------------------------------------------------------------------------
# Bed responses
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class BedResponse:
    """A calibrated bed's static response: the bed's ``K_v``, ``K_r``, uplift-onset moment
    ``onset_moment``, ``N_ult`` (inf for elastic springs), and the ``monotonic`` and ``cyclic``
    pushovers (θ, M, settlement = −V, contact) on the continuum's rotation paths."""

    calibration: Calibration
    K_v: float
    K_r: float
    onset_moment: float
    N_ult: float
    monotonic: dict = field(repr=False)
    cyclic: dict = field(repr=False)


def bed_scene(scene: Scene, cal: Calibration) -> Scene:
    """The scene with its foundation replaced by the calibrated bed."""
    data = copy.deepcopy(scene.data)
    old = data.get("foundation", {})
    table = cal.foundation_table()
    for key in ("damping_ratio", "restitution", "impact_multiple"):
        if key in old:
            table[key] = old[key]
    data["foundation"] = table
    return scene_from_dict(data, source=scene.source, merged=True)


def _pushover_record(model, thetas) -> dict:
    """A rocking pushover of the bed. The reduced model measures V from static equilibrium, so
    the settlement of the base centre is the static compression there, Σ k_i δ0_i / Σ k_i
    (= N/K_v for a symmetric bed), minus V."""
    p = rocking_pushover(model, thetas)
    found = model.foundation_slice
    k, d0 = model.params["k"][found], model.params["d0"][found]
    static = float(np.sum(k * d0) / np.sum(k))
    return {"theta": np.asarray(thetas, dtype=float), "M": p.moment,
            "settlement": static - p.vertical, "contact": p.contact}


def bed_response(scene: Scene, cal: Calibration, ref: ContinuumReference) -> BedResponse:
    model = build_reduced(bed_scene(scene, cal))
    layout = model.layout
    onset = uplift_onset_force(model) * float(model.heights[-1])
    N_ult = cal.yield_multiple * model.weight if cal.law == "elastoplastic" else math.inf
    return BedResponse(cal, layout.vertical_stiffness, layout.rocking_stiffness, onset, N_ult,
                       _pushover_record(model, ref.monotonic["theta"]),
                       _pushover_record(model, ref.cyclic["theta"]))


# ---------------------------------------------------------------------------------------------
# Error table and recommendation
# ---------------------------------------------------------------------------------------------


def _at(record: Mapping, key: str, theta: float) -> float:
    thetas = np.asarray(record["theta"])
    k = int(np.argmin(np.abs(thetas - theta)))
    if abs(thetas[k] - theta) > 1e-9 * max(abs(theta), 1e-300):
        raise RuntimeError(f"θ = {theta:g} is not on the path")
    return float(np.asarray(record[key])[k])


def _energy(record: Mapping) -> float:
    """Dissipated work ∮ M dθ along a path (trapezoids)."""
    theta, M = np.asarray(record["theta"]), np.asarray(record["M"])
    return float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(theta)))


def _peaks(record: Mapping) -> np.ndarray:
    """M at the turning points of a cyclic path (each ±amplitude)."""
    theta, M = np.asarray(record["theta"]), np.asarray(record["M"])
    d = np.diff(theta)
    turns = [k + 1 for k in range(d.size - 1) if d[k] * d[k + 1] < 0]
    return M[turns]


def _quantities(ref: ContinuumReference, options: Options) -> list[tuple[str, str, str, float]]:
    """(key, label, group, floor) of every compared quantity."""
    NB, s0 = ref.N * ref.B, abs(ref.monotonic["settlement"][0])
    q = [("K_r", "K_r", "bonded stiffness", 0.0), ("K_v", "K_v", "bonded stiffness", 0.0),
         ("onset_moment", "uplift-onset M", "uplift onset", FLOORS["moment"] * NB)]
    for r in options.theta_ratios:
        q.append((f"M_{r:g}", f"M at {r:g} θ_on", "monotonic M–θ", FLOORS["moment"] * NB))
    for r in options.theta_ratios:
        q.append((f"contact_{r:g}", f"c at {r:g} θ_on", "contact length",
                  FLOORS["contact"] * ref.B))
    q.append(("settlement_0", "settlement under N", "settlement", FLOORS["settlement"] * s0))
    for r in options.theta_ratios:
        q.append((f"settlement_{r:g}", f"settlement at {r:g} θ_on", "settlement",
                  FLOORS["settlement"] * s0))
    q += [("N_ult", "N_ult", "capacity", 0.0),
          ("M_max", "largest M (pushover)", "capacity", FLOORS["moment"] * NB),
          ("cyclic_M", "cyclic peak M (worst)", "cyclic M–θ", FLOORS["moment"] * NB),
          ("cyclic_energy", "cyclic dissipated energy", "cyclic M–θ",
           FLOORS["energy"] * NB * ref.theta_on),
          ("cyclic_settlement", "settlement over the cycles", "cyclic M–θ",
           FLOORS["settlement"] * s0)]
    return q


def _path_values(mono: Mapping, cyc: Mapping, options: Options) -> dict:
    out, scale = {}, mono["_theta_on"]
    for r in options.theta_ratios:
        out[f"M_{r:g}"] = _at(mono, "M", r * scale)
        out[f"contact_{r:g}"] = _at(mono, "contact", r * scale)
        out[f"settlement_{r:g}"] = _at(mono, "settlement", r * scale)
    out["settlement_0"] = _at(mono, "settlement", 0.0)
    out["M_max"] = float(np.max(mono["M"]))
    out["cyclic_energy"] = _energy(cyc)
    out["cyclic_settlement"] = float(cyc["settlement"][-1] - cyc["settlement"][0])
    out["_cyclic_peaks"] = _peaks(cyc)
    return out


@dataclass(frozen=True, eq=False)
class ErrorTable:
    """Signed relative errors (bed − continuum)/max(|continuum|, floor) of each calibration
    (rows, :data:`CALIBRATIONS` order) in each quantity (columns): ``errors`` (ncal, nq),
    ``values`` (ncal, nq) the beds' values and ``reference`` (nq) the continuum's (units of the
    scene; N_ult of elastic springs is inf, its error NaN: no capacity)."""

    calibrations: tuple[str, ...]
    quantities: tuple[str, ...]
    labels: tuple[str, ...]
    groups: tuple[str, ...]
    floors: np.ndarray
    reference: np.ndarray
    values: np.ndarray
    errors: np.ndarray

    def error(self, calibration: str, quantity: str) -> float:
        return float(self.errors[self.calibrations.index(calibration),
                                 self.quantities.index(quantity)])


def _dynamic_quantities(ref: ContinuumReference, scene: Scene, dynamics) -> list[tuple]:
    """(key, label, group, floor) of the dynamic peaks; floors 0.1 × θ_on (θ), 0.1 × the
    story deformation at the Winkler bed's quasi-static uplift, (N B/6)/(h k) (u), and 0.1 ×
    the continuum's settlement under N (uplift, residual settlement)."""
    s0 = abs(ref.monotonic["settlement"][0])
    k = scene.structure.stories[-1].stiffness
    floors = {"theta": 0.1 * ref.theta_on, "u": 0.1 * ref.N * ref.B / (6.0 * ref.h * k),
              "uplift": 0.1 * s0, "residual_settlement": 0.1 * s0}
    return [(f"{run.key}_{m}", f"{DYNAMIC_LABELS[m]} ({run.key})", f"dynamics ({run.key})",
             floors[m]) for run in dynamics.runs for m in DYNAMIC_MEASURES]


def error_table(ref: ContinuumReference, beds: Sequence[BedResponse],
                options: Options, dynamic: Sequence[tuple] = (), runs: Sequence = ()
                ) -> ErrorTable:
    """The error table of every calibration against the continuum (module docstring), with
    the ``dynamic`` quantities (:func:`_dynamic_quantities`) of the dynamic ``runs``."""
    spec = _quantities(ref, options) + list(dynamic)
    mono = dict(ref.monotonic, _theta_on=ref.theta_on)
    cont = {"K_r": ref.K_r, "K_v": ref.K_v, "onset_moment": _onset_moment(ref),
            "N_ult": ref.N_ult, **_path_values(mono, ref.cyclic, options)}
    for run in runs:
        cont.update({f"{run.key}_{m}": run.continuum["peaks"][m] for m in DYNAMIC_MEASURES})
    rows, vals = [], []
    for bed in beds:
        v = {"K_r": bed.K_r, "K_v": bed.K_v, "onset_moment": bed.onset_moment,
             "N_ult": bed.N_ult,
             **_path_values(dict(bed.monotonic, _theta_on=ref.theta_on), bed.cyclic, options)}
        for run in runs:
            peaks = run.beds[bed.calibration.name]["peaks"]
            v.update({f"{run.key}_{m}": peaks[m] for m in DYNAMIC_MEASURES})
        err = []
        for key, _, _, floor in spec:
            if key == "cyclic_M":
                e = [relative_error(a, c, floor) for a, c in zip(v["_cyclic_peaks"],
                                                                 cont["_cyclic_peaks"])]
                k = int(np.argmax(np.abs(e)))
                err.append(e[k])
                v["cyclic_M"] = float(v["_cyclic_peaks"][k])
                continue
            err.append(relative_error(v[key], cont[key], floor) if math.isfinite(v[key])
                       else math.nan)
        rows.append(err)
        vals.append([v[key] for key, *_ in spec])
    peaks = cont["_cyclic_peaks"]
    cont["cyclic_M"] = float(peaks[int(np.argmax(np.abs(peaks)))])
    return ErrorTable(tuple(b.calibration.name for b in beds), tuple(s[0] for s in spec),
                      tuple(s[1] for s in spec), tuple(s[2] for s in spec),
                      np.array([s[3] for s in spec]),
                      np.array([cont[key] for key, *_ in spec], dtype=float),
                      np.array(vals, dtype=float), np.array(rows, dtype=float))


def _onset_moment(ref: ContinuumReference) -> float:
    onset = ref.onset("monotonic")
    return float(onset["M"]) if "M" in onset else math.nan


@dataclass(frozen=True)
class Recommendation:
    """Which calibration to pick: ``per_quantity`` quantity -> the best calibrations (ties
    within 1e-9), ``per_group`` question -> (best calibration, its largest |error| over the
    question's quantities, runner-up, its largest |error|), and the ``text``."""

    per_quantity: dict
    per_group: dict
    text: str


def recommend(table: ErrorTable, adequate: float = 0.10) -> Recommendation:
    """The calibration with the smallest |error| per quantity, and per question (group) the
    calibration whose largest |error| over the group's quantities is smallest; the text says
    whether that error is within ``adequate``. NaN (no value) counts as worse than any
    number."""
    e = np.where(np.isfinite(table.errors), np.abs(table.errors), np.inf)
    per_quantity = {}
    for j, q in enumerate(table.quantities):
        best = e[:, j].min()
        per_quantity[q] = [c for i, c in enumerate(table.calibrations)
                           if e[i, j] <= best + 1e-9] if math.isfinite(best) else []
    per_group, lines = {}, []
    for group in dict.fromkeys(table.groups):
        cols = [j for j, g in enumerate(table.groups) if g == group]
        worst = e[:, cols].max(axis=1)
        order = np.argsort(worst, kind="stable")
        first, second = int(order[0]), int(order[1]) if order.size > 1 else int(order[0])
        per_group[group] = (table.calibrations[first], float(worst[first]),
                            table.calibrations[second], float(worst[second]))
        names = ", ".join(table.labels[j] for j in cols)
        if not math.isfinite(worst[first]):
            lines.append(f"- **{group}** ({names}): no calibration gives every quantity.")
            continue
        tied = [table.calibrations[i] for i in order if worst[i] <= worst[first] + 1e-9]
        pick = " or ".join(f"`{c}`" for c in tied)
        tail = (f"; next `{table.calibrations[second]}` at {_pct(worst[second])}"
                if len(tied) == 1 and order.size > 1 else "")
        verdict = (f"within {_pct(adequate)}" if worst[first] <= adequate else
                   f"no calibration within {_pct(adequate)}")
        lines.append(f"- **{group}** ({names}): pick {pick}, largest error "
                     f"{_pct(worst[first])} ({verdict}){tail}.")
    return Recommendation(per_quantity, per_group, "\n".join(lines))


def _pct(value: float) -> str:
    return "—" if not math.isfinite(value) else f"{100 * value:.3g} %"


def _spct(value: float) -> str:
    return "—" if not math.isfinite(value) else f"{100 * value:+.3g} %"


# ---------------------------------------------------------------------------------------------
# Dynamics (needs upliftlab.continuum.dynamics)
# ---------------------------------------------------------------------------------------------


DYNAMIC_MEASURES = ("u", "theta", "uplift", "residual_settlement")
DYNAMIC_LABELS = {"u": "peak u", "theta": "peak θ", "uplift": "peak edge uplift",
                  "residual_settlement": "residual settlement"}
HISTORIES = ("theta", "u", "uplift", "settlement", "contact")


@dataclass(frozen=True, eq=False)
class DynamicRun:
    """One motion: ``continuum`` and each bed's (``beds``) histories on a common ``time`` grid
    (θ, u, edge uplift, settlement of the centre from rest, contact length) and ``peaks``
    (:data:`DYNAMIC_MEASURES`, from the full-resolution histories)."""

    key: str
    label: str
    time: np.ndarray
    continuum: dict = field(repr=False)
    beds: dict = field(repr=False)


@dataclass(frozen=True, eq=False)
class DynamicComparison:
    """The dynamic comparison (``runs``, one per motion), or why it did not run
    (``available`` False, ``reason``)."""

    available: bool
    reason: str
    runs: tuple[DynamicRun, ...] = ()

    def peaks(self) -> dict:
        """motion -> model (``continuum`` or a calibration) -> measure -> peak (None: NaN)."""
        return {r.key: {name: {m: _finite(rec["peaks"][m]) for m in DYNAMIC_MEASURES}
                        for name, rec in (("continuum", r.continuum), *r.beds.items())}
                for r in self.runs}


def dynamics_available() -> tuple[bool, str]:
    """(True, "") when :mod:`upliftlab.continuum.dynamics` imports and offers ``run_dynamic``
    and ``DynamicOptions``; else (False, the reason)."""
    if importlib.util.find_spec("upliftlab.continuum.dynamics") is None:
        return False, "upliftlab.continuum.dynamics does not exist"
    try:
        from ..continuum import dynamics
    except Exception as exc:  # a module being written may not import yet
        return False, f"upliftlab.continuum.dynamics does not import ({type(exc).__name__}: {exc})"
    missing = [n for n in ("run_dynamic", "DynamicOptions") if not hasattr(dynamics, n)]
    if missing:
        return False, f"upliftlab.continuum.dynamics lacks {', '.join(missing)}"
    return True, ""


def _motion_scene(point: Mapping) -> Scene:
    """The point's scene with its motion table (a record is located by its ``_path``)."""
    data = copy.deepcopy(point["scene"])
    motion = dict(point["motion"])
    if motion["type"] == "record":
        motion = {"type": "record", "name": motion["_path"], "scale": motion.get("scale", 1.0)}
        if point["motion"].get("duration"):
            motion["duration"] = point["motion"]["duration"]
    data["motion"] = motion
    return scene_from_dict(data, merged=True)


def _edge_gap(gap: np.ndarray) -> np.ndarray:
    """Uplift of the footing's edges over time: the larger gap of the two edge nodes."""
    gap = np.asarray(gap, dtype=float)
    return np.maximum(np.maximum(gap[:, 0], gap[:, -1]), 0.0)


def _histories(time, theta, u, uplift, settlement, contact, grid) -> dict:
    """Peaks from the full histories and the histories on ``grid`` (linear interpolation).
    The residual settlement is the settlement of the centre at the moment of the last quarter
    of the run when the footing is flattest (smallest |θ|): rocking that goes on at the end
    (an undamped elastic bed rocks for ever) does not lift it."""
    time = np.asarray(time, dtype=float)
    series = {"theta": theta, "u": u, "uplift": uplift, "settlement": settlement,
              "contact": contact}
    series = {k: np.asarray(v, dtype=float) for k, v in series.items()}
    tail = np.flatnonzero(time >= time[0] + 0.75 * (time[-1] - time[0]))
    flat = tail[int(np.argmin(np.abs(series["theta"][tail])))]
    peaks = {"u": float(np.max(np.abs(series["u"]))),
             "theta": float(np.max(np.abs(series["theta"]))),
             "uplift": float(np.max(series["uplift"])),
             "residual_settlement": float(series["settlement"][flat])}
    return {"peaks": peaks, **{k: _floats(np.interp(grid, time, v)) for k, v in series.items()}}


def _grid(duration: float, step: float) -> np.ndarray:
    return np.linspace(0.0, duration, int(round(duration / step)) + 1)


def evaluate_dynamic(point: Mapping) -> dict:
    """One continuum dynamic run (:func:`upliftlab.continuum.dynamics.run_dynamic` with default
    :class:`DynamicOptions`, no soil snapshots or energy account) of the point's scene and
    motion: the histories of every step (JSON values, units of the scene): θ, the story
    deformation u, the edge uplift, the settlement of the centre from rest and the contact
    length. Peaks are taken from them by the study, so that the stored run does not depend on
    how they are measured."""
    from ..continuum import build_model
    from ..continuum.dynamics import DynamicOptions, run_dynamic

    scene = _motion_scene(point)
    motion = scene.build_motion()
    model = build_model(scene)
    result = run_dynamic(model, scene, motion, DynamicOptions(snapshots=0, energy=False))
    time_ = np.asarray(result.time, dtype=float)
    footing = np.asarray(result.footing, dtype=float)
    u = np.asarray(result.structure_u, dtype=float).reshape(time_.size, -1)[:, -1]
    return {"time": _floats(time_ - time_[0]), "theta": _floats(footing[:, 2]), "u": _floats(u),
            "uplift": _floats(_edge_gap(result.gap)),
            "settlement": _floats(-(footing[:, 1] - footing[0, 1])),
            "contact": _floats(result.contact_length), "steps": int(time_.size),
            "dofs": int(model.dofs)}


def _bed_dynamic(scene: Scene, cal: Calibration, point: Mapping, grid: np.ndarray) -> dict:
    """The calibrated bed's run of the same motion (reduced model, not stored: milliseconds)."""
    from ..reduced import IntegrationError, run as run_reduced

    data = copy.deepcopy(bed_scene(scene, cal).data)
    try:
        response = run_reduced(_motion_scene({"scene": data, "motion": point["motion"]}))
    except IntegrationError as exc:  # refused: no values (NaN errors), the reason kept
        nan = [math.nan] * grid.size
        return {"peaks": dict.fromkeys(DYNAMIC_MEASURES, math.nan), "refused": str(exc),
                **dict.fromkeys(HISTORIES, nan)}
    model = response.model
    found = model.foundation_slice
    x, d0 = model.params["x"][found], model.params["d0"][found]
    ep = response.plastic[:, found]
    b = model.layout.half_width
    left, right = int(np.argmin(x)), int(np.argmax(x))
    gap = np.column_stack([b * response.theta + response.V - d0[left] + ep[:, left],
                           -b * response.theta + response.V - d0[right] + ep[:, right]])
    out = _histories(response.time, response.theta, response.u, _edge_gap(gap),
                     response.settlement, response.contact_length, grid)
    out["peaks"]["u"] = max(out["peaks"]["u"], response.peaks["u"])
    out["peaks"]["theta"] = max(out["peaks"]["theta"], response.peaks["theta"])
    return out


def _dynamic_motions(scene: Scene, options: Options, fast: bool) -> list[tuple[str, str, dict]]:
    """(key, label, motion point) of the dynamic comparison: the scene's pulse (shortened to
    ``pulse_duration`` if given) and, in full mode, each record of ``records``."""
    from ..motions import find_motion
    from .study import file_sha256

    motions = []
    spec = dict(scene.data.get("motion", {}))
    if spec.get("type") in ("sine", "cosine", "ricker"):
        if options.pulse_duration is not None:
            spec["duration"] = options.pulse_duration
        motions.append(("pulse", f"{spec['type']} pulse, {spec['amplitude']:g} g, T = "
                                 f"{spec['period']:g} s, {spec.get('duration', '')} s", spec))
    for name in () if fast else options.records:
        path = find_motion(name)
        table = {"type": "record", "name": name, "sha256": file_sha256(path),
                 "_path": str(path.resolve())}
        if options.record_duration is not None:
            table["duration"] = options.record_duration
        motions.append((name, name, table))
    return motions


def dynamic_points(scene: Scene, options: Options, fast: bool) -> tuple[list, list, str]:
    """(motions, points, reason): the continuum dynamic runs to make, or why there are none.
    The dynamic runs take ``dynamic_overrides``, and in fast mode ``fast_dynamic_overrides``
    on top (coarser meshes)."""
    if not options.dynamic:
        return [], [], "dynamic comparison not run: options.dynamic = false"
    ok, why = dynamics_available()
    if not ok:
        return [], [], f"{DYNAMIC_MISSING} ({why})"
    motions = _dynamic_motions(scene, options, fast)
    if not motions:
        return [], [], ("dynamic comparison not run: the scene's motion is no pulse and no "
                        "record was asked for")
    overrides = _dynamic_overrides(options, fast)
    if overrides:
        scene = scene.with_overrides(*overrides)
    table = {k: v for k, v in copy.deepcopy(scene.data).items() if k != "motion"}
    points = [{"scene": table, "motion": m, "analysis": "dynamic",
               "history_dt": options.history_dt} for _, _, m in motions]
    return motions, points, ""


def _dynamic_overrides(options: Options, fast: bool) -> tuple[str, ...]:
    """The scene overrides of the continuum's dynamic runs in this mode."""
    return options.dynamic_overrides + (options.fast_dynamic_overrides if fast else ())


def compare_dynamics(scene: Scene, calibrations, motions, points, records,
                     reason: str) -> DynamicComparison:
    """The beds' runs of the motions the continuum ran (``records``), side by side."""
    if not points:
        return DynamicComparison(False, reason)
    runs = []
    for (key, label, _), point, rec in zip(motions, points, records):
        grid = _grid(rec["time"][-1], point["history_dt"])
        continuum = _histories(rec["time"], *(rec[k] for k in HISTORIES), grid)
        continuum.update(steps=rec["steps"], dofs=rec["dofs"])
        beds = {c.name: _bed_dynamic(scene, c, point, grid) for c in calibrations}
        runs.append(DynamicRun(key, label, grid, continuum, beds))
    return DynamicComparison(True, "", tuple(runs))


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class WinklerVsContinuum:
    """The study's result: files and summary (``study``), the continuum ``reference``, the
    ``calibrations`` and their ``beds``, the error ``table``, the ``recommendation``, the
    ``anchors`` checked on the way, and the ``dynamics``."""

    study: StudyResult
    scene: Scene
    reference: ContinuumReference
    calibrations: tuple[Calibration, ...]
    beds: tuple[BedResponse, ...]
    table: ErrorTable
    recommendation: Recommendation
    anchors: dict
    dynamics: DynamicComparison
    options: Options

    def calibration(self, name: str) -> Calibration:
        return next(c for c in self.calibrations if c.name == name)

    def bed(self, name: str) -> BedResponse:
        return next(b for b in self.beds if b.calibration.name == name)


def _anchors(ref: ContinuumReference, beds: Sequence[BedResponse]) -> dict:
    """The anchor checks of the module docstring, as numbers."""
    from ..continuum.output import half_plane_rocking, winkler_rocking

    NB = ref.N * ref.B
    out = {"K_r_closed_form": ref.K_r_closed_form,
           "K_r_error_vs_closed_form": ref.K_r / ref.K_r_closed_form - 1.0,
           "K_r_over_K_v": ref.K_r / ref.K_v, "half_width_squared": (0.5 * ref.B) ** 2}
    for which in ("elastic", "monotonic"):
        onset = ref.onset(which)
        out[f"continuum_{which}_onset_e_over_B"] = (onset["e"] / ref.B if "e" in onset
                                                    else math.nan)
    uniform = next(b for b in beds if b.calibration.name == "uniform")
    out["winkler_onset_e_over_B"] = uniform.onset_moment / NB
    out["winkler_onset_closed_form"] = WINKLER_ONSET
    n = uniform.calibration.springs
    out["winkler_onset_discrete_closed_form"] = WINKLER_ONSET * (1.0 + 1.0 / n)
    theta = np.asarray(uniform.monotonic["theta"])
    k = uniform.K_v / ref.B
    closed = winkler_rocking(theta, ref.N, ref.B, k)
    beyond = theta > closed["theta_up"]
    out["winkler_theta_up"] = float(closed["theta_up"])
    out["winkler_M_error_vs_closed_form"] = float(np.max(np.abs(
        uniform.monotonic["M"][1:] / closed["M"][1:] - 1.0)))
    out["winkler_settlement_error"] = float(np.max(np.abs(
        uniform.monotonic["settlement"] - closed["settlement"])) / (ref.N / (k * ref.B)))
    out["winkler_contact_error"] = float(np.max(np.abs(uniform.monotonic["contact"]
                                                       - closed["c"])) / ref.B)
    out["winkler_M_error_after_uplift"] = float(np.max(np.abs(
        uniform.monotonic["M"][beyond] / closed["M"][beyond] - 1.0))) if beyond.any() else None
    el = ref.elastic
    hp = half_plane_rocking(np.asarray(el["theta"]), ref.N, ref.B, ref.G, ref.nu)
    out["half_plane_M_error"] = float(np.max(np.abs(np.asarray(el["M"][1:]) - hp["M"][1:]))
                                      / NB)
    if ref.cu is not None:
        prandtl = (2.0 + math.pi) * ref.cu * ref.B
        v = ref.N / ref.N_ult
        out["prandtl_N_ult"] = prandtl
        out["N_ult_error_vs_prandtl"] = ref.N_ult / prandtl - 1.0
        out["vm_envelope_M_over_NB"] = (1.0 - v) / 2.0  # B V_ult v(1 − v)/2 ÷ N B
        out["continuum_M_max_over_NB"] = float(np.max(ref.monotonic["M"]) / NB)
    return out


def compute(scene: str | Scene, ctx: Context) -> WinklerVsContinuum:
    """The continuum reference, the calibrated beds, their errors and the dynamics of
    ``scene`` (with ``[soil]``) under ``ctx.options`` (default :data:`FAST_OPTIONS` or
    :data:`FULL_OPTIONS`). Every parameter is checked before anything runs."""
    fast = ctx.fast
    options = check_options(ctx.options or (FAST_OPTIONS if fast else FULL_OPTIONS))
    if options.figures:
        require_matplotlib(STUDY)
    scene = scene if isinstance(scene, Scene) else load_scene(scene)
    if fast and options.fast_overrides:
        scene = scene.with_overrides(*options.fast_overrides)
    _check_scene(scene)
    end_zone(scene.foundation.half_width, options.springs, options.end_length)
    static, theta_on = _continuum_points(scene, options)
    motions, dynamic, reason = dynamic_points(scene, options, fast)
    executor = ctx.executor
    with contextlib.ExitStack() as stack:
        if executor is None:  # one worker per point at most
            workers = min(os.cpu_count() or 1, len(static) + len(dynamic))
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=workers))
        records = run_sweep(evaluate_continuum, static + dynamic, ctx.store, study=STUDY,
                            chunk=1, executor=executor, progress=ctx.progress)  # statics first
    ref = continuum_reference(scene, theta_on, records[:len(static)])
    calibrations = calibrate(ref, options)
    beds = tuple(bed_response(scene, c, ref) for c in calibrations)
    dynamics = compare_dynamics(scene, calibrations, motions, dynamic, records[len(static):],
                                reason)
    table = error_table(ref, beds, options, _dynamic_quantities(ref, scene, dynamics),
                        dynamics.runs)
    return WinklerVsContinuum(None, scene, ref, calibrations, beds, table,
                              recommend(table, options.adequate), _anchors(ref, beds),
                              dynamics, options)


def run(scene: str | Scene = "strip_footing_clay", fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        options: Options | None = None, executor=None, scheduler=None,
        progress=None) -> WinklerVsContinuum:
    """Run the study on ``scene`` (with ``[soil]``; its own motion is used for nothing static).

    ``fast`` applies ``options.fast_overrides`` (a coarse mesh) and the smaller
    :data:`FAST_OPTIONS` paths; full mode uses the scene's mesh and :data:`FULL_OPTIONS`.
    ``out``: output directory (default ``results/winkler_vs_continuum[-fast]``); ``store`` the
    results store (default ``<out>/store``); ``executor``/``scheduler``/``progress`` go to
    :func:`.sweep.run_sweep`. Every parameter is checked before anything runs.
    """
    return run_study(DEFINITION, scene, Context(fast=fast, out=out, store=store, options=options,
                                                executor=executor, scheduler=scheduler,
                                                progress=progress))


# ---------------------------------------------------------------------------------------------
# Output: data, figures, summary
# ---------------------------------------------------------------------------------------------


def write(result: WinklerVsContinuum, ctx: Context) -> StudyResult:
    """Paths, errors, dynamics, figures and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, scene=result.scene.name, scene_digest=result.scene.digest,
                      overrides=list(result.scene.overrides), fast=fast,
                      options=asdict(result.options), store=str(store.root),
                      continuum_dofs=result.reference.dofs)
    files = [_write_paths(result, "monotonic", out / "monotonic.csv"),
             _write_paths(result, "cyclic", out / "cyclic.csv"),
             _write_errors(result.table, out / "errors.nc", prov)]
    files += [_write_dynamic(run, out / f"dynamic_{run.key}.nc", prov)
              for run in result.dynamics.runs]
    if result.options.figures:
        files += _figures(result, out / "figures")
    elapsed = ctx.elapsed()
    numbers = _numbers(result, elapsed)
    text = _markdown(result, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def _write_paths(result: WinklerVsContinuum, which: str, path: Path) -> Path:
    ref = result.reference
    cont = getattr(ref, which)
    columns = {"theta": cont["theta"], "theta_over_theta_on": np.asarray(cont["theta"])
               / ref.theta_on, "M_continuum": cont["M"],
               "settlement_continuum": cont["settlement"], "contact_continuum": cont["contact"]}
    if which == "monotonic":
        columns.update(M_continuum_elastic=ref.elastic["M"],
                       contact_continuum_elastic=ref.elastic["contact"])
    for bed in result.beds:
        rec, name = getattr(bed, which), bed.calibration.name
        columns.update({f"M_{name}": rec["M"], f"settlement_{name}": rec["settlement"],
                        f"contact_{name}": rec["contact"]})
    units = result.scene.units
    return write_csv(path, columns, header=(
        f"{STUDY}: {which} rotation pushover at N = {ref.N:g} {units.force}/{units.length}, "
        f"B = {ref.B:g} {units.length}; theta in rad, theta_on = {ref.theta_on:.6g} rad; M in "
        f"{units.force}*{units.length}/{units.length}, settlement (down) and contact length in "
        f"{units.length}; continuum = the scene's soil, continuum_elastic = elastic soil"))


def _write_errors(table: ErrorTable, path: Path, prov: Mapping) -> Path:
    dims = ("calibration", "quantity")
    variables = {"error": (dims, table.errors, {"long_name": "(bed - continuum)/max(|continuum|,"
                                                             " floor)"}),
                 "value": (dims, np.where(np.isfinite(table.values), table.values, -1.0),
                           {"missing": "-1 where the bed has no such value (elastic N_ult)"}),
                 "reference": (("quantity",), table.reference, {}),
                 "floor": (("quantity",), table.floors, {})}
    attrs = {"title": f"{STUDY}: error table", "calibrations": list(table.calibrations),
             "quantities": list(table.quantities),
             "labels": [ascii_text(s) for s in table.labels],
             "groups": [ascii_text(s) for s in table.groups], "provenance": prov}
    return write_netcdf(path, variables, attrs)


def _write_dynamic(run: DynamicRun, path: Path, prov: Mapping) -> Path:
    """The overlaid histories of one motion (continuum and beds) with their peaks."""
    models = ("continuum",) + tuple(run.beds)
    variables = {"time": (("time",), run.time, {"units": "s"})}
    for key in HISTORIES:
        data = [run.continuum[key]] + [run.beds[n][key] for n in run.beds]
        variables[key] = (("model", "time"), np.array(data, dtype=float), {})
    peaks = np.array([[run.continuum["peaks"][m]] + [run.beds[n]["peaks"][m] for n in run.beds]
                      for m in DYNAMIC_MEASURES], dtype=float)
    variables["peak"] = (("measure", "model"), peaks, {})
    attrs = {"title": ascii_text(f"{STUDY}: {run.label}"), "models": list(models),
             "measures": list(DYNAMIC_MEASURES), "provenance": prov}
    return write_netcdf(path, variables, attrs)


_COLORS = {"uniform": "tab:red", "end_stiffened": "tab:blue", "uniform_plastic": "tab:orange",
           "end_stiffened_plastic": "tab:cyan"}


def _figures(result: WinklerVsContinuum, directory: Path) -> list[Path]:
    files = [_monotonic_figure(result, directory / "monotonic.png"),
             _cyclic_figure(result, directory / "cyclic.png"),
             _error_figure(result.table, directory / "errors.png")]
    for run in result.dynamics.runs:
        files.append(_dynamic_figure(result, run, directory / f"dynamic_{run.key}.png"))
    return files


def _dynamic_figure(result: WinklerVsContinuum, run: DynamicRun, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    length = result.scene.units.length
    fig, axes = plt.subplots(4, 1, figsize=(10, 10), sharex=True, constrained_layout=True)
    panels = (("theta", "θ [rad]"), ("u", f"u [{length}]"), ("uplift", f"edge uplift [{length}]"),
              ("settlement", f"settlement from rest [{length}]"))
    for ax, (key, label) in zip(axes, panels):
        ax.plot(run.time, run.continuum[key], "k-", lw=1.5, label="continuum")
        for name, bed in run.beds.items():
            ax.plot(run.time, bed[key], "-", lw=0.9, color=_COLORS[name], label=LABELS[name])
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[0].set_title(f"{result.scene.name}: {run.label}")
    axes[-1].set_xlabel("time [s]")
    return write_figure(path, fig)


def _monotonic_figure(result: WinklerVsContinuum, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ..continuum.output import half_plane_rocking, winkler_rocking

    ref = result.reference
    NB, B = ref.N * ref.B, ref.B
    fig, axes = plt.subplots(3, 1, figsize=(8, 10), sharex=True, constrained_layout=True)
    t = np.asarray(ref.monotonic["theta"]) / ref.theta_on
    for key, ax, scale in (("M", axes[0], NB), ("contact", axes[1], B),
                           ("settlement", axes[2], 1.0)):
        ax.plot(t, np.asarray(ref.monotonic[key]) / scale, "ko-", ms=3,
                label="continuum (scene soil)")
        if key != "settlement":
            ax.plot(t, np.asarray(ref.elastic[key]) / scale, "k:", label="continuum (elastic)")
        for bed in result.beds:
            ax.plot(t, np.asarray(bed.monotonic[key]) / scale, "-",
                    color=_COLORS[bed.calibration.name], label=bed.calibration.label)
    fine = np.linspace(0.0, t.max(), 400) * ref.theta_on
    hp = half_plane_rocking(fine, ref.N, B, ref.G, ref.nu)
    uni = result.bed("uniform")
    wk = winkler_rocking(fine, ref.N, B, uni.K_v / B)
    axes[0].plot(fine / ref.theta_on, hp["M"] / NB, "g--", lw=1, label="half-plane closed form")
    axes[0].plot(fine / ref.theta_on, wk["M"] / NB, "m--", lw=1,
                 label="Winkler closed form (anchor §3)")
    axes[0].set_ylabel("M / (N B)")
    axes[1].set_ylabel("contact length c / B")
    axes[2].set_ylabel(f"settlement [{result.scene.units.length}]")
    axes[2].set_xlabel("θ / θ_on")
    axes[0].set_title(f"{result.scene.name}: monotonic rocking at N = {ref.N:g}")
    for ax in axes:
        ax.set_xscale("symlog", linthresh=1.0)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    return write_figure(path, fig)


def _cyclic_figure(result: WinklerVsContinuum, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ref = result.reference
    NB = ref.N * ref.B
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
    t = np.asarray(ref.cyclic["theta"]) / ref.theta_on
    ax.plot(t, np.asarray(ref.cyclic["M"]) / NB, "ko-", ms=3, label="continuum")
    bx.plot(np.asarray(ref.cyclic["settlement"]), "ko-", ms=3, label="continuum")
    for bed in result.beds:
        c = _COLORS[bed.calibration.name]
        ax.plot(t, np.asarray(bed.cyclic["M"]) / NB, "-", color=c, label=bed.calibration.label)
        bx.plot(np.asarray(bed.cyclic["settlement"]), "-", color=c, label=bed.calibration.label)
    ax.set_xlabel("θ / θ_on")
    ax.set_ylabel("M / (N B)")
    bx.set_xlabel("step of the cyclic path")
    bx.set_ylabel(f"settlement [{result.scene.units.length}]")
    for a in (ax, bx):
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    return write_figure(path, fig)


def _error_figure(table: ErrorTable, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    percent = np.clip(100.0 * np.abs(table.errors), 0.01, 1000.0)
    fig, ax = plt.subplots(figsize=(1.0 + 0.45 * len(table.quantities), 3.2),
                           constrained_layout=True)
    image = ax.imshow(percent, norm=LogNorm(0.01, 1000.0), cmap="viridis", aspect="auto")
    for i, j in zip(*np.nonzero(np.isfinite(table.errors))):
        ax.text(j, i, f"{100 * table.errors[i, j]:+.2g}", ha="center", va="center", fontsize=5,
                color="white" if percent[i, j] < 10 else "black")
    ax.set_xticks(range(len(table.quantities)), table.labels, rotation=90, fontsize=6)
    ax.set_yticks(range(len(table.calibrations)), table.calibrations, fontsize=7)
    fig.colorbar(image, ax=ax, label="|error| (%)")
    ax.set_title("Winkler beds against the continuum: (bed − continuum)/continuum (%)",
                 fontsize=8)
    return write_figure(path, fig)


def _numbers(result: WinklerVsContinuum, elapsed: float) -> dict:
    ref, t = result.reference, result.table
    return {
        "continuum": {"K_r": ref.K_r, "K_v": ref.K_v, "theta_on": ref.theta_on,
                      "N_ult": ref.N_ult, "q_ult": ref.q_ult,
                      "yield_multiple": ref.N_ult / ref.N, "dofs": ref.dofs,
                      "onset": ref.onset("monotonic"), "elastic_onset": ref.onset("elastic")},
        "calibrations": {c.name: {"layout": c.layout, "law": c.law, "springs": c.springs,
                                  "K_v": c.vertical_stiffness, "K_r": c.rocking_stiffness,
                                  "end_stiffness_ratio": c.end_stiffness_ratio,
                                  "end_length": c.end_length,
                                  "yield_multiple": c.yield_multiple if c.law != "elastic"
                                  else None, "matches": list(c.matches), "note": c.note}
                         for c in result.calibrations},
        "end_stiffening": asdict(result.calibration("end_stiffened").stiffening),
        "errors": {c: {q: (float(t.errors[i, j]) if math.isfinite(t.errors[i, j]) else None)
                       for j, q in enumerate(t.quantities)}
                   for i, c in enumerate(t.calibrations)},
        "reference_values": {q: float(t.reference[j]) for j, q in enumerate(t.quantities)},
        "best_per_quantity": result.recommendation.per_quantity,
        "best_per_question": {g: {"pick": v[0], "largest_error": _finite(v[1]),
                                  "next": v[2], "next_largest_error": _finite(v[3])}
                              for g, v in result.recommendation.per_group.items()},
        "anchors": result.anchors,
        "onset_ordering_holds": _ordering(result.anchors),
        "dynamic": {"available": result.dynamics.available, "text": result.dynamics.reason,
                    "peaks": result.dynamics.peaks(),
                    "refused": {f"{r.key}/{n}": b["refused"] for r in result.dynamics.runs
                                for n, b in r.beds.items() if "refused" in b}},
        "elapsed_s": elapsed,
    }


def _finite(value: float):
    return float(value) if math.isfinite(value) else None


def _ordering(anchors: Mapping) -> bool:
    """Continuum uplift onset (elastic and the scene's soil) later than the Winkler bed's."""
    w = anchors["winkler_onset_e_over_B"]
    return bool(anchors["continuum_elastic_onset_e_over_B"] > w
                and anchors["continuum_monotonic_onset_e_over_B"] > w)


def _markdown(result: WinklerVsContinuum, fast: bool, elapsed: float) -> str:
    ref, a, sc = result.reference, result.anchors, result.scene
    u = sc.units
    soil = sc.soil
    stiff = result.calibration("end_stiffened").stiffening
    lines = [f"# Winkler beds against the continuum{' (fast)' if fast else ''}", "",
             f"Scene `{sc.name}` ({', '.join(sc.overrides) or 'no overrides'}): B = {ref.B:g} "
             f"{u.length}, N = {ref.N:g} {u.force}/{u.length}, h = {ref.h:g} {u.length}; soil "
             f"{soil.model} (E = {soil.youngs_modulus:g}, ν = {soil.poisson_ratio:g}"
             + (f", c_u = {ref.cu:g}" if ref.cu else "") + f"), {soil.interface} interface; "
             f"continuum mesh of {ref.dofs} DOFs. θ_on = 2N(1 − ν)/(πGB) = {ref.theta_on:.4g} "
             f"rad. Wall time {elapsed:.1f} s.", "",
             "## The continuum reference and its anchors", "",
             f"- K_r = {ref.K_r:.6g} ({_spct(a['K_r_error_vs_closed_form'])} against π G B²/"
             f"(8(1 − ν)) = {a['K_r_closed_form']:.6g}, anchors §4); K_v = {ref.K_v:.6g} in this "
             f"box (no 2D strip K_v exists: it depends on the box, anchors §4). K_r/K_v = "
             f"{a['K_r_over_K_v']:.4g} {u.length}² against b² = {a['half_width_squared']:.4g}.",
             f"- Uplift onset, elastic soil: e/B = "
             f"{a['continuum_elastic_onset_e_over_B']:.4f} (half-plane anchor 1/4: "
             f"{_spct(a['continuum_elastic_onset_e_over_B'] / ONSET_ANCHOR - 1.0)}); the "
             f"scene's soil: e/B = {a['continuum_monotonic_onset_e_over_B']:.4f}; uniform "
             f"Winkler bed: e/B = {a['winkler_onset_e_over_B']:.4f} (closed form 1/6, "
             f"discrete (1/6)(1 + 1/n) = {a['winkler_onset_discrete_closed_form']:.4f}). "
             f"Continuum onset later than Winkler's: **{_ordering(a)}**.",
             f"- Uniform bed against M/M_up = 3 − 2√(θ_up/θ) (anchors §3): largest deviation "
             f"{_pct(a['winkler_M_error_vs_closed_form'])} over the path; contact length "
             f"within {a['winkler_contact_error']:.3g} B of c = B√(θ_up/θ), settlement within "
             f"{a['winkler_settlement_error']:.3g} × N/(kB) of its closed form.",
             f"- Elastic continuum against the half-plane closed form: largest |ΔM|/(N B) = "
             f"{a['half_plane_M_error']:.3g}."]
    if ref.cu is not None:
        lines.append(f"- Vertical capacity N_ult = {ref.N_ult:.5g} (q_ult = {ref.q_ult:.5g}; "
                     f"{_spct(a['N_ult_error_vs_prandtl'])} against Prandtl (2 + π) c_u B = "
                     f"{a['prandtl_N_ult']:.5g}), so FS_v = q_ult B/N = {ref.N_ult / ref.N:.4g}. "
                     f"Largest M on the pushover {a['continuum_M_max_over_NB']:.4f} N B against "
                     f"the V–M envelope (1 − v)/2 = {a['vm_envelope_M_over_NB']:.4f} N B.")
    lines += ["", "## Calibrations", "",
              "| calibration | layout | law | K_v | K_θ | R_k | R_e (× b) | FS_v | matched |",
              "|---|---|---|---|---|---|---|---|---|"]
    for c in result.calibrations:
        fs = "—" if c.law == "elastic" else f"{c.yield_multiple:.4g}"
        lines.append(f"| `{c.name}` | {c.layout} ({c.springs} springs) | {c.law} | "
                     f"{c.vertical_stiffness:.6g} | {c.rocking_stiffness:.6g} | "
                     f"{c.end_stiffness_ratio:.4g} | {c.end_length:.4g} | {fs} | "
                     f"{', '.join(c.matches)} |")
    note = result.calibration("end_stiffened").note
    lines += ["", (f"End stiffening (R_e = {result.options.end_length:.4g} b, i.e. end zones of "
                   f"{result.options.end_length * ref.B / 2:.4g} {u.length} at each edge): target "
                   f"K_r/K_v = {stiff.target:.4g}, solved R_k = {stiff.exact:.6g}; "
                   + ("feasible." if stiff.feasible else f"**infeasible** — {note}."))]
    lines += ["", "## Error table", "",
              "Signed relative error (bed − continuum)/max(|continuum|, floor); floors "
              f"{FLOORS['moment']:g} N B (moments), {FLOORS['contact']:g} B (contact), "
              f"{FLOORS['settlement']:g} × the continuum's settlement under N (settlements), "
              f"{FLOORS['energy']:g} N B θ_on (energy). — : the bed has no such value (elastic "
              "springs have no capacity).", ""]
    lines += _error_markdown(result.table)
    lines += ["", "## Which calibration for which question", "",
              "Computed from the table: per question, the calibration whose largest |error| "
              "over the question's quantities is smallest.", "", result.recommendation.text, "",
              "Best per quantity: " + "; ".join(
                  f"{lbl}: {', '.join(result.recommendation.per_quantity[q]) or '—'}"
                  for q, lbl in zip(result.table.quantities, result.table.labels)) + ".", "",
              "## Dynamics", "", result.dynamics.reason if not result.dynamics.available
              else _dynamic_markdown(result.dynamics, result.options, fast), ""]
    return "\n".join(lines)


def _error_markdown(table: ErrorTable) -> list[str]:
    head = "| quantity | continuum | " + " | ".join(f"`{c}`" for c in table.calibrations) + " |"
    rows = [head, "|---|---|" + "---|" * len(table.calibrations)]
    for j, label in enumerate(table.labels):
        rows.append(f"| {label} | {table.reference[j]:.5g} | "
                    + " | ".join(_spct(table.errors[i, j])
                                 for i in range(len(table.calibrations))) + " |")
    return rows


def _dynamic_markdown(dyn: DynamicComparison, options: Options, fast: bool) -> str:
    """Peaks per motion: the continuum's and each bed's (errors are in the error table)."""
    overrides = ", ".join(_dynamic_overrides(options, fast))
    lines = ["The continuum's dynamic runs: `run_dynamic` with its default options (the "
             "scene's `continuum.dynamics`, explicit central differences by default; automatic "
             "step), the scene's boundaries"
             + (f", and the overrides {overrides}" if overrides else "")
             + ". The beds: the reduced model with the scene's foundation damping "
             "and impact settings. Peak edge uplift is the larger gap at x = ±b; residual "
             "settlement is the settlement of the centre at the end, from rest.", ""]
    for run in dyn.runs:
        names = list(run.beds)
        lines += [f"### {run.label}", "",
                  f"Continuum: {run.continuum['steps']} steps on {run.continuum['dofs']} DOFs. "
                  "Histories overlaid in `figures/dynamic_" + run.key + ".png`.", "",
                  "| measure | continuum | " + " | ".join(f"`{n}`" for n in names) + " |",
                  "|---|---|" + "---|" * len(names)]
        for m in DYNAMIC_MEASURES:
            lines.append(f"| {DYNAMIC_LABELS[m]} | {run.continuum['peaks'][m]:.4g} | "
                         + " | ".join(f"{run.beds[n]['peaks'][m]:.4g}" for n in names) + " |")
        lines.append("")
        lines += [f"- `{n}` refused by the reduced integrator: {run.beds[n]['refused']}"
                  for n in names if "refused" in run.beds[n]]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _arguments(parser) -> None:
    parser.add_argument("--end-length", type=float, default=Options.end_length,
                        help="end-zone length of the end-stiffened bed, fraction of b")
    parser.add_argument("--no-dynamic", action="store_true")


def _context_from(args, ctx: Context, say) -> Context:
    base = FAST_OPTIONS if args.fast else FULL_OPTIONS
    return replace(ctx, options=replace(base, end_length=args.end_length,
                                        dynamic=not args.no_dynamic,
                                        figures=not args.no_figures))


def _describe(result: WinklerVsContinuum) -> list[str]:
    return [result.recommendation.text,
            result.dynamics.reason if not result.dynamics.available else "dynamics compared"]


DEFINITION = Study(STUDY, "Winkler against the continuum",
                   "How well the reduced model's Winkler bed matches the plane-strain continuum.",
                   Options, compute, write, scene="strip_footing_clay", describe=_describe,
                   arguments=_arguments, context_from=_context_from,
                   help_fast="coarse mesh, short paths")
main = main_for(DEFINITION)


if __name__ == "__main__":
    sys.exit(main())
