"""The q–z bed's calibration functions against hand values
(comparisons/beds/qz/calibration.py, reduced/qz.py).

Every reference below is worked out by hand in the comment above its assertion."""

from types import SimpleNamespace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.beds.qz.calibration import (
    calibrate_qz, elastic_range_from_unloading, qz_stiffnesses, spring_capacities,
    suction_from_cyclic, z50_from_pushover)
from upliftlab.reduced.laws.qz import QZ_SOILS, common_zref, z50_lower_bound, zref_from_z50


def test_capacities_follow_the_tributary_widths():
    # 120 over widths 1, 2, 1 (sum 4): 30, 60, 30
    assert spring_capacities(120.0, [1.0, 2.0, 1.0]) == pytest.approx([30.0, 60.0, 30.0],
                                                                      rel=1e-15)


def test_stiffnesses_reproduce_K_v_and_K_r():
    # b = 3, 6 strips of width 1 at ±0.5, ±1.5, ±2.5; end zone |x| ≥ 3(1 − 1/3) = 2: the two
    # outer springs. R_k = 2: weights 2, 1, 1, 1, 1, 2 (sum 8), so with K_v = 8, k = 2 at the
    # ends and 1 inside; K_r = 2·2·2.5² + 1·2·(0.5² + 1.5²) = 25 + 5 = 30. Given K_v = 8 and
    # K_r = 30 the calibration must find R_k = 2 and these k.
    k, ratio, feasible = qz_stiffnesses(8.0, 30.0, 3.0, 6, 1.0 / 3.0, 100.0)
    assert feasible
    assert ratio == pytest.approx(2.0, rel=1e-12)
    assert k == pytest.approx([2.0, 1.0, 1.0, 1.0, 1.0, 2.0], rel=1e-12)


def test_an_unreachable_ratio_keeps_K_r():
    # the same bed with R_k at most 2; asked for K_r/K_v = 37.5/7.5 = 5 (exact R_k =
    # (A_m − 5 W_m)/(5 W_e − A_e) = (5 − 20)/(10 − 12.5) = 6 > 2): R_k = 2, whose K_r/K_v is
    # 3.75, and K_r = 37.5 kept: K_v = 37.5/3.75 = 10, k = 2.5 at the ends and 1.25 inside
    k, ratio, feasible = qz_stiffnesses(7.5, 37.5, 3.0, 6, 1.0 / 3.0, 2.0)
    assert not feasible
    assert ratio == 2.0
    assert k == pytest.approx([2.5, 1.25, 1.25, 1.25, 1.25, 2.5], rel=1e-12)


def test_z50_is_the_settlement_at_half_capacity():
    # N = 40 at s = 1, 70 at s = 2; half of 100 is 50: s = 1 + (50 − 40)/30 = 1.3333
    assert z50_from_pushover([0, 1, 2, 3], [0, 40, 70, 90], 100.0) == pytest.approx(4 / 3,
                                                                                    rel=1e-14)
    with pytest.raises(InputError, match="never cross half"):
        z50_from_pushover([0, 1, 2], [0, 10, 20], 100.0)


def test_suction_is_the_largest_tension_over_capacity():
    # least force −2 over capacity 100: 0.02; never below 0: 0; −20 is beyond QzSimple's 0.1
    assert suction_from_cyclic([0, 50, 10, -2, 0], 100.0) == pytest.approx(0.02, rel=1e-15)
    assert suction_from_cyclic([0, 5, 0], 100.0) == 0.0
    with pytest.raises(InputError, match="at most 0.1"):
        suction_from_cyclic([0, 5, -20], 100.0)


def test_elastic_range_is_the_span_unloaded_on_the_initial_stiffness():
    # reversal at (s, N) = (2, 80); secants back to (1.9, 70), (1.8, 60): 100 = k; to
    # (1.7, 52): 28/0.3 = 93.3, 6.7 % off (> 5 %). The elastic span is 80 − 60 = 20, 0.2 of 100
    s = [0, 1, 2, 1.9, 1.8, 1.7, 1.6]
    n = [0, 50, 80, 70, 60, 52, 48]
    assert elastic_range_from_unloading(s, n, 100.0, 100.0) == pytest.approx(0.2, rel=1e-12)
    # the first unloading only: a reloading past the first peak afterwards changes nothing
    assert elastic_range_from_unloading(s + [1.7, 2.5], n + [60, 90], 100.0, 100.0) == \
        pytest.approx(0.2, rel=1e-12)


def test_zref_from_z50_is_the_hand_value():
    # z50 = q_ult/(2k) + z_ref((2(1 − 0.2))^(1/1.2) − 1) with q_ult = 10, k = 100, z50 = 0.5:
    # 1.6^(1/1.2) = 1.479 49, z_ref = 0.45/0.479 49 = 0.938 50
    assert zref_from_z50(10.0, 100.0, 0.5, QZ_SOILS["clay"]) == pytest.approx(0.93850, rel=1e-4)


def test_calibrate_qz_from_a_reference():
    # B = 6, 6 springs, K_v = 800, K_r = 3000 (ratio 3.75: R_k = 2 as above, k = 200 and 100);
    # N_ult = 120 over 6 equal strips: 20 each; N = 40: multiple 3; half capacity 60 between
    # (1, 40) and (2, 70): z50 = 1 + 20/30 = 1.6667
    ref = SimpleNamespace(B=6.0, K_v=800.0, K_r=3000.0, N_ult=120.0, N=40.0,
                          vertical={"settlement": [0, 1, 2, 3], "N": [0, 40, 70, 120]})
    cal = calibrate_qz(ref, 6, 1.0 / 3.0, 100.0)
    assert cal.stiffnesses == pytest.approx([200, 100, 100, 100, 100, 200], rel=1e-12)
    assert cal.capacities == pytest.approx(np.full(6, 20.0), rel=1e-15)
    assert cal.z50 == pytest.approx(5 / 3, rel=1e-14)
    assert cal.capacity_multiple == pytest.approx(3.0, rel=1e-15)
    assert cal.suction == 0.0
    table = cal.foundation_table()
    assert (table["law"], table["end_stiffness_ratio"]) == ("qz", pytest.approx(2.0, rel=1e-12))
    # a bed too soft for the pushover: k = 2, 1, 1, 1, 1, 2 and q_ult = 20 each; Σ min(k z, 20)
    # = 8 z until the end springs cap (z = 10) reaches half the capacity, 60, at z = 7.5 > z50
    soft = SimpleNamespace(**{**vars(ref), "K_v": 8.0, "K_r": 30.0})
    with pytest.raises(InputError, match="least settlement 7.5 at which"):
        calibrate_qz(soft, 6, 1.0 / 3.0, 100.0)


def test_least_z50_of_a_bed_is_the_hand_value():
    # k = 2, 1, 1, 1, 1, 2 and q_ult = 10 each (capacity 60, half 30): Σ min(k z, 10) = 8 z
    # until the end springs cap at z = 5 (40 ≥ 30): z = 30/8 = 3.75
    assert z50_lower_bound([2, 1, 1, 1, 1, 2], np.full(6, 10.0), 60.0) == pytest.approx(3.75,
                                                                                      rel=1e-14)
    # half 50: past z = 5 the ends carry 20 and the middle 4 z: 20 + 4 z = 50, z = 7.5
    assert z50_lower_bound([2, 1, 1, 1, 1, 2], np.full(6, 10.0), 100.0) == pytest.approx(
        7.5, rel=1e-14)


def test_common_zref_of_a_proportional_bed_is_the_closed_form():
    # k_i proportional to q_ult,i: every spring alike, so the bed's z_ref is a spring's closed
    # form (0.938 50 for q_ult = 10, k = 100, z50 = 0.5, checked by hand above)
    zref = common_zref(np.full(4, 100.0), np.full(4, 10.0), 0.5, QZ_SOILS["clay"])
    assert zref == pytest.approx(0.93850, rel=1e-4)
    assert zref == pytest.approx(float(zref_from_z50(10.0, 100.0, 0.5, QZ_SOILS["clay"])),
                                 rel=1e-10)


def test_bed_vertical_path_is_the_spring_backbone_times_the_count():
    # n identical springs settling alike carry n times one spring's force: the backbone's
    # closed form at z50 gives q_ult/2 each, so the bed carries half its capacity there
    from upliftlab.comparisons.beds.qz.calibration import bed_vertical_path
    forces = bed_vertical_path(np.full(4, 100.0), np.full(4, 10.0), 0.5, [0.25, 0.5])
    assert forces[1] == pytest.approx(20.0, rel=1e-10)
    assert forces[0] < 20.0


@pytest.mark.slow
def test_calibration_from_a_continuum_cyclic_pushover():
    """The strip on clay (8 elements across B): a cyclic vertical pushover, down to 0.8 N_ult,
    up past lift-off and down again. References: the unilateral contact cannot pull (suction
    0 to round-off); the unloading starts on the soil's condensed elastic stiffness, computed
    independently by footing_stiffness (1e-6); the calibrated uniform bed carries N_ult/2 at
    the continuum's z50 (1e-9, by construction through another solver)."""
    from upliftlab import continuum
    from upliftlab.comparisons.beds.qz.calibration import bed_vertical_path
    from upliftlab.scenes import load_scene
    model = continuum.build_model(load_scene("strip_footing_clay",
                                             overrides=["continuum.elements_across=8"]))
    K_v = continuum.footing_stiffness(model).vertical
    B = 2.0
    mono = np.linspace(0.0, 0.05 * B, 41)[1:]
    push = continuum.vertical_pushover(model, mono)
    capacity = float(push.N.max())
    z50 = z50_from_pushover(mono, push.N, capacity)
    top = float(mono[np.argmax(push.N >= 0.8 * capacity)])
    path = np.concatenate([np.linspace(0, top, 21)[1:], np.linspace(top, -0.002, 41)[1:]])
    cyclic = continuum.vertical_pushover(model, path)
    assert suction_from_cyclic(cyclic.N, capacity) <= 1e-12
    turn = int(np.flatnonzero(np.diff(path) < 0)[0])
    secant = (cyclic.N[turn] - cyclic.N[turn + 1]) / (path[turn] - path[turn + 1])
    assert secant == pytest.approx(K_v, rel=1e-6)
    assert 0.0 < elastic_range_from_unloading(path, cyclic.N, K_v, capacity) <= 1.0
    n = 48
    k, q = np.full(n, K_v / n), spring_capacities(capacity, np.full(n, B / n))
    assert bed_vertical_path(k, q, z50, [z50])[0] == pytest.approx(0.5 * capacity, rel=1e-9)
