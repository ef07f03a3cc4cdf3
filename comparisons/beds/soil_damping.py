"""The soil's Rayleigh damping carried into a bed: a dashpot β k_i beside every spring.

What it is: the continuum's soil damping C = α M + β K₀ (``continuum.damping_ratio``,
:mod:`~upliftlab.continuum.dynamics.rayleigh`) as the reduced model's bed sees it. A soil whose
every stiffness carries the viscous part β (a Kelvin–Voigt solid, modulus E (1 + iωβ)) has, by
the correspondence principle, every static stiffness of its footing scaled by (1 + iωβ): K_v and
K_r gain the dashpots β K_v and β K_r. A bed whose springs k_i match K_v = Σ k_i and
K_r = Σ k_i x_i² matches them with a dashpot c_i = β k_i beside each spring. The mass part α M
acts on the soil's own inertia, which a massless bed does not have, and the continuum gives the
footing and the structure no Rayleigh damping: so the bed gets no α m. The continuum's
explicit route carries β K₀ through a Maxwell arm relaxing at ω_c = 10 ω₂ (its loss within 1 %
of β's up to ω₂); the bed's Kelvin–Voigt dashpot stands for it there (on the map's half-plane
points at FS_v 3 the arm moved the continuum's peaks by at most 0.17 % against β K₀ itself).

The macro-element (``law = "macro"``, :mod:`.macro_bed`) has no springs to put dashpots beside:
it takes the same β K_v as its one dashpot density (``damping_ratio`` β ω_v/2, ω_v = √(K_v/m_v)
on the structure's vertical mass m_v), whose rocking part is then β K_r alike.

Off unless asked for (:func:`with_soil_damping` on a bed's ``[foundation]`` table, or
``bed_foundation(..., soil_beta=β)`` of :mod:`.registry`): every bed's numbers stay what they
were. The dashpots are added to a bed's own (a radiation bed's); a bed with a
``damping_ratio`` of its own (a stiffness-proportional dashpot already) is refused, since the
scene takes one or the other.
"""

from __future__ import annotations

from ...checks import InputError
from ...reduced.compatibility import layout_for
from ...scenes.structure import read_foundation
from ...units import UnitSystem, unit_system
from .macro_bed import element_damping_ratio

__all__ = ["soil_dashpots", "with_soil_damping"]


def soil_dashpots(table: dict, beta: float, units: UnitSystem | None = None) -> tuple[float, ...]:
    """β k_i (force·time/length per length) of the springs of the ``[foundation]`` ``table``,
    from −b to +b (the order of its ``dashpots``)."""
    units = units or unit_system("kN-m-s")
    layout = layout_for(read_foundation(dict(table), 1.0, units))
    return tuple(float(beta * k) for k in layout.stiffnesses)


def with_soil_damping(table: dict, beta: float | None, units: UnitSystem | None = None,
                      vertical_mass: float | None = None) -> dict:
    """The ``[foundation]`` ``table`` with the soil's β k_i added to its springs' dashpots
    (module docstring); ``table`` itself when ``beta`` is None. β ≥ 0 (s). The macro-element's
    table takes β K_v as its ``damping_ratio`` on ``vertical_mass`` (mass per length)."""
    if beta is None:
        return table
    if not beta >= 0.0:
        raise InputError(f"soil_beta = {beta!r}: the soil's Rayleigh β (s); valid range is "
                         "β ≥ 0")
    if table.get("damping_ratio", 0.0):
        raise InputError(f"foundation.damping_ratio = {table['damping_ratio']:g} with the "
                         "soil's Rayleigh dashpots: a bed takes one or the other; valid: 0")
    if table.get("law") == "macro":
        return {**table, "damping_ratio": element_damping_ratio(table, beta, vertical_mass)}
    added = soil_dashpots(table, beta, units)
    own = table.get("dashpots") or [0.0] * len(added)
    if len(own) != len(added):
        raise InputError(f"foundation.dashpots has {len(own)} entries for {len(added)} springs")
    return {**table, "dashpots": [float(c + d) for c, d in zip(own, added)]}
