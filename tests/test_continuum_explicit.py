"""The explicit route of the continuum dynamics (upliftlab.continuum.dynamics.explicit and its
kernels).

References, one per test:
- the compiled return maps and internal force: the vectorised return maps of
  continuum/materials/ and the sparse Bᵀσ assembly of continuum/assembly.py (independent
  implementations of the same formulas);
- the lumped mass: the soil's mass ρ × area per component (closed form);
- the stable step: the largest eigenvalue of M^{-1/2} K M^{-1/2} by dense LAPACK (an
  independent algorithm to the Lanczos iteration of the code) and the stability theory of
  central differences, dt ω_max ≤ 2 (Belytschko, Liu, Moran & Elkhodary, *Nonlinear Finite
  Elements for Continua and Structures*, 2014, §6.3);
- the contact step: enumeration of every active set of a small complementarity problem, and
  the implicit route's solver (continuum/contact/footing.py ``solve_contact``) for friction;
- the time history: the implicit route (HHT-α, Newton) at a quarter of its default step on
  the same mesh; energy conservation of an undamped elastic system;
- the compiled time loop: the Python loop of the same steps.
"""

from __future__ import annotations

import itertools

import types

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import OPEN, build_model
from upliftlab.continuum import geostatic
from upliftlab.continuum.dynamics import run as dyn
from upliftlab.continuum.dynamics import ground
from upliftlab.continuum.dynamics.iteration_matrix import elastic_plane_tangent
from upliftlab.continuum.dynamics import explicit as ex
from upliftlab.continuum.dynamics import explicit_step
from upliftlab.continuum.contact.step import normal_forces, tangential_step
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.continuum.contact.footing import (ContactError, ContactProblem, Footing, Interface,
                                                 solve_contact)
from upliftlab.continuum.materials import Elastic, Tresca, VonMises, point_return
from upliftlab.continuum.statics.newton import ConvergenceError
from upliftlab.continuum.dynamics.run_control import BearingFailure
from upliftlab.motions import free_vibration
from upliftlab.scenes import load_scene

SCENE = "strip_footing_clay"
COARSE = ["continuum.elements_across=4"]  # Q2, 10B x 10B, 1296 DOFs


# ---------------------------------------------------------------------------------------------
# Kernels
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("material", [Tresca(50e3, 0.3, 50.0),
                                      VonMises(50e3, 0.3, 50.0, 2000.0), Elastic(50e3, 0.3)])
def test_compiled_return_maps_match_the_vectorised_ones(material):
    # Reference: the model's vectorised return map (continuum/materials/<model>.py) at 3000
    # random plane-strain points, from a plastic history (a first update at 70 % of the
    # strain), so that every return region is hit.
    rng = np.random.default_rng(7)
    n = 3000
    e = rng.normal(scale=3e-3, size=(4, n))
    strain = np.zeros((3, 3, n))
    strain[0, 0], strain[1, 1], strain[2, 2] = e[0], e[1], 0.3 * e[2]
    strain[0, 1] = strain[1, 0] = e[3]
    _, _, old = material(0.7 * strain, material.initial_state(n))
    stress, _, new = material(strain, old)
    constants = material.kernel_constants()
    p = old.plastic_strain
    got = np.array([point_return(
        constants, strain[0, 0, i], strain[1, 1, i], strain[2, 2, i], strain[0, 1, i],
        p[0, 0, i], p[1, 1, i], p[2, 2, i], p[0, 1, i], old.equivalent_plastic_strain[i])
        for i in range(n)])
    ref_stress = np.stack([stress[0, 0], stress[1, 1], stress[2, 2], stress[0, 1]], axis=1)
    dp = new.plastic_strain - p
    ref_plastic = np.stack([dp[0, 0], dp[1, 1], dp[2, 2], dp[0, 1]], axis=1)
    scale = np.abs(ref_stress).max()
    assert np.abs(got[:, :4] - ref_stress).max() <= 1e-12 * scale
    assert np.abs(got[:, 4:8] - ref_plastic).max() <= 1e-12
    ref_bar = new.equivalent_plastic_strain - old.equivalent_plastic_strain
    assert np.abs(got[:, 8] - ref_bar).max() <= 1e-12
    if not material.linear:
        assert np.count_nonzero(new.region) > n // 2  # the maps were really exercised


def test_compiled_internal_force_matches_the_assembly():
    # Reference: ContinuumModel.respond (vectorised Tresca, sparse Bᵀσ) from the geostatic
    # state at a random displacement that yields most points.
    scene = load_scene(SCENE, overrides=COARSE)
    model = build_model(scene)
    state = geostatic(model)
    u = np.random.default_rng(3).normal(scale=2e-3, size=model.disc.ndofs)
    response = model.respond(u, state.material, state.eigenstrain)
    force = ex.SoilForce(model, state)
    got = force(u)
    ref = response.residual + model.body_force
    assert np.abs(got - ref).max() <= 1e-12 * np.abs(ref).max()
    assert np.mean(response.material.region > 0) > 0.5
    assert np.abs(force.material.equivalent_plastic_strain
                  - response.material.equivalent_plastic_strain).max() <= 1e-15


# ---------------------------------------------------------------------------------------------
# Mass and stable step
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("element", ["Q2", "Q1", "P1"])
def test_lumped_mass_is_positive_and_sums_to_the_soil_mass(element):
    # Reference: the soil's mass per component, ρ × (10B × 10B) = 1.8 × 400 t/m.
    scene = load_scene(SCENE, overrides=COARSE + [f"continuum.element={element}"])
    model = build_model(scene)
    mass = ex.lumped_mass(model)
    assert mass.min() > 0.0
    assert mass.sum() == pytest.approx(2 * 1.8 * 20.0 * 20.0, rel=1e-12)


def test_a_basis_without_a_positive_lumped_mass_is_refused(monkeypatch):
    # P2's vertex functions integrate to zero: no diagonal mass, refused before any work.
    scene = load_scene(SCENE, overrides=COARSE + ["continuum.element=P2"])
    model = build_model(scene)
    assert ex.lumped_mass(model).min() <= 1e-12 * ex.lumped_mass(model).max()
    monkeypatch.setattr(ground, "gravity_state", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(InputError, match="continuum.element = 'P2'"):
        run_dynamic(model, scene, scene.build_motion(), DynamicOptions(method="explicit"))


def test_stable_step_is_twice_the_inverse_of_the_largest_frequency():
    # Reference: dense LAPACK eigenvalues of M^{-1/2} K M^{-1/2} on the free DOFs.
    from upliftlab.continuum import assembly

    scene = load_scene(SCENE, overrides=["continuum.elements_across=2"])
    model = build_model(scene)
    mass = ex.lumped_mass(model)
    free = np.setdiff1d(np.arange(model.disc.ndofs), dyn.dynamic_fixed(model, "rigid",
                                                                     "rollers"))
    critical, omega = ex.critical_step(model, mass, free)
    K = assembly.stiffness(model.disc, elastic_plane_tangent(model))[free][:, free].toarray()
    scale = 1.0 / np.sqrt(mass[free])
    top = np.linalg.eigvalsh(scale[:, None] * K * scale[None, :]).max()
    assert omega == pytest.approx(np.sqrt(top), rel=1e-9)
    assert critical == pytest.approx(2.0 / np.sqrt(top), rel=1e-9)


def test_a_step_beyond_the_stable_limit_is_refused_with_the_limit(monkeypatch):
    scene = load_scene(SCENE, overrides=COARSE)
    model = build_model(scene)
    mass = ex.lumped_mass(model)
    free = np.setdiff1d(np.arange(model.disc.ndofs), dyn.dynamic_fixed(model, "rigid",
                                                                     "rollers"))
    critical, _ = ex.critical_step(model, mass, free)
    limit = ex.STABILITY_FRACTION * critical
    monkeypatch.setattr(ground, "gravity_state", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(InputError) as info:
        run_dynamic(model, scene, scene.build_motion(),
                    DynamicOptions(method="explicit", dt=1.001 * limit))
    text = str(info.value)
    assert "DynamicOptions.dt" in text and f"valid range is (0, {limit:.4g}] s" in text
    assert f"2/ω_max = {critical:.4g} s" in text


def _free_rocking(velocity=0.05, duration=0.3):
    """Free vibration of the clay scene's structure on elastic, bonded, undamped soil (linear,
    in full contact), coarse mesh."""
    scene = load_scene(SCENE, overrides=COARSE + ["soil.model=elastic", "soil.interface=bonded",
                                                  "structure.damping_ratio=0.0"])
    return scene, build_model(scene), free_vibration(duration, 0.005, velocity=velocity)


@pytest.mark.parametrize("fraction, stable", [(0.98, True), (1.02, False)])
def test_central_differences_are_stable_up_to_two_over_omega_max(fraction, stable,
                                                                  monkeypatch):
    # Reference: central differences are stable for dt ω_max ≤ 2 and grow without bound beyond
    # it (the amplification factor of the highest mode leaves the unit circle). The step is set
    # by allowing that fraction of the limit; a diverged run fails naming the time and the
    # step's share of the limit.
    scene, model, motion = _free_rocking()
    monkeypatch.setattr(explicit_step, "STABILITY_FRACTION", fraction)
    mass = ex.lumped_mass(model)
    free = np.setdiff1d(np.arange(model.disc.ndofs), dyn.dynamic_fixed(model, "rigid",
                                                                     "rollers"))
    critical, _ = ex.critical_step(model, mass, free)
    options = DynamicOptions(method="explicit", dt=fraction * critical, snapshots=0)
    if stable:
        result = run_dynamic(model, scene, motion, options)
        assert result.energy_balance_error < 1e-3
        assert result.metadata["max_plastic_strain"] == 0.0  # elastic soil
    else:
        with pytest.raises(ConvergenceError, match="diverged") as info:
            run_dynamic(model, scene, motion, options)
        assert f"dt = {fraction * critical:.4g} s is {fraction:.3g} of the stability limit" \
            in str(info.value)


@pytest.mark.parametrize("growth, settlement, bearing", [(1.0001, 0.35, True),
                                                         (1.49, 0.35, False),
                                                         (1.0001, 0.15, False)])
def test_a_displacement_beyond_the_footing_width_is_reported_with_where_and_how_fast(
        growth, settlement, bearing):
    # Reference: the hand-made state. A soil DOF moved 1.5 B (beyond the check's one footing
    # width) after growing by ``growth`` over the last step: 1.0001 is a footing punching into
    # failing soil (found on the Winkler map's sand at FS_v = 2: 2 m at the footing's edge
    # after 11 s of slow growth, the footing settled 0.35 m = 0.17 B), 1.49 the highest
    # mode's amplification per step just beyond the stability limit (|λ| of
    # λ² − (2 − (ω dt)²) λ + 1 = 0 at ω dt = 2.04). The message names the DOF's place, the
    # growth and the footing's state, before the step's share of the stability limit. Slow
    # growth with the footing settled by 0.1 B or more (B = 2 m here: 0.35 m is 0.175 B,
    # 0.15 m is 0.075 B) is a bearing failure; anything else stays a divergence.
    scene, model, _ = _free_rocking()
    assert model.width == 2.0
    run = object.__new__(ex._Explicit)
    run.model, run.settings = model, types.SimpleNamespace(dt=1e-3, critical=2e-3)
    j = 17
    u = np.zeros(model.disc.ndofs)
    u[j] = -1.5 * model.width
    footing = np.array([0.0, -settlement, -0.037])
    with pytest.raises(ConvergenceError) as info:
        with run.diverging(40, 44, u, u / growth, footing):
            pass
    assert isinstance(info.value, BearingFailure) is bearing
    text = str(info.value)
    x, y = model.disc.basis.doflocs[:, j]
    assert f"a displacement of {1.5 * model.width:.3g}" in text
    assert f"at x = {x:.3g}, y = {y:.3g}, grown ×{growth:.6g} over the last step" in text
    assert f"the footing at v = {-settlement:.3g}, θ = -0.037 rad" in text
    assert "dt = 0.001 s is 0.5 of the stability limit" in text
    if bearing:
        assert text.startswith("the soil failed in bearing in explicit steps 40…44")
        assert ("the footing had settled 0.35 (0.175 B, at least the 0.1 B of a conventional "
                "failure) and tilted -0.037 rad; a displacement") in text
        assert (info.value.time, info.value.settlement, info.value.rotation) == (
            pytest.approx(0.044), pytest.approx(0.35), pytest.approx(-0.037))
    else:
        assert text.startswith("explicit steps 40…44 (t = 0.04…0.044 s) diverged")
    u[j] = 0.9 * model.width  # within a footing width: no error
    with run.diverging(40, 44, u, u / growth, footing):
        pass


# ---------------------------------------------------------------------------------------------
# The contact step
# ---------------------------------------------------------------------------------------------


def test_normal_forces_solve_the_complementarity_problem():
    # Reference: enumeration of all 2^n active sets of g = g* + W P, W = diag(d) + L K⁻¹ Lᵀ:
    # exactly one gives P >= 0 and g >= 0 (W is positive definite).
    rng = np.random.default_rng(11)
    n = 7
    x = np.linspace(-1.0, 1.0, n)
    L = np.column_stack((np.ones(n), -x))
    for _ in range(50):
        d = rng.uniform(0.5, 2.0, n)
        K = np.diag(rng.uniform(0.2, 3.0, 2))
        gstar = rng.normal(size=n)
        W = np.diag(d) + L @ np.linalg.solve(K, L.T)
        found = []
        for closed in itertools.product((False, True), repeat=n):
            c = np.array(closed)
            P = np.zeros(n)
            if c.any():
                P[c] = np.linalg.solve(W[np.ix_(c, c)], -gstar[c])
            g = gstar + W @ P
            if P.min() >= -1e-12 and g.min() >= -1e-12:
                found.append(P)
        assert len(found) == 1
        P, g, _ = normal_forces(gstar, d, np.ascontiguousarray(L), K, np.zeros(n, dtype=bool))
        assert np.abs(P - found[0]).max() <= 1e-12 * max(1.0, np.abs(found[0]).max())
        assert np.abs(P * g).max() <= 1e-12 and g.min() >= -1e-12 and P.min() >= 0.0


@pytest.mark.parametrize("kind, mu", [("bonded", 0.0), ("coulomb", 0.3)])
def test_tangential_step_matches_the_implicit_contact_solver(kind, mu):
    # Reference: footing.solve_contact on the same diagonal soil, random states (the few it
    # cannot settle in its 100 sweeps are not compared; at least 90 of 100 are).
    rng = np.random.default_rng(5)
    n = 9
    x = np.linspace(-1.0, 1.0, n)
    interface = Interface(kind, mu)
    footing = Footing(x=x, ux=np.arange(n), uy=np.arange(n, 2 * n), weight=np.full(n, 2 / n),
                      width=2.0, interface=interface)
    compared = 0
    for _ in range(100):
        s = rng.uniform(1e3, 5e3, 2 * n)
        uc = rng.normal(scale=1e-3, size=2 * n)
        q = np.array([0.0, rng.normal(scale=1e-3), rng.normal(scale=1e-3)])
        slip0 = rng.normal(scale=1e-4, size=n)
        Kq = np.diag(rng.uniform(1e3, 1e4, 3))
        rq = rng.normal(scale=10.0, size=3) + np.array([0.0, 30.0, 0.0])
        free = np.zeros(3, dtype=bool)
        problem = ContactProblem(footing, np.diag(s), np.zeros(2 * n), uc, q, slip0, free,
                                 np.zeros(3), Kq, rq)
        try:
            ref = solve_contact(problem, np.full(n, OPEN, dtype=np.int8))
        except ContactError:  # the reference's sets cycled past its 100 sweeps: not compared
            continue
        status = np.full(n, OPEN, dtype=np.int8)
        duc, dq, force, _ = tangential_step(s, uc, q, slip0, x, free, np.zeros(3), Kq, rq,
                                            interface.mu, 2.0, status)
        assert np.array_equal(status, ref.status)
        assert np.abs(force - ref.force).max() <= 1e-12 * np.abs(ref.force).max()
        assert np.abs(dq - ref.dq).max() <= 1e-12 * np.abs(ref.dq).max()
        compared += 1
    assert compared >= 90


# ---------------------------------------------------------------------------------------------
# Time histories
# ---------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def pulse():
    """The clay scene (Tresca, frictionless) under its Ricker pulse, coarse mesh, 1.5 s:
    explicit (every step recorded) and implicit at a quarter of its default step."""
    scene = load_scene(SCENE, overrides=COARSE + ["motion.duration=1.5"])
    model, motion = build_model(scene), scene.build_motion()
    explicit = run_dynamic(model, scene, motion, DynamicOptions(method="explicit", snapshots=3,
                                                                record_every=1))
    implicit = run_dynamic(model, scene, motion, DynamicOptions(
        method="implicit", snapshots=0, dt=0.25 * dyn.time_step_limit(model)))
    return model, explicit, implicit


def test_the_largest_plastic_strain_of_a_run_is_recorded(pulse):
    # Reference: the snapshot at the last step, whose element averages of ε̄p bound the
    # largest quadrature-point value: avg ≤ max ≤ 4 avg over a 2×2 rule of non-negative values
    # (ε̄p only accumulates, so the last step's largest value is the run's). Both routes.
    model, explicit, implicit = pulse
    last = float(np.max(explicit.plastic_strain[-1]))
    assert explicit.snapshot_step[-1] == explicit.time.size - 1 and last > 0.0
    peak = explicit.metadata["max_plastic_strain"]
    assert last <= peak <= 4.0 * last
    assert implicit.metadata["max_plastic_strain"] > 0.0


def test_explicit_agrees_with_implicit_on_a_pulse(pulse):
    # Reference: the implicit route (HHT-α, Newton to rtol 1e-5) at a quarter of its default
    # step on the same mesh. Measured: peak θ −0.06 %, θ history within 0.4 % and v within
    # 0.3 % of their peaks (the mesh's lumped against consistent mass and the schemes'
    # different high-frequency damping); required 0.5 %, 1 % and 1 %.
    model, explicit, implicit = pulse
    assert explicit.contact_length.min() < 0.9 * model.width  # the footing lifts off
    for k, peak_tol, history_tol in ((2, 0.005, 0.01), (1, 0.005, 0.01)):
        a, b = explicit.footing[:, k], implicit.footing[:, k]
        peak = np.abs(b).max()
        on_grid = np.interp(implicit.time, explicit.time, a)
        print(f"component {k}: peak {np.abs(a).max() / peak - 1:+.3%}, history "
              f"{np.abs(on_grid - b).max() / peak:.3%}")
        assert np.abs(a).max() == pytest.approx(peak, rel=peak_tol)
        assert np.abs(on_grid - b).max() <= history_tol * peak


def test_contact_complementarity_holds_at_every_step(pulse):
    # Reference: the contact conditions P >= 0, g >= 0, P g = 0 at each node, each step. The
    # pressure of row n is that of step n (in the equation of motion at t_n), which closes the
    # gaps at t_{n+1}: it pairs with the gap of row n + 1 (every step is recorded here).
    model, explicit, _ = pulse
    P, g = explicit.pressure, explicit.gap
    scale_p, scale_g = np.abs(P).max(), model.width
    assert P.min() >= -1e-9 * scale_p
    assert g.min() >= -1e-9 * scale_g
    assert np.abs(P[1:-1] * g[2:]).max() <= 1e-9 * scale_p * scale_g
    assert (explicit.status == OPEN).any() and (explicit.status != OPEN).any()
    # the status of a row is that of its pressure: a closed node pushes, an open one does not
    closed = explicit.status[1:] != OPEN
    assert np.all(P[1:][~closed] == 0.0)


def _unbalanced(model, result) -> np.ndarray:
    """The largest residual of the footing's and story's equation of motion over the rows of
    ``result`` (every step recorded), per free component of (u, v, θ, s), relative to the peak
    of its reaction (the story: of its ground load)
    (:func:`test_recorded_reactions_balance_the_recorded_motion_of_footing_and_story`)."""
    from upliftlab.continuum.dynamics.superstructure import structure_matrices

    z = structure_matrices(model.scene)
    dt = result.metadata["dt"]
    assert result.metadata["record_every"] == 1
    Z = np.column_stack([result.footing, result.structure_u])
    half = np.diff(Z, axis=0) / dt
    n = np.arange(1, Z.shape[0] - 1)
    inertia = (half[n] - half[n - 1]) @ z.M.T / dt + 0.5 * (half[n] + half[n - 1]) @ z.C.T
    loads = np.outer(result.ground_acceleration[n], -(z.M @ z.r)) + z.gravity
    residual = inertia + Z[n] @ z.K.T - loads
    R = np.column_stack([result.H, -result.N, result.M])
    residual[:, :3] += R[n]
    peaks = np.append(np.abs(R[1:]).max(axis=0), np.abs(loads[:, 0]).max())
    # a frictionless footing's u follows the base: its horizontal force is not a contact one
    free = [model.footing.interface.tangential, True, True, True]
    return (np.abs(residual).max(axis=0) / peaks)[free]


def test_recorded_reactions_balance_the_recorded_motion_of_footing_and_story(pulse):
    # Reference: Newton's second law of the rigid footing and the story (closed form) on the
    # recorded rows, every step: M (v₊ − v₋)/dt + C (v₊ + v₋)/2 + K z_n = F_n − [R_n; 0] with
    # v± the half-step velocities from z_{n±1}, z = (u, v, θ, s), F_n the weight and the
    # ground's inertia load at t_n, R_n = (H, −N, M) of row n: the reactions of a row are those
    # in equilibrium with the motion of that row. Required to 1e-9 of each reaction's peak
    # (round-off; measured 3e-13 (N), 8e-12 (M)); measured before issue 37's fix (the
    # reactions one step late) 1.2 % (N) and 2.2 % (M) on this frictionless run (Tresca).
    model, explicit, _ = pulse
    off = _unbalanced(model, explicit)
    print("residual / peak (v, θ, s):", off)
    assert np.all(off <= 1e-9)


def test_recorded_reactions_of_a_bonded_footing_balance_its_motion():
    # Reference: as above, with the horizontal reaction H of a bonded footing (its u is free):
    # Newton's second law on the recorded rows, to 1e-9 of each reaction's peak. Measured
    # before issue 37's fix (the reactions one step late): 5.1 % (H), 1.7 % (N), 2.2 % (M),
    # the compiled and the Python loop alike.
    scene = load_scene(SCENE, overrides=COARSE + ["motion.duration=0.8", "soil.interface=bonded",
                                                  "soil.model=elastic"])
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(method="explicit", snapshots=0, record_every=1))
    off = _unbalanced(model, result)
    print("residual / peak (u, v, θ, s):", off)
    assert off.size == 4 and np.all(off <= 1e-9)


def test_the_explicit_moment_is_not_shifted_against_the_implicit_one(pulse):
    # Reference: the implicit route (HHT-α, Newton, contact at the end of each step: its M_n
    # is in equilibrium with θ_n) on the same mesh, an independent algorithm. The explicit
    # M(t) shifted by L of its steps, M(t + L dt), against the implicit M(t) on the implicit
    # rows: the RMS difference is least at L = 0 and within 1 % of the peak. Measured before
    # issue 37's fix: least at L = +1 (0.55 % of the peak there, 0.71 % at L = 0; the
    # explicit route recorded its reactions one step late).
    _, explicit, implicit = pulse
    dt = explicit.metadata["dt"]
    peak = np.abs(implicit.M).max()
    rms = {L: float(np.sqrt(np.mean((np.interp(implicit.time, explicit.time - L * dt,
                                                 explicit.M) - implicit.M) ** 2))) / peak
           for L in range(-3, 4)}
    print("RMS of M(t + L dt) − M_implicit(t) / peak:", rms)
    assert min(rms, key=rms.get) == 0
    assert rms[0] <= 0.01


def test_energy_balance_closes_on_a_plastic_pulse(pulse):
    # Reference: conservation; central differences close the account to O(dt²) (measured
    # 7.8e-5 of the input on this pulse). The contact forces only take energy out (a landing
    # node stops with the footing) and the soil's plastic work is in the strain term.
    model, explicit, _ = pulse
    e = explicit.energy
    assert explicit.energy_balance_error < 1e-3
    assert e[-1, 4] > 0.0 and e[:, 4].min() >= -1e-6 * e[:, 3].max()
    assert e[:, 1].max() > 0.1 * e[:, 3].max()  # energy really went into the soil


def test_energy_is_conserved_by_an_undamped_elastic_system():
    # Reference: the undamped linear system conserves its energy exactly; central differences
    # to O((ω dt)²) of the modes carrying it (measured 5.7e-5 of the initial kinetic energy).
    scene, model, motion = _free_rocking(duration=0.6)
    result = run_dynamic(model, scene, motion, DynamicOptions(method="explicit", snapshots=0))
    E = result.total_energy
    assert not (result.status == OPEN).any()
    assert E[0] > 0.0 and result.energy[:, 1].max() > 0.1 * E[0]
    assert np.max(np.abs(E - E[0])) / E[0] < 1e-4


@pytest.mark.parametrize("overrides", [[], ["soil.interface=bonded", "soil.model=elastic"]])
def test_compiled_loop_repeats_the_python_loop(overrides, monkeypatch):
    # Reference: the Python loop of the same steps (COMPILED_LOOP = False); the same
    # arithmetic, so the histories agree to round-off.
    scene = load_scene(SCENE, overrides=COARSE + ["motion.duration=0.8"] + overrides)
    model, motion = build_model(scene), scene.build_motion()
    runs = {}
    for compiled in (False, True):
        monkeypatch.setattr(ex, "COMPILED_LOOP", compiled)
        runs[compiled] = run_dynamic(model, scene, motion,
                                     DynamicOptions(method="explicit", snapshots=2))
    a, b = runs[False], runs[True]
    for name in ("footing", "gap", "pressure", "structure_u", "displacement", "plastic_strain"):
        x, y = getattr(a, name), getattr(b, name)
        assert np.abs(x - y).max() <= 1e-9 * max(np.abs(x).max(), 1e-30), name
    assert np.array_equal(a.status, b.status)
    assert np.abs(a.energy - b.energy).max() <= 1e-9 * np.abs(a.energy).max()


def test_implicit_scheme_options_are_refused_on_the_explicit_route():
    # An option that the explicit route would ignore is refused, not dropped.
    scene = load_scene(SCENE, overrides=COARSE)
    model = build_model(scene)
    for options in (DynamicOptions(method="explicit", scheme="newmark"),
                    DynamicOptions(method="explicit", alpha=-0.2),
                    DynamicOptions(method="explicit", mass="consistent")):
        with pytest.raises(InputError, match="DynamicOptions"):
            run_dynamic(model, scene, scene.build_motion(), options)


def test_a_footing_without_rotary_inertia_is_refused_by_the_explicit_route():
    # Reference: the footing-and-story mass matrix M = diag(m_b, m_v, I0, 0) + m a aᵀ with
    # a = (1, 0, h, 1) (continuum/dynamics/run.py) has its θ row equal to h times the story's when
    # I0 = 0: singular, which central differences cannot advance (found by the fuzzer:
    # rotary_inertia = 1e-300 failed with a singular matrix at the first step; a subnormal value
    # is now refused when the scene is read, upliftlab/bounds.py, and so is 0 for a rocking base;
    # 1e-8 kN·m·s² is physical yet below MIN_ROTARY_INERTIA m h² = 2.8e-7 of this scene).
    # Refused with the field and its range; the implicit route, which adds the soil's
    # stiffness, runs it.
    scene = load_scene(SCENE, overrides=COARSE + ["structure.rotary_inertia=1e-8",
                                                  "analysis.duration=0.02"])
    model = build_model(scene)
    with pytest.raises(InputError, match=r"structure.rotary_inertia = 1e-08: .*valid range"):
        run_dynamic(model, scene, scene.build_motion(), DynamicOptions(snapshots=0))
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(method="implicit", snapshots=0))
    assert np.isfinite(result.footing).all()


# ---------------------------------------------------------------------------------------------
# The soil's mass scaled (a diagnostic of the soil's own dynamics)
# ---------------------------------------------------------------------------------------------


def test_a_scaled_soil_mass_shrinks_the_stable_step_as_its_square_root():
    # Reference: K x = ω² s M x has the eigenvalues of K x = ω² M x over s, so the
    # central-difference limit 2/ω_max scales as √s (eigsh's tolerance 1e-8 bounds the
    # agreement). The scaled run still closes its energy account (the scaled mass in the
    # kinetic energy and in the soil's seismic load alike) and keeps its contact exact.
    scene = load_scene(SCENE, overrides=COARSE + ["analysis.duration=0.3"])
    model = build_model(scene)
    runs = {s: run_dynamic(model, scene, scene.build_motion(),
                           DynamicOptions(method="explicit", snapshots=0, soil_mass_scale=s))
            for s in (1.0, 0.25)}
    ratio = runs[0.25].metadata["dt_critical"] / runs[1.0].metadata["dt_critical"]
    assert ratio == pytest.approx(0.5, rel=1e-6)
    scaled = runs[0.25]
    assert scaled.energy_balance_error < 1e-3
    assert scaled.pressure.min() >= -1e-9 * np.abs(scaled.pressure).max()
    assert scaled.gap.min() >= -1e-9 * model.width


@pytest.mark.parametrize("options, field", [
    (dict(method="implicit", soil_mass_scale=0.5), "only the explicit route"),
    (dict(method="explicit", sides="lysmer", soil_mass_scale=0.5), "keep the dashpots"),
])
def test_a_scaled_soil_mass_that_would_do_nothing_or_half_is_refused(options, field,
                                                                     monkeypatch):
    # The implicit route has no scaled mass, and the Lysmer dashpots (ρ V) would stay those of
    # the unscaled soil: refused before any work, naming the field and what is valid.
    scene = load_scene(SCENE, overrides=COARSE)
    model = build_model(scene)
    monkeypatch.setattr(ground, "gravity_state", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(InputError, match=rf"DynamicOptions.soil_mass_scale = 0.5: .*{field}"):
        run_dynamic(model, scene, scene.build_motion(), DynamicOptions(**options))


@pytest.mark.parametrize("value, why", [(0.0, "valid range"), (-0.1, "valid range"),
                                        (1.5, "valid range"), (float("nan"), "finite")])
def test_a_soil_mass_scale_outside_zero_to_one_is_refused(value, why):
    with pytest.raises(InputError, match=rf"DynamicOptions.soil_mass_scale = .*{why}"):
        DynamicOptions(soil_mass_scale=value)
