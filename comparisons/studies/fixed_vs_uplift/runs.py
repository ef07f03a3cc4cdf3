"""The study's reduced runs: Figs. 11–12 with histories, and the spectrum's batch of runs,
each kept in the study's store."""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence

from ....motions import ELCENTRO, find_motion
from ....reduced import run as run_reduced
from ....reduced.batch import run_batch
from ....scenes import Scene, load_scene, scene_from_dict
from ...framework.freshness import check_stale, stale_keys
from ...framework.store import POINT_FUNCTIONS, Store, point_function, point_key, record_meta
from ...framework.study import file_sha256
from .grid import BUILDINGS, Grid, OUTPUT_DT, STUDY


# ---------------------------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------------------------


def building_scene(building: str, support: str) -> Scene:
    return load_scene(BUILDINGS[building], case=support)


def elcentro_entry() -> dict:
    path = find_motion(ELCENTRO)
    return {"motion_sha256": file_sha256(path), "_motion_path": str(path.resolve())}


def point_scene(point: Mapping) -> Scene:
    data = copy.deepcopy(point["scene"])
    if "period" in point:
        data["structure"].pop("stiffness", None)
        data["structure"]["period"] = point["period"]
    if "_motion_path" in point:
        data["motion"]["name"] = point["_motion_path"]
    return scene_from_dict(data, merged=True)


@point_function("upliftlab.comparisons.fixed_vs_uplift:figure_run", models=("reduced",))
def figure_run(point: Mapping) -> dict:
    """One run of Figs. 11–12 with histories: time (s), u (length) and the peaks."""
    response = run_reduced(point_scene(point), output_dt=OUTPUT_DT)
    pk = response.peaks
    return {"time": response.time.tolist(), "u": response.u.tolist(), "peak_u": pk["u"],
            "base_shear": pk["base_shear"], "theta": pk["theta"],
            "uplift": pk.get("uplift_max", 0.0),
            "weight": response.model.scene.structure.weight}


def cached_run(store: Store, name: str, params: dict):
    """The record of point function ``name`` (of this module) at ``params``: from the store
    (checked first if earlier code made it, :func:`.freshness.check_stale`), or computed and
    stored if missing."""
    declared = POINT_FUNCTIONS[f"upliftlab.comparisons.fixed_vs_uplift:{name}"]
    key = point_key(STUDY, declared, params)
    if stale_keys(store, [key]):
        check_stale(store, declared, {key: params})
    record = store.get(key)
    if record is None:
        record = globals()[name](params)
        store.put(key, record, record_meta(STUDY, declared, params))
    return record


def figure_records(building: str, store: Store, record: dict) -> dict:
    """The runs of the figure of ``building`` (Fig. 11 or 12), fixed base and Case C:
    {support: the record of :func:`figure_run`}."""
    return {s: cached_run(store, "figure_run", {"scene": building_scene(building, s).data,
                                                **record})
            for s in ("fixed", "C")}


def spectrum_points(grid: Grid, record: dict) -> list[dict]:
    """One point per family, support and period: the scene table (period replaced)."""
    points = []
    for family in grid.families:
        for support in grid.supports:
            data = building_scene(family, support).data
            for t in grid.periods:
                points.append({"scene": data, "period": float(t), **record,
                               "family": family, "support": support})
    return points


def run_spectrum_batch(points: Sequence[Mapping], workers: int | None) -> list[dict]:
    scenes = [point_scene(p) for p in points]
    result = run_batch(scenes, workers=workers)
    out = []
    for i, (p, s) in enumerate(zip(points, scenes)):
        row = result.row(i)
        if row["status"] != "ok":
            out.append({"error": row["status"]})
            continue
        out.append({"u": row["u"], "base_shear": row["base_shear"], "theta": row["theta"],
                    "uplift": row["uplift_left"], "weight": s.structure.weight,
                    "dt": row["dt"], "energy_balance_error": row["energy_balance_error"]})
    return out


@point_function("upliftlab.comparisons.fixed_vs_uplift:spectrum_point", models=("reduced",))
def spectrum_point(point: Mapping) -> dict:
    """One point of the spectrum, as the batch makes it (:func:`run_spectrum_batch`)."""
    return run_spectrum_batch([point], 1)[0]


def spectrum_records(points, store: Store, workers) -> list[dict]:
    """The spectrum's records: stored ones (checked first if earlier code made them), the
    others made in one batch on ``workers`` processes and stored."""
    keys = [point_key(STUDY, spectrum_point, p) for p in points]
    old = set(stale_keys(store, keys))
    stale = {k: p for k, p in zip(keys, points) if k in old}
    if stale:
        check_stale(store, spectrum_point, stale, evaluate=lambda f, items: list(zip(
            [k for k, _ in items], run_spectrum_batch([p for _, p in items], workers))))
    todo = [i for i, k in enumerate(keys) if not store.has(k)]
    if todo:
        for i, record in zip(todo, run_spectrum_batch([points[i] for i in todo], workers)):
            store.put(keys[i], record, record_meta(STUDY, spectrum_point, points[i]))
    return [store.get(k) for k in keys]
