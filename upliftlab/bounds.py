"""Physical bounds of scene fields: a value outside them describes no structure or soil.

A positive number is not yet a meaningful one: a Young's modulus of 1e300 or a weight of 1e-300
passes ``> 0`` and then overflows, divides by zero or makes the integrators take 10¹⁵ steps.
Each dimensional field has a *kind* (:data:`KINDS`) with a range stated in SI, wide enough for
any structure from a laboratory model to a dam (a base 0.1 mm to 100 km wide, a weight of
1 µN to 10¹³ N, a soil from peat to steel), and converted to the scene's units in the message.

These are ranges of meaning, not of accuracy: a value inside them can still ask for a run too
long or too large to be useful, which :mod:`upliftlab.budget` estimates and refuses before the
run starts.
"""

from __future__ import annotations

from dataclasses import dataclass

from .checks import InputError, finite
from .units import UnitSystem

__all__ = ["Kind", "KINDS", "check", "checker"]


@dataclass(frozen=True)
class Kind:
    """A physical quantity: its dimension as exponents of (force, length), its unit in a scene
    (``template`` with {F} and {L}), its SI unit ``si`` and its valid range in SI, ``low`` to
    ``high`` (``low_open``: > low). A kind whose range starts at zero may set ``tiny``: a value
    between zero and it is no quantity but a zero written otherwise (a subnormal number, say),
    which would make a matrix singular instead of leaving the term out: it is refused."""

    force: int
    length: int
    template: str
    si: str
    low: float
    high: float
    low_open: bool = False
    tiny: float = 0.0

    def factor(self, units: UnitSystem) -> float:
        """SI value of one scene unit of this kind."""
        return units.newtons ** self.force * units.metres ** self.length

    def unit(self, units: UnitSystem) -> str:
        return self.template.format(F=units.force, L=units.length)


#: The kinds of the scene's dimensional fields. Mass enters as force·s²/length.
KINDS: dict[str, Kind] = {
    "length": Kind(0, 1, "{L}", "m", 1e-4, 1e5),
    "force": Kind(1, 0, "{F}", "N", 1e-6, 1e13),
    "stiffness": Kind(1, -1, "{F}/{L}", "N/m", 1e-6, 1e16),
    "dashpot": Kind(1, -1, "{F}*s/{L}", "N*s/m", 0.0, 1e16, tiny=1e-9),
    "rocking_stiffness": Kind(1, 1, "{F}*{L}/rad", "N*m/rad", 1e-6, 1e18),
    # a rotary inertia 0 < I0 < 1e-9 kg m² (a 1 g body 1 mm across) is a zero written otherwise
    "rotary_inertia": Kind(1, 1, "{F}*{L}*s^2", "kg*m^2", 0.0, 1e18, tiny=1e-9),
    "modulus": Kind(1, -2, "{F}/{L}^2", "Pa", 1e3, 1e13),
    "strength": Kind(1, -2, "{F}/{L}^2", "Pa", 0.0, 1e10),
    "strength_gradient": Kind(1, -3, "{F}/{L}^3", "Pa/m", 0.0, 1e10),
    "hardening": Kind(1, -2, "{F}/{L}^2", "Pa", 0.0, 1e13),
    "density": Kind(1, -4, "{F}*s^2/{L}^4", "kg/m^3", 0.0, 1e5),
    "velocity": Kind(0, 1, "{L}/s", "m/s", -1e3, 1e3),
    "displacement": Kind(0, 1, "{L}", "m", -1e3, 1e3),
    "period": Kind(0, 0, "s", "s", 1e-5, 1e4),
    "duration": Kind(0, 0, "s", "s", 1e-6, 1e6),
    "step": Kind(0, 0, "s", "s", 1e-9, 1e3),
    "rotation": Kind(0, 0, "rad", "rad", -1.0, 1.0),
    "acceleration_g": Kind(0, 0, "g", "g", -100.0, 100.0),
}


def check(field: str, value, kind: str, units: UnitSystem) -> float:
    """``value`` (scene units) as a float within the physical range of ``kind``; an
    :class:`InputError` names the field, the value and the range in scene units and in SI."""
    value = finite(field, value)
    k = KINDS[kind]
    factor = k.factor(units)
    si = value * factor
    below = si <= k.low if k.low_open else si < k.low
    if si != 0.0 and abs(si) < k.tiny:
        what = kind.replace("_", " ")
        raise InputError(f"{field} = {value:g}: not zero, yet below {k.tiny / factor:.3g} "
                         f"{k.unit(units)} ({k.tiny:g} {k.si}), no physical {what}; give 0 or "
                         "a value in the physical range")
    if below or si > k.high:
        unit = k.unit(units)
        left = "(" if k.low_open else "["
        scene = f"{left}{k.low / factor:.3g}, {k.high / factor:.3g}] {unit}".rstrip()
        si_text = "" if factor == 1.0 else f" ({left}{k.low:g}, {k.high:g}] {k.si})"
        raise InputError(f"{field} = {value:g}: outside the physical range {scene}{si_text}")
    return value


def checker(kind: str, units: UnitSystem):
    """``check`` as a ``(field, value) -> float`` validator for one kind and unit system."""
    return lambda field, value: check(field, value, kind, units)
