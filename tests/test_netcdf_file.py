"""The NetCDF-4 file upliftlab writes without xarray is the file xarray writes.

Reference: an independent implementation, ``xarray.Dataset.to_netcdf(engine="h5netcdf")``,
given the same data after the same CF encoding (:func:`upliftlab.cf.encode`) and the encoding
:mod:`upliftlab.netcdf_file` documents (zlib level 4 with shuffle on arrays of numbers, no
``_FillValue`` on the floating-point coordinates). The two files must open as identical
datasets (``xarray.testing.assert_identical``, values exact, with the CF decoding off so that
the attributes are compared as stored) and agree, variable by variable, on what xarray does not
show: the HDF5 type, the fill value, the compression filter and level, the shuffle and each
variable's dimensions. The data: a continuum dynamic run's labelled data (histories, text
labels, soil fields along ``dof`` and ``element``, the far field's 2-D peaks, flags), and a
hand-made set with what the run lacks (a scalar, a 2-D coordinate, a coordinate no variable
names, text data, a boolean and int64, a dimension's coordinate given among the data as the
reduced model's ``story`` is).
"""

from __future__ import annotations

import io

import h5py
import numpy as np
import pytest
import xarray as xr

from upliftlab import cf, load_scene
from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.continuum.output.labelled import labelled_data
from upliftlab.labelled_data import LabelledData
from upliftlab.motions import Motion
from upliftlab.netcdf_file import netcdf_bytes
from upliftlab.results import cf_attributes, read_dataset, write_dataset


def _xarray_bytes(data: LabelledData, no_fill: frozenset) -> bytes:
    """The reference: xarray's own writer, on the same encoded data."""
    dataset = data.to_xarray()
    encoding = {}
    for name, var in dataset.variables.items():
        entry = {}
        if var.ndim and var.dtype.kind in "fiu":
            entry.update(zlib=True, complevel=4, shuffle=True)
        if name in no_fill:
            entry["_FillValue"] = None
        if entry:
            encoding[name] = entry
    buffer = io.BytesIO()
    dataset.to_netcdf(buffer, engine="h5netcdf", format="NETCDF4", encoding=encoding)
    return buffer.getvalue()


def _encoded(data: LabelledData):
    variables = {n: (d, v.astype(np.int8) if v.dtype == bool else v, cf_attributes(a))
                 for n, (d, v, a) in data.variables.items()}
    return cf.encode(data.replace(variables=variables, attrs=cf_attributes(data.attrs)))


def _hdf5(blob: bytes) -> dict:
    """{variable: (type, fill value, compression, level, shuffle, dimension names)}."""
    out = {}
    with h5py.File(io.BytesIO(blob), "r") as file:
        for name, item in file.items():
            if not isinstance(item, h5py.Dataset) or "_Netcdf4Dimid" in item.attrs and \
                    item.attrs.get("NAME", b"").startswith(b"This is a netCDF dimension"):
                continue
            fill = item.fillvalue
            dims = tuple(file[ref].name for dim in item.dims for ref in
                         ([dim[0].ref] if len(dim) else []))
            out[name] = (str(item.dtype), "nan" if fill != fill else repr(fill),
                         item.compression, item.compression_opts, item.shuffle, dims)
    return out


def _same_file(data: LabelledData, folder) -> None:
    """upliftlab's file of ``data`` (through write_dataset) against xarray's."""
    encoded, no_fill = _encoded(data)
    ours = write_dataset(folder / "ours.nc", data).read_bytes()
    assert ours == netcdf_bytes(encoded, no_fill)
    theirs = _xarray_bytes(encoded, no_fill)
    opened = [xr.load_dataset(io.BytesIO(b), engine="h5netcdf", decode_cf=False)
              for b in (ours, theirs)]
    xr.testing.assert_identical(*opened)
    assert list(opened[0].variables) == list(opened[1].variables)
    assert _hdf5(ours) == _hdf5(theirs)


@pytest.fixture(scope="module")
def dynamic_data() -> LabelledData:
    scene = load_scene("strip_footing_clay", overrides=("continuum.elements_across=2",))
    t = np.arange(11) * 0.005
    motion = Motion("half sine", 0.005, 0.1 * np.sin(np.pi * t / t[-1]), source="builtin")
    result = run_dynamic(build_model(scene), scene, motion, DynamicOptions(snapshots=3),
                         progress=False)
    return labelled_data(result)


def test_a_continuum_runs_file_is_the_file_xarray_writes(dynamic_data, tmp_path):
    assert {"time", "component", "far_field_shear_strain", "displacement"} <= set(
        dynamic_data.variables)
    _same_file(dynamic_data, tmp_path)


def test_what_a_run_lacks_is_written_as_xarray_writes_it(tmp_path):
    data = LabelledData.build(
        {"peak": ((), 2.5, {"units": "m"}),
         "field": (("row", "col"), np.arange(6.0).reshape(2, 3), {"units": "Pa"}),
         "note": ("row", np.array(["a", "bé"]), {"long_name": "text data"}),
         "flag": ("col", np.array([True, False, True]), {}),
         "count": ("col", np.array([1, 2, 3], np.int64), {"units": "1"}),
         "level": ("level", np.arange(1, 3), {"units": "1"}),
         "drift": ("level", [0.1, 0.2], {"units": "1"})},
        coords={"row": ("row", [0.5, 1.5], {"units": "m"}),
                "grid": (("row", "col"), np.ones((2, 3)), {"units": "m"}),
                "case": ("case", ["x", "y", "z", "w"], {"long_name": "cases"}),
                "lonely": ("other", [1.0, 2.0], {"units": "s"})},
        attrs={"title": "hand-made", "numbers": [1.0, 2.0], "names": ["a", "b"]})
    _same_file(data, tmp_path)
    back = read_dataset(tmp_path / "ours.nc")
    assert back["flag"].dtype == np.int8 and back["count"].dtype == np.int64  # NetCDF: no bool


def test_a_saved_run_reads_back_as_its_dataset(tmp_path, dynamic_data):
    """Round trip through the file (the reading side is xarray's): the values, types and units
    of every variable come back as the labelled data held them (its flags already int8)."""
    path = write_dataset(tmp_path / "result.nc", dynamic_data)
    back = read_dataset(path)
    for name, (dims, values, attrs) in dynamic_data.variables.items():
        assert back[name].dims == dims
        np.testing.assert_array_equal(back[name].values, values)
        assert back[name].dtype == values.dtype or values.dtype.kind == "U"
        assert back[name].attrs.get("units") == attrs.get("units")


@pytest.mark.parametrize("variables, message", [
    ({"a": (("n",), np.arange(3.0), {}), "b": (("n",), np.arange(4.0), {})},
     "dimension 'n' is 3 and 4"),
    ({"a": (("n", "m"), np.arange(3.0), {})}, "variable 'a': 2 dims for shape (3,)"),
    ({"a": (("n",), np.array([1 + 2j]), {})}, "variable 'a': values of type complex128"),
    ({"a": (("n",), np.array([object()]), {})}, "variable 'a': objects other than text")])
def test_data_a_netcdf_file_cannot_hold_is_refused_before_writing(variables, message):
    # Reference: the record's own rules (LabelledData's docstring): one length per dimension,
    # as many dimensions as the values have, numbers, booleans or text only.
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        LabelledData(variables)
