"""The soil's Rayleigh damping C = α M + β K₀ (``continuum.damping_ratio``,
upliftlab.continuum.dynamics.rayleigh), on both dynamic routes.

References, one per test:
- the free vibration of a uniform elastic column (shear sides, rigid base, the light footing of
  tests/test_continuum_far_field.py) rung by one sine period of base acceleration at its first
  mode: the closed form ω₁ = πV_s/(2H) and, for Rayleigh damping, the first mode's damping
  ratio ξ₁ = α/(2ω₁) + βω₁/2 (Chopra, Dynamics of Structures, ch. 11), read from the
  logarithmic decrement of the surface's free vibration; with the pair (2, 12) Hz, not
  bracketing f₁ = 5.17 Hz, so that ξ₁ = 3.5 % is not the ξ = 5 % given; the default pair
  (f₁ = V_s/(4H), 5 f₁) gives ξ₁ = ξ. Without damping the decrement is below 0.1 %.
- the energy balance of the same runs: kinetic + strain + damping + contact − input constant
  (the runs' own account, checked against the closed form above: the damping's work is most
  of the input once the column has rung down by exp(−2ξ₁ω₁t)), closing within 1 %;
- the stable step: central differences with a damping force at the last half-step velocity
  are stable for dt ≤ (2/ω)(√(1 + ξ²) − ξ) (Belytschko, Liu & Moran 2000, §6.3): a one-DOF
  oscillator stepped by the explicit kernel itself decays at 0.98 of that step and blows up
  at 1.02. Through the route's Maxwell arm the same oscillator stays bounded at 0.98 of
  ``damped_critical`` and blows up at 1.02, and for ω ≫ ω_c that limit is the closed form of
  a spring β ω_c k beside k, 2/(ω √(1 + β ω_c)); the route's step is the limit at the mesh's
  ω_max (an independent eigenvalue solve, ``critical_step``), and a run at it stays bounded;
- the Maxwell arm's stress under a constant strain rate: the closed form of its exponential
  update, σ_m = (1 − aⁿ) β D₀ ε̇ after n steps; with a = 0 its force is β K₀ v, K₀ assembled
  by scikit-fem;
- the refusals: the valid ranges stated in upliftlab/scenes/soil.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics import explicit_step as ex
from upliftlab.continuum.dynamics.ground import dynamic_ground
from upliftlab.continuum.dynamics.kernels import layout, soil_predict, viscous_force
from upliftlab.continuum.dynamics.rayleigh import (Rayleigh, damped_critical, rayleigh,
                                                   rayleigh_pair, viscous_tangent)
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.motions import Motion
from upliftlab.scenes import load_scene

DEPTH = 5.0  # m: continuum.domain_depth = 2.5 B, B = 2 m
COLUMN = ["continuum.elements_across=4", "continuum.boundary=shear", "continuum.domain_depth=2.5",
          "continuum.domain_width=3", "structure.weight=1", "structure.rotary_inertia=0.1",
          "soil.model=elastic"]
RATIO = 0.05
PAIR = (2.0, 12.0)  # Hz
DAMPED = [f"continuum.damping_ratio={RATIO}", f"continuum.damping_frequencies={list(PAIR)}"]


def _scene(extra=()):
    return load_scene("strip_footing_clay", overrides=COLUMN + list(extra))


def _omega1(scene) -> float:
    """ω₁ = πV_s/(2H) (rad/s) of the column."""
    return math.pi * math.sqrt(scene.soil.shear_modulus / scene.soil.density) / (2.0 * DEPTH)


def _pulse(period: float, a: float = 0.05, dt: float = 0.002, total: float = 1.6) -> Motion:
    """One sine period of base acceleration (g), then still ground to ``total`` (s)."""
    t = np.arange(int(total / dt) + 1) * dt
    return Motion("pulse", dt, np.where(t < period, a * np.sin(2.0 * np.pi * t / period), 0.0),
                  source="builtin:pulse")


def _ring(extra, method):
    scene = _scene(extra)
    model = build_model(scene)
    T1 = 2.0 * math.pi / _omega1(scene)
    result = run_dynamic(model, scene, _pulse(T1), DynamicOptions(method=method, snapshots=401),
                         progress=False)
    return scene, result


def _decrement(result, start: float) -> tuple[float, float]:
    """(ξ, period) of the surface's free vibration at the box's side from ``start`` (s): the
    peaks of |u_x| (one per half cycle), ln|u| fitted by a line of slope −ξω_n."""
    xy, direction = result.dof_xy, result.dof_direction
    dofs = np.flatnonzero((np.abs(xy[:, 1]) < 1e-9) & (direction == 0))
    j = dofs[np.argmax(xy[dofs, 0])]
    t, u = result.snapshot_time, result.displacement[:, j] - result.displacement[0, j]
    keep = t >= start
    t, u = t[keep], np.abs(u[keep])
    peaks = np.flatnonzero((u[1:-1] >= u[:-2]) & (u[1:-1] > u[2:])) + 1
    assert peaks.size >= 8
    slope = np.polyfit(t[peaks], np.log(u[peaks]), 1)[0]
    period = 2.0 * float(np.mean(np.diff(t[peaks])))
    omega_d = 2.0 * math.pi / period
    xi = -slope / math.hypot(omega_d, slope)  # σ = ξω_n, ω_d = ω_n √(1 − ξ²)
    return xi, period


@pytest.fixture(scope="module")
def rung():
    return {(method, damped): _ring(DAMPED if damped else [], method)
            for method in ("explicit", "implicit") for damped in (False, True)}


@pytest.mark.parametrize("method", ["explicit", "implicit"])
def test_the_first_mode_decays_at_the_rayleigh_ratio_of_its_closed_form_frequency(rung, method):
    # Reference: ω₁ = πV_s/(2H), ξ₁ = α/(2ω₁) + βω₁/2 (module docstring); the decrement to
    # 3 % of ξ₁, the period to 1 %; undamped: ξ below 0.1 %.
    scene, result = rung[(method, True)]
    w1 = _omega1(scene)
    w = 2.0 * math.pi * np.array(PAIR)
    alpha, beta = 2.0 * RATIO * w[0] * w[1] / w.sum(), 2.0 * RATIO / w.sum()
    xi1 = alpha / (2.0 * w1) + 0.5 * beta * w1
    assert xi1 == pytest.approx(0.03505, abs=5e-5)  # not the 5 % given: the pair misses f₁
    assert result.metadata["rayleigh_alpha"] == pytest.approx(alpha, rel=1e-12)
    assert result.metadata["rayleigh_beta"] == pytest.approx(beta, rel=1e-12)
    start = 4.0 * math.pi / w1  # after the pulse's period and one more
    xi, period = _decrement(result, start)
    assert xi == pytest.approx(xi1, rel=0.03)
    assert period == pytest.approx(2.0 * math.pi / w1, rel=0.01)
    undamped, _ = _decrement(rung[(method, False)][1], start)
    assert abs(undamped) < 1e-3


def test_the_default_pair_damps_the_column_at_the_ratio_given():
    # Reference: f₁ = V_s/(4H) is the column's own first frequency, so ξ₁ = ξ (5 %), to 3 %.
    scene, result = _ring([f"continuum.damping_ratio={RATIO}"], "explicit")
    f1 = _omega1(scene) / (2.0 * math.pi)
    assert result.metadata["damping_frequencies"] == pytest.approx([f1, 5.0 * f1], rel=1e-12)
    xi, _ = _decrement(result, 4.0 * math.pi / _omega1(scene))
    assert xi == pytest.approx(RATIO, rel=0.03)


@pytest.mark.parametrize("method", ["explicit", "implicit"])
def test_a_damped_run_closes_its_energy_balance(rung, method):
    # Reference: the balance's constant total (module docstring), within 1 % of the input;
    # the column rings down to exp(−2ξ₁ω₁ t) of its energy, so the damping took most of it.
    _, result = rung[(method, True)]
    energy = result.energy[-1]
    assert result.energy_balance_error < 0.01
    assert energy[2] > 0.8 * energy[3] > 0.0
    _, undamped = rung[(method, False)]
    assert undamped.energy_balance_error < 0.01
    # only the light story's own 5 % dashpot (0.2 % of the input), no soil damping
    assert 0.0 <= undamped.energy[-1, 2] < 0.005 * undamped.energy[-1, 3]


def _one_dof(factor: float, xi: float = 0.4, omega: float = 100.0, steps: int = 400,
             damping: Rayleigh | None = None) -> float:
    """|u| after ``steps`` explicit steps (the kernel soil_predict) of a unit-mass oscillator
    of frequency ``omega`` with a damping force 2ξ/ω k v at the last half-step velocity,
    dt = ``factor`` × (2/ω)(√(1 + ξ²) − ξ), from u = 1 at rest; with ``damping``, its α m
    and its β k v through the Maxwell arm s ← a s + (1 − a) β k v, a = exp(−ω_c dt), at
    dt = ``factor`` × ``damped_critical``."""
    beta = 2.0 * xi / omega
    dt = factor * (2.0 / omega) * (math.sqrt(1.0 + xi * xi) - xi)
    decay, alpha, arm = 0.0, 0.0, 0.0
    if damping is not None:
        beta, alpha = damping.beta, damping.alpha
        dt = factor * damped_critical(omega, damping)
        decay = math.exp(-damping.relaxation * dt)

    def one(x):
        return np.array([x], dtype=float)
    u, u_prev, v = one(1.0), one(1.0), one(0.0)
    R_prev, F_prev, u_next, v_next, zero = one(0), one(0), one(0), one(0), one(0)
    for k in range(steps):
        arm = decay * arm + (1.0 - decay) * beta * omega ** 2 * float(v[0])
        soil_predict(u, u_prev, v, omega ** 2 * u, one(arm), zero, one(1.0), zero,
                     zero, 0.0, 0.0, one(1.0), one(alpha), dt, k == 0, R_prev, F_prev, u_next,
                     v_next)
        u_prev, u, u_next = u, u_next, u_prev
        v, v_next = v_next, v
    return abs(float(u[0]))


def test_the_damped_step_limit_is_the_central_difference_one():
    # Reference: dt ≤ (2/ω)(√(1 + ξ²) − ξ) (module docstring): 2 % inside, the oscillator
    # dies out; 2 % beyond, it grows without bound.
    assert _one_dof(0.98) < 1e-10
    assert _one_dof(1.02) > 1e6


@pytest.mark.parametrize("omega", [2000.0, 7600.0, 30000.0])
def test_the_maxwell_arm_keeps_the_step_and_its_limit_is_the_schemes(omega):
    # Reference: the one-DOF oscillator stepped by the kernel with the arm (bounded at 0.98 of
    # damped_critical, growing at 1.02), and for ω ≫ ω_c the spring β ω_c k beside k,
    # 2/(ω √(1 + β ω_c)), to 0.2 %; the Kelvin–Voigt limit it avoids is shorter, the more so
    # the finer the mesh (ω_max 7,600 rad/s: the map's half-plane on 16 across). The
    # damping: ξ = 1 % at 1.29 and 6.45 Hz, the map's half-plane (ω_c = 405 rad/s).
    alpha, beta = rayleigh_pair(0.01, 1.29, 6.45)
    damping = Rayleigh(0.01, (1.29, 6.45), alpha, beta)
    assert damping.relaxation == pytest.approx(10 * 2 * math.pi * 6.45, rel=1e-12)
    assert _one_dof(0.98, omega=omega, steps=4000, damping=damping) < 1.0
    assert _one_dof(1.02, omega=omega, steps=400, damping=damping) > 1e6
    spring = 2.0 / (omega * math.sqrt(1.0 + beta * damping.relaxation))
    assert damped_critical(omega, damping) == pytest.approx(spring, rel=2e-3)
    xi = alpha / (2.0 * omega) + 0.5 * beta * omega  # the Kelvin–Voigt limit, by hand
    gain = damped_critical(omega, damping) / (2.0 / omega * (math.sqrt(1.0 + xi * xi) - xi))
    assert gain > {2000.0: 1.38, 7600.0: 3.16, 30000.0: 11.4}[omega]  # 1.383, 3.165, 11.50


def test_an_arm_that_does_not_remember_is_the_kelvin_voigt_force_beta_k0_v():
    # Reference: the assembled initial stiffness K₀ (scikit-fem's assembly of the elastic
    # tangent, continuum/assembly.py) times β and a random velocity: the arm with a = 0 gives
    # the same force to 1e-12 of its largest entry, and its stress is β D₀ ε̇ itself.
    from upliftlab.continuum import assembly
    from upliftlab.continuum.dynamics.iteration_matrix import elastic_plane_tangent

    scene = _scene(DAMPED)
    model = build_model(scene)
    damping = rayleigh(model)
    lay = layout(model.disc)
    v = np.random.default_rng(36).standard_normal(model.disc.ndofs)
    arm = np.full(lay.shape[:2] + (3,), 7.0)  # what a = 0 must forget
    work, out = np.zeros(lay.shape[::2] + (2,)), np.zeros(model.disc.ndofs)
    viscous_force(lay, v, viscous_tangent(model, damping), arm, 0.0, work, out)
    expected = damping.beta * (assembly.stiffness(model.disc, elastic_plane_tangent(model)) @ v)
    assert np.abs(out - expected).max() <= 1e-12 * np.abs(expected).max()


def test_the_arms_stress_relaxes_toward_the_kelvin_voigt_stress():
    # Reference: σ_m,n = aσ_m,n−1 + (1 − a) β D₀ ε̇ from zero is (1 − aⁿ) β D₀ ε̇ under a
    # constant ε̇: on every quadrature point of a 4-across mesh with the velocity field
    # v = (c y, 0) (ε̇xx = ε̇yy = 0, γ̇xy = c), to 1e-12 of β D₀ ε̇.
    scene = _scene(DAMPED)
    model = build_model(scene)
    damping = rayleigh(model)
    lay = layout(model.disc)
    D = viscous_tangent(model, damping)
    xy = model.disc.basis.doflocs
    v = np.zeros(model.disc.ndofs)
    v[0::2] = 0.3 * xy[1, 0::2]
    arm = np.zeros(lay.shape[:2] + (3,))
    work, out = np.zeros(lay.shape[::2] + (2,)), np.zeros(model.disc.ndofs)
    a = damping.arm_decay(1e-4)
    for _ in range(7):
        viscous_force(lay, v, D, arm, a, work, out)
    target = (1.0 - a ** 7) * D @ np.array([0.0, 0.0, 0.3])
    assert np.abs(arm - target).max() <= 1e-12 * np.abs(D @ np.array([0.0, 0.0, 0.3])).max()
    assert 0.0 < a < 1.0 and abs(target[2]) > 0.0


def test_the_explicit_step_is_the_damped_limit_and_a_run_at_it_is_stable():
    # Reference: the formula at ω_max of an independent eigenvalue solve (critical_step).
    scene = _scene(DAMPED)
    model = build_model(scene)
    options = DynamicOptions(method="explicit", snapshots=0)
    ground = dynamic_ground(model, options)
    mass = ex.lumped_mass(model)
    free = np.setdiff1d(np.arange(model.disc.ndofs), ground.fixed)
    _, omega = ex.critical_step(model, mass, free)
    w = 2.0 * math.pi * np.array(PAIR)
    alpha, beta = 2.0 * RATIO * w[0] * w[1] / w.sum(), 2.0 * RATIO / w.sum()
    damping = Rayleigh(RATIO, PAIR, alpha, beta)
    critical = damped_critical(omega, damping)  # its own test above
    motion = _pulse(2.0 * math.pi / _omega1(scene), total=0.3)
    settings = ex.explicit_settings(model, scene, motion, options, ground, mass, free)
    assert settings.critical == pytest.approx(critical, rel=1e-6)
    assert settings.reduction == pytest.approx(critical * omega / 2.0, rel=1e-6)
    assert settings.dt <= ex.STABILITY_FRACTION * critical
    result = run_dynamic(model, scene, motion, DynamicOptions(
        method="explicit", snapshots=0, dt=ex.STABILITY_FRACTION * critical), progress=False)
    assert np.all(np.isfinite(result.footing)) and result.energy_balance_error < 0.01
    with pytest.raises(InputError, match=r"DynamicOptions\.dt .*Maxwell arm relaxing"):
        run_dynamic(model, scene, motion, DynamicOptions(
            method="explicit", dt=1.001 * ex.STABILITY_FRACTION * critical), progress=False)


def test_the_compiled_loop_damps_as_the_python_loop(monkeypatch):
    # Reference: the explicit route's Python loop (continuum/dynamics/explicit.py steps), the
    # same steps without the compiled time loop, to round-off.
    from upliftlab.continuum.dynamics import explicit

    scene = _scene(DAMPED + ["soil.interface=bonded"])
    model = build_model(scene)
    motion = _pulse(2.0 * math.pi / _omega1(scene), total=0.25)
    options = DynamicOptions(method="explicit", snapshots=3)
    compiled = run_dynamic(model, scene, motion, options, progress=False)
    monkeypatch.setattr(explicit, "COMPILED_LOOP", False)
    python = run_dynamic(build_model(scene), scene, motion, options, progress=False)
    assert compiled.metadata["dt_reduction"] < 0.9  # the damping is there, and bounds the step
    assert compiled.metadata["damping_relaxation"] == pytest.approx(
        10 * 2 * math.pi * PAIR[1], rel=1e-12)
    scale = np.abs(compiled.displacement).max()
    assert np.allclose(python.displacement, compiled.displacement, rtol=0, atol=1e-9 * scale)
    assert np.allclose(python.energy, compiled.energy, rtol=1e-7, atol=1e-12)
    assert compiled.energy[-1, 2] > 0.0


@pytest.mark.parametrize("fields, named", [
    (["continuum.damping_ratio=0.3"], "continuum.damping_ratio = 0.3"),
    (["continuum.damping_ratio=-0.01"], "continuum.damping_ratio = -0.01"),
    (["continuum.damping_ratio=0.02", "continuum.damping_frequencies=[5.0, 5.0]"],
     "continuum.damping_frequencies = [5.0, 5.0]: valid range is 0 < f1 < f2"),
    (["continuum.damping_ratio=0.02", "continuum.damping_frequencies=[6.0, 2.0]"],
     "continuum.damping_frequencies = [6.0, 2.0]: valid range is 0 < f1 < f2"),
    (["continuum.damping_ratio=0.02", "continuum.damping_frequencies=[0.0, 2.0]"],
     "continuum.damping_frequencies[0] = 0"),
    (["continuum.damping_ratio=0.02", "continuum.damping_frequencies=[2.0]"],
     "continuum.damping_frequencies = [2.0]: expected two frequencies"),
    (["continuum.damping_frequencies=[2.0, 12.0]"],
     "continuum.damping_frequencies = [2.0, 12.0]: the frequencies are the damping's"),
])
def test_bad_damping_is_refused_naming_the_field_and_the_valid_range(fields, named):
    # Reference: the valid ranges of upliftlab/scenes/soil.py (0 ≤ ξ < 0.3; 0 < f₁ < f₂).
    with pytest.raises(InputError) as info:
        _scene(fields)
    text = str(info.value)
    assert named in text and "\n" not in text
    assert "valid" in text or "must be > 0" in text or "expected" in text
