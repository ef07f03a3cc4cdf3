"""The sway spring: a horizontal spring, dashpot and slider under the base (foundation.sway_*).

References: the closed-form response of a damped SDOF to a harmonic ground acceleration from
rest (transient and steady state); the eigenvalues of the bonded system assembled by hand in
other coordinates (scipy.linalg.eigh); the closed-form motion of a block on an
elastic–perfectly-plastic slider under a constant ground acceleration; conservation of energy.
"""

import math

import numpy as np
import pytest
import scipy.linalg

from upliftlab.checks import InputError
from upliftlab.motions import Motion
from upliftlab.reduced import build_model, run
from upliftlab.scenes import load_scene, scene_from_dict

G = 9.80665  # m/s², the kN-m-s scene's g (asserted below)


def sway_scene(*, rigid=True, support="fixed", sway=None, motion=None, analysis=None,
               structure=None, foundation=None):
    """A kN-m-s scene: 1000 kN at 2 m (rigid, or a story of T = 0.25 s) on a 2 m base."""
    s = {"weight": 1000.0, "height": 2.0, "rotary_inertia": 50.0, "rigid": rigid,
         "period": 0.25}
    if not rigid:
        s.update(vertical_weight=1300.0)
    s.update(structure or {})
    f = {"support": support, "half_width": 1.0, "layout": "winkler", "springs": 10,
         "vertical_period": 0.05}
    f.update(sway or {})
    f.update(foundation or {})
    data = {"schema": 1, "units": "kN-m-s", "structure": s, "foundation": f,
            "motion": motion or {"type": "free", "velocity": 0.1, "duration": 1.0}}
    if analysis:
        data["analysis"] = analysis
    return scene_from_dict(data)


def harmonic_from_rest(t, mass, k, c, accel, omega_g):
    """u(t) of m ü + c u̇ + k u = −m A sin(Ω t) from rest (closed form, underdamped): the
    steady state u_p = P₀[(k − mΩ²) sin Ωt − cΩ cos Ωt]/D, D = (k − mΩ²)² + (cΩ)², P₀ = −mA,
    plus the free vibration e^{−ζωt}(C₁ cos ω_d t + C₂ sin ω_d t) that starts it at rest."""
    p0 = -mass * accel
    d = (k - mass * omega_g**2) ** 2 + (c * omega_g) ** 2
    up = p0 * ((k - mass * omega_g**2) * np.sin(omega_g * t) - c * omega_g * np.cos(omega_g * t)) / d
    omega = math.sqrt(k / mass)
    zeta = c / (2.0 * math.sqrt(k * mass))
    wd = omega * math.sqrt(1.0 - zeta**2)
    c1 = p0 * c * omega_g / d
    c2 = (zeta * omega * c1 - p0 * (k - mass * omega_g**2) * omega_g / d) / wd
    return up + np.exp(-zeta * omega * t) * (c1 * np.cos(wd * t) + c2 * np.sin(wd * t))


def test_rigid_block_on_a_sway_spring_is_the_damped_sdof_under_harmonic_motion():
    """Rigid structure on a fixed (non-rocking) base with a sway spring (T_h = 0.3 s, ζ = 5 %)
    under a_g = 0.2 g sin(2πt/0.5 s) for 3 s: the base's sway equals the closed form from rest
    at every stored state within 1e-5 of its peak (samples 0.2 ms apart, whose linear
    interpolation of the sine is off by (Ωdt)²/8 = 1e-7; event stepper at rtol 1e-8)."""
    mass = 1000.0 / G
    k = mass * (2.0 * math.pi / 0.3) ** 2
    c = 0.05 * 2.0 * math.sqrt(k * mass)
    scene = sway_scene(sway={"sway_stiffness": k, "sway_damping": c},
                       motion={"type": "harmonic", "amplitude": 0.2, "period": 0.5,
                               "duration": 3.0, "dt": 2e-4},
                       analysis={"rtol": 1e-8, "output_dt": 0.01})
    assert scene.g == pytest.approx(G, rel=1e-12)
    model = build_model(scene)
    assert model.dofs.names == ("u_G",) and model.mass[0] == pytest.approx(mass, rel=1e-14)
    response = run(scene)
    exact = harmonic_from_rest(response.time, mass, k, c, 0.2 * G, 2.0 * math.pi / 0.5)
    fine = np.linspace(0.0, 3.0, 600_001)  # the peak between the stored states
    peak = np.max(np.abs(harmonic_from_rest(fine, mass, k, c, 0.2 * G, 2.0 * math.pi / 0.5)))
    assert np.max(np.abs(response.sway - exact)) < 1e-5 * peak
    assert response.peaks["sway"] == pytest.approx(peak, rel=1e-5)
    assert response.summary()["peak_sway"] == response.peaks["sway"]


def hand_matrices(*, flexible, p_delta=False):
    """(K, M) of the bonded system assembled by hand in the coordinates (u_b, θ, V[, u]):
    u_b the base's sway, u the story's deformation relative to the base (flexible only).

    Each mass's absolute horizontal displacement (less the ground's) is u_b + h θ (+ u): the
    mass matrix is full in these coordinates (the model's is diagonal in its own). Stiffness:
    the sway spring k_h on u_b; the bed Σk_i, Σk_i x_i² on V, θ (its coupling Σk_i x_i is zero,
    symmetric); the story k_s on u. P-Δ of one story: −W (hθ + u)²/(2h), an inverted pendulum
    about O."""
    kh, W, h, Wv, I0 = 3.0e5, 1000.0, 2.0, 1300.0, 50.0
    m = W / G
    n_spring, b = 10, 1.0
    x = -b + (2 * b / n_spring) * (np.arange(n_spring) + 0.5)
    kv = (Wv / G if flexible else m) * (2.0 * math.pi / 0.05) ** 2
    ki = np.full(n_spring, kv / n_spring)
    mb = (Wv - W) / G if flexible else 0.0
    lever = np.array([1.0, h, 0.0] + ([1.0] if flexible else []))  # ∂(mass's X)/∂coords
    n = lever.size
    M = m * np.outer(lever, lever)
    M[0, 0] += mb
    M[1, 1] += I0
    M[2, 2] += Wv / G if flexible else m
    K = np.zeros((n, n))
    K[0, 0] = kh
    K[1, 1] = np.sum(ki * x * x)
    K[2, 2] = np.sum(ki)
    K[1, 2] = K[2, 1] = -np.sum(ki * x)
    if flexible:
        K[3, 3] = m * (2.0 * math.pi / 0.25) ** 2
    if p_delta:  # one flexible story: −W (hθ + u)²/(2h)
        r = np.array([0.0, h, 0.0, 1.0])
        K -= W / h * np.outer(r, r)
    return K, M


@pytest.mark.parametrize("flexible,p_delta", [(False, False), (True, False), (True, True)])
def test_bonded_frequencies_with_sway_match_the_system_assembled_by_hand(flexible, p_delta):
    """Structure + sway + rocking + vertical, every spring elastic and bonded: the model's
    natural frequencies (in its own DOFs, u_G or x relative to the ground, diagonal mass) equal
    those of (K, M) assembled by hand in (u_b, θ, V[, u]) with scipy.linalg.eigh, to 1e-6."""
    scene = sway_scene(rigid=not flexible, support="bonded", sway={"sway_stiffness": 3.0e5},
                       structure={"p_delta": p_delta})
    model = build_model(scene)
    K, _ = model.bonded_matrices()
    model_w2 = np.sort(scipy.linalg.eigh(K, np.diag(model.mass), eigvals_only=True))
    Kh, Mh = hand_matrices(flexible=flexible, p_delta=p_delta)
    hand_w2 = np.sort(scipy.linalg.eigh(Kh, Mh, eigvals_only=True))
    assert model_w2.size == hand_w2.size == (4 if flexible else 3)
    np.testing.assert_allclose(np.sqrt(model_w2), np.sqrt(hand_w2), rtol=1e-6)


def test_block_slides_under_a_constant_acceleration_above_mu_g():
    """A rigid block on a stiff slider (μ = 0.3, k_h = 1e7 kN/m, no dashpot) under a constant
    a_g = 0.5 g for 1 s. Closed form: elastic while k|u| < μW, u = −(a/ω²)(1 − cos ωt) up to
    t₁ with cos ωt₁ = 1 − μg/a; then it slides at the relative acceleration −(a − μg):
    u = u₁ + v₁ τ − ½(a − μg) τ². Every stored state within 1e-6 of the final slip; the
    sliding (plastic) displacement and the energy balance close."""
    mass, mu, a = 1000.0 / G, 0.3, 0.5 * G
    k = 1.0e7
    scene = sway_scene(sway={"sway_stiffness": k, "sliding_friction": mu},
                       analysis={"rtol": 1e-9, "output_dt": 0.01, "duration": 1.0})
    motion = Motion(name="constant", dt=0.01, acceleration=np.full(200, 0.5), source="test")
    response = run(scene, motion=motion)
    omega = math.sqrt(k / mass)
    t1 = math.acos(1.0 - mu * G / a) / omega
    u1 = -mu * mass * G / k
    v1 = -(a / omega) * math.sin(omega * t1)
    t = response.time
    tau = t - t1
    exact = np.where(t < t1, -(a / omega**2) * (1.0 - np.cos(omega * t)),
                     u1 + v1 * tau - 0.5 * (a - mu * G) * tau**2)
    final = abs(exact[-1])
    assert final > 0.9  # it slid: 0.2 g over 1 s is about 0.98 m
    assert np.max(np.abs(response.sway - exact)) < 1e-6 * final
    spring = build_model(scene).sway_spring
    assert spring == 0  # no story springs: the sway spring comes first
    sliding = response.plastic[-1, spring]
    assert sliding == pytest.approx(exact[-1] - u1, rel=1e-6)
    assert response.peaks["sliding"] == sliding
    assert response.energy_balance_error < 1e-6


def test_sway_with_rocking_and_uplift_closes_its_energy_balance(elcentro):
    """The short-period building (Case B) on a sway spring with a dashpot and a slider, with
    a flexible story and a base mass, under 6 s of El Centro: it uplifts, slides and
    rocks; the balance input = kinetic + strain + gravity + viscous + plastic closes to 1e-5
    (the run checks 1e-3), and the top's displacement relative to the ground is the sum of
    the base's sway, its rotation and the story's deformation, x = u_b + hθ + u (to 1e-12)."""
    scene = load_scene("short_period_elcentro", case="B", overrides=[
        "structure.vertical_weight=300", "foundation.sway_stiffness=20000",
        "foundation.sway_damping=50", "foundation.sliding_friction=0.1",
        "analysis.duration=6"])
    response = run(scene)
    assert response.peaks["sliding"] != 0.0 and response.peaks["uplift_max"] > 0.0
    assert response.energy_balance_error < 1e-5
    h = scene.structure.height
    rebuilt = response.sway + h * response.theta + response.u
    assert np.max(np.abs(response.x - rebuilt)) < 1e-12 * np.max(np.abs(response.x))


def test_rigid_block_rocking_and_swaying_keeps_x_consistent():
    """A rigid block (DOF u_G) released with a velocity on an uplifting bed and a sway spring:
    the top's displacement is u_b + hθ, with u_b the sway spring's deformation u_G − h_G θ
    (h_G = Σ m h / M, here 2 m: the whole mass at the top); the balance closes to 1e-6 at
    rtol 1e-7 (measured 5.8e-8; 1.9e-5 at the default rtol, 1.2e-5 for the same block
    without sway)."""
    scene = sway_scene(support="uplift", sway={"sway_stiffness": 3.0e5, "sway_damping": 100.0},
                       motion={"type": "free", "velocity": 0.3, "duration": 1.0},
                       analysis={"rtol": 1e-7})
    model = build_model(scene)
    assert model.sway_height == pytest.approx(2.0, rel=1e-14)
    response = run(scene)
    theta = response.theta
    assert np.max(np.abs(response.sway - (response.q[:, model.dofs.sway] - 2.0 * theta))) \
        < 1e-12 * np.max(np.abs(response.sway))
    assert np.max(np.abs(response.x - (response.sway + 2.0 * theta))) \
        < 1e-12 * np.max(np.abs(response.x))
    assert response.qd[0, model.dofs.sway] - 2.0 * response.qd[0, model.dofs.theta] == 0.0
    assert response.peaks["uplift_max"] > 0.0
    assert response.energy_balance_error < 1e-6


@pytest.mark.parametrize("changes,message", [
    ({"sway": {"sway_damping": 10.0}}, "foundation.sway_damping without foundation.sway_stiffness"),
    ({"sway": {"sliding_friction": 0.3}}, "foundation.sliding_friction without"),
    ({"sway": {"sway_stiffness": 1e5, "sliding_friction": 0.0}},
     "foundation.sliding_friction = 0: valid range is (0, 10]"),
    ({"sway": {"sway_stiffness": -1.0}}, "foundation.sway_stiffness = -1: outside the physical"),
    ({"sway": {"sway_stiffness": 1e5, "sway_damping": -2.0}}, "foundation.sway_damping = -2"),
    ({"sway": {"sway_stiffness": 1e5}, "structure": {"kinematics": "exact"}, "support": "uplift"},
     "foundation.sway_stiffness with structure.kinematics = 'exact'"),
    ({"sway": {"sway_stiffness": 1e5}, "rigid": False, "structure": {"vertical_weight": 1000.0},
      "support": "uplift"}, "structure.vertical_weight = 1000 with foundation.sway_stiffness"),
    ({"foundation": {"dashpots": [1.0] * 9}, "support": "uplift"},
     "foundation.dashpots has 9 entries: give one per spring (10)"),
    ({"foundation": {"dashpots": [1.0] * 10, "damping_ratio": 0.1}, "support": "uplift"},
     "foundation.damping_ratio = 0.1 with foundation.dashpots"),
    ({"foundation": {"dashpots": [-1.0] * 10}, "support": "uplift"},
     "foundation.dashpots[0] = -1"),
])
def test_sway_and_dashpot_keys_are_checked_up_front(changes, message):
    """Each bad combination is one InputError naming the field, the value and the range."""
    changes = dict(changes)
    kwargs = {"rigid": changes.pop("rigid", True), "support": changes.pop("support", "fixed")}
    with pytest.raises(InputError) as err:
        sway_scene(**kwargs, **changes)
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_rigid_structure_on_a_fixed_base_without_sway_is_still_refused():
    """Only the sway spring gives a rigid structure on a fixed base any motion."""
    with pytest.raises(InputError, match="a rigid structure on a fixed base has no motion"):
        sway_scene()


def _sliding_building():
    """A flexible story on an uplifting elasto-plastic bed with a sliding sway spring, under a
    0.5 g Ricker pulse: every switch of the model at once (uplift, yield, slip)."""
    return sway_scene(rigid=False, support="uplift",
                      sway={"sway_stiffness": 3e5, "sway_damping": 200.0, "sliding_friction": 0.2},
                      motion={"type": "ricker", "amplitude": 0.5, "period": 0.4, "duration": 2.0},
                      foundation={"law": "elastoplastic", "damping_ratio": 0.1})


@pytest.mark.parametrize("integrator", ["events", "rk4", "abm4", "newmark", "hht"])
def test_every_integrator_agrees_on_a_sliding_rocking_building(integrator):
    """Each integrator at its own step (events at its default error control, the others at a
    fixed 0.2 ms) against the event stepper at fixed 20 µs steps (a converged run of another
    discretization): peak sway, θ and u, and the final slip, within 1e-4 (measured: 1.3e-6 or
    less in sway, 4.1e-5 in θ for the implicit ones)."""
    scene = _sliding_building()
    reference = run(scene, integrator="events", dt=2e-5)
    response = run(scene, integrator=integrator, dt=None if integrator == "events" else 2e-4)
    assert reference.peaks["sliding"] < -0.01  # it slid by centimetres
    for key in ("sway", "theta", "u", "sliding"):
        assert response.peaks[key] == pytest.approx(reference.peaks[key], rel=1e-4), key


def test_a_sway_scene_is_changed_and_written_back_like_any_other():
    """scene.replace on the sway keys validates them as a file would and records the change;
    the scene's table gives back the same foundation."""
    from upliftlab.scenes.edit import scene_table
    from upliftlab.scenes import scene_from_dict as from_dict

    scene = _sliding_building().replace("foundation", sway_stiffness=2.0e5)
    assert scene.foundation.sway_stiffness == 2.0e5
    assert "foundation.sway_stiffness=200000.0" in scene.overrides
    assert from_dict(scene_table(scene)).foundation == scene.foundation
    with pytest.raises(InputError, match="foundation.sliding_friction = 20"):
        scene.replace("foundation", sliding_friction=20.0)


def test_the_opensees_export_refuses_a_sway_spring():
    """Its footing node is fixed horizontally: refused in one line, not silently dropped."""
    from upliftlab.comparisons.opensees.spec import check_representable

    with pytest.raises(InputError, match="foundation.sway_stiffness = 300000: the OpenSees"):
        check_representable(_sliding_building())


@pytest.mark.parametrize("rigid", [True, False])
def test_statics_do_not_see_an_undeformed_sway_spring(rigid):
    """Statics of equilibrium: a lateral force P at the top is carried by the sway spring in
    shear and by the bed in the moment P h about O, whatever the sway; so the uplift-onset
    force is that of the same scene without sway (to 1e-12), and a rocking pushover (the
    base rotated, the sway spring left undeformed) gives the same M–θ (to 1e-12)."""
    from upliftlab.reduced import rocking_pushover, uplift_onset_force

    plain = sway_scene(rigid=rigid, support="uplift", foundation={"law": "elastoplastic"})
    swaying = sway_scene(rigid=rigid, support="uplift", foundation={"law": "elastoplastic"},
                         sway={"sway_stiffness": 3.0e5, "sliding_friction": 0.2})
    onset = uplift_onset_force(build_model(plain))
    assert uplift_onset_force(build_model(swaying)) == pytest.approx(onset, rel=1e-12)
    thetas = np.linspace(0.0, 0.01, 21)
    a = rocking_pushover(build_model(plain), thetas)
    b = rocking_pushover(build_model(swaying), thetas)
    np.testing.assert_allclose(b.moment, a.moment, rtol=1e-12, atol=1e-12 * np.max(a.moment))
    np.testing.assert_allclose(b.vertical, a.vertical, rtol=1e-12)


def test_a_sway_spring_is_added_to_a_scene_by_replace():
    """scene.replace(foundation, sway_stiffness=…) on a scene without sway gives the scene a
    sway spring without a dashpot (the other sway keys stay unset), as the same key in a file."""
    plain = sway_scene(rigid=False, support="uplift")
    scene = plain.replace("foundation", sway_stiffness=3.0e5)
    assert scene.foundation.sway_damping is None and scene.foundation.sliding_friction is None
    model = build_model(scene)
    assert model.params["c"][model.sway_spring] == 0.0
    assert model.params["k"][model.sway_spring] == 3.0e5
    assert math.isinf(model.params["fy"][model.sway_spring])


def test_the_sway_is_labelled_data_and_saved(tmp_path):
    """The base's sway is a history of the dataset and the frame (only with a sway spring),
    its peaks are scalar variables with units, and the file reads back the same history."""
    import xarray as xr

    response = run(_sliding_building())
    ds = response.to_xarray()
    np.testing.assert_array_equal(ds["sway"].values, response.sway)
    assert ds["sway"].attrs["units"] == "m" and "u_b" in list(ds["dof"].values)
    assert float(ds["peak_sway"]) == response.peaks["sway"]
    assert ds["peak_sliding"].attrs["units"] == "m"
    assert "sway" in response.to_dataframe().columns
    path = response.save(tmp_path / "run.nc")[0]
    with xr.open_dataset(path) as back:
        np.testing.assert_array_equal(back["sway"].values, response.sway)
    plain = run(sway_scene(rigid=False, support="uplift"))
    assert "sway" not in plain.to_xarray() and "peak_sway" not in plain.to_xarray()
    assert "sway" not in plain.to_dataframe().columns
