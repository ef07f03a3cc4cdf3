"""Stale records checked, not thrown away: a seeded sample made again and compared.

A record made by other code than today's (:meth:`.store.Store.is_fresh`) may still be right:
most edits change no number. Before a study uses stale records, :func:`check_stale` makes a
seeded sample of them again with today's code and compares each with its stored record, field
by field (:func:`record_change`), within the point function's declared tolerance:

* all within it: the store accepts the records' code for today's (a stamp in
  ``provenance.json`` with the sample and the largest change found), and the study goes on;
* any beyond it: :class:`StaleStoreError` names the points that moved, the field and by how
  much, and nothing is accepted (exit 3 on the command line).

The sample is seeded by the stale keys themselves, so the same store and code check the same
points. ``upliftlab store verify DIR --sample N`` runs the same check by hand.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import math
import random
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

from ...checks import InputError
from .store import POINT_FUNCTIONS, Store, entry_code, function_name, revisions

__all__ = ["StaleStoreError", "Check", "record_change", "check_stale", "seeded_sample",
           "DEFAULT_SAMPLE", "ABSOLUTE_FLOOR", "FIELD_ROUNDOFF"]

#: How many stale records of a function a study makes again before accepting the rest.
DEFAULT_SAMPLE = 3

#: Below this absolute difference two numbers are the same (results are in SI or the scene's
#: units; 1e-12 of a metre, a radian or a kilonewton is no physical difference).
ABSOLUTE_FLOOR = 1e-12
#: Below this fraction of the largest number of the same field (a top-level entry of the
#: record: a matrix, a history) two numbers are the same: round-off of that field. A term that
#: is zero by symmetry (the vertical–rocking coupling of a symmetric footing's impedance,
#: 1e-11 beside entries of 1e4) comes out as noise whose sign the libraries' arithmetic sets.
FIELD_ROUNDOFF = 1e-12


class StaleStoreError(RuntimeError):
    """Stale records that today's code does not reproduce within the declared tolerance."""


@dataclass(frozen=True)
class Check:
    """The outcome of a check: the ``function``, how many records were ``stale``, the keys
    made again (``sample``), the largest relative change and where (``field``), and the
    fields today's code records that the kept records lack (``added``)."""

    function: str
    stale: int
    sample: tuple[str, ...]
    largest: float
    field: str
    added: tuple[str, ...] = ()

    def sentence(self) -> str:
        return (f"{self.function}: {self.stale} records made by earlier code, {len(self.sample)} "
                f"made again, largest relative change {self.largest:.2g}"
                + (f" ({self.field})" if self.field else "")
                + (f"; fields today's code adds, absent from the kept records: "
                   f"{', '.join(self.added)}" if self.added else ""))


def record_change(old, new, ignore: Sequence[str] = (), where: str = "",
                  floor: float = ABSOLUTE_FLOOR) -> tuple[float, str]:
    """The largest relative change between two records, and where: numbers by
    |a − b| / max(|a|, |b|), none below ``floor`` (:data:`ABSOLUTE_FLOOR`, or
    :data:`FIELD_ROUNDOFF` of the largest number of the same field, whichever is larger;
    NaN equals NaN), text and flags by equality (inf when they differ), tables key by key
    and lists element by element (inf when their shapes differ). Fields named in ``ignore``
    (timings) are skipped, and so are fields only the new record has (:func:`added_fields`:
    today's code records more, which changes none of the stored numbers; the readers take a
    record without them as before); a field only the old record has is a change (inf):
    today's code no longer makes it."""
    if isinstance(old, Mapping) and isinstance(new, Mapping):
        keys = set(old) - set(ignore)
        worst = (0.0, "")
        for k in sorted(keys):
            if k not in new:
                return math.inf, f"{where}.{k}".lstrip(".")
            field_floor = max(floor, FIELD_ROUNDOFF * _magnitude(old[k])) if not where \
                else floor
            worst = max(worst, record_change(old[k], new[k], ignore, f"{where}.{k}",
                                             field_floor), key=lambda w: w[0])
        return worst
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            return math.inf, f"{where} (length {len(old)} → {len(new)})".lstrip(".")
        worst = (0.0, "")
        for i, (a, b) in enumerate(zip(old, new)):
            worst = max(worst, record_change(a, b, ignore, f"{where}[{i}]", floor),
                        key=lambda w: w[0])
        return worst
    if _number(old) and _number(new):
        a, b = float(old), float(new)
        if (math.isnan(a) and math.isnan(b)) or a == b or abs(a - b) <= floor:
            return 0.0, ""
        scale = max(abs(a), abs(b))
        return (abs(a - b) / scale if math.isfinite(scale) else math.inf), where.lstrip(".")
    return (0.0, "") if old == new else (math.inf, where.lstrip("."))


def _magnitude(value) -> float:
    """The largest finite |number| in ``value`` (nested lists and tables), 0 if none."""
    if isinstance(value, Mapping):
        return max((_magnitude(v) for v in value.values()), default=0.0)
    if isinstance(value, list):
        return max((_magnitude(v) for v in value), default=0.0)
    if _number(value) and math.isfinite(float(value)):
        return abs(float(value))
    return 0.0


def added_fields(old, new, where: str = "") -> list[str]:
    """The fields (dotted names) that ``new`` has and ``old`` has not, at any depth of tables."""
    if not (isinstance(old, Mapping) and isinstance(new, Mapping)):
        return []
    out = [f"{where}.{k}".lstrip(".") for k in sorted(set(new) - set(old))]
    for k in sorted(set(new) & set(old)):
        out += added_fields(old[k], new[k], f"{where}.{k}")
    return out


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def seeded_sample(keys: Sequence[str], size: int) -> list[str]:
    """``size`` of ``keys`` (all if fewer), chosen with a seed made from the keys themselves."""
    ordered = sorted(set(keys))
    seed = int(hashlib.sha256("\n".join(ordered).encode()).hexdigest()[:16], 16)
    return sorted(random.Random(seed).sample(ordered, min(size, len(ordered))))


def check_stale(store: Store, function: Callable, stale: Mapping[str, Mapping], *,
                sample: int = DEFAULT_SAMPLE, evaluate: Callable | None = None) -> Check:
    """Check the stale records ``stale`` {key: point} of ``function`` in ``store`` (module
    docstring); ``evaluate(function, [(key, point)]) -> [(key, record)]`` makes them again
    (default: here, one after another). Returns the :class:`Check` once the store has
    accepted them; raises :class:`StaleStoreError` if any moved."""
    name = function_name(function)
    declared = getattr(function, "point", None)
    tolerance = declared.tolerance if declared else 0.0
    ignore = declared.ignore if declared else ()
    keys = seeded_sample(list(stale), sample)
    made = (evaluate or _here)(function, [(k, stale[k]) for k in keys])
    changes, added = {}, set()
    for key, record in made:
        changes[key] = record_change(store.get(key), record, ignore)
        added.update(added_fields(store.get(key), record))
    moved = {k: c for k, c in changes.items() if not c[0] <= tolerance}
    if moved:
        lines = "; ".join(f"{k[:12]} by {c[0]:.3g} in {c[1] or 'the record'}"
                          for k, c in sorted(moved.items()))
        raise StaleStoreError(
            f"store {store.root}: {len(stale)} records of {name} were made by earlier code and "
            f"{len(moved)} of the {len(keys)} made again moved beyond the tolerance "
            f"{tolerance:g}: {lines}. The code changes these numbers: raise the model's "
            "REVISION (its records are then made anew), or find out why")
    largest, field = max(changes.values(), key=lambda c: c[0], default=(0.0, ""))
    codes = {entry_code(store.entry(k) or {}) for k in stale} - {None}
    store.stamp(name, sorted(codes), {
        "sample": keys, "largest_change": largest, "field": field, "tolerance": tolerance,
        "added_fields": sorted(added),
        "utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")})
    return Check(name, len(stale), tuple(keys), largest, field, tuple(sorted(added)))


def _here(function, items):
    return [(key, function(point)) for key, point in items]


def _estimate(store: Store, stale: Mapping[str, Mapping], sample: int) -> str:
    """", about N s" from the wall times the sampled records kept when they were made (what
    making them again costs, give or take the machine), or "" when they kept none."""
    times = [(store.get(k) or {}).get("wall_time_s") for k in seeded_sample(list(stale), sample)]
    times = [t for t in times if isinstance(t, (int, float)) and math.isfinite(t)]
    return f", about {sum(times):.0f} s (their recorded wall times)" if times else ""


def _here_saying(say):
    """:func:`_here` that says, after each record made again, how many are done, the elapsed
    time and an estimate of the time left (the mean so far times the records left)."""
    def evaluate(function, items):
        made, start = [], time.monotonic()
        for key, point in items:
            made.append((key, function(point)))
            elapsed = time.monotonic() - start
            left = elapsed / len(made) * (len(items) - len(made))
            say(f"upliftlab store verify: {function_name(function)}: {len(made)} of "
                f"{len(items)} made again, {elapsed:.0f} s"
                + (f", about {left:.0f} s left" if len(made) < len(items) else ""))
        return made
    return evaluate


def stale_keys(store: Store, keys: Sequence[str]) -> list[str]:
    """Those of ``keys`` whose stored records are stale (made by other, unaccepted code)."""
    out = []
    for key in keys:
        entry = store.entry(key)
        if entry is not None and not store.is_fresh(entry):
            out.append(key)
    return out


def verify_store(store: Store, *, sample: int = DEFAULT_SAMPLE, say=print) -> list[Check]:
    """``upliftlab store verify``: check every function's stale records in ``store`` from the
    parameters the records keep (their locators, if any, found again by the point function);
    raises :class:`StaleStoreError` at the first function whose sample moved. The point
    functions are those declared so far (:data:`.store.POINT_FUNCTIONS`): import the studies
    first. A stale record of another revision of its models (``entry["models"]``, which
    today's keys never reach: :func:`.store.point_key`) is kept as data and not made again:
    today's code makes today's revision's numbers, not its."""
    by_function: dict[str, dict[str, Mapping]] = {}
    older: dict[str, int] = {}
    for key in stale_keys(store, list(store.keys())):
        entry = store.entry(key)
        name = entry.get("function", "")
        function = POINT_FUNCTIONS.get(name)
        if function is not None and "models" in entry \
                and entry["models"] != revisions(function):
            older[name] = older.get(name, 0) + 1
            continue
        by_function.setdefault(name, {})[key] = entry.get("params", {})
    for name, count in sorted(older.items()):
        say(f"upliftlab store verify: {name}: {count} records of another model revision than "
            f"today's {revisions(POINT_FUNCTIONS[name])}: never read, kept as data, not checked")
    checks = []
    for name, stale in sorted(by_function.items()):
        function = POINT_FUNCTIONS.get(name)
        if function is None:
            raise StaleStoreError(f"store {store.root}: {len(stale)} stale records of {name!r}, "
                                  "a point function this upliftlab does not have")
        say(f"upliftlab store verify: {name}: {len(stale)} stale records, making "
            f"{min(sample, len(stale))} again{_estimate(store, stale, sample)}")
        try:
            checks.append(check_stale(store, function, stale, sample=sample,
                                      evaluate=_here_saying(say)))
        except (KeyError, InputError) as exc:
            raise InputError(f"store {store.root}: the records of {name} cannot be made again "
                             f"from what the store keeps ({type(exc).__name__}: {exc}); run the "
                             "study that made them, which checks them itself") from None
        say(f"upliftlab store verify: {checks[-1].sentence()}: accepted")
    return checks
