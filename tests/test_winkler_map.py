"""The Winkler map (fast grid: the clay of strip_footing_clay, FS_v 2 and 5, h/B 1.5, T 0.2 s,
3 × a_up, one Ricker pulse of 0.2 s, 4 elements across B): it runs end to end and writes its
files; its key numbers against anchors; its statements recomputed from the written NetCDF;
its refusals; and a second run recomputes nothing.

References:
- calibration identity (anchors §4, calibrate Winkler moduli to K_r): every bed is built so that
  Σ k_i x_i² equals the continuum's K_r; the reference K_r is the continuum's own
  :func:`upliftlab.continuum.footing_stiffness` of the same mesh, computed here independently
  of the study's store, and the bed is rebuilt here by the reduced model (1e-9);
- the map's FS_v is the continuum's: N = V_ult/FS_v with V_ult the largest load of the
  continuum's vertical pushover, so V_ult/N reproduces the grid's FS_v to round-off (1e-12);
  V_ult itself is within 0–8 % above Prandtl's (2 + π) c_u B (anchors §4; displacement FE
  approaches from above, +6.9 % on 4 across in benchmarks/CONTINUUM.md with a rough base);
- the regions, the medians and 90th percentiles are recomputed from ``map.nc`` with numpy alone
  (an independent implementation of the summary's rules), to 1e-12.
"""

from __future__ import annotations

import concurrent.futures as cf
import json
import math
from dataclasses import replace

import numpy as np
import pytest

from upliftlab.cli import main as cli_main

from upliftlab.anchors import prandtl_capacity, winkler_rocking
from upliftlab.checks import InputError
from upliftlab.comparisons.beds import bed_foundation, BedReference, bed_names
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.comparisons.framework.store import Store
from upliftlab.comparisons.framework.study import ascii_text
from upliftlab.comparisons.studies.winkler_map.analysis import analyse, regions
from upliftlab.comparisons.studies.winkler_map.maps import calibration_inputs
from upliftlab.comparisons.studies.winkler_map.parts import (POINT_DIMS, errors_of, estimate_of,
                                                             map_of, statics_of, texts)
from upliftlab.comparisons.studies.winkler_map.rocking import QUANTITY_GROUPS
from upliftlab.comparisons.studies.registry import STUDIES, definition
from upliftlab.continuum import build_model, footing_stiffness
from upliftlab.reduced import build_model as build_reduced
from upliftlab.results import read_dataset
from upliftlab.scenes import load_scene, scene_from_dict

FILES = ("map.nc", "statics.nc", "summary.md", "summary.json", "figures/theta_error.png",
         "figures/uplift_error.png", "figures/residual_settlement_error.png",
         "figures/error_distribution.png", "figures/speed.png")

#: The beds of the fast map, on the box reference (the macro-element stands on the half-plane).
BOX_BEDS = bed_names(wm.FAST_OPTIONS)


@pytest.fixture(scope="module")
def executor():
    """One in-process worker: the continuum's explicit loop compiles once per process, so the
    fast study's runs share this process's compilation with the other continuum tests."""
    with cf.ThreadPoolExecutor(1) as pool:
        yield pool


@pytest.fixture(scope="module")
def study(tmp_path_factory, executor, fast_stores):
    """The fast map from an empty store, its runs published for the modules that read them
    (conftest.FastStores)."""
    out = tmp_path_factory.mktemp("winkler_map")
    made = wm.run(fast=True, out=out, executor=executor, progress=False)
    fast_stores.publish("winkler_map", out / "store")
    return made


@pytest.fixture(scope="module")
def m(study):
    """The map dataset the study computed (``tree["map"]``)."""
    return map_of(study.data)


@pytest.fixture(scope="module")
def inputs(study):
    """({soil: statics}, {soil: impedance}, {(soil, fs_v): rotation pushovers}) the fast map's
    beds were calibrated from, read back from its store."""
    return calibration_inputs(wm.FAST_GRID, wm.FAST_OPTIONS, BOX_BEDS,
                              Store(study.study.directory / "store"))


@pytest.fixture(scope="module")
def written(study):
    return read_dataset(study.study.directory / "map.nc"), \
        read_dataset(study.study.directory / "statics.nc")


def test_the_fast_map_runs_end_to_end_and_writes_its_files(study, m):
    """Every file is written; the map has the grid's points (1 soil × 2 FS_v × 1 × 1 × 1 × 1
    motion) and the registered calibrations; every measure is finite; the estimate made
    before the work counted the runs the grid implies (one soil's statics, its impedance for
    the impedance bed, four rotation pushovers, 2 dynamic and, the fast options making E_F, the
    2 dynamic points' energy runs)."""
    out = study.study.directory
    for name in FILES:
        assert (out / name).is_file(), name
    assert m.continuum_wall_time.dims == POINT_DIMS
    assert m.continuum_wall_time.shape == (1, 2, 1, 1, 1, 1)
    assert tuple(m.calibration.values) == BOX_BEDS
    for q in wm.MEASURES:
        assert np.isfinite(m[f"continuum_{q}"]).all() and np.isfinite(m[f"bed_{q}"]).all()
    # one soil's statics pair, its impedance, and a cyclic and a monotonic rotation pushover
    # per FS_v; each dynamic point twice (its run and its energy run)
    estimate = estimate_of(m)
    assert (estimate.runs, estimate.static, estimate.dynamic) == (10, 6, 4)
    assert int(m.attrs["computed"]) == 10
    assert "winkler_map" in STUDIES and definition("winkler_map") is wm.DEFINITION
    tree = study.study.to_xarray()
    c = list(BOX_BEDS).index("uniform")
    assert float(tree["map"].error.sel(calibration="uniform", measure="theta", fs_v=2.0)
                 .squeeze()) == pytest.approx(float(errors_of(m)[0, 0, 0, 0, 0, 0, c, 0]), abs=0)


def test_the_opened_folder_selects_an_error_by_label_as_the_summary_states_it(study):
    """``upliftlab.open_study`` of the fast map's folder selects one error by its labels
    (soil, FS_v, h/B, period, intensity, calibration, measure = "theta"; one motion) and it
    equals the signed median that summary.json states for that FS_v (a median over the one
    point there is that point's error), exactly. A consistency check, not a verification: the
    reference is the summary the study's own summarise wrote from the same data; it shows that
    the folder opens by label as what the summary read."""
    from upliftlab import open_study

    folder = study.study.directory
    tree = open_study(folder)
    numbers = json.loads((folder / "summary.json").read_text())["numbers"]
    for name in BOX_BEDS:
        for f, fs in enumerate(wm.FAST_GRID.fs_v):
            error = tree["map"].error.sel(soil="clay", fs_v=fs, h_over_B=1.5, period=0.2,
                                          intensity=3.0, calibration=name, measure="theta")
            assert error.dims == ("motion",) and error.size == 1
            assert float(error.squeeze()) == numbers["signed_bias"]["clay"][name]["theta"][f]
    assert tree.attrs["signed_bias"] == numbers["signed_bias"]


def test_every_bed_has_the_continuums_rocking_stiffness(written, inputs):
    """Calibration identity: Σ k_i x_i² of every built bed equals the continuum's K_r of the
    4-across mesh (footing_stiffness computed here, not read from the store) to 1e-9, in the
    file and in a bed rebuilt here from the registry; the continuum's K_r is within 1 % of
    π G B²/(8(1 − ν)) (anchors §4; +0.76 % on 4 across in benchmarks/CONTINUUM.md)."""
    ds, statics = written
    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4"])
    k = footing_stiffness(build_model(scene))
    assert float(statics.K_r.sel(soil="clay")) == pytest.approx(k.rocking, rel=1e-12)
    np.testing.assert_allclose(ds.bed_rocking_stiffness.values, k.rocking, rtol=1e-9)
    soil = scene.soil
    closed = math.pi * soil.shear_modulus * 4.0 / (8.0 * (1.0 - soil.poisson_ratio))
    assert abs(k.rocking / closed - 1.0) < 0.01
    structure = {"weight": 100.0, "height": 3.0, "period": 0.2, "damping_ratio": 0.05,
                 "rotary_inertia": 10.0}
    pushover = {"settlement": [float(v) for v in statics["settlement"].sel(soil="clay").values],
                "load": [float(v) for v in statics["load"].sel(soil="clay").values]}
    ref = BedReference("clay", 100.0, 2.0, 3.0, k.vertical, k.rocking, 500.0,
                          soil.shear_modulus, soil.poisson_ratio,
                          extra={"density": soil.density, "structure": structure,
                                 "impedance": inputs[1]["clay"], **pushover})
    pushovers = inputs[2]
    for name in BOX_BEDS:
        rocking = pushovers["clay", 2.0]  # the fitted bed's statics (any FS_v: K_r is kept)
        table = bed_foundation(name, replace(ref, extra={**ref.extra, "rocking": rocking}),
                                  wm.FAST_OPTIONS)
        data = {"schema": 1, "units": "kN-m-s", "structure": dict(structure),
                "foundation": table, "motion": {"type": "free", "velocity": 1.0,
                                                "duration": 1.0}}
        layout = build_reduced(scene_from_dict(data)).layout
        assert layout.rocking_stiffness == pytest.approx(k.rocking, rel=1e-9), name


def test_the_maps_fs_v_is_the_continuums_capacity_over_N(written):
    """V_ult/N = FS_v to 1e-12 (N = V_ult/FS_v by construction, V_ult the continuum's own
    vertical capacity), and V_ult lies 0–8 % above Prandtl's (2 + π) c_u B (anchors §4)."""
    ds, statics = written
    v_ult = float(statics.V_ult.sel(soil="clay"))
    ratio = v_ult / ds.vertical_load.sel(soil="clay").values
    np.testing.assert_allclose(ratio, ds.fs_v.values, rtol=1e-12)
    prandtl = prandtl_capacity(50.0, 2.0)
    assert 0.0 < v_ult / prandtl - 1.0 < 0.08


def test_the_regions_recomputed_from_the_file(study, written, m):
    """The region rule, implemented again with numpy on map.nc: a (FS_v, h/B) cell passes when,
    at every period and intensity, the median over the motions of |error| is ≤ 10 % in peak θ
    and in edge uplift and ≤ 20 % in residual settlement; the passing counts equal the
    summary's, and the largest all-passing corner rectangle has the region's size."""
    ds, _ = written
    numbers = json.loads((study.study.directory / "summary.json").read_text())["numbers"]
    err = np.abs(ds.error)
    med = err.median(dim="motion", skipna=True)
    ok = ((med.sel(measure="theta") <= 0.10) & (med.sel(measure="uplift") <= 0.10)
          & (med.sel(measure="residual_settlement") <= 0.20))
    ok = ok.all(dim=("period", "intensity"))
    for entry in numbers["regions"]:
        cells = ok.sel(soil=entry["soil"], calibration=entry["calibration"]).values  # fs, hb
        assert entry["passing"] == int(cells.sum())
        assert entry["total"] == cells.size
        region = analyse(m).region(entry["calibration"], entry["soil"]).region
        assert region.count == _largest_corner(cells)


def test_a_bearing_failure_is_a_hit_only_for_a_bed_that_fails_too(m):
    """The fast map's data with its FS_v = 5 point turned into a bearing failure of the
    continuum (measures and errors NaN) that the first calibration's bed called and the others
    did not. Reference, by hand from the unchanged errors: the FS_v = 2 point is a hit where
    |error| ≤ 10 % in peak θ and edge uplift; the failed point is a hit for the first bed only;
    each share is (hit at FS_v = 2 + hit at the failure)/2, and only the other beds miss the
    failure."""
    from upliftlab.comparisons.studies.winkler_map.analysis import missed_failures, share

    names = [str(c) for c in m.calibration.values]
    nb = len(names)
    failed = m.copy(deep=True)
    failed["continuum_bearing_failure"].loc[{"fs_v": 5.0}] = 1
    failed["bed_bearing_failure"].loc[{"fs_v": 5.0, "calibration": names[0]}] = 1
    for q in wm.MEASURES:
        failed[f"continuum_{q}"].loc[{"fs_v": 5.0}] = np.nan
    failed["error"].loc[{"fs_v": 5.0}] = np.nan
    got = share(failed)
    e = np.abs(errors_of(m)[0, 0]).reshape(nb, -1)  # one motion at FS_v = 2: (bed, measure)
    q = wm.MEASURES.index
    hit = (e[:, q("theta")] <= 0.10) & (e[:, q("uplift")] <= 0.10)
    assert got.points == 2 and got.bearing_failures == 1
    assert got.by_bed == {n: (float(hit[c]) + (c == 0)) / 2 for c, n in enumerate(names)}
    assert got.called == {n: int(c == 0) for c, n in enumerate(names)}
    missed = missed_failures(failed)
    assert not missed[0, 0].any() and not missed[0, 1, ..., 0].any()
    assert missed[0, 1, ..., 1:].all()


def test_a_region_stated_in_the_maps_own_parameters(m):
    """Hand-made errors on a 2 FS_v × 3 h/B grid with three motions: |error| 5 % everywhere,
    except peak θ 30 % at FS_v = 2 and residual settlement 50 % at h/B = 2.5, and one motion
    90 % off in peak θ everywhere (the median over the motions ignores it). By hand: the cells
    FS_v = 5 with h/B ≤ 1.5 pass, a corner region of 2 cells."""
    import xarray as xr

    shape = (1, 2, 3, 1, 1, 3, len(BOX_BEDS), len(wm.MEASURES))
    errors = np.full(shape, 0.05)
    theta, settle = wm.MEASURES.index("theta"), wm.MEASURES.index("residual_settlement")
    errors[:, 0, ..., theta] = 0.30
    errors[:, :, 2, ..., settle] = -0.50
    errors[..., 2, :, theta] = 0.90
    coords = {"soil": ["clay"], "fs_v": [2.0, 5.0], "h_over_B": [1.0, 1.5, 2.5],
              "period": [0.2], "intensity": [3.0], "motion": ["a", "b", "c"],
              "calibration": list(BOX_BEDS), "measure": list(wm.MEASURES)}
    none = np.zeros(shape[:6], np.int8)
    data = xr.Dataset({"error": (POINT_DIMS + ("calibration", "measure"), errors),
                       "continuum_bearing_failure": (POINT_DIMS, none),
                       "bed_bearing_failure": (POINT_DIMS + ("calibration",),
                                               np.zeros(shape[:7], np.int8))},
                      coords=coords, attrs=m.attrs)
    for region in regions(data):
        assert (region.passing, region.total, region.region.count) == (2, 6, 2)
        assert "for FS_v ≥ 5 and h/B ≤ 1.5 (2 of 6 cells; 2 pass anywhere)" in region.text


def _largest_corner(cells: np.ndarray) -> int:
    """Largest all-true rectangle holding a corner of ``cells`` (brute force)."""
    nx, ny = cells.shape
    best = 0
    for flip_x in (False, True):
        for flip_y in (False, True):
            c = cells[::-1] if flip_x else cells
            c = c[:, ::-1] if flip_y else c
            for i in range(1, nx + 1):
                for j in range(1, ny + 1):
                    if c[:i, :j].all():
                        best = max(best, i * j)
    return best


def test_medians_and_percentiles_recomputed_from_the_file(study, written):
    """Per measure and calibration, the median and 90th percentile of |error| over every point
    of map.nc (numpy, linear interpolation) equal the summary's to 1e-12; the pick is the
    smallest median."""
    ds, _ = written
    numbers = json.loads((study.study.directory / "summary.json").read_text())["numbers"]
    for measure in wm.MEASURES:
        pick = numbers["picks"][measure]
        for name in ds.calibration.values:
            values = np.abs(ds.error.sel(measure=measure, calibration=name).values).ravel()
            values = values[np.isfinite(values)]
            assert pick["median"][name] == pytest.approx(float(np.median(values)), rel=1e-12)
            assert pick["p90"][name] == pytest.approx(float(np.percentile(values, 90)),
                                                      rel=1e-12)
        assert pick["best"] == min(pick["median"], key=lambda n: pick["median"][n])
    share = numbers["share"]
    e = np.abs(ds.error)
    within = ((e.sel(measure="theta") <= 0.10) & (e.sel(measure="uplift") <= 0.10))
    best = float(within.sel(calibration=share["best"]).mean())
    assert share["best_share"] == pytest.approx(best, abs=1e-12)


def test_the_beds_pass_reports_its_progress(study, tmp_path, executor):
    """The beds' live runs (minutes over the whole grid, after the stored continuum runs are
    read) report their progress as a sweep does: the fast map again on its own store (every
    continuum run stored, so none is made, and its estimate says so) reports its two points'
    beds 0, 1 and 2 of 2."""
    seen = []
    again = wm.run(fast=True, out=tmp_path / "again", store=study.study.directory / "store",
                   executor=executor, progress=seen.append)
    m = map_of(again.data)
    assert int(m.attrs["computed"]) == 0 and estimate_of(m).runs == 0
    assert "already stored): every run is read from the store" in estimate_of(m).text(1)
    assert [(p.done, p.total) for p in seen if p.study == "winkler_map beds"] == \
        [(0, 2), (1, 2), (2, 2)]


def test_the_goal_verdict_counts_the_best_fast_bed_and_how_it_misses(m):
    """The goal (one bed within 10 % in peak θ and edge uplift at more than half the points,
    at least 1000 times faster) on the fast map's two points with errors set by hand: the
    first bed hits both, the second only at FS_v = 5 (at FS_v = 2 its edge uplift is 30 %
    short), every other misses both (50 % over). Reference, by hand: with the first bed too
    slow (500 ×) the second is the best fast bed, at 50 %, which is not most, so the goal is
    not met; its one miss lifts less; with every bed fast the first covers 100 % and meets
    it; with none fast the verdict names the best bed and says none is that fast."""
    from upliftlab.comparisons.studies.winkler_map.analysis import share
    from upliftlab.comparisons.studies.winkler_map.goal import goal, goal_text

    names, q = [str(c) for c in m.calibration.values], wm.MEASURES.index
    errors = np.full(m.error.shape, 0.5)
    errors[..., 0, :] = 0.0
    errors[0, 1, ..., 1, :] = 0.0
    errors[0, 0, ..., 1, :] = 0.0
    errors[0, 0, ..., 1, q("uplift")] = -0.3
    data = m.copy(deep=True)
    data["error"] = (POINT_DIMS + ("calibration", "measure"), errors)
    data["continuum_bearing_failure"][:] = 0
    data["bed_bearing_failure"][:] = 0
    by_bed = share(data).by_bed
    slow_first = goal(data, by_bed, {n: 500.0 if n == names[0] else 2000.0 for n in names})
    assert (slow_first.met, slow_first.bed, slow_first.share) == (False, names[1], 0.5)
    assert slow_first.by_soil_fs_v == {("clay", 2.0): 0.0, ("clay", 5.0): 1.0}
    assert (slow_first.misses, slow_first.over, slow_first.under) == (1, 0.0, 1.0)
    every_fast = goal(data, by_bed, dict.fromkeys(names, 2000.0))
    assert (every_fast.met, every_fast.bed, every_fast.share, every_fast.misses) == \
        (True, names[0], 1.0, 0)
    none_fast = goal(data, by_bed, dict.fromkeys(names, 500.0))
    assert (none_fast.met, none_fast.bed) == (False, names[0])
    assert "is **not met**: no bed is that fast; the best bed, " + names[0] in \
        goal_text(none_fast)
    assert "is **met**" in goal_text(every_fast)
    assert "lifts the edge further than the continuum by more than 10 % at 0 % and less by " \
        "more than 10 % at 100 %" in goal_text(slow_first)


def test_the_summarys_goal_is_recomputed_from_the_file(study, written):
    """summary.json's goal: its bed's share per FS_v counted from map.nc's errors with numpy
    (within 10 % in peak θ and edge uplift; the fast map has no bearing failure) and its
    share the summary's share of that bed; the summary states the verdict."""
    ds, _ = written
    summary = study.study.directory / "summary.json"
    numbers = json.loads(summary.read_text())["numbers"]
    g = numbers["goal"]
    e = np.abs(ds.error)
    within = (e.sel(measure="theta") <= 0.10) & (e.sel(measure="uplift") <= 0.10)
    for fs in ds.fs_v.values:
        assert g["share_by_soil_fs_v"][f"clay FS_v={fs:g}"] == pytest.approx(float(
            within.sel(soil="clay", fs_v=fs, calibration=g["calibration"]).mean()), abs=1e-12)
    # the bed: the largest share among those at least 1000 times faster (else among all)
    shares, speed = numbers["share"]["by_calibration"], numbers["speed"]["median"]
    fast = [n for n in ds.calibration.values if (speed[n] or 0) >= 1000] or \
        list(ds.calibration.values)
    expected = max(fast, key=lambda n: (float(within.sel(calibration=n).mean()),
                                        -list(ds.calibration.values).index(n)))
    assert g["calibration"] == expected
    assert g["share"] == pytest.approx(float(within.sel(calibration=expected).mean()), abs=1e-12)
    assert shares[expected] == pytest.approx(g["share"], abs=1e-12)  # the summary's own share
    assert g["met"] == (g["share"] > 0.5 and (g["median_speedup"] or 0) >= 1000)
    verdict = "is **met**" if g["met"] else "is **not met**"
    assert verdict in (study.study.directory / "summary.md").read_text()



def test_the_summarys_foundation_energy_is_recomputed_from_the_file(study, written):
    """E_F and E_M (the fast options make the continuum's energy runs): every point has the
    continuum's, positive (the clay takes energy from the structure, and of the motion's input);
    each error is (bed − continuum)/max(|continuum|, floor) from map.nc's energies and floor,
    and summary.json's median, 90th percentile and pick per bed are numpy's over those errors
    (1e-12)."""
    ds, _ = written
    numbers = json.loads((study.study.directory / "summary.json").read_text())["numbers"]
    for name in ("foundation_energy", "motion_energy"):
        e = numbers["foundation_energy"][name]
        continuum = ds[f"continuum_{name}"]
        assert e["points"] == continuum.size == 2 and float(continuum.min()) > 0.0
        floor = ds.floor_energy.broadcast_like(continuum)
        expected = (ds[f"bed_{name}"] - continuum) / np.maximum(np.abs(continuum), floor)
        error = ds[f"{name}_error"]
        np.testing.assert_allclose(error.values, expected.transpose(*error.dims).values,
                                   rtol=1e-12)
        for bed in ds.calibration.values:
            values = np.abs(error.sel(calibration=bed).values.ravel())
            assert e["median"][bed] == pytest.approx(float(np.median(values)), abs=1e-12)
            assert e["p90"][bed] == pytest.approx(float(np.percentile(values, 90)), abs=1e-12)
        assert e["best"] == min(ds.calibration.values,
                                key=lambda n: (e["median"][n], e["p90"][n]))
    assert "Points with the continuum's E_F: 2 of 2." in \
        (study.study.directory / "summary.md").read_text()


@pytest.mark.parametrize("change, message", [
    ({"fs_v": (0.5, 3.0)}, r"grid\.fs_v\[0\] = 0\.5: valid range is \(1, 100\]"),
    ({"soils": ("peat",)}, r"grid\.soils\[0\] = 'peat'.*clay.*sand"),
    ({"h_over_B": (2.5, 1.0)}, r"grid\.h_over_B = \[2\.5, 1\.0\]: values must strictly ascend"),
    ({"periods": (0.0,)}, r"grid\.periods\[0\] = 0: valid range is \[0\.02, 5\]"),
    ({"fema_components": 45}, r"grid\.fema_components = 45: valid range is \[0, 44\]"),
])
def test_bad_grid_values_are_refused_before_anything_runs(tmp_path, change, message):
    """One-line InputError naming the field, the value and the valid range; nothing written."""
    with pytest.raises(InputError, match=message) as info:
        wm.run(fast=True, out=tmp_path / "out", grid=replace(wm.FAST_GRID, **change),
               progress=False)
    assert "\n" not in str(info.value)
    assert not (tmp_path / "out").exists()


def test_bad_options_are_refused(tmp_path):
    with pytest.raises(InputError, match=r"options\.beds\[0\] = 'winkler'"):
        wm.run(fast=True, out=tmp_path, options=replace(wm.FAST_OPTIONS, beds=("winkler",)))
    with pytest.raises(InputError, match=r"options\.elements_across = 1"):
        wm.run(fast=True, out=tmp_path, options=replace(wm.FAST_OPTIONS, elements_across=1))


def test_the_command_lines_beds_are_the_options_beds(tmp_path, capsys):
    # --beds names the calibrations compared: an unknown one is refused in one line before
    # anything runs (exit 2, nothing written); known ones become options.beds
    from upliftlab.comparisons.studies.winkler_map.workflow import _arguments, _context_from
    import argparse

    code = cli_main(["study", "winkler_map", "--fast", "--out", str(tmp_path / "o"), "--beds",
                     "qz,winkler"])
    assert code == 2 and not (tmp_path / "o").exists()
    assert "options.beds[1] = 'winkler'" in capsys.readouterr().err
    parser = argparse.ArgumentParser()
    _arguments(parser)
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--no-figures", action="store_true")
    args = parser.parse_args(["--fast", "--no-figures", "--beds", " qz, uniform "])
    ctx = _context_from(args, wm.workflow.Context(fast=True), print)
    assert ctx.options.beds == ("qz", "uniform")


def test_a_run_over_its_budget_is_refused_with_its_estimate(tmp_path, capsys):
    """``--budget`` below the estimate: exit 2, one line naming the budget and the estimate,
    the estimate logged first; no continuum run is made (the store stays empty)."""
    code = cli_main(["study", "winkler_map", "--fast", "--out", str(tmp_path / "o"),
                     "--budget", "0.001", "--no-figures"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert err[-1].startswith("upliftlab: error: options.budget = 0.001 s: the map's 10 "
                              "continuum runs")
    assert any("10 continuum runs to make (6 static, 4 dynamic" in line for line in err)
    assert not any((tmp_path / "o" / "store").glob("??/*.json"))


def test_a_second_run_recomputes_nothing(study, executor):
    """Same grid, same store: no sweep computes a point, the stored records are untouched and
    the numbers of every continuum run are the same (they are read back)."""
    store = study.study.directory / "store"
    before = {p: p.stat().st_mtime_ns for p in store.glob("??/*.json")}
    seen = []
    again = wm.run(fast=True, out=study.study.directory, executor=executor,
                   progress=seen.append,
                   options=replace(wm.FAST_OPTIONS, figures=False))
    m, first = map_of(again.data), map_of(study.data)
    assert int(m.attrs["computed"]) == 0 and estimate_of(m).runs == 0
    assert all(p.computed == 0 for p in seen if p.study == wm.STUDY)  # the sweeps'
    assert {p: p.stat().st_mtime_ns for p in store.glob("??/*.json")} == before
    for name in [f"continuum_{q}" for q in wm.MEASURES] + ["continuum_wall_time"]:
        np.testing.assert_array_equal(m[name].values, first[name].values)


def test_the_gazetas_bed_carries_the_handbook_strips_dashpots():
    # Reference: Gazetas' strip written out by hand here: V_La = 3.4 V_s / (π (1 − ν)) (Lysmer's
    # analog velocity), C_v = ρ V_La B and C_r = ρ V_La B³/12; the bed's springs sit at the
    # centres of 20 equal strips of the 2 m base. Both sums to 1e-12.
    G, nu, rho, B = 17_857.0, 0.4, 1.8, 2.0
    ref = BedReference("clay", 100.0, B, 3.0, 27_000.0, 43_000.0, 500.0, G, nu,
                          extra={"density": rho})
    table = bed_foundation("uniform_plastic_gazetas", ref, wm.FAST_OPTIONS)
    n = table["springs"]
    x = -1.0 + (2.0 / n) * (np.arange(n) + 0.5)
    c = np.asarray(table["dashpots"])
    v_la = 3.4 * math.sqrt(G / rho) / (math.pi * (1.0 - nu))
    assert c.sum() == pytest.approx(rho * v_la * B, rel=1e-12)
    assert (c * x**2).sum() == pytest.approx(rho * v_la * B**3 / 12.0, rel=1e-12)
    assert (c >= 0.0).all() and table["law"] == "elastoplastic"
    with pytest.raises(InputError, match=r"^soil.density = 0.0: .* valid range is > 0$"):
        bed_foundation("uniform_plastic_gazetas", replace(ref, extra={"density": 0.0}),
                          wm.FAST_OPTIONS)


def test_the_bearing_bed_yields_at_one_pressure_where_the_plastic_bed_yields_at_its_stiffness(
        inputs):
    # Reference: the bearing capacity V_ult shared over the tributary widths (V_ult/B per unit
    # width, by hand); the springs and the dashpots are those of the end-stiffened plastic and
    # the impedance beds, built here from the registry (1e-12)
    G, nu, B, V_ult, N = 19_230.8, 0.3, 2.0, 500.0, 200.0
    structure = {"weight": N, "height": 3.0, "period": 0.2, "damping_ratio": 0.05,
                 "rotary_inertia": 10.0}
    ref = BedReference("clay", N, B, 3.0, 27_000.0, 43_000.0, V_ult, G, nu,
                          extra={"density": 1.8, "structure": structure,
                                 "impedance": inputs[1]["clay"]})
    tables = {name: bed_foundation(name, ref, wm.FAST_OPTIONS)
              for name in ("end_stiffened_plastic", "end_stiffened_bearing",
                           "end_stiffened_plastic_impedance", "uniform_plastic_impedance")}
    models = {}
    for name, table in tables.items():
        data = {"schema": 1, "units": "kN-m-s", "structure": dict(structure),
                "foundation": table, "motion": {"type": "free", "velocity": 1.0,
                                                "duration": 1.0}}
        models[name] = build_reduced(scene_from_dict(data))
    bearing = models["end_stiffened_bearing"]
    widths = bearing.layout.widths
    fy = bearing.params["fy"][bearing.foundation_slice]
    np.testing.assert_allclose(fy / widths, V_ult / B, rtol=1e-12)
    weighted = models["end_stiffened_plastic"]
    np.testing.assert_allclose(bearing.layout.stiffnesses, weighted.layout.stiffnesses,
                               rtol=1e-12)
    f0 = weighted.params["f0"][weighted.foundation_slice]
    # at a uniform settlement F0 ∝ k: the stiffened ends hold R_k times the middle's pressure
    q_w = weighted.params["fy"][weighted.foundation_slice] / widths
    R_k = tables["end_stiffened_plastic"]["end_stiffness_ratio"]
    assert R_k > 1.0 and q_w[0] / q_w[q_w.size // 2] == pytest.approx(R_k, rel=1e-12)
    np.testing.assert_allclose(weighted.params["fy"][weighted.foundation_slice], 2.5 * f0,
                               rtol=1e-12)
    assert tables["end_stiffened_plastic_impedance"]["dashpots"] == \
        tables["uniform_plastic_impedance"]["dashpots"]
    assert {k: v for k, v in tables["end_stiffened_plastic_impedance"].items()
            if k != "dashpots"} == tables["end_stiffened_plastic"]


def test_the_uniform_beds_pushover_is_the_tensionless_winkler_closed_form(study, written):
    # Reference: anchors §3, a rigid strip on a tensionless uniform Winkler bed of modulus
    # k = K_v/B: M = (N B/6)(3 − 2√(θ_up/θ)) and c = B √(θ_up/θ) past θ_up = 2N/(k B²)
    # (upliftlab.anchors.winkler_rocking). The study's bed of 48 discrete springs approximates
    # the continuous bed: measured within 9.4e-4 at 2 and 5 θ_on on both FS_v; asserted 2e-3.
    ds, statics = written
    for fs in ds.fs_v.values:
        N = float(ds.vertical_load.sel(soil="clay", fs_v=fs))
        # the box's beds are the same for every structure: the fast grid has one
        k = float(ds.bed_vertical_stiffness.sel(soil="clay", fs_v=fs, calibration="uniform")
                  .squeeze(("h_over_B", "period"))) / 2.0
        theta_on = float(statics.theta_on.sel(soil="clay", fs_v=fs))
        # θ_on of the elastic half-plane, 2N(1 − ν)/(π G B), written out here
        G = 50.0e3 / (2.0 * 1.3)
        assert theta_on == pytest.approx(2.0 * N * 0.7 / (math.pi * G * 2.0), rel=1e-12)
        for r in wm.FAST_OPTIONS.theta_ratios:
            closed = winkler_rocking(np.array([r * theta_on]), N, 2.0, k)
            at = {"soil": "clay", "fs_v": fs, "calibration": "uniform"}
            assert float(statics[f"rocking_bed_M_{r:g}"].sel(**at)) == pytest.approx(
                closed["M"][0], rel=2e-3)
            assert float(statics[f"rocking_bed_contact_{r:g}"].sel(**at)) == pytest.approx(
                closed["c"][0], rel=2e-3)


def test_the_statics_rows_errors_recomputed_from_the_file(study, written):
    """Each statics error in statics.nc is (bed − continuum)/max(|continuum|, floor) of the
    values and floors in the same file (numpy here, 1e-12); the summary's worst error per
    group is the largest of them over FS_v and the group's quantities; an elastic bed
    dissipates nothing on a rotation cycle (its M–θ loop has no area: error −100 %, exact to
    1e-9), which the continuum's plastic clay does (positive work)."""
    _, statics = written
    err = statics.rocking_error
    for key in statics.statics_quantity.values:
        bed = statics[f"rocking_bed_{key}"].transpose("soil", "fs_v", "calibration").values
        cont = statics[f"rocking_continuum_{key}"].values[..., None]
        floor = statics[f"rocking_floor_{key}"].values[..., None]
        expected = (bed - cont) / np.maximum(np.abs(cont), floor)
        got = err.sel(statics_quantity=key).transpose("soil", "fs_v", "calibration").values
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-15)
    worst = study.study.numbers["statics_worst_error"]["clay"]
    groups = np.array([str(g) for g in statics.statics_group.values])  # ASCII in the file
    for name in statics.calibration.values:
        for group in QUANTITY_GROUPS:
            block = err.sel(calibration=name, soil="clay").transpose(
                "fs_v", "statics_quantity").values[:, groups == ascii_text(group)]
            assert worst[str(name)][group] == pytest.approx(np.nanmax(np.abs(block)),
                                                            rel=1e-12)
    assert (statics.rocking_continuum_cyclic_energy.values > 0).all()
    np.testing.assert_allclose(
        err.sel(statics_quantity="cyclic_energy", calibration="uniform").values, -1.0,
        atol=1e-9)


def test_the_qz_bed_runs_on_the_fast_map(m):
    """The q–z bed's runs on the fast map give finite measures: a run whose energy balance is
    beyond the project's tolerance (analysis.energy_tolerance, 1e-3 of the input) is refused by
    reduced.run and would leave NaN here."""
    for q in wm.MEASURES:
        assert np.isfinite(m[f"bed_{q}"].sel(calibration="qz")).all()
    assert not [r for r in texts(m.attrs["refusals"]) if r.endswith("qz: ") or ", qz:" in r]


#: The README's map commands (its second finding and "Comparisons and the report") as argv
#: (after ``python``; the test adds the value of the last ``--out``: argparse takes the last
#: one), with the count of the runs each makes from an empty store (by hand) and its grid.
_MAP = ["study", "winkler_map"]
_KEPT = ["--store", "benchmarks/winkler_map_store"]


def _records_slice(soil: str, period: str, intensity: str, out: str) -> tuple:
    """The README's command for one soil under El Centro and FF-01a..FF-10a at one period and
    intensity: 4 FS_v × 3 h/B × 11 records = 132 dynamic runs, and the soil's 10 static."""
    argv = [*_MAP, "--grid", f"soils={soil}", "--grid", f"periods={period}", "--grid",
            f"intensities={intensity}", "--grid", "pulse_periods=", "--grid",
            "fema_components=10", *_KEPT, "--out", out, "--out"]
    return (argv, "142 continuum runs to make (10 static, 132 dynamic; 0 already stored)",
            dict(soils=(soil,), periods=(float(period),), intensities=(float(intensity),),
                 pulse_periods=(), fema_components=10))


README_MAP_COMMANDS = [
    # 2 soils × 4 FS_v × 3 h/B × 2 T × 2 intensities × 2 pulses = 192 dynamic; per soil the
    # statics pair, the impedance and a cyclic and a monotonic rotation pushover per FS_v = 10
    ([*_MAP, "--grid", "elcentro=false", "--grid", "fema_components=0", *_KEPT, "--out",
      "results/winkler_map-pulses", "--out"],
     "212 continuum runs to make (20 static, 192 dynamic; 0 already stored)",
     dict(elcentro=False, fema_components=0)),
    _records_slice("clay", "0.5", "3", "results/winkler_map-clay-records"),
    _records_slice("clay", "0.5", "1.5", "results/winkler_map-clay-records-1.5"),
    _records_slice("clay", "0.2", "3", "results/winkler_map-clay-records-0.2s"),
    _records_slice("clay", "0.2", "1.5", "results/winkler_map-clay-records-0.2s-1.5"),
    # the clay's whole grid: 4 × 3 × 2 × 2 × 13 motions = 624 dynamic; 10 static
    ([*_MAP, "--grid", "soils=clay", *_KEPT, "--out", "results/winkler_map-clay", "--out"],
     "634 continuum runs to make (10 static, 624 dynamic; 0 already stored)",
     dict(soils=("clay",))),
    _records_slice("sand", "0.5", "3", "results/winkler_map-sand-records"),
    _records_slice("sand", "0.5", "1.5", "results/winkler_map-sand-records-1.5"),
    _records_slice("sand", "0.2", "1.5", "results/winkler_map-sand-records-0.2s-1.5"),
    _records_slice("sand", "0.2", "3", "results/winkler_map-sand-records-0.2s"),
    # E_F under the records: 2 soils × 4 FS_v × 11 records = 88 points, each run twice (its
    # dynamic run and its energy run) = 176; 2 × 10 static
    ([*_MAP, "--energy", "--grid", "h_over_B=1.5", "--grid", "periods=0.5", "--grid",
      "intensities=3", "--grid", "pulse_periods=", "--grid", "fema_components=10", *_KEPT,
      "--out", "results/winkler_map-energy-records", "--out"],
     "196 continuum runs to make (20 static, 176 dynamic; 0 already stored)",
     dict(h_over_B=(1.5,), periods=(0.5,), intensities=(3.0,), pulse_periods=(),
          fema_components=10)),
    # the whole grid: 2 × 4 × 3 × 2 × 2 × 13 motions = 1248 dynamic; 2 × 10 static
    ([*_MAP, *_KEPT, "--out", "results/winkler_map", "--out"],
     "1268 continuum runs to make (20 static, 1248 dynamic; 0 already stored)", {}),
]


@pytest.mark.parametrize("argv, counted, grid", README_MAP_COMMANDS)
def test_the_readme_map_commands_are_estimated_before_they_run(tmp_path, monkeypatch, capsys,
                                                               argv, counted, grid):
    """The docs' map commands (docs/comparisons.md), run as written (the command line's entry
    point in this process: a fresh process each took 5 s, the estimate 0.3 s) from an empty
    folder (so their store is empty) with --budget 1 added: the grid is the one the README
    describes (hand count above) and its cost is estimated and refused before any run
    (exit 2), leaving nothing behind."""
    import shlex
    from pathlib import Path

    page = (Path(__file__).resolve().parents[1] / "docs" / "comparisons.md").read_text()
    assert shlex.join(["upliftlab", *argv[:-1]]) in page  # the command as the docs have it
    monkeypatch.chdir(tmp_path)
    status = cli_main([*argv, str(tmp_path / "out"), "--budget", "1"])
    stderr = capsys.readouterr().err
    assert status == 2, stderr[-2000:]
    assert counted in stderr
    assert stderr.strip().splitlines()[-1].startswith("upliftlab: error: options.budget = 1 s")
    assert not (tmp_path / "out").exists()  # no copied records left behind
    texts = [a for a, flag in zip(argv[1:], argv) if flag == "--grid"]
    assert wm.grid_with(wm.FULL_GRID, texts) == replace(wm.FULL_GRID, **grid)


@pytest.mark.parametrize("text, message", [
    ("soil=clay", "expected FIELD=VALUES with FIELD one of"),
    ("fs_v=2,a", "--grid fs_v = '2,a': expected comma-separated numbers"),
    ("elcentro=yes", "--grid elcentro = 'yes': expected true or false"),
])
def test_grid_assignments_are_refused_in_one_line(text, message):
    """A --grid text that is not FIELD=VALUES of a known field is one InputError line."""
    with pytest.raises(InputError) as exc:
        wm.grid_with(wm.FULL_GRID, [text])
    assert message in str(exc.value) and "\n" not in str(exc.value)


def test_the_signed_bias_recomputed_from_the_file(study, written):
    """summary.json's signed median error per soil, FS_v, bed and measure equals numpy's
    median of map.nc's signed errors over h/B, period, intensity and motion (1e-12); the
    summary prints it as a table per soil with one column per FS_v."""
    ds, _ = written
    bias = study.study.numbers["signed_bias"]
    for soil in ds.soil.values:
        for name in ds.calibration.values:
            for measure in ("theta", "uplift", "residual_settlement"):
                err = ds.error.sel(soil=soil, calibration=name, measure=measure)
                for f, fs in enumerate(ds.fs_v.values):
                    values = err.sel(fs_v=fs).values.ravel()
                    expected = np.median(values[np.isfinite(values)])
                    assert bias[str(soil)][str(name)][measure][f] == pytest.approx(
                        expected, rel=1e-12, abs=1e-15)
    text = (study.study.directory / "summary.md").read_text()
    assert "## Where the beds miss" in text
    assert "| bed (signed median error, %) | FS_v = 2 | FS_v = 5 |" in text


def test_the_estimate_divides_by_workers_only_when_it_knows_them():
    """On local workers the line states the wall time on them (3600 s over 2: 30 min); on a
    Dask cluster or a caller's executor, whose worker count the estimate cannot know, it
    divides by nothing."""
    e = wm.Estimate(3, 1, 2, 0, 3600.0, {"clay": 3600.0}, 1000.0, "default")
    assert "about 30 min on 2 workers" in e.text(2)
    text = e.text(None)
    assert "split over the executor's workers" in text and " on " not in text.split(";")[1]


def test_a_continuum_pushover_that_stopped_leaves_its_statics_row_empty_and_says_why():
    """A rotation pushover the soil could not follow is stored as an error record: its
    (soil, FS_v) row of the statics is NaN for the continuum and every bed, and the failure
    names the soil, FS_v, which path and the solver's message (no exception)."""
    from upliftlab.comparisons.studies.winkler_map.rocking import rocking_data

    records = [{"error": "the rotation pushover stopped: load step 9: gave up"},
               {"error": "the rotation pushover stopped: load step 4: gave up"}]
    data = rocking_data(("clay",), (3.0,), np.array([[173.0]]), records, [[]], 2.0,
                        wm.FAST_OPTIONS, 7)
    assert np.isnan(data.continuum).all() and np.isnan(data.beds).all()
    assert data.beds.shape[:3] == (1, 1, 7)
    assert len(data.failures) == 1
    text = data.failures[0]
    assert text.startswith("clay, FS_v = 3: the continuum's rotation pushover did not reach")
    assert "cyclic: the rotation pushover stopped: load step 9" in text
    assert "monotonic: the rotation pushover stopped: load step 4" in text


def test_a_continuum_run_that_fails_is_reported_and_left_out_or_held_to(tmp_path, executor,
                                                                        monkeypatch):
    """The fast map with the continuum's run of its FS_v = 5 point made to diverge (a stand-in
    ConvergenceError) and that of its FS_v = 2 point to end in a bearing failure (a stand-in
    BearingFailure, the footing settled 0.25 m = 0.125 B): the study finishes; both points'
    continuum measures and every bed's errors are NaN; both failures are listed with the
    point and the message. The diverged point is left out of the share; the bearing failure
    is counted, and each bed is held to it: a hit where the bed's base settled 0.1 B = 0.2 m
    or more in its run of the point, else a miss. Reference for the flags: the beds' peak
    settlements from their own runs of the point (``run_bed``), against 0.2 m. The failures
    are stored: a second run does not retry them."""
    from upliftlab.comparisons.studies.winkler_map import points as wmp
    from upliftlab.comparisons.beds import BASE_SCENE, base_table, bed_foundation
    from upliftlab.comparisons.studies.winkler_map.plan import dynamic_points, reference, scene_of
    from upliftlab.continuum import BearingFailure, ConvergenceError
    from upliftlab.scenes import load_scene

    real = wmp._timed_run

    def fails(scene):
        if scene.continuum.elements_across == 2:  # the kernels' warm-up run
            return real(scene)
        if scene.structure.weight < 200.0:  # N = V_ult/5 ≈ 105 kN/m, not V_ult/2
            raise ConvergenceError("explicit steps 10…14 diverged\n(stand-in)")
        raise BearingFailure("the soil failed in bearing (stand-in)", step=14, time=0.5,
                             settlement=0.25, rotation=0.01)

    monkeypatch.setattr(wmp, "_timed_run", fails)
    result = wm.run(fast=True, out=tmp_path / "out", executor=executor, progress=False)
    d = map_of(result.data)
    share = analyse(d).share
    names = [str(c) for c in d.calibration.values]
    for q in wm.MEASURES:
        assert np.isnan(d[f"continuum_{q}"]).all()
    assert np.isnan(d.error).all()
    failure = d.continuum_bearing_failure
    assert failure.sel(fs_v=2.0).all() and not failure.sel(fs_v=5.0).any()
    failed = [r for r in texts(d.attrs["refusals"]) if "the continuum:" in r]
    assert len(failed) == 2
    assert failed[0].startswith("clay, FS_v = 2")
    assert "BearingFailure: the soil failed in bearing (stand-in)" in failed[0]
    assert failed[1].startswith("clay, FS_v = 5")
    assert "ConvergenceError: explicit steps 10…14 diverged (stand-in)" in failed[1]
    beds = np.stack([d[f"bed_{q}"].values for q in wm.MEASURES], axis=-1)
    assert np.isfinite(beds[0, 0, ..., :2]).all() and np.isnan(beds[0, 1]).all()
    # each bed's flag against its own peak settlement at the failed point
    statics, impedances, pushovers = calibration_inputs(
        wm.FAST_GRID, wm.FAST_OPTIONS, BOX_BEDS, Store(tmp_path / "out" / "store"))
    st = statics["clay"]
    motions = wm.study_motions(wm.FAST_GRID, wm.FAST_OPTIONS, tmp_path / "out")
    point = dynamic_points(wm.FAST_GRID, wm.FAST_OPTIONS, motions, base_table(),
                           load_scene(BASE_SCENE).g, {"clay": st.V_ult})[0]
    ref = reference(st, scene_of(point["scene"]), point["scene"]["structure"],
                    impedances.get("clay"), pushovers["clay", 2.0])
    called = {name: wm.run_bed(point, bed_foundation(name, ref, wm.FAST_OPTIONS))[
        "peak_settlement"] >= 0.2 for name in names}
    assert {n: bool(d.bed_bearing_failure.sel(fs_v=2.0, calibration=n).squeeze())
            for n in names} == called
    assert share.points == 1 and share.bearing_failures == 1
    assert share.by_bed == {n: float(v) for n, v in called.items()}
    assert share.called == {n: int(v) for n, v in called.items()}
    assert "1 of the points ended in a bearing failure" in (tmp_path / "out" /
                                                            "summary.md").read_text()
    monkeypatch.setattr(wmp, "_timed_run", real)
    again = wm.run(fast=True, out=tmp_path / "out", executor=executor, progress=False)
    m = map_of(again.data)
    assert int(m.attrs["computed"]) == 0
    assert m.continuum_bearing_failure.sel(fs_v=2.0).all()


def test_a_bed_run_above_the_reduced_models_budget_is_that_beds_refusal(study, inputs,
                                                                          tmp_path):
    """A bed's run that the reduced model refuses before it starts (its cost check: here the
    fast map's first point with ``analysis.max_steps`` = 10, as a one-minute record refuses
    the q–z bed on the half-plane) comes back as that bed's refusal, its measures NaN and the
    reduced model's one-line reason kept, and does not stop the map; the same point with the
    default budget runs. Reference: the reduced model's own refusal message."""
    from upliftlab.comparisons.beds import BASE_SCENE, base_table, bed_foundation
    from upliftlab.comparisons.studies.winkler_map.plan import dynamic_points, reference, scene_of
    from upliftlab.scenes import load_scene

    statics, impedances, pushovers = inputs
    st = statics["clay"]
    motions = wm.study_motions(wm.FAST_GRID, wm.FAST_OPTIONS, tmp_path)
    point = dynamic_points(wm.FAST_GRID, wm.FAST_OPTIONS, motions, base_table(),
                           load_scene(BASE_SCENE).g, {"clay": st.V_ult})[0]
    ref = reference(st, scene_of(point["scene"]), point["scene"]["structure"],
                    impedances.get("clay"), pushovers["clay", 2.0])
    table = bed_foundation("uniform", ref, wm.FAST_OPTIONS)
    ran = wm.run_bed(point, table)
    assert "refused" not in ran and np.isfinite(list(ran["measures"].values())).all()
    tight = {**point, "scene": {**point["scene"], "analysis": {
        **point["scene"].get("analysis", {}), "max_steps": 10}}}
    refused = wm.run_bed(tight, table)
    assert refused["refused"].startswith("analysis.max_steps = 10: the reduced run would take")
    assert all(math.isnan(v) for v in refused["measures"].values())


def test_the_summary_states_the_workers_the_map_ran_on(study, m):
    """The summary's cost line divides the estimate by the workers of the run that made it, as
    the line logged before the work does (reference: :meth:`Estimate.text` of the same
    estimate, tested above), not always by one."""
    from upliftlab.comparisons.studies.winkler_map.summary import cost_text

    st = statics_of(study.data)
    for workers in (1, 2, None):
        attrs = {k: v for k, v in m.attrs.items() if k != "workers"}
        if workers is not None:
            attrs["workers"] = workers
        ds = m.copy()
        ds.attrs = attrs
        text = cost_text(ds, st)
        assert f"Estimated before any work: {estimate_of(m).text(workers)}." in text
    assert "on 2 workers" in cost_text(m.assign_attrs(workers=2), st)


def _copied_store(study, tmp_path, revision=None):
    """A copy of the fast study's store; ``revision`` rewrites the continuum revision every
    dynamic run records (runs stored by another revision of the model)."""
    import json
    import shutil

    root = tmp_path / "store"
    shutil.copytree(study.study.directory / "store", root)
    if revision is not None:
        for path in root.glob("??/*.json"):
            entry = json.loads(path.read_text())
            if entry["function"].endswith(":evaluate_dynamic"):
                path.write_text(json.dumps({**entry, "models": {"continuum": revision}}))
    return root


def test_the_stores_timed_runs_are_its_dynamic_runs_of_the_current_model(study, tmp_path):
    """The runs a new slice's rates come from: every dynamic run the fast study stored (their
    wall times are the map's own, read from its result), none of its statics, and none at all
    once the runs were made by another revision of the continuum."""
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies.winkler_map.cost import timed_dynamic_runs

    timed = timed_dynamic_runs(Store(_copied_store(study, tmp_path)))
    walls = np.sort(np.ravel(map_of(study.data).continuum_wall_time.values))
    assert sorted(r["wall_time_s"] for r in timed) == pytest.approx(walls, rel=1e-12)
    other = Store(_copied_store(study, tmp_path / "stale", revision=0))
    assert timed_dynamic_runs(other) == []


def test_a_new_slice_of_a_kept_store_is_estimated_at_its_rates(study, tmp_path, capsys):
    """The fast grid at another intensity (its statics stored, none of its dynamic runs: two
    points, each run twice as the fast options make E_F): the estimate takes the per-step rate
    of the store's other runs, not the default; with those runs made by another revision of
    the continuum it falls back to the default, and both refuse a budget of 1 ms before any
    run."""
    def source(root):
        code = cli_main(["study", "winkler_map", "--fast", "--out", str(tmp_path / "o"),
                         "--store", str(root),
                        "--grid", "intensities=1.5", "--budget", "0.001", "--no-figures"])
        err = capsys.readouterr().err
        assert code == 2 and "4 continuum runs to make (0 static, 4 dynamic" in err
        return err.split("compiled return map: ")[1].split(",")[0]

    assert source(_copied_store(study, tmp_path)) == "the stored runs'"
    assert source(_copied_store(study, tmp_path / "stale", revision=0)) == "default"


def test_its_files_pass_the_cf_checker(study, m, cf_failures):
    # Reference: the IOOS compliance checker, cf:1.10 (tests/test_cf.py says which): no
    # failing required check and no check that raised in map.nc and statics.nc (the map's
    # intensity, PGA over a_up, was written with units = "a_up", which UDUNITS does not know:
    # now a ratio, "1", the quantity in its long name). Values unchanged: the file's axis is
    # the grid's and its errors the computed map's, bit for bit.
    from upliftlab.study_files import study_files

    files = study_files(study.study.directory)
    assert {"map", "statics"} <= set(files)
    for name, path in files.items():
        assert cf_failures(path) == ([], []), name
    back = read_dataset(files["map"])
    assert back.intensity.attrs["units"] == "1" and "a_up" in back.intensity.attrs["long_name"]
    assert back.intensity.values.tolist() == list(wm.FAST_GRID.intensities)
    np.testing.assert_array_equal(back.error.values, m.error.values)


def test_the_maps_verdicts_are_its_stored_runs_counted_apart(study, written):
    """The far field and the small-strain verdict of every point in ``map.nc`` and
    ``summary.json``, against the fast map's stored dynamic records read here from its store
    (their ``far_field``: "elastic" or "from z1 to z2"; their ``validity``)."""
    from upliftlab.comparisons.beds import BASE_SCENE, base_table
    from upliftlab.comparisons.studies.winkler_map.plan import dynamic_points, point_key_of
    from upliftlab.continuum.dynamics.validity import BEYOND

    store = Store(study.study.directory / "store")
    statics, _, _ = calibration_inputs(wm.FAST_GRID, wm.FAST_OPTIONS, BOX_BEDS, store)
    motions = wm.study_motions(wm.FAST_GRID, wm.FAST_OPTIONS, study.study.directory)
    points = dynamic_points(wm.FAST_GRID, wm.FAST_OPTIONS, motions, base_table(),
                            load_scene(BASE_SCENE).g, {"clay": statics["clay"].V_ult})
    records = [store.get(point_key_of(p, wm.evaluate_dynamic)) for p in points]
    assert all(r["far_field"] == "elastic" or r["far_field"].startswith("from ")
               for r in records)
    yielded = [int(r["far_field"] != "elastic") for r in records]
    beyond = [int(r["validity"] == BEYOND) for r in records]
    m = written[0]
    assert m.continuum_far_field_yielded.values.ravel().tolist() == yielded  # one motion
    assert m.continuum_beyond_small_strain.values.ravel().tolist() == beyond
    assert (int(m.attrs["count_far_field_yielded"]), int(m.attrs["count_beyond_small_strain"]),
            str(m.attrs["continuum_reference"])) == (sum(yielded), sum(beyond), "box")
    counts = json.loads((study.study.directory / "summary.json").read_text())["numbers"][
        "continuum_verdicts"]
    assert counts == {"reference": "box", "points": len(records),
                      "beyond_small_strain": sum(beyond), "far_field_yielded": sum(yielded),
                      "far_field_yielded_compared": sum(
                          y and not b for y, b in zip(yielded, beyond)),
                      "far_field_elastic": len(records) - sum(yielded),
                      "far_field_not_recorded": 0}
    text = (study.study.directory / "summary.md").read_text()
    assert f"Of its {len(records)} runs, {sum(beyond)} went beyond the small-strain" in text
    assert f"yielded under the motion in {sum(yielded)} runs" in text
