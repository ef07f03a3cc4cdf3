"""The estimated discretisation error of a continuum dynamic run (``--error-estimate``,
:mod:`upliftlab.continuum.dynamics.mesh_error`).

References:
- closed form: a quantity f(h) = f₀ + c hᵖ on meshes of 2, 4 and 8 across (h = 1/n) has the
  observed order p exactly, and Richardson's estimate of f₈'s error is exactly c h₈ᵖ;
- the committed table ``benchmarks/CONTINUUM_CONVERGENCE.md`` (its rows "mesh: explicit 8
  across against 32" and "mesh: explicit 16 across against 32"), read back here for the orders
  the two-mesh estimate uses; the residual settlement's order log₂(5.612/1.381) = 2.023 worked
  by hand from those cells;
- a converged run: the clay scene with an elastic soil under the first 1.2 s of its Ricker
  pulse (the footing lifts off), estimated on 8 across from 4 (and 2), against the
  independent finer run on 16 across: the true error |f₈ − f₁₆| is within
  :data:`BRACKET` times the estimate for every peak and history (the slow variant: 16 from 8
  and 4, against 32);
- the command line's documented exit codes (2: bad input, before any work) and the budget
  (:func:`upliftlab.budget.in_sequence`: the coarser runs' times add to the run's).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from upliftlab import cli
from upliftlab.budget import Cost, in_sequence
from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics.error_estimate import (coarser_scenes, estimate_from_results,
                                                          history)
from upliftlab.continuum.dynamics.mesh_error import (FLAGS, STUDY_DIFFERENCES, STUDY_ORDERS,
                                                      history_differences, mesh_error,
                                                      observed_order, richardson)
from upliftlab.continuum.dynamics.options import DynamicOptions
from upliftlab.continuum.dynamics.run import run_dynamic
from upliftlab.continuum.output.summaries import dynamic_summary
from upliftlab.checks import InputError
from upliftlab.results import read_dataset, read_netcdf
from upliftlab.scenes import load_scene

SCENE = "strip_footing_clay"
ELASTIC = ("soil.model=elastic", "soil.undrained_strength=", "analysis.duration=1.2")
#: The true error (against the finer run) may be this many times the estimate, at most.
BRACKET = 3.0
TABLE = Path(__file__).resolve().parents[1] / "benchmarks" / "CONTINUUM_CONVERGENCE.md"


def _synthetic(p: float, c: float = 0.7, meshes=(8, 4, 2)):
    t = np.linspace(0.0, 2.0, 201)
    summaries, histories = [], []
    for n in meshes:
        h = 1.0 / n
        summaries.append({"peak_theta": 3.0 + c * h ** p, "residual_settlement": 1.0})
        histories.append({"time": t, "theta": np.sin(3 * t) * (1 + c * h ** p),
                          "v": -t * (1 + c * h ** p)})
    return mesh_error(summaries, histories, meshes, [1e-3 * 8 / n for n in meshes])


@pytest.mark.parametrize("p", [1.0, 2.0, 3.0])
def test_a_power_law_gives_its_order_and_its_exact_error(p):
    estimate = _synthetic(p)
    for name in ("peak_theta", "theta_history", "v_history"):
        q = estimate[name]
        assert q.order == pytest.approx(p, rel=1e-9) and q.flag == FLAGS[0]
        peak = {"peak_theta": 1.0, "theta_history": np.abs(np.sin(np.linspace(0, 6, 201))).max(),
                "v_history": 2.0}[name]
        assert q.estimate == pytest.approx(0.7 * 8.0 ** -p * peak, rel=1e-9)
    assert estimate.step_ratio == pytest.approx(2.0) and "too" in estimate.time_note()


def test_an_order_that_does_not_hold_gives_the_plain_difference():
    assert math.isnan(observed_order(-1.0, 0.5))  # oscillating: no order
    assert observed_order(-1.0, 0.5, signed=False) == pytest.approx(1.0)
    assert math.isnan(observed_order(32.0, 1.0))  # p = 5 is out of [0.5, 4]
    assert math.isnan(observed_order(1.0, 1.0))  # p = 0
    assert richardson(-0.3, math.nan) == 0.3 and richardson(0.3, 1.0) == pytest.approx(0.3)
    q = _synthetic(5.0)["peak_theta"]
    assert math.isnan(q.order) and q.flag == FLAGS[1]
    assert q.estimate == pytest.approx(0.7 * (8.0 ** -5 - 4.0 ** -5) * -1, rel=1e-9)


def test_two_meshes_use_the_committed_studys_order():
    two = _synthetic(2.0, meshes=(8, 4))
    assert two["theta_history"].order == STUDY_ORDERS["theta_history"]
    assert "CONTINUUM_CONVERGENCE" in two["theta_history"].order_source
    assert two["peak_theta"].flag == FLAGS[1]  # the study's θ peak oscillates: no order
    assert two["residual_settlement"].order == pytest.approx(math.log2(5.612 / 1.381), rel=1e-9)


def test_the_study_differences_are_the_committed_tables():
    names = ("peak theta", "peak edge uplift", "residual settlement", "theta history",
             "v history")
    keys = ("peak_theta", "peak_edge_uplift", "residual_settlement", "theta_history",
            "v_history")
    rows = {}
    for line in TABLE.read_text().splitlines():
        for n in (8, 16):
            if line.startswith(f"| mesh: explicit {n} across against 32 |"):
                cells = [c.strip() for c in line.strip("|").split("|")][3:]
                rows[n] = [float(c.rstrip(" %")) / 100 for c in cells]
    assert set(rows) == {8, 16}
    for k, (key, name) in enumerate(zip(keys, names)):
        assert STUDY_DIFFERENCES[key] == pytest.approx((rows[8][k], rows[16][k]),
                                                       rel=1e-12), name


def test_the_coarser_meshes_are_checked_before_any_work():
    scene = load_scene(SCENE)  # 16 across
    assert [s.continuum.elements_across for s in coarser_scenes(scene, 3)] == [8, 4]
    for n, meshes in ((3, 2), (2, 2), (4, 3), (6, 3)):
        with pytest.raises(InputError, match="continuum.elements_across"):
            coarser_scenes(scene.with_overrides(f"continuum.elements_across={n}"), meshes)


def _runs(meshes):
    runs = {}
    for n in meshes:
        scene = load_scene(SCENE, overrides=[f"continuum.elements_across={n}", *ELASTIC])
        model = build_model(scene)
        runs[n] = (model, run_dynamic(model, scene, scene.build_motion(),
                                      DynamicOptions(snapshots=0), progress=False), scene)
    return runs


def _check_bracket(runs, fine: int, meshes: int, reference: int) -> None:
    chain = [fine // 2 ** k for k in range(meshes)]
    estimate = estimate_from_results([runs[n][1] for n in chain], [runs[n][0] for n in chain],
                                     runs[fine][2])
    model, result, _ = runs[reference]
    truth = dynamic_summary(result, width=model.width)
    checked = 0
    for q in estimate.quantities:
        if q.name.endswith("_history"):
            true = history_differences(history(runs[fine][1]), history(result))[q.name]
        else:
            true = q.values[0] - truth[q.name]
        if q.values[0] == 0.0 and true == 0.0:
            continue  # an elastic soil's plastic strain
        assert abs(true) <= BRACKET * q.estimate, (q.name, fine, meshes, true, q.estimate)
        checked += 1
    assert checked >= 6


@pytest.fixture(scope="module")
def elastic_runs():
    return _runs((2, 4, 8, 16))


@pytest.mark.parametrize("meshes", [2, 3])
def test_the_estimate_brackets_the_error_against_a_finer_run(elastic_runs, meshes):
    _check_bracket(elastic_runs, 8, meshes, 16)


def test_the_coarse_estimate_brackets_too(elastic_runs):
    _check_bracket(elastic_runs, 4, 2, 16)


@pytest.mark.slow
def test_the_estimate_brackets_the_error_against_32_across():
    runs = _runs((4, 8, 16, 32))
    for meshes in (2, 3):
        _check_bracket(runs, 16, meshes, 32)


def test_in_sequence_adds_the_times():
    a = Cost("a", 100, 0.1, 8e6, 10.0, "100 DOFs")
    b = Cost("b", 50, 0.2, 2e6, 1.5, "25 DOFs")
    both = in_sequence([a, b], "both")
    assert (both.steps, both.memory, both.seconds) == (100, 8e6, 11.5)


def _cli(tmp_path, *extra, name="out"):
    out = tmp_path / name
    return cli.main(["continuum", SCENE, "--analysis", "dynamic", "--json", "--no-render",
                     "--out", str(out), *extra]), out


@pytest.mark.parametrize("extra", [
    ["--set", "continuum.elements_across=3", "--error-estimate"],
    ["--set", "continuum.elements_across=2", "--error-estimate"],
    ["--set", "continuum.elements_across=4", "--error-estimate=3"],
    ["--error-estimate=4"],
])
def test_the_command_refuses_a_mesh_that_does_not_halve(tmp_path, capsys, extra):
    code, out = _cli(tmp_path, *extra)
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and not out.exists(), err


def test_the_pushover_refuses_the_estimate(tmp_path, capsys):
    code = cli.main(["continuum", SCENE, "--error-estimate", "--out", str(tmp_path / "p")])
    assert code == 2 and "only the dynamic" in capsys.readouterr().err


def test_the_budget_counts_the_coarser_runs(tmp_path, capsys):
    times = []
    for extra in ([], ["--error-estimate"]):
        code, out = _cli(tmp_path, "--set", "continuum.elements_across=16", "--budget", "0.001",
                         *extra)  # refused before meshing; 16 across: seconds, not rounded away
        err = capsys.readouterr().err
        assert code == 2 and not out.exists()
        times.append(float(re.search(r"raise it \(--budget ([0-9.e+]+)\)", err).group(1)))
    assert "coarser run" in err and times[1] > times[0]


def test_the_command_writes_the_estimate(tmp_path, capsys, cf_failures):
    code, out = _cli(tmp_path, "--set", "continuum.elements_across=4", "--set",
                     "analysis.duration=0.3", "--error-estimate")
    summary = json.loads(capsys.readouterr().out)
    assert code == 0
    theta = [np.abs(read_netcdf(path)[0]["theta"]).max()
             for path in (out / "result.nc", out / "error_estimate" / "2_across" / "result.nc")]
    data = read_dataset(out / "error_estimate.nc")
    assert list(data["elements_across"].values) == [4, 2]
    assert data["peak_theta"].values == pytest.approx(theta, rel=1e-12)
    record = summary["error_estimate"]["quantities"]["peak_theta"]
    assert record["value"] == pytest.approx(theta[0], rel=1e-12)
    assert record["coarse_value"] == pytest.approx(theta[1], rel=1e-12)
    assert record["estimate"] == pytest.approx(float(data["peak_theta_error"]), rel=1e-12)
    assert record["flag"] in FLAGS and int(data["peak_theta_flag"]) == FLAGS.index(record["flag"])
    assert json.loads((out / "error_estimate.json").read_text())["elements_across"] == [4, 2]
    files = json.loads((out / "upliftlab-run.json").read_text())["files"]
    assert "error_estimate/2_across/result.nc" in files and "error_estimate.nc" in files
    required, errors = cf_failures(out / "error_estimate.nc")
    assert not required and not errors, (required, errors)


@pytest.mark.parametrize("failure", ["interrupted", "energy"])
def test_a_coarser_run_that_stops_leaves_the_folder_incomplete(tmp_path, capsys, monkeypatch,
                                                                failure):
    # The coarser run (the second call of run_dynamic) made to stop as a Ctrl-C or a failed
    # energy check would: exit 130 or 3 (upliftlab/cli/__init__.py), one line, the finest
    # run's files kept, no estimate and no completion marker.
    from upliftlab.continuum.dynamics import run as run_module
    from upliftlab.continuum.dynamics.run_control import EnergyBalanceError, Interrupted
    from upliftlab.outdir import read_marker

    real, calls = run_module.run_dynamic, []

    def stand_in(model, scene, motion, options=DynamicOptions(), *, progress=None):
        result = real(model, scene, motion, options, progress=progress)
        calls.append(model.options.elements_across)
        if len(calls) == 2:
            raise (Interrupted(result) if failure == "interrupted"
                   else EnergyBalanceError(result, 0.5, 0.05))
        return result

    monkeypatch.setattr(run_module, "run_dynamic", stand_in)
    code, out = _cli(tmp_path, "--set", "continuum.elements_across=4", "--set",
                     "analysis.duration=0.1", "--error-estimate")
    err = capsys.readouterr().err
    assert code == (130 if failure == "interrupted" else 3) and calls == [4, 2]
    assert "error estimate's run on 2 across" in err
    assert (out / "result.nc").is_file() and not (out / "error_estimate.nc").exists()
    assert read_marker(out) is None
    assert (out / "error_estimate" / "2_across" / "result.nc").is_file() == (failure == "energy")
