"""The half-plane's stiffnesses at the structure's rocking frequency, which a bed can be
calibrated to instead of the continuum box's statics.

**Why.** A rigid strip on an elastic half-plane has a static rocking stiffness
(πGB²/(8(1 − ν)), frictionless) but no static vertical one: Re K_v(ω) falls to zero as
1/ln(1/a0) as ω → 0, so a "static K_v" is that of the box it was computed in (the Winkler map's
20 m deep box gives 27,513 kN/m/m on its soils). What the half-plane defines is K_v(ω); at the
frequency the structure rocks at, Re K_v(ω̃) and Re K_r(ω̃) are the stiffnesses the soil shows
it, and Im K_j(ω̃)/ω̃ its radiation dashpots (:mod:`.radiation`, the same frequency).

**The frequency** ω̃ (rad/s) is the flexible-base fundamental frequency of the one-story
structure (mass m = weight/g, story stiffness k = m (2π/T)², height h, rotary inertia I of the
base about O) on the footing's rocking impedance, the footing held horizontally (the Winkler
map's frictionless footing does not sway: its u is prescribed to the base's): ω̃² is the lower
root of

    m I ω⁴ − [k I + m (k h² + K_r)] ω² + k K_r = 0,   K_r = Re K_r(ω̃),

the same equation :func:`.radiation.rocking_frequency` solves on a bed of rocking stiffness K_r
(so the radiation dashpots of a bed calibrated here are taken at this ω̃). With I = 0 it is
Veletsos & Meek's (1974) flexible-base period T̃ = T √(1 + k h²/K_r). A footing that sways,
on the impedance's K_h = Re K_h(ω̃) (``sway``, a bonded footing) or on a ``tie`` of constant
K_h (the Winkler map's half-plane reference holds its frictionless footing so), adds the base's
horizontal DOF with its own ``base_mass`` m_b: ω̃² is then the lowest eigenvalue of
K = [[k, −k, −k h], [−k, k + K_h, k h], [−k h, k h, k h² + K_r]] against
M = diag(m, m_b, I) on (u_story, u_base, θ), massless DOFs condensed out; with I = m_b = 0 it
is their T̃ = T √(1 + k/K_h + k h²/K_r). Because K_r
depends on ω̃, it is solved by fixed-point iteration ω_{n+1} = ω̃(K(ω_n)) from the fixed-base
frequency 2π/T (brought into the impedance's frequencies), until
|ω_{n+1} − ω_n| ≤ ``tolerance`` ω_{n+1}; not converged in ``max_iterations`` is refused.

**Interpolation.** Between the impedance's frequencies Re K_j is taken linear in ω, as
:func:`.radiation.impedance_dashpots` takes C_j = Im K_j/ω; a frequency outside them is refused
(no extrapolation), with the value and the range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg

from ... import checks
from ...checks import InputError
from .radiation import impedance_at, impedance_dashpots

__all__ = ["BED_STIFFNESS", "RockingStiffness", "impedance_stiffness", "flexible_base_omega",
           "rocking_stiffness", "stiffness_reference"]

#: What the beds' K_v and K_r are calibrated to: ``static`` the continuum box's statics (the
#: default), ``rocking`` the half-plane's Re K_v(ω̃), Re K_r(ω̃) (:func:`stiffness_reference`).
BED_STIFFNESS = ("static", "rocking")


@dataclass(frozen=True)
class RockingStiffness:
    """The impedance at the structure's rocking frequency: ``omega`` ω̃ (rad/s), its ``a0`` =
    ω̃ (B/2)/V_s and ``period`` 2π/ω̃ (s); ``K_v``, ``K_h`` and ``K_r`` the real parts there
    (force/length², force·length/rad per length; K_h 0 without ``sway``); ``C_v`` and ``C_r``
    the dashpots Im K/ω there; ``iterations`` of the fixed point."""

    omega: float
    a0: float
    period: float
    K_v: float
    K_h: float
    K_r: float
    C_v: float
    C_r: float
    iterations: int
    sway: bool = False


def _grid(impedance) -> np.ndarray:
    return np.asarray(impedance.omega, dtype=float)


def _a0(impedance, omega: float) -> float:
    """a0 = ω b/V_s at ``omega``: proportional to ω, read off the impedance's first frequency."""
    return omega * float(impedance.a0[0]) / float(_grid(impedance)[0])


def impedance_stiffness(impedance, omega: float) -> tuple[float, float, float]:
    """(Re K_v, Re K_h, Re K_r) of an :class:`~upliftlab.continuum.impedance.analysis.Impedance`
    at ``omega`` (rad/s), linear in ω between its frequencies; an :class:`InputError` outside
    them (:func:`.radiation.impedance_at`)."""
    return impedance_at(impedance, omega,
                        [K.real for K in (impedance.K_v, impedance.K_h, impedance.K_r)],
                        "half-plane stiffness")


def flexible_base_omega(*, mass: float, stiffness: float, height: float, K_r: float,
                        rotary_inertia: float = 0.0, K_h: float = math.inf,
                        base_mass: float = 0.0) -> float:
    """ω̃ (rad/s): the lowest flexible-base frequency (module docstring) of a story of
    ``mass`` m, ``stiffness`` k and ``height`` h on a rocking spring K_r (base
    ``rotary_inertia`` I) and, if ``K_h`` is finite, a sway spring with the base's own
    ``base_mass`` m_b. One eigenproblem on (u_story, u_base, θ), u_base dropped when the
    footing is held (K_h infinite) and massless DOFs condensed out; the closed forms of the
    module docstring are its cases."""
    m, k, h = mass, stiffness, height
    K = np.array([[k, -k, -k * h], [-k, k + K_h, k * h], [-k * h, k * h, k * h * h + K_r]])
    M = np.array([m, base_mass, rotary_inertia])
    dofs = [0, 1, 2] if math.isfinite(K_h) else [0, 2]
    K, M = K[np.ix_(dofs, dofs)], M[dofs]
    kept, gone = np.flatnonzero(M > 0.0), np.flatnonzero(M == 0.0)
    condensed = K[np.ix_(kept, kept)] - K[np.ix_(kept, gone)] @ np.linalg.solve(
        K[np.ix_(gone, gone)], K[np.ix_(gone, kept)])
    w2 = scipy.linalg.eigh(condensed, np.diag(M[kept]), eigvals_only=True)
    return math.sqrt(float(w2[0]))


def rocking_stiffness(impedance, *, mass: float, period: float, height: float,
                      rotary_inertia: float = 0.0, sway: bool = False,
                      tie: float | None = None, base_mass: float = 0.0,
                      tolerance: float = 1e-10, max_iterations: int = 50) -> RockingStiffness:
    """The :class:`RockingStiffness` of ``impedance`` at the rocking frequency ω̃ of a story
    of ``mass`` (force·s²/length per length), fixed-base ``period`` T (s), ``height`` h
    (length) and base ``rotary_inertia`` (mass·length² per length), the footing swaying on
    the impedance's K_h (``sway``) or on a ``tie`` of constant K_h (force/length²) with its
    ``base_mass`` (force·s²/length per length), solved as the module docstring says.
    InputError for bad input, a frequency outside the impedance's, or no convergence."""
    m = checks.positive("structure mass", mass)
    T = checks.positive("structure.period", period)
    h = checks.positive("structure.height", height)
    I = checks.nonnegative("structure.rotary_inertia", rotary_inertia)
    m_b = checks.nonnegative("footing mass", base_mass)
    tol = checks.in_range("rocking frequency tolerance", tolerance, 0.0, 0.1, low_open=True)
    n_max = checks.integer_at_least("rocking frequency max_iterations", max_iterations, 1)
    if sway and (tie is not None or impedance.interface != "bonded"):
        raise InputError(f"rocking frequency with sway: tie = {tie!r} and interface = "
                         f"{impedance.interface!r}; valid: no tie, on a 'bonded' footing (a "
                         "frictionless one has no K_h; a tied one sways on its tie)")
    if tie is not None:
        tie = checks.positive("continuum.horizontal_tie", tie)
    held = tie if tie is not None else math.inf  # K_h of a footing not swaying on K(ω)
    k = m * (2.0 * math.pi / T) ** 2
    grid = _grid(impedance)
    omega = min(max(2.0 * math.pi / T, grid[0]), grid[-1])
    for n in range(1, n_max + 1):
        K_v, K_h, K_r = impedance_stiffness(impedance, omega)
        if not K_r > 0.0 or (sway and not K_h > 0.0):
            raise InputError(f"half-plane stiffness: Re K_r = {K_r:.6g}, Re K_h = {K_h:.6g} at "
                             f"ω = {omega:.6g} rad/s; valid: > 0 (a rocking frequency needs "
                             "a positive stiffness)")
        new = flexible_base_omega(mass=m, stiffness=k, height=h, K_r=K_r, rotary_inertia=I,
                                  K_h=K_h if sway else held, base_mass=m_b)
        change = abs(new - omega) / new
        if change <= tol:
            K_v, K_h, K_r = impedance_stiffness(impedance, new)
            C_v, _, C_r = impedance_dashpots(impedance, new)
            return RockingStiffness(new, _a0(impedance, new), 2.0 * math.pi / new, K_v,
                                    K_h if sway else 0.0, K_r, C_v, C_r, n, bool(sway))
        omega = new
    raise InputError(f"rocking frequency: the fixed point ω = ω̃(K(ω)) did not converge to "
                     f"{tol:g} in {n_max} iterations (last ω = {omega:.6g} rad/s, relative change "
                     f"{change:.3g}); valid: an impedance whose K_r(ω) varies "
                     "slowly enough, or more iterations")


def stiffness_reference(reference, basis: str, g: float):
    """``reference`` (a :class:`.base.BedReference`) as the beds are calibrated under
    ``basis`` (one of :data:`BED_STIFFNESS`): unchanged for ``static``; for ``rocking`` its
    ``K_v`` and ``K_r`` replaced by the half-plane's Re K_v(ω̃) and Re K_r(ω̃) at the rocking
    frequency of its structure (``extra["structure"]``: weight, period, height, rotary
    inertia, and the footing's share of ``vertical_weight``; g the scene's gravity; swaying on
    ``extra["sway_stiffness"]`` where the reference's footing has a tie), on its
    ``extra["impedance"]``, with
    ``extra["stiffness"]`` the :class:`RockingStiffness` and the statics it replaced."""
    checks.one_of("options.bed_stiffness", basis, BED_STIFFNESS)
    if basis == "static":
        return reference
    impedance, structure = reference.extra.get("impedance"), reference.extra.get("structure")
    if impedance is None or structure is None:
        raise InputError("options.bed_stiffness = 'rocking': the beds need the soil's continuum "
                         "impedance and the point's [structure] table; valid: a reference "
                         "with both (the map computes the impedance for it)")
    footing = structure.get("vertical_weight", structure["weight"]) - structure["weight"]
    at = rocking_stiffness(impedance, mass=structure["weight"] / g, period=structure["period"],
                           height=structure["height"],
                           rotary_inertia=structure.get("rotary_inertia", 0.0),
                           tie=reference.extra.get("sway_stiffness"), base_mass=footing / g)
    extra = {**reference.extra, "stiffness": {"basis": basis, "rocking": at,
                                              "K_v_static": reference.K_v,
                                              "K_r_static": reference.K_r}}
    return replace(reference, K_v=at.K_v, K_r=at.K_r, extra=extra)
