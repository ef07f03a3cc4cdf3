"""The batch API (``upliftlab.reduced.batch.run_batch``) against single runs.

Reference: :func:`upliftlab.reduced.run.run` with ``histories=False`` on the same scene — the
batch promises the same model, motion, step and kernel, so the same peaks to round-off (1e-12
relative here; in practice bit for bit). Also: bad input in one scene of many is refused before
anything is integrated, and a scene the integrator gives up on gets a nonzero status and NaN
values while its neighbours keep their numbers.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.reduced import batch_chunks as batch_module
from upliftlab.reduced import kernels as kn
from upliftlab.reduced.batch import COLUMNS, run_batch
from upliftlab.reduced.run import run
from upliftlab.scenes import load_scene

RTOL = 1e-12

# (scene, case, overrides): every foundation case, the fixed base, every integrator, records
# scaled by pga and by factor, free vibration, a story that yields
ELCENTRO_SCENES = [
    ("short_period_elcentro", "A", ["analysis.duration=3", "foundation.springs=8"]),
    ("short_period_elcentro", "B", ["analysis.duration=3", "analysis.integrator=rk4",
                                    "motion.pga=0.5"]),
    ("short_period_elcentro", "C", ["analysis.duration=3", "foundation.springs=20",
                                    "foundation.yield_multiple=2.5"]),
    ("short_period_elcentro", "C", ["analysis.duration=3", "analysis.integrator=abm4",
                                    "structure.period=0.3"]),
    ("short_period_elcentro", "fixed", ["analysis.duration=3",
                                        "analysis.integrator=newmark"]),
    ("long_period_elcentro", "C", ["analysis.duration=3", "analysis.integrator=hht",
                                   "motion.scale=1.5"]),
    ("short_period_elcentro", "B", ["analysis.duration=3", "analysis.dt=0.01"]),
]
FREE_SCENES = [
    ("wall_free", "e07", []),
    ("wall_free", "e10", ["analysis.integrator=rk4"]),
]


def _scenes(specs):
    return [load_scene(name, case=case, overrides=overrides) for name, case, overrides in specs]


def _expected(scene) -> dict:
    """The batch's columns, from a single run (NaN where the scene has no foundation)."""
    r = run(scene, histories=False)
    pk = r.peaks
    return {"u": pk["u"], "theta": pk["theta"], "uplift_left": pk.get("uplift_left", math.nan),
            "weighted_plastic_settlement": pk.get("weighted_plastic_settlement", math.nan),
            "final_vertical_position": pk.get("final_vertical_position", math.nan),
            "base_shear": pk["base_shear"], "energy_balance_error": pk["energy_balance_error"],
            "dt": r.info["dt"]}


def _assert_rows_match(result, scenes):
    assert result.ok.all(), result.status
    for i, scene in enumerate(scenes):
        want = _expected(scene)
        for name in COLUMNS:
            got = float(getattr(result, name)[i])
            if math.isnan(want[name]):
                assert math.isnan(got), (i, name, got)
            else:
                assert got == pytest.approx(want[name], rel=RTOL, abs=1e-300), (i, name)


def test_batch_equals_single_runs_in_a_pool(elcentro):
    """Every case (A, B, C, fixed), every integrator taken from its scene (integrator=None),
    scaled records; on a pool of 2 processes, chunks of 2 (so rows cross chunk borders)."""
    scenes = _scenes(ELCENTRO_SCENES)
    result = run_batch(scenes, integrator=None, workers=2, chunk=2)
    assert len(result) == len(scenes)
    assert result.names == tuple(s.name for s in scenes)
    assert result.info["workers"] == 2
    _assert_rows_match(result, scenes)
    # the fixed base has no foundation: no uplift, no settlement
    fixed = [i for i, (_, case, _) in enumerate(ELCENTRO_SCENES) if case == "fixed"]
    assert np.isnan(result.uplift_left[fixed]).all()


def test_batch_equals_single_runs_in_process():
    """Free vibration (no record needed), in this process; the row accessor names the status."""
    scenes = _scenes(FREE_SCENES)
    result = run_batch(scenes, integrator=None, workers=1)
    _assert_rows_match(result, scenes)
    assert result.row(0)["status"] == "ok"
    assert result.row(1)["uplift_left"] == float(result.uplift_left[1])


def test_batch_integrator_and_dt_override_each_scene():
    """``integrator`` and ``dt`` given to the batch win over the scenes' own, as in run()."""
    scenes = _scenes(FREE_SCENES)
    result = run_batch(scenes, integrator="newmark", dt=0.001, workers=1)
    assert (result.dt == 0.001).all()
    for i, scene in enumerate(scenes):
        r = run(scene, integrator="newmark", dt=0.001, histories=False)
        assert result.u[i] == pytest.approx(r.peaks["u"], rel=RTOL)
        assert result.uplift_left[i] == pytest.approx(r.peaks["uplift_left"], rel=RTOL)


def test_bad_scene_among_many_is_refused_before_any_integration(monkeypatch):
    """A step beyond RK4's stability limit in scene 5 of 12: InputError naming the scene and
    the limit, and the kernel is never called (for any scene)."""
    calls = []
    monkeypatch.setattr(batch_module, "integrate", lambda *a, **k: calls.append(1))
    good = load_scene("wall_free", case="e07")
    bad = load_scene("wall_free", case="e07",
                     overrides=["analysis.integrator=rk4", "analysis.dt=0.01"])
    scenes = [good] * 5 + [bad] + [good] * 6
    message = r"1 of 12 scenes.*scene 5 \(wall_free-e07\): analysis.dt = 0.01 s .*stability limit"
    with pytest.raises(InputError, match=message):
        run_batch(scenes, workers=1, integrator=None)
    assert calls == []
    with pytest.raises(InputError, match="scene 2: expected a Scene"):
        run_batch([good, good, "wall_free"], workers=1)
    with pytest.raises(InputError, match="workers"):
        run_batch([good], workers=0)
    with pytest.raises(InputError, match="dt"):
        run_batch([good], dt=-1.0)


def test_failed_scene_gets_a_status_and_leaves_the_others_alone(monkeypatch):
    """A failure injected into one scene's integration (the kernel's CHATTER and NONFINITE
    codes, as the compiled integrators return them): that row is NaN with its status, every
    other row equals its single run. (A physically chattering scene is not cheap to build.)"""
    scenes = _scenes(FREE_SCENES + FREE_SCENES)
    real = batch_module.integrate
    count = {"n": 0}

    def failing(*args, **kwargs):
        status, out, counters = real(*args, **kwargs)
        count["n"] += 1
        if count["n"] == 2:
            return kn.CHATTER, out, counters
        if count["n"] == 3:
            return kn.NONFINITE, out, counters
        return status, out, counters

    monkeypatch.setattr(batch_module, "integrate", failing)
    result = run_batch(scenes, integrator=None, workers=1)
    assert result.status.tolist() == [kn.OK, kn.CHATTER, kn.NONFINITE, kn.OK]
    assert result.row(1)["status"] == "chattering"
    assert result.row(2)["status"] == "non-finite state"
    for i in (1, 2):
        assert all(math.isnan(result.row(i)[name]) for name in COLUMNS)
    monkeypatch.setattr(batch_module, "integrate", real)
    for i in (0, 3):
        want = _expected(scenes[i])
        assert result.u[i] == pytest.approx(want["u"], rel=RTOL)
        assert result.uplift_left[i] == pytest.approx(want["uplift_left"], rel=RTOL)


# ---------------------------------------------------------------------------------------------
# Scale: a DataFrame, a Dask scheduler, warnings from workers, an interruption that resumes
# ---------------------------------------------------------------------------------------------


def test_the_batch_is_a_dataframe_with_its_units():
    """One row per run, in order: the scene's name, case and units, its peaks (the same numbers
    as its single run, RTOL), its status; attrs give each column's unit in the scene's system
    (kip-in-s: in, kip)."""
    scenes = _scenes(FREE_SCENES)
    frame = run_batch(scenes, integrator=None, workers=1).to_dataframe()
    assert frame.index.name == "run" and len(frame) == len(scenes)
    assert frame["scene"].tolist() == [s.name for s in scenes]
    assert frame["case"].tolist() == ["e07", "e10"] and set(frame["units"]) == {"kip-in-s"}
    assert frame["status"].tolist() == ["ok", "ok"]
    for i, scene in enumerate(scenes):
        want = _expected(scene)
        for name in COLUMNS:
            assert frame[name].iloc[i] == pytest.approx(want[name], rel=RTOL, nan_ok=True)
    units = frame.attrs["units"]
    assert (units["u"], units["base_shear"], units["theta"], units["dt"]) == \
        ("in", "kip", "rad", "s")


def _cluster():
    import distributed  # the test extra installs it: upliftlab[dask]

    return distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                    dashboard_address=None)


def test_the_batch_runs_on_a_dask_scheduler_and_its_warnings_reach_the_caller(monkeypatch):
    """On a Dask LocalCluster, given as a cluster and as its inproc:// address (a valid Dask
    address of a scheduler in this process, accepted by the address check): the same rows as
    the batch in this process, bit for bit. A warning raised while a run is integrated on the
    worker is raised again in the caller, naming the run (index and scene)."""
    scenes = _scenes(FREE_SCENES)
    local = run_batch(scenes, integrator=None, workers=1)
    real = batch_module._row

    def warning_row(job, out):
        if job.name == "rk4":  # the second scene's integrator
            import warnings
            warnings.warn("a worker's warning", RuntimeWarning)
        return real(job, out)

    monkeypatch.setattr(batch_module, "_row", warning_row)
    with _cluster() as cluster:
        address = cluster.scheduler_address
        assert address.startswith("inproc://")
        with pytest.warns(RuntimeWarning, match=r"^run 1 \(wall_free-e10\): a worker's warning"):
            on_dask = run_batch(scenes, integrator=None, chunk=1, scheduler=cluster)
        with pytest.warns(RuntimeWarning, match=r"^run 1 \(wall_free-e10\)"):
            by_address = run_batch(scenes, integrator=None, chunk=1, scheduler=address)
    for result in (on_dask, by_address):
        np.testing.assert_array_equal(result.status, local.status)
        for name in COLUMNS:
            np.testing.assert_array_equal(getattr(result, name), getattr(local, name))
    assert on_dask.info["scheduler"] == address


def test_an_interrupted_batch_ends_in_one_line_and_resumes(monkeypatch):
    """Ctrl-C during the second chunk: BatchInterrupted (a KeyboardInterrupt) whose notebook
    rendering is one line with the resume call, and whose ``partial`` keeps the finished run
    (the rest NOT_RUN); the CLI's line for it is one line too. Resumed, the batch integrates
    only the missing runs (3 chunk calls, not 4) and equals an uninterrupted batch bit for
    bit."""
    from upliftlab.cli.exits import interrupted_line
    from upliftlab.reduced.batch import NOT_RUN, BatchInterrupted

    scenes = _scenes(FREE_SCENES + FREE_SCENES)
    whole = run_batch(scenes, integrator=None, workers=1)
    real, calls = batch_module.run_chunk, []

    def interrupted(*args):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt("SIGINT")
        return real(*args)

    monkeypatch.setattr(batch_module, "run_chunk", interrupted)
    with pytest.raises(BatchInterrupted) as caught:
        run_batch(scenes, integrator=None, workers=1, chunk=1)
    exc = caught.value
    assert isinstance(exc, KeyboardInterrupt)
    lines = exc._render_traceback_()
    assert len(lines) == 1 and "\n" not in lines[0]
    assert lines[0].startswith("run_batch interrupted (SIGINT): 1 of 4 runs done; resume with: "
                               "run_batch(scenes, ")
    assert exc.partial.status.tolist() == [whole.status[0]] + [NOT_RUN] * 3
    again = pickle.loads(pickle.dumps(exc))  # as it comes back from a worker process
    assert again.line == exc.line and again.partial.status.tolist() == exc.partial.status.tolist()
    assert exc.partial.to_dataframe()["status"].tolist()[1] == "not run (interrupted)"
    line = interrupted_line(exc, ["study", "fixed_vs_uplift"])
    assert "\n" not in line and "1 of 4 runs done" in line and line.endswith(
        "resume with: upliftlab study fixed_vs_uplift")
    calls.clear()
    monkeypatch.setattr(batch_module, "run_chunk", lambda *a: (calls.append(1), real(*a))[1])
    resumed = run_batch(scenes, integrator=None, workers=1, chunk=1, resume=exc.partial)
    assert len(calls) == 3
    np.testing.assert_array_equal(resumed.status, whole.status)
    for name in COLUMNS:
        np.testing.assert_array_equal(getattr(resumed, name), getattr(whole, name))
    with pytest.raises(InputError, match="resume"):
        run_batch(scenes[:2], workers=1, resume=exc.partial)


def test_an_inproc_address_is_refused_on_the_command_line(capsys):
    """inproc:// names a scheduler in the process that made it: the API takes it, a command
    (a new process) refuses it in one line before any work (exit 2)."""
    from upliftlab import cli
    from upliftlab.checks import scheduler_address

    assert scheduler_address("s", "inproc://10.0.0.1/4242/1") == "inproc://10.0.0.1/4242/1"
    for bad in ("inproc://", "inproc://h/x/1", "inproc://h/1"):
        with pytest.raises(InputError, match="scheduler"):
            scheduler_address("s", bad)
    assert cli.main(["study", "verification", "--scheduler", "inproc://h/1/1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "inproc://" in err and "tcp://" in err
