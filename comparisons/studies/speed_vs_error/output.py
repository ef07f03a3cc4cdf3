"""The study's data files (points and Pareto fronts) and its write step."""

from __future__ import annotations

from dataclasses import asdict
from pathlib import Path

import numpy as np

from ....provenance import provenance
from ....results import write_csv
from ...framework.protocol import Context
from ...framework.study import StudyResult, write_summary
from .analysis import Point, SceneResult, SpeedVsError
from .figures import write_scene_figure
from .grid import INTEGRATORS, QUANTITIES, STUDY
from .summary import summary_markdown, summary_numbers

# ---------------------------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------------------------


def write(result: SpeedVsError, ctx: Context) -> StudyResult:
    """Points, Pareto fronts, figures and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, fast=fast, grid=asdict(result.grid),
                      options=asdict(result.options), context=result.context,
                      store=str(store.root))
    files = [_write_points(result, out / "points.csv"), _write_pareto(result, out / "pareto.csv")]
    if result.options.figures:
        files += [write_scene_figure(s, out / "figures" / f"{s.label}.png") for s in result.scenes]
    elapsed = ctx.elapsed()
    numbers = summary_numbers(result, elapsed)
    text = summary_markdown(result, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


_MODEL_CODE = {"edges": -2, "equivalent": -1, "continuum": 1}


def _columns(rows: list[tuple[SceneResult, Point]]) -> dict:
    cols = {"scene": [i for i, _ in rows], "springs": [p.springs for _, p in rows],
            "layout_code": [_MODEL_CODE.get(p.model, 0) for _, p in rows],
            "integrator": [INTEGRATORS.index(p.integrator) for _, p in rows],
            "dt_s": [p.dt for _, p in rows], "runtime_s": [p.runtime for _, p in rows],
            "repeats": [p.repeats for _, p in rows]}
    for q in QUANTITIES:
        cols[q] = [p.values[q] for _, p in rows]
        cols[f"error_{q}"] = [p.errors[q] for _, p in rows]
    return {k: np.array(v, dtype=float) for k, v in cols.items()}


def _legend(result: SpeedVsError) -> str:
    scenes = ", ".join(f"{i} = {s.label}" for i, s in enumerate(result.scenes))
    return (f"scene index: {scenes}\nlayout_code: -2 edges (two springs at +/-b), -1 "
            f"equivalent (+/-b/sqrt3), 0 Winkler bed of `springs` springs, 1 continuum mesh "
            f"of `springs` elements across the footing\nintegrator: "
            + ", ".join(f"{i} = {n}" for i, n in enumerate(INTEGRATORS))
            + "\nerrors: (value - reference)/max(|reference|, floor); NaN: refused run")


def _write_points(result: SpeedVsError, path: Path) -> Path:
    rows = [(i, p) for i, s in enumerate(result.scenes) for p in s.points]
    return write_csv(path, _columns(rows), header=f"{STUDY}: every run\n{_legend(result)}")


def _write_pareto(result: SpeedVsError, path: Path) -> Path:
    cols: dict[str, list] = {"scene": [], "quantity": [], "rank": []}
    rows = []
    for i, s in enumerate(result.scenes):
        for qi, q in enumerate(QUANTITIES):
            for r, p in enumerate(s.front(q)):
                cols["scene"].append(i)
                cols["quantity"].append(qi)
                cols["rank"].append(r)
                rows.append((i, p))
    data = {k: np.array(v, dtype=float) for k, v in cols.items()}
    if rows:
        data.update(_columns(rows))
    legend = _legend(result) + "\nquantity: " + ", ".join(f"{i} = {q}" for i, q in
                                                           enumerate(QUANTITIES))
    return write_csv(path, data, header=f"{STUDY}: Pareto fronts (runtime vs |error|)\n{legend}")
