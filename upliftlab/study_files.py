"""A study's output folder, opened again from disk as labelled data: :func:`open_study`.

A study (:mod:`upliftlab.comparisons.studies`) writes its result as CF-compliant NetCDF files
(:func:`upliftlab.results.write_dataset`) beside ``summary.json``, the numbers its summary
states. :func:`open_study` reads them all back into one :class:`xarray.DataTree`, so that a
notebook selects by label what the study computed, without running it again::

    tree = open_study("results/two_spring_equivalence-fast")
    tree["map_aspect"].error.sel(case="C", layout="edges", measure="u", h_over_b=4.0)
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from .checks import InputError
from .results import read_dataset

__all__ = ["open_study", "study_files"]

#: The folder where a study keeps its points (:class:`upliftlab.comparisons.framework.store.Store`
#: records, JSON): not part of its result.
STORE_FOLDER = "store"


def study_files(folder: str | os.PathLike) -> dict[str, Path]:
    """The NetCDF files of a study's output ``folder`` by their node name: the path relative to
    the folder without ``.nc`` (``map_aspect``, ``figures/spectrum``), sorted. The points'
    store (:data:`STORE_FOLDER`) and hidden files (an unfinished write) are left out."""
    root = Path(folder)
    found = {}
    for path in sorted(root.rglob("*.nc")):
        relative = path.relative_to(root)
        if relative.parts[0] == STORE_FOLDER or any(p.startswith(".") for p in relative.parts):
            continue
        found[relative.with_suffix("").as_posix()] = path
    return found


def _summary_attributes(folder: Path) -> dict:
    """The numbers of ``summary.json``, one attribute per key as JSON gives them (a nested
    mapping stays a dict), and its provenance under ``provenance``; {} without the file."""
    path = folder / "summary.json"
    if not path.is_file():
        return {}
    summary = json.loads(path.read_text())
    numbers = summary.get("numbers", {k: v for k, v in summary.items() if k != "provenance"})
    provenance = summary.get("provenance", numbers.get("provenance"))
    attrs = {k: v for k, v in numbers.items() if k != "provenance"}
    if provenance is not None:
        attrs["provenance"] = provenance
    return attrs


def open_study(path: str | os.PathLike):
    """The study written into folder ``path`` as an :class:`xarray.DataTree`, loaded into
    memory (the files are closed): one node per NetCDF file, named by its relative path without
    ``.nc`` (:func:`study_files`), holding the dataset as written (coordinates, units,
    attributes); the root's attributes are the summary's numbers, one per key, and their
    ``provenance``. A folder with ``summary.json`` and no NetCDF file opens as a root with its
    numbers alone. Raises
    :class:`~upliftlab.checks.InputError` when ``path`` is not a folder, or holds neither a
    NetCDF file nor ``summary.json``."""
    import xarray as xr

    folder = Path(path)
    if not folder.is_dir():
        raise InputError(f"open_study: {str(folder)!r} is not a folder; expected a study's "
                         "output folder (results/<study>[-fast])")
    files = study_files(folder)
    if not files and not (folder / "summary.json").is_file():
        raise InputError(f"open_study: {str(folder)!r} holds neither a NetCDF file nor "
                         "summary.json; is it a study's output folder, written completely?")
    tree = xr.DataTree.from_dict({name: read_dataset(p) for name, p in files.items()},
                                 name=folder.name)
    tree.attrs = _summary_attributes(folder)
    return tree
