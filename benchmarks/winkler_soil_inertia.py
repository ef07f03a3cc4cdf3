"""Winkler beds against the continuum with and without the soil's own inertia: how much of the
Winkler map's gap is the soil's dynamics, which no bed of foundation springs can hold?

    python benchmarks/winkler_soil_inertia.py [--scale S] [--store DIR] [--workers W]
                                              [--out DIR] [--write]

The points are the Winkler map's clay slice under its two pulses (Tresca, c_u = 50 kPa, h/B =
1.5, T = 0.5 s, FS_v ∈ {2, 3, 5, 10}, 1.5 and 3 × a_up, Ricker pulses of 0.25 and 0.6 s; 16
points on the reference mesh, 16 elements across B), with the map's seven beds. Each point's
continuum runs twice: as in the map, and with the soil's mass times ``--scale`` (default 0.01;
``DynamicOptions.soil_mass_scale``): the soil keeps its weight, stiffness and strength, but its
inertia (the box's own shaking, the seismic load on the soil, the footing's radiation) falls to
a hundredth, so the footing rocks on a soil that responds quasi-statically, which is what a bed
of springs assumes. The beds are the map's, run on the same motions. A bed's error against the
quasi-static continuum is its error as a foundation model; what its error against the map's
continuum adds is the soil's dynamics.

One point (FS_v = 10, 3 × a_up, the 0.25 s pulse) runs once more at each scale with the soil's
fields kept: the share of elements that yielded during the motion, under the footing (|x| < B,
depth < B) and away from it (|x| > 3B), by depth.

The continuum runs are stored points of the map (``--store``: pass the map's store to reuse its
runs; default ``<out>/store``), so an interrupted run resumes. The cost is estimated before any
run: the map's own estimate, and for the scaled runs the unscaled runs' wall time over √scale
(the stable step shrinks as √scale). Writes ``WINKLER_SOIL_INERTIA.md`` to ``--out`` (default
``results/bench/winkler_soil_inertia``); ``--write`` rewrites the committed
``benchmarks/WINKLER_SOIL_INERTIA.md`` instead.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import add_output_arguments, output_folder  # noqa: E402

NAME = "winkler_soil_inertia"
#: The depth bands (m below the surface) of the yield table, and the point it is taken at:
#: (FS_v, intensity, pulse period).
BANDS = ((0.0, 2.0), (2.0, 5.0), (5.0, 10.0), (10.0, 20.0))
FIELD_POINT = (10.0, 3.0, 0.25)


def _map(store, workers):
    """The map's clay slice under the pulses (its data), its dynamic points and its store."""
    from upliftlab.comparisons.protocol import Context
    from upliftlab.comparisons.store import Store
    from upliftlab.comparisons.winkler_map.beds import bed_names
    from upliftlab.comparisons.winkler_map.grid import FULL_OPTIONS, Grid
    from upliftlab.comparisons.winkler_map.maps import _dynamic_points, compute_map
    from upliftlab.comparisons.winkler_map.motions import study_motions
    from upliftlab.comparisons.winkler_map.points import BASE_SCENE, base_table
    from upliftlab.scenes import load_scene

    grid = Grid(soils=("clay",), h_over_B=(1.5,), periods=(0.5,), elcentro=False,
                fema_components=0)
    options = replace(FULL_OPTIONS, figures=False)
    motions = study_motions(grid, options, Path(store))
    store = Store(store)
    data = compute_map(grid, options, bed_names(options), motions,
                       Context(out=store.root, store=store, workers=workers))
    loads = {s.soil: s.V_ult for s in data.statics}
    points = _dynamic_points(grid, options, motions, base_table(),
                             load_scene(BASE_SCENE).g, loads)
    return data, points, store


def _scaled_runs(data, points, store, scale, workers, say):
    """The continuum's measures (…, motion, measure) of every point with the soil's mass
    scaled, after their estimate."""
    from upliftlab.comparisons.sweep import run_sweep
    from upliftlab.comparisons.winkler_map.grid import MEASURES, STUDY
    from upliftlab.comparisons.winkler_map.maps import _key
    from upliftlab.comparisons.winkler_map.points import evaluate_dynamic

    scaled = [{**p, "soil_mass_scale": float(scale)} for p in points]
    walls = data.continuum_wall.ravel()
    todo = [not store.has(_key(p, evaluate_dynamic)) for p in scaled]
    seconds = float(np.nansum(walls[np.array(todo)])) / math.sqrt(scale)
    say(f"{NAME}: {sum(todo)} continuum runs with the soil's mass × {scale:g} to make "
        f"({len(todo) - sum(todo)} stored), estimated {seconds / 60:.0f} min of one worker "
        f"(the map's runs' wall time over √{scale:g})")
    records = run_sweep(evaluate_dynamic, scaled, store, study=STUDY, workers=workers)
    out = np.full(data.continuum.shape, np.nan)
    flat = out.reshape(-1, len(MEASURES))
    for k, record in enumerate(records):
        if "error" not in record:
            flat[k] = [record["measures"][q] for q in MEASURES]
    return out


def _errors(beds, continuum, floors):
    """(bed − continuum)/max(|continuum|, floor) over (…, motion, calibration, measure)."""
    reference = continuum[..., None, :]
    return (beds - reference) / np.maximum(np.abs(reference), floors)


def _floors(data):
    from upliftlab.comparisons.winkler_map.grid import FLOOR_FRACTION

    f = FLOOR_FRACTION * data.scale  # (soil, fs_v, h/B, period, measure)
    return f[:, :, :, :, None, None, None, :]


def yield_table(points, V_ult: float, scale: float) -> dict:
    """Share of elements whose ε̄p grew during the motion, by depth band, under the footing
    and away from it, at :data:`FIELD_POINT` (soil's mass × ``scale``; N = V_ult/FS_v)."""
    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics import DynamicOptions, run_dynamic
    from upliftlab.comparisons.winkler_map.points import point_scene

    fs, intensity, period = FIELD_POINT
    point = next(p for p in points if p["intensity"] == intensity
                 and p["motion"].get("period") == period
                 and math.isclose(p["scene"]["structure"]["weight"] * fs, V_ult,
                                  rel_tol=1e-9))
    scene = point_scene(point)
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(snapshots=2, soil_mass_scale=scale))
    grew = np.asarray(result.plastic_strain)[-1] > np.asarray(result.plastic_strain)[0] + 1e-9
    mesh = model.mesh
    x, y = mesh.p[:, mesh.t].mean(axis=1)
    B = scene.foundation.width
    rows = {}
    for name, where in (("under", (np.abs(x) < B) & (y > -B)), ("away", np.abs(x) > 3 * B)):
        for top, bottom in BANDS:
            band = where & (-y >= top) & (-y < bottom)
            rows[(name, top, bottom)] = (float(grew[band].mean()) if band.any() else math.nan,
                                         int(band.sum()))
    rows["theta"] = float(np.max(np.abs(np.asarray(result.footing)[:, 2])))
    return rows


def _pct(v) -> str:
    return "n/a" if not np.isfinite(v) else f"{100 * v:.1f}"


def tables(data, scaled, scale, fields) -> str:
    from upliftlab.comparisons.winkler_map.grid import MEASURES

    q = {m: MEASURES.index(m) for m in ("theta", "uplift", "residual_settlement")}
    floors = _floors(data)
    against = {"the map's continuum": data.errors,
               f"soil's mass × {scale:g}": _errors(data.beds, scaled, floors)}
    lines = ["| bed | against | peak θ: median / 90th pct. \\|error\\| (%) | peak edge uplift | "
             "residual settlement | within 10 % in θ and uplift |", "|---|---|---|---|---|---|"]
    for c, name in enumerate(data.calibrations):
        for label, err in against.items():
            e = np.abs(err[..., c, :])
            cells = [f"{_pct(np.nanmedian(e[..., q[m]]))} / "
                     f"{_pct(np.nanpercentile(e[..., q[m]], 90))}" for m in q]
            ok = (e[..., q["theta"]] <= 0.1) & (e[..., q["uplift"]] <= 0.1)
            lines.append(f"| {name} | {label} | " + " | ".join(cells)
                         + f" | {_pct(ok.mean())} % |")
    share = []
    for label, err in against.items():
        ok = (np.abs(err[..., q["theta"]]) <= 0.1) & (np.abs(err[..., q["uplift"]]) <= 0.1)
        by_bed = ok.reshape(-1, ok.shape[-1]).mean(axis=0)
        share.append(f"{label}: best single bed {_pct(by_bed.max())} %, best bed point by "
                     f"point {_pct(ok.any(axis=-1).mean())} %")
    shift = (scaled - data.continuum) / np.maximum(np.abs(data.continuum),
                                                   floors[..., 0, :])
    lines += ["", "Share of the 16 points: " + "; ".join(share) + ".", "",
              "The continuum itself, soil's mass × {:g} against the map's (signed, %), peak θ / "
              "peak edge uplift / residual settlement, per FS_v (columns) and pulse and "
              "intensity (rows):".format(scale), ""]
    fs_v = data.grid.fs_v
    lines += ["| pulse, intensity | " + " | ".join(f"FS_v = {v:g}" for v in fs_v) + " |",
              "|---|" + "---|" * len(fs_v)]
    for m, motion in enumerate(data.motions):
        for i, intensity in enumerate(data.grid.intensities):
            cells = [" / ".join(f"{100 * shift[0, f, 0, 0, i, m, q[k]]:+.0f}" for k in q)
                     for f in range(len(fs_v))]
            lines.append(f"| {motion['name']}, {intensity:g} × a_up | " + " | ".join(cells)
                         + " |")
    fs, intensity, period = FIELD_POINT
    lines += ["", f"Elements that yielded during the motion (share of the band), FS_v = {fs:g}, "
              f"{intensity:g} × a_up, the {period:g} s pulse; peak θ "
              + ", ".join(f"{fields[s]['theta']:.3e} rad at mass × {s:g}" for s in fields)
              + ":", "",
              "| where | depth (m) | " + " | ".join(f"mass × {s:g}" for s in fields) + " |",
              "|---|---|" + "---|" * len(fields)]
    for name in ("under", "away"):
        label = "under the footing (\\|x\\| < B)" if name == "under" else "away (\\|x\\| > 3B)"
        for top, bottom in BANDS:
            cells = [f"{_pct(fields[s][(name, top, bottom)][0])} % of "
                     f"{fields[s][(name, top, bottom)][1]}" for s in fields]
            if fields[next(iter(fields))][(name, top, bottom)][1]:
                lines.append(f"| {label} | {top:g}–{bottom:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scale", type=float, default=0.01,
                        help="the soil's mass factor of the quasi-static runs, in (0, 1)")
    parser.add_argument("--store", default=None, help="results store (default <out>/store)")
    parser.add_argument("--workers", type=int, default=None, help="worker processes")
    add_output_arguments(parser, NAME)
    args = parser.parse_args(argv)
    if not 0.0 < args.scale < 1.0:
        print(f"{NAME}: error: --scale = {args.scale:g}: valid range is (0, 1)", file=sys.stderr)
        return 2
    out = output_folder(args, NAME)
    say = lambda m: print(m, file=sys.stderr, flush=True)  # noqa: E731
    started = time.perf_counter()
    data, points, store = _map(args.store or out / "store", args.workers)
    scaled = _scaled_runs(data, points, store, args.scale, args.workers, say)
    fields = {}
    for s in (1.0, args.scale):
        say(f"{NAME}: the soil's fields at mass × {s:g} (elapsed "
            f"{time.perf_counter() - started:.0f} s)")
        fields[s] = yield_table(points, data.statics[0].V_ult, s)
    text = (f"# Winkler beds against the continuum, with and without the soil's inertia\n\n"
            f"`python benchmarks/{NAME}.py --scale {args.scale:g}`, {datetime.date.today()}, "
            f"{platform.machine()}, Python {platform.python_version()}.\n\n"
            + __doc__.split("\n\n", 2)[2].strip() + "\n\n" + tables(data, scaled, args.scale,
                                                                  fields) + "\n")
    (out / "WINKLER_SOIL_INERTIA.md").write_text(text)
    print(text)
    say(f"wrote {out / 'WINKLER_SOIL_INERTIA.md'} in {time.perf_counter() - started:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
