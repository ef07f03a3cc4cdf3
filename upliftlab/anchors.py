"""The closed forms used as references: each once, with its source and its tolerance.

The prose and derivations are in ``upliftlab/docs/anchors.md`` (sections §1–§5, shipped with
the package and printed as the report's appendix); this module is their code. The tests and
the report's verification table (:mod:`upliftlab.comparisons.studies.verification`) both take a
reference from here, and the tolerance it is checked to from :data:`TOLERANCES`, so that a
reference and its tolerance exist in one place.

Notation as in anchors.md: B the full footing width, b = B/2, h the height of the mass, N (or
W) the vertical load, θ the rotation, G and ν the soil's shear modulus and Poisson's ratio,
c_u its undrained strength. Units follow the arguments; in plane strain forces, moments and
stiffnesses are per unit length of footing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Tolerance", "TOLERANCES", "rocking_restitution_rectangle", "HOUSNER_PERIOD_HB5",
           "edge_springs_onset_force", "equivalent_springs_onset_force", "winkler_onset_force",
           "WINKLER_ONSET_ECCENTRICITY", "winkler_uplift_rotation", "winkler_rocking",
           "winkler_moment_ratio", "winkler_contact_ratio",
           "ultimate_moment_ratio", "first_yield_rotation_ratio", "HALF_PLANE_ONSET_ECCENTRICITY",
           "half_plane_rocking_stiffness", "half_plane_onset_rotation", "half_plane_rocking",
           "flamant_compliance_slope", "prandtl_capacity", "davis_booker_factor",
           "undrained_capacity", "vm_envelope_moment_ratio",
           "drop_mass_stroke"]


@dataclass(frozen=True)
class Tolerance:
    """How closely a computed value must meet an anchor: ``value`` (relative unless ``kind``
    says ``absolute`` or ``bound``), the ``anchor`` section of anchors.md, and ``why`` this
    tolerance (the discretisation error it allows)."""

    value: float
    anchor: str
    why: str
    kind: str = "relative"


#: Tolerances of the verification table and of the tests that check the same anchors.
TOLERANCES: dict[str, Tolerance] = {
    "housner_period": Tolerance(0.01, "§1", "event stepper against the exact nonlinear period"),
    "housner_restitution": Tolerance(0.01, "§1", "worst of three impacts, ε = 0.9"),
    "winkler_pushover": Tolerance(0.005, "§3", "a bed of 200 springs against the continuous bed"),
    "ultimate_moment": Tolerance(2e-3, "§3", "400 springs pushed to 2000 θ_up"),
    "first_yield": Tolerance(0.02, "§3", "400 springs, bisection of the pushover"),
    "rocking_stiffness": Tolerance(0.01, "§4", "Q2 (2×2), 16 elements across B, 10B box"),
    "flamant": Tolerance(0.02, "§4", "boxes 5B–40B, Q2 8 across"),
    "prandtl": Tolerance(0.02, "§4", "Q2, 16 across B; the FE capacity converges from above",
                         "bound"),
    "prandtl_coarse": Tolerance(0.05, "§4", "Q2, 8 across B: O(h) overshoot", "bound"),
    "half_plane_onset": Tolerance(0.01, "§4", "Q2, 16 across B, 10B box"),
}


# ---------------------------------------------------------------------------------------------
# §1 A rigid block rocking on a rigid base (Housner 1963)
# ---------------------------------------------------------------------------------------------

#: Period (s) of free rocking of a uniform rigid block, R = 1 m, g = 9.81 m/s², h/b = 5, from
#: rest at θ₀ = α/2: the full nonlinear equation solved to 1e-11 (anchors.md §1).
HOUSNER_PERIOD_HB5 = 1.944300


def rocking_restitution_rectangle(alpha: float) -> float:
    """e = 1 − 1.5 sin²α: the velocity ratio θ̇⁺/θ̇⁻ of a uniform rectangular block (slenderness
    α = atan(b/h), rad) at an impact, from angular momentum about the new pivot (§1)."""
    return 1 - 1.5 * math.sin(alpha) ** 2


# ---------------------------------------------------------------------------------------------
# §2–3 Two springs and the tensionless Winkler bed
# ---------------------------------------------------------------------------------------------


def edge_springs_onset_force(W: float, b: float, h: float) -> float:
    """Base shear at uplift of a rigid structure of weight W, centre of mass at h, on two
    springs at ±b: W b/h (§2)."""
    return W * b / h


def equivalent_springs_onset_force(W: float, b: float, h: float) -> float:
    """The same on two springs at ±b/√3: W b/(√3 h) (§2)."""
    return W * b / (math.sqrt(3) * h)


def winkler_onset_force(W: float, b: float, h: float, springs: int | None = None) -> float:
    """The same on a uniform bed: W b/(3h), or W b/(3h)(1 + 1/N) for N equal strips (their
    outer centres at b(1 − 1/N)) (§2)."""
    if springs is None:
        return W * b / (3 * h)
    return W * b / (3 * h) * (1 + 1 / springs)


#: e/B = M/(N B) at uplift onset of a rigid footing on a uniform tensionless bed (§3).
WINKLER_ONSET_ECCENTRICITY = 1.0 / 6.0


def winkler_uplift_rotation(N: float, B: float, k: float) -> float:
    """θ_up = 2N/(k B²) (rad): uplift onset on a uniform bed of modulus k (§3)."""
    return 2.0 * N / (k * B ** 2)


def winkler_rocking(theta, N: float, B: float, k: float) -> dict:
    """A rigid footing on a tensionless uniform Winkler bed of modulus ``k`` (force/length² per
    unit length) under N (§3): ``M``, contact length ``c`` and centre ``settlement`` (down) at
    rotations ``theta`` (the closed form of a monotonic pushover, odd in θ), and ``theta_up``.
    M = (kB³/12)θ to θ_up, then M = (N B/6)(3 − 2√(θ_up/θ)) with c = B√(θ_up/θ)."""
    theta = np.asarray(theta, dtype=float)
    a = np.abs(theta)
    theta_up = 2.0 * N / (k * B ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(a > theta_up, theta_up / np.maximum(a, 1e-300), 1.0)
    c = B * np.sqrt(ratio)
    M = np.where(a <= theta_up, k * B ** 3 / 12.0 * a, N * B / 6.0 * (3.0 - 2.0 * np.sqrt(ratio)))
    settlement = np.where(a <= theta_up, N / (k * B), a * (c - 0.5 * B))
    return {"M": np.sign(theta) * M, "c": c, "settlement": settlement, "theta_up": theta_up}


def winkler_moment_ratio(theta_ratio):
    """M/M_up at θ/θ_up = ``theta_ratio`` on that bed: θ/θ_up before uplift, 3 − 2√(θ_up/θ)
    after (M_up = N B/6; the dimensionless form of :func:`winkler_rocking`, §3)."""
    return np.where(theta_ratio <= 1, theta_ratio, 3 - 2 * np.sqrt(1 / theta_ratio))


def winkler_contact_ratio(theta_ratio):
    """c/B at θ/θ_up = ``theta_ratio`` on that bed: 1 before uplift, √(θ_up/θ) after (§3)."""
    return np.where(theta_ratio <= 1, 1.0, np.sqrt(1 / theta_ratio))


def ultimate_moment_ratio(yield_multiple: float) -> float:
    """M_ult/(N B) = (1 − 1/FS_v)/2 on a bed of elasto-plastic springs with FS_v = N_ult/N
    (Meyerhof's effective width, §3)."""
    return 0.5 * (1.0 - 1.0 / yield_multiple)


def first_yield_rotation_ratio(yield_multiple: float) -> float:
    """θ_y/θ_up = FS_v²/4: the rotation at which the first spring yields, when FS_v > 2 (§3)."""
    return yield_multiple ** 2 / 4


# ---------------------------------------------------------------------------------------------
# §4 A strip footing on a plane-strain continuum
# ---------------------------------------------------------------------------------------------

#: e/B = M/(N B) at which a rigid strip on an elastic half-plane starts to lift off (§4).
HALF_PLANE_ONSET_ECCENTRICITY = 0.25


def half_plane_rocking_stiffness(G: float, B: float, nu: float) -> float:
    """K_r = πGB²/(8(1 − ν)): rocking stiffness of a rigid frictionless strip in full contact
    with an elastic half-plane (§4)."""
    return math.pi * G * B ** 2 / (8.0 * (1.0 - nu))


def half_plane_onset_rotation(N: float, B: float, G: float, nu: float) -> float:
    """θ_on = 2N(1 − ν)/(πGB) (rad): the rotation at which that strip starts to lift off
    (§4)."""
    return 2.0 * N * (1.0 - nu) / (math.pi * G * B)


def half_plane_rocking(theta, N: float, B: float, G: float, nu: float) -> dict:
    """A rigid frictionless strip on an elastic half-plane, tensionless (Johnson 1985, §5.2;
    anchors §4): ``M`` and contact length ``c`` at rotations ``theta``, and ``theta_on``.
    M = K_r θ to θ_on, then M = N B (1/2 − θ_on/(4θ)) with c = B θ_on/θ."""
    theta = np.asarray(theta, dtype=float)
    a = np.abs(theta)
    theta_on = 2.0 * N * (1.0 - nu) / (math.pi * G * B)
    K_r = math.pi * G * B ** 2 / (8.0 * (1.0 - nu))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(a > theta_on, theta_on / np.maximum(a, 1e-300), 1.0)
    M = np.where(a <= theta_on, K_r * a, N * B * (0.5 - 0.25 * ratio))
    return {"M": np.sign(theta) * M, "c": B * ratio, "theta_on": theta_on}


def flamant_compliance_slope(G: float, nu: float) -> float:
    """(1 − ν)/(πG): how much the vertical compliance 1/K_v of a strip grows per unit increase
    of ln(domain size) (Flamant; no static vertical stiffness of a strip exists in 2D, §4)."""
    return (1.0 - nu) / (math.pi * G)


def prandtl_capacity(undrained_strength: float, B: float) -> float:
    """N_ult = (2 + π) c_u B: Prandtl's bearing capacity of a strip of width B on Tresca soil
    (per unit length, §4)."""
    return (2.0 + math.pi) * undrained_strength * B


def davis_booker_factor(x: float, rough: bool = False) -> float:
    """Davis & Booker's (1973) F at x = k B/c_u0 (a strength c_u0 + k z growing linearly with
    depth; smooth or ``rough`` strip), by the curve fit of their chart in API RP 2GEO (2011)
    and ISO 19901-4 (F(0) = 1.007, the fit's own error); F grows with x, and x beyond the fit's
    range [0, 25] is taken as 25 (F then errs low)."""
    x = min(max(float(x), 0.0), 25.0)
    if rough:
        return 2.56 + 0.457 * x - math.sqrt((0.713 + 0.457 * x) ** 2 + 1.38 ** 2)
    return 1.372 + 0.07 * x - math.sqrt((0.07 * x - 0.128) ** 2 + 0.342 ** 2)


def undrained_capacity(undrained_strength: float, gradient: float, B: float,
                       rough: bool = False) -> float:
    """N_ult of a strip of width B on Tresca soil whose strength is c_u0 + k z (per unit
    length): Prandtl's (2 + π) c_u0 B when k = 0, else Davis & Booker's (1973)
    F [(2 + π) c_u0 + k B/4] B (:func:`davis_booker_factor`, smooth or ``rough``)."""
    if gradient == 0.0:
        return prandtl_capacity(undrained_strength, B)
    F = davis_booker_factor(gradient * B / undrained_strength, rough)
    return F * ((2.0 + math.pi) * undrained_strength + gradient * B / 4.0) * B


def vm_envelope_moment_ratio(v: float) -> float:
    """M/(N B) = (1 − v)/2 on the V–M capacity envelope of a strip on Tresca soil with a
    tensionless interface, v = N/N_ult (M/(B V_ult) = v(1 − v)/2, §4)."""
    return (1.0 - v) / 2.0


# ---------------------------------------------------------------------------------------------
# §5 Ewing's impact damper on a drop mass
# ---------------------------------------------------------------------------------------------


def drop_mass_stroke(cstar: float, m: float, v0: float, eps: float) -> float:
    """Δy = (v₀ m/c*)(1 − ε): the stroke over which a dashpot c* alone brings a mass m landing
    at v₀ to ε v₀ (§5)."""
    return v0 * m * (1 - eps) / cstar
