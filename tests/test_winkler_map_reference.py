"""The Winkler map's continuum reference (``Options.reference``, comparisons/studies/winkler_map/
reference.py) and the verdicts on its runs counted apart (verdicts.py).

References:
- the kept store ``benchmarks/winkler_map_store``, made by earlier code: the default ``box``
  reference's points of a slice of the grid are all in it (their keys unchanged), and none of
  the half-plane's dynamic or clay statics points is (read only; nothing is written there);
- the handbook strip's sway (Gazetas 1991, Table 1, strip): K_h = 2G/(2 − ν) and C_h = ρ V_s B,
  evaluated here by hand for the map's soils (E = 50 MPa, ν = 0.3, ρ = 1.8 t/m³, B = 2 m):
  G = 19,230.769 kPa, K_h = 22,624.434 kN/m/m, V_s = 103.362 m/s, C_h = 372.104 kN s/m/m;
- the soil's Rayleigh β on the half-plane by hand: ξ = 1 % at f₁ = V_s/(4H), f₂ = 5 f₁ with
  H = 10 B = 20 m: f₁ = 1.292 Hz, β = 2ξ/(2π · 6 f₁) = 4.1061e-4 s (Rayleigh's pair,
  e.g. Chopra, Dynamics of Structures, §11.4);
- the counts of the verdicts by hand from four stand-in records whose outcomes are known.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from upliftlab.checks import InputError
from upliftlab.cli import main as cli_main
from upliftlab.comparisons.beds import BEDS, base_table, bed_names
from upliftlab.comparisons.beds.continuum_points import evaluate_continuum
from upliftlab.comparisons.framework.protocol import CHECKOUT, Context
from upliftlab.comparisons.framework.store import Store
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.comparisons.studies.winkler_map.assemble import _continuum_into
from upliftlab.comparisons.studies.winkler_map.dataset import PointArrays
from upliftlab.comparisons.studies.winkler_map.plan import (dynamic_points, map_rocking_points,
                                                            plan_map, point_key_of, scene_of)
from upliftlab.comparisons.studies.winkler_map.points import evaluate_dynamic, point_table
from upliftlab.comparisons.studies.winkler_map.reference import reference_soil
from upliftlab.comparisons.studies.winkler_map.statics import evaluate_static, static_points
from upliftlab.comparisons.studies.winkler_map.verdicts import verdict_counts, verdict_lines
from upliftlab.comparisons.studies.winkler_map.workflow import (KEPT_STORES, _arguments,
                                                                _check_store_reference,
                                                                _context_from)
from upliftlab.continuum.dynamics.validity import BEYOND, WITHIN

KEPT = Path(__file__).resolve().parents[1] / "benchmarks" / "winkler_map_store"
#: A slice of the full grid the kept store holds: the clay's pulses at h/B 1.5, T 0.5 s.
SLICE = replace(wm.FULL_GRID, soils=("clay",), fs_v=(3.0, 5.0, 10.0), h_over_B=(1.5,),
                periods=(0.5,), intensities=(1.5, 3.0), pulse_periods=(0.25, 0.6),
                elcentro=False, fema_components=0)
G = 50.0e3 / (2.0 * 1.3)  # kPa
K_H, C_H = 2.0 * G / 1.7, 1.8 * math.sqrt(G / 1.8) * 2.0  # 22624.434..., 372.104...


def _points(reference: str, tmp_path):
    """The slice's static, dynamic and rocking points on ``reference``, N from the capacity in
    that reference's kept store."""
    options = replace(wm.FULL_OPTIONS, reference=reference)
    store = Store(CHECKOUT / KEPT_STORES[reference])
    motions = wm.study_motions(SLICE, options, tmp_path)
    base, g, statics, records, _, _ = plan_map(SLICE, options, bed_names(options), motions,
                                               store)
    V_ult = store.get(point_key_of(static_points("clay", options, 1.0)[1],
                                   evaluate_static))["capacity"]
    dynamic = dynamic_points(SLICE, options, motions, base, g, {"clay": V_ult})
    rocking = map_rocking_points(SLICE, options, base, {"clay": V_ult})
    return statics, dynamic, rocking


@pytest.mark.parametrize("reference, other", [("box", "half_plane"), ("half_plane", "box")])
def test_each_reference_finds_its_slice_in_its_kept_store_and_none_in_the_others(
        tmp_path, reference, other):
    """The slice's runs (the clay's pulses at h/B 1.5, T 0.5 s; both kept stores hold them)
    are found in the reference's own kept store, every one, and none in the other's: the two
    references' keys differ (their soils, bases, ties and damping are in the points)."""
    statics, dynamic, rocking = _points(reference, tmp_path)
    assert len(dynamic) == 12 and len(rocking) == 6
    mine, theirs = (Store(CHECKOUT / KEPT_STORES[r]) for r in (reference, other))
    for points, function in ((statics, evaluate_static), (dynamic, evaluate_dynamic),
                             (rocking, evaluate_continuum)):
        keys = [point_key_of(p, function) for p in points]
        assert all(mine.has(k) for k in keys)
        assert not any(theirs.has(k) for k in keys)


@pytest.mark.parametrize("soil", ["clay", "sand"])
def test_the_half_plane_point_is_the_compliant_base_the_shear_sides_and_the_handbook_tie(soil):
    table = point_table(base_table(), soil, 16, 150.0, 1.5, 0.5, 9.80665, "half_plane")
    scene = scene_of(table)
    c = scene.continuum
    assert (c.base, c.boundary) == ("compliant", "shear")
    assert c.horizontal_tie == pytest.approx(K_H, rel=1e-12)
    assert c.horizontal_tie_damping == pytest.approx(C_H, rel=1e-12)
    assert (c.horizontal_tie, c.horizontal_tie_damping) == pytest.approx((22624.434, 372.104),
                                                                         abs=1e-3)
    # the footing carries 1 % of N on the half-plane (a swaying base's mass), the story the rest
    assert (scene.structure.vertical_weight, scene.structure.weight) == pytest.approx(
        (150.0, 148.5), rel=1e-12)
    gradient = {"clay": 1.7, "sand": 0.0}[soil]
    assert scene.soil.undrained_strength_gradient == gradient
    box = point_table(base_table(), soil, 16, 150.0, 1.5, 0.5, 9.80665)
    assert box["soil"] == wm.SOILS[soil] and scene_of(box).continuum.base == "rigid"
    assert scene_of(box).continuum.horizontal_tie is None
    assert scene_of(box).structure.vertical_weight == scene_of(box).structure.weight == 150.0
    # the sand's table is the map's as it is; the clay's only adds its gradient
    assert {k: v for k, v in table["soil"].items()
            if k != "undrained_strength_gradient"} == wm.SOILS[soil]
    assert reference_soil(soil, "half_plane") == table["soil"]


@pytest.mark.parametrize("reference", ["box", "half_plane"])
def test_a_bed_sways_on_the_half_planes_tie_and_not_in_the_box(reference):
    """A bed on a half-plane point sways on the continuum's tie (K_h, C_h by hand above); in
    the box, whose footing does not sway, it has no sway spring (Ewing's fixed base)."""
    from upliftlab.comparisons.studies.winkler_map.bed_runs import bed_scene

    table = point_table(base_table(), "clay", 16, 150.0, 1.5, 0.5, 9.80665, reference)
    point = {"scene": table, "motion": {"type": "ricker", "period": 0.25, "duration": 0.75},
             "intensity": 1.5}
    foundation = dict(table["foundation"])
    scene = bed_scene(point, foundation)
    f = scene.foundation
    if reference == "half_plane":
        assert (f.sway_stiffness, f.sway_damping) == pytest.approx((K_H, C_H), rel=1e-12)
    else:
        assert (f.sway_stiffness, f.sway_damping) == (None, None)
    # the soil's small-strain damping: in the continuum's scene and, as β k_i, in the bed's
    from upliftlab.reduced.compatibility import layout_for

    stiffnesses = np.asarray(layout_for(f).stiffnesses)
    if reference == "half_plane":
        assert scene_of(table).continuum.damping_ratio == 0.01
        f1 = math.sqrt(G / 1.8) / (4.0 * 20.0)
        beta = 2.0 * 0.01 / (2.0 * math.pi * 6.0 * f1)
        assert beta == pytest.approx(4.1061e-4, rel=1e-4)
        assert np.asarray(f.dashpots) == pytest.approx(beta * stiffnesses, rel=1e-9)
    else:
        assert scene_of(table).continuum.damping_ratio is None
        assert not np.any(np.asarray(f.dashpots or [0.0]))
    assert scene.motion.amplitude == pytest.approx(1.5 * 2.0 / (6.0 * 3.0), rel=1e-12)


def test_a_bad_reference_is_refused_in_one_line(tmp_path, capsys):
    with pytest.raises(InputError) as info:
        wm.check_options(replace(wm.FULL_OPTIONS, reference="halfplane"), tuple(BEDS))
    assert str(info.value) == ("options.reference = 'halfplane': must be one of 'box', "
                               "'half_plane'")
    code = cli_main(["study", "winkler_map", "--fast", "--out", str(tmp_path / "o"),
                     "--reference", "plane", "--no-figures"])
    assert code == 2 and not (tmp_path / "o").exists()
    assert "options.reference = 'plane': must be one of 'box', 'half_plane'" in \
        capsys.readouterr().err
    parser = argparse.ArgumentParser()
    _arguments(parser)
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--no-figures", action="store_true")
    for argv, expected in ((["--no-figures"], "box"),
                           (["--no-figures", "--reference", "half_plane"], "half_plane")):
        ctx = _context_from(parser.parse_args(argv), Context(), print)
        assert ctx.options.reference == expected


def test_a_reference_refuses_the_other_references_kept_store(tmp_path):
    box, half = (CHECKOUT / KEPT_STORES[r] for r in ("box", "half_plane"))
    assert box.resolve() == KEPT.resolve() and box.parent == half.parent and box != half
    with pytest.raises(InputError, match=r"^store = '.*winkler_map_store': the kept store of "
                                         r"the 'box' reference; valid for options\.reference "
                                         r"= 'half_plane'"):
        _check_store_reference(Store(box), "half_plane")
    with pytest.raises(InputError, match="the kept store of the 'half_plane' reference"):
        _check_store_reference(half, "box")
    for reference in ("box", "half_plane"):
        _check_store_reference(Store(tmp_path / "store"), reference)  # any other folder
    _check_store_reference(Store(box), "box")
    _check_store_reference(None, "half_plane")


def _arrays_of_four_runs():
    """The arrays of a 2 × 2 point grid filled from four stand-in runs: compared with an
    elastic far field; compared with a yielded one; beyond the small-strain reference with a
    yielded far field; a run the solver gave up on (nothing recorded)."""
    measures = {q: 1.0 for q in wm.MEASURES}
    done = {"measures": measures, "wall_time_s": 1.0, "steps": 10, "energy_balance_error": 0.0,
            "dofs": 100, "validity": WITHIN, "max_plastic_strain": 0.01}
    runs = [{**done, "far_field": "elastic"}, {**done, "far_field": "from 0 to 3.5"},
            {**done, "validity": BEYOND, "max_plastic_strain": 0.3,
             "far_field": "from 0 to 20"},
            {"error": "ConvergenceError: stand-in", "soil_model": "tresca", "wall_time_s": 1.0}]
    shape = (1, 1, 1, 1, 2, 2)
    a, refusals = PointArrays.empty(shape, 1), []
    kept = [_continuum_into(a, (0, 0, 0, 0, i // 2, i % 2), run, None, f"point {i}", refusals)
            for i, run in enumerate(runs)]
    return a, refusals, kept


def test_the_far_field_and_the_small_strain_verdict_are_marked_point_by_point():
    a, refusals, kept = _arrays_of_four_runs()
    assert kept == [True, True, False, False]
    np.testing.assert_array_equal(a.far_yield.reshape(-1), [0, 1, 1, -1])
    np.testing.assert_array_equal(a.beyond.reshape(-1), [False, False, True, False])
    assert len(refusals) == 2 and BEYOND in refusals[0]


def test_the_summary_counts_the_verdicts_apart():
    a, _, _ = _arrays_of_four_runs()
    dims = ("soil", "fs_v", "h_over_B", "period", "intensity", "motion")
    m = xr.Dataset({"continuum_wall_time": (dims, a.continuum_wall),
                    "continuum_beyond_small_strain": (dims, a.beyond.astype("i1")),
                    "continuum_far_field_yielded": (dims, a.far_yield)},
                   attrs={"options_reference": "half_plane", "options_elements_across": 16,
                          "options_springs": 48, "options_settlement_ratio": 0.05,
                          "options_theta_ratios": [2.0], "options_cycle_ratios": [2.0],
                          "options_theta_tolerance": 0.1, "options_settlement_tolerance": 0.2,
                          "options_figures": 0})
    assert verdict_counts(m) == {"reference": "half_plane", "points": 4,
                                 "beyond_small_strain": 1, "far_field_yielded": 2,
                                 "far_field_yielded_compared": 1, "far_field_elastic": 1,
                                 "far_field_not_recorded": 1}
    text = " ".join(verdict_lines(m))
    assert "the half-plane" in text and "Of its 4 runs, 1 went beyond" in text
    assert "yielded under the motion in 2 runs (1 of them compared" in text
    assert "elastic in 1, and was not recorded in 1" in text
    # a map written before the far field was stored: every run not recorded
    old = m.drop_vars("continuum_far_field_yielded")
    old.attrs.pop("options_reference")
    counts = verdict_counts(old)
    assert counts["reference"] == "box" and counts["far_field_not_recorded"] == 4
    assert counts["far_field_yielded"] == 0 and counts["beyond_small_strain"] == 1



def test_the_cost_estimate_counts_the_soils_damping_in_its_steps():
    """The map's cost estimate with the soil's Rayleigh damping (the half-plane reference's),
    written out by hand: the Courant steps ⌈duration V_p/(0.3 h_min)⌉ of the 4-across clay
    (V_p = 193.37 m/s, h_min = 0.5 m, 1406 DOFs: tests/test_explicit_mohr_coulomb.py) divided by
    the explicit route's factor at ω = 2/dt, that of its Maxwell arm (``damped_critical``, held
    to the scheme in tests/test_continuum_damping.py; within 1 % of the closed form
    1/√(1 + β ω_c) of its spring), with Rayleigh's α = 2ξ₀ω₁ω₂/(ω₁ + ω₂), β = 2ξ₀/(ω₁ + ω₂) at
    f₁ = V_s/(4H), f₂ = 5 f₁, ω_c = 10 ω₂; and a stored damped run's steps counted as its
    undamped ones."""
    from upliftlab.continuum.dynamics.rayleigh import Rayleigh, damped_critical
    from upliftlab.comparisons.studies.winkler_map import cost
    from upliftlab.scenes import load_scene

    over = ["continuum.elements_across=4"]
    plain = load_scene("strip_footing_clay", overrides=over)
    damped = load_scene("strip_footing_clay", overrides=over + ["continuum.damping_ratio=0.01"])
    vp, vs = math.sqrt(50e3 * 0.7 / (1.3 * 0.4) / 1.8), math.sqrt(G / 1.8)
    H = damped.continuum.domain_depth * damped.foundation.width
    w1 = 2.0 * math.pi * vs / (4.0 * H)
    alpha, beta = 2.0 * 0.01 * w1 * 5.0 * w1 / (6.0 * w1), 2.0 * 0.01 / (6.0 * w1)
    per_second = vp / (0.3 * 0.5)
    omega = 2.0 * per_second
    damping = Rayleigh(0.01, (w1 / (2 * math.pi), 5 * w1 / (2 * math.pi)), alpha, beta)

    def factor_at(w):
        return damped_critical(w, damping) * w / 2.0

    factor = factor_at(omega)
    spring = 1.0 / math.sqrt(1.0 + beta * 10.0 * 5.0 * w1)
    assert factor == pytest.approx(spring, rel=0.01) and 0.8 < factor < 1.0
    for scene, steps in ((plain, math.ceil(2.0 * per_second)),
                         (damped, math.ceil(2.0 * per_second / factor))):
        estimate = cost.estimate_cost([], [("clay", scene, 2.0, False)], [], [])
        assert estimate.per_run == pytest.approx(4.0e-4 * 1406 + 1.0e-7 * 1406 * steps,
                                                 rel=1e-12)
    # a stored run of 2000 steps in 1 s at half its undamped step: 1000 undamped steps a second
    stored = {"dofs": 1406, "steps": 2000, "duration": 1.0, "compiled": True,
              "soil_model": "tresca", "dt_reduction": 0.5,
              "wall_time_s": 4.0e-4 * 1406 + 1.0e-7 * 1406 * 2000}
    factor = factor_at(2000.0)
    for scene, steps in ((plain, 1000), (damped, math.ceil(1000.0 / factor))):
        estimate = cost.estimate_cost([], [("clay", scene, 1.0, False)], [], [stored])
        assert estimate.per_run == pytest.approx(4.0e-4 * 1406 + 1.0e-7 * 1406 * steps,
                                                 rel=1e-9)


def test_the_fixed_and_per_step_costs_are_fitted_to_stored_runs_of_two_lengths():
    """Stored runs made by hand from a fixed cost F = 1e-4 s/DOF and a per-step cost
    R = 4e-8 s/(DOF step), neither the default, at two lengths (pulses of 1 and 2 s on 1406
    DOFs, and one on 2000): the fit recovers both (1e-9). A record of 30 s (30,000 steps at the
    stored runs' 1000 undamped steps a second) is estimated at F·dofs + R·dofs·steps or, when
    that is less, at its steps at the stored runs' median of wall/(dofs·steps), every second
    counted as the steps' (here the larger). Runs of one length, or of the same steps on two
    meshes, cannot tell F from R: no fit (the default F and the median R then, as the test
    above). Noisy walls (±20 %, seeded) of pulses of 2.75 and 3.8 s extrapolated to a 56 s
    record are never estimated below its true cost. Reference: the cost model's own equation,
    evaluated by hand."""
    from upliftlab.comparisons.studies.winkler_map import cost
    from upliftlab.scenes import load_scene

    F, R = 1.0e-4, 4.0e-8
    runs = [(1406, 1000, F * 1406 + R * 1406 * 1000), (1406, 2000, F * 1406 + R * 1406 * 2000),
            (2000, 1000, F * 2000 + R * 2000 * 1000)]
    assert cost.fit_rates(runs) == pytest.approx((F, R), rel=1e-9)
    assert cost.fit_rates(runs[:1] * 3) is None
    assert cost.fit_rates([runs[0], runs[2]]) is None
    stored = [{"dofs": d, "steps": s, "duration": s / 1000.0, "compiled": True,
               "soil_model": "tresca", "wall_time_s": w} for d, s, w in runs[:2]]
    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4"])
    estimate = cost.estimate_cost([], [("clay", scene, 30.0, False)], [], stored)
    whole = float(np.median([w / (d * s) for d, s, w in runs[:2]]))
    assert whole * 1406 * 30000 > F * 1406 + R * 1406 * 30000
    assert estimate.per_run == pytest.approx(whole * 1406 * 30000, rel=1e-9)
    assert "compiled return map: the stored runs' (fixed part fitted)" in estimate.text()
    rng = np.random.default_rng(11)
    dofs, F, R = 20160, 3.0e-5, 3.6e-8
    pulses = [(dofs, s, (F * dofs + R * dofs * s) * rng.uniform(0.8, 1.2))
              for s in (12650, 17480) for _ in range(48)]
    fixed, rate = cost.fit_rates(pulses)
    whole = float(np.median([w / (d * s) for d, s, w in pulses]))
    steps = 257140
    assert max(fixed * dofs + rate * dofs * steps, whole * dofs * steps) >= \
        F * dofs + R * dofs * steps


@pytest.mark.parametrize("reference", ["box", "half_plane"])
def test_the_beds_are_calibrated_to_the_whole_weight_on_the_footing(reference):
    """A bed's N is the whole weight on the footing (the point's N = 150 kN/m, by
    construction of the point), not the story's share of it (148.5 kN/m on the half-plane,
    where the footing carries 1 %): the elasto-plastic beds yield at V_ult/N times their
    static force, so a 1 % low N made them 1 % too strong. On the half-plane the reference
    carries the tie's K_h (by hand above) for the beds' rocking frequency; in the box none."""
    from upliftlab.comparisons.studies.winkler_map.plan import reference as bed_reference
    from upliftlab.comparisons.studies.winkler_map.statics import SoilStatics

    table = point_table(base_table(), "clay", 16, 150.0, 1.5, 0.5, 9.80665, reference)
    scene = scene_of(table)
    st = SoilStatics("clay", 27513.1, 43146.1, 527.71, 0.0, (0.0,), (0.0,), 20160, 1.0)
    ref = bed_reference(st, scene, table["structure"])
    assert ref.N == 150.0 and ref.V_ult / ref.N == pytest.approx(527.71 / 150.0, rel=1e-12)
    if reference == "half_plane":
        assert ref.extra["sway_stiffness"] == pytest.approx(K_H, rel=1e-12)
    else:
        assert "sway_stiffness" not in ref.extra
