"""The macro-element on the points of a slice of the half-plane map, beside the map's beds on
the same points (issue 36 §3: slices, before the whole map).

    python benchmarks/macro_map_slice.py --map DIR/map.nc [--out DIR] [--write]

``--map``: the map's dataset of the slice, made by ``upliftlab study winkler_map --reference
half_plane --store benchmarks/winkler_map_halfplane_store --grid h_over_B=1.5 --grid
periods=0.5 --grid fema_components=0 --grid elcentro=false`` (the pulses of one slice), or
with ``--grid h_over_B=1.0,1.5 --grid fema_components=10`` (two slices, the records with the
pulses), and ``--budget 1`` so that nothing but the kept runs is used (its continuum runs and
the macro-element's fits read from the kept store; the beds and the element run live). The
macro-element is a bed of the map's registry (``macro``,
:mod:`upliftlab.comparisons.beds.macro_bed`): fitted once per soil to the store's rotation
pushovers (nothing dynamic), put under each point's structure with the point's K_v and K_r, the
footing's sway tie and the soil's Rayleigh β as its dashpot density β K_v/B, run on Newmark at
0.25 ms (the map's ``options.macro_integrator`` and ``macro_dt``). Its error in each
measure is the map's: relative, with the map's floor (a tenth of the measure at the uplift
threshold). The table gives, per soil and all together, the share of the points within 10 % in
both peak θ and edge uplift and within 20 % in residual settlement, and the median error per
measure, for the macro-element and for every bed, on the points where the continuum's run is
compared (bearing failures and runs beyond small strain left out, as the map does), and the
share within 10 % in θ and uplift on the pulses and on the records apart.

It reads the dataset only (under a second). Writes ``MACRO_MAP_SLICE.md`` to ``--out``
(default ``results/bench/macro_map_slice``); ``--write`` also the committed table.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, output_folder,  # noqa: E402
                          run_sections, write_text)

NAME = "macro_map_slice"


def compute(args) -> dict:
    """The map's dataset with the macro-element among its calibrations, and its run times."""
    import xarray as xr

    ds = xr.load_dataset(args.map)
    labels = [str(x) for x in ds["calibration_key"].values]
    if "macro" not in labels:
        raise SystemExit(f"{NAME}: --map: {args.map!r} has no macro-element among its beds "
                         f"({', '.join(labels)}): make it on the half-plane reference")
    walls = ds["bed_wall_time"].values[..., labels.index("macro")]
    return {"ds": ds, "walls": walls[np.isfinite(walls)]}


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
             "beyond small strain left out, as the map does), and a model's run that failed "
             "there as a miss (the medians are of the runs that completed).", ""]
    if "points" not in done:
        write_text(folder / "MACRO_MAP_SLICE.md", "\n".join(
            lines + [f"(not measured: {missing.get('points', 'not run yet')})", ""]))
        return
    r = done["points"]
    ds = r["ds"]
    q = {m: MEASURES.index(m) for m in MEASURES}
    bed_err = ds["error"].values  # soil, fs, hb, T, I, motion, calibration, measure
    labels = [str(x) for x in ds["calibration_key"].values]
    soils = [str(s) for s in ds["soil_label"].values]
    shown = ("theta", "uplift", "residual_settlement", "u", "base_shear")
    kinds = np.array([str(k) for k in ds["motion_kind"].values])
    lines += [f"The slice: h/B {', '.join(f'{x:g}' for x in ds['h_over_B'].values)}, T "
              f"{', '.join(f'{x:g}' for x in ds['period'].values)} s, intensities "
              f"{', '.join(f'{x:g}' for x in ds['intensity'].values)} a_up; "
              f"{int((kinds == 'ricker').sum())} pulses and {int((kinds != 'ricker').sum())} "
              "records.", ""]
    lines += ["## Shares and errors", "", "| model | points | runs failed | "
              "θ and uplift within 10 %: all | "
              + " | ".join(soils) + " | residual settlement within 20 %: all | "
              + " | ".join(soils) + " | " + " | ".join(f"median abs. error, {m}"
                                                         for m in shown) + " |",
              "|" + "---|" * (5 + 2 * len(soils) + len(shown))]
    lines[-2] = lines[-2][:-1] + "| θ and uplift within 10 %: pulses | records |"
    lines[-1] += "---|---|"
    # the continuum's run is compared where any model has an error there: a model's own
    # failed run must not take the point out of the other models' counts (or its own)
    compared = np.isfinite(bed_err[..., q["theta"]]).any(axis=-1)
    pulse = np.broadcast_to(kinds == "ricker", compared.shape)  # motion: the last axis
    order = ["macro"] + [name for name in labels if name != "macro"]
    for name in order:
        cube = bed_err[..., labels.index(name), :]
        failed = compared & ~np.isfinite(cube[..., q["theta"]])
        cells = ["macro-element" if name == "macro" else name, str(int(compared.sum())),
                 str(int(failed.sum()))]
        for group, tol in (((q["theta"], q["uplift"]), 0.10), ((q["residual_settlement"],), 0.20)):
            cells.append(_share(cube, compared, group, tol))
            for s in range(len(soils)):
                mask = compared.copy()
                mask[np.arange(mask.shape[0]) != s] = False
                cells.append(_share(cube, mask, group, tol))
        cells += [f"{np.nanmedian(np.abs(cube[..., q[m]][compared])):.1%}" for m in shown]
        for on in (pulse, ~pulse):
            cells.append(_share(cube, compared & on, (q["theta"], q["uplift"]), 0.10))
        lines.append("| " + " | ".join(cells) + " |")
    walls = r["walls"]
    lines += ["", f"The macro-element's runs: median {np.median(walls):.2f} s, largest "
              f"{np.max(walls):.2f} s (in the map's process, kernels compiled).", ""]
    refusals = ds.attrs.get("refusals", [])
    refusals = refusals.split("\n") if isinstance(refusals, str) else list(np.atleast_1d(
        refusals))
    refused = [str(x) for x in refusals if ", macro:" in str(x)]
    if refused:
        lines += ["Refused runs of the macro-element (each counted as a miss):", ""]
        lines += [f"- {x}" for x in refused] + [""]
    write_text(folder / "MACRO_MAP_SLICE.md", "\n".join(lines))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--map", required=True, help="the slice's map.nc (docstring)")
    args = parser.parse_args(argv)
    if not Path(args.map).is_file():
        parser.error(f"--map: {args.map!r} is not a file")
    folder = output_folder(args, NAME)
    sections = [Section("points", lambda: compute(args), 1.0)]

    def commit(done):
        write_text(HERE / "MACRO_MAP_SLICE.md", (folder / "MACRO_MAP_SLICE.md").read_text())

    return run_sections(NAME, sections, publish, folder,
                        commit=commit if args.write else None, model="reading the map")


if __name__ == "__main__":
    raise SystemExit(main())
