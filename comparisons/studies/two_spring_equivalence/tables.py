"""The study's table: the rocking pushovers of every foundation as CSV."""

from __future__ import annotations

from pathlib import Path

from ....results import write_csv
from .grid import STUDY
from .statics import Statics


def write_statics(statics: Statics, path: Path) -> Path:
    """The elastic and elasto-plastic backbones M/(N B) of every foundation against θ/θ_up,
    one column each, into the CSV ``path``."""
    columns = {"theta_over_theta_up": statics.theta}
    for s in statics.layouts:
        slug = s.label.replace(" ", "_").replace("(", "").replace(")", "").replace("-", "_")
        columns[f"M_elastic_{slug}"] = s.elastic
        columns[f"M_plastic_{slug}"] = s.plastic
    return write_csv(path, columns, header=f"{STUDY}: rocking pushovers, M/(N B) against "
                     f"theta/theta_up, N = {statics.springs} springs, "
                     f"FS_v = {statics.yield_multiple:g}")
