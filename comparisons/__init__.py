"""upliftlab.comparisons: studies that put models side by side on the same scene.

The machinery: :class:`Store` (content-addressed results, one file per point) and
:func:`run_sweep` (parallel, chunked, resumable sweeps on local processes or a Dask cluster).
Each study is a module with ``run(scene, fast) -> result`` and ``main()``:

* :mod:`.two_spring_equivalence` — when can a Winkler bed be replaced by two springs?
* :mod:`.winkler_vs_continuum` — how well does a calibrated Winkler bed match the continuum?
* :mod:`.verification` and :mod:`.report` — every anchor's measured error; one HTML report.
* :mod:`.speed_vs_error` — what each model and discretization costs for the error it leaves.
* :mod:`.advise` — the cheapest model and discretization within a tolerance, measured per scene.
* :mod:`.fixed_vs_uplift` — Figs. 11–12 and a base-shear spectrum: fixed base against uplift.
"""

from .store import Store, point_key
from .study import StudyResult
from .sweep import SweepProgress, run_sweep, sweep_executor

__all__ = ["Store", "point_key", "run_sweep", "sweep_executor", "SweepProgress", "StudyResult"]
