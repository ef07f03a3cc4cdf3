"""The study's CSV tables, written from its ``comparison`` dataset: the monotonic and the
cyclic rotation pushover of the continuum and every bed (``monotonic.csv``, ``cyclic.csv``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....results import write_csv
from ....units import unit_system
from .dataset import PATH_MODELS
from .options import STUDY

__all__ = ["write_tables"]


def write_tables(ds, out: Path) -> list[Path]:
    """``monotonic.csv`` and ``cyclic.csv`` of the comparison dataset ``ds`` into ``out``."""
    return [_write_path(ds, "monotonic", out / "monotonic.csv"),
            _write_path(ds, "cyclic", out / "cyclic.csv")]


def _write_path(ds, which: str, path: Path) -> Path:
    theta = ds[f"{which}_theta"].values
    theta_on = ds.theta_on.item()

    def column(key: str, model: str) -> np.ndarray:
        return ds[f"{key}_{which}"].sel(model=model).values

    columns = {"theta": theta, "theta_over_theta_on": theta / theta_on,
               "M_continuum": column("M", "continuum"),
               "settlement_continuum": column("settlement", "continuum"),
               "contact_continuum": column("contact", "continuum")}
    if which == "monotonic":
        columns.update(M_continuum_elastic=column("M", "continuum_elastic"),
                       contact_continuum_elastic=column("contact", "continuum_elastic"))
    for name in [str(m) for m in ds.model.values if m not in PATH_MODELS]:
        columns.update({f"M_{name}": column("M", name),
                        f"settlement_{name}": column("settlement", name),
                        f"contact_{name}": column("contact", name)})
    units = unit_system(str(ds.attrs["units"]))
    return write_csv(path, columns, header=(
        f"{STUDY}: {which} rotation pushover at N = {ds.N.item():g} "
        f"{units.force}/{units.length}, B = {ds.B.item():g} {units.length}; theta in rad, "
        f"theta_on = {theta_on:.6g} rad; M in {units.force}*{units.length}/{units.length}, "
        f"settlement (down) and contact length in {units.length}; continuum = the scene's "
        "soil, continuum_elastic = elastic soil"))
