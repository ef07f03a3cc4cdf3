"""The fuzz test's harm classes that are not inputs (``tests/test_fuzz.py`` fuzzes the inputs):
a full disk, a signal at every phase of a run, and concurrent runs. Each is driven through the
command line in a child process, through more than one subcommand or moment.

The rule each case is held to (issue 37, "trusted on every path"):

* **a full disk** (a file-size limit, RLIMIT_FSIZE, with SIGXFSZ ignored so that a write gets
  EFBIG as it gets ENOSPC on a full disk: no root needed) ends with exactly one line
  ``upliftlab: error: no space left on device ...`` and exit 3, never a crash of HDF5 (before:
  a segmentation fault, exit -11, and on a full tmpfs a part file and the lock left behind), and
  leaves no part file and no lock;
* **a signal** (Ctrl-C to the whole process group, SIGTERM to the command, SIGKILL) at any
  moment ends every process the command started; Ctrl-C and SIGTERM end it with exit 130 and
  one line, the last, that names the command resuming it, no traceback; what was computed is
  kept: a study's stored points, a continuum run's rows (in the time loop: the rows so far,
  marked incomplete; after it: the whole run);
* **concurrent runs** never mix: a second command into a folder a live run holds is refused in
  one line (exit 2) and the first run's result is unaffected.

Reference: the rule itself; the continuum's kept rows are compared with an uninterrupted run of
the same command (equal to 1e-12 rad: the same arithmetic, step by step).
"""

from __future__ import annotations

import json
import os
import resource
import signal
import subprocess
import sys
import threading
import time
import uuid
from pathlib import Path

import numpy as np
import pytest

from upliftlab.results import read_netcdf

SMALL_BOX = ["--set", "continuum.elements_across=4", "--set", "continuum.domain_width=3",
             "--set", "continuum.domain_depth=3"]
RUN = ["run", "wall_free", "--case", "e07", "--set", "analysis.duration=0.2", "--no-figure"]
PUSHOVER = ["continuum", "strip_footing_clay", *SMALL_BOX, "--steps", "3", "--no-render"]
DYNAMIC = ["continuum", "strip_footing_clay", "--analysis", "dynamic", *SMALL_BOX,
           "--set", "analysis.duration=0.3", "--no-render"]
STUDY = ["study", "two_spring_equivalence", "--fast", "--no-figures", "--workers", "2"]
#: The marker each child's environment carries, inherited by every process it starts.
TAG = "UPLIFTLAB_FUZZ_TAG"


def _env(tag: str = "") -> dict:
    return {**os.environ, "MPLBACKEND": "Agg", TAG: tag}


def _leftovers(folder: Path) -> list[str]:
    """Part files and locks under ``folder``: what no ending of a command may leave."""
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*")
                  if p.name.endswith(".part") or p.name == ".upliftlab.lock")


def _final_line(stderr: str, start: str) -> str:
    """The one line of ``stderr`` that begins with ``start``; it must be the last, and no
    traceback may come before it."""
    lines = [line for line in stderr.splitlines() if line.strip()]
    mine = [line for line in lines if line.startswith(("upliftlab: error:",
                                                       "upliftlab: interrupted"))]
    assert "Traceback" not in stderr, stderr[-3000:]
    assert len(mine) == 1 and lines[-1] == mine[0] and mine[0].startswith(start), lines[-5:]
    return mine[0]


# ---------------------------------------------------------------------------------------------
# A full disk
# ---------------------------------------------------------------------------------------------

def _limited(limit: int):
    def start():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return start


def _cli(argv, cwd, limit: int | None = None, timeout: float = 600):
    return subprocess.run([sys.executable, "-m", "upliftlab", *argv], cwd=cwd, env=_env(),
                          capture_output=True, text=True, timeout=timeout,
                          preexec_fn=_limited(limit) if limit else None)


@pytest.mark.parametrize("command", ["run", "pushover", "opensees"])
def test_a_full_disk_ends_in_one_line_with_exit_3_and_leaves_nothing_half_written(
        command, tmp_path):
    """Each command first runs unlimited (which also fills the compiled-code cache, which a
    limit would stop); then with a file-size limit of half its largest file (its result file
    fails), and of 1 byte (the folder's lock fails): exit 3, one line, no part file, no lock,
    and no completion marker."""
    argv = {"run": RUN, "pushover": PUSHOVER,
            "opensees": ["opensees", "wall_free", "--case", "e10"]}[command]
    whole = _cli([*argv, "--out", "whole"], tmp_path)
    assert whole.returncode == 0, whole.stderr[-2000:]
    largest = max(p.stat().st_size for p in (tmp_path / "whole").iterdir())
    for limit in sorted({largest // 2, 1}):
        out = tmp_path / f"limit{limit}"
        done = _cli([*argv, "--out", out.name], tmp_path, limit=limit)
        line = _final_line(done.stderr, "upliftlab: error: no space left on device")
        assert done.returncode == 3, (limit, line)
        assert not out.exists() or (_leftovers(out) == []
                                    and not (out / "upliftlab-run.json").exists()), limit


def test_hdf5_files_meet_a_full_disk_as_an_os_error(tmp_path):
    """The writers of HDF5 files (NetCDF through xarray, XDMF's .h5 through meshio) under a
    file-size limit in a child: an OSError (EFBIG) that the caller sees, the temporary files
    removed, instead of HDF5 ending the process (before: a segmentation fault)."""
    code = f"""
import errno, os, sys
import numpy as np, xarray as xr
from upliftlab.results import write_dataset
folder = {str(tmp_path)!r}
try:
    write_dataset(os.path.join(folder, "big.nc"),
                  xr.Dataset({{"a": ("x", np.random.default_rng(1).random(200_000))}}))
except OSError as exc:
    print("netcdf", exc.errno == errno.EFBIG)
from upliftlab.continuum.output import xdmf
axis = xdmf.TimeAxis(np.array([0.0]), "time", "s", "time")
points = np.random.default_rng(2).random((30_000, 2))
try:
    xdmf._write_series(os.path.join(folder, "f.xdmf"), points,
                       [("vertex", np.arange(30_000).reshape(-1, 1))],
                       [({{"u": points}}, {{}})], axis, [])
except OSError as exc:
    print("xdmf", exc.errno == errno.EFBIG)
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=_env(), preexec_fn=_limited(100_000), timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split() == ["netcdf", "True", "xdmf", "True"]
    assert sorted(p.name for p in tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------------------------
# Signals: every process the command started ends; what was computed is kept
# ---------------------------------------------------------------------------------------------

def _tagged(tag: str) -> list[int]:
    """Running processes (not zombies) whose environment carries ``tag``."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/environ", "rb") as fh:
                if f"{TAG}={tag}".encode() not in fh.read().split(b"\0"):
                    continue
            with open(f"/proc/{entry}/stat") as fh:
                if fh.read().rsplit(")", 1)[1].split()[0] != "Z":
                    found.append(int(entry))
        except OSError:
            continue
    return found


def _as_from_a_terminal() -> None:
    """The command starts with Ctrl-C's default disposition, as from a user's terminal: a test
    run started in the background of a non-interactive shell ignores SIGINT (POSIX), and the
    command would inherit that and, rightly, not stop on Ctrl-C."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _interrupt(argv, cwd, when, how: str, timeout: float = 600, wait: float = 120,
               tag: str = ""):
    """Start ``upliftlab argv`` in a session of its own; when ``when(child pids, stderr so
    far)`` is true, signal it (``how``: ``ctrl-c`` SIGINT to the process group, ``term``
    SIGTERM to the command, ``kill`` SIGKILL to it); return (exit code, stderr, the tag of its
    processes, ``tag`` if given). A command still running ``wait`` s after the signal fails
    the test (and is killed)."""
    tag = tag or uuid.uuid4().hex
    proc = subprocess.Popen([sys.executable, "-m", "upliftlab", *argv], cwd=cwd,
                            env=_env(tag), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True, start_new_session=True, preexec_fn=_as_from_a_terminal)
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(proc.stderr), daemon=True)
    reader.start()  # the lines as they come (the pipe closes only when every holder ends)
    deadline = time.monotonic() + timeout
    while proc.poll() is None and time.monotonic() < deadline:
        if when([p for p in _tagged(tag) if p != proc.pid], "".join(lines)):
            break
        time.sleep(0.01)
    assert proc.poll() is None, f"the command ended before the signal: {''.join(lines)[-2000:]}"
    if how == "ctrl-c":
        os.killpg(proc.pid, signal.SIGINT)
    else:
        proc.send_signal(signal.SIGTERM if how == "term" else signal.SIGKILL)
    try:
        proc.wait(timeout=wait)
    except subprocess.TimeoutExpired:
        for pid in _tagged(tag):
            os.kill(pid, signal.SIGKILL)
        pytest.fail(f"{how}: the command still ran {wait} s after the signal")
    reader.join(timeout=120)
    if reader.is_alive():
        survivors = _tagged(tag)
        for pid in survivors:
            os.kill(pid, signal.SIGKILL)
        pytest.fail(f"{how}: processes {survivors} held the command's pipe for 120 s")
    err = "".join(lines)
    return proc.returncode, err, tag


def _gone(tag: str, within: float = 20.0) -> list[int]:
    """The processes of ``tag`` still running after ``within`` s (killed then, and returned)."""
    deadline = time.monotonic() + within
    while _tagged(tag) and time.monotonic() < deadline:
        time.sleep(0.2)
    survivors = _tagged(tag)
    for pid in survivors:
        os.kill(pid, signal.SIGKILL)
    return survivors


def _workers(n: int):
    """When ``n`` worker processes have been spawned (they may still be starting)."""
    def when(children, err):
        return sum(1 for p in children if b"spawn_main" in _cmdline(p)) >= n
    return when


def _cmdline(pid: int) -> bytes:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as fh:
            return fh.read()
    except OSError:
        return b""


def _stored(store: Path, n: int):
    """When the study's store holds ``n`` points."""
    def when(children, err):
        return store.is_dir() and len([p for p in store.rglob("*.json")]) >= n
    return when


@pytest.mark.parametrize("moment, how", [("first worker starting", "term"),
                                         ("first worker starting", "kill"),
                                         ("second worker starting", "ctrl-c"),
                                         ("points stored", "ctrl-c"),
                                         ("points stored", "term")])
def test_an_interrupted_study_ends_every_process_it_started(moment, how, tmp_path):
    """A study's sweep on two worker processes, interrupted while its workers start or once
    points are stored: no process it started survives (before: a worker that was starting when
    its parent went lived on forever, holding the caller's pipe); Ctrl-C and SIGTERM end in
    one line naming the resume command, exit 130, no traceback; the stored points are kept,
    each a whole record."""
    out = tmp_path / "study"
    when = {"first worker starting": _workers(1), "second worker starting": _workers(2),
            "points stored": _stored(out / "store", 2)}[moment]
    code, err, tag = _interrupt([*STUDY, "--out", str(out)], tmp_path, when, how)
    assert _gone(tag) == []
    assert _leftovers(tmp_path) == [] or how == "kill"
    if how == "kill":
        assert code == -signal.SIGKILL
        return
    line = _final_line(err, "upliftlab: interrupted")
    assert code == 130 and f"resume with: upliftlab {' '.join(STUDY)}" in line
    records = list((out / "store").rglob("*.json")) if (out / "store").is_dir() else []
    assert all(json.loads(p.read_text()) for p in records)
    assert (moment != "points stored") or len(records) >= 2


def test_an_ended_pool_leaves_no_thread_for_the_interpreters_exit_to_wake():
    """The traceback once printed after an interrupted study's line ("Exception ignored in
    <module 'threading'> … OSError: Bad file descriptor"): CPython 3.11's exit wakes every
    process pool's manager thread through a pipe that the thread, still ending, may be
    closing. After :func:`upliftlab.workers.process_pool`'s block ends in an exception (its
    two workers busy, then terminated), that thread has ended, three times in three, so the
    exit finds the pipe closed. (Reference: the thread's own state; before the fix it was
    still alive after 3 of 6 such blocks.)"""
    from upliftlab.workers import process_pool

    managers = []
    for _ in range(3):
        with pytest.raises(RuntimeError):
            with process_pool(2) as pool:
                pool.submit(time.sleep, 30.0)
                pool.submit(time.sleep, 30.0)
                managers.append(pool._executor_manager_thread)
                time.sleep(1.0)  # the workers spawned and sleeping
                raise RuntimeError("an interruption")
    assert [m.is_alive() for m in managers] == [False, False, False]


def _line(text: str):
    """When stderr has a line containing ``text``."""
    return lambda children, err: text in err


@pytest.fixture(scope="module")
def whole_dynamic(tmp_path_factory):
    """The uninterrupted dynamic run's result.nc (the reference of the kept rows)."""
    folder = tmp_path_factory.mktemp("whole")
    done = _cli([*DYNAMIC, "--out", "whole"], folder)
    assert done.returncode == 0, done.stderr[-2000:]
    return read_netcdf(folder / "whole" / "result.nc")


@pytest.mark.parametrize("moment, how", [("model built", "term"), ("in the loop", "term"),
                                         ("in the loop", "ctrl-c"), ("loop ended", "term"),
                                         ("writing", "ctrl-c")])
def test_an_interrupted_continuum_run_keeps_what_it_computed(moment, how, tmp_path,
                                                             whole_dynamic):
    """SIGTERM or Ctrl-C before, in and after the time loop and while the files are written:
    exit 130, one line, no lock, no part file, no completion marker, and result.nc holds
    what was computed: nothing before the loop; in it, rows marked incomplete that are the
    uninterrupted run's first rows; after it, the whole run (before: a traceback or
    'interrupted before any result was computed' with nothing written at the loop's end, and
    the process killed with its lock left during the writing)."""
    out = tmp_path / "dyn"
    when = {"model built": _line("DOFs, soil"), "in the loop": _line("(10%)"),
            "loop ended": _line("(100%)"), "writing": _line("dyn/result.nc")}[moment]
    code, err, tag = _interrupt([*DYNAMIC, "--out", str(out)], tmp_path, when, how)
    assert _gone(tag) == []
    line = _final_line(err, "upliftlab: interrupted")
    assert code == 130 and "resume with: upliftlab continuum strip_footing_clay" in line
    assert _leftovers(tmp_path) == [] and not (out / "upliftlab-run.json").exists()
    if moment == "model built":
        assert not (out / "result.nc").exists()
        return
    rows, attrs = read_netcdf(out / "result.nc")
    whole = whole_dynamic[0]
    n = rows["time"].size
    assert np.array_equal(rows["time"], whole["time"][:n])
    assert np.abs(rows["theta"] - whole["theta"][:n]).max() <= 1e-12
    if attrs.get("incomplete") == 1:
        assert moment == "in the loop" and 1 <= n < whole["time"].size
        assert attrs["completed_until"] == pytest.approx(rows["time"][-1], rel=1e-6)
    else:
        assert n == whole["time"].size and (out / "fields.xdmf").is_file()


# ---------------------------------------------------------------------------------------------
# Signals to the reduced model's run, at every moment from the interpreter's start to its exit
# ---------------------------------------------------------------------------------------------

#: The command's ``sitecustomize`` (on its PYTHONPATH, loaded as its interpreter starts): it
#: sends the command, once, the signal ``UPLIFTLAB_TEST_SIGNAL`` = ``<moment>:<SIGNAME>`` names,
#: at ``import:<module>`` (as the module starts loading), ``weakref:<module>`` (from inside a
#: weakref callback run then, where a raised KeyboardInterrupt is swallowed), ``commit`` (as a
#: NetCDF part file, written whole, is about to be renamed into place) or ``exit`` (from the
#: last exit handler, after ``main`` has returned): the moments no sleep hits reliably.
_SITECUSTOMIZE = """
import os, signal, sys

_moment, _name = os.environ["UPLIFTLAB_TEST_SIGNAL"].rsplit(":", 1)
_kind, _, _module = _moment.partition(":")
_fired = []


def _fire():
    if not _fired:
        _fired.append(True)
        os.kill(os.getpid(), getattr(signal, _name))
        sum(range(100))  # a call: the handler runs here


if _kind == "exit":
    import atexit
    atexit.register(_fire)
elif _kind == "commit":
    _replace = os.replace

    def _replacing(source, target, *args, **kwargs):
        if str(source).endswith(".part") and ".nc." in str(source):
            _fire()
        return _replace(source, target, *args, **kwargs)

    os.replace = _replacing
else:
    class _Finder:
        def find_spec(self, fullname, path=None, target=None):
            if fullname == _module and not _fired:
                if _kind == "weakref":
                    import weakref

                    class _Thing:
                        pass

                    thing = _Thing()
                    ref = weakref.ref(thing, lambda r: _fire())
                    del thing
                else:
                    _fire()
            return None

    sys.meta_path.insert(0, _Finder())
"""


def _signalled(argv, tmp_path, at: str, script: bool = False):
    """``upliftlab argv`` (``script``: through its console script, else ``python -m``) in
    ``tmp_path``, sent the signal ``at`` names (:data:`_SITECUSTOMIZE`); its finished
    process."""
    hooks = tmp_path / "hooks"
    hooks.mkdir(exist_ok=True)
    (hooks / "sitecustomize.py").write_text(_SITECUSTOMIZE)
    env = {**_env(), "PYTHONPATH": os.pathsep.join(
        [str(hooks), *filter(None, [os.environ.get("PYTHONPATH")])]),
        "UPLIFTLAB_TEST_SIGNAL": at}
    start = ([str(Path(sys.executable).with_name("upliftlab"))] if script
             else [sys.executable, "-m", "upliftlab"])
    return subprocess.run([*start, *argv], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=300, preexec_fn=_as_from_a_terminal)


@pytest.mark.parametrize("name, script", [("SIGINT", True), ("SIGTERM", True),
                                          ("SIGINT", False), ("SIGTERM", False)])
def test_a_signal_while_the_command_loads_numpy_ends_it_in_one_line(name, script, tmp_path):
    """A signal as numpy starts loading (the first few tenths of a second of any command,
    before its ``main`` runs): one line, exit 130, nothing written (before: SIGINT printed
    the KeyboardInterrupt's traceback from the import, SIGTERM ended the process silently with
    143, as its default action)."""
    done = _signalled([*RUN, "--out", "o"], tmp_path, f"import:numpy:{name}", script)
    assert done.stderr.splitlines() == [
        f"upliftlab: interrupted ({name}); resume with: upliftlab {' '.join(RUN)} --out o"]
    assert done.returncode == 130 and not (tmp_path / "o").exists()


@pytest.mark.parametrize("name", ["SIGINT", "SIGTERM"])
def test_a_signal_as_the_command_exits_changes_nothing(name, tmp_path):
    """A signal after ``main`` has returned (the run complete, its summary printed), as the
    interpreter exits: exit 0, the summary, no traceback (before: SIGTERM killed the process,
    143, no line; SIGINT raised a KeyboardInterrupt in the exit handler)."""
    done = _signalled([*RUN, "--out", "o"], tmp_path, f"exit:{name}")
    assert done.returncode == 0, done.stderr[-2000:]
    assert "peak u =" in done.stdout and "Traceback" not in done.stderr
    assert "interrupted" not in done.stderr and "Exception ignored" not in done.stderr
    assert json.loads((tmp_path / "o" / "upliftlab-run.json").read_text())["complete"]


def test_a_signal_that_lands_in_a_weakref_callback_still_ends_the_run(tmp_path):
    """SIGTERM whose handler runs inside a weakref callback, where Python swallows what the
    handler raises (as it did from numba's caches, 3-4.5 s into a run): one line, exit 130,
    no folder claimed (before: "Exception ignored ... KeyboardInterrupt", then the run went on
    to write its result and exit 0)."""
    done = _signalled([*RUN, "--out", "o"], tmp_path, "weakref:upliftlab.cli.commands:SIGTERM")
    assert done.stderr.splitlines() == [
        f"upliftlab: interrupted (SIGTERM); resume with: upliftlab {' '.join(RUN)} --out o"]
    assert done.returncode == 130 and not (tmp_path / "o").exists()


def test_a_signal_while_the_result_is_written_lets_the_writing_finish(tmp_path):
    """Ctrl-C as the NetCDF file's part, written whole, is about to be renamed into place:
    the NetCDF file and the CSV are written, the folder is not marked complete, one line
    names them, exit 130 (before: the part file and the whole folder were removed). The file
    holds the whole run (its last time is the run's 0.2 s)."""
    done = _signalled([*RUN, "--csv", "--out", "o"], tmp_path, "commit:SIGINT")
    out = tmp_path / "o"
    line = _final_line(done.stderr, "upliftlab: interrupted")
    assert done.returncode == 130 and line == (
        "upliftlab: interrupted (SIGINT) after the run was computed; wrote wall_free-e07.csv, "
        f"wall_free-e07.nc to o, not marked complete; resume with: upliftlab {' '.join(RUN)} "
        "--csv --out o")
    # and the record of the files being written, which stays until the folder is complete:
    # the next run knows those two as upliftlab's (upliftlab.outdir.WRITING)
    assert sorted(p.name for p in out.iterdir()) == [".upliftlab-writing.json",
                                                      "wall_free-e07.csv", "wall_free-e07.nc"]
    rows, _ = read_netcdf(out / "wall_free-e07.nc")
    assert rows["time"][-1] == pytest.approx(0.2)


#: A run whose compiled time loop would take about 13 minutes (3e8 steps of RK4).
ENDLESS = ["run", "wall_free", "--case", "e07", "--integrator", "rk4", "--dt", "1e-8",
           "--set", "analysis.max_steps=1e9", "--budget", "1e6", "--no-figure", "--verbose"]


def _cpu_seconds(pids) -> float:
    """The CPU time (user and system, s) the processes ``pids`` have used."""
    total = 0
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat") as fh:
                fields = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        total += int(fields[11]) + int(fields[12])
    return total / os.sysconf("SC_CLK_TCK")


def _in_the_loop(tag: str, text: str, seconds: float = 2.0):
    """When stderr has ``text`` (the line the run logs before it loads its compiled loop) and
    the command's processes (``tag``) have used ``seconds`` of CPU since: past loading the
    kernel from numba's cache (well under a second of CPU), in the loop."""
    seen: list[float] = []

    def when(children, err):
        if text not in err:
            return False
        used = _cpu_seconds(_tagged(tag))
        seen[:] = seen or [used]
        return used - seen[0] >= seconds
    return when


@pytest.mark.parametrize("how", ["ctrl-c", "term"])
def test_a_signal_in_the_compiled_time_loop_ends_the_run_at_once(how, tmp_path):
    """Ctrl-C or SIGTERM with the compiled time loop running (2 s of CPU after its --verbose
    line): the run ends there, one line, exit 130, no process left, the folder it created
    removed (before: the loop held the signal off until its end, minutes later here, 14 s
    later in the review's run)."""
    out, tag = tmp_path / "long", uuid.uuid4().hex
    code, err, tag = _interrupt([*ENDLESS, "--out", str(out)], tmp_path,
                                _in_the_loop(tag, "rk4: dt = 1e-08 s"), how, wait=60, tag=tag)
    assert _gone(tag) == []
    line = _final_line(err, "upliftlab: interrupted")
    name = "SIGINT" if how == "ctrl-c" else "SIGTERM"
    assert code == 130 and line == (f"upliftlab: interrupted ({name}); resume with: "
                                    f"upliftlab {' '.join(ENDLESS)} --out {out}")
    assert not out.exists() and _leftovers(tmp_path) == []


# ---------------------------------------------------------------------------------------------
# Concurrent runs
# ---------------------------------------------------------------------------------------------

def test_a_second_run_into_a_folder_a_live_run_holds_is_refused_in_one_line(tmp_path):
    """While a dynamic run writes into ``held``, the same and another command into ``held``
    are refused (one line, exit 2) and a run into another folder completes; the first run,
    interrupted, leaves its folder unlocked, and the next run completes there."""
    held = tmp_path / "held"
    tag = uuid.uuid4().hex
    long = [*DYNAMIC, "--set", "analysis.duration=60"]  # about 10 s of solving
    first = subprocess.Popen([sys.executable, "-m", "upliftlab", *long, "--out", str(held)],
                             cwd=tmp_path, env=_env(tag), stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    for line in first.stderr:
        if "DOFs, soil" in line:
            break
    # Stopped, the first run stays alive and holds its lock however long the checks take:
    # a faster machine cannot finish it before them (it did on CI, with 3 s of motion).
    first.send_signal(signal.SIGSTOP)
    try:
        assert (held / ".upliftlab.lock").read_text().strip() == str(first.pid)
        for argv in (DYNAMIC, RUN):
            refused = _cli([*argv, "--out", str(held)], tmp_path)
            line = _final_line(refused.stderr, "upliftlab: error:")
            assert refused.returncode == 2 and "another upliftlab run is writing to it" in line
        beside = _cli([*RUN, "--out", "beside"], tmp_path)
        assert beside.returncode == 0, beside.stderr[-2000:]
    finally:
        first.send_signal(signal.SIGTERM)
        first.send_signal(signal.SIGCONT)
    rest = first.communicate(timeout=300)[1]
    assert first.returncode in (0, 130), rest[-2000:]
    assert _gone(tag) == [] and _leftovers(held) == []
    again = _cli([*RUN, "--out", str(held), "--force"], tmp_path)
    assert again.returncode == 0, again.stderr[-2000:]
    assert json.loads((held / "upliftlab-run.json").read_text())["complete"]


_CAUGHT_IN_EXEC = """
import os, signal, sys
from upliftlab.cli.exits import forget_handled_interrupt

def stop(signum, frame):
    raise KeyboardInterrupt("SIGTERM")

signal.signal(signal.SIGTERM, stop)
try:  # the interruption leaves code exec ran from a string, and is caught
    exec("import os, signal\\nos.kill(os.getpid(), signal.SIGTERM)\\nfor i in range(9): pass")
except KeyboardInterrupt:
    print("upliftlab: interrupted (SIGTERM)", file=sys.stderr)
if {forget}:
    forget_handled_interrupt(130)
raise SystemExit(130)
"""


@pytest.mark.parametrize("forget", [False, True])
def test_an_interruption_caught_after_exec_ends_a_module_run_with_130(forget, tmp_path):
    """``python -m`` of a module that catches a KeyboardInterrupt raised inside code ``exec``
    ran from a string (as a dataclass's methods are made while a module is imported) and
    exits 130: CPython 3.11 kills it with SIGINT at the end (-2, the reference: the
    interpreter's own behaviour, shown by the run without the mend), unless the command
    clears the mark (:func:`upliftlab.cli.exits.forget_handled_interrupt`), as ``python -m
    upliftlab`` does (before: the CI's run of the continuum interrupted just after its model
    was built ended with -2 once in ~1,700 tests)."""
    (tmp_path / "caught_in_exec.py").write_text(_CAUGHT_IN_EXEC.format(forget=forget))
    done = subprocess.run([sys.executable, "-m", "caught_in_exec"], cwd=tmp_path, env=_env(),
                          capture_output=True, text=True, timeout=120)
    assert done.stderr.strip() == "upliftlab: interrupted (SIGTERM)"
    assert done.returncode == (130 if forget else -signal.SIGINT)


CALIBRATE = ["calibrate", "strip_footing_clay", "--mesh", "elements_across=4", "--fs-v", "3",
             "--evaluations", "10", "--set", "structure.vertical_weight=200"]


def test_an_interrupted_calibration_keeps_its_continuum_runs(tmp_path):
    """SIGTERM while the fit runs (its first progress line): exit 130, one line naming the
    command that resumes it, no lock, no part file, no completion marker, no result files;
    the store keeps the five continuum runs it made (the stiffness, the vertical pushover and
    the three rotation pushovers at FS_v 3: monotonic, cycles and repeated cycles; each a whole
    record) and the fit's
    evaluations are kept in fit-cache.npz, which the line names."""
    out = tmp_path / "cal"
    code, err, tag = _interrupt([*CALIBRATE, "--out", str(out)], tmp_path, _line("fit: "),
                                "term")
    assert _gone(tag) == []
    line = _final_line(err, "upliftlab: interrupted")
    assert code == 130 and "resume with: upliftlab calibrate strip_footing_clay" in line
    assert _leftovers(tmp_path) == [] and not (out / "upliftlab-run.json").exists()
    assert not (out / "calibration.json").exists()
    records = list((out / "store").rglob("*.json"))
    assert len(records) == 5 and all(json.loads(p.read_text()) for p in records)
    assert (out / "fit-cache.npz").is_file() and "evaluations kept in fit-cache.npz" in line
