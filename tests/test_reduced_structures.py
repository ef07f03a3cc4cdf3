"""Superstructures beyond the SDOF: shear buildings, yielding stories, P-Δ, initial states.

References: the matrix exponential of the linear first-order system (exact), the eigenvalues
of (K, M), closed-form periods with P-Δ, and a second independent integrator (eqsig-style
cross-check of two algorithms) for the yielding story.
"""

import math

import numpy as np
import pytest
import scipy.linalg

from upliftlab.reduced import build_model, run
from upliftlab.reduced.run import initial_conditions
from upliftlab.scenes import load_scene, scene_from_dict


def building(stories, *, support="fixed", damping=0.0, p_delta=False, motion=None):
    data = {"schema": 1, "units": "kip-in-s",
            "structure": {"damping_ratio": damping, "rotary_inertia": 5000.0, "p_delta": p_delta,
                          "story": [dict(s) for s in stories]},
            "foundation": {"support": support, "half_width": 120.0, "layout": "winkler",
                           "springs": 20, "vertical_period": 0.06},
            "motion": motion or {"type": "free", "velocity": 10.0, "duration": 2.0}}
    return scene_from_dict(data)


THREE = [{"weight": 100.0, "height": 144.0, "stiffness": 600.0},
         {"weight": 100.0, "height": 288.0, "stiffness": 500.0},
         {"weight": 80.0, "height": 432.0, "stiffness": 400.0}]


def test_shear_building_free_vibration_is_exact():
    """Three stories, fixed base, 5 % stiffness-proportional damping: the integrated response
    (Δt = 0.2 ms, so that RK4's own error is below 1e-9) equals expm(J t)·y0 to 1e-8."""
    scene = building(THREE, damping=0.05)
    model = build_model(scene)
    K, C = model.bonded_matrices()
    n = model.mass.size
    J = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-K / model.mass[:, None], -C / model.mass[:, None]]])
    q0, qd0 = initial_conditions(model, scene.build_motion())
    response = run(scene, dt=2e-4, output_dt=0.1)
    for t, q in zip(response.time, response.q):
        exact = (scipy.linalg.expm(J * t) @ np.concatenate([q0, qd0]))[:n]
        np.testing.assert_allclose(q, exact, atol=1e-8 * np.abs(qd0).max())


def test_stiffness_proportional_damping_gives_zeta_in_the_first_mode():
    """ζ_s is a fraction of critical for the fixed-base first mode: the eigenvalues of the
    damped first-order system have −Re λ/|λ| = 0.05 in mode 1."""
    model = build_model(building(THREE, damping=0.05))
    K, C = model.bonded_matrices()
    n = model.mass.size
    J = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-K / model.mass[:, None], -C / model.mass[:, None]]])
    lam = np.linalg.eigvals(J)
    first = lam[np.argmin(np.abs(lam))]
    assert -first.real / abs(first) == pytest.approx(0.05, rel=1e-10)


def test_one_story_building_equals_the_sdof_scene():
    """A one-entry [[structure.story]] list and the SDOF shorthand are the same model."""
    sdof = load_scene("short_period_free", case="C", overrides=["motion.duration=1.0"])
    story = sdof.structure.stories[0]
    data = dict(sdof.data)
    data["structure"] = {"damping_ratio": 0.05, "rotary_inertia": 7694.0,
                         "story": [{"weight": story.weight, "height": story.height,
                                    "stiffness": story.stiffness}]}
    mdof = scene_from_dict(data, merged=True)
    a, b = run(sdof, output_dt=0.01), run(mdof, output_dt=0.01)
    np.testing.assert_allclose(a.q, b.q, rtol=0, atol=1e-14)


def test_p_delta_lengthens_the_rocking_period():
    """Rigid structure on bonded springs with P-Δ: small free rocking at
    ω² = (K_θ − W h)/(I0 + m h²) (V decoupled for a symmetric bed); 0.05 % on the period."""
    m, h, b, kv, i0 = 1.0, 200.0, 60.0, 2.0e4, 1000.0
    data = {"schema": 1, "units": "kip-in-s",
            "structure": {"weight": m * 386.09, "height": h, "stiffness": 1.0, "rigid": True,
                          "rotary_inertia": i0, "p_delta": True},
            "foundation": {"support": "bonded", "half_width": b, "layout": "edges",
                           "stiffness": kv},
            "motion": {"type": "free", "rotation": 1e-4, "duration": 3.0},
            "analysis": {"output_dt": 1e-3}}
    response = run(scene_from_dict(data))
    k_theta = kv * b * b - m * 386.09 * h
    period = 2 * math.pi * math.sqrt((i0 + m * h * h) / k_theta)
    theta, t = response.theta, response.time
    up = np.flatnonzero((theta[:-1] < 0) & (theta[1:] >= 0))
    times = t[up] - theta[up] * (t[up + 1] - t[up]) / (theta[up + 1] - theta[up])
    assert np.mean(np.diff(times)) == pytest.approx(period, rel=5e-4)


def test_p_delta_on_a_fixed_base_sdof_softens_it_by_w_over_h():
    """Fixed-base SDOF with P-Δ: the story stiffness becomes k − W/h (story drift P-Δ)."""
    model = build_model(load_scene("short_period_free", overrides=[
        "foundation.support='fixed'", "structure.p_delta=true"]))
    K, _ = model.bonded_matrices()
    k = load_scene("short_period_free").structure.stories[0].stiffness
    assert K[0, 0] == pytest.approx(k - 202.0 / 336.0, rel=1e-12)


def test_yielding_story_agrees_between_independent_integrators(elcentro):
    """A yielding fixed-base story (Fy at 40 % of the elastic demand, 3 % hardening) under El
    Centro: the event stepper and Newmark–Newton (fine step) agree on the peak drift and the
    residual drift to 0.2 % — two algorithms, one answer."""
    stories = [{"weight": 202.0, "height": 336.0, "stiffness": 917.99, "yield_force": 60.0,
                "post_yield_ratio": 0.03}]
    scene = building(stories, damping=0.05, motion={"type": "record",
                                                    "name": elcentro.source})
    events = run(scene, integrator="events", output_dt=0.02)
    newmark = run(scene, integrator="newmark", dt=2e-4, output_dt=0.02)
    assert events.peaks["u"] == pytest.approx(newmark.peaks["u"], rel=2e-3)
    assert events.u[-1] == pytest.approx(newmark.u[-1], rel=2e-3, abs=2e-3 * events.peaks["u"])
    assert events.peaks["u"] > 60.0 / 917.99                # it did yield
    assert events.energy[-1, 6] > 0.1 * events.energy[-1, 0]  # plastic work is a real share
    assert events.energy_balance_error < 1e-3


def test_free_vibration_from_an_initial_displacement():
    """Released from the static state that holds the top at X0: it starts at X0, at rest, and
    (undamped, bonded) keeps its energy to 1e-6 (event stepper at analysis.rtol = 1e-8)."""
    scene = load_scene("short_period_free", case="A", overrides=[
        "foundation.support='bonded'", "foundation.damping_ratio=0.0",
        "structure.damping_ratio=0.0", "motion.velocity=0.0", "motion.displacement=0.5",
        "motion.duration=1.0", "analysis.rtol=1e-8"])
    response = run(scene, output_dt=0.01)
    assert response.x[0] == pytest.approx(0.5, rel=1e-12)
    assert np.abs(response.qd[0]).max() == 0.0
    assert response.energy_balance_error < 1e-6
