"""The study's CSV tables, read from its dataset: every run (``points.csv``) and the Pareto
fronts of runtime against |error| per scene and quantity (``pareto.csv``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....results import write_csv
from .analysis import Run, front, runs
from .grid import INTEGRATORS, QUANTITIES, STUDY

#: A model's code in the tables (a Winkler bed is 0).
_MODEL_CODE = {"edges": -2, "equivalent": -1, "continuum": 1}


def _columns(rows: list[tuple[int, Run]]) -> dict:
    """The columns of ``rows`` (scene index, run): codes, step (s), runtime (s), repeats, and
    per quantity the value and its signed relative error."""
    cols = {"scene": [i for i, _ in rows], "springs": [p.springs for _, p in rows],
            "layout_code": [_MODEL_CODE.get(p.model, 0) for _, p in rows],
            "integrator": [INTEGRATORS.index(p.integrator) for _, p in rows],
            "dt_s": [p.dt for _, p in rows], "runtime_s": [p.runtime for _, p in rows],
            "repeats": [p.repeats for _, p in rows]}
    for q in QUANTITIES:
        cols[q] = [p.values[q] for _, p in rows]
        cols[f"error_{q}"] = [p.errors[q] for _, p in rows]
    return {k: np.array(v, dtype=float) for k, v in cols.items()}


def _legend(labels: list[str]) -> str:
    scenes = ", ".join(f"{i} = {label}" for i, label in enumerate(labels))
    return (f"scene index: {scenes}\nlayout_code: -2 edges (two springs at +/-b), -1 "
            f"equivalent (+/-b/sqrt3), 0 Winkler bed of `springs` springs, 1 continuum mesh "
            f"of `springs` elements across the footing\nintegrator: "
            + ", ".join(f"{i} = {n}" for i, n in enumerate(INTEGRATORS))
            + "\nerrors: (value - reference)/max(|reference|, floor); NaN: refused run")


def write_tables(ds, directory: Path) -> list[Path]:
    """``points.csv`` (every run, scene by scene in the order they were made) and
    ``pareto.csv`` (each scene's and quantity's front, ranked by ascending runtime) of the
    study's dataset ``ds`` into ``directory``; the files."""
    labels = ds.scene.values.tolist()
    scenes = [runs(ds, label) for label in labels]
    every = [(i, p) for i, points in enumerate(scenes) for p in points]
    files = [write_csv(directory / "points.csv", _columns(every),
                       header=f"{STUDY}: every run\n{_legend(labels)}")]
    cols: dict[str, list] = {"scene": [], "quantity": [], "rank": []}
    rows = []
    for i, points in enumerate(scenes):
        for qi, q in enumerate(QUANTITIES):
            for r, p in enumerate(front(points, q)):
                cols["scene"].append(i)
                cols["quantity"].append(qi)
                cols["rank"].append(r)
                rows.append((i, p))
    data = {k: np.array(v, dtype=float) for k, v in cols.items()}
    if rows:
        data.update(_columns(rows))
    legend = _legend(labels) + "\nquantity: " + ", ".join(f"{i} = {q}" for i, q in
                                                          enumerate(QUANTITIES))
    files.append(write_csv(directory / "pareto.csv", data,
                           header=f"{STUDY}: Pareto fronts (runtime vs |error|)\n{legend}"))
    return files
