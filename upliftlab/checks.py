"""Input checks that fail early with a message naming the field, the value and the valid range.

Every scene, motion and option passes through these before any work starts. The error is an
:class:`InputError` (a ``ValueError``), so callers and the CLI can report it in one line.
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Iterable, Sequence

import numpy as np

__all__ = [
    "InputError",
    "finite",
    "positive",
    "nonnegative",
    "in_range",
    "ascending",
    "one_of",
    "integer_at_least",
    "boolean",
    "not_subnormal",
    "scheduler_address",
    "SMALLEST_NORMAL",
]

#: The smallest positive normal double (2.2e-308). Below it a number is subnormal: it has lost
#: precision, and no physical quantity in any unit system of a scene is that small, so a value
#: 0 < |x| < SMALLEST_NORMAL is a mistake, never a quantity (it would make a matrix singular or
#: a response all zeros instead of leaving a term out).
SMALLEST_NORMAL = sys.float_info.min


class InputError(ValueError):
    """A scene field, motion file or option that makes no sense."""


def _number(field: str, value) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer,
                                                                    np.floating)):
        raise InputError(f"{field} = {value!r}: expected a number")
    value = _as_float(field, value)
    if math.isnan(value):
        raise InputError(f"{field} = nan: expected a finite number")
    return not_subnormal(field, value)


def not_subnormal(field: str, value: float) -> float:
    """``value``, unless it is subnormal (0 < |value| < :data:`SMALLEST_NORMAL`)."""
    if value != 0.0 and abs(value) < SMALLEST_NORMAL:
        raise InputError(f"{field} = {value:g}: not zero, yet a subnormal number (0 < |value| < "
                         f"{SMALLEST_NORMAL:.3g}), below anything physical; give 0 or a value "
                         "in the field's range")
    return value


def _as_float(field: str, value) -> float:
    """``value`` as a float; an integer beyond the float range (about 1.8e308) is refused, not
    an OverflowError."""
    try:
        return float(value)
    except OverflowError:
        text = str(value)
        shown = text if len(text) <= 24 else f"{text[:12]}…({len(text)} digits)"
        raise InputError(f"{field} = {shown}: beyond the range of a number here "
                         "(|value| < 1.8e308)") from None


def finite(field: str, value) -> float:
    """``value`` as a float, refusing NaN and infinity."""
    value = _number(field, value)
    if math.isinf(value):
        raise InputError(f"{field} = {value}: expected a finite number")
    return value


def positive(field: str, value, *, allow_inf: bool = False) -> float:
    """A number > 0 (finite unless ``allow_inf``)."""
    value = _number(field, value) if allow_inf else finite(field, value)
    if not value > 0.0:
        raise InputError(f"{field} = {value:g}: must be > 0")
    return value


def nonnegative(field: str, value) -> float:
    """A finite number >= 0."""
    value = finite(field, value)
    if value < 0.0:
        raise InputError(f"{field} = {value:g}: must be >= 0")
    return value


def in_range(field: str, value, low: float, high: float, *,
             low_open: bool = False, high_open: bool = False) -> float:
    """A finite number within [low, high]; either end may be open."""
    value = finite(field, value)
    below = value <= low if low_open else value < low
    above = value >= high if high_open else value > high
    if below or above:
        left = "(" if low_open else "["
        right = ")" if high_open else "]"
        raise InputError(f"{field} = {value:g}: valid range is {left}{low:g}, {high:g}{right}")
    return value


def ascending(field: str, values, low: float, high: float, *,
              low_open: bool = False) -> tuple[float, ...]:
    """A non-empty list of numbers in [low, high] (or (low, high]) that strictly ascend, as a
    tuple: the axes of a study's grid."""
    left = "(" if low_open else "["
    if isinstance(values, (str, bytes)) or not isinstance(values, Sequence) or not values:
        raise InputError(f"{field} = {values!r}: expected a non-empty list of numbers in "
                         f"{left}{low:g}, {high:g}]")
    out = tuple(in_range(f"{field}[{i}]", v, low, high, low_open=low_open)
                for i, v in enumerate(values))
    if any(b <= a for a, b in zip(out, out[1:])):
        raise InputError(f"{field} = {list(values)!r}: values must strictly ascend")
    return out


def one_of(field: str, value, choices: Iterable[str]) -> str:
    """A string among ``choices``."""
    choices = tuple(choices)
    if value not in choices:
        raise InputError(f"{field} = {value!r}: must be one of {', '.join(map(repr, choices))}")
    return value


def integer_at_least(field: str, value, minimum: int) -> int:
    """An integer >= ``minimum`` (numpy integers and integral floats are accepted)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer,
                                                                    np.floating)):
        raise InputError(f"{field} = {value!r}: expected an integer >= {minimum}")
    if isinstance(value, (int, np.integer)):
        _as_float(field, value)  # an integer beyond every range is refused here
        value = int(value)
    elif not math.isfinite(value) or value != int(value):
        raise InputError(f"{field} = {value!r}: expected an integer >= {minimum}")
    if int(value) < minimum:
        raise InputError(f"{field} = {int(value)}: must be an integer >= {minimum}")
    return int(value)


def boolean(field: str, value) -> bool:
    """A true/false flag."""
    if not isinstance(value, bool):
        raise InputError(f"{field} = {value!r}: expected true or false")
    return value


#: A Dask scheduler address: an optional protocol, a host name, IPv4 address or bracketed IPv6
#: address, and an optional port.
_ADDRESS = re.compile(r"(?:(?P<scheme>tcp|tls|ws|wss|ucx)://)?"
                      r"(?P<host>\[[0-9A-Fa-f:.]+\]"
                      r"|[A-Za-z0-9](?:[A-Za-z0-9.-]{0,251}[A-Za-z0-9])?)"
                      r"(?::(?P<port>[0-9]{1,5}))?/?", re.ASCII)
#: The address of a Dask scheduler in this process (``LocalCluster(processes=False)``, whose
#: ``scheduler_address`` is ``inproc://<host>/<process id>/<counter>``): reachable from this
#: process only, as Dask's own ``inproc`` transport is.
_INPROC = re.compile(r"inproc://(?:[A-Za-z0-9](?:[A-Za-z0-9.-]{0,251}[A-Za-z0-9])?"
                     r"|\[[0-9A-Fa-f:.]+\])/[0-9]{1,10}/[0-9]{1,10}", re.ASCII)


def scheduler_address(field: str, value, *, in_process: bool = True) -> str:
    """A Dask scheduler address, ``host:port`` or ``tcp://host:port`` (also ``tls``, ``ws``,
    ``wss``, ``ucx``; the port 1–65535 optional), or the ``inproc://host/pid/n`` address of a
    scheduler in this process (as a ``LocalCluster(processes=False)`` gives it: the same
    cluster is accepted as an object or by its address), checked before any work: an address
    that is not one used to start the work and fail (or hang) when the first sweep connected.
    ``in_process`` False (a command line, whose new process holds no scheduler) refuses an
    ``inproc://`` address."""
    valid = ("expected a Dask scheduler address such as tcp://host:8786 or host:8786 (or the "
             "inproc://host/pid/n address of a scheduler in this process)")
    if not isinstance(value, str):
        raise InputError(f"{field} = {value!r}: {valid}")
    if _INPROC.fullmatch(value.strip()):
        if not in_process:
            raise InputError(f"{field} = {value!r}: an inproc:// scheduler lives in the process "
                             "that made it, not in this command's; give its tcp:// address")
        return value.strip()
    match = _ADDRESS.fullmatch(value.strip())
    if not value.strip() or match is None:
        raise InputError(f"{field} = {value[:80]!r}: {valid}")
    port = match.group("port")
    if port is not None and not 1 <= int(port) <= 65535:
        raise InputError(f"{field} = {value!r}: port {port} is not in 1..65535; {valid}")
    return value.strip()
