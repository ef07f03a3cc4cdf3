"""Rocking pushovers of the bed and the two-spring layouts against their closed forms
(anchors §2–3): uplift onset, capacity and the ultimate moment."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ....anchors import WINKLER_ONSET_ECCENTRICITY, ultimate_moment_ratio
from ....reduced import build_model, rocking_pushover, uplift_onset_force
from .grid import Options, STATIC_MOTION
from .points import Base, make_point, point_scene


# ---------------------------------------------------------------------------------------------
# Statics
# ---------------------------------------------------------------------------------------------


def static_model(base: Base, bed, layout, springs, options, law):
    point = make_point(base, bed=bed, layout=layout, springs=springs, options=options, case="B",
                       motion=STATIC_MOTION)
    point["foundation"]["law"] = law
    return build_model(point_scene(point))


def _rigid_plastic_moment(model, fs: float) -> float:
    """Limit moment of a rigid base on springs that yield at FS_v × their static force
    (force·length): the compressed side carries the weight at yield from the edge inward."""
    found = model.foundation_slice
    x, f0 = model.params["x"][found], model.params["f0"][found]
    order = np.argsort(-x)
    left, moment = model.weight, 0.0
    for i in order:
        take = min(fs * f0[i], left)
        moment += take * x[i]
        left -= take
        if left <= 0.0:
            break
    return moment


def _static_layout(base, bed, layout, springs, options, thetas) -> dict:
    """One foundation's pushovers, normalised by N B (N the weight, B = 2b): ``onset``
    uplift-onset moment; ``capacity`` the elastic moment as θ → ∞ (beds: extrapolated in
    θ^(-1/2) from 100 and 400 θ_up); ``ultimate`` the elasto-plastic moment at the last θ
    (1000 θ_up); each with its closed form; the ``elastic`` and ``plastic`` backbones M/(N B)
    at ``thetas`` (θ/θ_up, θ_up = N/(K_v b)) and the spring ``positions`` x/b."""
    elastic = static_model(base, bed, layout, springs, options, "elastic")
    plastic = static_model(base, bed, layout, springs, options, "elastoplastic")
    w, b = elastic.weight, elastic.layout.half_width
    nb = w * 2.0 * b
    theta_up = w / (elastic.layout.vertical_stiffness * b)
    x = elastic.layout.positions
    onset = uplift_onset_force(elastic) * float(elastic.heights[-1]) / nb
    far = rocking_pushover(elastic, theta_up * np.array([100.0, 400.0])).moment / nb
    capacity = far[1] if x.size == 2 else 2.0 * far[1] - far[0]
    fs = base.yield_multiple
    if x.size == 2:
        onset_cf = capacity_cf = float(x[1]) / (2.0 * b)
        ultimate_cf = min(1.0, fs - 1.0) * onset_cf
    else:
        k, kv = elastic.layout.stiffnesses, elastic.layout.vertical_stiffness
        outer = float(np.max(x))
        onset_cf = (WINKLER_ONSET_ECCENTRICITY if bed == "uniform"
                    else float(np.sum(k * x**2)) / (kv * outer * 2.0 * b))
        capacity_cf = 0.5
        ultimate_cf = (ultimate_moment_ratio(fs) if bed == "uniform"
                       else _rigid_plastic_moment(plastic, fs) / nb)
    path = rocking_pushover(plastic, theta_up * thetas)
    return {"positions": x / b, "onset": onset, "onset_closed_form": onset_cf,
            "capacity": float(capacity), "capacity_closed_form": capacity_cf,
            "ultimate": float(path.moment[-1] / nb), "ultimate_closed_form": ultimate_cf,
            "elastic": rocking_pushover(elastic, theta_up * thetas).moment / nb,
            "plastic": path.moment / nb}


def compute_statics(base: Base, springs: int, options: Options, points: int):
    """Pushovers and closed forms of the beds and the two-spring layouts (anchors §2–3) at N =
    ``springs`` and the base's FS_v, as a labelled dataset (:func:`statics_dataset`)."""
    thetas = np.geomspace(0.05, 1000.0, points)
    rows = [("uniform bed", "uniform", "winkler"), ("end-stiffened bed", "end_stiffened",
                                                    "winkler"),
            ("edges", None, "edges"), ("equivalent", None, "equivalent"),
            ("calibrated (uniform)", "uniform", "calibrated"),
            ("calibrated (end-stiffened)", "end_stiffened", "calibrated")]
    found = {label: {**_static_layout(base, bed, layout, springs, options, thetas),
                     "bed": bed or "", "layout": layout}
             for label, bed, layout in rows}
    return statics_dataset(found, thetas, springs, base.yield_multiple)


#: The scalar results of each foundation, M/(N B), and what they mean.
SCALARS = {"onset": "uplift-onset moment", "capacity": "elastic moment as theta -> infinity",
           "ultimate": "elasto-plastic moment at the largest theta"}


def statics_dataset(found: Mapping, thetas, springs: int, yield_multiple: float):
    """The statics as a labelled dataset by ``foundation`` (its label: ``uniform bed``,
    ``edges``, …; with its ``bed`` and ``layout``): ``onset``, ``capacity``, ``ultimate`` and
    their ``*_closed_form`` (M/(N B)); the ``elastic`` and ``plastic`` backbones over
    ``theta_over_theta_up``; the spring ``position`` x/b over ``spring``, NaN beyond a
    foundation's own springs (two for a pair, N for a bed)."""
    import xarray as xr

    labels = list(found)
    width = max(len(f["positions"]) for f in found.values())
    position = np.full((len(labels), width), np.nan)
    for i, f in enumerate(found.values()):
        position[i, :len(f["positions"])] = f["positions"]
    one = ("foundation",)
    data = {}
    for key, meaning in SCALARS.items():
        data[key] = (one, np.array([f[key] for f in found.values()], float),
                     {"units": "1", "long_name": f"{meaning}, M/(N B)"})
        data[f"{key}_closed_form"] = (one, np.array([f[f"{key}_closed_form"]
                                                     for f in found.values()], float),
                                      {"units": "1", "long_name": f"{meaning}, closed form"})
    for which in ("elastic", "plastic"):
        data[which] = (("foundation", "theta_over_theta_up"),
                       np.array([f[which] for f in found.values()], float),
                       {"units": "1", "long_name": f"{which} springs' backbone, M/(N B)"})
    data["position"] = (("foundation", "spring"), position, {
        "units": "1", "long_name": "spring position x/b (NaN: no such spring)"})
    coords = {"foundation": ("foundation", labels, {"long_name": "foundation"}),
              "bed": ("foundation", [f["bed"] for f in found.values()],
                      {"long_name": "Winkler bed of the foundation (empty: none)"}),
              "layout": ("foundation", [f["layout"] for f in found.values()],
                         {"long_name": "layout of the springs"}),
              "theta_over_theta_up": ("theta_over_theta_up", np.asarray(thetas, float), {
                  "units": "1", "long_name": "rotation over theta_up = N/(K_v b)"})}
    attrs = {"Conventions": "CF-1.10", "title": "rocking pushovers of every foundation",
             "springs": int(springs), "yield_multiple": float(yield_multiple)}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def positions(ds, label: str) -> tuple[float, ...]:
    """The spring positions x/b of foundation ``label``."""
    x = ds.position.sel(foundation=label).values
    return tuple(float(v) for v in x[np.isfinite(x)])


def of(ds, label: str, key: str) -> float:
    """One scalar result (``onset``, ``capacity_closed_form``, …) of foundation ``label``."""
    return float(ds[key].sel(foundation=label))


def onset_ratio(ds) -> float:
    """Uplift-onset moment, equivalent springs over the uniform bed (anchor 1.73)."""
    return of(ds, "equivalent", "onset") / of(ds, "uniform bed", "onset")


def capacity_ratio(ds) -> float:
    """Capacity as θ → ∞, equivalent springs over the uniform bed (anchor 0.58)."""
    return of(ds, "equivalent", "capacity") / of(ds, "uniform bed", "capacity")


def within(ds, label: str, threshold: float, which: str = "elastic") -> float:
    """Largest θ/θ_up up to which ``label``'s backbone stays within ``threshold`` of the
    uniform bed's (0 if not even at the first point)."""
    mine = ds[which].sel(foundation=label).values
    ref = ds[which].sel(foundation="uniform bed").values
    bad = np.abs(mine - ref) > threshold * np.abs(ref)
    first = int(np.argmax(bad)) if bad.any() else mine.size
    return float(ds.theta_over_theta_up.values[first - 1]) if first > 0 else 0.0
