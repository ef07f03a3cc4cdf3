"""The macro-element's update: (its state, the footing's new displacement) → (forces, tangent,
new state, energy dissipated), as one pure function (:func:`step`).

Displacements split into an elastic part, carried by the elastic-and-uplift mechanism in closed
form (:mod:`.uplift`; H = K_h u_e), and a plastic part d_p = (v_p, u_p, θ_p). The plastic part
follows a bounding-surface model (Dafalias 1986, as Cremer et al. 2001 and Chatzigogos et al.
2009 use it for footings):

- the **bounding surface** is the capacity (:mod:`.capacity`) scaled by a size ζ(κ) =
  1 − (1 − ζ0) exp(−κ/κ_ref), κ the accumulated plastic settlement (m): it grows to the
  failure surface as the footing settles, and no load ever lies beyond it;
- the **image point** Q_I is where the line from the projection centre Q_c (the last load
  reversal; the static load at rest) through the trial forces meets the bounding surface, and
  s = |Q − Q_c| / |Q_I − Q_c| ∈ [0, 1] (in forces scaled by V_ult, V_ult, B V_ult) says how far
  the load has gone towards it;
- the **plastic modulus** is K_p = K_b + h0 (K_v/V_ult²) ((1 − s)/s)^γ: infinite at the centre
  (elastic reloading), the bounding surface's own hardening K_b = (ζ′/ζ) ⟨m_v⟩ on it (no
  hardening: perfectly plastic at the capacity);
- the **flow** is along m = n + χ |(n_H, n_M)| e_V in the scaled forces, n the normal ∂F/∂Q at
  the image point: with χ > 0 the footing settles while it yields in rotation or shear, the
  coupling of settlement and rocking that springs yielding one by one lack;
- a **reversal** (the trial load turns back, n·ΔQ < 0) moves the projection centre to the
  present load, so that every unload-reload loop dissipates, a little less as it shrinks.

The step is integrated in sub-steps no larger than ``max_force_step`` (V_ult-scaled) of trial
force each: the elastic part exact at every sub-step (no drift), the plastic multiplier
explicit, and a load that ends beyond the bounding surface returned onto it along m (so F ≤ 0
holds to round-off). The returned tangent is the continuum elasto-plastic tangent
D_e − D_e m nᵀ D_e / (K_p + nᵀ D_e m) of the last sub-step (D_e, the elastic one, after a
reversal), non-symmetric when χ > 0, as a non-associated flow makes it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .capacity import failure_function, failure_gradient, failure_size_derivative
from .params import MacroElement, MacroStepError
from .uplift import vertical_rocking_displacement, vertical_rocking_forces

__all__ = ["MacroState", "MacroStep", "at_rest", "elastic_forces", "step", "size",
           "stored_energy"]

#: Largest trial force change per sub-step, scaled by V_ult (and B V_ult for M).
MAX_FORCE_STEP = 2e-3
MAX_SUBSTEPS = 200_000


@dataclass(frozen=True)
class MacroState:
    """The macro-element's state: ``displacement`` (v, u, θ) (m, m, rad), its ``plastic``
    part, the ``forces`` (V, H, M) (kN/m, kN/m, kN·m/m), the projection ``centre`` (forces
    at the last reversal), ``settlement`` κ (m, the accumulated plastic settlement the size
    grows with) and ``dissipated`` (kN·m/m, the plastic work so far)."""

    displacement: np.ndarray
    plastic: np.ndarray
    forces: np.ndarray
    centre: np.ndarray
    settlement: float = 0.0
    dissipated: float = 0.0


@dataclass(frozen=True)
class MacroStep:
    """One step's outcome: the new ``state`` and the ``tangent`` ∂Q/∂d (3×3)."""

    state: MacroState
    tangent: np.ndarray


def size(law: MacroElement, settlement: float) -> float:
    """ζ(κ): the bounding surface's size after a plastic settlement κ (m)."""
    return 1.0 - (1.0 - law.initial_size) * math.exp(-settlement / law.hardening_settlement)


def elastic_forces(law: MacroElement, elastic, guess=None):
    """(Q, ∂Q/∂d_e (3×3), stored energy) of the elastic-and-uplift mechanism at elastic
    displacement (v_e, u_e, θ_e)."""
    v, u, theta = elastic
    nm, k2, energy = vertical_rocking_forces(law, v, theta,
                                             None if guess is None else guess[[0, 2]])
    Q = np.array([nm[0], law.horizontal_stiffness * u, nm[1]])
    D = np.zeros((3, 3))
    D[np.ix_([0, 2], [0, 2])] = k2
    D[1, 1] = law.horizontal_stiffness
    return Q, D, energy + 0.5 * law.horizontal_stiffness * u * u


def stored_energy(law: MacroElement, state: MacroState) -> float:
    """The energy the elastic-and-uplift mechanism stores in ``state`` (kN·m/m)."""
    return elastic_forces(law, state.displacement - state.plastic, state.forces)[2]


def at_rest(law: MacroElement, vertical_load: float) -> MacroState:
    """The footing at rest under a central ``vertical_load`` V0 (kN/m): elastic, with the
    projection centre at its static load. V0 must lie inside the initial bounding surface."""
    from ....checks import InputError

    limit = law.initial_size * law.ultimate_load
    if not 0.0 < vertical_load < limit:
        raise InputError(f"macro: vertical load = {vertical_load:g}: valid range is (0, "
                         f"{limit:g}) (inside the initial bounding surface ζ0 V_ult)")
    v0 = vertical_load / law.vertical_stiffness
    d = np.array([v0, 0.0, 0.0])
    Q = elastic_forces(law, d)[0]
    return MacroState(d, np.zeros(3), Q, Q.copy())


def _scales(law: MacroElement) -> np.ndarray:
    vu = law.ultimate_load
    return np.array([vu, vu, law.width * vu])


def _image(law: MacroElement, centre, direction, zeta):
    """The distance t (in units of ``direction``) from ``centre`` to the bounding surface."""
    reach = 10.0 / max(np.max(np.abs(direction / _scales(law))), 1e-300)  # beyond the surface
    high = min(1.0, reach)
    while failure_function(law, centre + high * direction, zeta) <= 0.0:
        high *= 2.0
        if high > reach:
            raise MacroStepError("macro: the bounding surface is not closed along the load")
    low = 0.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        if failure_function(law, centre + mid * direction, zeta) <= 0.0:
            low = mid
        else:
            high = mid
        if high - low <= 1e-15 * high:
            break
    return low


def _flow(law: MacroElement, normal, scale):
    """m from the normal n (both ∂/∂Q in force units): χ |(n_H, n_M)| added to n_V in
    V_ult-scaled forces."""
    scaled = normal * scale
    scaled = scaled + np.array([law.settlement_coupling * math.hypot(scaled[1], scaled[2]),
                                0.0, 0.0])
    return scaled / scale


def _plastic_modulus(law, state, image, flow, s, zeta):
    """K_p (1/(kN·m)) at distance ratio s: the bounding surface's own hardening
    K_b = −∂F/∂ζ ζ′(κ) ⟨m_v⟩ plus the interior term."""
    vu = law.ultimate_load
    grow = (1.0 - law.initial_size) / law.hardening_settlement * math.exp(
        -state.settlement / law.hardening_settlement)
    bound = -failure_size_derivative(law, image, zeta) * grow * max(flow[0], 0.0)
    if s <= 0.0:
        return math.inf
    if s >= 1.0:
        return bound
    interior = law.interior_modulus * law.vertical_stiffness / vu ** 2
    return bound + interior * ((1.0 - s) / s) ** law.interior_exponent


def _substep(law: MacroElement, state: MacroState, target, scale):
    """One sub-step to total displacement ``target``: (new state, tangent)."""
    Q0 = state.forces
    trial, D, _ = elastic_forces(law, target - state.plastic, Q0)
    if trial[0] <= 0.0:  # lifted off: no load, and the footing's sway is free
        plastic = np.array([state.plastic[0], target[1], state.plastic[2]])
        return replace(state, displacement=target, plastic=plastic, forces=np.zeros(3)), \
            np.zeros((3, 3))
    zeta = size(law, state.settlement)
    centre = state.centre
    direction = (trial - centre) / scale
    if np.linalg.norm(direction) <= 1e-13:
        return replace(state, displacement=target, forces=trial), D
    t = _image(law, centre, direction * scale, zeta)
    image = centre + t * direction * scale
    normal = failure_gradient(law, image, zeta)
    if normal @ (trial - Q0) < 0.0:  # a reversal: the centre moves to the present load
        centre = Q0.copy()
        direction = (trial - centre) / scale
        t = _image(law, centre, direction * scale, zeta)
        image = centre + t * direction * scale
        normal = failure_gradient(law, image, zeta)
    s = np.linalg.norm((Q0 - centre) / scale) / max(t * np.linalg.norm(direction), 1e-300)
    flow = _flow(law, normal, scale)
    modulus = _plastic_modulus(law, state, image, flow, min(s, 1.0), zeta)
    loading = normal @ (trial - Q0)
    if not math.isfinite(modulus) or loading <= 0.0:
        return replace(state, displacement=target, forces=trial, centre=centre), D
    Dm = D @ flow
    lam = loading / (modulus + normal @ Dm)
    plastic = state.plastic + lam * flow
    Q, D1, _ = elastic_forces(law, target - plastic, trial)
    settlement = state.settlement + max(lam * flow[0], 0.0)
    zeta1 = size(law, settlement)
    if failure_function(law, Q, zeta1) > 0.0:
        before = plastic[0]
        plastic, Q = _return(law, target, Q, zeta1)
        settlement += max(plastic[0] - before, 0.0)
        D1 = elastic_forces(law, target - plastic, Q)[1]
    work = 0.5 * (Q0 + Q) @ (plastic - state.plastic)
    tangent = D1 - np.outer(D1 @ flow, normal @ D1) / (modulus + normal @ (D1 @ flow))
    new = MacroState(target, plastic, Q, centre, settlement, state.dissipated + work)
    return new, tangent


def _return(law, target, Q, zeta):
    """A load ``Q`` beyond the bounding surface returned onto it radially, towards the
    surface's inner point (ζ V_ult/2, 0, 0), and the elastic displacement that carries the
    returned load (the inverse of the mechanism, in closed form): (plastic displacement,
    forces). Only a sub-step's drift, or a footing that lifts off, is returned so."""
    inner = np.array([0.5 * zeta * law.ultimate_load, 0.0, 0.0])
    t = _image(law, inner, Q - inner, zeta)
    returned = inner + t * (Q - inner)
    v, theta = vertical_rocking_displacement(law, returned[0], returned[2])
    elastic = np.array([v, returned[1] / law.horizontal_stiffness, theta])
    return target - elastic, returned


def step(law: MacroElement, state: MacroState, displacement,
         max_force_step: float = MAX_FORCE_STEP) -> MacroStep:
    """The macro-element moved from ``state`` to total ``displacement`` (v, u, θ): its new
    state and tangent, in sub-steps of at most ``max_force_step`` trial force (V_ult-scaled)."""
    target = np.asarray(displacement, dtype=float)
    scale = _scales(law)
    trial = elastic_forces(law, target - state.plastic, state.forces)[0]
    count = max(1, math.ceil(np.max(np.abs(trial - state.forces) / scale) / max_force_step))
    if count > MAX_SUBSTEPS:
        raise MacroStepError(f"macro: a step of {count} sub-steps (more than {MAX_SUBSTEPS}); "
                             "take smaller steps")
    start = state.displacement
    tangent = None
    for i in range(1, count + 1):
        state, tangent = _substep(law, state, start + (target - start) * (i / count), scale)
    return MacroStep(state, tangent)
