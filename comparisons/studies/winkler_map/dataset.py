"""The map as labelled data: an :class:`xarray.DataTree` of two datasets, ``map`` (every
point's runs, written ``map.nc``) and ``statics`` (the continuum statics per soil and the beds'
rocking pushovers against them, written ``statics.nc``, :mod:`.statics_dataset`).

``map`` is over (``soil``, ``fs_v``, ``h_over_B``, ``period``, ``intensity``, ``motion``)
(:data:`POINT_DIMS`), with ``calibration`` for each bed's run and ``measure`` for the errors:
both models' measures (``continuum_<measure>``, ``bed_<measure>``), the signed ``error``
(bed − continuum)/max(|continuum|, floor) and the floors ``floor_<measure>``; each continuum
run's wall time, steps, DOFs and energy balance and each bed run's wall time; the bearing
failures; the energies of :data:`.energy.ENERGIES` and their errors; over (soil, fs_v) the
vertical load N and each built bed's stiffness. Its attributes hold what judges the map
(``options_*``), its grid (``grid_*``), the runs that failed (``refusals``), the cost
estimated before the work (``estimate_*``), the continuum runs made (``computed``) and the
local ``workers`` the estimate was divided by::

    tree["map"].error.sel(h_over_B=1.5, calibration="uniform", measure="theta")
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ....results import cf_attributes
from ...beds import BEDS
from ...framework.study import ascii_text
from .cost import Estimate
from .energy import ENERGIES
from .grid import FLOOR_FRACTION, MEASURE_LABELS, MEASURE_UNITS, MEASURES
from .parts import POINT_DIMS

#: The dimensions of a structure on a soil (a bed is built once for each).
STRUCTURE_DIMS = POINT_DIMS[:4]
from .points import SIDES

__all__ = ["POINT_DIMS", "PointArrays", "map_dataset"]


@dataclass
class PointArrays:
    """What the map measured, filled point by point as the beds run (NaN, or False, where a
    run is missing), in :data:`POINT_DIMS` order (…): ``continuum`` (…, measure), ``beds`` and
    ``errors`` (…, calibration, measure), ``scale`` (soil, fs_v, h_over_B, period, measure)
    the floors' basis, ``continuum_wall``, ``steps``, ``balance``, ``dofs`` and ``bearing``
    (…), ``bed_wall`` and ``bed_bearing`` (…, calibration), ``N`` (soil, fs_v), ``bed_K_r``
    and ``bed_K_v`` (soil, fs_v, h_over_B, period, calibration: a bed calibrated at the
    structure's rocking frequency differs by structure), ``continuum_energy`` (…, energy),
    ``bed_energy`` and ``energy_errors`` (…, calibration, energy), ``energy_scale`` (soil,
    fs_v, h_over_B, period), ``energy_left`` (…), ``beyond`` (…) the continuum's run
    passed the small-strain limit (:mod:`upliftlab.continuum.dynamics.validity`) and
    ``far_yield`` (…) its far field yielded under the motion: 1 yes, 0 no, -1 not recorded
    (a run that failed, or a record made before the far field was stored)."""

    continuum: np.ndarray
    beds: np.ndarray
    errors: np.ndarray
    scale: np.ndarray
    continuum_wall: np.ndarray
    steps: np.ndarray
    balance: np.ndarray
    dofs: np.ndarray
    bed_wall: np.ndarray
    bearing: np.ndarray
    bed_bearing: np.ndarray
    N: np.ndarray
    bed_K_r: np.ndarray
    bed_K_v: np.ndarray
    continuum_energy: np.ndarray
    bed_energy: np.ndarray
    energy_errors: np.ndarray
    energy_scale: np.ndarray
    energy_left: np.ndarray
    beyond: np.ndarray
    far_yield: np.ndarray

    @classmethod
    def empty(cls, shape: tuple[int, ...], beds: int) -> PointArrays:
        """NaN and False arrays of the point ``shape`` (:data:`POINT_DIMS`) and ``beds``."""
        nq, ne = len(MEASURES), len(ENERGIES)

        def nan(*dims):
            return np.full(dims, np.nan)

        return cls(nan(*shape, nq), nan(*shape, beds, nq), nan(*shape, beds, nq),
                   nan(*shape[:4], nq), nan(*shape), nan(*shape), nan(*shape), nan(*shape),
                   nan(*shape, beds), np.zeros(shape, bool), np.zeros(shape + (beds,), bool),
                   nan(*shape[:2]), nan(*shape[:4], beds), nan(*shape[:4], beds),
                   nan(*shape, ne), nan(*shape, beds, ne), nan(*shape, beds, ne),
                   nan(*shape[:4]), nan(*shape), np.zeros(shape, bool),
                   np.full(shape, -1, dtype="i1"))


def _coords(grid, motions, calibrations) -> dict:
    return {
        "soil": ("soil", list(grid.soils), {"long_name": "soil of the continuum"}),
        "fs_v": ("fs_v", np.array(grid.fs_v, dtype=float), {
            "units": "1", "long_name": "vertical factor of safety V_ult/N on the continuum's "
                                       "own vertical capacity"}),
        "h_over_B": ("h_over_B", np.array(grid.h_over_B, dtype=float), {
            "units": "1", "long_name": "slenderness: story height over footing width"}),
        "period": ("period", np.array(grid.periods, dtype=float), {
            "units": "s", "long_name": "fixed-base period of the structure"}),
        "intensity": ("intensity", np.array(grid.intensities, dtype=float), {
            # a ratio (UDUNITS knows no a_up): CF units "1", the quantity in the long name
            "units": "1", "long_name": "intensity in units of a_up: PGA over a_up = g B/(6h), "
                                       "the rigid block's uplift acceleration on a uniform "
                                       "tensionless Winkler bed"}),
        "motion": ("motion", [m["name"] for m in motions], {"long_name": "ground motion"}),
        "motion_kind": ("motion", [m["kind"] for m in motions], {
            "long_name": "kind of motion: ricker, elcentro or fema_p695"}),
        "calibration": ("calibration", list(calibrations), {
            "long_name": "calibrated reduced model (bed)"}),
        "measure": ("measure", list(MEASURES), {"long_name": "quantity compared"}),
        "measure_label": ("measure", [ascii_text(MEASURE_LABELS[m]) for m in MEASURES], {
            "long_name": "what each measure is (its values: variables bed_<measure> and "
                         "continuum_<measure>)"}),
        "calibration_label": ("calibration", [ascii_text(BEDS[c].label) if c in BEDS else c
                                              for c in calibrations],
                              {"long_name": "what each calibration matches"}),
    }


def _variables(a: PointArrays) -> dict:
    d, db = POINT_DIMS, POINT_DIMS + ("calibration",)
    out = {
        "error": (db + ("measure",), a.errors, {
            "units": "1", "long_name": "signed relative error of the bed against the "
                                       "continuum, (bed - continuum)/max(|continuum|, floor); "
                                       "NaN: the bed's run was refused or the "
                                       "continuum's did not finish"}),
        "continuum_wall_time": (d, a.continuum_wall, {
            "units": "s", "long_name": "wall time of the continuum run (stored with it)"}),
        "bed_wall_time": (db, a.bed_wall, {
            "units": "s", "long_name": "wall time of the bed's run (this run)"}),
        "continuum_steps": (d, a.steps, {
            "units": "1", "long_name": "time steps of the continuum run"}),
        "continuum_dofs": (d, a.dofs, {
            "units": "1", "long_name": "degrees of freedom of the continuum mesh"}),
        "energy_balance_error": (d, a.balance, {
            "units": "1", "long_name": "energy balance error of the continuum run (fraction "
                                       "of its input)"}),
        "vertical_load": (("soil", "fs_v"), a.N, {
            "units": "kN/m", "long_name": "vertical load N = V_ult/FS_v"}),
        "bed_rocking_stiffness": (STRUCTURE_DIMS + ("calibration",), a.bed_K_r, {
            "units": "kN m/rad/m", "long_name": "rocking stiffness of the built bed, "
                                                "sum k_i x_i^2"}),
        "bed_vertical_stiffness": (STRUCTURE_DIMS + ("calibration",), a.bed_K_v, {
            "units": "kN/m/m", "long_name": "vertical stiffness of the built bed, sum k_i"}),
        "continuum_bearing_failure": (d, a.bearing.astype("i1"), {
            "units": "1", "long_name": "1: the continuum's run ended in a bearing failure of "
                                       "the soil (its measures NaN)"}),
        "continuum_beyond_small_strain": (d, a.beyond.astype("i1"), {
            "units": "1", "long_name": "1: the continuum's run passed the small-strain limit "
                                       "of plastic strain (left out like a refused run, its "
                                       "measures NaN; only runs that stored the verdict)"}),
        "continuum_far_field_yielded": (d, a.far_yield.astype("i1"), {
            "units": "1", "long_name": "1: the far field (the box's side columns) of the "
                                       "continuum's run yielded under the motion, 0: it stayed "
                                       "elastic, -1: not recorded (a failed run, or a record "
                                       "made before the far field was stored)"}),
        "bed_bearing_failure": (db, a.bed_bearing.astype("i1"), {
            "units": "1", "long_name": "1: at a bearing failure of the continuum, the bed's "
                                       "base settled by the failure settlement too"}),
    }
    out.update(_energy_variables(a, d, db))
    for q, m in enumerate(MEASURES):
        label, units = ascii_text(MEASURE_LABELS[m]), MEASURE_UNITS[m]
        out[f"bed_{m}"] = (db, a.beds[..., q], {"units": units,
                                                "long_name": f"{label} of the bed's run"})
        out[f"continuum_{m}"] = (d, a.continuum[..., q], {
            "units": units, "long_name": f"{label} of the continuum's run"})
        out[f"floor_{m}"] = (d[:4], FLOOR_FRACTION * a.scale[..., q], {
            "units": units, "long_name": f"error floor of {label}: {FLOOR_FRACTION:g} x its "
                                         "value at a uniform bed's uplift threshold"})
    return out


def _energy_variables(a: PointArrays, d: tuple, db: tuple) -> dict:
    """The energies of :data:`.energy.ENERGIES` of both models, their errors and the floor."""
    what = {"foundation_energy": "foundation energy E_F, the energy the structure lost to its "
                                 "foundation over the run",
            "motion_energy": "E_M, the foundation energy less the work of the structure's "
                             "weight (W times its settlement)"}
    out = {}
    for k, name in enumerate(ENERGIES):
        out[f"continuum_{name}"] = (d, a.continuum_energy[..., k], {
            "units": "kN m/m", "long_name": f"{what[name]}, of the continuum's energy run (NaN: "
                                           "not stored)"})
        out[f"bed_{name}"] = (db, a.bed_energy[..., k], {
            "units": "kN m/m", "long_name": f"{what[name]}, of the bed's run"})
        out[f"{name}_error"] = (db, a.energy_errors[..., k], {
            "units": "1", "long_name": f"signed relative error of the bed's {name} against the "
                                       "continuum's, (bed - continuum)/max(|continuum|, floor)"})
    out["continuum_energy_left"] = (d, a.energy_left, {
        "units": "kN m/m", "long_name": "kinetic and story energy the continuum's structure "
                                        "still holds at the end of its energy run"})
    out["floor_energy"] = (d[:4], FLOOR_FRACTION * a.energy_scale, {
        "units": "kN m/m", "long_name": f"error floor of both energies: {FLOOR_FRACTION:g} x "
                                        "(N B/6)^2/(2 K_r), a uniform bed's strain energy at its "
                                        "uplift threshold"})
    return out


def map_dataset(a: PointArrays, grid, options, motions, calibrations, refusals,
                estimate: Estimate, computed: int, workers: int | None, fast: bool):
    """The ``map`` dataset (module docstring) of the arrays ``a`` of ``grid`` under
    ``options``: ``motions`` (dicts with ``name`` and ``kind``), ``calibrations`` (names),
    ``refusals`` (texts), the ``estimate`` made before the work, the continuum runs
    ``computed``, the local ``workers`` (None: a cluster or a caller's executor) and ``fast``."""
    import xarray as xr

    attrs = {"Conventions": "CF-1.10", "title": "Winkler beds against the continuum: the map",
             "elements_across": options.elements_across, "continuum_boundary": SIDES,
             "floor_fraction": FLOOR_FRACTION, "refusals": list(refusals),
             "fast": bool(fast), "grid": asdict(grid), "options": asdict(options),
             "estimate": asdict(estimate), "computed": int(computed), "workers": workers,
             "continuum_reference": options.reference,
             "count_beyond_small_strain": int(np.sum(a.beyond)),
             "count_far_field_yielded": int(np.sum(a.far_yield == 1)),
             "count_far_field_not_recorded": int(np.sum(a.far_yield == -1))}
    return xr.Dataset(_variables(a), coords=_coords(grid, motions, calibrations),
                      attrs=cf_attributes(attrs))
