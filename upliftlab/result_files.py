"""One result file opened as labelled data split by dimension: :func:`open_result`.

A result file holds variables over different sets of dimensions: a reduced run's histories
along ``time``, its springs' along ``time`` and ``spring``, its DOFs', its energy account's,
its peaks (scalars), the ground motion along ``record_time``. ``xarray.open_dataset(path)
.to_dataframe()`` crosses them all into one table (time × spring × DOF × component × record
samples: 10⁹ rows for an El Centro run), which no memory holds. :func:`open_result` gives the
same file as an :class:`xarray.DataTree` with one node per set of dimensions, nested in the
order of the dimensions, so that each node's table is what it holds and no more::

    tree = open_result("results/wall_elcentro-e10/wall_elcentro-e10.nc")
    tree["time"].to_dataset().to_dataframe()         # a row per time step: u, x, θ, V, …
    tree["time/spring"].to_dataset().to_dataframe()  # a row per (time step, spring)
    tree["record_time"].ground_acceleration          # the motion as the run read it
    tree.peak_u                                      # the scalars (peaks) at the root

The root holds the scalars and the file's attributes (units, scene, provenance). A node holds
the coordinates along its dimensions (a continuum run's soil fields in
``snapshot/dof`` carry ``dof_x`` and ``dof_y``, the node of each DOF). Values, units and
attributes are the file's (:func:`upliftlab.results.read_dataset`: the time axis in s).
"""

from __future__ import annotations

import os
from pathlib import Path

from .checks import InputError
from .results import read_dataset

__all__ = ["open_result", "split_by_dimensions"]


def _node_path(dims: tuple[str, ...]) -> str:
    return "/" + "/".join(dims)


def split_by_dimensions(dataset) -> dict[str, object]:
    """``dataset`` as {node path: dataset}: its variables grouped by their dimensions (a path
    per dimension tuple, ``/time/spring``; the scalars at ``/``), each group with the
    coordinates along its dimensions that its ancestors do not hold (a node inherits theirs,
    :class:`xarray.DataTree`); a coordinate that no variable's dimensions cover gets its own
    node."""
    import xarray as xr

    groups: dict[tuple[str, ...], list[str]] = {}
    for name, var in dataset.data_vars.items():
        groups.setdefault(tuple(var.dims), []).append(str(name))
    for name, var in dataset.coords.items():
        if not any(set(var.dims) <= set(dims) for dims in groups if dims):
            groups.setdefault(tuple(var.dims), [])
    held: dict[tuple[str, ...], set[str]] = {}
    nodes = {}
    for dims in sorted(groups, key=len):
        inherited = set().union(*(held.get(dims[:k], set()) for k in range(len(dims))))
        coords = [str(n) for n, c in dataset.coords.items()
                  if n not in inherited and c.dims and set(c.dims) <= set(dims)]
        held[dims] = set(coords)
        node = dataset[groups[dims]]
        node = node.drop_vars([n for n in node.coords if n not in coords]).assign_coords(
            {n: dataset.coords[n] for n in coords})
        nodes[_node_path(dims)] = node.assign_attrs(dataset.attrs) if not dims else node
    if "/" not in nodes:
        nodes["/"] = xr.Dataset(attrs=dataset.attrs)
    for path, node in nodes.items():
        if path != "/":
            node.attrs = {}
    return nodes


def open_result(path: str | os.PathLike):
    """A result file (a reduced run's ``<scene>.nc``, a continuum run's ``result.nc``, a
    study's data file) as an :class:`xarray.DataTree` split by dimensions (module docstring),
    loaded into memory (the file is closed). Raises :class:`~upliftlab.checks.InputError` when
    ``path`` is not a file."""
    import xarray as xr

    path = Path(path)
    if not path.is_file():
        raise InputError(f"open_result: {str(path)!r} is not a file; expected a result file "
                         "(results/<scene>-<case>/<scene>-<case>.nc, .../result.nc)")
    return xr.DataTree.from_dict(split_by_dimensions(read_dataset(path)), name=path.stem)
