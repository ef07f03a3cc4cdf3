"""The Winkler map on a Dask cluster of separate processes, as ``docs/comparisons.md`` gives the
recipe: a ``dask scheduler`` process and a ``dask worker`` process (two single-threaded
workers) started from the command line, and the study run against the scheduler's address.

Reference: the same fast map run in this process on local workers (the ``winkler_map`` tests'
own fast run is not reused: this one is made here), whose continuum measures the cluster's
must reproduce to 1e-12 (each run is deterministic and does not depend on where it runs); and
the estimate line, which names no worker count on a cluster ("split over the executor's
workers").
"""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from upliftlab.results import read_dataset

DASK = str(Path(sys.executable).with_name("dask"))


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _start(argv, log: Path) -> subprocess.Popen:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
           "MKL_NUM_THREADS": "1"}
    return subprocess.Popen(argv, stdout=log.open("w"), stderr=subprocess.STDOUT, env=env,
                            start_new_session=True)


def _stop(process: subprocess.Popen) -> None:
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(20)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait(10)


@pytest.fixture
def cluster(tmp_path):
    """A scheduler and a worker process with two workers; their address."""
    from distributed import Client

    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    scheduler = _start([DASK, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                        "--dashboard-address", ":0"], tmp_path / "scheduler.log")
    worker = _start([DASK, "worker", address, "--nthreads", "1", "--nworkers", "2",
                     "--dashboard-address", ":0", "--local-directory", str(tmp_path / "w")],
                    tmp_path / "worker.log")
    try:
        deadline = time.monotonic() + 120
        while True:
            try:
                with Client(address, timeout=5) as client:
                    client.wait_for_workers(2, timeout=max(1, deadline - time.monotonic()))
                break
            except (OSError, TimeoutError):
                if time.monotonic() > deadline:
                    raise
                time.sleep(1)
        yield address
    finally:
        _stop(worker)
        _stop(scheduler)


def _study(*argv, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "upliftlab", "study", "winkler_map", *argv],
                          capture_output=True, text=True, timeout=900, cwd=cwd,
                          env={**os.environ, "OMP_NUM_THREADS": "1"})


def test_the_fast_map_runs_on_a_cluster_of_separate_processes(cluster, tmp_path, fast_stores):
    on_cluster = _study("--fast", "--no-figures", "--scheduler", cluster, "--out",
                        str(tmp_path / "cluster"), cwd=tmp_path)
    assert on_cluster.returncode == 0, on_cluster.stderr[-3000:]
    assert "split over the executor's workers" in on_cluster.stderr
    # the local map's runs: those another process of this session made, when one has
    # (conftest.FastStores), else made here; either way not the cluster's
    fast_stores.seed("winkler_map", tmp_path / "local" / "store")
    local = _study("--fast", "--no-figures", "--workers", "1", "--out", str(tmp_path / "local"),
                   cwd=tmp_path)
    assert local.returncode == 0, local.stderr[-3000:]
    a, b = (read_dataset(tmp_path / f / "map.nc") for f in ("cluster", "local"))
    for q in ("theta", "uplift", "residual_settlement", "u", "base_shear"):
        np.testing.assert_allclose(a[f"continuum_{q}"].values, b[f"continuum_{q}"].values,
                                   rtol=1e-12)
    summary = json.loads((tmp_path / "cluster" / "summary.json").read_text())
    assert summary["numbers"]["points"] == 2
