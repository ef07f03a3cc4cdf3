"""The speed-against-error study's parameters: its scene panel, grid and options, and their
checks."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from .... import checks
from ....checks import InputError
from ....reduced.integrators import METHODS


STUDY = "speed_vs_error"
QUANTITIES = ("u", "theta", "uplift", "residual_settlement")
# reduced rows and continuum rows measure uplift and settlement differently (..measures); the
# labels say so: reduced_edge_uplift_from_peaks against continuum_peak_edge_gap, and
# reduced_plastic_settlement against continuum_settlement_change
LABELS = {"u": "peak u", "theta": "peak θ",
          "uplift": "peak edge uplift (reduced: from peaks; continuum: edge gap)",
          "residual_settlement": "residual settlement (reduced: Σkε_p/Σk; continuum: "
                                 "V(0) − V(end))"}
INTEGRATORS = tuple(METHODS)
IMPLICIT = tuple(name for name, m in METHODS.items() if not m.explicit)
MODELS = ("edges", "equivalent", "winkler")
FLOOR_FRACTION = 0.1  # error floor: this fraction of the quantity's uplift-threshold scale
STABILITY_MARGIN = 0.95  # a ladder step is used only below this fraction of the limit
MAX_HALVINGS = 16


# ---------------------------------------------------------------------------------------------
# Parameters
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class SceneSpec:
    """One scene of the panel: a packaged scene ``scene`` with ``case`` and ``overrides``
    (dotted TOML keys), shown as ``label``. ``pulse`` = (kind, period in s, intensity in units
    of a_up = g·b/(3h)) replaces the scene's motion by a one-cycle ``sine`` or a ``ricker``
    pulse followed by 2 s of free vibration. ``continuum_levels``: elements across the footing
    of the continuum meshes to run (the scene needs a ``[soil]`` table)."""

    label: str
    scene: str
    case: str | None = None
    overrides: tuple[str, ...] = ()
    pulse: tuple[str, float, float] | None = None
    continuum_levels: tuple[int, ...] = ()


_PAPER = tuple(SceneSpec(f"{b}-{c}", f"{b}_period_elcentro", c)
               for b in ("short", "long") for c in ("A", "B", "C"))
# The paper's impact damper is sized per spring and its bed has no limit in N, so the paper's
# Case C and the wall have no converged reference; with the tributary impact mass they do.
_TRIBUTARY = ("foundation.impact_mass=tributary",)
_CONVERGING = (tuple(SceneSpec(f"{b}-C-tributary", f"{b}_period_elcentro", "C", _TRIBUTARY)
                     for b in ("short", "long"))
               + (SceneSpec("wall-e07-tributary", "wall_elcentro", "e07", _TRIBUTARY),))
_PULSES = tuple(SceneSpec(f"sine-{i:g}a_up-B", "short_period_elcentro", "B", (),
                          ("sine", 0.3, i)) for i in (1.0, 2.0, 4.0))


@dataclass(frozen=True)
class Grid:
    """The discretizations. ``springs`` the Winkler beds N (ascending; the largest is the
    reference bed); ``integrators``; ``event_levels`` and ``other_levels`` the number of Δt
    levels of the event stepper and of the others; ``reference_dt`` (s) the reference step
    (event stepper, largest bed); ``repeats`` and ``repeat_budget`` (s) of the timing."""

    scenes: tuple[SceneSpec, ...]
    springs: tuple[int, ...] = (10, 20, 40, 80, 160, 320, 640)
    integrators: tuple[str, ...] = INTEGRATORS
    two_springs: tuple[str, ...] = ("edges", "equivalent")
    event_levels: int = 4
    other_levels: int = 2
    reference_dt: float = 6.25e-4
    repeats: int = 5
    repeat_budget: float = 0.5


_CLAY = SceneSpec("strip-clay-ricker", "strip_footing_clay", None,
                  ("motion.duration=1.5", "continuum.domain_width=6.0",
                   "continuum.domain_depth=4.0"), None, (4, 8))
FULL_GRID = Grid(scenes=_PAPER + (SceneSpec("wall-e07", "wall_elcentro", "e07"),) + _CONVERGING
                 + _PULSES + (_CLAY,))
FAST_GRID = Grid(scenes=(SceneSpec("sine-2a_up-B", "short_period_elcentro", "B", (),
                                   ("sine", 0.3, 2.0)),
                         SceneSpec("ricker-3a_up-A", "short_period_elcentro", "A", (),
                                   ("ricker", 0.25, 3.0))),
                 springs=(10, 40, 160), event_levels=3, other_levels=2)


@dataclass(frozen=True)
class Options:
    """How the study judges and what it writes: ``convergence_tolerance`` the largest change
    of the reference from the next-finer level for it to count as converged; ``tolerances``
    the error levels of the table (fractions); ``figures`` writes PNGs."""

    convergence_tolerance: float = 0.01
    tolerances: tuple[float, ...] = (0.01, 0.05, 0.10)
    figures: bool = True


def check_grid(grid: Grid) -> Grid:
    """Validate the grid; an :class:`InputError` names the field, value and valid range."""
    if not isinstance(grid.scenes, Sequence) or not grid.scenes:
        raise InputError(f"grid.scenes = {grid.scenes!r}: expected a non-empty list of scenes")
    labels = [s.label for s in grid.scenes]
    if len(set(labels)) != len(labels):
        raise InputError(f"grid.scenes: labels {labels!r} repeat; each scene needs its own")
    counts = grid.springs
    if isinstance(counts, (str, bytes)) or not isinstance(counts, Sequence) or not counts:
        raise InputError(f"grid.springs = {counts!r}: expected a non-empty list of integers")
    for i, n in enumerate(counts):
        checks.integer_at_least(f"grid.springs[{i}]", n, 4)
        if n > 4096:
            raise InputError(f"grid.springs[{i}] = {n}: valid range is [4, 4096]")
    if any(b <= a for a, b in zip(counts, counts[1:])):
        raise InputError(f"grid.springs = {list(counts)!r}: values must strictly ascend")
    if counts[-1] % 2:
        raise InputError(f"grid.springs[-1] = {counts[-1]}: the reference bed must be even "
                         "(its convergence check halves it)")
    for i, name in enumerate(grid.integrators):
        checks.one_of(f"grid.integrators[{i}]", name, INTEGRATORS)
    for i, name in enumerate(grid.two_springs):
        checks.one_of(f"grid.two_springs[{i}]", name, MODELS[:2])
    checks.integer_at_least("grid.event_levels", grid.event_levels, 1)
    checks.integer_at_least("grid.other_levels", grid.other_levels, 1)
    checks.in_range("grid.reference_dt", grid.reference_dt, 0.0, 0.01, low_open=True)
    checks.integer_at_least("grid.repeats", grid.repeats, 1)
    checks.in_range("grid.repeat_budget", grid.repeat_budget, 0.0, 600.0, low_open=True)
    for s in grid.scenes:
        for i, n in enumerate(s.continuum_levels):
            checks.integer_at_least(f"scene {s.label}: continuum_levels[{i}]", n, 2)
        if s.pulse is not None:
            kind, period, intensity = s.pulse
            checks.one_of(f"scene {s.label}: pulse kind", kind, ("sine", "ricker"))
            checks.in_range(f"scene {s.label}: pulse period", period, 0.02, 10.0)
            checks.in_range(f"scene {s.label}: pulse intensity", intensity, 0.0, 50.0,
                            low_open=True)
    return grid


def check_options(options: Options) -> Options:
    """Validate the options; an :class:`InputError` names the field, value and valid range."""
    checks.in_range("options.convergence_tolerance", options.convergence_tolerance, 0.0, 0.5,
                    low_open=True)
    if not options.tolerances:
        raise InputError("options.tolerances = (): expected at least one tolerance")
    for i, t in enumerate(options.tolerances):
        checks.in_range(f"options.tolerances[{i}]", t, 0.0, 1.0, low_open=True, high_open=True)
    checks.boolean("options.figures", options.figures)
    return options
