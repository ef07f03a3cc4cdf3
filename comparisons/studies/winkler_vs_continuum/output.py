"""The study's data files (paths, errors, dynamic histories) and its write step."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path

import numpy as np

from ....provenance import provenance
from ....results import write_csv, write_dataset
from ...framework.protocol import Context
from ...framework.study import StudyResult, write_summary
from .analysis import ErrorTable
from .dynamics import DynamicRun
from .figures import write_figures
from .options import STUDY
from .result import WinklerVsContinuum
from .summary import summary_markdown, summary_numbers
from .datasets import dynamic_dataset, errors_dataset

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


