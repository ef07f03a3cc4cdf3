"""What the pictures of :mod:`~upliftlab.meshes.render` draw, without drawing it: the linear
sub-mesh of a (quadratic) basis, the frames of a run's snapshots, and the view fixed over all
frames of a run (window, magnification, colour and axis limits, units).

**Quadratic elements** are drawn on their linear sub-mesh (:func:`linear_submesh`): each Q2
quad is split into 4 quads on its 9 nodes, each P2 triangle into 4 triangles on its 6 nodes,
so every nodal displacement is drawn exactly; element values repeat on their sub-cells.

**Results** are duck typed (the ``FieldHistory`` of
:mod:`upliftlab.continuum.output.field_history`): a static
path with recorded fields or a dynamic result, offering ``time``, ``footing`` (nt, 3),
``x``, ``pressure`` and ``gap`` (nt, nc), ``contact_length``, ``N``, ``M``, ``snapshot_time``,
``displacement`` (nk, ndofs), ``plastic_strain`` (nk, nelems) and ``metadata``; a static path
also has ``snapshot_step``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..checks import InputError

__all__ = ["SubMesh", "linear_submesh", "View", "Frame", "uplift_view", "frames",
           "snapshot_rows", "nice_scale", "window_of", "units_of"]


@dataclass(frozen=True, eq=False)
class SubMesh:
    """A linear mesh on the nodes of a Lagrange basis (see the module docstring).

    ``points`` (np, 2) the basis nodes; ``cells`` (nc, k) with ``cell_type`` ``quad`` or
    ``triangle``; ``parent`` (nc,) the element each sub-cell lies in; ``dofs`` (np, 2) the DOFs
    of (ux, uy) at each point in the vector basis; ``edges`` (ne, 2) point pairs of the element
    outlines (the geometric mesh's facets).
    """

    points: np.ndarray
    cells: np.ndarray
    cell_type: str
    parent: np.ndarray
    dofs: np.ndarray
    edges: np.ndarray = field(repr=False)

    @property
    def nelements(self) -> int:
        return int(self.parent.max()) + 1

    def vectors(self, u: np.ndarray) -> np.ndarray:
        """(…, np, 2) nodal displacement of a DOF vector (…, ndofs)."""
        return np.asarray(u)[..., self.dofs]

    def cell_values(self, per_element: np.ndarray) -> np.ndarray:
        """(…, nc) the element values (…, nelems) repeated on each sub-cell."""
        return np.asarray(per_element)[..., self.parent]


def _lattice_cells(order: int, quad: bool) -> list[tuple]:
    """Sub-cells of the reference cell as lattice points (i, j), counter-clockwise."""
    if quad:
        return [((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1))
                for j in range(order) for i in range(order)]
    cells = [((i, j), (i + 1, j), (i, j + 1)) for j in range(order) for i in range(order - j)]
    cells += [((i + 1, j), (i + 1, j + 1), (i, j + 1))
              for j in range(order) for i in range(order - j - 1)]
    return cells


def _signed_areas(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Shoelace areas of polygons ``cells`` (nc, k), positive counter-clockwise."""
    x, y = points[cells, 0], points[cells, 1]
    return 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)


def linear_submesh(basis) -> SubMesh:
    """The :class:`SubMesh` of a scikit-fem vector (or scalar) Lagrange basis on triangles or
    quads: P1/Q1 give the mesh itself, P2/Q2 four sub-cells per element; every sub-cell is
    counter-clockwise."""
    import skfem

    vector = isinstance(basis.elem, skfem.ElementVector)
    scalar = basis.split_bases()[0] if vector else basis
    quad = isinstance(basis.mesh, skfem.MeshQuad1)
    if not (quad or isinstance(basis.mesh, skfem.MeshTri1)):
        raise InputError(f"mesh = {type(basis.mesh).__name__}: expected a linear triangle or "
                         "quad mesh")
    reference = np.asarray(getattr(scalar.elem, "doflocs", np.zeros((0, 2))), dtype=float)
    order = 2 if (2.0 * reference % 2.0).any() else 1  # P2/Q2 have midpoint nodes
    lattice = {tuple(np.rint(r * order).astype(int)): k for k, r in enumerate(reference)}
    try:
        local = np.array([[lattice[pt] for pt in cell] for cell in _lattice_cells(order, quad)])
    except KeyError:
        local = None
    if local is None or len(lattice) != scalar.element_dofs.shape[0]:
        raise InputError(f"element = {type(scalar.elem).__name__}: expected a Lagrange element "
                         "of order 1 or 2 (P1, P2, Q1, Q2)")
    element_dofs = np.asarray(scalar.element_dofs)  # (nloc, nelems)
    cells = element_dofs[local]  # (nsub, k, nelems)
    nsub, k, nelems = cells.shape
    cells = cells.transpose(2, 0, 1).reshape(-1, k)
    points = np.asarray(scalar.doflocs, dtype=float).T.copy()
    clockwise = _signed_areas(points, cells) < 0.0  # skfem may sort a triangle's vertices
    cells[clockwise] = cells[clockwise, ::-1]
    parent = np.repeat(np.arange(nelems), nsub)
    if vector:
        dofs = np.column_stack(basis.split_indices())
    else:
        dofs = np.column_stack((np.arange(scalar.N), np.arange(scalar.N)))
    vertex_point = np.asarray(scalar.nodal_dofs)[0]
    edges = vertex_point[np.asarray(basis.mesh.facets)].T
    return SubMesh(points=points, cells=cells,
                   cell_type="quad" if quad else "triangle", parent=parent, dofs=dofs,
                   edges=edges)


def snapshot_rows(result) -> np.ndarray:
    """The history row of each snapshot: ``snapshot_step`` if the result has it (a static
    path), else the row whose ``time`` is nearest each ``snapshot_time``."""
    steps = getattr(result, "snapshot_step", None)
    if steps is not None:
        return np.asarray(steps, dtype=int)
    time = np.asarray(result.time, dtype=float)
    wanted = np.asarray(result.snapshot_time, dtype=float)
    right = np.clip(np.searchsorted(time, wanted), 1, time.size - 1)
    left = right - 1
    return np.where(np.abs(time[left] - wanted) <= np.abs(time[right] - wanted), left, right)


@dataclass(frozen=True, eq=False)
class Frame:
    """One picture's data: nodal ``displacement`` (np, 2) on the sub-mesh, element
    ``plastic_strain`` (nelems), ``footing`` (u, v, θ), the contact ``x``, ``pressure`` and
    ``gap`` along the base, ``M``, ``N``, ``contact_length`` and a ``label`` (step or time)."""

    displacement: np.ndarray
    plastic_strain: np.ndarray
    footing: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    M: float
    N: float
    contact_length: float
    label: str


def _label(result, k: int, row: int) -> str:
    """A static path's step, a dynamic run's time (a dynamic result has snapshot steps too)."""
    if getattr(result, "kind", "") != "dynamic" and \
            getattr(result, "snapshot_step", None) is not None:
        return f"step {row + 1} of {np.size(result.time)}"
    return f"t = {float(np.asarray(result.snapshot_time)[k]):.3f} s"


def frames(result, sub: SubMesh) -> list[Frame]:
    """One :class:`Frame` per snapshot of a result (module docstring)."""
    displacement = np.asarray(result.displacement)
    plastic = np.asarray(result.plastic_strain)
    if displacement.ndim != 2 or displacement.shape[0] == 0:
        raise InputError("result: no soil fields recorded (pass record_fields=True to the "
                         "pushover, or ask the dynamic run for snapshots)")
    if displacement.shape[1] != sub.dofs.max() + 1 or plastic.shape[-1] != sub.nelements:
        raise InputError(f"result: fields of shape {displacement.shape} and {plastic.shape} do "
                         f"not fit the mesh ({sub.dofs.max() + 1} DOFs, {sub.nelements} "
                         "elements)")
    footing = np.asarray(result.footing)
    out = []
    for k, row in enumerate(snapshot_rows(result)):
        out.append(Frame(displacement=sub.vectors(displacement[k]),
                         plastic_strain=plastic[k], footing=footing[row],
                         x=np.asarray(result.x), pressure=np.asarray(result.pressure)[row],
                         gap=np.asarray(result.gap)[row], M=float(result.M[row]),
                         N=float(result.N[row]),
                         contact_length=float(result.contact_length[row]),
                         label=_label(result, k, row)))
    return out


@dataclass(frozen=True)
class View:
    """What every frame of a run shares: the ``window`` (xmin, xmax, ymin, ymax) in length,
    the magnification ``scale``, colour and axis limits, units and the ``title``."""

    footing_width: float
    window: tuple[float, float, float, float]
    scale: float
    plastic_max: float
    pressure_max: float
    gap_max: float
    length_unit: str = ""
    stress_unit: str = ""
    moment_unit: str = ""
    force_unit: str = ""
    title: str = ""


def nice_scale(target: float) -> float:
    """The largest of 1, 2, 5 × 10^k not above ``target`` (≥ 1e-12)."""
    if not target > 0.0 or not math.isfinite(target):
        return 1.0
    power = 10.0 ** math.floor(math.log10(target))
    return max(step * power for step in (1.0, 2.0, 5.0) if step * power <= target * (1 + 1e-12))


def window_of(width: float) -> tuple[float, float, float, float]:
    return (-1.5 * width, 1.5 * width, -1.25 * width, 0.35 * width)


def units_of(metadata: dict) -> dict:
    units = metadata.get("units", {}) if isinstance(metadata, dict) else {}
    if isinstance(units, str):
        import json
        try:
            units = json.loads(units)
        except ValueError:
            units = {}
    length = units.get("length", "")
    force = units.get("force/length", "").split("/")[0] if units.get("force/length") else ""
    stress = units.get("stress") or (f"{force}/{length}^2" if force and length else "")
    return {"length_unit": length, "stress_unit": stress,
            "moment_unit": units.get("moment/length", ""),
            "force_unit": units.get("force/length", "")}


def uplift_view(result, sub: SubMesh, footing_width: float, *, scale: float | None = None,
                title: str = "") -> View:
    """The :class:`View` of a run: limits over all its snapshots, and the magnification
    ``scale`` (default: the :func:`nice_scale` that makes the largest displacement in the
    window 8 % of B, at least 1)."""
    if footing_width <= 0.0:
        raise InputError(f"footing_width = {footing_width:g}: must be > 0")
    window = window_of(footing_width)
    inside = ((sub.points[:, 0] >= window[0]) & (sub.points[:, 0] <= window[1])
              & (sub.points[:, 1] >= window[2]))
    u = sub.vectors(np.asarray(result.displacement))[:, inside]
    largest = float(np.max(np.linalg.norm(u, axis=-1))) if u.size else 0.0
    if scale is None:
        scale = max(1.0, nice_scale(0.08 * footing_width / largest)) if largest > 0 else 1.0
    elif not (scale > 0 and math.isfinite(scale)):
        raise InputError(f"scale = {scale!r}: the magnification must be a number > 0")
    rows = snapshot_rows(result)
    plastic = float(np.max(result.plastic_strain)) if np.size(result.plastic_strain) else 0.0
    pressure = float(np.max(np.asarray(result.pressure)[rows], initial=0.0))
    gap = float(np.max(np.asarray(result.gap)[rows], initial=0.0))
    metadata = getattr(result, "metadata", {}) or {}
    return View(footing_width=footing_width, window=window, scale=float(scale),
                plastic_max=plastic, pressure_max=pressure, gap_max=gap,
                title=title or str(metadata.get("scene", "")), **units_of(metadata))
