"""A dynamic run with the estimated discretisation error of each of its peaks: the run on its
own mesh (``n`` elements across the footing) and on the next coarser one (``n/2``; with
``meshes=3`` also ``n/4``), compared by :func:`~.mesh_error.mesh_error` (the method, the order
and the flags are in :mod:`~.mesh_error`).

:func:`coarser_scenes` gives the scenes of the coarser runs, checked before any work (an odd
``n``, or a coarser mesh below :data:`~upliftlab.scenes.soil.MIN_ELEMENTS_ACROSS` across, is an
:class:`~upliftlab.checks.InputError`); :func:`estimate_error` runs them all and returns the
estimate with the runs' results; :func:`estimate_from_results` makes the estimate from runs
done elsewhere (the command line's, which writes each run's files as it ends).
"""

from __future__ import annotations

from ...checks import InputError
from .mesh_error import MeshErrorEstimate, mesh_error

__all__ = ["coarser_scenes", "estimate_error", "estimate_from_results", "history",
           "MESHES"]

#: How many meshes an estimate may use: two (the order from the committed study) or three
#: (the order observed on the run's own meshes).
MESHES = (2, 3)


def coarser_scenes(scene, meshes: int = 2) -> list:
    """The scenes of the ``meshes − 1`` coarser runs of ``scene`` (``n/2``, then ``n/4``
    elements across), each with ``continuum.elements_across`` overridden; refused before any
    work where ``n`` does not halve to a mesh the code allows."""
    from ...scenes import ContinuumOptions
    from ...scenes.soil import MIN_ELEMENTS_ACROSS

    if meshes not in MESHES:
        raise InputError(f"--error-estimate = {meshes!r}: the number of meshes; valid: "
                         f"{' or '.join(map(str, MESHES))}")
    n = (scene.continuum or ContinuumOptions()).elements_across
    factor = 2 ** (meshes - 1)
    if n % factor or n // factor < MIN_ELEMENTS_ACROSS:
        raise InputError(f"continuum.elements_across = {n}: --error-estimate={meshes} runs "
                         f"{', '.join(f'{n}/{2 ** k}' for k in range(1, meshes))} across as "
                         f"well; valid: a multiple of {factor} of at least "
                         f"{factor * MIN_ELEMENTS_ACROSS} (the coarsest mesh has at least "
                         f"{MIN_ELEMENTS_ACROSS} across)")
    return [scene.with_overrides(f"continuum.elements_across={n // 2 ** k}")
            for k in range(1, meshes)]


def history(result) -> dict:
    """The θ and v histories of a :class:`~.result.DynamicResult` ({"time", "theta", "v"})."""
    import numpy as np

    footing = np.asarray(result.footing)
    return {"time": np.asarray(result.time), "theta": footing[:, 2], "v": footing[:, 1]}


def estimate_from_results(results, models, scene) -> MeshErrorEstimate:
    """The estimate from the :class:`~.result.DynamicResult` of each run (finest first) and its
    model; ``scene`` (the finest run's) gives the units and the name."""
    from ..output.summaries import dynamic_summary

    summaries = [dynamic_summary(r, width=m.width) for r, m in zip(results, models)]
    across = [m.options.elements_across for m in models]
    dt = [float(r.metadata["dt"]) for r in results]
    return mesh_error(summaries, [history(r) for r in results], across, dt,
                      units={"length": scene.units.length},
                      metadata={"scene": scene.name, "scene_digest": scene.digest,
                                "method": results[0].metadata.get("method"),
                                "model": "continuum", "analysis": "mesh_error_estimate"})


def estimate_error(scene, motion, options=None, *, meshes: int = 2, progress=None):
    """``scene`` under ``motion`` run on its own mesh and on ``meshes − 1`` coarser ones with
    the same ``options`` (:class:`~.options.DynamicOptions`), finest first; returns
    ``(estimate, results)``: the :class:`~.mesh_error.MeshErrorEstimate` and the runs'
    :class:`~.result.DynamicResult`. ``progress`` as for
    :func:`~.run.run_dynamic`, for each run. Every coarser scene is checked before the first
    run (:func:`coarser_scenes`)."""
    from ..model import build_model
    from .options import DynamicOptions
    from .run import run_dynamic

    scenes = [scene, *coarser_scenes(scene, meshes)]
    options = options or DynamicOptions()
    results, models = [], []
    for s in scenes:
        model = build_model(s)
        results.append(run_dynamic(model, s, motion, options, progress=progress))
        models.append(model)
    return estimate_from_results(results, models, scene), results
