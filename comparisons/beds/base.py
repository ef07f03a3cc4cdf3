"""What any bed of the registry is calibrated from, and the four base beds.

:class:`BedReference` holds the continuum's numbers at one point; :func:`base_builder` gives the
builder of one of :func:`.stiffness.calibrate`'s beds (``uniform``, ``end_stiffened`` and their
elasto-plastic forms), which the registry (:mod:`.registry`) holds and the beds built on them
(:mod:`.dashpots`, :mod:`.fitted`) start from. The beds' structure, when a builder needs one (a
mode, a pushover), is that of the base scene :data:`BASE_SCENE` (:func:`base_table`), the Winkler
map's scene.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from ...checks import InputError
from ...scenes import load_scene
from .stiffness import calibrate

__all__ = ["BASE_SCENE", "base_table", "BedReference", "base_builder", "calibration",
           "required_extra"]

#: The scene the beds are built in: a 2 m strip footing on clay, in kN-m-s.
BASE_SCENE = "strip_footing_clay"


def base_table() -> dict:
    """The base scene's table without its motion."""
    data = copy.deepcopy(load_scene(BASE_SCENE).data)
    data.pop("motion", None)
    return data


@dataclass(frozen=True)
class BedReference:
    """The continuum's numbers a bed is calibrated from, at one point of the map (scene units:
    kN, m, per metre of footing).

    ``soil`` its name; ``N`` the vertical load, ``B`` the footing width, ``h`` the story height;
    ``K_v`` and ``K_r`` the continuum footing's vertical and rocking stiffness in full contact;
    ``V_ult`` the continuum's vertical capacity of the soil (its vertical pushover);
    ``G``, ``nu`` the soil's shear modulus and Poisson ratio; ``extra`` more continuum
    quantities a future calibration may need, by name.
    """

    soil: str
    N: float
    B: float
    h: float
    K_v: float
    K_r: float
    V_ult: float
    G: float
    nu: float
    extra: Mapping = field(default_factory=dict)

    @property
    def fs_v(self) -> float:
        """V_ult/N, the vertical factor of safety on the continuum's capacity."""
        return self.V_ult / self.N

    @property
    def N_ult(self) -> float:
        """V_ult (force/length), under the name :func:`.stiffness.calibrate` reads."""
        return float(self.V_ult)


def calibration(reference: BedReference, options, name: str):
    """The bed ``name`` of :func:`.stiffness.calibrate` for ``reference``, with the ``springs``,
    ``end_length`` and ``max_end_stiffness_ratio`` of ``options``."""
    return next(c for c in calibrate(reference, options) if c.name == name)


def base_builder(name: str) -> Callable:
    """The builder ``build(reference, options) -> [foundation] table`` of calibration
    ``name`` of :func:`.stiffness.calibrate`."""
    def build(reference: BedReference, options) -> dict:
        return calibration(reference, options, name).foundation_table()

    build.__name__ = build.__qualname__ = f"build_{name}"
    build.__doc__ = (f"The ``{name}`` bed of :func:`.stiffness.calibrate` as a "
                     "[foundation] table.")
    return build


def required_extra(reference: BedReference, name: str, needs: str):
    """``reference.extra[name]``, refused in one line saying what the bed ``needs`` it for
    where the reference does not carry it."""
    value = reference.extra.get(name)
    if value is None:
        raise InputError(f"BedReference.extra[{name!r}] is missing: {needs}")
    return value
