"""Compatibility assembly (Ewing eqs. 3–9) and static analyses against closed forms.

References: anchor §2 (eq. 6 entries, the wall's quantities, the two-spring equivalence),
anchor §3 (rigid footing on a tensionless Winkler bed, elasto-plastic capacity).
"""

import math

import numpy as np
import pytest
import scipy.linalg

from upliftlab.reduced import (build_model, compatibility_matrix, edge_springs,
                               end_stiffened_bed, equivalent_springs, rocking_pushover,
                               stiffness_matrix, uplift_onset_force, winkler_bed)
from upliftlab.reduced.compatibility import DofMap
from upliftlab.reduced.static import initial_state
from upliftlab.scenes import load_scene


def test_two_spring_stiffness_matches_eq6():
    """Anchor §2: h = 288, b = 72, k1 = k2 = 3000, k3 = 500 → K_θθ = 7.2576e7, K_Xθ = −1.44e5,
    and the entries of eq. 6 for unequal springs."""
    dofs = DofMap.build(1, rigid=False, fixed=False)          # (x, θ, V)
    h, b = 288.0, 72.0
    for k1, k2, k3 in [(3000.0, 3000.0, 500.0), (1000.0, 4000.0, 250.0)]:
        layout = edge_springs(b, k1 + k2)
        A = compatibility_matrix(dofs, [h], layout)
        K = stiffness_matrix(A, [k3, k1, k2])
        assert K[0, 0] == pytest.approx(k3)
        assert K[0, 1] == pytest.approx(-h * k3)
        assert K[1, 1] == pytest.approx(h * h * k3 + b * b * (k1 + k2))
        assert K[2, 2] == pytest.approx(k1 + k2)
        # eq. 6b/6c coupling b(k1 − k2) with springs of K_v/2: zero here
    A = compatibility_matrix(dofs, [h], edge_springs(b, 6000.0))
    K = stiffness_matrix(A, [500.0, 3000.0, 3000.0])
    assert K[1, 1] == pytest.approx(7.2576e7, rel=1e-12)
    assert K[0, 1] == pytest.approx(-1.44e5, rel=1e-12)


def test_unequal_springs_give_the_eq6_coupling():
    """Eq. 6b–c: K_θV = b(k1 − k2) for springs k1 at −b and k2 at +b (our V is up and θ puts
    the right edge down; the sign follows from e_i = x_i θ − V)."""
    from upliftlab.reduced import custom_springs
    dofs = DofMap.build(1, rigid=False, fixed=False)
    b, k1, k2 = 50.0, 1000.0, 4000.0
    A = compatibility_matrix(dofs, [100.0], custom_springs(b, [-b, b], [k1, k2]))
    K = stiffness_matrix(A, [1.0, k1, k2])
    assert K[1, 2] == pytest.approx(-(k2 - k1) * b) == pytest.approx(b * (k1 - k2))


def test_layouts_match_uniform_bed_stiffness():
    """Anchor §2: springs of K_v/2 at ±b/√3 match the uniform bed's K_v and K_θ = K_v b²/3; a
    Winkler bed of N strips gives K_θ = K_v b²/3 (1 − 1/N²) (midpoint rule, exact)."""
    b, kv = 2.0, 1000.0
    eq = equivalent_springs(b, kv)
    assert eq.vertical_stiffness == pytest.approx(kv)
    assert eq.rocking_stiffness == pytest.approx(kv * b * b / 3, rel=1e-14)
    for n in (2, 12, 200):
        bed = winkler_bed(b, kv, n)
        assert bed.rocking_stiffness == pytest.approx(kv * b * b / 3 * (1 - 1 / n**2), rel=1e-12)
        assert bed.widths.sum() == pytest.approx(2 * b)
    end = end_stiffened_bed(b, kv, 20, stiffness_ratio=4.0, end_length=0.2)
    assert end.vertical_stiffness == pytest.approx(kv, rel=1e-12)
    assert end.stiffnesses[0] == pytest.approx(4 * end.stiffnesses[10])


def test_static_reactions_equal_the_weight():
    """At rest the spring compressions F0 carry the weight: Σ F0 = W and Σ x F0 = 0, also for
    an asymmetric user layout (whose rest state then has a static rotation)."""
    for name, sets in [("wall_free", []),
                       ("short_period_free", ["foundation.layout='custom'",
                                              "foundation.springs=",
                                              "foundation.vertical_period=",
                                              "foundation.positions=[-120.0, 10.0, 120.0]",
                                              "foundation.stiffnesses=[2000.0, 1000.0, 3000.0]"])]:
        model = build_model(load_scene(name, overrides=sets))
        f = model.params[model.foundation_slice]
        assert f["f0"].sum() == pytest.approx(model.weight, rel=1e-12)
        assert np.sum(f["x"] * f["f0"]) == pytest.approx(0.0, abs=1e-9 * model.weight * 120)


def test_bonded_frequencies_are_the_eigenvalues_of_K_M():
    """Free vibration of the bonded, undamped system at the dominant frequency: the response
    of a modal initial state oscillates at ω = √λ of (K, M) — checked against the eigen-solver
    via the period of the integrated response."""
    from upliftlab.reduced import run
    scene = load_scene("short_period_free", overrides=[
        "foundation.support='bonded'", "foundation.law='elastic'", "foundation.damping_ratio=0.0",
        "foundation.restitution=1.0", "structure.damping_ratio=0.0", "motion.duration=3.0"])
    model = build_model(scene)
    K, _ = model.bonded_matrices()
    lam, vec = scipy.linalg.eigh(K, np.diag(model.mass))
    periods = 2 * np.pi / np.sqrt(lam)
    np.testing.assert_allclose(np.sort(model.bonded_periods()), np.sort(periods), rtol=1e-12)
    # integrate the first mode: velocity initial condition along the mode shape
    r = run(scene, output_dt=1e-3)
    x = r.q[:, 0]
    crossings = np.flatnonzero(np.diff(np.sign(x)) > 0)
    t = r.time[crossings] - x[crossings] * (r.time[crossings + 1] - r.time[crossings]) / (
        x[crossings + 1] - x[crossings])
    # Ẋ(0) excites mostly mode 1 (the lateral mode); its period is the zero-crossing spacing
    measured = np.median(np.diff(t))
    assert measured == pytest.approx(periods[0], rel=2e-3)


@pytest.fixture(scope="module")
def winkler200():
    scene = load_scene("wall_free", overrides=["foundation.springs=200"])
    return build_model(scene)


def test_pushover_matches_tensionless_winkler_closed_form(winkler200):
    """Anchor §3 with 200 springs: M/M_up = 3 − 2√(θ_up/θ) and contact c/B = √(θ_up/θ) beyond
    uplift, M = (kB³/12)θ before it, to 0.5 %."""
    model = winkler200
    N, B = model.weight, 2 * model.layout.half_width
    kv = model.layout.vertical_stiffness
    theta_up = 2 * N / (kv * B)            # 2N/(kB²) with k = K_v/B per unit length
    ratios = np.array([0.5, 1.5, 3.0, 10.0])
    push = rocking_pushover(model, ratios * theta_up)
    M_up = N * B / 6
    closed = np.where(ratios <= 1, ratios, 3 - 2 * np.sqrt(1 / ratios))
    np.testing.assert_allclose(push.moment / M_up, closed, rtol=5e-3)
    np.testing.assert_allclose(push.moment / (N * B), [0.083333, 0.227834, 0.307550, 0.394591],
                               rtol=5e-3)                                     # anchor table
    contact = np.where(ratios <= 1, 1.0, np.sqrt(1 / ratios))
    np.testing.assert_allclose(push.contact / B, contact, rtol=5e-3)


def test_uplift_onset_force_on_the_wall():
    """Anchor §2, wall scene: quasi-static uplift at W b/h for edge springs, W b/(√3 h) at ±b/√3,
    and W b/(3h) for a uniform bed — with N strips exactly W b/(3h)·(1 + 1/N) (the outer strip
    centre sits at b(1 − 1/N)), so 200 springs land within 0.5 %."""
    base = load_scene("wall_free")
    W, b, h = 200.0, 72.0, 288.0
    two = ("foundation.springs=2",)
    assert uplift_onset_force(build_model(base.with_overrides(
        "foundation.layout='edges'", *two))) == pytest.approx(W * b / h, rel=1e-12)     # 50 kip
    assert uplift_onset_force(build_model(base.with_overrides(
        "foundation.layout='equivalent'", *two))) == pytest.approx(W * b / (math.sqrt(3) * h),
                                                                   rel=1e-12)         # 28.868
    for n in (12, 200):
        p = uplift_onset_force(build_model(base.with_overrides(f"foundation.springs={n}")))
        assert p == pytest.approx(W * b / (3 * h) * (1 + 1 / n), rel=1e-12)
    p200 = uplift_onset_force(build_model(base.with_overrides("foundation.springs=200")))
    assert abs(p200 / (W * b / (3 * h)) - 1) <= 5e-3 + 1e-12                          # 16.667


def test_elastoplastic_bed_approaches_meyerhof_capacity():
    """Anchor §3: yield comes after uplift when FS_v > 2, at θ = (FS²/4)θ_up, and the moment
    tends to M_ult = (N B/2)(1 − 1/FS_v) as θ grows (400 springs, θ up to 2000 θ_up)."""
    scene = load_scene("short_period_free", overrides=["foundation.springs=400"])
    model = build_model(scene)
    N, B, fs = model.weight, 2 * model.layout.half_width, 3.0
    theta_up = 2 * N / (model.layout.vertical_stiffness * B)
    thetas = theta_up * np.geomspace(0.1, 2000.0, 400)
    push = rocking_pushover(model, thetas)
    m_ult = N * B / 2 * (1 - 1 / fs)
    assert push.moment[-1] / m_ult == pytest.approx(1.0, abs=2e-3)
    yielded = np.flatnonzero(push.plastic.max(axis=1) > 0)[0]
    assert thetas[yielded] / theta_up == pytest.approx(fs**2 / 4, rel=0.02)     # 2.25 θ_up
    assert np.all(np.diff(push.moment) > -1e-9 * m_ult)                          # monotonic


def test_initial_rotation_state_is_in_vertical_equilibrium():
    """A block released at θ0 starts in static vertical equilibrium: Σ spring forces = W."""
    from upliftlab.reduced.static import _forces
    from upliftlab.reduced.springs import HISTORY_DTYPE
    model = build_model(load_scene("wall_free", overrides=["foundation.layout='edges'",
                                                           "foundation.springs=2"]))
    q = initial_state(model, rotation=0.002)
    _, _, total, _, _ = _forces(model, q, np.zeros(model.spring_count, dtype=HISTORY_DTYPE))
    assert total[model.foundation_slice].sum() == pytest.approx(model.weight, rel=1e-10)
