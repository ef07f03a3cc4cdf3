"""What every result file gets on its way to disk to follow the CF-1.10 conventions, and back.

Checked by the IOOS compliance checker (``compliance-checker --test cf:1.10``, which ships the
CF standard-name table and UDUNITS): ``tests/test_cf.py`` writes every kind of result file and
finds no failing required check. :func:`encode` is applied by
:func:`upliftlab.results.write_dataset` to every dataset (as a
:class:`~upliftlab.labelled_data.LabelledData`), :func:`decode` by
:func:`upliftlab.results.read_dataset` to every file it opens:

- **Time.** A run's time axis is seconds from its start, held in memory in ``s``. CF (section
  4.4) wants a time coordinate's units to name a reference date, so on disk they are
  :data:`TIME_UNITS`, with ``standard_name = "time"`` and ``axis = "T"``; the date is nominal
  (the start of the run), the numbers are the same seconds. :func:`decode` reads them back as
  ``s``; ``xarray.open_dataset`` decodes them into dates from 1970-01-01 unless given
  ``decode_times=False``.
- **No fill value on a coordinate** (section 2.5.1): every other floating-point variable has
  ``_FillValue = NaN``, as xarray gives it (:mod:`upliftlab.netcdf_file`).
- **Flags typed like their variable** (section 3.5): ``flag_values``, ``flag_masks`` and the
  ``valid_*`` attributes are cast to the variable's type (int8 state codes, not int64).
- **Labels are not coordinate variables.** A coordinate variable is numeric and strictly
  monotonic (CF section 1.3; ``string x(x)`` is not allowed, cf-conventions issue 174), so a
  dimension labelled by text (``dof``, ``component``, ``case``) is written without one, its
  labels as the auxiliary coordinate ``<dimension>_label`` (section 6.1; ``<dimension>_key``
  if the dataset has a ``<dimension>_label`` of its own); :func:`decode` makes them the
  dimension's index again. With ``xarray.open_dataset``:
  ``ds.set_index(dof="dof_label")`` or ``ds.swap_dims(dof="dof_label")``.
- **Index coordinates have units**: a numeric coordinate variable without units (a spring's,
  a load step's, a node's index) gets ``units = "1"``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["CONVENTIONS", "TIME_UNITS", "encode", "decode", "is_time"]

#: The conventions every result file follows (its global ``Conventions`` unless it names them).
CONVENTIONS = "CF-1.10"

#: The units of a run's time axis on disk: seconds from the run's start, the date nominal.
TIME_UNITS = "seconds since 1970-01-01 00:00:00"

#: Attributes whose values must have the type of their variable (CF sections 2.5.1, 3.5).
TYPED_ATTRIBUTES = ("flag_values", "flag_masks", "valid_min", "valid_max", "valid_range",
                    "actual_range")


def is_time(name: str, attrs) -> bool:
    """True if a variable is what the CF conventions (and their checkers) take for a time
    coordinate: named ``time``, or with ``standard_name = "time"`` or ``axis = "T"``."""
    return (name.lower() == "time" or attrs.get("standard_name") == "time"
            or attrs.get("axis") == "T")


def _time_attributes(attrs: dict) -> dict:
    """A time axis in seconds (``units = "s"``) as CF wants it on disk."""
    return {**attrs, "units": TIME_UNITS, "standard_name": "time", "axis": "T"}


def _typed(attrs: dict, dtype) -> dict:
    out = dict(attrs)
    for key in TYPED_ATTRIBUTES:
        if key in out and dtype.kind in "iuf":
            out[key] = np.asarray(out[key]).astype(dtype)
    return out


#: The names of a dimension's text labels on disk: the first one the dataset leaves free (a
#: study may already label ``calibration`` keys by a ``calibration_label`` of its own).
LABELS = ("{}_label", "{}_key")


def _labels(data) -> list[str]:
    """The dimensions of ``data`` (a LabelledData) whose coordinate variable holds text."""
    return [d for d in data.sizes if d in data.coords and data.variables[d][0] == (d,)
            and data.variables[d][1].dtype.kind in "USO"]


def encode(data) -> tuple[object, frozenset[str]]:
    """``data`` (a :class:`~upliftlab.labelled_data.LabelledData` with CF attributes) as it goes
    to disk, and the variables that must have no ``_FillValue`` (the floating-point
    coordinates). Values are not touched: attributes change, and text labels move to
    ``<dimension>_label``. Raises ValueError if such a name is taken."""
    attrs = dict(data.attrs)
    attrs.setdefault("Conventions", CONVENTIONS)
    sizes = data.sizes
    variables, no_fill = {}, set()
    for name, (dims, values, var_attrs) in data.variables.items():
        var_attrs = _typed(var_attrs, values.dtype)
        if is_time(name, var_attrs) and var_attrs.get("units") == "s":
            var_attrs = _time_attributes(var_attrs)
        if name in sizes and values.dtype.kind in "iuf" and "units" not in var_attrs:
            var_attrs["units"] = "1"
        variables[name] = (dims, values, var_attrs)
        if name in data.coords and values.dtype.kind in "fc":
            no_fill.add(name)
    labels = {}
    for d in _labels(data):
        free = [f.format(d) for f in LABELS if f.format(d) not in data.variables]
        if not free:
            raise ValueError(f"cannot write the labels of {d!r}: "
                             f"{[f.format(d) for f in LABELS]} are taken")
        labels[d] = free[0]
    variables = {labels.get(n, n): v for n, v in variables.items()}
    coords = frozenset(labels.get(n, n) for n in data.coords)
    return data.replace(variables=variables, coords=coords, attrs=attrs), frozenset(no_fill)


def _label_of(dataset, dim: str) -> str | None:
    """The variable that holds ``dim``'s text labels on disk (as :func:`encode` named it), or
    None: ``<dim>_key`` when ``<dim>_label`` is the dataset's own, else ``<dim>_label``."""
    if dim in dataset.variables:
        return None
    names = [f.format(dim) for f in LABELS]
    found = [n for n in names if n in dataset.coords and dataset[n].dims == (dim,)
             and dataset[n].dtype.kind in "USO"]
    if names[1] in found and names[0] in dataset.variables:
        return names[1]
    return names[0] if names[0] in found else None


def decode(dataset):
    """A dataset read with ``decode_times=False`` as it was in memory: a time axis in ``s``,
    each dimension's text labels its index again."""
    for var in dataset.variables.values():
        if var.attrs.get("units") == TIME_UNITS:
            var.attrs["units"] = "s"
    for dim in list(dataset.dims):
        label = _label_of(dataset, str(dim))
        if label is not None:
            values = dataset[label]
            dataset = dataset.drop_vars(label).assign_coords(
                {dim: (dim, values.values, values.attrs)})
    return dataset
