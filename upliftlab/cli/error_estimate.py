"""``upliftlab continuum SCENE --analysis dynamic --error-estimate[=3]``: the run's peaks, each
with its estimated discretisation error.

After the run on the scene's own mesh (``n`` across) and its files, the same run on ``n/2``
across (``--error-estimate=3``: and ``n/4``), each with its progress and its data files in
``<out>/error_estimate/<m>_across/`` (no pictures); then ``error_estimate.nc`` (CF-1.10) and
``error_estimate.json`` in ``<out>``, and the estimate in the summary (``--json``:
``error_estimate``). The method, the order and the flags:
:mod:`upliftlab.continuum.dynamics.mesh_error`. The extra runs are in the cost checked against
``--budget`` before any work; a scene whose mesh does not halve is refused then too.
"""

from __future__ import annotations

import json
import sys
import time

from ..checks import InputError
from .common import number, say
from .exits import EXIT_INTERRUPTED, EXIT_NUMERICS

__all__ = ["add_argument", "meshes", "coarser", "run_coarser", "write_estimate", "SUBFOLDER",
           "ESTIMATE_NAMES", "COARSER_FILES"]

#: The subfolder of ``--out`` that holds the coarser runs' files.
SUBFOLDER = "error_estimate"
#: The estimate's files in ``--out``.
ESTIMATE_NAMES = ("error_estimate.nc", "error_estimate.json")
#: The glob (in ``--out``) of the coarser runs' files, whose folders are named by the meshes.
COARSER_FILES = f"{SUBFOLDER}/*_across/*"


def add_argument(parser) -> None:
    parser.add_argument("--error-estimate", nargs="?", const="2", metavar="MESHES",
                        help="dynamic: run the scene on the next coarser mesh too (n/2 "
                             "across; =3: and n/4) and give each peak its estimated "
                             "discretisation error (Richardson where the order holds), in "
                             f"<out>/error_estimate.nc; coarser runs' files in <out>/{SUBFOLDER}")


def meshes(args) -> int | None:
    """The meshes of ``--error-estimate`` (2 or 3), or None; refused off the dynamics."""
    value = getattr(args, "error_estimate", None)
    if value is None:
        return None
    if args.analysis != "dynamic":
        raise InputError(f"--error-estimate = {value}: has no effect: only the dynamic "
                         "analysis takes it")
    return number("--error-estimate", value, integer=True, low=2, high=3)


def coarser(scene, count: int | None) -> list:
    """The coarser scenes of ``--error-estimate`` (none without it), checked."""
    if not count:
        return []
    from ..continuum.dynamics.error_estimate import coarser_scenes
    return coarser_scenes(scene, count)


def run_coarser(scenes, motion, threads: int, out, flag, dynamic_progress, command: str):
    """Each coarser run of ``scenes`` in turn, its files written as it ends; returns
    [(model, result)] or the exit code of a run that was interrupted or failed (the finest
    run's files are kept; the folder is not marked complete)."""
    from ..continuum import build_model
    from ..continuum.dynamics.run import DynamicOptions, run_dynamic
    from ..continuum.dynamics.run_control import EnergyBalanceError, Interrupted
    from ..continuum.output.series import write_outputs

    done = []
    for k, scene in enumerate(scenes, start=2):
        started = time.perf_counter()
        model = build_model(scene)
        across = model.options.elements_across
        say(f"error estimate: run {k} of {len(scenes) + 1}, {across} across "
            f"({model.mesh.nelements} elements, {model.dofs} DOFs)")
        report = dynamic_progress(scene.analysis.duration or motion.duration, started)

        def progress(i, n, state):
            flag.defer()
            report(i, n, state)
            if i < n:
                flag.check()

        folder = out.path / SUBFOLDER / f"{across}_across"
        try:
            result = run_dynamic(model, scene, motion, DynamicOptions(threads=threads),
                                 progress=progress)
        except Interrupted:
            print(f"upliftlab: interrupted ({flag.name or 'Ctrl-C'}) in the error estimate's "
                  f"run on {across} across; the run on the scene's own mesh is written to "
                  f"{out.path}, the estimate is not; resume with: {command}", file=sys.stderr)
            return EXIT_INTERRUPTED
        except EnergyBalanceError as exc:
            exc.result.metadata["energy_check"] = "failed"
            folder.mkdir(parents=True, exist_ok=True)
            path = exc.result.save(folder / "result.nc")
            print(f"upliftlab: error: the error estimate's run on {across} across: {exc} "
                  f"(result written to {path}, energy_check = failed; no estimate)",
                  file=sys.stderr)
            return EXIT_NUMERICS
        folder.mkdir(parents=True, exist_ok=True)
        written = write_outputs(folder, model, result, scene=scene, renders=False,
                                progress=say)
        say(f"error estimate: {across} across solved and written in "
            f"{time.perf_counter() - started:.1f} s")
        done.append((model, result, list(written.values())))
        if flag.stopped:
            print(f"upliftlab: interrupted ({flag.name}) after the error estimate's run on "
                  f"{across} across; no estimate written; resume with: {command}",
                  file=sys.stderr)
            return EXIT_INTERRUPTED
    return done


def write_estimate(out, scene, model, result, coarse) -> tuple[object, list]:
    """The estimate from the finest run and the ``coarse`` runs of :func:`run_coarser`,
    written to ``error_estimate.nc`` and ``error_estimate.json``; returns (estimate, every
    file written, the coarser runs' included)."""
    from ..continuum.dynamics.error_estimate import estimate_from_results
    from ..results import write_text

    estimate = estimate_from_results([result, *(r for _, r, _ in coarse)],
                                     [model, *(m for m, _, _ in coarse)], scene)
    files = [f for _, _, written in coarse for f in written]
    netcdf, record = ESTIMATE_NAMES
    files.append(estimate.save(out.path / netcdf))
    files.append(write_text(out.path / record,
                            json.dumps(estimate.to_dict(), indent=2) + "\n"))
    say(f"wrote {files[-2]} and {files[-1].name}")
    return estimate, files
