"""The hysteretic q–z spring at one point (reduced/laws/qz/compiled.py), before any assembly:
monotonic loading against the closed-form backbone, unloading, uplift, recontact, cycles, the
dissipation against the loop area and the tangent against a finite difference.

References, each independent of the law's own solver: the closed-form virgin backbone
z(Q) = Q/k + z_ref(((q_ult − q_r)/(q_ult − Q))^(1/n) − 1), written out in this file; hand
values worked out in the comments; the trapezoid rule over a fine path for loop areas; central
differences of the trial force for the tangent.
"""

import math

import numpy as np
import pytest

from upliftlab.reduced import springs as sp
from upliftlab.reduced.kernels import CONTACT, QZ, qz_commit, qz_force, qz_start, qz_trial

K, QULT, Z50 = 100.0, 10.0, 0.5            # force/length, force, length
N, ELAST, EMAX = 1.2, 0.2, 0.7             # the clay shape
# z50 = q_ult/(2k) + z_ref((2(1 − 0.2))^(1/1.2) − 1): 1.6^(1/1.2) = 1.479 49, so
# z_ref = (0.5 − 0.05)/0.479 49 = 0.938 50 (length)
ZREF_HAND = 0.93850


def _spring(suction=0.0, c=0.0):
    table = sp.spring_table(1)
    table["kind"], table["nnz"], table["k"], table["c"] = QZ, 2, K, c
    table["qult"], table["npow"], table["elast"], table["emax"] = QULT, N, ELAST, EMAX
    table["zref"] = (Z50 - 0.5 * QULT / K) / ((2 * (1 - ELAST)) ** (1 / N) - 1)
    table["qd"], table["zd"] = suction * QULT, 0.5 * Z50
    P = sp.derive_columns(table)
    H = np.zeros(1, dtype=sp.HISTORY_DTYPE)
    qz_start(P[0], H[0], 0.0)
    return P[0], H[0]


def _backbone_z(q):
    """Closed-form virgin backbone (the reference, not the law's code)."""
    qr = ELAST * QULT
    plastic = 0.0 if q <= qr else ZREF_HAND * (((QULT - qr) / (QULT - q)) ** (1 / N) - 1)
    return q / K + plastic


def _walk(p, h, path):
    """Commit every point of a path; returns the forces and the dissipated work."""
    forces, work = [], 0.0
    for z in path:
        work += qz_commit(p, h, z)
        forces.append(h["qc"])
    return np.array(forces), work


def test_zref_is_the_hand_value():
    p, _ = _spring()
    assert p["zref"] == pytest.approx(ZREF_HAND, rel=1e-4)  # hand value to 5 digits


def test_monotonic_loading_follows_the_closed_form_backbone():
    p, h = _spring()
    for q in (1.0, 2.0, 3.0, 5.0, 7.0, 9.0, 9.9):
        z = _backbone_z(q)
        # the hand z_ref carries 5 digits: the force it implies is good to ~1e-4 relative
        assert qz_trial(p, h, z)[0] == pytest.approx(q, rel=2e-4)
    # q at z50 is half the capacity (the definition of z50), to the solver's round-off
    assert qz_trial(p, h, Z50)[0] == pytest.approx(0.5 * QULT, rel=1e-12)
    # asymptote: at z = 100 z50 the force is below q_ult and within the closed form's
    # 1 − Q/q_ult = 0.8 (z_ref/(z_ref + z_p))^1.2, z_p ≈ 50 − 0.1: 0.8·(0.9385/50.84)^1.2 = 0.0067
    q_far = qz_trial(p, h, 100 * Z50)[0]
    assert q_far < QULT
    # by hand: q ≈ 9.934 so z_p = 50 − 0.0993 = 49.9007; 0.93850/50.8392 = 0.0184602;
    # 0.0184602^1.2 = exp(1.2 ln 0.0184602) = exp(−4.79063) = 0.0083021; × 0.8 = 0.0066417
    assert 1 - q_far / QULT == pytest.approx(0.0066417, rel=1e-3)


def test_loading_in_steps_equals_loading_at_once():
    """The trial is a function of z: committing 1000 small steps or one gives the same state."""
    p1, h1 = _spring()
    p2, h2 = _spring()
    _walk(p1, h1, np.linspace(0, 1.2, 1001)[1:])
    qz_commit(p2, h2, 1.2)
    assert h1["qc"] == pytest.approx(h2["qc"], rel=1e-12)
    assert h1["zp"] == pytest.approx(h2["zp"], rel=1e-12)


def test_unloading_stiffness_is_the_initial_stiffness():
    p, h = _spring()
    assert 1.0 / qz_trial(p, h, 1e-6)[1] == pytest.approx(K, rel=1e-12)  # initial: k
    _walk(p, h, np.linspace(0, 1.0, 101)[1:])
    assert 1.0 / qz_trial(p, h, 1.0)[1] < 0.2 * K  # soft on the backbone
    dz = 1e-6
    # unloading from the backbone: rigid near field, closed gap, so dQ/dz = k
    assert (h["qc"] - qz_trial(p, h, 1.0 - dz)[0]) / dz == pytest.approx(K, rel=1e-9)


def test_uplift_never_pulls_and_recontacts_at_the_settled_surface():
    p, h = _spring()
    forces, _ = _walk(p, h, np.linspace(0, 1.0, 101)[1:])
    q_peak, settled = h["qc"], h["zp"]
    # unloading elastically, the near field rigid while Q > q_peak − w (q_peak = 6.51 < 0.7
    # q_ult + 0: w grows to q_peak, so no reverse yield): Q = 0 at z = z_p, then the gap opens
    forces, _ = _walk(p, h, np.linspace(1.0, -0.5, 151)[1:])
    assert forces.min() == 0.0  # no drag: never tension, not even round-off
    assert h["zg"] == pytest.approx(-0.5 - settled, rel=1e-12)
    assert h["zp"] == settled
    # recontact exactly at the settled surface
    assert qz_trial(p, h, settled - 1e-9)[0] == 0.0
    assert qz_trial(p, h, settled + 1e-6)[0] == pytest.approx(K * 1e-6, rel=1e-6)
    assert q_peak > 0.5 * QULT


def test_uplift_with_drag_stays_above_the_suction_capacity():
    p, h = _spring(suction=0.05)
    qd = 0.05 * QULT
    _walk(p, h, np.linspace(0, 1.0, 101)[1:])
    forces, _ = _walk(p, h, np.linspace(1.0, -3.0, 401)[1:])
    assert forces.min() > -qd
    # far open, the drag hyperbola from its reversal at (q_a, 0): opening by v = −z_g,
    # Q = −q_d + (q_d + q_a) z_d/(z_d + v); q_a is the force at which the gap opened
    v = -h["zg"]
    qa = h["qa"]
    assert h["qc"] == pytest.approx(-qd + (qd + qa) * 0.25 / (0.25 + v), rel=1e-10)


def test_cyclic_displacement_settles_more_every_cycle():
    """One-sided cycles 0 → 2 → 0: the peak force 7.9 > 0.7 q_ult, so each unloading yields
    back (Masing range capped at 0.7 q_ult) and each reloading yields further: the settled
    surface (z_p after unloading) grows every cycle, by less each time."""
    p, h = _spring()
    settled = []
    for _ in range(6):
        _walk(p, h, np.linspace(0, 2.0, 101)[1:])
        _walk(p, h, np.linspace(2.0, 0.0, 101)[1:])
        settled.append(h["zp"])
    steps = np.diff(settled)
    assert np.all(steps > 0)
    assert np.all(np.diff(steps) < 0)


def _drive_to_force(p, h, q):
    """Commit the z at which the trial force is q (bisection on z: the test's own driver)."""
    lo, hi = h["zc"] - 10.0, h["zc"] + 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if qz_trial(p, h, mid)[0] < q else (lo, mid)
    qz_commit(p, h, hi)


def test_force_cycles_ratchet_by_the_hand_value():
    """One-sided force cycles 0 → 0.8 q_ult → 0. From the second cycle on the range is its
    cap, w = 0.7 q_ult: unloading from 8 yields back below q_l = 1 down to 0, reloading from
    0 yields past q_r = 7 up to 8. Per cycle (z_ref = 0.93850, n = 1.2):
    forward z_ref((3/2)^(1/1.2) − 1) = 0.93850 · 0.40199 = 0.37727,
    back z_ref((11/10)^(1/1.2) − 1) = 0.93850 · 0.082665 = 0.077581,
    net settlement 0.29969 a cycle."""
    p, h = _spring()
    peaks = []
    for _ in range(5):
        for q in np.linspace(0, 8.0, 40)[1:]:
            _drive_to_force(p, h, q)
        peaks.append(h["zp"])
        for q in np.linspace(8.0, 0.0, 40)[1:]:
            _drive_to_force(p, h, q)
    assert np.diff(peaks)[1:] == pytest.approx(0.29969, rel=1e-4)


@pytest.mark.parametrize("suction", [0.0, 0.05])
def test_dissipation_per_cycle_is_the_loop_area(suction):
    """Over a cycle of z (2 → −0.5 → 2) the dissipated work (the law's closed form) equals
    ∮ Q dz by the trapezoid rule on a fine path (its error ~ (Δz)²·Q'' ≈ 1e-7 of the area
    here) less the change of the stored Q²/(2k) (the force at the end of a cycle is lower:
    the spring has settled)."""
    p, h = _spring(suction)
    _walk(p, h, np.linspace(0, 2.0, 101)[1:])  # first loading, not a closed cycle
    cycle = np.concatenate([np.linspace(2.0, -0.5, 50001), np.linspace(-0.5, 2.0, 50001)[1:]])
    for _ in range(2):
        q0 = h["qc"]
        forces, work = _walk(p, h, cycle[1:])
        area = np.trapezoid(np.concatenate([[q0], forces]), cycle)
        stored = 0.5 * (h["qc"] ** 2 - q0 ** 2) / K
        assert work == pytest.approx(area - stored, rel=1e-6)
        assert work > 0


def test_tangent_matches_a_finite_difference():
    """dQ/dz of the trial on its branch against a one-sided difference of the trial force in
    the same direction, from committed states along a cyclic history."""
    rng = np.random.default_rng(13)
    for suction in (0.0, 0.05):
        p, h = _spring(suction)
        checked = 0
        for z in (1.0, 0.6, 1.5, -0.3, 2.2, 0.9):
            qz_commit(p, h, z)
            for _ in range(20):
                zt = z + rng.uniform(-0.5, 0.5)
                q, dz = qz_trial(p, h, zt)[:2]
                if math.isinf(dz) or abs(zt - z) < 1e-3:
                    continue
                step = 1e-7 * math.copysign(1.0, z - zt)  # back towards the committed z
                q2 = qz_trial(p, h, zt + step)[0]
                near_kink = qz_trial(p, h, zt - step)[1]
                if abs(near_kink - dz) > 1e-3 * dz:
                    continue  # on a range end or a closure: one-sided slopes differ
                assert (q2 - q) / step == pytest.approx(1.0 / dz, rel=1e-5)
                checked += 1
        assert checked > 40


def test_dashpot_acts_in_contact_and_never_pulls():
    p, h = _spring(c=50.0)
    qz_start(p, h, 4.0)
    p["zs"] = h["zc"]
    p["f0"] = 4.0
    p["d0"] = 4.0 / K
    f, power, fd, kt, ct, mode = qz_force(p, h, 0.0, 0.01)
    assert (f, fd, ct, mode) == (pytest.approx(0.5), pytest.approx(0.5), 50.0, CONTACT)
    assert power == pytest.approx(0.005)
    f, _, fd, kt, ct, _ = qz_force(p, h, 0.0, -1.0)  # −50 against Q = 4: clipped at Q
    assert f + 4.0 == 0.0 and fd == -4.0 and kt == 0.0 and ct == 0.0


def test_the_dispatching_forms_agree_with_the_qz_functions():
    """Through reduced/kernels/laws.py: commit_step books qz_commit's work and the contact
    flag, spring_state reads the trial force and Q²/(2k), trial_mode the force's mode; random
    trial states around a cyclic history (reference: qz_force/qz_commit on a copy)."""
    from upliftlab.reduced.kernels import commit_step, spring_state, trial_mode
    rng = np.random.default_rng(7)
    p, h = _spring(suction=0.02, c=5.0)
    qz_start(p, h, 3.0)
    p["zs"], p["f0"], p["d0"] = h["zc"], 3.0, 3.0 / K
    for step in range(200):
        e = rng.uniform(-0.6, 1.2)
        ed = rng.uniform(-1, 1)
        copy = h.copy()
        force, _, fd, _, _, mode = qz_force(p, h, e, ed)
        ep, q, energy = spring_state(0, p, 0, h, e)
        assert q == pytest.approx(force + 3.0 - fd, rel=1e-12, abs=1e-12)
        assert energy == pytest.approx(0.5 * q * q / K, rel=1e-12, abs=1e-15)
        assert trial_mode(p, h, e, ed) == mode
        work, contact = commit_step(p, e, ed, h, 1)
        assert work == qz_commit(p, copy, p["zs"] + e)
        assert contact == (0 if h["zg"] < 0 else 1)
        assert h["ep"] == pytest.approx(h["zp"] - (p["zs"] - p["d0"]), abs=1e-15)


def _steep_spring():
    """A spring of the shape the Winkler map's q–z bed fits to the clay (n = 7.83, elastic
    range 0.68 q_ult, Masing ranges up to 1.36 q_ult): its hyperbola all but reaches q_ult within
    a few z_ref, and a reload after a reversal near capacity has a range reaching past q_ult."""
    table = sp.spring_table(1)
    table["kind"], table["nnz"], table["k"] = QZ, 2, K
    table["qult"], table["npow"], table["elast"], table["emax"] = QULT, 7.83, 0.68, 1.36
    table["zref"], table["zd"] = 0.06, 0.25
    P = sp.derive_columns(table)
    H = np.zeros(1, dtype=sp.HISTORY_DTYPE)
    qz_start(P[0], H[0], 0.0)
    return P[0], H[0]


def test_the_work_done_on_the_spring_is_stored_or_dissipated_up_to_its_capacity():
    # Load to 0.3 (Q ≈ 0.998 q_ult), unload to 0.2 (a reversal: the next range is as wide as
    # the loop, ~1.36 q_ult from the reversal's force, reaching past q_ult), reload to 1.0 far
    # past the capacity. Reference: the work ∫ Q dz by the trapezoid rule over the fine path
    # equals the dissipation the law books plus the far field's stored Q²/(2k) (its change);
    # the force never exceeds q_ult; beyond the capacity the spring flows perfectly plastically,
    # dissipating q_ult per unit of z (hand: 10 × 0.5 over the last half of the path).
    p, h = _steep_spring()
    path = np.concatenate([np.linspace(0.0, 0.3, 3001), np.linspace(0.3, 0.2, 1001)[1:],
                           np.linspace(0.2, 1.0, 8001)[1:]])
    q_prev, work, booked = qz_trial(p, h, path[0])[0], 0.0, 0.0
    flow = None
    for i, z in enumerate(path[1:], start=1):
        q = qz_trial(p, h, z)[0]
        assert q <= QULT
        work += 0.5 * (q_prev + q) * (z - path[i - 1])
        step = qz_commit(p, h, z)
        booked += step
        if z > 0.5 and flow is None:
            flow = booked
        q_prev = q
    stored = 0.5 * q_prev**2 / K
    assert booked + stored == pytest.approx(work, rel=1e-5)
    assert booked - flow == pytest.approx(QULT * (1.0 - path[path > 0.5][0]), rel=1e-6)
    assert q_prev == pytest.approx(QULT, rel=1e-9)
