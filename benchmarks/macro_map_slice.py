"""The macro-element on the pulse points of one slice of the half-plane map, beside the map's
beds on the same points (issue 36 §3: a first slice, before the whole map).

    python benchmarks/macro_map_slice.py --map DIR/map.nc [--calibration JSON] [--quick]
                                         [--out DIR] [--write]

``--map``: the map's dataset of the slice, made by ``upliftlab study winkler_map --reference
half_plane --store benchmarks/winkler_map_halfplane_store --grid h_over_B=1.5 --grid
periods=0.5 --grid fema_components=0 --grid elcentro=false`` (its continuum runs all read from
the kept store; the beds run live): it holds the continuum's measures, their error floors and
every bed's errors at each point. For each point the reduced model runs the point's structure
(the map's, :func:`~upliftlab.comparisons.studies.winkler_map.points.point_table`) on the
macro-element calibrated to the soil's statics (``--calibration``, default
``benchmarks/macro_calibration.json``: fitted to the half-plane store's rotation pushovers,
nothing dynamic), with the footing's sway tie and the soil's Rayleigh damping as the beds have
them (the tie's spring and dashpot; the element's dashpot density β K_v/B, a uniform bed's
β k(x)), under the point's Ricker pulse. Its error in each measure is the map's: relative, with
the map's floor (a tenth of the measure at the uplift threshold). The table gives, per soil and
all together, the share of the points within 10 % in both peak θ and edge uplift and within
20 % in residual settlement, and the median error per measure, for the macro-element and for
every bed. ``--quick`` (the tests' path): the clay at FS_v 3 only.

Cost model: each macro-element run about 5 s (a pulse of 3T + 2 s at the element's ~300 µs a
step); 32 points about 3 min. Writes ``MACRO_MAP_SLICE.md`` to ``--out`` (default
``results/bench/macro_map_slice``); ``--write`` also the committed table.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, output_folder,  # noqa: E402
                          run_sections, write_text)

NAME = "macro_map_slice"
SOIL_KEYS = {"clay": "clay", "sand": "sand"}
PLASTIC = ("initial_size", "hardening_settlement", "interior_modulus", "interior_exponent",
           "settlement_coupling", "rounding_ratio", "sliding_ratio")


def foundation(law_fields: dict, point: dict, g: float) -> dict:
    """The ``[foundation]`` of the macro-element under a point's structure (module
    docstring)."""
    from upliftlab.comparisons.studies.winkler_map.bed_runs import bed_sway
    from upliftlab.comparisons.studies.winkler_map.points import point_scene
    from upliftlab.continuum.dynamics.rayleigh import scene_rayleigh
    from upliftlab.reduced.laws.macro import MacroElement

    law = MacroElement(**law_fields)
    table = point["scene"]
    W = table["structure"]["vertical_weight"]
    V_ult = law.ultimate_load
    beta = scene_rayleigh(point_scene(point)).beta
    omega_v = math.sqrt(law.vertical_stiffness * g / W)
    f = {"support": "uplift", "half_width": 0.5 * law.width, "layout": "winkler",
         "springs": 20, "stiffness": law.vertical_stiffness, "law": "macro",
         "rocking_stiffness": law.rocking_stiffness, "capacity_multiple": V_ult / W,
         "frictional_share": law.frictional_modulus * law.width ** 2 / V_ult,
         "damping_ratio": 0.5 * beta * omega_v,
         **{k: float(getattr(law, k)) for k in PLASTIC},
         **bed_sway(table.get("continuum", {}))}
    return f


def run_point(law_fields: dict, point: dict, g: float) -> dict:
    """The macro-element's measures at ``point`` (the map's, :func:`measured`), its wall time
    (s) or why it was refused."""
    import copy

    from upliftlab.comparisons.studies.winkler_map.points import measured, motion_table
    from upliftlab.reduced import IntegrationError, run
    from upliftlab.scenes import scene_from_dict

    data = copy.deepcopy(point["scene"])
    data["foundation"] = foundation(law_fields, point, g)
    B = 2.0 * data["foundation"]["half_width"]
    data["motion"] = motion_table(point["motion"], point["intensity"], B,
                                  data["structure"]["height"])
    for table in ("soil", "continuum"):
        data.pop(table, None)
    scene = scene_from_dict(data, merged=True)
    started = time.perf_counter()
    try:
        response = run(scene, histories=True)
    except (IntegrationError, RuntimeError) as exc:
        return {"refused": " ".join(str(exc).split())}
    t = np.asarray(response.time, dtype=float)
    out = measured(t - t[0], response.theta, response.peaks["uplift_max"],
                   np.asarray(response.settlement, dtype=float),
                   max(float(np.max(np.abs(response.u))), float(response.peaks["u"])),
                   np.max(np.abs(response.base_shear)))
    out["theta"] = max(out["theta"], float(response.peaks["theta"]))
    return {"measures": out, "wall_time_s": time.perf_counter() - started}


def points_of(ds, grid_motions, quick: bool):
    """(index, point) of every point of the map dataset ``ds`` (its scene table and motion)."""
    from upliftlab.comparisons.beds import base_table
    from upliftlab.comparisons.studies.winkler_map.points import point_table

    base = base_table()
    g = 9.80665
    for i, soil in enumerate(ds["soil_label"].values):
        for j, fs in enumerate(ds["fs_v"].values):
            if quick and (soil != "clay" or fs != 3.0):
                continue
            for k, intensity in enumerate(ds["intensity"].values):
                for m, motion in enumerate(grid_motions):
                    N = float(ds["vertical_load"].values[i, j])
                    if not np.isfinite(N):
                        continue
                    table = point_table(base, str(soil), 16, N,
                                        float(ds["h_over_B"].values[0]),
                                        float(ds["period"].values[0]), g, "half_plane")
                    yield (i, j, k, m), {"scene": table, "motion": motion,
                                         "intensity": float(intensity)}


def compute(args) -> dict:
    import xarray as xr

    from upliftlab.comparisons.framework.study import relative_error
    from upliftlab.comparisons.studies.winkler_map.grid import MEASURES

    ds = xr.load_dataset(args.map)
    laws = json.loads(Path(args.calibration).read_text())
    from upliftlab.comparisons.studies.winkler_map.grid import Options

    tail = Options().pulse_tail
    periods = [float(str(label).split("_T")[1].rstrip("s")) for label in ds["motion_label"].values]
    motions = [{"type": "ricker", "name": f"ricker_T{T:g}s", "kind": "ricker", "period": T,
                "duration": 3.0 * T + tail} for T in periods]
    shape = ds["error"].shape[:6] + (len(MEASURES),)
    errors = np.full(shape, np.nan)
    values = np.full(shape, np.nan)
    refused, walls = [], []
    for (i, j, k, m), point in points_of(ds, motions, args.quick):
        soil = str(ds["soil_label"].values[i])
        out = run_point(laws[SOIL_KEYS[soil]]["law"], point, 9.80665)
        if "refused" in out:
            refused.append(f"{soil}, FS_v {ds['fs_v'].values[j]:g}, "
                           f"{ds['intensity'].values[k]:g} a_up, {motions[m]['name']}: "
                           f"{out['refused']}")
            continue
        walls.append(out["wall_time_s"])
        for q, measure in enumerate(MEASURES):
            c = float(ds[f"continuum_{measure}"].values[i, j, 0, 0, k, m])
            floor = float(ds[f"floor_{measure}"].values[i, j, 0, 0])
            values[i, j, 0, 0, k, m, q] = out["measures"][measure]
            if np.isfinite(c):
                errors[i, j, 0, 0, k, m, q] = relative_error(out["measures"][measure], c,
                                                             floor)
    return {"ds": ds, "errors": errors, "values": values, "refused": refused, "walls": walls}


def _share(cube, mask, q, tolerance) -> str:
    """The share of the points of ``mask`` whose |error| in every measure of ``q`` is within
    ``tolerance``."""
    ok = np.ones(int(mask.sum()), dtype=bool)
    for i in q:
        ok &= np.abs(cube[..., i][mask]) <= tolerance
    return f"{ok.mean():.0%}" if ok.size else "—"


def publish(folder: Path, done: dict, missing: dict) -> None:
    from upliftlab.comparisons.studies.winkler_map.grid import MEASURES

    lines = ["# The macro-element on a slice of the half-plane map", "",
             "Command `python benchmarks/macro_map_slice.py`; what is run and compared: the "
             "script's docstring. Errors are relative, with the map's floors; a share counts "
             "the points where the continuum's run is compared (bearing failures and runs "
             "beyond small strain left out, as the map does).", ""]
    if "points" not in done:
        write_text(folder / "MACRO_MAP_SLICE.md", "\n".join(
            lines + [f"(not measured: {missing.get('points', 'not run yet')})", ""]))
        return
    r = done["points"]
    ds, err = r["ds"], r["errors"]
    q = {m: MEASURES.index(m) for m in MEASURES}
    bed_err = ds["error"].values  # soil, fs, hb, T, I, motion, calibration, measure
    labels = [str(x) for x in ds["calibration_key"].values]
    soils = [str(s) for s in ds["soil_label"].values]
    shown = ("theta", "uplift", "residual_settlement", "u", "base_shear")
    lines += ["## Shares and errors", "", "| model | points | θ and uplift within 10 %: all | "
              + " | ".join(soils) + " | residual settlement within 20 %: all | "
              + " | ".join(soils) + " | " + " | ".join(f"median abs. error, {m}"
                                                         for m in shown) + " |",
              "|" + "---|" * (4 + 2 * len(soils) + len(shown))]
    compared = np.isfinite(err[..., q["theta"]]) & np.isfinite(bed_err[..., 0, q["theta"]])
    for name, cube in [("macro-element", err)] + [
            (labels[c], bed_err[..., c, :]) for c in range(len(labels))]:
        cells = [name, str(int(compared.sum()))]
        for group, tol in (((q["theta"], q["uplift"]), 0.10), ((q["residual_settlement"],), 0.20)):
            cells.append(_share(cube, compared, group, tol))
            for s in range(len(soils)):
                mask = compared.copy()
                mask[np.arange(mask.shape[0]) != s] = False
                cells.append(_share(cube, mask, group, tol))
        cells += [f"{np.median(np.abs(cube[..., q[m]][compared])):.1%}" for m in shown]
        lines.append("| " + " | ".join(cells) + " |")
    walls = r["walls"]
    lines += ["", f"The macro-element's runs: median {np.median(walls):.2f} s, largest "
              f"{np.max(walls):.2f} s (in this process, kernels compiled).", ""]
    if r["refused"]:
        lines += ["Refused runs (no error counted):", ""] + [f"- {x}" for x in r["refused"]]
        lines.append("")
    write_text(folder / "MACRO_MAP_SLICE.md", "\n".join(lines))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--map", required=True, help="the slice's map.nc (docstring)")
    parser.add_argument("--calibration", default=str(HERE / "macro_calibration.json"))
    parser.add_argument("--quick", action="store_true", help="the clay at FS_v 3 only")
    args = parser.parse_args(argv)
    for option in ("map", "calibration"):
        if not Path(getattr(args, option)).is_file():
            parser.error(f"--{option}: {getattr(args, option)!r} is not a file")
    if args.quick and args.write:
        parser.error("--write: a quick run never updates the committed table")
    folder = output_folder(args, NAME)
    sections = [Section("points", lambda: compute(args), 8.0 if args.quick else 200.0)]

    def commit(done):
        write_text(HERE / "MACRO_MAP_SLICE.md", (folder / "MACRO_MAP_SLICE.md").read_text())

    return run_sections(NAME, sections, publish, folder,
                        commit=commit if args.write else None,
                        model="a macro-element run about 5 s")


if __name__ == "__main__":
    raise SystemExit(main())
