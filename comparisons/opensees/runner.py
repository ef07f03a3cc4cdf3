"""Run the standalone OpenSees script in a subprocess, with a timeout, and read what it wrote.

openseespy lives in a subprocess: its global state and its ``exit()`` on some errors can then
never touch the caller, and a run that hangs is ended at the timeout. The child's progress
lines (stderr) are passed through as they come.
"""

from __future__ import annotations

import contextlib
import csv
import importlib.util
import json
import os
import re
import subprocess
import sys
import threading
import time
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...checks import InputError
from ...log import logger
from ...paths import remove_stale_temporaries
from ...workers import dying_with_this_process
from .model_script import NO_SPACE_EXIT  # the script's exit code for a full disk

__all__ = ["RUN_OUTPUTS", "OPENSEES_EXTRA", "OpenSeesRun", "OpenSeesError", "opensees_available",
           "require_opensees", "run_script"]

OPENSEES_EXTRA = 'pip install "upliftlab[opensees]"'
_PROBE = ("import importlib.util, os, ctypes\n"
          "try:\n    import openseespy.opensees\n"
          "except Exception:\n"
          "    s = importlib.util.find_spec('openseespylinux')\n"
          "    lib = os.path.join(list(s.submodule_search_locations)[0], 'lib', 'libblas.so.3')\n"
          "    ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)\n"
          "    import openseespy.opensees\n")


class OpenSeesError(RuntimeError):
    """The OpenSees run failed, timed out or wrote nothing readable."""


@dataclass(frozen=True)
class OpenSeesRun:
    """What the script wrote: its ``summary`` (the peaks, ``runtime_s`` of the time-step loop,
    ``setup_s``), its ``histories`` (columns by name, each an array over time) and the ``wall``
    time of the whole subprocess (s)."""

    summary: dict
    histories: dict = field(repr=False)
    wall: float = 0.0


def opensees_available() -> bool:
    """True when openseespy imports here (a subprocess tries, with the same fallback for its
    BLAS as the script's), False when it is missing or broken."""
    if importlib.util.find_spec("openseespy") is None:
        return False
    try:
        probe = subprocess.run(dying_with_this_process([sys.executable, "-c", _PROBE]),
                               capture_output=True, text=True, timeout=120,
                               env=_environment())
    except subprocess.TimeoutExpired:
        return False
    return probe.returncode == 0


def require_opensees() -> None:
    """Raise :class:`InputError` (one line naming the extra) unless openseespy imports."""
    if not opensees_available():
        raise InputError(f"openseespy is not installed or does not import: {OPENSEES_EXTRA}")


def _environment() -> dict:
    return dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")


def _relay(stream, keep: deque, echo: bool) -> None:
    for line in stream:
        keep.append(line.rstrip("\n"))
        if echo:
            logger("opensees").info(line.rstrip("\n"))


#: The files the OpenSees script writes beside itself when it runs.
RUN_OUTPUTS = ("opensees_summary.json", "opensees_histories.csv")


def run_script(script: str | Path, *, timeout: float = 3600.0, echo: bool = True) -> OpenSeesRun:
    """Run ``script`` (``python model.py`` in its folder) and read its two output files.

    Raises :class:`OpenSeesError` when it times out, exits non-zero, or its summary says the
    run did not complete.
    """
    script = Path(script).resolve()
    folder = script.parent
    outputs = RUN_OUTPUTS
    before = {name: _stamp(folder / name) for name in outputs}  # never read a previous run's
    for name in outputs:  # the temporaries of a run that was killed while it wrote them
        remove_stale_temporaries(folder / name)
    start = time.perf_counter()
    child = subprocess.Popen(dying_with_this_process([sys.executable, script.name]),
                             cwd=folder, env=_environment(), stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    tail: deque = deque(maxlen=20)
    relay = threading.Thread(target=_relay, args=(child.stderr, tail, echo), daemon=True)
    relay.start()
    try:
        child.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        _end(child, folder)
        raise OpenSeesError(f"OpenSees run of {script} timed out after {timeout:g} s "
                            "(--timeout)") from None
    except BaseException:  # an interruption (Ctrl-C, SIGTERM): the run ends with this one
        _end(child, folder)
        raise
    relay.join(timeout=5)
    child.stdout.close()
    wall = time.perf_counter() - start
    summary_path = folder / RUN_OUTPUTS[0]
    no_space = _no_space(tail) if child.returncode == NO_SPACE_EXIT else None
    if no_space is not None:
        raise no_space
    if any(_stamp(folder / name) in (None, before[name]) for name in outputs):
        last = next((line for line in reversed(tail) if line.strip()), "no message")
        raise OpenSeesError(f"OpenSees run of {script} exited with code {child.returncode} "
                            f"and did not write both its outputs: {last[:300]}")
    try:
        summary = json.loads(summary_path.read_text())
    except (OSError, ValueError) as exc:
        raise OpenSeesError(f"OpenSees run of {script}: its summary {summary_path.name} cannot "
                            f"be read ({exc})") from None
    if child.returncode != 0 or summary.get("verdict") != "completed":
        raise OpenSeesError(f"OpenSees run of {script}: {summary.get('verdict')} "
                            f"(exit code {child.returncode})")
    return OpenSeesRun(summary, read_histories(folder / RUN_OUTPUTS[1]), wall)


_NO_SPACE_LINE = re.compile(r"^opensees: no space left on device writing (.*) \(errno (\d+): ")


def _no_space(tail) -> OSError | None:
    """The OSError of a run whose results found no room, its errno and file from the script's
    line that says so (the command's own line for a full disk follows, exit 3); None if no
    line of the run's last says so (a script that exits 3 for another reason)."""
    for line in reversed(tail):
        found = _NO_SPACE_LINE.match(line)
        if found:
            code = int(found.group(2))
            return OSError(code, os.strerror(code), found.group(1))
    return None


def _end(child: subprocess.Popen, folder: Path) -> None:
    """End the OpenSees run ``child`` now, reap it, and remove the temporary file it was
    writing, if any. Reaped with ``os.waitpid`` when ``Popen.wait`` cannot: an interruption
    that lands in ``Popen.wait`` just after it took its internal lock and before its ``try``
    leaves the lock held, and a second ``wait`` would then block for ever."""
    child.kill()
    try:
        child.wait(timeout=5.0)
    except subprocess.TimeoutExpired:  # Popen's lock left held: reap the child directly
        with contextlib.suppress(ChildProcessError):
            os.waitpid(child.pid, 0)
    for name in RUN_OUTPUTS:
        remove_stale_temporaries(folder / name)


def _stamp(path: Path) -> tuple[int, int, int] | None:
    """(inode, size, modification time in ns) of ``path``, or None if it is absent: a file the
    run did not write keeps its stamp (files already there are left alone, not removed)."""
    try:
        st = path.stat()
    except FileNotFoundError:
        return None
    return st.st_ino, st.st_size, st.st_mtime_ns


def read_histories(path: Path) -> dict:
    """The script's CSV: comment lines, a header, then one row per step."""
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    names, data = rows[0], np.array(rows[1:], dtype=float)
    return {name: data[:, i] for i, name in enumerate(names)}
