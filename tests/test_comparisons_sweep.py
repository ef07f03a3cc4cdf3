"""The sweep machinery: content-addressed store, parallel sweeps, interruption and resumption,
and the same sweep on a Dask cluster.

References: a record's own values (what was put is what is read), SHA-256 of the documented
canonical text (hashlib), the closed form of the test function, and the same points evaluated
in this process.
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import sys
import time

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.studies import two_spring_equivalence as tse
from upliftlab.comparisons.framework.store import Store, point_key
from upliftlab.comparisons.framework.sweep import StderrProgress, run_sweep

# A test function of one point with a closed form, and a switch that makes it fail.
FAIL_AFTER = {"calls": None}


def square_plus(point):
    """{"x": x, "y": x² + 0.1}; raises once FAIL_AFTER["calls"] calls have been made."""
    if FAIL_AFTER["calls"] is not None:
        if FAIL_AFTER["calls"] == 0:
            raise RuntimeError("simulated failure")
        FAIL_AFTER["calls"] -= 1
    return {"x": point["x"], "y": point["x"] ** 2 + 0.1}


def squares(points):
    """The batched form of :func:`square_plus`."""
    return [square_plus(p) for p in points]


def _points(n):
    return [{"x": float(i), "tag": "p"} for i in range(n)]


def _expected(n):
    return [{"x": float(i), "y": float(i) ** 2 + 0.1} for i in range(n)]


@pytest.fixture(autouse=True)
def _no_failures():
    FAIL_AFTER["calls"] = None
    yield
    FAIL_AFTER["calls"] = None


def _pulse_points(springs=8, intensity=2.0):
    """Four short reduced-model runs (Ewing's short-period building, 0.2 s sine pulse of
    ``intensity`` times the uplift threshold)."""
    base = tse.load_base("short_period_elcentro")
    return [tse.make_point(base, bed="uniform", layout=layout, springs=springs,
                           options=tse.Options(), case=case,
                           motion={"type": "sine", "period": 0.2, "intensity": intensity})
            for layout in ("winkler", "equivalent") for case in ("A", "C")]


# ---------------------------------------------------------------------------------------------
# Store
# ---------------------------------------------------------------------------------------------


def test_point_key_is_sha256_of_the_canonical_text():
    """Reference: hashlib on the canonical text the store documents (sorted keys, no spaces,
    numpy scalars as plain numbers, ``_`` locators left out)."""
    params = {"b": [np.float64(1.0), np.int64(2)], "a": 1, "_path": "/somewhere/else"}
    text = "\n".join(['"study"', '"mod:fn"', '{"a":1,"b":[1.0,2]}'])
    expected = hashlib.sha256(text.encode()).hexdigest()
    assert point_key("study", "mod:fn", params) == expected
    assert point_key("study", "mod:fn", {"a": 1, "b": [1.0, 2]}) == expected
    assert point_key("study", "mod:fn", {"a": 2, "b": [1.0, 2]}) != expected


def test_store_round_trip_and_partial_files(tmp_path):
    """What is put is read back exactly (tolerance 0); a half-written temporary file is not a
    record; a truncated record (records are written atomically: not one of upliftlab's) is
    refused naming the file, not read as missing and written over."""
    store = Store(tmp_path / "store")
    key = point_key("s", "m:f", {"x": 0.1})
    assert store.get(key) is None and not store.has(key)
    record = {"u": 0.1 + 0.2, "list": [1.5e-300, -2.0], "nan": float("nan")}
    store.put(key, record, {"params": {"x": 0.1}})
    back = store.get(key)
    assert back["u"] == 0.1 + 0.2 and back["list"] == [1.5e-300, -2.0]
    assert np.isnan(back["nan"])
    assert len(store) == 1 and list(store.keys()) == [key]
    # a crash mid-write leaves at most a temporary file beside the record: ignored
    (store.path(key).parent / f".{key}.json.x1.part").write_text('{"key": "')
    assert len(store) == 1
    other = point_key("s", "m:f", {"x": 0.2})
    store.path(other).parent.mkdir(parents=True, exist_ok=True)
    store.path(other).write_text('{"key": "' + other + '", "rec')  # truncated record
    with pytest.raises(InputError, match=f"store record '{store.path(other)}': not JSON"):
        store.get(other, "missing")
    store.path(other).unlink()  # the user moves it out of the store
    assert not store.has(other) and store.get(other, "missing") == "missing"
    store.put(other, {"u": 2.0})
    assert store.get(other) == {"u": 2.0}


def test_bad_points_and_options_are_refused_before_anything_runs(tmp_path):
    """Each error names the parameter and the value; nothing is stored (0 records)."""
    store = Store(tmp_path / "store")
    with pytest.raises(InputError, match=r"points\[1\]\.x = nan"):
        run_sweep(square_plus, [{"x": 1.0}, {"x": float("nan")}], store)
    with pytest.raises(InputError, match=r"points\[0\] = 3"):
        run_sweep(square_plus, [3], store)
    with pytest.raises(InputError, match=r"chunk = 0"):
        run_sweep(square_plus, _points(2), store, chunk=0)
    with pytest.raises(InputError, match="lambda"):
        run_sweep(lambda p: p, _points(2), store)
    assert len(store) == 0


# ---------------------------------------------------------------------------------------------
# Sweeps
# ---------------------------------------------------------------------------------------------


def test_sweep_returns_every_record_in_order_and_skips_stored_points(tmp_path):
    """Reference: the closed form x² + 0.1 (exact). A repeated point is computed once; a second
    sweep computes nothing (0 points)."""
    store = Store(tmp_path / "store")
    points = _points(7) + [{"x": 3.0, "tag": "p"}]
    seen = []
    with cf.ThreadPoolExecutor(2) as pool:
        records = run_sweep(square_plus, points, store, executor=pool, chunk=2,
                            progress=seen.append)
    assert records == _expected(7) + [{"x": 3.0, "y": 9.1}]
    assert len(store) == 7
    assert (seen[-1].done, seen[-1].total, seen[-1].computed) == (7, 7, 7)
    FAIL_AFTER["calls"] = 0  # any evaluation would now fail
    with cf.ThreadPoolExecutor(2) as pool:
        again = run_sweep(square_plus, points, store, executor=pool)
    assert again == records


def test_batched_sweep_matches_pointwise(tmp_path):
    """Reference: the closed form x² + 0.1 (exact), five points in chunks of two."""
    with cf.ThreadPoolExecutor(1) as pool:
        records = run_sweep(squares, _points(5), tmp_path / "s", executor=pool, chunk=2,
                            batched=True, progress=False)
    assert records == _expected(5)


def test_failing_point_stops_the_sweep_and_resume_loses_nothing(tmp_path):
    """The function fails at its 6th call, inside a chunk of 4: the 5 points evaluated before
    it are stored (write-through), the error carries a note, and resuming evaluates only the
    rest. Every point is stored exactly once and equals x² + 0.1 (exact)."""
    store = Store(tmp_path / "store")
    FAIL_AFTER["calls"] = 5
    with cf.ThreadPoolExecutor(1) as pool, pytest.raises(RuntimeError) as failure:
        run_sweep(square_plus, _points(12), store, executor=pool, chunk=4, progress=False)
    assert "running the sweep again computes only the rest" in "".join(
        getattr(failure.value, "__notes__", []))
    assert len(store) == 5
    FAIL_AFTER["calls"] = None
    seen = []
    with cf.ThreadPoolExecutor(1) as pool:
        records = run_sweep(square_plus, _points(12), store, executor=pool, chunk=4,
                            progress=seen.append)
    assert seen[-1].computed == 7
    assert records == _expected(12)
    assert len(store) == 12 and len(set(store.keys())) == 12


def test_interrupted_process_sweep_resumes_to_the_uninterrupted_result(tmp_path):
    """A KeyboardInterrupt from the progress hook after the first chunk stops a sweep on local
    processes; resuming completes it. Reference: the same reduced-model runs evaluated in this
    process (equal to the last bit). The interrupt leaves points unstored (the workers are
    ended with the sweep), the resume computes exactly the rest, and every point is stored
    exactly once."""
    points = _pulse_points() + _pulse_points(intensity=3.0)
    reference = [tse.evaluate_point(p) for p in points]
    store = Store(tmp_path / "store")

    def interrupt(progress):
        if progress.computed >= 1:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(tse.evaluate_point, points, store, chunk=1, workers=2, progress=interrupt)
    # an interrupt ends the workers (upliftlab.workers.process_pool): a point a worker stored
    # before it was stopped is kept; count the store once it has stopped growing
    stored_before, deadline = len(store), time.monotonic() + 60.0
    while time.monotonic() < deadline:
        time.sleep(2.0)
        if len(store) == stored_before:
            break
        stored_before = len(store)
    assert 0 < stored_before < len(points)
    seen = []
    records = run_sweep(tse.evaluate_point, points, store, chunk=1, workers=2,
                        progress=seen.append)
    assert records == reference
    assert seen[-1].computed == len(points) - stored_before  # nothing lost, nothing redone
    assert len(store) == len(points)


def test_progress_is_printed_on_stderr_for_long_sweeps(capsys):
    """StderrProgress prints once the sweep has run ``after`` seconds, and the last line:
    3 of 3 points (100 %)."""
    from upliftlab.comparisons.framework.sweep import SweepProgress

    show = StderrProgress(every=0.0, after=0.0)
    show(SweepProgress("demo", 1, 3, 1, 2.0))
    show(SweepProgress("demo", 3, 3, 3, 6.0))
    err = capsys.readouterr().err.splitlines()
    assert err[0] == "demo: 1/3 points (33 %), 2 s, about 4 s left"
    assert err[1] == "demo: 3/3 points (100 %), 6 s"
    quiet = StderrProgress(after=5.0)
    quiet(SweepProgress("demo", 3, 3, 3, 1.0))
    assert capsys.readouterr().err == ""


# ---------------------------------------------------------------------------------------------
# Dask
# ---------------------------------------------------------------------------------------------


def test_dask_local_cluster_gives_the_local_result(tmp_path):
    """The reduced-model sweep on a Dask LocalCluster (2 in-process workers, the cluster itself
    given; its inproc:// address is taken too: tests/test_reduced_batch.py) equals the
    same points evaluated in this process, to the last bit, and stores every point once."""
    import distributed  # the test extra installs it: upliftlab[dask]
    points = _pulse_points()
    reference = [tse.evaluate_point(p) for p in points]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        records = run_sweep(tse.evaluate_point, points, tmp_path / "store",
                            scheduler=cluster, chunk=2, progress=False)
    assert records == reference
    assert len(Store(tmp_path / "store")) == len(points)


def test_dask_requested_but_not_installed_is_a_clear_error(tmp_path, monkeypatch):
    """Without the dask extra, a scheduler address is refused with the install hint, before
    anything runs (0 records)."""
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    with pytest.raises(InputError, match=r"dask\[distributed\]"):
        run_sweep(square_plus, _points(2), tmp_path / "store", scheduler="tcp://127.0.0.1:1")
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "tcp://127.0.0.1:1")
    with pytest.raises(InputError, match="tcp://127.0.0.1:1"):
        run_sweep(square_plus, _points(2), tmp_path / "store")
    assert len(Store(tmp_path / "store")) == 0
