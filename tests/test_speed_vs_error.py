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
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("speed_vs_error")
    return sve.run(fast=True, out=out, progress=False)


def _winkler(scene, integrator, rank_dt=None):
    """Winkler points of ``integrator`` by N at the finest step it ran (dict N -> Point)."""
    pts = [p for p in scene.points if p.model == "winkler" and p.integrator == integrator]
    dt = min(p.dt for p in pts) if rank_dt is None else rank_dt
    return {p.springs: p for p in pts if math.isclose(p.dt, dt)}


def test_references_converge_to_one_percent(study):
    """Each fast scene's reference changes by ≤ 1 % (the stated tolerance) from half the
    springs and from twice the step, in all four quantities."""
    for s in study.scenes:
        ref = s.reference
        assert ref.tolerance == 0.01
        for q in sve.QUANTITIES:
            assert ref.change_springs[q] <= 0.01, (s.label, q)
            assert ref.change_dt[q] <= 1e-3, (s.label, q)
            assert ref.converged[q]
        assert ref.values["uplift"] > 0.0  # both pulses uplift the base
    assert study.study.numbers["scenes"]["sine-2a_up-B"]["reference"]["springs"] == 160


def test_errors_decrease_with_springs(study):
    """Event stepper at its finest ladder step: the error in peak edge uplift falls
    monotonically with N, at least as N^-0.5 between 10 and 40 springs (measured ≈ N^-0.8),
    and the 10-spring bed beats the equivalent two springs."""
    for s in study.scenes:
        by_n = _winkler(s, "events")
        errors = [by_n[n].abs_error("uplift") for n in (10, 40, 160)]
        assert errors[0] > errors[1] > errors[2], (s.label, errors)
        rate = math.log(errors[0] / errors[1]) / math.log(4.0)
        assert rate > 0.5, (s.label, rate)
        two = [p for p in s.points if p.model == "equivalent" and p.integrator == "events"]
        assert min(p.abs_error("uplift") for p in two) > errors[0]


def test_errors_decrease_with_step(study):
    """On the reference bed (N = 160), halving the event stepper's step reduces the error in
    peak u and peak θ at every level; the finest ladder level is within 0.01 %."""
    for s in study.scenes:
        pts = sorted((p for p in s.points if p.model == "winkler" and p.springs == 160
                      and p.integrator == "events"), key=lambda p: -p.dt)
        assert len(pts) == 3
        assert [p.dt / pts[0].dt for p in pts] == pytest.approx([1.0, 0.5, 0.25])
        for q in ("u", "theta"):
            e = [p.abs_error(q) for p in pts]
            assert e[0] > e[1] > e[2], (s.label, q, e)
            assert e[2] < 1e-4


def test_pareto_front_of_the_study(study):
    """Every front is sorted by runtime with strictly falling |error|, and no evaluated point is
    both faster and more accurate than any point on it."""
    for s in study.scenes:
        for q in sve.QUANTITIES:
            front = s.front(q)
            assert front, (s.label, q)
            times = [p.runtime for p in front]
            errs = [p.abs_error(q) for p in front]
            assert times == sorted(times)
            assert all(b < a for a, b in zip(errs, errs[1:]))
            for f in front:
                assert not any(p.runtime < f.runtime and p.abs_error(q) < f.abs_error(q)
                               for p in s.points)


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
    for s1, s2 in zip(study.scenes, again.scenes):
        assert [p.runtime for p in s1.points] == [p.runtime for p in s2.points]
    assert again.sessions == 1
    assert again.context == study.context


def test_summary_is_computed_and_states_continuum(study):
    numbers = study.study.numbers
    assert "continuum" in study.study.summary.lower()
    assert "not run" in numbers["continuum"] or "continuum points" in numbers["continuum"]
    assert numbers["measurement_context"]["threads"] == 1
    cheapest = numbers["scenes"]["sine-2a_up-B"]["cheapest"]["uplift"]["0.01"]
    assert cheapest is not None and abs(cheapest["errors"]["uplift"]) <= 0.01
    names = {p.name for p in study.study.files}
    assert {"points.csv", "pareto.csv", "summary.md", "summary.json"} <= names


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
    """The clay scene's 20 ms warm-up is refused by the energy check (its Ricker pulse has put
    almost no energy in by then: measured 2.1 × the input), yet the kernels are loaded and the
    point itself runs: its measures equal a direct reduced run of the same scene (1e-12)."""
    from upliftlab.comparisons.studies.speed_vs_error import points as svp
    from upliftlab.reduced import IntegrationError
    from upliftlab.scenes import load_scene

    scene = load_scene("strip_footing_clay", overrides=["motion.duration=0.5"])
    tiny = scene.with_overrides("foundation.layout='edges'", "foundation.springs=2",
                                "analysis.duration=0.02", "analysis.dt=")
    with pytest.raises(IntegrationError, match="energy balance"):
        run(tiny, integrator="events", histories=False)
    monkeypatch.setattr(svp, "_WARM", set())
    point = {"scene": scene.data, "model": "winkler", "springs": 20, "integrator": "events",
             "step": {"dt": 0.005}, "repeats": 1, "repeat_budget": 0.5}
    out = svp.evaluate_point(point)
    assert "error" not in out, out
    assert "events" in svp._WARM
    direct = run(svp.point_scene(point), integrator="events", dt=0.005, histories=False)
    assert out["theta"] == pytest.approx(direct.peaks["theta"], rel=1e-12)
    assert out["u"] == pytest.approx(direct.peaks["u"], rel=1e-12)
