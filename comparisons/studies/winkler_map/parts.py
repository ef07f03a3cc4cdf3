"""The map's data read back, as the analysis, the summary and the figures read it: the ``map``
and ``statics`` datasets of the map's :class:`xarray.DataTree` (as computed, or opened again
from its folder by :func:`upliftlab.open_study`), arrays of its variables in point order, its
options and estimate, and the per-soil records its statics dataset holds."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np

from ...framework.study import ascii_text
from .cost import Estimate
from .rocking import QUANTITY_GROUPS, group_worst

__all__ = ["POINT_DIMS", "map_of", "statics_of", "Statics", "soil_statics_of", "impedances_of",
           "capacity_fits_of", "worst_statics", "labels", "point_array", "point_values",
           "errors_of", "bearing_failures", "options_of", "estimate_of", "texts", "names"]

#: The dimensions of a map point (one continuum run and each bed's run of it).
POINT_DIMS = ("soil", "fs_v", "h_over_B", "period", "intensity", "motion")


def map_of(tree):
    """The ``map`` dataset of the map's tree."""
    return tree["map"].to_dataset()


def statics_of(tree):
    """The ``statics`` dataset of the map's tree."""
    return tree["statics"].to_dataset()


def labels(ds, dim: str) -> list[str]:
    """The text labels of dimension ``dim`` (soil, motion, calibration)."""
    return [str(v) for v in ds[dim].values]


@dataclass(frozen=True)
class Statics:
    """One soil's continuum statics as the statics dataset holds them: K_v (kN/m/m), K_r
    (kN m/rad/m), V_ult (kN/m), the pushover's last-step ``plateau`` (1), ``dofs`` and the two
    runs' ``wall_time_s`` (s)."""

    soil: str
    K_v: float
    K_r: float
    V_ult: float
    plateau: float
    dofs: int
    wall_time_s: float


def soil_statics_of(st) -> list[Statics]:
    """Every soil's :class:`Statics` of the statics dataset ``st``, in its soil order."""
    return [Statics(soil, float(st.K_v.values[s]), float(st.K_r.values[s]),
                    float(st.V_ult.values[s]), float(st.plateau.values[s]),
                    int(st.dofs.values[s]), float(st.wall_time.values[s]))
            for s, soil in enumerate(labels(st, "soil"))]


def impedances_of(st) -> dict:
    """{soil: {a0, omega, C_v, C_r (arrays), dofs, wall_time_s}} of the continuum's impedance
    in the statics dataset ``st`` ({} when no bed needed it)."""
    if "impedance_a0" not in st:
        return {}
    out = {}
    for s, soil in enumerate(labels(st, "soil")):
        a0 = st.impedance_a0.values[s]
        keep = np.isfinite(a0)
        wall = float(st.impedance_wall_time.values[s])
        out[soil] = {"a0": a0[keep], "omega": st.impedance_omega.values[s][keep],
                     "C_v": st.impedance_dashpot_v.values[s][keep],
                     "C_r": st.impedance_dashpot_r.values[s][keep],
                     "dofs": int(st.impedance_dofs.values[s]),
                     "wall_time_s": wall if math.isfinite(wall) else None}
    return out


def capacity_fits_of(st) -> dict:
    """{(soil, fs_v): (β, misfit)} of the fitted bed (when it is compared; else {})."""
    if "capacity_beta" not in st:
        return {}
    out = {}
    for s, soil in enumerate(labels(st, "soil")):
        for f, fs in enumerate(st.fs_v.values.tolist()):
            beta = float(st.capacity_beta.values[s, f])
            if math.isfinite(beta):
                out[soil, fs] = (beta, float(st.capacity_misfit.values[s, f]))
    return out


def worst_statics(st) -> np.ndarray:
    """(soil, calibration, group) the largest |error| of each bed's rocking pushovers over FS_v
    and each group's quantities, the groups in :data:`.rocking.QUANTITY_GROUPS` order."""
    errors = st.rocking_error.transpose("soil", "fs_v", "calibration", "statics_quantity")
    groups = [str(g) for g in st.statics_group.values]
    return group_worst(np.asarray(errors.values), groups,
                       [ascii_text(name) for name in QUANTITY_GROUPS])


def point_array(da, *last: str) -> np.ndarray:
    """The values of the :class:`xarray.DataArray` ``da`` as an array in :data:`POINT_DIMS`
    order (those it has) followed by ``last`` (e.g. ``"calibration", "measure"``)."""
    dims = [d for d in POINT_DIMS if d in da.dims] + list(last)
    return np.asarray(da.transpose(*dims).values)


def point_values(ds, name: str, *last: str) -> np.ndarray:
    """:func:`point_array` of variable ``name`` of the map dataset ``ds``."""
    return point_array(ds[name], *last)


def texts(value) -> tuple[str, ...]:
    """A list of texts as an attribute holds it (one item is a plain string, none the empty
    one)."""
    if isinstance(value, str):
        return (value,) if value else ()
    return tuple(str(v) for v in np.asarray(value).ravel())


def _numbers(value) -> tuple[float, ...]:
    return tuple(float(v) for v in np.atleast_1d(value))


def options_of(ds) -> dict:
    """The options that made the map (``options_*`` attributes), numbers and tuples as the
    :class:`.grid.Options` record holds them."""
    a = ds.attrs
    return {"elements_across": int(a["options_elements_across"]),
            "springs": int(a["options_springs"]),
            "settlement_ratio": float(a["options_settlement_ratio"]),
            "theta_ratios": _numbers(a["options_theta_ratios"]),
            "cycle_ratios": _numbers(a["options_cycle_ratios"]),
            "theta_tolerance": float(a["options_theta_tolerance"]),
            "settlement_tolerance": float(a["options_settlement_tolerance"]),
            "figures": bool(a["options_figures"]),
            "reference": str(a.get("options_reference", "box"))}


def estimate_of(ds) -> Estimate:
    """The :class:`.cost.Estimate` made before the work (``estimate_*`` attributes)."""
    a = ds.attrs
    by_soil = a["estimate_by_soil"]
    return Estimate(int(a["estimate_runs"]), int(a["estimate_static"]),
                    int(a["estimate_dynamic"]), int(a["estimate_stored"]),
                    float(a["estimate_seconds"]),
                    json.loads(by_soil) if isinstance(by_soil, str) else dict(by_soil),
                    float(a["estimate_per_run"]), str(a["estimate_source"]),
                    int(a["estimate_checks"]), float(a["estimate_check_seconds"]))


def errors_of(ds) -> np.ndarray:
    """The signed errors (soil, fs_v, h_over_B, period, intensity, motion, calibration,
    measure) of the map dataset ``ds``."""
    return point_values(ds, "error", "calibration", "measure")


def bearing_failures(ds) -> tuple[np.ndarray, np.ndarray]:
    """(continuum (…, motion), bed (…, motion, calibration)): where the continuum's run ended
    in a bearing failure of the soil, and where a bed's base settled by the failure settlement
    too (booleans)."""
    return (point_values(ds, "continuum_bearing_failure").astype(bool),
            point_values(ds, "bed_bearing_failure", "calibration").astype(bool))


def names(ds, dim: str) -> tuple:
    """The labels of dimension ``dim`` of ``ds`` (str for text, float for numbers)."""
    values = ds[dim].values.tolist()
    return tuple(str(v) if isinstance(v, (str, bytes)) else float(v) for v in values)
