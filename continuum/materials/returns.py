"""What every return map of :mod:`~upliftlab.continuum.materials` shares: the quadrature-point
history (:class:`State`), the return regions (:class:`Region`), and the tensor layouts.

Internally a return map works on a flat batch: (N, 3, 3) tensors and (N, 6, 6) Mandel matrices
(orthonormal: shear components × √2), so that a tangent's products are plain matrix products;
:func:`prepare` flattens a strain and its state, :func:`finish` restores the batch shape and
turns the Mandel tangent into the 6×6 Voigt one (engineering shear strain columns).
:func:`plane_strain`, :func:`plane_strain_tangent` and :func:`plane_strain_stress` connect the
3D return maps to the plane-strain assembly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

__all__ = ["VOIGT", "RTOL", "Region", "State", "initial_state", "prepare", "Piecewise",
           "voigt_tangent", "finish", "mandel", "trace", "elastic_mandel", "elastic_stress",
           "deviator", "frobenius_norm", "plane_strain", "plane_strain_tangent",
           "plane_strain_stress"]

VOIGT = ("xx", "yy", "zz", "xy", "xz", "yz")
"""Order of the 6×6 tangent's rows and columns (engineering shear strain columns)."""

#: Yield is declared when f_trial > RTOL × (strength + stress scale).
RTOL = 1e-12
SQ2 = math.sqrt(2.0)
VOIGT_I = np.array([0, 1, 2, 0, 0, 1])
VOIGT_J = np.array([0, 1, 2, 1, 2, 2])
MANDEL_WEIGHTS = np.array([1.0, 1.0, 1.0, SQ2, SQ2, SQ2])
MANDEL_TO_VOIGT = np.outer(1.0 / MANDEL_WEIGHTS, 1.0 / MANDEL_WEIGHTS)
ONE6 = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
ONE_ONE6 = np.outer(ONE6, ONE6)
IDEV6 = np.eye(6) - ONE_ONE6 / 3.0
EYE3 = np.eye(3)
PAIRS = ((0, 1), (0, 2), (1, 2))


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


def prepare(strain, state: State | None):
    """(ε (N, 3, 3) symmetrised, εp (N, 3, 3), ε̄p (N), batch shape) of a strain (3, 3, *batch)
    and its state (None: virgin); a non-finite strain raises FloatingPointError."""
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
class Piecewise:
    """N Mandel tangents that equal ``constant`` (6, 6) except at ``mask``, where they are
    ``values`` (k, 6, 6) (None if the mask is empty)."""

    constant: np.ndarray
    mask: np.ndarray
    values: np.ndarray | None


def voigt_tangent(tangent, batch) -> np.ndarray:
    """The (6, 6, *batch) Voigt tangent of (N, 6, 6) Mandel tangents or a :class:`Piecewise`
    (filled in one pass, without an (N, 6, 6) intermediate)."""
    if not isinstance(tangent, Piecewise):
        voigt = (tangent * MANDEL_TO_VOIGT).transpose(1, 2, 0).reshape((6, 6) + batch)
        return np.ascontiguousarray(voigt)
    out = np.empty((6, 6, tangent.mask.size))
    out[...] = (tangent.constant * MANDEL_TO_VOIGT)[:, :, None]
    if tangent.values is not None:
        out[:, :, tangent.mask] = (tangent.values * MANDEL_TO_VOIGT).transpose(1, 2, 0)
    return out.reshape((6, 6) + batch)


def finish(batch, stress, tangent_mandel, eps_p, ebar, region):
    """(stress (3, 3, *batch), Voigt tangent (6, 6, *batch), new :class:`State`) of a return
    map's flat results."""
    out_stress = stress.transpose(1, 2, 0).reshape((3, 3) + batch)
    state = State(eps_p.transpose(1, 2, 0).reshape((3, 3) + batch), ebar.reshape(batch),
                  np.asarray(region, dtype=np.int8).reshape(batch))
    return np.ascontiguousarray(out_stress), voigt_tangent(tangent_mandel, batch), state


def mandel(t):
    """(…, 3, 3) symmetric tensors -> (…, 6) Mandel vectors (orthonormal: shear × √2)."""
    return t[..., VOIGT_I, VOIGT_J] * MANDEL_WEIGHTS


def trace(t):
    """The traces of (N, 3, 3) tensors."""
    return np.einsum("nii->n", t)


def elastic_mandel(params) -> np.ndarray:
    """The isotropic elastic Mandel matrix K 𝟏⊗𝟏 + 2G I_dev (6, 6) of ``params``."""
    return params.bulk_modulus * ONE_ONE6 + 2.0 * params.shear_modulus * IDEV6


def elastic_stress(e, params):
    """Hooke's law λ tr(e) 𝟏 + 2G e for elastic strains (N, 3, 3)."""
    return (params.lame * trace(e))[:, None, None] * EYE3 + 2.0 * params.shear_modulus * e


def deviator(e):
    """(deviator, trace) of (N, 3, 3) tensors."""
    vol = trace(e)
    return e - (vol / 3.0)[:, None, None] * EYE3, vol


def frobenius_norm(t):
    """‖t‖ = √(t:t) of (N, 3, 3) tensors."""
    return np.sqrt(np.einsum("nij,nij->n", t, t))


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

