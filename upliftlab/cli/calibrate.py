"""``upliftlab calibrate SCENE``: the macro-element of the scene's own soil and footing, fitted
to the continuum's statics (:mod:`upliftlab.comparisons.studies.macro_calibration`), and the
``--set`` overrides that put it under the scene's structure in the reduced model.

Before any run: the scene, the options and the whole cost (the continuum's statics and
pushovers at the continuum's per-step rates, the fit at
:data:`~upliftlab.comparisons.beds.macro.FIT_SECONDS_PER_STEP` per step of the law's pushovers,
at most its evaluation bound) are checked against the budget. The
continuum runs go to a store in the output folder, so the same command resumes an interrupted
calibration without making them again; the fit is made again (minutes). Progress: the sweep's
lines, then the fit's every :data:`FIT_REPORT_SECONDS` with its ETA. The overrides are checked
by validating the scene with them before anything is written.
"""

from __future__ import annotations

import json
import math
import shlex
import sys
import time
from dataclasses import replace

from ..budget import CONTINUUM_BUDGET_SECONDS, MAX_BUDGET_SECONDS, Cost, continuum_cost
from ..budget import check as check_budget
from ..budget import in_sequence, time_budget
from ..checks import InputError
from ..extras import need_extra
from ..outdir import claim
from .common import (FORCE_HELP, default_out, mesh_overrides, number,
                     refuse_without_effect)
from .common import say as _say

__all__ = ["add_calibrate", "calibrate_command", "DEFAULT_EVALUATIONS", "CALIBRATION_NAMES"]

#: The fit's default budget of evaluations (the map's soils converged in 346 and 442).
DEFAULT_EVALUATIONS = 500
EVALUATIONS_RANGE = (10, 20000)
#: How often (s) the fit reports its progress.
FIT_REPORT_SECONDS = 10.0
_META = ("schema", "units", "title", "description", "reference")
#: What the calibration reads of a scene: its soil, footing and mesh; the structure's
#: vertical weight (the capacity as its multiple) and the foundation's fields (the overrides
#: that replace them).
USED = (*_META, "structure.weight", "structure.vertical_weight", "structure.story.*.weight",
        "foundation*", "soil*", "continuum*", "analysis.max_steps", "analysis.max_memory")


def add_calibrate(sub) -> None:
    c = sub.add_parser("calibrate", help="the macro-element of a scene's soil and footing, "
                                         "fitted to the continuum's statics")
    c.add_argument("scene", help="a packaged scene name or a TOML path (needs a [soil] table "
                                 "with a strength)")
    c.add_argument("--case", help="a case of the scene")
    c.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    c.add_argument("--mesh", action="append", default=[], metavar="KEY=VALUE[,KEY=VALUE]",
                   help="continuum mesh options, e.g. elements_across=8 (repeatable)")
    c.add_argument("--fs-v", help="the FS_v = V_ult/N of the rotation pushovers, comma "
                                  "separated (default 10,5,3,2: the map's)")
    c.add_argument("--evaluations", help="the fit's budget of evaluations (default "
                                         f"{DEFAULT_EVALUATIONS}; valid "
                                         f"{EVALUATIONS_RANGE[0]} to {EVALUATIONS_RANGE[1]})")
    c.add_argument("--workers", help="processes for the continuum runs (default 1)")
    c.add_argument("--out", help="output directory (default results/<scene>-calibrate, with a "
                                 "digest of the options when there are any)")
    c.add_argument("--json", action="store_true", help="print the record as one JSON object")
    c.add_argument("--force", action="store_true", help=FORCE_HELP)
    c.add_argument("--budget", metavar="SECONDS",
                   help="refuse (exit 2) before any run a calibration estimated to take "
                        "longer than this (default 86400 s)")


def say(message: str) -> None:
    _say(message, "calibrate")


def _fs_v(text: str | None):
    from ..comparisons.studies.macro_calibration import DEFAULT_FS_V, check_fs_v

    if text is None:
        return check_fs_v(DEFAULT_FS_V)
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(f"--fs-v = {text!r}: expected comma-separated numbers") from None
    return check_fs_v(values)


def _cost(scene, fs_v, evaluations: int) -> Cost:
    """The calibration's cost: the continuum runs one after another, then the fit."""
    from ..comparisons.beds.macro import FIT_SECONDS_PER_STEP, evaluation_bound
    from ..comparisons.studies.macro_calibration import rotation_steps
    from ..comparisons.studies.macro_calibration.plan import VERTICAL_STEPS
    from ..scenes import ContinuumOptions
    from .continuum import _grid

    dofs, _ = _grid(scene, scene.continuum or ContinuumOptions())
    steps = rotation_steps(fs_v)
    runs = [continuum_cost(analysis="pushover", steps=n, step=0.0, dofs=dofs, snapshots=0)
            for n in (1, VERTICAL_STEPS, steps)]
    bound = evaluation_bound(evaluations)
    fit = Cost("the fit", 0, 0.0, 1e6, bound * steps * FIT_SECONDS_PER_STEP,
               f"at most {bound} evaluations of {steps} steps", "fewer --evaluations")
    whole = in_sequence([*runs, fit], "the calibration")
    return replace(whole, smaller="fewer --evaluations or --fs-v values, or a coarser mesh")


def _fit_progress(started: list, cache=None):
    """A ``progress(evaluations, at_most, lowest)`` printing every FIT_REPORT_SECONDS, and
    saving ``cache`` (the fit's evaluations) as often."""
    last = [0.0]

    def report(done: int, at_most: int, lowest: float) -> None:
        now = time.perf_counter()
        if not started:
            started.append(now)
        elapsed = now - started[0]
        if elapsed - last[0] < FIT_REPORT_SECONDS:
            return
        last[0] = elapsed
        left = elapsed / done * (at_most - done)
        say(f"fit: {done} of at most {at_most} evaluations, lowest cost so far {lowest:.4g}; "
            f"{elapsed:.0f} s, at most about {left:.0f} s left")
        if cache is not None:
            cache.save()
    return report


#: The files the calibration writes at its end (its record and its notes), declared before any
#: work; its fit cache and store are the state an interrupted calibration resumes from.
CALIBRATION_NAMES = ("calibration.json", "CALIBRATION.md")


def _own_folder(path, root):
    """``path`` (under ``root``), refused if it or anything under it is a symbolic link: the
    store's workers write into it, and every file written must lie inside the output
    folder."""
    from pathlib import Path

    path = Path(path)
    for entry in [path, *(path.rglob("*") if path.is_dir() and not path.is_symlink() else ())]:
        if entry.is_symlink():
            raise InputError(f"--out = {str(root)!r}: {str(entry.relative_to(root))!r} is a "
                             "symbolic link; the calibration writes only inside its output "
                             "folder; valid: a folder without links (or another --out)")
    return path


def _check_at_rest(scene) -> None:
    """The reduced model of ``scene`` (the calibrated element under the structure) built, its
    element at rest under the weight; a failure is the calibration's (exit 3), never a line
    that fails when the user runs it."""
    from ..reduced import build_model
    from ..reduced.laws.macro import MacroStepError

    try:
        build_model(scene)
    except (MacroStepError, InputError) as exc:
        raise RuntimeError(f"the calibrated element cannot carry the structure at rest ({exc});"
                           " no calibration is written") from None


def _run_line(args, items: list[str]) -> list[str]:
    """``upliftlab run`` of the scene (its case, the user's overrides that the reduced model
    reads) with the calibrated element."""
    line = ["upliftlab", "run", args.scene] + (["--case", args.case] if args.case else [])
    reduced = ("structure.", "foundation.", "motion.", "analysis.")
    for item in [*args.overrides, *items]:
        if item.startswith(reduced):
            line += ["--set", item]
    return line


def calibrate_command(args) -> int:
    from ..comparisons.framework.store import Store
    from ..comparisons.studies.macro_calibration import (FitCache, calibrate_scene,
                                                         calibration_markdown,
                                                         calibration_record, check_reach,
                                                         check_reduced_scene,
                                                         estimated_capacity, macro_strength,
                                                         scene_overrides)
    from ..results import write_text
    from ..scenes import load_scene

    need_extra("upliftlab calibrate", "skfem", "meshio")
    fs_v = _fs_v(args.fs_v)
    evaluations = number("--evaluations", args.evaluations, integer=True,
                         low=EVALUATIONS_RANGE[0], high=EVALUATIONS_RANGE[1])
    evaluations = evaluations or DEFAULT_EVALUATIONS
    workers = number("--workers", args.workers, integer=True, low=1, high=256) or 1
    seconds = number("--budget", args.budget, high=MAX_BUDGET_SECONDS)
    overrides = list(args.overrides) + mesh_overrides(args.mesh)
    scene = load_scene(args.scene, case=args.case, overrides=overrides)
    refuse_without_effect(overrides, "the calibration", USED)
    macro_strength(scene)  # a soil without strength is refused before any run
    check_reduced_scene(scene)  # as is a structure that cannot carry the element
    check_reach(scene, estimated_capacity(scene), fs_v, estimated=True)
    cost = _cost(scene, fs_v, evaluations)
    check_budget(cost, scene.analysis.max_steps, scene.analysis.max_memory,
                 time_budget(seconds, CONTINUUM_BUDGET_SECONDS))
    command = shlex.join(["upliftlab", *getattr(args, "argv", sys.argv[1:])])
    settings = {"command": "calibrate", "scene": scene.name, "scene_digest": scene.digest,
                "overrides": list(scene.overrides), "fs_v": list(fs_v),
                "evaluations": evaluations}
    default = default_out(f"{scene.name}-calibrate",
                          {"overrides": overrides, "fs_v": args.fs_v,
                           "evaluations": args.evaluations})
    record_name, notes_name = CALIBRATION_NAMES
    with claim(args.out, default, settings=settings, force=args.force,
               outputs=CALIBRATION_NAMES) as out:
        store = _own_folder(out.path / "store", out.path)
        say(f"{scene.name}: calibrating the macro-element at FS_v "
            f"{', '.join(f'{v:g}' for v in fs_v)} ({cost.sizes}); estimated at most "
            f"{math.ceil(cost.seconds / 60):.0f} min")
        cache = FitCache(out.path / "fit-cache.npz")
        try:
            cal = calibrate_scene(scene, Store(store), fs_v=fs_v, evaluations=evaluations,
                                  workers=workers, cache=cache,
                                  fit_progress=_fit_progress([], cache))
        except KeyboardInterrupt as exc:
            if cache:
                cache.save()
                exc.add_note(f"the fit's {len(cache)} evaluations kept in "
                             f"{cache.path.name}, replayed on resuming")
            raise
        cache.save()
        items = scene_overrides(cal, scene)
        _check_at_rest(scene.with_overrides(*items))
        record = calibration_record(cal, items)
        out.start_writing()
        written = [write_text(out.path / record_name,
                              json.dumps(record, indent=1, allow_nan=False) + "\n"),
                   write_text(out.path / notes_name,
                              calibration_markdown(cal, shlex.join(_run_line(args, items)),
                                                   command)), cache.path]
        out.complete(written)
    for path in written:
        say(f"wrote {path}")
    if args.json:
        print(json.dumps(record, allow_nan=False))
    else:
        worst = max(record["pushovers"], key=lambda p: p["moment_rms"])
        print(f"{scene.name}: V_ult {cal.V_ult:.4g}, K_v {cal.K_v:.4g}, K_r {cal.K_r:.4g}; "
              f"fit cost {cal.fit.cost:.3g} in {cal.fit.evaluations} evaluations, worst "
              f"moment rms {worst['moment_rms']:.1%} ({worst['label']})")
        print("use it: " + shlex.join(_run_line(args, items)))
    return 0
