"""Winkler beds against the continuum, mapped: where a calibrated bed of springs is enough.

Every calibration of :data:`...beds.BEDS` (a registry: a new calibration plugs in as one entry,
``name -> build(continuum reference numbers, options) -> [foundation] table``) is run against
the plane-strain continuum (:mod:`upliftlab.continuum`) over a grid of

* soil: the clay of ``strip_footing_clay`` (Tresca, c_u) and a frictional soil (Mohr–Coulomb,
  c and φ; the continuum's stiffness does not grow with confinement);
* FS_v: N = V_ult/FS_v with V_ult the continuum's own vertical capacity of that soil (a stored
  vertical pushover), so the map's FS_v is the continuum's;
* h/B and the structure's fixed-base period;
* intensity: the PGA over a_up = g B/(6h), the rigid block's quasi-static uplift acceleration on
  a uniform tensionless Winkler bed (e = B/6);
* motions: Ricker pulses, El Centro (on ``UPLIFTLAB_MOTIONS``) and FEMA P695 far-field components
  (the ``records`` extra), each run in full.

Per soil the continuum's statics (K_v, K_r, V_ult; and its dynamic impedance when a bed needs
it, :mod:`.impedance_points`) and per point one continuum dynamic run are points of
:func:`.sweep.run_sweep` in a content-addressed store (resumable, local processes or Dask with
``--scheduler``), each stored with its own wall time and keyed by what was asked (the point
and the continuum's revision, :mod:`..store`), so that a store kept with the repository
(``benchmarks/winkler_map_store``) is reused while the continuum's numbers are unchanged (a
sample made again checks records of earlier code, :mod:`..freshness`); each bed's reduced run of
the same point is live
(milliseconds) and timed in the same run. Measured alike on both models:
peak θ, peak edge uplift, residual settlement, residual rotation, peak u, peak base shear; and
the foundation energy E_F, the energy the structure lost to its foundation (:mod:`.energy`), at
the points whose continuum energy run is stored (``--energy`` makes them: one more continuum run
per point, :mod:`.energy_points`).
Before any run the study logs how many continuum runs it will make and what they should cost
(:mod:`.cost`), and refuses above ``--budget``.

The result is labelled data (:mod:`.dataset`): an :class:`xarray.DataTree` of ``map`` (every
point by soil, fs_v, h_over_B, period, intensity, motion, calibration and measure) and
``statics`` (per soil and FS_v, :mod:`.statics_dataset`), written as ``map.nc`` and
``statics.nc`` (NetCDF-4, CF) and opened again by :func:`upliftlab.open_study`::

    tree["map"].error.sel(h_over_B=1.5, calibration="uniform", measure="theta")

The summary (:mod:`.summary`) reads that data alone. Written too: figures (one question each),
``summary.md``/``summary.json``: each bed's region within 10 % in peak θ and edge uplift and
20 % in residual settlement, the calibration to pick per quantity with the median and 90th
percentile of its error, the share of the map the best bed covers, the speed of each bed.

Run it with ``upliftlab study winkler_map [--fast] [--out DIR] [--scheduler
ADDR] [--budget SECONDS] [--energy]``.
"""

from __future__ import annotations

from .analysis import (Analysis, BedRegion, Pick, Share, Speed, analyse, cell_passes,
                       median_over_motions)
from .cost import Estimate, estimate_cost, impedance_dofs, timed_dynamic_runs
from .grid import (FAST_GRID, FAST_OPTIONS, FLOOR_FRACTION, FULL_GRID, FULL_OPTIONS, Grid,
                   MEASURES, Options, SOILS, STUDY, check_grid, check_options, grid_with)
from .impedance_points import evaluate_impedance, impedance_point_of, soil_impedance
from .dataset import POINT_DIMS
from .maps import compute_map, estimate_map
from .bed_runs import reduced_measures, run_bed
from .energy_points import evaluate_energy
from .motions import study_motions
from .points import continuum_measures, evaluate_dynamic, scales, story_constants
from .reference import REFERENCES, handbook_sway, reference_continuum, reference_soil
from .rocking import pushover_points
from .statics import SoilStatics, evaluate_static
from .summary import key_numbers, summarise
from .workflow import DEFINITION, KEPT_STORE, KEPT_STORES, compute, run, write

__all__ = ["STUDY", "SOILS", "MEASURES", "Grid", "Options", "FULL_GRID", "FAST_GRID",
           "FULL_OPTIONS", "FAST_OPTIONS", "check_grid", "check_options", "grid_with", "Estimate",
           "estimate_cost",
           "POINT_DIMS", "compute_map", "estimate_map", "SoilStatics", "evaluate_static",
           "evaluate_dynamic", "evaluate_energy", "run_bed", "Analysis", "BedRegion", "Pick",
           "Share", "Speed",
           "analyse", "cell_passes", "median_over_motions", "key_numbers", "summarise",
           "DEFINITION", "compute",
           "write", "run", "KEPT_STORE", "FLOOR_FRACTION", "impedance_dofs",
           "timed_dynamic_runs", "evaluate_impedance", "impedance_point_of", "soil_impedance",
           "reduced_measures", "continuum_measures", "scales", "story_constants",
           "pushover_points", "study_motions", "REFERENCES", "handbook_sway", "reference_soil",
           "reference_continuum", "KEPT_STORES"]
