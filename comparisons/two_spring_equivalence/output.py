"""The study's data files (statics, convergence, maps) and its write step."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path

import numpy as np

from ...results import provenance, write_csv, write_netcdf
from ..protocol import Context
from ..study import StudyResult, ascii_text, write_summary
from .convergence import Convergence
from .figures import write_figures
from .grid import FLOOR_FRACTION, METRICS, STUDY
from .maps import ErrorMap
from .result import TwoSpringEquivalence
from .statics import Statics
from .summary import summary_markdown, summary_numbers


# ---------------------------------------------------------------------------------------------
# Output: data, figures, summary
# ---------------------------------------------------------------------------------------------


def write(result: TwoSpringEquivalence, ctx: Context) -> StudyResult:
    """Statics, convergence, maps, figures and the summary into ``ctx.out``."""
    base, fast, out, store = result.base, ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, scene=base.name, fast=fast, grid=asdict(result.grid),
                      options=asdict(result.options), springs=result.springs,
                      store=str(store.root))
    files = [_write_statics(result.statics, out / "statics.csv"),
             _write_convergence(result.convergence, out / "convergence.nc", prov)]
    files += [_write_map(m, out / f"map_{m.name}.nc", prov) for m in result.maps]
    if result.options.figures:
        files += write_figures(result, out / "figures")
    elapsed = ctx.elapsed()
    numbers = summary_numbers(result, elapsed)
    text = summary_markdown(result, base, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def _write_statics(statics: Statics, path: Path) -> Path:
    columns = {"theta_over_theta_up": statics.theta}
    for s in statics.layouts:
        slug = s.label.replace(" ", "_").replace("(", "").replace(")", "").replace("-", "_")
        columns[f"M_elastic_{slug}"] = s.elastic
        columns[f"M_plastic_{slug}"] = s.plastic
    return write_csv(path, columns, header=f"{STUDY}: rocking pushovers, M/(N B) against "
                     f"theta/theta_up, N = {statics.springs} springs, "
                     f"FS_v = {statics.yield_multiple:g}")


def _write_convergence(conv: Convergence, path: Path, prov: Mapping) -> Path:
    variables = {"springs": (("springs",), np.array(conv.candidates), {})}
    for key, values in conv.static.items():
        variables[f"static_{key}"] = (("springs",), np.array(values), {"units": "M/(N B)"})
    for case, measures in conv.dynamic.items():
        for m, values in measures.items():
            variables[f"case_{case}_{m}"] = (("springs",), np.array(values, dtype=float), {})
    attrs = {"title": f"{STUDY}: convergence of the Winkler bed in N", "chosen_springs":
             conv.springs, "converged": conv.converged, "changes": conv.changes,
             "motion": ascii_text(conv.motion), "provenance": prov}
    return write_netcdf(path, variables, attrs)


def _write_map(emap: ErrorMap, path: Path, prov: Mapping) -> Path:
    dims5 = ("case", "layout", "measure", "y", "x")
    numeric_y = all(isinstance(v, (int, float)) for v in emap.y.values)
    variables = {
        "x": (("x",), np.array(emap.x.values, dtype=float),
              {"long_name": ascii_text(emap.x.label)}),
        "y": (("y",), np.array(emap.y.values if numeric_y else range(len(emap.y.values)),
                               dtype=float), {"long_name": ascii_text(emap.y.label)}),
        "error": (dims5, emap.errors, {"long_name": "(two-spring - bed)/max(|bed|, floor)"}),
        "value": (dims5, emap.values, {}),
        "reference": (("case", "measure", "y", "x"), emap.reference, {}),
        "uplifted": (("case", "y", "x"), emap.uplifted, {}),
    }
    attrs = {"title": ascii_text(emap.title), "bed": emap.bed, "cases": list(emap.cases),
             "layouts": list(emap.layouts), "measures": list(METRICS),
             "y_labels": [str(v) for v in emap.y.values], "floor_fraction": FLOOR_FRACTION,
             "failures": list(emap.failures), "provenance": prov}
    return write_netcdf(path, variables, attrs)
