"""The macro-element as the reduced model's foundation law: the element a scene's
``foundation.law = "macro"`` builds (:class:`BaseElement`), on the base's three DOFs, and its
entry in the registry of laws (:data:`LAW`).

The element's displacement is d = d_rest + T q: the settlement v = v_rest − V (V the base
centre's DOF, up), the sway u (the base's u_b, or u_G − h_G θ for a rigid structure) and the
rotation θ (the edge at +b sinks when θ > 0, as the springs' e_i = x_i θ − V). At rest it
carries the weight centrally, in the state :func:`rest_state` finds: elastic when the weight is
inside the initial bounding surface, else loaded along V to it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ....scenes.laws import MacroLaw
from ..base import Base, Law
from .params import MacroElement
from .plastic import MacroState, at_rest, at_vertical_load, elastic_forces, stored_energy

__all__ = ["BaseElement", "LAW", "element", "rest_state", "held_state", "PUSH_STEPS"]

#: Equal steps of the push from rest to a free vibration's initial rotation (:func:`held_state`).
PUSH_STEPS = 40


@dataclass(frozen=True, eq=False)
class BaseElement:
    """A macro-element under the base: its ``law``, its state at ``rest``, ``transform`` T
    (3 × n, d − d_rest = T q), the dashpots (``dashpot_density`` c′, force·s/length² per unit
    length of contact; ``sway_dashpot`` c_h, force·s/length, times the contact's share of the
    width) and ``force_step``, the largest change of trial force in one of its sub-steps
    (V_ult-scaled, as the compiled update takes it)."""

    law: MacroElement
    rest: MacroState
    transform: np.ndarray
    dashpot_density: float
    sway_dashpot: float
    force_step: float

    @property
    def rest_energy(self) -> float:
        """The energy the element stores at rest (force·length)."""
        return stored_energy(self.law, self.rest)

    def tangent(self) -> np.ndarray:
        """∂Q/∂d at rest (3×3), elastic: in full contact, the bonded stiffnesses."""
        r = self.rest
        return elastic_forces(self.law, r.displacement - r.plastic, r.forces, r.rounding)[1]

    def damping(self) -> np.ndarray:
        """The dashpots in full contact (3×3): c′ B, c_h and c′ B³/12."""
        width = self.law.width
        return np.diag([self.dashpot_density * width, self.sway_dashpot,
                        self.dashpot_density * width ** 3 / 12.0])

    def bonded_matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """(Tᵀ D T, Tᵀ C T) on q: the element's stiffness and damping at rest."""
        T = self.transform
        return T.T @ self.tangent() @ T, T.T @ self.damping() @ T


def rest_state(law: MacroElement, weight: float) -> MacroState:
    """The element at rest under the central ``weight``: elastic inside the initial bounding
    surface ζ0 V_ult; beyond it, loaded along V from half of that (a footing that settled
    plastically under its own weight)."""
    limit = law.initial_size * law.ultimate_load
    if weight < limit:
        return at_rest(law, weight)
    return at_vertical_load(law, at_rest(law, 0.5 * limit), (0.0, 0.0), weight)[0]


def held_state(element: BaseElement, q: np.ndarray) -> MacroState:
    """The element under the base's sway and rotation of ``q`` (d = d_rest + T q; q's V is not
    read), pushed there from rest in :data:`PUSH_STEPS` equal steps, each step's settlement
    from vertical equilibrium V = V_rest: where a free vibration released from a held
    rotation starts. The path matters once the element yields (the springs' static push has
    none: they yield in their own compression alone). Raises
    :class:`~.params.MacroStepError` where the element cannot carry the weight on the way."""
    rest = element.rest
    target = rest.displacement + element.transform @ np.asarray(q, dtype=float)
    start = rest.displacement[1:]
    state = rest
    for k in range(1, PUSH_STEPS + 1):
        held = start + (target[1:] - start) * (k / PUSH_STEPS)
        state, _ = at_vertical_load(element.law, state, held, rest.forces[0])
    return state


def element(record: MacroLaw, base: Base) -> BaseElement:
    """The :class:`BaseElement` of a scene's macro law on its base."""
    layout = base.layout
    width = 2.0 * layout.half_width
    settlement = record.hardening_settlement
    law = MacroElement.of_capacity(
        width, layout.vertical_stiffness, base.sway_stiffness,
        record.rocking_stiffness or layout.rocking_stiffness,
        record.capacity_multiple * base.weight, record.frictional_share,
        sliding_ratio=record.sliding_ratio, initial_size=record.initial_size,
        hardening_settlement=settlement if settlement is not None else width / 100.0,
        interior_modulus=record.interior_modulus, interior_exponent=record.interior_exponent,
        settlement_coupling=record.settlement_coupling, rounding_ratio=record.rounding_ratio,
        flow_dilatancy=record.flow_dilatancy, coupling_exponent=record.coupling_exponent,
        memory_modulus=record.memory_modulus)
    return BaseElement(law, rest_state(law, base.weight), np.array(base.transform, dtype=float),
                       base.dashpot_density, base.sway_dashpot,
                       record.force_step * base.weight / law.ultimate_load)


#: The macro law's entry in the registry of the reduced model's laws.
LAW = Law(record=MacroLaw, springs=None, kinds=(), element=element)
