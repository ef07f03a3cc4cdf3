"""An undrained strength that grows with depth, c_u(z) = c_u0 + k z (``[soil]
undrained_strength_gradient``; upliftlab.continuum.materials.undrained and its two routes).

References, one per test:
- the scene field: the project's input rule (field, value, valid range), one line before work;
- the yield stress at depth: closed forms. Plane-strain simple shear far past yield from the
  virgin state returns to τ = c_u(z) = c_u0 + k z for Tresca (σ1 − σ3 = 2 c_u) and for von Mises
  (σ_y = √3 c_u, pure shear in plane strain: τ = σ_y/√3), in the vectorised map and in the
  compiled point return;
- the compiled element loop with a gradient: the vectorised map with the sparse Bᵀσ assembly
  (ContinuumModel.respond), an independent implementation, on a coarse mesh;
- the bearing capacity of a smooth strip on clay whose strength grows linearly with depth: Davis
  & Booker (1973), q_u = F [(2 + π) c_u0 + k B/4], F from their chart for a smooth footing, read
  through the curve fit that API RP 2GEO (2011) and ISO 19901-4 give for it (module constant
  below); the continuum's default interface, frictionless, is the smooth footing.
Units: kN, m, kPa; E = 50 MPa, ν = 0.3, ρ = 1.8 t/m³ (the clay scene's soil).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.anchors import davis_booker_factor, undrained_capacity
from upliftlab.checks import InputError
from upliftlab.continuum import build_model, geostatic, make_model, vertical_pushover
from upliftlab.continuum import materials as mat
from upliftlab.continuum.dynamics.soil_force import SoilForce
from upliftlab.scenes import ContinuumOptions, Soil, load_scene

E, NU = 5.0e4, 0.3
G = E / (2 * (1 + NU))
CU0, K = 20.0, 3.0  # kPa, kPa/m
DEPTHS = np.array([[0.0, 1.0, 2.5], [5.0, 12.0, 20.0]])  # m, a (2, 3) batch of points


# ---------------------------------------------------------------------------------------------
# The scene field
# ---------------------------------------------------------------------------------------------

def test_the_gradient_defaults_to_a_uniform_soil_and_reaches_the_record():
    # Reference: the field's stated default (0: today's soil) and its value as given.
    assert load_scene("strip_footing_clay").soil.undrained_strength_gradient == 0.0
    scene = load_scene("strip_footing_clay",
                       overrides=["soil.undrained_strength_gradient=1.75"])
    assert scene.soil.undrained_strength_gradient == 1.75
    record = mat.material_from_soil(scene.soil)
    assert record.undrained_strength_gradient == 1.75 and record.graded


@pytest.mark.parametrize("value, why", [
    ("-1", "outside the physical range [0,"), ("nan", "expected a finite number"),
    ("inf", "expected a finite number")])
def test_a_negative_or_non_finite_gradient_is_refused(value, why):
    # Reference: the input rule; the range is [0, 1e10] Pa/m.
    with pytest.raises(InputError) as info:
        load_scene("strip_footing_clay", overrides=[f"soil.undrained_strength_gradient={value}"])
    message = str(info.value)
    assert message.startswith("soil.undrained_strength_gradient = ") and why in message
    assert "\n" not in message


@pytest.mark.parametrize("model", ["elastic", "mohr_coulomb", "drucker_prager"])
def test_a_gradient_for_a_model_without_undrained_strength_is_refused(model):
    # Reference: the input rule: the field means nothing to these models (valid [0, 0]), in
    # the scene reader and in the continuum's record builder (a Soil built in Python).
    extra = [] if model == "elastic" else ["soil.cohesion=5", "soil.friction_angle=30"]
    with pytest.raises(InputError, match=r"^soil\.undrained_strength_gradient = 2: model "
                                         rf"'{model}' reads no undrained strength; valid range "
                                         r"is \[0, 0\]"):
        load_scene("strip_footing_clay", overrides=[f"soil.model={model}", *extra,
                                                    "soil.undrained_strength_gradient=2"])
    soil = Soil(youngs_modulus=E, poisson_ratio=NU, model=model, cohesion=5.0,
                friction_angle=30.0, undrained_strength_gradient=2.0)
    with pytest.raises(InputError, match=r"^soil\.undrained_strength_gradient = 2: model"):
        mat.material_from_soil(soil)
    assert mat.graded_models() == ("tresca", "von_mises")


# ---------------------------------------------------------------------------------------------
# The yield stress at depth, both routes
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("record", [mat.Tresca(E, NU, CU0, undrained_strength_gradient=K),
                                    mat.VonMises(E, NU, CU0, undrained_strength_gradient=K)],
                         ids=["tresca", "von_mises"])
def test_the_yield_stress_at_depth_is_twice_cu0_plus_k_z_in_both_maps(record):
    # Reference: closed form (module docstring): simple shear to 10 times the deepest point's
    # yield strain, one step from the virgin state: τ = c_u0 + k z, i.e. σ1 − σ3 = 2 (c_u0 + k z)
    # with σ_xx = σ_yy = σ_zz = 0, to 1e-12 of the strength; the compiled return with the
    # record's per-point gain k z the same to 1e-12.
    at = record.at_points(DEPTHS)
    cu = CU0 + K * DEPTHS
    gamma = 10.0 * cu.max() / G
    strain = np.zeros((3, 3) + DEPTHS.shape)
    strain[0, 1] = strain[1, 0] = gamma / 2
    stress, _, state = at(strain)
    assert np.abs(stress[0, 1] - cu).max() <= 1e-12 * cu.max()
    spread = 2.0 * np.hypot(0.5 * (stress[0, 0] - stress[1, 1]), stress[0, 1])
    assert np.abs(spread - 2.0 * cu).max() <= 1e-12 * cu.max()
    assert np.all(state.region == mat.Region.SMOOTH)
    constants, gain = at.kernel_constants(), at.strength_gain(DEPTHS.shape)
    assert constants.undrained_strength == CU0 and np.array_equal(gain, K * DEPTHS)
    for i, j in np.ndindex(DEPTHS.shape):
        got = mat.point_return(constants, 0.0, 0.0, 0.0, gamma / 2, 0.0, 0.0, 0.0, 0.0, 0.0,
                               gain[i, j])
        assert abs(got[3] - cu[i, j]) <= 1e-12 * cu.max()
        assert max(abs(v) for v in got[:3]) <= 1e-12 * cu.max()


def test_a_uniform_soil_keeps_its_scalar_strength_and_a_zero_gain():
    # Reference: the uniform soil's arithmetic (k = 0): the map reads the float c_u itself and
    # the compiled return adds exactly 0; a model without undrained strength refuses a gain.
    record = mat.Tresca(E, NU, CU0)
    assert record.at_points(DEPTHS) is record and record.strength(DEPTHS.shape) == CU0
    assert np.array_equal(record.strength_gain(DEPTHS.shape), np.zeros(DEPTHS.shape))
    with pytest.raises(ValueError, match="gain = 1.0"):
        mat.point_return(mat.Elastic(E, NU).kernel_constants(), *[0.0] * 9, 1.0)
    graded = mat.Tresca(E, NU, CU0, undrained_strength_gradient=K)
    with pytest.raises(ValueError, match="needs the depths"):
        graded(np.zeros((3, 3, 2)))


@pytest.mark.parametrize("overrides", [[], ["soil.model=von_mises"]],
                         ids=["tresca", "von_mises"])
def test_the_element_loop_with_a_gradient_matches_the_assembly(overrides):
    # Reference: ContinuumModel.respond (vectorised map, sparse Bᵀσ) from the geostatic state
    # at a random displacement that yields many points, 2 elements across, k = 40 kPa/m over
    # a 20 m box (c_u from 50 to 850 kPa): forces to 1e-12 of their peak, ε̄p to 1e-14; and the
    # gradient changes the answer (fewer points yield than in the uniform soil).
    scene = load_scene("strip_footing_clay", overrides=overrides + [
        "continuum.elements_across=2", "soil.undrained_strength_gradient=40"])
    model = build_model(scene)
    state = geostatic(model)
    u = np.random.default_rng(5).normal(scale=2e-3, size=model.disc.ndofs)
    response = model.respond(u, state.material, state.eigenstrain)
    force = SoilForce(model, state)
    assert force.compiled
    got, ref = force(u), response.residual + model.body_force
    assert np.abs(got - ref).max() <= 1e-12 * np.abs(ref).max()
    assert np.abs(force.material.equivalent_plastic_strain
                  - response.material.equivalent_plastic_strain).max() <= 1e-14
    uniform = build_model(load_scene("strip_footing_clay", overrides=overrides + [
        "continuum.elements_across=2"]))
    plain = uniform.respond(u, state.material, state.eigenstrain).material.region > 0
    graded = response.material.region > 0
    assert 0 < graded.sum() < plain.sum()


# ---------------------------------------------------------------------------------------------
# Bearing capacity: Davis & Booker (1973)
# ---------------------------------------------------------------------------------------------

def test_davis_and_bookers_factor_is_the_api_fit_of_their_chart():
    # Reference: the API RP 2GEO (2011) / ISO 19901-4 fit of Davis & Booker's chart, by hand:
    # smooth F = 1.372 + 0.07 x − √((0.07 x − 0.128)² + 0.342²), rough F = 2.56 + 0.457 x −
    # √((0.713 + 0.457 x)² + 1.38²): x = 0 gives 1.0068 for both (their chart: 1), x = 4 gives
    # 1.2777 and 1.4964, x = 25 (the fit's end) 1.4643 and 1.7688; to 1e-4. A uniform soil is
    # Prandtl's (2 + π) c_u B exactly.
    for x, smooth, rough in ((0.0, 1.0068, 1.0067), (4.0, 1.2777, 1.4964),
                             (25.0, 1.4643, 1.7688)):
        assert davis_booker_factor(x) == pytest.approx(smooth, abs=1e-4)
        assert davis_booker_factor(x, rough=True) == pytest.approx(rough, abs=1e-4)
    assert davis_booker_factor(40.0) == davis_booker_factor(25.0)  # the fit's range
    assert undrained_capacity(50.0, 0.0, 2.0) == (2.0 + math.pi) * 50.0 * 2.0

B, CU_SURFACE, GRADIENT = 2.0, 10.0, 20.0  # m, kPa, kPa/m: kB/c_u0 = 4
SOIL = Soil(youngs_modulus=E, poisson_ratio=NU, density=1.8, model="tresca",
            undrained_strength=CU_SURFACE, undrained_strength_gradient=GRADIENT)


def test_a_smooth_strip_on_clay_stronger_with_depth_carries_davis_and_bookers_load():
    # Reference: Davis & Booker (1973), smooth strip: kB/c_u0 = 4, F = 1.278 (the API fit of
    # their chart), q_u = F [(2 + π) c_u0 + k B/4] = 78.47 kPa; uniform soil of c_u0 would
    # carry 51.42 kPa (Prandtl). Q2, 8 elements across graded 16 towards the edges, a 6B × 3B
    # box (the mechanism is shallower than Prandtl's, ~0.7 B deep), settlement to 5 % of B.
    # The mesh converges from above at O(h): on uniform clay this mesh is +0.97 % above
    # Prandtl (tests/test_continuum_bearing.py). Measured +0.20 % (16 across graded 16:
    # −0.02 %; 8 across ungraded +3.36 %; a 10B × 5B box +0.15 %; a rough footing, F = 1.496,
    # +0.51 %): the fit holds Davis & Booker's chart to its reading accuracy (F(0) = 1.007),
    # so the band is [−1 %, +2 %]; c_u0 alone would give −34 %.
    options = ContinuumOptions(element="Q2", elements_across=8, grading=16.0, domain_width=6.0,
                               domain_depth=3.0)
    path = vertical_pushover(make_model(SOIL, B, options), np.linspace(0.0, 0.1, 11)[1:])
    q_u = undrained_capacity(CU_SURFACE, GRADIENT, B) / B
    assert q_u == pytest.approx(78.47, abs=0.005)
    error = path.N[-1] / (B * q_u) - 1.0
    print(f"Davis & Booker smooth: q = {path.N[-1] / B:.2f} kPa, q_u = {q_u:.2f}, "
          f"{error:+.2%}")
    assert -0.01 <= error <= 0.02, error
    assert np.ptp(path.N[-3:]) <= 2e-3 * path.N[-1]  # a plateau: collapse
    assert path.N[-1] / B > 1.3 * (2.0 + math.pi) * CU_SURFACE  # far from the uniform soil's


# ---------------------------------------------------------------------------------------------
# The free field: a column under a uniform horizontal acceleration
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("gradient", [0.0, 2.0])
def test_the_free_field_column_yields_below_the_closed_form_depth(gradient):
    # Reference: closed form. A column of density ρ under a uniform horizontal acceleration a
    # carries τ(z) = ρ a z; with the isotropic geostatic stress (K0 = 1) a Tresca point yields
    # where ρ a z > c_u0 + k z, i.e. below z* = c_u0/(ρ a − k): the map's clay (c_u0 = 50 kPa,
    # ρ = 1.8 t/m³, 20 m box) at a = 0.5 g gives z* = 5.67 m for k = 0, 7.33 m for k = 2 kPa/m.
    # The column's elastic displacement u_x = −ρ a y²/(2G) (y = −z) is quadratic, so Q2
    # reproduces its shear strain at every quadrature point: the points the continuum yields
    # (the vectorised map and the compiled loop, from the geostatic state) are exactly those
    # below z*, where τ is c_u0 + k z. (One evaluation at the elastic state: a real column redistributes after its
    # first yield, at the base, where ρ a z/(c_u0 + k z) is largest.)
    scene = load_scene("strip_footing_clay", overrides=[
        "continuum.elements_across=4", f"soil.undrained_strength_gradient={gradient}"])
    model = build_model(scene)
    state = geostatic(model)
    rho, a = model.soil.density, 0.5 * model.gravity
    y = model.disc.basis.doflocs[1]
    u = np.zeros(model.disc.ndofs)
    u[0::2] = -rho * a * y[0::2] ** 2 / (2.0 * model.soil.shear_modulus)
    depth = -model.disc.qp_coordinates[1]
    z_star = 50.0 / (rho * a - gradient)
    response = model.respond(u, state.material, state.eigenstrain)
    demand, strength = rho * a * depth, 50.0 + gradient * depth
    tau = np.abs(response.stress[0, 1])  # the demand, capped at the strength where it yields
    assert np.abs(tau - np.minimum(demand, strength)).max() <= 1e-9 * demand.max()
    near = np.abs(depth - z_star) < 1e-9 * z_star  # none on this mesh
    assert not near.any()
    assert np.array_equal(response.material.region > 0, depth > z_star)
    force = SoilForce(model, state)
    force(u)
    assert np.array_equal(force.material.equivalent_plastic_strain > 0, depth > z_star)
    print(f"k = {gradient}: z* = {z_star:.3f} m, yielded points from "
          f"{depth[response.material.region > 0].min():.3f} m")


def test_the_command_line_checks_a_load_against_the_graded_soils_capacity(tmp_path, capsys):
    # Reference: Davis & Booker's capacity of the clay scene with k = 2 kPa/m (smooth, kB/c_u0
    # = 0.08, F = 1.0144): 1.0144 × (257.08 + 1) × 2 = 523.6 kN/m, above Prandtl's 514.2; a
    # load of 540 is refused before meshing (exit 2), naming the rule and the number.
    from upliftlab.cli import main
    code = main(["continuum", "strip_footing_clay", "--no-render", "--out", str(tmp_path / "o"),
                 "--set", "soil.undrained_strength_gradient=2",
                 "--set", "structure.vertical_weight=540"])
    assert code == 2
    error = capsys.readouterr().err
    assert "bearing capacity F [(2 + π) c_u + k B/4] B, Davis & Booker = 523.6" in error
