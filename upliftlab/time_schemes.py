"""The coefficients of Newmark's method and of HHT-α, shared by both models' implicit routes.

Newmark's method advances displacement d, velocity v and acceleration a over a step dt by
d₁ = d + dt v + dt² ((1/2 − β) a + β a₁) and v₁ = v + dt ((1 − γ) a + γ a₁). Hilber, Hughes &
Taylor (1977) weight the stiffness, damping and external forces (1 + α) at the end of the step
and −α at its start (α in [−1/3, 0]) and take β = (1 − α)²/4, γ = 1/2 − α: second order,
unconditionally stable, and dissipative at high frequencies for α < 0. α = 0 is Newmark's average
acceleration (β = 1/4, γ = 1/2), which conserves the energy of a linear undamped system exactly.

Solved for the end-of-step displacement d₁, the scheme gives a₁ = a0 (d₁ − d) − a1 v − a2 a and
v₁ = c0 (d₁ − d) + c1 v + c2 a; :class:`NewmarkCoefficients` holds these constants once, so
that every implicit integrator uses the same numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

from .checks import InputError

__all__ = ["NewmarkCoefficients", "hht"]


@dataclass(frozen=True)
class NewmarkCoefficients:
    """Newmark/HHT-α constants of one step ``dt`` (s): ``alpha`` (HHT's α), ``beta``,
    ``gamma``; ``a0`` = 1/(β dt²) (1/s²), ``a1`` = 1/(β dt) (1/s), ``a2`` = 1/(2β) − 1,
    ``c0`` = γ/(β dt) (1/s), ``c1`` = 1 − γ/β, ``c2`` = dt (1 − γ/(2β)) (s) (module docstring)."""

    alpha: float
    beta: float
    gamma: float
    dt: float
    a0: float
    a1: float
    a2: float
    c0: float
    c1: float
    c2: float


def hht(alpha: float, dt: float) -> NewmarkCoefficients:
    """The HHT-α constants for α in [−1/3, 0] (0: Newmark's average acceleration) and a step
    ``dt`` > 0 (s): β = (1 − α)²/4, γ = 1/2 − α."""
    if not -1.0 / 3.0 <= alpha <= 0.0:
        raise InputError(f"HHT alpha = {alpha:g}: valid range is [-1/3, 0]")
    if not dt > 0.0:
        raise InputError(f"time step dt = {dt:g} s: must be > 0")
    beta, gamma = 0.25 * (1.0 - alpha) ** 2, 0.5 - alpha
    return NewmarkCoefficients(
        alpha=alpha, beta=beta, gamma=gamma, dt=dt,
        a0=1.0 / (beta * dt * dt), a1=1.0 / (beta * dt), a2=0.5 / beta - 1.0,
        c0=gamma / (beta * dt), c1=1.0 - gamma / beta, c2=dt * (1.0 - 0.5 * gamma / beta))
