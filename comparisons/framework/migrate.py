"""Stores of an older upliftlab, re-keyed by what was asked.

Up to upliftlab 0.1.0 of 2026-11-28 a record's key also held the package version and the
fingerprint of its point function's code, so that any edit of that code made every record
unreachable, and a record kept its parameters' machine paths. :func:`migrate` rewrites each
such record of a declared point function (:data:`.store.POINT_FUNCTIONS`) under the key of
what was asked (:func:`.store.point_key`), its old code fingerprint kept as its provenance:
the records are stale under today's code, and the first study that reads them checks a sample
(:mod:`.freshness`). Records of other functions are left as they are.
"""

from __future__ import annotations

from .store import POINT_FUNCTIONS, Store, plain_params, point_key, revisions

__all__ = ["migrate", "old_format"]


def old_format(entry: dict) -> bool:
    """Whether ``entry`` is a record of the older format (a code fingerprint, no provenance)."""
    return "provenance" not in entry and "function" in entry and "params" in entry


def migrate(store: Store) -> tuple[int, int]:
    """Re-key every old-format loose record of a declared point function in ``store`` (import
    the studies first); returns (records re-keyed, records left as they were)."""
    moved = kept = 0
    for key in list(store.keys()):
        entry = store.entry(key)
        function = POINT_FUNCTIONS.get(entry.get("function", "")) if entry else None
        if entry is None or function is None or not old_format(entry) \
                or not store.path(key).is_file():
            kept += 1
            continue
        new_key = point_key(entry["study"], function, entry["params"])
        store.put(new_key, entry["record"], {
            "study": entry["study"], "function": entry["function"],
            "params": plain_params(entry["params"]), "models": revisions(function),
            "provenance": {"depends_sha256": entry.get("code"),
                           "upliftlab_version": entry.get("version")}})
        if new_key != key:
            store.path(key).unlink()
            try:
                store.path(key).parent.rmdir()  # only if no record is left in it
            except OSError:
                pass
        moved += 1
    return moved, kept
