"""Soil constitutive models for the plane-strain continuum model, as pure functions.

Each model is one pure function ``update(strain, state, params) -> (stress, tangent, new_state)``
in the style of FElupe, evaluated at every quadrature point at once:

- ``strain``: the **total** small strain ε_{n+1}, a tensor of shape ``(3, 3, *batch)``
  (tensorial shear, ε_xy = γ_xy/2). It is symmetrised on entry. Plane strain is the special case
  ε_zz = ε_xz = ε_yz = 0 (:func:`plane_strain` embeds a 2×2 strain). ``batch`` is any shape,
  e.g. scikit-fem's ``(nelems, nqp)``.
- ``state``: the converged :class:`State` of step n (``None`` for a virgin material). It is never
  modified. Newton iterations call the update again with the new total strain and the *same* old
  state; only the converged ``new_state`` of a step is kept.
- ``stress``: σ_{n+1}, shape ``(3, 3, *batch)``. **Tension positive.**
- ``tangent``: the consistent (algorithmic) tangent dσ_{n+1}/dε_{n+1}, a 6×6 Voigt matrix per
  point, shape ``(6, 6, *batch)``, in the order (xx, yy, zz, xy, xz, yz), mapping **engineering**
  shear strains (γ_xy = 2ε_xy) to tensorial shear stresses (σ_xy):
  ``dσ_I = D[I, J] dε̂_J`` with ε̂ = (ε_xx, ε_yy, ε_zz, γ_xy, γ_xz, γ_yz).
  :func:`plane_strain_tangent` keeps rows and columns (xx, yy, xy): the 3×3 matrix D for the 2D
  B-matrix assembly Bᵀ D B with B rows (∂u/∂x, ∂v/∂y, ∂u/∂y + ∂v/∂x). The tangent is not
  symmetric for non-associated flow (ψ < φ).

The models, with the return regions each handles (:class:`Region`):

- :func:`linear_elastic`: isotropic Hooke's law.
- :func:`von_mises` (undrained clay): q ≤ σ_y = √3 c_u + H ε̄p (plane-strain match: in plane
  strain the limit shear stress is c_u), radial return (SMOOTH).
- :func:`tresca`: σ1 − σ3 ≤ 2 c_u, multi-surface return in principal space: main plane (SMOOTH),
  triaxial-compression edge σ1 = σ2 (EDGE_COMPRESSION), triaxial-extension edge σ2 = σ3
  (EDGE_EXTENSION); spectral consistent tangent.
- :func:`mohr_coulomb`: (σ1 − σ3) + (σ1 + σ3) sin φ ≤ 2c cos φ with plastic potential
  (σ1 − σ3) + (σ1 + σ3) sin ψ (ψ ≤ φ): main plane, both edges and the apex σ = c cot φ 𝟏 (APEX).
  The return mapping follows de Souza Neto, Perić & Owen, *Computational Methods for
  Plasticity* (2008), ch. 8 (perfect plasticity: every region is closed form).
- :func:`drucker_prager`: √J2 + η p ≤ ξ c, potential √J2 + η̄ p (p = tr σ / 3): return to the cone
  (SMOOTH) and to the apex p = c cot φ (APEX). **Plane-strain match** to Mohr–Coulomb (the natural
  one for strip footings), see :class:`DruckerPrager`: for ψ = φ it is the textbook
  η = 3 tan φ / √(9 + 12 tan²φ), ξ = 3 / √(9 + 12 tan²φ).

σ1 ≥ σ2 ≥ σ3 are the principal stresses (tension positive, so σ3 is the most compressive).
Hardening (``hardening_modulus`` H) is implemented for von Mises only; the other plastic models
are perfectly plastic. ``State.equivalent_plastic_strain`` is ε̄p = ∫ √(2/3) ‖dεp‖ for every model
(von Mises' hardening variable; a diagnostic for the others).

Use :func:`material_from_soil` to turn a :class:`upliftlab.scenes.Soil` into a callable,
validated parameter record: ``material(strain, state) -> (stress, tangent, new_state)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from .. import checks
from ..checks import InputError

if TYPE_CHECKING:  # pragma: no cover
    from ..scenes import Soil

__all__ = [
    "Region",
    "State",
    "initial_state",
    "Elastic",
    "VonMises",
    "Tresca",
    "DruckerPrager",
    "MohrCoulomb",
    "linear_elastic",
    "von_mises",
    "tresca",
    "drucker_prager",
    "mohr_coulomb",
    "material_from_soil",
    "plane_strain",
    "plane_strain_tangent",
    "plane_strain_stress",
    "VOIGT",
]

VOIGT = ("xx", "yy", "zz", "xy", "xz", "yz")
"""Order of the 6×6 tangent's rows and columns (engineering shear strain columns)."""

_RTOL = 1e-12  # yield is declared when f_trial > _RTOL * (strength + stress scale)
_SQ2 = math.sqrt(2.0)
_VI = np.array([0, 1, 2, 0, 0, 1])
_VJ = np.array([0, 1, 2, 1, 2, 2])
_MANDEL_W = np.array([1.0, 1.0, 1.0, _SQ2, _SQ2, _SQ2])
_MANDEL_TO_VOIGT = np.outer(1.0 / _MANDEL_W, 1.0 / _MANDEL_W)
_ONE6 = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
_ONE_ONE6 = np.outer(_ONE6, _ONE6)
_IDEV6 = np.eye(6) - _ONE_ONE6 / 3.0
_EYE3 = np.eye(3)
_PAIRS = ((0, 1), (0, 2), (1, 2))


class Region(IntEnum):
    """Return region of the last update at each point (``State.region``)."""

    ELASTIC = 0
    SMOOTH = 1  # von Mises radial return, Tresca/Mohr–Coulomb main plane, Drucker–Prager cone
    EDGE_COMPRESSION = 2  # σ1 = σ2 > σ3 (triaxial compression edge)
    EDGE_EXTENSION = 3  # σ1 > σ2 = σ3 (triaxial extension edge)
    APEX = 4  # hydrostatic apex σ = c cot φ 𝟏


@dataclass(frozen=True, eq=False)
class State:
    """Quadrature-point history: plastic strain εp ``(3, 3, *batch)``, equivalent plastic strain
    ε̄p = ∫ √(2/3) ‖dεp‖ ``batch``, and the return ``region`` of the update that produced it
    (int8 ``batch``, a diagnostic: see :class:`Region`)."""

    plastic_strain: np.ndarray
    equivalent_plastic_strain: np.ndarray
    region: np.ndarray

    @property
    def batch_shape(self) -> tuple[int, ...]:
        return self.equivalent_plastic_strain.shape


def initial_state(batch_shape=()) -> State:
    """The virgin state: no plastic strain, elastic region."""
    if np.ndim(batch_shape) == 0:
        batch_shape = (int(batch_shape),)
    batch_shape = tuple(int(size) for size in batch_shape)
    return State(np.zeros((3, 3) + batch_shape), np.zeros(batch_shape),
                 np.zeros(batch_shape, dtype=np.int8))


# ---------------------------------------------------------------------------------------------
# Parameters: frozen, validated, callable records
# ---------------------------------------------------------------------------------------------

def _check_elastic(prefix: str, youngs_modulus, poisson_ratio) -> None:
    checks.positive(f"{prefix}youngs_modulus", youngs_modulus)
    nu = checks.finite(f"{prefix}poisson_ratio", poisson_ratio)
    if nu >= 0.5:
        raise InputError(f"{prefix}poisson_ratio = {nu:g}: valid range is (-1, 0.5); ν = 0.5 is "
                         "incompressible, which displacement elements cannot take (use ν ≤ 0.49 "
                         "with a mixed or reduced-integration element)")
    checks.in_range(f"{prefix}poisson_ratio", nu, -1.0, 0.5, low_open=True, high_open=True)


def _check_undrained(prefix: str, model: str, undrained_strength) -> None:
    if undrained_strength is None:
        raise InputError(f"{prefix}undrained_strength = None: model {model!r} needs it, "
                         "valid range is > 0")
    checks.positive(f"{prefix}undrained_strength", undrained_strength)


def _check_frictional(prefix: str, cohesion, friction_angle, dilation_angle) -> None:
    checks.nonnegative(f"{prefix}cohesion", cohesion)
    checks.in_range(f"{prefix}friction_angle", friction_angle, 0.0, 60.0, high_open=True)
    checks.finite(f"{prefix}dilation_angle", dilation_angle)
    if not 0.0 <= dilation_angle <= friction_angle:
        raise InputError(f"{prefix}dilation_angle = {dilation_angle:g}: valid range is "
                         f"[0, friction_angle = {friction_angle:g}]")
    if cohesion == 0.0 and friction_angle == 0.0:
        raise InputError(f"{prefix}cohesion = 0 with {prefix}friction_angle = 0: the soil has no "
                         "shear strength; valid range is cohesion > 0 or friction_angle > 0")


class _Elasticity:
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
class Elastic(_Elasticity):
    """Linear isotropic elasticity: E > 0, −1 < ν < 0.5."""

    youngs_modulus: float
    poisson_ratio: float

    def __post_init__(self):
        _check_elastic("Elastic.", self.youngs_modulus, self.poisson_ratio)


@dataclass(frozen=True)
class VonMises(_Elasticity):
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
        _check_elastic("VonMises.", self.youngs_modulus, self.poisson_ratio)
        _check_undrained("VonMises.", "von_mises", self.undrained_strength)
        checks.nonnegative("VonMises.hardening_modulus", self.hardening_modulus)


@dataclass(frozen=True)
class Tresca(_Elasticity):
    """Tresca plasticity (perfectly plastic): σ1 − σ3 ≤ 2 c_u."""

    youngs_modulus: float
    poisson_ratio: float
    undrained_strength: float

    def __post_init__(self):
        _check_elastic("Tresca.", self.youngs_modulus, self.poisson_ratio)
        _check_undrained("Tresca.", "tresca", self.undrained_strength)


@dataclass(frozen=True)
class _Frictional(_Elasticity):
    youngs_modulus: float
    poisson_ratio: float
    cohesion: float
    friction_angle: float  # degrees
    dilation_angle: float = 0.0  # degrees, 0 <= ψ <= φ

    def __post_init__(self):
        prefix = f"{type(self).__name__}."
        _check_elastic(prefix, self.youngs_modulus, self.poisson_ratio)
        _check_frictional(prefix, self.cohesion, self.friction_angle, self.dilation_angle)

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
class MohrCoulomb(_Frictional):
    """Mohr–Coulomb, perfectly plastic, non-associated (dilation angle ψ ≤ φ), angles in degrees.

    Yield (σ1 − σ3) + (σ1 + σ3) sin φ − 2 c cos φ ≤ 0, potential (σ1 − σ3) + (σ1 + σ3) sin ψ.
    """


@dataclass(frozen=True)
class DruckerPrager(_Frictional):
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


# ---------------------------------------------------------------------------------------------
# Layout helpers (internally: flat batch first, (N, 3, 3) tensors and (N, 6, 6) Mandel matrices)
# ---------------------------------------------------------------------------------------------

def _prepare(strain, state: State | None):
    strain = np.asarray(strain, dtype=float)
    if strain.ndim < 2 or strain.shape[:2] != (3, 3):
        raise ValueError(f"strain must have shape (3, 3, *batch), got {strain.shape}")
    batch = strain.shape[2:]
    eps = strain.reshape(3, 3, -1).transpose(2, 0, 1)
    eps = 0.5 * (eps + eps.transpose(0, 2, 1))
    if not np.isfinite(eps).all():
        bad = int(np.count_nonzero(~np.isfinite(eps).all(axis=(1, 2))))
        raise FloatingPointError(f"strain is NaN or infinite at {bad} of {len(eps)} points")
    if state is None:
        state = initial_state(batch)
    if state.batch_shape != batch or state.plastic_strain.shape != (3, 3) + batch:
        raise ValueError(f"state batch shape {state.batch_shape} does not match strain {batch}")
    eps_p = state.plastic_strain.reshape(3, 3, -1).transpose(2, 0, 1)
    ebar = state.equivalent_plastic_strain.reshape(-1)
    return eps, eps_p, ebar, batch


@dataclass(frozen=True, eq=False)
class _Piecewise:
    """N Mandel tangents that equal ``constant`` (6, 6) except at ``mask``, where they are
    ``values`` (k, 6, 6) (None if the mask is empty)."""

    constant: np.ndarray
    mask: np.ndarray
    values: np.ndarray | None


def _voigt_tangent(tangent, batch) -> np.ndarray:
    """The (6, 6, *batch) Voigt tangent of (N, 6, 6) Mandel tangents or a :class:`_Piecewise`
    (filled in one pass, without an (N, 6, 6) intermediate)."""
    if not isinstance(tangent, _Piecewise):
        voigt = (tangent * _MANDEL_TO_VOIGT).transpose(1, 2, 0).reshape((6, 6) + batch)
        return np.ascontiguousarray(voigt)
    out = np.empty((6, 6, tangent.mask.size))
    out[...] = (tangent.constant * _MANDEL_TO_VOIGT)[:, :, None]
    if tangent.values is not None:
        out[:, :, tangent.mask] = (tangent.values * _MANDEL_TO_VOIGT).transpose(1, 2, 0)
    return out.reshape((6, 6) + batch)


def _finish(batch, stress, tangent_mandel, eps_p, ebar, region):
    out_stress = stress.transpose(1, 2, 0).reshape((3, 3) + batch)
    state = State(eps_p.transpose(1, 2, 0).reshape((3, 3) + batch), ebar.reshape(batch),
                  np.asarray(region, dtype=np.int8).reshape(batch))
    return np.ascontiguousarray(out_stress), _voigt_tangent(tangent_mandel, batch), state


def _mandel(t):
    """(…, 3, 3) symmetric tensors -> (…, 6) Mandel vectors (orthonormal: shear × √2)."""
    return t[..., _VI, _VJ] * _MANDEL_W


def _trace(t):
    return np.einsum("nii->n", t)


def _elastic_mandel(params) -> np.ndarray:
    return params.bulk_modulus * _ONE_ONE6 + 2.0 * params.shear_modulus * _IDEV6


def _elastic_stress(e, params):
    return (params.lame * _trace(e))[:, None, None] * _EYE3 + 2.0 * params.shear_modulus * e


def _deviator(e):
    vol = _trace(e)
    return e - (vol / 3.0)[:, None, None] * _EYE3, vol


def _norm(t):
    return np.sqrt(np.einsum("nij,nij->n", t, t))


# ---------------------------------------------------------------------------------------------
# Plane-strain helpers for the 2D assembly
# ---------------------------------------------------------------------------------------------

def plane_strain(strain2d) -> np.ndarray:
    """Embed an in-plane strain ``(2, 2, *batch)`` as a 3×3 tensor with ε_zz = ε_xz = ε_yz = 0."""
    strain2d = np.asarray(strain2d, dtype=float)
    out = np.zeros((3, 3) + strain2d.shape[2:])
    out[:2, :2] = strain2d
    return out


def plane_strain_tangent(tangent) -> np.ndarray:
    """The plane-strain 3×3 tangent ``(3, 3, *batch)`` for (xx, yy, xy) from a 6×6 Voigt tangent:
    dσ_xx, dσ_yy, dσ_xy from dε_xx, dε_yy and the engineering shear dγ_xy = 2 dε_xy."""
    index = np.array([0, 1, 3])
    return np.ascontiguousarray(np.asarray(tangent)[index][:, index])


def plane_strain_stress(stress) -> np.ndarray:
    """(σ_xx, σ_yy, σ_xy) of a stress ``(3, 3, *batch)``, shape ``(3, *batch)``."""
    stress = np.asarray(stress)
    return np.stack([stress[0, 0], stress[1, 1], stress[0, 1]])


# ---------------------------------------------------------------------------------------------
# Models
# ---------------------------------------------------------------------------------------------

def linear_elastic(strain, state: State | None, params: Elastic):
    """Hooke's law σ = λ tr(εe) 𝟏 + 2G εe with εe = ε − εp (εp of ``state``, normally zero)."""
    eps, eps_p, ebar, batch = _prepare(strain, state)
    stress = _elastic_stress(eps - eps_p, params)
    tangent = np.broadcast_to(_elastic_mandel(params), (len(eps), 6, 6))
    return _finish(batch, stress, tangent, eps_p.copy(), ebar.copy(),
                   np.zeros(len(eps), dtype=np.int8))


def von_mises(strain, state: State | None, params: VonMises):
    """von Mises with linear isotropic hardening: radial return (exact for linear hardening) and
    its consistent tangent (de Souza Neto et al. 2008, ch. 7)."""
    eps, eps_p, ebar, batch = _prepare(strain, state)
    K, G, H = params.bulk_modulus, params.shear_modulus, params.hardening_modulus
    dev, vol = _deviator(eps - eps_p)
    s_trial = 2.0 * G * dev
    norm = _norm(s_trial)
    q_trial = math.sqrt(1.5) * norm
    yield_stress = math.sqrt(3.0) * params.undrained_strength + H * ebar
    f_trial = q_trial - yield_stress
    plastic = f_trial > _RTOL * yield_stress
    q_safe = np.where(plastic, q_trial, 1.0)
    dgamma = np.where(plastic, f_trial / (3.0 * G + H), 0.0)
    unit = s_trial / np.where(norm > 0.0, norm, 1.0)[:, None, None]
    shrink = 3.0 * G * dgamma / q_safe  # 0 where elastic
    stress = s_trial * (1.0 - shrink)[:, None, None] + (K * vol)[:, None, None] * _EYE3
    d_eps_p = (math.sqrt(1.5) * dgamma)[:, None, None] * unit
    n6 = _mandel(unit)
    b = np.where(plastic, 6.0 * G * G * (dgamma / q_safe - 1.0 / (3.0 * G + H)), 0.0)
    tangent = (K * _ONE_ONE6 + (2.0 * G * (1.0 - shrink))[:, None, None] * _IDEV6
               + b[:, None, None] * n6[:, :, None] * n6[:, None, :])
    region = np.where(plastic, Region.SMOOTH, Region.ELASTIC)
    return _finish(batch, stress, tangent, eps_p + d_eps_p, ebar + dgamma, region)


def drucker_prager(strain, state: State | None, params: DruckerPrager):
    """Drucker–Prager (perfectly plastic, non-associated): closed-form return to the cone or to
    the apex, consistent tangent (cf. de Souza Neto et al. 2008, ch. 8; derived here for this
    parametrisation and checked by finite differences in the tests)."""
    eps, eps_p, ebar, batch = _prepare(strain, state)
    K, G = params.bulk_modulus, params.shear_modulus
    eta, eta_bar, xi, c = params.eta, params.eta_bar, params.xi, params.cohesion
    e_trial = eps - eps_p
    dev, vol = _deviator(e_trial)
    s_trial = 2.0 * G * dev
    norm = _norm(s_trial)
    j_trial = norm / _SQ2  # √J2
    p_trial = K * vol
    f_trial = j_trial + eta * p_trial - xi * c
    plastic = f_trial > _RTOL * (xi * c + j_trial + abs(eta * p_trial))
    a = 1.0 / (G + K * eta * eta_bar)
    dgamma = np.where(plastic, f_trial * a, 0.0)
    apex = plastic & (j_trial - G * dgamma < 0.0) & (eta > 0.0)
    cone = plastic & ~apex
    dgamma = np.where(cone, dgamma, 0.0)
    j_safe = np.where(cone, j_trial, 1.0)
    unit = s_trial / np.where(norm > 0.0, norm, 1.0)[:, None, None]
    shrink = np.where(apex, 1.0, G * dgamma / j_safe)
    p_apex = xi * c / eta if eta > 0.0 else 0.0
    p = np.where(apex, p_apex, p_trial - K * eta_bar * dgamma)
    stress = s_trial * (1.0 - shrink)[:, None, None] + p[:, None, None] * _EYE3
    d_eps_p = dgamma[:, None, None] * (unit / _SQ2 + eta_bar / 3.0 * _EYE3)
    d_eps_p = np.where(apex[:, None, None],
                       e_trial - (p_apex / (3.0 * K)) * _EYE3, d_eps_p)
    n6 = _mandel(unit)
    c1 = np.where(cone, 2.0 * G * G * (dgamma / j_safe - a), 0.0)[:, None, None]
    c2 = np.where(cone, _SQ2 * G * a * K, 0.0)[:, None, None]
    c3 = np.where(cone, K * K * eta * eta_bar * a, 0.0)[:, None, None]
    tangent = ((2.0 * G * (1.0 - shrink))[:, None, None] * _IDEV6
               + c1 * n6[:, :, None] * n6[:, None, :]
               - c2 * (eta * n6[:, :, None] * _ONE6 + eta_bar * _ONE6[:, None] * n6[:, None, :])
               + (K - c3) * _ONE_ONE6)
    tangent = np.where(apex[:, None, None], 0.0, tangent)
    region = np.select([apex, cone], [Region.APEX, Region.SMOOTH], Region.ELASTIC)
    d_ebar = math.sqrt(2.0 / 3.0) * _norm(d_eps_p)
    return _finish(batch, stress, tangent, eps_p + d_eps_p, ebar + d_ebar, region)


def tresca(strain, state: State | None, params: Tresca):
    """Tresca (perfectly plastic): principal-space return to the main plane or an edge, spectral
    consistent tangent. Mohr–Coulomb with φ = ψ = 0 and c = c_u."""
    return _principal_return(strain, state, params, 0.0, 1.0, 0.0, params.undrained_strength)


def mohr_coulomb(strain, state: State | None, params: MohrCoulomb):
    """Mohr–Coulomb (perfectly plastic, non-associated): principal-space return to the main
    plane, either edge or the apex (de Souza Neto et al. 2008, ch. 8), spectral consistent
    tangent."""
    return _principal_return(strain, state, params, params.sin_phi, params.cos_phi,
                             params.sin_psi, params.cohesion)


def _principal_return(strain, state, params, sin_phi, cos_phi, sin_psi, cohesion):
    eps, eps_p, ebar, batch = _prepare(strain, state)
    n = len(eps)
    sig_trial = _elastic_stress(eps - eps_p, params)
    k = 2.0 * cohesion * cos_phi
    high, low = _extreme_principal(sig_trial)
    f_trial = (high - low) + (high + low) * sin_phi - k
    plastic = f_trial > _RTOL * (k + np.maximum(np.abs(high), np.abs(low)))
    stress = sig_trial
    tangent = _Piecewise(_elastic_mandel(params), plastic, None)
    eps_p_new, ebar_new = eps_p.copy(), ebar.copy()
    region = np.zeros(n, dtype=np.int8)
    if plastic.any():
        values, vectors = np.linalg.eigh(sig_trial[plastic])
        values, vectors = values[:, ::-1], vectors[:, :, ::-1]  # σ1 >= σ2 >= σ3
        sig, d3, spin, reg = _mc_principal(values, params, sin_phi, cos_phi, sin_psi, cohesion)
        d_eps_p = (values - sig) @ np.linalg.inv(_principal_elasticity(params))
        stress[plastic] = np.einsum("nia,na,nja->nij", vectors, sig, vectors)
        eps_p_new[plastic] += np.einsum("nia,na,nja->nij", vectors, d_eps_p, vectors)
        ebar_new[plastic] += math.sqrt(2.0 / 3.0) * np.linalg.norm(d_eps_p, axis=1)
        tangent = _Piecewise(tangent.constant, plastic, _spectral_tangent(vectors, d3, spin))
        region[plastic] = reg
    return _finish(batch, stress, tangent, eps_p_new, ebar_new, region)


def _extreme_principal(sig):
    """(σ1, σ3): the largest and smallest principal values of symmetric (n, 3, 3) tensors. In
    plane strain (σxz = σyz = 0 everywhere) in closed form: σzz and the in-plane pair
    (σxx + σyy)/2 ± √(((σxx − σyy)/2)² + σxy²); otherwise by LAPACK."""
    if np.any(sig[:, 0, 2]) or np.any(sig[:, 1, 2]):
        w = np.linalg.eigvalsh(sig)  # ascending
        return w[:, 2], w[:, 0]
    centre = 0.5 * (sig[:, 0, 0] + sig[:, 1, 1])
    radius = np.hypot(0.5 * (sig[:, 0, 0] - sig[:, 1, 1]), sig[:, 0, 1])
    zz = sig[:, 2, 2]
    return np.maximum(centre + radius, zz), np.minimum(centre - radius, zz)


def _principal_elasticity(params) -> np.ndarray:
    return params.lame * np.ones((3, 3)) + 2.0 * params.shear_modulus * _EYE3


def _plane(i: int, j: int, s: float) -> np.ndarray:
    """Gradient of (σ_i − σ_j) + (σ_i + σ_j) s in principal space."""
    v = np.zeros(3)
    v[i], v[j] = 1.0 + s, -(1.0 - s)
    return v


def _return_to_planes(trial, ce, grads, flows, k):
    """Closed-form return onto the active planes grads·σ = k (perfect plasticity, linear).

    Returns the principal stresses (n, 3) and the principal tangent D3 (3, 3), which maps
    principal strain increments to principal stress increments."""
    grads, flows = np.atleast_2d(grads), np.atleast_2d(flows)
    c_flow, c_grad = flows @ ce, grads @ ce  # rows: Ce·N (Ce is symmetric)
    m_inv = np.linalg.inv(grads @ ce @ flows.T)
    dgamma = (trial @ grads.T - k) @ m_inv.T
    return trial - dgamma @ c_flow, ce - c_flow.T @ m_inv @ c_grad


def _mc_principal(trial, params, sin_phi, cos_phi, sin_psi, cohesion):
    """Mohr–Coulomb return in principal space for trial principal stresses (n, 3), descending.

    Returns stresses (n, 3), principal tangents (n, 3, 3), spin coefficients (n, 3) for the
    pairs (12, 13, 23) and the region codes (n,)."""
    n = len(trial)
    G = params.shear_modulus
    ce = _principal_elasticity(params)
    k = 2.0 * cohesion * cos_phi
    main_sig, main_d = _return_to_planes(trial, ce, _plane(0, 2, sin_phi), _plane(0, 2, sin_psi), k)
    main_ok = (main_sig[:, 0] >= main_sig[:, 1]) & (main_sig[:, 1] >= main_sig[:, 2])
    # Which edge when the main plane fails: the extension edge σ2 = σ3 when this is > 0
    # (the larger of the two ordering violations, weighted by the flow vector).
    extension = ((1.0 - sin_psi) * trial[:, 0] - 2.0 * trial[:, 1]
                 + (1.0 + sin_psi) * trial[:, 2]) > 0.0
    comp_sig, comp_d = _return_to_planes(
        trial, ce, [_plane(0, 2, sin_phi), _plane(1, 2, sin_phi)],
        [_plane(0, 2, sin_psi), _plane(1, 2, sin_psi)], k)
    ext_sig, ext_d = _return_to_planes(
        trial, ce, [_plane(0, 2, sin_phi), _plane(0, 1, sin_phi)],
        [_plane(0, 2, sin_psi), _plane(0, 1, sin_psi)], k)
    comp_sig[:, :2] = comp_sig[:, :2].mean(axis=1, keepdims=True)  # exact ties on the edge
    ext_sig[:, 1:] = ext_sig[:, 1:].mean(axis=1, keepdims=True)
    edge_sig = np.where(extension[:, None], ext_sig, comp_sig)
    edge_ok = (edge_sig[:, 0] >= edge_sig[:, 2]) | (sin_phi == 0.0)
    apex = ~main_ok & ~edge_ok
    region = np.select([main_ok, apex, extension],
                       [Region.SMOOTH, Region.APEX, Region.EDGE_EXTENSION],
                       Region.EDGE_COMPRESSION)
    sig = np.where(main_ok[:, None], main_sig, edge_sig)
    d3 = np.where(main_ok[:, None, None], main_d,
                  np.where(extension[:, None, None], ext_d, comp_d))
    if apex.any():
        sig[apex] = cohesion * cos_phi / sin_phi
        d3[apex] = 0.0
    spin = np.empty((n, 3))
    scale = k + np.abs(trial).max(axis=1)
    for col, (a, b) in enumerate(_PAIRS):
        gap = trial[:, a] - trial[:, b]
        tiny = np.abs(gap) <= 1e-10 * scale
        spin[:, col] = np.where(tiny, d3[:, a, a] - d3[:, a, b],
                                2.0 * G * (sig[:, a] - sig[:, b]) / np.where(tiny, 1.0, gap))
    spin[region == Region.EDGE_COMPRESSION, 0] = 0.0  # σ1 = σ2 on the edge
    spin[region == Region.EDGE_EXTENSION, 2] = 0.0  # σ2 = σ3 on the edge
    spin[apex] = 0.0
    return sig, d3, spin, region


def _spectral_tangent(vectors, d3, spin):
    """Mandel tangent of an isotropic return map from its principal form.

    With the orthonormal eigenbasis E_a = v_a⊗v_a and N_ab = (v_a⊗v_b + v_b⊗v_a)/√2, the tangent
    is block diagonal: D3 on the E_a and (σ_a − σ_b)/(εtr_a − εtr_b) on each N_ab."""
    n = len(vectors)
    basis = np.empty((n, 6, 6))
    for a in range(3):
        v = vectors[:, :, a]
        basis[:, :, a] = _mandel(v[:, :, None] * v[:, None, :])
    for col, (a, b) in enumerate(_PAIRS, start=3):
        va, vb = vectors[:, :, a], vectors[:, :, b]
        outer = va[:, :, None] * vb[:, None, :]
        basis[:, :, col] = _mandel(outer + outer.transpose(0, 2, 1)) / _SQ2
    block = np.zeros((n, 6, 6))
    block[:, :3, :3] = d3
    block[:, [3, 4, 5], [3, 4, 5]] = spin
    return basis @ block @ basis.transpose(0, 2, 1)


Elastic.update = staticmethod(linear_elastic)
VonMises.update = staticmethod(von_mises)
Tresca.update = staticmethod(tresca)
DruckerPrager.update = staticmethod(drucker_prager)
MohrCoulomb.update = staticmethod(mohr_coulomb)


# ---------------------------------------------------------------------------------------------
# Factory
# ---------------------------------------------------------------------------------------------

def material_from_soil(soil: Soil):
    """The validated, callable parameter record for ``soil.model``.

    ``material(strain, state) -> (stress, tangent, new_state)``. Raises :class:`InputError`
    naming the ``soil.*`` field, its value and the valid range.
    """
    model = checks.one_of("soil.model", soil.model,
                          ("elastic", "tresca", "von_mises", "drucker_prager", "mohr_coulomb"))
    _check_elastic("soil.", soil.youngs_modulus, soil.poisson_ratio)
    hardening = checks.nonnegative("soil.hardening_modulus", soil.hardening_modulus)
    if hardening > 0.0 and model != "von_mises":
        raise InputError(f"soil.hardening_modulus = {hardening:g}: model {model!r} is perfectly "
                         "plastic here, valid range is [0, 0] (hardening is implemented for "
                         "von_mises only)")
    elastic = dict(youngs_modulus=float(soil.youngs_modulus),
                   poisson_ratio=float(soil.poisson_ratio))
    if model == "elastic":
        return Elastic(**elastic)
    if model in ("tresca", "von_mises"):
        _check_undrained("soil.", model, soil.undrained_strength)
        if model == "tresca":
            return Tresca(**elastic, undrained_strength=float(soil.undrained_strength))
        return VonMises(**elastic, undrained_strength=float(soil.undrained_strength),
                        hardening_modulus=hardening)
    _check_frictional("soil.", soil.cohesion, soil.friction_angle, soil.dilation_angle)
    cls = MohrCoulomb if model == "mohr_coulomb" else DruckerPrager
    return cls(**elastic, cohesion=float(soil.cohesion), friction_angle=float(soil.friction_angle),
               dilation_angle=float(soil.dilation_angle))
