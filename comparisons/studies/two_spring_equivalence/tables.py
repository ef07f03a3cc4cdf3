"""The study's table: the rocking pushovers of every foundation as CSV."""

from __future__ import annotations

from pathlib import Path

from ....results import write_csv
from .grid import STUDY


def write_statics(statics, path: Path) -> Path:
    """The elastic and elasto-plastic backbones M/(N B) of every foundation against θ/θ_up,
    one column each, from the study's statics dataset (:func:`.statics.statics_dataset`)
    into the CSV ``path``."""
    columns = {"theta_over_theta_up": statics.theta_over_theta_up.values}
    for label in (str(v) for v in statics.foundation.values):
        slug = label.replace(" ", "_").replace("(", "").replace(")", "").replace("-", "_")
        columns[f"M_elastic_{slug}"] = statics.elastic.sel(foundation=label).values
        columns[f"M_plastic_{slug}"] = statics.plastic.sel(foundation=label).values
    return write_csv(path, columns, header=f"{STUDY}: rocking pushovers, M/(N B) against "
                     f"theta/theta_up, N = {int(statics.attrs['springs'])} springs, "
                     f"FS_v = {float(statics.attrs['yield_multiple']):g}")
