"""The verification's records: a row (one anchor), an observed order, and
the builders of rows that decide pass or fail from a tolerance."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


STUDY = "verification"
PASS, FAIL, SKIP = "pass", "fail", "skipped"


# ---------------------------------------------------------------------------------------------
# Records
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Row:
    """One anchor: ``measured`` against ``expected`` (None for a bound), the ``error`` as
    ``kind`` (``relative`` (measured/expected − 1), ``absolute`` (measured − expected) or
    ``value``: the measured value itself against a bound), the ``tolerance`` text and
    ``status`` (pass, fail, skipped); ``unit`` of the measured and expected values
    (:func:`unit_of`, "–" for a ratio)."""

    group: str
    id: str
    quantity: str
    reference: str
    measured: float | None
    expected: float | None
    error: float | None
    kind: str
    tolerance: str
    status: str
    note: str = ""
    unit: str = ""

    @property
    def passed(self) -> bool:
        return self.status == PASS


@dataclass(frozen=True)
class Order:
    """An observed convergence order: ``slope`` of log error against log step (Δt or h)
    fitted over ``steps``/``errors``, against ``expected`` with the band [low, high]."""

    group: str
    case: str
    method: str
    steps: tuple[float, ...]
    errors: tuple[float, ...]
    slope: float | None
    expected: str
    low: float
    high: float
    status: str
    note: str = ""


#: The unit of each anchor's measured and expected values, by row id (a trailing ``*`` matches
#: any suffix). The reduced anchors run in kip, in and s (the paper's), the continuum ones in
#: kN and m per metre of footing length (plane strain); "–" marks a ratio.
UNITS = {"K_thth": "kip·in/rad", "K_Xth": "kip/rad", "K_thV": "kip", "K_VV": "kip/in",
         "reaction_*": "kip", "moment_*": "–", "bonded_*": "s", "nj_*": "in",
         "pushover_*": "–", "onset_edges": "kip", "onset_equivalent": "kip",
         "onset_winkler*": "kip", "M_ult": "kip·in", "yield_rotation": "–",
         "drop_dy_*": "in", "drop_dt_*": "s", "drop_energy": "kip·in", "drop_eps_*": "–",
         "housner_period": "s", "housner_restitution": "–", "energy_*": "–",
         "K_r*": "kN·m/m per rad", "flamant": "m²/kN", "prandtl*": "–", "p1_locking": "–",
         "onset_e": "–", "onset_theta": "rad", "error_*": "–"}


def unit_of(id: str) -> str:
    """The unit of anchor ``id`` (:data:`UNITS`); "" for an id it does not list (the report's
    test requires one for every anchor of the verification)."""
    if id in UNITS:
        return UNITS[id]
    for key, unit in UNITS.items():
        if key.endswith("*") and id.startswith(key[:-1]):
            return unit
    return ""


def relative_row(group, id, quantity, reference, measured, expected, tol, note="") -> Row:
    err = float(measured) / float(expected) - 1.0
    ok = abs(err) <= tol
    return Row(group, id, quantity, reference, float(measured), float(expected), err,
               "relative", f"abs(rel) ≤ {tol:.3g}", PASS if ok else FAIL, note, unit_of(id))


def absolute_row(group, id, quantity, reference, measured, expected, tol, note="") -> Row:
    err = float(measured) - float(expected)
    ok = abs(err) <= tol
    return Row(group, id, quantity, reference, float(measured), float(expected), err,
               "absolute", f"abs(err) ≤ {tol:.3g}", PASS if ok else FAIL, note, unit_of(id))


def bound_row(group, id, quantity, reference, measured, low, high, note="") -> Row:
    """The measured value itself within [low, high] (either may be ±inf)."""
    ok = low <= measured <= high
    text = (f"≤ {high:.3g}" if low == -math.inf else f"≥ {low:.3g}" if high == math.inf
            else f"in [{low:.3g}, {high:.3g}]")
    return Row(group, id, quantity, reference, float(measured), None, float(measured), "value",
               text, PASS if ok else FAIL, note, unit_of(id))


def skipped_row(group, id, quantity, reference, tolerance, note) -> Row:
    return Row(group, id, quantity, reference, None, None, None, "", tolerance, SKIP, note,
               unit_of(id))


def order_row(group, case, method, steps, errors, expected, low, high, note="") -> Order:
    slope = float(np.polyfit(np.log(steps), np.log(errors), 1)[0])
    ok = low <= slope <= high
    return Order(group, case, method, tuple(float(s) for s in steps),
                 tuple(float(e) for e in errors), slope, expected, low, high,
                 PASS if ok else FAIL, note)


# ---------------------------------------------------------------------------------------------
# Reduced model
# ---------------------------------------------------------------------------------------------

R = "reduced"
C = "continuum"


@dataclass(frozen=True)
class CheckContext:
    fast: bool
    record: object | None
    record_note: str
