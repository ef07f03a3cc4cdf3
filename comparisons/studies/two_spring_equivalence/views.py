"""Reading the study's data (:mod:`.dataset`), in memory or opened from its folder by
:func:`upliftlab.open_study`: the study's attributes, its maps in order, a map's axes and its
errors, the convergence check. NetCDF gives a one-element list attribute back as a scalar and
booleans as 0/1; these functions read either form."""

from __future__ import annotations

import numpy as np

from ...framework.study import Axis
from .grid import AXES, CASES, METRICS

#: The node of the statics; its attributes also hold the study's own (:func:`study_attrs`).
STATICS = "statics"
#: The node of the convergence check in N.
CONVERGENCE = "convergence"
#: The prefix of each map's node (``map_aspect``).
MAP_PREFIX = "map_"


def as_list(value) -> list:
    """An attribute written as a list, as a list ("" and None: empty)."""
    if value is None or (isinstance(value, str) and value == ""):
        return []
    if isinstance(value, str):
        return [value]
    return [v.item() if isinstance(v, np.generic) else v for v in np.atleast_1d(value)]


def axis(key: str, values) -> Axis:
    """The map parameter ``key`` (:data:`.grid.AXES`) over ``values``."""
    label, unit = AXES[key]
    return Axis(key, label, tuple(v.item() if isinstance(v, np.generic) else v for v in values),
                unit)


def study_attrs(tree) -> dict:
    """The study's attributes: ``scene``, ``h_over_b``, ``period`` (s) and ``yield_multiple``
    of the base scene, ``threshold``, ``fast``, ``record_note``, ``maps`` (their order) and
    ``springs`` (the converged N), read from the statics node."""
    attrs = dict(tree[STATICS].attrs)
    attrs["maps"] = as_list(attrs.get("maps"))
    attrs["fast"] = bool(attrs.get("fast", 0))
    return attrs


def maps(tree) -> list:
    """The error maps in the study's order, each an :class:`xarray.Dataset` with its ``name``
    attribute (``aspect``, …)."""
    out = []
    for name in study_attrs(tree)["maps"]:
        ds = tree[MAP_PREFIX + name].to_dataset()
        out.append(ds.assign_attrs(name=name))
    return out


def map_axes(ds) -> tuple[Axis, Axis]:
    """(x, y): the map's two parameter axes, the last two dimensions of its ``error``."""
    y, x = ds.error.dims[-2:]
    return axis(x, ds[x].values), axis(y, ds[y].values)


def cases(ds) -> list[str]:
    return [str(c) for c in ds.case.values]


def layouts(ds) -> list[str]:
    return [str(k) for k in ds.layout.values]


def error(ds, case: str, layout: str, metric: str = "all") -> np.ndarray:
    """|error| of one case and layout on the map's (y, x) grid; ``all`` is the largest over
    the six measures (NaN where a run failed)."""
    e = np.abs(ds.error.sel(case=case, layout=layout).transpose("measure", ...).values)
    return e.max(axis=0) if metric == "all" else e[METRICS.index(metric)]


def uplifted(ds, case: str) -> np.ndarray:
    """Whether the bed separated, on the (y, x) grid."""
    return ds.uplifted.sel(case=case).values.astype(bool)


def heading(ds) -> str:
    """The map's title in text (Unicode)."""
    return str(ds.attrs["heading"])


def failures(ds) -> list[str]:
    return [str(f) for f in as_list(ds.attrs.get("failures"))]


def convergence(tree) -> dict:
    """The convergence check as plain values: ``candidates`` (N), ``springs`` (the chosen N),
    ``converged``, ``tolerance``, ``static_tolerance``, ``static`` {measure: values per N},
    ``dynamic`` {case: {measure: values per N}}, ``changes`` {"static" | case: the largest
    relative change from each N to the next} and ``motion`` (text)."""
    ds = tree[CONVERGENCE].to_dataset()
    attrs = ds.attrs
    found = [c for c in CASES if f"case_{c}_{METRICS[0]}" in ds]
    static = {str(k)[len("static_"):]: ds[k].values.tolist() for k in ds.data_vars
              if str(k).startswith("static_")}
    keys = ["static", *found]
    return {"candidates": tuple(int(n) for n in ds.springs.values),
            "springs": int(attrs["chosen_springs"]), "converged": bool(attrs["converged"]),
            "tolerance": float(attrs["tolerance"]),
            "static_tolerance": float(attrs["static_tolerance"]), "static": static,
            "dynamic": {c: {m: ds[f"case_{c}_{m}"].values.tolist() for m in METRICS}
                        for c in found},
            "changes": {k: [float(v) for v in as_list(attrs[f"changes_{k}"])] for k in keys},
            "motion": str(attrs["motion_label"])}
