"""Does the box matter? The continuum's dynamic answer when its box doubles in width and depth,
on the old boundaries (a rigid base) and on the half-plane ones (a compliant base).

    python benchmarks/halfplane_box.py [--out DIR] [--write] [--cases a,b,...] [--boxes 10,20]
                                       [--across 8,16]
                                       [--point clay-pulse,clay-record,sand-record]
                                       [--tail SECONDS] [--soil KEY=VALUE ...]
                                       [--continuum KEY=VALUE ...]
                                       [--input-scales 0.99,1.01]

Writes ``HALFPLANE_BOX.md`` and ``halfplane_box.json`` to ``--out`` (default
``results/bench/halfplane_box``), rewritten as each run ends; ``--write`` also rewrites the
committed ``benchmarks/HALFPLANE_BOX.md`` (with the command line and date) once every run has
ended without a failure. Each run is a fresh model (mesh, gravity, explicit time loop) in this
process.

**Cases** (``continuum.base``, the sides ``continuum.boundary``, how the footing is held):

- ``rigid-fixed``: the scene's default, a rigid base with the sides' u_x held (a rigid
  container), the frictionless footing's u prescribed to the base's;
- ``rigid-shear``: the map's, a rigid base with free-field shear sides (u_y held, u_x free);
- ``compliant-shear``: the half-plane with free-field shear sides: a compliant base
  (Lysmer–Kuhlemeyer dashpots, the record entering as the incident S wave 2ρV_s v_inc), the
  footing held horizontally by a tie ``continuum.horizontal_tie`` = K_h to the free field's
  surface, with its dashpot ``continuum.horizontal_tie_damping`` = C_h;
- ``compliant-lysmer``: the same with dashpots on the sides as well;
- ``compliant-shear-undamped``, ``compliant-lysmer-undamped``: the tie without its dashpot.

The tie's stiffness K_h = 2G/(2 − ν) is the handbook strip's horizontal stiffness per unit length
and C_h = ρ V_s B its high-frequency dashpot (Gazetas 1991,
:mod:`upliftlab.continuum.impedance.gazetas`), the sway spring and dashpot a bed would carry.

**Points.** ``clay-pulse``: ``strip_footing_clay`` as packaged (its own Ricker pulse, 0.3 g,
0.4 s, 4 s). ``clay-record`` / ``sand-record``: the map's point (:mod:`upliftlab.comparisons.
studies.winkler_map.points`) with the clay scene's N = 171.4 kN/m (FS_v = 3 on the clay's
Prandtl capacity; more on the sand), h/B = 1.5, T = 0.5 s, under the first ``--record-seconds``
(default 10) of El Centro at 1.5 a_up (0.167 g), on the map's clay or sand;
``clay-record-light`` / ``sand-record-light``: the same with N × :data:`LIGHT_LOAD` (FS_v 10 on
the clay), points whose plastic strain stays within the small-strain limit on the map's mesh
(the heavier ones pass it there: the map leaves them out). ``--elastic``: the
same points on elastic soil (the uplift stays), which separates the boundaries from the soil's
yielding. ``--tail``: the motion padded with that many seconds of still ground after it ends
(free vibration), so that the settlement is read once the rocking has died out (radiation damps
it on the half-plane; nothing does in the closed box). ``--soil [SOIL:]KEY=VALUE``: a ``[soil]``
field set on every run, or with ``SOIL:`` (clay or sand) on that soil's points only (e.g.
``clay:undrained_strength_gradient=1.7``, kPa/m); a number or a word.
``--continuum KEY=VALUE``: a ``[continuum]`` field set on every run, its value read as TOML
would (a number, a word, a list: ``damping_ratio=0.02``, ``damping_frequencies=[1.0,5.0]``);
the box, base and sides stay the case's.
``--input-scales``: the first box of each case and point again with the motion's amplitude
(a record's PGA, a pulse's amplitude) scaled by each factor, reported against the unscaled run
like a larger box: how far the answer moves when what reaches the footing moves by 1 %, the
yardstick for the box's own effect (a box that changes the motion under the footing by 1 % can
move an ill-conditioned point by more than the targets, whatever its boundaries).

**Measures** (the map's, :func:`~upliftlab.comparisons.studies.winkler_map.points.
continuum_measures`): peak |θ|, peak edge uplift, residual settlement (when flattest in the last
quarter); and the settlement averaged over the last quarter, which a footing that still rocks at
the end (the clay scene's does, ±5 mrad, on either base) oscillates about. Each larger box's
row gives the change against the box before it (a doubling, with ``--boxes 10,20,40``) of the
same case and point: the targets of issue 35 are 2 % (θ, uplift) and 5 % (settlement).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import itertools  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import tomllib  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import HERE, add_output_arguments, output_folder, say, write_text  # noqa: E402

NAME = "halfplane_box"
CASES = {"rigid-fixed": ("rigid", "fixed", False, False),
         "rigid-shear": ("rigid", "shear", False, False),
         "compliant-shear": ("compliant", "shear", True, True),
         "compliant-lysmer": ("compliant", "lysmer", True, True),
         "compliant-shear-undamped": ("compliant", "shear", True, False),
         "compliant-lysmer-undamped": ("compliant", "lysmer", True, False)}
POINTS = ("clay-pulse", "clay-record", "sand-record", "clay-record-light", "sand-record-light")
#: N of a ``-light`` point over the clay scene's: FS_v 10 on the clay's Prandtl capacity
LIGHT_LOAD = 0.3
#: The map point of a record run: h/B, T (s), intensity (× a_up); N is the clay scene's
RECORD_POINT = (1.5, 0.5, 1.5)
TARGETS = {"theta": 0.02, "uplift": 0.02, "residual_settlement": 0.05}


def handbook_sway(soil, width: float) -> tuple[float, float]:
    """(K_h, C_h) per unit length of a strip of ``width`` B on ``soil`` (a scene's soil):
    2G/(2 − ν) and ρ V_s B (the map's half-plane reference's tie,
    :func:`upliftlab.comparisons.studies.winkler_map.reference.handbook_sway`)."""
    from upliftlab.comparisons.studies.winkler_map.reference import handbook_sway as sway

    return sway(soil.shear_modulus, soil.poisson_ratio, soil.density, width)


def point_data(point: str, across: int, record_seconds: float) -> dict:
    """The scene table of ``point`` (module docstring)."""
    import copy

    from upliftlab.scenes import load_scene

    base = load_scene("strip_footing_clay")
    data = copy.deepcopy(dict(base.table))
    if point != "clay-pulse":
        from upliftlab.comparisons.studies.winkler_map.points import motion_table, point_table
        from upliftlab.motions import ELCENTRO, find_motion

        soil = point.split("-")[0]
        hb, period, intensity = RECORD_POINT
        N = base.structure.vertical_weight * (LIGHT_LOAD if point.endswith("-light") else 1.0)
        data = point_table(data, soil, across, N, hb, period, base.g)
        data["motion"] = motion_table({"type": "record", "_path": str(find_motion(ELCENTRO))},
                                      intensity, 2.0 * data["foundation"]["half_width"],
                                      data["structure"]["height"])
        data.setdefault("analysis", {})["duration"] = float(record_seconds)
    data["continuum"] = {**data["continuum"], "elements_across": int(across)}
    return data


def run(point: str, case: str, box: str, across: int, record_seconds: float,
        elastic: bool = False, tail: float = 0.0, soil: dict | None = None,
        input_scale: float = 1.0, continuum: dict | None = None) -> dict:
    """One run: the map's measures, the run's size and time."""
    from upliftlab.comparisons.studies.winkler_map.points import continuum_measures
    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
    from upliftlab.scenes import scene_from_dict

    base, sides, tie, damped = CASES[case]
    data = point_data(point, across, record_seconds)
    width, _, depth = box.partition("x")
    data["continuum"] = {**data["continuum"], **(continuum or {}), "domain_width": float(width),
                         "domain_depth": float(depth or width), "base": base, "boundary": sides}
    if elastic:
        data["soil"] = {k: v for k, v in data["soil"].items()
                        if k in ("youngs_modulus", "poisson_ratio", "density", "interface")}
        data["soil"]["model"] = "elastic"
    mine = point.split("-")[0]
    data["soil"] = {**data["soil"], **{k: v for (only, k), v in (soil or {}).items()
                                       if only in (None, mine)}}
    if input_scale != 1.0:
        data = scaled_input(data, input_scale)
    if tail > 0.0:
        data = with_tail(data, tail)
    scene = scene_from_dict(data, merged=True)
    if tie:
        K_h, C_h = handbook_sway(scene.soil, scene.foundation.width)
        scene = scene.replace("continuum", horizontal_tie=K_h,
                              horizontal_tie_damping=C_h if damped else None)
    started, cpu = time.perf_counter(), time.process_time()
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(), DynamicOptions(snapshots=0))
    wall, cpu = time.perf_counter() - started, time.process_time() - cpu
    *_, measures = continuum_measures(scene, result)
    label = box if input_scale == 1.0 else f"{box}, input ×{input_scale:g}"
    return {"point": point + (" (elastic)" if elastic else ""), "case": case, "box": label,
            "across": across,
            "theta": measures["theta"], "uplift": measures["uplift"],
            "residual_settlement": measures["residual_settlement"],
            "settlement_end": float(result.footing[0, 1] - result.footing[-1, 1]),
            "settlement_mean": tail_mean(result),
            "dofs": int(model.dofs), "steps": int(result.metadata["steps"]),
            "energy": float(result.energy_balance_error),
            "max_plastic_strain": float(result.metadata.get("max_plastic_strain", math.nan)),
            "tie": scene.continuum.horizontal_tie, "wall": wall, "cpu": cpu,
            "dt": float(result.metadata["dt"]),
            "damping_ratio": scene.continuum.damping_ratio}


def with_tail(data: dict, tail: float) -> dict:
    """The scene table ``data`` with ``tail`` s of still ground after its motion: the motion's
    and the analysis' durations lengthened (a record or pulse is padded with zeros)."""
    from upliftlab.scenes import scene_from_dict

    motion = scene_from_dict(data, merged=True).build_motion()
    analysis = data.get("analysis", {})
    length = min(motion.duration, analysis.get("duration", math.inf)) + float(tail)
    return {**data, "motion": {**data["motion"], "duration": length},
            "analysis": {**analysis, "duration": length}}


def scaled_input(data: dict, factor: float) -> dict:
    """The scene table ``data`` with its motion's amplitude (``pga`` or ``amplitude``) times
    ``factor``."""
    motion = dict(data["motion"])
    key = "pga" if "pga" in motion else "amplitude"
    if key not in motion:
        raise ValueError(f"motion {motion.get('type')!r} has neither a pga nor an amplitude")
    motion[key] = float(motion[key]) * factor
    return {**data, "motion": motion}


def tail_mean(result) -> float:
    """The settlement v(0) − v averaged over the run's last quarter (trapezoidal rule): the
    settlement about which a footing that still rocks at the end oscillates."""
    import numpy as np

    t, v = np.asarray(result.time), np.asarray(result.footing)[:, 1]
    tail = t >= t[0] + 0.75 * (t[-1] - t[0])
    s = v[0] - v[tail]
    return float(np.sum(0.5 * (s[1:] + s[:-1]) * np.diff(t[tail])) / (t[tail][-1] - t[tail][0]))


def table(rows: list[dict]) -> str:
    """The Markdown table of ``rows``: each larger box against the box before it (the
    doubling), each 'input ×' row against the first box, of the same case and point."""
    head = ("| point | case | across | box (×B, W or WxD) | peak θ (mrad) | uplift (mm) "
            "| residual settlement (mm) "
            "| Δθ | Δuplift | Δsettlement | within targets | mean settlement, last quarter (mm) "
            "| its Δ | largest ε̄p | DOFs | energy error | wall (s) |")
    lines = [head, "|" + "|".join("---" for _ in range(head.count("|") - 1)) + "|"]
    first, before = {}, {}
    for r in rows:
        key = (r["point"], r["case"], r["across"])
        ref = first.setdefault(key, r)
        if "input" not in str(r["box"]):  # a box: against the one before it
            ref, before[key] = before.get(key, r), r
        if ref is r:
            d = ["", "", "", "", f"{1e3 * r['settlement_mean']:.2f}", ""]
        else:
            ch = {m: r[m] / ref[m] - 1.0 if ref[m] else math.nan for m in TARGETS}
            ok = all(abs(ch[m]) <= TARGETS[m] for m in TARGETS)
            mean = r["settlement_mean"] / ref["settlement_mean"] - 1.0
            d = [f"{100 * ch[m]:+.1f} %" for m in TARGETS] + [
                "yes" if ok else "no", f"{1e3 * r['settlement_mean']:.2f}", f"{100 * mean:+.1f} %"]
        lines.append(f"| {r['point']} | {r['case']} | {r['across']} | {r['box']} | "
                     f"{1e3 * r['theta']:.3f} | "
                     f"{1e3 * r['uplift']:.2f} | {1e3 * r['residual_settlement']:.2f} | "
                     + " | ".join(d) + f" | {r['max_plastic_strain']:.3g} | {r['dofs']} | "
                     f"{r['energy']:.3g} | {r['wall']:.0f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--cases", default=",".join(CASES))
    parser.add_argument("--points", default="clay-pulse")
    parser.add_argument("--boxes", default="10,20",
                        help="boxes (× B): a width = depth, or WxD (width x depth)")
    parser.add_argument("--across", default="8",
                        help="elements across the footing, comma separated (e.g. 8,16: each "
                             "mesh its own rows)")
    parser.add_argument("--record-seconds", type=float, default=10.0)
    parser.add_argument("--tail", type=float, default=0.0,
                        help="seconds of still ground after the motion (free vibration)")
    parser.add_argument("--soil", action="append", default=[], metavar="KEY=VALUE",
                        help="a [soil] field set on every run (repeatable)")
    parser.add_argument("--continuum", action="append", default=[], metavar="KEY=VALUE",
                        help="a [continuum] field set on every run (repeatable), e.g. "
                             "damping_ratio=0.02")
    parser.add_argument("--input-scales", default="",
                        help="factors on the motion's amplitude, comma separated, run on the "
                             "first box (e.g. 0.99,1.01): the point's own sensitivity")
    parser.add_argument("--elastic", action="store_true",
                        help="the soil elastic (its Young's modulus, ν, ρ and interface kept): "
                             "the boundaries without the soil's yielding")
    args = parser.parse_args(argv)
    cases = args.cases.split(",")
    points = args.points.split(",")
    for c in cases:
        if c not in CASES:
            parser.error(f"--cases: {c!r}; valid: {', '.join(CASES)}")
    for p in points:
        if p not in POINTS:
            parser.error(f"--points: {p!r}; valid: {', '.join(POINTS)}")
    boxes = args.boxes.split(",")
    for b in boxes:
        try:
            [float(x) for x in b.split("x")]
        except ValueError:
            parser.error(f"--boxes: {b!r}; valid: a number or WxD")
    if not (0.0 <= args.tail <= 60.0):
        parser.error(f"--tail: {args.tail!r}; valid: 0 to 60 s")
    soil = {}
    for item in args.soil:
        key, sep, value = item.partition("=")
        only, colon, key = key.rpartition(":") if ":" in key else (None, "", key)
        if not sep or not key.isidentifier() or only not in (None, "clay", "sand"):
            parser.error(f"--soil: {item!r}; valid: [clay:|sand:]KEY=VALUE, KEY a [soil] field")
        try:
            soil[(only, key)] = float(value)
        except ValueError:
            soil[(only, key)] = value
    continuum = {}
    for item in args.continuum:
        key, sep, value = item.partition("=")
        if not sep or not key.isidentifier() or key in ("domain_width", "domain_depth", "base",
                                                         "boundary"):
            parser.error(f"--continuum: {item!r}; valid: KEY=VALUE, KEY a [continuum] field "
                         "name other than the box's and the case's (domain_width, "
                         "domain_depth, base, boundary)")
        try:
            continuum[key] = tomllib.loads(f"v = {value}")["v"]
        except tomllib.TOMLDecodeError:
            continuum[key] = value
    try:
        scales = [float(x) for x in args.input_scales.split(",") if x]
    except ValueError:
        parser.error(f"--input-scales: {args.input_scales!r}; valid: numbers, comma separated")
    for f in scales:
        if not (0.5 <= f <= 2.0):
            parser.error(f"--input-scales: {f:g}; valid: 0.5 to 2")
    try:
        meshes = [int(x) for x in args.across.split(",")]
    except ValueError:
        meshes = []
    if not meshes or any(not 2 <= n <= 64 for n in meshes):
        parser.error(f"--across: {args.across!r}; valid: integers 2 to 64, comma separated")
    folder = output_folder(args, NAME)
    rows = []
    for p, c, across in itertools.product(points, cases, meshes):
        for b, f in [(b, 1.0) for b in boxes] + [(boxes[0], f) for f in scales]:
            say(f"{NAME}: {p}, {c}, box {b} B, input ×{f:g}, {across} across ...")
            try:
                rows.append(run(p, c, b, across, args.record_seconds, args.elastic,
                                args.tail, soil, f, continuum))
            except Exception as exc:  # a failed run is reported, the others go on
                say(f"{NAME}: {p}, {c}, box {b}: {type(exc).__name__}: {exc}")
                continue
            say(f"{NAME}:   {rows[-1]['wall']:.0f} s")
            write_text(folder / "halfplane_box.json", json.dumps(rows, indent=1))
            write_text(folder / "HALFPLANE_BOX.md", table(rows))
    failed = len(points) * len(cases) * len(meshes) * (len(boxes) + len(scales)) - len(rows)
    if args.write and failed:
        say(f"{NAME}: {failed} run(s) failed: benchmarks/HALFPLANE_BOX.md not rewritten")
        return 1
    if args.write:
        write_text(HERE / "HALFPLANE_BOX.md", committed_text(rows, argv))
        say(f"{NAME}: wrote {HERE / 'HALFPLANE_BOX.md'}")
    return 0


def committed_text(rows: list[dict], argv) -> str:
    """The committed table: its title, how it was made, the targets and the table."""
    import datetime
    import platform

    command = " ".join(["python benchmarks/halfplane_box.py",
                        *(sys.argv[1:] if argv is None else argv)])
    return (f"# Does the box matter? The continuum's dynamic answer when its box doubles\n\n"
            f"Measured {datetime.date.today()} on {platform.machine()}, Python "
            f"{platform.python_version()}; command `{command}`. What each case, point and "
            f"measure is: the script's docstring. Targets (issue 35): peak θ and uplift within "
            f"{100 * TARGETS['theta']:g} %, residual settlement within "
            f"{100 * TARGETS['residual_settlement']:g} % when the box doubles; the rows "
            f"'input ×' are the first box with the motion's amplitude scaled, the point's own "
            f"sensitivity to what reaches the footing.\n\n" + table(rows))


if __name__ == "__main__":
    raise SystemExit(main())
