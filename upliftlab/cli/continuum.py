"""``upliftlab continuum``: a rotation pushover or a dynamic run of a scene in the continuum.

Everything is checked before the mesh is built: the scene and its ``[soil]``, the options,
overrides the analysis would ignore (a pushover takes no motion; the continuum has no springs),
the physics the model can carry (a small-strain model: rotations up to
:data:`MAX_ROTATION`; a load below the strip's bearing capacity; a soil with mass for the
dynamics; a load that is not lost in the solver's tolerance against the soil's stiffness),
the output folder, and the size of the mesh and of the run against the scene's budget and the
time budget (``--budget``; :mod:`upliftlab.budget`), first estimated from the grid lines, then
counted on the mesh.

An interruption (Ctrl-C, SIGTERM) of a dynamic run is a flag its time loop checks
(:mod:`.stop`): in the loop the run ends at the step it reached and writes the rows computed
so far, marked incomplete; after the loop every data file is still written (the pictures are
skipped) and the folder is left without its completion marker; either way the exit code is 130
with one line saying what was written.

The pictures of a dynamic run (``uplift.png`` at the largest |θ|, ``uplift.gif`` over the
snapshots) may cost at most :data:`PICTURE_SHARE` of the solve's CPU time (from the model
built to the time loop's end): the GIF takes as many evenly spaced snapshots as fit in what
the PNG left, at least :data:`~upliftlab.meshes.render.MIN_FRAMES`
(:func:`~upliftlab.meshes.render.write_pictures`); the line reporting the GIF says how many.
"""

from __future__ import annotations

import math
import shlex
import sys
import time

from .. import bounds
from ..anchors import undrained_capacity
from ..budget import check as check_budget
from ..budget import (CONTINUUM_BUDGET_SECONDS, MAX_BUDGET_SECONDS, continuum_cost,
                      in_sequence, time_budget)
from ..checks import InputError
from ..extras import need_extra
from .common import (FORCE_HELP, MESH_KEYS, default_out, eta, mesh_overrides, number,
                     refuse_without_effect, say, say_if_rounded)
from . import error_estimate as estimate_cli
from .exits import EXIT_INTERRUPTED, EXIT_NUMERICS
from ..outdir import claim
from .stop import stop_flag

__all__ = ["add_continuum", "continuum", "CONTINUUM_ANALYSES", "MAX_ROTATION",
           "continuum_outputs"]

CONTINUUM_ANALYSES = ("pushover", "dynamic", "impedance")
#: Largest rotation of a pushover (rad): the continuum is small-strain and small-rotation
#: (sin θ ≈ θ to 0.2 %, the footing's corners move by θ²B/2 ≈ 0.005 B).
MAX_ROTATION = 0.1
#: Smallest load N/(E B) the pushover resolves: below it the moment is lost in the Newton
#: tolerance (relative to the soil's stiffness forces). Measured on the strip on clay, 4
#: elements across: M/(N B) = 0.4525 at every N/(E B) from 1e-7 down to 1e-14, and 0.84 to 2.5
#: (impossible: at most 1/2) at 1e-15 to 1e-19; the bound keeps a factor 100.
MIN_LOAD_RATIO = 1e-12
#: Least soil density of a dynamic run (kg/m³; air is 1.2).
MIN_DENSITY = 1.0
#: The share of a dynamic run's solve (CPU time) its pictures may cost (module docstring).
PICTURE_SHARE = 0.10
#: The part of that share the GIF's frames are planned to fill: a frame's CPU time, measured on
#: the first, varies by about ±20 % on a shared machine (20–30 ms a frame), so frames planned to
#: the whole share overshoot it (1.10 s against 0.98 s measured).
PICTURE_PLAN = 0.8
_META = ("schema", "units", "title", "description", "reference")
#: What each analysis reads of a scene.
USED = {
    "pushover": (*_META, "structure.weight", "structure.vertical_weight",
                 "structure.story.*.weight", "foundation.half_width", "foundation.support",
                 "foundation.layout", "foundation.stiffness", "foundation.vertical_period",
                 "foundation.springs", "soil*", "continuum*", "analysis.max_steps",
                 "analysis.max_memory"),
    "dynamic": (*_META, "structure*", "foundation.half_width", "motion*", "analysis.duration",
                "analysis.hht_alpha", "analysis.max_steps", "analysis.max_memory", "soil*",
                "continuum*"),
    "impedance": (*_META, "foundation.half_width", "soil*", "continuum*"),
}


def add_continuum(sub) -> None:
    c = sub.add_parser("continuum", help="run one scene in the continuum model: a rotation "
                                         "pushover or a dynamic run, with XDMF and pictures")
    c.add_argument("scene", help="a packaged scene name or a TOML path (needs a [soil] table)")
    c.add_argument("--analysis", default="pushover",
                   help=f"{' or '.join(CONTINUUM_ANALYSES)} (default pushover: rotation at "
                        "constant N = the structure's vertical weight)")
    c.add_argument("--case", help="a case of the scene")
    c.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable), e.g. "
                        "analysis.duration=2 runs the first 2 s of the motion")
    c.add_argument("--mesh", action="append", default=[], metavar="KEY=VALUE[,KEY=VALUE]",
                   help=f"mesh options ({', '.join(MESH_KEYS)}), e.g. "
                        "elements_across=8,grading=2,element=Q2 (repeatable)")
    c.add_argument("--theta-max", help="pushover: largest rotation (rad, in (0, "
                                       f"{MAX_ROTATION:g}]; default 10 times the elastic "
                                       "half-plane's uplift rotation)")
    c.add_argument("--steps", help="pushover: rotation steps (default 40; two more below "
                                   "uplift if they are coarse)")
    c.add_argument("--motion", help="dynamic: a record name on UPLIFTLAB_MOTIONS or a path; "
                                    "replaces the scene's motion")
    c.add_argument("--a0", help="impedance: frequencies a0 = ω B/(2 V_s), comma separated "
                                "(default 0.1, 0.2, …, 2)")
    c.add_argument("--boundary", help="impedance: absorbing boundary pml (default) or lysmer")
    c.add_argument("--scale", help="displacement magnification of the pictures (default: "
                                   "automatic, stated in each picture)")
    c.add_argument("--threads", help="dynamic, explicit route: threads of the compiled soil "
                                     "kernels (default 1; more pays only on an otherwise idle "
                                     "machine)")
    estimate_cli.add_argument(c)
    c.add_argument("--out", help="output directory (default results/<scene>-continuum-"
                                 "<analysis>, with a digest of the overrides when there are "
                                 "any)")
    c.add_argument("--no-render", action="store_true",
                   help="skip the PNG and GIF renders (dynamic: the pictures cost at most "
                        f"{PICTURE_SHARE * 100:.0f}%% of the solve's CPU time, the GIF taking "
                        "as many evenly spaced snapshots as fit, at least 9)")
    c.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    c.add_argument("--force", action="store_true", help=FORCE_HELP)
    c.add_argument("--budget", metavar="SECONDS",
                   help="refuse (exit 2) before any meshing a run estimated to take longer "
                        "than this (default 86400 s); raise it to run one on purpose")


def _options(args) -> dict:
    """The command-line options, checked (each refused where the analysis ignores it)."""
    if args.analysis not in CONTINUUM_ANALYSES:
        raise InputError(f"--analysis = {args.analysis!r}: must be one of "
                         f"{', '.join(CONTINUUM_ANALYSES)}")
    pushover = args.analysis == "pushover"
    for flag, value in (("--theta-max", args.theta_max), ("--steps", args.steps)):
        if value is not None and not pushover:
            raise InputError(f"{flag} = {value}: has no effect: only the pushover takes it")
    if args.no_render and args.scale is not None:
        raise InputError(f"--scale = {args.scale}: has no effect with --no-render (it "
                         "magnifies the renders' displacements)")
    if args.analysis != "dynamic" and args.motion is not None:
        raise InputError("--motion: has no effect: only the dynamic analysis takes a motion")
    if args.threads is not None and args.analysis != "dynamic":
        raise InputError(f"--threads = {args.threads}: has no effect: only the dynamic "
                         "analysis takes it")
    for flag, value in (("--a0", args.a0), ("--boundary", args.boundary)):
        if value is not None and args.analysis != "impedance":
            raise InputError(f"{flag} = {value}: has no effect: only the impedance analysis "
                             "takes it")
    return {"theta_max": number("--theta-max", args.theta_max, high=MAX_ROTATION),
            "steps": number("--steps", args.steps, integer=True, low=2, high=10**9),
            "scale": number("--scale", args.scale, high=1e9),
            "threads": number("--threads", args.threads, integer=True, low=1, high=256),
            "error_estimate": estimate_cli.meshes(args)}


def _physics(scene, analysis: str) -> None:
    """What the continuum can carry, checked on the scene before meshing."""
    soil, N, B = scene.soil, scene.structure.vertical_weight, scene.foundation.width
    if soil.undrained:
        k = soil.undrained_strength_gradient
        capacity = undrained_capacity(soil.undrained_strength, k, B,
                                      rough=soil.interface == "bonded")
        rule = "(2 + π) c_u B" if k == 0.0 else "F [(2 + π) c_u + k B/4] B, Davis & Booker"
        if N >= capacity:
            raise InputError(f"structure.vertical_weight = {N:g}: at or above the strip's "
                             f"bearing capacity {rule} = {capacity:.4g} (FS_v = "
                             f"{capacity / N:.3g}); the footing cannot stand on this soil; "
                             f"valid range is (0, {capacity:.4g})")
    if N < MIN_LOAD_RATIO * soil.youngs_modulus * B:
        raise InputError(f"structure.vertical_weight = {N:g}: {N / (soil.youngs_modulus * B):.3g}"
                         f" of the soil's E·B = {soil.youngs_modulus * B:.4g}; below "
                         f"{MIN_LOAD_RATIO:g} the footing's response is lost in the solver's "
                         "tolerance (a stiffer soil needs a heavier load)")
    density = bounds.KINDS["density"]
    low = MIN_DENSITY / density.factor(scene.units)
    if analysis == "dynamic" and not soil.density >= low:
        raise InputError(f"soil.density = {soil.density:g} (0 when it is missing): the "
                         f"continuum dynamics needs the soil's mass; valid range is "
                         f"[{low:.3g}, {density.high / density.factor(scene.units):.3g}] "
                         f"{density.unit(scene.units)}")
    if analysis == "dynamic" and (scene.continuum is None
                                  or scene.continuum.dynamics == "explicit"):
        from ..continuum.dynamics.explicit import check_footing_mass

        check_footing_mass(scene)
    depth = soil.layer_depth
    if depth is not None and depth < 0.25 * B:
        raise InputError(f"soil.layer_depth = {depth:g}: a layer thinner than B/4 = "
                         f"{0.25 * B:g} is not meshed; valid range is [{0.25 * B:g}, ...)")


def continuum(args) -> int:
    from ..scenes import ContinuumOptions, load_scene

    options = _options(args)
    seconds = number("--budget", args.budget, high=MAX_BUDGET_SECONDS)  # not in the folder name
    need_extra("upliftlab continuum", "skfem", "meshio")
    if args.analysis == "pushover":  # the M-θ figure
        need_extra("upliftlab continuum", "matplotlib")
    if not args.no_render:
        need_extra("upliftlab continuum", "matplotlib", "PIL",
                   why="or add --no-render")
    overrides = list(args.overrides) + mesh_overrides(args.mesh)
    scene = load_scene(args.scene, case=args.case, overrides=overrides,
                       motion=args.motion if args.analysis == "dynamic" else None)
    refuse_without_effect(overrides, f"the continuum {args.analysis}", USED[args.analysis])
    if scene.soil is None:
        raise InputError(f"scene {scene.name!r}: soil is missing; the continuum model needs a "
                         "[soil] table")
    if args.analysis == "impedance":
        from .impedance import run_impedance
        return run_impedance(args, scene, overrides)
    _physics(scene, args.analysis)
    if args.analysis == "dynamic":
        motion = scene.build_motion()  # reads and checks the record before any meshing
    # name the default folder (the error estimate only where it is asked for)
    given = {k: v for k, v in options.items() if k != "threads"
             and not (k == "error_estimate" and v is None)}
    budget = scene.analysis
    coarser = estimate_cli.coarser(scene, options["error_estimate"])  # checked before work
    costs = []
    for run_scene in (scene, *coarser):  # from the grid lines: nothing is meshed yet
        dofs, h_min = _grid(run_scene, run_scene.continuum or ContinuumOptions())
        if args.analysis == "pushover":
            options["theta_max"] = _theta_max(scene, options["theta_max"])
            steps = snapshots = (options["steps"] or 40) + 3
            dt = 0.0
        else:
            (steps, dt), snapshots = _dynamic_steps(run_scene, motion, h_min), 41
        route = run_scene.continuum.dynamics if run_scene.continuum else "explicit"
        costs.append(continuum_cost(analysis=args.analysis, steps=steps, step=dt, dofs=dofs,
                                    snapshots=snapshots, route=route))
    cost = costs[0] if not coarser else in_sequence(
        costs, "the continuum dynamic with its " + ("coarser run" if len(coarser) == 1
                                                    else f"{len(coarser)} coarser runs")
        + " of --error-estimate")
    check_budget(cost, budget.max_steps, budget.max_memory,
                 time_budget(seconds, CONTINUUM_BUDGET_SECONDS))
    steps, dt = costs[0].steps, costs[0].step
    variant = {"overrides": overrides, "motion": args.motion, **given}
    settings = {"command": f"continuum {args.analysis}", "scene": scene.name,
                "scene_digest": scene.digest, "overrides": list(scene.overrides),
                "motion": args.motion, "theta_max": given["theta_max"],
                "steps": given["steps"]}
    if coarser:
        settings["error_estimate"] = options["error_estimate"]
    default = default_out(f"{scene.name}-continuum-{args.analysis}", variant)
    outputs = continuum_outputs(args.analysis, not args.no_render)
    if coarser:
        outputs += estimate_cli.ESTIMATE_NAMES
    with claim(args.out, default, settings=settings, force=args.force, outputs=outputs,
               patterns=[estimate_cli.COARSER_FILES] if coarser else []) as out, \
            stop_flag() as flag:
        from ..continuum import build_model

        started = time.perf_counter()
        model = build_model(scene)
        built = time.process_time()
        say(f"{scene.name}: {model.disc.element}, {model.mesh.nelements} elements, "
             f"{model.dofs} DOFs, soil {scene.soil.model}")
        failed = None  # a bearing failure: its rows and snapshots are written, then exit 3
        if args.analysis == "pushover":
            result = _pushover(model, scene, options["theta_max"], options["steps"])
        else:
            from ..continuum.dynamics.run_control import BearingFailure

            try:
                result = _dynamic(model, scene, motion, options["threads"] or 1, out, started,
                                  flag, _command(args))
            except BearingFailure as exc:
                if exc.result is None or exc.result.time.size < 2:
                    raise
                result, failed = exc.result, exc
            if isinstance(result, int):
                return result
            say_if_rounded("upliftlab continuum", scene.analysis.duration or motion.duration,
                           steps, dt)
        say(f"solved in {time.perf_counter() - started:.1f} s")
        from ..continuum.output.series import (dynamic_summary, pushover_summary, summary_line,
                                               write_outputs)
        from ..continuum.output.summaries import dynamic_warnings

        summary = (pushover_summary(result) if args.analysis == "pushover"
                   else dynamic_summary(result, width=model.width))
        _admissible(summary, args.analysis)
        if args.analysis != "pushover":
            for words in dynamic_warnings(summary, {"length": scene.units.length}):
                print(f"upliftlab: warning: {words}", file=sys.stderr)
        out.start_writing()
        pictures = (PICTURE_PLAN * PICTURE_SHARE * (time.process_time() - built)
                  if args.analysis == "dynamic" else None)
        written = write_outputs(out.path, model, result, scene=scene, picture_budget=pictures,
                                renders=not args.no_render, scale=options["scale"],
                                progress=say, stop=lambda: flag.stopped)
        if failed is not None:  # no completion marker: the folder holds a failed run
            print(f"upliftlab: error: {' '.join(str(failed).split())} (the rows and snapshots "
                  f"until t = {float(result.time[-1]):.4g} s written to "
                  f"{out.path}, result.nc marked incomplete = 1, failure = bearing)",
                  file=sys.stderr)
            return EXIT_NUMERICS
        if flag.stopped:  # after the time loop: every data file written, no completion marker
            print(f"upliftlab: interrupted ({flag.name}) after the time loop ended at t = "
                  f"{float(result.time[-1]):.4g} s; wrote {', '.join(sorted(written))} to "
                  f"{out.path}{'' if args.no_render else ' (pictures skipped)'}, not marked "
                  f"complete; resume with: {_command(args)}", file=sys.stderr)
            return EXIT_INTERRUPTED
        files = list(written.values() if isinstance(written, dict) else written)
        if coarser:
            done = estimate_cli.run_coarser(coarser, motion, options["threads"] or 1, out, flag,
                                            _dynamic_progress, _command(args))
            if isinstance(done, int):
                return done
            estimate, more = estimate_cli.write_estimate(out, scene, model, result, done)
            summary["error_estimate"] = estimate.to_dict()
            files += more
        out.complete(files)
    if args.json:
        import json
        print(json.dumps(summary))
    else:
        units = {"length": scene.units.length,
                 "moment/length": f"{scene.units.force}*{scene.units.length}/{scene.units.length}"}
        print(summary_line(summary, units))
        if coarser:
            print(f"discretisation error estimate ({estimate.across[0]} across against "
                  f"{', '.join(map(str, estimate.across[1:]))}; {estimate.time_note()}):")
            for line in estimate.lines():
                print(f"  {line}")
    return 0


#: The files :func:`~upliftlab.continuum.output.series.write_outputs` writes for every run,
#: for a pushover, and as pictures (its docstring; that module is not to change with this one).
RUN_FILES = ("result.nc", "fields.xdmf", "fields.h5", "footing.xdmf", "footing.h5")
PUSHOVER_FILES = ("moment_rotation.png",)
PICTURE_FILES = ("uplift.png", "uplift.gif")


def continuum_outputs(analysis: str, renders: bool) -> list[str]:
    """The files a continuum ``analysis`` (pushover or dynamic) writes in its folder, with its
    pictures if ``renders``: declared before any work, so that each is checked
    (:func:`upliftlab.outdir.claim`)."""
    return [*RUN_FILES, *(PUSHOVER_FILES if analysis == "pushover" else ()),
            *(PICTURE_FILES if renders else ())]


def _grid(scene, options) -> tuple[int, float]:
    """(DOFs, shortest element edge) of the mesh the scene asks for, from its grid lines."""
    import numpy as np

    from ..continuum.setup_cache import grid_lines

    x, y = grid_lines(scene.foundation.width, options, scene.soil.layer_depth)
    order = 2 if options.element in ("P2", "Q2") else 1
    dofs = 2 * (order * (x.size - 1) + 1) * (order * (y.size - 1) + 1)
    return dofs, float(min(np.diff(x).min(), np.diff(y).min()))


def _dynamic_steps(scene, motion, h_min: float) -> tuple[int, float]:
    """(steps, dt) of the continuum dynamics on a mesh whose shortest edge is ``h_min``: the
    record step divided down to the route's limit (as :func:`run_dynamic` does; the explicit
    route's exact limit needs the mesh,
    :data:`~upliftlab.continuum.dynamics.explicit.COURANT_ESTIMATE`
    estimates it from below, and the soil's Rayleigh damping shortens it by its Maxwell
    arm's factor at the mesh's highest frequency, estimated from the same step,
    ω_max ≈ 2 × STABILITY_FRACTION/dt, :mod:`~upliftlab.continuum.dynamics.rayleigh`)."""
    from ..continuum.dynamics.run import COURANT_LIMIT, wave_speeds
    from ..continuum.dynamics.explicit import COURANT_ESTIMATE, STABILITY_FRACTION
    from ..continuum.dynamics.rayleigh import damped_critical, scene_rayleigh

    explicit = (scene.continuum.dynamics if scene.continuum else "explicit") == "explicit"
    courant = COURANT_ESTIMATE if explicit else COURANT_LIMIT
    limit = courant * h_min / wave_speeds(scene.soil)[0]
    damping = scene_rayleigh(scene) if explicit else None
    if damping is not None:
        omega_max = 2.0 * STABILITY_FRACTION / limit
        limit *= damped_critical(omega_max, damping) * omega_max / 2.0
    dt = motion.dt / max(1, math.ceil(motion.dt / limit * (1.0 - 1e-12)))
    duration = scene.analysis.duration or motion.duration
    if duration < 0.5 * dt:
        raise InputError(f"analysis.duration = {duration:g} s: shorter than one time step "
                         f"of this mesh ({dt:.4g} s, V_p dt/h_min = {courant:g})")
    return max(1, int(round(duration / dt))), dt


def _admissible(summary: dict, analysis: str) -> None:
    """A result that no tensionless footing can give is a failure, not a result."""
    bad = [k for k, v in summary.items() if isinstance(v, float) and not math.isfinite(v)]
    if bad:
        raise RuntimeError(f"the continuum {analysis} gave a non-finite {bad[0]}")
    ratio = summary.get("peak_M_over_NB")
    if ratio is not None and ratio > 0.5 * 1.005:
        raise RuntimeError(f"the continuum pushover gave M/(N B) = {ratio:.4g}, above the 1/2 "
                           "that a footing on a tensionless interface can carry")


def _theta_on(scene) -> float:
    """The rigid strip's uplift rotation on the elastic half-plane, 2N(1 − ν)/(πGB) (rad)."""
    soil, N, B = scene.soil, scene.structure.vertical_weight, scene.foundation.width
    return 2.0 * N * (1.0 - soil.poisson_ratio) / (math.pi * soil.shear_modulus * B)


def _theta_max(scene, given: float | None) -> float:
    """The pushover's largest rotation: ``given``, or 10 θ_on, within :data:`MAX_ROTATION`."""
    if given is not None:
        return given
    theta_max = 10.0 * _theta_on(scene)
    if theta_max > MAX_ROTATION:
        raise InputError(f"--theta-max: the default 10 θ_on = {theta_max:.4g} rad is beyond "
                         f"the small-rotation model's {MAX_ROTATION:g} rad; give --theta-max "
                         f"in (0, {MAX_ROTATION:g}]")
    return theta_max


def _pushover(model, scene, theta_max, steps):
    from ..continuum import rotation_pushover
    from ..continuum.output.series import rotation_schedule

    N, theta_on = scene.structure.vertical_weight, _theta_on(scene)
    rotations = rotation_schedule(theta_max, 40 if steps is None else steps, theta_on)
    say(f"rotation pushover at N = {N:g} to θ = {theta_max:.4g} rad in {rotations.size - 1} "
         f"steps (elastic half-plane uplift at θ_on = {theta_on:.4g} rad)")
    started = time.perf_counter()

    def progress(k, n, state):
        say(f"step {k + 1}/{n}: θ = {state.q[2]:.4g} rad, M = {state.M:.4g}, "
             f"{state.iterations} Newton iterations{eta(started, k + 1, n)}")

    return rotation_pushover(model, N, rotations, record_fields=True, progress=progress)


def _dynamic(model, scene, motion, threads: int, out, started: float, flag, command: str):
    """The dynamic run, or the exit code of a run that was interrupted (``flag``, checked at
    every step of the time loop: the rows computed so far written to ``result.nc``, marked
    incomplete, no completion marker) or that failed its energy check (its result written,
    marked failed)."""
    from ..continuum.dynamics.run import DynamicOptions, run_dynamic
    from ..continuum.dynamics.run_control import EnergyBalanceError, Interrupted

    duration = scene.analysis.duration or motion.duration
    say(f"{model.options.dynamics} dynamics (continuum.dynamics), {duration:g} s of "
         f"{motion.name} (--set analysis.duration=T runs the first T s)")
    report = _dynamic_progress(duration, started)

    def progress(k, n, state):
        flag.defer()  # the loop has rows to keep: a signal now only sets the flag
        report(k, n, state)
        if k < n:  # at the last step the run is whole: it is written as after the loop
            flag.check()

    try:
        return run_dynamic(model, scene, motion, DynamicOptions(threads=threads),
                           progress=progress)
    except Interrupted as exc:
        if exc.result.time.size == 0:  # stopped before the loop's first row: nothing to keep
            raise KeyboardInterrupt(flag.name) from None
        out.start_writing()
        path = exc.result.save(out.path / "result.nc")
        until = exc.result.metadata.get("completed_until", float(exc.result.time[-1]))
        print(f"upliftlab: interrupted at t = {until:.4g} s of the motion ("
              f"{flag.name or 'Ctrl-C'}); wrote the rows computed so far to {path} "
              "(attribute incomplete = 1, "
              f"completed_until = {until:.4g} s); resume with: {command}", file=sys.stderr)
        return EXIT_INTERRUPTED
    except EnergyBalanceError as exc:
        out.start_writing()
        exc.result.metadata["energy_check"] = "failed"
        path = exc.result.save(out.path / "result.nc")
        print(f"upliftlab: error: {exc} (result written to {path}, energy_check = failed)",
              file=sys.stderr)
        return EXIT_NUMERICS


def _command(args) -> str:
    """The command line that runs this command again."""
    return shlex.join(["upliftlab", *getattr(args, "argv", sys.argv[1:])])


def _dynamic_progress(duration: float, started: float):
    """A ``progress(k, n, state)`` that reports every 5 % of a dynamic run: simulated time,
    elapsed wall time and the ETA from the rate of the time loop so far."""
    first = {}

    def progress(k, n, state):
        now = time.perf_counter()
        first.setdefault("time", (now, k))
        tick = 20 * k // max(n, 1)
        if k and k != n and tick <= first.get("tick", -1):
            return
        first["tick"] = tick
        t0, k0 = first["time"]
        rate = (now - t0) / (k - k0) if k > k0 else math.nan
        eta = rate * (n - k)
        say(f"t = {duration * k / max(n, 1):.3f} of {duration:g} s ({k / max(n, 1):.0%}), "
             f"elapsed {now - started:.1f} s, ETA {eta:.0f} s"
             + ("" if math.isfinite(eta) else " (measuring)")
             + f": θ = {state.q[2]:.4g} rad, N = {state.N:.4g}")

    return progress
