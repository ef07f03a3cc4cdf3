"""Material damping of the soil at small strain: Rayleigh damping C = α M + β K₀, the same in
both dynamic routes.

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
the mean of the half-step velocities. β K₀ v acts at the last half-step velocity v_{n−½}, as a
Kelvin–Voigt stress β D₀ ε̇ at every quadrature point summed element by element
(:func:`~upliftlab.continuum.dynamics.kernels.viscous_force`: the numbers of the product
(β K₀) v; it adds 0.10 ms to a step of 0.17 ms on 5184 DOFs, where a CSR product added 0.26 ms).
Acting at v_{n−½}, it bounds the step: a mode of frequency ω with damping ratio ξ is stable
under central differences for dt ≤ (2/ω)(√(1 + ξ²) − ξ) (Belytschko, Liu & Moran 2000,
§6.3), applied with ξ_max = βω_max/2 + α/(2ω_max) at the mesh's highest frequency ω_max
(:func:`damped_critical`; the α part is in fact treated implicitly, so counting it errs on the
safe side).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .waves import wave_speeds

__all__ = ["UPPER_FREQUENCY_FACTOR", "Rayleigh", "rayleigh_pair", "rayleigh_of", "rayleigh",
           "scene_rayleigh", "describe", "metadata", "damped_critical", "stiffness_data", "viscous_tangent"]

#: f₂ = this × f₁ when only ξ is given (module docstring).
UPPER_FREQUENCY_FACTOR = 5.0


@dataclass(frozen=True)
class Rayleigh:
    """The soil's Rayleigh damping: ``ratio`` ξ at ``frequencies`` (f₁, f₂) (Hz), the mass
    coefficient ``alpha`` (1/s) and the stiffness coefficient ``beta`` (s)."""

    ratio: float
    frequencies: tuple[float, float]
    alpha: float
    beta: float

    def ratio_at(self, omega: float) -> float:
        """ξ(ω) = α/(2ω) + βω/2 of a mode of circular frequency ``omega`` (rad/s)."""
        return self.alpha / (2.0 * omega) + 0.5 * self.beta * omega


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
    """One line naming the damping (ξ, f₁, f₂, α, β) and, for the explicit route, the
    ``reduction`` of its stable step: the damping's extra cost in steps."""
    f1, f2 = damping.frequencies
    words = (f"Rayleigh damping of the soil ξ = {damping.ratio:g} at {f1:.3g} and {f2:.3g} Hz "
             f"(α = {damping.alpha:.4g}/s, β = {damping.beta:.4g} s)")
    if reduction is not None and reduction < 1.0:
        words += (f"; the explicit stable step × {reduction:.3g} (√(1 + ξ²) − ξ at the mesh's "
                  f"highest frequency): {1.0 / reduction:.2g} × the steps of the undamped run")
    return words


def metadata(damping: Rayleigh | None, reduction: float | None = None) -> dict:
    """A run's metadata entries of its ``damping`` (none without it): ``damping_ratio`` ξ,
    ``damping_frequencies`` [f₁, f₂] (Hz), ``rayleigh_alpha`` (1/s), ``rayleigh_beta`` (s),
    and for the explicit route ``dt_reduction``, its stable step's factor."""
    if damping is None:
        return {}
    entries = {"damping_ratio": damping.ratio, "damping_frequencies": list(damping.frequencies),
               "rayleigh_alpha": damping.alpha, "rayleigh_beta": damping.beta}
    if reduction is not None:
        entries["dt_reduction"] = reduction
    return entries


def damped_critical(omega_max: float, damping: Rayleigh | None) -> float:
    """The central-difference limit (s) of the mesh's highest mode ``omega_max`` (rad/s) with
    the Rayleigh ``damping``: (2/ω)(√(1 + ξ²) − ξ), ξ = βω/2 + α/(2ω) (module docstring);
    2/ω without damping."""
    if damping is None:
        return 2.0 / omega_max
    xi = damping.ratio_at(omega_max)
    return 2.0 / omega_max * (math.sqrt(1.0 + xi * xi) - xi)


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
