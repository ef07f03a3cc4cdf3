"""upliftlab.comparisons: studies that put models side by side on the same scene.

The machinery: :class:`Store` (content-addressed results, one file per point) and
:func:`run_sweep` (parallel, chunked, resumable sweeps on local processes or a Dask cluster).
Each study is a module with ``run(scene, fast) -> result`` and ``main()``:

* :mod:`.two_spring_equivalence` — when can a Winkler bed be replaced by two springs?
"""

from .store import Store, point_key
from .study import StudyResult
from .sweep import SweepProgress, run_sweep, sweep_executor

__all__ = ["Store", "point_key", "run_sweep", "sweep_executor", "SweepProgress", "StudyResult"]
