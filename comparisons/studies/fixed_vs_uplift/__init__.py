"""Fixed base against uplift allowed: Ewing's Figs. 11–12 and a base-shear spectrum.

**Figs. 11–12.** The paper's short-period (T = 0.15 s) and long-period (T = 0.59 s) buildings
under El Centro 1940 N-S, in the reduced model: the ``fixed`` case (θ and V locked) against
Case C (elasto-plastic springs with 10 % damping and impact damping, ε = 0.7; uplift allowed),
on the scenes' Winkler bed of 12 springs, as drawn in Fig. 1(b). The continuum counterpart
(a stiff bonded footing against unilateral contact) runs when
:mod:`upliftlab.continuum.dynamics.run` exists; the summary says when it was not run.

**Spectrum** (in the manner of Yim and Chopra 1985). The superstructure period T is swept over
0.05–3 s with everything else held (base width, height and so the aspect ratio h/b = 2.8, the
weights, the rotary inertia of each building's base body, the foundation), for the fixed base,
uplift allowed in Case C, and uplift allowed on Case A's elastic springs with 40 % damping (the
model of Yim and Chopra). Peak base shear (as a coefficient V/W) and peak deformation u are
compared as ratios uplift/fixed at each period. The reduced runs go through
:func:`upliftlab.reduced.run_batch`; every run is kept in a content-addressed
:class:`.store.Store`, so running the study again computes nothing already stored. The
summary's statements (the period ranges over which uplift reduces each peak, and by how much)
are computed from the data.

The result is one :class:`xarray.Dataset` (:func:`.dataset.study_dataset`: Figs. 11–12 by
``building`` and ``support``, the spectrum by ``family``, ``support`` and ``period``), written
as ``fixed_vs_uplift.nc`` beside its CSV tables; the summary is computed from it alone
(:func:`.summary.summarise`), so :func:`upliftlab.open_study` of the output folder gives it back.

Run it with ``upliftlab study fixed_vs_uplift [--fast] [--out DIR]``.
"""

from __future__ import annotations

from .analysis import Ranges, at, figure_ratio, ratio, reduction_ranges, spectrum_ranges
from .dataset import study_dataset
from .grid import (BUILDINGS, FAST_GRID, FIGURES, FULL_GRID, Grid, NO_CHANGE, OUTPUT_DT, Options,
                   PAPER_FIG11_PEAK_U, PAPER_PERIODS, STUDY, SUPPORTS, SUPPORT_LABELS, check_grid)
from .runs import figure_run, run_spectrum_batch, spectrum_points
from .summary import key_numbers, summarise
from .workflow import DEFINITION, compute, run, write

__all__ = ["STUDY", "BUILDINGS", "SUPPORTS", "Grid", "FULL_GRID", "FAST_GRID", "Ranges",
           "Options", "DEFINITION", "compute", "write", "run", "study_dataset", "summarise",
           "key_numbers", "figure_ratio", "ratio", "at", "spectrum_ranges", "figure_run",
           "spectrum_points", "reduction_ranges", "check_grid",
           "PAPER_FIG11_PEAK_U", "NO_CHANGE", "SUPPORT_LABELS", "PAPER_PERIODS", "OUTPUT_DT",
           "FIGURES", "run_spectrum_batch"]
