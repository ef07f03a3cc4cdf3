"""The macro-element as the reduced model's foundation law (foundation.law = "macro"): its
elastic limit against a bed of springs, the energy balance with plasticity, step convergence,
the overturning verdict and the scene's checks.

References: the existing compression-only elastic springs (law "elastic", an independent
implementation): a uniform bed of many springs is the tensionless Winkler bed that the
element's uplift mechanism integrates in closed form, so with a capacity far beyond the loads
the two are the same model, up to the bed's discretisation (its rocking stiffness is
K_v b²/3 (1 − 1/N²), its outermost spring sits b/N inside the edge); the run's own energy
balance against the project's tolerance (analysis.energy_tolerance, 1e-3 of the input); the
run at half the step (the integrator's convergence).
"""

import functools

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.reduced import IntegrationError, build_model, run
from upliftlab.reduced.batch import run_batch
from upliftlab.scenes import scene_from_dict

ENERGY_TOL = 1e-3  # the project's default analysis.energy_tolerance
SPRINGS = 400      # the bed standing for the continuous one
ELASTIC = {"capacity_multiple": 1e5, "initial_size": 0.999, "interior_modulus": 1e6,
           "sliding_ratio": 4.0}
CLAY = {"capacity_multiple": 3.0, "initial_size": 0.67, "interior_modulus": 80.0,
        "interior_exponent": 1.1, "settlement_coupling": 0.1, "rounding_ratio": 0.5,
        "hardening_settlement": 0.1}


def _scene(amplitude, law="macro", rigid=False, integrator=None, dt=None, motion=None,
           **foundation):
    """Ewing's short-period wall (W = 202 kip, h = 336 in, b = 120 in), its base weighing
    40 kip more, on K_v = K_h = 20,000 kip/in, under a Ricker pulse of 0.3 s."""
    f = {"support": "uplift", "half_width": 120.0, "layout": "winkler", "springs": SPRINGS,
         "stiffness": 20000.0, "sway_stiffness": 20000.0, "law": law, "damping_ratio": 0.0}
    if law == "macro":
        f.update(ELASTIC)
    f.update(foundation)
    f = {k: v for k, v in f.items() if v is not None}  # None: the key left out
    structure = {"weight": 202.0, "height": 336.0, "damping_ratio": 0.0,
                 "rotary_inertia": 7694.0, "vertical_weight": 242.0}
    if rigid:  # a block: its weight's overturning moment (P-Δ) tips it
        structure.update(rigid=True, stiffness=1.0, p_delta=True)
    else:
        structure["period"] = 0.15
    data = {"schema": 1, "units": "kip-in-s", "structure": structure, "foundation": f,
            "motion": motion or {"type": "ricker", "amplitude": amplitude, "period": 0.3,
                                 "duration": 2.0},
            "analysis": {"integrator": integrator or "rk4"}}
    if dt:
        data["analysis"]["dt"] = dt
    return scene_from_dict(data)


@pytest.mark.parametrize("rigid, amplitude", [(False, 0.15), (True, 0.3)])
def test_its_elastic_limit_is_a_bed_of_many_springs(rigid, amplitude):
    """Far from its capacity, the element is the continuous tensionless bed: θ, V, the sway
    and the least contact length of 400 elastic springs, through the same integrator and step,
    within 1e-4 (the bed's rocking stiffness differs by 1/N² = 6e-6); the larger edge gap
    within θ b/N of the outermost spring's (0.25 %). A rigid structure checks the sway's
    u = u_G − h_G θ. The pulses keep V above 0.4 W: nearer the bounding surface's apex at V = 0
    the element yields even on this strong a soil (issue 36's note)."""
    macro = run(_scene(amplitude, rigid=rigid, dt=2e-4))
    bed = run(_scene(amplitude, law="elastic", rigid=rigid, dt=2e-4))
    m, s = macro.peaks, bed.peaks
    assert m["uplift_max"] > 0.05  # the base lifts off: the nonlinear range is tested
    assert m["min_contact_length"] < 0.4 * 240.0
    assert np.abs(macro.base[:, 3:6]).max() < 1e-5 * 242.0 / 20000.0  # elastic: v_p, u_p, θ_p
    for key in ("theta", "V_max", "V_min", "min_contact_length"):
        assert m[key] == pytest.approx(s[key], rel=1e-4, abs=1e-9), key
    # the element's sway is tracked at the steps' ends, the sway spring's peak between them
    assert m["sway"] == pytest.approx(s["sway"], rel=1e-3)
    if not rigid:
        assert m["u"] == pytest.approx(s["u"], rel=1e-4)
    outer = 120.0 - 120.0 / SPRINGS  # the bed's outermost spring
    assert m["uplift_max"] == pytest.approx(s["uplift_max"] * 120.0 / outer, rel=1e-3)
    assert macro.energy_balance_error <= ENERGY_TOL
    history = np.interp(bed.time, macro.time, macro.theta)
    assert np.max(np.abs(history - bed.theta)) <= 1e-3 * np.max(np.abs(bed.theta))


def test_it_yields_settles_and_closes_its_energy_balance():
    """A heavy wall (FS_v 3) under a strong pulse: the element dissipates (its own account and
    the integrator's agree), the base settles plastically (χ > 0 couples settlement to
    rocking), the soil's surface rounds, and the balance closes."""
    response = run(_scene(0.6, **CLAY))
    p = response.peaks
    assert response.energy_balance_error <= ENERGY_TOL
    assert response.energy_of("plastic")[-1] > 0.3 * response.energy_of("input").max()
    assert response.base[-1, 9] == pytest.approx(response.energy_of("plastic")[-1], rel=1e-9)
    assert p["plastic_settlement"] > 0.0
    assert response.base[-1, 8] > 0.0  # the rounding ρ
    assert response.info["macro_negative_work"] <= 1e-3 * response.energy_of("input").max()


def test_it_converges_with_its_force_step_and_the_time_step():
    """At the default sub-step (3e-4 of the weight in trial force, one sub-step a time step
    here) peak θ, the edge gap and the plastic settlement are within 1e-3 of a run at a 5×
    finer sub-step (the sub-step is first order: their difference is 4/5 of the default's
    own error; measured: θ 1e-6, the gap 1.3e-5, the plastic settlement 1.5e-4), and halving
    the time step moves them by less than 1e-3. (At the law's first default, 2e-3 of V_ult,
    and its radial interior, the final position moved by 75 % between time steps of 3e-4 and
    3.75e-5 s.)"""
    default = _clay_pulse().peaks
    fine = run(_scene(0.6, force_step=6e-5, **CLAY)).peaks
    half = run(_scene(0.6, dt=default_dt(), **CLAY)).peaks
    for key in ("theta", "uplift_max", "plastic_settlement"):
        assert default[key] == pytest.approx(fine[key], rel=1e-3), key
        assert half[key] == pytest.approx(default[key], rel=1e-3), key


def default_dt():
    """Half the step the scene takes by default (s)."""
    return 0.5 * _clay_pulse().info["dt"]


@functools.cache
def _clay_pulse():
    """The clay element under the 0.6 g pulse by RK4 at the default step and sub-step (run
    once: two tests read it)."""
    return run(_scene(0.6, **CLAY))


def test_abm4_agrees_with_rk4():
    reference = _clay_pulse().peaks
    response = run(_scene(0.6, integrator="abm4", **CLAY))
    assert response.energy_balance_error <= ENERGY_TOL
    for key in ("theta", "uplift_max", "plastic_settlement"):
        assert response.peaks[key] == pytest.approx(reference[key], rel=1e-2), key


def test_dashpots_act_in_contact_and_dissipate():
    """The foundation's damping as dashpots under the contact: the viscous work is positive,
    the balance closes, and the response is smaller than without them."""
    damped = run(_scene(0.15, damping_ratio=0.2))
    free = run(_scene(0.15))
    assert damped.energy_balance_error <= ENERGY_TOL
    assert damped.energy_of("viscous")[-1] > 0.0
    assert damped.peaks["theta"] < free.peaks["theta"]


def test_a_run_whose_element_creates_energy_is_refused():
    """The flexible wall lifting its base off almost entirely (V down to about 0.01 W) while
    its base shear pushes: the load reaches the surface's cone at the apex V = 0 (H/(t_h V)
    and M/(V b) together at their limit, whatever the soil's strength), and the flow and
    return there do negative plastic work (1.9 % of the input here). The balance still closes
    (the account is consistent), so the run is refused on its own check."""
    with pytest.raises(IntegrationError, match="negative plastic work"):
        run(_scene(0.5))


def test_its_states_are_stored_and_labelled():
    """The response's base columns are the kernels' (N_BASE_OUT), named alike in the response
    and its labelled data, and the file carries each with its unit."""
    from upliftlab.reduced.kernels import N_BASE_OUT
    from upliftlab.reduced.labelled import BASE_STATES
    from upliftlab.reduced.response import BASE_NAMES
    response = run(_scene(0.15))
    assert response.base.shape[1] == N_BASE_OUT == len(BASE_NAMES)
    assert tuple(BASE_STATES) == BASE_NAMES
    data = response.to_xarray()
    assert data["base_V"].attrs["units"] == "kip"
    np.testing.assert_array_equal(data["base_dissipated"].values, response.base[:, 9])
    assert response.contact_length.min() == pytest.approx(response.peaks["min_contact_length"],
                                                          rel=1e-2)


def test_the_model_has_no_springs_under_it():
    model = build_model(_scene(0.5))
    assert model.base is not None
    assert model.spring_count == 1  # the story spring alone
    assert model.sway_spring == -1
    K, _ = model.bonded_matrices()
    bed = build_model(_scene(0.5, law="elastic"))
    Kb, _ = bed.bonded_matrices()
    # the same bonded stiffness as the bed's (the element takes its K_v, K_θ and K_h)
    np.testing.assert_allclose(K, Kb, rtol=1e-9, atol=1e-9 * np.abs(Kb).max())


@pytest.mark.parametrize("rigid", [False, True])
def test_a_free_rocking_release_starts_from_the_held_rotation(rigid):
    """A wall (or a block) released from a held rotation θ0 = 2 θ_up (its static uplift
    rotation), no ground motion. Reference: 400 elastic springs, whose static push to θ0 is
    their own vertical equilibrium (the element's elastic limit: the same bed): θ's
    history within 1e-3 of its peak, the peaks θ, V_max, V_min and the least contact length
    within 1e-4; at the start the element carries the weight (V = W to 1e-9) at θ0 and has
    done no plastic work; the energy balance closes."""
    theta_up = 2 * 242.0 / (20000.0 / 240.0 * 240.0 ** 2)  # 2W/(k B²), k = K_v/B
    free = {"type": "free", "rotation": 2 * theta_up, "duration": 1.0}
    macro = run(_scene(0.0, rigid=rigid, dt=2e-4, motion=free))
    bed = run(_scene(0.0, law="elastic", rigid=rigid, dt=2e-4, motion=free))
    assert macro.theta[0] == pytest.approx(2 * theta_up, rel=1e-12)
    assert macro.base[0, 0] == pytest.approx(242.0, rel=1e-9)
    assert np.abs(macro.base[:, 3:6]).max() < 1e-5 * 242.0 / 20000.0
    m, s = macro.peaks, bed.peaks
    for key in ("theta", "V_max", "V_min", "min_contact_length"):
        assert m[key] == pytest.approx(s[key], rel=1e-4, abs=1e-9), key
    history = np.interp(bed.time, macro.time, macro.theta)
    assert np.max(np.abs(history - bed.theta)) <= 1e-3 * np.max(np.abs(bed.theta))
    assert macro.energy_balance_error <= ENERGY_TOL


def test_the_event_stepper_is_refused():
    with pytest.raises(InputError, match="valid: 'rk4', 'abm4', 'newmark', 'hht'"):
        run(_scene(0.5, integrator="events"))


@pytest.mark.parametrize("integrator, dt, tolerance", [("newmark", 1e-3, 1.5e-2),
                                                       ("newmark", 2.5e-4, 2e-3),
                                                       ("hht", 2.5e-4, 2e-3)])
def test_the_implicit_integrators_carry_it_as_rk4_does(integrator, dt, tolerance):
    """Newmark and HHT-α with the element's force and tangent in their Newton iteration
    (:func:`upliftlab.reduced.kernels.base.base_tangent`) against RK4 at its own step
    (2.9e-4 s; an independent explicit method of fourth order): on the clay element near its
    capacity (the wall at 0.5 g, the base yielding, settling 30 mm and lifting off), peak θ,
    edge uplift, the peak sway and the plastic settlement within ``tolerance`` (measured at
    1e-3 s: −0.01 %, −0.28 %, +0.17 %, −1.2 %; at 2.5e-4 s: all within 0.06 %, HHT 0.1 %),
    closing on RK4's as the step shrinks; the energy balance within 1e-4 of the input (the
    element's plastic work booked once per accepted step: measured 4e-5 and 3e-6)."""
    explicit = run(_scene(0.5, **CLAY))
    implicit = run(_scene(0.5, integrator=integrator, dt=dt, **CLAY))
    e, i = explicit.peaks, implicit.peaks
    assert e["uplift_max"] > 0.05 and e["plastic_settlement"] > 1e-2  # yields and lifts off
    for key in ("theta", "uplift_max", "sway", "plastic_settlement"):
        assert i[key] == pytest.approx(e[key], rel=tolerance), key
    assert implicit.energy_balance_error <= 1e-4


@pytest.mark.parametrize("change, field", [
    ({"restitution": 0.7}, "foundation.restitution"),
    ({"sway_stiffness": None}, "foundation.sway_stiffness"),
    ({"sliding_friction": 0.5}, "foundation.sliding_friction"),
    ({"support": "bonded"}, "foundation.support"),
    ({"frictional_share": 1.5}, "foundation.frictional_share"),
    ({"capacity_multiple": 0.5}, "foundation.capacity_multiple"),
    ({"settlement_coupling": 0.5}, "foundation.settlement_coupling"),
    ({"flow_dilatancy": 1.5}, "foundation.flow_dilatancy"),
    ({"flow_dilatancy": -0.1}, "foundation.flow_dilatancy"),
    ({"coupling_exponent": 9.0}, "foundation.coupling_exponent"),
    ({"memory_modulus": -1.0}, "foundation.memory_modulus"),
    ({"memory_modulus": 2e6}, "foundation.memory_modulus"),
])
def test_a_scene_it_cannot_take_is_refused_with_its_field(change, field):
    with pytest.raises(InputError, match=field.replace(".", r"\.")):
        _scene(0.5, **change)


def test_the_tools_that_take_springs_refuse_it_up_front(tmp_path):
    """The OpenSees writer and the advisor take beds of springs: one line naming the law."""
    from upliftlab.comparisons.advise.ladder import advise
    from upliftlab.comparisons.opensees.spec import check_representable
    scene = _scene(0.15)
    for tool in (check_representable, advise):
        with pytest.raises(InputError, match=r"^foundation.law = 'macro'"):
            tool(scene)


def test_an_initial_displacement_is_refused_alone_and_in_a_batch():
    held = {"type": "free", "displacement": 0.5, "duration": 1.0}  # the top mass held aside
    with pytest.raises(InputError, match=r"^motion\.displacement with foundation\.law"):
        run(_scene(0, motion=held))
    with pytest.raises(InputError, match=r"scene 0 .*motion\.displacement with foundation"):
        run_batch([_scene(0, motion=held)], integrator=None, workers=1)
    # the batch's default integrator (the event stepper) cannot carry it: refused up front
    with pytest.raises(InputError, match=r"nothing was integrated: .*'events' with "
                       r"foundation\.law = 'macro'"):
        run_batch([_scene(0.5, **CLAY)], workers=1)


def test_a_batch_gives_each_runs_own_peaks():
    """Reference: each scene run alone (``run``, no histories: the same kernel and step), whose
    peaks the batch must give to round-off (1e-12): u, θ, base shear, the plastic settlement
    v_p at the end and the final V; and the left edge's peak gap against the run of the mirror
    image (the ground motion negated, the wall symmetric), whose left edge is the first run's
    right: the larger of the two left gaps is the element's own larger edge gap
    (``uplift_max``), and the two differ (a column of the larger gap would give both the
    same). A yielding clay wall and a stiff one, Newmark and RK4, two processes."""
    scenes = [_scene(0.6, integrator="newmark", dt=1e-3, **CLAY),
              _scene(0.3, integrator="rk4", **CLAY)]
    mirrored = [_scene(-0.6, integrator="newmark", dt=1e-3, **CLAY),
                _scene(-0.3, integrator="rk4", **CLAY)]
    batch = run_batch(scenes + mirrored, integrator=None, workers=2)
    assert batch.ok.all()
    for i, scene in enumerate(scenes):
        alone = run(scene, histories=False)
        row, mirror = batch.row(i), batch.row(i + len(scenes))
        for key in ("u", "theta", "base_shear"):
            assert row[key] == pytest.approx(alone.peaks[key], rel=1e-12), key
        assert row["weighted_plastic_settlement"] == pytest.approx(alone.base[-1, 3], rel=1e-12)
        assert row["final_vertical_position"] == pytest.approx(
            alone.q[-1, alone.model.dofs.v], rel=1e-12)
        assert alone.peaks["uplift_max"] > 0.0  # the base lifts off
        assert max(row["uplift_left"], mirror["uplift_left"]) == pytest.approx(
            alone.peaks["uplift_max"], rel=1e-9)
        # one edge, not the larger of both: the two runs' left edges differ (measured: 2 %)
        assert abs(row["uplift_left"] / mirror["uplift_left"] - 1.0) > 1e-3
        assert row["energy_balance_error"] <= ENERGY_TOL


def test_its_cost_is_counted_before_the_run():
    """Reference: :data:`upliftlab.budget.MACRO_SECONDS_PER_STEP`, 300 µs a step (measured:
    270 µs on this wall at 0.6 g, ``benchmarks/MACRO_SPEED.md``, against 3 µs for a bed of 48
    springs): the 2 s pulse's 6,800 RK4 steps are estimated at 2 s, so a budget of 1 s refuses
    the run before it starts, naming the element; the bed of springs at the same budget runs."""
    with pytest.raises(InputError, match=r"^--budget = 1 s: .*a macro-element"):
        run(_scene(0.6, **CLAY), budget=1.0)
    bed = _scene(0.6, law="elastoplastic", capacity_multiple=3.0, sliding_ratio=None)
    assert run(bed, budget=1.0, histories=False).info["verdict"] == "completed"
