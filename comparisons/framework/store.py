"""Kept results: one record per evaluated point, keyed by what was asked.

A point's key (:func:`point_key`) is the SHA-256 of what was asked: the study, the point
function's declared name (:func:`point_function`), its parameters as canonical JSON and the
revision of each model it computes with (``upliftlab.continuum.REVISION``, …), which a model
raises on purpose when its numbers are meant to change. The code is not in the key: a record
carries which code made it as provenance (:func:`upliftlab.provenance.code_digest`, the
package version, the libraries and the host), so that an edit that changes no number leaves
every record reachable. A record made by other code than today's is *stale*, not gone: a study
checks a seeded sample of its stale records by running them again (:mod:`.freshness`) and then
accepts them, or stops and says which moved.

The store is a folder: loose records (``<k[:2]>/<k>.json``, one per point, written atomically
so that several processes may add to it at once) and packs (``packs/*.jsonl.gz``, many records
in one compressed file, read only: how a store is kept with the repository, :meth:`Store.pack`).
``provenance.json`` holds the code digests a check accepted. Parameters named ``_…`` locate an
input on this machine (a file path): they stay out of the key and out of the record. A file
where a record belongs that is not one (not JSON, not gzip, another key, no record) is refused
with an :class:`~upliftlab.checks.InputError` naming it (and a pack's line) when it is read:
it is never skipped, rewritten, packed or removed.
"""

from __future__ import annotations

import gzip
import hashlib
import importlib
import json
import math
import os
import zlib
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...checks import InputError
from ...paths import output_root
from ...provenance import MODEL_SOURCES, code_digest, provenance
from ...results import atomic_path

__all__ = ["Store", "point_key", "canonical_json", "function_name", "point_function",
           "POINT_FUNCTIONS", "PointFunction", "revisions", "plain_params", "record_meta",
           "depends_digest", "entry_code", "DEFAULT_SOURCES"]

_SUFFIX = ".json"
PACKS = "packs"
STAMPS = "provenance.json"

#: Every declared point function by its key name (filled as the studies' modules load).
POINT_FUNCTIONS: dict[str, Callable] = {}

#: The sources a stored record depends on unless its function declares others: the models'
#: and the comparisons' (not the command line's).
DEFAULT_SOURCES = MODEL_SOURCES + ("upliftlab.comparisons/",)


@dataclass(frozen=True)
class PointFunction:
    """What a point function declares (:func:`point_function`): its ``name`` in the keys,
    the ``models`` whose revisions enter its keys, the relative ``tolerance`` within which a
    record made again must reproduce the stored one, the record fields to ``ignore`` when
    comparing (timings), and the ``sources`` its records depend on (prefixes as
    :func:`upliftlab.provenance.code_digest` takes them)."""

    name: str
    models: tuple[str, ...] = ()
    tolerance: float = 1e-6
    ignore: tuple[str, ...] = ("wall_time_s", "compile_time_s", "runtime", "runtimes", "session",
                               "measured_utc")
    sources: tuple[str, ...] = ()

    def depends_on(self) -> tuple[str, ...]:
        """The sources whose code digest says whether a record is stale: the declared ones,
        else the models' and the comparisons' (:data:`DEFAULT_SOURCES`)."""
        return self.sources or DEFAULT_SOURCES


def point_function(name: str, *, models: Sequence[str] = (), tolerance: float = 1e-6,
                   ignore: Sequence[str] = PointFunction.ignore, sources: Sequence[str] = ()):
    """Declare a study's point function: the ``name`` that identifies it in keys (kept when the
    function moves), the ``models`` it computes with (``"reduced"``, ``"continuum"``), the
    relative ``tolerance`` of a re-run check, the timing fields it ignores and the sources its
    records depend on (default :data:`DEFAULT_SOURCES`)."""
    if not (0.0 <= tolerance < 1.0):
        raise InputError(f"tolerance = {tolerance!r}: valid range is [0, 1)")

    def declare(function):
        function.point = PointFunction(name, tuple(models), float(tolerance), tuple(ignore),
                                       tuple(sources))
        POINT_FUNCTIONS[name] = function
        return function

    return declare


def _plain(value, where: str):
    """``value`` as plain JSON types (numpy scalars and arrays become numbers and lists), its
    ``_…`` entries (locators) left out."""
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


def plain_params(params: Mapping, where: str = "params") -> dict:
    """``params`` as stored: plain JSON values, without their locators (``_…``)."""
    return _plain(params, where)


def canonical_json(value, where: str = "point") -> str:
    """Canonical JSON of ``value``: sorted keys, no spaces, finite numbers only, ``_…``
    entries left out (they locate an input whose content another entry identifies)."""
    return json.dumps(_plain(value, where), sort_keys=True, separators=(",", ":"),
                      ensure_ascii=True, allow_nan=False)


def function_name(function) -> str:
    """What identifies a function in a key: its declared name, else ``module:qualname``."""
    declared = getattr(getattr(function, "point", None), "name", None)
    if isinstance(declared, str) and declared:
        return declared
    module = getattr(function, "__module__", None)
    qualname = getattr(function, "__qualname__", None)
    if not module or not qualname:
        raise InputError(f"function {function!r}: needs a module and a name (a top-level def)")
    return f"{module}:{qualname}"


def revisions(function) -> dict[str, int]:
    """The declared revision of each model ``function`` computes with."""
    models = getattr(getattr(function, "point", None), "models", ())
    return {m: int(importlib.import_module(f"upliftlab.{m}").REVISION) for m in models}


def point_key(study: str, function, params: Mapping, *, where: str = "params") -> str:
    """SHA-256 (hex) of what was asked (module docstring). ``function`` is a function or its
    name (a name keys without model revisions). A parameter that is not a finite JSON value is
    refused with an :class:`InputError` naming it (``where`` prefixes its path)."""
    name = function if isinstance(function, str) else function_name(function)
    parts = [canonical_json(study, "study"), canonical_json(name, "function"),
             canonical_json(params, where)]
    models = {} if isinstance(function, str) else revisions(function)
    if models:
        parts.append(canonical_json(models, "models"))
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()


def _declared(function_or_name) -> PointFunction:
    name = function_or_name if isinstance(function_or_name, str) else None
    function = POINT_FUNCTIONS.get(name) if name is not None else function_or_name
    return getattr(function, "point", None) or PointFunction(name or "")


def depends_digest(function_or_name) -> str:
    """Today's code digest of the sources the records of a point function (or its declared
    name) depend on (:meth:`PointFunction.depends_on`)."""
    return code_digest(_declared(function_or_name).depends_on())


def record_meta(study: str, function, params: Mapping) -> dict:
    """What a record keeps beside its result: the study, the function, its parameters (no
    locators), the models' revisions and the provenance of the code that made it (with
    ``depends_sha256``, the digest of the sources its numbers depend on)."""
    return {"study": study, "function": function_name(function),
            "params": plain_params(params), "models": revisions(function),
            "provenance": {**provenance(), "depends_sha256": depends_digest(function)}}


def entry_code(entry: Mapping) -> str | None:
    """The digest of the sources an entry depends on, as they were when it was made (older
    entries kept their code fingerprint as ``code``)."""
    prov = entry.get("provenance")
    return prov.get("depends_sha256") if isinstance(prov, Mapping) else entry.get("code")


_HEX = frozenset("0123456789abcdef")
_VALID = ("a record is a JSON table with its 'key' (64 lowercase hex digits, the loose file's "
          "name) and its 'record'")


def _is_key(text) -> bool:
    """Whether ``text`` is a store key: 64 lowercase hex digits (a SHA-256)."""
    return isinstance(text, str) and len(text) == 64 and set(text) <= _HEX


def _checked(entry, where: str, key: str | None = None) -> dict:
    """``entry`` if it is a complete record (of ``key``, when given), else an
    :class:`InputError` naming ``where`` (the file, and a pack's line)."""
    if not isinstance(entry, dict) or not _is_key(entry.get("key")) or "record" not in entry:
        raise InputError(f"{where}: not a record; {_VALID}; move it out of the store")
    if key is not None and entry["key"] != key:
        raise InputError(f"{where}: holds the record of key {entry['key']!r}, not of its file "
                         f"name's; {_VALID}; move it out of the store")
    return entry


def _read_pack(pack: Path) -> dict[str, dict]:
    """The entries of the pack ``pack`` by key. A pack that is not gzip-compressed JSON lines
    of records is refused, naming it (and the line): its records must not be lost unseen."""
    where, entries = f"store pack {str(pack)!r}", {}
    try:
        with gzip.open(pack, "rt", encoding="utf-8") as fh:
            for number, line in enumerate(fh, 1):
                try:
                    entry = json.loads(line)
                except ValueError as exc:
                    raise InputError(f"{where}, line {number}: not JSON ({exc}); {_VALID}; "
                                     "move the pack out of the store") from None
                entry = _checked(entry, f"{where}, line {number}")
                entries[entry["key"]] = entry
    except (OSError, EOFError, zlib.error, UnicodeDecodeError) as exc:
        raise InputError(f"{where}: cannot be read as gzip-compressed JSON lines ({exc}); move "
                         "it out of the store") from None
    return entries


@dataclass(frozen=True)
class Store:
    """A folder of records (module docstring)."""

    root: Path
    _packs: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self):
        object.__setattr__(self, "root", Path(self.root).expanduser())

    def path(self, key: str) -> Path:
        """Where the loose record of ``key`` lives (length-64 hex key)."""
        if len(key) != 64 or any(c not in "0123456789abcdef" for c in key):
            raise InputError(f"store key {key!r}: expected 64 lowercase hex digits (SHA-256)")
        return self.root / key[:2] / f"{key}{_SUFFIX}"

    def _packed(self) -> dict[str, dict]:
        """Every packed entry by key (read once per store object)."""
        if "entries" not in self._packs:
            entries = {}
            for pack in sorted((self.root / PACKS).glob("*.jsonl.gz")):
                entries.update(_read_pack(pack))
            self._packs["entries"] = entries
        return self._packs["entries"]

    def has(self, key: str) -> bool:
        """True if a complete record of ``key`` is stored."""
        return self.entry(key) is not None

    def entry(self, key: str) -> dict | None:
        """The stored entry of ``key`` (record and metadata), its loose file's else its
        pack's, or None. A loose file that is not a record of ``key`` (not JSON, another key)
        is refused naming it (:meth:`_loose`): it is not the store's to skip or rewrite."""
        entry = self._loose(key)
        return entry if entry is not None else self._packed().get(key)

    def _loose(self, key: str) -> dict | None:
        """The entry in the loose file of ``key``, None if there is no such file; a file that
        cannot be read, or is not a record of ``key``, is an :class:`InputError` naming it.
        (Records are written atomically: a loose file is never half-written by upliftlab.)"""
        path = self.path(key)
        where = f"store record {str(path)!r}"
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return None
        except (OSError, UnicodeDecodeError) as exc:
            reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
            raise InputError(f"{where}: cannot be read ({reason}); move it out of the store"
                             ) from None
        try:
            entry = json.loads(text)
        except ValueError as exc:
            raise InputError(f"{where}: not JSON ({exc}); {_VALID}; move it out of the store"
                             ) from None
        return _checked(entry, where, key)

    def get(self, key: str, default=None):
        """The record stored under ``key``, or ``default``."""
        entry = self.entry(key)
        return default if entry is None else entry["record"]

    def put(self, key: str, record, meta: Mapping | None = None) -> Path:
        """Store ``record`` (JSON: numbers, text, lists, tables) under ``key``, atomically,
        with ``meta`` (:func:`record_meta`) beside it."""
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
        """Every stored key, loose and packed. A loose ``??/*.json`` file not named as a
        record (``<k[:2]>/<k>.json``) is refused naming it (it is no record to skip)."""
        loose = set()
        if self.root.is_dir():
            for path in self.root.glob(f"??/*{_SUFFIX}"):
                if path.name.startswith("."):  # a temporary of a write under way
                    continue
                if not _is_key(path.stem) or path.parent.name != path.stem[:2]:
                    raise InputError(f"store file {str(path)!r}: not named as a record "
                                     "(<64 lowercase hex digits>.json in the folder of its "
                                     "first two); move it out of the store")
                loose.add(path.stem)
        yield from sorted(loose | self._packed().keys())

    def __len__(self) -> int:
        return sum(1 for _ in self.keys())

    def __contains__(self, key: str) -> bool:
        return self.has(key)

    # -- provenance -----------------------------------------------------------------------

    def accepted(self) -> dict:
        """``provenance.json``: per function name, the code digests accepted for each code
        digest that checked them (:mod:`.freshness`)."""
        return self._stamps().get("accepted", {})

    def _stamps(self) -> dict:
        """``provenance.json`` as a table; {} when there is none. A file that is not such a
        table is refused naming it: read as empty, the next :meth:`stamp` would write over
        the checks it holds."""
        path = self.root / STAMPS
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return {}
        except (OSError, UnicodeDecodeError) as exc:
            raise InputError(f"store provenance {str(path)!r}: cannot be read ({exc}); move "
                             "it out of the store") from None
        try:
            stamps = json.loads(text)
        except ValueError as exc:
            raise InputError(f"store provenance {str(path)!r}: not JSON ({exc}); move it out "
                             "of the store") from None
        if not isinstance(stamps, dict) or not isinstance(stamps.get("accepted", {}), dict):
            raise InputError(f"store provenance {str(path)!r}: not a table of accepted code "
                             "digests ('accepted', 'checks'); move it out of the store")
        return stamps

    def is_fresh(self, entry: Mapping) -> bool:
        """Whether ``entry`` was made by today's code (:func:`depends_digest` of its function),
        or by code a check accepted for today's."""
        code = depends_digest(entry.get("function", ""))
        made = entry_code(entry)
        if made == code:
            return True
        return made in self.accepted().get(entry.get("function", ""), {}).get(code, [])

    def stamp(self, function: str, accepts: Sequence[str], check: Mapping) -> Path:
        """Record that today's code reproduced the records of ``function`` made by the code
        digests ``accepts`` (``check``: what was run and how close it came)."""
        stamps = self._stamps()
        code = depends_digest(function)
        per_code = stamps.setdefault("accepted", {}).setdefault(function, {})
        per_code[code] = sorted(set(per_code.get(code, [])) | set(accepts))
        stamps.setdefault("checks", []).append({"function": function, "code": code,
                                                "accepts": sorted(set(accepts)), **check})
        with output_root(self.root), atomic_path(self.root / STAMPS) as tmp:
            tmp.write_text(json.dumps(stamps, indent=1, sort_keys=True) + "\n")
        return self.root / STAMPS

    # -- packs ----------------------------------------------------------------------------

    def pack(self, name: str, keys: Sequence[str] | None = None) -> Path:
        """Move loose records (``keys``, default all) into the compressed pack
        ``packs/<name>.jsonl.gz`` (added to one of that name), and remove their loose files.
        A pack holds no machine paths: the records' locators are already left out. Every
        record (loose and in the pack) is read before anything is written or removed: a file
        that is not one is refused naming it (:meth:`_loose`, :func:`_read_pack`)."""
        from ...paths import path_component

        path_component(name, "pack name")
        target = self.root / PACKS / f"{name}.jsonl.gz"
        entries = _read_pack(target) if target.is_file() else {}
        loose = {k: self._loose(k) for k in (keys if keys is not None else list(self.keys()))}
        chosen = [k for k, entry in loose.items() if entry is not None]
        entries.update((k, loose[k]) for k in chosen)
        with output_root(self.root), atomic_path(target) as tmp:
            with gzip.GzipFile(tmp, "wb", compresslevel=9, mtime=0) as fh:
                for key in sorted(entries):
                    fh.write((json.dumps(entries[key], sort_keys=True) + "\n").encode())
        for key in chosen:
            self.path(key).unlink()
        for folder in {self.path(key).parent for key in chosen}:
            try:
                folder.rmdir()  # only if no record is left in it
            except OSError:
                pass
        self._packs.clear()
        return target
