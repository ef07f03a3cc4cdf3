"""The study's data files (paths, errors, dynamic histories) and its write step."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path

import numpy as np

from ...provenance import provenance
from ...results import cf_attributes, write_csv, write_dataset
from ..protocol import Context
from ..study import StudyResult, ascii_text, write_summary
from .analysis import ErrorTable
from .dynamics import DYNAMIC_LABELS, DYNAMIC_MEASURES, HISTORIES, DynamicRun
from .figures import write_figures
from .options import STUDY
from .result import WinklerVsContinuum
from .summary import quantity_unit, summary_markdown, summary_numbers

# ---------------------------------------------------------------------------------------------
# Output: data, figures, summary
# ---------------------------------------------------------------------------------------------


def write(result: WinklerVsContinuum, ctx: Context) -> StudyResult:
    """Paths, errors, dynamics, figures and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, scene=result.scene.name, scene_digest=result.scene.digest,
                      overrides=list(result.scene.overrides), fast=fast,
                      options=asdict(result.options), store=str(store.root),
                      continuum_dofs=result.reference.dofs)
    files = [_write_paths(result, "monotonic", out / "monotonic.csv"),
             _write_paths(result, "cyclic", out / "cyclic.csv"),
             _write_errors(result.table, out / "errors.nc", prov, result.scene.units)]
    files += [_write_dynamic(run, out / f"dynamic_{run.key}.nc", prov, result.scene.units)
              for run in result.dynamics.runs]
    if result.options.figures:
        files += write_figures(result, out / "figures")
    elapsed = ctx.elapsed()
    numbers = summary_numbers(result, elapsed)
    text = summary_markdown(result, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def _write_paths(result: WinklerVsContinuum, which: str, path: Path) -> Path:
    ref = result.reference
    cont = getattr(ref, which)
    columns = {"theta": cont["theta"], "theta_over_theta_on": np.asarray(cont["theta"])
               / ref.theta_on, "M_continuum": cont["M"],
               "settlement_continuum": cont["settlement"], "contact_continuum": cont["contact"]}
    if which == "monotonic":
        columns.update(M_continuum_elastic=ref.elastic["M"],
                       contact_continuum_elastic=ref.elastic["contact"])
    for bed in result.beds:
        rec, name = getattr(bed, which), bed.calibration.name
        columns.update({f"M_{name}": rec["M"], f"settlement_{name}": rec["settlement"],
                        f"contact_{name}": rec["contact"]})
    units = result.scene.units
    return write_csv(path, columns, header=(
        f"{STUDY}: {which} rotation pushover at N = {ref.N:g} {units.force}/{units.length}, "
        f"B = {ref.B:g} {units.length}; theta in rad, theta_on = {ref.theta_on:.6g} rad; M in "
        f"{units.force}*{units.length}/{units.length}, settlement (down) and contact length in "
        f"{units.length}; continuum = the scene's soil, continuum_elastic = elastic soil"))


def _write_errors(table: ErrorTable, path: Path, prov: Mapping, units) -> Path:
    return write_dataset(path, errors_dataset(table, prov, units))


def _write_dynamic(run: DynamicRun, path: Path, prov: Mapping, units) -> Path:
    return write_dataset(path, dynamic_dataset(run, prov, units))


def errors_dataset(table: ErrorTable, prov: Mapping, units):
    """The error table as a labelled dataset: ``error`` over (calibration, quantity), so that
    ``ds.error.sel(calibration="uniform_plastic", quantity="onset_moment")`` is one entry, with
    each quantity's label and group as coordinates along it; the quantities mix units, so each
    has its own ``value_<quantity>`` (the beds, over calibration) and ``reference_<quantity>``
    (the continuum, its error floor as an attribute), in the scene's units per unit length."""
    import xarray as xr

    coords = {
        "calibration": ("calibration", list(table.calibrations),
                        {"long_name": "Winkler-bed calibration"}),
        "quantity": ("quantity", list(table.quantities), {"long_name": "quantity compared"}),
        "label": ("quantity", [ascii_text(s) for s in table.labels],
                  {"long_name": "what the quantity is"}),
        "group": ("quantity", [ascii_text(s) for s in table.groups],
                  {"long_name": "what the quantity belongs to"}),
    }
    data = {"error": (("calibration", "quantity"), table.errors, {
        "units": "1", "long_name": "(bed - continuum)/max(|continuum|, floor); NaN: none"})}
    for k, (key, label) in enumerate(zip(table.quantities, table.labels)):
        unit = quantity_unit(key, units, cf=True)
        data[f"value_{key}"] = ("calibration", table.values[:, k], {
            "units": unit, "long_name": ascii_text(f"{label} of the bed (inf: no capacity)")})
        data[f"reference_{key}"] = ((), table.reference[k], {
            "units": unit, "long_name": ascii_text(f"{label} of the continuum"),
            "error_floor": float(table.floors[k])})
    attrs = {"Conventions": "CF-1.10", "title": f"{STUDY}: error table", "provenance": prov}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


def dynamic_dataset(run: DynamicRun, prov: Mapping, units):
    """One motion's overlaid histories (continuum and beds) over (model, time) and their peaks
    over (measure, model)."""
    import xarray as xr

    models = ("continuum",) + tuple(run.beds)
    length = units.length
    history_units = {"theta": ("rad", "footing rotation"), "u": (length, "story deformation"),
                     "uplift": (length, "uplift of the footing's edge"),
                     "settlement": (length, "settlement of the centre from rest (down)"),
                     "contact": (length, "length of the base in contact")}
    coords = {"model": ("model", list(models), {"long_name": "continuum or bed calibration"}),
              "time": ("time", run.time, {"units": "s", "long_name": "time", "axis": "T"}),
              "measure": ("measure", list(DYNAMIC_MEASURES), {"long_name": "peak measure"})}
    data = {}
    for key in HISTORIES:
        values = [run.continuum[key]] + [run.beds[n][key] for n in run.beds]
        unit, long = history_units[key]
        data[key] = (("model", "time"), np.array(values, dtype=float),
                     {"units": unit, "long_name": long})
    for m in DYNAMIC_MEASURES:
        values = [run.continuum["peaks"][m]] + [run.beds[n]["peaks"][m] for n in run.beds]
        unit = "rad" if m == "theta" else length
        data[f"peak_{m}"] = ("model", np.array(values, dtype=float),
                             {"units": unit, "long_name": ascii_text(DYNAMIC_LABELS[m])})
    attrs = {"Conventions": "CF-1.10", "title": ascii_text(f"{STUDY}: {run.label}"),
             "provenance": prov}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))
