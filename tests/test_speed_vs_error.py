"""The speed-against-error study (fast panel: two short pulses on the short-period building,
Winkler beds N = 10, 40, 160, every integrator at two or three steps).

References: the study's own converged reference (event stepper, N = 160, Δt = 6.25e-4 s),
checked by the change from the next-finer level (half the springs, twice the step); the edge
gap of a bed computed exactly from its stored histories (b|θ| + V − δ₀ + ε_p at each stored
state); a hand-built Pareto front. Runtimes are never asserted.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.studies import speed_vs_error as sve
from upliftlab.comparisons.framework.measures import reduced_edge_uplift_from_peaks
from upliftlab.comparisons.framework.store import Store
from upliftlab.reduced import run


@pytest.fixture(scope="module")
def study(tmp_path_factory, fast_stores):
    """The fast study, its points published for the report's test (conftest.FastStores)."""
    out = tmp_path_factory.mktemp("speed_vs_error")
    made = sve.run(fast=True, out=out, progress=False)
    fast_stores.publish("speed_vs_error", out / "store")
    return made


def _scenes(ds) -> list[str]:
    return ds.scene.values.tolist()


def _winkler(ds, label, integrator):
    """The runs of Winkler beds of ``integrator`` in scene ``label`` at the finest step it ran
    on any bed, by N: {N: (dt in s, the run's cells over quantity)}."""
    beds = [m for m, layout in zip(ds.model.values.tolist(), ds.layout.values.tolist())
            if layout == "winkler"]
    one = ds.sel(scene=label, integrator=integrator, model=beds)
    finest = float(one.dt.where(one.ran == 1).min())
    out = {}
    for model in beds:
        at = one.sel(model=model)
        for level in at.level.values.tolist():
            cell = at.sel(level=level)
            if int(cell.ran) and math.isclose(float(cell.dt), finest):
                out[int(ds.springs.sel(model=model))] = cell
    return out


def _abs_error(cells, quantity: str) -> float:
    return abs(float(cells.error.sel(quantity=quantity)))


def test_references_converge_to_one_percent(study):
    """Each fast scene's reference changes by ≤ 1 % (the stated tolerance) from half the
    springs and from twice the step, in all four quantities."""
    ds = study.data
    assert ds.attrs["options_convergence_tolerance"] == 0.01
    for label in _scenes(ds):
        one = ds.sel(scene=label)
        converged = sve.converged(ds, label)
        for q in sve.QUANTITIES:
            assert float(one.change_half_springs.sel(quantity=q)) <= 0.01, (label, q)
            assert float(one.change_double_dt.sel(quantity=q)) <= 1e-3, (label, q)
            assert converged[q]
        assert float(one.reference.sel(quantity="uplift")) > 0.0  # both pulses uplift the base
    assert study.study.numbers["scenes"]["sine-2a_up-B"]["reference"]["springs"] == 160


def test_errors_decrease_with_springs(study):
    """Event stepper at its finest ladder step: the error in peak edge uplift falls
    monotonically with N, at least as N^-0.5 between 10 and 40 springs (measured ≈ N^-0.8),
    and the 10-spring bed beats the equivalent two springs."""
    ds = study.data
    for label in _scenes(ds):
        by_n = _winkler(ds, label, "events")
        errors = [_abs_error(by_n[n], "uplift") for n in (10, 40, 160)]
        assert errors[0] > errors[1] > errors[2], (label, errors)
        rate = math.log(errors[0] / errors[1]) / math.log(4.0)
        assert rate > 0.5, (label, rate)
        two = ds.sel(scene=label, model="equivalent", integrator="events")
        ran = two.error.sel(quantity="uplift").where(two.ran == 1)
        assert int((two.ran == 1).sum()) > 0
        assert float(abs(ran).min()) > errors[0]


def test_errors_decrease_with_step(study):
    """On the reference bed (N = 160), halving the event stepper's step reduces the error in
    peak u and peak θ at every level; the finest ladder level is within 0.01 %."""
    ds = study.data
    for label in _scenes(ds):
        bed = ds.sel(scene=label, model="N=160", integrator="events")
        levels = sorted((lv for lv in bed.level.values.tolist()
                         if int(bed.ran.sel(level=lv))),
                        key=lambda lv: -float(bed.dt.sel(level=lv)))
        assert len(levels) == 3
        dts = [float(bed.dt.sel(level=lv)) for lv in levels]
        assert [dt / dts[0] for dt in dts] == pytest.approx([1.0, 0.5, 0.25])
        for q in ("u", "theta"):
            e = [abs(float(bed.error.sel(level=lv, quantity=q))) for lv in levels]
            assert e[0] > e[1] > e[2], (label, q, e)
            assert e[2] < 1e-4


def test_pareto_front_of_the_study(study):
    """Every front is sorted by runtime with strictly falling |error|, and no evaluated point is
    both faster and more accurate than any point on it."""
    ds = study.data
    for label in _scenes(ds):
        points = sve.runs(ds, label)
        for q in sve.QUANTITIES:
            front = sve.front(points, q)
            assert front, (label, q)
            times = [p.runtime for p in front]
            errs = [p.abs_error(q) for p in front]
            assert times == sorted(times)
            assert all(b < a for a, b in zip(errs, errs[1:]))
            for f in front:
                assert not any(p.runtime < f.runtime and p.abs_error(q) < f.abs_error(q)
                               for p in points)


def test_pareto_front_by_hand():
    """(runtime, error): (1, 0.5), (2, 0.6), (3, 0.1), (3, 0.05), (4, nan), (5, 0.01)."""
    runtimes = [1.0, 2.0, 3.0, 3.0, 4.0, 5.0]
    errors = [0.5, -0.6, 0.1, 0.05, math.nan, -0.01]
    assert sve.pareto_front(runtimes, errors) == [0, 3, 5]


def test_edge_uplift_against_histories(elcentro, study):
    """The edge uplift estimate (peak spring gap + (b − |x|)·θ_peak) of a 40-spring bed is
    within 1 % of the exact edge gap sampled from the histories (which cannot exceed it by
    more than the sampling misses)."""
    scene = sve.load_spec(sve.FAST_GRID.scenes[0]).with_overrides("foundation.springs=40")
    r = run(scene, output_dt=0.0005)
    m = r.model
    found = m.foundation_slice
    x, d0 = m.params["x"][found], m.params["d0"][found]
    ep = r.plastic[:, found]
    b = m.layout.half_width
    left, right = int(np.argmin(x)), int(np.argmax(x))
    exact = max((b * r.theta + r.V - d0[left] + ep[:, left]).max(),
                (-b * r.theta + r.V - d0[right] + ep[:, right]).max())
    assert reduced_edge_uplift_from_peaks(r) == pytest.approx(exact, rel=0.01)


def test_rerun_recomputes_nothing(study, tmp_path):
    """Running again on the same store evaluates no point: the store does not grow and every
    runtime is the stored one (runtimes are stored with their measurement context)."""
    store = Store(study.study.directory / "store")
    before = len(store)
    again = sve.run(fast=True, out=tmp_path / "again", store=store, progress=False,
                    options=sve.Options(figures=False))
    assert len(store) == before
    for label in _scenes(study.data):  # a refused run's runtime is NaN on both
        np.testing.assert_array_equal([p.runtime for p in sve.runs(study.data, label)],
                                      [p.runtime for p in sve.runs(again.data, label)])
    np.testing.assert_array_equal(again.data.runtime, study.data.runtime)
    assert again.data.attrs["sessions"] == 1

    def context(ds):
        return {k: v for k, v in ds.attrs.items() if k.startswith("context_")}

    assert context(again.data) == context(study.data)


def test_summary_is_computed_and_states_continuum(study):
    numbers = study.study.numbers
    assert "continuum" in study.study.summary.lower()
    assert "not run" in numbers["continuum"] or "continuum points" in numbers["continuum"]
    assert numbers["measurement_context"]["threads"] == 1
    cheapest = numbers["scenes"]["sine-2a_up-B"]["cheapest"]["uplift"]["0.01"]
    assert cheapest is not None and abs(cheapest["errors"]["uplift"]) <= 0.01
    names = {p.name for p in study.study.files}
    assert {"points.csv", "pareto.csv", "speed_vs_error.nc", "summary.md",
            "summary.json"} <= names


def test_the_folder_opens_again_as_the_same_labelled_data(study):
    """:func:`upliftlab.open_study` of the study's folder: the dataset it wrote, selected by
    label, holds the references of ``summary.json`` (bit for bit), with units; the summary and
    the key numbers computed from it are the ones written."""
    import json

    from upliftlab import open_study

    folder = study.study.directory
    ds = open_study(folder)["speed_vs_error"].to_dataset()
    written = json.loads((folder / "summary.json").read_text())["numbers"]
    assert ds.dt.attrs["units"] == "s" and ds.runtime.attrs["units"] == "s"
    for label, scene in written["scenes"].items():
        for q in sve.QUANTITIES:
            at = ds.sel(scene=label, quantity=q)
            assert float(at.reference) == scene["reference"]["values"][q]
            assert float(at.change_half_springs) == scene["reference"]["change_half_springs"][q]
    assert sve.summarise(ds) == (folder / "summary.md").read_text()
    assert json.loads(json.dumps(sve.key_numbers(ds), default=float)) == written


@pytest.mark.parametrize("change, message", [
    ({"springs": (40, 10, 160)}, "grid.springs"),
    ({"springs": (10, 41)}, "grid.springs[-1] = 41"),
    ({"integrators": ("events", "euler")}, "grid.integrators[1] = 'euler'"),
    ({"event_levels": 0}, "grid.event_levels"),
    ({"reference_dt": 0.5}, "grid.reference_dt = 0.5: valid range is (0, 0.01]"),
    ({"scenes": ()}, "grid.scenes"),
])
def test_bad_grid_is_refused(change, message, tmp_path):
    with pytest.raises(InputError, match=message.replace("[", r"\[").replace("(", r"\(")
                       .replace("]", r"\]").replace(")", r"\)")):
        sve.run(fast=True, out=tmp_path, grid=replace(sve.FAST_GRID, **change), progress=False)
    assert not (tmp_path / "store").exists()


def test_bad_options_are_refused(tmp_path):
    with pytest.raises(InputError, match=r"options.tolerances\[0\] = 1.5"):
        sve.run(fast=True, out=tmp_path, options=sve.Options(tolerances=(1.5,)))
    with pytest.raises(InputError, match="options.convergence_tolerance = 0"):
        sve.run(fast=True, out=tmp_path, options=sve.Options(convergence_tolerance=0.0))


def test_a_refused_warm_up_does_not_make_the_point_an_error(monkeypatch):
    """The clay scene's 20 ms warm-up was refused by the energy check (its Ricker pulse has put
    almost no energy in by then: 2.1 × the input, before the check's scale counted the static
    energies; it now runs). A refused warm-up (made here to raise) still leaves the kernels
    loaded and the point itself runs: its measures equal a direct reduced run of the same
    scene (1e-12)."""
    from upliftlab.comparisons.studies.speed_vs_error import points as svp
    from upliftlab.reduced import IntegrationError
    from upliftlab.scenes import load_scene

    scene = load_scene("strip_footing_clay", overrides=["motion.duration=0.5"])
    tiny = scene.with_overrides("foundation.layout='edges'", "foundation.springs=2",
                                "analysis.duration=0.02", "analysis.dt=")
    assert run(tiny, integrator="events", histories=False).peaks["theta"] > 0
    real, refused = svp.run_reduced, []

    def refuse_the_warm_up(s, **kw):
        if s.analysis.duration == 0.02:
            refused.append(s)
            raise IntegrationError("energy balance: refused for this test")
        return real(s, **kw)

    monkeypatch.setattr(svp, "run_reduced", refuse_the_warm_up)
    monkeypatch.setattr(svp, "_WARM", set())
    point = {"scene": scene.data, "model": "winkler", "springs": 20, "integrator": "events",
             "step": {"dt": 0.005}, "repeats": 1, "repeat_budget": 0.5}
    out = svp.evaluate_point(point)
    assert "error" not in out, out
    assert len(refused) == 1 and "events" in svp._WARM
    direct = run(svp.point_scene(point), integrator="events", dt=0.005, histories=False)
    assert out["theta"] == pytest.approx(direct.peaks["theta"], rel=1e-12)
    assert out["u"] == pytest.approx(direct.peaks["u"], rel=1e-12)


def test_its_files_pass_the_cf_checker(study, cf_failures):
    # Reference: the IOOS compliance checker, cf:1.10 (tests/test_cf.py says which): no
    # failing required check and no check that raised, in every NetCDF file of the folder.
    from upliftlab.study_files import study_files

    files = study_files(study.study.directory)
    assert files
    for name, path in files.items():
        assert cf_failures(path) == ([], []), name
