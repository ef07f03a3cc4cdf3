"""Unilateral contact of the rigid footing on elastic soil (upliftlab.continuum).

References:
- Winkler bed (compression-only springs): uplift starts at e = M/N = B/6.
- Elastic half-plane, rigid flat frictionless punch (Johnson, *Contact Mechanics*, 1985, §2.8
  and §5.2; derived here): under N and M the pressure is
  p(x) = (N/π + 2 M x/(π b²))/√(b² − x²), b = B/2, so the heel's edge coefficient vanishes and
  uplift starts at e = B/4, at θ_on = 2 N (1 − ν)/(π G B). After uplift the contact has one
  sharp edge (the toe) and one smooth end, p ∝ √((c − s)/s), whose resultant lies c/4 from the
  toe: c = 2B − 4e, and the rotation gives c/B = θ_on/θ, M/(N B) = 1/2 − θ_on/(4θ).
- Coulomb friction: once every node slips, H = μ N exactly.
- Mirror symmetry of the mesh, and path independence of a frictionless elastic contact.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import (OPEN, STICK, Control, follow, make_model, moment_pushover,
                                 rotation_pushover, uplift_onset)
from upliftlab.continuum import geostatic
from upliftlab.continuum.contact.footing import SLIP_NEGATIVE, SLIP_POSITIVE, separation_fraction
from upliftlab.scenes import ContinuumOptions, Soil

E, NU, B, N = 50e3, 0.3, 2.0, 171.39  # kPa, -, m, kN/m (the scene's FS_v = 3)
G = E / (2 * (1 + NU))
THETA_ON = 2 * N * (1 - NU) / (math.pi * G * B)  # half-plane uplift onset rotation
SOIL = Soil(youngs_modulus=E, poisson_ratio=NU, density=1.8, model="elastic")
RATIOS = np.array([0.25, 0.5, 1.5, 2.0, 3.0, 5.0, 10.0])  # θ / θ_on


def model_for(n=16, interface="frictionless", friction=0.0, **kw):
    soil = dataclasses.replace(SOIL, interface=interface, interface_friction=friction)
    return make_model(soil, B, ContinuumOptions(elements_across=n, **kw))


@pytest.fixture(scope="module")
def pushovers():
    """Rotation pushovers at constant N on the default box, 8 and 16 across B."""
    return {n: rotation_pushover(model_for(n), N, RATIOS * THETA_ON) for n in (8, 16)}


def test_full_contact_then_uplift_with_exact_complementarity(pushovers):
    # Reference: contact conditions P ≥ 0, g ≥ 0, P g = 0 (solved exactly, no penalty):
    # pressures ≥ −1e-9 of the largest, gaps ≥ −1e-12 m, and no node both open and loaded.
    path = pushovers[16]
    assert (path.status[:2] != OPEN).all()  # θ < θ_on: full contact
    assert (path.status[2:] == OPEN).any(axis=1).all()  # θ > θ_on: lift-off
    pmax = path.pressure.max()
    assert path.pressure.min() >= -1e-9 * pmax
    assert path.gap.min() >= -1e-12
    open_ = path.status == OPEN
    assert np.max(np.abs(path.pressure[open_])) <= 1e-9 * pmax
    assert np.max(np.abs(path.gap[~open_])) <= 1e-12
    assert np.allclose(path.N, N, rtol=1e-10)


def test_uplift_onset_eccentricity_is_a_quarter_width_not_a_sixth(pushovers):
    # Reference: half-plane onset e = B/4 (module docstring); Winkler's is B/6 (compression-only
    # springs). Measured on the 10B box: e/B = 0.24929 (8 across), 0.24910 (16), 0.24906 (32); the
    # −0.36 % from 1/4 is the box (20B: 0.24993, 40B: 0.25012). Asserted within 1 % of B/4,
    # converging (|Δe| from 8 to 16 below 0.1 %), and 49 % above Winkler's B/6.
    e8, e16 = (uplift_onset(pushovers[n]).e / B for n in (8, 16))
    assert abs(e16 / 0.25 - 1.0) <= 0.01
    assert abs(e16 - e8) <= 1e-3 * 0.25
    assert e16 / (1.0 / 6.0) - 1.0 >= 0.45
    onset = uplift_onset(pushovers[16])
    assert abs(onset.theta / THETA_ON - 1.0) <= 0.01


def test_contact_length_follows_the_half_plane_law_and_converges(pushovers):
    # Reference: c/B = θ_on/θ after uplift (module docstring), θ_on measured on the same mesh.
    # The contact length ends at the separation point interpolated between the last closed
    # and the first open node: the largest error is 0.024 B (8 across) and 0.019 B (16)
    # (the midpoint rule gave 0.052 and 0.035 B), asserted within one node spacing (B/(2n)
    # for Q2) and falling with refinement.
    errors = {}
    for n, path in pushovers.items():
        theta_on = uplift_onset(path).theta
        expected = np.minimum(1.0, theta_on / path.theta)
        errors[n] = np.max(np.abs(path.contact_fraction - expected))
        assert errors[n] <= 1.0 / (2 * n)
    assert errors[16] < errors[8]


@pytest.mark.parametrize("n", [8, 16])
def test_contact_length_is_measured_where_the_contact_ends(n):
    # Reference: the half-plane's contact length after onset, L_c = 4(B/2 − e) with e = M/N
    # (module docstring), at the FE's own eccentricity, at every one of 24 steps from just
    # past onset to 10 θ_on. Measured: largest error 0.78 node spacings (8 across), 0.67 (16)
    # and 0.69 (32); the midpoint rule it replaces: 0.75, 1.17 and 1.19 spacings (rms 0.54,
    # 0.57, 0.63 against 0.46, 0.36, 0.32 now). Asserted: within one node spacing B/(2n) at
    # every step, and a smaller rms error than the midpoint rule's. On 8 across the largest error
    # is at 10 θ_on, where the patch is three elements long and both rules are off by the
    # FE's own O(h) error of the patch.
    ratios = np.concatenate(([0.5], np.linspace(1.05, 10.0, 24)))
    path = rotation_pushover(model_for(n), N, ratios * THETA_ON)
    e = path.M / path.N
    after = e > B / 4
    assert after.sum() >= 23
    error = (path.contact_length - 4 * (B / 2 - e))[after] / (B / (2 * n))
    assert np.max(np.abs(error)) <= 1.0, error
    midpoint = np.array([model_for(n).footing.contact_length(st != OPEN)
                         for st in path.status])
    old = (midpoint - 4 * (B / 2 - e))[after] / (B / (2 * n))
    assert np.sqrt(np.mean(error ** 2)) < np.sqrt(np.mean(old ** 2))


def _patches_by_walking(footing, closed, pressure, gap):
    """The reference for :meth:`Footing.contact_lengths`: walk one row node by node, open a
    patch at a closed node after an open one (or at the left edge) and close it at a closed
    node before an open one (or at the right edge), each inner end placed by the scalar
    separation fraction of its own pair of nodes (without ``pressure``: half-way)."""
    x, n, total, left = footing.x, footing.nodes, 0.0, None

    def end(i, j):
        if pressure is None:
            return 0.5 * (x[i] + x[j])  # the midpoint rule
        t = separation_fraction(np.array([pressure[i]]), np.array([gap[j]]),
                                abs(x[j] - x[i]), footing.modulus)[0]
        return x[i] + t * (x[j] - x[i])

    for i in range(n):
        if closed[i] and (i == 0 or not closed[i - 1]):
            left = x[0] if i == 0 else end(i, i - 1)
        if closed[i] and (i == n - 1 or not closed[i + 1]):
            total += (x[-1] if i == n - 1 else end(i, i + 1)) - left
    return total


def test_contact_lengths_of_many_rows_are_each_rows_own_patches():
    # Reference: the node-by-node walk above, one row at a time, on 400 random rows of open
    # and closed nodes (several patches a row, patches at both edges, rows all open or all
    # closed) with random pressures and gaps. Asserted to 1e-12 of B.
    footing = model_for(8).footing
    rng = np.random.default_rng(35)
    closed = rng.random((400, footing.nodes)) < rng.random((400, 1))
    closed[0], closed[1] = False, True
    pressure = rng.random(closed.shape) * 50.0
    gap = rng.random(closed.shape) * 1e-3
    lengths = footing.contact_lengths(closed, pressure, gap)
    walked = [_patches_by_walking(footing, c, p, g) for c, p, g in zip(closed, pressure, gap)]
    assert np.max(np.abs(lengths - walked)) <= 1e-12 * B
    assert lengths[0] == 0.0 and lengths[1] == pytest.approx(B, abs=1e-12)
    assert footing.contact_length(closed[7], pressure[7], gap[7]) == lengths[7]
    midpoint = footing.contact_lengths(closed)
    walked = [_patches_by_walking(footing, c, None, None) for c in closed]
    assert np.max(np.abs(midpoint - walked)) <= 1e-12 * B


def test_separation_point_inverts_the_half_plane_edge_asymptotics():
    # Reference: p = α√d inside and g = 4α e^{3/2}/(3E*) outside a smooth separation point
    # (footing.separation_fraction): nodal values built from a known end t recover it to the
    # bisection's precision; p = 0 puts the end at the closed node, g = 0 at the open one.
    E_star, h, alpha = E / (1 - NU ** 2), 0.1, 37.0
    t = np.array([0.01, 0.2, 0.5, 0.8, 0.99])
    p = alpha * np.sqrt(t * h)
    g = 4 * alpha * ((1 - t) * h) ** 1.5 / (3 * E_star)
    assert np.allclose(separation_fraction(p, g, h, E_star), t, atol=1e-12)
    assert separation_fraction(np.array([0.0]), np.array([1e-3]), h, E_star)[0] == 0.0
    assert separation_fraction(np.array([5.0]), np.array([0.0]), h, E_star)[0] == 1.0


def test_moment_after_uplift_matches_the_half_plane(pushovers):
    # Reference: M/(N B) = 1/2 − θ_on/(4θ) after uplift, M = K_r θ before (module docstring).
    # Measured (16 across, θ_on from the same mesh): within 0.34 %; asserted 0.5 %.
    path = pushovers[16]
    theta_on = uplift_onset(path).theta
    after = path.theta > theta_on
    expected = N * B * (0.5 - theta_on / (4 * path.theta[after]))
    assert np.max(np.abs(path.M[after] / expected - 1.0)) <= 0.005
    assert np.all(np.diff(path.M) > 0.0) and np.all(np.diff(path.settlement[2:]) < 0.0)


def test_cyclic_rotation_is_symmetric_and_path_independent():
    # Reference: a frictionless elastic contact has one equilibrium per θ (path independence)
    # and the mesh is mirror symmetric: M(−θ) = −M(θ), equal settlement, and a revisited θ
    # gives the same M, to 1e-9 relative.
    model = model_for(8)
    amplitude = 3.0 * THETA_ON
    history = amplitude * np.array([0.5, 1.0, 0.0, -0.5, -1.0, 0.0, 0.5, 1.0])
    path = rotation_pushover(model, N, history)
    assert abs(path.M[1] + path.M[4]) <= 1e-9 * abs(path.M[1])
    assert abs(path.M[0] + path.M[3]) <= 1e-9 * abs(path.M[0])
    assert abs(path.settlement[1] - path.settlement[4]) <= 1e-9 * path.settlement[1]
    assert np.allclose(path.M[6:], path.M[:2], rtol=1e-9)
    assert np.allclose(path.pressure[4], path.pressure[1][::-1], rtol=1e-7,
                       atol=1e-9 * path.pressure.max())
    assert abs(path.M[2]) <= 1e-9 * abs(path.M[1])


def test_moment_control_retraces_rotation_control():
    # Reference: two independent controls of one problem: prescribing the moments that a
    # rotation pushover found gives back its rotations (elastic, below the capacity), 1e-8.
    model = model_for(8)
    rotations = THETA_ON * np.array([0.5, 2.0, 4.0])
    by_rotation = rotation_pushover(model, N, rotations)
    by_moment = moment_pushover(model, N, by_rotation.M)
    assert np.allclose(by_moment.theta, rotations, rtol=1e-8)
    assert np.allclose(by_moment.contact_length, by_rotation.contact_length)


def test_coulomb_footing_slides_at_mu_times_n():
    # Reference: Coulomb's law, |T_i| ≤ μ P_i with equality when slipping: pushing the footing
    # sideways at constant N, H rises, never exceeds μN, and equals μN (1e-9) once every node
    # slips. Under N alone the centre sticks and the edges slip symmetrically (the soil's
    # Poisson spreading under a rough flat punch, cf. Spence 1975), with antisymmetric T.
    mu = 0.3
    model = model_for(8, interface="coulomb", friction=mu)
    state = geostatic(model)
    controls = [Control((False, False, True), (0.0, -N * k / 2, 0.0)) for k in (1, 2)]
    controls += [Control((True, False, True), (u, -N, 0.0)) for u in (1e-4, 1e-3, 2e-2)]
    states = follow(model, state, controls)
    H = np.array([s.H for s in states[2:]])
    assert np.all(H <= mu * N * (1 + 1e-12)) and np.all(np.diff(H) > 0.0)
    centred = states[1]
    status, n = centred.status, model.footing.nodes
    assert status[n // 2] == STICK and np.array_equal(status == SLIP_POSITIVE,
                                                      (status == SLIP_NEGATIVE)[::-1])
    T, P = centred.force[n:], -centred.force[:n]
    assert np.max(np.abs(T + T[::-1])) <= 1e-9 * N
    assert np.all(np.abs(T) <= mu * P + 1e-9 * N)
    final = states[-1].status
    assert np.isin(final, (SLIP_POSITIVE, SLIP_NEGATIVE)).all()
    assert abs(H[-1] / (mu * N) - 1.0) <= 1e-9


def test_frictionless_footing_refuses_a_horizontal_force():
    # Reference: the project's input rule: a frictionless base has no horizontal stiffness.
    model = model_for(4)
    with pytest.raises(InputError, match="frictionless interface"):
        follow(model, geostatic(model), [Control((False, False, True), (10.0, -N, 0.0))])


@pytest.mark.slow
def test_uplift_refinement_study():
    # Reference: as the fast tests. 8, 16, 32, 64 across B on the 10B box (5 184 … 313 584
    # DOFs): the onset e/B = 0.249293, 0.249099, 0.249056, 0.249015 (within 0.3 % of 1/4, the
    # box's share; spread 0.12 %, asserted 0.2 %); the largest contact-length error against
    # θ_on/θ is 0.024, 0.019, 0.0097, 0.0038 B (the contact ends at the interpolated separation
    # point; the midpoint rule gave 0.055, 0.035, 0.018, 0.0076 B), a fitted rate 0.90
    # (asserted 0.6–1.6); M after
    # uplift within 0.35 % of the half-plane law from 16 across (measured 0.34, 0.28, 0.29 %:
    # the box's share).
    ns = np.array([8, 16, 32, 64])
    onsets, errors = [], []
    for n in ns:
        path = rotation_pushover(model_for(int(n)), N, RATIOS * THETA_ON)
        onset = uplift_onset(path)
        onsets.append(onset.e / B)
        errors.append(np.max(np.abs(path.contact_fraction
                                    - np.minimum(1.0, onset.theta / path.theta))))
        after = path.theta > onset.theta
        expected = N * B * (0.5 - onset.theta / (4 * path.theta[after]))
        if n >= 16:
            assert np.max(np.abs(path.M[after] / expected - 1.0)) <= 0.0035
    onsets = np.array(onsets)
    assert np.all(np.abs(onsets / 0.25 - 1.0) <= 0.005) and np.ptp(onsets) <= 0.002 * 0.25
    rate = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    assert 0.6 <= rate <= 1.6, (errors, rate)
