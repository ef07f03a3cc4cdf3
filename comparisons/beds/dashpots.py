"""The ``uniform_plastic`` bed with radiation dashpots from the continuum's own impedance.

What it is: the uniform elasto-plastic bed (K_r and V_ult of the continuum) plus one vertical
dashpot per spring, distributed (:func:`.radiation.distribute`: a uniform part plus a
concentration at the centre or the ends) so that Σ c_i = C_v and Σ c_i x_i² = C_r, the dashpots
of the continuum's FE impedance of the soil (the map's
:mod:`~upliftlab.comparisons.studies.winkler_map.impedance_points`, C_j = Im K_j(ω)/ω, linear in
ω between its frequencies) at the point's rocking frequency ω.
Why: the handbook's dashpots (``uniform_plastic_gazetas``) are those of high frequency; at the
low a0 of rocking structures the 2D strip radiates several times more vertically and several
times less in rocking than they say, and this bed takes the continuum's own numbers instead.

The frequency ω (rad/s) is the structure's flexible-base fundamental frequency on this bed:
the lowest bonded mode of the reduced model other than the vertical one
(:func:`.radiation.rocking_frequency`). For the map's one-story structure on a symmetric bed the
vertical mode is uncoupled and ω² is the lower root of

    m I ω⁴ − [k I + m (k h² + K_r)] ω² + k K_r = 0,

m = N/g the story mass, k = m (2π/T)² its stiffness, h its height, I the structure's rotary
inertia about the base (``structure.rotary_inertia``) and K_r = Σ k_i x_i² the bed's rocking
stiffness (no P-Δ on the map): the fixed-base period lengthened by the rocking spring
(Veletsos' 1/ω² = 1/ω_s² + m h²/K_r when I → 0), with the base's own rotary inertia.

No sway spring of its own and no horizontal dashpot from the impedance: the map's soils have a
frictionless interface, whose impedance's K_h and C_h are zero. In the closed box the
continuum's explicit route prescribes the footing's horizontal displacement to be the base's
(``ExplicitSettings.prescribe_u``), so the footing does not sway. On the half-plane reference
it sways on a tie to the free field (``BedReference.extra["sway_stiffness"]``, the handbook
strip's K_h), every bed sways on the same spring, and ω is then the mode's with the sway and
the footing's own mass (``structure.vertical_weight`` − ``weight``) in it: u_story, u_base and
θ, the flexible base of Veletsos and Meek with the base's inertia.

Needs in ``BedReference.extra``: ``impedance`` (the soil's
:class:`~upliftlab.continuum.impedance.analysis.Impedance`) and ``structure`` (the point's
``[structure]`` table: weight kN/m, height m, period s, damping ratio, rotary inertia t m²/m).
A rocking frequency outside the impedance's frequencies is refused (InputError), before any
dynamic run of the map (its :func:`~upliftlab.comparisons.studies.winkler_map.maps.compute_map`
builds every bed first).
"""

from __future__ import annotations

from dataclasses import dataclass

from ...checks import InputError
from ...reduced import build_model
from ...reduced.compatibility import winkler_bed
from ...scenes import scene_from_dict
from .radiation import distribute, impedance_dashpots, rocking_frequency
from .base import base_builder, base_table

__all__ = ["ImpedanceDashpots", "bed_rocking_frequency", "impedance_dashpots_of",
           "build_uniform_plastic_impedance"]

_FREE = {"type": "free", "velocity": 1.0, "duration": 1.0}  # a scene's motion, unused


@dataclass(frozen=True)
class ImpedanceDashpots:
    """The bed's dashpots at one point: the rocking frequency ``omega`` (rad/s) and its
    ``a0`` = ω (B/2)/V_s, the impedance's ``C_v`` (kN s/m/m) and ``C_r`` (kN m s/rad/m) there,
    the springs' ``dashpots`` c_i (kN s/m/m, from −b to +b) and ``where`` the concentration
    sits (``centre`` or ``ends``)."""

    omega: float
    a0: float
    C_v: float
    C_r: float
    dashpots: tuple[float, ...]
    where: str


def _base_bed(reference, options) -> dict:

    return dict(base_builder("uniform_plastic")(reference, options))


def _extra(reference, name: str):
    value = reference.extra.get(name)
    if value is None:
        raise InputError(f"BedReference.extra[{name!r}] is missing: the impedance bed needs the "
                         "soil's continuum impedance ('impedance') and the point's [structure] "
                         "table ('structure')")
    return value


def bed_rocking_frequency(reference, options) -> float:
    """The rocking frequency ω (rad/s) of the point's structure on the ``uniform_plastic`` bed
    of ``reference`` (swaying on ``extra["sway_stiffness"]`` when it is given): its
    flexible-base fundamental bonded mode (module docstring)."""
    structure = _extra(reference, "structure")
    table = _base_bed(reference, options)
    foundation = {"support": "uplift", "half_width": 0.5 * reference.B, **table}
    if reference.extra.get("sway_stiffness") is not None:
        foundation["sway_stiffness"] = float(reference.extra["sway_stiffness"])
    data = {k: v for k, v in base_table().items() if k not in ("soil", "continuum")}
    data.update(structure=dict(structure), foundation=foundation, motion=dict(_FREE))
    return rocking_frequency(build_model(scene_from_dict(data, merged=True)))


def impedance_dashpots_of(reference, options) -> ImpedanceDashpots:
    """The dashpots of the impedance bed at ``reference`` (module docstring)."""
    impedance = _extra(reference, "impedance")
    table = _base_bed(reference, options)
    omega = bed_rocking_frequency(reference, options)
    C_v, _, C_r = impedance_dashpots(impedance, omega)
    layout = winkler_bed(0.5 * reference.B, 1.0, table["springs"])
    c, _, _, where = distribute(layout.positions, layout.widths, C_v, C_r)
    a0 = omega * float(impedance.a0[0]) / float(impedance.omega[0])
    return ImpedanceDashpots(omega, a0, C_v, C_r, tuple(float(v) for v in c), where)


def build_uniform_plastic_impedance(reference, options) -> dict:
    """The ``uniform_plastic`` bed with the continuum impedance's C_v and C_r at the point's
    rocking frequency distributed over its springs (module docstring); no sway spring."""
    table = _base_bed(reference, options)
    table["dashpots"] = list(impedance_dashpots_of(reference, options).dashpots)
    return table
