"""``upliftlab calibrate SCENE`` (issue 36 §2): the macro-element of a user's own soil and
footing from the continuum's statics, end to end through the command line, on the packaged
strip on clay (4 elements across, one FS_v, a short fit: the test's path; the full one is
``benchmarks/macro_calibration.py``'s).

References: Prandtl's (2 + π) c_u B = 514.16 kN/m and the half-plane's K_r = π G B²/(8(1 −
ν)) = 43 153.6 kN·m/rad/m (closed forms; the 4-across mesh in its 10 B box measured +4.3 % and
+0.8 %); the calibration record itself for the round trip into the reduced model (the scene
the overrides make must carry that law, to 1e-12); the first run for the resumed one (the
store's runs are not made again and the fit is deterministic: equal to 1e-12).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from upliftlab.reduced import build_model
from upliftlab.scenes import load_scene

BASE = ["calibrate", "strip_footing_clay", "--mesh", "elements_across=4", "--fs-v", "3",
        "--evaluations", "10", "--set", "structure.vertical_weight=200"]
PRANDTL = (2.0 + math.pi) * 50.0 * 2.0
K_R = math.pi * (50e3 / 2.6) * 4.0 / (8.0 * 0.7)


def _cli(argv, cwd):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    return subprocess.run([sys.executable, "-m", "upliftlab", *argv], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=900)


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    """The calibration's folder and its record, and the stderr of the run."""
    folder = tmp_path_factory.mktemp("calibrate")
    done = _cli([*BASE, "--out", "cal"], folder)
    assert done.returncode == 0, done.stderr[-3000:]
    out = folder / "cal"
    return out, json.loads((out / "calibration.json").read_text()), done


def test_its_statics_meet_their_closed_forms(calibrated):
    """V_ult within 6 % of Prandtl's and K_r within 2 % of the half-plane's; the vertical
    pushover has found its plateau; the capacity on clay is cohesive only (q₁ = 0)."""
    _, record, _ = calibrated
    statics = record["statics"]
    assert abs(statics["V_ult"] / PRANDTL - 1.0) <= 0.06, statics
    assert abs(statics["K_r"] / K_R - 1.0) <= 0.02, statics
    assert statics["plateau"] <= 0.02
    assert record["capacity_line"]["q1"] == 0.0
    assert [p["label"] for p in record["pushovers"]] == ["FS_v 3, monotonic", "FS_v 3, cycles",
                                                         "FS_v 3, repeated"]
    assert all(p["load_miss"] <= 1e-6 for p in record["pushovers"])


def test_its_overrides_put_that_law_in_the_reduced_model(calibrated):
    """The scene with the record's overrides builds an element whose V_ult, K_v, K_r and
    plastic parameters are the record's (to 1e-12); the folder holds the record, the page and
    the completion marker, and the command prints the line that runs it."""
    out, record, done = calibrated
    scene = load_scene("strip_footing_clay", overrides=["structure.vertical_weight=200",
                                                        *record["overrides"]])
    law = build_model(scene).base.law
    assert law.ultimate_load == pytest.approx(record["statics"]["V_ult"], rel=1e-12)
    assert law.vertical_stiffness == pytest.approx(record["statics"]["K_v"], rel=1e-12)
    assert law.rocking_stiffness == pytest.approx(record["statics"]["K_r"], rel=1e-12)
    for key in ("initial_size", "hardening_settlement", "interior_modulus",
                "interior_exponent", "settlement_coupling", "rounding_ratio", "flow_dilatancy",
                "coupling_exponent", "memory_modulus"):
        assert getattr(law, key) == pytest.approx(record["law"][key], rel=1e-12), key
    assert sorted(p.name for p in out.iterdir()) == ["CALIBRATION.md", "calibration.json",
                                                     "fit-cache.npz", "store",
                                                     "upliftlab-run.json"]
    line = [x for x in done.stdout.splitlines() if x.startswith("use it: upliftlab run ")]
    assert len(line) == 1 and "--set foundation.law=macro" in line[0]
    assert "structure.vertical_weight=200" in line[0] and "elements_across" not in line[0]
    assert "fit: " in done.stderr  # the fit's progress, with its ETA
    assert "left" in [x for x in done.stderr.splitlines() if "fit: " in x][0]


def test_the_same_command_resumes_from_its_store(calibrated, tmp_path):
    """A second command into a copy of the folder without its results (the store and the fit's
    evaluations) makes no continuum run (the store's four records are all it holds), replays
    the fit and gives the same law (to 1e-12). (That the fit, interrupted, goes on to the same
    law when it must compute: the interrupted-fit test below.)"""
    import shutil

    out, record, _ = calibrated
    copy = tmp_path / "cal"
    shutil.copytree(out / "store", copy / "store")  # the continuum's runs
    shutil.copy(out / "fit-cache.npz", copy / "fit-cache.npz")  # and the fit's evaluations
    records = sorted(p.name for p in (copy / "store").rglob("*.json"))
    done = _cli([*BASE, "--out", str(copy)], tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    assert sorted(p.name for p in (copy / "store").rglob("*.json")) == records
    again = json.loads((copy / "calibration.json").read_text())
    for key, value in record["law"].items():
        assert again["law"][key] == pytest.approx(value, rel=1e-12, abs=1e-300), key


@pytest.mark.parametrize("change, field", [
    (["--set", "soil.model=elastic", "--set", "soil.undrained_strength="], "soil.model"),
    (["--fs-v", "0.9"], "--fs-v"),
    (["--fs-v", "3,3"], "--fs-v"),
    (["--fs-v", "1.5", "--set", "soil.youngs_modulus=20000"], "--fs-v"),
    (["--evaluations", "5"], "--evaluations"),
    (["--budget", "1"], "--budget"),
    (["--set", "structure.vertical_weight=171.39"], "structure.vertical_weight"),
    (["--set", "motion.amplitude=0.5"], "motion.amplitude"),
])
def test_what_it_cannot_calibrate_is_refused_before_any_run(change, field, tmp_path):
    """One line naming the field, exit 2, and no folder: a soil without strength, an FS_v out of
    range, repeated, or whose path would pass 0.1 rad (on Prandtl's capacity), too few
    evaluations, a budget below the estimate, a structure that cannot carry the element in
    the reduced model (no base mass to sway), an override the calibration does not read."""
    done = _cli([*BASE, *change, "--out", "cal"], tmp_path)
    lines = [x for x in done.stderr.splitlines() if x.strip()]
    assert done.returncode == 2, done.stderr[-2000:]
    assert lines[-1].startswith("upliftlab: error: ") and field in lines[-1], lines
    assert "Traceback" not in done.stderr
    assert not Path(tmp_path / "cal").exists()


def test_an_interrupted_fit_resumes_from_its_evaluations(calibrated, tmp_path):
    """The fit stopped (KeyboardInterrupt from its progress) after 20 evaluations, its cache
    saved; a second fit given the cache replays them and ends with the law of the
    uninterrupted run (to 1e-12: the fit is deterministic) in as many evaluations."""
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies.macro_calibration import FitCache, calibrate_scene

    out, record, _ = calibrated
    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                        "structure.vertical_weight=200"])
    store = Store(out / "store")

    def stop(done, at_most, lowest):
        if done == 20:
            first.save()
            raise KeyboardInterrupt("SIGTERM")

    first = FitCache(tmp_path / "fit-cache.npz")
    with pytest.raises(KeyboardInterrupt):
        calibrate_scene(scene, store, fs_v=(3.0,), evaluations=10, cache=first,
                        fit_progress=stop)
    kept = FitCache(tmp_path / "fit-cache.npz")
    cal = calibrate_scene(scene, store, fs_v=(3.0,), evaluations=10, cache=kept)
    assert 0 < 20 <= len(kept) and cal.fit.evaluations == record["fit"]["evaluations"]
    for key, value in record["law"].items():
        assert getattr(cal.fit.law, key) == pytest.approx(value, rel=1e-12, abs=1e-300), key


def test_a_weight_the_element_cannot_rest_under_is_refused_after_the_statics(tmp_path):
    """W = 600 on V_ult ≈ 536: one line naming structure.vertical_weight with its range,
    exit 2, after the two statics runs and before any pushover or fit (the store holds two
    records, nothing else is written)."""
    done = _cli([*BASE, "--set", "structure.vertical_weight=600", "--out", "cal"], tmp_path)
    lines = [x for x in done.stderr.splitlines() if x.strip()]
    assert done.returncode == 2, done.stderr[-2000:]
    assert lines[-1].startswith("upliftlab: error: structure.vertical_weight = 600: ")
    assert "valid range is" in lines[-1]
    assert len(list((tmp_path / "cal" / "store").rglob("*.json"))) == 2
    assert not (tmp_path / "cal" / "calibration.json").exists()


def test_a_store_that_is_a_link_out_of_the_folder_is_refused(tmp_path):
    """The output folder's store/ a symbolic link to another folder: one line, exit 2, and
    nothing written in the folder it points to."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "cal").mkdir()
    (tmp_path / "cal" / "store").symlink_to(elsewhere)
    done = _cli([*BASE, "--out", "cal"], tmp_path)
    assert done.returncode == 2, done.stderr[-2000:]
    assert done.stderr.strip().splitlines()[-1].startswith("upliftlab: error: --out = ")
    assert list(elsewhere.iterdir()) == []
