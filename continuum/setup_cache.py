"""A content-addressed cache on disk of what a continuum run computes before its first step and
computes the same way every time: the gravity state, the explicit route's stable step and the
mesh's grid lines.

A fresh process spent seconds of CPU on them (a dozen sparse factorisations for the gravity
state, a Lanczos run for the stable step; for the grid lines, whose growth ratios are roots
from ``scipy.optimize.brentq``, the import of all of ``scipy.optimize``, about 0.15 s) for
results that depend only on the model and a few options (the grid lines: on the footing's
width and the mesh's options alone). :func:`cached` keeps them in
``$XDG_CACHE_HOME/upliftlab/setup/<kind>/<key>.npz`` (``~/.cache/...``), where

- ``key`` is the SHA-256 of exactly the inputs, written as canonical JSON: the model's
  (:func:`model_inputs`: the soil's fields, the footing width, g, the element, its quadrature
  order and the mesh itself, by the digest of its points, cells and named boundaries), the
  options the piece reads, the code digest of the modules that build it
  (:func:`upliftlab.provenance.code_digest`) and the libraries' versions. Anything else (the
  motion, the dynamics route, the output) is not in it: the implicit and the explicit run of one
  scene share their gravity state.
- An entry holds the arrays of the piece, its key (``__key__``) and the SHA-256 of the arrays'
  names, types, shapes and bytes (``__digest__``). It is written to a temporary file beside it
  and moved into place (``os.replace``), so a reader never sees half an entry.
- Reading checks the key and the digest: an entry that fails (truncated, altered, another key)
  is built again and written again, never trusted. A folder that cannot be written leaves the
  piece built in every process, as before.

Loaded arrays are the built ones bit for bit, so a run with the cache gives the numbers of a
run without it (a test runs both).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import tempfile
import zipfile
from pathlib import Path
from typing import Callable

import numpy as np

__all__ = ["MODEL_SOURCES", "GRID_SOURCES", "model_inputs", "array_digest", "entry_key", "read",
           "write", "cached", "grid_lines"]

_UMASK = os.umask(0o022)  # read the process's umask once (setting it back at once)
os.umask(_UMASK)

#: The sources that turn a scene's soil, footing and mesh into a model
#: (:func:`~upliftlab.continuum.model.make_model`), as ``code_digest`` names them.
MODEL_SOURCES = ("upliftlab.continuum/model.py", "upliftlab.continuum/assembly.py",
                 "upliftlab.continuum/condensation.py", "upliftlab.continuum/contact/",
                 "upliftlab.continuum/materials/", "upliftlab.meshes/")
#: The source of a mesh's grid lines (:func:`upliftlab.meshes.soil.grid_lines`).
GRID_SOURCES = ("upliftlab.meshes/soil.py",)


def array_digest(arrays: dict[str, np.ndarray]) -> str:
    """SHA-256 (hex) of named arrays: each name, type, shape and bytes, in name order."""
    digest = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        digest.update(f"{name}\0{a.dtype.str}\0{a.shape}\0".encode())
        digest.update(a.tobytes())
    return digest.hexdigest()


def model_inputs(model) -> dict:
    """What a :class:`~upliftlab.continuum.model.ContinuumModel` is made of, as JSON-ready
    values: the soil's fields, the footing width, g, the element and its quadrature order,
    and the mesh's digest (points, cells, named boundaries)."""
    mesh = model.mesh
    arrays = {"p": mesh.p, "t": mesh.t}
    for name, facets in sorted((mesh.boundaries or {}).items()):
        arrays[f"boundary {name}"] = np.asarray(facets)
    return {"soil": dataclasses.asdict(model.soil), "width": model.width,
            "gravity": model.gravity, "element": model.disc.element,
            "intorder": model.disc.intorder, "mesh": type(mesh).__name__,
            "mesh_digest": array_digest(arrays)}


def entry_key(kind: str, inputs: dict, sources: tuple[str, ...]) -> str:
    """SHA-256 (hex) of ``kind``, the ``inputs`` (canonical JSON), the code digest of
    ``sources`` and the libraries' versions (module docstring)."""
    from ..provenance import code_digest, library_versions

    text = json.dumps({"kind": kind, "inputs": inputs, "code": code_digest(sources),
                       "libraries": library_versions()}, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()


def _path(kind: str, key: str) -> Path:
    from ..provenance import cache_folder

    return cache_folder("setup") / kind / f"{key}.npz"


def read(kind: str, key: str) -> dict[str, np.ndarray] | None:
    """The arrays of the entry ``key`` of ``kind``, or None if there is none or it fails its
    checks (module docstring)."""
    try:
        with np.load(_path(kind, key), allow_pickle=False) as entry:
            arrays = {name: entry[name] for name in entry.files}
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None
    stored_key, stored_digest = arrays.pop("__key__", None), arrays.pop("__digest__", None)
    if stored_key is None or stored_digest is None or str(stored_key) != key:
        return None
    return arrays if str(stored_digest) == array_digest(arrays) else None


def write(kind: str, key: str, arrays: dict[str, np.ndarray]) -> bool:
    """Write the entry ``key`` of ``kind`` atomically; False (and nothing written) if the
    cache folder cannot be written."""
    tmp = None
    try:
        folder = _path(kind, key).parent
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".part-", suffix=".npz",
                                         delete=False) as handle:
            tmp = handle.name
            np.savez(handle, __key__=np.array(key), __digest__=np.array(array_digest(arrays)),
                     **arrays)
        os.chmod(tmp, 0o666 & ~_UMASK)  # an ordinary file, not the temporary's owner-only mode
        os.replace(tmp, _path(kind, key))
        return True
    except OSError:
        if tmp is not None and os.path.exists(tmp):
            os.unlink(tmp)
        return False


def cached(kind: str, inputs: dict, sources: tuple[str, ...],
           build: Callable[[], dict[str, np.ndarray]]) -> tuple[dict[str, np.ndarray], bool]:
    """(arrays, True) read from the entry of ``kind`` for these ``inputs`` and ``sources``, or
    (``build()``, False), written for the next process, when there is none that passes its
    checks."""
    key = entry_key(kind, inputs, sources)
    arrays = read(kind, key)
    if arrays is not None:
        return arrays, True
    arrays = build()
    write(kind, key, arrays)
    return arrays, False


def grid_lines(footing_width: float, options, layer_depth: float | None = None
               ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`upliftlab.meshes.soil.grid_lines` of a footing ``footing_width`` wide (length),
    the scene's ``[continuum]`` ``options`` and ``layer_depth`` (length, or None), read from
    the entry of these inputs when an earlier process made them (the same arrays, bit for
    bit), else computed and written."""
    from ..meshes.soil import grid_lines as lines

    inputs = {"footing_width": footing_width, "layer_depth": layer_depth,
              **{name: getattr(options, name) for name in ("domain_width", "domain_depth",
                                                           "element", "elements_across",
                                                           "grading")}}
    arrays, _ = cached("grid_lines", inputs, GRID_SOURCES,
                       lambda: dict(zip("xy", lines(footing_width, options, layer_depth))))
    return arrays["x"], arrays["y"]
