"""The Winkler beds calibrated from continuum quantities, in one registry (:data:`BEDS`).

A bed builder takes the continuum's numbers at one point (a :class:`BedReference`: N, B, h,
the footing's K_v and K_r, the soil's V_ult, G and ν, and by name further quantities such as
the vertical pushover or the dynamic impedance) and returns the reduced model's
``[foundation]`` table of that bed (:func:`bed_foundation`). The registry's entry of a bed
says what it is, its short code, what it matches and what it needs (:mod:`.registry`).

The calibrations, one idea each: the four base beds' stiffness (:mod:`.stiffness`, built by
:mod:`.base`; to the box's statics, or to the half-plane's stiffness at the structure's rocking
frequency, :mod:`.rocking_stiffness`), their radiation dashpots (:mod:`.radiation`,
:mod:`.dashpots`), the q–z bed's springs and backbone (:mod:`.qz`), the capacity profile fitted
to the continuum's rocking (:mod:`.fitted`), the macro-element's parameters fitted to the
continuum's statics (:mod:`.macro`) and the element under a point's structure
(:mod:`.macro_bed`); the rotation paths on which beds and continuum are pushed over and the values
they are compared in (:mod:`.pushover`); and the continuum runs they are calibrated from and
compared against, one point function for both Winkler studies (:mod:`.continuum_points`).

Nothing here imports a study: the Winkler studies and the advisor use the beds.
"""

from __future__ import annotations

from .base import BASE_SCENE, BedReference, base_table
from .pushover import (FLOORS, BedResponse, bed_response, bed_rocking, bed_scene, cyclic_path,
                       path_values, pushover_record, rotation_path)
from .registry import BEDS, BedEntry, bed_foundation, bed_names
from .stiffness import (CALIBRATIONS, LABELS, Calibration, EndStiffening, calibrate,
                        end_stiffening, end_zone)

__all__ = ["BEDS", "BedEntry", "BedReference", "bed_foundation", "bed_names", "BASE_SCENE",
           "base_table", "CALIBRATIONS", "LABELS", "Calibration", "EndStiffening", "calibrate",
           "end_stiffening", "end_zone", "FLOORS", "BedResponse", "bed_response", "bed_rocking",
           "bed_scene", "cyclic_path", "path_values", "pushover_record", "rotation_path"]
