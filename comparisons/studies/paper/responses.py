"""The responses the conclusions are decided from: the reduced runs of the paper's scenes and
the apparent period of a response."""

from __future__ import annotations

import math

import numpy as np

from ....motions import ELCENTRO, MOTIONS_ENV, Motion
from ....reduced.run import run as run_reduced
from ....scenes import load_scene
from .records import BUILDINGS


# ---------------------------------------------------------------------------------------------
# Measures
# ---------------------------------------------------------------------------------------------


def apparent_period(time_s: np.ndarray, signal: np.ndarray, *, window: float | None = None
                    ) -> float:
    """Mean period (s) from the upward zero crossings of ``signal`` (linearly interpolated)
    within the first ``window`` seconds (all of it if None); NaN with fewer than two."""
    t, x = np.asarray(time_s, float), np.asarray(signal, float)
    if window is not None:
        keep = t <= t[0] + window
        t, x = t[keep], x[keep]
    up = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    if up.size < 2:
        return math.nan
    crossing = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    return float(np.mean(np.diff(crossing)))


def peak_ratio(a: float, b: float) -> float:
    return a / b if b else math.inf


# ---------------------------------------------------------------------------------------------
# The conclusions
# ---------------------------------------------------------------------------------------------


def paper_responses(record: Motion | None, output_dt: float) -> dict:
    """The runs the conclusions read: free vibration and (with the record) El Centro of both
    buildings in Cases A, B, C and, on El Centro, the fixed base."""
    out = {}
    for building in BUILDINGS:
        for case in "ABC":
            out[f"{building}_free-{case}"] = run_reduced(
                load_scene(f"{building}_free", case=case), output_dt=output_dt)
        if record is None:
            continue
        for case in ("A", "B", "C", "fixed"):
            out[f"{building}_elcentro-{case}"] = run_reduced(
                load_scene(f"{building}_elcentro", case=case), motion=record,
                output_dt=output_dt)
    return out


def reduced_label(building: str) -> str:
    return f"reduced model (Winkler bed, 12 springs), {building.replace('_', '-')} building"


def record_note(record: Motion | None) -> str:
    if record is not None:
        return ""
    return (f"El Centro runs skipped: the record {ELCENTRO}.txt was not found; set "
            f"{MOTIONS_ENV} to its directory or pass --motion PATH.")
