"""What the continuum reference changes in the Winkler map: the same grid on the closed box and
on the half-plane, bed by bed, per soil and FS_v.

    python benchmarks/map_references.py [--grid FIELD=VALUES ...] [--quick] [--workers N]
                                        [--scheduler ADDRESS] [--budget S] [--out DIR] [--write]

Three sections, each written as it ends (``benchmarks/bench_output.py``):

1. ``box``: ``upliftlab study winkler_map`` on the grid with the box's kept store
   (``benchmarks/winkler_map_store``), into ``<out>/box``;
2. ``half_plane``: the same with ``--reference half_plane`` and its kept store
   (``benchmarks/winkler_map_halfplane_store``), into ``<out>/half_plane``; both with the beds
   that stand on both references (:func:`shared_beds`: not the macro-element);
3. ``compare``: the two ``map.nc`` read back, and ``MAP_REFERENCES.md`` written from them
   alone: per soil and FS_v, the points each reference counts (a run beyond the small-strain
   reference, refused or failed has no error), each bed's share within the θ tolerance in peak
   θ and edge uplift (a bearing failure a hit for a bed that fails too, as the map counts it,
   :func:`~upliftlab.comparisons.studies.winkler_map.goal.hits`) and its median |error| in
   residual settlement, on each reference, over the points both references count (the same
   points on both sides: a point one of them leaves out is left out of both); how the
   continuum itself moved (the median over
   the points both count of half-plane/box − 1 in peak θ, edge uplift and residual
   settlement); and, where the grid has two records or more, each reference's out-of-sample
   scores (:mod:`~upliftlab.comparisons.studies.winkler_map.holdout`).

Cost: the two map runs print their own estimates before any work (the continuum runs their
stores do not hold yet; ``--budget`` refuses a run above it) and compute only what their
stores lack; the beds are run live, about 0.2 s per point and bed on this machine. The grid
must be one the box's store holds whole (the full map's grid holds every one of its slices):
the box section runs with a budget of 1 s and is refused otherwise. ``--quick`` is one point
that both kept stores hold (:data:`QUICK_GRID`: a smoke check of the script, seconds of beds).
``--beds`` runs only the beds named (both maps; the table names those left out): on the
half-plane the q–z bed's runs take seconds each (its footing's own mass on the sway tie sets a
step of microseconds), most of the whole grid's bed time. ``--write`` rewrites the committed
``benchmarks/MAP_REFERENCES.md``.
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, incomplete_note,  # noqa: E402
                          missing_section, output_folder, run_sections, write_text)

NAME = "map_references"
REFERENCES = ("box", "half_plane")
STORES = {"box": HERE / "winkler_map_store", "half_plane": HERE / "winkler_map_halfplane_store"}
COMPARED = ("theta", "uplift", "residual_settlement")
#: ``--quick``'s grid: one clay pulse point, held by both kept stores.
QUICK_GRID = ["soils=clay", "fs_v=10", "h_over_B=1.5", "periods=0.5", "intensities=1.5",
              "pulse_periods=0.25", "elcentro=false", "fema_components=0"]


def shared_beds() -> list[str]:
    """The beds that stand on both references (the macro-element stands on the half-plane
    only): both maps run these, so that they compare bed by bed."""
    from upliftlab.comparisons.beds import BEDS

    return [name for name, entry in BEDS.items() if set(STORES) <= set(entry.references)]


def _beds(text: str) -> list[str]:
    """``--beds``: names of :func:`shared_beds`, comma-separated."""
    names, known = [n.strip() for n in text.split(",") if n.strip()], shared_beds()
    unknown = [n for n in names if n not in known]
    if not names or unknown:
        raise argparse.ArgumentTypeError(f"{text!r}: valid: names of {', '.join(known)}")
    return names


def run_map(reference: str, grid: list[str], folder: Path, args) -> Path:
    """The map on ``reference`` (its kept store) into ``folder/reference``; its map.nc."""
    out = folder / reference
    command = [sys.executable, "-m", "upliftlab", "study", "winkler_map", "--out", str(out),
               "--store", str(STORES[reference]), "--reference", reference, "--no-figures",
               "--beds", ",".join(args.beds or shared_beds())]
    for assignment in grid:
        command += ["--grid", assignment]
    if args.workers:
        command += ["--workers", str(args.workers)]
    if args.scheduler:
        command += ["--scheduler", args.scheduler]
    budget = 1.0 if reference == "box" else args.budget
    if budget is not None:
        command += ["--budget", str(budget)]
    done = subprocess.run(command, env=os.environ.copy())
    if done.returncode != 0:
        raise RuntimeError(f"the {reference} map ended with exit status {done.returncode}")
    return out / "map.nc"


def _counted(m) -> np.ndarray:
    """(soil, fs_v, h/B, period, intensity, motion): the points ``m`` counts (its continuum
    run finished, or ended in a bearing failure)."""
    from upliftlab.comparisons.studies.winkler_map.goal import hits

    return hits(m)[1]


def _shares(m, common: np.ndarray) -> tuple[dict, dict]:
    """On the points of ``common`` (…, motion): ({(soil, fs_v): {bed: share within the θ
    tolerance}}, {(soil, fs_v): {bed: median |residual-settlement error|}})."""
    from upliftlab.comparisons.studies.winkler_map.goal import hits
    from upliftlab.comparisons.studies.winkler_map.grid import MEASURES
    from upliftlab.comparisons.studies.winkler_map.parts import errors_of, labels

    hit = hits(m)[0]
    err = np.abs(errors_of(m)[..., MEASURES.index("residual_settlement")])
    beds = labels(m, "calibration")
    shares, settle = {}, {}
    for s, soil in enumerate(labels(m, "soil")):
        for f, fs in enumerate(m.fs_v.values.tolist()):
            k, at = common[s, f], (soil, float(fs))
            shares[at] = {b: float(hit[s, f][k][:, c].mean()) if k.any() else math.nan
                          for c, b in enumerate(beds)}
            settle[at] = {b: _median(err[s, f][k][:, c]) for c, b in enumerate(beds)}
    return shares, settle


def _median(values: np.ndarray) -> float:
    values = values[np.isfinite(values)]
    return float(np.median(values)) if values.size else math.nan


def _pct(value: float) -> str:
    return "n/a" if not math.isfinite(value) else f"{100 * value:.0f} %"


def continuum_moves(box, hp, common: np.ndarray) -> dict:
    """{soil: {measure: (median half-plane/box − 1, points)}} over the points of ``common``
    (both count them) with a finite value on both and a box value above 1e-12 (peak θ, edge
    uplift, residual settlement)."""
    from upliftlab.comparisons.studies.winkler_map.parts import labels, point_values

    out = {}
    for s, soil in enumerate(labels(box, "soil")):
        out[soil] = {}
        for q in COMPARED:
            a = point_values(box, f"continuum_{q}")[s].ravel()
            b = point_values(hp, f"continuum_{q}")[s].ravel()
            ok = common[s].ravel() & np.isfinite(a) & np.isfinite(b) & (np.abs(a) > 1e-12)
            out[soil][q] = (_median(b[ok] / a[ok] - 1.0), int(ok.sum()))
    return out


def compare(maps: dict) -> dict:
    """Everything the table shows, from the two map datasets."""
    from upliftlab.comparisons.studies.winkler_map.holdout import out_of_sample
    from upliftlab.comparisons.studies.winkler_map.parts import labels
    from upliftlab.comparisons.studies.winkler_map.verdicts import verdict_counts

    box, hp = maps["box"], maps["half_plane"]
    if labels(box, "calibration") != labels(hp, "calibration") or box.error.shape != \
            hp.error.shape:
        raise ValueError("the two maps are not of the same grid and beds")
    counted = {r: _counted(maps[r]) for r in REFERENCES}
    common = counted["box"] & counted["half_plane"]
    points = {(soil, float(fs)): tuple(int(c[s, f].sum()) for c in (*counted.values(), common))
              for s, soil in enumerate(labels(box, "soil"))
              for f, fs in enumerate(box.fs_v.values.tolist())}
    return {"beds": labels(box, "calibration"), "counted": points,
            "shares": {r: _shares(maps[r], common) for r in REFERENCES},
            "moves": continuum_moves(box, hp, common),
            "tolerance": float(box.attrs["options_theta_tolerance"]),
            "verdicts": {r: verdict_counts(maps[r]) for r in REFERENCES},
            "holdout": {r: out_of_sample(maps[r]) for r in REFERENCES},
            "motions": labels(box, "motion"), "points": int(box.continuum_wall_time.size)}


def _bed_table(c: dict) -> list[str]:
    from upliftlab.comparisons.studies.winkler_map.sections import short

    (bs, bq), (hs, hq) = c["shares"]["box"], c["shares"]["half_plane"]
    cells = list(bs)
    head = " | ".join(f"{soil} {fs:g}" for soil, fs in cells)
    lines = ["| bed | " + head + " |", "|---|" + "---|" * len(cells),
             "| points (box, half-plane, both) | " + " | ".join(
                 ", ".join(map(str, c["counted"][at])) for at in cells) + " |"]
    for bed in c["beds"]:
        row = " | ".join(f"{_pct(bs[at][bed])} → {_pct(hs[at][bed])}" for at in cells)
        lines.append(f"| {short(bed)} | {row} |")
    lines += ["", "## Median |error| in residual settlement, box → half-plane", "",
              "| bed | " + head + " |", "|---|" + "---|" * len(cells)]
    for bed in c["beds"]:
        row = " | ".join(f"{_pct(bq[at][bed])} → {_pct(hq[at][bed])}" for at in cells)
        lines.append(f"| {short(bed)} | {row} |")
    return lines


def _holdout_table(c: dict) -> list[str]:
    rows = [(r, s) for r in REFERENCES for s in c["holdout"][r]]
    if not rows:
        return ["The grid has fewer than two records: nothing to hold out."]
    lines = ["| reference | pick | soil | in sample | out of sample | held-out points |",
             "|---|---|---|---|---|---|"]
    for r, s in rows:
        lines.append(f"| {r} | {s.level} | {s.soil} | {_pct(s.in_sample)} | "
                     f"{_pct(s.out_of_sample)} | {s.points} |")
    return lines


def table(c: dict, command: str) -> str:
    from upliftlab.comparisons.studies.winkler_map.sections import short

    v = {r: c["verdicts"][r] for r in REFERENCES}
    left_out = [short(b) for b in shared_beds() if b not in c["beds"]]
    lines = [f"Beds: {', '.join(short(b) for b in c['beds'])}"
             + (f" (left out by --beds: {', '.join(left_out)})" if left_out else "") + ".", "",
             f"{c['points']} points on each reference; motions: {', '.join(c['motions'])}. "
             f"Runs beyond the small-strain reference (left out): box "
             f"{v['box']['beyond_small_strain']}, half-plane "
             f"{v['half_plane']['beyond_small_strain']}; far fields that yielded: box "
             f"{v['box']['far_field_yielded']}, half-plane "
             f"{v['half_plane']['far_field_yielded']}.",
             "", f"## Each bed within {100 * c['tolerance']:g} % in peak θ and edge uplift, "
             "box → half-plane", "",
             "Columns: soil, FS_v. On the points both references count (the first row: "
             "how many each counts, and both).", "",
             *_bed_table(c), "", "## The continuum itself, half-plane over box", "",
             "| soil | " + " | ".join(COMPARED) + " |", "|---|" + "---|" * len(COMPARED)]
    for soil, moves in c["moves"].items():
        lines.append(f"| {soil} | " + " | ".join(
            f"{'n/a' if not math.isfinite(m) else f'{100 * m:+.1f} %'} ({n})"
            for m, n in moves.values()) + " |")
    lines += ["", "Median of half-plane/box − 1 over the points both count (their number in "
              "brackets).", "", "## Out of sample", "", *_holdout_table(c)]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--grid", action="append", default=[], metavar="FIELD=VALUES")
    parser.add_argument("--workers", type=int, default=None)
    parser.add_argument("--scheduler", default=None)
    parser.add_argument("--budget", type=float, default=None)
    parser.add_argument("--beds", type=_beds, default=None, metavar="NAME,...",
                        help="the beds both maps run (default: every bed that stands on both "
                             "references, shared_beds())")
    parser.add_argument("--quick", action="store_true",
                        help="one point both kept stores hold (a smoke check; no --write)")
    args = parser.parse_args(argv)
    if args.quick and args.grid:
        parser.error("--quick is its own grid: give --grid or --quick, not both")
    grid = QUICK_GRID if args.quick else args.grid
    if args.workers is not None and not 1 <= args.workers <= 1024:
        parser.error(f"--workers: {args.workers}; valid: 1 to 1024")
    folder = output_folder(args, NAME)
    command = " ".join(["python benchmarks/map_references.py",
                        *(sys.argv[1:] if argv is None else argv)])
    maps: dict = {}

    def load(reference):
        from upliftlab.results import read_dataset

        maps[reference] = read_dataset(run_map(reference, grid, folder, args))
        return str(folder / reference / "map.nc")

    sections = [Section("box", lambda: load("box")),
                Section("half_plane", lambda: load("half_plane")),
                Section("compare", lambda: compare(maps))]
    head = (f"# The Winkler map on the box and on the half-plane\n\n{datetime.date.today()}; "
            f"command `{command}`. What each column is: the script's docstring.\n\n")

    def publish(out: Path, done: dict, missing: dict) -> None:
        body = (table(done["compare"], command) if "compare" in done
                else missing_section("## The comparison", "compare", missing))
        write_text(out / "MAP_REFERENCES.md", head + incomplete_note(missing) + body)

    def commit(done: dict) -> None:
        write_text(HERE / "MAP_REFERENCES.md", head + table(done["compare"], command))

    return run_sections(NAME, sections, publish, folder, commit=commit if args.write else None)


if __name__ == "__main__":
    raise SystemExit(main())
