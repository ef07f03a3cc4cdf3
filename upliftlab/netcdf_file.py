"""A :class:`~upliftlab.labelled_data.LabelledData` as the bytes of a NetCDF-4 file, written
through h5netcdf without xarray.

The file is the one ``xarray.Dataset.to_netcdf(engine="h5netcdf")`` writes for the same data
and encoding (``tests/test_netcdf_file.py`` holds the two to each other), so that
``xarray.open_dataset``, netCDF4, ncdump and ParaView read it as they read xarray's:

- each dimension is created when a variable first names it; a variable named as its one
  dimension is that dimension's coordinate variable (h5netcdf makes it the HDF5 dimension
  scale), a dimension without one gets h5netcdf's own scale;
- a floating-point variable has ``_FillValue`` NaN unless it is named in ``no_fill`` (CF wants
  none on a coordinate: :func:`upliftlab.cf.encode`);
- text is variable-length UTF-8;
- a data variable's ``coordinates`` attribute names, sorted, the non-dimension coordinates
  whose dimensions are among its own (CF section 5); a coordinate that no variable names so is
  listed in the global ``coordinates`` attribute, as xarray does to read it back as one;
- arrays (not scalars) of numbers are compressed with zlib at ``complevel`` with the byte
  shuffle, in the chunks h5py chooses.
"""

from __future__ import annotations

import io

import numpy as np

from .labelled_data import LabelledData

__all__ = ["netcdf_bytes"]


def _coordinates(data: LabelledData) -> tuple[dict[str, str], str]:
    """{data variable: its ``coordinates`` attribute}, and the global one ('' if none)."""
    auxiliary = sorted(n for n in data.coords if data.variables[n][0] != (n,))
    attribute, named = {}, set()
    for name, (dims, _, attrs) in data.variables.items():
        if name in data.coords:
            continue
        if "coordinates" in attrs:
            named.update(str(attrs["coordinates"]).split())
            continue
        own = [c for c in auxiliary if set(data.variables[c][0]) <= set(dims)]
        if own:
            attribute[name] = " ".join(own)
            named.update(own)
    return attribute, " ".join(c for c in auxiliary if c not in named)


def netcdf_bytes(data: LabelledData, no_fill=frozenset(), complevel: int = 4) -> bytes:
    """``data`` as the bytes of a NetCDF-4 file made in memory (module docstring); ``no_fill``:
    the floating-point variables without a ``_FillValue``. ``data`` is written as it is: already
    CF-encoded (:func:`upliftlab.cf.encode`), its booleans already int8, as
    :func:`upliftlab.results.write_dataset` makes it."""
    import h5netcdf
    import h5py

    coordinates, global_coordinates = _coordinates(data)
    attrs = dict(data.attrs)
    if global_coordinates and "coordinates" not in attrs:
        attrs["coordinates"] = global_coordinates
    buffer = io.BytesIO()
    with h5netcdf.File(buffer, "w") as file:
        for key, value in attrs.items():
            file.attrs[key] = value
        for dim, n in data.sizes.items():
            file.dimensions[dim] = n
        for name, (dims, values, var_attrs) in data.variables.items():
            kwargs = {}
            if values.ndim and values.dtype.kind in "fiu" and complevel:
                kwargs = dict(compression="gzip", compression_opts=complevel, shuffle=True,
                              chunks=None)
            text = values.dtype.kind == "U"
            fill = (values.dtype.type(np.nan)
                    if values.dtype.kind == "f" and name not in no_fill else None)
            var = file.create_variable(name, dims,
                                       dtype=h5py.string_dtype() if text else values.dtype,
                                       fillvalue=fill, **kwargs)
            for key, value in {**var_attrs, **({"coordinates": coordinates[name]}
                                               if name in coordinates else {})}.items():
                var.attrs[key] = value
            var[...] = values.astype(object) if text else values
    return buffer.getvalue()
