"""The time budget of a run (upliftlab.budget): a run estimated above it is refused before any
integration, with one line naming the budget, its value, the estimate and how to raise it;
a run within it runs; the budget is an option of the run, not of the scene.

References:
- the estimate of the 100 000-spring run by hand from the documented rates
  (:data:`upliftlab.budget.REDUCED_SECONDS_PER_STEP`, :data:`~upliftlab.budget.
  EVENTS_PER_SPRING_SECOND`): 548 trial steps of the event stepper (1 s of strip_footing_clay's
  pulse at 40 per shortest bonded period) and 20 × 100 001 × 2 = 4.0e6 located switches, at
  1e-6 + 1.3e-7 × 100 001 s each: 5.2012e4 s = 14.4 h (within the memory budget: 1.4 GiB);
- the packaged scenes' digests as main (bfbaf4c) gave them before the budget existed (the
  scene package and files are unchanged since): the store keys and result provenance that
  hold them stay valid;
- the same scene run with and without a budget: the same numbers, bit for bit.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from upliftlab.budget import CONTINUUM_BUDGET_SECONDS, REDUCED_BUDGET_SECONDS, time_budget
from upliftlab.checks import InputError
from upliftlab.cli import main as cli
from upliftlab.reduced import run
from upliftlab.reduced.model import build_model
from upliftlab.reduced.run import plan_run
from upliftlab.scenes import load_scene, packaged_scenes

#: 1 s of strip_footing_clay's pulse with 100 000 springs (issue 37: only a warning before)
MANY = ["foundation.springs=100000", "motion.duration=1"]
#: The estimate by hand (module docstring), s.
MANY_SECONDS = (548 + 20 * 100_001 * 2) * (1.0e-6 + 1.3e-7 * 100_001)


def _error(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0, err  # one line
    return err


def test_a_run_estimated_above_the_budget_is_refused_before_integrating(tmp_path, capsys):
    out = tmp_path / "o"
    assert cli(["run", "strip_footing_clay", "--set", MANY[0], "--set", MANY[1],
                "--no-figure", "--out", str(out)]) == 2
    line = _error(capsys)
    assert MANY_SECONDS == pytest.approx(5.2012e4, rel=1e-4)
    assert line.startswith("upliftlab: error: --budget = 3600 s: the reduced run would take "
                           "548 steps"), line
    assert "100001 springs" in line and "roughly 14.4 h" in line
    assert "raise it (--budget 57000, budget= of upliftlab.reduced.run)" in line
    assert not out.exists()  # nothing written, no lock left


def test_a_raised_budget_lets_the_same_run_through_its_checks():
    # the run itself would take days: its plan (every check before integrating) is the test
    scene = load_scene("strip_footing_clay", overrides=MANY)
    model = build_model(scene)
    motion = scene.build_motion()
    name = scene.analysis.integrator
    with pytest.raises(InputError, match=r"^--budget = 3600 s: .*14\.4 h"):
        plan_run(model, motion, name)
    with pytest.raises(InputError, match=r"^--budget = 52000 s: "):
        plan_run(model, motion, name, budget=5.2e4)  # just below the estimate
    plan, _ = plan_run(model, motion, name, budget=5.7e4)
    assert plan.steps * plan.dt == pytest.approx(1.0)


def test_an_in_budget_run_runs_and_the_budget_changes_no_number():
    scene = load_scene("wall_free", case="e07")
    plain = run(scene)
    budgeted = run(scene, budget=60.0)
    for name in ("q", "qd", "force", "energy"):
        assert np.array_equal(getattr(plain, name), getattr(budgeted, name)), name
    assert budgeted.provenance["scene_digest"] == scene.digest
    with pytest.raises(InputError, match=r"^--budget = 1e-09 s: the reduced run would take"):
        run(scene, budget=1e-9)


@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf, 2e9])
def test_a_budget_outside_its_range_is_refused_before_any_work(value, monkeypatch):
    reduced_run = sys.modules["upliftlab.reduced.run"]  # the package exports run() by its name

    def no_work(*_args, **_kwargs):
        raise AssertionError("the model was built")

    monkeypatch.setattr(reduced_run, "build_model", no_work)
    with pytest.raises(InputError, match=r"^--budget = .*: the estimated run time allowed, in "
                                         r"seconds; valid range is \(0, 1e\+09\]$"):
        run(load_scene("wall_free"), budget=value)
    assert time_budget(None, 5.0) == 5.0 and REDUCED_BUDGET_SECONDS == 3600.0


@pytest.mark.parametrize("text, shown", [("0", "0"), ("-5", "-5"), ("abc", "'abc'"),
                                         ("nan", "nan"), ("1e10", "1e10")])
def test_the_budget_option_is_checked_on_the_command_line(text, shown, tmp_path, capsys):
    out = tmp_path / "o"
    assert cli(["run", "wall_free", "--no-figure", "--budget", text, "--out", str(out)]) == 2
    assert f"--budget = {shown}" in _error(capsys)
    assert not out.exists()


def test_a_continuum_run_above_its_budget_is_refused_before_meshing(tmp_path, capsys):
    # the estimate from the grid lines (16 across, Q2: 20 586 DOFs before the mesh counts
    # 20 160) at the explicit route's documented 6.0e-8 s per DOF and step (its measured CPU
    # rate, 3.8e-8 in benchmarks/CONTINUUM_STARTUP.md, with a 1.6x margin), 2.08e4 steps:
    # about 26 s, above 10 s (the run itself takes about 20 s of CPU, 16 across) and far
    # below the default day
    out = tmp_path / "o"
    assert cli(["continuum", "strip_footing_clay", "--analysis", "dynamic", "--no-render",
                "--budget", "10", "--out", str(out)]) == 2
    line = _error(capsys)
    assert line.startswith("upliftlab: error: --budget = 10 s: the continuum dynamic would "
                           "take"), line
    assert "(20586 DOFs)" in line and "roughly 26 s" in line and not out.exists()
    assert "raise it (--budget 28) to run it anyway" in line and "a coarser mesh" in line
    assert CONTINUUM_BUDGET_SECONDS == 86400.0


#: The packaged scenes' digests (and their cases') at main bfbaf4c, before the time budget:
#: a budget that entered the scene would change them (and the results' provenance).
DIGESTS = {
    "long_period_elcentro": "a3b486da67856f21eca37ecae68cc7c5b239c84299f7b3590df79438a2e87871",
    "long_period_free": "74ad9f3e0c04b834b322cb44941bbc4dec14f5601be8becc17a6c70b47c7e292",
    "short_period_elcentro": "adb0735bea1b123b2997fc181ed8ea0d55b668c8127fc5bc76be06d814be081c",
    "short_period_free": "7b1b07b41f1c2f8f446bfb1520bd2a83ea28cc34ec058f759154c00e052d7350",
    "strip_footing_clay": "ce16ddd936fabf48e17b81664125fa07d84c1fb82f8f60320d1a9a3b6e4d3001",
    "three_story_frame": "937738433bd6fc515c696044f2db5277a0b8d3b27528fe29f63244136bd21852",
    "wall_elcentro": "08fffa5ce1a54fe44ce8fc9e15224c915f0b96d7750d4390d7bbfe94d03ef30a",
    "wall_free": "fede03eadfc4d29c6d88ea38e473d3de52fb1f3a9a8270c00aca5a043aada642",
    "wall_free/e07": "1d7244d42811852a2ef94cd158955ecf6110e9fa95db2dca27f019effff19ea9",
    "wall_elcentro/e07": "dd09b5136cf9d5ab9da3e9943dad5b6f0bada18db521618da5bf7c180515bae3",
    "long_period_elcentro/A": "43becab27bd55109708e459b05f831b6ea8cbf801112f30f8b0a6a528bcb8ace",
    "short_period_free/B": "b2ae176af9fadac993cba8cc9a2daccde53d537210b14ef10f288d1a10d384bc",
}


def test_the_packaged_scenes_keep_their_digests():
    assert set(packaged_scenes()) == {k for k in DIGESTS if "/" not in k}
    for key, digest in DIGESTS.items():
        name, _, case = key.partition("/")
        assert load_scene(name, case=case or None).digest == digest, key
