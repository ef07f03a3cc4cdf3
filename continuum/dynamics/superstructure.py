"""The SDOF superstructure on the rigid footing, and how both dynamic routes couple it to the soil.

**Unknowns.** z = (u, v, θ, s): the footing q = (u, v, θ) at the centre of its base and the
deformation s of the superstructure's story spring (the reduced model's u = X − Xg − hθ: the
story's lateral position less the ground's and the footing's rigid rotation). The story mass
m = W/g sits at height h on a shear spring k with a dashpot c = 2 ζ_s √(k m) (ζ_s of the
fixed-base mode, as in :mod:`upliftlab.reduced`); its lateral position is u + h θ + s. The
footing carries the vertical mass ``vertical_weight``/g, the rotary inertia I₀
(``structure.rotary_inertia``, about O, story mass excluded) and, horizontally, the base's own
mass ``vertical_weight``/g − m (zero when the structure's weight is all in the story). P-Δ is off.

**Coupling.** Each route writes the footing's and the story's equations of one step as an
affine relation A z_{n+1} + b + [Lᵀ f_c; 0] = 0 (f_c the contact forces on the soil, L the
footing's kinematics): :func:`hht_form` for the implicit route (HHT-α,
:mod:`~upliftlab.continuum.dynamics.implicit`), :func:`central_difference_form` for the explicit one
(:mod:`~upliftlab.continuum.dynamics.explicit`; its compiled loop repeats the same form). The
story's
equation is linear, so s is eliminated exactly (:func:`eliminate_story`, :func:`story_deformation`)
and the contact solver sees the footing's three DOFs only. :func:`structure_work` is the
superstructure's share of the energy account of either route.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checks import InputError

__all__ = ["StructureMatrices", "structure_matrices", "check_superstructure",
           "MIN_ROTARY_INERTIA", "check_footing_mass", "hht_form", "central_difference_form",
           "eliminate_story", "story_deformation", "structure_work"]


@dataclass(frozen=True)
class StructureMatrices:
    """Mass, damping, stiffness (4, 4) of z = (u, v, θ, s), the ground influence vector
    ``r`` (4) and the gravity load ``gravity`` (4) (force; −W on v)."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    r: np.ndarray
    gravity: np.ndarray
    story_mass: float
    height: float


def structure_matrices(scene) -> StructureMatrices:
    """The superstructure and footing of ``scene`` on z = (u, v, θ, s) (module docstring)."""
    s = scene.structure
    story = s.stories[0]
    m, k, h = story.weight / scene.g, story.stiffness, story.height
    c = 2.0 * s.damping_ratio * math.sqrt(k * m)
    mv = s.vertical_weight / scene.g
    a = np.array([1.0, 0.0, h, 1.0])
    M = np.diag([max(mv - m, 0.0), mv, s.rotary_inertia, 0.0]) + m * np.outer(a, a)
    return StructureMatrices(M=M, C=np.diag([0.0, 0.0, 0.0, c]), K=np.diag([0.0, 0.0, 0.0, k]),
                             r=np.array([1.0, 0.0, 0.0, 0.0]),
                             gravity=np.array([0.0, -s.vertical_weight, 0.0, 0.0]),
                             story_mass=m, height=h)


def check_superstructure(scene, motion) -> None:
    """Refuse a structure or a motion the continuum dynamics does not carry: more than one
    story, a rigid structure, P-Δ, an initial displacement or rotation."""
    s = scene.structure
    if len(s.stories) != 1:
        raise InputError(f"structure.story: {len(s.stories)} stories; the continuum dynamics "
                         "carries one story (an SDOF superstructure); valid: 1")
    if s.rigid:
        raise InputError("structure.rigid = true: the continuum dynamics needs the story spring; "
                         "valid: false")
    if s.p_delta:
        raise InputError("structure.p_delta = true: P-Δ is not in the continuum dynamics; "
                         "valid: false")
    for name in ("initial_displacement", "initial_rotation"):
        if getattr(motion, name):
            raise InputError(f"motion.{name} = {getattr(motion, name):g}: the continuum dynamics "
                             "starts from the static state; valid: 0 (initial_velocity is "
                             "supported)")


#: Smallest rotary inertia I₀ of the footing, relative to the story's m h², that the explicit
#: route integrates: its footing and story are advanced with their mass matrix, whose θ row is
#: h times the story's when I₀ = 0 (singular; the implicit route adds the soil's stiffness and
#: runs it).
MIN_ROTARY_INERTIA = 1e-9


def check_footing_mass(scene) -> None:
    """Refuse a footing whose rotary inertia the explicit route cannot advance."""
    s = scene.structure
    story = s.stories[0]
    low = MIN_ROTARY_INERTIA * story.weight / scene.g * story.height ** 2
    if not s.rotary_inertia >= low:
        raise InputError(f"structure.rotary_inertia = {s.rotary_inertia:g}: the explicit route "
                         "needs the footing's mass matrix positive definite; valid range is "
                         f"[{low:.3g}, ...) ({MIN_ROTARY_INERTIA:g} m h²), or set "
                         "continuum.dynamics = 'implicit'")


def hht_form(z: StructureMatrices, c, d, v, a, reaction, F1, F0):
    """(A, b) of one HHT-α step with the coefficients ``c``
    (:class:`~upliftlab.time_schemes.NewmarkCoefficients`) from z_n = ``d``, ż_n = ``v``,
    z̈_n = ``a``: inertia at n+1, stiffness, damping, contact (the footing's ``reaction`` at n)
    and the loads ``F1`` (n+1), ``F0`` (n) weighted (1 + α) and −α."""
    alpha = c.alpha
    A = c.a0 / (1.0 + alpha) * z.M + c.c0 * z.C + z.K
    mh = -c.a0 * d - c.a1 * v - c.a2 * a
    ch = -c.c0 * d + c.c1 * v + c.c2 * a
    b = z.M @ mh / (1.0 + alpha) + z.C @ ch - F1
    if alpha != 0.0:
        Xn = z.C @ v + z.K @ d + np.append(reaction, 0.0) - F0
        b = b - alpha / (1.0 + alpha) * Xn
    return A, b


def central_difference_form(z: StructureMatrices, dt: float, zn, vz, Fz, first: bool,
                            implicit=None):
    """(A, b) of one central-difference step from z_n = ``zn`` with the half-step velocity
    ż_{n−½} = ``vz`` (the first step: ż_0) under the load ``Fz`` at n. ``implicit`` (4, 4;
    None: none): the part of ``z.K`` taken at n+1 instead of n (a horizontal tie, which holds a
    footing that has no horizontal mass of its own: :mod:`~upliftlab.continuum.dynamics.
    explicit`)."""
    if first:
        h = 0.5 * dt * dt
        A = z.M / h
    else:
        h = dt * dt
        A = (z.M + 0.5 * dt * z.C) / h
    if implicit is not None:
        A = A + implicit
    if first:
        b = -A @ zn - z.M @ vz / (0.5 * dt) - Fz + z.K @ zn + z.C @ vz
    else:
        b = -A @ zn - (z.M - 0.5 * dt * z.C) @ vz / dt - Fz + z.K @ zn
    return A, b


def eliminate_story(A, b):
    """The footing's (3, 3) matrix and (3) vector after eliminating s from (A, b)."""
    return (A[:3, :3] - np.outer(A[:3, 3], A[3, :3]) / A[3, 3],
            b[:3] - A[:3, 3] * b[3] / A[3, 3])


def story_deformation(A, b, q) -> float:
    """The story deformation s at n+1 that the story's equation gives for the footing's q."""
    return -(A[3, :3] @ q + b[3]) / A[3, 3]


def structure_work(z: StructureMatrices, z0, z1, F0, F1, velocity, weight: float):
    """(strain, damping, input) work of the footing and story from z0 to z1 by the trapezoidal
    rule: story spring less the footing's weight; story dashpot at ``weight`` × ``velocity``
    (the mean velocity as ½ (ż0 + ż1), or the mid-step one with weight 1); ground loads
    ``F0``, ``F1`` (less the weight)."""
    dz = z1 - z0
    strain = 0.5 * float((z.K @ (z0 + z1)) @ dz) - float(z.gravity @ dz)
    damping = weight * float((z.C @ velocity) @ dz)
    inputs = 0.5 * float((F0 + F1 - 2.0 * z.gravity) @ dz)
    return strain, damping, inputs
