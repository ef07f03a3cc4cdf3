"""The q–z bed: QzSimple-class springs calibrated from the continuum's vertical pushover.

Its springs' capacities and stiffnesses (:mod:`.calibration`), the backbone fitted to the
whole pushover (:mod:`.fit`), and the bed's builder in the registry (:mod:`.bed`).
"""

from __future__ import annotations

from .bed import build_qz, qz_bed_fit
from .calibration import QzCalibration, calibrate_qz, qz_stiffnesses, spring_capacities
from .fit import QzFit, fit_backbone

__all__ = ["build_qz", "qz_bed_fit", "QzCalibration", "calibrate_qz", "qz_stiffnesses",
           "spring_capacities", "QzFit", "fit_backbone"]
