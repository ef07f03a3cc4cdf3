"""The parameter records of the soil models: frozen, validated on construction, and callable
(``material(strain, state) -> (stress, tangent, new_state)``, the model's pure return map)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ... import checks
from ...checks import InputError
from .returns import State, initial_state

__all__ = ["Elasticity", "Elastic", "VonMises", "Tresca", "Frictional", "MohrCoulomb",
           "DruckerPrager", "check_elastic", "check_undrained", "check_frictional"]


def check_elastic(prefix: str, youngs_modulus, poisson_ratio) -> None:
    """Refuse E ≤ 0 or ν outside (−1, 0.5), naming the field ``prefix`` + name."""
    checks.positive(f"{prefix}youngs_modulus", youngs_modulus)
    nu = checks.finite(f"{prefix}poisson_ratio", poisson_ratio)
    if nu >= 0.5:
        raise InputError(f"{prefix}poisson_ratio = {nu:g}: valid range is (-1, 0.5); ν = 0.5 is "
                         "incompressible, which displacement elements cannot take (use ν ≤ 0.49 "
                         "with a mixed or reduced-integration element)")
    checks.in_range(f"{prefix}poisson_ratio", nu, -1.0, 0.5, low_open=True, high_open=True)


def check_undrained(prefix: str, model: str, undrained_strength) -> None:
    """Refuse a missing or non-positive undrained strength of ``model``."""
    if undrained_strength is None:
        raise InputError(f"{prefix}undrained_strength = None: model {model!r} needs it, "
                         "valid range is > 0")
    checks.positive(f"{prefix}undrained_strength", undrained_strength)


def check_frictional(prefix: str, cohesion, friction_angle, dilation_angle) -> None:
    """Refuse c < 0, φ outside [0, 60)°, ψ outside [0, φ], or no strength at all."""
    checks.nonnegative(f"{prefix}cohesion", cohesion)
    checks.in_range(f"{prefix}friction_angle", friction_angle, 0.0, 60.0, high_open=True)
    checks.finite(f"{prefix}dilation_angle", dilation_angle)
    if not 0.0 <= dilation_angle <= friction_angle:
        raise InputError(f"{prefix}dilation_angle = {dilation_angle:g}: valid range is "
                         f"[0, friction_angle = {friction_angle:g}]")
    if cohesion == 0.0 and friction_angle == 0.0:
        raise InputError(f"{prefix}cohesion = 0 with {prefix}friction_angle = 0: the soil has no "
                         "shear strength; valid range is cohesion > 0 or friction_angle > 0")


class Elasticity:
    """Isotropic elastic constants shared by all parameter records."""

    youngs_modulus: float
    poisson_ratio: float
    update: ClassVar = None  # the pure update function, set after the functions below

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def bulk_modulus(self) -> float:
        return self.youngs_modulus / (3.0 * (1.0 - 2.0 * self.poisson_ratio))

    @property
    def lame(self) -> float:
        return self.bulk_modulus - 2.0 * self.shear_modulus / 3.0

    def __call__(self, strain, state: State | None = None):
        """``update(strain, state, self)``: (stress, tangent, new_state)."""
        return type(self).update(strain, state, self)

    def initial_state(self, batch_shape=()) -> State:
        return initial_state(batch_shape)


@dataclass(frozen=True)
class Elastic(Elasticity):
    """Linear isotropic elasticity: E > 0, −1 < ν < 0.5."""

    youngs_modulus: float
    poisson_ratio: float

    def __post_init__(self):
        check_elastic("Elastic.", self.youngs_modulus, self.poisson_ratio)


@dataclass(frozen=True)
class VonMises(Elasticity):
    """von Mises (J2) plasticity for undrained clay: q = √(3 J2) ≤ σ_y = √3 c_u + H ε̄p.

    σ_y = √3 c_u is the plane-strain match: at the plane-strain limit s_zz = 0, so the in-plane
    shear strength is c_u (Tresca's, in plane strain). H is dσ_y/dε̄p with ε̄p = ∫√(2/3)‖dεp‖;
    in plane-strain simple shear τ = c_u + H γp/3.
    """

    youngs_modulus: float
    poisson_ratio: float
    undrained_strength: float
    hardening_modulus: float = 0.0

    def __post_init__(self):
        check_elastic("VonMises.", self.youngs_modulus, self.poisson_ratio)
        check_undrained("VonMises.", "von_mises", self.undrained_strength)
        checks.nonnegative("VonMises.hardening_modulus", self.hardening_modulus)


@dataclass(frozen=True)
class Tresca(Elasticity):
    """Tresca plasticity (perfectly plastic): σ1 − σ3 ≤ 2 c_u."""

    youngs_modulus: float
    poisson_ratio: float
    undrained_strength: float

    def __post_init__(self):
        check_elastic("Tresca.", self.youngs_modulus, self.poisson_ratio)
        check_undrained("Tresca.", "tresca", self.undrained_strength)


@dataclass(frozen=True)
class Frictional(Elasticity):
    """A frictional soil: cohesion c, friction angle φ and dilation angle ψ (degrees)."""

    youngs_modulus: float
    poisson_ratio: float
    cohesion: float
    friction_angle: float  # degrees
    dilation_angle: float = 0.0  # degrees, 0 <= ψ <= φ

    def __post_init__(self):
        prefix = f"{type(self).__name__}."
        check_elastic(prefix, self.youngs_modulus, self.poisson_ratio)
        check_frictional(prefix, self.cohesion, self.friction_angle, self.dilation_angle)

    @property
    def sin_phi(self) -> float:
        return math.sin(math.radians(self.friction_angle))

    @property
    def cos_phi(self) -> float:
        return math.cos(math.radians(self.friction_angle))

    @property
    def sin_psi(self) -> float:
        return math.sin(math.radians(self.dilation_angle))


@dataclass(frozen=True)
class MohrCoulomb(Frictional):
    """Mohr–Coulomb, perfectly plastic, non-associated (dilation angle ψ ≤ φ), angles in degrees.

    Yield (σ1 − σ3) + (σ1 + σ3) sin φ − 2 c cos φ ≤ 0, potential (σ1 − σ3) + (σ1 + σ3) sin ψ.
    """


@dataclass(frozen=True)
class DruckerPrager(Frictional):
    """Drucker–Prager, perfectly plastic, matched to Mohr–Coulomb (c, φ, ψ) in plane strain.

    Yield √J2 + η p − ξ c ≤ 0, potential √J2 + η̄ p, p = tr σ / 3 (tension positive).

    Plane-strain match: at the plane-strain limit (ε̇p_zz = 0) the DP cone gives exactly the
    Mohr–Coulomb limit (σ1 − σ3)/2 = c cos φ − (σ1 + σ3)/2 sin φ, and the plastic dilatancy ratio
    ε̇p_v / (ε̇p_1 − ε̇p_3) equals Mohr–Coulomb's sin ψ:

        η̄ = 3 tan ψ / √(9 + 12 tan²ψ),  r = √(1 − η̄²/3),
        η = sin φ / (r + η̄ sin φ / 3),  ξ = cos φ / (r + η̄ sin φ / 3).

    For ψ = φ this is the textbook associated match η = 3 tan φ / √(9 + 12 tan²φ),
    ξ = 3 / √(9 + 12 tan²φ); for ψ = 0 it is η = sin φ, ξ = cos φ. The apex is
    p = ξ c / η = c cot φ.
    """

    @property
    def eta_bar(self) -> float:
        t = math.tan(math.radians(self.dilation_angle))
        return 3.0 * t / math.sqrt(9.0 + 12.0 * t * t)

    @property
    def _denominator(self) -> float:
        eb = self.eta_bar
        return math.sqrt(1.0 - eb * eb / 3.0) + eb * self.sin_phi / 3.0

    @property
    def eta(self) -> float:
        return self.sin_phi / self._denominator

    @property
    def xi(self) -> float:
        return self.cos_phi / self._denominator

