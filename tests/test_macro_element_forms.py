"""The macro-element's forms at a single point, before any structure: its capacity against the
effective-width and Green's closed forms, its uplift mechanism against the tensionless strip's
closed form and an independent sum of springs, and its tangents against finite differences.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.reduced.laws.macro import (MacroElement, at_rest, bed_energy, bed_forces,
                                          elastic_forces, failure_function,
                                          failure_gradient, horizontal_capacity,
                                          moment_capacity, remainder_compliance,
                                          rounding_force, vertical_rocking_forces)

CLAY = dict(width=2.0, vertical_stiffness=27513.0, horizontal_stiffness=30000.0,
            rocking_stiffness=43150.0, cohesion=50.0)


def clay(**changes):
    return MacroElement(**{**CLAY, **changes})


@pytest.mark.parametrize("fs_v", [2.0, 3.0, 5.0, 10.0])
def test_moment_capacity_is_the_effective_width_closed_form(fs_v):
    """Reference: effective width on a Tresca clay, M = N B/2 (1 − 1/FS_v); with the N_γ term
    alone, M = N B/2 (1 − 1/√FS_v) (V_cap ∝ B′²). The capacity to 1e-12, F on it to 1e-9 (the
    surface's ridge at M = 0 is rounded over 1e-12 B V_ult: :data:`RIDGE`)."""
    law = clay()
    n = law.ultimate_load / fs_v
    assert moment_capacity(law, n) == pytest.approx(n * 1.0 * (1 - 1 / fs_v), rel=1e-12)
    assert failure_function(law, (n, 0.0, n * (1 - 1 / fs_v))) == pytest.approx(0, abs=1e-9)
    sand = MacroElement(**{**CLAY, "cohesion": 0.0, "friction_angle": 30.0,
                           "unit_weight": 18.0})
    n = sand.ultimate_load / fs_v
    closed = n * 1.0 * (1 - 1 / math.sqrt(fs_v))
    assert moment_capacity(sand, n) == pytest.approx(closed, rel=1e-12)
    assert failure_function(sand, (n, 0.0, closed)) == pytest.approx(0, abs=1e-9)


def test_capacity_with_both_terms_is_the_textbook_strip():
    """Reference: B′ (c N_c + ½ γ B′ N_γ) with N_c = 30.14, N_γ = 22.40 at φ = 30° (Vesić
    1973's table): V_ult at B′ = B, and at V = 300 kN/m the moment that leaves B′ = 1.6 m
    bearing exactly V: to 1e-3 (the tables' digits)."""
    law = MacroElement(**{**CLAY, "cohesion": 5.0, "friction_angle": 30.0,
                          "unit_weight": 18.0})
    assert law.ultimate_load == pytest.approx(2.0 * (5.0 * 30.14 + 9.0 * 2.0 * 22.40), rel=1e-3)
    width = 1.6
    v = width * (5.0 * 30.14 + 9.0 * width * 22.40)
    assert moment_capacity(law, v) == pytest.approx(v * (2.0 - width) / 2, rel=1e-3)


def test_horizontal_capacity_peaks_on_greens_solution():
    """Reference: Green (1954), a bonded strip on Tresca clay under an inclined central load,
    V/(c B) = 1 + π − arcsin(H/(c B)) + √(1 − (H/(c B))²): its largest H, c B, at
    V = c B (1 + π/2) = V_ult/2. The default parabola passes through it, to 1e-12 (F to 1e-11:
    the cone at M = 0 is rounded over 1e-12 B V_ult)."""
    law = clay()
    assert horizontal_capacity(law, law.ultimate_load / 2) == pytest.approx(50.0 * 2.0,
                                                                            rel=1e-12)
    assert failure_function(law, (law.ultimate_load / 2, 100.0, 0.0)) == pytest.approx(
        0.0, abs=1e-11)


def test_failure_gradient_is_the_derivative():
    """Reference: central finite differences of F (step 1e-6 of each force), to 1e-6."""
    for law in (clay(), MacroElement(**{**CLAY, "cohesion": 5.0, "friction_angle": 30.0,
                                        "unit_weight": 18.0})):
        q = np.array([0.4 * law.ultimate_load, 0.05 * law.ultimate_load,
                      0.1 * law.ultimate_load])
        fd = np.array([(failure_function(law, q + 1e-6 * q[0] * e, 0.8)
                        - failure_function(law, q - 1e-6 * q[0] * e, 0.8)) / (2e-6 * q[0])
                       for e in np.eye(3)])
        np.testing.assert_allclose(failure_gradient(law, q, 0.8), fd, rtol=1e-6,
                                   atol=1e-6 * np.abs(fd).max())


def _sum_of_springs(k, b, v, theta, rho=0.0, count=20000):
    """An independent tensionless bed: ``count`` springs at strip centres (midpoint rule), on
    a surface ρ (x²/b² − 1/3) below the footing."""
    x = (np.arange(count) + 0.5) / count * 2 * b - b
    p = k * np.maximum(v + theta * x - rho * (x * x / b / b - 1 / 3), 0.0) * (2 * b / count)
    return np.array([p.sum(), (p * x).sum()]), 0.5 / k * (p * p).sum() / (2 * b / count)


@pytest.mark.parametrize("rho", [0.0, 1e-9, 0.004, 0.02])
@pytest.mark.parametrize("v, theta", [(0.01, 0.002), (0.01, 0.01), (0.002, -0.004),
                                      (-0.001, 0.003), (-0.01, 0.001), (0.0, 0.0)])
def test_tensionless_bed_is_a_sum_of_springs(v, theta, rho):
    """Reference: 20,000 tensionless springs summed (midpoint rule, error O(1/n²) but for the
    cells the contact's ends cross, O(1/n²) too), on a flat and on rounded surfaces (ρ down
    to 1e-9, where the contact's far root runs off to infinity): forces and energy to 1e-6;
    the rounding force F_ρ against central differences of the energy in ρ."""
    k, b = 1.0e4, 1.0
    forces, _ = bed_forces(k, b, v, theta, rho)
    springs, energy = _sum_of_springs(k, b, v, theta, rho)
    np.testing.assert_allclose(forces, springs, rtol=1e-6, atol=1e-6 * (abs(springs).max()
                                                                         + 1e-3))
    assert bed_energy(k, b, v, theta, rho) == pytest.approx(energy, rel=1e-6, abs=1e-12)
    h = 1e-7
    fd = -(bed_energy(k, b, v, theta, rho + h) - bed_energy(k, b, v, theta, rho - h)) / (2 * h)
    if rho > h:
        assert rounding_force(k, b, v, theta, rho) == pytest.approx(fd, rel=1e-5, abs=1e-6)


@pytest.mark.parametrize("v, theta, rho", [(0.005, 0.001, 0.003), (0.002, 0.004, 0.01),
                                           (0.01, -0.002, 0.02)])
def test_rounded_bed_tangent_is_the_derivative(v, theta, rho):
    """Reference: central finite differences of the rounded bed's forces (steps 1e-8), to
    1e-6: k times the contact's moments, by Leibniz's rule."""
    k, b = 1.0e4, 1.0
    _, tangent = bed_forces(k, b, v, theta, rho)
    fd = np.column_stack([(bed_forces(k, b, *(np.array([v, theta]) + 1e-8 * e), rho)[0]
                           - bed_forces(k, b, *(np.array([v, theta]) - 1e-8 * e), rho)[0])
                          / 2e-8 for e in np.eye(2)])
    np.testing.assert_allclose(tangent, fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max())


def test_uplift_at_constant_load_is_the_closed_form():
    """Reference: a rigid strip on a tensionless bed under N, M = N b (1 − (2/3)√(θ_up/θ))
    beyond θ_up = 2N/(k B²) and (k B³/12) θ before it; in series with the remainder, the
    rotation adds M C_x,θ. The macro-element's (v, θ) at (N, M) found by Newton on its own
    forces; to 1e-9."""
    for rocking in (5000.0, 43150.0):  # the remainder in rotation, then in settlement
        law = clay(rocking_stiffness=rocking)
        cx = remainder_compliance(law)
        assert (cx > 0.0).sum() == 1
        _uplift_matches_closed_form(law, cx)


def _uplift_matches_closed_form(law, cx):
    k, width, b = law.winkler_modulus, law.width, 1.0
    n = 200.0
    theta_up = 2 * n / (k * width ** 2)
    for ratio in (0.2, 1 / 3, 0.5, 0.8, 0.95):
        m = ratio * n * b
        bed = (m / (k * width ** 3 / 12) if ratio <= 1 / 3
               else theta_up * 4 / 9 / (1 - ratio) ** 2)
        theta_closed = bed + cx[1] * m
        d = np.array([n / law.vertical_stiffness, theta_closed])
        for _ in range(50):
            q, tangent, _ = vertical_rocking_forces(law, *d)
            d = d - np.linalg.solve(tangent, q - [n, m])
        assert d[1] == pytest.approx(theta_closed, rel=1e-9)


@pytest.mark.parametrize("v, theta", [(0.008, 0.0005), (0.008, 0.006), (0.004, -0.01),
                                      (0.001, 0.02)])
def test_elastic_tangent_is_the_derivative(v, theta):
    """Reference: central finite differences of the forces (steps 1e-7 of v and of B θ), with
    the remainder in series (K_v, K_r softer than the bed); to 1e-5."""
    law = clay(vertical_stiffness=20000.0, rocking_stiffness=30000.0)
    _, tangent, _ = vertical_rocking_forces(law, v, theta)
    steps = (1e-7, 1e-7 / law.width)
    fd = np.column_stack([
        (vertical_rocking_forces(law, *(np.array([v, theta]) + h * e))[0]
         - vertical_rocking_forces(law, *(np.array([v, theta]) - h * e))[0]) / (2 * h)
        for h, e in zip(steps, np.eye(2))])
    np.testing.assert_allclose(tangent, fd, rtol=1e-5, atol=1e-5 * np.abs(tangent).max())


def test_stored_energy_is_the_forces_potential():
    """Reference: the elastic mechanism's forces are the gradient of its stored energy
    (central finite differences of the energy, to 1e-6)."""
    law = clay(vertical_stiffness=20000.0, rocking_stiffness=30000.0)
    d = np.array([0.006, 0.0003, 0.007])
    q = elastic_forces(law, d)[0]
    h = np.array([1e-7, 1e-7, 1e-7 / law.width])
    fd = [(elastic_forces(law, d + hi * e)[2] - elastic_forces(law, d - hi * e)[2]) / (2 * hi)
          for hi, e in zip(h, np.eye(3))]
    np.testing.assert_allclose(q, fd, rtol=1e-6)


def test_bad_parameters_are_one_line_each():
    with pytest.raises(InputError, match="macro.initial_size = 1.5: valid range"):
        clay(initial_size=1.5)
    with pytest.raises(InputError, match="no bearing capacity"):
        clay(cohesion=0.0)
    with pytest.raises(InputError, match="vertical load = 400: valid range"):
        at_rest(clay(initial_size=0.5), 400.0)
