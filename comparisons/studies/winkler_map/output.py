"""The map's data files (labelled NetCDF-4, CF) and its write step."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict

import numpy as np

from ....provenance import provenance
from ....results import cf_attributes, write_dataset
from ...framework.protocol import Context
from ...framework.study import StudyResult, ascii_text, write_summary
from ...beds import BEDS
from .energy import ENERGIES
from .grid import FLOOR_FRACTION, MEASURE_LABELS, MEASURE_UNITS, MEASURES, SOIL_LABELS, STUDY
from .maps import MapData
from .points import SIDES

__all__ = ["write", "map_dataset", "statics_dataset", "rocking_variables"]

_DIMS = ("soil", "fs_v", "h_over_B", "period", "intensity", "motion")


def _coords(data: MapData) -> dict:
    g = data.grid
    return {
        "soil": ("soil", list(g.soils), {"long_name": "soil of the continuum"}),
        "fs_v": ("fs_v", np.array(g.fs_v, dtype=float), {
            "units": "1", "long_name": "vertical factor of safety V_ult/N on the continuum's "
                                       "own vertical capacity"}),
        "h_over_B": ("h_over_B", np.array(g.h_over_B, dtype=float), {
            "units": "1", "long_name": "slenderness: story height over footing width"}),
        "period": ("period", np.array(g.periods, dtype=float), {
            "units": "s", "long_name": "fixed-base period of the structure"}),
        "intensity": ("intensity", np.array(g.intensities, dtype=float), {
            "units": "a_up", "long_name": "PGA over a_up = g B/(6h), the rigid block's uplift "
                                          "acceleration on a uniform tensionless Winkler bed"}),
        "motion": ("motion", list(data.motion_names), {"long_name": "ground motion"}),
        "motion_kind": ("motion", list(data.motion_kinds), {
            "long_name": "kind of motion: ricker, elcentro or fema_p695"}),
        "calibration": ("calibration", list(data.calibrations), {
            "long_name": "calibrated reduced model (bed)"}),
        "measure": ("measure", list(MEASURES), {"long_name": "quantity compared"}),
        "measure_label": ("measure", [ascii_text(MEASURE_LABELS[m]) for m in MEASURES], {
            "long_name": "what each measure is (its values: variables bed_<measure> and "
                         "continuum_<measure>)"}),
        "calibration_label": ("calibration", [ascii_text(BEDS[c].label) if c in BEDS else c
                                              for c in data.calibrations],
                              {"long_name": "what each calibration matches"}),
    }


def map_dataset(data: MapData, prov: Mapping):
    """The map as an :class:`xarray.Dataset` over soil, fs_v, h_over_B, period, intensity,
    motion, calibration and measure, with units and a long name on every variable."""
    import xarray as xr

    d = _DIMS
    variables = {
        "error": (d + ("calibration", "measure"), data.errors, {
            "units": "1", "long_name": "signed relative error of the bed against the "
                                       "continuum, (bed - continuum)/max(|continuum|, floor); "
                                       "NaN: the bed's run was refused or the "
                                       "continuum's did not finish"}),
        "continuum_wall_time": (d, data.continuum_wall, {
            "units": "s", "long_name": "wall time of the continuum run (stored with it)"}),
        "bed_wall_time": (d + ("calibration",), data.bed_wall, {
            "units": "s", "long_name": "wall time of the bed's run (this run)"}),
        "continuum_steps": (d, data.steps, {
            "units": "1", "long_name": "time steps of the continuum run"}),
        "continuum_dofs": (d, data.dofs, {
            "units": "1", "long_name": "degrees of freedom of the continuum mesh"}),
        "energy_balance_error": (d, data.balance, {
            "units": "1", "long_name": "energy balance error of the continuum run (fraction "
                                       "of its input)"}),
        "vertical_load": (("soil", "fs_v"), data.N, {
            "units": "kN/m", "long_name": "vertical load N = V_ult/FS_v"}),
        "bed_rocking_stiffness": (("soil", "fs_v", "calibration"), data.bed_K_r, {
            "units": "kN m/rad/m", "long_name": "rocking stiffness of the built bed, "
                                                "sum k_i x_i^2"}),
        "bed_vertical_stiffness": (("soil", "fs_v", "calibration"), data.bed_K_v, {
            "units": "kN/m/m", "long_name": "vertical stiffness of the built bed, sum k_i"}),
    }
    if data.bearing_failure is not None:
        variables["continuum_bearing_failure"] = (d, data.bearing_failure.astype("i1"), {
            "units": "1", "long_name": "1: the continuum's run ended in a bearing failure of "
                                       "the soil (its measures NaN)"})
        variables["bed_bearing_failure"] = (d + ("calibration",),
                                            data.bed_bearing_failure.astype("i1"), {
            "units": "1", "long_name": "1: at a bearing failure of the continuum, the bed's "
                                       "base settled by the failure settlement too"})
    if data.energy_errors is not None:
        variables.update(_energy_variables(data, d))
    for q, m in enumerate(MEASURES):
        label, units = ascii_text(MEASURE_LABELS[m]), MEASURE_UNITS[m]
        variables[f"bed_{m}"] = (d + ("calibration",), data.beds[..., q], {
            "units": units, "long_name": f"{label} of the bed's run"})
        variables[f"continuum_{m}"] = (d, data.continuum[..., q], {
            "units": units, "long_name": f"{label} of the continuum's run"})
        variables[f"floor_{m}"] = (d[:4], FLOOR_FRACTION * data.scale[..., q], {
            "units": units, "long_name": f"error floor of {label}: {FLOOR_FRACTION:g} x its "
                                         "value at a uniform bed's uplift threshold"})
    attrs = {"Conventions": "CF-1.10", "title": "Winkler beds against the continuum: the map",
             "elements_across": data.options.elements_across,
             "continuum_boundary": SIDES,
             "floor_fraction": FLOOR_FRACTION, "refusals": list(data.refusals),
             "provenance": dict(prov)}
    return xr.Dataset(variables, coords=_coords(data), attrs=cf_attributes(attrs))


def _energy_variables(data: MapData, d: tuple) -> dict:
    """The energies of :data:`.energy.ENERGIES` of both models, their errors and the floor."""
    what = {"foundation_energy": "foundation energy E_F, the energy the structure lost to its "
                                 "foundation over the run",
            "motion_energy": "E_M, the foundation energy less the work of the structure's "
                             "weight (W times its settlement)"}
    out = {}
    for k, name in enumerate(ENERGIES):
        out[f"continuum_{name}"] = (d, data.continuum_energy[..., k], {
            "units": "kN m/m", "long_name": f"{what[name]}, of the continuum's energy run (NaN: "
                                           "not stored)"})
        out[f"bed_{name}"] = (d + ("calibration",), data.bed_energy[..., k], {
            "units": "kN m/m", "long_name": f"{what[name]}, of the bed's run"})
        out[f"{name}_error"] = (d + ("calibration",), data.energy_errors[..., k], {
            "units": "1", "long_name": f"signed relative error of the bed's {name} against the "
                                       "continuum's, (bed - continuum)/max(|continuum|, floor)"})
    out["continuum_energy_left"] = (d, data.continuum_energy_left, {
        "units": "kN m/m", "long_name": "kinetic and story energy the continuum's structure "
                                        "still holds at the end of its energy run"})
    out["floor_energy"] = (d[:4], FLOOR_FRACTION * data.energy_scale, {
        "units": "kN m/m", "long_name": f"error floor of both energies: {FLOOR_FRACTION:g} x "
                                        "(N B/6)^2/(2 K_r), a uniform bed's strain energy at its "
                                        "uplift threshold"})
    return out


def statics_dataset(data: MapData, prov: Mapping):
    """The continuum statics per soil (K_v, K_r, V_ult and the vertical pushover) and the
    statics rows: every bed's rocking pushovers against the continuum's per soil and FS_v."""
    import xarray as xr

    soils = [s.soil for s in data.statics]
    steps = max(len(s.load) for s in data.statics)

    def padded(values):
        out = np.full(steps, np.nan)
        out[:len(values)] = values
        return out

    variables = {
        "K_v": (("soil",), [s.K_v for s in data.statics], {
            "units": "kN/m/m", "long_name": "continuum vertical stiffness, full contact"}),
        "K_r": (("soil",), [s.K_r for s in data.statics], {
            "units": "kN m/rad/m", "long_name": "continuum rocking stiffness, full contact"}),
        "V_ult": (("soil",), [s.V_ult for s in data.statics], {
            "units": "kN/m", "long_name": "continuum vertical capacity (largest load of the "
                                          "vertical pushover)"}),
        "plateau": (("soil",), [s.plateau for s in data.statics], {
            "units": "1", "long_name": "load increase of the pushover's last step over V_ult"}),
        "settlement": (("soil", "step"), np.array([padded(s.settlement) for s in data.statics]),
                       {"units": "m", "long_name": "vertical pushover: settlement"}),
        "load": (("soil", "step"), np.array([padded(s.load) for s in data.statics]), {
            "units": "kN/m", "long_name": "vertical pushover: load"}),
        "dofs": (("soil",), [s.dofs for s in data.statics], {
            "units": "1", "long_name": "degrees of freedom of the mesh"}),
        "wall_time": (("soil",), [s.wall_time_s for s in data.statics], {
            "units": "s", "long_name": "wall time of the two static runs"}),
    }
    variables.update(rocking_variables(data))
    if data.capacity_fits:
        fits = dict(data.capacity_fits)
        beta = [[fits[s, fs].beta if (s, fs) in fits else np.nan for fs in data.grid.fs_v]
                for s in soils]
        variables["capacity_beta"] = (("soil", "fs_v"), np.array(beta, dtype=float), {
            "units": "1", "long_name": "the fitted bed's capacity exponent: yield pressure "
                                       "proportional to (k_i/w_i)**beta"})
    coords = {"soil": ("soil", soils, {"long_name": "soil of the continuum"}),
              "fs_v": ("fs_v", np.array(data.grid.fs_v, dtype=float), {
                  "units": "1", "long_name": "vertical factor of safety V_ult/N"}),
              "calibration": ("calibration", list(data.calibrations), {
                  "long_name": "calibrated reduced model (bed)"}),
              "statics_quantity": ("statics_quantity", list(data.rocking.quantities), {
                  "long_name": "quantity of the rocking pushovers compared"}),
              "statics_group": ("statics_quantity", [ascii_text(g)
                                                     for g in data.rocking.groups], {
                  "long_name": "what the quantity belongs to: uplift onset, M-theta backbone, "
                               "contact length, settlement against theta, cyclic dissipation "
                               "or cyclic settlement"}),
              "soil_label": ("soil", [ascii_text(SOIL_LABELS[s]) for s in soils],
                             {"long_name": "the soil's model and strength"}),
              "step": ("step", np.arange(steps), {"units": "1",
                                                  "long_name": "pushover step"})}
    attrs = {"Conventions": "CF-1.10", "title": "Winkler map: the continuum statics per soil",
             "provenance": dict(prov)}
    return xr.Dataset(variables, coords=coords, attrs=cf_attributes(attrs))


def _rocking_units(key: str) -> str:
    return "m" if key.startswith(("contact", "settlement", "cyclic_settlement")) else "kN m/m"


def rocking_variables(data: MapData) -> dict:
    """The statics rows (:mod:`.rocking`) as variables over soil, fs_v, calibration and
    statics_quantity: the signed errors, and each quantity's continuum and bed values and floor
    with its units."""
    r = data.rocking
    variables = {
        "rocking_error": (("soil", "fs_v", "calibration", "statics_quantity"), r.errors, {
            "units": "1", "long_name": "signed relative error of the bed's rocking pushover "
                                       "against the continuum's, (bed - continuum)/max("
                                       "|continuum|, floor)"}),
        "theta_on": (("soil", "fs_v"), r.theta_on, {
            "units": "rad", "long_name": "elastic half-plane uplift rotation 2N(1-nu)/(pi G B), "
                                         "the scale of the rotation paths"}),
    }
    for q, key in enumerate(r.quantities):
        units = _rocking_units(key)
        variables[f"rocking_continuum_{key}"] = (("soil", "fs_v"), r.continuum[..., q], {
            "units": units, "long_name": f"{key} of the continuum's pushover"})
        variables[f"rocking_bed_{key}"] = (("soil", "fs_v", "calibration"), r.beds[..., q], {
            "units": units, "long_name": f"{key} of the bed's pushover"})
        variables[f"rocking_floor_{key}"] = (("soil", "fs_v"), r.floors[..., q], {
            "units": units, "long_name": f"error floor of {key}"})
    return variables


def write(result, ctx: Context) -> StudyResult:
    """The map and statics files, the figures and the summary into ``ctx.out``."""
    from .figures import write_figures
    from .summary import summary_markdown, summary_numbers

    data, out = result.data, ctx.out
    prov = provenance(study=STUDY, fast=ctx.fast, grid=asdict(data.grid),
                      options=asdict(data.options), store=str(ctx.store.root))
    files = [write_dataset(out / "map.nc", map_dataset(data, prov)),
             write_dataset(out / "statics.nc", statics_dataset(data, prov))]
    if data.options.figures:
        files += write_figures(result, out / "figures")
    elapsed = ctx.elapsed()
    numbers = summary_numbers(result, elapsed)
    text = summary_markdown(result, ctx.fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, ctx.fast, out, tuple(files), text, numbers, prov, elapsed)

