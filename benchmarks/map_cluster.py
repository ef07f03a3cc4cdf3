"""How long the Winkler map's continuum runs take on a cluster of N workers, from the run
times its store keeps.

    python benchmarks/map_cluster.py [--store DIR ...] [--workers 8,32,128] [--slowdown F]
                                     [--out DIR] [--write]

Every continuum run of the map is one task of a Dask sweep (:mod:`upliftlab.comparisons.
framework.sweep`), computed on one single-threaded worker and kept in the store with the wall
time it took (``wall_time_s``, measured on the 2-core machine that made it). The tasks are
independent, so N workers take at least max(Σt/N, longest t); the sweep hands tasks to idle
workers, which the longest-processing-time-first list schedule (LPT) models, and LPT's
makespan is what is reported, beside that bound. Not counted: starting each worker (a fresh
process loads the compiled kernels from the on-disk cache in about 4 s,
``benchmarks/CONTINUUM_STARTUP.md``, or compiles them in about 50 s when its node has no
cache), the reduced model's beds (milliseconds per run) and the map's assembly. ``--slowdown``
scales every run's time (a reference whose runs cost more than the store's). One section per
store (``--store``, repeatable; by default both kept stores, the box's
``benchmarks/winkler_map_store`` and the half-plane's ``benchmarks/winkler_map_halfplane_store``,
each read for its own reference's run times).

Writes ``MAP_CLUSTER.md`` to ``--out`` (default ``results/bench/map_cluster``); ``--write``
also rewrites the committed ``benchmarks/MAP_CLUSTER.md``. It runs nothing but reads the store
(seconds): no cost estimate is needed.
"""

from __future__ import annotations

import argparse
import datetime
import heapq
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import HERE, add_output_arguments, output_folder, say, write_text  # noqa: E402
from map_references import STORES as KEPT_STORES  # noqa: E402  (the box's, the half-plane's)

NAME = "map_cluster"
#: The map's point functions whose runs are continuum runs (the store's ``function`` names).
CONTINUUM_FUNCTIONS = ("evaluate_dynamic", "evaluate_energy", "evaluate_static",
                       "evaluate_impedance")


def run_times(store: Path) -> dict[str, list[float]]:
    """{function: wall times (s)} of the continuum runs kept in ``store``."""
    from upliftlab.comparisons.framework.store import Store

    kept = Store(store)
    times: dict[str, list[float]] = {}
    for key in kept.keys():
        entry = kept.entry(key)
        name = entry["function"].rsplit(":", 1)[-1]
        wall = entry["record"].get("wall_time_s") if isinstance(entry["record"], dict) else None
        if name in CONTINUUM_FUNCTIONS and wall is not None:
            times.setdefault(name, []).append(float(wall))
    return times


def lpt_makespan(times: list[float], workers: int) -> float:
    """The makespan (s) of ``times`` on ``workers`` by the longest-first list schedule."""
    loads = [0.0] * workers
    for t in sorted(times, reverse=True):
        heapq.heapreplace(loads, loads[0] + t)
    return max(loads)


def table(times: dict[str, list[float]], workers: list[int], slowdown: float) -> str:
    every = [slowdown * t for ts in times.values() for t in ts]
    total, longest = sum(every), max(every)
    lines = [f"- `{n}`: {len(ts)} runs, {sum(ts) / 3600:.2f} h, the longest {max(ts):.0f} s"
             for n, ts in sorted(times.items())] + [
             "", f"All: {len(every)} runs, {total / 3600:.2f} h of one worker"
             + (f" (× {slowdown:g})" if slowdown != 1.0 else "")
             + f", the longest {longest:.0f} s.", "",
             "| workers | LPT makespan (h) | bound max(Σt/N, longest) (h) | efficiency |",
             "|---|---|---|---|"]
    for n in [1] + workers:
        makespan = lpt_makespan(every, n)
        bound = max(total / n, longest)
        lines.append(f"| {n} | {makespan / 3600:.3f} | {bound / 3600:.3f} | "
                     f"{total / (n * makespan):.1%} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--store", action="append", default=None,
                        help="a map's store (repeatable; default: both kept stores)")
    parser.add_argument("--workers", default="8,32,128")
    parser.add_argument("--slowdown", type=float, default=1.0)
    args = parser.parse_args(argv)
    try:
        workers = [int(w) for w in args.workers.split(",")]
    except ValueError:
        parser.error(f"--workers: {args.workers!r}; valid: whole numbers, comma separated")
    if not all(1 <= w <= 100_000 for w in workers):
        parser.error(f"--workers: {args.workers!r}; valid: 1 to 100000 each")
    if not 0.0 < args.slowdown <= 1000.0:
        parser.error(f"--slowdown: {args.slowdown!r}; valid: (0, 1000]")
    stores = args.store or [str(path) for path in KEPT_STORES.values()]
    for store in stores:
        if not Path(store).is_dir():
            parser.error(f"--store: {store!r} is not a folder")
    if len({Path(s).resolve() for s in stores}) != len(stores):
        parser.error(f"--store: {stores!r} names one store twice")
    sections = []
    for store in stores:
        times = run_times(Path(store))
        if not times:
            parser.error(f"--store: {store!r} keeps no continuum run of the map")
        sections.append(f"## `{Path(store).name}`\n\n" + table(times, workers, args.slowdown))
    folder = output_folder(args, NAME)
    command = " ".join(["python benchmarks/map_cluster.py", *(sys.argv[1:] if argv is None
                                                               else argv)])
    text = (f"# The Winkler map's continuum runs on N workers\n\nFrom the run times kept in "
            f"each store, {datetime.date.today()}; command `{command}`. What is modelled and "
            f"what is not: the script's docstring.\n\n" + "\n".join(sections))
    write_text(folder / "MAP_CLUSTER.md", text)
    if args.write:
        write_text(HERE / "MAP_CLUSTER.md", text)
    say(f"{NAME}: wrote {folder / 'MAP_CLUSTER.md'}" + (" and benchmarks/MAP_CLUSTER.md"
                                                         if args.write else ""))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
