"""Newton's method, its tangent, step cutting and the V–M envelope (upliftlab.continuum).

References:
- Finite differences (as SfePy checks its tangents): the consistent tangent equals central
  differences of the residual, and the footing tangent dF/dq equals central differences of the
  re-equilibrated reactions, with the contact active set and the plastic state frozen.
- Perfect plasticity: the limit load does not depend on the load path (one big step that needs
  bisection and ten small steps reach the same plateau).
- Effective width (Meyerhof 1953): for a strip on Tresca soil with a tensionless
  interface, M/(B V_ult) = v(1 − v)/2. For a smooth base the effective-width stress field
  (Prandtl's field on B' = vB, no contact beyond) is statically admissible, so it is a lower
  bound: the exact envelope lies on or above it.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import (Control, ConvergenceError, NewtonOptions, assembly, equilibrium,
                                 follow, footing_tangent, make_model, vertical_pushover,
                                 vm_envelope)
from upliftlab.continuum import geostatic
from upliftlab.continuum.dynamics.iteration_matrix import FrozenTangent
from upliftlab.scenes import ContinuumOptions, Soil

B, CU = 2.0, 50.0
SMALL = ContinuumOptions(elements_across=4, domain_width=4, domain_depth=2)
SOILS = {
    "tresca": dict(model="tresca", undrained_strength=CU, interface="frictionless"),
    "von_mises": dict(model="von_mises", undrained_strength=CU, interface="bonded"),
    "mohr_coulomb": dict(model="mohr_coulomb", cohesion=20.0, friction_angle=25.0,
                         dilation_angle=5.0, interface="coulomb", interface_friction=0.5),
    "drucker_prager": dict(model="drucker_prager", cohesion=20.0, friction_angle=25.0,
                           dilation_angle=5.0, interface="bonded"),
}


def soil(**kw):
    return Soil(**{"youngs_modulus": 50e3, "poisson_ratio": 0.3, "density": 1.8, **kw})


def rocked(name):
    """A small model pushed under N and then rotated into uplift and plastic flow: the last
    two converged states."""
    model = make_model(soil(**SOILS[name]), B, SMALL)
    N = 150.0 if name in ("tresca", "von_mises") else 100.0
    fixed_u = not model.footing.interface.tangential
    controls = [Control((fixed_u, False, True), (0.0, -N * k / 3, 0.0)) for k in (1, 2, 3)]
    controls += [Control((fixed_u, False, True), (0.0, -N, t)) for t in (0.002, 0.004)]
    states = follow(model, geostatic(model), controls)
    return model, states[-2], states[-1]


@pytest.mark.parametrize("name", sorted(SOILS))
def test_residual_tangent_matches_finite_differences(name):
    # Reference: central differences of the residual R(u) with the quadrature-point history
    # frozen (the old state of the step), step h = 1e-8 m on a random direction; relative error
    # below 1e-6 (measured 2e-10 – 2e-8). The state has plastic points and open contact nodes.
    model, old, new = rocked(name)
    assert np.count_nonzero(new.material.region) > 0
    rng = np.random.default_rng(1)
    direction = rng.standard_normal(model.disc.ndofs)
    direction[model.blocks.fixed] = 0.0
    K = assembly.stiffness(model.disc, new.tangent)
    h = 1e-8
    plus, minus = (model.respond(new.u + s * h * direction, old.material, old.eigenstrain)
                   for s in (1.0, -1.0))
    assert np.array_equal(plus.material.region, new.material.region)
    fd = (plus.residual - minus.residual) / (2 * h)
    free = np.concatenate((model.blocks.interior, model.blocks.contact))
    error = np.linalg.norm((K @ direction - fd)[free]) / np.linalg.norm(fd[free])
    assert error < 1e-6, error


@pytest.mark.parametrize("name", sorted(SOILS))
def test_compiled_response_matches_the_vectorised_one(name):
    # Reference: the vectorised return maps of continuum.materials (each tested against closed
    # forms in tests/test_materials.py), evaluated on the same rocked state with plastic points;
    # the compiled kernels that modified Newton's iterations use must give the same stress,
    # plastic strain, ε̄p and residual to 1e-10 of their scale, and the same tangent when it is
    # asked for. Drucker–Prager has no compiled map: its frozen-matrix model keeps the
    # vectorised route.
    model, old, new = rocked(name)
    frozen = FrozenTangent(**{f.name: getattr(model, f.name)
                              for f in dataclasses.fields(model) if f.init} | {"_cache": {}})
    u = new.u + 0.5 * (new.u - old.u)  # further into plastic flow than the converged step
    reference = model.respond(u, old.material, old.eigenstrain)
    compiled = frozen.respond(u, old.material, old.eigenstrain)
    assert np.count_nonzero(reference.material.equivalent_plastic_strain) > 0
    assert callable(compiled.lazy_tangent) == (name != "drucker_prager")

    def close(a, b):
        return np.max(np.abs(a - b)) <= 1e-10 * max(np.max(np.abs(b)), 1e-300)
    assert close(compiled.stress, reference.stress)
    assert close(compiled.material.plastic_strain, reference.material.plastic_strain)
    assert close(compiled.material.equivalent_plastic_strain,
                 reference.material.equivalent_plastic_strain)
    assert close(compiled.residual, reference.residual)
    assert close(compiled.tangent, reference.tangent)
    assert not callable(compiled.lazy_tangent)  # computed once, then kept


@pytest.mark.parametrize("name", sorted(SOILS))
def test_footing_tangent_matches_finite_differences(name):
    # Reference: central differences of the footing reaction (H, −N, M) re-equilibrated by
    # Newton (rtol 1e-13) at q ± h e_k, h = 1e-6, with the contact status and the plastic
    # history frozen; relative error below 1e-6 (measured 1e-9 – 1e-8). Covers open nodes,
    # plastic points, Coulomb slip (mohr_coulomb) and a non-symmetric tangent (ψ < φ).
    model, old, new = rocked(name)
    assert (new.status == 0).any()
    K = footing_tangent(model, new)
    frozen = dataclasses.replace(old, status=new.status)
    h, fd = 1e-6, np.zeros((3, 3))
    columns = range(3) if model.footing.interface.tangential else (1, 2)
    for k in columns:
        F = []
        for sign in (1.0, -1.0):
            q = new.q.copy()
            q[k] += sign * h
            state = equilibrium(model, frozen, Control((True, True, True), tuple(q)),
                                NewtonOptions(rtol=1e-13), frozen=True)
            F.append(state.reaction)
        fd[:, k] = (F[0] - F[1]) / (2 * h)
    assert np.max(np.abs(fd - K)) <= 1e-6 * np.max(np.abs(K))


def test_affine_soil_and_footing_terms_for_dynamics():
    # Reference: direct linear algebra. A soil term c M u + offset (M scikit-fem's mass
    # matrix, as a Newmark inertia adds) with the footing pushed down in full contact: u solves
    # (K + c M) u = −offset with the base nodes on the footing (1e-9). With a footing spring k
    # on v under a vertical load N the response is affine: v = (−N − F0)/(K_v + k), F0 the
    # contact's vertical force at v = 0 and K_v its tangent (1e-9).
    import skfem
    from scipy.sparse.linalg import spsolve

    from upliftlab.continuum import FootingTerm, SoilTerm
    from upliftlab.continuum.materials import plane_strain_tangent

    model = make_model(soil(model="elastic", density=0.0), B,
                       ContinuumOptions(elements_across=4, domain_width=4, domain_depth=2))
    fine = skfem.Basis(model.mesh, model.disc.basis.elem, intorder=4)
    M = skfem.BilinearForm(lambda u, v, w: u[0] * v[0] + u[1] * v[1]).assemble(fine)
    c = 2.0e4
    term = SoilTerm(data=model.disc.pattern.gather(c * M),
                    offset=-c * M @ np.full(model.disc.ndofs, 1e-4))
    state = geostatic(model)
    pushed = equilibrium(model, state, Control((True, True, True), (0.0, -1e-3, 0.0)),
                         soil_term=term)
    D = plane_strain_tangent(model.material(np.zeros((3, 3, 1)))[1])[..., 0]
    A = (assembly.stiffness(model.disc, D) + c * M).tocsr()
    x = np.zeros(model.disc.ndofs)
    x[model.footing.uy] = -1e-3
    free = np.setdiff1d(np.arange(model.disc.ndofs),
                        np.concatenate((model.blocks.fixed, model.footing.uy)))
    x[free] = spsolve(A[free][:, free].tocsc(), (-term.offset - A @ x)[free])
    assert np.max(np.abs(pushed.u - x)) <= 1e-9 * 1e-3
    k, N = 5.0e3, 100.0
    spring = FootingTerm(K=np.diag([0.0, k, 0.0]), offset=np.zeros(3))
    loaded = equilibrium(model, state, Control((True, False, True), (0.0, -N, 0.0)),
                         soil_term=term, footing_term=spring)
    assert (loaded.status != 0).all()
    held = equilibrium(model, state, Control((True, True, True), (0.0, 0.0, 0.0)),
                       soil_term=term)
    K_v = footing_tangent(model, loaded, soil_term=term)[1, 1]
    expected = (-N - held.reaction[1]) / (K_v + k)
    assert abs(loaded.q[1] / expected - 1.0) <= 1e-9


def test_one_big_step_is_bisected_and_reaches_the_same_limit_load():
    # Reference: path independence of the perfectly plastic limit load. Pushing to 0.1 m in
    # one step needs bisection; its load equals ten steps' to 0.2 %.
    model = make_model(soil(**SOILS["tresca"]), B, SMALL)
    one = vertical_pushover(model, [0.1])
    ten = vertical_pushover(model, np.linspace(0.01, 0.1, 10))
    assert one.cuts[0] >= 1
    assert abs(one.N[-1] / ten.N[-1] - 1.0) <= 0.002


def test_newton_gives_up_with_the_step_and_residual():
    # Reference: a hard case: a vertical load above the capacity has no equilibrium;
    # Newton must say which step failed and with what residual, not return garbage.
    model = make_model(soil(**SOILS["tresca"]), B, SMALL)
    capacity = vertical_pushover(model, np.linspace(0.02, 0.1, 5)).capacity
    controls = [Control((True, False, True), (0.0, -f * capacity, 0.0)) for f in (0.5, 1.3)]
    with pytest.raises(ConvergenceError, match=r"^load step 1 .*gave up") as error:
        follow(model, geostatic(model), controls, NewtonOptions(max_cuts=4))
    assert error.value.step == 1 and 0.0 <= error.value.fraction < 1.0
    assert error.value.residual > 1e-8 or error.value.residual != error.value.residual
    assert isinstance(error.value, RuntimeError)


def test_a_singular_tangent_is_a_newton_failure_that_the_step_cutting_handles(monkeypatch):
    """A factorisation that finds the tangent singular (a perfectly plastic mechanism under
    the prescribed loads: it stopped a Mohr–Coulomb rotation pushover of the Winkler map on
    16 across) is a ConvergenceError of the step, bisected and then given up on with the step
    named, never scipy's bare RuntimeError. Counted here: every bisection asked for a new
    factorisation (max_cuts = 3: the step and its three halvings)."""
    model = make_model(soil(**SOILS["tresca"]), B, SMALL)
    state = geostatic(model)
    calls = []

    def singular(*args, **kwargs):
        calls.append(1)
        raise RuntimeError("Factor is exactly singular")

    monkeypatch.setattr(type(model), "condense", singular)
    controls = [Control((True, False, True), (0.0, -50.0, 0.0))]
    with pytest.raises(ConvergenceError, match=r"^load step 0 .*the tangent is singular"):
        follow(model, state, controls, NewtonOptions(max_cuts=3))
    assert len(calls) == 4


@pytest.mark.parametrize("field, value", [("rtol", 0.0), ("max_iterations", 0),
                                          ("max_cuts", 1.5)])
def test_bad_newton_options(field, value):
    # Reference: the project's input rule: bad input names the field, the value and the valid range.
    with pytest.raises(InputError, match=f"^NewtonOptions.{field} = "):
        NewtonOptions(**{field: value})


def test_vm_envelope_against_effective_width():
    # Reference: M/(B V_ult) = v(1 − v)/2, a lower bound for the smooth tensionless base (module
    # docstring). Q2 8 across, 10B × 10B, θ to 0.05 rad, V_ult from the same mesh
    # (+2.0 % above (2 + π) c_u B). Measured: +2.3 %, +1.4 %, +1.3 % at v = 0.25, 0.5, 0.75.
    # Asserted −1 % ≤ error ≤ +4 %: the sign of a lower bound, plus the mesh's overshoot
    # (of the order of its V_ult overshoot, +2 %) on the narrower effective width.
    model = make_model(soil(**SOILS["tresca"]), B, ContinuumOptions(elements_across=8))
    envelope = vm_envelope(model, [0.25, 0.5, 0.75], np.linspace(0.005, 0.05, 10),
                           settlements=np.linspace(0.01, 0.1, 10))
    expected = envelope.v * (1 - envelope.v) / 2
    error = envelope.m / expected - 1.0
    assert np.all(error >= -0.01) and np.all(error <= 0.04), error
    assert abs(envelope.V_ult / ((2 + np.pi) * CU * B) - 1.0) <= 0.03


SAND = dict(model="mohr_coulomb", cohesion=5.0, friction_angle=30.0, dilation_angle=30.0,
            interface="frictionless")  # the Winkler map's frictional soil


def test_vm_envelope_of_the_sand_against_effective_width():
    # Reference: effective width with both terms of the strip's capacity, V = B′ c N_c +
    # B′² ½ γ N_γ on B′ = B − 2M/V (Meyerhof 1953), with N_c = 30.14 (Prandtl, φ = 30°) and
    # the N_γ term the rest of the continuum's own V_ult (N_γ = 11.2 on this smooth base).
    # Measured on Q2 8 across: +3.2 %, +6.0 %, +11.0 % at v = 0.25, 0.5, 0.75 (16 across:
    # +3.2 %, +6.1 %, +11.3 %: converged); the one-term rules miss by −15 … −24 % (c N_c alone)
    # and +27 … +41 % (N_γ alone). Asserted: the rule lies below the continuum by 0 … +13 %,
    # the gap growing with v.
    model = make_model(soil(**SAND), B, ContinuumOptions(elements_across=8))
    envelope = vm_envelope(model, [0.25, 0.5, 0.75], np.linspace(0.005, 0.05, 10),
                           settlements=np.linspace(0.01, 0.1, 10))
    cohesive = 5.0 * 30.14
    frictional = (envelope.V_ult / B - cohesive) / B
    width = 2 * envelope.V / (cohesive + np.sqrt(cohesive ** 2 + 4 * frictional * envelope.V))
    error = envelope.m / (envelope.V * (B - width) / 2 / (B * envelope.V_ult)) - 1.0
    assert np.all(error >= 0.0) and np.all(error <= 0.13), error
    assert np.all(np.diff(error) > 0.0), error


@pytest.mark.slow
def test_vm_envelope_refinement():
    # Reference: effective width, as above. Q2 16 across (20 160 DOFs): the errors stay within
    # −1 % … +3 % and do not grow from 8 across at any v.
    errors = {}
    for n in (8, 16):
        model = make_model(soil(**SOILS["tresca"]), B, ContinuumOptions(elements_across=n))
        envelope = vm_envelope(model, [0.25, 0.5, 0.75], np.linspace(0.005, 0.05, 10),
                               settlements=np.linspace(0.01, 0.1, 10))
        errors[n] = envelope.m / (envelope.v * (1 - envelope.v) / 2) - 1.0
    assert np.all(errors[16] >= -0.01) and np.all(errors[16] <= 0.03), errors
    assert np.all(errors[16] <= errors[8] + 1e-3), errors
