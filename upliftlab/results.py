"""Result files: self-describing NetCDF, CSV and text, all written atomically, with provenance.

NetCDF is written with :func:`scipy.io.netcdf_file` (classic 64-bit offset format), so the
reduced model needs no extra dependency; ``xarray.open_dataset`` reads the files. Every writer
goes through :func:`atomic_path`: the file appears complete or not at all.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import functools
import hashlib
import json
import os
import platform
import tempfile
from collections.abc import Iterator, Mapping
from pathlib import Path

import numpy as np
from scipy.io import netcdf_file

__all__ = ["atomic_path", "write_netcdf", "read_netcdf", "write_csv", "write_text",
           "provenance", "Variable"]

Variable = tuple  # (dims: tuple[str, ...], values: array-like, attrs: dict)


_UMASK = os.umask(0o022)  # read the process's umask once (setting it back at once)
os.umask(_UMASK)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; move it into place only if the block succeeds.

    The file gets the permissions of an ordinary new file (0o666 less the umask), not the
    owner-only mode of the temporary file it started as.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_UMASK)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def _netcdf_array(values) -> np.ndarray:
    array = np.asarray(values)
    if array.dtype == bool:
        return array.astype(np.int8)
    if np.issubdtype(array.dtype, np.integer):
        return array.astype(np.int32)
    return array.astype(np.float64)


def _attr(value):
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, (int, float, str, np.integer, np.floating)):
        return value
    return json.dumps(value, default=str)


def write_netcdf(path: str | os.PathLike, variables: Mapping[str, Variable],
                 attrs: Mapping[str, object] | None = None) -> Path:
    """Write ``variables`` {name: (dims, values, attrs)} and global ``attrs`` to NetCDF.

    Non-scalar attributes are stored as JSON text. Booleans become int8.
    """
    sizes: dict[str, int] = {}
    for name, (dims, values, _) in variables.items():
        shape = np.shape(values)
        if len(shape) != len(dims):
            raise ValueError(f"variable {name!r}: {len(dims)} dims for shape {shape}")
        for dim, n in zip(dims, shape):
            if sizes.setdefault(dim, n) != n:
                raise ValueError(f"dimension {dim!r} is {sizes[dim]} and {n}")
    with atomic_path(path) as tmp:
        with netcdf_file(tmp, "w", version=2) as nc:
            for key, value in (attrs or {}).items():
                setattr(nc, key, _attr(value))
            for dim, n in sizes.items():
                nc.createDimension(dim, n)
            for name, (dims, values, var_attrs) in variables.items():
                array = _netcdf_array(values)
                var = nc.createVariable(name, array.dtype, tuple(dims))
                var[...] = array
                for key, value in (var_attrs or {}).items():
                    setattr(var, key, _attr(value))
    return Path(path)


def read_netcdf(path: str | os.PathLike) -> tuple[dict[str, np.ndarray], dict[str, object]]:
    """Read a NetCDF file written by :func:`write_netcdf`: (variables, global attributes)."""
    with netcdf_file(path, "r", mmap=False) as nc:
        variables = {name: np.array(var[...]) for name, var in nc.variables.items()}
        attrs = {k: (v.decode() if isinstance(v, bytes) else v)
                 for k, v in nc._attributes.items()}
    return variables, attrs


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


def provenance(**extra) -> dict[str, object]:
    """Package version, a digest of its sources, time, platform and the versions of the
    numerical libraries, plus ``extra`` (scene, model, options)."""
    from . import __version__

    record = {
        "upliftlab_version": __version__,
        "source_sha256": source_digest(),
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": _version("scipy"),
        "numba": _version("numba"),
        "platform": platform.platform(terse=True),
    }
    record.update(extra)
    return record


def _version(package: str) -> str:
    from importlib import metadata

    try:
        return metadata.version(package)
    except metadata.PackageNotFoundError:
        return "not installed"


@functools.cache
def source_digest() -> str:
    """SHA-256 of every Python source of the package and its subpackages (wherever the install
    put them), by module name and content: which code produced a result, beyond the version."""
    import importlib.util

    files = {}
    subpackages = {name.rsplit(".", 1)[1] for name in SOURCE_PACKAGES if "." in name}
    for package in SOURCE_PACKAGES:
        spec = importlib.util.find_spec(package)
        short = package.rsplit(".", 1)[-1]
        for folder in (spec.submodule_search_locations or []) if spec else []:
            if Path(folder).name != short:  # the checkout's root, which a source run adds
                continue
            for path in Path(folder).rglob("*.py"):
                relative = path.relative_to(folder)
                if "__pycache__" in relative.parts or (
                        package == "upliftlab" and relative.parts[0] in subpackages):
                    continue  # the installed layout nests the subpackages: read them once
                files[f"{package}/{relative.as_posix()}"] = path
    digest = hashlib.sha256()
    for name, path in sorted(files.items()):
        digest.update(name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


#: The packages whose sources :func:`source_digest` covers.
SOURCE_PACKAGES = ("upliftlab", "upliftlab.reduced", "upliftlab.continuum", "upliftlab.meshes",
                   "upliftlab.comparisons")
