"""Each spring law at a single point, along displacement paths, before any assembly.

References: the laws as stated in design.md and Ewing's Figs. 3b and 6 (closed forms for the
force at every point of each path), and anchor §5 for the impact damper.
"""

import numpy as np
import pytest

from upliftlab.reduced import springs as sp

K, F0, FS = 100.0, 10.0, 3.0          # stiffness, static compression, yield multiple
D0 = F0 / K                            # static compression δ0 = 0.1


def foundation(law="elastic", c=0.0, cimp=0.0, dzf=0.0, kind=sp.UPLIFT):
    table = sp.spring_table(1)
    table["kind"], table["k"], table["f0"], table["c"] = kind, K, F0, c
    table["fy"] = FS * F0 if law == "elastoplastic" else np.inf
    table["cimp"], table["dzf"], table["nnz"] = cimp, dzf, 2
    return sp.derive_columns(table)


def story(k=50.0, fy=5.0, alpha=0.0, c=0.0):
    table = sp.spring_table(1)
    table["kind"], table["k"], table["kh"], table["fy"], table["c"] = (
        sp.STORY, (1 - alpha) * k, alpha * k, (1 - alpha) * fy, c)
    table["nnz"] = 2
    return sp.derive_columns(table)


def walk(P, path, rate=0.0):
    """Drive one spring through deformations ``path`` with the return map of the fixed-step
    integrators; returns total forces (F0 + increment for a foundation spring) and contact."""
    H = np.zeros(1, dtype=sp.HISTORY_DTYPE)
    forces, contact, was = [], [], 1
    for e in path:
        mode = sp.natural_mode(P[0], e, rate, H[0]["ep"], H[0]["imp"])
        f = sp.force_in_mode(mode, P[0], e, rate, H[0]["ep"], H[0]["imp"])[0]
        _, was = sp.commit_step(P[0], e, rate, H[0], was)
        forces.append(f + (P[0]["f0"] if P[0]["kind"] != sp.STORY else 0.0))
        contact.append(was)
    return np.array(forces), np.array(contact), H


def test_elastic_load_unload_separate_recontact():
    """Compression-only elastic spring: F = k(δ0 + e) while > 0, separated (F = 0) once its
    tension from static exceeds the static compression, e < −δ0; recontacts at e = −δ0."""
    path = np.concatenate([np.linspace(0, 2 * D0, 21), np.linspace(2 * D0, -2 * D0, 41),
                           np.linspace(-2 * D0, D0, 31)])
    forces, contact, _ = walk(foundation(), path)
    expected = np.maximum(K * (D0 + path), 0.0)
    np.testing.assert_allclose(forces, expected, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(contact, (path > -D0).astype(int))


def test_elastoplastic_yield_settlement_and_shifted_separation():
    """Fig. 6: yield at FS·F0 (compression 3δ0); plastic settlement ep = e − 2δ0 accumulates;
    unloading is elastic and separation moves to e = ep − δ0; reloading yields again at Fy."""
    peak = 4 * D0
    path = np.concatenate([np.linspace(0, peak, 41), np.linspace(peak, -D0, 51),
                           np.linspace(-D0, peak + D0, 61)])
    forces, contact, H = walk(foundation("elastoplastic"), path)
    ep1 = peak - 2 * D0                                   # settlement after the first excursion
    assert forces.max() == pytest.approx(FS * F0, rel=1e-12)
    unload = slice(41, 92)
    np.testing.assert_allclose(forces[unload], np.maximum(K * (D0 + path[unload] - ep1), 0),
                               atol=1e-12)
    sep = path[unload][contact[unload] == 0]
    assert sep.max() <= ep1 - D0 + 1e-12                  # separated only below ep − δ0
    assert H[0]["ep"] == pytest.approx(peak + D0 - 2 * D0, rel=1e-12)   # second excursion


def test_bonded_spring_carries_tension():
    """support = 'bonded': the same spring pulls (F < 0) instead of separating."""
    path = np.linspace(0, -3 * D0, 31)
    forces, contact, _ = walk(foundation(kind=sp.BONDED), path)
    np.testing.assert_allclose(forces, K * (D0 + path), atol=1e-12)
    assert contact.min() == 1


def test_dashpot_detaches_and_never_pulls():
    """Parallel dashpot: F = k d + c ė in contact, clipped at zero while opening, and nothing
    once separated (design.md, as OpenSees QzSimple)."""
    P = foundation(c=20.0)
    p = P[0]
    H = np.zeros(1, dtype=sp.HISTORY_DTYPE)[0]
    for e, ed in [(0.0, 1.0), (0.0, -0.2), (-0.05, -1.0), (-0.2, -1.0), (-0.2, 1.0)]:
        mode = sp.natural_mode(p, e, ed, 0.0, 0.0)
        total = sp.force_in_mode(mode, p, e, ed, 0.0, 0.0)[0] + F0
        d = D0 + e
        expected = max(K * d + 20.0 * ed, 0.0) if d > 0 else 0.0
        assert total == pytest.approx(expected, abs=1e-12)
        assert sp.validity(mode, p, e, ed, H) >= 0.0


def test_impact_damper_activates_on_recontact_then_locks():
    """Eqs. 10–17: recontact with closing velocity v0 switches c* on for the stroke
    Δz = v0·m(1−ε)/c*; the damper then locks."""
    m, eps, cstar = 2.0, 0.7, 500.0
    P = foundation(cimp=cstar, dzf=m * (1 - eps) / cstar)
    p = P[0]
    H = np.zeros(1, dtype=sp.HISTORY_DTYPE)
    h = H[0]
    v0 = 3.0
    mode = sp.switch_mode(sp.SEPARATED, p, -D0 + 1e-12, v0, h)   # touches the surface
    assert mode == sp.CONTACT and h["imp"] == 1.0
    assert h["dz"] == pytest.approx(v0 * m * (1 - eps) / cstar, rel=1e-12)
    f = sp.force_in_mode(mode, p, -D0 + 1e-12, v0, 0.0, 1.0)[0] + F0
    assert f == pytest.approx(cstar * v0, rel=1e-9)                # dashpot force at contact
    e_lock = -D0 + h["dz"] + 1e-12
    assert sp.validity(mode, p, e_lock + 1e-9, v0, h) < 0           # stroke done: switch
    mode = sp.switch_mode(mode, p, e_lock + 1e-9, eps * v0, h)
    assert mode == sp.CONTACT and h["imp"] == 0.0


def test_story_spring_bilinear_hardening_cycle():
    """Story spring: elastic-perfectly-plastic k(1−α) capped at Fy(1−α) plus αk; a symmetric
    cycle gives the bilinear kinematic-hardening loop (closed form below)."""
    k, fy, alpha = 50.0, 5.0, 0.1
    uy = fy / k
    path = np.concatenate([np.linspace(0, 3 * uy, 31), np.linspace(3 * uy, -3 * uy, 61),
                           np.linspace(-3 * uy, 3 * uy, 61)])
    forces, _, _ = walk(story(k, fy, alpha), path)
    # reference: integrate the bilinear law incrementally with a tiny independent step
    ref, up = [], 0.0
    for u in path:
        f_ep = (1 - alpha) * k * (u - up)
        if abs(f_ep) > (1 - alpha) * fy:
            up = u - np.sign(f_ep) * uy
        ref.append(alpha * k * u + (1 - alpha) * k * (u - up))
    np.testing.assert_allclose(forces, ref, atol=1e-12)
    assert forces.max() == pytest.approx(fy + alpha * k * 2 * uy, rel=1e-12)


@pytest.mark.parametrize("law", ["elastic", "elastoplastic"])
def test_every_switch_leaves_a_valid_state(law):
    """switch_mode always returns a mode in which the state is valid (validity ≥ 0), from any
    state where the old mode was crossed: 20 000 random states."""
    rng = np.random.default_rng(1)
    P = foundation(law, c=5.0, cimp=50.0, dzf=0.01)
    p = P[0]
    bad = 0
    for _ in range(20_000):
        H = np.zeros(1, dtype=sp.HISTORY_DTYPE)
        h = H[0]
        h["ep"] = rng.uniform(0, 3 * D0)
        h["imp"] = float(rng.random() < 0.3)
        h["e0"], h["dz"] = rng.uniform(-D0, D0), rng.uniform(0, D0)
        mode = int(rng.integers(0, 4))
        e, ed = rng.uniform(-3 * D0, 5 * D0), rng.uniform(-2, 2)
        if sp.validity(mode, p, e, ed, h) >= 0:
            continue
        new = sp.switch_mode(mode, p, e, ed, h)
        bad += sp.validity(new, p, e, ed, h) < -1e-9
    assert bad == 0
