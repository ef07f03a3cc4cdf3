"""The elasto-plastic bed with a uniform bearing capacity (foundation.capacity_multiple with
law = 'elastoplastic'): every spring yields at the same bearing pressure, q_y = FS_v W/B over
its tributary width, whatever its stiffness.

References: the static forces of a two-zone (end-stiffened) bed worked by hand; the rigid-plastic
stress block of a tensionless footing under N and M, whose moment capacity is N B/2 (1 − 1/FS_v)
for a uniform bearing pressure (anchor §2's ultimate moment ratio, written once in
upliftlab.anchors) and a stiffness-weighted bed's, worked by hand; the energy balance of a run
(every term computed independently of the integrator) and two independent integrators (the
event stepper and RK4).
"""

import numpy as np
import pytest

from upliftlab.anchors import ultimate_moment_ratio
from upliftlab.checks import InputError
from upliftlab.reduced import build_model, rocking_pushover, run
from upliftlab.reduced.compatibility import end_stiffened_bed
from upliftlab.reduced.laws.elastoplastic import bearing_yield_forces, static_forces
from upliftlab.scenes.edit import scene_table
from upliftlab.scenes import scene_from_dict

W, B = 100.0, 2.0  # kN/m and m: the hand cases' weight and base width
R_K, R_E, SPRINGS = 10.0, 1.0 / 3.0, 48  # end zones of 8 springs each: widths 2/3 m and 4/3 m


def bed_scene(**foundation):
    """A kN-m-s scene: W = 100 kN/m at 3 m (T = 0.3 s, 5 %) on an end-stiffened bed of 48
    springs, R_k = 10 over R_e = b/3, elasto-plastic."""
    f = {"support": "uplift", "half_width": 0.5 * B, "layout": "end_stiffened",
         "springs": SPRINGS, "stiffness": 2.0e5, "end_stiffness_ratio": R_K,
         "end_length": R_E, "law": "elastoplastic"}
    f.update(foundation)
    f = {key: value for key, value in f.items() if value is not None}  # None: key removed
    return scene_from_dict({
        "schema": 1, "units": "kN-m-s",
        "structure": {"weight": W, "height": 3.0, "period": 0.3, "damping_ratio": 0.05,
                      "rotary_inertia": 10.0},
        "foundation": f,
        "motion": {"type": "ricker", "amplitude": 0.6, "period": 0.4, "duration": 3.0}})


@pytest.mark.parametrize("fs, end_pressure, middle_pressure", [
    # FS 3: q_y = 150 kPa is above the elastic end pressure W/(R_k W_e + W_m) · R_k = 125 kPa:
    # nothing yields at rest, the middle carries 12.5 kPa
    (3.0, 125.0, 12.5),
    # FS 2: q_y = 100 kPa; the end zones (2/3 m) carry 66.7 kN/m at their cap and the middle
    # (4/3 m) the remaining 33.3 kN/m: 25 kPa
    (2.0, 100.0, 25.0),
])
def test_static_forces_of_a_two_zone_bed_match_the_hand_values(fs, end_pressure,
                                                                middle_pressure):
    bed = end_stiffened_bed(0.5 * B, 1.0e5, SPRINGS, R_K, R_E)
    fy = bearing_yield_forces(bed, fs * W)
    np.testing.assert_allclose(fy / bed.widths, fs * W / B, rtol=1e-14)
    F0, theta = static_forces(bed, W, fy)
    end = bed.stiffnesses > bed.stiffnesses.min() * 1.5
    assert end.sum() == 16
    np.testing.assert_allclose((F0 / bed.widths)[end], end_pressure, rtol=1e-12)
    np.testing.assert_allclose((F0 / bed.widths)[~end], middle_pressure, rtol=1e-12)
    assert abs(theta) < 1e-14 and F0.sum() == pytest.approx(W, rel=1e-14)


def test_an_asymmetric_bed_is_balanced_in_moment_with_its_springs_capped():
    # custom springs, a stiff one right of centre: it reaches its cap at rest, and the others
    # must share the rest as one rigid base (a common θ and V) with no moment
    from upliftlab.reduced.compatibility import custom_springs

    x = np.array([-0.9, -0.4, 0.1, 0.5, 0.9])
    k = np.array([1.0, 1.0, 20.0, 2.0, 1.0]) * 1e4
    bed = custom_springs(1.0, x, k)
    fy = bearing_yield_forces(bed, 1.5 * W)
    F0, theta = static_forces(bed, W, fy)
    assert F0.sum() == pytest.approx(W, rel=1e-13)
    assert (F0 * x).sum() == pytest.approx(0.0, abs=1e-12 * W)
    capped = F0 >= fy * (1 - 1e-12)
    assert capped.tolist() == [False, False, True, False, False]
    assert (F0[~capped] < fy[~capped]).all()
    # the elastic springs lie on one plane F/k = x θ − V: fitted by least squares from them
    # alone, it returns the static rotation and leaves no residual
    (theta_fit, v_fit), *_ = np.linalg.lstsq(np.c_[x[~capped], -np.ones(4)],
                                             F0[~capped] / k[~capped], rcond=None)
    assert theta_fit == pytest.approx(theta, rel=1e-10)
    np.testing.assert_allclose(k[~capped] * (x[~capped] * theta_fit - v_fit), F0[~capped],
                               rtol=1e-10)
    assert k[2] * (x[2] * theta_fit - v_fit) > fy[2]  # elastic, it would carry more than its cap


@pytest.mark.parametrize("fs", [1.5, 3.0, 8.0])
def test_the_pushed_bed_reaches_the_uniform_stress_block_moment(fs):
    """Pushed to 0.5 rad at constant weight, the uniform-capacity bed carries the stress
    block's moment N B/2 (1 − 1/FS_v) to within one strip's share (the block's edge falls
    inside a strip)."""
    thetas = np.linspace(0.0, 0.5, 401)
    M = rocking_pushover(build_model(bed_scene(capacity_multiple=fs)), thetas).moment[-1]
    block = W * B * ultimate_moment_ratio(fs)
    assert M == pytest.approx(block, abs=fs * W / B * (B / SPRINGS) * 0.5 * B)
    assert abs(M / block - 1.0) < 0.01


@pytest.mark.parametrize("fs", [3.0, 8.0])
def test_the_stiffness_weighted_bed_carries_the_moment_of_its_stiff_ends(fs):
    """The same bed with yield_multiple (each spring at FS_v × its static force) holds a
    larger moment: its ends' pressure capacity is FS_v × 125 kPa, so the block L = W/(FS_v ·
    125 kPa) lies in the end zone (L ≤ 2/3 m) and M = W (b − L/2), by hand."""
    thetas = np.linspace(0.0, 0.5, 401)
    M = rocking_pushover(build_model(bed_scene(yield_multiple=fs)), thetas).moment[-1]
    L = W / (fs * 125.0)
    assert M == pytest.approx(W * (0.5 * B - 0.5 * L), rel=0.005)
    assert M > 1.08 * W * B * ultimate_moment_ratio(fs)


@pytest.mark.parametrize("integrator", ["events", "rk4"])
def test_a_run_on_a_bed_yielded_at_rest_closes_its_energy_and_integrators_agree(integrator):
    # FS_v = 2: the end springs start at their cap
    scene = bed_scene(capacity_multiple=2.0)
    out = run(scene, integrator=integrator, dt=0.001 if integrator == "rk4" else 0.005)
    assert out.peaks["energy_balance_error"] < 1e-3
    assert out.settlement[-1] > 0.0  # the yielded ends settle
    if integrator == "rk4":
        ref = run(scene, integrator="events", dt=0.005)
        assert out.peaks["theta"] == pytest.approx(ref.peaks["theta"], rel=0.01)
        assert out.settlement[-1] == pytest.approx(ref.settlement[-1], rel=0.01)


def test_given_yield_forces_are_the_capacity_beds_forces():
    # the uniform capacity written out as one force per spring (FS_v W/B times each strip's
    # width, by hand) builds the same model as capacity_multiple, to round-off
    fs = 2.0
    widths = np.full(SPRINGS, B / SPRINGS)
    given = build_model(bed_scene(yield_forces=[fs * W / B * w for w in widths]))
    bearing = build_model(bed_scene(capacity_multiple=fs))
    for field in ("fy", "f0", "k"):
        np.testing.assert_allclose(given.params[field], bearing.params[field], rtol=1e-12)
    # a custom layout's forces follow its positions, as its dashpots do
    x, k, fy = [0.5, -0.5, 0.0], [2e4, 1e4, 1e4], [70.0, 50.0, 60.0]
    custom = build_model(bed_scene(layout="custom", positions=x, stiffnesses=k,
                                   yield_forces=fy, springs=3, stiffness=None,
                                   end_stiffness_ratio=None, end_length=None))
    order = np.argsort(x)
    np.testing.assert_allclose(custom.params["fy"][custom.foundation_slice],
                               np.array(fy)[order], rtol=0)


def test_capacity_keys_are_checked_up_front():
    with pytest.raises(InputError, match="yield_multiple with foundation.capacity_multiple"):
        bed_scene(capacity_multiple=3.0, yield_multiple=3.0)
    with pytest.raises(InputError, match="capacity_multiple with foundation.yield_forces"):
        bed_scene(capacity_multiple=3.0, yield_forces=[10.0] * SPRINGS)
    with pytest.raises(InputError, match=r"yield_forces has 3 entries: give one per spring "
                                         r"\(48\)"):
        bed_scene(yield_forces=[10.0] * 3)
    with pytest.raises(InputError, match=r"foundation.yield_forces\[1\] = -1"):
        bed_scene(yield_forces=[10.0, -1.0] + [10.0] * (SPRINGS - 2))
    with pytest.raises(InputError, match=r"yield_forces is read only with foundation.law = "
                                         r"'elastoplastic' \(law is 'elastic'\)"):
        bed_scene(yield_forces=[10.0] * SPRINGS, law="elastic")
    with pytest.raises(InputError, match=r"cannot carry the weight|tension at rest"):
        build_model(bed_scene(yield_forces=[1.0] * SPRINGS))  # Σ Fy = 48 kN/m < W
    with pytest.raises(InputError, match=r"capacity_multiple is read only with foundation.law = "
                                         r"'elastoplastic' or 'qz' or 'macro' "
                                         r"\(law is 'elastic'\)"):
        bed_scene(capacity_multiple=3.0, law="elastic")
    with pytest.raises(InputError, match=r"foundation.capacity_multiple = 1"):
        bed_scene(capacity_multiple=1.0)
    with pytest.raises(InputError, match=r"foundation.z50 is read only"):
        bed_scene(capacity_multiple=3.0, z50=0.01)


def test_a_bearing_capacity_bed_is_written_back_as_it_was_read():
    scene = bed_scene(capacity_multiple=2.5)
    table = scene_table(scene)["foundation"]
    assert table["capacity_multiple"] == 2.5 and "yield_multiple" not in table
    again = scene_from_dict({**scene_table(scene)})
    assert again.foundation.law.capacity_multiple == 2.5
    plain = scene_table(bed_scene(yield_multiple=2.5))["foundation"]
    assert plain["yield_multiple"] == 2.5 and "capacity_multiple" not in plain
    assert bed_scene().foundation.law.capacity_multiple is None  # the yield-multiple variant
    forces = [5.0] * SPRINGS
    table = scene_table(bed_scene(yield_forces=forces))["foundation"]
    assert table["yield_forces"] == forces and "yield_multiple" not in table
    assert scene_from_dict(scene_table(bed_scene(yield_forces=forces))).foundation == \
        bed_scene(yield_forces=forces).foundation


def test_the_opensees_bridge_refuses_a_bed_yielding_at_other_forces():
    from upliftlab.comparisons.opensees.spec import check_representable

    check_representable(bed_scene(yield_multiple=3.0))  # written: yield_multiple x F0
    for key, value in (("capacity_multiple", 3.0), ("yield_forces", [5.0] * SPRINGS)):
        with pytest.raises(InputError, match=rf"^foundation.{key}: the OpenSees script yields "):
            check_representable(bed_scene(**{key: value}))
