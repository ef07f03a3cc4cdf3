"""What does each model cost for the error it leaves? Runtime against error on a panel of scenes.

For every scene of a panel (the paper's short- and long-period buildings in Cases A, B and C,
the shear wall, pulses at several intensities) every model runs at every discretization:

* two springs: ``edges`` (±b) and ``equivalent`` (±b/√3);
* a uniform Winkler bed of N springs, N = 10 … 640;
* each integrator (``events``, ``rk4``, ``abm4``, ``newmark``, ``hht``) at a ladder of steps
  Δt = record Δt / 2^(k₀ + r), r = 0, 1, …, where k₀ is the first level inside the
  integrator's stability limit for that model (0 for the implicit ones);
* continuum mesh levels, when :mod:`upliftlab.continuum.dynamics.run` exists (the summary says
  when they were not run).

The error of a run is |value − reference| / max(|reference|, floor) in four quantities: peak
superstructure deformation u, peak base rotation θ, peak edge uplift and residual settlement.
The reference is the finest discretization: the event stepper on the largest bed at
``reference_dt``. Its convergence is checked by the change from the next-finer level down: the
bed of half as many springs at the same step, and the same bed at twice the step.

**Runtime** is the wall time of a whole reduced run (model, step choice, integration, peaks) in a
single-threaded worker process, the median of up to ``repeats`` repeats (fewer once a point's
runs have taken ``repeat_budget`` s), after a warm-up run of the same integrator in that process.
Runtimes are **stored with their measurement context** (host, CPU, thread settings, versions,
the number of concurrent workers and the time of measurement): the context is part of each
point's key, so re-running on the same machine recomputes nothing, and another machine measures
everything afresh. The summary states the context and how many measurement sessions contributed.

**Its data** (:func:`compute`) is one :class:`xarray.Dataset`, ``speed_vs_error.nc``: every run
over ``scene``, ``model`` (``edges``, ``equivalent``, ``N=<springs>``, ``continuum-<n>``, with
its ``layout`` and ``springs``), ``integrator``, ``level`` (the step ladder's rung) and
``quantity``: step (s), runtime (s), value and error; per scene the reference and its
convergence. The summary (:func:`summarise`, :func:`key_numbers`), the tables ``points.csv`` and
``pareto.csv`` (:func:`write_tables`), the Pareto fronts and the figures are computed from it
alone, so :func:`upliftlab.open_study` of the output folder gives the same summary back.

Run it with ``upliftlab study speed_vs_error [--fast] [--out DIR]``.
"""

from __future__ import annotations

from .analysis import (Run, cheapest, continuum_note, converged, front, pareto_front, runs,
                       table_note)
from .dataset import model_label, runs_dataset
from .grid import (FAST_GRID, FLOOR_FRACTION, FULL_GRID, Grid, IMPLICIT, INTEGRATORS, LABELS,
                   MAX_HALVINGS, MODELS, Options, QUANTITIES, STABILITY_MARGIN, STUDY, SceneSpec,
                   check_grid, check_options)
from .points import (continuum_status, evaluate_continuum, evaluate_point, load_spec,
                     measurement_context, motion_entry, point_scene, pulse_overrides, scales,
                     scene_points)
from .summary import key_numbers, summarise
from .tables import write_tables
from .workflow import DEFINITION, compute, run, write

__all__ = ["STUDY", "QUANTITIES", "INTEGRATORS", "MODELS", "SceneSpec", "Grid", "Options",
           "FULL_GRID", "FAST_GRID", "Run", "DEFINITION", "compute", "write", "run",
           "summarise", "key_numbers", "write_tables", "runs_dataset", "model_label", "runs",
           "front", "cheapest", "converged", "table_note", "continuum_note", "evaluate_point",
           "point_scene", "pareto_front", "motion_entry", "scales", "load_spec", "scene_points",
           "check_grid", "check_options", "measurement_context", "continuum_status",
           "pulse_overrides", "LABELS", "IMPLICIT", "FLOOR_FRACTION", "STABILITY_MARGIN",
           "MAX_HALVINGS", "evaluate_continuum"]
