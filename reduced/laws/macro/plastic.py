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
  present load, so that every unload-reload loop dissipates, a little less as it shrinks;
- the **rounding** ρ of the soil's surface grows by λ_ρ b |dθ_p| while the bed presses its
  edges harder than its middle (F_ρ > 0, :mod:`.uplift`), and absorbs F_ρ dρ: rocking that
  yields the soil under each edge in turn leaves the footing resting on its middle.

The update is compiled (:mod:`.compiled`); here are its readable entry points. The step is
integrated in sub-steps no larger than ``max_force_step`` (V_ult-scaled) of trial
force each: the elastic part exact at every sub-step (no drift), the plastic multiplier
explicit, and a load that ends beyond the bounding surface returned onto it along m (so F ≤ 0
holds to round-off). The returned tangent is the continuum elasto-plastic tangent
D_e − D_e m nᵀ D_e / (K_p + nᵀ D_e m) of the last sub-step (D_e, the elastic one, after a
reversal), non-symmetric when χ > 0, as a non-associated flow makes it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ....checks import InputError, positive
from . import compiled as cc
from .params import MacroElement, MacroStepError

__all__ = ["MacroState", "MacroStep", "at_rest", "elastic_forces", "step", "size",
           "stored_energy", "MAX_FORCE_STEP"]

#: Largest trial force change per sub-step, scaled by V_ult (and B V_ult for M).
MAX_FORCE_STEP = 2e-3

_FAILURES = {cc.STEP_CONTACT: "the contact's iterations did not converge",
             cc.STEP_SURFACE: "the bounding surface is not closed along the load",
             cc.STEP_SUBSTEPS: f"the step needs more than {cc.MAX_SUBSTEPS} sub-steps",
             cc.STEP_FLOW: "the load has no stiffness along its plastic flow"}


@dataclass(frozen=True)
class MacroState:
    """The macro-element's state: ``displacement`` (v, u, θ) (m, m, rad), its ``plastic``
    part, the ``forces`` (V, H, M) (kN/m, kN/m, kN·m/m), the projection ``centre`` (forces
    at the last reversal), ``settlement`` κ (m, the accumulated plastic settlement the size
    grows with), ``dissipated`` (kN·m/m, the plastic work so far) and ``rounding`` ρ (m, of
    the soil's surface under the footing, :mod:`.uplift`)."""

    displacement: np.ndarray
    plastic: np.ndarray
    forces: np.ndarray
    centre: np.ndarray
    settlement: float = 0.0
    dissipated: float = 0.0
    rounding: float = 0.0

    def packed(self) -> np.ndarray:
        """The state as the compiled forms hold it."""
        S = np.empty(cc.S_COUNT)
        S[cc.S_D:cc.S_D + 3], S[cc.S_P:cc.S_P + 3] = self.displacement, self.plastic
        S[cc.S_Q:cc.S_Q + 3], S[cc.S_C:cc.S_C + 3] = self.forces, self.centre
        S[cc.S_KAPPA], S[cc.S_W], S[cc.S_ROUND] = self.settlement, self.dissipated, self.rounding
        return S

    @classmethod
    def unpacked(cls, S) -> MacroState:
        return cls(S[cc.S_D:cc.S_D + 3].copy(), S[cc.S_P:cc.S_P + 3].copy(),
                   S[cc.S_Q:cc.S_Q + 3].copy(), S[cc.S_C:cc.S_C + 3].copy(),
                   float(S[cc.S_KAPPA]), float(S[cc.S_W]), float(S[cc.S_ROUND]))


@dataclass(frozen=True)
class MacroStep:
    """One step's outcome: the new ``state``, the ``tangent`` ∂Q/∂d (3×3) and the number of
    ``substeps`` it took."""

    state: MacroState
    tangent: np.ndarray
    substeps: int = 1


def size(law: MacroElement, settlement: float) -> float:
    """ζ(κ): the bounding surface's size after a plastic settlement κ (m)."""
    return cc.size(cc.pack(law), settlement)


def elastic_forces(law: MacroElement, elastic, guess=None, rounding: float = 0.0):
    """(Q, ∂Q/∂d_e (3×3), stored energy) of the elastic-and-uplift mechanism at elastic
    displacement (v_e, u_e, θ_e), the soil's surface rounded by ρ = ``rounding`` (m)."""
    Q, D = np.empty(3), np.empty((3, 3))
    g = np.zeros(3) if guess is None else np.asarray(guess, dtype=float)
    energy, ok = cc.elastic(cc.pack(law), np.asarray(elastic, dtype=float), g, Q, D,
                            float(rounding))
    if not ok:
        raise MacroStepError(f"macro: {_FAILURES[cc.STEP_CONTACT]} at {list(elastic)}")
    return Q, D, energy


def stored_energy(law: MacroElement, state: MacroState) -> float:
    """The energy the elastic-and-uplift mechanism stores in ``state`` (kN·m/m)."""
    return elastic_forces(law, state.displacement - state.plastic, state.forces,
                          state.rounding)[2]


def at_rest(law: MacroElement, vertical_load: float) -> MacroState:
    """The footing at rest under a central ``vertical_load`` V0 (kN/m): elastic, with the
    projection centre at its static load. V0 must lie inside the initial bounding surface."""
    limit = law.initial_size * law.ultimate_load
    if not 0.0 < vertical_load < limit:
        raise InputError(f"macro: vertical load = {vertical_load:g}: valid range is (0, "
                         f"{limit:g}) (inside the initial bounding surface ζ0 V_ult)")
    d = np.array([vertical_load / law.vertical_stiffness, 0.0, 0.0])
    Q = elastic_forces(law, d)[0]
    return MacroState(d, np.zeros(3), Q, Q.copy())


def step(law: MacroElement, state: MacroState, displacement,
         max_force_step: float = MAX_FORCE_STEP, substeps: int = 0) -> MacroStep:
    """The macro-element moved from ``state`` to total ``displacement`` (v, u, θ): its new
    state and tangent, in sub-steps of at most ``max_force_step`` trial force (V_ult-scaled),
    or in exactly ``substeps`` of them (an iteration on one step keeps their number, so that
    the update is a smooth function of the displacement). A step that cannot be completed
    raises :class:`MacroStepError`."""
    positive("max_force_step", max_force_step)
    P, S, D = cc.pack(law), state.packed(), np.empty((3, 3))
    target, W = np.asarray(displacement, dtype=float), np.empty(cc.W_COUNT)
    count = int(substeps) if substeps > 0 else cc.substeps(P, S, target, float(max_force_step),
                                                            D, W)
    status = cc.step_into(P, S, target, float(max_force_step), count, D, W) if count else \
        cc.STEP_CONTACT
    if status != cc.STEP_OK:
        raise MacroStepError(f"macro: {_FAILURES[status]} (from {state.forces.tolist()} to "
                             f"displacement {list(displacement)})")
    return MacroStep(MacroState.unpacked(S), D, count)
