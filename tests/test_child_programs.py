"""The programs upliftlab starts (the OpenSees run of ``upliftlab opensees --run``, the browser
that prints the report) end with the command that started them, however it ends: SIGTERM, and
SIGKILL, which nothing can catch (:func:`upliftlab.workers.dying_with_this_process`).

Before: both outlived the command. A SIGTERM or a SIGKILL to ``upliftlab opensees --run`` left
its ``python model.py`` running, orphaned (parent 1), for as long as its run (up to the
one-hour ``--timeout``), writing its files into the folder after the command had ended; a
killed report left its browser running until it finished printing.

The PDF the browser printed is put in place at once or not at all: a full disk leaves no part
of it (before: moved across file systems, a copy of its first bytes stayed at its name).

The OpenSees run is a stand-in script here (one that waits, as a long run does), run as
``opensees --run`` runs it (:func:`~upliftlab.comparisons.opensees.runner.run_script`).

Reference: the project's rule (a signal at any moment leaves no orphan process; a full disk
leaves nothing half-written); each test of a signal finds the program by the process id it
wrote and asserts it has gone within 3 s of the signal.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest


def _alive(pid: int) -> bool:
    """Whether ``pid`` is a running process (a zombie is not)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _gone(pids, within: float = 3.0) -> list[int]:
    """Those of ``pids`` still running ``within`` s from now (killed then, and returned)."""
    deadline = time.monotonic() + within
    while any(map(_alive, pids)) and time.monotonic() < deadline:
        time.sleep(0.1)
    survivors = [p for p in pids if _alive(p)]
    for pid in survivors:
        os.kill(pid, signal.SIGKILL)
    return survivors


def _wait_for(found, proc, what: str, timeout: float = 300.0):
    """``found()`` once it is true, while ``proc`` runs (else the test fails)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = found()
        if value:
            return value
        if proc.poll() is not None:
            pytest.fail(f"the command ended before {what}: {proc.stderr.read()[-2000:]}")
        time.sleep(0.1)
    proc.kill()
    pytest.fail(f"no {what} after {timeout:g} s")


@pytest.mark.parametrize("how", ["ctrl-c", "kill"])
def test_the_opensees_run_ends_with_the_process_that_runs_it(how, tmp_path):
    """A process running an OpenSees script (:func:`~.opensees.runner.run_script`, the script a
    stand-in that writes its process id and waits, as a long run does) interrupted (SIGINT: the
    KeyboardInterrupt that a command's SIGTERM also becomes) or killed (SIGKILL): the script
    has gone within 3 s."""
    script = tmp_path / "model.py"
    script.write_text(f"import os, time\nopen({str(tmp_path / 'pid')!r}, 'w').write("
                      "str(os.getpid()))\ntime.sleep(300)\n")
    code = ("import sys\nfrom upliftlab.comparisons.opensees.runner import run_script\n"
            "run_script(sys.argv[1], echo=False)\n")
    proc = subprocess.Popen([sys.executable, "-c", code, str(script)], stderr=subprocess.PIPE,
                            text=True)
    pid_file = tmp_path / "pid"
    pid = _wait_for(lambda: pid_file.exists() and pid_file.read_text().strip(), proc,
                    "the OpenSees run")
    proc.send_signal(signal.SIGINT if how == "ctrl-c" else signal.SIGKILL)
    proc.wait(timeout=60)
    assert _gone([int(pid)]) == []


def test_the_browser_ends_with_a_killed_print(tmp_path):
    """A process printing the report (:func:`print_pdf`, its browser a stand-in that writes
    its process id and waits) killed with SIGKILL: the browser has gone within 3 s."""
    browser = tmp_path / "browser"
    browser.write_text(f"#!/bin/sh\necho $$ > {str(tmp_path / 'pid')!r}\nexec sleep 300\n")
    browser.chmod(0o755)
    page = tmp_path / "report.html"
    page.write_text("<html><head></head><body>a report</body></html>")
    code = ("import sys\nfrom upliftlab.comparisons.report.printing import print_pdf\n"
            "print_pdf(sys.argv[1], sys.argv[2], 'A4', executable=sys.argv[3])\n")
    proc = subprocess.Popen([sys.executable, "-c", code, str(page), str(tmp_path / "r.pdf"),
                             str(browser)], stderr=subprocess.PIPE, text=True)
    pid_file = tmp_path / "pid"
    pid = _wait_for(lambda: pid_file.exists() and pid_file.read_text().strip(), proc,
                    "the browser")
    time.sleep(0.2)  # the stand-in has executed sleep in its place
    proc.kill()
    proc.wait(timeout=60)
    assert _gone([int(pid)]) == []


def test_a_pdf_that_meets_a_full_disk_leaves_no_part_of_itself(tmp_path):
    """The browser prints into a temporary folder on another file system (TMPDIR on
    /dev/shm), and the disk of the output folder is full (a file-size limit of 100 kB, which
    the stand-in browser lifts for itself): print_pdf raises the OSError, and the folder holds
    no part of the 300 kB PDF (before: the move across file systems copied 100 kB of it into
    place and left them there)."""
    if not Path("/dev/shm").is_dir() or os.stat("/dev/shm").st_dev == os.stat(tmp_path).st_dev:
        pytest.fail("the test needs /dev/shm on a file system other than the test's folder")
    browser = tmp_path / "browser"
    browser.write_text(f"#!{sys.executable}\nimport resource, sys\n"
                       "resource.setrlimit(resource.RLIMIT_FSIZE, (resource.RLIM_INFINITY,) * 2)\n"
                       "out = next(a for a in sys.argv if a.startswith('--print-to-pdf='))\n"
                       "open(out.split('=', 1)[1], 'wb').write(b'%PDF' + bytes(300_000))\n")
    browser.chmod(0o755)
    page = tmp_path / "report.html"
    page.write_text("<html><head></head><body>a report</body></html>")
    folder = tmp_path / "out"
    folder.mkdir()
    code = ("import errno, resource, signal, sys\n"
            "from upliftlab.comparisons.report.printing import print_pdf\n"
            "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
            "resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, resource.RLIM_INFINITY))\n"
            "try:\n    print_pdf(sys.argv[1], sys.argv[2], 'A4', executable=sys.argv[3])\n"
            "except OSError as exc:\n    print('full', exc.errno == errno.EFBIG)\n")
    done = subprocess.run([sys.executable, "-c", code, str(page), str(folder / "r.pdf"),
                           str(browser)], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "TMPDIR": "/dev/shm"})
    assert done.stdout.split() == ["full", "True"], done.stderr[-2000:]
    assert sorted(p.name for p in folder.iterdir()) == []


def test_the_opensees_runs_results_that_meet_a_full_disk_end_in_one_line(tmp_path):
    """``upliftlab opensees --run`` with a file-size limit of 100 kB (its script and numbers
    fit, the OpenSees run's 400 kB of histories do not): exit 3 and the command's own line for
    a full disk naming the histories, and no part of them left (before: the script's
    traceback, a last line "… did not write both its outputs: Process 0 Terminating", and the
    first 100 kB of the histories at their name)."""
    def limited():
        import resource

        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "upliftlab", "opensees", "wall_free", "--case",
                           "e10", "--run", "--out", str(out)], cwd=tmp_path,
                          env={**os.environ, "MPLBACKEND": "Agg"}, capture_output=True,
                          text=True, timeout=600, preexec_fn=limited)
    last = done.stderr.strip().splitlines()[-1]
    assert done.returncode == 3 and last.startswith(
        f"upliftlab: error: no space left on device writing {out / 'opensees_histories.csv'} "
        "(File too large)"), done.stderr[-2000:]
    assert "Traceback" not in done.stderr
    assert sorted(p.name for p in out.iterdir()) == [".upliftlab-writing.json", "model.json",
                                                     "model.py"]


def test_the_wrapper_runs_no_module_of_the_users_folder_and_says_what_it_cannot_run(tmp_path):
    """The wrapper of :func:`dying_with_this_process` started in a folder holding a
    ``ctypes.py`` and a ``signal.py`` of the user's: neither runs (the program runs, exit 0);
    a program that does not exist: exit 127 and one line naming it (before the fix: the user's
    module ran in its place; a missing program ended in a traceback)."""
    from upliftlab.workers import dying_with_this_process

    for name in ("ctypes.py", "signal.py"):
        (tmp_path / name).write_text(f"open({str(tmp_path / 'ran')!r}, 'w').write('ran')\n")
    done = subprocess.run(dying_with_this_process(["true"]), cwd=tmp_path, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0 and not (tmp_path / "ran").exists(), done.stderr
    missing = str(tmp_path / "no-such-program")
    done = subprocess.run(dying_with_this_process([missing]), cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 127
    assert done.stderr == f"cannot run {missing!r}: No such file or directory\n"


def test_the_scripts_results_are_whole_and_never_beside_an_earlier_summary(tmp_path,
                                                                            monkeypatch):
    """The OpenSees script's writer (:func:`model_script.write_outputs`) failing in the middle
    of the histories (a row that cannot be formatted): the earlier run's summary is gone, and
    neither a part of the histories nor a temporary file is left; the temporary files are named
    as upliftlab's own, so that the next run through upliftlab removes a killed run's
    (:func:`~upliftlab.paths.remove_stale_temporaries`)."""
    from upliftlab.comparisons.opensees import model_script as ms
    from upliftlab.paths import remove_stale_temporaries

    monkeypatch.setattr(ms, "HERE", str(tmp_path))
    monkeypatch.setattr(ms, "TITLE", "t")
    monkeypatch.setattr(ms, "UNITS", "kip-in-s")
    (tmp_path / "opensees_summary.json").write_text('{"verdict": "completed"}')

    class Rows:
        rows = [(0.0,) * 6, ("not a number",) * 6]
        peak = {}

    with pytest.raises(ValueError):
        ms.write_outputs(Rows(), "completed", 1.0, 1.0, 1)
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    with monkeypatch.context() as m:  # a run killed before it could remove its temporary
        m.setattr(ms.os, "remove", lambda path: None)
        with pytest.raises(ValueError):
            ms.write_outputs(Rows(), "completed", 1.0, 1.0, 1)
    (left,) = tmp_path.iterdir()
    dead = _a_dead_pid()
    stale = left.rename(tmp_path / left.name.replace(f"-{os.getpid()}-", f"-{dead}-"))
    assert remove_stale_temporaries(tmp_path / "opensees_histories.csv") == [stale]
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def _a_dead_pid() -> int:
    """The process id of a process that has ended."""
    child = subprocess.Popen(["true"])
    child.wait()
    return child.pid


def test_an_interrupted_wait_does_not_leave_the_run_unreaped(tmp_path):
    """An interruption that lands in ``Popen.wait`` just after it took its internal lock leaves
    the lock held (CPython's timed wait releases it in a ``finally`` it has not entered yet);
    ending the run must still kill and reap the script, not block on the lock for ever (the
    signal test above hung 60 s once under load). Reference: the process table (the script's
    pid gone) and a thread that returns within 10 s."""
    import threading

    from upliftlab.comparisons.opensees.runner import _end

    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)"])
    child._waitpid_lock.acquire()  # as the interrupted timed wait leaves it
    ended = threading.Thread(target=_end, args=(child, tmp_path), daemon=True)
    ended.start()
    ended.join(timeout=10)
    assert not ended.is_alive(), "ending the run blocked on Popen's wait lock"
    assert _gone([child.pid]) == []
