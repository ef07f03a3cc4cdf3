"""The macro-element's update: (its state, the footing's new displacement) → (forces, tangent,
new state, energy dissipated), as one pure function (:func:`step`).

Displacements split into an elastic part, carried by the elastic-and-uplift mechanism in closed
form (:mod:`.uplift`; H = K_h u_e), and a plastic part d_p = (v_p, u_p, θ_p). The plastic part
follows a bounding-surface model (Dafalias 1986, as Cremer et al. 2001 and Chatzigogos et al.
2009 use it for footings):

- the **bounding surface** is the capacity (:mod:`.capacity`) scaled by a size ζ(κ) =
  1 − (1 − ζ0) exp(−κ/κ_ref), κ the accumulated plastic settlement (m): it grows to the
  failure surface as the footing settles, and no load ever lies beyond it;
- the **mobilisation** ζ_Q of a load is the size of the surface through it (the capacity
  scaled until it carries the load): a central V is at V/V_ult, and a footing that lifts off
  under a load at eccentricity b − a/3 (contact a) is at 3V/(2 a q) on a Tresca clay, the
  pressure under its contact against the soil's, not the load's nearness to the overturning
  limit M = V b (the first form of this law took s along the ray from the centre to its
  image on the bounding surface, which an uplifting footing's load heads for near the apex
  at V = 0, and the normal there: on a wall at FS_v 3 under Ricker pulses of 0.3 and 0.6 g it
  did negative plastic work of 5.4e-4 and 1.0e-4 of the input, this form none);
  s = (ζ_Q − ζ_c)/(ζ − ζ_c) ∈ [0, 1] says how far the load has gone from the projection
  centre's mobilisation ζ_c (the last reversal; the static load at rest) to the bounding
  surface;
- the **plastic modulus** is K_p = K_b + h0 (K_v/V_ult²) ((1 − s)/s)^γ: infinite at the centre
  (elastic reloading), the bounding surface's own hardening K_b = −∂F/∂ζ ζ′(κ) ⟨m_v⟩ on it
  (no hardening: perfectly plastic at the capacity);
- the **flow** is along m = (⟨n_V⟩ − δ ⟨−n_V⟩ + χ s^ε |(n_H, n_M)|, n_H, n_M) in the scaled
  forces, n the normal ∂F/∂Q of the surface through the load, at the load (so that Q·n ≥ 0
  wherever that surface is convex, the clay's everywhere, and Q·m ≥ Q·n as V ≥ 0): with
  χ > 0 the footing settles while it yields in rotation or shear, the coupling of settlement
  and rocking that springs yielding one by one lack; with ε > 0 that coupling fades in the
  small cycles inside the bounding surface (s → 0), where free rocking after a pulse would
  otherwise ratchet the footing down cycle after cycle; and δ < 1 (the flow's dilatancy)
  takes part or all of the heave out of the normal where it points to less V (loads below
  the surface's widest V, which the contact-pressure mobilisation of a lifting footing puts
  most rocking loads at): associated flow (δ = 1) heaves a light footing that rocks at its
  capacity, as an upper-bound mechanism of a rigid block does, which an undrained clay
  under cycles does not; the flow's settlement beyond the normal's, a = m_V − n_V, is held
  where it would take more than half of the load's stiffness along its flow
  (a (−nᵀD e_V) ≤ ½ nᵀDn, D the trial's tangent), so that K_p + nᵀDm > 0 on every step:
  δ = 0 with χ > 0 otherwise fails 3 of 20 seeded walks of settlement, sway and rotation on
  either soil (χ ≤ 0.4 and δ ≥ 0.5 none);
- a **reversal** (the mobilisation falls, n·ΔQ < 0) moves the projection centre to the
  present load: unloading is elastic, and every unload-reload loop dissipates, a little less
  as it shrinks;
- the **memory** (ζ⁺, ζ⁻) is the largest mobilisation a load has reached on each side (the
  sign of M: the edge it presses): a load below its side's memory ζ_m is reloading the soil
  has carried before, and the interior term of its plastic modulus is (1 + μ w) times as
  large (μ the ``memory_modulus``), w = (ζ_m − ζ_Q)/(ζ_m − ζ_c) the share of the way back
  from the memory to the last reversal: stiffest just after the reversal, the first
  loading's modulus again as the load regains its memory (continuous, so that the update
  stays a continuous function of the displacement: a switch at the memory made the fit's
  laws miss N by 0.6 % on a pushover, where V(v) jumped across it). A footing
  cycled at one amplitude then settles in its first cycle and ever less after it, as the
  continuum does (it shakes down: on the half-plane reference, six cycles at 2 θ_on settle the
  clay's footing by +1.04 mm in the first and +0.001 mm in the second, at FS_v 3); without the
  memory (μ = 0, revision 2) the projection centre alone starts every reloading anew, and the
  element settled about as much in the sixth cycle as in the first (0.86 to 1.14 of it,
  ``benchmarks/MACRO_SMALL_CYCLES.md``);
- the **rounding** ρ of the soil's surface grows by λ_ρ b |dθ_p| while the bed presses its
  edges harder than its middle (F_ρ > 0, :mod:`.uplift`), and absorbs F_ρ dρ: rocking that
  yields the soil under each edge in turn leaves the footing resting on its middle.

The update is compiled (:mod:`.compiled`); here are its readable entry points. The step is
integrated in sub-steps no larger than ``max_force_step`` (V_ult-scaled) of trial force each:
the elastic part exact at every sub-step (no drift), the plastic multiplier explicit, and a load
that ends beyond the bounding surface returned radially onto it, towards (ζ V_ult/2, 0, 0), with
the plastic displacement that leaves the elastic part carrying it (so F ≤ 0 holds to
round-off). The returned tangent is the update's own over the last sub-step,
D − (D m − r g) nᵀ D / (K_p + nᵀ D m) (r g the rounding's share, r = λ_ρ b |m_θ|, g = ∂Q/∂ρ),
non-symmetric when χ > 0, δ < 1 or the surface rounds; the elastic one after a reversal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ....checks import InputError, positive
from . import compiled as cc
from .params import MacroElement, MacroStepError

__all__ = ["MacroState", "MacroStep", "at_rest", "elastic_forces", "step", "size",
           "stored_energy", "at_vertical_load", "MAX_FORCE_STEP", "LOAD_TOLERANCE"]

#: Largest trial force change per sub-step, scaled by V_ult (and B V_ult for M): on the clay's
#: calibrated law, a cyclic rotation pushover at FS_v 3 ends settled by 4.2832 mm at this
#: step, 4.2830 at 2e-4 and 4.2828 at 2e-5 (3.907 at 2e-3, the first default).
MAX_FORCE_STEP = 5e-4

#: Why a step of the macro-element failed, by its status.
FAILURES = {cc.STEP_CONTACT: "the contact's iterations did not converge",
             cc.STEP_SURFACE: "the bounding surface is not closed along the load",
             cc.STEP_SUBSTEPS: f"the step needs more than {cc.MAX_SUBSTEPS} sub-steps",
             cc.STEP_FLOW: "the load has no stiffness along its plastic flow"}


@dataclass(frozen=True)
class MacroState:
    """The macro-element's state: ``displacement`` (v, u, θ) (m, m, rad), its ``plastic``
    part, the ``forces`` (V, H, M) (kN/m, kN/m, kN·m/m), the projection ``centre`` (forces
    at the last reversal), ``settlement`` κ (m, the accumulated plastic settlement the size
    grows with), ``dissipated`` (kN·m/m, the plastic work so far), ``rounding`` ρ (m, of
    the soil's surface under the footing, :mod:`.uplift`) and ``memory`` (ζ⁺, ζ⁻), the
    largest mobilisation a load has reached with M ≥ 0 and with M < 0 (0 before any load)."""

    displacement: np.ndarray
    plastic: np.ndarray
    forces: np.ndarray
    centre: np.ndarray
    settlement: float = 0.0
    dissipated: float = 0.0
    rounding: float = 0.0
    memory: tuple[float, float] = (0.0, 0.0)

    def packed(self) -> np.ndarray:
        """The state as the compiled forms hold it."""
        S = np.empty(cc.S_COUNT)
        S[cc.S_D:cc.S_D + 3], S[cc.S_P:cc.S_P + 3] = self.displacement, self.plastic
        S[cc.S_Q:cc.S_Q + 3], S[cc.S_C:cc.S_C + 3] = self.forces, self.centre
        S[cc.S_KAPPA], S[cc.S_W], S[cc.S_ROUND] = self.settlement, self.dissipated, self.rounding
        S[cc.S_MEM:cc.S_MEM + 2] = self.memory
        return S

    @classmethod
    def unpacked(cls, S) -> MacroState:
        return cls(S[cc.S_D:cc.S_D + 3].copy(), S[cc.S_P:cc.S_P + 3].copy(),
                   S[cc.S_Q:cc.S_Q + 3].copy(), S[cc.S_C:cc.S_C + 3].copy(),
                   float(S[cc.S_KAPPA]), float(S[cc.S_W]), float(S[cc.S_ROUND]),
                   (float(S[cc.S_MEM]), float(S[cc.S_MEM + 1])))


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
        raise MacroStepError(f"macro: {FAILURES[cc.STEP_CONTACT]} at {list(elastic)}")
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
        raise MacroStepError(f"macro: {FAILURES[status]} (from {state.forces.tolist()} to "
                             f"displacement {list(displacement)})")
    return MacroStep(MacroState.unpacked(S), D, count)


#: The vertical load's tolerance of :func:`at_vertical_load`, relative to it. The update is
#: discontinuous where a sub-step's load turns (a reversal moves the projection centre), by
#: up to about 3e-5 N on the clay's cycles: an iteration that cannot reach 1e-10 N for that
#: reason ends at the best v it found, if within this.
LOAD_TOLERANCE = 1e-4


def at_vertical_load(law: MacroElement, state: MacroState, sway_rotation, load: float,
                     strict: bool = True) -> tuple[MacroState, float]:
    """(the state at horizontal displacement and rotation ``sway_rotation`` = (u, θ) whose V is
    ``load``, its |V − load|/load): V(v), one step from ``state`` in the sub-steps the first
    trial asked for, solved by Newton's method kept inside a bracket, halved when a step leaves
    it, does not halve the residual or meets a falling V (a footing that softens as it
    rounds). Not ``strict``: the closest state when none is within :data:`LOAD_TOLERANCE`
    (else :class:`MacroStepError`)."""
    u, theta = (float(x) for x in sway_rotation)
    v = state.displacement[0]
    count, low, high = 0, None, None
    best, best_state = math.inf, None
    for _ in range(100):
        out = step(law, state, [v, u, theta], substeps=count)
        count = out.substeps
        residual = out.state.forces[0] - load
        if abs(residual) <= 1e-10 * load:
            return out.state, abs(residual) / load
        if residual < 0.0:
            low = v if low is None else max(low, v)
        else:
            high = v if high is None else min(high, v)
        slope = out.tangent[0, 0]
        guess = v - residual / slope if slope > 0.0 else math.nan
        inside = (low is None or guess > low) and (high is None or guess < high)
        if not (math.isfinite(guess) and inside and abs(residual) < 0.5 * best):
            if low is not None and high is not None:
                guess = 0.5 * (low + high)
            elif not math.isfinite(guess) or not inside:
                scale = max(abs(v), load / law.vertical_stiffness)
                guess = v + (scale if residual < 0.0 else -scale)
        if abs(residual) < best:
            best, best_state = abs(residual), out.state
        if low is not None and high is not None and high - low <= 1e-14 * abs(v):
            break
        v = guess
    if best_state is not None and (best <= LOAD_TOLERANCE * load or not strict):
        return best_state, best / load
    raise MacroStepError(f"macro: V did not settle at {load:g} at (u, θ) = ({u:g}, {theta:g})"
                         f" (closest {best:.3g} away)")
