"""Elastic soil under a rigid footing: stiffnesses and geostatic stress of upliftlab.continuum.

References (closed forms for a rigid strip on an elastic half-plane unless stated):
- rocking stiffness of a rigid frictionless strip on an elastic half-plane,
  K_r = π G B²/(8(1 − ν)); a bonded footing is about 5 % stiffer at ν = 0.3;
- Flamant: 1/K_v grows by (1 − ν)/(π G) per unit ln(domain size);
- a thin layer on a rigid base: K_v → E_oed B/H as H/B → 0 (one-dimensional compression,
  E_oed = E(1 − ν)/((1 + ν)(1 − 2ν))), with an O(H/B) edge correction;
- geostatic stress: K0 stress is in equilibrium with the weight; an elastic gravity step
  under roller sides gives σ_xx/σ_yy = ν/(1 − ν).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from upliftlab.continuum import elastic_gravity_stress, footing_stiffness, k0_stress, make_model
from upliftlab.continuum import geostatic
from upliftlab.scenes import ContinuumOptions, Soil

E, NU, B = 50e3, 0.3, 2.0  # kPa, -, m
G = E / (2 * (1 + NU))
K_R = math.pi * G * B ** 2 / (8 * (1 - NU))  # kN m/rad per m
SOIL = Soil(youngs_modulus=E, poisson_ratio=NU, density=1.8, model="elastic")


def rocking(n=16, intorder=None, interface="frictionless", **kw):
    soil = dataclasses.replace(SOIL, interface=interface)
    model = make_model(soil, B, ContinuumOptions(elements_across=int(n), intorder=intorder, **kw))
    return footing_stiffness(model).rocking


def test_rocking_stiffness_on_default_mesh_within_1_percent():
    # Reference: K_r = π G B²/(8(1 − ν)) (Muskhelishvili's rigid punch). Default mesh: Q2 2×2
    # reduced, 16 elements across B, 10B × 10B box, 20 160 DOFs. Measured: −0.018 %.
    error = rocking() / K_R - 1.0
    assert abs(error) <= 0.01, error


def test_rocking_stiffness_converges_at_first_order_with_full_integration():
    # Reference: the footing-edge singularity limits convergence to O(h);
    # Q2 with full 3×3 integration at n = 4, 8, 16 across B: +7.64 %, +3.75 %, +1.83 %, fitted
    # rate 1.03 (asserted 1 ± 0.15); Richardson 2 K(16) − K(8) = −0.085 % (asserted 0.2 %).
    # The reduced default converges faster and from nearer: +0.76 %, +0.14 %, −0.02 %.
    ns = np.array([4, 8, 16])
    full = np.array([rocking(n, intorder=4) for n in ns])
    rate = np.polyfit(np.log(1.0 / ns), np.log(full / K_R - 1.0), 1)[0]  # error ~ h^rate
    assert abs(rate - 1.0) <= 0.15, rate
    assert abs((2 * full[-1] - full[-2]) / K_R - 1.0) <= 0.002
    reduced = np.abs(np.array([rocking(n) for n in ns]) / K_R - 1.0)
    assert np.all(np.diff(reduced) < 0.0) and np.all(reduced < full / K_R - 1.0)


@pytest.mark.slow
def test_rocking_stiffness_refinement_study():
    # Reference: K_r closed form; the box limit is the Richardson extrapolation of Q2 full
    # integration at 32 and 64 across (measured −0.07 % from the half-plane: the 10B box).
    # Observed: reduced Q2 errors against that limit fall at rate ≈ 1.9 (asserted > 1.5),
    # full integration at rate 1 ± 0.15; the box limit is within 0.2 % of the closed form.
    ns = np.array([8, 16, 32, 64])
    full = np.array([rocking(n, intorder=4) for n in ns[1:]])
    limit = 2 * full[-1] - full[-2]
    assert abs(limit / K_R - 1.0) <= 0.002
    rate_full = -np.polyfit(np.log(ns[1:]), np.log(full - limit), 1)[0]
    assert abs(rate_full - 1.0) <= 0.15
    reduced = np.array([rocking(n) for n in ns])
    rate = -np.polyfit(np.log(ns), np.log(np.abs(reduced - limit)), 1)[0]
    assert rate > 1.5, rate


def test_bonded_footing_is_about_five_percent_stiffer_in_rocking():
    # Reference: the half-plane solutions of bonded and frictionless strips, "a bonded (rough)
    # footing is about 5 % stiffer at ν = 0.3". Measured on the default mesh: +5.6 %; asserted 4–7
    # %.
    ratio = rocking(interface="bonded") / rocking()
    assert abs(ratio - 1.055) <= 0.015, ratio


def test_vertical_compliance_grows_with_log_of_domain_size():
    # Reference: Flamant: d(1/K_v)/d ln L = (1 − ν)/(π G). Boxes 5B, 10B, 20B,
    # 40B (square), Q2 8 across: fitted slope −0.75 % from the closed form (asserted 2 %).
    sizes = np.array([5.0, 10.0, 20.0, 40.0])
    compliance = []
    for size in sizes:
        model = make_model(SOIL, B, ContinuumOptions(elements_across=8, domain_width=size,
                                                     domain_depth=size))
        compliance.append(1.0 / footing_stiffness(model).vertical)
    slope = np.polyfit(np.log(sizes), compliance, 1)[0]
    assert abs(slope / ((1 - NU) / (math.pi * G)) - 1.0) <= 0.02


def test_thin_layer_on_rigid_base_tends_to_oedometric_stiffness():
    # Reference: one-dimensional compression of a thin layer, K_v H/(E_oed B) → 1 as H/B → 0,
    # with an O(H/B) edge correction. Layers H = 0.1 and 0.05 m under B = 2 m: +1.46 %, +0.73 %;
    # linear extrapolation to H = 0 within 0.1 %, each within 0.3 H/B.
    e_oed = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))
    ratios = []
    for depth in (0.1, 0.05):
        soil = dataclasses.replace(SOIL, layer_depth=depth)
        model = make_model(soil, B, ContinuumOptions(elements_across=16))
        ratio = footing_stiffness(model).vertical * depth / (e_oed * B)
        assert 0.0 < ratio - 1.0 <= 0.3 * depth / B
        ratios.append(ratio)
    assert abs(2 * ratios[1] - ratios[0] - 1.0) <= 1e-3


def test_k0_stress_is_in_equilibrium_with_the_weight():
    # Reference: σ_yy = ρ g y, σ_xx = K0 σ_yy solves div σ + ρ g = 0 with a free surface and
    # roller sides; Q2 with 2×2 Gauss integrates both sides exactly on rectangles, so the
    # residual at u = 0 vanishes to round-off (1e-10 of the weight's nodal forces).
    model = make_model(SOIL, B, ContinuumOptions(elements_across=8))
    state = geostatic(model)
    R = model.respond(state.u, state.material, state.eigenstrain).residual
    free = np.concatenate((model.blocks.interior, model.blocks.contact))
    assert np.max(np.abs(R[free])) <= 1e-10 * np.max(np.abs(model.body_force))
    assert abs(model.k0 - NU / (1 - NU)) <= 1e-15  # elastic default
    stress = state.stress
    y = model.disc.qp_coordinates[1]
    assert np.max(np.abs(stress[1, 1] - 1.8 * 9.80665 * y)) <= 1e-9


def test_elastic_gravity_step_gives_k0_of_nu_over_one_minus_nu():
    # Reference: laterally confined elastic column, σ_xx = σ_zz = ν/(1 − ν) σ_yy and
    # σ_yy = ρ g y; two independent routes (K0 procedure, elastic gravity solve) agree to
    # 1e-8 of the largest stress.
    model = make_model(SOIL, B, ContinuumOptions(elements_across=8))
    solved, k0 = elastic_gravity_stress(model), k0_stress(model)
    assert np.max(np.abs(solved - k0)) <= 1e-8 * np.max(np.abs(k0))
