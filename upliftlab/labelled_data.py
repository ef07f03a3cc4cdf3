"""Labelled arrays as a NetCDF file holds them, without xarray: the record every result file is
made from.

A :class:`LabelledData` is what an :class:`xarray.Dataset` is on disk: named variables, each
with its dimensions, values and attributes; which of them are coordinates; global attributes.
A result's ``save`` builds one and writes it (:func:`upliftlab.results.write_dataset`) without
importing xarray, whose import (with dask and dask.distributed, which xarray imports whenever
they are installed) costs about a second of a fresh process; ``to_xarray`` gives the same data
as a Dataset for a notebook.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

__all__ = ["LabelledData"]


def _array(name: str, values) -> np.ndarray:
    """``values`` as a numpy array a NetCDF-4 file can hold (numbers or text)."""
    array = np.asarray(values)
    if array.dtype.kind == "O":
        if not all(isinstance(v, str) for v in array.flat):
            raise ValueError(f"variable {name!r}: objects other than text cannot be written")
        array = array.astype(str)
    if array.dtype.kind not in "biufU":
        raise ValueError(f"variable {name!r}: values of type {array.dtype} cannot be written "
                         f"(numbers, booleans and text can)")
    return array


@dataclass(frozen=True)
class LabelledData:
    """Named variables {name: (dims, values, attrs)} (``values`` a numpy array of numbers,
    booleans or text; ``attrs`` a mapping), the names among them that are coordinates, and the
    global ``attrs``. A variable named as its one dimension is that dimension's coordinate.
    Raises ValueError if a variable's dimensions do not match its shape or two variables
    disagree on a dimension's length."""

    variables: Mapping[str, tuple]
    coords: frozenset = frozenset()
    attrs: Mapping[str, object] = field(default_factory=dict)

    def __post_init__(self):
        variables, sizes = {}, {}
        for name, (dims, values, attrs) in self.variables.items():
            dims, array = tuple(str(d) for d in dims), _array(name, values)
            if array.ndim != len(dims):
                raise ValueError(f"variable {name!r}: {len(dims)} dims for shape {array.shape}")
            for dim, n in zip(dims, array.shape):
                if sizes.setdefault(dim, n) != n:
                    raise ValueError(f"dimension {dim!r} is {sizes[dim]} and {n}")
            variables[str(name)] = (dims, array, dict(attrs or {}))
        coords = set(self.coords) | {n for n, (dims, _, _) in variables.items() if dims == (n,)}
        unknown = coords - set(variables)
        if unknown:
            raise ValueError(f"coordinates {sorted(unknown)} are not variables")
        object.__setattr__(self, "variables", MappingProxyType(variables))
        object.__setattr__(self, "coords", frozenset(coords))
        object.__setattr__(self, "attrs", dict(self.attrs or {}))

    @property
    def sizes(self) -> dict[str, int]:
        """{dimension: length}, in the order the variables first name them."""
        sizes: dict[str, int] = {}
        for dims, values, _ in self.variables.values():
            for dim, n in zip(dims, values.shape):
                sizes.setdefault(dim, n)
        return sizes

    @classmethod
    def build(cls, data: Mapping[str, tuple], coords: Mapping[str, tuple] | None = None,
              attrs: Mapping[str, object] | None = None) -> "LabelledData":
        """From data variables and coordinates given as xarray takes them:
        {name: (dims, values, attrs)}, a single dimension given as a string."""
        variables = {}
        for name, (dims, values, var_attrs) in {**data, **(coords or {})}.items():
            variables[name] = ((dims,) if isinstance(dims, str) else tuple(dims), values,
                               var_attrs)
        return cls(variables, frozenset(coords or {}), dict(attrs or {}))

    @classmethod
    def from_xarray(cls, dataset) -> "LabelledData":
        """The variables, coordinates and attributes of an :class:`xarray.Dataset` (its
        ``encoding`` is not carried: a result file is written as
        :func:`upliftlab.results.write_dataset` says)."""
        variables = {str(name): (tuple(var.dims), np.asarray(var.values), dict(var.attrs))
                     for name, var in dataset.variables.items()}
        return cls(variables, frozenset(str(c) for c in dataset.coords), dict(dataset.attrs))

    def to_xarray(self):
        """The same data as an :class:`xarray.Dataset`."""
        import xarray as xr

        data = {n: v for n, v in self.variables.items() if n not in self.coords}
        coords = {n: v for n, v in self.variables.items() if n in self.coords}
        return xr.Dataset(data, coords=coords, attrs=dict(self.attrs))

    def replace(self, variables: Mapping[str, tuple] | None = None,
                coords=None, attrs: Mapping[str, object] | None = None) -> "LabelledData":
        """A copy with any of the three replaced."""
        return LabelledData(self.variables if variables is None else variables,
                            self.coords if coords is None else coords,
                            self.attrs if attrs is None else attrs)
