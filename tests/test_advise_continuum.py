"""``upliftlab advise`` on a scene with ``[soil]``: the continuum ladder and the Winkler map.

The scene is ``strip_footing_clay`` made to sit on the fast Winkler map's grid (h/B = 1.5,
T = 0.2 s, a Ricker pulse of 0.2 s at 3 a_up, FS_v = 3.1 on the map's capacity), on the fast
ladder (2, 4, 8 elements across). References, each by another call path than the advisor's:
the map's own point function :func:`winkler_map.evaluate_dynamic` for the continuum values; a
direct :func:`upliftlab.reduced.run` of each bed's table for the bed errors; the map's
``map.nc`` read with xarray and reduced with numpy for the map's evidence. Runtimes are never
asserted.
"""

from __future__ import annotations

import copy
import json
import math
from dataclasses import replace

import numpy as np
import pytest
import xarray as xr

from upliftlab import cli
from upliftlab.comparisons.advise import ladder as adv
from upliftlab.comparisons.advise import continuum as ac
from upliftlab.comparisons.advise import map_evidence as am
from upliftlab.comparisons.beds import bed_foundation, BedReference, BEDS
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.comparisons.studies.winkler_map.grid import FAST_OPTIONS
from upliftlab.reduced import run as reduced_run
from upliftlab.results import read_dataset
from upliftlab.scenes import load_scene, scene_from_dict

SCENE = "strip_footing_clay"
#: h = 3 m (h/B = 1.5), T = 0.2 s, amplitude 3 a_up = 3 g B/(6h) = 1/3 g.
ON_MAP = ["structure.height=3.0", "structure.period=0.2", "motion.period=0.2",
          "motion.duration=0.6", "motion.amplitude=0.3333333333333333",
          "continuum.boundary=shear"]
TOL = 0.10


@pytest.fixture(scope="module")
def fast_map(tmp_path_factory, fast_stores):
    """The fast map's file, its continuum runs read from the session's when another module
    has made them (conftest.FastStores)."""
    out = tmp_path_factory.mktemp("winkler_map")
    fast_stores.seed("winkler_map", out / "store")
    wm.run(fast=True, out=out, options=replace(FAST_OPTIONS, figures=False))
    return out / "map.nc"


@pytest.fixture(scope="module")
def advice(fast_map):
    return adv.advise(SCENE, "peak_theta", TOL, overrides=ON_MAP, fast=True,
                      map_path=fast_map)


def _direct_continuum(n: int) -> float:
    """Peak θ of the map's own point function on ``n`` elements across (the same scene as a
    map point: intensity 3 × a_up)."""
    data = copy.deepcopy(load_scene(SCENE, overrides=ON_MAP).data)
    data.pop("motion")
    data["continuum"]["elements_across"] = n
    point = {"scene": data, "motion": {"type": "ricker", "period": 0.2, "duration": 0.6},
             "intensity": 3.0}
    return wm.evaluate_dynamic(point)["measures"]["theta"]


def test_ladder_values_equal_the_maps_point_function(advice):
    """Each rung's peak θ equals the map's evaluate_dynamic on the same mesh (1e-12): the
    advisor runs the continuum as the map does. Reference = finest mesh; uncertainty = its
    change from 4 across, recomputed."""
    c = advice.continuum_advice
    assert [r.elements_across for r in c.reference.runs] == [2, 4, 8]
    values = {n: _direct_continuum(n) for n in (2, 4, 8)}
    for r in c.reference.runs:
        assert r.value == pytest.approx(values[r.elements_across], rel=1e-12)
    assert c.reference.value == pytest.approx(values[8], rel=1e-12)
    assert abs(values[8]) > c.reference.floor
    assert c.reference.uncertainty == pytest.approx(abs(values[4] - values[8]) / abs(values[8]),
                                                    rel=1e-12)


def test_bed_errors_from_a_direct_reduced_run(advice):
    """Each bed's error equals (bed − continuum)/continuum with the bed run directly from its
    [foundation] table (built from the reported statics, scene N, B, h) and the continuum value
    of the map's point function (1e-12); the certification rule holds on these numbers, each
    bed's counted work (rhs calls, springs) equals the direct run's, and the recommendation is
    the certified bed of least modelled cost (advise_continuum.PICK_RULE; it was the least
    measured runtime, which moved from run to run)."""
    c = advice.continuum_advice
    scene = load_scene(SCENE, overrides=ON_MAP)
    soil, s = scene.soil, c.statics
    # the impedance and the rotation pushovers are inputs of the beds (computed by the map's
    # impedance point and rotation pushovers), not reference values; the vertical pushover is
    # the reported one
    reference = BedReference("tresca", scene.structure.weight, 2.0, 3.0, s.K_v, s.K_r,
                                s.V_ult, soil.shear_modulus, soil.poisson_ratio,
                                extra={"density": soil.density,
                                       "structure": dict(scene.data["structure"]),
                                       "settlement": s.settlement, "load": s.load,
                                       "impedance": ac.scene_impedance(scene, 8),
                                       "rocking": ac.scene_pushovers(scene, 8, fast=True)})
    continuum = _direct_continuum(8)
    uncertainty = abs(_direct_continuum(4) - continuum) / abs(continuum)
    assert len(c.beds) == len(BEDS)
    for bed in c.beds:
        if bed.name == "macro":  # no calibration given: left out, saying how to make one
            assert bed.failure.endswith(ac.MACRO_NEEDS) and not bed.meets
            continue
        data = copy.deepcopy(scene.data)
        data["foundation"] = bed_foundation(bed.name, reference, FAST_OPTIONS)
        del data["soil"], data["continuum"]
        response = reduced_run(scene_from_dict(data, merged=True))
        value = max(float(np.max(np.abs(response.theta))), float(response.peaks["theta"]))
        assert bed.value == pytest.approx(value, rel=1e-12)
        assert bed.error == pytest.approx((value - continuum) / continuum, rel=1e-12, abs=1e-15)
        assert bed.meets == (abs(bed.error) + uncertainty <= TOL)
        assert bed.speed_ratio == pytest.approx(c.reference.finest.wall_time_s
                                                / bed.wall_time_s, rel=1e-12)
        assert (bed.work.rhs_calls, bed.work.springs) == (response.info["counters"][2],
                                                          response.model.spring_count)
    passing = [b for b in c.beds if b.meets]
    if passing:
        cheapest = min(b.work.seconds for b in passing)
        assert c.recommendation.work.seconds == cheapest
        assert c.recommendation.meets
    else:
        assert c.recommendation is None and "closest" in c.reason


def test_the_bed_pick_does_not_move_with_timing_noise():
    """Three certified beds and a failing one, their runtimes multiplied by seeded log-normal
    noise (σ = 0.5) in 200 draws: the pick stays the bed of least modelled cost (reference:
    advise_continuum.PICK_RULE by hand, the second bed's 0.010 s), never the failing bed, and a
    tie in modelled cost goes to the bed with fewer springs."""
    names = list(BEDS)[:4]

    def bed(name, seconds, springs, runtime, meets=True):
        work = ac.Work("events", springs, 600, 5000, seconds)
        return ac.BedCheck(name, name, 0.0, 0.0, runtime, 1.0, meets, work=work)

    beds = [bed(names[0], 0.014, 41, 0.012), bed(names[1], 0.010, 81, 0.016),
            bed(names[2], 0.013, 21, 0.011), bed(names[3], 0.005, 11, 0.004, meets=False)]
    rng = np.random.default_rng(7)
    for _ in range(200):
        noisy = [replace(b, wall_time_s=b.wall_time_s * float(rng.lognormal(0.0, 0.5)))
                 for b in beds]
        assert ac.select_bed(noisy).name == names[1]
    tied = [bed(names[0], 0.010, 41, 0.02), bed(names[1], 0.010, 81, 0.01)]
    assert ac.select_bed(tied).name == names[0]
    assert ac.select_bed([beds[3]]) is None


def test_map_evidence_recomputed_from_the_map(advice, fast_map):
    """The scene sits inside the fast map (clay; FS_v between the map's 2 and 5; h/B, T and
    intensity on its single values): each bed's median, 90th percentile and share within tol of
    |error| in peak θ over the cells fs_v ∈ {2, 5} and every motion, recomputed with numpy from
    map.nc (1e-12)."""
    e = advice.continuum_advice.map
    assert e.inside and e.soil == "clay"
    ds = read_dataset(fast_map)
    V_ult = float(read_dataset(fast_map.with_name("statics.nc"))["V_ult"].sel(soil="clay"))
    assert e.coordinates["fs_v"] == pytest.approx(V_ult / 171.39, rel=1e-12)
    assert 2.0 < e.coordinates["fs_v"] < 5.0
    assert e.cells == {"fs_v": [2.0, 5.0], "h_over_B": [1.5], "period": [0.2],
                       "intensity": [3.0]}
    err = ds["error"].sel(soil="clay", measure="theta")
    for bed in e.beds:
        values = np.abs(err.sel(calibration=bed.name).values.ravel())
        values = values[np.isfinite(values)]
        assert bed.count == values.size == 2
        assert bed.median == pytest.approx(np.median(values), rel=1e-12)
        assert bed.p90 == pytest.approx(np.percentile(values, 90), rel=1e-12)
        assert bed.share_within == pytest.approx(np.mean(values <= TOL), rel=1e-12)
    assert e.best == min(e.beds, key=lambda b: b.median)
    text = adv.format_advice(advice)
    assert "map's evidence" in text and "not this scene's runs" in text
    assert "certified against: the continuum (plane strain, explicit route) on 8 elements" \
        in text


def test_map_evidence_holds_each_bed_to_a_bearing_failure(fast_map, tmp_path):
    """The fast map rewritten with its FS_v = 5 run a bearing failure of the continuum (its
    errors NaN) that the first bed failed with and the others did not. Reference, by hand from
    the unchanged map.nc: each bed keeps the FS_v = 2 run's |error| alone as its median; its
    share within tol is (hit at FS_v = 2 + hit at the failure)/2, the hit at the failure being
    the first bed's only; the verdict warns when its bed missed the failure."""
    import shutil

    ds = read_dataset(fast_map).load()
    err = np.abs(ds["error"].sel(soil="clay", measure="theta"))
    first = str(ds["calibration"].values[0])
    failed = ds.copy(deep=True)
    failed["error"].loc[dict(soil="clay", fs_v=5.0)] = np.nan
    bearing = xr.zeros_like(ds["continuum_steps"], dtype="i1")
    bearing.loc[dict(soil="clay", fs_v=5.0)] = 1
    called = xr.zeros_like(ds["bed_wall_time"], dtype="i1")
    called.loc[dict(soil="clay", fs_v=5.0, calibration=first)] = 1
    failed["continuum_bearing_failure"], failed["bed_bearing_failure"] = bearing, called
    path = tmp_path / "map.nc"
    failed.to_netcdf(path)
    shutil.copy(fast_map.with_name("statics.nc"), tmp_path / "statics.nc")
    scene = load_scene(SCENE, overrides=ON_MAP)
    e = am.map_evidence(path, scene, "theta", TOL)
    assert e.inside
    for bed in e.beds:
        at_2 = float(err.sel(calibration=bed.name, fs_v=2.0).values.ravel()[0])
        assert (bed.count, bed.bearing_failures) == (1, 1)
        assert bed.called == int(bed.name == first)
        assert bed.median == pytest.approx(at_2, rel=1e-12)
        assert bed.share_within == pytest.approx(((at_2 <= TOL) + (bed.name == first)) / 2,
                                                 rel=1e-12)
    text = "\n".join(am.format_evidence(e, TOL))
    assert "the continuum failed in bearing in 1 run(s) here" in text
    assert ("which no error of a bed measures" in text) is (e.best.name != first)


@pytest.mark.parametrize("override, words", [
    ("structure.height=5.0", ["h_over_B = 2.5", "1 above the map's range [1.5, 1.5]"]),
    ("soil.undrained_strength=40.0", ["soil.undrained_strength = 40.0",
                                      "the map's clay: 50.0"]),
    ("continuum.boundary=fixed", ["continuum.boundary = 'fixed'", "sides 'shear'"]),
    ("continuum.base=compliant", ["continuum.base = 'compliant'",
                                  "the map's runs have 'rigid' (its 'box' reference)"]),
    ("continuum.damping_ratio=0.01", ["continuum.damping_ratio = 0.01",
                                      "the map's runs have None (its 'box' reference)"]),
])
def test_scene_outside_the_map_says_which_parameter(fast_map, override, words):
    """Outside the map's box: the reason names the parameter, its value and the map's range."""
    scene = load_scene(SCENE, overrides=ON_MAP + [override])
    e = am.map_evidence(fast_map, scene, "theta", TOL)
    assert not e.inside and e.beds == ()
    for w in words:
        assert w in e.outside


G_CLAY = 50.0e3 / 2.6  # kPa: the map's clay, E = 50 MPa, ν = 0.3


def test_a_half_plane_map_is_evidence_only_for_a_half_plane_scene(fast_map, tmp_path):
    """The fast map marked as made on the half-plane reference (its ``options_reference``):
    the clay scene as it is (uniform c_u, rigid base) is outside, by its soil's strength
    gradient (the half-plane's clay: 1.7 kPa/m); with that gradient, by its base; then by the
    footing's tie (the handbook strip's K_h = 2G/(2 − ν) and C_h = ρ V_s B, by hand with
    G = 50 MPa/2.6, ν = 0.3, ρ = 1.8 t/m³, B = 2 m) and by the soil's damping (1 %); with all
    of the half-plane's, inside."""
    import shutil

    ds = read_dataset(fast_map)
    ds.attrs["options_reference"] = "half_plane"
    ds.to_netcdf(tmp_path / "map.nc")
    shutil.copyfile(fast_map.with_name("statics.nc"), tmp_path / "statics.nc")
    hp = ["soil.undrained_strength_gradient=1.7", "continuum.base=compliant"]
    tie = [f"continuum.horizontal_tie={2.0 * G_CLAY / 1.7!r}",
           f"continuum.horizontal_tie_damping={1.8 * math.sqrt(G_CLAY / 1.8) * 2.0!r}"]
    cases = [([], "soil.undrained_strength_gradient = 0.0 (the map's clay: 1.7)"),
             (["soil.undrained_strength_gradient=1.7"],
              "continuum.base = 'rigid': the map's runs have 'compliant' (its 'half_plane' "
              "reference)"),
             (hp, "continuum.horizontal_tie = None: the map's runs have 22624.43"),
             (hp + tie, "continuum.damping_ratio = None: the map's runs have 0.01"),
             (hp + tie + ["continuum.damping_ratio=0.02"],
              "continuum.damping_ratio = 0.02: the map's runs have 0.01"),
             (hp + tie + ["continuum.damping_ratio=0.01"], None)]
    for extra, words in cases:
        e = am.map_evidence(tmp_path / "map.nc", load_scene(SCENE, overrides=ON_MAP + extra),
                            "theta", TOL)
        assert e.inside is (words is None)
        if words is not None:
            assert words in e.outside and e.beds == ()


def _no_runs(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("a run started")

    monkeypatch.setattr(ac, "continuum_run", refuse)
    monkeypatch.setattr(ac, "soil_numbers", refuse)
    monkeypatch.setattr(adv.sve, "evaluate_point", refuse)


def test_budget_below_the_estimate_is_refused_before_any_run(monkeypatch, tmp_path, capsys):
    """--budget below the estimate, and no map: exit 2, one line naming --budget and the
    estimate (the same number the plan estimates), and no run of either model."""
    _no_runs(monkeypatch)
    monkeypatch.chdir(tmp_path)  # no results/winkler_map/map.nc here
    plan = ac.plan_continuum(load_scene(SCENE, overrides=ON_MAP), "theta", TOL, fast=True)
    args = ["advise", SCENE, "--quantity", "peak_theta", "--fast", "--budget", "1"]
    code = cli.main(args + [x for s in ON_MAP for x in ("--set", s)])
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert code == 2
    assert err.startswith("upliftlab: error: --budget = 1 s")
    assert f"estimated at {plan.estimate.seconds:.0f} s" in err and "no Winkler map" in err
    assert plan.estimate.seconds > 1.0


def _kept(checkout, rate: float, revision: int | None = None) -> None:
    """A kept map store under ``checkout`` with one timed dynamic run whose per-step rate
    (the wall time less the fixed cost, per DOF and step) is ``rate`` s, on a mesh (one DOF)
    that no ladder mesh has, so only its rate can change an estimate; ``revision``: the
    continuum revision it was made with (default today's)."""
    from upliftlab.comparisons.framework.store import Store, function_name, revisions
    from upliftlab.comparisons.studies.winkler_map.cost import FIXED_SECONDS_PER_DOF
    from upliftlab.comparisons.studies.winkler_map.points import evaluate_dynamic
    from upliftlab.comparisons.studies.winkler_map.workflow import KEPT_STORE

    dofs, steps = 1, 1000
    record = {"dofs": dofs, "steps": steps, "duration": 1.0, "compiled": True,
              "soil_model": "tresca",
              "wall_time_s": FIXED_SECONDS_PER_DOF[False] * dofs + rate * dofs * steps}
    models = revisions(evaluate_dynamic) if revision is None else {"continuum": revision}
    meta = {"function": function_name(evaluate_dynamic), "models": models}
    Store(checkout / KEPT_STORE).put("0" * 63 + "1", record, meta)


def test_the_ladders_estimate_is_at_the_kept_runs_rates(monkeypatch, tmp_path):
    """The estimate is linear in the per-step rate of the dynamic runs (the cost model:
    fixed + rate × DOFs × steps per run), so with kept runs at rates r1 and r2 and the default
    r0 (no kept store, or kept runs of another revision of the continuum), (E0 − E1)/(E0 − E2)
    = (r0 − r1)/(r0 − r2):
    a hand relation that holds only if the ladder is estimated at the kept runs' rate."""
    from upliftlab.comparisons.studies.winkler_map.cost import SECONDS_PER_DOF_STEP

    scene = load_scene(SCENE, overrides=ON_MAP)

    def estimate(rate=None, revision=None):
        checkout = tmp_path / f"checkout-{rate}-{revision}"
        checkout.mkdir()
        if rate is not None:
            _kept(checkout, rate, revision)
        monkeypatch.setattr(ac, "CHECKOUT", checkout)
        return ac.plan_continuum(scene, "theta", TOL, fast=False).estimate.seconds

    r0, r1, r2 = SECONDS_PER_DOF_STEP[True], 2.5e-8, 5.0e-8
    e0, e1, e2 = estimate(), estimate(r1), estimate(r2)
    assert e1 < e2 < e0
    assert (e0 - e1) / (e0 - e2) == pytest.approx((r0 - r1) / (r0 - r2), rel=1e-9)
    assert estimate(r1, revision=0) == pytest.approx(e0, rel=1e-12)  # another revision's runs


def test_over_budget_inside_the_map_gives_the_maps_verdict_without_running(
        monkeypatch, fast_map, capsys):
    """Over --budget but inside the map: the continuum is not run, nothing is certified
    (exit 3), and the map's evidence is reported as the map's."""
    _no_runs(monkeypatch)

    def reduced_refused(*args, **kwargs):
        raise adv.InputError("the reduced reference is not run in this test")

    monkeypatch.setattr(adv, "_reference", reduced_refused)
    args = ["advise", SCENE, "--quantity", "peak_theta", "--fast", "--budget", "1",
            "--map", str(fast_map)]
    code = cli.main(args + [x for s in ON_MAP for x in ("--set", s)])
    out = capsys.readouterr().out
    assert code == 3
    assert "the continuum was not run" in out and "map's evidence" in out
    assert "certifies nothing" in out and "beds against the continuum (measured" not in out
    err = read_dataset(fast_map)["error"].sel(soil="clay", measure="theta")
    medians = {str(c): float(np.nanmedian(np.abs(err.sel(calibration=c).values)))
               for c in err["calibration"].values}
    best = min(medians, key=medians.get)
    assert f"map's verdict (evidence, not a certification): {best} has the least median " \
           f"|error|, {100 * medians[best]:.3g} %" in out


def test_cli_json_fast(advice, fast_map, capsys):
    """The command line on the fast ladder: the JSON carries the continuum reference, its
    uncertainty and each bed's error, equal to the Python API's (a deterministic re-run)."""
    args = ["advise", SCENE, "--quantity", "peak_theta", "--tol", "10%", "--fast", "--json",
            "--map", str(fast_map)]
    code = cli.main(args + [x for s in ON_MAP for x in ("--set", s)])
    out = json.loads(capsys.readouterr().out)
    c, mine = out["continuum_advice"], advice.continuum_advice
    assert code == (0 if mine.recommendation is not None else 3)
    assert c["reference"]["value"] == pytest.approx(mine.reference.value, rel=1e-12)
    assert c["reference"]["uncertainty"] == pytest.approx(mine.reference.uncertainty,
                                                          rel=1e-12)
    assert c["reference"]["elements_across"] == 8
    assert c["certified_against"].startswith("the continuum (plane strain, explicit route) on "
                                             "8 elements across")
    for got, bed in zip(c["beds"], mine.beds):
        assert got["name"] == bed.name
        assert got["error"] == pytest.approx(bed.error, rel=1e-12, nan_ok=True)
    assert c["map"]["inside"] is True


@pytest.mark.parametrize("args, words", [
    (["--budget", "0"], ["--budget = 0", "valid range is (0, 1e+09]"]),
    (["--budget", "nan"], ["--budget = nan", "valid range"]),
    (["--map", "no/such/map.nc"], ["--map = 'no/such/map.nc'", "no such file"]),
    (["--set", "continuum.elements_across=4"], ["has no effect", "continuum.elements_across"]),
])
def test_cli_bad_continuum_options_refused_before_any_run(args, words, monkeypatch, capsys):
    """Bad --budget, a missing --map and an override of the mesh the ladder chooses: exit 2,
    one line naming the option, and no run of either model."""
    _no_runs(monkeypatch)
    code = cli.main(["advise", SCENE, "--fast"] + args)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    for w in words:
        assert w in err[0]


@pytest.mark.parametrize("option", ["--map", "--macro-calibration"])
# a device: /dev/null, not /dev/zero, so that code which opened it would read nothing, not fill
# the memory (the old --macro-calibration read /dev/zero until the kernel killed it)
@pytest.mark.parametrize("given, kind", [("adir", "a folder"), ("fifo.txt", "a named pipe"),
                                         ("/dev/null", "a character device")])
def test_a_map_or_calibration_that_is_not_a_regular_file_says_what_it_is(
        option, given, kind, tmp_path, monkeypatch, capsys, fifo):
    """--map of a folder or a named pipe was refused as 'no such file'; --macro-calibration of
    a named pipe waited for a writer until killed. One line naming the option, the path and
    what it is, before any run; the pipe is never opened."""
    _no_runs(monkeypatch)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "adir").mkdir()
    fifo("fifo.txt")
    code = cli.main(["advise", SCENE, "--fast", option, given])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert err[0].startswith(f"upliftlab: error: {option} = '{given}': {kind}, not a regular "
                             "file; "), err


@pytest.mark.parametrize("args", [["--budget", "100"], ["--map", "map.nc"]])
def test_continuum_options_on_a_scene_without_soil_are_refused(args, monkeypatch, capsys):
    """--budget and --map have no effect on a scene without [soil]: refused in one line
    before any run (the project's rule for inputs without effect)."""
    _no_runs(monkeypatch)
    code = cli.main(["advise", "short_period_elcentro", "--case", "B", "--fast"] + args)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert f"{args[0]}: has no effect" in err[0] and "no [soil] table" in err[0]


def test_a_file_that_is_not_a_map_is_refused(tmp_path):
    """--map pointing at a NetCDF file without the map's variables: one InputError naming what
    is missing, before any run."""
    import xarray as xr

    from upliftlab.results import write_dataset

    path = write_dataset(tmp_path / "other.nc", xr.Dataset({"x": ("n", np.arange(3.0))}))
    scene = load_scene(SCENE, overrides=ON_MAP)
    with pytest.raises(adv.InputError, match=r"--map = .*other.nc.*not a Winkler map \(no error"):
        am.map_evidence(path, scene, "theta", TOL)


def test_the_scenes_fs_v_is_on_the_whole_weight_on_its_footing():
    """FS_v = V_ult/N with N the whole weight the footing carries (``vertical_weight``), not
    the story's share: a footing carrying 1 % of N itself (the half-plane map's points) sits
    at the map's FS_v, by the definition FS_v = V_ult/N."""
    scene = load_scene(SCENE, overrides=ON_MAP)
    N = scene.structure.weight
    shared = load_scene(SCENE, overrides=ON_MAP + [f"structure.weight={0.99 * N!r}",
                                                   f"structure.vertical_weight={N!r}"])
    for s in (scene, shared):
        assert am.scene_coordinates(s, 3.0 * N)["fs_v"] == pytest.approx(3.0, rel=1e-12)


def test_a_calibration_puts_the_macro_element_in_the_ladder(tmp_path):
    """With ``upliftlab calibrate``'s record (here the clay's law of the map's calibration,
    ``benchmarks/macro_calibration.json``, written as that record) the ``macro`` bed is built
    from the ladder's statics under the scene's structure (given a footing mass to sway with)
    and run like any bed: its value is a direct reduced run's (1e-12) and its modelled cost
    adds the element's stated seconds per step to the springs' model (closed form). A record
    of another footing width, or a file that is no record, is refused in one line before any
    run."""
    from pathlib import Path

    from upliftlab.budget import MACRO_SECONDS_PER_STEP
    from upliftlab.checks import InputError
    from upliftlab.comparisons.advise.macro import read_macro_calibration

    law = json.loads((Path(__file__).resolve().parent.parent / "benchmarks"
                      / "macro_calibration.json").read_text())["clay"]["law"]
    path = tmp_path / "calibration.json"
    path.write_text(json.dumps({"scene": "strip_footing_clay", "law": law}))
    scene = load_scene(SCENE, overrides=ON_MAP + ["structure.vertical_weight=180.0"])
    statics = ac.SoilNumbers(8, 27500.0, 43100.0, 530.0, 530.0 / 180.0, 1.0)
    reference = ac.bed_reference(scene, statics, None, None, read_macro_calibration(path, scene))
    table = bed_foundation("macro", reference, FAST_OPTIONS)
    r = ac.bed_run(scene, table, repeats=1)
    data = copy.deepcopy(scene.data)
    data["foundation"] = table
    del data["soil"], data["continuum"]
    response = reduced_run(scene_from_dict(data, merged=True))
    value = max(float(np.max(np.abs(response.theta))), float(response.peaks["theta"]))
    assert r["measures"]["theta"] == pytest.approx(value, rel=1e-12)
    work = r["work"]
    springs_model = ac.RUN_SECONDS + ac.SPRING_CALL_SECONDS[work.integrator] * work.rhs_calls * (
        work.springs + ac.SPRING_OFFSET)
    assert work.seconds == pytest.approx(springs_model + MACRO_SECONDS_PER_STEP * work.steps,
                                         rel=1e-12)
    wide = tmp_path / "wide.json"
    wide.write_text(json.dumps({"law": {**law, "width": 3.0}}))
    with pytest.raises(InputError, match="made for a footing 3 wide, the scene's is 2"):
        read_macro_calibration(wide, scene)
    with pytest.raises(InputError, match="not a calibration written by `upliftlab calibrate`"):
        read_macro_calibration(fast_path := tmp_path / "nothing.json", scene)
    assert not fast_path.exists()
