"""upliftlab.comparisons: studies that put models side by side on the same scene.

By role, each one way up from the one before:

* :mod:`.framework` — what every study shares: the protocol (:class:`Study`, :func:`run_study`),
  the store keyed by what was asked (:class:`Store`), parallel resumable sweeps
  (:func:`run_sweep`), the checks of stale records (:mod:`.framework.freshness`), what the
  studies measure (:mod:`.framework.measures`) and their figures' records.
* :mod:`.studies` — one package per study, in the report's order
  (:data:`.studies.registry.STUDIES`): verification, two-spring equivalence, Winkler against
  the continuum, the Winkler map, speed against error, fixed base against uplift, the paper's
  conclusions, the uplift zone.
* :mod:`.report` — one self-contained HTML report of every study; :mod:`.advise` — the
  cheapest model within a tolerance for one scene; :mod:`.opensees` — the scene as an
  OpenSees model, run beside upliftlab.

Nothing here is a command line: :mod:`upliftlab.cli` runs these (``upliftlab study NAME``,
``upliftlab report``, ``upliftlab advise``, ``upliftlab opensees``) and turns what they raise
into exit codes.
"""

from .framework.protocol import Context, Study, run_study
from .framework.store import Store, point_key
from .framework.study import StudyResult
from .framework.sweep import SweepProgress, run_sweep, sweep_executor

__all__ = ["Store", "point_key", "run_sweep", "sweep_executor", "SweepProgress", "StudyResult",
           "Study", "Context", "run_study"]
