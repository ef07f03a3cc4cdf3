"""Graded plane-strain soil domains under a strip footing, with named boundaries.

Units: every length is in the scene's length unit (the same unit as ``footing_width``).
``domain_width`` and ``domain_depth`` are multiples of the footing width B; ``layer_depth`` is an
absolute length.

Geometry: the soil occupies ``-W/2 <= x <= W/2``, ``-D <= y <= 0``; the footing base is the
surface segment ``|x| <= B/2``. The contact pressure is singular at the footing edges
``x = ±B/2``, so the grid lines are graded towards them:

- **across the footing** the ``elements_across`` elements grow geometrically from each edge to the
  centre, the centre element being ``grading`` times the edge element (``grading = 1``: uniform);
- **beyond the edges** (along the surface and with depth, starting at the edge element size) a
  length L gets ``ceil((n/2) log2(1 + 2L/B))`` elements that grow geometrically: n/2 elements for
  each doubling of the distance from the footing edge plus B/2, capped at L/h_edge elements.

Every length in the grid scales as 1/n, so a convergence study refines by ``elements_across``
alone. The mesh is a tensor-product grid of quads, split symmetrically about x = 0 into
triangles for P1/P2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np
import skfem

from ..checks import InputError, in_range, integer_at_least, one_of, positive
from ..scenes import ELEMENTS, ContinuumOptions

__all__ = ["BOUNDARIES", "SoilMesh", "FootingDofs", "soil_mesh", "from_options", "footing_dofs",
           "grid_lines"]

#: The named boundaries of a soil mesh: footing base, free surface, lateral sides, base.
BOUNDARIES = ("footing", "surface", "sides", "bottom")

_SKFEM = {
    "P1": (skfem.MeshTri1, skfem.ElementTriP1),
    "P2": (skfem.MeshTri1, skfem.ElementTriP2),
    "Q1": (skfem.MeshQuad1, skfem.ElementQuad1),
    "Q2": (skfem.MeshQuad1, skfem.ElementQuad2),
}


@dataclass(frozen=True, eq=False)
class FootingDofs:
    """DOFs of a two-component vector basis on the footing base, sorted by ``x``.

    ``x[i]`` is the location of DOFs ``ux[i]`` (horizontal) and ``uy[i]`` (vertical): mesh nodes
    and, for P2/Q2, facet midpoints. ``len()`` is the total number of DOFs.
    """

    x: np.ndarray
    ux: np.ndarray
    uy: np.ndarray

    def __len__(self) -> int:
        return self.ux.size + self.uy.size

    @property
    def all(self) -> np.ndarray:
        """All footing DOFs: ``ux`` then ``uy``."""
        return np.concatenate((self.ux, self.uy))


@dataclass(frozen=True)
class SoilMesh:
    """A graded soil mesh and the parameters that built it (see :func:`soil_mesh`).

    ``mesh`` is a linear :class:`skfem.MeshTri1` or :class:`skfem.MeshQuad1` with the named
    boundaries :data:`BOUNDARIES`; ``element`` names the basis (P2/Q2 are a basis choice on the
    same geometric mesh). Two meshes compare equal when their parameters do.
    """

    mesh: skfem.Mesh = field(repr=False, compare=False)
    element: str
    footing_width: float
    domain_width: float
    domain_depth: float
    elements_across: int
    grading: float
    layer_depth: float | None = None

    @property
    def width(self) -> float:
        """Domain width W (length)."""
        return self.domain_width * self.footing_width

    @property
    def depth(self) -> float:
        """Domain depth D (length): ``layer_depth`` if given, else ``domain_depth`` × B."""
        return self.domain_depth * self.footing_width if self.layer_depth is None \
            else self.layer_depth

    @property
    def skfem_element(self) -> skfem.Element:
        """The scalar skfem element; wrap it in ``skfem.ElementVector`` for displacements."""
        return _SKFEM[self.element][1]()

    @property
    def footing_x(self) -> np.ndarray:
        """Sorted x of the mesh nodes on the footing base, from -B/2 to B/2."""
        nodes = np.unique(self.mesh.facets[:, self.mesh.boundaries["footing"]])
        return np.sort(self.mesh.p[0, nodes])

    @property
    def edge_size(self) -> float:
        """Size of the footing-edge element (the smallest along the surface), length."""
        x = self.footing_x
        return float(x[1] - x[0])

    @property
    def parameters(self) -> dict:
        """The parameters used, for provenance."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "mesh"}

    def footing_dofs(self, basis: skfem.Basis) -> FootingDofs:
        """:func:`footing_dofs` of a vector ``basis`` built on this mesh."""
        if basis.mesh is not self.mesh:
            raise InputError("basis: built on another mesh; build it on SoilMesh.mesh")
        return footing_dofs(basis)


def soil_mesh(footing_width: float, *, domain_width: float = 10.0, domain_depth: float = 10.0,
              element: str = "Q2", elements_across: int = 16, grading: float = 1.0,
              layer_depth: float | None = None) -> SoilMesh:
    """A soil domain W × D graded towards the footing edges (see the module docstring).

    ``footing_width`` B (length); ``domain_width`` W/B in (1, 1e4]; ``domain_depth`` D/B in
    (0, 1e4]; ``element`` one of P1, P2, Q1, Q2; ``elements_across`` the footing, >= 2;
    ``grading`` the centre-to-edge element size ratio across the footing, in [1, 100] (no
    effect with 2 elements across);
    ``layer_depth`` (length) overrides the depth for a finite layer on a rigid base.
    Identical parameters give the identical mesh.
    """
    params = _checked(footing_width, domain_width, domain_depth, element, elements_across,
                      grading, layer_depth)
    return _soil_mesh(params, *_lines(params))


def _lines(params: dict) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) of the grid lines of the checked ``params`` (module docstring)."""
    b, n = params["footing_width"], params["elements_across"]
    depth = params["layer_depth"] or params["domain_depth"] * b
    x = _x_lines(b, params["domain_width"] * b, n, params["grading"])
    return x, _y_lines(b, depth, n, first=float(np.diff(x).min()))


def _soil_mesh(params: dict, x: np.ndarray, y: np.ndarray) -> SoilMesh:
    """The mesh of the checked ``params`` on the grid lines ``x``, ``y``."""
    b = params["footing_width"]
    depth = params["layer_depth"] or params["domain_depth"] * b
    mesh = _mesh(params["element"], x, y)
    mesh = mesh.with_boundaries(_boundaries(mesh, 0.5 * b, x[-1], depth))
    return SoilMesh(mesh=mesh, **params)


def from_options(footing_width: float, options: ContinuumOptions,
                 layer_depth: float | None = None,
                 lines: tuple[np.ndarray, np.ndarray] | None = None) -> SoilMesh:
    """:func:`soil_mesh` from a scene's ``[continuum]`` options (``base``/``boundary`` are the
    solver's business and do not change the mesh). ``lines``: the (x, y) that
    :func:`grid_lines` gives for the same arguments, when the caller has them already (the
    continuum keeps them in its set-up cache); None: computed here."""
    params = _checked(footing_width, options.domain_width, options.domain_depth,
                      options.element, options.elements_across, options.grading, layer_depth)
    return _soil_mesh(params, *(_lines(params) if lines is None else lines))


def grid_lines(footing_width: float, options: ContinuumOptions,
               layer_depth: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) of the grid lines of the mesh :func:`from_options` would build, without building
    it (for estimating a run's size and time step before meshing): the mesh has
    ``(x.size - 1)(y.size - 1)`` quads, and its shortest edge is the smallest spacing."""
    return _lines(_checked(footing_width, options.domain_width, options.domain_depth,
                           options.element, options.elements_across, options.grading,
                           layer_depth))


def footing_dofs(basis: skfem.Basis, boundary: str = "footing") -> FootingDofs:
    """The x and y DOFs of a two-component vector ``basis`` on ``boundary``, sorted by x.

    Includes the facet (midside) DOFs of P2/Q2. The contact code ties these to the footing.
    """
    names = basis.mesh.boundaries or {}
    if boundary not in names:
        raise InputError(f"boundary = {boundary!r}: the mesh has no such boundary "
                         f"(it has {sorted(names)})")
    view = basis.get_dofs(boundary)
    ux, uy = view.all("u^1"), view.all("u^2")
    if ux.size == 0 or ux.size != uy.size:
        raise InputError(f"basis element = {type(basis.elem).__name__}: expected a "
                         "two-component skfem.ElementVector")
    ux, uy = (d[np.argsort(basis.doflocs[0, d], kind="stable")] for d in (ux, uy))
    return FootingDofs(x=basis.doflocs[0, ux], ux=ux, uy=uy)


# ---------------------------------------------------------------------------------------------
# Validation
# ---------------------------------------------------------------------------------------------


def _checked(footing_width, domain_width, domain_depth, element, elements_across, grading,
             layer_depth) -> dict:
    """The parameters, validated (ranges as in the scene's ``[continuum]`` table)."""
    return dict(
        element=one_of("element", element, ELEMENTS),
        footing_width=positive("footing_width", footing_width),
        domain_width=in_range("domain_width", domain_width, 1.0, 1e4, low_open=True),
        domain_depth=in_range("domain_depth", domain_depth, 0.0, 1e4, low_open=True),
        elements_across=integer_at_least("elements_across", elements_across, 2),
        grading=in_range("grading", grading, 1.0, 100.0),
        layer_depth=None if layer_depth is None else positive("layer_depth", layer_depth),
    )


# ---------------------------------------------------------------------------------------------
# Grid lines
# ---------------------------------------------------------------------------------------------


def _footing_nodes(width: float, n: int, grading: float) -> np.ndarray:
    """x of the n + 1 nodes across the footing: sizes grow geometrically from both edges."""
    steps = np.minimum(np.arange(n), np.arange(n)[::-1])  # elements from the nearer edge
    ratio = grading ** (1.0 / steps.max()) if steps.max() > 0 else 1.0
    sizes = ratio ** steps
    x = width * (np.concatenate(([0.0], np.cumsum(sizes))) / sizes.sum() - 0.5)
    return _antisymmetric(x, 0.5 * width)


def _antisymmetric(x: np.ndarray, half: float) -> np.ndarray:
    """``x`` made exactly antisymmetric (x[i] == -x[-1-i]) with ends at ±half."""
    x = 0.5 * (x - x[::-1])
    x[0], x[-1] = -half, half
    return x


def _outer_count(n: int, length: float, half_footing: float, first: float) -> int:
    """Number of elements over ``length`` beyond a footing edge (module docstring)."""
    count = math.ceil(0.5 * n * math.log2(1.0 + length / half_footing))
    return max(1, min(count, math.floor(length / first)))


def _growth_ratio(first: float, count: int, length: float) -> float:
    """q >= 1 with first · (1 + q + ... + q^(count-1)) = length."""
    from scipy.optimize import brentq  # here, not at the top: its import costs every fresh
    # process about 0.2 s of CPU, and only a graded mesh needs it

    if count == 1 or count * first >= length:
        return 1.0
    powers = np.arange(count)
    upper = (length / first) ** (1.0 / (count - 1))
    return brentq(lambda q: first * np.sum(q ** powers) - length, 1.0, upper, xtol=1e-15)


def _graded_offsets(first: float, count: int, length: float) -> np.ndarray:
    """Offsets 0 ... length of ``count`` elements growing geometrically from ``first``."""
    sizes = first * _growth_ratio(first, count, length) ** np.arange(count)
    offsets = np.concatenate(([0.0], np.cumsum(sizes)))
    offsets[-1] = length
    return offsets


def _x_lines(b: float, width: float, n: int, grading: float) -> np.ndarray:
    """Sorted x of the vertical grid lines, symmetric about x = 0."""
    footing = _footing_nodes(b, n, grading)
    first, length = footing[1] - footing[0], 0.5 * (width - b)
    outer = 0.5 * b + _graded_offsets(first, _outer_count(n, length, 0.5 * b, first), length)
    outer[-1] = 0.5 * width
    return np.concatenate((-outer[:0:-1], footing, outer[1:]))


def _y_lines(b: float, depth: float, n: int, first: float) -> np.ndarray:
    """Sorted y of the horizontal grid lines, -depth ... 0, the top one ``first`` deep."""
    offsets = _graded_offsets(first, _outer_count(n, depth, 0.5 * b, first), depth)
    return 0.0 - offsets[::-1]


# ---------------------------------------------------------------------------------------------
# Cells and boundaries
# ---------------------------------------------------------------------------------------------


def _quad_grid(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes (2, nx·ny), row by row from the bottom, and quads (4, ·) [BL, BR, TR, TL]."""
    xx, yy = np.meshgrid(x, y)
    i, j = np.meshgrid(np.arange(x.size - 1), np.arange(y.size - 1))
    corner = (j * x.size + i).ravel()
    quads = np.vstack((corner, corner + 1, corner + 1 + x.size, corner + x.size))
    return np.vstack((xx.ravel(), yy.ravel())), quads


def _triangles(p: np.ndarray, quads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Split quads into triangles, mirror-symmetric about x = 0.

    Right of x = 0 the diagonal runs from top-left to bottom-right, left of it from bottom-left
    to top-right. Quads straddling x = 0 (odd ``elements_across``) get four triangles around a
    new centre node on x = 0.
    """
    bl, br, tr, tl = quads
    right, left = p[0, bl] >= 0.0, p[0, br] <= 0.0
    mid = ~(right | left)
    centre = p.shape[1] + np.arange(mid.sum())
    centre_p = np.vstack((np.zeros(centre.size), 0.5 * (p[1, bl[mid]] + p[1, tl[mid]])))
    tris = [(bl, br, tl, right), (br, tr, tl, right), (bl, br, tr, left), (bl, tr, tl, left)]
    cells = [np.vstack((a[m], b[m], c[m])) for a, b, c, m in tris]
    sides = ((bl, br), (br, tr), (tr, tl), (tl, bl))
    cells += [np.vstack((a[mid], b[mid], centre)) for a, b in sides]
    return np.hstack((p, centre_p)), np.hstack(cells)


def _mesh(element: str, x: np.ndarray, y: np.ndarray) -> skfem.Mesh:
    p, quads = _quad_grid(x, y)
    if _SKFEM[element][0] is skfem.MeshQuad1:
        return skfem.MeshQuad1(p, quads)
    return skfem.MeshTri1(*_triangles(p, quads))


def _boundaries(mesh: skfem.Mesh, half_footing: float, half_width: float,
                depth: float) -> dict[str, np.ndarray]:
    """Facet indices of each named boundary, found by exact coordinates of the grid lines."""
    facets = mesh.boundary_facets()
    x, y = (mesh.p[k][mesh.facets[:, facets]] for k in (0, 1))
    top = (y == 0.0).all(axis=0)
    footing = top & (np.abs(x) <= half_footing).all(axis=0)
    return {
        "footing": facets[footing],
        "surface": facets[top & ~footing],
        "sides": facets[(np.abs(x) == half_width).all(axis=0)],
        "bottom": facets[(y == -depth).all(axis=0)],
    }
