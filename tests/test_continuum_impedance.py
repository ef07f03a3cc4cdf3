"""Dynamic impedance of the rigid strip on elastic soil (upliftlab.continuum.impedance.analysis).

References, one per test:
- the exact impedance of the rigid strip on the half-plane, computed by
  :mod:`upliftlab.continuum.impedance.halfplane`: a Chebyshev–Galerkin solution of the mixed
  problem on
  Lamb's wavenumber-domain Green's function, written without the FE code (no mesh, no basis);
  it is itself checked here against closed forms: the static rocking stiffness of the
  frictionless strip πGB²/(8(1 − ν)) (Muskhelishvili's punch), the high-frequency
  dashpots ρV_pB (vertical), ρV_sB (horizontal) and ρV_pI (rocking, I = B³/12) (a plane wave
  under the whole base: the impedance of a 1-D rod), the static kernel of Flamant
  ((1 − ν)/(μ|k|)) and Cerruti, and the bonded/frictionless ratio of the static rocking
  stiffness at ν = 0.3 (+3.5 % with the footing free to translate);
- the handbook formulas of Gazetas (1991, J. Geotech. Eng. 117(9), Table 1) against hand values;
- the free rocking decay of a massive footing in the time domain (run_dynamic, Newmark, Lysmer
  sides, a deep rigid base whose reflections return after the window): the complex root of the
  footing–story system's characteristic equation with the computed K_r(ω).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import least_squares

from upliftlab import cli
from upliftlab.checks import InputError
from upliftlab.continuum import OPEN, build_model, run_dynamic
from upliftlab.continuum.dynamics.run import DynamicOptions
from upliftlab.continuum.impedance.gazetas import (ROCKING_FIT, handbook_strip,
                                                   lysmer_analog_velocity)
from upliftlab.continuum.impedance.halfplane import green, strip_impedance
from upliftlab.continuum.impedance.analysis import (DEFAULT_A0, ImpedanceOptions, impedance,
                                                    impedance_model, static_normalisers)
from upliftlab.continuum.impedance.output import (ImpedanceAccuracyError, impedance_errors,
                                                  reference_for, verify)
from upliftlab.motions import free_vibration
from upliftlab.results import read_netcdf
from upliftlab.scenes import ContinuumOptions, Soil, load_scene

E, RHO, B = 50e3, 1.8, 2.0  # kPa, t/m³, m
A0 = (0.1, 0.5, 1.0, 1.5, 2.0)


def soil(nu, interface="frictionless"):
    return Soil(youngs_modulus=E, poisson_ratio=nu, density=RHO, interface=interface)


def speeds(nu):
    G = E / (2 * (1 + nu))
    vs = math.sqrt(G / RHO)
    return G, vs, vs * math.sqrt(2 * (1 - nu) / (1 - 2 * nu))


# ---------------------------------------------------------------------------------------------
# 1. The exact reference
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("nu", [0.25, 1 / 3])
def test_half_plane_reference_meets_its_static_and_high_frequency_limits(nu):
    # Static rocking of the frictionless strip: measured 1.000002 of the closed form at a0 =
    # 1e-3 (the remaining term is O(a0²)); asserted 1e-4. High frequency (a0 = 40): the
    # dashpots reach ρV_pB, ρV_sB, ρV_pI within 0.02 % (measured); asserted 0.5 %.
    G, vs, vp = speeds(nu)
    exact = math.pi * G * B ** 2 / (8 * (1 - nu))
    low = strip_impedance([1e-3], shear_modulus=G, poisson=nu, width=B)
    assert low.rocking[0].real / exact - 1 == pytest.approx(0.0, abs=1e-4)
    high = strip_impedance([40.0], shear_modulus=G, poisson=nu, width=B, interface="bonded")
    omega = 40.0 * vs / (B / 2)
    assert high.vertical[0].imag / omega / (RHO * vp * B) == pytest.approx(1.0, abs=0.005)
    assert high.horizontal[0].imag / omega / (RHO * vs * B) == pytest.approx(1.0, abs=0.005)
    assert high.rocking[0].imag / omega / (RHO * vp * B ** 3 / 12) == pytest.approx(1.0,
                                                                                    abs=0.005)


def test_half_plane_green_function_tends_to_flamant_and_cerruti():
    # For |k| ≫ k_s the dynamic kernel is the static one: G_xx, G_zz → (1 − ν)/(μ|k|) and
    # G_xz → −i(1 − 2ν)/(2μk) (Flamant, Cerruti); the next term is O((k_s/k)²): at k = 1000 k_s
    # the relative difference is below 1e-5.
    nu, a0 = 0.3, 1.0
    gxx, gzz, gxz = green(np.array([1000.0]), a0, nu)
    assert gxx[0].real * 1000.0 == pytest.approx(1 - nu, rel=1e-5)
    assert gzz[0].real * 1000.0 == pytest.approx(1 - nu, rel=1e-5)
    assert (gxz[0] * 1000.0).imag == pytest.approx(-(1 - 2 * nu) / 2, rel=1e-5)


def test_half_plane_reference_bonded_rocking_and_convergence():
    # Anchors §4: a bonded strip at ν = 0.3 is 3.5 % stiffer in rocking than the frictionless
    # one when free to translate (K_r − K_hr²/K_h): measured +3.497 % at a0 = 1e-4; asserted
    # within 0.1 %. The Chebyshev series converges: 16 and 32 terms agree to 2e-5 at a0 = 1
    # (measured 1.2e-5 on K_r); asserted 1e-4.
    G = E / 2.6
    bonded = strip_impedance([1e-4], shear_modulus=G, poisson=0.3, width=B, interface="bonded",
                             terms=32).matrix[0]
    relaxed = strip_impedance([1e-4], shear_modulus=G, poisson=0.3, width=B).matrix[0]
    free = (bonded[2, 2] - bonded[0, 2] ** 2 / bonded[0, 0]).real
    assert free / relaxed[2, 2].real - 1 == pytest.approx(0.035, abs=0.001)
    k16, k32 = (strip_impedance([1.0], shear_modulus=G, poisson=0.3, width=B,
                                interface="bonded", terms=t).matrix[0] for t in (16, 32))
    assert np.max(np.abs(k16 - k32) / np.abs(k32).max()) < 1e-4


def test_half_plane_reference_refuses_bad_input():
    with pytest.raises(InputError, match="poisson = 0.5"):
        strip_impedance([1.0], shear_modulus=1.0, poisson=0.5, width=1.0)
    with pytest.raises(InputError, match="a0"):
        strip_impedance([0.0], shear_modulus=1.0, poisson=0.3, width=1.0)
    with pytest.raises(InputError, match="interface"):
        strip_impedance([1.0], shear_modulus=1.0, poisson=0.3, width=1.0, interface="rough")


# ---------------------------------------------------------------------------------------------
# 2. The FE impedance against the exact one
# ---------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def computed():
    """The FE impedance on the default PML box (6B × 3B, layer 1.5B), Q2, 16 across."""
    out = {}
    for nu in (0.25, 1 / 3):
        for interface in ("frictionless", "bonded"):
            options = ImpedanceOptions(a0=A0)
            model = impedance_model(soil(nu, interface), B, ContinuumOptions(), options)
            out[nu, interface] = impedance(model, options)
    return out


@pytest.mark.parametrize("nu", [0.25, 1 / 3])
@pytest.mark.parametrize("interface", ["frictionless", "bonded"])
def test_fe_impedance_matches_the_exact_half_plane(computed, nu, interface):
    # Tolerances of the issue: K_r and K_h within 3 %, K_v within 5 % of the exact solution
    # for a0 ≤ 2. Measured (16 across, largest over a0 = 0.1 … 2): frictionless K_v 0.21 %,
    # K_r 0.47 % (ν = 0.25) and 0.55 % (1/3); bonded K_v 0.23 / 0.25 %, K_r 0.40 / 0.52 %,
    # K_h 0.66 / 0.69 %, K_hr 0.29 / 0.42 % (ν = 0.25 / 1/3).
    imp = computed[nu, interface]
    errors = impedance_errors(imp, reference_for(imp))
    assert np.max(errors["v"]) <= 0.05
    assert np.max(errors["r"]) <= 0.03
    if interface == "bonded":
        assert np.max(errors["h"]) <= 0.03
        assert np.max(errors["hr"]) <= 0.03
    else:  # no shear under a frictionless base: no horizontal impedance at all
        assert np.all(imp.K_h == 0.0) and np.all(imp.K_hr == 0.0)
    for mode in ("v", "r") + (("h",) if interface == "bonded" else ()):
        assert np.all(getattr(imp, f"K_{mode}").imag > 0.0)  # e^{+iωt}: radiation dissipates


def test_fe_rocking_tends_to_the_static_closed_form(computed):
    # Anchors §4: K_r → πGB²/(8(1 − ν)) as a0 → 0 (frictionless). At a0 = 0.1 the exact
    # dynamic factor is 0.9902 (ν = 1/3); the FE's k_r = Re K_r/K_static is within 0.2 % of it
    # (measured 0.9914, +0.12 %) and so within 1.2 % of the static value.
    imp = computed[1 / 3, "frictionless"]
    k_r, _ = imp.coefficients("r")
    exact = reference_for(imp).rocking.real / static_normalisers(E / (2 * (1 + 1 / 3)), 1 / 3,
                                                                 B)["r"]
    assert k_r[0] == pytest.approx(exact[0], rel=0.002)
    assert k_r[0] == pytest.approx(1.0, abs=0.012)


@pytest.mark.parametrize("nu", [0.25, 1 / 3])
def test_fe_dashpots_head_for_the_wave_impedances(computed, nu):
    # The exact dashpots at a0 = 2 (bonded) are already 0.989 / 0.971 ρV_pB (vertical) and
    # 0.990 / 1.000 ρV_sB (horizontal) at ν = 0.25 / 1/3, while rocking is at 0.78 / 0.74 ρV_pI
    # (still rising: 0.998 at a0 = 20, first test). The FE's are within 3 % of the exact ones
    # (measured 0.990 / 0.973 and 0.986 / 0.993), and 19 % / 20 % above the handbook's
    # vertical dashpot ρV_La B (c̃ = 1), which is not the limit.
    G, vs, vp = speeds(nu)
    imp = computed[nu, "bonded"]
    ref = reference_for(imp)
    last = -1
    for mode, limit in (("v", RHO * vp * B), ("h", RHO * vs * B)):
        fe = imp.dashpot(mode)[last]
        exact = {"v": ref.vertical, "h": ref.horizontal}[mode][last].imag / imp.omega[last]
        assert fe == pytest.approx(exact, rel=0.03)
        assert fe / limit == pytest.approx(1.0, abs=0.05)
    book = handbook_strip(imp.a0, shear_modulus=G, poisson=nu, density=RHO, width=B)
    assert imp.dashpot("v")[last] / book.C_v - 1 > 0.1


def test_pml_impedance_does_not_depend_on_the_box():
    # A larger PML box (10B × 5B, layer 2.5B) changes K_v and K_r by less than 1 % at a0 ≤ 1
    # (measured, 12 across: 0.11 % and 0.06 %); a static box would not (the 2D static vertical
    # stiffness grows without bound with the box).
    nu = 0.3
    results = []
    for width, depth, layer in ((6.0, 3.0, 1.5), (10.0, 5.0, 2.5)):
        options = ImpedanceOptions(a0=(0.1, 0.5, 1.0), domain_width=width, domain_depth=depth,
                                   pml_thickness=layer)
        model = impedance_model(soil(nu), B, ContinuumOptions(elements_across=12), options)
        results.append(impedance(model, options))
    for mode in ("K_v", "K_r"):
        a, b = (getattr(r, mode) for r in results)
        assert np.max(np.abs(a - b) / np.abs(b)) < 0.01


# ---------------------------------------------------------------------------------------------
# 3. The handbook formulas
# ---------------------------------------------------------------------------------------------


def test_gazetas_strip_formulas_against_hand_values():
    # Hand values, G = 1, ρ = 1 (V_s = 1), ν = 1/3, B = 2 (b = 1): K_v = 0.73/(2/3) = 1.095,
    # K_h = 2/(5/3) = 1.2, K_r = 1.2 (4/3)^0.75 / (2/3) = 2.233452, V_La = 3.4/(π 2/3) =
    # 1.623380, C_v = ρ V_La B = 3.246761, C_h = ρ V_s B = 2, C_r = ρ V_La B³/12 = 1.082254,
    # k_r(a0 = 1.5) = 1 − 0.2 · 1.5 = 0.7.
    book = handbook_strip([1.5], shear_modulus=1.0, poisson=1 / 3, density=1.0, width=2.0)
    assert book.K_v == pytest.approx(1.095, rel=1e-12)
    assert book.K_h == pytest.approx(1.2, rel=1e-12)
    assert ROCKING_FIT == pytest.approx(1.488968, rel=1e-6)
    assert book.K_r == pytest.approx(2.233452, rel=1e-6)
    assert lysmer_analog_velocity(1.0, 1 / 3) == pytest.approx(1.623380, rel=1e-6)
    assert book.C_v == pytest.approx(3.246761, rel=1e-6)
    assert book.C_h == pytest.approx(2.0, rel=1e-12)
    assert book.C_r == pytest.approx(1.082254, rel=1e-6)
    assert book.k_r[0] == pytest.approx(0.7, rel=1e-12)
    assert book.impedance("r")[0] == pytest.approx(book.K_r * 0.7 + 1.5j * book.C_r, rel=1e-12)


# ---------------------------------------------------------------------------------------------
# 4. The record, the command, bad input
# ---------------------------------------------------------------------------------------------


def test_impedance_record_round_trips_and_summarises(computed, tmp_path):
    imp = computed[0.25, "bonded"]
    data = imp.to_dict()
    assert data["a0"] == list(A0) and len(data["K_r"]) == len(A0)
    assert data["K_r"][2] == [imp.K_r[2].real, imp.K_r[2].imag]
    back, attrs = read_netcdf(imp.save(tmp_path / "impedance.nc"))
    assert np.array_equal(back["K_hr_imag"], imp.K_hr.imag)
    assert np.array_equal(back["a0"], imp.a0) and attrs["kind"] == "impedance"
    k, c = imp.coefficients("v")
    assert np.allclose((k + 1j * imp.a0 * c) * imp.normalisers()["v"], imp.K_v, rtol=1e-12)
    assert np.allclose(imp.dashpot("r") * imp.omega, imp.K_r.imag, rtol=1e-12)


def test_verify_refuses_an_inaccurate_impedance():
    # 4 across B is too coarse at a0 = 2 (K_r 22.5 % and K_v 6.2 % off, measured): verify must
    # refuse it.
    options = ImpedanceOptions(a0=(2.0,))
    imp = impedance(impedance_model(soil(0.25), B, ContinuumOptions(elements_across=4), options),
                    options)
    with pytest.raises(ImpedanceAccuracyError, match="refine the mesh"):
        verify(imp, reference_for(imp))


def test_command_prints_the_impedance_as_json(capsys, tmp_path):
    code = cli.main(["continuum", "strip_footing_clay", "--analysis", "impedance",
                     "--set", "soil.model=elastic", "--a0", "0.25,1", "--json", "--no-render",
                     "--out", str(tmp_path)])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["a0"] == [0.25, 1.0] and set(out) >= {"K_v", "K_h", "K_r", "K_hr", "exact"}
    assert all(len(pair) == 2 and pair[1] >= 0.0 for pair in out["K_r"])
    assert out["max_error"]["K_r"] <= 0.03
    assert (tmp_path / "impedance.nc").exists()


@pytest.mark.parametrize("argv, message", [
    (["--analysis", "impedance"], "soil.model = 'tresca'"),
    (["--analysis", "impedance", "--set", "soil.model=elastic", "--a0", "0,1"], "a0"),
    (["--analysis", "impedance", "--set", "soil.model=elastic", "--boundary", "sponge"],
     "impedance boundary"),
    (["--analysis", "impedance", "--set", "soil.model=elastic", "--set",
      "soil.interface=coulomb", "--set", "soil.interface_friction=0.5"], "soil.interface"),
    (["--analysis", "impedance", "--set", "soil.model=elastic", "--mesh", "domain_width=3"],
     "pml_thickness"),
    (["--analysis", "pushover", "--a0", "1"], "only the impedance analysis takes it"),
])
def test_command_refuses_bad_input_before_any_work(argv, message, capsys, tmp_path):
    code = cli.main(["continuum", "strip_footing_clay", *argv, "--out", str(tmp_path / "x")])
    assert code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_default_frequencies_span_the_issue_range():
    assert min(DEFAULT_A0) == pytest.approx(0.1) and max(DEFAULT_A0) == pytest.approx(2.0)


# ---------------------------------------------------------------------------------------------
# 5. Time domain: free rocking decay
# ---------------------------------------------------------------------------------------------

#: A massive footing (I₀ = 14 t m²/m) with a light stiff story (1 kN/m at 2 m, T = 0.01 s) on
#: the clay scene's elastic soil, frictionless (u held, θ uncoupled from v): its rocking mode
#: sits at a0 ≈ 0.5. The box is 30B × 25B: the bottom's P reflection returns after 0.52 s.
DECAY = ["soil.model=elastic", "structure.weight=1.0", "structure.vertical_weight=171.39",
         "structure.period=0.01", "structure.height=2.0", "structure.rotary_inertia=14.0",
         "structure.damping_ratio=0.05", "continuum.domain_width=30",
         "continuum.domain_depth=25"]


def predicted_rocking(scene, n, exact=False) -> complex:
    """The complex root ω = ω_d + iσ of the footing–story system with the computed K_r(ω)
    (``exact``: the half-plane's): (K_r(ω) − ω²(I₀ + m h²))(k + iωc − ω² m) − ω⁴ m² h² = 0,
    K_r a cubic in ω fitted to the impedance at a0 = 0.3 … 0.7 (its continuation off the real
    axis)."""
    st = scene.structure
    story = st.stories[0]
    m, h, k = story.weight / scene.g, story.height, story.stiffness
    c = 2 * st.damping_ratio * math.sqrt(k * m)
    options = ImpedanceOptions(a0=tuple(np.linspace(0.3, 0.7, 9)))
    imp = impedance(impedance_model(scene.soil, scene.foundation.width,
                                    ContinuumOptions(elements_across=n), options), options)
    K_r = reference_for(imp).rocking if exact else imp.K_r
    coef = np.polyfit(imp.omega, K_r, 3)

    def det(w):
        return (np.polyval(coef, w) - w * w * (st.rotary_inertia + m * h * h)) \
            * (k + 1j * w * c - w * w * m) - w ** 4 * (m * h) ** 2

    w = complex(imp.omega[4])
    for _ in range(40):
        d = 1e-6 * abs(w)
        w -= det(w) / ((det(w + d) - det(w - d)) / (2 * d))
    return w


def measured_rocking(scene, duration=0.48) -> tuple[float, float]:
    """(ω_d, σ) of θ(t) = A e^{−σt} cos(ω_d t + φ) fitted over 0.1 … 0.48 s of a Newmark run
    (no numerical damping) from a story velocity of 0.01 m/s."""
    model = build_model(scene)
    run = run_dynamic(model, scene, free_vibration(duration, 0.005, velocity=0.01),
                      DynamicOptions(method="implicit", scheme="newmark", sides="lysmer",
                                     base="rigid", snapshots=0, energy=False))
    assert not (run.status == OPEN).any()  # linear: the footing stays in full contact
    t, theta = run.time, run.theta
    window = t >= 0.1
    fit = least_squares(lambda p: p[0] * np.exp(-p[1] * t[window])
                        * np.cos(p[2] * t[window] + p[3]) - theta[window],
                        [np.max(np.abs(theta)), 3.0, 50.0, 0.0])
    assert np.sqrt(np.mean(fit.fun ** 2)) < 0.01 * abs(fit.x[0])  # one damped mode
    return fit.x[2], fit.x[1]


def test_free_rocking_decay_agrees_with_the_computed_impedance():
    # Measured (8 across): time domain ω_d = 51.711 rad/s, σ = 3.066 1/s (ζ = 0.059); predicted
    # from the FE K_r(ω) with the same elements across: 51.861, 3.075 (−0.29 %, −0.28 %).
    # Asserted: ω_d within 1 %, σ within 5 % (the decay is radiation only: Newmark adds none,
    # and its period error at 1/49 of the period is 0.14 %).
    scene = load_scene("strip_footing_clay", overrides=DECAY + ["continuum.elements_across=8"])
    omega, sigma = measured_rocking(scene)
    root = predicted_rocking(scene, 8)
    message = f"measured {omega:.3f}, {sigma:.4f}; predicted {root.real:.3f}, {root.imag:.4f}"
    assert omega == pytest.approx(root.real, rel=0.01), message
    assert sigma == pytest.approx(root.imag, rel=0.05), message


@pytest.mark.slow
def test_free_rocking_decay_converges_to_the_exact_half_plane():
    # 16 across (35k DOFs, about a minute): measured ω_d = 51.756, σ = 3.061 against the
    # exact half-plane's root 51.769, 3.055 (K_r from halfplane.py): within 0.03 % and 0.2 %;
    # asserted 0.5 % and 2 %.
    scene = load_scene("strip_footing_clay", overrides=DECAY + ["continuum.elements_across=16"])
    omega, sigma = measured_rocking(scene)
    root = predicted_rocking(scene, 16, exact=True)
    assert omega == pytest.approx(root.real, rel=0.005)
    assert sigma == pytest.approx(root.imag, rel=0.02)
