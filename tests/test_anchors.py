"""The closed forms of upliftlab.anchors against the numbers printed in upliftlab/docs/anchors.md
(each checked there by an independent computation: a bed of 4000 springs, an ODE solved to
1e-11, the paper's scenes), and against each other where two forms of one result exist.

References: anchors.md §1 (e = 0.942308 at h/b = 5, 0.850000 at h/b = 3), §2 (onset forces of
the wall, W = 200 kip, b = 72 in, h = 288 in: 50 kip, 28.868 kip, 16.667 kip), §3 (M/(N B) =
0.083333, 0.227834, 0.307550, 0.394591 and c/B = 1, 0.816497, 0.577350, 0.316228 at θ/θ_up =
0.5, 1.5, 3, 10; M_ult = (N B/2)(1 − 1/FS_v)), §4 (q_u = 2.968500 σ_y for c_u = σ_y/√3), §5
(Δy = 1.5540, 0.15540, 0.015540 in for c* = 1, 10, 100). Tolerances: the printed digits.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab import anchors as an


def test_rocking_restitution_of_a_rectangle():
    # §1: 1 − 1.5 sin²α, printed to six digits.
    assert an.rocking_restitution_rectangle(math.atan(1 / 5)) == pytest.approx(0.942308, abs=5e-7)
    assert an.rocking_restitution_rectangle(math.atan(1 / 3)) == pytest.approx(0.850000, abs=5e-7)


def test_onset_forces_of_the_wall():
    # §2: W b/h = 50, W b/(√3 h) = 28.868, W b/(3h) = 16.667 kip; N strips: × (1 + 1/N).
    W, b, h = 200.0, 72.0, 288.0
    assert an.edge_springs_onset_force(W, b, h) == pytest.approx(50.0, rel=1e-15)
    assert an.equivalent_springs_onset_force(W, b, h) == pytest.approx(28.868, abs=5e-4)
    assert an.winkler_onset_force(W, b, h) == pytest.approx(16.667, abs=5e-4)
    assert an.winkler_onset_force(W, b, h, 200) == pytest.approx(16.667 * 1.005, abs=5e-4)


def test_winkler_rocking_table():
    # §3's table: M/(N B) and c/B at θ/θ_up = 0.5, 1.5, 3, 10, printed to six digits; the
    # dimensionless forms give the same numbers (M/M_up = 6 M/(N B)).
    N, B, k = 3.0, 2.0, 7.0
    theta_up = an.winkler_uplift_rotation(N, B, k)
    ratios = np.array([0.5, 1.5, 3.0, 10.0])
    closed = an.winkler_rocking(ratios * theta_up, N, B, k)
    assert closed["theta_up"] == pytest.approx(theta_up, rel=1e-15)
    np.testing.assert_allclose(closed["M"] / (N * B), [0.083333, 0.227834, 0.307550, 0.394591],
                               atol=5e-7)
    np.testing.assert_allclose(closed["c"] / B, [1.0, 0.816497, 0.577350, 0.316228], atol=5e-7)
    np.testing.assert_allclose(an.winkler_moment_ratio(ratios) / 6.0, closed["M"] / (N * B),
                               rtol=1e-13)
    np.testing.assert_allclose(an.winkler_contact_ratio(ratios), closed["c"] / B, rtol=1e-13)
    assert an.WINKLER_ONSET_ECCENTRICITY == pytest.approx(0.083333 * 2, abs=1e-6)


def test_ultimate_moment_and_first_yield():
    # §3: M_ult/(N B) = (1 − 1/FS_v)/2 (1/3 at FS_v = 3), first yield at FS_v²/4 θ_up.
    assert an.ultimate_moment_ratio(3.0) == pytest.approx(1.0 / 3.0, rel=1e-15)
    assert an.ultimate_moment_ratio(1e12) == pytest.approx(0.5, rel=1e-11)
    assert an.first_yield_rotation_ratio(3.0) == pytest.approx(2.25, rel=1e-15)


def test_half_plane_rocking_is_continuous_at_onset():
    # §4: below θ_on M = K_r θ; above, N B (1/2 − θ_on/(4θ)); at θ_on both give N B/4
    # (e = B/4), and c/B = θ_on/θ.
    N, B, G, nu = 171.39, 2.0, 50e3 / 2.6, 0.3
    theta_on = an.half_plane_onset_rotation(N, B, G, nu)
    K_r = an.half_plane_rocking_stiffness(G, B, nu)
    assert K_r * theta_on == pytest.approx(an.HALF_PLANE_ONSET_ECCENTRICITY * N * B, rel=1e-13)
    both = an.half_plane_rocking(theta_on * np.array([1 - 1e-12, 1 + 1e-12, 4.0]), N, B, G, nu)
    assert both["theta_on"] == pytest.approx(theta_on, rel=1e-15)
    np.testing.assert_allclose(both["M"][:2] / (N * B), 0.25, rtol=1e-9)
    assert both["M"][2] / (N * B) == pytest.approx(0.5 - 0.25 / 4.0, rel=1e-13)
    assert both["c"][2] / B == pytest.approx(0.25, rel=1e-13)


def test_prandtl_and_the_envelope():
    # §4: q_u = (2 + π) c_u = 2.968500 σ_y for von Mises soil (c_u = σ_y/√3); the V–M
    # envelope M/(B V_ult) = v(1 − v)/2 peaks at 1/8 for v = 1/2.
    assert an.prandtl_capacity(1.0 / math.sqrt(3.0), 1.0) == pytest.approx(2.968500, abs=5e-7)
    assert 0.5 * an.vm_envelope_moment_ratio(0.5) == pytest.approx(0.125, rel=1e-15)
    assert an.flamant_compliance_slope(1.0, 0.3) == pytest.approx(0.7 / math.pi, rel=1e-15)


def test_drop_mass_strokes():
    # §5: Δy = (v₀ m/c*)(1 − ε) = 1.5540, 0.15540, 0.015540 in (m = 0.518, v₀ = 10, ε = 0.7).
    for cstar, dy in ((1.0, 1.5540), (10.0, 0.15540), (100.0, 0.015540)):
        assert an.drop_mass_stroke(cstar, 0.518, 10.0, 0.7) == pytest.approx(dy, rel=1e-12)


def test_every_tolerance_names_its_anchor():
    # Each tolerance is a positive fraction below 10 % and names a section of anchors.md.
    for name, tol in an.TOLERANCES.items():
        assert 0.0 < tol.value < 0.1, name
        assert tol.anchor in ("§1", "§2", "§3", "§4", "§5"), name
        assert tol.kind in ("relative", "absolute", "bound"), name
