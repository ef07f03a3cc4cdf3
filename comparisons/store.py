"""Content-addressed results: one small JSON file per evaluated point.

A point's key is the SHA-256 of its study name, the function that evaluates it, its parameters
as canonical JSON, the upliftlab version and, for a point function of the package, the code it
computes with (:func:`point_key`, :mod:`.fingerprint`). Equal keys mean equal inputs computed by
the same code, so a sweep or a report never re-runs a point that is already stored, and a store
resumed after the code changed never mixes the old code's records with the new. Parameters named ``_…`` are
locators (file paths) and stay out of the key; the content they locate is keyed by a digest.

Each record is written to a temporary file beside its final name, flushed to disk and moved into
place (:func:`upliftlab.results.atomic_path`): an interrupted writer leaves either the complete
record or none (at most a ``.*.part`` file, which readers ignore). Records are independent
files, so processes can write to one store at once.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import __version__
from ..checks import InputError
from ..paths import output_root
from ..results import atomic_path
from .fingerprint import code_fingerprint

__all__ = ["Store", "point_key", "canonical_json", "function_name", "function_code", "keyed_as"]

_SUFFIX = ".json"


def _plain(value, where: str):
    """``value`` as plain JSON types (numpy scalars and arrays become numbers and lists)."""
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise InputError(f"{where}: key {k!r} is not a string; point keys must be text")
            if not k.startswith("_"):
                out[k] = _plain(v, f"{where}.{k}")
        return out
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(value):
            raise InputError(f"{where} = {float(value)}: parameters must be finite numbers")
        return float(value)
    if value is None or isinstance(value, str):
        return value
    raise InputError(f"{where} = {value!r}: not a JSON value (numbers, text, lists, tables)")


def canonical_json(value, where: str = "point") -> str:
    """Canonical JSON of ``value``: sorted keys, no spaces, finite numbers only.

    Table entries whose names start with ``_`` are left out: they *locate* an input (a file
    path on this machine) whose content is identified by another entry (e.g. its SHA-256).
    """
    return json.dumps(_plain(value, where), sort_keys=True, separators=(",", ":"),
                      ensure_ascii=True, allow_nan=False)


def keyed_as(name: str):
    """Declare the name that identifies a point function in store keys (``module:qualname``
    where it was first written), so that moving the function to another module keeps every
    stored point's key."""

    def declare(function):
        function.key_name = name
        return function

    return declare


def function_name(function) -> str:
    """What identifies a function in a key: its declared :func:`keyed_as` name, else its
    ``module:qualname``."""
    declared = getattr(function, "key_name", None)
    if isinstance(declared, str) and declared:
        return declared
    module = getattr(function, "__module__", None)
    qualname = getattr(function, "__qualname__", None)
    if not module or not qualname:
        raise InputError(f"function {function!r}: needs a module and a name (a top-level def)")
    return f"{module}:{qualname}"


def function_code(function) -> str | None:
    """The fingerprint of the code ``function`` computes with, if it is defined in the
    ``upliftlab`` package (:func:`.fingerprint.code_fingerprint`), else None."""
    module = getattr(function, "__module__", None)
    if isinstance(module, str) and (module == "upliftlab" or module.startswith("upliftlab.")):
        return code_fingerprint(module)
    return None


def point_key(study: str, function, params: Mapping, version: str = __version__, *,
              where: str = "params") -> str:
    """SHA-256 (hex) of (study, function, canonical parameters, upliftlab version[, code]).

    ``function`` is a function or its ``module:qualname``. A function defined in the
    ``upliftlab`` package adds the fingerprint of its module's code
    (:func:`.fingerprint.code_fingerprint`); a name, or a function of another package, keys by
    the version alone. A parameter that is not a finite JSON value is refused with an
    :class:`InputError` naming it (``where`` prefixes its path).
    """
    name = function if isinstance(function, str) else function_name(function)
    parts = [canonical_json(study, "study"), canonical_json(name, "function"),
             canonical_json(params, where), canonical_json(version, "version")]
    code = None if isinstance(function, str) else function_code(function)
    if code is not None:
        parts.append(canonical_json(code, "code"))
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()


@dataclass(frozen=True)
class Store:
    """A directory of records, one JSON file per key (``<root>/<k[:2]>/<k>.json``)."""

    root: Path

    def __post_init__(self):
        object.__setattr__(self, "root", Path(self.root).expanduser())

    def path(self, key: str) -> Path:
        """Where the record of ``key`` lives (length-64 hex key)."""
        if len(key) != 64 or any(c not in "0123456789abcdef" for c in key):
            raise InputError(f"store key {key!r}: expected 64 lowercase hex digits (SHA-256)")
        return self.root / key[:2] / f"{key}{_SUFFIX}"

    def has(self, key: str) -> bool:
        """True if a complete record of ``key`` is stored."""
        return self.entry(key) is not None

    def entry(self, key: str) -> dict | None:
        """The stored entry of ``key`` (record and metadata), or None.

        An unreadable file (not JSON, or for another key) counts as missing: it is rewritten by
        the next :meth:`put`.
        """
        try:
            entry = json.loads(self.path(key).read_text())
        except (OSError, ValueError):
            return None
        if not isinstance(entry, dict) or entry.get("key") != key or "record" not in entry:
            return None
        return entry

    def get(self, key: str, default=None):
        """The record stored under ``key``, or ``default``."""
        entry = self.entry(key)
        return default if entry is None else entry["record"]

    def put(self, key: str, record, meta: Mapping | None = None) -> Path:
        """Store ``record`` (JSON: numbers, text, lists, tables) under ``key``, atomically.

        ``meta`` (study, function, params, version, code) is kept beside the record for provenance.
        """
        entry = {"key": key, "record": record, **dict(meta or {})}
        try:
            text = json.dumps(entry, sort_keys=True, allow_nan=True)
        except (TypeError, ValueError) as exc:
            raise InputError(f"record for key {key[:12]}…: not JSON-serialisable ({exc}); a "
                             "sweep function must return numbers, text, lists or tables") from None
        path = self.path(key)
        with output_root(self.root), atomic_path(path) as tmp:  # the store is the user's choice
            with open(tmp, "w") as fh:
                fh.write(text)
                fh.flush()
                os.fsync(fh.fileno())
        return path

    def keys(self) -> Iterator[str]:
        """Every stored key (complete records only; temporary files are skipped)."""
        if not self.root.is_dir():
            return
        for path in sorted(self.root.glob(f"??/*{_SUFFIX}")):
            if not path.name.startswith("."):
                yield path.stem

    def __len__(self) -> int:
        return sum(1 for _ in self.keys())

    def __contains__(self, key: str) -> bool:
        return self.has(key)
