"""How soon a fresh continuum process takes its first step, and 3 s of El Centro explicit
against implicit, each a whole ``upliftlab continuum`` process as a user runs it.

    python benchmarks/continuum_startup.py [--quick] [--repeats R] [--out DIR] [--write]

Every run is a fresh process of the command line on the clay scene (Tresca c_u = 50 kPa,
frictionless unilateral contact, Q2 with 2×2 reduced integration, 10B × 10B box, 16 elements
across B; ``--quick``: 4 across), with ``-v``, one numba thread and a private cache folder
(``XDG_CACHE_HOME`` = ``<out>/cache``: numba's compiled kernels and the set-up cache,
:mod:`upliftlab.continuum.setup_cache`), so that the user's own cache is neither used nor
changed. ``PYTHONDONTWRITEBYTECODE`` is taken out of the processes' environment: an installed
package has its bytecode (pip compiles it), so the package's modules are read as bytecode, not
compiled afresh in every process (the first, cold, run writes it beside an editable checkout's
sources, in ``__pycache__``, which git ignores). Every row is the **median of ``--repeats``
runs** (default 3; ``--quick``: 1), each run's value listed beside it, and every ratio is
formed from the medians of this one invocation. What is timed, from the moment the process is
started:

- **first step**: until the process reports its first row (the first progress line
  ``t = ... of``, written after the first time step): wall clock, and the process's CPU time then (read from
  ``/proc``: Linux). ``cold``: an empty cache folder (every kernel compiled, the set-up built);
  ``kernels cached``: the set-up cache emptied, numba's kept; ``warm``: both kept. The run
  itself: the Ricker pulse of the scene for 0.01 s, ``--no-render``.
- **El Centro**: the first 3 s of El Centro 1940 N-S (``--quick``: 0.5 s) by the explicit route
  (the default) and by the implicit one, the cache warm, each a whole process (wall clock, and
  CPU time of the process and its threads from ``getrusage``), ``--no-render``; the speed-up is
  implicit over explicit, from their medians. Before the timed runs each route runs once
  untimed: the pulse does not reach every kernel a record does (the separation point of a
  footing that uplifts; the implicit route's), and a run that compiles one is a cold run, not a
  warm one. The repeats go round the three runs in turn (explicit, implicit, explicit with
  pictures), so that a change in the machine's load falls on all three alike. The explicit run
  again with its default pictures (PNG and GIF) gives their cost: the CPU time the run itself
  reports for them (``the pictures took ... s CPU``, timed around the drawing in the process:
  the difference of two whole processes varies by more than the pictures cost), against the
  explicit solve's CPU time (from the first step to ``solved in``).

The machine may be shared: wall times then carry the other jobs' load, CPU times much less,
and the ratios of one invocation are what to compare. The tables go to
``CONTINUUM_STARTUP.md`` in ``--out`` (default ``results/bench/continuum_startup``), rewritten
as each section ends; ``--write`` also rewrites the committed
``benchmarks/CONTINUUM_STARTUP.md`` once every section has completed (never with ``--quick``).

Cost model (the estimate printed before any work): each run (a section) costs the wall time the
committed ``benchmarks/CONTINUUM_STARTUP.md`` records for its row (its ``wall [s]`` cells, a
median); a row it does not record has no estimate.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import platform  # noqa: E402
import re  # noqa: E402
import resource  # noqa: E402
import shutil  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, number, output_folder, run_sections, say,
                          write_text)
from upliftlab.continuum.output.series import PICTURES_SPENT  # noqa: E402

NAME = "continuum_startup"
SCENE = "strip_footing_clay"
#: Targets (issue 35, section 2): the first step within 2 s of the process start (cache warm);
#: 3 s of El Centro explicit at least 8 times faster than implicit; default pictures at most
#: 10 % of the solve.
TARGET_FIRST, TARGET_SPEEDUP, TARGET_PICTURES = 2.0, 8.0, 0.10
#: The progress line of the first recorded row: after the first step (explicit: the row of
#: t = 0, recorded after step 0; implicit: the row after its first step).
FIRST_ROW = re.compile(r" t = \d+\.\d+ of ")
SOLVED = "solved in "
#: The run's own report of its pictures' CPU time (continuum/output/series.py).
PICTURES = re.compile(re.escape(PICTURES_SPENT) + r"([0-9.]+) s CPU")


def _cpu_of(pid: int) -> float:
    """CPU time (user + system, s) of the running process ``pid`` so far."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(args: list[str], cache: Path, out: Path) -> dict:
    """One fresh ``upliftlab continuum`` process with ``args``: wall and CPU time to the first
    step and to the line ``solved in``, and of the whole process; raises on a failure."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR",
                                                            "NUMBA_DISABLE_JIT",
                                                            "PYTHONDONTWRITEBYTECODE")}
    env.update(XDG_CACHE_HOME=str(cache), MPLBACKEND="Agg")
    command = [sys.executable, "-m", "upliftlab", "continuum", SCENE, "--analysis", "dynamic",
               "-v", "--threads", "1", "--force", "--out", str(out), *args]
    before = _children_cpu()
    start = time.perf_counter()
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True)
    row = {"first_wall": float("nan"), "first_cpu": float("nan"),
           "solved_cpu": float("nan"), "pictures_cpu": float("nan")}
    tail = []
    for line in process.stderr:
        now = time.perf_counter() - start
        if FIRST_ROW.search(line) and row["first_wall"] != row["first_wall"]:
            row["first_wall"], row["first_cpu"] = now, _cpu_of(process.pid)
        if SOLVED in line:
            row["solved_cpu"] = _cpu_of(process.pid)
        spent = PICTURES.search(line)
        if spent:
            row["pictures_cpu"] = float(spent.group(1))
        tail = (tail + [line.rstrip()])[-5:]
    status = process.wait()
    row.update(wall=time.perf_counter() - start, cpu=_children_cpu() - before)
    if status != 0:
        raise RuntimeError(f"exit status {status}: " + " | ".join(tail))
    return row


def first_step(kind: str, folder: Path, n: int) -> dict:
    """A start of ``kind``: cold (empty cache), kernels cached (set-up cache emptied), warm."""
    cache = folder / "cache"
    if kind == "cold":
        shutil.rmtree(cache, ignore_errors=True)
    elif kind == "kernels cached":
        shutil.rmtree(cache / "upliftlab" / "setup", ignore_errors=True)
    row = timed(["--set", f"continuum.elements_across={n}", "--set", "analysis.duration=0.01",
                 "--no-render"], cache, folder / "runs" / "pulse")
    return {"kind": kind, **row}


def elcentro(route: str, render: bool, folder: Path, n: int, span: float) -> dict:
    """``span`` s of El Centro by ``route``, the cache warm, with or without the pictures."""
    from upliftlab.motions import ELCENTRO

    args = ["--motion", ELCENTRO, "--set", f"continuum.elements_across={n}", "--set",
            f"analysis.duration={span:g}", "--set", f"continuum.dynamics={route}"]
    row = timed(args + ([] if render else ["--no-render"]), folder / "cache",
                folder / "runs" / f"elcentro-{route}{'-pictures' if render else ''}")
    return {"route": route, "render": render, "span": span, **row}


#: The times a row reports: the median over its runs, each run's value listed beside it.
TIMES = ("first_wall", "first_cpu", "solved_cpu", "pictures_cpu", "wall", "cpu")


def _median(rows: list[dict]) -> dict:
    """The first of ``rows`` with every time of :data:`TIMES` replaced by its median over them,
    ``runs`` their number and ``<time>_all`` the values of each run, in order."""
    return {**rows[0], **{k: statistics.median(r[k] for r in rows) for k in TIMES},
            **{f"{k}_all": [r[k] for r in rows] for k in TIMES}, "runs": len(rows)}


def _each(values: list[float], digits: int) -> str:
    return ", ".join(f"{v:.{digits}f}" for v in values)


def first_table(starts: list[dict]) -> list[str]:
    lines = ["| start | runs | first step wall [s] | first step CPU [s] | whole process wall [s] | "
             "whole process CPU [s] | first step CPU of each run [s] |",
             "|---|---|---|---|---|---|---|"]
    for kind in ("cold", "kernels cached", "warm"):
        rows = [r for r in starts if r["kind"] == kind]
        if rows:
            r = _median(rows)
            lines.append(f"| {kind} | {r['runs']} | {r['first_wall']:.2f} | "
                         f"{r['first_cpu']:.2f} | {r['wall']:.2f} | {r['cpu']:.2f} | "
                         f"{_each(r['first_cpu_all'], 2)} |")
    return lines


ROUTES = (("explicit", False), ("implicit", False), ("explicit", True))


def _medians(runs: dict) -> dict:
    """{(route, render): the median row} of the timed runs ``runs`` {(route, render, i): row}."""
    out = {}
    for key in ROUTES:
        rows = [r for (route, render, _), r in sorted(runs.items()) if (route, render) == key]
        if rows:
            out[key] = _median(rows)
    return out


def elcentro_table(runs: dict) -> list[str]:
    lines = ["| route | pictures | simulated [s] | runs | first step wall [s] | "
             "first step CPU [s] | wall [s] | CPU [s] | CPU of each run [s] |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in _medians(runs).values():
        lines.append(f"| {r['route']} | {'default' if r['render'] else 'none'} | "
                     f"{r['span']:g} | {r['runs']} | {r['first_wall']:.2f} | "
                     f"{r['first_cpu']:.2f} | {r['wall']:.1f} | {r['cpu']:.1f} | "
                     f"{_each(r['cpu_all'], 1)} |")
    return lines


def targets(starts: list[dict], runs: dict) -> list[str]:
    lines = ["| target | met | measured |", "|---|---|---|"]
    warm = [r for r in starts if r["kind"] == "warm"]
    if warm:
        r = _median(warm)
        lines.append(f"| first step within {TARGET_FIRST:g} s of the process start (warm) | "
                     f"{'yes' if r['first_cpu'] <= TARGET_FIRST else 'no'} (CPU); "
                     f"{'yes' if r['first_wall'] <= TARGET_FIRST else 'no'} (wall) | "
                     f"CPU {r['first_cpu']:.2f} s, wall {r['first_wall']:.2f} s |")
    medians = _medians(runs)
    ex, im = medians.get(("explicit", False)), medians.get(("implicit", False))
    if ex and im:
        wall, cpu = im["wall"] / ex["wall"], im["cpu"] / ex["cpu"]
        lines.append(f"| El Centro {ex['span']:g} s explicit at least {TARGET_SPEEDUP:g}× "
                     f"faster than implicit (whole processes) | "
                     f"{'yes' if cpu >= TARGET_SPEEDUP else 'no'} (CPU); "
                     f"{'yes' if wall >= TARGET_SPEEDUP else 'no'} (wall) | "
                     f"CPU {cpu:.1f}×, wall {wall:.1f}× |")
    pictures = medians.get(("explicit", True))
    if ex and pictures:
        solve = statistics.median(s - f for s, f in zip(pictures["solved_cpu_all"],
                                                        pictures["first_cpu_all"]))
        cost = pictures["pictures_cpu"]
        share = cost / solve
        lines.append(f"| default pictures at most {100 * TARGET_PICTURES:g} % of the solve | "
                     f"{'yes' if share <= TARGET_PICTURES else 'no'} | "
                     f"{cost:.2f} s CPU against a {solve:.1f} s solve: "
                     f"{100 * share:.0f} % |")
    return lines


def document(args, starts: list[dict], runs: dict, missing: dict) -> str:
    n = 4 if args.quick else 16
    text = ["# Continuum start-up: the first step, and El Centro as whole processes", "",
            f"Measured {datetime.date.today().isoformat()} on {platform.machine()} "
            f"({os.cpu_count()} cores, shared with other jobs: compare CPU times and ratios), "
            f"Python {platform.python_version()}; command `python benchmarks/"
            f"continuum_startup.py{' --quick' if args.quick else ''} --repeats "
            f"{args.repeats}`; the clay scene on {n} across. Every time is the median of "
            f"{args.repeats} run{'s' if args.repeats > 1 else ''} (each run's CPU time listed "
            "beside it), every ratio one of medians; the El Centro routes each ran once "
            "untimed first. What is timed: the script's docstring.", ""]
    if missing:
        text += [incomplete_note(missing).strip(), ""]
    if starts:
        text += ["## First step", "", *first_table(starts), ""]
    if runs:
        text += ["## El Centro", "", *elcentro_table(runs), ""]
    if starts or runs:
        text += ["## Targets (issue 35, section 2)", "", *targets(starts, runs), ""]
    return "\n".join(text)


def cost(key: str) -> float | None:
    """The wall time (s) the committed table records for the row of the run ``key`` (its
    median), or None."""
    tables = committed_tables("CONTINUUM_STARTUP.md")
    for row in tables.get("First step", []):
        if key.startswith(f"start: {row['start']} "):
            return number(row["whole process wall [s]"])
    for row in tables.get("El Centro", []):
        if key.startswith(f"elcentro: {row['route']}, pictures {row['pictures']} "):
            return number(row["wall [s]"])
    return None


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="4 across, 0.5 s of El Centro, one run of each row (a smoke check)")
    parser.add_argument("--repeats", type=int, default=None,
                        help="runs of each row, their median reported (default 3; 1 with "
                             "--quick)")
    add_output_arguments(parser, NAME)
    args = parser.parse_args(argv)
    args.repeats = args.repeats or (1 if args.quick else 3)
    if args.repeats < 1:
        parser.error(f"--repeats = {args.repeats}: valid range is >= 1")
    from upliftlab.checks import InputError
    from upliftlab.motions import ELCENTRO, find_motion
    try:
        find_motion(ELCENTRO)
    except InputError as exc:
        say(f"{NAME}: error: {exc}; nothing was run or written")
        return 2
    folder = output_folder(args, NAME)
    n, span = (4, 0.5) if args.quick else (16, 3.0)
    starts: list[dict] = []
    runs: dict = {}

    def start(kind, i):
        starts.append(first_step(kind, folder, n))
        r = starts[-1]
        say(f"{kind} {i + 1}: first step after {r['first_wall']:.2f} s wall, "
            f"{r['first_cpu']:.2f} s CPU")
        return r

    def one(route, render, i):
        r = elcentro(route, render, folder, n, span)
        if i is not None:  # None: the untimed run before the timed ones
            runs[route, render, i] = r
        say(f"El Centro {route}{' with pictures' if render else ''} "
            f"{'(untimed, first)' if i is None else i + 1}: {r['wall']:.1f} s wall, "
            f"{r['cpu']:.1f} s CPU")
        return r

    # cold and kernels cached alternate, so that each cold run starts from an empty cache and
    # each kernels-cached run from the kernels the cold run before it compiled
    sections = []
    for i in range(args.repeats):
        for kind in ("cold", "kernels cached"):
            key = f"start: {kind} {i + 1}"
            sections.append(Section(key, lambda kind=kind, i=i: start(kind, i), cost(key)))
    for i in range(args.repeats):
        key = f"start: warm {i + 1}"
        sections.append(Section(key, lambda i=i: start("warm", i), cost(key)))

    def label(route, render):
        return f"elcentro: {route}, pictures {'default' if render else 'none'}"

    for route, render in ROUTES[:2]:
        key = f"{label(route, render)} untimed"
        sections.append(Section(key, lambda r=route, p=render: one(r, p, None), cost(key)))
    for i in range(args.repeats):
        for route, render in ROUTES:
            key = f"{label(route, render)} {i + 1}"
            sections.append(Section(key, lambda r=route, p=render, i=i: one(r, p, i),
                                    cost(key)))

    def publish(target: Path, done: dict, missing: dict) -> None:
        write_text(target / "CONTINUUM_STARTUP.md", document(args, starts, runs, missing))

    def commit(done: dict) -> None:
        publish(HERE, done, {})
        say(f"wrote {HERE / 'CONTINUUM_STARTUP.md'}")

    status = run_sections(NAME, sections, publish, folder,
                          commit=commit if args.write else None,
                          model="wall times recorded in benchmarks/CONTINUUM_STARTUP.md")
    if status == 0:
        print(document(args, starts, runs, {}))
        say(f"wrote {folder / 'CONTINUUM_STARTUP.md'}")
    return status


if __name__ == "__main__":
    raise SystemExit(main())
