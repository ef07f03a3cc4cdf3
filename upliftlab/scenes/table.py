"""Reading a scene's TOML tables key by key: every key a reader does not ask for is an error,
and every check names the field, the value and the valid range."""

from __future__ import annotations

from typing import Any

from .. import checks
from ..checks import InputError

__all__ = ["SCHEMA_VERSION", "MAX_DEPTH", "check_values", "MISSING", "Table", "string", "choice", "in_range", "numbers",
           "bounded_integer"]

#: The scene files' schema this upliftlab reads (``schema = 1``).
SCHEMA_VERSION = 1

#: The default of a key that must be given.
MISSING = object()


class Table:
    """A TOML table read key by key; :meth:`done` refuses keys nobody asked for."""

    def __init__(self, data: Any, path: str):
        if not isinstance(data, dict):
            raise InputError(f"{path} = {data!r}: expected a table")
        self.data, self.path, self.used = data, path, set()

    def get(self, key: str, check=None, default=MISSING):
        self.used.add(key)
        name = f"{self.path}.{key}" if self.path else key
        if key not in self.data:
            if default is MISSING:
                raise InputError(f"{name} is missing")
            return default
        value = self.data[key]
        return check(name, value) if check else value

    def has(self, key: str) -> bool:
        return key in self.data

    def done(self) -> None:
        unknown = sorted(set(self.data) - self.used)
        if unknown:
            where = f"{self.path}." if self.path else ""
            valid = ", ".join(sorted(self.used))
            raise InputError(f"{where}{unknown[0]}: unknown key (valid keys here: {valid})")


def string(name: str, value) -> str:
    """``value`` if it is a string."""
    if not isinstance(value, str):
        raise InputError(f"{name} = {value!r}: expected a string")
    return value


def choice(choices):
    """A check that a value is one of ``choices``."""
    return lambda name, value: checks.one_of(name, value, choices)


def in_range(low, high, low_open=False, high_open=False):
    """A check that a number lies in [low, high] (open ends as given)."""
    return lambda name, value: checks.in_range(name, value, low, high,
                                               low_open=low_open, high_open=high_open)


def numbers(name: str, value) -> tuple[float, ...]:
    """A non-empty list of finite numbers, as a tuple."""
    if not isinstance(value, list) or not value:
        raise InputError(f"{name} = {value!r}: expected a non-empty list of numbers")
    return tuple(checks.finite(f"{name}[{i}]", v) for i, v in enumerate(value))


def bounded_integer(low: int, high: int):
    """A check that a value is an integer in [low, high]."""
    def check(name, value):
        value = checks.integer_at_least(name, value, low)
        if value > high:
            raise InputError(f"{name} = {value}: valid range is [{low}, {high}]")
        return value
    return check


#: Deepest nesting of tables and lists a scene may have (a scene file nests three deep:
#: ``[cases.A.structure]`` holding a list of stories; anything far deeper is not a scene).
MAX_DEPTH = 12


def check_values(data, where: str = "scene", depth: int = 0) -> None:
    """Refuse, naming the key, what no field of a scene can hold and that would otherwise fail
    deep inside the reading: tables and lists nested beyond :data:`MAX_DEPTH`, integers
    beyond the range of a float, and subnormal numbers (:func:`~upliftlab.checks.not_subnormal`)."""
    if depth > MAX_DEPTH:
        raise InputError(f"{where}: tables or lists nested more than {MAX_DEPTH} deep; a scene "
                         "file nests at most a few levels")
    if isinstance(data, dict):
        for key, value in data.items():
            check_values(value, f"{where}.{key}" if where != "scene" else str(key), depth + 1)
    elif isinstance(data, list):
        for i, value in enumerate(data):
            check_values(value, f"{where}[{i}]", depth + 1)
    elif isinstance(data, float):
        checks.not_subnormal(where, data)
    elif isinstance(data, int) and not isinstance(data, bool):
        try:
            float(data)
        except OverflowError:
            text = str(data)
            raise InputError(f"{where} = {text[:12]}…({len(text)} digits): beyond the range "
                             "of a number here (|value| < 1.8e308)") from None
