"""The study's data: an :class:`xarray.DataTree` of labelled datasets with CF attributes, one
node per file it writes. ``convergence`` (the bed in N), ``statics`` (the rocking pushovers
of every foundation by ``foundation``, and the study's own attributes) and one node per error
map (``map_aspect``, …), each over its own parameters, so that
``tree["map_aspect"].error.sel(case="C", layout="edges", measure="u", h_over_b=4.0)`` selects
by label. :func:`upliftlab.open_study` of the study's folder gives the same tree back; its
readers are in :mod:`.views`."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ....results import cf_attributes
from ....units import unit_system
from ...framework.study import ascii_text
from .grid import FLOOR_FRACTION, METRIC_LABELS, METRICS, STUDY
from .views import CONVERGENCE, MAP_PREFIX, STATICS, maps

__all__ = ["measure_units", "convergence_dataset", "map_dataset", "study_tree", "error_frame"]

#: The dimensions every map has besides its two axes.
_FIXED_DIMENSIONS = ("case", "layout", "measure")


def measure_units(units: str) -> dict[str, str]:
    """The unit of each compared measure (:data:`METRICS`) in the scene's unit system."""
    u = unit_system(units)
    return {"u": u.length, "theta": "rad", "uplift": u.length, "residual_settlement": u.length,
            "base_shear": u.force, "dissipated_energy": f"{u.force}*{u.length}"}


def convergence_dataset(check: Mapping, units: str):
    """The convergence check in N as a labelled dataset over ``springs``. ``check``: the
    ``candidates`` (N), the chosen ``springs``, ``converged``, ``tolerance`` and
    ``static_tolerance``, the ``static`` {measure: values per N} and ``dynamic`` {case:
    {measure: values per N}} measures, the ``changes`` {"static" | case: change per doubling}
    and the ``motion`` (text), as :mod:`.convergence` decides them."""
    import xarray as xr

    unit_of = measure_units(units)
    springs = ("springs",)
    data = {f"static_{key}": (springs, np.array(values, dtype=float), {
        "units": "1", "long_name": f"{key} of the uniform bed, M/(N B)"})
        for key, values in check["static"].items()}
    for case, measures in check["dynamic"].items():
        for m, values in measures.items():
            data[f"case_{case}_{m}"] = (springs, np.array(values, dtype=float), {
                "units": unit_of[m],
                "long_name": f"Case {case}: {METRIC_LABELS.get(m, m)}"})
    coords = {"springs": (springs, np.array(check["candidates"]),
                          {"units": "1", "long_name": "number of springs in the bed"})}
    attrs = {"Conventions": "CF-1.10", "title": f"{STUDY}: convergence of the Winkler bed in N",
             "chosen_springs": check["springs"], "converged": check["converged"],
             "changes": check["changes"], "motion": ascii_text(check["motion"]),
             "motion_label": check["motion"], "tolerance": check["tolerance"],
             "static_tolerance": check["static_tolerance"]}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


def map_dataset(spec, arrays: Mapping, units: str):
    """An error map as a labelled dataset. ``spec``: the map's ``name``, ``title``, axes ``x``
    and ``y`` (:class:`~..framework.study.Axis`), ``bed`` and ``cases``; ``arrays``: ``errors``
    and ``values`` (case, layout, measure, y, x), ``reference`` (case, measure, y, x),
    ``uplifted`` (case, y, x), ``failures`` and ``energy_balance_error``. Variables: ``error``
    over (case, layout, measure) and the map's two axes, each named after its parameter
    (``h_over_b``, ``intensity``, ``pulse_period``, ``period``, ``yield_multiple``,
    ``restitution``, ``record``) with its values and units; the two-spring values and the bed's
    reference per measure with its units (``value_u``, ``reference_u``); ``uplifted``. The
    title is ``title`` (ASCII) and ``heading`` (as the summary writes it)."""
    import xarray as xr

    unit_of = measure_units(units)
    x, y = spec.x, spec.y
    if x.key == y.key or x.key in _FIXED_DIMENSIONS or y.key in _FIXED_DIMENSIONS:
        raise ValueError(f"map {spec.name!r}: axes {x.key!r} and {y.key!r} must be distinct "
                         f"dimension names, none of {_FIXED_DIMENSIONS}")
    numeric_y = all(isinstance(v, (int, float)) for v in y.values)
    layouts = arrays["layouts"]
    coords = {
        "case": ("case", list(spec.cases), {"long_name": "foundation model (Case A, B or C)"}),
        "layout": ("layout", list(layouts), {"long_name": "two-spring layout"}),
        "measure": ("measure", list(METRICS), {"long_name": "measure compared"}),
        x.key: (x.key, np.array(x.values, dtype=float), _axis_attributes(x.label, x.unit)),
        y.key: (y.key, np.array(y.values, dtype=float) if numeric_y
                else [str(v) for v in y.values], _axis_attributes(y.label, y.unit)),
    }
    dims = ("case", "layout", "measure", y.key, x.key)
    data = {
        "error": (dims, arrays["errors"], {
            "units": "1", "long_name": "(two-spring - bed)/max(|bed|, floor); NaN: run failed"}),
        "uplifted": (("case", y.key, x.key), arrays["uplifted"].astype(np.int8), {
            "long_name": "the bed separated", "flag_values": np.array([0, 1], np.int8),
            "flag_meanings": "in_contact uplifted"}),
    }
    for k, m in enumerate(METRICS):
        label = METRIC_LABELS[m]
        data[f"value_{m}"] = (("case", "layout", y.key, x.key), arrays["values"][:, :, k], {
            "units": unit_of[m], "long_name": f"{label} of the two springs"})
        data[f"reference_{m}"] = (("case", y.key, x.key), arrays["reference"][:, k], {
            "units": unit_of[m], "long_name": f"{label} of the Winkler bed ({spec.bed})"})
    attrs = {"Conventions": "CF-1.10", "title": ascii_text(spec.title), "heading": spec.title,
             "bed": spec.bed, "floor_fraction": FLOOR_FRACTION,
             "failures": list(arrays["failures"]),
             "energy_balance_error": arrays["energy_balance_error"]}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


#: The axes' units that UDUNITS knows (CF section 3.1); any other is a named quantity.
_CF_UNITS = ("s",)


def _axis_attributes(label: str, unit: str) -> dict:
    """An axis's ``long_name`` and CF ``units``: seconds as ``s``; a multiple of a named
    quantity (``× a_up``), which UDUNITS does not know, as the ratio it is (``1``) with the
    quantity named in the long name (``intensity in units of a_up``); ``1`` for a plain
    number or a label."""
    text = ascii_text(unit).strip().lstrip("x×* ").strip()
    if text and text not in _CF_UNITS:
        return {"long_name": f"{ascii_text(label)} in units of {text}", "units": "1"}
    return {"long_name": ascii_text(label), "units": text or "1"}


def study_tree(convergence, statics, error_maps, attrs: Mapping):
    """The study's :class:`xarray.DataTree`: the ``convergence`` and ``statics`` datasets and
    the ``error_maps`` {name: dataset}; ``attrs`` (the study's own: base scene, threshold,
    fast, record note) go on the statics node, with the maps' order (``maps``)."""
    import xarray as xr

    own = cf_attributes({**attrs, "maps": list(error_maps)})
    nodes = {CONVERGENCE: convergence, STATICS: statics.assign_attrs(own)}
    nodes.update({MAP_PREFIX + name: ds for name, ds in error_maps.items()})
    return xr.DataTree.from_dict(nodes, name=STUDY)


def error_frame(tree):
    """Every map's errors in long form, one row per (map, case, layout, measure and the map's
    two parameters), as a :class:`pandas.DataFrame` (column ``error``, relative; one column per
    parameter, ``h_over_b``, ``intensity``, …, empty where a map has no such axis)."""
    import pandas as pd

    frames = [ds.error.to_dataframe().reset_index().assign(map=ds.attrs["name"])
              for ds in maps(tree)]
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()
