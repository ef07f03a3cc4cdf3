"""The command line around a continuum dynamic run: part of a record, interruption, the energy
check, the time-integration key and the thread settings.

References: the requested duration and the command line's documented exit codes
(upliftlab/cli/__init__.py:
2 bad input, 3 a failed computation, 130 interrupted); an interrupted run's rows are those of an
uninterrupted run of the same scene (a prefix, to round-off).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from upliftlab import cli
from upliftlab.results import read_netcdf

SCENE = "strip_footing_clay"
COARSE = ["--set", "continuum.elements_across=2"]


def _run(tmp_path, *extra, name="out"):
    out = tmp_path / name
    code = cli.main(["continuum", SCENE, "--analysis", "dynamic", "--json", "--no-render",
                     "--out", str(out), *COARSE, *extra])
    return code, out


def test_analysis_duration_runs_part_of_the_record(tmp_path, capsys):
    code, out = _run(tmp_path, "--set", "analysis.duration=0.35")
    summary = json.loads(capsys.readouterr().out)
    variables, attrs = read_netcdf(out / "result.nc")
    assert code == 0
    assert variables["time"][-1] == pytest.approx(0.35, rel=1e-12)
    assert summary["duration"] == pytest.approx(0.35, rel=1e-12)
    assert attrs["method"] == "explicit" and "incomplete" not in attrs
    assert summary["energy_balance_error"] < 1e-3


def test_dynamics_key_selects_the_implicit_route(tmp_path, capsys):
    code, out = _run(tmp_path, "--set", "analysis.duration=0.2", "--set",
                     "continuum.dynamics=implicit")
    assert code == 0 and json.loads(capsys.readouterr().out)["method"] == "implicit"
    assert read_netcdf(out / "result.nc")[1]["scheme"] == "hht"


@pytest.mark.parametrize("route", ["explicit", "implicit"])
def test_a_bearing_failure_writes_what_it_computed_and_exits_3(route, tmp_path, capsys,
                                                               monkeypatch):
    # A stand-in bearing failure after t = 0.2 s of a 0.5 s run (the route's divergence check,
    # or its step, made to raise it): exit 3 (upliftlab/cli/__init__.py: a failed run) with one line
    # that says so; result.nc holds the rows until the failure, marked incomplete with the
    # failure's kind, time and settlement; the snapshots' fields are written for a look at
    # the mechanism; the folder has no completion marker (it holds a failed run).
    import contextlib

    from upliftlab.continuum.dynamics import explicit, implicit
    from upliftlab.continuum.dynamics.run_control import BearingFailure
    from upliftlab.outdir import read_marker

    def failure(k, dt):
        return BearingFailure("the soil failed in bearing (stand-in)", step=k, time=k * dt,
                              settlement=0.3, rotation=0.01)

    if route == "explicit":
        real = explicit._Explicit.diverging

        @contextlib.contextmanager
        def fails_late(self, k0, k1, u, u_prev, footing):
            with real(self, k0, k1, u, u_prev, footing):
                yield
            if k1 * self.settings.dt > 0.2:
                raise failure(k1, self.settings.dt)

        monkeypatch.setattr(explicit._Explicit, "diverging", fails_late)
    else:
        real_step = implicit.ImplicitRun.step

        def fails_late(self, state, control, term, fterm, k, start=None):
            if k * self.settings.dt > 0.2:
                raise failure(k, self.settings.dt)
            return real_step(self, state, control, term, fterm, k, start)

        monkeypatch.setattr(implicit.ImplicitRun, "step", fails_late)
    code, out = _run(tmp_path, "--set", "analysis.duration=0.5", "--set",
                     f"continuum.dynamics={route}")
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 3
    assert err[-1].startswith("upliftlab: error: the soil failed in bearing (stand-in) (the "
                              "rows and snapshots until t = ")
    assert "result.nc marked incomplete = 1, failure = bearing)" in err[-1]
    variables, attrs = read_netcdf(out / "result.nc")
    assert attrs["incomplete"] == 1 and attrs["failure"] == "bearing"
    assert attrs["failure_settlement"] == pytest.approx(0.3)
    assert 0.2 - 0.05 <= attrs["completed_until"] <= 0.2 + 0.05
    assert variables["time"][-1] == pytest.approx(attrs["completed_until"], rel=1e-6)
    assert np.isfinite(variables["theta"]).all()
    assert (out / "fields.xdmf").is_file() and read_marker(out) is None


def test_bad_dynamics_key_is_refused(tmp_path, capsys):
    code, out = _run(tmp_path, "--set", "continuum.dynamics=leapfrog")
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and err[-1].startswith("upliftlab: error: continuum.dynamics = 'leapfrog'")
    assert not out.exists()


@pytest.mark.parametrize("value", ["0", "2"])
def test_bad_energy_tolerance_is_refused(tmp_path, capsys, value):
    code, _ = _run(tmp_path, "--set", f"continuum.energy_tolerance={value}")
    assert code == 2
    assert "continuum.energy_tolerance" in capsys.readouterr().err


def test_energy_balance_beyond_the_tolerance_fails_the_run(tmp_path, capsys):
    # The measured error (about 1e-5 here) against a tolerance it cannot meet: exit 3, one
    # line with the figure, the result written and marked failed.
    code, out = _run(tmp_path, "--set", "analysis.duration=0.5", "--set",
                     "continuum.energy_tolerance=1e-12")
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 3
    assert err[-1].startswith("upliftlab: error: energy balance error ")
    assert "exceeds continuum.energy_tolerance = 1e-12" in err[-1]
    attrs = read_netcdf(out / "result.nc")[1]
    assert attrs["energy_check"] == "failed" and attrs["energy_balance_error"] > 1e-12


def _env(**extra):
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
    env.update(extra)
    return env


def test_interrupted_run_keeps_what_it_computed(tmp_path):
    # SIGTERM during the time loop: exit 130, a result.nc marked incomplete whose rows are a
    # prefix of the uninterrupted run's. The record lasts 240 s so that the signal, sent when
    # the run reports 5 %, still finds it running on a loaded machine (with 60 s, about 13 s
    # of wall time, the run once finished before the signal took effect, during the full
    # suite); an interrupted run costs only what it ran.
    out = tmp_path / "stopped"
    command = [sys.executable, "-m", "upliftlab", "continuum", SCENE, "--analysis", "dynamic",
               "--no-render", "--out", str(out), "--set", "continuum.elements_across=4",
               "--set", "motion.duration=240", "--set", "analysis.duration=240"]
    proc = subprocess.Popen(command, stderr=subprocess.PIPE, text=True, env=_env())
    lines = []
    for line in proc.stderr:
        lines.append(line)
        if "t = " in line and "ETA" in line and "(0%)" not in line:
            break
    time.sleep(0.5)
    proc.send_signal(signal.SIGTERM)
    rest = proc.stderr.read()
    assert proc.wait(timeout=120) == 130, "".join(lines) + rest
    assert "interrupted at t = " in rest and "incomplete = 1" in rest
    variables, attrs = read_netcdf(out / "result.nc")
    until = attrs["completed_until"]
    assert attrs["incomplete"] == 1 and 0.0 < until < 240.0
    assert variables["time"][-1] == pytest.approx(until, rel=1e-6)  # attribute: float32
    assert np.isfinite(variables["theta"]).all()
    # the same rows from an uninterrupted run of that length
    code = cli.main(["continuum", SCENE, "--analysis", "dynamic", "--no-render", "--out",
                     str(tmp_path / "whole"), "--set", "continuum.elements_across=4", "--set",
                     "motion.duration=240", "--set", f"analysis.duration={until + 0.1}"])
    whole, _ = read_netcdf(tmp_path / "whole" / "result.nc")
    n = variables["time"].size
    assert code == 0 and np.array_equal(whole["time"][:n], variables["time"])
    assert np.abs(whole["theta"][:n] - variables["theta"]).max() <= 1e-12


def test_command_line_runs_blas_on_one_thread_unless_told():
    code = ("import sys, upliftlab\n"
            "assert 'numpy' not in sys.modules\n"
            "import upliftlab.cli, os\n"
            "print(os.environ['OPENBLAS_NUM_THREADS'], os.environ['OMP_NUM_THREADS'])\n")
    default = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             env=_env())
    assert default.returncode == 0, default.stderr
    assert default.stdout.split() == ["1", "1"]
    told = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=_env(OPENBLAS_NUM_THREADS="2"))
    assert told.stdout.split() == ["2", "1"]


def test_threads_option_is_checked(tmp_path, capsys):
    code, _ = _run(tmp_path, "--threads", "0")
    assert code == 2 and "--threads" in capsys.readouterr().err


def test_package_imports_lazily():
    assert Path(cli.__file__).parent.name == "cli"
    code = "import sys, upliftlab; print('numpy' in sys.modules); print(upliftlab.load_scene)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            env=_env())
    assert result.returncode == 0 and result.stdout.splitlines()[0] == "False"
