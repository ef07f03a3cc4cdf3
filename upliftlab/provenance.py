"""Which code ran: one digest of upliftlab's sources, and the provenance every result carries.

:func:`code_digest` is the one answer to "which code ran". It is the SHA-256 of the package's
Python sources (and its packaged scenes), each by its name inside the package and its bytes,
wherever the install put them. Three things use it:

* every result's provenance (:func:`provenance`, in each file written);
* the numba cache folder, over the compiled kernels' sources only (``upliftlab/__init__.py``):
  numba keys a cached function on its own file, so an edit to a law inlined elsewhere must
  start a new cache;
* each record of a store (:mod:`upliftlab.comparisons.framework.store`), as provenance, never
  as its key. A store whose records came from another digest is stale, not lost: it is
  checked by re-running a sample.

It is computed once per process (the code of a running process does not change). It imports
nothing heavy, so that ``import upliftlab`` stays light.
"""

from __future__ import annotations

import datetime as _dt
import functools
import hashlib
import importlib.util
import platform
from collections.abc import Iterable
from importlib import metadata
from pathlib import Path

__all__ = ["PACKAGES", "LIBRARIES", "MODEL_SOURCES", "code_digest", "package_files",
           "library_versions", "provenance", "cache_folder"]

#: upliftlab's packages, whose sources the digest covers (the subpackages may be installed
#: nested in ``upliftlab/`` or, in a checkout, stand beside it).
PACKAGES = ("upliftlab", "upliftlab.reduced", "upliftlab.continuum", "upliftlab.meshes",
            "upliftlab.comparisons", "upliftlab.scene_files")

#: The libraries that compute the numbers, named in every provenance.
LIBRARIES = ("numpy", "scipy", "numba", "scikit-fem", "xarray", "h5py")

#: The sources that decide the models' numbers (the core, both models, the meshes and the
#: packaged scenes), as :func:`code_digest` prefixes; a study adds its own.
MODEL_SOURCES = ("upliftlab/", "upliftlab.reduced/", "upliftlab.continuum/", "upliftlab.meshes/",
                 "upliftlab.scene_files/")

_SOURCES = (".py", ".toml")


def _folders(package: str) -> list[Path]:
    spec = importlib.util.find_spec(package)
    short = package.rsplit(".", 1)[-1]
    if spec is None or spec.submodule_search_locations is None:
        return []
    if package == "upliftlab.scene_files":
        return [Path(p) for p in spec.submodule_search_locations]
    # a checkout run as it is adds its root to upliftlab's path: only the package's own folder
    return [Path(p) for p in spec.submodule_search_locations if Path(p).name == short]


@functools.cache
def package_files() -> dict[str, Path]:
    """Every source of the package by its name inside it (``upliftlab.continuum/model.py``)."""
    nested = {p.rsplit(".", 1)[-1] for p in PACKAGES if "." in p}
    files = {}
    for package in PACKAGES:
        for folder in _folders(package):
            for path in folder.rglob("*"):
                relative = path.relative_to(folder)
                if path.suffix not in _SOURCES or "__pycache__" in relative.parts:
                    continue
                if package == "upliftlab" and relative.parts[0] in nested:
                    continue  # an installed subpackage nested here: read under its own name
                files[f"{package}/{relative.as_posix()}"] = path
    return files


def code_digest(names: Iterable[str] | None = None) -> str:
    """SHA-256 (hex) of upliftlab's sources: every one (``names`` None), or those whose names
    (as :func:`package_files` gives them) start with one of ``names``."""
    return _digest(None if names is None else tuple(sorted(names)))


@functools.cache
def _digest(prefixes: tuple[str, ...] | None) -> str:
    digest = hashlib.sha256()
    for name, path in sorted(package_files().items()):
        if prefixes is None or name.startswith(prefixes):
            digest.update(name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def library_versions() -> dict[str, str]:
    """The installed version of each library in :data:`LIBRARIES` ("absent" if missing), by
    its name with ``-`` written ``_``."""
    out = {}
    for name in LIBRARIES:
        key = name.replace("-", "_")  # a name that can be an attribute of a file
        try:
            out[key] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[key] = "absent"
    return out


def provenance(**extra) -> dict[str, object]:
    """Which code made a result, when and where: the package version, :func:`code_digest`, the
    time (UTC), Python, the libraries' versions and the platform, plus ``extra`` (the scene,
    the model, the options)."""
    from .version import __version__

    record = {
        "upliftlab_version": __version__,
        "source_sha256": code_digest(),
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "python": platform.python_version(),
        **library_versions(),
        "platform": platform.platform(terse=True),
    }
    record.update(extra)
    return record


def cache_folder(name: str) -> Path:
    """``$XDG_CACHE_HOME/upliftlab/<name>`` (``~/.cache/...``), created: where upliftlab keeps
    what it can make again (compiled kernels, records written from a package)."""
    import os

    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    folder = Path(base) / "upliftlab" / name
    folder.mkdir(parents=True, exist_ok=True)
    return folder
