"""The macro-element's calibration from continuum statics (upliftlab.comparisons.beds.macro):
the capacity line against an effective-width strip built by hand, the law's pushover at
constant N against the tensionless strip's closed form, and the fit against pushovers of a law
of known parameters.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.beds.macro import (_LOGS, PLASTIC_BOUNDS, RotationPushover,
                                              calibrate_macro, capacity_line, macro_pushover)
from upliftlab.reduced.laws.macro import MacroElement

B = 2.0
ELASTIC = dict(width=B, vertical_stiffness=27513.0, horizontal_stiffness=27513.0,
               rocking_stiffness=43146.0)


def strip_pushover(N, q0, q1):
    """A pushover whose largest moment is the effective-width strip's with q(B′) = q0 + q1 B′:
    B′ the root of N = B′ (q0 + q1 B′), M = N (B − B′)/2."""
    reduced = (-q0 + math.sqrt(q0 * q0 + 4 * q1 * N)) / (2 * q1) if q1 else N / q0
    theta = np.linspace(0, 0.01, 5)
    return RotationPushover(N, theta, np.linspace(0, N * (B - reduced) / 2, 5), 0 * theta)


def test_capacity_line_recovers_a_strip():
    """Reference: strips built by hand from q(B′) = 170 + 88 B′ (kPa): the line through
    V_ult/B = q(B) comes back to 1e-12, every residual 0; held flat without a frictional
    term, its residuals are the flat line's misfit, computed here by hand."""
    q0, q1 = 170.0, 88.0
    v_ult = B * (q0 + q1 * B)
    pushes = [strip_pushover(f * v_ult, q0, q1) for f in (0.1, 0.2, 1 / 3, 0.5)]
    base, slope, residuals = capacity_line(pushes, v_ult, B)
    assert (base, slope) == pytest.approx((q0, q1), rel=1e-12)
    np.testing.assert_allclose(residuals, 0.0, atol=1e-12)
    base, slope, residuals = capacity_line(pushes, v_ult, B, frictional=False)
    assert (base, slope) == (v_ult / B, 0.0)
    reduced = np.array([(-q0 + math.sqrt(q0 * q0 + 4 * q1 * p.N)) / (2 * q1) for p in pushes])
    np.testing.assert_allclose(residuals, (v_ult / B) / (q0 + q1 * reduced) - 1, rtol=1e-12)


def test_pushover_at_constant_load_is_the_uplift_closed_form():
    """Reference: a rigid strip on a tensionless bed under N, M = N b (1 − (2/3)√(θ_up/θ))
    beyond θ_up = 2N/(k B²), (k B³/12) θ before (the bed matches K_r: no remainder in
    rotation), with plasticity out of reach (h0 = 1e12, capacity 100 times N): to 1e-6."""
    law = MacroElement(**ELASTIC, cohesion=5000.0, interior_modulus=1e12)
    N = 200.0
    k = law.winkler_modulus
    theta_up = 2 * N / (k * B * B)
    thetas = np.concatenate([[0.0, 0.5 * theta_up], np.geomspace(theta_up, 20 * theta_up, 8)])
    M, _ = macro_pushover(law, N, thetas)
    closed = np.where(thetas <= theta_up, k * B ** 3 / 12 * thetas,
                      N * 1.0 * (1 - 2 / 3 * np.sqrt(theta_up / np.maximum(thetas, 1e-300))))
    np.testing.assert_allclose(M, closed, rtol=1e-6, atol=1e-9)


KNOWN = MacroElement(**ELASTIC, cohesion=50.0, initial_size=0.75, hardening_settlement=0.005,
                     interior_modulus=2.0, interior_exponent=1.2, settlement_coupling=0.3,
                     rounding_ratio=0.5, memory_modulus=10.0)
FITTED = ("initial_size", "hardening_settlement", "interior_modulus", "interior_exponent",
          "settlement_coupling", "rounding_ratio", "memory_modulus")


def _known_pushovers():
    """Pushovers made by :data:`KNOWN` at FS 2.5 and 5: a monotonic one to 8 θ_on, a cycle to
    ±4 θ_on and two repeated cycles at ±2 θ_on (the path that identifies the memory's μ)."""
    theta_on = 2e-3
    mono = np.linspace(0, 8 * theta_on, 9)
    cycle = np.concatenate([np.linspace(0, 4, 5), np.linspace(4, -4, 9),
                            np.linspace(-4, 0, 5)[1:]]) * theta_on
    repeated = np.concatenate([[0.0]] + [np.array([1, 2, 1, 0, -1, -2, -1, 0.0])] * 2) * theta_on
    pushes = []
    for fs in (2.5, 5.0):
        N = KNOWN.ultimate_load / fs
        for path in (mono, cycle, repeated):
            M, s = macro_pushover(KNOWN, N, path)
            pushes.append(RotationPushover(N, path, M, s, f"fs {fs}"))
    return pushes


def _recovers_the_known_law(rel=1e-2, rel_fit=1e-3, **fit):
    """The fit of :func:`_known_pushovers` (``fit``: :func:`calibrate_macro`'s options) gives
    each fitted parameter within ``rel`` of :data:`KNOWN`'s, and its pushovers theirs within
    ``rel_fit`` of the largest moment and of the settlement's range."""
    pushes = _known_pushovers()
    cal = calibrate_macro(pushes, width=B, V_ult=KNOWN.ultimate_load,
                          K_v=ELASTIC["vertical_stiffness"], K_r=ELASTIC["rocking_stiffness"],
                          cohesion=50.0, **fit)
    for name in FITTED:
        assert getattr(cal.law, name) == pytest.approx(getattr(KNOWN, name), rel=rel), name
    for p in pushes:
        M, s = macro_pushover(cal.law, p.N, p.theta)
        assert np.max(np.abs(M - p.M)) <= rel_fit * np.max(np.abs(p.M))
        change = p.settlement - p.settlement[0]
        assert np.max(np.abs((s - s[0]) - change)) <= rel_fit * max(np.ptp(change), 2e-3)


def test_the_fit_started_at_a_known_law_keeps_it():
    """Reference: pushovers made by a law of stated parameters (:func:`_known_pushovers`).
    Started at them, the fit (its survey of 24 points, then four polishes) keeps them to
    1e-9 and its pushovers theirs to 1e-8: the objective is zero there and nothing in the
    fit's scaling, its logarithms or its capacity line moves it (measured: 0 and 2e-16
    in the parameters, 6e-10 of the settlement's range). That the fit comes back from afar:
    the slow test below. (A fast one from 7–25 % away in 400 evaluations, 140 s, was not
    converged: the pushovers pin H0, its exponent and the memory's μ weakly, 1 % in H0
    moving the largest moment by 0.09 % and in μ by 0.02 %, so that where the fit stopped
    hung on the machine's rounding: within 1 % on one machine, H0 −1.7 %, its exponent
    −1.2 %, μ −1.9 % on an AVX-512 EPYC.)"""
    at_known = [math.log10(getattr(KNOWN, name)) if name in _LOGS else getattr(KNOWN, name)
                for name, _, _ in PLASTIC_BOUNDS]  # in the fit's variables
    _recovers_the_known_law(start=at_known, max_evaluations=65, rel=1e-9, rel_fit=1e-8)


@pytest.mark.slow
def test_calibration_finds_a_law_of_known_parameters_from_its_own_start():
    """Reference: :data:`KNOWN`. From the fit's default start and its survey, every
    parameter within 1 % and the pushovers within 0.1 % (measured: every parameter within
    2e-5 of the truth after 748 evaluations, 5 min on this machine)."""
    _recovers_the_known_law(max_evaluations=1600)


def test_a_calibration_without_a_monotonic_pushover_is_refused():
    cycle = RotationPushover(100.0, np.array([0.0, 1e-3, 0.0]), np.zeros(3), np.zeros(3))
    with pytest.raises(InputError, match="no monotonic rotation pushover"):
        calibrate_macro([cycle], width=B, V_ult=500.0, K_v=2e4, K_r=4e4, cohesion=50.0)
