"""Mesh quality of triangle and quad meshes: corner angles, aspect ratios, degenerate elements.

Definitions (lengths in the mesh's unit, angles in degrees):

- **corner angle**: the interior angle at each element corner, signed by the element's own
  orientation, so that a reflex corner (non-convex or self-intersecting quad) is negative and a
  zero-area element has angles 0 or 180.
- **aspect ratio**: area of the ideal element (equilateral triangle, square) built on the
  longest edge, divided by the element's area: 1 for the ideal shape, a/b for an a × b
  rectangle, √3 for a right isosceles triangle, infinite for a zero-area element.
- **folded**: two elements lying on the same side of the facet they share (one is inverted
  relative to the other). Vertex order alone cannot tell, because ``skfem.MeshTri1`` sorts it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import skfem

from ..checks import InputError

__all__ = ["MeshQuality", "element_areas", "corner_angles", "aspect_ratios", "min_angle",
           "max_aspect_ratio", "quality", "check_quality"]

_IDEAL_AREA = {3: np.sqrt(3.0) / 4.0, 4: 1.0}  # ideal element of unit edge


@dataclass(frozen=True)
class MeshQuality:
    """Worst values over a mesh: ``min_angle`` (degrees) at element ``min_angle_element`` and
    ``max_aspect`` at element ``max_aspect_element``."""

    elements: int
    min_angle: float
    min_angle_element: int
    max_aspect: float
    max_aspect_element: int


def _skfem_mesh(mesh) -> skfem.Mesh:
    """The skfem mesh of a :class:`~upliftlab.meshes.SoilMesh`, or ``mesh`` itself."""
    return getattr(mesh, "mesh", mesh)


def _corners(mesh) -> np.ndarray:
    """Corner coordinates (2, ncorners, nelems) of a linear triangle or quad mesh."""
    mesh = _skfem_mesh(mesh)
    if isinstance(mesh, skfem.MeshTri1):
        return mesh.p[:, mesh.t[:3]]
    if isinstance(mesh, skfem.MeshQuad1):
        return mesh.p[:, mesh.t[:4]]
    raise InputError(f"mesh = {type(mesh).__name__}: expected a skfem triangle or quad mesh")


def _signed_areas(c: np.ndarray) -> np.ndarray:
    """Shoelace areas of the polygons in ``c`` (2, ncorners, nelems); > 0 counterclockwise."""
    x, y = c
    return 0.5 * np.sum(x * np.roll(y, -1, axis=0) - np.roll(x, -1, axis=0) * y, axis=0)


def _edge_lengths(c: np.ndarray) -> np.ndarray:
    return np.linalg.norm(np.roll(c, -1, axis=1) - c, axis=0)


def element_areas(mesh) -> np.ndarray:
    """Area of each element (length²)."""
    return np.abs(_signed_areas(_corners(mesh)))


def corner_angles(mesh) -> np.ndarray:
    """Interior corner angles (nelems, ncorners) in degrees, signed by element orientation."""
    c = _corners(mesh)
    ahead, behind = np.roll(c, -1, axis=1) - c, np.roll(c, 1, axis=1) - c
    cross = ahead[0] * behind[1] - ahead[1] * behind[0]
    dot = np.sum(ahead * behind, axis=0)
    sense = np.sign(_signed_areas(c))
    return np.degrees(np.arctan2(sense * cross, dot)).T


def aspect_ratios(mesh) -> np.ndarray:
    """Aspect ratio of each element (module docstring); inf for a zero-area element."""
    c = _corners(mesh)
    ideal = _IDEAL_AREA[c.shape[1]] * _edge_lengths(c).max(axis=0) ** 2
    with np.errstate(divide="ignore"):
        return ideal / np.abs(_signed_areas(c))


def min_angle(mesh) -> float:
    """Smallest corner angle of the mesh, degrees."""
    return float(corner_angles(mesh).min())


def max_aspect_ratio(mesh) -> float:
    """Largest element aspect ratio of the mesh."""
    return float(aspect_ratios(mesh).max())


def quality(mesh) -> MeshQuality:
    """The worst angle and aspect ratio of ``mesh`` and where they are."""
    angles, aspects = corner_angles(mesh).min(axis=1), aspect_ratios(mesh)
    i, j = int(np.argmin(angles)), int(np.argmax(aspects))
    return MeshQuality(elements=angles.size, min_angle=float(angles[i]), min_angle_element=i,
                       max_aspect=float(aspects[j]), max_aspect_element=j)


def check_quality(mesh, *, min_angle: float = 1.0, max_aspect: float = 100.0) -> MeshQuality:
    """:func:`quality`, refusing degenerate meshes with an :class:`InputError` that names the
    element: zero area, inverted or non-convex corners, folded elements, a corner angle below
    ``min_angle`` degrees or an aspect ratio above ``max_aspect``."""
    _check_areas(mesh)
    _check_convex(mesh)
    _check_folds(_skfem_mesh(mesh))
    result = quality(mesh)
    if result.min_angle < min_angle:
        raise InputError(f"mesh element {result.min_angle_element}: minimum angle = "
                         f"{result.min_angle:g} degrees: valid range is [{min_angle:g}, 180)")
    if result.max_aspect > max_aspect:
        raise InputError(f"mesh element {result.max_aspect_element}: aspect ratio = "
                         f"{result.max_aspect:g}: valid range is [1, {max_aspect:g}]")
    return result


def _check_areas(mesh) -> None:
    c = _corners(mesh)
    area, scale = np.abs(_signed_areas(c)), _edge_lengths(c).max(axis=0) ** 2
    bad = np.flatnonzero(~(area > 1e-12 * scale))
    if bad.size:
        raise InputError(f"mesh element {bad[0]}: area = {area[bad[0]]:g}: must be > 0 "
                         "(degenerate element)")


def _check_convex(mesh) -> None:
    angles = corner_angles(mesh).min(axis=1)
    bad = np.flatnonzero(~(angles > 0.0))
    if bad.size:
        raise InputError(f"mesh element {bad[0]}: corner angle = {angles[bad[0]]:g} degrees: "
                         "must be > 0 (inverted, self-intersecting or non-convex element)")


def _check_folds(mesh: skfem.Mesh) -> None:
    facets = np.flatnonzero(mesh.f2t[1] >= 0)  # facets between two elements
    a, b = (mesh.p[:, mesh.facets[k, facets]] for k in (0, 1))
    centroids = _corners(mesh).mean(axis=1)
    left, right = (centroids[:, mesh.f2t[k, facets]] - a for k in (0, 1))
    side = _cross(b - a, left) * _cross(b - a, right)
    bad = np.flatnonzero(~(side < 0.0))
    if bad.size:
        e1, e2 = mesh.f2t[:, facets[bad[0]]]
        raise InputError(f"mesh element {e1}: folded over element {e2} across facet "
                         f"{facets[bad[0]]}: both lie on the same side (inverted element)")


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[0] * v[1] - u[1] * v[0]
