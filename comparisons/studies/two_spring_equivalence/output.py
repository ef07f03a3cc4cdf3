"""The study's data files (statics, convergence, maps) and its write step."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path


from ....provenance import provenance
from ....results import write_csv, write_dataset
from ...framework.protocol import Context
from ...framework.study import StudyResult, write_summary
from .convergence import Convergence
from .figures import write_figures
from .grid import STUDY
from .maps import ErrorMap
from .result import TwoSpringEquivalence
from .statics import Statics
from .summary import summary_markdown, summary_numbers
from .datasets import convergence_dataset, map_dataset

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
             _write_convergence(result.convergence, out / "convergence.nc", prov,
                                base.table["units"])]
    files += [_write_map(m, out / f"map_{m.name}.nc", prov, base.table["units"])
              for m in result.maps]
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


def _write_convergence(conv: Convergence, path: Path, prov: Mapping, units: str) -> Path:
    return write_dataset(path, convergence_dataset(conv, prov, units))


def _write_map(emap: ErrorMap, path: Path, prov: Mapping, units: str) -> Path:
    return write_dataset(path, map_dataset(emap, prov, units))


