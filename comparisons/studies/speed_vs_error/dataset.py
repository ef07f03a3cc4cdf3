"""The study's data: every run of every scene as one labelled dataset, built from the sweep's
records (its point functions are in :mod:`.points`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import asdict

import numpy as np

from ....checks import InputError
from ....results import cf_attributes
from ....scenes import Scene
from .grid import FLOOR_FRACTION, Grid, LABELS, Options, QUANTITIES, SceneSpec
from .points import scales

#: The run's fields that are text, with their value where a cell was not run.
_TEXT = ("failure", "measured_utc")


def model_label(point: Mapping) -> str:
    """The ``model`` label of a point: ``edges``, ``equivalent``, ``N=<springs>`` (a Winkler
    bed) or ``continuum-<elements across>``."""
    model, n = point["model"], int(point["springs"])
    return {"winkler": f"N={n}", "continuum": f"continuum-{n}"}.get(model, model)


def _level(point: Mapping) -> int:
    """The point's rung of the step ladder (0 for a continuum mesh's automatic step)."""
    return int(point["step"].get("rank", 0))


def relative_to_reference(value: float, reference: float, floor: float) -> float:
    """Signed relative error (value − reference)/max(|reference|, floor) (dimensionless;
    ``floor`` in the quantity's units keeps a near-zero reference from inflating it)."""
    return (value - reference) / max(abs(reference), floor)


def _reference(records: Sequence[Mapping], dt: float, floors: dict) -> dict:
    """The reference run's values and its changes from half the springs and twice the step."""
    ref, half, coarse = records
    for r, what in ((ref, "reference"), (half, "half-springs check"), (coarse, "2·dt check")):
        if "error" in r:
            raise InputError(f"the {what} run (event stepper, dt ≤ {2 * dt:g} s) failed: "
                             f"{r['error']}")
    return {"reference": [ref[q] for q in QUANTITIES],
            "change_half_springs": [abs(relative_to_reference(half[q], ref[q], floors[q]))
                                    for q in QUANTITIES],
            "change_double_dt": [abs(relative_to_reference(coarse[q], ref[q], floors[q]))
                                 for q in QUANTITIES],
            "floor": [floors[q] for q in QUANTITIES], "reference_runtime": ref["runtime"]}


class _Cells:
    """The run arrays over (scene, model, integrator, level), filled point by point."""

    def __init__(self, shape: tuple[int, ...]):
        nan = np.full(shape, np.nan)
        self.numbers = {k: nan.copy() for k in ("dt", "runtime", "repeats")}
        self.value = np.full(shape + (len(QUANTITIES),), np.nan)
        self.error = self.value.copy()
        self.ran = np.zeros(shape, dtype=np.int8)
        self.text = {k: np.full(shape, "", dtype=object) for k in _TEXT}

    def put(self, at: tuple, record: Mapping, reference: dict) -> None:
        self.ran[at] = 1
        if "error" in record:
            self.text["failure"][at] = record["error"]
            return
        self.numbers["dt"][at] = record["dt"]
        self.numbers["runtime"][at] = record["runtime"]
        self.numbers["repeats"][at] = len(record["runtimes"])
        self.text["measured_utc"][at] = record["measured_utc"]
        for k, q in enumerate(QUANTITIES):
            self.value[at + (k,)] = record[q]
            self.error[at + (k,)] = relative_to_reference(
                record[q], reference["reference"][k], reference["floor"][k])


def runs_dataset(specs: Sequence[SceneSpec], scenes: Sequence[Scene], points, records,
                 grid: Grid, options: Options, attrs: Mapping):
    """Every run as an :class:`xarray.Dataset` over ``scene``, ``model`` (two springs, beds of
    N springs, continuum meshes; with its ``layout`` and ``springs``), ``integrator`` and
    ``level`` (of the step ladder) and ``quantity``: the step ``dt`` (s), the ``runtime`` (s,
    median of ``repeats``), the ``value`` and its signed relative ``error`` against the scene's
    reference, the ``failure`` of a refused run and whether a cell ``ran``; per scene the
    ``reference`` values, their changes from half the springs and from twice the step, and the
    error ``floor``. ``points`` and ``records`` are per scene: (ladder points, reference
    points) and their records, in the same order. ``attrs`` are added (the measurement
    context, the sessions, the continuum note); the ``grid`` and the ``options`` are kept as
    attributes (``grid_springs``, ``options_tolerances``, ...)."""
    models = list(dict.fromkeys(model_label(p) for pts, _ in points for p in pts))
    levels = max(grid.event_levels, grid.other_levels)
    # the grid's integrators, and the one a continuum mesh ran with should the grid leave it out
    integrators = list(dict.fromkeys([*grid.integrators,
                                      *(p["integrator"] for pts, _ in points for p in pts)]))
    cells = _Cells((len(specs), len(models), len(integrators), levels))
    per_scene = {k: [] for k in ("reference", "change_half_springs", "change_double_dt",
                                 "floor", "reference_runtime")}
    layout, springs = {}, {}
    for i, (scene, (pts, _), (recs, ref_recs)) in enumerate(zip(scenes, points, records)):
        floors = {q: FLOOR_FRACTION * v for q, v in scales(scene).items()}
        reference = _reference(ref_recs, grid.reference_dt, floors)
        for key, value in reference.items():
            per_scene[key].append(value)
        for p, r in zip(pts, recs):
            label = model_label(p)
            layout[label], springs[label] = p["model"], int(p["springs"])
            at = (i, models.index(label), integrators.index(p["integrator"]), _level(p))
            cells.put(at, r, reference)
    return _dataset(specs, scenes, models, layout, springs, integrators, cells, per_scene, grid,
                    options, attrs)


def _dataset(specs, scenes, models, layout, springs, integrators, cells, per_scene, grid,
             options, attrs):
    import xarray as xr

    run = ("scene", "model", "integrator", "level")
    s_q = ("scene", "quantity")
    one = {"units": "1"}
    data = {
        "dt": (run, cells.numbers["dt"], {"units": "s", "long_name": "time step"}),
        "runtime": (run, cells.numbers["runtime"], {
            "units": "s", "long_name": "wall time of the run, median of its repeats"}),
        "repeats": (run, cells.numbers["repeats"], {**one, "long_name": "timed repeats"}),
        "value": (run + ("quantity",), cells.value, {
            "long_name": "the quantity (units: length_unit of the scene; theta in rad)"}),
        "error": (run + ("quantity",), cells.error, {
            **one, "long_name": "(value - reference)/max(|reference|, floor); NaN: refused"}),
        "ran": (run, cells.ran, {"long_name": "the discretization was run",
                                 "flag_values": np.array([0, 1], np.int8),
                                 "flag_meanings": "not_run run"}),
        "failure": (run, cells.text["failure"].astype(str), {
            "long_name": "why the run was refused (empty: it was not)"}),
        "measured_utc": (run, cells.text["measured_utc"].astype(str), {
            "long_name": "when the runtime was measured (UTC)"}),
        "reference": (s_q, np.array(per_scene["reference"]), {
            "long_name": "reference value: event stepper, largest bed, reference step"}),
        "change_half_springs": (s_q, np.array(per_scene["change_half_springs"]), {
            **one, "long_name": "relative change of the reference from half the springs"}),
        "change_double_dt": (s_q, np.array(per_scene["change_double_dt"]), {
            **one, "long_name": "relative change of the reference from twice the step"}),
        "floor": (s_q, np.array(per_scene["floor"]), {
            "long_name": f"error floor, {FLOOR_FRACTION:g} of the uplift-threshold scale"}),
        "reference_runtime": ("scene", np.array(per_scene["reference_runtime"]), {
            "units": "s", "long_name": "wall time of the reference run"}),
    }
    coords = {
        "scene": ("scene", [s.label for s in specs], {"long_name": "scene of the panel"}),
        "scene_name": ("scene", [s.name for s in scenes], {"long_name": "packaged scene"}),
        "length_unit": ("scene", [s.units.length for s in scenes],
                        {"long_name": "unit of length of the scene"}),
        "model": ("model", models, {"long_name": "foundation model and discretization"}),
        "layout": ("model", [layout[m] for m in models], {"long_name": "foundation model"}),
        "springs": ("model", np.array([springs[m] for m in models]), {
            **one, "long_name": "springs (two springs, a bed), or elements across (continuum)"}),
        "integrator": ("integrator", integrators, {"long_name": "integrator"}),
        "level": ("level", np.arange(cells.ran.shape[-1]), {
            **one, "long_name": "rung of the step ladder (0: coarsest stable step)"}),
        "quantity": ("quantity", list(QUANTITIES), {
            "long_name": "; ".join(f"{q}: {LABELS[q]}" for q in QUANTITIES)})}
    attrs = {"Conventions": "CF-1.10", "title": "speed against error: every run of the panel",
             "grid": asdict(grid), "options": asdict(options), "floor_fraction": FLOOR_FRACTION,
             **attrs}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))
