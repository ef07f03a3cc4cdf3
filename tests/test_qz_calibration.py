"""The q–z bed's calibration functions against hand values
(comparisons/winkler_vs_continuum/qz_calibration.py, reduced/qz.py).

Every reference below is worked out by hand in the comment above its assertion."""

from types import SimpleNamespace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.winkler_vs_continuum.qz_calibration import (
    calibrate_qz, elastic_range_from_unloading, qz_stiffnesses, spring_capacities,
    suction_from_cyclic, z50_from_pushover)
from upliftlab.reduced.qz import QZ_SOILS, zref_from_z50


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
    # a bed too soft for the pushover: q_ult/(2k) = 20/(2·1) = 10 > z50
    soft = SimpleNamespace(**{**vars(ref), "K_v": 8.0, "K_r": 30.0})
    with pytest.raises(InputError, match="z50"):
        calibrate_qz(soft, 6, 1.0 / 3.0, 100.0)
