"""Every form of each spring law agrees with the others (reduced/kernels/laws.py, which
dispatches a foundation spring to its law's forms: reduced/laws/elastoplastic.py).

A spring law is written in several forms, each for one integrator: the direct force in a mode
(``force_in_mode``), the affine coefficients the event stepper tabulates (``law``), the tangent
of the implicit integrators (``tangent``), the conditions that bound a mode (``condition``,
their least ``validity``), the switch at a crossed limit (``switch_mode``) and the fixed-step
return map (``commit_step``). Random springs of every kind (story, uplifting and bonded
foundation; elastic and elasto-plastic; with and without the impact dashpot) in random modes,
histories and states are driven through all of them, compiled.

Reference: the direct form, ``force_in_mode``, a line-by-line statement of Ewing's laws
(documented in :mod:`upliftlab.reduced.laws.elastoplastic`); the other forms must reproduce it
to 1e-12 of the size of the terms they sum (they sum the same terms in another order).
"""

import numpy as np
import pytest

from upliftlab.reduced import kernels as kn, springs as sp

RNG_SEED = 20261124
SAMPLES = 400   # random states per kind and law
TOL = 1e-12     # relative to the size of the terms summed

MODES = {sp.STORY: (sp.ELASTIC, sp.YIELD_POS, sp.YIELD_NEG),
         sp.UPLIFT: (sp.SEPARATED, sp.CONTACT, sp.YIELDING, sp.CLIPPED),
         sp.BONDED: (sp.CONTACT, sp.YIELDING)}


def _springs(rng, kind: int, plastic: bool):
    """SAMPLES random springs of one kind (records), their histories and states (e, ė)."""
    table = sp.spring_table(SAMPLES)
    k = 10.0 ** rng.uniform(2, 5, SAMPLES)
    table["kind"], table["nnz"], table["k"] = kind, 2, k
    table["c"] = rng.uniform(0, 50, SAMPLES)
    if kind == sp.STORY:
        table["kh"] = rng.uniform(0, 0.1, SAMPLES) * k
        table["fy"] = rng.uniform(1, 100, SAMPLES) if plastic else np.inf
    else:
        table["f0"] = rng.uniform(1, 100, SAMPLES)
        table["fy"] = table["f0"] * rng.uniform(1.5, 5, SAMPLES) if plastic else np.inf
        impact = rng.random(SAMPLES) < 0.5
        table["cimp"] = np.where(impact, rng.uniform(1, 100, SAMPLES), 0.0)
        table["dzf"] = np.where(impact, rng.uniform(1e-4, 1e-2, SAMPLES), 0.0)
    P = sp.derive_columns(table).view(np.recarray)
    scale = np.where(kind == sp.STORY, np.where(np.isfinite(P.dy), P.dy, 1.0 / k), P.d0)
    H = np.zeros(SAMPLES, dtype=sp.HISTORY_DTYPE).view(np.recarray)
    H.ep = rng.uniform(-0.5, 0.5, SAMPLES) * scale
    H.imp = np.where(P.cimp > 0, (rng.random(SAMPLES) < 0.5).astype(float), 0.0)
    H.e0 = rng.uniform(-1, 1, SAMPLES) * scale
    H.dz = rng.uniform(0, 1, SAMPLES) * scale
    e = rng.uniform(-3, 3, SAMPLES) * scale
    ed = rng.uniform(-1, 1, SAMPLES) * scale * 30.0
    return P, H, e, ed


def _cases():
    return [(kind, plastic) for kind in MODES for plastic in (False, True)]


def _size(p, h, e, ed):
    """The size of the terms a law sums at (e, ė): its force scale."""
    fy = p.fy if np.isfinite(p.fy) else 0.0
    return (p.k + p.kh) * (abs(e) + abs(p.d0) + abs(h.ep)) + (p.c + p.cimp) * abs(ed) + p.f0 + fy


def _modes(p):
    return [m for m in MODES[p.kind]
            if np.isfinite(p.fy) or m not in (sp.YIELDING, sp.YIELD_POS, sp.YIELD_NEG)]


@pytest.mark.parametrize("kind, plastic", _cases())
def test_tabulated_and_tangent_forms_equal_the_direct_force(kind, plastic):
    """In every mode: the tabulated force K e + C ė + F and powers (a + b e + c ė) ė (viscous,
    impact) and P ė (plastic) equal ``force_in_mode``'s; the tangent (dF/de, dF/dė) equals the
    table's (K, C) and the central difference of the direct force (affine in a mode, so exact
    to rounding: 1e-6 with a step of 1e-3 of the state)."""
    P, H, e, ed = _springs(np.random.default_rng(RNG_SEED + 10 * kind + plastic), kind, plastic)
    for j in range(SAMPLES):
        p, h = P[j], H[j]
        size = _size(p, h, e[j], ed[j])
        for mode in _modes(p):
            f, pv, pi, pp, _, _ = kn.force_in_mode(mode, p, e[j], ed[j], h.ep, h.imp)
            K, C, F, v0, v1, v2, i0, i1, i2, Pp = kn.law(mode, p, h)
            assert K * e[j] + C * ed[j] + F == pytest.approx(f, abs=TOL * size)
            assert (v0 + v1 * e[j] + v2 * ed[j]) * ed[j] == pytest.approx(
                pv, abs=TOL * size * abs(ed[j]))
            assert (i0 + i1 * e[j] + i2 * ed[j]) * ed[j] == pytest.approx(
                pi, abs=TOL * size * abs(ed[j]))
            assert Pp * ed[j] == pytest.approx(pp, abs=TOL * size * abs(ed[j]))
            kt, ct = kn.tangent(mode, p, h.imp)
            assert (kt, ct) == pytest.approx((K, C), rel=TOL, abs=TOL * (p.k + p.c))
            de, dv = 1e-3 * (abs(e[j]) + 1e-12), 1e-3 * (abs(ed[j]) + 1e-12)
            slope_e = (kn.force_in_mode(mode, p, e[j] + de, ed[j], h.ep, h.imp)[0]
                       - kn.force_in_mode(mode, p, e[j] - de, ed[j], h.ep, h.imp)[0]) / (2 * de)
            slope_v = (kn.force_in_mode(mode, p, e[j], ed[j] + dv, h.ep, h.imp)[0]
                       - kn.force_in_mode(mode, p, e[j], ed[j] - dv, h.ep, h.imp)[0]) / (2 * dv)
            assert slope_e == pytest.approx(kt, abs=1e-6 * size / de * 1e-3 + 1e-6 * p.k)
            assert slope_v == pytest.approx(ct, abs=1e-6 * size / dv * 1e-3 + 1e-6 * p.c)


@pytest.mark.parametrize("kind, plastic", _cases())
def test_validity_is_the_least_condition(kind, plastic):
    """``validity`` is the least of the mode's conditions α + β e + γ ė (``condition``, the
    form the event stepper tabulates and searches), wherever either is below 1 (a condition the
    mode does not use is the constant 1); and ``past_limit`` says a limit was crossed exactly
    when the validity is below −1e-9 (states away from the switch tolerance)."""
    P, H, e, ed = _springs(np.random.default_rng(RNG_SEED + 100 + 10 * kind + plastic), kind,
                           plastic)
    for j in range(SAMPLES):
        p, h = P[j], H[j]
        size = _size(p, h, e[j], ed[j]) * (p.gs + p.gd) + abs(ed[j]) + 1.0
        for mode in _modes(p):
            least = min(a + b * e[j] + g * ed[j]
                        for a, b, g in (kn.condition(k, mode, p, h)
                                        for k in range(kn.N_CONDITIONS)))
            valid = kn.validity(mode, p, e[j], ed[j], h)
            assert min(valid, 1.0) == pytest.approx(min(least, 1.0), abs=TOL * size)
            if abs(valid) > 1e-9:
                assert kn.past_limit(mode, p, e[j], ed[j], h) == (valid < 0.0)


@pytest.mark.parametrize("kind, plastic", _cases())
def test_a_switch_lands_in_a_valid_mode_and_the_return_map_where_the_switch_does(kind, plastic):
    """From any mode whose limit a state has crossed, ``switch_mode`` (applied as the event
    stepper does, at most four times) reaches a mode valid for the state (validity ≥ −1e-9);
    and where a trial state is past yield in contact, ``commit_step``'s return map puts the
    plastic deformation where the switch to yield puts it, leaving the spring force on the
    yield surface (|spring force| ≤ Fy (1 + 1e-12)) with the plastic work Fy |Δεp|."""
    P, H, e, ed = _springs(np.random.default_rng(RNG_SEED + 200 + 10 * kind + plastic), kind,
                           plastic)
    for j in range(SAMPLES):
        p = P[j]
        for mode in _modes(p):
            h = np.array([H[j]], dtype=sp.HISTORY_DTYPE).view(np.recarray)[0]
            for _ in range(4):
                if not kn.past_limit(mode, p, e[j], ed[j], h):
                    break
                mode = kn.switch_mode(mode, p, e[j], ed[j], h)
            assert kn.validity(mode, p, e[j], ed[j], h) >= -1e-9
        if not plastic:
            continue
        trial = np.array([H[j]], dtype=sp.HISTORY_DTYPE).view(np.recarray)[0]
        trial.imp = 0.0
        switched = np.array([trial], dtype=sp.HISTORY_DTYPE).view(np.recarray)[0]
        ep = trial.ep
        if kind == sp.STORY:
            spring = p.k * (e[j] - ep)
        else:
            spring = p.k * (p.d0 + e[j] - ep)
        if abs(spring) <= p.fy * (1 + 1e-9) or (kind != sp.STORY and spring < 0):
            continue
        work, contact = kn.commit_step(p, e[j], ed[j], trial, 1)
        start = sp.ELASTIC if kind == sp.STORY else sp.CONTACT
        kn.switch_mode(start, p, e[j], 1.0, switched)
        assert trial.ep == pytest.approx(switched.ep, rel=TOL, abs=TOL * abs(p.dy))
        after = p.k * (e[j] - trial.ep) if kind == sp.STORY else p.k * (p.d0 + e[j] - trial.ep)
        assert abs(after) <= p.fy * (1 + 1e-12)
        assert work == pytest.approx(p.fy * abs(trial.ep - ep), rel=TOL)
        assert contact == 1
