"""The macro-element foundation law's record: one element for the whole base, its forces
(V, H, M) at the base's centre against its settlement, sway and rotation (the law itself:
:mod:`upliftlab.reduced.laws.macro`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ... import bounds
from ...checks import InputError
from ..table import Table, in_range
from .base import LawContext, LawRecord
from .elastoplastic import MULTIPLE

#: The largest memory modulus μ, for the scenes and the law alike: reloading 1e6 times stiffer
#: than the first loading is, to the sub-step's force resolution, elastic.
MAX_MEMORY_MODULUS = 1e6

__all__ = ["MacroLaw", "SLIDING_RATIO", "MAX_SETTLEMENT_COUPLING"]

#: t_h of Green's (1954) peak for a bonded strip on clay, H_max = t_h V (1 − V/V_ult).
SLIDING_RATIO = 4.0 / (2.0 + math.pi)
#: Largest settlement coupling χ a scene may give. With χ the flow's extra settlement lowers V
#: elastically; below the surface's widest point (V < ζ V_ult/2) that pushes the load outward,
#: and the plastic multiplier's denominator K_p + nᵀDn + χ r nᵀD e_V would turn negative once χ
#: passed χ* = min over the surface of (K_p + nᵀDn)/(r |nᵀD e_V|): 1.44 for the calibrated
#: clay's elastic part (lower with a softer sway or a larger t_h: 0.86 at K_h/2, 0.58 at
#: t_h = 1.5), reached under combined sway and rocking near lift-off. The law holds the flow's
#: extra settlement to half of nᵀDn's worth (revision 2), so a larger χ no longer fails the
#: step, but there its settlement is the hold's, not χ's: the scenes and the fit keep to
#: the range where the hold does not act on the calibrated laws' elastic parts.
MAX_SETTLEMENT_COUPLING = 0.4


def _coupling(name: str, value) -> float:
    """χ in [0, :data:`MAX_SETTLEMENT_COUPLING`], refused with the reason above it."""
    value = in_range(0.0, math.inf)(name, value)
    if value > MAX_SETTLEMENT_COUPLING:
        raise InputError(f"{name} = {value:g}: beyond {MAX_SETTLEMENT_COUPLING:g} the flow's "
                         "settlement can push the load out of the surface under sway and "
                         "rocking near lift-off, and the element's step fails; valid range is "
                         f"[0, {MAX_SETTLEMENT_COUPLING:g}]")
    return value


@dataclass(frozen=True, eq=False, kw_only=True)
class MacroLaw(LawRecord):
    """The macro-element: the base's bearing capacity under a central load V_ult is
    ``capacity_multiple`` times the weight; ``frictional_share`` of it comes from the N_γ term
    (½ γ B² N_γ: the capacity of a narrower contact falls with the square of its width), the
    rest from the cohesive term (c B N_c: with the width); ``rocking_stiffness`` K_r
    (force·length/rad; None: the bonded K_θ of the scene's springs' layout);
    ``sliding_ratio`` t_h; ``initial_size`` ζ0 of the bounding surface, growing to 1 with the
    plastic settlement over ``hardening_settlement`` (length; None: B/100);
    ``interior_modulus`` h0 and ``interior_exponent`` γ of the plastic modulus inside it;
    ``settlement_coupling`` χ and its ``coupling_exponent`` ε (the coupling scaled by s^ε,
    s the load's distance ratio to the bounding surface); ``memory_modulus`` μ (reloading
    below the largest mobilisation the load's side has reached is 1 + μ times stiffer in its
    plastic part: 0, no memory); ``flow_dilatancy`` δ (the share of
    the normal's heave the flow keeps, 1 associated); ``rounding_ratio`` λ_ρ; ``force_step``
    the largest change of trial force in one of the element's sub-steps, as a fraction of the
    weight (of the loads in play, not of the capacity: a strong soil's V_ult would make the
    sub-steps coarse where the footing lifts off and its load nears the bounding surface's
    apex). The foundation's ``stiffness`` is K_v, ``sway_stiffness`` K_h (required), and its
    damping (``damping_ratio`` and ``sway_damping``) acts where the base is in contact.

    The element opens its own gap on uplift (``support`` must be ``uplift``), has no impact
    damper (``restitution`` must be 1), carries its own horizontal capacity (no
    ``sliding_friction``) and is curved (the event stepper cannot tabulate it: a scene that
    names no integrator takes ``rk4``)."""

    name: ClassVar[str] = "macro"
    curved: ClassVar[str] = "the macro-element is curved"

    capacity_multiple: float
    frictional_share: float = 0.0
    rocking_stiffness: float | None = None
    sliding_ratio: float = SLIDING_RATIO
    initial_size: float = 0.5
    hardening_settlement: float | None = None
    interior_modulus: float = 1.0
    interior_exponent: float = 1.0
    settlement_coupling: float = 0.0
    rounding_ratio: float = 0.0
    flow_dilatancy: float = 1.0
    coupling_exponent: float = 0.0
    memory_modulus: float = 0.0
    force_step: float = 3e-4

    @classmethod
    def read(cls, table: Table, context: LawContext) -> MacroLaw:
        if context.support != "uplift":
            raise InputError(f"foundation.support = {context.support!r} with foundation.law = "
                             "'macro': the macro-element opens its own gap on uplift; valid: "
                             "'uplift'")
        length = bounds.checker("length", context.units)
        rocking = bounds.checker("rocking_stiffness", context.units)
        return cls(
            capacity_multiple=table.get("capacity_multiple", MULTIPLE),
            frictional_share=table.get("frictional_share", in_range(0.0, 1.0), 0.0),
            rocking_stiffness=table.get("rocking_stiffness", rocking, None),
            sliding_ratio=table.get("sliding_ratio", in_range(0.0, 4.0, low_open=True),
                                    SLIDING_RATIO),
            initial_size=table.get("initial_size", in_range(0.0, 1.0, low_open=True), 0.5),
            hardening_settlement=table.get("hardening_settlement", length, None),
            interior_modulus=table.get("interior_modulus", in_range(1e-6, 1e6), 1.0),
            interior_exponent=table.get("interior_exponent", in_range(0.1, 10.0), 1.0),
            settlement_coupling=table.get("settlement_coupling", _coupling, 0.0),
            rounding_ratio=table.get("rounding_ratio", in_range(0.0, 1.0), 0.0),
            flow_dilatancy=table.get("flow_dilatancy", in_range(0.0, 1.0), 1.0),
            coupling_exponent=table.get("coupling_exponent", in_range(0.0, 8.0), 0.0),
            memory_modulus=table.get("memory_modulus", in_range(0.0, MAX_MEMORY_MODULUS), 0.0),
            force_step=table.get("force_step", in_range(1e-6, 0.1), 3e-4))

    def check(self, foundation) -> None:
        if foundation.restitution < 1.0:
            raise InputError(f"foundation.restitution = {foundation.restitution:g} with "
                             "foundation.law = 'macro': the macro-element has no impact damper "
                             "(its plasticity dissipates the landing); valid: 1")
        if foundation.sway_stiffness is None:
            raise InputError("foundation.sway_stiffness is missing with foundation.law = "
                             "'macro': the element carries the base's horizontal force, and "
                             "its elastic part needs K_h (force/length, > 0)")
        if foundation.sliding_friction is not None:
            raise InputError(f"foundation.sliding_friction = {foundation.sliding_friction:g} "
                             "with foundation.law = 'macro': the element's horizontal "
                             "capacity is its own (foundation.sliding_ratio); remove it")
        if foundation.dashpots is not None:
            raise InputError("foundation.dashpots with foundation.law = 'macro': the element "
                             "has no springs to carry them; its dashpots come from "
                             "foundation.damping_ratio and foundation.sway_damping")
