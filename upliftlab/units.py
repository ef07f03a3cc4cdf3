"""Consistent unit systems. A scene declares one; the acceleration of gravity follows from it.

The model itself is unit-agnostic: every length, force, mass and time in a scene is in the
declared system, and ground motions (stored in g) are converted once, at load.
"""

from __future__ import annotations

from dataclasses import dataclass

from .checks import InputError

__all__ = ["UnitSystem", "UNIT_SYSTEMS", "unit_system"]


@dataclass(frozen=True)
class UnitSystem:
    """A consistent (force, length, time) system.

    ``gravity`` is g in length/s². Mass is force·s²/length (kip·s²/in, tonne, kg).
    ``newtons`` and ``metres`` are the SI values of one force and one length unit (for the
    physical bounds of :mod:`upliftlab.bounds`, which are stated in SI).
    """

    name: str
    force: str
    length: str
    time: str
    gravity: float
    newtons: float = 1.0
    metres: float = 1.0

    @property
    def mass(self) -> str:
        return f"{self.force}*{self.time}^2/{self.length}"

    @property
    def moment(self) -> str:
        return f"{self.force}*{self.length}"


UNIT_SYSTEMS = {
    "kip-in-s": UnitSystem("kip-in-s", "kip", "in", "s", 386.09, 4448.2216152605, 0.0254),
    "kN-m-s": UnitSystem("kN-m-s", "kN", "m", "s", 9.80665, 1000.0, 1.0),
    "N-m-s": UnitSystem("N-m-s", "N", "m", "s", 9.80665, 1.0, 1.0),
}


def unit_system(name: str) -> UnitSystem:
    """The unit system called ``name``; an :class:`InputError` names the valid ones."""
    try:
        return UNIT_SYSTEMS[name]
    except KeyError:
        valid = ", ".join(repr(k) for k in UNIT_SYSTEMS)
        raise InputError(f"units = {name!r}: must be one of {valid}") from None
