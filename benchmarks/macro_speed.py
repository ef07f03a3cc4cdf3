"""The macro-element's cost in the reduced model, and its error, against a bed of springs.

    python benchmarks/macro_speed.py [--quick] [--out DIR] [--write]

The scene: Ewing's short-period wall (W = 242 kip on the base, h = 336 in, B = 240 in) on a
clay macro-element at FS_v 3 (the law of ``tests/test_macro_element_runs.py``), under a Ricker
pulse of 0.3 s at 0.15 g (the load mostly inside the bounding surface) and at 0.6 g (on it),
RK4 at the automatic step. Each run is timed whole in a fresh process (``upliftlab run``,
kernels cached: warm; the interpreter's start and the imports counted) and in this process (the
integration alone, median of three), at the default ``force_step`` and at 3 and 10 times it;
its error is that of θ_max and the plastic settlement against a run at a tenth of the default
sub-step (the reference: the same law converged in its sub-step). Beside it the same wall on a
bed of 48 elasto-plastic springs (the bed's cost per step). The element's update runs at every
stage of a step (five a step with RK4) in sub-steps of at most ``force_step`` of trial force:
its cost follows the path of the load, and its sub-step is first order, so a coarser one buys
speed at the price of the settlement (the table's second block).

Cost model: each row's runs are estimated at the run's steps × 300 µs (the default) and a fresh
process at 4 s; the whole benchmark about 2 min. ``--quick`` (the tests' path): the 0.15 g
pulse only, at the default sub-step and its reference. Writes ``MACRO_SPEED.md`` to ``--out``
(default ``results/bench/macro_speed``); ``--write`` also the committed copy in
``benchmarks/``.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, output_folder,  # noqa: E402
                          run_sections, write_text)

NAME = "macro_speed"
#: The clay element at FS_v 3 (the runs' test law) and the wall.
CLAY = {"capacity_multiple": 3.0, "initial_size": 0.67, "interior_modulus": 80.0,
        "interior_exponent": 1.1, "settlement_coupling": 0.1, "rounding_ratio": 0.5,
        "hardening_settlement": 0.1}
FORCE_STEP = 3e-4
FACTORS = (0.1, 1.0, 3.0, 10.0)
AMPLITUDES = (0.15, 0.6)


def scene_data(amplitude: float, force_step: float | None, bed: bool = False) -> dict:
    f = {"support": "uplift", "half_width": 120.0, "layout": "winkler", "stiffness": 20000.0,
         "sway_stiffness": 20000.0, "damping_ratio": 0.0}
    if bed:
        f.update(law="elastoplastic", springs=48, capacity_multiple=3.0)
    else:
        f.update(law="macro", springs=20, sliding_ratio=4.0, force_step=force_step, **CLAY)
    return {"schema": 1, "units": "kip-in-s",
            "structure": {"weight": 202.0, "height": 336.0, "damping_ratio": 0.0,
                          "rotary_inertia": 7694.0, "vertical_weight": 242.0, "period": 0.15},
            "foundation": f,
            "motion": {"type": "ricker", "amplitude": amplitude, "period": 0.3,
                       "duration": 2.0},
            "analysis": {"integrator": "rk4"}}


def _toml(data: dict) -> str:
    lines = []
    for key in ("schema", "units"):
        lines.append(f"{key} = {data[key]!r}".replace("'", '"'))
    for table in ("structure", "foundation", "motion", "analysis"):
        lines.append(f"[{table}]")
        for k, v in data[table].items():
            lines.append(f"{k} = " + (f'"{v}"' if isinstance(v, str) else repr(v)))
    return "\n".join(lines) + "\n"


def in_process(data: dict, repeats: int = 3) -> tuple[float, dict, int]:
    """(median wall of ``repeats`` runs, peaks, steps): the integration alone, kernels
    compiled (``repeats`` 0: one run, untimed, for its peaks: a wall of nan)."""
    from upliftlab.reduced import run
    from upliftlab.scenes import scene_from_dict

    scene = scene_from_dict(data)
    response = run(scene, histories=False)
    if not repeats:
        return float("nan"), dict(response.peaks), int(response.info["steps"])
    walls = []
    for _ in range(repeats):
        start = time.perf_counter()
        response = run(scene, histories=False)
        walls.append(time.perf_counter() - start)
    return statistics.median(walls), dict(response.peaks), int(response.info["steps"])


def whole_process(data: dict, folder: Path) -> float:
    """The wall time (s) of ``upliftlab run`` on the scene in a fresh process (warm cache)."""
    path = folder / "scene.toml"
    write_text(path, _toml(data))
    argv = [sys.executable, "-m", "upliftlab", "run", str(path), "--out", str(folder / "run"),
            "--force", "--no-figure"]
    subprocess.run(argv, check=True, capture_output=True)  # the cache, once
    start = time.perf_counter()
    subprocess.run(argv, check=True, capture_output=True)
    return time.perf_counter() - start


def measure(amplitude: float, folder: Path, factors=FACTORS) -> dict:
    rows = {}
    for factor in factors:  # the reference (the first, a tenth) is not timed: run once
        rows[factor] = in_process(scene_data(amplitude, FORCE_STEP * factor),
                                  repeats=0 if factor == factors[0] else 3)
    rows["bed"] = in_process(scene_data(amplitude, None, bed=True))
    rows["process"] = whole_process(scene_data(amplitude, FORCE_STEP), folder)
    rows["bed process"] = whole_process(scene_data(amplitude, None, bed=True), folder)
    return rows


def _error(value: float, reference: float) -> str:
    return f"{(value / reference - 1.0):+.2e}" if reference else "—"


def publish(folder: Path, done: dict, missing: dict, factors=FACTORS,
            amplitudes=AMPLITUDES) -> None:
    lines = ["# The macro-element's cost in the reduced model", "",
             "Command `python benchmarks/macro_speed.py`; what is run: the script's docstring. "
             "Times on the project's shared 2-core machine; compare within a row block.", ""]
    for amplitude in amplitudes:
        key = f"{amplitude:g} g"
        lines.append(f"## {key}")
        if key not in done:
            lines += ["", f"(not measured: {missing.get(key, 'not run yet')})", ""]
            continue
        rows = done[key]
        ref = rows[0.1][1]
        lines += ["", "| foundation | force_step | run (s) | µs a step | θ_max error | "
                  "plastic settlement error |", "|---|---|---|---|---|---|"]
        for factor in factors[1:]:
            wall, peaks, steps = rows[factor]
            lines.append(f"| macro-element | {FORCE_STEP * factor:.0e} | {wall:.3f} | "
                         f"{wall / steps * 1e6:.0f} | {_error(peaks['theta'], ref['theta'])} | "
                         f"{_error(peaks['plastic_settlement'], ref['plastic_settlement'])} |")
        wall, peaks, steps = rows["bed"]
        lines.append(f"| 48 elasto-plastic springs | — | {wall:.3f} | "
                     f"{wall / steps * 1e6:.0f} | — | — |")
        lines += ["", f"A fresh `upliftlab run` (warm cache): macro-element "
                  f"{rows['process']:.2f} s, the bed {rows['bed process']:.2f} s "
                  f"({rows['process'] / rows['bed process']:.2f}×).", ""]
    write_text(folder / "MACRO_SPEED.md", "\n".join(lines))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--quick", action="store_true",
                        help="the 0.15 g pulse at the default sub-step only (the tests' path)")
    args = parser.parse_args(argv)
    if args.quick and args.write:
        parser.error("--write: a quick run never updates the committed table")
    folder = output_folder(args, NAME)
    factors, amplitudes = (FACTORS[:2], AMPLITUDES[:1]) if args.quick else (FACTORS, AMPLITUDES)
    sections = [Section(f"{a:g} g", lambda a=a: measure(a, folder, factors), 60.0)
                for a in amplitudes]

    def commit(done):
        write_text(HERE / "MACRO_SPEED.md", (folder / "MACRO_SPEED.md").read_text())

    def publish_these(folder, done, missing):
        publish(folder, done, missing, factors, amplitudes)

    return run_sections(NAME, sections, publish_these, folder,
                        commit=commit if args.write else None,
                        model="run steps × 300 µs, a fresh process 4 s")


if __name__ == "__main__":
    raise SystemExit(main())
