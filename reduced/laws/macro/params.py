"""The macro-element's parameters (:class:`MacroElement`): one rigid strip footing of width B on
its soil, per unit length of the strip, with every value checked before any work starts.

Forces are per unit length of the strip (kN/m, and kN·m/m for the moment), displacements of the
footing's centre in m and rad, in any consistent system (the names say kN and m only for the
reader). The generalised forces are Q = (V, H, M): V the vertical force, compression positive;
H the horizontal force; M the moment about the footing's centre. Their work-conjugate
displacements are d = (v, u, θ): v the settlement of the centre (positive into the soil), u the
horizontal displacement, θ the rotation (the edge at x = +B/2 sinks when θ > 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ....checks import InputError, in_range, nonnegative, positive
from ....scenes.laws.macro import MAX_MEMORY_MODULUS

__all__ = ["MacroElement", "MacroStepError", "bearing_factors"]


class MacroStepError(RuntimeError):
    """A step of the macro-element could not be completed: the contact's iterations did not
    converge, the bounding surface was not found along the load, the step needed too many
    sub-steps, or the load had no stiffness along its plastic flow; or a load could not be
    held. Its numbers would not be trusted, so none are given."""


def bearing_factors(friction_angle: float) -> tuple[float, float, float]:
    """(N_c, N_q, N_γ) of a strip for a friction angle φ (degrees): Prandtl's N_c and N_q
    (Reissner), N_c = 2 + π at φ = 0, and Vesić's (1973) N_γ = 2 (N_q + 1) tan φ."""
    if friction_angle == 0.0:
        return 2.0 + math.pi, 1.0, 0.0
    t = math.tan(math.radians(friction_angle))
    n_q = math.exp(math.pi * t) * math.tan(math.radians(45.0 + 0.5 * friction_angle)) ** 2
    return (n_q - 1.0) / t, n_q, 2.0 * (n_q + 1.0) * t


@dataclass(frozen=True)
class MacroElement:
    """A rigid strip footing on its soil, as the macro-element sees it.

    Elastic part: ``vertical_stiffness`` K_v (kN/m/m), ``horizontal_stiffness`` K_h (kN/m/m)
    and ``rocking_stiffness`` K_r (kN·m/rad/m) of the footing in full contact.

    Uplift: the footing's contact is a tensionless Winkler bed of modulus
    :attr:`winkler_modulus` (kN/m³) whose full-contact stiffness is no softer
    than K_v and K_r, in series with the elastic remainder (:mod:`.uplift`).

    Capacity (:mod:`.capacity`): the strip's effective-width capacity under V and M, from
    ``cohesion`` c (kPa), ``friction_angle`` φ (degrees) and ``unit_weight`` γ (kN/m³) of the
    soil, V = B′ c N_c + B′² ½ γ N_γ, each term scaled by its factor (``cohesive_factor``,
    ``frictional_factor``: 1 is the textbook value, a calibration sets them to the continuum's
    own capacity), and a horizontal capacity t_h V (1 − V/V_ult) (``sliding_ratio`` t_h). A
    Tresca clay is c = c_u and φ = 0.

    Plasticity (:mod:`.plastic`): a bounding surface, the capacity scaled by a size ζ that
    starts at ``initial_size`` ζ0 and grows towards 1 with the accumulated plastic settlement
    κ as ζ = 1 − (1 − ζ0) exp(−κ / ``hardening_settlement``) (m); inside it the plastic modulus
    ``interior_modulus`` h0 · ((1 − s)/s)^``interior_exponent`` (in units of K_v/V_ult², s the
    distance to the bounding surface along the line from the last reversal); and the flow
    direction the surface's normal, its upward settlement part (where the normal points to
    less V, below the surface's widest V) scaled by ``flow_dilatancy`` δ (1: associated, the
    footing heaves there as the surface's normal says; 0: it does not heave, as an undrained
    soil that keeps its volume), with ``settlement_coupling`` χ times s^``coupling_exponent``
    ε times its moment-and-shear part added to the settlement: χ = 0 and δ = 1 is associated
    flow, χ > 0 settles the footing while it yields in rotation, and ε > 0 makes that
    coupling act near the bounding surface (s → 1) and fade in the small cycles inside it
    (s → 0). ``memory_modulus`` μ: the interior modulus is up to 1 + μ times stiffer while
    the load's mobilisation is below the largest its side (the sign of M) has reached (0: no
    memory, the law of revision 2). ``rounding_ratio`` λ_ρ: the fraction of the edges'
    plastic travel b |dθ_p| that rounds the soil's surface (:mod:`.uplift`), while the edges
    press harder than the middle; 0: the surface stays flat.
    """

    width: float
    vertical_stiffness: float
    horizontal_stiffness: float
    rocking_stiffness: float
    cohesion: float
    friction_angle: float = 0.0
    unit_weight: float = 0.0
    cohesive_factor: float = 1.0
    frictional_factor: float = 1.0
    sliding_ratio: float = 4.0 / (2.0 + math.pi)
    initial_size: float = 0.5
    hardening_settlement: float = 0.01
    interior_modulus: float = 1.0
    interior_exponent: float = 1.0
    settlement_coupling: float = 0.0
    rounding_ratio: float = 0.0
    flow_dilatancy: float = 1.0
    coupling_exponent: float = 0.0
    memory_modulus: float = 0.0

    def __post_init__(self):
        positive("macro.width", self.width)
        positive("macro.vertical_stiffness", self.vertical_stiffness)
        positive("macro.horizontal_stiffness", self.horizontal_stiffness)
        positive("macro.rocking_stiffness", self.rocking_stiffness)
        nonnegative("macro.cohesion", self.cohesion)
        in_range("macro.friction_angle", self.friction_angle, 0.0, 50.0)
        nonnegative("macro.unit_weight", self.unit_weight)
        nonnegative("macro.cohesive_factor", self.cohesive_factor)
        nonnegative("macro.frictional_factor", self.frictional_factor)
        in_range("macro.sliding_ratio", self.sliding_ratio, 0.0, 4.0, low_open=True)
        in_range("macro.initial_size", self.initial_size, 0.0, 1.0, low_open=True)
        positive("macro.hardening_settlement", self.hardening_settlement)
        positive("macro.interior_modulus", self.interior_modulus)
        positive("macro.interior_exponent", self.interior_exponent)
        in_range("macro.settlement_coupling", self.settlement_coupling, 0.0, 10.0)
        in_range("macro.rounding_ratio", self.rounding_ratio, 0.0, 1.0)
        in_range("macro.flow_dilatancy", self.flow_dilatancy, 0.0, 1.0)
        in_range("macro.coupling_exponent", self.coupling_exponent, 0.0, 8.0)
        in_range("macro.memory_modulus", self.memory_modulus, 0.0, MAX_MEMORY_MODULUS)
        if not self.ultimate_load > 0.0:
            raise InputError(f"macro: cohesion = {self.cohesion:g}, friction_angle = "
                             f"{self.friction_angle:g}, unit_weight = {self.unit_weight:g}: the "
                             "strip has no bearing capacity (needs c > 0, or φ > 0 and γ > 0)")

    @classmethod
    def of_capacity(cls, width: float, vertical_stiffness: float, horizontal_stiffness: float,
                    rocking_stiffness: float, ultimate_load: float, frictional_share: float,
                    **plastic) -> MacroElement:
        """The element whose central capacity is ``ultimate_load`` V_ult (force), a share
        ``frictional_share`` s of it from the N_γ term and the rest from the cohesive term:
        V(B′) = (1 − s) V_ult B′/B + s V_ult (B′/B)². The soil enters the capacity only
        through these two pressures, so c, φ and γ are placeholders (c = 1, φ = 30°, γ = 1)
        whose terms the factors scale to them; ``plastic`` the other fields."""
        in_range("frictional_share", frictional_share, 0.0, 1.0)
        positive("ultimate_load", ultimate_load)
        n_c, _, n_gamma = bearing_factors(30.0)
        return cls(width, vertical_stiffness, horizontal_stiffness, rocking_stiffness,
                   cohesion=1.0 if frictional_share < 1.0 else 0.0, friction_angle=30.0,
                   unit_weight=1.0,
                   cohesive_factor=(1.0 - frictional_share) * ultimate_load / (width * n_c),
                   frictional_factor=frictional_share * ultimate_load
                   / (width * width * 0.5 * n_gamma), **plastic)

    @property
    def cohesive_pressure(self) -> float:
        """c N_c times its factor (kPa): the cohesive term's bearing pressure."""
        return self.cohesive_factor * self.cohesion * bearing_factors(self.friction_angle)[0]

    @property
    def frictional_modulus(self) -> float:
        """½ γ N_γ times its factor (kN/m³): the frictional term's pressure per metre of B′."""
        n_gamma = bearing_factors(self.friction_angle)[2]
        return self.frictional_factor * 0.5 * self.unit_weight * n_gamma

    @property
    def ultimate_load(self) -> float:
        """V_ult (kN/m): the strip's capacity under a central vertical load."""
        b = self.width
        return b * self.cohesive_pressure + b * b * self.frictional_modulus

    @property
    def remainder_compliance(self) -> tuple[float, float]:
        """C_x = (1/K_v − 1/(k B), 1/K_r − 12/(k B³)) (m/kN, rad/(kN·m)): the elastic
        remainder in series with the bed, each ≥ 0 (:mod:`.uplift`)."""
        k, b = self.winkler_modulus, self.width
        # max(0, ·) only removes round-off: k is chosen so that both are ≥ 0
        return (max(0.0, 1.0 / self.vertical_stiffness - 1.0 / (k * b)),
                max(0.0, 1.0 / self.rocking_stiffness - 12.0 / (k * b ** 3)))

    @property
    def winkler_modulus(self) -> float:
        """k (kN/m³: force per unit length of strip, per metre of width, per metre of
        compression): the tensionless bed's modulus, the
        softest whose full-contact stiffnesses k B and k B³/12 are at least K_v and K_r, so
        that the elastic remainder in series is a compliance ≥ 0 (zero in rotation or in
        settlement, whichever the bed matches)."""
        b = self.width
        return max(self.vertical_stiffness / b, 12.0 * self.rocking_stiffness / b ** 3)
