"""Read and write soil meshes with their named boundaries through meshio.

Formats, chosen by the file suffix:

- ``.vtu`` and ``.xdmf`` (with its ``.h5`` beside it): the domain cells, then one ``line`` cell
  per facet of any named boundary. Each boundary is an int8 cell-data array
  ``boundary:<name>``, 1 on its lines and 0 elsewhere (so boundaries may overlap).
- ``.msh`` (Gmsh 2.2 ASCII, which meshio 5.3.5 writes reliably; Gmsh 4.1 files are read too):
  each boundary is a physical group of line elements with that name (dimension 1), the domain
  the physical group ``soil`` (dimension 2). A user's Gmsh mesh needs line physical groups named
  ``footing``, ``surface``, ``sides`` and ``bottom``.

Only the geometric (linear) mesh is stored: P2/Q2 are a basis choice in skfem. Quadratic cells
in a file are read by their corners. Coordinates are written at full precision, so a round trip
keeps nodes, connectivity and each boundary's facets exactly. Files appear complete or not at
all.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import skfem

from ..checks import InputError
from ..results import atomic_path, move_into_place, staging_folder
from .soil import BOUNDARIES

if TYPE_CHECKING:
    import meshio

__all__ = ["write_mesh", "read_mesh", "SUFFIXES"]

#: File suffix -> meshio format used to write it.
SUFFIXES = {".vtu": "vtu", ".xdmf": "xdmf", ".msh": "gmsh22"}
# Readers by format (meshio's submodule of each): meshio.read itself calls sys.exit on a file it
# cannot parse. The Gmsh reader takes 2.2 and 4.1 files. meshio is imported where a mesh file is
# read or written, not with this module: its import costs every fresh continuum process about
# 0.05 s of CPU before its first step, which reads and writes no mesh file.
_READERS = {"vtu": "vtu", "xdmf": "xdmf", "gmsh22": "gmsh"}

_TAG = "boundary:"  # prefix of the VTU/XDMF cell-data arrays that flag boundary lines
_DOMAIN_GROUP = "soil"  # Gmsh physical group of the domain cells
_CELLS = {"triangle": (skfem.MeshTri1, 3), "triangle6": (skfem.MeshTri1, 3),
          "triangle7": (skfem.MeshTri1, 3), "quad": (skfem.MeshQuad1, 4),
          "quad8": (skfem.MeshQuad1, 4), "quad9": (skfem.MeshQuad1, 4)}
_LINES = ("line", "line3")


def write_mesh(path: str | os.PathLike, mesh) -> Path:
    """Write a :class:`~upliftlab.meshes.SoilMesh` or skfem triangle/quad mesh, with its named
    boundaries, to ``path`` (.vtu, .xdmf or .msh). Returns the path."""
    path = Path(path)
    file_format = _file_format(path)
    data = _to_meshio(_linear(mesh), gmsh=file_format == "gmsh22")
    if file_format == "xdmf":
        _write_xdmf(path, data)
        return path
    options = {"binary": False} if file_format == "gmsh22" else {}
    import meshio

    with atomic_path(path) as tmp:
        meshio.write(tmp, data, file_format=file_format, **options)
    return path


def read_mesh(path: str | os.PathLike, *, required=BOUNDARIES) -> skfem.Mesh:
    """Read a triangle or quad mesh and its named boundaries (see the module docstring).

    Raises :class:`InputError` if the file is unreadable, not a plane triangle/quad mesh, a
    boundary line is not an edge of the mesh, or a boundary in ``required`` is missing.
    """
    path = Path(path)
    data = _read(path, _file_format(path))
    cls, points, cells = _domain(path, data)
    points, cells, lines = _drop_unused(points, cells, _named_lines(data))
    mesh = cls(points, cells)
    missing = [name for name in required if name not in lines]
    if missing:
        raise InputError(f"{path}: named boundaries {', '.join(missing)} are missing "
                         f"(found {sorted(lines) or 'none'}); expected {', '.join(required)}")
    return mesh.with_boundaries({name: _facets(mesh, name, pairs)
                                 for name, pairs in lines.items()})


# ---------------------------------------------------------------------------------------------
# Writing
# ---------------------------------------------------------------------------------------------


def _file_format(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise InputError(f"path = {str(path)!r}: suffix {suffix or '(none)'!r} must be one of "
                         f"{', '.join(SUFFIXES)}")
    return SUFFIXES[suffix]


def _linear(mesh) -> tuple:
    """(points (n, 3), cell type, cells (ncells, k), facets (2, nfacets), boundaries) of the
    geometric mesh; ``boundaries`` maps names to facet indices."""
    mesh = getattr(mesh, "mesh", mesh)  # a SoilMesh holds its skfem mesh
    for cell_type in ("triangle", "quad"):
        cls, corners = _CELLS[cell_type]
        if isinstance(mesh, cls):
            vertices = mesh.p[:, :mesh.nvertices].T  # a quadratic mesh stores midpoints after
            points = np.column_stack((vertices, np.zeros(len(vertices))))
            boundaries = {name: np.asarray(f) for name, f in (mesh.boundaries or {}).items()}
            return points, cell_type, mesh.t[:corners].T, mesh.facets, boundaries
    raise InputError(f"mesh = {type(mesh).__name__}: expected a skfem triangle or quad mesh")


def _to_meshio(linear: tuple, gmsh: bool) -> meshio.Mesh:
    import meshio

    points, cell_type, cells, facets, boundaries = linear
    encode = _gmsh_groups if gmsh else _flags
    blocks, cell_data, field_data = encode(len(cells), facets, boundaries)
    return meshio.Mesh(points, [(cell_type, cells)] + blocks, cell_data=cell_data,
                       field_data=field_data)


def _flags(ncells: int, facets: np.ndarray, boundaries: dict) -> tuple:
    """One line per boundary facet; an int8 flag array ``boundary:<name>`` per boundary."""
    if not boundaries:
        return [], {}, {}
    union = np.unique(np.concatenate(list(boundaries.values())))
    cell_data = {_TAG + name: [np.zeros(ncells, np.int8), np.isin(union, own).astype(np.int8)]
                 for name, own in boundaries.items()}
    return [("line", facets[:, union].T)], cell_data, {}


def _gmsh_groups(ncells: int, facets: np.ndarray, boundaries: dict) -> tuple:
    """One block of lines per boundary, tagged with its physical group 1, 2, ...; the domain
    cells in the physical group ``soil``."""
    if _DOMAIN_GROUP in boundaries:
        raise InputError(f"boundary name {_DOMAIN_GROUP!r} is reserved for the domain in .msh")
    names = [name for name in boundaries if len(boundaries[name])]
    tags = [np.full(ncells, len(names) + 1)]
    tags += [np.full(len(boundaries[name]), k + 1) for k, name in enumerate(names)]
    field_data = {name: np.array([k + 1, 1]) for k, name in enumerate(names)}
    field_data[_DOMAIN_GROUP] = np.array([len(names) + 1, 2])
    blocks = [("line", facets[:, boundaries[name]].T) for name in names]
    return blocks, {"gmsh:physical": tags, "gmsh:geometrical": tags}, field_data


def _write_xdmf(path: Path, data: meshio.Mesh) -> None:
    """Write ``path`` and its ``.h5`` (referenced by base name) in a private directory beside
    them, then move each into place; the .xdmf comes last."""
    import meshio

    with staging_folder(path) as tmp:
        inner = tmp / path.name
        meshio.write(inner, data, file_format="xdmf")
        move_into_place(inner.with_suffix(".h5"), path.with_suffix(".h5"))
        move_into_place(inner, path)


# ---------------------------------------------------------------------------------------------
# Reading
# ---------------------------------------------------------------------------------------------


def _read(path: Path, file_format: str) -> meshio.Mesh:
    if not path.is_file():
        raise InputError(f"path = {str(path)!r}: no such file")
    import meshio

    try:
        return getattr(meshio, _READERS[file_format]).read(path)
    except Exception as error:  # a parser meeting a broken file may raise anything
        raise InputError(f"{path}: not a readable {path.suffix} mesh: {error}") from error


def _domain(path: Path, data: meshio.Mesh) -> tuple:
    """(mesh class, points (n, 2), corner connectivity (ncells, k)) of the 2D cells."""
    kinds = [block.type for block in data.cells if block.type in _CELLS]
    classes = {_CELLS[kind] for kind in kinds}
    if len(classes) != 1:
        raise InputError(f"{path}: cells {sorted({b.type for b in data.cells})}: expected one "
                         "kind of 2D cell, triangles or quads (linear or quadratic)")
    cls, corners = classes.pop()
    cells = np.vstack([b.data[:, :corners] for b in data.cells if b.type in _CELLS])
    points = np.asarray(data.points, dtype=float)
    if points.shape[1] > 2 and np.any(points[:, 2:] != 0.0):
        raise InputError(f"{path}: z = {np.abs(points[:, 2:]).max():g}: a plane mesh needs "
                         "z = 0")
    return cls, points[:, :2], cells


def _named_lines(data: meshio.Mesh) -> dict[str, np.ndarray]:
    """Node pairs (k, 2) of each named boundary: ``boundary:<name>`` flags or Gmsh physical
    groups of dimension 1."""
    lines: dict[str, list] = {}
    for key, values in data.cell_data.items():
        if key.startswith(_TAG):
            _collect(lines, key[len(_TAG):], data.cells, [np.asarray(v) != 0 for v in values])
    physical = data.cell_data.get("gmsh:physical", [])
    for name, group in data.field_data.items():
        tag_dim = np.ravel(group)
        if tag_dim.size == 2 and tag_dim[1] == 1:
            _collect(lines, name, data.cells, [np.asarray(v) == tag_dim[0] for v in physical])
    return {name: np.vstack(pairs) for name, pairs in lines.items()}


def _collect(lines: dict, name: str, blocks, masks) -> None:
    pairs = [b.data[m, :2] for b, m in zip(blocks, masks) if b.type in _LINES and m.any()]
    if pairs:
        lines.setdefault(name, []).extend(pairs)


def _drop_unused(points: np.ndarray, cells: np.ndarray, lines: dict) -> tuple:
    """Renumber nodes to those the cells use (Gmsh files may hold others); transpose for skfem."""
    used = np.unique(cells)
    if used.size < len(points):
        number = np.full(len(points), -1)
        number[used] = np.arange(used.size)
        points, cells = points[used], number[cells]
        lines = {name: number[pairs] for name, pairs in lines.items()}
    return np.ascontiguousarray(points.T), np.ascontiguousarray(cells.T), lines


def _facets(mesh: skfem.Mesh, name: str, pairs: np.ndarray) -> np.ndarray:
    """Sorted facet indices of ``mesh`` matching the node ``pairs`` of boundary ``name``."""
    keys, wanted = _keys(mesh.facets.T, mesh.p.shape[1]), _keys(pairs, mesh.p.shape[1])
    order = np.argsort(keys)
    index = order[np.minimum(np.searchsorted(keys, wanted, sorter=order), keys.size - 1)]
    bad = np.flatnonzero(keys[index] != wanted)
    if bad.size:
        raise InputError(f"boundary {name!r}: line with nodes {pairs[bad[0]].tolist()} is not "
                         "an edge of the mesh")
    return np.unique(index)


def _keys(pairs: np.ndarray, nodes: int) -> np.ndarray:
    """One integer per unordered node pair."""
    pairs = np.sort(np.asarray(pairs, dtype=np.int64), axis=1)
    return pairs[:, 0] * nodes + pairs[:, 1]
