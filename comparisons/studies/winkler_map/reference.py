"""The map's continuum reference (``Options.reference``): the closed box or the half-plane.

``box`` (the default, the kept store's): the base scene's box (10 B wide and deep) on a rigid
base with free-field shear sides (:data:`.points.SIDES`), the map's soils as they are
(:data:`.soils.SOILS`). A point's scene table is exactly the one the kept store was made of.

``half_plane`` (issue 35; checked in ``benchmarks/halfplane_box.py``, case
``compliant-shear``): the same box with a compliant base (Lysmer–Kuhlemeyer dashpots, the motion
entering as the incident S wave), the same shear sides, and the footing held horizontally by a
tie to the free field's surface, ``continuum.horizontal_tie`` = K_h = 2G/(2 − ν) with its
dashpot ``continuum.horizontal_tie_damping`` = C_h = ρ V_s B (:func:`handbook_sway`: the sway
spring and dashpot of the handbook strip, Gazetas 1991, that a bed would carry). The clay's
undrained strength grows with depth, :data:`CLAY_STRENGTH_GRADIENT` = 1.7 kPa/m from its 50 kPa
at the surface (a normally consolidated clay, c_u/σ'v ≈ 0.22 on its buoyant unit weight, Mesri
1975); the frictional soil is unchanged (its strength grows with its own confinement). The
soil has material damping at small strain: Rayleigh damping
``continuum.damping_ratio`` = :data:`SMALL_STRAIN_DAMPING` at the default pair f₁ = V_s/(4H),
f₂ = 5 f₁ (:mod:`upliftlab.continuum.dynamics.rayleigh`), and every bed carries the same soil's
β as a dashpot β k_i beside each spring (:func:`.bed_runs.bed_soil_damping`,
:mod:`comparisons.beds.soil_damping`). The
statics a bed is calibrated from (K_v, K_r, V_ult and the rotation pushovers) are of the
reference's soil in the box on its rigid base: the plane-strain half-plane has no static
vertical stiffness, so the box's statics stay the calibration's basis; the impedance is of the
elastic half-plane either way (:mod:`.impedance_points`).
"""

from __future__ import annotations

import copy
from collections.abc import Mapping

from .soils import SOILS

__all__ = ["REFERENCES", "CLAY_STRENGTH_GRADIENT", "FOOTING_WEIGHT_FRACTION",
           "SMALL_STRAIN_DAMPING", "reference_soil",
           "reference_continuum", "reference_weights", "handbook_sway"]

#: The continuum references (module docstring), the default first.
REFERENCES = ("box", "half_plane")
#: The clay's undrained-strength gradient on the half-plane reference (kPa/m).
CLAY_STRENGTH_GRADIENT = 1.7
#: The footing's own share of the weight N on the half-plane reference: a footing that sways on
#: its tie needs a horizontal mass of its own in the reduced model (a flexible structure's
#: swaying base; the beds sway on the same spring, :func:`.bed_runs.bed_sway`), and the
#: continuum's footing is given the same, so that both carry one structure. 1 % is the least
#: that keeps the base's sway mode (√(K_h/m_b) ≈ 60 Hz at FS_v = 3 on the map's soils) apart
#: from the story's; N on the footing, and so FS_v, is unchanged.
FOOTING_WEIGHT_FRACTION = 0.01
#: The soil's damping ratio at small strain on the half-plane reference: Darendeli's (2001)
#: D_min at the map's depths (mean effective stress about 0.5 atm, 1 Hz) is 0.7 % for a clean
#: sand (PI 0) and 1.1 % for a clay of PI 30, normally consolidated; one value, 1 %, stands for
#: both. Stated with every run (``continuum.damping_ratio`` in its scene and its metadata).
SMALL_STRAIN_DAMPING = 0.01
#: What the half-plane reference adds to each soil's ``[soil]`` table.
_HALF_PLANE_SOIL = {"clay": {"undrained_strength_gradient": CLAY_STRENGTH_GRADIENT},
                    "sand": {}}


def handbook_sway(shear_modulus: float, poisson: float, density: float,
                  width: float) -> tuple[float, float]:
    """(K_h, C_h) per unit length of a rigid strip of ``width`` B on the elastic half-plane:
    the static sway stiffness 2G/(2 − ν) (force/length per length) and the high-frequency
    dashpot ρ V_s B (force·time/length per length), V_s = √(G/ρ)
    (:func:`upliftlab.continuum.impedance.gazetas.handbook_strip`)."""
    from ....continuum.impedance.gazetas import handbook_strip

    strip = handbook_strip([0.0], shear_modulus=shear_modulus, poisson=poisson, density=density,
                           width=width)
    return float(strip.K_h), float(strip.C_h)


def reference_soil(soil: str, reference: str = "box") -> dict:
    """The ``[soil]`` table of the map's ``soil`` on ``reference`` (a fresh copy)."""
    table = copy.deepcopy(SOILS[soil])
    if reference == "half_plane":
        table.update(_HALF_PLANE_SOIL[soil])
    return table


def reference_weights(N: float, reference: str = "box") -> dict:
    """The ``[structure]`` weights of a point of weight ``N`` on the footing (force/length):
    on the box the story carries all of it (``weight`` = N, Ewing's massless base); on the
    half-plane the footing carries :data:`FOOTING_WEIGHT_FRACTION` of it (``weight`` the
    story's, ``vertical_weight`` = N)."""
    if reference == "box":
        return {"weight": float(N)}
    return {"weight": float(N) * (1.0 - FOOTING_WEIGHT_FRACTION), "vertical_weight": float(N)}


def reference_continuum(soil_table: Mapping, width: float, reference: str = "box") -> dict:
    """The ``[continuum]`` fields ``reference`` adds to a dynamic point's scene on
    ``soil_table`` under a footing of ``width`` B (m): none for the box; the compliant base and
    the tie with its dashpot for the half-plane."""
    if reference == "box":
        return {}
    E, nu = float(soil_table["youngs_modulus"]), float(soil_table["poisson_ratio"])
    K_h, C_h = handbook_sway(E / (2.0 * (1.0 + nu)), nu, float(soil_table["density"]), width)
    return {"base": "compliant", "horizontal_tie": K_h, "horizontal_tie_damping": C_h,
            "damping_ratio": SMALL_STRAIN_DAMPING}
