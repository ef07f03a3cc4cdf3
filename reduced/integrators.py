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
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg

from ..checks import InputError
from . import kernels as kn
from .model import ReducedModel

GROWTH_TOL = 1e-7

__all__ = ["GROWTH_TOL", "Method", "METHODS", "method", "stability_boundary", "stability_limit",
           "resolution_limit", "shortest_mode", "time_step", "StepPlan", "RESOLUTION"]


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


def _no_growth(z: np.ndarray) -> np.ndarray:
    """The implicit integrators are unconditionally stable: no step grows a mode."""
    return np.zeros(np.shape(z))


@dataclass(frozen=True)
class Method:
    """An integrator: its name, order, whether it is explicit, its stability region and the
    compiled kernel that runs it. This registry (:data:`METHODS`) is the one list of the
    reduced model's integrators: the run, its step plan, its cost and the tests read it.

    ``points_per_period`` sets the automatic step: enough steps per shortest bonded period for
    about 1e-4 in peak u on the paper's fixed-base scenes (measured against Nigam–Jennings:
    ABM4 loses order at the record's slope breaks, Newmark is second order). ``growth`` is the
    largest amplification |y₁/y₀| of one step on y' = λy at z = λh. ``kind`` says how the kernel
    is called: ``"events"`` (switches located inside the step, optional error control, an
    impact log), ``"fixed"`` (explicit, fixed step, end-of-step return map) or ``"implicit"``
    (Newton; ``alpha`` the HHT-α parameter, None: the scene's ``analysis.hht_alpha``).
    ``multistep``: a multistep method (its stability is a root condition, its energy residual
    measured after its starting steps).
    """

    name: str
    order: int
    explicit: bool
    description: str
    points_per_period: int
    growth: Callable[[np.ndarray], np.ndarray]
    kernel: Callable
    kind: str
    alpha: float | None = 0.0
    multistep: bool = False

    @property
    def locates_switches(self) -> bool:
        """True for the event stepper, whose steps end at every switch of a spring."""
        return self.kind == "events"


METHODS = {m.name: m for m in (
    Method("events", 4, True, "RK4 with switches located inside the step", 40, _rk4_growth,
           kn.integrate_events, "events"),
    Method("rk4", 4, True, "classical Runge-Kutta, fixed step (Ewing)", 40, _rk4_growth,
           kn.integrate_rk4, "fixed"),
    Method("abm4", 4, True, "Adams-Bashforth-Moulton predictor-corrector, PECE (Ewing)", 150,
           _abm4_growth, kn.integrate_abm4, "fixed", multistep=True),
    Method("newmark", 2, False, "Newmark average acceleration, Newton", 350, _no_growth,
           kn.integrate_newmark, "implicit", alpha=0.0),
    Method("hht", 2, False, "HHT-alpha, Newton", 350, _no_growth, kn.integrate_newmark,
           "implicit", alpha=None),
)}


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
    parts = 2 if m.multistep else 32
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


def _first_order(model: ReducedModel, all_impact: bool):
    """(J, M, K, C) of the bonded system at rest (P-Δ softening left out: it does not bound the
    step), ẏ = J y for y = (q, q̇), with every impact dashpot acting at once if
    ``all_impact``. Exact kinematics is taken at its linearisation (:attr:`linearised`)."""
    model = model.linearised
    K, C = model.bonded_matrices(with_impact=all_impact)
    K = K - model.geometric
    minv = 1.0 / model.mass
    n = model.mass.size
    J = np.block([[np.zeros((n, n)), np.eye(n)], [-minv[:, None] * K, -minv[:, None] * C]])
    return J, np.diag(model.mass), K, C


def _eigenvalues(model: ReducedModel, all_impact: bool) -> np.ndarray:
    return np.linalg.eigvals(_first_order(model, all_impact)[0])


def stability_boundary(model: ReducedModel, name: str) -> float:
    """Largest step (s) of integrator ``name`` at which no bonded mode grows (inf if
    unconditional): the edge of the method's region of absolute stability. Beyond it a run
    diverges; near it a fixed-step run is stable but inaccurate (see :func:`stability_limit`).

    Fixed-step explicit methods keep an impact dashpot on for whole steps, so several can act at
    once: they assume all of them do. The event stepper ends each stroke where it ends and caps
    its steps while a dashpot acts (``IMPH``), so its boundary is the bonded system's.
    """
    m = method(name)
    if not m.explicit:
        return math.inf
    lams = _eigenvalues(model, all_impact=not m.locates_switches)
    lams = lams[(np.abs(lams) > 0) & (lams.imag >= 0)]  # one of each conjugate pair
    return float(np.min(_ray_limits(m, lams), initial=math.inf))


def _step_residual(m: Method, J, M, K, C, h: float, states: np.ndarray) -> float:
    """Largest error of the energy balance that steps of ``m`` leave per step on the bonded
    linear system, relative to each initial state's energy: the kernels' scheme (RK4, or ABM4
    started by RK4) on y = (q, q̇) with the dashpots' dissipation integrated alongside, from
    the columns of ``states`` (the modes' real and imaginary parts)."""
    n = M.shape[0]

    def energy(y):
        q, v = y[:n], y[n:]
        return 0.5 * np.einsum("ik,ij,jk->k", v, M, v) + 0.5 * np.einsum("ik,ij,jk->k", q, K, q)

    def power(y):
        v = y[n:]
        return np.einsum("ik,ij,jk->k", v, C, v)

    def rk4(y):
        f1 = J @ y
        f2 = J @ (y + 0.5 * h * f1)
        f3 = J @ (y + 0.5 * h * f2)
        f4 = J @ (y + h * f3)
        d = h / 6 * (power(y) + 2 * power(y + 0.5 * h * f1) + 2 * power(y + 0.5 * h * f2)
                     + power(y + h * f3))
        return y + h / 6 * (f1 + 2 * f2 + 2 * f3 + f4), d

    e0 = energy(states)
    if not m.multistep:
        y1, dissipated = rk4(states)
        return float(np.max(np.abs(energy(y1) - e0 + dissipated) / e0))
    # ABM4 (PECE on y and the dissipation) after its three RK4 starting steps: the residual it
    # adds per step over the next eight
    y, dis, f, p, marks = states, np.zeros(states.shape[1]), [], [], []
    for step in range(11):
        f.insert(0, J @ y)
        p.insert(0, power(y))
        if step < 3:
            y, d = rk4(y)
            dis = dis + d
        else:
            ys = y + h / 24 * (55 * f[0] - 59 * f[1] + 37 * f[2] - 9 * f[3])
            fs, ps = J @ ys, power(ys)
            y = y + h / 24 * (9 * fs + 19 * f[0] - 5 * f[1] + f[2])
            dis = dis + h / 24 * (9 * ps + 19 * p[0] - 5 * p[1] + p[2])
        marks.append(energy(y) - e0 + dis)
    return float(np.max(np.abs(marks[-1] - marks[2]) / 8 / e0))


def stability_limit(model: ReducedModel, name: str, *, duration: float | None = None,
                    tolerance: float | None = None) -> float:
    """Largest step (s) of a fixed-step explicit integrator at which the energy balance stays
    within ``tolerance`` (default the scene's ``analysis.energy_tolerance``) over a run of
    ``duration`` s (default the scene's): every step may add at most tolerance·h/duration of the
    energy of any bonded mode (every impact dashpot on for the fixed-step methods), so that a
    run whose energy sat in the worst mode would still close its balance. Never beyond the
    :func:`stability_boundary`; inf for the implicit integrators, which are limited instead by
    the periods they must resolve (:func:`resolution_limit`). For the event stepper under error
    control (``analysis.rtol`` > 0) this is its boundary: the control keeps its accuracy."""
    m = method(name)
    boundary = stability_boundary(model, name)
    a = model.scene.analysis
    if not m.explicit or (m.locates_switches and a.rtol > 0):
        return boundary
    tolerance = a.energy_tolerance if tolerance is None else tolerance
    if duration is None:
        duration = a.duration or model.scene.build_motion().duration
    J, M, K, C = _first_order(model, all_impact=not m.locates_switches)
    lam, vectors = np.linalg.eig(J)
    keep = np.abs(lam) > 0
    states = np.concatenate([vectors[:, keep].real, vectors[:, keep].imag], axis=1)
    norms = np.linalg.norm(states, axis=0)
    states = states[:, norms > 1e-9 * norms.max()]
    states = states / np.linalg.norm(states, axis=0)

    def ok(h):
        return _step_residual(m, J, M, K, C, h, states) <= tolerance * h / duration

    grid = boundary * np.geomspace(1e-4, 1.0, 80)
    bad = [h for h in grid if not ok(h)]
    if not bad:
        return boundary
    hi = bad[0]
    lo = grid[np.searchsorted(grid, hi) - 1] if hi > grid[0] else 0.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return float(lo)


#: Steps per period an implicit integrator must take in the shortest bonded mode.
RESOLUTION = 10


def shortest_mode(model: ReducedModel) -> tuple[float, str]:
    """The shortest bonded period (s) and what moves in it: a story, the rocking or the vertical
    motion of the base (the DOF holding most of the mode's kinetic energy)."""
    lin = model.linearised
    K, _ = lin.bonded_matrices()
    w2, vecs = scipy.linalg.eigh(K - lin.geometric, np.diag(lin.mass))
    w2 = np.clip(w2, 1e-300, None)
    mode = vecs[:, -1]
    share = mode * mode * lin.mass
    dof = lin.dofs.names[int(np.argmax(share))]
    what = {"theta": "rocking", "V": "vertical"}.get(dof, f"story {dof[1:]}")
    return float(2.0 * np.pi / np.sqrt(w2[-1])), what


def resolution_limit(model: ReducedModel) -> tuple[float, str]:
    """Largest step (s) of an implicit integrator: :data:`RESOLUTION` steps per shortest bonded
    period, and that mode's description. Unconditional stability lets Newmark and HHT step
    over a mode, but not resolve it: a mode crossed in a few steps is shifted and damped."""
    period, what = shortest_mode(model)
    return period / RESOLUTION, f"the bonded {what} mode, T = {period:.4g} s"


@dataclass(frozen=True)
class StepPlan:
    """The time step chosen for a run: ``dt`` (s) taken by the integrator (the event stepper
    under error control: the spacing of the points every step meets), ``substeps`` per
    requested step when subcycling, the ``limit`` the step is checked against and why ``dt``
    was chosen; ``rtol`` of the error control (0: fixed steps), ``h0`` its first trial step,
    ``hmax`` its longest and ``output_dt`` the spacing of the states it stores, interpolated
    within its steps (s; 0: every ``stride`` steps instead)."""

    dt: float
    steps: int
    stride: int
    limit: float
    substeps: int
    reason: str
    rtol: float = 0.0
    h0: float = math.inf
    hmax: float = math.inf
    output_dt: float = 0.0

    @property
    def rows(self) -> int:
        """Stored states: every ``stride`` steps, or every ``output_dt`` interpolated."""
        if self.output_dt > 0:
            return int(round(self.steps * self.dt / self.output_dt)) + 1
        return self.steps // self.stride + 1 + (1 if self.steps % self.stride else 0)

    def without_histories(self) -> StepPlan:
        """The same plan storing only the first and last states."""
        return replace(self, stride=self.steps,
                       output_dt=self.steps * self.dt if self.output_dt > 0 else 0.0)


def time_step(model: ReducedModel, name: str, *, record_dt: float, duration: float,
              dt: float | None = None, subcycle: bool = False,
              output_dt: float | None = None, max_records: int = 20_000_000) -> StepPlan:
    """Choose or check the step for integrator ``name`` over a run of ``duration`` s.

    Event stepper under error control (the default, ``analysis.rtol`` > 0): the steps meet every
    multiple of ``dt`` (the record's step unless given), the control picks steps between them,
    never beyond 0.9 times the stability boundary, and the stored states (every ``output_dt``,
    default :data:`OUTPUT_DT`) are interpolated within the steps, so that what a run stores
    does not change its numbers.
    Fixed steps: automatic is the largest ``record_dt / n`` (n integer, so steps meet every
    record sample) below both 0.9 times the stability limit and the shortest bonded period over
    the method's points per period; a requested step beyond the limit is refused, unless
    ``subcycle``. The implicit integrators refuse a step that cannot resolve the shortest
    bonded period (:func:`resolution_limit`).
    """
    m = method(name)
    a = model.scene.analysis
    out = output_dt if output_dt is not None else None
    if m.locates_switches and a.rtol > 0:
        return _controlled(model, record_dt, duration, dt, out, max_records)
    limit = stability_limit(model, name, duration=duration)
    substeps = 1
    if dt is None:
        shortest = float(model.linearised.bonded_periods()[-1])
        target = min(shortest / m.points_per_period, 0.9 * limit)
        n = max(1, math.ceil(record_dt / target - 1e-9))
        dt = record_dt / n
        reason = (f"automatic: record dt {record_dt:g} s / {n}; shortest bonded period "
                  f"{shortest:.4g} s, {m.points_per_period} points per period")
    else:
        reason = "requested"
        if not m.explicit:
            largest, what = resolution_limit(model)
            if dt > largest:
                raise InputError(
                    f"analysis.dt = {dt:g} s: integrator {name!r} cannot resolve {what} in "
                    f"steps this long; valid range is (0, {largest:.4g}] s ({RESOLUTION} steps "
                    "per period)")
        elif dt > limit:
            if not subcycle:
                raise InputError(
                    f"analysis.dt = {dt:g} s is beyond the stability limit {limit:.4g} s of "
                    f"integrator {name!r} for this scene (the largest step that keeps the "
                    f"energy balance within analysis.energy_tolerance = {a.energy_tolerance:g} "
                    f"over {duration:g} s); use dt <= {limit:.4g} s, set analysis.subcycle = "
                    "true, or " + ("let the error control choose the steps (analysis.rtol "
                                   "> 0)" if m.locates_switches else "use the event stepper "
                                   "(integrator 'events')"))
            substeps = math.ceil(dt / (0.95 * limit))
            reason = f"requested {dt:g} s, subcycled {substeps}x (limit {limit:.4g} s)"
    step = dt / substeps
    steps, step = _steps(duration, step)
    stride = max(1, int(round((out if out is not None else max(dt, 0.005)) / step)))
    _check_records(steps // stride + 1, max_records)
    return StepPlan(step, steps, stride, limit, substeps, reason)


def _steps(duration: float, step: float) -> tuple[int, float]:
    """Steps that end exactly at ``duration``: ``step`` if it divides it (to round-off), else
    the next shorter step that does."""
    steps = max(1, math.ceil(duration / step - 1e-9))
    return steps, duration / steps


def _check_records(rows: int, max_records: int) -> None:
    if rows > max_records:
        raise InputError(f"analysis.output_dt: {rows} stored states exceed the limit of "
                         f"{max_records}; set a longer analysis.output_dt")


#: Spacing of the stored states of the event stepper under error control, by default (s).
OUTPUT_DT = 0.005


def _controlled(model, record_dt, duration, dt, output_dt, max_records) -> StepPlan:
    """The event stepper's plan under error control (see :func:`time_step`)."""
    a = model.scene.analysis
    boundary = stability_boundary(model, "events")
    steps, span = _steps(duration, dt if dt is not None else record_dt)
    shortest = float(model.linearised.bonded_periods()[-1])
    h0 = min(shortest / METHODS["events"].points_per_period, 0.9 * boundary, span)
    rows = max(1, int(round(duration / (output_dt or OUTPUT_DT))))
    _check_records(rows + 1, max_records)
    reason = (f"error control: rtol {a.rtol:g}, steps meeting every {span:g} s, at most "
              f"{0.9 * boundary:.4g} s (0.9 x the stability boundary)")
    return StepPlan(span, steps, steps, boundary, 1, reason, rtol=a.rtol, h0=h0,
                    hmax=0.9 * boundary, output_dt=duration / rows)
