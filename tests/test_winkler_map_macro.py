"""The macro-element as a bed of the Winkler map (issue 36 §3): built under a point's structure
from the soil's stored fit, with the soil's damping, fitted once per soil and kept, and
compared on the half-plane reference only.

References: the effective-width capacity in closed form, V(B′) = B′ q₀ + B′² q₁ with the
fitted law's q₀ = c N_c f_c and q₁ = ½ γ N_γ f_γ (Meyerhof's rule, the law's form), and its
moment capacity N (B − B′)/2 at V = N; the Kelvin–Voigt correspondence for the soil's Rayleigh
β (every static stiffness K gains a dashpot β K); the uniform tensionless bed's uplift onset at
an eccentricity B/6 (M = N B/6); the fit's own cost bound (its evaluation bound times the
paths' steps at the stated seconds per step).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import upliftlab.comparisons.studies.winkler_map as wm
from upliftlab.checks import InputError
from upliftlab.comparisons.beds import BEDS, BedReference, base_table, bed_foundation, bed_names
from upliftlab.comparisons.beds.macro import (FIT_SECONDS_PER_STEP, LOAD_TOLERANCE,
                                              evaluation_bound)
from upliftlab.comparisons.beds.soil_damping import with_soil_damping
from upliftlab.comparisons.framework.store import Store
from upliftlab.comparisons.studies.winkler_map.bed_runs import bed_scene
from upliftlab.comparisons.studies.winkler_map.macro_points import (evaluate_macro_fit,
                                                                    fit_rotation_points)
from upliftlab.comparisons.studies.winkler_map.points import point_table
from upliftlab.reduced import build_model
from upliftlab.reduced.laws.macro import MacroElement
from upliftlab.reduced.laws.macro.capacity import moment_capacity
from upliftlab.reduced.laws.macro.params import bearing_factors

HERE = Path(__file__).resolve().parent
CALIBRATION = json.loads((HERE.parent / "benchmarks" / "macro_calibration.json").read_text())
G_ACC = 9.80665


def _point(soil: str, fs_v: float, law: MacroElement) -> tuple[dict, BedReference]:
    """A half-plane point of the map (h/B 1.5, T 0.5 s) and its reference with the fit."""
    N = law.ultimate_load / fs_v
    table = point_table(base_table(), soil, 16, N, 1.5, 0.5, G_ACC, "half_plane")
    ref = BedReference(soil, table["structure"]["vertical_weight"], law.width, 3.0,
                       1.2 * law.vertical_stiffness, 0.9 * law.rocking_stiffness,
                       law.ultimate_load, 19230.0, 0.3,
                       extra={"sway_stiffness": table["continuum"]["horizontal_tie"],
                              "macro": {"law": {k: float(v) for k, v in
                                                CALIBRATION[soil]["law"].items()}}})
    point = {"scene": table, "motion": {"type": "ricker", "name": "ricker_T0.5s",
                                        "kind": "ricker", "period": 0.5, "duration": 3.5},
             "intensity": 1.5}
    return point, ref


@pytest.mark.parametrize("soil", ["clay", "sand"])
def test_the_bed_is_the_fitted_element_under_the_points_weight(soil):
    """The reduced model's element of the ``macro`` bed has the point's K_v and K_r and the
    fitted law's capacity: V_ult, and the effective-width capacity at B′ = B/2 and 3B/4 in
    closed form (q₀ B′ + q₁ B′², from the fitted law's c N_c f_c and ½ γ N_γ f_γ), within
    1e-9; its moment capacity at V = N is N (B − B′)/2 at that B′ (within 1e-6)."""
    fitted = MacroElement(**CALIBRATION[soil]["law"])
    point, ref = _point(soil, 3.0, fitted)
    model = build_model(bed_scene(point, bed_foundation("macro", ref, wm.FULL_OPTIONS)))
    law = model.base.law
    assert law.vertical_stiffness == pytest.approx(ref.K_v, rel=1e-12)
    assert law.rocking_stiffness == pytest.approx(ref.K_r, rel=1e-12)
    n_c, _, n_gamma = bearing_factors(fitted.friction_angle)
    q0 = fitted.cohesion * n_c * fitted.cohesive_factor
    q1 = 0.5 * fitted.unit_weight * n_gamma * fitted.frictional_factor
    B = fitted.width
    assert law.ultimate_load == pytest.approx(q0 * B + q1 * B * B, rel=1e-9)
    for share in (0.5, 0.75):
        reduced = share * B
        V = q0 * reduced + q1 * reduced ** 2
        assert moment_capacity(law, V) == pytest.approx(V * (B - reduced) / 2.0, rel=1e-6)
    for key in ("initial_size", "hardening_settlement", "interior_modulus",
                "interior_exponent", "settlement_coupling", "rounding_ratio", "sliding_ratio",
                "flow_dilatancy", "coupling_exponent", "memory_modulus"):
        assert getattr(law, key) == pytest.approx(getattr(fitted, key), rel=1e-12)
    assert model.base.rest.forces[0] == pytest.approx(ref.N, rel=1e-9)


def test_the_soils_damping_is_beta_K_v_on_the_element():
    """The soil's Rayleigh β enters the element as its one dashpot: c′ B = β K_v (the
    correspondence principle's dashpot of the static K_v), within 1e-12; a bed of springs
    gets β k_i beside each spring instead (Σ = β K_v alike)."""
    fitted = MacroElement(**CALIBRATION["clay"]["law"])
    point, ref = _point("clay", 5.0, fitted)
    beta, mass = 0.004, point["scene"]["structure"]["vertical_weight"] / G_ACC
    table = with_soil_damping(bed_foundation("macro", ref, wm.FULL_OPTIONS), beta,
                              vertical_mass=mass)
    data = {**point, "scene": {**point["scene"],
                               "continuum": {k: v for k, v in point["scene"]["continuum"].items()
                                             if k != "damping_ratio"}}}
    model = build_model(bed_scene(data, table))
    assert model.base.dashpot_density * fitted.width == pytest.approx(beta * ref.K_v, rel=1e-12)
    springs = with_soil_damping(bed_foundation("uniform_plastic", ref, wm.FULL_OPTIONS), beta)
    assert "damping_ratio" not in springs and len(springs["dashpots"]) == 48
    with pytest.raises(InputError, match="vertical mass"):
        with_soil_damping(bed_foundation("macro", ref, wm.FULL_OPTIONS), beta)


def test_the_element_stands_on_the_half_plane_only():
    """The box holds its footing horizontally and the element carries the base's sway: the
    ``macro`` bed is left out of the box's default beds and refused there by name, in one
    line naming the reference and the beds that stand on it."""
    assert "macro" in BEDS and "macro" not in bed_names(wm.FULL_OPTIONS)
    assert "macro" in bed_names(replace(wm.FULL_OPTIONS, reference="half_plane"))
    with pytest.raises(InputError, match=r"'macro' with options.reference = 'box'.*half_plane"):
        bed_names(replace(wm.FULL_OPTIONS, beds=("uniform", "macro")))


def test_the_map_fits_the_element_once_and_keeps_it(tmp_path):
    """The fast map on the half-plane with the ``macro`` bed: before, the estimate counts one
    fit, at most its evaluation bound times the paths' steps at the stated rate; the map fits
    it (the law holding N on every pushover within the load tolerance), stores it, and a
    second estimate has nothing left to fit; the element's statics row has its uplift onset
    at N B/6 and its runs compare at every point."""
    options = replace(wm.FAST_OPTIONS, beds=("uniform_plastic", "macro"), energy=False,
                      figures=False, reference="half_plane")
    store = tmp_path / "store"
    before = wm.estimate_map(wm.FAST_GRID, options, ("uniform_plastic", "macro"),
                             wm.study_motions(wm.FAST_GRID, options, tmp_path / "m"),
                             Store(store))
    assert before.fits == 1
    loads = {"clay": 1.0}
    steps = sum(len(p["rotations"]) for p in fit_rotation_points(("clay",), options,
                                                                 base_table(), loads))
    assert before.fit_seconds == pytest.approx(
        evaluation_bound(options.macro_evaluations) * steps * FIT_SECONDS_PER_STEP, rel=1e-12)
    wm.run(fast=True, out=tmp_path / "out", store=store, options=options)
    kept = Store(store)
    fits = [kept.entry(k) for k in kept.keys()
            if kept.entry(k)["function"].endswith("evaluate_macro_fit")]
    assert len(fits) == 1 and "law" in fits[0]["record"]
    assert max(fits[0]["record"]["load_misses"]) <= LOAD_TOLERANCE
    again = wm.estimate_map(wm.FAST_GRID, options, ("uniform_plastic", "macro"),
                            wm.study_motions(wm.FAST_GRID, options, tmp_path / "m2"), kept)
    assert again.fits == 0 and again.runs == 0
    import xarray as xr

    statics = xr.load_dataset(tmp_path / "out" / "statics.nc")
    macro = list(statics["calibration_label"].values).index("macro")
    onset = statics["rocking_bed_onset_moment"].values[0, :, macro]
    B = 2.0 * base_table()["foundation"]["half_width"]
    loads = float(statics["V_ult"].values.ravel()[0]) / np.asarray(wm.FAST_GRID.fs_v)
    assert np.allclose(onset, loads * B / 6.0, rtol=1e-12), onset
    points = xr.load_dataset(tmp_path / "out" / "map.nc")
    macro = list(points["calibration_key"].values).index("macro")
    assert np.isfinite(points["error"].values[..., macro, :]).all()


def test_a_fit_refused_is_a_record_that_says_why():
    """A soil whose pushovers all stopped has no monotonic one to fit the capacity to: the
    fit's record is the refusal, in one line, and the bed built on it is refused by name."""
    point = {"soil": "clay", "width": 2.0, "K_v": 27513.0, "K_r": 43146.0, "V_ult": 527.7,
             "strength": {"cohesion": 50.0}, "pushovers": [], "evaluations": 30}
    record = evaluate_macro_fit(point)
    assert "no monotonic rotation pushover" in record["error"]
    fitted = MacroElement(**CALIBRATION["clay"]["law"])
    _, ref = _point("clay", 3.0, fitted)
    ref = replace(ref, extra={**ref.extra, "macro": record})
    with pytest.raises(InputError, match="fit was refused: macro calibration: no monotonic"):
        bed_foundation("macro", ref, wm.FULL_OPTIONS)
    assert math.isfinite(fitted.ultimate_load)


def test_the_kept_fits_are_the_published_calibration():
    """The half-plane store keeps the map's fit of each soil at today's revision of the
    reduced model (``packs/macro-fits*``; a fit of an earlier revision is kept as data, not
    read): its law is ``benchmarks/macro_calibration.json``'s field by field (1e-12: the
    published table is the kept fit), it holds N on every pushover, and pushed again over
    the continuum's pushovers that the fit point keeps (the reference: the continuum's stored
    runs), its moment misfit per pushover is the record's (1e-9) and within 35 % rms of the
    pushover's largest moment (measured: at most 30.3 %, the sand's FS_v 2 cycles). That the
    optimizer makes the same law again is the store's check of a stale fit (a re-run sample
    within 1e-6) and ``benchmarks/macro_calibration.py --refit``."""
    from upliftlab.comparisons.beds.macro import macro_pushover
    from upliftlab.reduced import REVISION

    store = Store(HERE.parent / "benchmarks" / "winkler_map_halfplane_store")
    fits = {}
    for key in store.keys():
        entry = store.entry(key)
        if entry["function"].endswith("evaluate_macro_fit") \
                and entry["models"] == {"reduced": REVISION}:
            assert entry["params"]["soil"] not in fits
            fits[entry["params"]["soil"]] = entry
    assert sorted(fits) == ["clay", "sand"]
    for soil, entry in fits.items():
        record = entry["record"]
        for field, value in CALIBRATION[soil]["law"].items():
            assert record["law"][field] == pytest.approx(value, rel=1e-12, abs=1e-15), field
        assert max(record["load_misses"]) <= LOAD_TOLERANCE
        law = MacroElement(**record["law"])
        pushes = sorted(entry["params"]["pushovers"], key=lambda p: (p["N"], len(p["theta"])))
        for p, rms in zip(pushes, record["moment_rms"], strict=True):
            M, _ = macro_pushover(law, p["N"], p["theta"])
            again = math.sqrt(np.mean(((M - p["M"]) / np.max(np.abs(p["M"]))) ** 2))
            assert again == pytest.approx(rms, rel=1e-9)
            assert again <= 0.35


def test_on_the_half_plane_newmark_takes_the_steps_rk4_cannot():
    """On the half-plane a point's footing sways on the tie's dashpot with its own mass (1 %
    of N): an overdamped mode (λ = −2.1e3 /s) that bounds RK4's energy-limited step to about
    2e-5 s. Newmark, with the element in its Newton iteration, runs the same point at the
    map's step (0.25 ms): at least 10 times fewer steps, and every measure of the map within
    1e-3 of RK4's (measured on revision 3's clay: within 9e-5; at 1 ms its residual
    settlement was 2.1e-3 off, Newmark's own error: 4.8e-4 at 0.5 ms), its energy balance
    within 1e-4."""
    from upliftlab.comparisons.studies.winkler_map.bed_runs import (element_analysis,
                                                                    reduced_measures)
    from upliftlab.reduced import run
    from upliftlab.scenes import scene_from_dict

    fitted = MacroElement(**CALIBRATION["clay"]["law"])
    point, ref = _point("clay", 3.0, fitted)
    ref = replace(ref, K_v=fitted.vertical_stiffness, K_r=fitted.rocking_stiffness)
    scene = bed_scene(point, bed_foundation("macro", ref, wm.FULL_OPTIONS))
    explicit = run(scene)
    data = {**scene.data, "analysis": {**scene.data.get("analysis", {}),
                                       **element_analysis(wm.FULL_OPTIONS)}}
    newmark = scene_from_dict(data, merged=True)
    assert (newmark.analysis.integrator, newmark.analysis.dt) == ("newmark", 2.5e-4)
    implicit = run(newmark)
    assert implicit.info["steps"] * 10 <= explicit.info["steps"]
    e, i = reduced_measures(explicit), reduced_measures(implicit)
    scale = {"residual_settlement": abs(e["residual_settlement"]), "residual_rotation":
             abs(e["theta"])}  # a residual rotation near 0 is held to the peak's scale
    for key, value in e.items():
        assert i[key] == pytest.approx(value, rel=1e-3, abs=1e-3 * scale.get(key, 0.0)), key
    assert implicit.energy_balance_error <= 1e-4


def test_a_light_structure_gets_the_step_that_resolves_its_fastest_mode():
    """At FS_v 10 the footing's sway (its mass a share of a light N) has a period under 10 ms:
    Newmark at 1 ms (the map's first step; a user's ``macro_dt`` may be as long as 10 ms)
    could not resolve it (10 steps a period) and was refused at 4 of the slice's 32 points;
    the map's run shortens the step to 0.95 of T_min/10, T_min from the eigenvalues of M⁻¹K
    of the bonded model by numpy (an independent computation), and the run completes."""
    from upliftlab.comparisons.studies.winkler_map.bed_runs import (_resolved, element_analysis,
                                                                    run_bed)
    from upliftlab.reduced import build_model

    fitted = MacroElement(**CALIBRATION["clay"]["law"])
    point, ref = _point("clay", 10.0, fitted)
    foundation = bed_foundation("macro", ref, wm.FULL_OPTIONS)
    analysis = element_analysis(replace(wm.FULL_OPTIONS, macro_dt=1e-3))
    scene = _resolved(bed_scene(point, foundation, analysis))
    model = build_model(scene).linearised
    K, _ = model.bonded_matrices()
    omega2 = np.linalg.eigvals(np.diag(1.0 / model.mass) @ (K - model.geometric)).real
    T_min = 2.0 * math.pi / math.sqrt(omega2.max())
    assert T_min < 10e-3
    assert scene.analysis.dt == pytest.approx(0.95 * T_min / 10.0, rel=1e-9)
    assert "refused" not in run_bed(point, foundation, analysis)
