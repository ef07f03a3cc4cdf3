"""The error maps: each two-spring layout against the converged bed over two parameters."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ...framework.study import Axis, relative_error
from ...framework.sweep import run_sweep
from .grid import ENERGY_TOLERANCE, FLOOR_FRACTION, Grid, LAYOUTS, METRICS, Options, STUDY
from .motions import motion_label
from .dataset import map_dataset
from .points import Base, evaluate_point, make_point
from .views import axis


# ---------------------------------------------------------------------------------------------
# Error maps
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _MapSpec:
    name: str
    title: str
    x: Axis
    y: Axis
    bed: str
    cases: tuple[str, ...]


@dataclass(frozen=True)
class MapContext:
    base: Base
    grid: Grid
    options: Options
    springs: int
    reference_motion: dict
    records: tuple[dict, ...]


def _intensity_axis(values) -> Axis:
    return axis("intensity", values)


def _map_specs(ctx: MapContext) -> list[_MapSpec]:
    g = ctx.grid
    ref = motion_label(ctx.reference_motion)
    cases = tuple(g.cases)
    aspect = axis("h_over_b", g.aspect_ratios)
    pulses = axis("pulse_period", g.pulse_periods)
    specs = {
        "aspect": _MapSpec("aspect", f"h/b × intensity, {ref}", aspect,
                           _intensity_axis(g.intensities), "uniform", cases),
        "period": _MapSpec("period", f"period × intensity, {ref}",
                           axis("period", g.periods),
                           _intensity_axis(g.intensities), "uniform", cases),
        "yield_restitution": _MapSpec(
            "yield_restitution", f"FS_v × ε, elasto-plastic bed (10 % damping), {ref} at "
            f"{g.reference_intensity:g} × a_up", axis("yield_multiple", g.yield_multiples),
            axis("restitution", g.restitutions), "uniform", ("B/C",)),
        "sine_pulse": _MapSpec("sine_pulse", "one-cycle sine pulse: period × intensity", pulses,
                               _intensity_axis(g.intensities), "uniform", cases),
        "ricker_pulse": _MapSpec("ricker_pulse", "Ricker pulse: period × intensity", pulses,
                                 _intensity_axis(g.intensities), "uniform", cases),
        "records": _MapSpec("records", "records × intensity",
                            _intensity_axis(g.record_intensities),
                            axis("record", [r["name"] for r in ctx.records]),
                            "uniform", cases),
        "end_stiffened": _MapSpec(
            "end_stiffened", f"end-stiffened bed (R_k = {ctx.options.end_stiffness_ratio:g}, "
            f"R_e = {ctx.options.end_length:g} b): h/b × intensity, {ref}", aspect,
            _intensity_axis(g.intensities), "end_stiffened", cases)}
    return [specs[m] for m in g.maps if m != "records" or ctx.records]


def _cell(spec: _MapSpec, ctx: MapContext, case: str, iy: int, ix: int) -> dict:
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


def _map_points(spec: _MapSpec, ctx: MapContext) -> list[dict]:
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


def _assemble(spec: _MapSpec, records: Sequence[Mapping], units: str):
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
    return map_dataset(spec, {"layouts": LAYOUTS, "errors": errors, "values": values,
                              "reference": reference, "uplifted": uplifted,
                              "failures": failures, "energy_balance_error": balance}, units)


def compute_maps(ctx: MapContext, store, sweep_options: Mapping) -> dict:
    """Every map's points in one sweep, then the errors of each layout against the bed: {name:
    the map's dataset (:func:`.dataset.map_dataset`)}."""
    specs = _map_specs(ctx)
    per_map = [_map_points(spec, ctx) for spec in specs]
    records = run_sweep(evaluate_point, [p for pts in per_map for p in pts], store, study=STUDY,
                        **sweep_options)
    maps, start, units = {}, 0, ctx.base.table["units"]
    for spec, pts in zip(specs, per_map):
        maps[spec.name] = _assemble(spec, records[start:start + len(pts)], units)
        start += len(pts)
    return maps
