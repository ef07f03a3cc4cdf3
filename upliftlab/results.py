"""Result files: self-describing NetCDF, CSV and text, all written atomically, with provenance.

NetCDF files are NetCDF-4 (HDF5 underneath), written through h5netcdf with every array
compressed (zlib, level 4, byte shuffle): a labelled :class:`xarray.Dataset`, or the same data
as a :class:`~upliftlab.labelled_data.LabelledData` (which a result's ``save`` writes without
importing xarray), goes to disk as it is (:func:`write_dataset`; the file is the one xarray's
own ``to_netcdf`` writes: :mod:`upliftlab.netcdf_file`), and :func:`read_dataset` gives back
the same coordinates, units and attributes; ParaView, ncdump, netCDF4 and
``xarray.open_dataset`` read the files too. The files follow the CF-1.10 conventions
(:mod:`upliftlab.cf` says what that changes on disk: the time axis, text labels, fill values,
flag types) and open as tables split by dimension with :func:`upliftlab.open_result`.
Attributes follow the CF conventions: numbers, text and flat lists only; a mapping of scalars
becomes one attribute per key (``provenance_numpy``), and only a nested record that no
coordinate or variable could hold (the scene as loaded) stays JSON text
(:func:`cf_attributes`). Every writer goes through :func:`atomic_path`: the file appears
complete or not at all.

**A full disk.** HDF5 does not survive a write that fails for want of space (it ends the
process with a segmentation fault, leaving its part file and the folder's lock), so no HDF5
file is written to disk by HDF5: a NetCDF file is made in memory (:func:`netcdf_bytes`) and
written with Python's own I/O (:func:`write_bytes`), where a full disk (ENOSPC), a quota
(EDQUOT) or a file-size limit (EFBIG) is an ordinary :class:`OSError`
(:func:`disk_full`) that removes the part file on its way out.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
from collections.abc import Iterator, Mapping
from pathlib import Path

import numpy as np

from . import cf
from .labelled_data import LabelledData
from .netcdf_file import netcdf_bytes
from .paths import (DISK_FULL, check_target, disk_full, forget_temporary,
                    temporary_sibling)

__all__ = ["atomic_path", "staging_folder", "move_into_place", "write_dataset", "write_netcdf",
           "read_netcdf", "read_dataset", "cf_attributes", "write_csv", "write_text",
           "write_bytes", "netcdf_bytes", "disk_full", "DISK_FULL", "Variable"]

Variable = tuple  # (dims: tuple[str, ...], values: array-like, attrs: dict)


_UMASK = os.umask(0o022)  # read the process's umask once (setting it back at once)
os.umask(_UMASK)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; move it into place only if the block succeeds.

    ``path`` must be a regular file or absent, and inside the output folder while a command
    holds one (:func:`upliftlab.paths.check_target`); the temporary file is named as
    upliftlab's own, so that a later run removes it only if its writer was killed
    (:func:`upliftlab.paths.temporary_sibling`). The file gets the permissions of an ordinary
    new file (0o666 less the umask), not the owner-only mode of the temporary file it started
    as.
    """
    path = Path(path)
    tmp = temporary_sibling(path)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_UMASK)
        check_target(path)  # again: something may have been put there while writing
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
        forget_temporary(tmp)


@contextlib.contextmanager
def staging_folder(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a private folder beside ``path`` (checked as :func:`atomic_path` checks it) for
    writers that make several files at once (XDMF and its HDF5); move each into place with
    :func:`move_into_place`. The folder and whatever is left in it are removed at the end."""
    folder = temporary_sibling(path, directory=True)
    try:
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        forget_temporary(folder)


def move_into_place(written: str | os.PathLike, path: str | os.PathLike) -> Path:
    """Move the finished file ``written`` to ``path``, a regular file or absent, inside the
    output folder (:func:`upliftlab.paths.check_target`)."""
    check_target(path)
    os.chmod(written, 0o666 & ~_UMASK)
    os.replace(written, path)
    return Path(path)


def write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically with Python's own I/O, flushed to the disk (so
    that a full disk is seen here, as an :class:`OSError` naming ``path``, and not later)."""
    with atomic_path(path) as tmp:
        try:
            with open(tmp, "wb") as fh:
                fh.write(data)
                fh.flush()
                os.fsync(fh.fileno())
        except OSError as exc:
            if exc.filename is None and disk_full(exc):
                raise OSError(exc.errno, exc.strerror, str(path)) from None
            raise
    return Path(path)


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    return write_bytes(path, text.encode())


def _netcdf_array(values) -> np.ndarray:
    array = np.asarray(values)
    if array.dtype == bool:
        return array.astype(np.int8)
    if array.dtype.kind in "US":
        return array.astype(str)
    if np.issubdtype(array.dtype, np.integer):
        return array.astype(np.int32)
    return array.astype(np.float64)


def _scalar(value) -> bool:
    return isinstance(value, (bool, np.bool_, int, float, str, np.integer, np.floating))


def _attribute(value):
    """One CF attribute value: a number or text (booleans as 0/1), a flat list of numbers (an
    array) or of text; anything else as JSON text."""
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if _scalar(value):
        return value
    if isinstance(value, (list, tuple, np.ndarray)) and len(value) and all(
            _scalar(v) and not isinstance(v, (bool, np.bool_)) for v in value):
        if all(isinstance(v, str) for v in value):
            return [str(v) for v in value]
        if all(isinstance(v, (int, np.integer)) for v in value):
            return np.asarray(value, dtype=np.int64)
        if not any(isinstance(v, str) for v in value):
            return np.asarray(value, dtype=float)
    return json.dumps(value, default=str)


def cf_attributes(attrs: Mapping[str, object] | None, prefix: str = "") -> dict[str, object]:
    """``attrs`` as CF attributes: a value of ``None`` is left out (absent means none), an empty
    list is the empty text, a mapping becomes one attribute per key (``provenance_numpy``), and
    only a mapping inside a mapping (the scene as loaded) is JSON text."""
    out: dict[str, object] = {}
    for key, value in (attrs or {}).items():
        name = f"{prefix}{key}".replace("/", "_per_")
        if value is None:
            continue
        if isinstance(value, Mapping) and not prefix:
            out.update(cf_attributes(value, prefix=f"{name}_"))
        elif isinstance(value, (list, tuple)) and not value:
            out[name] = ""
        else:
            out[name] = _attribute(value)
    return out


def write_dataset(path: str | os.PathLike, dataset) -> Path:
    """Write ``dataset`` (an :class:`xarray.Dataset` or a
    :class:`~upliftlab.labelled_data.LabelledData`) to ``path`` as compressed NetCDF-4 (module
    docstring); atomic. Booleans are stored as int8 (NetCDF has no boolean type); the time
    axis, the coordinates' fill values and the flags' types as CF-1.10 wants them
    (:mod:`upliftlab.cf`). A Dataset's ``encoding`` is not used. Values must be numbers,
    booleans or text (:class:`~upliftlab.labelled_data.LabelledData`): bytes, dates, complex
    numbers and missing text (None) raise ValueError before anything is written."""
    data = dataset if isinstance(dataset, LabelledData) else LabelledData.from_xarray(dataset)
    variables = {name: (dims, values.astype(np.int8) if values.dtype == bool else values,
                        cf_attributes(attrs))
                 for name, (dims, values, attrs) in data.variables.items()}
    data, no_fill = cf.encode(data.replace(variables=variables,
                                           attrs=cf_attributes(data.attrs)))
    return write_bytes(path, netcdf_bytes(data, no_fill))


def write_netcdf(path: str | os.PathLike, variables: Mapping[str, Variable],
                 attrs: Mapping[str, object] | None = None) -> Path:
    """Write ``variables`` {name: (dims, values, attrs)} and global ``attrs`` as a dataset
    (:func:`write_dataset`): a variable named as its one dimension is that dimension's
    coordinate; integers are stored as int32, other numbers as float64. Raises ValueError,
    before anything is written, if two variables disagree on the length of a dimension."""
    data = {name: (tuple(dims), _netcdf_array(values), dict(var_attrs or {}))
            for name, (dims, values, var_attrs) in variables.items()}
    return write_dataset(path, LabelledData(data, attrs=dict(attrs or {})))


def read_dataset(path: str | os.PathLike):
    """A result file as an :class:`xarray.Dataset`, loaded into memory (the file is closed),
    as it was before it was written: its time axis in seconds (:func:`upliftlab.cf.decode`)."""
    import xarray as xr

    return cf.decode(xr.load_dataset(path, engine="h5netcdf", decode_times=False,
                                     decode_timedelta=False))


def read_netcdf(path: str | os.PathLike) -> tuple[dict[str, np.ndarray], dict[str, object]]:
    """A result file as plain arrays: ({name: values} of every variable and coordinate, global
    attributes)."""
    dataset = read_dataset(path)
    variables = {name: np.asarray(var.values) for name, var in dataset.variables.items()}
    return variables, dict(dataset.attrs)


def write_csv(path: str | os.PathLike, columns: Mapping[str, np.ndarray],
              header: str = "") -> Path:
    """Write equal-length 1-D ``columns`` as CSV, with an optional ``#`` header line."""
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    with atomic_path(path) as tmp:
        with open(tmp, "w") as fh:
            if header:
                for line in header.splitlines():
                    fh.write(f"# {line}\n")
            fh.write(",".join(names) + "\n")
            np.savetxt(fh, data, delimiter=",", fmt="%.10g")
    return Path(path)
