"""Radiation dashpots distributed over a Winkler bed (comparisons/beds/radiation).

References: hand solutions of the two conditions Σc = C_v, Σc x² = C_r (worked out below);
linear interpolation by hand between an Impedance record's frequencies; Gazetas' (1991) strip
dashpots evaluated by hand; the closed-form free vibration of a damped SDOF (the rocking mode
of a rigid footing on a bonded bed, ζ = C_r/(2√(K_r I))).
"""

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.beds.radiation import (
    distribute, gazetas_dashpots, impedance_dashpots, radiation_dashpots, rocking_frequency,
    with_radiation)
from upliftlab.continuum.impedance.analysis import Impedance, ImpedanceOptions
from upliftlab.reduced import build_model, run
from upliftlab.reduced.compatibility import winkler_bed
from upliftlab.scenes import Soil, load_scene


def test_a_pair_of_springs_reproduces_both_dashpots():
    """Springs at x = −0.5 and 1.0 m, C_v = 3, C_r = 2: c₁ + c₂ = 3 and 0.25 c₁ + c₂ = 2 give
    0.75 c₁ = 1, so c₁ = 4/3 and c₂ = 5/3 (to 1e-12)."""
    c, alpha, beta, where = distribute([-0.5, 1.0], [0.75, 0.75], 3.0, 2.0)
    np.testing.assert_allclose(c, [4.0 / 3.0, 5.0 / 3.0], rtol=1e-12)
    assert math.isnan(alpha) and math.isnan(beta) and where == "pair"


def test_a_symmetric_pair_reproduces_both_only_at_its_own_ratio():
    """A pair at ±0.8 m has Σc x² = 0.64 Σc: C_v = 5, C_r = 3.2 gives 2.5 each; C_r = 3 is
    refused, naming the positions that would reproduce it (±√0.6 = ±0.7746)."""
    c, *_ = distribute([-0.8, 0.8], [1.0, 1.0], 5.0, 3.2)
    np.testing.assert_allclose(c, [2.5, 2.5], rtol=1e-12)
    with pytest.raises(InputError, match=r"only at ±0\.774597"):
        distribute([-0.8, 0.8], [1.0, 1.0], 5.0, 3.0)


def test_four_springs_uniform_part_plus_end_concentration_by_hand():
    """A uniform bed of 4 on b = 1 m: w = 0.5, x = ±0.25, ±0.75. W = Σw = 2,
    A = Σw x² = 0.5 (2·0.0625 + 2·0.5625) = 0.625, E = x₁² + x₄² = 1.125. With C_v = 10,
    C_r = 4: 2α + 2β = 10 and 0.625 α + 1.125 β = 4 give β = 1.75, α = 3.25, so the middle
    springs carry 0.5 α = 1.625 and the end ones 1.625 + 1.75 = 3.375 (to 1e-12). The ratio
    C_r/C_v = 0.4 is above the uniform part's A/W = 0.3125: the concentration goes to the ends."""
    bed = winkler_bed(1.0, 1.0, 4)
    c, alpha, beta, where = distribute(bed.positions, bed.widths, 10.0, 4.0)
    assert alpha == pytest.approx(3.25, rel=1e-12) and beta == pytest.approx(1.75, rel=1e-12)
    assert where == "ends"
    np.testing.assert_allclose(c, [3.375, 1.625, 1.625, 3.375], rtol=1e-12)


def test_four_springs_uniform_part_plus_centre_concentration_by_hand():
    """The same bed with C_v = 10, C_r = 2 (ratio 0.2, below A/W = 0.3125): the concentration
    goes to the two springs nearest O, at ±0.25 (E_c = 2·0.0625 = 0.125):
    2α + 2β = 10 and 0.625 α + 0.125 β = 2 give β = 2.25, α = 2.75, so the end springs carry
    0.5 α = 1.375 and the middle ones 1.375 + 2.25 = 3.625 (to 1e-12)."""
    bed = winkler_bed(1.0, 1.0, 4)
    c, alpha, beta, where = distribute(bed.positions, bed.widths, 10.0, 2.0)
    assert alpha == pytest.approx(2.75, rel=1e-12) and beta == pytest.approx(2.25, rel=1e-12)
    assert where == "centre"
    np.testing.assert_allclose(c, [1.375, 3.625, 3.625, 1.375], rtol=1e-12)


@pytest.mark.parametrize("springs", [3, 20, 48, 257])
@pytest.mark.parametrize("toward", [0.0, 0.3, 1.0])
def test_n_spring_beds_reproduce_both_dashpots(springs, toward):
    """Uniform beds of N springs on b = 1.3 m, C_v = 7.1 and C_r/C_v 30 % (and all) of the way
    from the uniform part's ratio Σw x²/Σw to the ends' x_N², and as far towards the centre
    springs' x_c² (at either bound exactly, all the concentration and no uniform part): Σc = C_v
    and Σc x² = C_r to 1e-12, every c ≥ 0."""
    bed = winkler_bed(1.3, 1.0, springs)
    x = bed.positions
    uniform = np.sum(bed.widths * x * x) / np.sum(bed.widths)
    for bound, where in ((x[-1] ** 2, "ends"), (np.min(x * x), "centre")):
        C_v = 7.1
        C_r = C_v * (uniform + toward * (bound - uniform))
        c, alpha, beta, got = distribute(x, bed.widths, C_v, C_r)
        assert np.all(c >= 0.0) and alpha >= 0.0 and beta >= 0.0
        if toward > 0:
            assert got == where
        else:  # the uniform part alone
            assert beta <= 1e-12 * C_v
        assert np.sum(c) == pytest.approx(C_v, rel=1e-12)
        assert np.sum(c * x * x) == pytest.approx(C_r, rel=1e-12)


def test_no_non_negative_distribution_is_refused_with_the_range():
    """On the 4-spring bed above the reachable C_r/C_v is [E_c/2, E/2] = [0.0625, 0.5625]
    (length²), the centre springs' ratio to the ends': 0.05 and 0.6 are refused in one line
    naming it."""
    bed = winkler_bed(1.0, 1.0, 4)
    for ratio, where in ((0.05, "below the centre springs'"), (0.6, "above the ends'")):
        with pytest.raises(InputError) as err:
            distribute(bed.positions, bed.widths, 10.0, 10.0 * ratio)
        assert "[0.0625, 0.5625]" in str(err.value) and where in str(err.value)
        assert "\n" not in str(err.value)


def _record(a0, K_v, K_h, K_r):
    """An Impedance record by hand on soil of V_s = 100 m/s (G = 2e4 kPa, ρ = 2 t/m³) under
    B = 2 m: ω = a0 V_s/(B/2) = 100 a0 rad/s."""
    soil = Soil(youngs_modulus=2.0 * 2.0e4 * 1.25, poisson_ratio=0.25, density=2.0)
    matrix = np.zeros((len(a0), 3, 3), dtype=complex)
    matrix[:, 1, 1], matrix[:, 0, 0], matrix[:, 2, 2] = K_v, K_h, K_r
    return Impedance(a0=np.asarray(a0, dtype=float), matrix=matrix, soil=soil, width=2.0,
                     interface="bonded", mesh={}, options=ImpedanceOptions(a0=tuple(a0)),
                     dofs=0)


def test_dashpots_interpolate_linearly_in_frequency_between_the_records_a0():
    """a0 = 0.5 and 1.0 are ω = 50 and 100 rad/s. Im K_v = 5000 and 8000 give C_v = 100 and
    80; Im K_h = 2500, 6000 give C_h = 50, 60; Im K_r = 1000, 3000 give C_r = 20, 30. At
    ω = 60 (a fifth of the way): C_v = 100 − 0.2·20 = 96, C_h = 50 + 0.2·10 = 52,
    C_r = 20 + 0.2·10 = 22 (to 1e-12). ω = 40 and 110 are outside the grid: refused."""
    record = _record([0.5, 1.0], [1e5 + 5000j, 1e5 + 8000j], [3e4 + 2500j, 3e4 + 6000j],
                     [5e4 + 1000j, 5e4 + 3000j])
    np.testing.assert_allclose(record.omega, [50.0, 100.0], rtol=1e-14)
    np.testing.assert_allclose(impedance_dashpots(record, 60.0), [96.0, 52.0, 22.0], rtol=1e-12)
    np.testing.assert_allclose(impedance_dashpots(record, 100.0), [80.0, 60.0, 30.0], rtol=1e-12)
    for omega in (40.0, 110.0):
        with pytest.raises(InputError, match="outside the impedance's frequencies"):
            impedance_dashpots(record, omega)


def test_gazetas_strip_dashpots_by_hand():
    """G = 2e4 kPa, ν = 1/3, ρ = 2 t/m³, B = 2 m: V_s = 100 m/s, Lysmer's analog velocity
    V_La = 3.4·100/(π·2/3) = 162.338 m/s; C_v = ρ V_La B = 649.352, C_h = ρ V_s B = 400,
    C_r = ρ V_La B³/12 = 216.451 (kN·s/m per m; kN·m·s per m), to 1e-12."""
    v_la = 3.4 * 100.0 / (math.pi * (2.0 / 3.0))
    got = gazetas_dashpots(shear_modulus=2.0e4, poisson=1.0 / 3.0, density=2.0, width=2.0)
    np.testing.assert_allclose(got, [2.0 * v_la * 2.0, 400.0, 2.0 * v_la * 8.0 / 12.0],
                               rtol=1e-12)
    assert got[0] == pytest.approx(649.352, rel=1e-6)


def _footing(**changes):
    """The 2 m clay strip as a rigid footing (block and story as one rigid body) on a bonded
    elastic bed of 20 springs, released from a rotation of 1e-4 rad (2 s stored every 0.1 ms)."""
    overrides = ["structure.rigid=true", "foundation.support=bonded",
                 "motion.type=free", "motion.rotation=1e-4", "motion.duration=2",
                 "motion.amplitude=", "motion.period=", "analysis.rtol=1e-9",
                 "analysis.output_dt=1e-4"]
    overrides += [f"{k}={v}" for k, v in changes.items()]
    return load_scene("strip_footing_clay", overrides=overrides)


def test_rocking_frequency_of_a_rigid_footing_is_sqrt_kr_over_i():
    """Rigid footing on a symmetric bonded bed: θ and V decouple, so the rocking mode is
    ω_r = √(K_θ/I_θ), K_θ = Σ k x², I_θ = I₀ + m h² (to 1e-12)."""
    scene = _footing()
    model = build_model(scene)
    s = scene.structure
    inertia = s.rotary_inertia + s.weight / scene.g * s.height**2
    assert rocking_frequency(model) == pytest.approx(
        math.sqrt(model.layout.rocking_stiffness / inertia), rel=1e-12)


def test_rigid_footing_decays_in_rocking_with_the_damping_ratio_of_c_r():
    """The footing with the handbook's dashpots distributed over its bed (uniform part plus
    ends; the scene's clay: E = 50 MPa, ν = 0.3, ρ = 1.8 t/m³) rocks freely as the SDOF
    I θ̈ + C_r θ̇ + K_θ θ = 0: θ(t) = θ₀ e^{−ζωt}(cos ω_d t + ζ/√(1 − ζ²) sin ω_d t) with
    ζ = C_r/(2√(K_θ I)) (0.0263 here: the 4 m block's own rotary mass is large), to 1e-6 θ₀
    over 2 s, about four cycles (event stepper at rtol 1e-9); the logarithmic decrement over
    three cycles of the stored peaks (0.1 ms apart: a sampled peak is low by about
    (ω Δt)²/2 = 7e-7) gives ζ to 1e-4."""
    scene = _footing()
    radiation = radiation_dashpots(scene)
    assert radiation.source == "gazetas" and radiation.where == "ends"
    damped = with_radiation(scene, radiation, horizontal=False)
    model = build_model(damped)
    x, c = model.layout.positions, model.params["c"][model.foundation_slice]
    assert np.sum(c) == pytest.approx(radiation.C_v, rel=1e-12)
    assert np.sum(c * x * x) == pytest.approx(radiation.C_r, rel=1e-12)
    inertia = model.mass[model.dofs.theta]
    K = model.layout.rocking_stiffness
    zeta = radiation.C_r / (2.0 * math.sqrt(K * inertia))
    assert 0.02 < zeta < 0.5  # θ falls to 0.54 θ₀ in 2 s: a decay the test can see
    response = run(damped)
    omega = math.sqrt(K / inertia)
    wd = omega * math.sqrt(1.0 - zeta**2)
    t = response.time
    exact = 1e-4 * np.exp(-zeta * omega * t) * (np.cos(wd * t)
                                                 + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t))
    assert np.max(np.abs(response.theta - exact)) < 1e-6 * 1e-4
    theta = response.theta
    peaks = np.flatnonzero((theta[1:-1] > theta[:-2]) & (theta[1:-1] > theta[2:])) + 1
    decrement = math.log(theta[0] / theta[peaks[2]]) / 3.0
    measured = decrement / math.sqrt(4.0 * math.pi**2 + decrement**2)
    assert measured == pytest.approx(zeta, rel=1e-4)


def test_the_horizontal_dashpot_goes_on_the_sway_spring():
    """With a sway spring, C_h = ρ V_s B of the handbook strip (V_s = √(G/ρ), G = E/(2(1 + ν))
    = 19 231 kPa for the clay) becomes foundation.sway_damping; without one it is refused."""
    scene = _footing(**{"foundation.sway_stiffness": 5.0e4})
    radiation = radiation_dashpots(scene)
    G = 50.0e3 / 2.6
    assert radiation.C_h == pytest.approx(1.8 * math.sqrt(G / 1.8) * 2.0, rel=1e-12)
    damped = with_radiation(scene, radiation)
    assert damped.foundation.sway_damping == radiation.C_h
    model = build_model(damped)
    assert model.params["c"][model.sway_spring] == radiation.C_h
    with pytest.raises(InputError, match="foundation.sway_stiffness is missing"):
        with_radiation(_footing(), radiation)


def test_rocking_frequency_of_a_flexible_structure_is_its_flexible_base_fundamental():
    """The clay strip's SDOF (T = 0.3 s fixed base) on its bonded bed: V decouples (symmetric
    bed), and the frequency is the lowest of the (x, θ) system assembled by hand:
    M = diag(m, I₀), K = k [[1, −h], [−h, h²]] + diag(0, K_θ) (the story deforms by x − hθ),
    scipy.linalg.eigh, to 1e-12."""
    import scipy.linalg

    scene = load_scene("strip_footing_clay", overrides=["foundation.support=bonded"])
    model = build_model(scene)
    s = scene.structure
    m, h = s.weight / scene.g, s.height
    k = m * (2.0 * math.pi / 0.3) ** 2
    K = k * np.array([[1.0, -h], [-h, h * h]]) + np.diag([0.0, model.layout.rocking_stiffness])
    w2 = scipy.linalg.eigh(K, np.diag([m, s.rotary_inertia]), eigvals_only=True)
    assert rocking_frequency(model) == pytest.approx(math.sqrt(w2[0]), rel=1e-12)


def test_dashpots_from_a_continuum_impedance_go_to_the_centre_at_low_frequency():
    """The FE impedance of the clay strip (elastic, bonded interface, 4 elements across B, PML)
    at a0 = 0.08–0.16, and the rigid footing's rocking frequency (a0 = 0.114): the bed's
    dashpots reproduce the impedance's C_v and C_r, interpolated linearly in ω between the two
    neighbouring a0 (by hand below), to 1e-12, with the concentration at the centre (this 2D
    strip radiates far more vertically than in rocking here: C_r/C_v < b²/3); C_h = Im K_h/ω
    interpolated the same way."""
    from upliftlab.continuum.impedance.analysis import impedance, impedance_model

    scene = _footing(**{"soil.model": "elastic", "soil.undrained_strength": "",
                        "soil.interface": "bonded", "continuum.elements_across": 4})
    options = ImpedanceOptions(a0=(0.08, 0.12, 0.16))
    record = impedance(impedance_model(scene.soil, scene.foundation.width, scene.continuum,
                                       options), options)
    radiation = radiation_dashpots(scene, impedance=record)
    omega = radiation.omega
    assert record.omega[0] < omega < record.omega[1]
    f = (omega - record.omega[0]) / (record.omega[1] - record.omega[0])
    for mode, got in (("v", radiation.C_v), ("h", radiation.C_h), ("r", radiation.C_r)):
        C = record.matrix[:, {"v": 1, "h": 0, "r": 2}[mode], {"v": 1, "h": 0, "r": 2}[mode]]
        C = C.imag / record.omega
        assert got == pytest.approx(C[0] + f * (C[1] - C[0]), rel=1e-12)
    assert radiation.where == "centre" and radiation.C_r / radiation.C_v < 1.0 / 3.0
    c, x = np.array(radiation.dashpots), build_model(scene).layout.positions
    assert np.sum(c) == pytest.approx(radiation.C_v, rel=1e-12)
    assert np.sum(c * x * x) == pytest.approx(radiation.C_r, rel=1e-12)


def test_a_custom_layout_keeps_each_dashpot_with_its_position():
    """A custom bed listed out of order (x = 0.75, −0.25, −0.75, 0.25 on b = 1): the scene's
    dashpots follow its list, and the model's springs (sorted from −b to +b) carry the four
    springs' hand values of the centre case above, 1.375 at the ends and 3.625 in the middle,
    scaled here to C_v = 10 and C_r = 2 (to 1e-12)."""
    from upliftlab.comparisons.beds.radiation import RadiationDashpots

    scene = _footing(**{"foundation.layout": "custom", "foundation.springs": "",
                        "foundation.stiffness": "",
                        "foundation.positions": "[0.75, -0.25, -0.75, 0.25]",
                        "foundation.stiffnesses": "[3e4, 3e4, 3e4, 3e4]"})
    model = build_model(scene)
    c, alpha, beta, where = distribute(model.layout.positions, model.layout.widths, 10.0, 2.0)
    radiation = RadiationDashpots(1.0, 10.0, 0.0, 2.0, tuple(c), alpha, beta, where, "test")
    damped = with_radiation(scene, radiation, horizontal=False)
    np.testing.assert_allclose(damped.foundation.dashpots, [1.375, 3.625, 1.375, 3.625],
                               rtol=1e-12)
    got = build_model(damped)
    np.testing.assert_allclose(got.params["c"][got.foundation_slice], [1.375, 3.625, 3.625,
                                                                       1.375], rtol=1e-12)
