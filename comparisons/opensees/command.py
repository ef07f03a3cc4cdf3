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

from ...checks import InputError
from ...log import logger
from ...outdir import claim
from ...scenes import load_scene
from .compare import comparison_table, compare, write_comparison
from .script import write_script
from .spec import opensees_spec

__all__ = ["command"]


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


def command(args) -> int:
    """Run the subcommand; 0 when the script was written (and, with --run, both runs
    finished)."""
    if args.json and not args.run:
        raise InputError("--json: only with --run (it prints both models' summaries)")
    dt = _positive("--dt", args.dt)
    timeout = _positive("--timeout", args.timeout)
    scene = load_scene(args.scene, case=args.case, overrides=args.overrides, motion=args.motion)
    spec = opensees_spec(scene, dt=dt, dashpots=args.dashpots)  # refuses before any file
    settings = {"command": "opensees", "scene": scene.name, "scene_digest": scene.digest,
                "overrides": list(scene.overrides), "motion": args.motion, "dt": dt,
                "dashpots": args.dashpots, "run": bool(args.run)}
    default = Path("results") / f"{scene.name}-opensees"
    with claim(args.out, default, settings=settings, force=args.force) as out:
        out.start_writing()
        if not args.run:
            files = write_script(spec, out.path)
            out.complete([f for f in (files.script, files.motion) if f is not None])
            extra = f" and {files.motion}" if files.motion else ""
            print(f"upliftlab opensees: wrote {files.script}{extra}: {len(spec.springs)} "
                  f"foundation springs, {len(spec.stories)} stories, {spec.steps} Newmark steps "
                  f"of {spec.dt:.4g} s; run it with `python {files.script}` (needs openseespy)")
            return 0
        result = compare(scene, out.path, dt=dt, dashpots=args.dashpots, timeout=timeout)
        written = write_comparison(result, out.path)
        out.complete([result.files.script, *written,
                      *[f for f in (result.files.motion,) if f is not None]])
    for path in written:
        logger("opensees").info(f"upliftlab opensees: wrote {path}")
    if args.json:
        print(json.dumps(result.to_json()))
    else:
        print(comparison_table(result))
    return 0
