"""The continuum as a half-plane: a compliant base with the motion entering as an incident
wave, and a frictionless footing held horizontally by a tie to the free field
(``continuum.horizontal_tie``, :mod:`upliftlab.continuum.dynamics.ground`).

References, one per test:
- the 1-D wave solution on a homogeneous half-space: the free surface moves with the outcrop
  motion (twice the incident wave) delayed by the travel time D/V_s from the base; for a Ricker
  velocity v = A τ exp(−π² f² τ²) the displacement is −A/(2π² f²) exp(−π² f² τ²) + A/(2π² f²)
  in closed form;
- Newton's second law for the footing and the story on a frictionless interface: the soil
  gives them no horizontal force, so the tie's force K_t (u_ff − u) equals their horizontal
  inertia, m_f ü + m (ü + h θ̈ + s̈) (the static statement "H = K_t u + 0 from the soil",
  with H the inertia force); a tie four times stiffer leaves a quarter of the lag u − u_ff;
- the box-size check of issue 35, peak θ and uplift within 2 % when the box doubles
  (benchmarks/halfplane_box.py has the full table, with the residual settlement, which does not
  hold);
- bad input is refused before any work, naming the field, the value and the valid range.
The Lysmer base's absorption of a vertically incident pulse (reflected energy < 5 %, surface
amplitude 2 × incident within 5 %) is tests/test_continuum_dynamics.py's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics import ground
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic, wave_speeds
from upliftlab.scenes import load_scene

SCENE = "strip_footing_clay"
HALF_PLANE = ["continuum.elements_across=4", "continuum.base=compliant",
              "continuum.boundary=shear"]


def test_free_field_motion_is_the_delayed_outcrop_motion():
    scene = load_scene(SCENE, overrides=HALF_PLANE + ["continuum.horizontal_tie=22625"])
    model = build_model(scene)
    A, f, t0, dt = 0.2, 2.5, 0.6, 1e-3
    t = np.arange(4001) * dt
    c = (math.pi * f) ** 2
    v = A * (t - t0) * np.exp(-c * (t - t0) ** 2)
    u, v_ff = ground.free_field_motion(model, v, dt)
    delay = 10.0 * model.width / wave_speeds(model.soil)[1]
    tau = t - delay
    exact = np.where(tau > 0.0, A / (2 * c) * (np.exp(-c * t0 ** 2)
                                               - np.exp(-c * (tau - t0) ** 2)), 0.0)
    assert np.max(np.abs(u - exact)) < 1e-4 * np.max(np.abs(exact))
    exact_v = np.where(tau > 0.0, A * (tau - t0) * np.exp(-c * (tau - t0) ** 2), 0.0)
    assert np.max(np.abs(v_ff - exact_v)) < 1e-3 * np.max(np.abs(exact_v))


def _tied_run(tie: float):
    overrides = HALF_PLANE + [f"continuum.horizontal_tie={tie}", "soil.model=elastic",
                              "motion.amplitude=0.05", "motion.period=0.8",
                              "motion.duration=2.5"]
    scene = load_scene(SCENE, overrides=overrides)
    model = build_model(scene)
    motion = scene.build_motion()
    result = run_dynamic(model, scene, motion, DynamicOptions(snapshots=0))
    return scene, model, motion, result


def _outcrop_displacement(motion, g, times):
    """The record's displacement by the trapezoidal rule twice on its own step (not the code's
    integral), at ``times``."""
    a = np.append(motion.acceleration, 0.0) * g
    tm = np.arange(a.size) * motion.dt
    v = np.concatenate(([0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * motion.dt)))
    x = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * motion.dt)))
    return np.interp(times, tm, x, left=0.0)


def _tie_and_inertia(tie: float):
    """(K_t (u_ff − u), the footing's and story's horizontal inertia, max |u − u_ff|) of a
    tied run, the accelerations by second differences of the recorded rows."""
    scene, model, motion, result = _tied_run(tie)
    assert result.metadata["base"] == "compliant"
    t = np.asarray(result.time)
    u, theta = result.footing[:, 0], result.footing[:, 2]
    s = np.asarray(result.structure_u).reshape(t.size, -1)[:, -1]
    delay = 10.0 * model.width / wave_speeds(model.soil)[1]
    u_ff = _outcrop_displacement(motion, scene.g, t - delay)
    st = scene.structure
    m, h = st.weight / scene.g, st.stories[0].height
    m_f = (st.vertical_weight - st.weight) / scene.g
    dt = t[1] - t[0]

    def acc(x):
        return (x[2:] - 2.0 * x[1:-1] + x[:-2]) / dt ** 2

    inertia = m_f * acc(u) + m * (acc(u) + h * acc(theta) + acc(s))
    return tie * (u_ff - u)[1:-1], inertia, float(np.max(np.abs(u - u_ff)))


def test_the_tie_alone_holds_the_frictionless_footing():
    K = 22625.0  # 2G/(2 − ν), the handbook strip's K_h, per metre
    lags = []
    for tie in (K, 4.0 * K):
        force, inertia, lag = _tie_and_inertia(tie)
        miss = np.max(np.abs(force - inertia)) / np.max(np.abs(force))
        print(f"K_t = {tie:g}: peak tie force {np.max(np.abs(force)):.4g} kN/m, largest "
              f"difference from the inertia {miss:.2%}, largest lag {lag:.4g} m")
        assert miss < 0.03
        lags.append(lag)
    assert lags[1] == pytest.approx(lags[0] / 4.0, rel=0.10)


def _peaks(overrides):
    """(peak |θ|, peak edge uplift) of the clay scene's own pulse with ``overrides``."""
    scene = load_scene(SCENE, overrides=["continuum.elements_across=4"] + overrides)
    result = run_dynamic(build_model(scene), scene, scene.build_motion(),
                         DynamicOptions(snapshots=0))
    gap = np.asarray(result.gap)
    x = np.asarray(result.x)
    edges = [int(np.argmin(x)), int(np.argmax(x))]
    return np.max(np.abs(result.footing[:, 2])), max(0.0, np.max(gap[:, edges]))


def test_on_the_half_plane_the_box_no_longer_sets_the_peaks():
    # Reference: issue 35's box-size check, peak θ and uplift within 2 % when the box doubles
    # in width and depth (10B -> 20B), here on 4 across (benchmarks/halfplane_box.py: 8 across,
    # -0.1 % and +0.5 %; the rigid container moves them by +26 % and +18.5 %, which the second
    # half checks, so that the measure can fail).
    tie = ["continuum.base=compliant", "continuum.boundary=shear",
           "continuum.horizontal_tie=22625", "continuum.horizontal_tie_damping=372"]
    small, large = (_peaks(tie + [f"continuum.domain_width={b}", f"continuum.domain_depth={b}"])
                    for b in (10, 20))
    change = np.array(large) / np.array(small) - 1.0
    print(f"half-plane, box 10B -> 20B: peak θ {change[0]:+.2%}, uplift {change[1]:+.2%}")
    assert np.all(np.abs(change) < 0.02)
    small, large = (_peaks([f"continuum.domain_width={b}", f"continuum.domain_depth={b}"])
                    for b in (10, 20))
    change = np.array(large) / np.array(small) - 1.0
    print(f"rigid container, box 10B -> 20B: peak θ {change[0]:+.2%}, uplift {change[1]:+.2%}")
    assert np.all(np.abs(change) > 0.05)


@pytest.mark.parametrize("overrides, message", [
    (["continuum.horizontal_tie=1000"], "continuum.horizontal_tie = 1000: the tie holds a "
                                        "footing on a compliant base"),
    (["continuum.base=compliant"], "continuum.horizontal_tie > 0"),
])
def test_a_tie_without_a_compliant_base_and_a_free_footing_without_a_tie_are_refused(
        overrides, message, monkeypatch):
    scene = load_scene(SCENE, overrides=["continuum.elements_across=4"] + overrides)
    model = build_model(scene)
    monkeypatch.setattr(ground, "gravity_state", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(InputError) as info:
        run_dynamic(model, scene, scene.build_motion(), DynamicOptions())
    assert message in str(info.value)


def test_the_implicit_route_with_the_tie_follows_the_explicit_one():
    """The tie on the implicit route (HHT, Newton, the tie's spring and dashpot in the
    footing's matrices, its ground load at t_k) against the explicit route (central
    differences, the same tie), an independent integrator: the clay scene's pulse, its first
    1.6 s (the footing lifts off and the clay yields), 4 across. The routes differ by their
    own time discretisation (benchmarks/CONTINUUM_CONVERGENCE.md: peaks within 0.3 %,
    histories within 5–15 % of their peaks on the closed box); measured here: peak θ +0.08 %,
    θ history 0.43 %, u history 0.05 % of their peaks (2 s)."""
    scene = load_scene(SCENE, overrides=HALF_PLANE + ["analysis.duration=1.6"])
    K_h, C_h = 2.0 * scene.soil.shear_modulus / (2.0 - scene.soil.poisson_ratio), \
        scene.soil.density * wave_speeds(scene.soil)[1] * scene.foundation.width
    scene = scene.replace("continuum", horizontal_tie=K_h, horizontal_tie_damping=C_h)
    runs = {m: run_dynamic(build_model(scene), scene, scene.build_motion(),
                           DynamicOptions(method=m, snapshots=0), progress=False)
            for m in ("explicit", "implicit")}
    ex, im = runs["explicit"], runs["implicit"]
    fe, fi = np.asarray(ex.footing), np.asarray(im.footing)
    peak_e, peak_i = np.abs(fe[:, 2]).max(), np.abs(fi[:, 2]).max()
    assert peak_e > 1e-3  # it rocks
    assert abs(peak_i / peak_e - 1.0) < 0.01
    for j in (0, 2):  # u and θ histories, on the implicit route's times
        e = np.interp(im.time, ex.time, fe[:, j])
        assert np.abs(e - fi[:, j]).max() < 0.02 * np.abs(fi[:, j]).max()
    assert im.energy_balance_error < 0.01


@pytest.mark.parametrize("value", ["0", "-5"])
def test_a_tie_that_is_not_positive_is_refused(value):
    with pytest.raises(InputError) as info:
        load_scene(SCENE, overrides=[f"continuum.horizontal_tie={value}"])
    assert "continuum.horizontal_tie" in str(info.value) and value in str(info.value)
