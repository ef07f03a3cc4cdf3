"""The continuum's run of a map point with its foundation energy E_F (:mod:`.foundation_energy`):
the point function of the map's energy pass, stored like :func:`.points.evaluate_dynamic`.

The run is the same (same scene, same options, same code), so its measures are those of the
point's dynamic run; it adds E_F, taken from the structure's histories that the dynamic run's
record does not keep. A separate point function, so that E_F is made where a map asks for it.
"""

from __future__ import annotations

import time
from collections.abc import Mapping

import numpy as np

from ...framework.sources import point_sources
from ...framework.store import point_function
from .foundation_energy import structure_energy_terms
from .points import _timed_run, _warm_kernels, continuum_measures, point_scene

__all__ = ["continuum_energy_terms", "evaluate_energy"]


def continuum_energy_terms(scene, result) -> dict:
    """The structure's energy balance and E_F (``foundation``) of a continuum dynamic
    ``result`` of ``scene`` (:func:`.foundation_energy.structure_energy_terms`; force·length
    per length), from its footing's and story's histories and the structure's matrices."""
    from ....continuum.dynamics.superstructure import structure_matrices

    z = structure_matrices(scene)
    t = np.asarray(result.time, dtype=float)
    dofs = np.column_stack([np.asarray(result.footing, dtype=float),
                            np.asarray(result.structure_u, dtype=float).reshape(t.size)])
    return structure_energy_terms(t, dofs, np.asarray(result.structure_velocity).reshape(t.size),
                                 result.ground_acceleration, z.M, z.C, z.K, z.r, z.gravity)


@point_function("upliftlab.comparisons.winkler_map:evaluate_energy",
                models=("continuum",), tolerance=1e-4,
                sources=point_sources(__name__, __package__))
def evaluate_energy(point: Mapping) -> dict:
    """One continuum dynamic run of a point as :func:`.points.evaluate_dynamic` makes it, with
    ``foundation_energy`` E_F (scene units, force·length per length) and the structure's
    balance it comes from (``energy_terms``), the run's ``measures``
    and ``wall_time_s`` (s). A run the solver gives up on, or that ends in a bearing failure,
    has no E_F: ``{"error": kind and message, "wall_time_s"}`` (plus ``"failure": "bearing"``),
    which the map leaves out."""
    from ....continuum import BearingFailure, ContactError, ConvergenceError
    from ....continuum.dynamics.run_control import EnergyBalanceError

    _warm_kernels(point)
    scene = point_scene(point)
    started = time.perf_counter()
    try:
        _, result, wall = _timed_run(scene)
    except (ConvergenceError, ContactError, EnergyBalanceError) as exc:
        out = {"error": f"{type(exc).__name__}: {' '.join(str(exc).split())}",
               "wall_time_s": time.perf_counter() - started}
        if isinstance(exc, BearingFailure):
            out["failure"] = "bearing"
        return out
    *_, measures = continuum_measures(scene, result)
    terms = continuum_energy_terms(scene, result)
    return {"foundation_energy": terms["foundation"], "energy_terms": terms,
            "measures": measures, "wall_time_s": wall}
