"""Material damping of the soil at small strain: Rayleigh damping C = α M + β K₀ in both dynamic
routes, the explicit one's β K₀ through a Maxwell arm that relaxes above the damping's band.

**The pair.** ``continuum.damping_ratio`` ξ at the two frequencies
``continuum.damping_frequencies`` (f₁, f₂) gives α = 2ξω₁ω₂/(ω₁ + ω₂) (1/s) and
β = 2ξ/(ω₁ + ω₂) (s), so that a mode of circular frequency ω is damped by
ξ(ω) = α/(2ω) + βω/2: ξ at ω₁ and ω₂, less between them, more outside. Without the
frequencies the usual pair: f₁ = V_s/(4H), the soil column's fundamental frequency (H the box
depth, or ``soil.layer_depth``), and f₂ = 5 f₁ (Hudson, Idriss & Beikae 1994, QUAD4M; Kwok et
al. 2007, J. Geotech. Geoenviron. Eng. 133(11)), which keeps ξ(ω) within about ξ from f₁ to f₂
and leaves the much higher mesh frequencies heavily damped by β.

**M and K₀.** M is the soil's mass of the route (the explicit route's lumped mass, the
implicit one's consistent or lumped), K₀ the soil's initial elastic stiffness (the elastic
tangent at zero strain with the stiffness's quadrature, the matrix of the explicit stable
step): a yielding soil keeps the viscous stress of its elastic stiffness (a Kelvin–Voigt
element in parallel with the elastoplastic one), and neither term enters the return map.
The rigid base's relative formulation damps the velocity relative to the base; on a compliant
base the velocities are absolute, so α M also resists the free field's rigid motion a little
(α v_ff per unit mass: with ξ = 2 % at f₁ = 1 Hz, α = 0.21/s). The footing and the
superstructure carry no Rayleigh damping (their own dashpots are the structure's).

**Explicit route.** α M is diagonal: it joins the boundary dashpots in the diagonal update at
the mean of the half-step velocities. β K₀ acts at the last half-step velocity v_{n−½}, at
every quadrature point, summed element by element
(:func:`~upliftlab.continuum.dynamics.kernels.viscous_force`), through a **Maxwell arm**: the
dashpot β D₀ in series with a spring β ω_c D₀, whose stress σ_m relaxes in the time 1/ω_c,
σ̇_m + ω_c σ_m = β ω_c D₀ ε̇, integrated exactly for a constant ε̇ over the step:
σ_m,n = a σ_m,n−1 + (1 − a) β D₀ ε̇_{n−½}, a = exp(−ω_c dt). Below ω_c the arm is the
Kelvin–Voigt stress β D₀ ε̇ (a = 0 is that stress exactly); its loss modulus is
β E ω/(1 + (ω/ω_c)²) and its storage modulus β E ω²/ω_c/(1 + (ω/ω_c)²). With
ω_c = :data:`RELAXATION_FACTOR` ω₂ the arm damps within 1 % of β K₀ up to ω₂ (less below) and
stiffens the soil by at most β ω₂/10 there (0.17 % at ξ = 1 %, f₂ = 5 f₁); the implicit
route carries β K₀ itself, so the two routes differ by that much. Why: the Kelvin–Voigt
stress at v_{n−½} bounds the step, a mode of frequency ω with damping ratio ξ being stable
under central differences for dt ≤ (2/ω)(√(1 + ξ²) − ξ) (Belytschko, Liu & Moran 2000, §6.3),
and at the mesh's highest frequency ξ = βω_max/2 is large (about 1.5 on the map's half-plane:
the step × 0.29, 3.4 × the steps). Above ω_c the arm is a spring of β ω_c D₀ with little loss,
so the step is only shortened by about 1/√(1 + β ω_c) (0.93 on the map's half-plane): the
idea of the "Maxwell damping" of explicit codes that want a damping without its step (Huang,
Sturt & Willford 2019, "A damping model for nonlinear dynamic analysis providing uniform damping
over a frequency range", Computers & Structures 212, which sums several arms; here one arm
stands for β). :func:`damped_critical` finds the limit
exactly for the mode at ω_max, with α M, from the spectral radius of one step of the scheme.
The damping account counts the arm's work, which includes its stored energy
½ σ_m : (β ω_c D₀)⁻¹ : σ_m, dissipated in turn as the arm relaxes (given back only if the
strain reverses first), so the damping column may dip within a step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .waves import wave_speeds

__all__ = ["UPPER_FREQUENCY_FACTOR", "RELAXATION_FACTOR", "Rayleigh", "rayleigh_pair",
           "rayleigh_of", "rayleigh", "scene_rayleigh", "describe", "metadata", "damped_critical",
           "step_radius", "stiffness_data", "viscous_tangent"]

#: f₂ = this × f₁ when only ξ is given (module docstring).
UPPER_FREQUENCY_FACTOR = 5.0
#: The explicit route's Maxwell arm relaxes at ω_c = this × ω₂ (module docstring).
RELAXATION_FACTOR = 10.0


@dataclass(frozen=True)
class Rayleigh:
    """The soil's Rayleigh damping: ``ratio`` ξ at ``frequencies`` (f₁, f₂) (Hz), the mass
    coefficient ``alpha`` (1/s) and the stiffness coefficient ``beta`` (s)."""

    ratio: float
    frequencies: tuple[float, float]
    alpha: float
    beta: float

    @property
    def relaxation(self) -> float:
        """ω_c (rad/s), the explicit route's Maxwell arm's relaxation frequency:
        :data:`RELAXATION_FACTOR` × 2π f₂."""
        return RELAXATION_FACTOR * 2.0 * math.pi * self.frequencies[1]

    def arm_decay(self, dt: float) -> float:
        """a = exp(−ω_c dt): how much of the arm's stress is left after a step ``dt`` (s)."""
        return math.exp(-self.relaxation * dt)


def rayleigh_pair(ratio: float, f1: float, f2: float) -> tuple[float, float]:
    """(α, β) that give the damping ratio ``ratio`` at f₁ and f₂ (Hz)."""
    w1, w2 = 2.0 * math.pi * f1, 2.0 * math.pi * f2
    return 2.0 * ratio * w1 * w2 / (w1 + w2), 2.0 * ratio / (w1 + w2)


def rayleigh_of(options, soil, depth: float) -> Rayleigh | None:
    """The :class:`Rayleigh` damping of ``options``' (a scene's ``[continuum]``)
    ``damping_ratio`` and ``damping_frequencies`` for ``soil`` over a box ``depth`` deep
    (length); default f₁ = V_s/(4 depth), f₂ = :data:`UPPER_FREQUENCY_FACTOR` f₁. None without
    a damping ratio."""
    ratio = options.damping_ratio if options is not None else None
    if ratio is None:
        return None
    pair = options.damping_frequencies
    if pair is None:
        f1 = wave_speeds(soil)[1] / (4.0 * depth)
        pair = (f1, UPPER_FREQUENCY_FACTOR * f1)
    alpha, beta = rayleigh_pair(ratio, *pair)
    return Rayleigh(ratio=float(ratio), frequencies=(float(pair[0]), float(pair[1])),
                    alpha=alpha, beta=beta)


def rayleigh(model) -> Rayleigh | None:
    """The model's :class:`Rayleigh` damping (:func:`rayleigh_of`, the depth the mesh's)."""
    return rayleigh_of(model.options, model.soil, float(-model.mesh.p[1].min()))


def scene_rayleigh(scene) -> Rayleigh | None:
    """The scene's :class:`Rayleigh` damping before any mesh exists: the depth is
    ``soil.layer_depth``, else ``continuum.domain_depth`` × B (as the mesh makes it)."""
    options = scene.continuum
    if options is None or scene.soil is None:
        return None
    depth = scene.soil.layer_depth or options.domain_depth * scene.foundation.width
    return rayleigh_of(options, scene.soil, depth)


def describe(damping: Rayleigh, reduction: float | None = None) -> str:
    """One line naming the damping (ξ, f₁, f₂, α, β) and, for the explicit route, its Maxwell
    arm's ω_c and the ``reduction`` of its stable step: the damping's extra cost in steps."""
    f1, f2 = damping.frequencies
    words = (f"Rayleigh damping of the soil ξ = {damping.ratio:g} at {f1:.3g} and {f2:.3g} Hz "
             f"(α = {damping.alpha:.4g}/s, β = {damping.beta:.4g} s)")
    if reduction is not None:
        words += (f"; β K₀ through a Maxwell arm relaxing at ω_c = {damping.relaxation:.4g} "
                  f"rad/s, the explicit stable step × {reduction:.3g}")
    return words


def metadata(damping: Rayleigh | None, reduction: float | None = None) -> dict:
    """A run's metadata entries of its ``damping`` (none without it): ``damping_ratio`` ξ,
    ``damping_frequencies`` [f₁, f₂] (Hz), ``rayleigh_alpha`` (1/s), ``rayleigh_beta`` (s),
    and for the explicit route ``damping_relaxation`` ω_c (rad/s) of its Maxwell arm and
    ``dt_reduction``, its stable step's factor."""
    if damping is None:
        return {}
    entries = {"damping_ratio": damping.ratio, "damping_frequencies": list(damping.frequencies),
               "rayleigh_alpha": damping.alpha, "rayleigh_beta": damping.beta}
    if reduction is not None:
        entries.update(damping_relaxation=damping.relaxation, dt_reduction=reduction)
    return entries


def step_radius(dt: float, omega: float, damping: Rayleigh) -> float:
    """The spectral radius of one explicit step of a mode of circular frequency ``omega``
    (rad/s) with the ``damping``: on (x_n, v_{n−½}, s_{n−1}), the arm's force
    s_n = a s_{n−1} + (1 − a) β ω² v_{n−½} (a = exp(−ω_c dt)),
    v_{n+½} = ((1 − α dt/2) v_{n−½} − dt (ω² x_n + s_n)) / (1 + α dt/2),
    x_{n+1} = x_n + dt v_{n+½}. Above 1 the mode grows."""
    a = damping.arm_decay(dt)
    k, c = omega * omega, 0.5 * damping.alpha * dt
    s = np.array([0.0, (1.0 - a) * damping.beta * k, a])
    v = (np.array([0.0, 1.0 - c, 0.0]) - dt * (np.array([k, 0.0, 0.0]) + s)) / (1.0 + c)
    x = np.array([1.0, 0.0, 0.0]) + dt * v
    return float(np.max(np.abs(np.linalg.eigvals(np.array([x, v, s])))))


def damped_critical(omega_max: float, damping: Rayleigh | None) -> float:
    """The explicit route's stable step (s) for the mesh's highest mode ``omega_max``
    (rad/s) with the soil's ``damping`` through its Maxwell arm (module docstring): the
    largest dt ≤ 2/ω at which :func:`step_radius` is at most 1 (+1e-9), by bisection to
    1e-12 of 2/ω; 2/ω without damping."""
    top = 2.0 / omega_max
    if damping is None:
        return top

    def stable(dt):
        return step_radius(dt, omega_max, damping) <= 1.0 + 1e-9

    if stable(top):
        return top
    lo, hi = 0.0, top
    while hi - lo > 1e-12 * top:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


def stiffness_data(model) -> np.ndarray:
    """K₀, the soil's initial elastic stiffness, as CSR data in the model's pattern."""
    from .. import assembly
    from .iteration_matrix import elastic_plane_tangent

    return assembly.stiffness(model.disc, elastic_plane_tangent(model)).data


def viscous_tangent(model, damping: Rayleigh) -> np.ndarray:
    """β D₀ (3, 3): the plane elastic tangent at zero strain (on ε_xx, ε_yy, γ_xy) times the
    ``damping``'s β, the Kelvin–Voigt stress per strain rate whose ∫ Bᵀ (β D₀) ε̇ is β K₀ v."""
    from .iteration_matrix import elastic_plane_tangent

    return np.ascontiguousarray(damping.beta * elastic_plane_tangent(model)[:, :, 0, 0])
