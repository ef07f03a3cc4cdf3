"""The half-plane's stiffnesses at the rocking frequency (comparisons/beds/rocking_stiffness)
and the beds calibrated to them.

References: linear interpolation by hand between a synthetic Impedance record's frequencies;
the fixed point ω = ω̃(K(ω)) with a prescribed K_r(ω) = K₀ − sω, whose solution is a root of a
polynomial found by numpy's companion-matrix eigenvalues (an independent algorithm, not the
iteration); Veletsos & Meek's (1974) T̃ = T √(1 + k/K_h + k h²/K_r) written out here; the
reduced model's own bonded eigenproblem (radiation.rocking_frequency) for the structure on the
bed calibrated to K_r(ω̃); the closed-form low-frequency behaviour of the strip's vertical
compliance on the half-plane, Re(1/K_v) growing as ((1 − ν)/(πG)) ln(1/a0) (the Flamant
kernel (1 − ν)/(G|k|) integrated against the punch's pressure J₀(kb)², cut off at k_s); the
exact half-plane (continuum.impedance.halfplane, no FE) for the FE impedance at the map's
frequencies; and Gazetas' (1991) strip factors k_r = 1 − 0.20 a0 and chart of k_z.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.beds import BedReference, calibrate
from upliftlab.comparisons.beds.dashpots import bed_rocking_frequency
from upliftlab.comparisons.beds.rocking_stiffness import (flexible_base_omega,
                                                          impedance_stiffness,
                                                          rocking_stiffness,
                                                          stiffness_reference)
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.continuum.impedance.analysis import Impedance, ImpedanceOptions
from upliftlab.continuum.impedance.halfplane import strip_impedance
from upliftlab.scenes import Soil

G, NU, RHO = 2.0e4, 0.25, 2.0  # kPa, -, t/m³: V_s = 100 m/s, so ω = 100 a0 on B = 2 m


def _record(a0, K_v, K_r, K_h=None, interface="frictionless") -> Impedance:
    """A synthetic impedance on B = 2 m (b = 1 m), soil of V_s = 100 m/s: ω = 100 a0."""
    soil = Soil(youngs_modulus=2.0 * G * (1.0 + NU), poisson_ratio=NU, density=RHO)
    a0 = np.asarray(a0, dtype=float)
    matrix = np.zeros((a0.size, 3, 3), dtype=complex)
    matrix[:, 1, 1], matrix[:, 2, 2] = K_v, K_r
    if K_h is not None:
        matrix[:, 0, 0] = K_h
    return Impedance(a0=a0, matrix=matrix, soil=soil, width=2.0, interface=interface, mesh={},
                     options=ImpedanceOptions(a0=tuple(a0)), dofs=0)


def test_stiffness_interpolates_linearly_in_frequency_and_refuses_outside():
    """a0 = 0.5, 1.0 are ω = 50, 100 rad/s. Re K_v = 1e5, 8e4 and Re K_r = 5e4, 4e4: at ω = 60
    (a fifth of the way) K_v = 1e5 − 0.2·2e4 = 96,000 and K_r = 5e4 − 0.2·1e4 = 48,000 (to
    1e-12). ω = 40 is refused, naming the value and the range."""
    record = _record([0.5, 1.0], [1e5 + 5e3j, 8e4 + 8e3j], [5e4 + 1e3j, 4e4 + 3e3j])
    K_v, K_h, K_r = impedance_stiffness(record, 60.0)
    assert K_v == pytest.approx(96_000.0, rel=1e-12)
    assert K_r == pytest.approx(48_000.0, rel=1e-12) and K_h == 0.0
    with pytest.raises(InputError, match=r"ω = 40 rad/s .* outside .*\[50, 100\] rad/s"):
        impedance_stiffness(record, 40.0)


# A structure whose rocking frequency on K_r(ω) = K₀ − sω falls inside ω = 50 … 100 rad/s:
# m = 10 t/m, T = 0.05 s (k = m (2π/T)² = 157,914 kN/m/m), h = 2 m, K₀ = 4e5, s = 800.
M, T, H, K0, S = 10.0, 0.05, 2.0, 4.0e5, 800.0
A0_LINE = np.linspace(0.5, 1.0, 6)


def _line_record():
    omega = 100.0 * A0_LINE
    K_r = K0 - S * omega
    return _record(A0_LINE, 8.0e5 - 1000.0 * omega + 1e3j, K_r + 1e2j * omega)


def _root_in_range(coefficients) -> float:
    roots = np.roots(coefficients)
    real = [r.real for r in roots if abs(r.imag) < 1e-9 * abs(r) and 50.0 <= r.real <= 100.0]
    assert len(real) == 1
    return real[0]


def test_fixed_point_without_rotary_inertia_is_the_root_of_its_cubic():
    """I = 0: ω² = k K_r/(m (k h² + K_r)) with K_r = K₀ − sω is
    −m s ω³ + m (k h² + K₀) ω² + k s ω − k K₀ = 0; its one root in [50, 100] (numpy's
    companion matrix) is the iteration's ω̃ to 1e-9. K_v there is on its line 8e5 − 1000 ω,
    and C_r = Im K_r/ω = 100 (the record's)."""
    k = M * (2.0 * math.pi / T) ** 2
    exact = _root_in_range([-M * S, M * (k * H * H + K0), k * S, -k * K0])
    got = rocking_stiffness(_line_record(), mass=M, period=T, height=H)
    assert got.omega == pytest.approx(exact, rel=1e-9)
    assert got.K_r == pytest.approx(K0 - S * exact, rel=1e-9)
    assert got.K_v == pytest.approx(8.0e5 - 1000.0 * exact, rel=1e-9)
    assert got.C_r == pytest.approx(100.0, rel=1e-9)
    assert got.period == pytest.approx(2.0 * math.pi / got.omega, rel=1e-12)
    assert got.a0 == pytest.approx(got.omega / 100.0, rel=1e-12) and got.iterations > 1


def test_fixed_point_with_rotary_inertia_is_the_root_of_its_quintic():
    """I = 0.5 t m²/m: m I ω⁴ − [k I + m (k h² + K_r)] ω² + k K_r = 0 with K_r = K₀ − sω is
    m I ω⁴ + m s ω³ − (k I + m (k h² + K₀)) ω² − k s ω + k K₀ = 0; its root in [50, 100] is
    ω̃ to 1e-9, below the I = 0 one."""
    k, inertia = M * (2.0 * math.pi / T) ** 2, 0.5
    exact = _root_in_range([M * inertia, M * S, -(k * inertia + M * (k * H * H + K0)), -k * S,
                            k * K0])
    got = rocking_stiffness(_line_record(), mass=M, period=T, height=H, rotary_inertia=inertia)
    assert got.omega == pytest.approx(exact, rel=1e-9)
    assert got.omega < rocking_stiffness(_line_record(), mass=M, period=T, height=H).omega


def test_sway_gives_veletsos_and_meeks_period():
    """Frequency-independent K_h = 3e5, K_r = 4e5 on a bonded footing: T̃ = T √(1 + k/K_h +
    k h²/K_r) by hand, to 1e-10; on a frictionless footing, or with a tie as well, sway on the
    impedance's K_h is refused."""
    k = M * (2.0 * math.pi / T) ** 2
    record = _record(A0_LINE, 1e5 + 0j, 4e5 + 0j, K_h=3e5 + 0j, interface="bonded")
    got = rocking_stiffness(record, mass=M, period=T, height=H, sway=True)
    assert got.period == pytest.approx(T * math.sqrt(1 + k / 3e5 + k * H * H / 4e5), rel=1e-10)
    assert got.K_h == pytest.approx(3e5, rel=1e-12)
    assert flexible_base_omega(mass=M, stiffness=k, height=H, K_r=4e5) == pytest.approx(
        2.0 * math.pi / (T * math.sqrt(1 + k * H * H / 4e5)), rel=1e-12)
    with pytest.raises(InputError, match="'bonded' footing"):
        rocking_stiffness(_line_record(), mass=M, period=T, height=H, sway=True)
    with pytest.raises(InputError, match="tie = 300000.0"):
        rocking_stiffness(record, mass=M, period=T, height=H, sway=True, tie=3e5)


def _three_dof(k, K_h, K_r, m, m_b, I, h):
    """The lowest root of the swaying, rocking flexible base on (u_story, u_base, θ), by
    numpy's general eigenvalues of M⁻¹K (not the code's symmetric, condensed solve)."""
    K = np.array([[k, -k, -k * h], [-k, k + K_h, k * h], [-k * h, k * h, k * h * h + K_r]])
    w2 = np.linalg.eigvals(np.linalg.solve(np.diag([m, m_b, I]), K)).real
    return math.sqrt(float(np.min(w2)))


def test_a_tied_footing_with_its_mass_and_inertia_sways_as_the_three_dof_base():
    """The half-plane reference's footing: a tie of constant K_h = 3e5 with a footing mass
    1 % of the story's and a rotary inertia, on a frictionless impedance (K_r = 4e5): ω̃ is the
    3-DOF base's lowest root, to 1e-9; with the mass and inertia going to zero it tends to
    Veletsos & Meek's T̃ = T √(1 + k/K_h + k h²/K_r) (a massless DOF condensed, to 1e-9)."""
    k = M * (2.0 * math.pi / T) ** 2
    record = _record(A0_LINE, 1e5 + 0j, 4e5 + 0j)
    I = 0.5
    got = rocking_stiffness(record, mass=M, period=T, height=H, rotary_inertia=I, tie=3e5,
                            base_mass=0.01 * M)
    assert got.omega == pytest.approx(_three_dof(k, 3e5, 4e5, M, 0.01 * M, I, H), rel=1e-9)
    vm = 2.0 * math.pi / (T * math.sqrt(1 + k / 3e5 + k * H * H / 4e5))
    assert flexible_base_omega(mass=M, stiffness=k, height=H, K_r=4e5, K_h=3e5,
                               rotary_inertia=1e-9 * I, base_mass=0.0) == pytest.approx(
        vm, rel=1e-9)
    assert got.omega < rocking_stiffness(record, mass=M, period=T, height=H,
                                         rotary_inertia=I).omega
    with pytest.raises(InputError, match="footing mass"):
        rocking_stiffness(record, mass=M, period=T, height=H, tie=3e5, base_mass=-1.0)


def test_refusals_before_and_during_the_iteration():
    """Out of range (a soft K_r puts ω̃ below 50 rad/s), no convergence in 2 iterations, and
    bad structure fields are one-line InputErrors naming the value."""
    soft = _record(A0_LINE, np.full(6, 1e5 + 0j), np.full(6, 1e3 + 0j))
    with pytest.raises(InputError, match=r"outside the impedance's frequencies \[50, 100\]"):
        rocking_stiffness(soft, mass=M, period=T, height=H)
    with pytest.raises(InputError, match=r"did not converge to 1e-10 in 2 iterations .*"
                                         r"relative change 0\.0213"):
        rocking_stiffness(_line_record(), mass=M, period=T, height=H, max_iterations=2)
    with pytest.raises(InputError, match="structure.period"):
        rocking_stiffness(_line_record(), mass=M, period=-1.0, height=H)
    with pytest.raises(InputError, match="structure.height"):
        rocking_stiffness(_line_record(), mass=M, period=T, height=0.0)


def _reference(record, *, weight=M * 9.80665, K_v=2.0e5, K_r=5.0e5):
    structure = {"weight": weight, "height": H, "period": T, "damping_ratio": 0.0,
                 "rotary_inertia": M * (2.0 ** 2 + H * H) / 12.0}  # the map's rule
    return BedReference("clay", weight, 2.0, H, K_v, K_r, 10.0 * weight, G, NU,
                        extra={"impedance": record, "structure": structure})


def test_the_reference_at_the_rocking_frequency_and_the_beds_calibrated_to_it():
    """``static`` leaves the reference as it is. ``rocking`` replaces K_v, K_r by Re K(ω̃): the
    end-stiffened bed then has K_v(ω̃) and K_r(ω̃) (to 1e-9, a reachable ratio), the uniform
    bed K_r(ω̃); and the structure on that uniform bed rocks at ω̃ by the reduced model's own
    eigenproblem (radiation.rocking_frequency), to 1e-8. Unknown bases and a missing
    impedance are refused."""
    record = _line_record()
    ref = _reference(record)
    assert stiffness_reference(ref, "static", 9.80665) is ref
    at = stiffness_reference(ref, "rocking", 9.80665)
    rs = at.extra["stiffness"]["rocking"]
    assert (at.K_v, at.K_r) == (rs.K_v, rs.K_r)
    assert at.extra["stiffness"]["K_v_static"] == 2.0e5
    beds = {c.name: c for c in calibrate(at, wm.FULL_OPTIONS)}
    es = beds["end_stiffened"]
    assert es.matches == ("K_r", "K_v")
    assert es.vertical_stiffness == pytest.approx(rs.K_v, rel=1e-9)
    assert es.rocking_stiffness == pytest.approx(rs.K_r, rel=1e-9)
    assert beds["uniform"].rocking_stiffness == pytest.approx(rs.K_r, rel=1e-9)
    bed_omega = bed_rocking_frequency(at, SimpleNamespace(
        springs=48, end_length=1 / 3, max_end_stiffness_ratio=10.0))
    assert bed_omega == pytest.approx(rs.omega, rel=1e-8)
    with pytest.raises(InputError, match="options.bed_stiffness"):
        stiffness_reference(ref, "dynamic", 9.80665)
    with pytest.raises(InputError, match="impedance"):
        stiffness_reference(_reference(None), "rocking", 9.80665)


def test_the_half_planes_tied_footing_rocks_at_the_swaying_bases_frequency():
    """A reference whose footing sways on a tie (``extra["sway_stiffness"]``) and carries 1 %
    of the weight itself (``vertical_weight``), on a frequency-independent impedance: the
    beds are calibrated at the 3-DOF base's ω̃ (numpy, written out above), to 1e-9, and the
    structure on the uniform bed calibrated there, swaying on the same tie, rocks at that ω̃
    by the reduced model's own eigenproblem, to 1e-8."""
    record = _record(A0_LINE, np.full(6, 1e5 + 0j), np.full(6, 4e5 + 0j))
    ref = _reference(record, weight=0.99 * M * 9.80665)
    ref.extra["structure"]["vertical_weight"] = M * 9.80665
    ref.extra["sway_stiffness"] = 3e5
    at = stiffness_reference(ref, "rocking", 9.80665)
    s = ref.extra["structure"]
    k = 0.99 * M * (2.0 * math.pi / T) ** 2
    omega = _three_dof(k, 3e5, 4e5, 0.99 * M, 0.01 * M, s["rotary_inertia"], H)
    assert at.extra["stiffness"]["rocking"].omega == pytest.approx(omega, rel=1e-9)
    bed_omega = bed_rocking_frequency(at, SimpleNamespace(
        springs=48, end_length=1 / 3, max_end_stiffness_ratio=10.0))
    assert bed_omega == pytest.approx(omega, rel=1e-8)


def test_the_map_keeps_the_box_statics_by_default():
    """The map's default is unchanged (``static``) and its check refuses other names."""
    assert wm.FULL_OPTIONS.bed_stiffness == "static"
    from dataclasses import replace

    from upliftlab.comparisons.beds import BEDS
    from upliftlab.comparisons.studies.winkler_map.grid import check_options
    with pytest.raises(InputError, match="options.bed_stiffness"):
        check_options(replace(wm.FULL_OPTIONS, bed_stiffness="box"), tuple(BEDS))


def test_half_plane_vertical_compliance_grows_as_flamants_logarithm():
    """The 2D strip has no static K_v: Re(1/K_v) grows as ((1 − ν)/(πG)) ln(1/a0) as a0 → 0
    (closed form, module docstring). The exact half-plane's slope between a0 = 1e-4 and 1e-3
    is within 1 % of (1 − ν)/(πG) at ν = 0.3 (the next term is O(a0²)); and K_v(1e-4) is below
    K_v(1e-2): no finite static limit for a box to stand for."""
    G3, nu = 50.0e3 / 2.6, 0.3
    strip = strip_impedance([1e-4, 1e-3, 1e-2], shear_modulus=G3, poisson=nu, width=2.0)
    compliance = (1.0 / strip.vertical).real
    slope = (compliance[0] - compliance[1]) / math.log(10.0)
    assert slope == pytest.approx((1 - nu) / (math.pi * G3), rel=0.01)
    assert strip.vertical[0].real < strip.vertical[2].real


def test_no_bed_under_the_footing_reaches_the_half_planes_stiffness_ratio():
    """A bed of springs k_i at |x_i| ≤ b has K_r/K_v = Σ k x²/Σ k ≤ b². The exact half-plane's
    Re K_r/Re K_v (frictionless, ν = 0.3, B = 2 m) is above b² = 1 m² at every a0 from 0.02
    to 2 (measured 2.52 at a0 = 0.02, 1.51 at 0.25, 1.30 at 0.57, 1.26 at 0.87, 1.25 at 2; on a
    geometric grid of 12 from 0.02 to 2 the least is 1.25): neither the box's
    statics (1.568 m² on the map) nor the stiffness at any rocking frequency of this range can
    be matched in both K_v and K_r by a Winkler bed."""
    a0 = (0.02, 0.1, 0.25, 0.57, 0.87, 2.0)
    strip = strip_impedance(a0, shear_modulus=50.0e3 / 2.6, poisson=0.3, width=2.0)
    ratio = strip.rocking.real / strip.vertical.real
    assert ratio.min() > 1.2


def test_fe_impedance_at_the_maps_rocking_frequencies_matches_the_half_plane():
    """The FE impedance (PML box of the map's impedance, 8 across, the coarsest the existing
    tests trust below a0 = 0.5) against the exact half-plane at a0 = 0.02, 0.1, 0.25, where the
    map's structures rock (a0 0.057–0.246 at ω̃): Re K_v within 0.5 % (measured ≤ 0.07 %),
    Re K_r within 1 % (measured ≤ 0.45 %). The existing tests start at a0 = 0.1."""
    from upliftlab.continuum.impedance.analysis import impedance, impedance_model
    from upliftlab.scenes import ContinuumOptions

    a0 = (0.02, 0.1, 0.25)
    soil = Soil(youngs_modulus=50.0e3, poisson_ratio=0.3, density=1.8)
    options = ImpedanceOptions(a0=a0)
    fe = impedance(impedance_model(soil, 2.0, ContinuumOptions(elements_across=8), options),
                   options)
    exact = strip_impedance(a0, shear_modulus=soil.shear_modulus, poisson=0.3, width=2.0)
    np.testing.assert_allclose(fe.K_v.real, exact.vertical.real, rtol=0.005)
    np.testing.assert_allclose(fe.K_r.real, exact.rocking.real, rtol=0.01)
    # Gazetas (1991), Table 1, strip rocking: k_r = 1 − 0.20 a0 on the static π G B²/(8(1 − ν)):
    # the FE within 2 % (measured +0.8, +1.5, +1.5 % at a0 = 0.02, 0.1, 0.25 on 8 across)
    static = math.pi * soil.shear_modulus * 4.0 / (8.0 * 0.7)
    np.testing.assert_allclose(fe.K_r.real / static, 1.0 - 0.2 * np.asarray(a0), rtol=0.02)


def test_half_plane_dynamic_factors_against_gazetas_1991():
    """Published solutions for the strip (Gazetas 1991, J. Geotech. Eng. 117(9)): the rocking
    factor k_r = 1 − 0.20 a0 of Table 1, against the exact half-plane's Re K_r(a0)/K_r(0)
    (frictionless, ν = 1/3): within 1.5 % for a0 ≤ 1.5 (measured +1.1 % at 0.25, −0.1 % at 1);
    and the chart of k_z for L/B → ∞ (ν ≤ 0.4; read at a0 = 0.069, 0.256, 0.489, 0.747, 1.014
    as 1.057, 1.269, 1.367, 1.351, 1.272, geofound 1.1.4's digitisation of the chart,
    ``_raw_data/kz_gazetas_v_lte_0p4.csv``, column L/B = 1000) against Re K_v/(0.73 G/(1 − ν)):
    within 10 % (measured +1.7 … +8.2 %: a handbook chart, the same rise and fall)."""
    nu = 1.0 / 3.0
    a0 = np.array([1e-3, 0.25, 0.5, 1.0, 1.5])
    rocking = strip_impedance(a0, shear_modulus=1.0, poisson=nu, width=2.0).rocking.real
    np.testing.assert_allclose(rocking[1:] / rocking[0], 1.0 - 0.2 * a0[1:], rtol=0.015)
    a0 = np.array([0.069, 0.256, 0.489, 0.747, 1.014])
    chart = np.array([1.057, 1.269, 1.367, 1.351, 1.272])
    vertical = strip_impedance(a0, shear_modulus=1.0, poisson=nu, width=2.0).vertical.real
    np.testing.assert_allclose(vertical / (0.73 / (1.0 - nu)), chart, rtol=0.10)


def test_the_maps_beds_build_on_the_rocking_basis_from_the_kept_store():
    """One cell of the map (clay, FS_v 3, h/B 1.5, T 0.5 s) from the kept store's statics,
    impedance (16 across) and rotation pushovers: with ``bed_stiffness = "rocking"`` the map
    needs the impedance even for beds that do not; the registered beds build; the uniform
    bed has K_r(ω̃) and the impedance bed's dashpot frequency (the reduced model's own
    eigenproblem on that bed) is ω̃ to 1e-8; the default reference keeps the box's statics."""
    from upliftlab.comparisons.beds import BASE_SCENE, base_table, bed_foundation, bed_names
    from upliftlab.comparisons.beds.dashpots import impedance_dashpots_of
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies.winkler_map.maps import calibration_inputs
    from upliftlab.comparisons.studies.winkler_map.plan import bed_needs, reference, scene_of
    from upliftlab.comparisons.studies.winkler_map.points import point_table
    from upliftlab.scenes import load_scene
    from dataclasses import replace
    from pathlib import Path

    grid = replace(wm.FULL_GRID, soils=("clay",), fs_v=(3.0,), h_over_B=(1.5,),
                   periods=(0.5,))
    options = replace(wm.FULL_OPTIONS, bed_stiffness="rocking")
    assert bed_needs(("uniform",), options) == {"impedance"}
    assert bed_needs(("uniform",), wm.FULL_OPTIONS) == set()
    store = Store(Path(__file__).resolve().parents[1] / "benchmarks" / "winkler_map_store")
    statics, impedances, pushovers = calibration_inputs(grid, options, ("uniform",), store)
    st = statics["clay"]
    g = load_scene(BASE_SCENE).g
    table = point_table(base_table(), "clay", 16, st.V_ult / 3.0, 1.5, 0.5, g)
    args = (st, scene_of(table), table["structure"], impedances["clay"],
            pushovers["clay", 3.0])
    box = reference(*args)
    assert (box.K_v, box.K_r) == (st.K_v, st.K_r)
    ref = reference(*args, "rocking")
    at = ref.extra["stiffness"]["rocking"]
    assert ref.K_r == at.K_r and ref.K_v == at.K_v < st.K_v
    # every bed but the two that fit (qz 15 s, ES-f-I 45 s: their compiled pushovers), which
    # take K_v and K_r from the same reference
    tables = {name: bed_foundation(name, ref, options) for name in bed_names(options)
              if name not in ("qz", "end_stiffened_fitted_impedance")}
    assert all(t["support"] == "uplift" for t in tables.values())
    uniform = next(c for c in calibrate(ref, options) if c.name == "uniform")
    assert uniform.rocking_stiffness == pytest.approx(at.K_r, rel=1e-12)
    assert impedance_dashpots_of(ref, options).omega == pytest.approx(at.omega, rel=1e-8)


def test_the_command_lines_bed_stiffness_is_the_options():
    """``--bed-stiffness rocking`` sets ``options.bed_stiffness``; without it the default
    (``static``) stays; another word is refused by the parser (exit 2)."""
    import argparse

    from upliftlab.comparisons.studies.winkler_map.workflow import _arguments, _context_from

    parser = argparse.ArgumentParser()
    _arguments(parser)
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--no-figures", action="store_true")
    for argv, expected in ((["--bed-stiffness", "rocking"], "rocking"), ([], "static")):
        args = parser.parse_args(["--fast", "--no-figures", *argv])
        ctx = _context_from(args, wm.workflow.Context(fast=True), print)
        assert ctx.options.bed_stiffness == expected
    with pytest.raises(SystemExit) as exit_:
        parser.parse_args(["--bed-stiffness", "dynamic"])
    assert exit_.value.code == 2
