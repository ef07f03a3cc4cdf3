"""The macro-element calibrated from the continuum's statics, once per soil (issue 36 §2).

What it is fitted to, in order, each step a check with its residuals kept:

1. **Elastic part**: the continuum footing's K_v and K_r in full contact, as they are.
2. **Capacity**: the effective-width rule V = B′ q(B′) with q(B′) = c N_c f_c + ½ γ N_γ f_γ B′
   (:mod:`upliftlab.reduced.laws.macro.capacity`), a straight line in B′ through the
   continuum's own V_ult/B at B′ = B, fitted by least squares to the largest moment of each
   monotonic rotation pushover (B′ = B − 2 M_max/N). A line that would fall with B′ is held
   flat (the cohesive term alone, as on the clay).
3. **Plasticity**: ζ0, κ_ref, h0, γ, χ, λ_ρ, δ, ε and the memory's μ by least squares to the
   moment and the settlement along every stored rotation pushover of the soil, monotonic and
   cyclic (growing amplitudes, and repeated cycles at one, which say whether the footing
   shakes down), at every FS_v: residuals M/M_max and Δs/max(Δs, N/(10 K_v)), the settlement
   counted from θ = 0 (the law starts elastic under N, the continuum has yielded under it).
   The objective is piecewise smooth (it kinks where a sub-step's load turns) and has more
   than one minimum (h0 and γ trade off), so the fit surveys the bounds first (a seeded Latin
   hypercube) and polishes the four best points with scipy's dogleg method (box bounds,
   finite differences of 1 % in the fitted variables), keeping the best. A fitted law that
   cannot hold N on a pushover within ``LOAD_TOLERANCE`` is refused.

No dynamic run enters: the map is the test. :func:`macro_pushover` pushes the law over a
rotation path at constant N (the continuum's pushover, with u held).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import qmc

from ...checks import InputError
from ...scenes.laws.macro import MAX_SETTLEMENT_COUPLING
from ...scenes.soil import FRICTIONAL, SOIL_MODELS, UNDRAINED
from ...reduced.laws.macro import (LOAD_TOLERANCE, MacroElement, MacroStepError, at_rest,
                                    at_vertical_load)
from ...reduced.laws.macro.params import bearing_factors

__all__ = ["RotationPushover", "MacroCalibration", "capacity_line", "macro_pushover",
           "calibrate_macro", "evaluation_bound", "PLASTIC_BOUNDS", "SETTLEMENT_FLOOR",
           "LOAD_TOLERANCE", "FIT_SECONDS_PER_STEP", "macro_strength"]

#: The fitted plastic parameters and their bounds: ζ0, log10 κ_ref (m), log10 h0, γ, χ, λ_ρ,
#: δ (the flow's dilatancy: 1 associated), ε (the coupling's exponent: 0 everywhere alike) and
#: log10 μ (the memory's stiffening of reloading: 0.01, none to speak of, to 1e4, elastic).
#: χ keeps to the range a scene may give (:data:`...scenes.laws.macro.MAX_SETTLEMENT_COUPLING`:
#: the pushovers, pure rocking, would accept a χ whose dynamic runs, with sway, fail).
PLASTIC_BOUNDS = (("initial_size", 0.2, 0.999), ("hardening_settlement", -4.0, 0.0),
                  ("interior_modulus", -3.0, 3.0), ("interior_exponent", 0.2, 4.0),
                  ("settlement_coupling", 0.0, MAX_SETTLEMENT_COUPLING),
                  ("rounding_ratio", 0.0, 1.0), ("flow_dilatancy", 0.0, 1.0),
                  ("coupling_exponent", 0.0, 4.0), ("memory_modulus", -2.0, 4.0))
#: The survey of the plastic parameters before the fit: this many points of a seeded Latin
#: hypercube in the bounds (and the start); the best ``POLISHED`` of them are polished by least
#: squares and the better fit kept.
SURVEY = 24
POLISHED = 4
#: The settlement change below which a pushover's settlement residual is scaled by this, as a
#: fraction of the pushover's static settlement N/K_v: the map's floor for a residual
#: settlement (a tenth of that settlement at the uplift threshold), free of units. Its first
#: form was 2 mm on every pushover, in any unit system. Neither floor is reached by the
#: half-plane store's pushovers (each settles more over its path), and the clay's fit is
#: the same with either (473 evaluations, cost 2.57; the sand 315, 2.65; every parameter
#: alike).
SETTLEMENT_FLOOR = 0.1
_LOGS = ("hardening_settlement", "interior_modulus", "memory_modulus")
#: Seconds per step of the law's rotation pushover in the fit, an upper bound for a cost
#: estimate (each evaluation pushes the law over every continuum path): the clay's first
#: calibration took 2077 s for 346 evaluations of 248 steps, 24 ms a step; the χ-bounded one
#: 1418 s for 473, 12 ms (``benchmarks/MACRO_CALIBRATION.md``).
FIT_SECONDS_PER_STEP = 0.025


@dataclass(frozen=True)
class RotationPushover:
    """A continuum rotation pushover at constant ``N`` (kN/m): ``theta`` (rad), ``M``
    (kN·m/m) and ``settlement`` (m, positive down) per step; ``source`` names the run."""

    N: float
    theta: np.ndarray
    M: np.ndarray
    settlement: np.ndarray
    source: str = ""


@dataclass(frozen=True)
class MacroCalibration:
    """A soil's macro-element (``law``) and its checks: ``capacity_residuals`` (the fitted
    line's q(B′) against each pushover's, relative), ``moment_rms`` and ``settlement_rms``
    (per pushover, in the residuals' scales), ``load_misses`` (per pushover, the largest
    |V − N|/N the law was left with), ``sources`` the runs it came from."""

    law: MacroElement
    capacity_residuals: np.ndarray
    moment_rms: np.ndarray
    settlement_rms: np.ndarray
    load_misses: np.ndarray
    sources: tuple[str, ...] = ()
    cost: float = math.nan
    evaluations: int = 0
    details: Mapping = field(default_factory=dict, repr=False)


def macro_strength(scene) -> dict:
    """The macro-element's c, φ, γ (the form of its capacity) of the scene's soil: an undrained
    soil's c_u (its gradient enters through the fitted capacity line), a frictional soil's c,
    φ and unit weight ρ g. A soil without strength, or a frictional one without cohesion (the
    capacity line's intercept is the c N_c term), is refused in one line."""
    soil = scene.soil
    if soil is None:
        raise InputError(f"scene {scene.name!r}: soil is missing; the calibration runs the "
                         "continuum and needs a [soil] table")
    strength = SOIL_MODELS.get(soil.model)
    if strength == UNDRAINED:
        return {"cohesion": soil.undrained_strength}
    if strength == FRICTIONAL:
        if not soil.cohesion > 0.0:
            raise InputError(f"soil.cohesion = {soil.cohesion:g}: the macro-element's capacity "
                             "line has a cohesive term c N_c as its intercept; valid range is "
                             "(0, ...) (a small c, e.g. 1 kPa, for a sand)")
        return {"cohesion": soil.cohesion, "friction_angle": soil.friction_angle,
                "unit_weight": soil.density * scene.g}
    valid = ", ".join(repr(k) for k, v in SOIL_MODELS.items() if v is not None)
    raise InputError(f"soil.model = {soil.model!r}: has no strength, and the macro-element is "
                     f"fitted to the soil's yielding; valid: {valid}")


def capacity_line(pushovers: Sequence[RotationPushover], V_ult: float, width: float,
                  frictional: bool = True) -> tuple[float, float, np.ndarray]:
    """(q₀ (kPa), q₁ (kN/m³), residuals): q(B′) = q₀ + q₁ B′ through V_ult/B at B′ = B,
    fitted to each monotonic pushover's (B′, N/B′) at its largest moment (step 2); q₁ = 0
    without a ``frictional`` term, or where the fit would make it negative."""
    N = np.array([p.N for p in pushovers])
    reduced = width - 2.0 * np.array([np.max(p.M) for p in pushovers]) / N
    if np.any(reduced <= 0.0):
        raise InputError("macro calibration: a pushover's moment exceeds N B/2 (B′ ≤ 0)")
    q = N / reduced
    top = V_ult / width
    slope = float(np.sum((q - top) * (reduced - width)) / np.sum((reduced - width) ** 2))
    slope = max(slope, 0.0) if frictional else 0.0
    base = top - slope * width
    return base, slope, (base + slope * reduced) / q - 1.0


def _law(template: MacroElement, values) -> MacroElement:
    changes = {name: (10.0 ** x if name in _LOGS else float(x))
               for (name, _, _), x in zip(PLASTIC_BOUNDS, values)}
    return replace(template, **changes)


def macro_pushover(law: MacroElement, N: float, thetas, strict: bool = True):
    """(M, settlement) of the law along rotations ``thetas`` at constant N: each step's v the
    root of V(v) = N (:func:`~upliftlab.reduced.laws.macro.at_vertical_load`). Not
    ``strict``: a step whose V cannot be brought
    within :data:`LOAD_TOLERANCE` of N goes on from the closest state, and the largest
    |V − N|/N along the path is returned as a third value."""
    state = at_rest(law, N)
    moments, settlements, worst = [], [], 0.0
    for theta in thetas:
        state, miss = at_vertical_load(law, state, (0.0, float(theta)), N, strict)
        worst = max(worst, miss)
        moments.append(state.forces[2])
        settlements.append(state.displacement[0])
    out = (np.array(moments), np.array(settlements))
    return out if strict else (*out, worst)


def _residuals(law: MacroElement, pushovers: Sequence[RotationPushover]):
    """(every residual, per pushover: moment rms, settlement rms, largest |V − N|/N). A
    pushover the law cannot follow at constant N goes on from its closest states, its miss
    a residual of its own (× 10), so that the objective has no cliff."""
    parts, moment_rms, settlement_rms, misses = [], [], [], []
    for p in pushovers:
        scale_m = float(np.max(np.abs(p.M)))
        if not scale_m > 0.0:
            raise InputError(f"macro calibration: pushover {p.source!r} carries no moment")
        change = p.settlement - p.settlement[0]
        floor = SETTLEMENT_FLOOR * p.N / law.vertical_stiffness
        scale_s = max(float(np.max(np.abs(change))), floor)
        try:
            M, s, miss = macro_pushover(law, p.N, p.theta, strict=False)
        except MacroStepError:  # a step the law itself refuses
            M, s, miss = np.full(p.M.shape, 10.0 * scale_m), np.full(p.M.shape, 0.0), 1.0
        rm, rs = (M - p.M) / scale_m, ((s - s[0]) - change) / scale_s
        parts += [rm, 0.5 * rs, [10.0 * max(miss - LOAD_TOLERANCE, 0.0)]]
        moment_rms.append(math.sqrt(np.mean(rm ** 2)))
        settlement_rms.append(math.sqrt(np.mean(rs ** 2)))
        misses.append(miss)
    return np.concatenate(parts), np.array(moment_rms), np.array(settlement_rms), \
        np.array(misses)


def evaluation_bound(max_evaluations: int) -> int:
    """The most evaluations of the objective :func:`calibrate_macro` makes with
    ``max_evaluations``: the survey, then each polish's share (at least one step, a finite
    difference in each of the fitted variables per step)."""
    return max(int(max_evaluations), SURVEY + 1 + POLISHED * (len(PLASTIC_BOUNDS) + 1))


def calibrate_macro(pushovers: Sequence[RotationPushover], *, width: float, V_ult: float,
                    K_v: float, K_r: float, cohesion: float, friction_angle: float = 0.0,
                    unit_weight: float = 0.0,
                    start=(0.7, -2.0, 0.0, 1.0, 0.2, 0.5, 1.0, 0.0, 1.0),
                    max_evaluations: int = 200, progress=None, carry: float = 0.0,
                    length_unit: float = 1.0, cache=None) -> MacroCalibration:
    """The macro-element of a soil from its continuum statics (module docstring): the
    ``pushovers`` (monotonic ones give the capacity; all are fitted), the footing's ``width``,
    the continuum's ``V_ult``, ``K_v``, ``K_r``, and the soil's c, φ, γ (the capacity's form).
    ``progress(evaluations, at_most, lowest_cost)`` (None: silent) is called after every
    evaluation of the objective; an exception it raises (KeyboardInterrupt) stops the fit.
    ``carry``: a central load the law must carry inside its initial surface besides the
    pushovers' (a structure's weight: ζ0 V_ult above it, so that the element rests elastic
    under it). ``length_unit``: metres in the inputs' unit of length (κ_ref's bounds are in
    metres). ``cache`` (a mapping, None: none): the objective's
    residuals by the exact point, read before and written after each evaluation; the fit is
    deterministic, so a fit given the cache of an interrupted one replays its evaluations
    from it and goes on where it stopped.
    """
    monotonic = [p for p in pushovers if np.all(np.diff(p.theta) >= 0.0)]
    if not monotonic:
        raise InputError("macro calibration: no monotonic rotation pushover to fit the "
                         "capacity to")
    frictional = friction_angle > 0.0 and unit_weight > 0.0  # else no N_γ term in the form
    base, slope, capacity_residuals = capacity_line(monotonic, V_ult, width, frictional)
    n_c, _, n_gamma = bearing_factors(friction_angle)
    if not base > 0.0:
        raise InputError(f"macro calibration: the capacity line's intercept q₀ = {base:.4g} "
                         f"(its slope q₁ = {slope:.4g}): the pushovers' capacities fall faster "
                         "with the contact's width than the N_γ term alone; valid: q₀ > 0")
    if not cohesion > 0.0:
        raise InputError(f"macro calibration: cohesion = {cohesion!r}: the capacity line's "
                         f"intercept q₀ = {base:.4g} kPa is the law's c N_c term, which needs "
                         "c > 0")
    template = MacroElement(
        width=width, vertical_stiffness=K_v, horizontal_stiffness=K_v, rocking_stiffness=K_r,
        cohesion=cohesion, friction_angle=friction_angle, unit_weight=unit_weight,
        cohesive_factor=base / (cohesion * n_c),
        frictional_factor=slope / (0.5 * unit_weight * n_gamma) if frictional else 1.0)
    low = [b[1] for b in PLASTIC_BOUNDS]
    high = [b[2] for b in PLASTIC_BOUNDS]
    shift = -math.log10(length_unit)  # κ_ref's bounds and start, from metres
    low[1], high[1] = low[1] + shift, high[1] + shift
    start = np.asarray(start, dtype=float) + np.eye(len(PLASTIC_BOUNDS))[1] * shift
    load = max(max(p.N for p in pushovers), carry)
    low[0] = max(low[0], 1.02 * load / template.ultimate_load)
    if not low[0] < high[0]:
        raise InputError(f"macro calibration: a load of {load:.4g} is "
                         f"{load / template.ultimate_load:.3g} of V_ult = "
                         f"{template.ultimate_load:.4g}: the law's initial surface "
                         f"cannot hold it elastic (ζ0 ≤ {high[0]:g}); valid: loads below "
                         f"{high[0] / 1.02:.3g} V_ult")
    x0 = np.clip(start, low, high)
    calls, best = [0], [math.inf]
    at_most = evaluation_bound(max_evaluations)

    def objective(x):
        key = np.asarray(x, dtype=float).tobytes().hex()
        residuals = None if cache is None else cache.get(key)
        if residuals is None:
            residuals = _residuals(_law(template, x), pushovers)[0]
            if cache is not None:
                cache[key] = residuals
        calls[0] += 1
        best[0] = min(best[0], 0.5 * float(np.sum(residuals ** 2)))
        if progress is not None:
            progress(calls[0], at_most, best[0])
        return residuals

    candidates = [x0, *(low + (np.asarray(high) - low) * u for u in
                        qmc.LatinHypercube(d=len(x0), seed=0).random(SURVEY))]
    costs = [0.5 * float(np.sum(objective(x) ** 2)) for x in candidates]
    fit = None
    for k in np.argsort(costs)[:POLISHED]:  # the survey's best, each polished
        share = max(1, (max_evaluations - calls[0]) // (len(x0) + 1) // POLISHED)
        trial = least_squares(objective, candidates[k], bounds=(low, high), method="dogbox",
                              diff_step=1e-2, max_nfev=share)
        fit = trial if fit is None or trial.cost < fit.cost else fit
    law = _law(template, fit.x)
    _, moment_rms, settlement_rms, misses = _residuals(law, pushovers)
    if not np.all(misses <= LOAD_TOLERANCE):
        worst = int(np.argmax(misses))
        raise MacroStepError(f"macro calibration: the fitted law cannot hold N on pushover "
                             f"{pushovers[worst].source!r} (|V − N|/N = {misses[worst]:.2g}, "
                             f"beyond {LOAD_TOLERANCE:g}): no calibration is returned")
    return MacroCalibration(law=law, capacity_residuals=capacity_residuals,
                            moment_rms=moment_rms, settlement_rms=settlement_rms,
                            load_misses=misses, sources=tuple(p.source for p in pushovers),
                            cost=float(fit.cost), evaluations=int(calls[0]),
                            details={"capacity": {"q0": base, "q1": slope},
                                     "least_squares": {"status": int(fit.status),
                                                       "message": str(fit.message)}})
