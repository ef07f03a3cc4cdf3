"""A bed of hysteretic q–z springs in the reduced model (foundation.law = "qz"): energy balance,
the elastic limit against the existing elastic springs, settlement against intensity, and the
scene's checks.

References: the existing compression-only elastic springs (law "elastic", an independent
implementation of the same limit) through the same integrator and step, and through the event
stepper (exact switch location); the run's own energy balance, checked against the project's
tolerance (analysis.energy_tolerance, default 1e-3 of the input).
"""

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.reduced import build_model, run
from upliftlab.reduced.kernels import QZ
from upliftlab.scenes import ElasticLaw, QzLaw, scene_from_dict

ENERGY_TOL = 1e-3  # the project's default analysis.energy_tolerance


def _scene(amplitude, law="qz", integrator=None, **foundation):
    """Ewing's short-period wall (W = 202 kip, h = 336 in, T = 0.15 s) on 6 springs, no
    damping, under a Ricker pulse of 0.3 s."""
    f = {"support": "uplift", "half_width": 120.0, "layout": "winkler", "springs": 6,
         "vertical_period": 0.06, "law": law, "damping_ratio": 0.0}
    if law == "qz":
        f.update(capacity_multiple=3.0, z50=0.2)
    f.update(foundation)
    data = {"schema": 1, "units": "kip-in-s",
            "structure": {"weight": 202.0, "height": 336.0, "period": 0.15,
                          "damping_ratio": 0.0, "rotary_inertia": 7694.0},
            "foundation": f,
            "motion": {"type": "ricker", "amplitude": amplitude, "period": 0.3,
                       "duration": 2.0}}
    if integrator:
        data["analysis"] = {"integrator": integrator}
    return scene_from_dict(data)


def test_a_qz_scene_defaults_to_rk4_and_closes_its_energy_balance():
    response = run(_scene(0.6))
    assert response.info["integrator"] == "rk4"
    assert response.energy_balance_error <= ENERGY_TOL
    assert response.energy_of("plastic")[-1] > 0.0  # the hysteresis dissipated what it took


@pytest.mark.parametrize("integrator", ["newmark", "hht", "abm4"])
def test_every_accepting_integrator_closes_the_balance_and_agrees(integrator):
    """Against RK4 at its own step: the integrators converge to one response (second order
    for the implicit ones at 1/10 of the shortest bonded period: within 2 % of peak θ)."""
    reference = run(_scene(0.6))
    response = run(_scene(0.6, integrator=integrator))
    assert response.energy_balance_error <= ENERGY_TOL
    assert response.peaks["theta"] == pytest.approx(reference.peaks["theta"], rel=2e-2)
    assert response.peaks["final_vertical_position"] == pytest.approx(
        reference.peaks["final_vertical_position"], rel=2e-2)


@pytest.mark.parametrize("integrator", ["rk4", "newmark"])
def test_huge_capacity_reproduces_the_elastic_uplifting_bed(integrator):
    """q_ult = 10⁶ W: the near field never leaves its elastic range (0.2 q_ult), the gap
    opens at Q = 0 and closes where it opened: the compression-only elastic spring (Case A
    without damping). Same integrator and step: the states agree to 1e-9 of their size (they
    differ by round-off in the q–z solver); the event stepper's elastic run, which locates
    every switch, is within 1e-3 in peak θ and u (RK4 at 1 ms steps over the kinks)."""
    qz = run(_scene(0.6, integrator=integrator, capacity_multiple=1e6, z50=5e4))
    elastic = run(_scene(0.6, law="elastic", integrator=integrator))
    assert qz.info["dt"] == elastic.info["dt"]
    assert np.max(np.abs(qz.q - elastic.q)) <= 1e-9 * np.max(np.abs(elastic.q))
    assert np.max(np.abs(qz.energy_of("plastic"))) == 0.0  # the near field never moved
    events = run(_scene(0.6, law="elastic", integrator="events"))
    for key in ("theta", "u"):
        assert qz.peaks[key] == pytest.approx(events.peaks[key], rel=1e-3)


def test_settlement_at_the_end_grows_with_intensity():
    settlements = [-run(_scene(a)).peaks["final_vertical_position"]
                   for a in (0.2, 0.4, 0.6, 0.8)]
    assert settlements[0] > 0.0
    assert np.all(np.diff(settlements) > 0.0)


def test_the_static_state_sits_on_the_backbones():
    """Every spring of the symmetric bed carries W/6 at rest (equal capacities, equal z), and
    its compression is the virgin backbone's there."""
    model = build_model(_scene(0.6))
    found = model.params[model.foundation_slice]
    assert np.all(found["kind"] == QZ)
    assert found["f0"] == pytest.approx(np.full(6, 202.0 / 6), rel=1e-12)
    assert found["qult"] == pytest.approx(np.full(6, 3 * 202.0 / 6), rel=1e-15)


@pytest.mark.parametrize("edit, message", [
    ({"integrator": "events"}, "analysis.integrator = 'events' with foundation.law = 'qz'"),
    ({"restitution": 0.7}, "foundation.restitution = 0.7 with foundation.law = 'qz'"),
    # uniform bed: half the capacity 3W/2 on K_v = 5737 kip/in at 303/5737 = 0.0528 in at least
    ({"z50": 0.01}, "foundation.z50 = 0.01: the bed cannot carry half its capacity"),
    ({"capacity_multiple": 0.5}, "foundation.capacity_multiple"),
    ({"suction": 0.5}, "foundation.suction"),
    ({"support": "bonded"}, "foundation.support = 'bonded' with foundation.law = 'qz'"),
])
def test_bad_qz_input_is_refused_before_any_work(edit, message):
    edit = dict(edit)
    integrator = edit.pop("integrator", None)
    with pytest.raises(InputError) as info:
        build_model(_scene(0.6, integrator=integrator, **edit))
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_qz_keys_need_the_qz_law():
    with pytest.raises(InputError, match="foundation.z50 is read only with foundation.law"):
        _scene(0.6, law="elastic", z50=0.2)


def test_the_event_stepper_is_refused_when_asked_for_at_run_time():
    with pytest.raises(InputError, match="valid: 'rk4'"):
        run(_scene(0.6), integrator="events")


def test_rocking_pushover_of_a_huge_capacity_bed_is_the_elastic_beds():
    """The static route (reduced/static.py) through the q–z law: with q_ult = 10⁶ W the
    moment, settlement and contact along a rotation path are the elastic uplifting bed's (the
    existing elastic law) to 1e-9; with the calibrated capacity (3 W) the bed is weaker and
    settles more."""
    from upliftlab.reduced import rocking_pushover
    thetas = np.linspace(0.0, 0.004, 21)[1:]
    qz = rocking_pushover(build_model(_scene(0.6, capacity_multiple=1e6, z50=5e4)), thetas)
    elastic = rocking_pushover(build_model(_scene(0.6, law="elastic")), thetas)
    assert qz.moment == pytest.approx(elastic.moment, rel=1e-9)
    assert qz.vertical == pytest.approx(elastic.vertical, rel=1e-9, abs=1e-12)
    assert qz.contact == pytest.approx(elastic.contact, rel=1e-9)
    weak = rocking_pushover(build_model(_scene(0.6)), thetas)
    assert np.all(weak.moment[-5:] < elastic.moment[-5:])
    assert weak.vertical[-1] < elastic.vertical[-1]


def test_the_opensees_bridge_takes_the_qz_law_with_a_qzsimple2_exponent_only():
    """A q–z bed exports to QzSimple2 springs (tests/test_opensees_qz.py), whose exponents are
    1.2 (clay, type 1) and 5.5 (sand, type 2), from OpenSees' QzSimple2.cpp: the soil's own
    exponent is taken; a fitted one (2.0) has no QzSimple2 type and is refused in one line
    naming the field."""
    from upliftlab.comparisons.opensees.spec import opensees_spec

    assert len(opensees_spec(_scene(0.6)).qz) == 6
    with pytest.raises(InputError, match="foundation.qz_exponent = 2"):
        opensees_spec(_scene(0.6, qz_exponent=2.0))


def test_an_end_stiffened_bed_carries_half_its_capacity_at_z50():
    """End springs twice as stiff, capacities by tributary width: one z_ref puts the bed's
    virgin backbone through (z50, 1.5 W) — checked through the compiled law's own solver, not
    the bisection that calibrated it — its static forces sum to W with the stiffer ends
    carrying more, and a pulse run closes its balance."""
    from upliftlab.reduced.kernels import HISTORY_DTYPE, qz_start, qz_trial
    scene = _scene(0.6, layout="end_stiffened", springs=12, end_stiffness_ratio=2.0,
                   end_length=1.0 / 3.0)
    found = build_model(scene).params
    found = found[found["kind"] == QZ]
    history = np.zeros(found.size, dtype=HISTORY_DTYPE)
    total = 0.0
    for j in range(found.size):
        qz_start(found[j], history[j], 0.0)
        total += qz_trial(found[j], history[j], 0.2)[0]
    assert total == pytest.approx(1.5 * 202.0, rel=1e-9)
    assert found["f0"].sum() == pytest.approx(202.0, rel=1e-12)
    assert found["f0"][0] > found["f0"][5]
    assert run(scene).energy_balance_error <= ENERGY_TOL


def test_a_qz_scene_replaced_keeps_its_qz_fields_and_checks():
    # Reference: the fields given, and the scene read from the table the change writes.
    scene = _scene(0.6).replace("foundation", z50=0.3)
    assert (scene.foundation.law.name, scene.foundation.law.z50) == ("qz", 0.3)
    assert scene.foundation.law.capacity_multiple == 3.0
    assert scene.overrides[-1] == "foundation.z50=0.3"
    with pytest.raises(InputError, match="foundation.z50 = 0.01"):
        build_model(scene.replace("foundation", z50=0.01))
    # another law by name: a record of that law, none of the q–z fields left behind
    elastic = scene.replace("foundation", law="elastic")
    assert elastic.foundation.law == ElasticLaw()
    assert not set(QzLaw.keys()) - {"yield_multiple"} & set(elastic.table["foundation"])
    with pytest.raises(InputError, match=r"foundation.z50: not a field of Foundation or of its "
                                         r"law ElasticLaw"):
        scene.replace("foundation", law="elastic", z50=0.2)
    again = elastic.replace("foundation", law="qz", capacity_multiple=3.0, z50=0.3)
    assert again.digest == scene.digest
    with pytest.raises(InputError, match="capacity_multiple"):
        elastic.replace("foundation", law="qz", z50=0.3)
