"""The Winkler map's parameters: the soils, the grid, the options, and their checks.

Every field is checked before any work starts; a bad value is one :class:`InputError` line that
names the field, the value and the valid range.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from .... import checks
from ....checks import InputError
from .reference import REFERENCES
from .soils import SOIL_LABELS, SOILS  # noqa: F401  (re-exported: the map's soils)

STUDY = "winkler_map"

#: The measures, each taken alike on both models (:mod:`..measures`, :mod:`.points`).
MEASURES = ("theta", "uplift", "residual_settlement", "residual_rotation", "u", "base_shear")
MEASURE_LABELS = {"theta": "peak θ", "uplift": "peak edge uplift",
                  "residual_settlement": "residual settlement",
                  "residual_rotation": "residual rotation", "u": "peak u",
                  "base_shear": "peak base shear"}
MEASURE_UNITS = {"theta": "rad", "uplift": "m", "residual_settlement": "m",
                 "residual_rotation": "rad", "u": "m", "base_shear": "kN/m"}
#: Error floor: this fraction of the measure's scale at the uplift threshold
# (:func:`.points.scales`).
FLOOR_FRACTION = 0.1
MOTION_KINDS = ("ricker", "elcentro", "fema_p695")


@dataclass(frozen=True)
class Grid:
    """The map's axes.

    ``soils`` among :data:`SOILS`; ``fs_v`` the vertical factors of safety (N = V_ult/FS_v with
    V_ult the continuum's own vertical capacity of the soil); ``h_over_B`` the slenderness
    (h the story height, B the footing width); ``periods`` the structure's fixed-base periods
    (s); ``intensities`` the PGA over a_up = g B/(6h), the quasi-static uplift acceleration of a
    rigid block on a uniform tensionless Winkler bed (e = B/6); ``pulse_periods`` of the Ricker
    pulses (s); ``elcentro`` adds El Centro 1940 N-S (``UPLIFTLAB_MOTIONS``);
    ``fema_components`` how many FEMA P695 far-field components (the ``records`` extra): the
    ``a`` components of the first record pairs, then their ``b`` components (0: none).
    """

    soils: tuple[str, ...] = ("clay", "sand")
    fs_v: tuple[float, ...] = (2.0, 3.0, 5.0, 10.0)
    h_over_B: tuple[float, ...] = (1.0, 1.5, 2.5)
    periods: tuple[float, ...] = (0.2, 0.5)
    intensities: tuple[float, ...] = (1.5, 3.0)
    pulse_periods: tuple[float, ...] = (0.25, 0.6)
    elcentro: bool = True
    fema_components: int = 10


@dataclass(frozen=True)
class Options:
    """How the map is computed and judged.

    ``elements_across`` the continuum mesh (elements across B; the reference mesh is 16);
    ``springs`` of every bed; ``end_length`` R_e (fraction of b) and ``max_end_stiffness_ratio``
    of the end-stiffened beds; ``beds`` the calibrations compared (names of :data:`...beds.BEDS`;
    empty: all); ``pulse_tail`` (s) of free vibration after a pulse (a pulse run lasts 3 T plus
    this); ``settlement_ratio`` the depth of the vertical pushover (× B) in ``vertical_steps``;
    ``theta_ratios`` the rotations θ/θ_on at which the statics rows compare M, contact length
    and settlement (θ_on the elastic half-plane's uplift rotation), reached in
    ``monotonic_steps`` geometric steps beyond 1.5 θ_on; ``cycle_ratios`` the amplitudes
    θ/θ_on of the cyclic pushover (one full cycle each, ``cycle_steps`` per quarter);
    ``theta_tolerance`` and
    ``settlement_tolerance`` the region's thresholds (peak θ and edge uplift; residual
    settlement); ``energy``: make the continuum's foundation-energy run of every point
    (:mod:`.energy_points`, one more continuum run each, stored; off: the map compares E_F where
    the store holds those runs); ``budget`` (s): refuse a run whose estimated continuum cost
    exceeds it (None: no limit); ``figures``: write PNGs; ``reference`` the continuum
    reference (:mod:`.reference`): ``box`` (the closed box on a rigid base, the kept store's) or
    ``half_plane`` (a compliant base, the footing's horizontal tie, the clay's strength growing
    with depth).
    ``bed_stiffness``: what the beds' K_v
    and K_r are, ``static`` the box's statics (the default) or ``rocking`` the half-plane
    impedance's at each structure's rocking frequency (:mod:`...beds.rocking_stiffness`).
    ``macro_fs_v``: the FS_v whose rotation pushovers (monotonic and cyclic) the macro-element
    is fitted to, once per soil whatever the grid's FS_v (the whole map's four), in at most
    ``macro_evaluations`` evaluations of the fit (:mod:`.macro_points`); its runs take
    ``macro_integrator`` at ``macro_dt`` (s) (:func:`.bed_runs.element_analysis`);
    ``macro_repeat_fs_v``: the FS_v at which it is also fitted to ``repeat_cycles`` full
    cycles at ``repeat_ratio`` θ_on, the pushover that says whether the footing shakes down
    (the element's memory, revision 3).
    """

    elements_across: int = 16
    springs: int = 48
    end_length: float = 1.0 / 3.0
    max_end_stiffness_ratio: float = 10.0
    bed_stiffness: str = "static"
    beds: tuple[str, ...] = ()
    pulse_tail: float = 2.0
    settlement_ratio: float = 0.05
    vertical_steps: int = 10
    theta_ratios: tuple[float, ...] = (2.0, 5.0, 10.0, 30.0)
    monotonic_steps: int = 14
    cycle_ratios: tuple[float, ...] = (2.0, 5.0, 10.0)
    cycle_steps: int = 4
    theta_tolerance: float = 0.10
    settlement_tolerance: float = 0.20
    energy: bool = False
    budget: float | None = None
    figures: bool = True
    reference: str = "box"
    macro_fs_v: tuple[float, ...] = (2.0, 3.0, 5.0, 10.0)
    macro_evaluations: int = 1500
    macro_integrator: str = "newmark"
    macro_dt: float = 2.5e-4
    macro_repeat_fs_v: tuple[float, ...] = (3.0, 5.0)
    repeat_cycles: int = 6
    repeat_ratio: float = 2.0


FULL_GRID = Grid()
FAST_GRID = Grid(soils=("clay",), fs_v=(2.0, 5.0), h_over_B=(1.5,), periods=(0.2,),
                 intensities=(3.0,), pulse_periods=(0.2,), elcentro=False, fema_components=0)
FULL_OPTIONS = Options()
FAST_OPTIONS = Options(elements_across=4, pulse_tail=0.6, vertical_steps=8,
                       theta_ratios=(2.0, 5.0), monotonic_steps=3, cycle_ratios=(2.0,),
                       cycle_steps=2, energy=True, macro_fs_v=(2.0, 5.0),
                       macro_evaluations=30, macro_repeat_fs_v=(5.0,), repeat_cycles=2)


def grid_with(base: Grid, assignments: Sequence[str]) -> Grid:
    """``base`` with fields replaced from ``FIELD=VALUES`` texts (the command line's
    ``--grid``): a list field takes comma-separated values (``soils=clay``,
    ``fs_v=2,3,5,10``), ``elcentro`` true or false, ``fema_components`` an integer. An unknown
    field or an unreadable value is one :class:`InputError` line; the ranges are
    :func:`check_grid`'s."""
    lists = {"soils": str, "fs_v": float, "h_over_B": float, "periods": float,
             "intensities": float, "pulse_periods": float}
    changes = {}
    for text in assignments:
        field_name, sep, value = text.partition("=")
        field_name = field_name.strip()
        if not sep or field_name not in {*lists, "elcentro", "fema_components"}:
            raise InputError(f"--grid {text!r}: expected FIELD=VALUES with FIELD one of "
                             f"{[*lists, 'elcentro', 'fema_components']}")
        try:
            if field_name in lists:
                items = [v.strip() for v in value.split(",") if v.strip()]
                changes[field_name] = tuple(lists[field_name](v) for v in items)
            elif field_name == "elcentro":
                changes[field_name] = {"true": True, "false": False}[value.strip().lower()]
            else:
                changes[field_name] = int(value)
        except (ValueError, KeyError):
            kind = {"elcentro": "true or false", "fema_components": "an integer"}.get(
                field_name, "comma-separated numbers" if field_name != "soils" else "names")
            raise InputError(f"--grid {field_name} = {value!r}: expected {kind}") from None
    return replace(base, **changes)


def _choices(name: str, values, valid, *, empty: bool = False) -> tuple:
    if isinstance(values, str) or not isinstance(values, Sequence) or (not values and not empty):
        raise InputError(f"{name} = {values!r}: expected a list from {list(valid)}")
    for i, v in enumerate(values):
        checks.one_of(f"{name}[{i}]", v, valid)
    if len(set(values)) != len(values):
        raise InputError(f"{name} = {list(values)!r}: an entry is repeated")
    return tuple(values)


#: The most FEMA P695 far-field components there are (22 pairs).
FEMA_COMPONENTS = 44


def check_grid(grid: Grid) -> Grid:
    """Validate the grid; an :class:`InputError` names the field, value and valid range."""
    if not isinstance(grid, Grid):
        raise InputError(f"grid = {grid!r}: expected a winkler_map.Grid")
    _choices("grid.soils", grid.soils, tuple(SOILS))
    checks.ascending("grid.fs_v", grid.fs_v, 1.0, 100.0, low_open=True)
    checks.ascending("grid.h_over_B", grid.h_over_B, 0.25, 10.0)
    checks.ascending("grid.periods", grid.periods, 0.02, 5.0)
    checks.ascending("grid.intensities", grid.intensities, 0.0, 20.0, low_open=True)
    if grid.pulse_periods:
        checks.ascending("grid.pulse_periods", grid.pulse_periods, 0.02, 5.0)
    elif isinstance(grid.pulse_periods, str) or not isinstance(grid.pulse_periods, Sequence):
        raise InputError(f"grid.pulse_periods = {grid.pulse_periods!r}: expected a list of "
                         "periods in [0.02, 5] s")
    checks.boolean("grid.elcentro", grid.elcentro)
    n = checks.integer_at_least("grid.fema_components", grid.fema_components, 0)
    if n > FEMA_COMPONENTS:
        raise InputError(f"grid.fema_components = {n}: valid range is [0, {FEMA_COMPONENTS}]")
    if not grid.pulse_periods and not grid.elcentro and n == 0:
        raise InputError("grid.pulse_periods = []: with grid.elcentro = false and "
                         "grid.fema_components = 0 the map has no motion; give at least one")
    return grid


def check_options(options: Options, beds: Sequence[str]) -> Options:
    """Validate the options (``beds``: the registered calibrations); an :class:`InputError`
    names the field, value and valid range."""
    if not isinstance(options, Options):
        raise InputError(f"options = {options!r}: expected a winkler_map.Options")
    n = checks.integer_at_least("options.elements_across", options.elements_across, 2)
    if n > 64:
        raise InputError(f"options.elements_across = {n}: valid range is [2, 64]")
    checks.integer_at_least("options.springs", options.springs, 6)
    checks.in_range("options.end_length", options.end_length, 0.0, 1.0, low_open=True,
                    high_open=True)
    checks.in_range("options.max_end_stiffness_ratio", options.max_end_stiffness_ratio, 1.0,
                    1e4, low_open=True)
    checks.one_of("options.bed_stiffness", options.bed_stiffness, ("static", "rocking"))
    _choices("options.beds", options.beds, tuple(beds), empty=True)
    checks.in_range("options.pulse_tail", options.pulse_tail, 0.0, 60.0)
    checks.in_range("options.settlement_ratio", options.settlement_ratio, 0.0, 0.5,
                    low_open=True)
    checks.integer_at_least("options.vertical_steps", options.vertical_steps, 2)
    checks.ascending("options.theta_ratios", options.theta_ratios, 0.0, 1000.0, low_open=True)
    checks.integer_at_least("options.monotonic_steps", options.monotonic_steps, 1)
    checks.ascending("options.cycle_ratios", options.cycle_ratios, 0.0, 1000.0, low_open=True)
    checks.integer_at_least("options.cycle_steps", options.cycle_steps, 1)
    checks.in_range("options.theta_tolerance", options.theta_tolerance, 0.0, 10.0,
                    low_open=True)
    checks.in_range("options.settlement_tolerance", options.settlement_tolerance, 0.0, 10.0,
                    low_open=True)
    if options.budget is not None:
        checks.in_range("options.budget", options.budget, 0.0, 1e9, low_open=True)
    checks.boolean("options.energy", options.energy)
    checks.boolean("options.figures", options.figures)
    checks.one_of("options.reference", options.reference, REFERENCES)
    checks.ascending("options.macro_fs_v", options.macro_fs_v, 1.0, 100.0, low_open=True)
    evaluations = checks.integer_at_least("options.macro_evaluations",
                                          options.macro_evaluations, 1)
    if evaluations > 20000:
        raise InputError(f"options.macro_evaluations = {evaluations}: valid range is "
                         "[1, 20000]")
    checks.one_of("options.macro_integrator", options.macro_integrator,
                  ("newmark", "hht", "rk4", "abm4"))
    checks.in_range("options.macro_dt", options.macro_dt, 0.0, 0.01, low_open=True)
    if options.macro_repeat_fs_v:
        checks.ascending("options.macro_repeat_fs_v", options.macro_repeat_fs_v, 1.0, 100.0,
                         low_open=True)
    cycles = checks.integer_at_least("options.repeat_cycles", options.repeat_cycles, 2)
    if cycles > 50:
        raise InputError(f"options.repeat_cycles = {cycles}: valid range is [2, 50]")
    checks.in_range("options.repeat_ratio", options.repeat_ratio, 0.0, 1000.0, low_open=True)
    return options
