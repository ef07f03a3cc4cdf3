"""How well does a Winkler bed match the continuum? Calibrate beds from the continuum, compare.

The continuum (a plane-strain soil domain under a rigid footing, :mod:`upliftlab.continuum`) is
the reference. From it the study calibrates Winkler beds of compression-only springs
(:mod:`upliftlab.reduced`), under the same footing width B, vertical load N and height h:

* ``uniform``: a uniform bed whose bonded rocking stiffness Σ k_i x_i² equals the continuum's
  K_r (anchors §4: calibrate Winkler moduli to K_r);
* ``end_stiffened``: a bed with stiffer end zones (OpenSees ``ShallowFoundationGen`` /
  Harden–Hutchinson / ATC-40 practice) of a given end length R_e (a fraction of the half-width
  b; the default 1/3 is ATC-40's B/6 at each end), whose end-stiffness ratio R_k and total
  stiffness are solved so that the bed has both the continuum's K_r and the domain's K_v.
  K_v of a strip in 2D depends on the domain size (anchors §4), and no bed under the footing has
  K_θ/K_v > b²: when the target K_r/K_v lies outside what R_k ∈ [1, R_k,max] reaches, the bed
  keeps K_r exactly, takes the nearest R_k, and the K_v it then misses is reported;
* ``uniform_plastic``, ``end_stiffened_plastic``: the same beds with elasto-plastic springs that
  yield at FS_v times their static compression, FS_v = q_ult B/N with q_ult from the
  continuum's vertical pushover to failure.

**Compared** (bed against continuum, same N, B, h): K_r and K_v, the uplift-onset moment, the
monotonic M–θ (moment, contact length and settlement at several θ, the largest moment), a
cyclic M–θ path (peak moments, dissipated energy, settlement accumulated), the vertical
capacity, and, when :mod:`upliftlab.continuum.dynamics.run` is available, dynamic responses (peak
u, θ, edge uplift, residual settlement; histories overlaid) to the scene's pulse and, in full
mode, the first 10 s of El Centro; otherwise the summary says that the dynamic comparison was
not run. Fast mode puts the statics on a mesh of 8 elements across B and the dynamic pulse on
4 (seconds); full mode uses the scene's mesh (minutes for the statics, hours for El Centro).
Anchors checked on the way: K_r against π G B²/(8(1 − ν)), the
elastic half-plane's onset e/B = 1/4 against Winkler's 1/6 (anchors §3–4), the uniform bed's
M/M_up = 3 − 2√(θ_up/θ), and the capacity against Prandtl's (2 + π) c_u.

Each continuum analysis is one point of :func:`.sweep.run_sweep` in a content-addressed
:class:`.store.Store`: running the study again with the same inputs recomputes nothing. The
error table, the recommendation (the calibration with the smallest error per quantity and per
question) and every statement of ``summary.md`` are computed from the data.

The result is an :class:`xarray.DataTree` (:func:`.dataset.study_dataset`): the node
``comparison`` (the continuum's numbers, the paths over ``model``, the calibrations and the
error table over ``calibration`` and ``quantity``) and one node ``dynamic_<motion>`` per motion
(their time axes differ), written as ``comparison.nc`` and ``dynamic_<motion>.nc`` beside the
CSV paths; the summary is computed from it alone (:func:`.summary.summarise`,
:func:`.numbers.key_numbers`), so :func:`upliftlab.open_study` of the output folder gives it
back: ``open_study(folder)["comparison"].error.sel(calibration="uniform_plastic",
quantity="onset_moment")``.

Run it with ``upliftlab study winkler_vs_continuum [--fast] [--out DIR]``.
"""

from __future__ import annotations

from .analysis import (ErrorTable, Recommendation, error_table, quantity_names, recommend,
                       table_of)
from .closed_forms import closed_form_checks
from .dataset import comparison, dynamic_runs, motion_keys, study_dataset
from .dynamics import (DYNAMIC_LABELS, DYNAMIC_MEASURES, DynamicComparison, compare_dynamics,
                       dynamic_points, dynamics_available)
from .numbers import key_numbers
from .options import (DYNAMIC_MISSING, FAST_OPTIONS, FULL_OPTIONS, ONSET_ANCHOR, Options, STUDY,
                      WINKLER_ONSET, check_options)
from .reference import ContinuumReference, continuum_reference
from .summary import summarise
from .workflow import DEFINITION, compute, run, write

__all__ = ["STUDY", "Options", "FULL_OPTIONS", "FAST_OPTIONS", "check_options",
           "ContinuumReference", "ErrorTable", "Recommendation", "DynamicComparison",
           "error_table", "quantity_names", "table_of", "recommend", "DEFINITION", "compute",
           "write", "run", "study_dataset", "comparison", "dynamic_runs", "motion_keys",
           "summarise", "key_numbers", "DYNAMIC_MISSING", "DYNAMIC_MEASURES", "DYNAMIC_LABELS",
           "continuum_reference", "compare_dynamics", "dynamic_points", "dynamics_available",
           "closed_form_checks", "WINKLER_ONSET", "ONSET_ANCHOR"]
