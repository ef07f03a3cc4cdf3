"""The macro-element calibrated per soil from the continuum statics a map's store keeps, and
how closely it then follows them.

    python benchmarks/macro_calibration.py [--store DIR] [--soils clay,sand]
                                           [--evaluations N] [--quick] [--out DIR] [--write]

For each soil the store holds the footing's stiffness (K_v, K_r), its vertical capacity and,
at each FS_v, a monotonic rotation pushover and one of cycles at growing amplitude, and at
FS_v 3 and 5 six cycles at one amplitude (the map's statics rows and the fit's own,
:mod:`upliftlab.comparisons.studies.winkler_map.rocking`). The calibration
(:mod:`upliftlab.comparisons.beds.macro`) fits the macro-element to them: the capacity line
to the monotonic pushovers' largest moments, the plastic parameters to every pushover's moment
and settlement. Nothing dynamic enters. The table gives, per soil, the parameters, the capacity
line's residuals and, per pushover, the rms misfit of the moment (of its largest) and of the
settlement (of its range, at least N/(10 K_v)): the check of each step. ``--quick`` fits one
soil to its FS_v = 3 pushovers only, with few evaluations (the test's path).

A soil whose fit the store keeps (the map's ``evaluate_macro_fit`` record of today's reduced
model revision, made by ``upliftlab study winkler_map --beds macro`` on the same pushovers) is
read from it, with the fit's own wall time; ``--refit`` (or a store without it) fits again
here.

Writes ``MACRO_CALIBRATION.md`` and ``macro_calibration.json`` (the laws, with the store keys
of the runs they came from) to ``--out`` (default ``results/bench/macro_calibration``);
``--write`` also rewrites the committed copies in ``benchmarks/``. It runs no continuum: it
reads the store, and each fit takes ten to forty minutes (a pushover of the law is
milliseconds; the fit makes a few hundred passes over every pushover).
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import HERE, add_output_arguments, output_folder, say, write_text  # noqa: E402

NAME = "macro_calibration"
MODELS = {"tresca": "clay", "mohr_coulomb": "sand"}


def store_statics(store: Path) -> dict:
    """{soil: {"K_v", "K_r", "V_ult", "strength": {...}, "pushovers": [RotationPushover]}}
    from the map's kept records."""
    from upliftlab.comparisons.beds.macro import RotationPushover
    from upliftlab.comparisons.framework.store import Store

    kept, soils = Store(store), {}
    for key in kept.keys():
        entry = kept.entry(key)
        name, params, record = entry["function"], entry["params"], entry["record"]
        if name.endswith("winkler_map:evaluate_static"):
            soil = soils.setdefault(MODELS[params["soil"]["model"]], {"pushovers": []})
            soil["strength"] = strength(params["soil"])
            if params["analysis"] == "stiffness":
                soil["K_v"], soil["K_r"] = record["K_v"], record["K_r"]
            else:
                soil["V_ult"] = record["capacity"]
        elif name.endswith("evaluate_continuum") and params.get("analysis") == "rotation":
            soil = soils.setdefault(MODELS[params["scene"]["soil"]["model"]],
                                    {"pushovers": []})
            soil["pushovers"].append(RotationPushover(
                float(params["N"]), np.array(record["theta"]), np.array(record["M"]),
                np.array(record["settlement"]), key))
    return soils


def stored_fits(store: Path) -> dict:
    """{soil: (MacroCalibration, its pushovers, wall time s)} of the map's fits in ``store``
    made with today's reduced model revision (the last one found per soil)."""
    from upliftlab.comparisons.beds.macro import MacroCalibration, RotationPushover
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.reduced import REVISION
    from upliftlab.reduced.laws.macro import MacroElement

    kept, fits = Store(store), {}
    for key in kept.keys():
        entry = kept.entry(key)
        if not (entry["function"].endswith("winkler_map:evaluate_macro_fit")
                and entry.get("models") == {"reduced": REVISION}
                and "error" not in entry["record"]):
            continue
        params, record = entry["params"], entry["record"]
        pushes = sorted((RotationPushover(p["N"], np.array(p["theta"]), np.array(p["M"]),
                                          np.array(p["settlement"]), p["source"])
                         for p in params["pushovers"]), key=lambda p: (p.N, len(p.theta)))
        law = MacroElement(**record["law"])
        cal = MacroCalibration(
            law=law,
            capacity_residuals=np.array(record["capacity_residuals"]),
            moment_rms=np.array(record["moment_rms"]),
            settlement_rms=np.array(record["settlement_rms"]),
            load_misses=np.array(record["load_misses"]), sources=tuple(record["sources"]),
            cost=record["cost"], evaluations=record["evaluations"],
            details={"capacity": {"q0": law.cohesive_pressure, "q1": law.frictional_modulus}})
        fits[params["soil"]] = (cal, pushes, record["wall_time_s"])
    return fits


def strength(table: dict) -> dict:
    """The macro-element's c, φ, γ of a continuum soil table (kPa, degrees, kN/m³)."""
    if table["model"] == "tresca":
        return {"cohesion": table["undrained_strength"]}
    return {"cohesion": table["cohesion"], "friction_angle": table["friction_angle"],
            "unit_weight": table["density"] * 9.80665}


def label(p, V_ult: float) -> str:
    """"FS_v n, monotonic", "…, cycles" (growing amplitudes) or "…, k cycles at one
    amplitude" (repeated: whether the footing shakes down)."""
    theta = np.asarray(p.theta)
    kind = "monotonic"
    if np.any(np.diff(theta) < 0.0):
        peaks = theta[1:-1][(theta[1:-1] > theta[:-2]) & (theta[1:-1] >= theta[2:])]
        repeated = peaks.size > 1 and np.ptp(peaks) <= 1e-9 * np.max(np.abs(peaks))
        kind = f"{peaks.size} cycles at one amplitude" if repeated else "cycles"
    return f"FS_v {V_ult / p.N:.0f}, {kind}"


def calibrate(soil: dict, width: float, evaluations: int):
    from upliftlab.comparisons.beds.macro import calibrate_macro

    pushes = sorted(soil["pushovers"], key=lambda p: (p.N, len(p.theta)))
    return calibrate_macro(pushes, width=width, V_ult=soil["V_ult"], K_v=soil["K_v"],
                           K_r=soil["K_r"], max_evaluations=evaluations,
                           progress=fit_progress(time.perf_counter()), **soil["strength"])


def fit_progress(started: float, every: float = 30.0):
    """A fit's ``progress(evaluations, at_most, best_cost)``: a line every ``every`` s with
    the elapsed time and the most the rest can take."""
    last = [started]

    def report(done: int, at_most: int, best: float) -> None:
        now = time.perf_counter()
        if now - last[0] < every:
            return
        last[0] = now
        elapsed = now - started
        say(f"{NAME}: {done} of at most {at_most} evaluations, best cost {best:.4g}; "
            f"{elapsed:.0f} s, at most about {elapsed / done * (at_most - done):.0f} s left")
    return report


def one_pass(soil: dict, width: float) -> float:
    """The time (s) of one evaluation of the fit: every pushover of ``soil`` once, with the
    calibration's starting law (compiled already: the estimate excludes compiling)."""
    from upliftlab.comparisons.beds.macro import macro_pushover
    from upliftlab.reduced.laws.macro import MacroElement

    law = MacroElement(width=width, vertical_stiffness=soil["K_v"],
                       horizontal_stiffness=soil["K_v"], rocking_stiffness=soil["K_r"],
                       initial_size=0.9, **soil["strength"])
    macro_pushover(law, soil["pushovers"][0].N, soil["pushovers"][0].theta[:3], strict=False)
    start = time.perf_counter()
    for p in soil["pushovers"]:
        macro_pushover(law, p.N, p.theta, strict=False)
    return time.perf_counter() - start


def section(name: str, soil: dict, cal, seconds: float) -> str:
    from upliftlab.comparisons.studies.macro_calibration.output import law_table

    law = cal.law
    lines = [f"## {name}", "",
             f"V_ult {soil['V_ult']:.1f} kN/m, K_v {soil['K_v']:.0f} kN/m/m, K_r "
             f"{soil['K_r']:.0f} kN·m/rad/m; capacity line q(B′) = "
             f"{cal.details['capacity']['q0']:.1f} + {cal.details['capacity']['q1']:.1f} B′ "
             f"kPa, residuals {', '.join(f'{r:+.1%}' for r in cal.capacity_residuals)}; "
             f"fit: {cal.evaluations} evaluations, cost {cal.cost:.3g}, {seconds:.0f} s.", "",
             *law_table(law, "m"), "",
             "| pushover | moment rms (of its largest) | settlement rms (of its range) | "
             "largest miss of V (of N) |", "|---|---|---|---|"]
    for p, m, s, miss in zip(sorted(soil["pushovers"], key=lambda p: (p.N, len(p.theta))),
                             cal.moment_rms, cal.settlement_rms, cal.load_misses,
                             strict=True):
        lines.append(f"| {label(p, soil['V_ult'])} | {m:.1%} | {s:.1%} | {miss:.1e} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--store", default=str(HERE / "winkler_map_halfplane_store"))
    parser.add_argument("--soils", default="clay,sand")
    parser.add_argument("--evaluations", type=int, default=1500)
    parser.add_argument("--quick", action="store_true",
                        help="one soil, its FS_v = 3 pushovers, 30 evaluations")
    parser.add_argument("--refit", action="store_true",
                        help="fit again even where the store keeps the map's fit")
    args = parser.parse_args(argv)
    soils_asked = [s.strip() for s in args.soils.split(",") if s.strip()]
    if not soils_asked or any(s not in MODELS.values() for s in soils_asked):
        parser.error(f"--soils: {args.soils!r}; valid: clay, sand (comma separated)")
    if not 30 <= args.evaluations <= 20000:
        parser.error(f"--evaluations: {args.evaluations!r}; valid: 30 to 20000")
    if not Path(args.store).is_dir():
        parser.error(f"--store: {args.store!r} is not a folder")
    folder = output_folder(args, NAME)
    kept = store_statics(Path(args.store))
    missing = [s for s in soils_asked if not {"K_v", "V_ult"} <= set(kept.get(s, {}))
               or not kept[s]["pushovers"]]
    if missing:
        parser.error(f"--store: {args.store!r} keeps no statics and pushovers of "
                     f"{', '.join(missing)}")
    if args.quick:
        soils_asked = soils_asked[:1]
        for s in soils_asked:
            v_ult = kept[s]["V_ult"]
            kept[s]["pushovers"] = [p for p in kept[s]["pushovers"]
                                    if abs(v_ult / p.N - 3.0) < 0.1]
    width = 2.0
    sections, laws = [], {}
    budget = 30 if args.quick else args.evaluations
    stored = {} if args.quick or args.refit else stored_fits(Path(args.store))
    for name in soils_asked:
        if name in stored:
            cal, kept[name]["pushovers"], seconds = stored[name]
            say(f"{NAME}: the {name}'s fit read from the store ({cal.evaluations} "
                f"evaluations, {seconds:.0f} s when it was made)")
            sections.append(section(name, kept[name], cal, seconds))
        else:
            say(f"{NAME}: fitting the {name} ({len(kept[name]['pushovers'])} pushovers, at "
                f"most {budget} evaluations, estimated "
                f"{budget * one_pass(kept[name], width):.0f} s)")
            start = time.perf_counter()
            cal = calibrate(kept[name], width, budget)
            sections.append(section(name, kept[name], cal, time.perf_counter() - start))
        laws[name] = {"law": dataclasses.asdict(cal.law), "sources": list(cal.sources),
                      "moment_rms": cal.moment_rms.tolist(),
                      "settlement_rms": cal.settlement_rms.tolist()}
    command = " ".join(["python benchmarks/macro_calibration.py",
                        *(sys.argv[1:] if argv is None else argv)])
    text = (f"# The macro-element calibrated from the continuum's statics\n\nFrom the store "
            f"`{Path(args.store).name}`, {datetime.date.today()}; command `{command}`. What "
            f"is fitted to what: the script's docstring.\n\n" + "\n".join(sections))
    data = json.dumps({k: {**v, "law": {f: float(x) for f, x in v["law"].items()}}
                       for k, v in laws.items()}, indent=1, sort_keys=True) + "\n"
    write_text(folder / "MACRO_CALIBRATION.md", text)
    write_text(folder / "macro_calibration.json", data)
    if args.write:
        write_text(HERE / "MACRO_CALIBRATION.md", text)
        write_text(HERE / "macro_calibration.json", data)
    say(f"{NAME}: wrote {folder / 'MACRO_CALIBRATION.md'}"
        + (" and the committed copies" if args.write else ""))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
