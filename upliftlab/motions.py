"""Ground motions: records read from files, and built-in motions that need no file.

A :class:`Motion` holds ground acceleration in g, sampled at a uniform step ``dt``, and the
initial conditions of the structure (for free vibration). The acceleration is piecewise linear
between samples ``t_k = k·dt`` and returns to zero at ``t = n·dt``, which is the motion's duration.

Files
    * two columns ``time  acceleration[g]`` (uniform time step, ``#`` comments);
    * one column of accelerations in g, with ``dt`` given;
    * PEER NGA ``.AT2`` (four header lines, ``NPTS`` and ``DT`` on the fourth).

A motion is named either by a path or by a name looked up on the ``UPLIFTLAB_MOTIONS`` search
path (directories separated by ``os.pathsep``), e.g. ``elcentro_1940_ns`` finds
``$UPLIFTLAB_MOTIONS/elcentro_1940_ns.txt``.
"""

from __future__ import annotations

import functools
import math
import os
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .bounds import KINDS
from .checks import InputError, finite, in_range, nonnegative, positive
from .paths import NO_SUCH_FILE, REGULAR_FILE, file_kind

__all__ = [
    "Motion",
    "motion_checksum",
    "MOTIONS_ENV",
    "ELCENTRO",
    "read_motion",
    "sample_line",
    "find_motion",
    "load_motion",
    "free_vibration",
    "sine_pulse",
    "cosine_pulse",
    "ricker_pulse",
    "harmonic",
    "motion_search_path",
]

MOTIONS_ENV = "UPLIFTLAB_MOTIONS"
ELCENTRO = "elcentro_1940_ns"
ELCENTRO_DESCRIPTION = (
    "El Centro 1940 N-S as tabulated at 0.02 s in Chopra's Dynamics of Structures, in g; "
    "file elcentro_1940_ns.txt"
)
_SUFFIXES = ("", ".txt", ".dat", ".csv", ".acc", ".AT2", ".at2")
_UNIFORM_DT_RTOL = 1e-6
#: What ends a line of a motion file: what an editor counts (:func:`_editor_lines`).
_LINE_BREAK = re.compile(r"\r\n|\r|\n")
#: Largest motion file read (bytes): a record of ten million samples is about 200 MB of text.
MAX_FILE_BYTES = 256 * 2**20
#: Most samples a motion may have (400 MB of float64).
MAX_SAMPLES = 50_000_000


@dataclass(frozen=True)
class Motion:
    """A ground motion and the structure's initial conditions.

    Attributes
    ----------
    name : str
        Short name (a file stem or a built-in description).
    dt : float
        Sample interval (s).
    acceleration : numpy.ndarray
        Ground acceleration samples (g), piecewise linear, zero after ``n·dt``.
    initial_velocity : float
        Initial lateral velocity of the top mass relative to the ground (length/s).
    initial_displacement : float
        Initial lateral displacement of the top mass relative to the ground (length).
    initial_rotation : float
        Initial base rotation θ (rad), with the superstructure undeformed.
    source : str
        Where it came from: an absolute path or ``builtin:...``.
    """

    name: str
    dt: float
    acceleration: np.ndarray = field(repr=False)
    initial_velocity: float = 0.0
    initial_displacement: float = 0.0
    initial_rotation: float = 0.0
    source: str = ""

    def __post_init__(self):
        acc = np.array(self.acceleration, dtype=float).ravel()
        acc.setflags(write=False)
        object.__setattr__(self, "acceleration", acc)
        step = KINDS["step"]  # a record's step is a time step like any other (s)
        in_range("motion.dt", self.dt, step.low, step.high)
        if acc.size == 0:
            raise InputError(f"motion {self.name!r}: no samples")
        bad = np.flatnonzero(~np.isfinite(acc))
        if bad.size:
            raise InputError(
                f"motion {self.name!r}: acceleration sample {bad[0]} is {acc[bad[0]]}; "
                "every sample must be a finite number (g)")
        for key in ("initial_velocity", "initial_displacement", "initial_rotation"):
            finite(f"motion.{key}", getattr(self, key))

    @property
    def duration(self) -> float:
        """n·dt (s): the acceleration is zero from then on."""
        return self.acceleration.size * self.dt

    @property
    def time(self) -> np.ndarray:
        """Sample times k·dt (s)."""
        return np.arange(self.acceleration.size) * self.dt

    @property
    def pga(self) -> float:
        """Peak ground acceleration (g)."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def is_free_vibration(self) -> bool:
        return not np.any(self.acceleration)

    def scaled(self, factor: float) -> Motion:
        """This motion with its acceleration multiplied by ``factor``."""
        finite("motion.scale", factor)
        return replace(self, acceleration=self.acceleration * factor)

    def scaled_to_pga(self, pga: float) -> Motion:
        """This motion scaled so that its peak ground acceleration is ``pga`` (g)."""
        positive("motion.pga", pga)
        if self.pga == 0.0:
            raise InputError(f"motion {self.name!r} has zero acceleration: cannot scale it to a "
                             "PGA")
        return self.scaled(pga / self.pga)

    def extended(self, duration: float) -> Motion:
        """This motion padded with zero acceleration to at least ``duration`` (s)."""
        n = _sample_count(duration, self.dt, "the run's duration")
        if n <= self.acceleration.size:
            return self
        acc = np.concatenate([self.acceleration, np.zeros(n - self.acceleration.size)])
        return replace(self, acceleration=acc)

    def with_duration(self, duration: float) -> Motion:
        """This motion cut, or padded with zero acceleration, to exactly ``duration`` (s): a
        whole number of its steps, at least one (else an :class:`InputError` says which
        durations are valid)."""
        positive("motion.duration", duration)
        steps = duration / self.dt
        n = max(int(round(steps)), 1)
        if steps < 1.0 - 1e-9 or abs(steps - n) > 1e-6 * max(steps, 1.0):
            below, above = max(math.floor(steps), 1) * self.dt, math.ceil(steps) * self.dt
            valid = (f"{above:g} s" if below == above or steps < 1.0
                     else f"{below:g} or {above:g} s")
            raise InputError(f"motion.duration = {duration:g} s: not a whole number of the "
                             f"motion's steps of {self.dt:g} s; use {valid}")
        _sample_count(duration, self.dt)
        if n <= self.acceleration.size:
            return replace(self, acceleration=self.acceleration[:n])
        acc = np.concatenate([self.acceleration, np.zeros(n - self.acceleration.size)])
        return replace(self, acceleration=acc)

    def acceleration_at(self, t) -> np.ndarray:
        """Ground acceleration (g) at times ``t`` (s), linear between samples."""
        n = self.acceleration.size
        times = np.arange(n + 1) * self.dt
        values = np.append(self.acceleration, 0.0)
        return np.interp(t, times, values, right=0.0)


def _sample_count(duration: float, dt: float, what: str = "motion.duration") -> int:
    """Samples of ``duration`` (s) at ``dt`` (s), refused above :data:`MAX_SAMPLES`."""
    n = math.ceil(duration / dt - 1e-9)
    if n > MAX_SAMPLES:
        raise InputError(f"{what} = {duration:g} s at the motion's step of {dt:g} s: "
                         f"{n:.3g} samples; at most {MAX_SAMPLES:.0e} (a longer step or a "
                         "shorter motion)")
    return max(int(n), 1)


def motion_search_path() -> list[Path]:
    """Directories on ``UPLIFTLAB_MOTIONS``, in order."""
    raw = os.environ.get(MOTIONS_ENV, "")
    return [Path(p).expanduser() for p in raw.split(os.pathsep) if p.strip()]


def find_motion(name: str) -> Path:
    """The file for motion ``name`` on the ``UPLIFTLAB_MOTIONS`` path.

    Raises an :class:`InputError` that says which file to supply, and how, when it is missing.
    """
    path = motion_search_path()
    for directory in path:
        for suffix in _SUFFIXES:
            candidate = directory / f"{name}{suffix}"
            if candidate.is_file():
                return candidate
    where = (f"{MOTIONS_ENV}={os.pathsep.join(map(str, path))}" if path
             else f"{MOTIONS_ENV} is not set")
    hint = f" ({ELCENTRO_DESCRIPTION})" if name == ELCENTRO else ""
    raise InputError(
        f"motion {name!r} not found: {where}. Supply it as a file path, or set {MOTIONS_ENV} "
        f"to the directory that holds {name}.txt{hint}")


def load_motion(name_or_path: str | os.PathLike, dt: float | None = None) -> Motion:
    """Read a motion given by a path, or by a name on ``UPLIFTLAB_MOTIONS``."""
    text = str(name_or_path)
    candidate = Path(text).expanduser()
    looks_like_path = candidate.suffix != "" or os.sep in text or (os.altsep or os.sep) in text
    kind = file_kind(candidate, f"motion file {text!r}")
    if kind == REGULAR_FILE:
        return read_motion(candidate, dt=dt)
    if looks_like_path:
        if kind == NO_SUCH_FILE:
            raise InputError(f"motion file {text!r} does not exist")
        raise InputError(f"motion file {text!r} is {kind}, not a regular file; give a record "
                         "file (two columns, one column with motion.dt, or PEER .AT2)")
    motion = read_motion(find_motion(text), dt=dt)
    if text == ELCENTRO:
        _say_if_not_the_expected_elcentro(motion)
    return motion


_CHECKED_ELCENTRO: set[str] = set()


def _say_if_not_the_expected_elcentro(motion: Motion) -> None:
    """Warn (once per file) when the file found for El Centro is another digitization than
    the one upliftlab's stated numbers use (:mod:`upliftlab.elcentro`)."""
    from .elcentro import mismatch
    from .log import logger

    if motion.source in _CHECKED_ELCENTRO:
        return
    _CHECKED_ELCENTRO.add(motion.source)
    different = mismatch(motion)
    if different:
        logger("motions").warning(f"upliftlab: warning: {different}; results will differ from "
                                  "the numbers upliftlab states for El Centro")


def read_motion(path: str | os.PathLike, dt: float | None = None) -> Motion:
    """Read a motion file: PEER ``.AT2``, two columns (time, g), or one column (g) with ``dt``.

    A file is parsed once per process while its size and modification time stay the same
    (parsing a text record costs a sizeable share of a short reduced run); the
    :class:`Motion` is immutable, so the cached record is shared safely.
    """
    path = Path(path)
    kind = file_kind(path, f"motion file {str(path)!r}")
    if kind not in (REGULAR_FILE, NO_SUCH_FILE):  # before it is opened: a pipe would block
        raise InputError(f"motion file {str(path)!r} is {kind}, not a regular file")
    try:
        stat = path.stat()
    except OSError as exc:
        raise InputError(f"motion file {str(path)!r}: cannot read it ({exc.strerror})") from None
    if stat.st_size > MAX_FILE_BYTES:
        raise InputError(f"motion file {str(path)!r}: {stat.st_size / 2**20:.0f} MiB; a motion "
                         f"file may hold at most {MAX_FILE_BYTES // 2**20} MiB (about ten "
                         "million samples of text)")
    return _read_motion_cached(str(path), str(path.resolve()), stat.st_mtime_ns, stat.st_size,
                               dt)


@functools.lru_cache(maxsize=64)
def _read_motion_cached(given: str, resolved: str, mtime_ns: int, size: int,
                        dt: float | None) -> Motion:
    """:func:`read_motion` keyed by the file's identity and state (``mtime_ns``, ``size``);
    ``given`` is the path as the caller wrote it, for messages."""
    path = Path(given)
    try:
        text = path.read_text(errors="replace")
    except OSError as exc:
        raise InputError(f"motion file {str(path)!r}: cannot read it ({exc.strerror})") from None
    if "\x00" in text:
        raise InputError(f"motion file {str(path)!r}: binary data, not a text record")
    if _is_at2(text, path):
        step, acc = _parse_at2(text, path)
        _no_dt(dt, step, path)
    else:
        step, acc = _parse_columns(text, path, dt)
    return Motion(name=path.stem, dt=step, acceleration=acc, source=resolved)


def _is_at2(text: str, path: Path) -> bool:
    """Whether a motion file is a PEER .AT2 record: by its suffix or its first word."""
    return path.suffix.lower() == ".at2" or text.lstrip().upper().startswith("PEER")


def sample_line(motion: Motion, index: int) -> int | None:
    """The line of ``motion``'s record file that holds sample ``index``, for a message that
    names it; None for a built-in motion, or when the file is gone or no longer holds it."""
    path = Path(motion.source) if motion.source and not motion.source.startswith("builtin:") \
        else None
    if path is None or not path.is_file():
        return None
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return None
    lines = _editor_lines(text)
    numbers = (_at2_value_lines(lines) if _is_at2(text, path)
               else [number for number, _ in _data_rows(lines)])
    return int(numbers[index]) if 0 <= index < len(numbers) else None


def _data_rows(lines: list[str]):
    """(line number, text before any ``#``) of each line of a column file that holds data."""
    for number, line in enumerate(lines, start=1):
        body = line.split("#", 1)[0].strip()
        if body:
            yield number, body


def _editor_lines(text: str) -> list[str]:
    """``text`` cut into the lines an editor counts: at ``\\n``, ``\\r\\n`` and ``\\r`` alone.
    ``str.splitlines`` also cuts at a form feed, a vertical tab, ``\\x1c``-``\\x1e``, ``\\x85``,
    ``\\u2028`` and ``\\u2029``, so every message after one would name a line too far on
    (and a comment with one would go on as a data line). A final line break ends the last
    line; it does not begin an empty one (as with ``str.splitlines``)."""
    lines = _LINE_BREAK.split(text)
    if lines and lines[-1] == "":
        lines.pop()
    return lines


def _floats(line: str) -> bool:
    """Whether ``line`` is blank-separated numbers that ``float`` reads."""
    try:
        [float(f) for f in line.split()]
    except ValueError:
        return False
    return True


def _ascii_numbers(lines: list[str], path: Path, first: int = 0) -> None:
    """Refuse a data line (from index ``first``, before a ``#``) with characters that are
    not ASCII numbers: ``float`` reads '٠.١' (Arabic-Indic digits) and '1_0' as numbers, so a
    record in another script, or with a typo, would run as a different record."""
    for number, line in enumerate(lines[first:], start=first + 1):
        body = line.split("#", 1)[0]
        if not _DATA_LINE.fullmatch(body):
            raise InputError(f"motion file {str(path)!r} line {number}: {body.strip()[:60]!r} "
                             "is not numbers written in the digits 0-9")


def _parse_columns(text: str, path: Path, dt: float | None) -> tuple[float, np.ndarray]:
    rows, lines = [], []
    text_lines = _editor_lines(text)
    _ascii_numbers(text_lines, path)
    for number, body in _data_rows(text_lines):
        fields = body.replace(",", " ").split()
        try:
            rows.append([float(f) for f in fields])
        except ValueError:
            raise InputError(f"motion file {str(path)!r} line {number}: {body!r} "
                             "is not numbers") from None
        lines.append(number)
    if not rows:
        raise InputError(f"motion file {str(path)!r}: no data rows")
    width = len(rows[0])
    for row, number in zip(rows, lines):
        if len(row) != width:
            raise InputError(f"motion file {str(path)!r} line {number}: {len(row)} columns, "
                             f"but the first data row has {width}")
    if width not in (1, 2):
        raise InputError(f"motion file {str(path)!r}: {width} columns; expected 2 "
                         "(time [s], acceleration [g]) or 1 (acceleration [g], with dt given)")
    data = np.array(rows)
    _refuse_nan(data, path, lines)
    if width == 1:
        if dt is None:
            raise InputError(f"motion file {str(path)!r} has one column: give its dt "
                             "(motion.dt in the scene)")
        return positive("motion.dt", dt), data[:, 0]
    step = _uniform_step(data[:, 0], path, lines)
    _no_dt(dt, step, path)
    _say_if_shifted(data[0, 0], step, path, lines[0])
    return step, data[:, 1]


def _say_if_shifted(start: float, step: float, path: Path, line: int) -> None:
    """Say when a record's times do not start at 0 s: upliftlab's record starts with its first
    sample at 0 s (a motion is samples at a uniform step), so its times are shifted by
    ``-start`` (s). Said once per file read (the parse is cached)."""
    if abs(start) > 1e-9 * step:
        from .log import logger

        logger("motions").warning(
            f"upliftlab: note: motion file {str(path)!r} line {line}: its times start at "
            f"{start:g} s; the record starts at 0 s with this sample (its times shifted by "
            f"{-start:g} s)")


def _no_dt(dt: float | None, step: float, path: Path) -> None:
    """A file that gives its own step takes no ``motion.dt``: it would be ignored."""
    if dt is not None:
        raise InputError(f"motion.dt = {dt:g}: motion file {str(path)!r} gives its own time "
                         f"step ({step:g} s); motion.dt is for one-column files only (remove it)")


def _refuse_nan(data: np.ndarray, path: Path, lines: list[int]) -> None:
    bad = np.argwhere(~np.isfinite(data))
    if bad.size:
        row = bad[0][0]
        raise InputError(f"motion file {str(path)!r} line {lines[row]}: value "
                         f"{data[row, bad[0][1]]} is not a finite number")


def _uniform_step(time: np.ndarray, path: Path, lines: list[int]) -> float:
    if time.size < 2:
        raise InputError(f"motion file {str(path)!r}: needs at least two samples")
    steps = np.diff(time)
    back = np.flatnonzero(~(steps > 0))
    if back.size:
        # a repeated or earlier time: the row it is on is the one at fault, not its neighbour
        i = back[0]
        raise InputError(f"motion file {str(path)!r} line {lines[i + 1]}: time {time[i + 1]:g} s "
                         f"does not increase (the row before has {time[i]:g} s)")
    step = (time[-1] - time[0]) / (time.size - 1)
    if np.any(_off_step(steps, step)):
        i, typical = _first_odd_step(steps, step)
        raise InputError(
            f"motion file {str(path)!r} line {lines[i + 1]}: time step {steps[i]:g} s (from "
            f"the row before) differs from the file's {typical}; the time step must be uniform")
    in_range(f"motion file {str(path)!r} line {lines[1]}: the file's time step dt", step,
             KINDS["step"].low, KINDS["step"].high)
    return float(step)


def _off_step(steps: np.ndarray, step: float) -> np.ndarray:
    """Which ``steps`` (s) differ from ``step`` (s) by more than the tolerance of a uniform
    record (:data:`_UNIFORM_DT_RTOL`, relative, and 1e-12 s)."""
    return np.abs(steps - step) > _UNIFORM_DT_RTOL * step + 1e-12


def _first_odd_step(steps: np.ndarray, mean: float) -> tuple[int, str]:
    """Index of the first of ``steps`` (s) that differs from the record's typical step, and that
    step described. The typical step is the median: one bad row moves the mean (a deleted row,
    a wrong last time), so that every step differed from it, the first one included. A record is
    accepted or refused by the mean (its step, :func:`_uniform_step`) as before; only when no
    step differs from the median (steps that drift within the tolerance) is the mean named."""
    median = float(np.median(steps))
    odd = np.flatnonzero(_off_step(steps, median))
    if odd.size:
        return int(odd[0]), f"typical step {median:g} s (the median of its steps)"
    return int(np.flatnonzero(_off_step(steps, mean))[0]), f"mean step {mean:g} s"


#: A number as a PEER header writes it: ASCII digits only (``\\d`` and ``float`` also take
#: other scripts' digits), a whole word (not the start of ``.02abc`` or ``1.2.3``).
_COUNT = r"([0-9]{1,12})(?=[\s,]|$)"
_REAL = r"([+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]{1,3})?)(?=[\s,]|$)"
_AT2_HEADER = re.compile(r"NPTS\s*=\s*" + _COUNT + r"\s*,?\s*DT\s*=\s*" + _REAL,
                         re.IGNORECASE | re.ASCII)
_AT2_HEADER_NEW = re.compile(r"^\s*" + _COUNT + r"\s+" + _REAL + r"\s+NPTS",
                             re.IGNORECASE | re.ASCII)
#: A data line of a record: ASCII numbers, separated by blanks or commas.
_DATA_LINE = re.compile(r"[0-9eE+\-., \t\r\f\v]*|.*(?:nan|inf).*", re.IGNORECASE | re.ASCII)


def _parse_at2(text: str, path: Path) -> tuple[float, np.ndarray]:
    lines = _editor_lines(text)
    if len(lines) < 5:
        raise InputError(f"motion file {str(path)!r}: too short for a PEER .AT2 record")
    header = lines[3]
    matches = [m for m in (_AT2_HEADER.search(header), _AT2_HEADER_NEW.search(header)) if m]
    if len(matches) != 1 or len(re.findall(r"NPTS", header, re.IGNORECASE)) != 1:
        raise InputError(f"motion file {str(path)!r} line 4: {header.strip()[:80]!r} does not "
                         "give NPTS and DT once each, in the digits 0-9, as a PEER .AT2 header "
                         "does (e.g. 'NPTS=  2000, DT=   .0100 SEC')")
    npts, step = int(matches[0].group(1)), float(matches[0].group(2))
    _ascii_numbers(lines, path, first=4)
    try:
        values = np.array(" ".join(lines[4:]).split(), dtype=float)
    except ValueError:
        number = next(i for i, line in enumerate(lines[4:], start=5) if not _floats(line))
        raise InputError(f"motion file {str(path)!r} line {number}: "
                         f"{lines[number - 1].strip()[:60]!r} is not numbers") from None
    if values.size != npts:
        raise InputError(f"motion file {str(path)!r} line 4: the header says NPTS={npts} but "
                         f"lines 5-{len(lines)} hold {values.size} values")
    if not np.all(np.isfinite(values)):
        i = int(np.flatnonzero(~np.isfinite(values))[0])
        raise InputError(f"motion file {str(path)!r} line {_at2_value_lines(lines)[i]}: value "
                         f"{values[i]} is not a finite number")
    low, high = KINDS["step"].low, KINDS["step"].high
    return in_range(f"motion file {str(path)!r} line 4: DT", step, low, high), values


def _at2_value_lines(lines: list[str]) -> np.ndarray:
    """The line (1-based) of each value of a PEER .AT2 record's ``lines``: its values are read
    from line 5 on, several a line."""
    counts = [len(line.split()) for line in lines[4:]]
    return np.repeat(np.arange(5, 5 + len(counts)), counts)


def free_vibration(duration: float, dt: float = 0.01, *, velocity: float = 0.0,
                   displacement: float = 0.0, rotation: float = 0.0) -> Motion:
    """No ground motion; the structure starts from the given state (length/s, length, rad)."""
    positive("motion.duration", duration)
    positive("motion.dt", dt)
    if velocity == 0.0 and displacement == 0.0 and rotation == 0.0:
        raise InputError("free vibration needs a nonzero motion.velocity, motion.displacement "
                         "or motion.rotation")
    n = _sample_count(duration, dt)
    return Motion(name="free", dt=dt, acceleration=np.zeros(n), initial_velocity=velocity,
                  initial_displacement=displacement, initial_rotation=rotation,
                  source=f"builtin:free(v0={velocity:g}, x0={displacement:g}, "
                         f"theta0={rotation:g})")


def _pulse_samples(duration: float, dt: float) -> np.ndarray:
    positive("motion.duration", duration)
    positive("motion.dt", dt)
    return np.arange(_sample_count(duration, dt)) * dt


def sine_pulse(amplitude: float, period: float, cycles: float = 1.0, *,
               duration: float | None = None, dt: float = 0.005) -> Motion:
    """``a(t) = A sin(2πt/T)`` for ``0 ≤ t ≤ cycles·T``, then zero. A in g, T in s."""
    return _trig_pulse(np.sin, "sine", amplitude, period, cycles, duration, dt)


def cosine_pulse(amplitude: float, period: float, cycles: float = 1.0, *,
                 duration: float | None = None, dt: float = 0.005) -> Motion:
    """``a(t) = A cos(2πt/T)`` for ``0 ≤ t ≤ cycles·T``, then zero. A in g, T in s."""
    return _trig_pulse(np.cos, "cosine", amplitude, period, cycles, duration, dt)


def _trig_pulse(fn, kind, amplitude, period, cycles, duration, dt) -> Motion:
    finite("motion.amplitude", amplitude)
    positive("motion.period", period)
    positive("motion.cycles", cycles)
    length = cycles * period
    duration = max(duration if duration is not None else 4.0 * length, length)
    t = _pulse_samples(duration, dt)
    acc = np.where(t <= length + 1e-12, amplitude * fn(2.0 * np.pi * t / period), 0.0)
    return Motion(name=f"{kind}_pulse", dt=dt, acceleration=acc,
                  source=f"builtin:{kind}(A={amplitude:g} g, T={period:g} s, cycles={cycles:g})")


def ricker_pulse(amplitude: float, period: float, *, duration: float | None = None,
                 dt: float = 0.005, delay: float | None = None) -> Motion:
    """Ricker wavelet of peak A (g) and central period T = 1/f_p (s), centred at ``delay``.

    ``a(t) = A (1 − 2π²f²τ²) exp(−π²f²τ²)``, ``τ = t − delay``; the delay defaults to 1.5 T.
    """
    finite("motion.amplitude", amplitude)
    positive("motion.period", period)
    delay = 1.5 * period if delay is None else nonnegative("motion.delay", delay)
    duration = duration if duration is not None else 2.0 * delay + 3.0 * period
    t = _pulse_samples(duration, dt)
    arg = (np.pi * (t - delay) / period) ** 2
    acc = amplitude * (1.0 - 2.0 * arg) * np.exp(-arg)
    return Motion(name="ricker_pulse", dt=dt, acceleration=acc,
                  source=f"builtin:ricker(A={amplitude:g} g, T={period:g} s, delay={delay:g} s)")


def harmonic(amplitude: float, period: float, duration: float, *, dt: float = 0.005) -> Motion:
    """Steady harmonic ``a(t) = A sin(2πt/T)`` over the whole ``duration``. A in g, T in s."""
    finite("motion.amplitude", amplitude)
    positive("motion.period", period)
    t = _pulse_samples(duration, dt)
    acc = amplitude * np.sin(2.0 * np.pi * t / period)
    return Motion(name="harmonic", dt=dt, acceleration=acc,
                  source=f"builtin:harmonic(A={amplitude:g} g, T={period:g} s)")


def motion_checksum(motion: Motion) -> str:
    """SHA-256 of what a run was driven by: the record file's bytes when the motion was read
    from a file, else the samples and their step (a built-in motion)."""
    import hashlib

    path = Path(motion.source) if motion.source and not motion.source.startswith("builtin:") \
        else None
    if path is not None and path.is_file():
        return hashlib.sha256(path.read_bytes()).hexdigest()
    digest = hashlib.sha256(np.ascontiguousarray(motion.acceleration, dtype=float).tobytes())
    digest.update(repr(float(motion.dt)).encode())
    return digest.hexdigest()
