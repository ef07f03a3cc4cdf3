"""Compatibility assembly (Ewing eqs. 1–5, 9): spring layouts, the matrix A, K = A S Aᵀ.

Degrees of freedom (free, relative to the ground): the lateral displacements ``x_j`` of the
story masses (X − X_g), the base rotation θ (positive when it moves the top by +hθ) and the
vertical displacement V of the base centre O (positive up). Column ``i`` of A maps these to the
deformation of spring ``i``: ``e = Aᵀ q`` (eq. 3). Story springs deform by the story drift
relative to the rotated base, ``u_j − u_{j−1}`` with ``u_j = x_j − h_j θ`` (eq. 7). Foundation
springs deform by the *compression* of the base point above them, ``e_i = x_i θ − V``. The same
A turns spring forces into nodal forces, ``A s(e)``, for any spring law.

A base on a sway spring has one DOF more, its horizontal displacement relative to the ground:
the sway spring deforms by the base's displacement u_b and the first story's drift is taken
from it, ``u_1 = x_1 − h_1 θ − u_b``. For a flexible structure that DOF is u_b itself (the
story DOFs stay relative to the ground, so the mass matrix stays diagonal); for a rigid one it
is the horizontal displacement u_G of the centre of mass G, at height h_G above O, and
``u_b = u_G − h_G θ`` (the mass matrix is diagonal about G).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import InputError

__all__ = [
    "SpringLayout",
    "edge_springs",
    "equivalent_springs",
    "winkler_bed",
    "end_stiffened_bed",
    "custom_springs",
    "layout_for",
    "compatibility_matrix",
    "stiffness_matrix",
    "base_transform",
    "DofMap",
]


@dataclass(frozen=True)
class SpringLayout:
    """Foundation springs under a base of half-width b.

    ``positions`` x_i (length, from the centre O, positive towards +θ lean), ``stiffnesses`` k_i
    (force/length) and ``widths`` (length): the tributary strip of each spring, used to measure
    the contact length. Their sum is 2b.
    """

    half_width: float
    positions: np.ndarray
    stiffnesses: np.ndarray
    widths: np.ndarray

    def __post_init__(self):
        for name in ("positions", "stiffnesses", "widths"):
            array = np.array(getattr(self, name), dtype=float)
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    @property
    def count(self) -> int:
        return self.positions.size

    @property
    def vertical_stiffness(self) -> float:
        """K_v = Σ k_i (force/length)."""
        return float(self.stiffnesses.sum())

    @property
    def rocking_stiffness(self) -> float:
        """K_θ = Σ k_i x_i² about O (force·length/rad), bonded."""
        return float(np.sum(self.stiffnesses * self.positions**2))


def edge_springs(half_width: float, total_stiffness: float) -> SpringLayout:
    """Two springs of K_v/2 at ±b (Fig. 1a)."""
    b = half_width
    return SpringLayout(b, [-b, b], [total_stiffness / 2] * 2, [b, b])


def equivalent_springs(half_width: float, total_stiffness: float) -> SpringLayout:
    """Two springs of K_v/2 at ±b/√3: the bonded K_v and K_θ of a uniform bed (its rocking
    stiffness K_v b²/3 is 2 (K_v/2)(b/√3)²)."""
    b = half_width
    x = b / math.sqrt(3.0)
    return SpringLayout(b, [-x, x], [total_stiffness / 2] * 2, [b, b])


def winkler_bed(half_width: float, total_stiffness: float, count: int) -> SpringLayout:
    """A uniform bed: N springs of K_v/N at the centres of N equal strips (Fig. 1b, eq. 9)."""
    b = half_width
    width = 2.0 * b / count
    x = -b + width * (np.arange(count) + 0.5)
    return SpringLayout(b, x, np.full(count, total_stiffness / count), np.full(count, width))


def end_stiffened_bed(half_width: float, total_stiffness: float, count: int,
                      stiffness_ratio: float, end_length: float) -> SpringLayout:
    """A bed stiffer near its ends, as OpenSees BNWF practice: k_end = R_k · k_mid.

    ``end_length`` R_e is the end-zone length as a fraction of the half-width b (NIST GCR
    12-917-21; OpenSees ``ShallowFoundationGen`` uses a fraction of the full length, a factor 2
    apart). A spring whose strip centre lies within R_e·b of an edge is an end spring. The total
    stiffness K_v is kept.
    """
    bed = winkler_bed(half_width, total_stiffness, count)
    in_end = np.abs(bed.positions) >= half_width * (1.0 - end_length)
    weight = np.where(in_end, stiffness_ratio, 1.0) * bed.widths
    k = total_stiffness * weight / weight.sum()
    return SpringLayout(half_width, bed.positions, k, bed.widths)


def custom_springs(half_width: float, positions, stiffnesses) -> SpringLayout:
    """A user list of positions (length) and stiffnesses (force/length).

    Tributary widths run to the midpoints between neighbours and to the edges ±b.
    """
    x = np.asarray(positions, dtype=float)
    order = np.argsort(x)
    x, k = x[order], np.asarray(stiffnesses, dtype=float)[order]
    if np.any(np.diff(x) <= 0):
        raise InputError("foundation.positions: two springs at the same position")
    bounds = np.concatenate([[-half_width], 0.5 * (x[1:] + x[:-1]), [half_width]])
    return SpringLayout(half_width, x, k, np.diff(bounds))


def layout_for(foundation) -> SpringLayout:
    """The :class:`SpringLayout` a scene's :class:`~upliftlab.scenes.Foundation` describes."""
    f = foundation
    if f.layout == "edges":
        return edge_springs(f.half_width, f.stiffness)
    if f.layout == "equivalent":
        return equivalent_springs(f.half_width, f.stiffness)
    if f.layout == "winkler":
        return winkler_bed(f.half_width, f.stiffness, f.springs)
    if f.layout == "end_stiffened":
        return end_stiffened_bed(f.half_width, f.stiffness, f.springs, f.end_stiffness_ratio,
                                 f.end_length)
    return custom_springs(f.half_width, f.positions, f.stiffnesses)


@dataclass(frozen=True)
class DofMap:
    """Where each free DOF sits in q: story ``x`` indices (empty if rigid), ``theta``, ``v``
    (−1 when locked by a fixed base), ``sway`` (−1 without a sway spring: the base's u_b, or
    the centre of mass's u_G for a rigid structure). Names are for output."""

    stories: tuple[int, ...]
    theta: int
    v: int
    names: tuple[str, ...]
    sway: int = -1

    @property
    def size(self) -> int:
        return len(self.names)

    @classmethod
    def build(cls, story_count: int, *, rigid: bool, fixed: bool,
              exact: bool = False, sway: bool = False) -> DofMap:
        """Exact kinematics names its DOFs for what they hold: story deflections ``w`` in the
        rotated frame and ``sin_theta``. A sway DOF comes last: ``u_b``, or ``u_G`` for a rigid
        structure."""
        stories = () if rigid else tuple(range(story_count))
        names = [f"{'w' if exact else 'x'}{j + 1}" for j in stories]
        theta = v = sway_dof = -1
        if not fixed:
            theta, v = len(names), len(names) + 1
            names += ["sin_theta" if exact else "theta", "V"]
        if sway:
            sway_dof = len(names)
            names.append("u_G" if rigid else "u_b")
        return cls(stories, theta, v, tuple(names), sway_dof)


def compatibility_matrix(dofs: DofMap, heights, layout: SpringLayout | None, *,
                         exact: bool = False, sway_height: float = 0.0,
                         sway_spring: bool = True) -> np.ndarray:
    """A (n_dof × n_spring): story springs first, then the sway spring (if any), then the
    foundation springs (eqs. 3, 9).

    Story spring j: e = u_j − u_{j−1}, u_j = x_j − h_j θ (− u_b with a sway spring). Sway
    spring: e = u_b (a rigid structure: u_G − h_G θ, ``sway_height`` h_G). Foundation spring i:
    e = x_i θ − V. With ``exact`` kinematics the story DOFs are the deflections w_j in the
    base's rotated frame and the rotation DOF is sin θ: story spring j is e = w_j − w_{j−1}
    and foundation spring i e = x_i sin θ − V, still linear. Without ``sway_spring`` the sway
    DOF has no spring (a base element carries the base's horizontal force instead).
    """
    heights = np.asarray(heights, dtype=float)
    n_story = len(dofs.stories)
    n_sway = 1 if dofs.sway >= 0 and sway_spring else 0
    n_found = 0 if layout is None else layout.count
    A = np.zeros((dofs.size, n_story + n_sway + n_found))
    for j, dof in enumerate(dofs.stories):
        A[dof, j] = 1.0
        if j > 0:
            A[dofs.stories[j - 1], j] = -1.0
        if dofs.theta >= 0 and not exact:
            A[dofs.theta, j] = -(heights[j] - (heights[j - 1] if j > 0 else 0.0))
    if dofs.sway >= 0 and n_story:  # the first story's drift is taken from the base's sway
        A[dofs.sway, 0] = -1.0
    if n_sway:
        A[dofs.sway, n_story] = 1.0
        if not n_story and dofs.theta >= 0:
            A[dofs.theta, n_story] = -sway_height
    if layout is not None:
        first = n_story + n_sway
        A[dofs.theta, first:] = layout.positions
        A[dofs.v, first:] = -1.0
    return A


def base_transform(dofs: DofMap, sway_height: float = 0.0) -> np.ndarray:
    """T (3 × n): a base element's displacement from rest (v, u, θ) = T q, with v the settlement
    of O (down, −V), u its sway (u_b; a rigid structure's u_G − h_G θ, ``sway_height`` h_G)
    and θ the rotation."""
    T = np.zeros((3, dofs.size))
    T[0, dofs.v] = -1.0
    T[1, dofs.sway] = 1.0
    if not dofs.stories:
        T[1, dofs.theta] = -sway_height
    T[2, dofs.theta] = 1.0
    return T


def stiffness_matrix(A: np.ndarray, stiffnesses) -> np.ndarray:
    """K = A S Aᵀ with S = diag(k) (eq. 5)."""
    return (A * np.asarray(stiffnesses, dtype=float)) @ A.T
