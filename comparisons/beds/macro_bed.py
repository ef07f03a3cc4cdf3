"""The macro-element as a bed of the registry (issue 36 §3): the element calibrated once per
soil (:mod:`.macro`) put under a point's structure.

What the ``macro`` bed is at a point: the soil's fitted law (its plastic parameters and the
capacity's form, ``BedReference.extra["macro"]``: the fields of a
:class:`~upliftlab.reduced.laws.macro.MacroElement`, from the map's stored fit), with the
point's own elastic part, K_v and K_r of :class:`.base.BedReference` (the numbers every other
bed of the point is calibrated to), and its capacity as a multiple of the point's weight N.
It sways on the reference's tie where the reference's footing has one (the half-plane's; the
map's :func:`~upliftlab.comparisons.studies.winkler_map.bed_runs.bed_sway` sets it, as for
every bed), else on the scene's own sway spring (the advisor's scenes), else on Gazetas'
static K_h = 2G/(2 − ν) of a strip: the element carries the base's horizontal force and needs
a K_h, and this is the soil's.

The soil's Rayleigh damping β, which a bed of springs takes as β k_i beside each spring
(:mod:`.soil_damping`), the element takes as its one vertical dashpot density β K_v/B (the same
total β K_v, and β K_r in rocking): ``damping_ratio`` = β ω_v/2 with ω_v = √(K_v/m_v), the
reduced model's convention for the element (c′ = ζ 2√(K_v m_v)/B).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from ...checks import InputError
from ...reduced.laws.macro import MacroElement
from .base import required_extra

__all__ = ["PLASTIC_KEYS", "element_keys", "build_macro", "gazetas_sway_stiffness",
           "element_damping_ratio", "element_of", "macro_rocking"]

#: The law's fields that a scene's ``[foundation]`` takes by the same name.
PLASTIC_KEYS = ("initial_size", "hardening_settlement", "interior_modulus", "interior_exponent",
                "settlement_coupling", "rounding_ratio", "sliding_ratio", "flow_dilatancy",
                "coupling_exponent", "memory_modulus")


def gazetas_sway_stiffness(shear_modulus: float, poisson: float) -> float:
    """Gazetas' static horizontal stiffness of a strip on a half-plane, 2G/(2 − ν)
    (force/length per length)."""
    return 2.0 * shear_modulus / (2.0 - poisson)


def element_keys(law: MacroElement, weight: float) -> dict:
    """The ``[foundation]`` keys that make a scene's base the element ``law`` under a structure
    of vertical weight ``weight`` (force/length): the law, K_v (``stiffness``) and K_r, the
    capacity V_ult as a multiple of the weight, the N_γ term's share of it and the plastic
    parameters."""
    V_ult = law.ultimate_load
    share = law.frictional_modulus * law.width ** 2 / V_ult
    if not -1e-12 <= share <= 1.0 + 1e-12:
        raise InputError(f"macro: the N_γ term's share of V_ult = {share:.6g}; valid range is "
                         "[0, 1] (the law's capacity terms are both ≥ 0)")
    return {"law": "macro", "stiffness": float(law.vertical_stiffness),
            "rocking_stiffness": float(law.rocking_stiffness),
            "capacity_multiple": float(V_ult / weight),
            "frictional_share": float(min(max(share, 0.0), 1.0)),  # round-off only
            **{key: float(getattr(law, key)) for key in PLASTIC_KEYS}}


def _law(reference) -> MacroElement:
    fitted = required_extra(reference, "macro", "the macro bed needs the soil's fitted "
                            "element (the map's stored fit)")
    if "error" in fitted:
        raise InputError(f"macro: the soil's fit was refused: {fitted['error']}")
    return MacroElement(**{**fitted["law"], "vertical_stiffness": float(reference.K_v),
                           "rocking_stiffness": float(reference.K_r)})


def build_macro(reference, options) -> dict:
    """The ``[foundation]`` table of the ``macro`` bed at ``reference`` (module docstring)."""
    law = _law(reference)
    if not math.isclose(law.width, reference.B, rel_tol=1e-9):
        raise InputError(f"macro: the fitted element's width {law.width:g} is not the point's "
                         f"footing width {reference.B:g}")
    sway = reference.extra.get("sway_stiffness")
    if sway is None:
        sway = gazetas_sway_stiffness(reference.G, reference.nu)
    return {"support": "uplift", "half_width": 0.5 * reference.B, "layout": "winkler",
            "springs": int(options.springs), **element_keys(law, reference.N),
            "sway_stiffness": float(sway)}


def element_damping_ratio(table: Mapping, beta: float, vertical_mass: float) -> float:
    """The element's ``damping_ratio`` that gives it the soil's β K_v (module docstring):
    β ω_v/2, ω_v = √(K_v/m_v), ``vertical_mass`` m_v (mass per length)."""
    if vertical_mass is None or not vertical_mass > 0.0:
        raise InputError(f"vertical mass = {vertical_mass!r}: the element's soil damping needs "
                         "the structure's vertical mass; valid range is > 0")
    return 0.5 * beta * math.sqrt(float(table["stiffness"]) / vertical_mass)


def element_of(foundation: Mapping, N: float) -> MacroElement:
    """The element of a ``macro`` bed's ``[foundation]`` table under a weight ``N``
    (force/length), as the reduced model builds it (V_ult = ``capacity_multiple`` N)."""
    return MacroElement.of_capacity(
        2.0 * float(foundation["half_width"]), float(foundation["stiffness"]),
        float(foundation["sway_stiffness"]), float(foundation["rocking_stiffness"]),
        float(foundation["capacity_multiple"]) * N, float(foundation["frictional_share"]),
        **{key: float(foundation[key]) for key in PLASTIC_KEYS})


def macro_rocking(N: float, foundation: Mapping, cyclic_theta, monotonic_theta) -> dict:
    """The element's pushovers on the continuum's rotations, as
    :func:`.pushover.bed_rocking` gives a bed's: ``cyclic`` and ``monotonic`` records (θ, M and
    the settlement from :func:`.macro.macro_pushover` at constant N, the sway held; the
    contact's length NaN: the element keeps no contact width of its own) and the uplift onset
    moment N B/6, where its tensionless bed of uniform modulus starts to lift."""
    from .macro import macro_pushover

    law = element_of(foundation, N)
    records = {}
    for name, thetas in (("cyclic", cyclic_theta), ("monotonic", monotonic_theta)):
        thetas = np.asarray(thetas, dtype=float)
        M, settlement, _ = macro_pushover(law, N, thetas, strict=False)
        records[name] = {"theta": thetas, "M": M, "settlement": settlement,
                         "contact": np.full(thetas.shape, np.nan)}
    return {**records, "onset_moment": N * law.width / 6.0}
