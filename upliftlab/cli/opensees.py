"""``upliftlab opensees SCENE [--case X] [--set ...] [--out DIR] [--run [--json]]``.

Without ``--run``: write the standalone script (and the motion beside it) and say where. With
``--run``: also run upliftlab and OpenSees and write the comparison; ``--json`` prints
``{"upliftlab": {...}, "opensees": {...}}``. Bad input (Case C, exact kinematics, a missing
openseespy) ends with one line before any file is written.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from ..checks import InputError
from ..log import logger
from ..outdir import claim
from .common import FORCE_HELP

__all__ = ["add_opensees", "opensees_command"]

#: Seconds the OpenSees run of ``--run`` may take unless ``--timeout`` says otherwise.
DEFAULT_TIMEOUT = "3600"


def add_opensees(sub) -> None:
    """The parser of ``upliftlab opensees``."""
    o = sub.add_parser("opensees", help="write a standalone OpenSeesPy script of the scene (a "
                                        "BNWF model); with --run, run it beside upliftlab")
    o.add_argument("scene", help="a packaged scene name or a TOML path")
    o.add_argument("--case", help="a case of the scene: A or B (C has no OpenSees equivalent)")
    o.add_argument("--motion", help="a record name on UPLIFTLAB_MOTIONS or a file path")
    o.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    o.add_argument("--out", help="output directory (default results/<scene>-opensees)")
    o.add_argument("--dt", help="OpenSees Newmark step (s; default analysis.dt, else the record "
                                "step / n, 60 steps per shortest bonded period)")
    o.add_argument("--dashpots", default="clipped", help="foundation dashpots in OpenSees: "
                   "clipped (default, as upliftlab's), detaching or parallel")
    o.add_argument("--run", action="store_true", help="run it (the 'opensees' extra) and "
                   "upliftlab; write both models' peaks and histories side by side")
    o.add_argument("--timeout", help="with --run: of the OpenSees run (s, default 3600)")
    o.add_argument("--json", action="store_true", help="with --run: print one JSON object "
                   "{\"upliftlab\": {...}, \"opensees\": {...}}")
    o.add_argument("--force", action="store_true", help=FORCE_HELP)


def _positive(name: str, text: str | None) -> float | None:
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{name} = {text!r}: expected a number > 0 (s)") from None
    if not (math.isfinite(value) and value > 0.0):
        raise InputError(f"{name} = {text}: must be a finite number > 0 (s)")
    return value


def _scene_args(args) -> list[str]:
    """The arguments that chose the scene, as given: the scene, --case, --motion and each
    --set (for the command in the script's model.json, which adds the resolved step)."""
    chosen = [args.scene]
    for option, value in (("--case", args.case), ("--motion", args.motion)):
        chosen += [option, value] if value is not None else []
    return chosen + [a for o in args.overrides for a in ("--set", o)]


def opensees_command(args) -> int:
    """Run the subcommand; 0 when the script was written (and, with --run, both runs
    finished)."""
    # imported here, not with the parser: the comparison loads the reduced model, which every
    # other command (a continuum run among them) would otherwise load to build its parser
    from ..comparisons.opensees.compare import (COMPARISON_NAMES, check_upliftlab_runs,
                                                comparison_table, compare, write_comparison)
    from ..comparisons.opensees.runner import RUN_OUTPUTS, require_opensees
    from ..comparisons.opensees.script import script_names, write_script
    from ..comparisons.opensees.spec import opensees_spec
    from ..scenes import load_scene

    if args.json and not args.run:
        raise InputError("--json: only with --run (it prints both models' summaries)")
    if args.timeout is not None and not args.run:
        raise InputError(f"--timeout = {args.timeout!r}: only with --run (it limits the "
                         "OpenSees run, which only --run starts)")
    dt = _positive("--dt", args.dt)
    timeout = _positive("--timeout", DEFAULT_TIMEOUT if args.timeout is None else args.timeout)
    scene = load_scene(args.scene, case=args.case, overrides=args.overrides, motion=args.motion)
    if scene.foundation.law.name == "macro":
        return _macro_tcl(args, scene, dt)
    spec = opensees_spec(scene, dt=dt, dashpots=args.dashpots)  # refuses before any file
    if args.run:  # upliftlab's runs beside it, their cost included, before the folder is claimed
        check_upliftlab_runs(scene, spec.dt)
        require_opensees()  # the extra missing: one line, and no folder made for nothing
    settings = {"command": "opensees", "scene": scene.name, "scene_digest": scene.digest,
                "overrides": list(scene.overrides), "motion": args.motion, "dt": dt,
                "dashpots": args.dashpots, "run": bool(args.run)}
    default = Path("results") / f"{scene.name}-opensees"
    outputs = script_names(spec) + (list(RUN_OUTPUTS + COMPARISON_NAMES) if args.run else [])
    with claim(args.out, default, settings=settings, force=args.force,
               outputs=outputs) as out:
        out.start_writing()
        if not args.run:
            files = write_script(spec, out.path, _scene_args(args))
            out.complete([f for f in (files.script, files.numbers, files.motion)
                          if f is not None])
            extra = f" and {files.motion}" if files.motion else ""
            print(f"upliftlab opensees: wrote {files.script}, {files.numbers}{extra}: "
                  f"{len(spec.springs)} foundation springs, {len(spec.stories)} stories, "
                  f"{spec.steps} Newmark steps of {spec.dt:.4g} s; run it with "
                  f"`python {files.script}` (needs openseespy)")
            return 0
        result = compare(scene, out.path, dt=dt, dashpots=args.dashpots, timeout=timeout,
                         scene_args=_scene_args(args))
        written = write_comparison(result, out.path)
        out.complete([result.files.script, result.files.numbers, *written,
                      *[f for f in (result.files.motion,) if f is not None],
                      *[out.path / name for name in RUN_OUTPUTS]])
    for path in written:
        logger("opensees").info(f"upliftlab opensees: wrote {path}")
    if args.json:
        print(json.dumps(result.to_json()))
    else:
        print(comparison_table(result))
    return 0


def _macro_tcl(args, scene, dt) -> int:
    """A macro-element scene: the Tcl model on ``soilFootingSection2d``
    (:mod:`upliftlab.comparisons.opensees.tcl`), written, not run."""
    from ..comparisons.opensees.tcl import TCL_NAMES, tcl_numbers, write_tcl

    if args.run:
        raise InputError("--run: with foundation.law = 'macro' the OpenSees counterpart is "
                         "soilFootingSection2d, which only Tcl OpenSees has (openseespy 3.7 "
                         "does not); write the Tcl model without --run and run it with "
                         "`OpenSees model.tcl`")
    if args.dashpots != "clipped":
        raise InputError(f"--dashpots = {args.dashpots!r}: the Tcl model of a macro-element "
                         "scene has no springs to put dashpots on; valid: the default")
    numbers = tcl_numbers(scene, dt)  # refuses before any file
    settings = {"command": "opensees", "scene": scene.name, "scene_digest": scene.digest,
                "overrides": list(scene.overrides), "motion": args.motion, "dt": dt,
                "tcl": True}
    default = Path("results") / f"{scene.name}-opensees"
    with claim(args.out, default, settings=settings, force=args.force,
               outputs=TCL_NAMES) as out:
        out.start_writing()
        files = write_tcl(scene, out.path, dt)
        out.complete([files.motion, files.numbers, files.notes, files.script])
    print(f"upliftlab opensees: wrote {files.script}, {files.numbers}, {files.motion} and "
          f"{files.notes}: the macro-element as soilFootingSection2d (FS = "
          f"{numbers['FS']:.4g}, Vult = {numbers['Vult']:.6g}), {int(numbers['steps'])} Newmark "
          f"steps of {numbers['dt']:.4g} s; run it with `OpenSees {files.script.name}` (Tcl "
          "OpenSees; how the models correspond: model.md)")
    return 0
