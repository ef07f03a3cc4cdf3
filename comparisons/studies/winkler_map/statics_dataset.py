"""The map's ``statics`` dataset (written ``statics.nc``): per soil the continuum statics (K_v,
K_r, V_ult and the vertical pushover on ``step``) and, when a bed needed it, the continuum's
impedance dashpots on ``frequency``; over (soil, fs_v, calibration, statics_quantity) every
bed's rocking pushovers against the continuum's (:mod:`.rocking`), with θ_on, the fitted
bed's exponent and misfit, and the rows that could not be made (``rocking_failures``)."""

from __future__ import annotations

import numpy as np

from ....results import cf_attributes
from ...framework.study import ascii_text
from .grid import SOIL_LABELS
from .rocking import RockingData

__all__ = ["statics_dataset", "rocking_variables"]


def _padded(rows, width: int) -> np.ndarray:
    out = np.full((len(rows), width), np.nan)
    for i, values in enumerate(rows):
        out[i, :len(values)] = values
    return out


def _statics_variables(statics) -> dict:
    steps = max(len(s.load) for s in statics)
    return {
        "K_v": (("soil",), [s.K_v for s in statics], {
            "units": "kN/m/m", "long_name": "continuum vertical stiffness, full contact"}),
        "K_r": (("soil",), [s.K_r for s in statics], {
            "units": "kN m/rad/m", "long_name": "continuum rocking stiffness, full contact"}),
        "V_ult": (("soil",), [s.V_ult for s in statics], {
            "units": "kN/m", "long_name": "continuum vertical capacity (largest load of the "
                                          "vertical pushover)"}),
        "plateau": (("soil",), [s.plateau for s in statics], {
            "units": "1", "long_name": "load increase of the pushover's last step over V_ult"}),
        "settlement": (("soil", "step"), _padded([s.settlement for s in statics], steps),
                       {"units": "m", "long_name": "vertical pushover: settlement"}),
        "load": (("soil", "step"), _padded([s.load for s in statics], steps), {
            "units": "kN/m", "long_name": "vertical pushover: load"}),
        "dofs": (("soil",), [s.dofs for s in statics], {
            "units": "1", "long_name": "degrees of freedom of the mesh"}),
        "wall_time": (("soil",), [s.wall_time_s for s in statics], {
            "units": "s", "long_name": "wall time of the two static runs"}),
    }


def _impedance_variables(soils, impedances: dict) -> dict:
    """The continuum's impedance dashpots of each soil (:class:`~upliftlab.continuum.impedance.
    Impedance`) over ``frequency``, when a bed needed them (else none)."""
    if not impedances:
        return {}
    imps = [impedances[s] for s in soils]
    n = max(imp.a0.size for imp in imps)
    dims = ("soil", "frequency")
    return {
        "impedance_a0": (dims, _padded([imp.a0 for imp in imps], n), {
            "units": "1", "long_name": "dimensionless frequency omega (B/2)/V_s of the "
                                       "continuum's impedance"}),
        "impedance_omega": (dims, _padded([imp.omega for imp in imps], n), {
            "units": "rad/s", "long_name": "circular frequency of the continuum's impedance"}),
        "impedance_dashpot_v": (dims, _padded([imp.dashpot("v") for imp in imps], n), {
            "units": "kN s/m/m", "long_name": "vertical dashpot C_v = Im K_v/omega of the "
                                             "continuum's impedance"}),
        "impedance_dashpot_r": (dims, _padded([imp.dashpot("r") for imp in imps], n), {
            "units": "kN m s/rad/m", "long_name": "rocking dashpot C_r = Im K_r/omega of the "
                                                 "continuum's impedance"}),
        "impedance_dofs": (("soil",), [imp.dofs for imp in imps], {
            "units": "1", "long_name": "degrees of freedom of the impedance's mesh"}),
        "impedance_wall_time": (("soil",), [float(imp.metadata.get("wall_time_s", np.nan))
                                            for imp in imps], {
            "units": "s", "long_name": "wall time of the impedance run (stored with it)"}),
    }


def _fit_variables(soils, fs_v, fits: dict) -> dict:
    """The fitted bed's capacity exponent β and misfit per (soil, fs_v), when it is compared."""
    if not fits:
        return {}

    def per_cell(field):
        return np.array([[getattr(fits[s, fs], field) if (s, fs) in fits else np.nan
                          for fs in fs_v] for s in soils], dtype=float)

    return {"capacity_beta": (("soil", "fs_v"), per_cell("beta"), {
                "units": "1", "long_name": "the fitted bed's capacity exponent: yield pressure "
                                          "proportional to (k_i/w_i)**beta"}),
            "capacity_misfit": (("soil", "fs_v"), per_cell("misfit"), {
                "units": "1", "long_name": "the fitted bed's root-mean-square relative misfit "
                                          "to the continuum's rotation pushovers"})}


def _rocking_units(key: str) -> str:
    return "m" if key.startswith(("contact", "settlement", "cyclic_settlement")) else "kN m/m"


def rocking_variables(r: RockingData) -> dict:
    """The statics rows (:mod:`.rocking`) as variables over soil, fs_v, calibration and
    statics_quantity: the signed errors, and each quantity's continuum and bed values and floor
    with its units."""
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


def statics_dataset(statics, grid, calibrations, rocking: RockingData, fits: dict,
                    impedances: dict):
    """The ``statics`` dataset (module docstring) of the soils' :class:`.statics.SoilStatics`,
    the ``grid``'s FS_v, the ``calibrations``, the ``rocking`` rows, the fitted bed's
    ``fits`` ({(soil, fs_v): CapacityFit}) and the soils' ``impedances`` ({soil: Impedance},
    empty when no bed needed them)."""
    import xarray as xr

    soils = [s.soil for s in statics]
    variables = _statics_variables(statics)
    variables.update(rocking_variables(rocking))
    variables.update(_fit_variables(soils, grid.fs_v, fits))
    variables.update(_impedance_variables(soils, impedances))
    steps = variables["load"][1].shape[1]
    coords = {"soil": ("soil", soils, {"long_name": "soil of the continuum"}),
              "fs_v": ("fs_v", np.array(grid.fs_v, dtype=float), {
                  "units": "1", "long_name": "vertical factor of safety V_ult/N"}),
              "calibration": ("calibration", list(calibrations), {
                  "long_name": "calibrated reduced model (bed)"}),
              "statics_quantity": ("statics_quantity", list(rocking.quantities), {
                  "long_name": "quantity of the rocking pushovers compared"}),
              "statics_group": ("statics_quantity", [ascii_text(g) for g in rocking.groups], {
                  "long_name": "what the quantity belongs to: uplift onset, M-theta backbone, "
                               "contact length, settlement against theta, cyclic dissipation "
                               "or cyclic settlement"}),
              "soil_label": ("soil", [ascii_text(SOIL_LABELS[s]) for s in soils],
                             {"long_name": "the soil's model and strength"}),
              "step": ("step", np.arange(steps), {"units": "1",
                                                  "long_name": "pushover step"})}
    attrs = {"Conventions": "CF-1.10", "title": "Winkler map: the continuum statics per soil",
             "rocking_failures": list(rocking.failures)}
    return xr.Dataset(variables, coords=coords, attrs=cf_attributes(attrs))
