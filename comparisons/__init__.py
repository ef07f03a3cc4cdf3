"""upliftlab.comparisons: studies that put models side by side on the same scene.

The machinery: :class:`Store` (content-addressed results, one file per point),
:func:`run_sweep` (parallel, chunked, resumable sweeps on local processes or a Dask cluster) and
the study protocol (:mod:`.protocol`): each study declares a :class:`Study` record (a stable
name, its options record, ``compute(scene, context)`` and ``write(result, context)``) and is
run by :func:`run_study`; :func:`main_for` gives it its command line
(``python -m upliftlab.comparisons.<name>``). :data:`.registry.STUDIES` lists the studies of
the report in order. What the studies measure is defined once in :mod:`.measures`; the closed
forms they are checked against once in :mod:`upliftlab.anchors`.

* :mod:`.verification` and :mod:`.report` — every anchor's measured error; one HTML report.
* :mod:`.two_spring_equivalence` — when can a Winkler bed be replaced by two springs?
* :mod:`.winkler_vs_continuum` — how well does a calibrated Winkler bed match the continuum?
* :mod:`.speed_vs_error` — what each model and discretization costs for the error it leaves.
* :mod:`.fixed_vs_uplift` — Figs. 11–12 and a base-shear spectrum: fixed base against uplift.
* :mod:`.paper` — each conclusion of the founding paper, decided from runs.
* :mod:`.uplift_zone` — the uplift zone of a continuum rotation pushover.
* :mod:`.advise` — the cheapest model and discretization within a tolerance, measured per scene.

A large study is a package: ``grid`` or ``options`` (its parameters and their checks),
``points`` (the sweep's point function), the analysis modules, ``output``, ``figures``,
``summary`` (numbers and prose, computed from the data) and ``workflow`` (compute, run, the
study's definition and command line).
"""

from .protocol import Context, Study, main_for, run_study
from .store import Store, point_key
from .study import StudyResult
from .sweep import SweepProgress, run_sweep, sweep_executor

__all__ = ["Store", "point_key", "run_sweep", "sweep_executor", "SweepProgress", "StudyResult",
           "Study", "Context", "run_study", "main_for"]
