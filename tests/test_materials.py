"""Single-point verification of the soil constitutive models (upliftlab.continuum.materials).

Every test drives one or a few material points along a strain path and asserts numbers against a
stated reference: a closed form, an independent algorithm (closest-point projection by SciPy's
SLSQP, central finite differences of the return map) or the same path cut into more steps.
Units: kPa and strain; E = 50 MPa, ν = 0.3 (the clay scene's soil). Tension positive. The factory
and the input checks are in ``test_materials_inputs.py``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import minimize

from upliftlab.continuum import materials as mat

E, NU, CU = 5.0e4, 0.3, 50.0
G = E / (2 * (1 + NU))
K = E / (3 * (1 - 2 * NU))
LAM = K - 2 * G / 3
VI, VJ = [0, 1, 2, 0, 0, 1], [0, 1, 2, 1, 2, 2]
RNG_SEED = 20240611

VM = mat.VonMises(E, NU, CU)
VM_H = mat.VonMises(E, NU, CU, hardening_modulus=2.0e3)
TR = mat.Tresca(E, NU, CU)
MC = mat.MohrCoulomb(E, NU, 10.0, 30.0, 30.0)
MC_NA = mat.MohrCoulomb(E, NU, 10.0, 30.0, 5.0)
DP = mat.DruckerPrager(E, NU, 10.0, 30.0, 30.0)
DP_NA = mat.DruckerPrager(E, NU, 10.0, 30.0, 0.0)
def at_20_degrees(params):
    """The same model with φ = 20° (Mohr–Coulomb and Drucker–Prager at φ = 30°, ν = 0.3 never
    yield in oedometric compression: that needs sin φ < 1 − 2ν)."""
    if not hasattr(params, "friction_angle"):
        return params
    return replace(params, friction_angle=20.0, dilation_angle=min(params.dilation_angle, 20.0))


PLASTIC = {"von_mises": VM, "von_mises_hardening": VM_H, "tresca": TR,
           "mohr_coulomb": MC, "mohr_coulomb_psi5": MC_NA,
           "drucker_prager": DP, "drucker_prager_psi0": DP_NA}


# ---------------------------------------------------------------------------------------------
# Helpers: independent yield functions, path driver, finite-difference tangent
# ---------------------------------------------------------------------------------------------

def principal(sigma):
    return np.sort(np.linalg.eigvalsh(sigma))[::-1]


def yield_function(params, sigma, ebar=0.0):
    """The model's yield function, written out here from principal stresses and invariants."""
    s1, s2, s3 = principal(sigma)
    p = (s1 + s2 + s3) / 3
    j2 = ((s1 - s2) ** 2 + (s2 - s3) ** 2 + (s3 - s1) ** 2) / 6
    if isinstance(params, mat.VonMises):
        return math.sqrt(3 * j2) - (math.sqrt(3) * params.undrained_strength
                                    + params.hardening_modulus * ebar)
    if isinstance(params, mat.Tresca):
        return s1 - s3 - 2 * params.undrained_strength
    if isinstance(params, mat.MohrCoulomb):
        sp, cp = params.sin_phi, params.cos_phi
        return (s1 - s3) + (s1 + s3) * sp - 2 * params.cohesion * cp
    return math.sqrt(j2) + params.eta * p - params.xi * params.cohesion


def run_path(params, strains, state=None):
    """Drive one point through the (n, 3, 3) strain path; return stresses and states."""
    stresses, states = [], []
    for eps in strains:
        sigma, _, state = params(eps, state)
        stresses.append(sigma)
        states.append(state)
    return np.array(stresses), states


def voigt(sigma):
    return np.array([sigma[i, j] for i, j in zip(VI, VJ)])


def tile(state, n):
    return mat.State(np.repeat(state.plastic_strain[..., None], n, -1),
                     np.repeat(state.equivalent_plastic_strain[..., None], n, -1),
                     np.repeat(state.region[..., None], n, -1))


def fd_tangent(params, eps, state, h=1e-9):
    """Central differences of σ(ε; old state frozen) in the engineering-shear Voigt convention.

    Returns the 6×6 matrix and the return regions of the 12 perturbed evaluations."""
    perturbed = []
    for i, j in zip(VI, VJ):
        d = np.zeros((3, 3))
        d[i, j] += h / 2 if i != j else h
        d[j, i] += h / 2 if i != j else 0.0
        perturbed += [eps + d, eps - d]
    sigma, _, new = params(np.stack(perturbed, -1), tile(state, 12))
    columns = [(voigt(sigma[..., 2 * c]) - voigt(sigma[..., 2 * c + 1])) / (2 * h)
               for c in range(6)]
    return np.array(columns).T, new.region


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.diag(r))


ELASTIC_NORM = np.abs(mat.Elastic(E, NU)(np.zeros((3, 3)))[1]).max()  # λ + 2G


# ---------------------------------------------------------------------------------------------
# Elasticity
# ---------------------------------------------------------------------------------------------

def test_elastic_stress_is_hooke_and_plane_strain_sigma_zz():
    """σ = C:ε with C_ijkl = λ δ_ij δ_kl + G(δ_ik δ_jl + δ_il δ_jk), to 1e-12 (closed form)."""
    rng = np.random.default_rng(RNG_SEED)
    eps = rng.normal(size=(3, 3, 7, 4)) * 1e-3
    eps = 0.5 * (eps + eps.transpose(1, 0, 2, 3))
    d = np.eye(3)
    c4 = (LAM * np.einsum("ij,kl->ijkl", d, d)
          + G * (np.einsum("ik,jl->ijkl", d, d) + np.einsum("il,jk->ijkl", d, d)))
    sigma, tangent, state = mat.linear_elastic(eps, None, mat.Elastic(E, NU))
    expected = np.einsum("ijkl,kl...->ij...", c4, eps)
    assert sigma.shape == (3, 3, 7, 4) and tangent.shape == (6, 6, 7, 4)
    assert np.abs(sigma - expected).max() <= 1e-12 * np.abs(expected).max()
    assert np.all(state.region == mat.Region.ELASTIC)
    # Plane strain: σ_zz = ν(σ_xx + σ_yy), and the textbook 3×3 plane-strain matrix.
    sigma2, tangent2, _ = mat.linear_elastic(mat.plane_strain(eps[:2, :2]), None,
                                             mat.Elastic(E, NU))
    scale = np.abs(sigma2).max()
    assert np.abs(sigma2[2, 2] - NU * (sigma2[0, 0] + sigma2[1, 1])).max() <= 1e-12 * scale
    textbook = E / ((1 + NU) * (1 - 2 * NU)) * np.array(
        [[1 - NU, NU, 0], [NU, 1 - NU, 0], [0, 0, (1 - 2 * NU) / 2]])
    d_ps = mat.plane_strain_tangent(tangent2)
    assert d_ps.shape == (3, 3, 7, 4)
    assert np.abs(d_ps[..., 3, 2] - textbook).max() <= 1e-12 * E
    # The plane-strain matrix acts on (ε_xx, ε_yy, γ_xy) with engineering shear.
    e = eps[:2, :2, 3, 2]
    ps = mat.plane_strain_stress(sigma2)[:, 3, 2]
    assert np.abs(textbook @ [e[0, 0], e[1, 1], 2 * e[0, 1]] - ps).max() <= 1e-12 * scale


def test_vectorised_batch_equals_pointwise():
    """A (nelems, nqp) batch with mixed return regions equals point-by-point calls (1e-13)."""
    rng = np.random.default_rng(RNG_SEED + 1)
    eps = rng.normal(size=(3, 3, 6, 4)) * 2e-3
    eps = 0.5 * (eps + eps.transpose(1, 0, 2, 3))
    for params in (VM_H, TR, MC_NA, DP_NA):
        sigma, tangent, state = params(eps, params.initial_state((6, 4)))
        assert len(np.unique(state.region)) >= 2
        for e in range(6):
            for q in range(4):
                s1, d1, st1 = params(eps[:, :, e, q], None)
                assert np.allclose(s1, sigma[:, :, e, q], rtol=0, atol=1e-13 * 1e3)
                assert np.allclose(d1, tangent[:, :, e, q], rtol=0, atol=1e-13 * E)
                assert st1.region == state.region[e, q]


# ---------------------------------------------------------------------------------------------
# Closed-form strain paths
# ---------------------------------------------------------------------------------------------

def shear_path(gammas, pre=0.0):
    strains = np.zeros((len(gammas), 3, 3))
    strains[:, 0, 1] = strains[:, 1, 0] = np.asarray(gammas) / 2
    strains[:, [0, 1, 2], [0, 1, 2]] += pre
    return strains


@pytest.mark.parametrize("params", [VM, VM_H, TR], ids=["von_mises", "von_mises_H", "tresca"])
def test_undrained_simple_shear_saturates_at_cu(params):
    """Plane-strain simple shear: τ = Gγ until c_u, then τ = c_u (perfect plasticity) or
    τ = c_u + H γp/3 with γp = (Gγ − c_u)/(G + H/3) for von Mises with hardening (closed form,
    radial return is exact on this proportional path); to 1e-12 relative."""
    gamma_y = CU / G
    gammas = np.linspace(0, 10 * gamma_y, 41)
    sigma, states = run_path(params, shear_path(gammas))
    h = getattr(params, "hardening_modulus", 0.0)
    gamma_p = np.maximum(G * gammas - CU, 0.0) / (G + h / 3)
    tau = np.where(gammas <= gamma_y, G * gammas, CU + h * gamma_p / 3)
    assert np.abs(sigma[:, 0, 1] - tau).max() <= 1e-12 * CU
    assert np.abs(sigma[:, [0, 1, 2], [0, 1, 2]]).max() <= 1e-12 * CU  # no normal stress
    assert np.abs(2 * states[-1].plastic_strain[0, 1] - gamma_p[-1]).max() <= 1e-12
    assert states[-1].region == mat.Region.SMOOTH


def oedometer_path(e_max, n_load=40, n_unload=10, back=1e-3):
    load = np.linspace(0, e_max, n_load + 1)[1:]
    unload = e_max + np.linspace(0, back, n_unload + 1)[1:]
    strains = np.zeros((n_load + n_unload, 3, 3))
    strains[:, 0, 0] = np.concatenate([load, unload])
    return strains, n_load


@pytest.mark.parametrize("name", list(PLASTIC))
def test_oedometric_loading_stays_on_surface_and_unloads_elastically(name):
    """Uniaxial (oedometric) compression far past yield, then a small unloading.

    On the yield surface after yield: |f| < 1e-9 × stress scale (f written out independently).
    Unloading: dσ_xx/dε_xx = λ + 2G and dσ_yy/dε_xx = λ (closed form, 1e-9), plastic strain and
    ε̄p unchanged (exactly)."""
    params = at_20_degrees(PLASTIC[name])
    strains, n_load = oedometer_path(-0.02)
    sigma, states = run_path(params, strains)
    plastic = [i for i in range(n_load) if states[i].region != mat.Region.ELASTIC]
    assert len(plastic) >= n_load // 2
    for i in plastic:
        scale = np.abs(sigma[i]).max()
        f = yield_function(params, sigma[i], states[i].equivalent_plastic_strain)
        assert abs(f) < 1e-9 * scale
    de = np.diff(strains[n_load - 1:, 0, 0])
    assert np.allclose(np.diff(sigma[n_load - 1:, 0, 0]) / de, LAM + 2 * G, rtol=1e-9)
    assert np.allclose(np.diff(sigma[n_load - 1:, 1, 1]) / de, LAM, rtol=1e-9)
    for state in states[n_load:]:
        assert state.region == mat.Region.ELASTIC
        assert np.array_equal(state.plastic_strain, states[n_load - 1].plastic_strain)
        assert state.equivalent_plastic_strain == states[n_load - 1].equivalent_plastic_strain


def test_oedometric_closed_forms():
    """Closed forms for ε_xx = e < 0 past yield (lateral strain zero):

    - von Mises: σ_xx = K e − 2σ_y/3, σ_yy = σ_zz = K e + σ_y/3 (σ_y = √3 c_u);
    - Tresca (edge σ_yy = σ_zz): σ_xx = K e − 4c_u/3, σ_yy = K e + 2c_u/3;
    - Mohr–Coulomb at φ = 20° (compression edge): a straight line whose slope follows from
      consistency (1 + sin φ) dσ_yy = (1 − sin φ) dσ_xx and the flow rule of both active planes.
    All to 1e-10 relative."""
    e = -0.02
    strain = np.zeros((3, 3))
    strain[0, 0] = e
    sigma, _, st = VM(strain, None)
    sy = math.sqrt(3) * CU
    assert np.allclose(np.diag(sigma), [K * e - 2 * sy / 3] + [K * e + sy / 3] * 2, rtol=1e-12)
    sigma, _, st = TR(strain, None)
    assert st.region == mat.Region.EDGE_COMPRESSION
    assert np.allclose(np.diag(sigma), [K * e - 4 * CU / 3] + [K * e + 2 * CU / 3] * 2, rtol=1e-12)
    for params in (at_20_degrees(MC), at_20_degrees(MC_NA)):
        s, sp = params.sin_phi, params.sin_psi
        # Per unit dε_xx, with Δγ_a = Δγ_b = x: dε^p_yy = dε^p_zz = (1 + sin ψ) x,
        # dε^p_xx = −2(1 − sin ψ) x. Consistency fixes x, then the slope dσ_xx/dε_xx.
        def rates(x):
            dev_e = np.array([1 + 2 * (1 - sp) * x, -(1 + sp) * x, -(1 + sp) * x])
            return LAM * dev_e.sum() + 2 * G * dev_e
        r0, r1 = rates(0.0), rates(1.0) - rates(0.0)
        x = ((1 - s) * r0[0] - (1 + s) * r0[1]) / ((1 + s) * r1[1] - (1 - s) * r1[0])
        slope = rates(x)
        s1, _, st1 = params(strain, None)
        strain2 = strain * 1.5
        s2, _, st2 = params(strain2, None)
        assert st1.region == st2.region == mat.Region.EDGE_COMPRESSION
        assert np.allclose(np.diag(s2 - s1) / (0.5 * e), slope, rtol=1e-10)


def biaxial(params, p0=100.0, e_max=-0.1, steps=200):
    """Plane-strain biaxial compression: σ_xx = −p0 held by Newton on ε_xx (consistent tangent),
    ε_yy driven, ε_zz = γ = 0. Returns stresses, states and each step's residual history."""
    state = None
    e_xx = 0.0
    sigmas, states, histories = [], [], []
    for e_yy in np.linspace(-p0 / E, e_max, steps):
        history = []
        for _ in range(20):
            sigma, tangent, new = params(np.diag([e_xx, e_yy, 0.0]), state)
            history.append(abs(sigma[0, 0] + p0))
            if history[-1] < 1e-11 * p0:
                break
            e_xx -= (sigma[0, 0] + p0) / tangent[0, 0]
        state = new
        sigmas.append(sigma)
        states.append(new)
        histories.append(history)
    return np.array(sigmas), states, histories


@pytest.mark.parametrize("name", ["mohr_coulomb", "mohr_coulomb_psi5",
                                  "drucker_prager", "drucker_prager_psi0"])
def test_plane_strain_biaxial_limit_and_dilatancy(name):
    """Plane-strain biaxial test at confinement p0 = 100 kPa reaches the Mohr–Coulomb limit
    (σ1 − σ3)/2 = c cos φ − (σ1 + σ3)/2 sin φ with σ1 = −p0 (closed form; 1e-10 for Mohr–Coulomb,
    whose main-plane return is exact, and 1e-8 for Drucker–Prager, whose plane-strain match holds
    once ε̇p_zz = 0), and the dilatancy ratio ε̇p_v / (ε̇p_1 − ε̇p_3) = sin ψ (flow rule, 1e-8).
    Newton on ε_xx with the returned tangent converges quadratically:
    r_{k+1} ≤ 10 r_k²/p0 + 1e-12 p0 at every iteration of every step."""
    params = PLASTIC[name]
    p0 = 100.0
    sigma, states, histories = biaxial(params, p0)
    s, c = params.sin_phi, params.cohesion
    sigma3 = (-p0 * (1 + s) - 2 * c * params.cos_phi) / (1 - s)
    tol = 1e-10 if isinstance(params, mat.MohrCoulomb) else 1e-8
    assert abs(sigma[-1, 1, 1] - sigma3) < tol * abs(sigma3)
    assert abs(sigma[-1, 0, 0] + p0) < 1e-10 * p0
    assert sigma3 < sigma[-1, 2, 2] < -p0  # σ_zz is the intermediate principal stress
    assert states[-1].region == mat.Region.SMOOTH
    d = states[-1].plastic_strain - states[-2].plastic_strain
    ratio = np.trace(d) / (d[0, 0] - d[1, 1])
    assert abs(ratio - params.sin_psi) < 1e-8
    for history in histories:
        assert history[-1] < 1e-11 * p0
        for r0, r1 in zip(history, history[1:]):
            assert r1 <= 10 * r0 * r0 / p0 + 1e-12 * p0


@pytest.mark.parametrize("cls", [mat.MohrCoulomb, mat.DruckerPrager],
                         ids=["mohr_coulomb", "drucker_prager"])
def test_frictional_simple_shear_with_psi0_saturates(cls):
    """Isotropic precompression p0 then plane-strain simple shear, ψ = 0 (isochoric flow, so
    the mean stress stays −p0): τ saturates at c cos φ + p0 sin φ (closed form, 1e-10)."""
    p0 = 80.0
    params = cls(E, NU, 10.0, 30.0, 0.0)
    gammas = np.linspace(0, 0.02, 41)
    sigma, states = run_path(params, shear_path(gammas, pre=-p0 / (3 * K)))
    limit = params.cohesion * params.cos_phi + p0 * params.sin_phi
    assert abs(sigma[-1, 0, 1] - limit) < 1e-10 * limit
    assert np.allclose(np.trace(sigma[-1]) / 3, -p0, rtol=1e-12)
    assert states[-1].region == mat.Region.SMOOTH


@pytest.mark.parametrize("params", [MC, MC_NA, DP, DP_NA],
                         ids=["mc", "mc_psi5", "dp", "dp_psi0"])
def test_apex_return_in_tension(params):
    """Tension past the apex returns to σ = c cot φ 𝟏 (closed form, 1e-12), zero tangent, and
    εp = ε − c cot φ/(3K) 𝟏."""
    rng = np.random.default_rng(RNG_SEED + 2)
    apex = params.cohesion / math.tan(math.radians(params.friction_angle))
    dev = rng.normal(size=(3, 3)) * 1e-5
    dev = 0.5 * (dev + dev.T)
    dev -= np.trace(dev) / 3 * np.eye(3)
    strain = 3 * apex / (3 * K) * np.eye(3) + dev
    sigma, tangent, state = params(strain, None)
    assert state.region == mat.Region.APEX
    assert np.abs(sigma - apex * np.eye(3)).max() < 1e-12 * apex
    assert np.all(tangent == 0.0)
    expected = strain - apex / (3 * K) * np.eye(3)
    assert np.abs(state.plastic_strain - expected).max() < 1e-15


# ---------------------------------------------------------------------------------------------
# Consistent tangent against finite differences, each return region
# ---------------------------------------------------------------------------------------------

EXPECTED_REGIONS = {
    "von_mises": {0, 1}, "von_mises_hardening": {0, 1}, "tresca": {0, 1, 2, 3},
    "mohr_coulomb": {0, 1, 2, 3, 4}, "mohr_coulomb_psi5": {0, 1, 2, 3, 4},
    "drucker_prager": {0, 1, 4}, "drucker_prager_psi0": {0, 1, 4},
}


def sample_points(params, rng, per_region=4, tries=400):
    """Random rotated strains from a pre-strained (plastic) old state; per region, points whose
    12 finite-difference neighbours stay in the same region."""
    pre = np.diag([-4e-3, 1e-3, 0.0])
    _, _, old = params(pre, None)
    found = {}
    for _ in range(tries):
        e = np.diag(rng.normal(size=3)) * rng.choice([3e-4, 2e-3, 8e-3])
        e += np.eye(3) * rng.choice([0.0, -2e-3, 1e-3])
        q = random_rotation(rng)
        strain = pre + q @ e @ q.T
        _, tangent, new = params(strain, old)
        region = int(new.region)
        if len(found.get(region, [])) < per_region:
            fd, regions = fd_tangent(params, strain, old)
            if np.all(regions == region):
                found.setdefault(region, []).append((tangent, fd, strain, old))
    return found


@pytest.mark.parametrize("name", list(PLASTIC))
def test_consistent_tangent_matches_finite_differences(name):
    """dσ/dε by central differences (h = 1e-9, old state frozen) agrees with the returned
    tangent to 1e-5 × (λ + 2G) in every return region, and its plane-strain (xx, yy, xy) block
    is what plane_strain_tangent returns."""
    params = PLASTIC[name]
    found = sample_points(params, np.random.default_rng(RNG_SEED + 3))
    assert set(found) == EXPECTED_REGIONS[name]
    worst = 0.0
    for region, samples in found.items():
        for tangent, fd, _, _ in samples:
            worst = max(worst, np.abs(fd - tangent).max() / ELASTIC_NORM)
    assert worst < 1e-5
    tangent, fd, _, _ = found[1][0]
    idx = [0, 1, 3]
    assert np.array_equal(mat.plane_strain_tangent(tangent), tangent[np.ix_(idx, idx)])


@pytest.mark.parametrize("params", [TR, MC, MC_NA], ids=["tresca", "mc", "mc_psi5"])
def test_tangent_at_degenerate_edge(params):
    """Oedometric trial states have two equal principal stresses (σ_yy = σ_zz) and return to the
    compression edge (φ = 20°); the spectral tangent's equal-eigenvalue limit matches central
    differences (1e-5 × (λ + 2G)), also for a rotated frame."""
    rng = np.random.default_rng(RNG_SEED + 4)
    for q in (np.eye(3), random_rotation(rng)):
        strain = q @ np.diag([-0.01, 0.0, 0.0]) @ q.T
        _, tangent, state = at_20_degrees(params)(strain, None)
        assert state.region == mat.Region.EDGE_COMPRESSION
        fd, regions = fd_tangent(at_20_degrees(params), strain, mat.initial_state(), h=1e-10)
        assert np.abs(fd - tangent).max() < 1e-5 * ELASTIC_NORM


# ---------------------------------------------------------------------------------------------
# Independent algorithms: step size, closest-point projection, flow rule
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("params", [VM, VM_H, TR, MC], ids=["vm", "vm_H", "tresca", "mc"])
def test_one_step_equals_hundred_steps_on_proportional_path(params):
    """A proportional strain path with fixed principal axes ending 20 yield strains past yield:
    one step and 100 steps give the same stress and plastic strain to 1e-10 relative (radial
    return is exact for proportional loading on von Mises, with or without linear hardening;
    the main-plane return is exact while the principal axes and the active plane stay fixed)."""
    q = random_rotation(np.random.default_rng(RNG_SEED + 5))
    target = q @ np.diag([1.0e-2, -0.2e-2, -1.3e-2]) @ q.T
    one, _, one_state = params(target, None)
    many, states = run_path(params, np.linspace(0, 1, 101)[1:, None, None] * target)
    assert one_state.region == states[-1].region == mat.Region.SMOOTH
    assert np.abs(many[-1] - one).max() < 1e-10 * np.abs(one).max()
    diff = states[-1].plastic_strain - one_state.plastic_strain
    assert np.abs(diff).max() < 1e-10 * np.abs(one_state.plastic_strain).max()


def closest_point(params, trial):
    """Associated return = projection of the trial principal stresses onto the yield surface in
    the energy norm of C⁻¹ (principal space), solved by SLSQP over all six Mohr–Coulomb planes
    (or the Drucker–Prager cone)."""
    ce = LAM * np.ones((3, 3)) + 2 * G * np.eye(3)
    ce_inv = np.linalg.inv(ce)
    scale = np.abs(trial).max()
    if isinstance(params, mat.DruckerPrager):
        def g(x):
            s = x * scale
            dev = s - s.mean()
            return -(math.sqrt(0.5 * dev @ dev + 1e-30) + params.eta * s.mean()
                     - params.xi * params.cohesion) / scale
    else:
        sp = getattr(params, "sin_phi", 0.0)
        k = 2 * getattr(params, "cohesion", getattr(params, "undrained_strength", 0)) * getattr(
            params, "cos_phi", 1.0)
        rows = []
        for a in range(3):
            for b in range(3):
                if a != b:
                    v = np.zeros(3)
                    v[a], v[b] = 1 + sp, -(1 - sp)
                    rows.append(v)
        rows = np.array(rows)
        def g(x):
            return (k - rows @ (x * scale)) / scale
    res = minimize(lambda x: 0.5 * (trial / scale - x) @ ce_inv @ (trial / scale - x) * scale,
                   x0=np.full(3, -0.1),  # a hydrostatic compression: admissible for all
                   constraints=[{"type": "ineq", "fun": g}], method="SLSQP",
                   options={"ftol": 1e-15, "maxiter": 500})
    return np.sort(res.x * scale)[::-1]


@pytest.mark.parametrize("params", [TR, MC, DP], ids=["tresca", "mc", "dp"])
def test_associated_return_is_closest_point_projection(params):
    """For associated flow the return map is the C⁻¹-norm closest point of the yield surface.
    Random trial states in all regions agree with SciPy SLSQP to 1e-6 × stress scale."""
    rng = np.random.default_rng(RNG_SEED + 6)
    regions = set()
    for _ in range(16):
        e = rng.normal(size=3) * 3e-3 + rng.choice([0.0, -3e-3, 1e-3])
        sigma, _, state = params(np.diag(e), None)
        regions.add(int(state.region))
        trial = np.sort(LAM * e.sum() + 2 * G * e)[::-1]
        reference = closest_point(params, trial)
        assert np.abs(principal(sigma) - reference).max() < 1e-6 * np.abs(trial).max()
    assert len(regions) >= (4 if params is TR else 3)


@pytest.mark.parametrize("params", [MC_NA, mat.MohrCoulomb(E, NU, 0.0, 40.0, 10.0)],
                         ids=["c10_phi30_psi5", "c0_phi40_psi10"])
def test_non_associated_mohr_coulomb_flow_rule(params):
    """Random trials: the returned stress is admissible on all six planes and on the surface
    (|f| < 1e-10 × scale), and the plastic strain increment, in the trial principal frame, is a
    non-negative combination of the flow vectors (1 + sin ψ) e_a − (1 − sin ψ) e_b of the active
    planes (least-squares residual < 1e-10 × |Δεp|, multipliers ≥ 0)."""
    rng = np.random.default_rng(RNG_SEED + 7)
    sp = params.sin_psi
    def flow(a, b):
        v = np.zeros(3)
        v[a], v[b] = 1 + sp, -(1 - sp)
        return v
    active = {mat.Region.SMOOTH: [flow(0, 2)],
              mat.Region.EDGE_COMPRESSION: [flow(0, 2), flow(1, 2)],
              mat.Region.EDGE_EXTENSION: [flow(0, 2), flow(0, 1)]}
    seen = set()
    for _ in range(200):
        strain = np.diag(rng.normal(size=3) * 3e-3 + rng.choice([0.0, -4e-3, 1e-3]))
        q = random_rotation(rng)
        strain = q @ strain @ q.T
        sigma, _, state = params(strain, None)
        region = mat.Region(int(state.region))
        seen.add(region)
        if region == mat.Region.ELASTIC:
            continue
        scale = np.abs(sigma).max() + params.cohesion
        assert abs(yield_function(params, sigma)) <= 1e-10 * scale
        if region == mat.Region.APEX:
            assert np.trace(state.plastic_strain) > 0
            continue
        values, vectors = np.linalg.eigh(LAM * np.trace(strain) * np.eye(3) + 2 * G * strain)
        vectors = vectors[:, ::-1]
        dep = np.einsum("ia,ij,ja->a", vectors, state.plastic_strain, vectors)
        basis = np.array(active[region]).T
        gamma, *_ = np.linalg.lstsq(basis, dep, rcond=None)
        assert np.abs(basis @ gamma - dep).max() < 1e-10 * np.abs(dep).max()
        assert np.all(gamma > -1e-10 * np.abs(dep).max())
    assert seen == set(mat.Region)


def test_non_associated_drucker_prager_flow_rule():
    """Cone return with ψ = 10°: Δεp_v / (√2 ‖dev Δεp‖) = η̄ and dev Δεp ∥ s (flow rule of the
    potential √J2 + η̄ p, 1e-10), on the surface to 1e-10 × scale."""
    params = mat.DruckerPrager(E, NU, 10.0, 30.0, 10.0)
    rng = np.random.default_rng(RNG_SEED + 8)
    checked = 0
    for _ in range(40):
        strain = rng.normal(size=(3, 3)) * 3e-3
        strain = 0.5 * (strain + strain.T) - 1e-3 * np.eye(3)
        sigma, _, state = params(strain, None)
        if state.region != mat.Region.SMOOTH:
            continue
        checked += 1
        dep = state.plastic_strain
        dev = dep - np.trace(dep) / 3 * np.eye(3)
        s = sigma - np.trace(sigma) / 3 * np.eye(3)
        assert abs(np.trace(dep) / (math.sqrt(2) * np.linalg.norm(dev)) - params.eta_bar) < 1e-10
        assert np.abs(dev / np.linalg.norm(dev) - s / np.linalg.norm(s)).max() < 1e-10
        assert abs(yield_function(params, sigma)) < 1e-10 * (np.abs(sigma).max() + 10.0)
    assert checked >= 10


def test_drucker_prager_plane_strain_match():
    """For ψ = φ the match is the textbook η = 3 tan φ/√(9 + 12 tan²φ), ξ = 3/√(9 + 12 tan²φ);
    for ψ = 0 it is η = sin φ, ξ = cos φ; the apex ξc/η is c cot φ (closed forms, 1e-14)."""
    for phi in (5.0, 20.0, 35.0, 55.0):
        t = math.tan(math.radians(phi))
        assoc = mat.DruckerPrager(E, NU, 10.0, phi, phi)
        assert abs(assoc.eta - 3 * t / math.sqrt(9 + 12 * t * t)) < 1e-14
        assert abs(assoc.xi - 3 / math.sqrt(9 + 12 * t * t)) < 1e-14
        assert abs(assoc.eta_bar - assoc.eta) < 1e-14
        zero = mat.DruckerPrager(E, NU, 10.0, phi, 0.0)
        assert abs(zero.eta - math.sin(math.radians(phi))) < 1e-14
        assert abs(zero.xi - math.cos(math.radians(phi))) < 1e-14
        for p in (assoc, zero, mat.DruckerPrager(E, NU, 10.0, phi, phi / 2)):
            assert abs(p.xi * 10.0 / p.eta - 10.0 / t) < 1e-12 * 10.0 / t
