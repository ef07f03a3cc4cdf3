"""The four beds both Winkler studies build, and what any bed of the map is calibrated from.

:class:`BedReference` holds the continuum's numbers at one point of the map; :func:`base_builder`
gives the builder of one of :func:`..winkler_vs_continuum.calibrate`'s beds (``uniform``,
``end_stiffened`` and their elasto-plastic forms), which the map's registry (:mod:`.beds`)
holds and the beds built on them (:mod:`.impedance_bed`, :mod:`.fitted_bed`) start from.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

from ..winkler_vs_continuum import Options as CalibrationOptions, calibrate
from ..winkler_vs_continuum.reference import ContinuumReference

__all__ = ["BedReference", "base_builder", "calibration"]


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


def calibration(reference: BedReference, options, name: str):
    """The bed ``name`` of :func:`..winkler_vs_continuum.calibrate` for ``reference``."""
    ref = ContinuumReference(N=reference.N, B=reference.B, h=reference.h, G=reference.G,
                             nu=reference.nu, cu=None, K_v=reference.K_v, K_r=reference.K_r,
                             theta_on=0.0, monotonic={}, cyclic={}, elastic={},
                             vertical={"capacity": reference.V_ult})
    calibration = replace(CalibrationOptions(), springs=options.springs,
                          end_length=options.end_length,
                          max_end_stiffness_ratio=options.max_end_stiffness_ratio)
    return next(c for c in calibrate(ref, calibration) if c.name == name)


def base_builder(name: str) -> Callable:
    """The builder ``build(reference, options) -> [foundation] table`` of calibration
    ``name`` of :func:`..winkler_vs_continuum.calibrate`."""
    def build(reference: BedReference, options) -> dict:
        return calibration(reference, options, name).foundation_table()

    build.__name__ = build.__qualname__ = f"build_{name}"
    build.__doc__ = (f"The ``{name}`` bed of :func:`..winkler_vs_continuum.calibrate` as a "
                     "[foundation] table.")
    return build
