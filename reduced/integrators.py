"""Integrators of the reduced model: what they are, their stability limits and their time step.

Every method knows its stability limit for a given model. The limit is computed, not guessed:
the eigenvalues λ of the bonded first-order system ``[[0, I], [−M⁻¹K, −M⁻¹C]]`` (every spring in
contact and elastic: the stiffest state) and of each impact dashpot acting on its spring's
effective mass, and the largest h with ``λh`` inside the method's region of absolute stability.
A step counts as stable when no mode grows by more than ``GROWTH_TOL`` = 1e-7 per step: the
Adams–Bashforth–Moulton PECE pair is weakly unstable for undamped modes (growth 1 + O((ωh)⁶)),
and this bounds its spurious growth to 1% over 10⁵ steps. RK4 is not affected (|R(iy)| < 1).
A step beyond the limit is refused with the limit in the message, or subcycled on request.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import InputError
from .model import ReducedModel

GROWTH_TOL = 1e-7

__all__ = ["GROWTH_TOL", "Method", "METHODS", "method", "stability_limit", "time_step", "StepPlan"]


def _rk4_growth(z: np.ndarray) -> np.ndarray:
    return np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)


def _abm4_growth(z: np.ndarray) -> np.ndarray:
    """Largest root modulus of the AB4–AM4 PECE recurrence for y' = λy, z = λh.

    y_{n+1} = y_n + c(9y* + 19y_n − 5y_{n−1} + y_{n−2}), y* = y_n + c(55y_n − 59y_{n−1}
    + 37y_{n−2} − 9y_{n−3}), c = z/24: the roots of ζ⁴ − a₁ζ³ − a₂ζ² − a₃ζ − a₄, found as the
    eigenvalues of the companion matrices, batched.
    """
    c = np.asarray(z, dtype=complex).ravel() / 24.0
    a = np.stack([1 + 28 * c + 495 * c**2, -531 * c**2 - 5 * c, 333 * c**2 + c, -81 * c**2],
                 axis=-1)
    companion = np.zeros((c.size, 4, 4), dtype=complex)
    companion[:, 0, :] = a
    companion[:, 1, 0] = companion[:, 2, 1] = companion[:, 3, 2] = 1.0
    roots = np.linalg.eigvals(companion)
    return np.max(np.abs(roots), axis=-1).reshape(np.shape(z))


@dataclass(frozen=True)
class Method:
    """An integrator: its name, order, whether it is explicit, and its stability region.

    ``points_per_period`` sets the automatic step: enough steps per shortest bonded period for
    about 1e-4 in peak u on the paper's fixed-base scenes (measured against Nigam–Jennings:
    ABM4 loses order at the record's slope breaks, Newmark is second order).
    """

    name: str
    order: int
    explicit: bool
    description: str
    points_per_period: int

    def growth(self, z: np.ndarray) -> np.ndarray:
        if self.name in ("rk4", "events"):
            return _rk4_growth(z)
        if self.name == "abm4":
            return _abm4_growth(z)
        return np.zeros(np.shape(z))


METHODS = {
    "events": Method("events", 4, True, "RK4 with switches located inside the step", 40),
    "rk4": Method("rk4", 4, True, "classical Runge-Kutta, fixed step (Ewing)", 40),
    "abm4": Method("abm4", 4, True, "Adams-Bashforth-Moulton predictor-corrector, PECE (Ewing)",
                   150),
    "newmark": Method("newmark", 2, False, "Newmark average acceleration, Newton", 350),
    "hht": Method("hht", 2, False, "HHT-alpha, Newton", 350),
}


def method(name: str) -> Method:
    try:
        return METHODS[name]
    except KeyError:
        raise InputError(f"analysis.integrator = {name!r}: must be one of "
                         f"{', '.join(map(repr, METHODS))}") from None


def _ray_limits(m: Method, lams: np.ndarray) -> np.ndarray:
    """Largest h with |growth(λh)| ≤ 1 along the ray of each λ (nonzero), all rays at once: a
    scan of 400 points up to 4/|λ| brackets the first unstable one, then each round splits the
    bracket into ``parts`` to round-off — 32 parts for the cheap RK4 polynomial, halves
    (bisection) for ABM4, whose growth takes an eigenvalue problem per point."""
    scale = 1.0 / np.abs(lams)
    hs = np.linspace(0.0, 4.0, 401)[1:] * scale[:, None]
    ok = m.growth(lams[:, None] * hs) <= 1.0 + GROWTH_TOL
    limits = np.full(lams.size, math.inf)
    rows = np.flatnonzero(~ok.all(axis=1))
    if rows.size == 0:
        return limits
    first_bad = np.argmin(ok[rows], axis=1)
    hi = hs[rows, first_bad]
    lo = np.where(first_bad > 0, hs[rows, np.maximum(first_bad - 1, 0)], 0.0)
    lam = lams[rows][:, None]
    parts = 2 if m.name == "abm4" else 32
    fractions = np.arange(1, parts) / parts
    index = np.arange(rows.size)
    for _ in range(math.ceil(50 / math.log2(parts))):
        trial = lo[:, None] + (hi - lo)[:, None] * fractions
        stable = m.growth(lam * trial) <= 1.0 + GROWTH_TOL
        first = np.where(stable.all(axis=1), parts - 1, np.argmin(stable, axis=1))
        hi = np.where(first < parts - 1, trial[index, np.minimum(first, parts - 2)], hi)
        lo = np.where(first > 0, trial[index, np.maximum(first - 1, 0)], lo)
    limits[rows] = lo
    return limits


def _eigenvalues(model: ReducedModel, all_impact: bool) -> np.ndarray:
    """Eigenvalues of the bonded first-order system (P-Δ softening left out: it does not bound
    the step), with every impact dashpot acting at once if ``all_impact``."""
    K, C = model.bonded_matrices(with_impact=all_impact)
    K = K - model.geometric
    minv = 1.0 / model.mass
    n = model.mass.size
    J = np.block([[np.zeros((n, n)), np.eye(n)], [-minv[:, None] * K, -minv[:, None] * C]])
    return np.linalg.eigvals(J)


def stability_limit(model: ReducedModel, name: str) -> float:
    """Largest stable time step (s) of integrator ``name`` on ``model`` (inf if unconditional).

    Fixed-step explicit methods keep an impact dashpot on for whole steps, so several can act at
    once: their limit assumes all of them do. The event stepper ends each stroke where it ends
    and caps its steps while a dashpot acts (``IMPH``), so its limit is the bonded system's.
    """
    m = method(name)
    if not m.explicit:
        return math.inf
    lams = _eigenvalues(model, all_impact=name != "events")
    lams = lams[(np.abs(lams) > 0) & (lams.imag >= 0)]  # one of each conjugate pair
    return float(np.min(_ray_limits(m, lams), initial=math.inf))


@dataclass(frozen=True)
class StepPlan:
    """The time step chosen for a run: ``dt`` (s) taken by the integrator, ``output_dt`` (s),
    ``substeps`` per requested step when subcycling, the ``limit`` and why ``dt`` was chosen."""

    dt: float
    steps: int
    stride: int
    limit: float
    substeps: int
    reason: str


def time_step(model: ReducedModel, name: str, *, record_dt: float, duration: float,
              dt: float | None = None, subcycle: bool = False,
              output_dt: float | None = None, max_records: int = 20_000_000) -> StepPlan:
    """Choose or check the step for integrator ``name``.

    Automatic: the largest ``record_dt / n`` (n integer, so steps meet every record sample) below
    both 0.9 times the stability limit and the shortest bonded period over the method's points per
    period. Requested: refused beyond the stability limit, unless ``subcycle``.
    """
    m = method(name)
    limit = stability_limit(model, name)
    substeps = 1
    if dt is None:
        shortest = float(model.bonded_periods()[-1])
        target = min(shortest / m.points_per_period, 0.9 * limit)
        n = max(1, math.ceil(record_dt / target - 1e-9))
        dt = record_dt / n
        reason = (f"automatic: record dt {record_dt:g} s / {n}; shortest bonded period "
                  f"{shortest:.4g} s, {m.points_per_period} points per period")
    else:
        reason = "requested"
        if dt > limit:
            if not subcycle:
                raise InputError(
                    f"analysis.dt = {dt:g} s is beyond the stability limit {limit:.4g} s of "
                    f"integrator {name!r} for this scene; use dt <= {limit:.4g} s, set "
                    "analysis.subcycle = true, or use an implicit integrator (newmark, hht)")
            substeps = math.ceil(dt / (0.95 * limit))
            reason = f"requested {dt:g} s, subcycled {substeps}x (limit {limit:.4g} s)"
    step = dt / substeps
    steps = max(1, int(round(duration / step)))
    out = output_dt if output_dt is not None else max(dt, 0.005)
    stride = max(1, int(round(out / step)))
    return StepPlan(step, steps, stride, limit, substeps, reason)
