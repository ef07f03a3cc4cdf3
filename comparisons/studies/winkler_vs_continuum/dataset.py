"""The study's data as labelled datasets, built from what :func:`.workflow.compute` ran.

The result is an :class:`xarray.DataTree` of two kinds of node, one NetCDF file each:

* ``comparison``: the continuum's numbers (``N``, ``B``, ``K_r``, ``K_v``, ``N_ult``,
  ``theta_on``, its uplift onsets ``onset_*`` and, on elastic soil, ``elastic_onset_*``), its
  vertical pushover (``vertical_step``), the rotation paths of the continuum, the elastic
  continuum and each bed over ``model`` (``M_monotonic`` over ``theta_over_theta_on``;
  ``M_cyclic`` over ``cyclic_step``, since a cycle visits each θ twice), each bed's
  calibration over ``calibration`` (its stiffness as calibrated, R_k, R_e, FS_v, what it
  matches and why it misses), the end stiffening (``end_stiffening_*``), and the error table:
  ``error`` over (calibration, quantity), with each quantity's ``value_<q>`` (the beds) and
  ``reference_<q>`` (the continuum, its error floor as an attribute);
* ``dynamic_<motion>``: one motion's histories over (model, time) and its peaks over model
  (:func:`.dynamic_data.dynamic_dataset`).

The motions' runs have time axes of different lengths (3 s of pulse, 10 s of El Centro), which
no one ``time`` dimension holds: hence one node per motion, not one dataset. The comparison's
``motions`` attribute lists them in order. Units are the scene's, per unit length of the strip.
``tree["comparison"].error.sel(calibration="uniform_plastic", quantity="onset_moment")``.
"""

from __future__ import annotations

import numpy as np

from ....results import cf_attributes
from ...beds.stiffness import LABELS
from ...framework.study import ascii_text
from .analysis import ErrorTable, texts
from .dynamic_data import dynamic_dataset
from .dynamics import DynamicComparison, run_overrides
from .options import STUDY, Options
from .reference import ContinuumReference
from .units import quantity_unit

__all__ = ["study_dataset", "comparison", "motion_keys", "dynamic_runs", "texts",
           "PATH_MODELS"]

#: The continuum's rows of the paths' ``model`` dimension (the beds follow).
PATH_MODELS = ("continuum", "continuum_elastic")
NODE = "comparison"


def study_dataset(scene, options: Options, fast: bool, ref: ContinuumReference,
                  calibrations, beds, table: ErrorTable, dynamics: DynamicComparison):
    """The study's :class:`xarray.DataTree` (module docstring)."""
    import xarray as xr

    units = scene.units
    nodes = {NODE: _comparison(scene, options, fast, ref, calibrations, beds, table,
                               dynamics)}
    nodes.update({f"dynamic_{run.key}": dynamic_dataset(run, units)
                  for run in dynamics.runs})
    return xr.DataTree.from_dict(nodes, name=STUDY)


# ---------------------------------------------------------------------------------------------
# Reading the tree (in memory, or opened from disk by upliftlab.open_study)
# ---------------------------------------------------------------------------------------------


def comparison(data):
    """The ``comparison`` node of the study's tree as an :class:`xarray.Dataset`."""
    return data[NODE].to_dataset()


def motion_keys(data) -> list[str]:
    """The motions of the dynamic comparison, in the order they ran."""
    return texts(comparison(data).attrs.get("motions", ""))


def dynamic_runs(data) -> list:
    """The ``dynamic_<motion>`` datasets of the study's tree, in the order they ran."""
    return [data[f"dynamic_{key}"].to_dataset() for key in motion_keys(data)]


# ---------------------------------------------------------------------------------------------
# The comparison node
# ---------------------------------------------------------------------------------------------


def _scalar(value, unit: str, long_name: str) -> tuple:
    return ((), value, {"units": unit, "long_name": ascii_text(long_name)})


def _reference(ref: ContinuumReference, units) -> dict:
    """The continuum's numbers, its uplift onsets and its vertical pushover."""
    F, L = units.force, units.length
    out = {"N": _scalar(ref.N, f"{F}/{L}", "vertical load per length"),
           "B": _scalar(ref.B, L, "footing width"),
           "h": _scalar(ref.h, L, "height of the structure"),
           "G": _scalar(ref.G, f"{F}/{L}^2", "soil shear modulus"),
           "nu": _scalar(ref.nu, "1", "soil Poisson ratio"),
           "c_u": _scalar(np.nan if ref.cu is None else ref.cu, f"{F}/{L}^2",
                          "undrained strength (NaN: the soil is not undrained)"),
           "K_r": _scalar(ref.K_r, f"{F}*{L}/{L}/rad", "continuum rocking stiffness, bonded"),
           "K_v": _scalar(ref.K_v, f"{F}/{L}/{L}",
                          "continuum vertical stiffness, bonded (depends on the box)"),
           "N_ult": _scalar(ref.N_ult, f"{F}/{L}", "continuum vertical capacity"),
           "theta_on": _scalar(ref.theta_on, "rad",
                               "half-plane uplift rotation 2N(1 - nu)/(pi G B)"),
           "continuum_dofs": _scalar(int(ref.dofs), "1", "degrees of freedom of the mesh")}
    for prefix, which, soil in (("", "monotonic", "the scene's soil"),
                                ("elastic_", "elastic", "elastic soil")):
        onset = ref.onset(which)
        for key, unit, what in (("theta", "rad", "rotation"), ("M", f"{F}*{L}/{L}", "moment"),
                                ("e", L, "eccentricity M/N")):
            out[f"{prefix}onset_{key}"] = _scalar(float(onset.get(key, np.nan)), unit,
                                                  f"uplift onset on {soil}: {what}")
        if "error" in onset:  # why none was found
            out[f"{prefix}onset_error"] = ((), onset["error"], {
                "long_name": f"why no uplift onset was found on {soil}"})
    out["vertical_settlement"] = (("vertical_step",), np.asarray(ref.vertical["settlement"],
                                                                 float),
                                  {"units": L, "long_name": "vertical pushover: settlement"})
    out["vertical_load"] = (("vertical_step",), np.asarray(ref.vertical["N"], float),
                            {"units": f"{F}/{L}", "long_name": "vertical pushover: load"})
    return out


_PATHS = {"M": ("{F}*{L}/{L}", "moment"), "settlement": ("{L}", "settlement (down)"),
          "contact": ("{L}", "contact length")}


def _paths(ref: ContinuumReference, beds, units) -> dict:
    """The monotonic and cyclic paths over (model, step); the elastic continuum ran the
    monotonic path alone (NaN on the cyclic one)."""
    if not np.array_equal(ref.elastic["theta"], ref.monotonic["theta"]):
        raise RuntimeError("the elastic continuum's rotations differ from the scene soil's")
    out = {}
    for path, dim in (("monotonic", "theta_over_theta_on"), ("cyclic", "cyclic_step")):
        rows = [getattr(ref, path), ref.elastic if path == "monotonic" else None]
        rows += [getattr(bed, path) for bed in beds]
        for key, (unit, what) in _PATHS.items():
            size = len(ref.monotonic["theta"] if path == "monotonic" else ref.cyclic["theta"])
            values = np.array([np.full(size, np.nan) if r is None else
                               np.asarray(r[key], dtype=float) for r in rows])
            out[f"{key}_{path}"] = (("model", dim), values, {
                "units": unit.format(F=units.force, L=units.length),
                "long_name": f"{path} rotation pushover: {what}"})
    return out


def _calibrations(calibrations, units) -> dict:
    F, L = units.force, units.length

    def per_bed(field, unit, long_name, convert=float):
        attrs = {"long_name": long_name} | ({"units": unit} if unit else {})
        return ("calibration",), np.array([convert(getattr(c, field)) for c in calibrations]), \
            attrs

    return {
        "springs": per_bed("springs", "1", "springs of the bed", int),
        "bed_vertical_stiffness": per_bed("vertical_stiffness", f"{F}/{L}/{L}",
                                          "bed vertical stiffness as calibrated, sum k_i"),
        "bed_rocking_stiffness": per_bed("rocking_stiffness", f"{F}*{L}/{L}/rad",
                                         "bed rocking stiffness as calibrated, sum k_i x_i^2"),
        "end_stiffness_ratio": per_bed("end_stiffness_ratio", "1", "end-stiffness ratio R_k"),
        "end_length": per_bed("end_length", "1", "end length R_e over the half-width b"),
        "yield_multiple": (("calibration",), np.array(
            [c.yield_multiple if c.law != "elastic" else np.nan for c in calibrations]), {
                "units": "1", "long_name": "springs' yield force over their static force, "
                                           "FS_v (NaN: elastic springs)"}),
        "matches": per_bed("matches", None, "continuum quantities the bed is calibrated to",
                           ",".join),
        "note": per_bed("note", None, "why the bed misses a quantity (empty: it does not)",
                        str)}


def _end_stiffening(calibrations, units) -> dict:
    """The end-stiffened bed's solve for R_k (:class:`...beds.stiffness.EndStiffening`)."""
    s = next(c.stiffening for c in calibrations if c.name == "end_stiffened")
    L2 = f"{units.length}^2"
    return {"end_stiffening_target": _scalar(s.target, L2, "target K_r/K_v"),
            "end_stiffening_ratio": _scalar(s.ratio, "1", "R_k used"),
            "end_stiffening_exact": _scalar(s.exact, "1", "R_k solving the target unbounded"),
            "end_stiffening_reachable": (("bound",), np.array(s.reachable, dtype=float), {
                "units": L2, "long_name": "K_theta/K_v over R_k in [1, R_k,max]"}),
            "end_stiffening_supremum": _scalar(s.supremum, L2, "K_theta/K_v as R_k -> inf"),
            "end_stiffening_feasible": ((), bool(s.feasible),
                                        {"long_name": "an R_k reaches the target"})}


def error_variables(table: ErrorTable, units) -> dict:
    """The error table: ``error`` over (calibration, quantity), each quantity's values."""
    data = {"error": (("calibration", "quantity"), table.errors, {
        "units": "1", "long_name": "(bed - continuum)/max(|continuum|, floor); NaN: none"})}
    for k, (key, label) in enumerate(zip(table.quantities, table.labels)):
        unit = quantity_unit(key, units, cf=True)
        data[f"value_{key}"] = ("calibration", table.values[:, k], {
            "units": unit, "long_name": ascii_text(f"{label} of the bed (inf: no capacity)")})
        data[f"reference_{key}"] = ((), table.reference[k], {
            "units": unit, "long_name": ascii_text(f"{label} of the continuum"),
            "error_floor": float(table.floors[k])})
    return data


def _coords(ref: ContinuumReference, calibrations, table: ErrorTable) -> dict:
    names = [c.name for c in calibrations]
    return {
        "calibration": ("calibration", names, {"long_name": "Winkler-bed calibration"}),
        "calibration_label": ("calibration", [ascii_text(LABELS[n]) for n in names],
                              {"long_name": "what the bed is"}),
        "layout": ("calibration", [c.layout for c in calibrations],
                   {"long_name": "spring layout"}),
        "law": ("calibration", [c.law for c in calibrations], {"long_name": "spring law"}),
        "quantity": ("quantity", list(table.quantities), {"long_name": "quantity compared"}),
        "label": ("quantity", [ascii_text(s) for s in table.labels],
                  {"long_name": "what the quantity is"}),
        "group": ("quantity", [ascii_text(s) for s in table.groups],
                  {"long_name": "what the quantity belongs to"}),
        "model": ("model", list(PATH_MODELS) + names,
                  {"long_name": "continuum (scene soil), continuum on elastic soil, or bed"}),
        "theta_over_theta_on": ("theta_over_theta_on",
                                np.asarray(ref.monotonic["theta"]) / ref.theta_on,
                                {"units": "1", "long_name": "monotonic path: theta/theta_on"}),
        "monotonic_theta": ("theta_over_theta_on", np.asarray(ref.monotonic["theta"], float),
                            {"units": "rad", "long_name": "monotonic path: rotation"}),
        "cyclic_step": ("cyclic_step", np.arange(len(ref.cyclic["theta"])),
                        {"long_name": "step of the cyclic path"}),
        "cyclic_theta": ("cyclic_step", np.asarray(ref.cyclic["theta"], float),
                         {"units": "rad", "long_name": "cyclic path: rotation"}),
        "bound": ("bound", ["low", "high"], {"long_name": "end of a range"})}


def _comparison(scene, options: Options, fast: bool, ref: ContinuumReference, calibrations,
                beds, table: ErrorTable, dynamics: DynamicComparison):
    import xarray as xr

    units, soil = scene.units, scene.soil
    data = {**_reference(ref, units), **_paths(ref, beds, units),
            **_calibrations(calibrations, units), **_end_stiffening(calibrations, units),
            **error_variables(table, units)}
    attrs = {"Conventions": "CF-1.10", "title": f"{STUDY}: Winkler beds against the continuum",
             "scene": scene.name, "scene_digest": scene.digest,
             "overrides": list(scene.overrides), "units": units.name, "fast": bool(fast),
             "soil_model": soil.model, "soil_youngs_modulus": soil.youngs_modulus,
             "soil_interface": soil.interface, "adequate": options.adequate,
             "theta_ratios": list(options.theta_ratios),
             "dynamic_available": dynamics.available, "dynamic_reason": dynamics.reason,
             "dynamic_overrides": list(run_overrides(options, fast)),
             "motions": [run.key for run in dynamics.runs]}
    return xr.Dataset(data, coords=_coords(ref, calibrations, table),
                      attrs=cf_attributes(attrs))
