"""The study's key numbers (``summary.json``), computed from its data alone: the tree
:func:`.workflow.compute` returns, or the same read back by :func:`upliftlab.open_study`.
:func:`read` gathers what both the numbers and the Markdown (:mod:`.summary`) state."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from ....units import UnitSystem, unit_system
from .analysis import ErrorTable, Recommendation, recommend, table_of
from .closed_forms import closed_form_checks
from .dataset import comparison, dynamic_runs
from .dynamics import DYNAMIC_MEASURES
from .options import finite_or_none

__all__ = ["Reading", "read", "key_numbers", "onset", "ordering"]


@dataclass(frozen=True, eq=False)
class Reading:
    """What the summary reads off the study's data: the ``comparison`` dataset ``ds``, the
    dynamic ``runs`` (datasets, in the order they ran), the error ``table`` and its
    ``recommendation``, the ``anchors`` (:func:`.closed_forms.closed_form_checks`), the
    scene's ``units`` and the wall time ``elapsed`` (s, the ``elapsed_s`` attribute)."""

    ds: object
    runs: list
    table: ErrorTable
    recommendation: Recommendation
    anchors: dict
    units: UnitSystem
    elapsed: float


def read(data) -> Reading:
    """The :class:`Reading` of the study's tree ``data``."""
    ds = comparison(data)
    table = table_of(ds)
    return Reading(ds, dynamic_runs(data), table, recommend(table, float(ds.attrs["adequate"])),
                   closed_form_checks(ds), unit_system(str(ds.attrs["units"])),
                   float(ds.attrs.get("elapsed_s", math.nan)))


def onset(ds, prefix: str = "") -> dict:
    """The continuum's uplift onset (θ, M, e) on the scene's soil (``prefix`` '') or elastic
    soil (``elastic_``), or why none was found (``error``)."""
    if f"{prefix}onset_error" in ds:
        return {"error": str(ds[f"{prefix}onset_error"].item())}
    return {k: ds[f"{prefix}onset_{k}"].item() for k in ("theta", "M", "e")}


def ordering(anchors: Mapping) -> bool:
    """Continuum uplift onset (elastic and the scene's soil) later than the Winkler bed's."""
    w = anchors["winkler_onset_e_over_B"]
    return bool(anchors["continuum_elastic_onset_e_over_B"] > w
                and anchors["continuum_monotonic_onset_e_over_B"] > w)


def _calibrations(ds) -> dict:
    out = {}
    for name in ds.calibration.values:
        c = ds.sel(calibration=name)
        law = str(c.law.item())
        out[str(name)] = {
            "layout": str(c.layout.item()), "law": law, "springs": int(c.springs),
            "K_v": c.bed_vertical_stiffness.item(), "K_r": c.bed_rocking_stiffness.item(),
            "end_stiffness_ratio": c.end_stiffness_ratio.item(),
            "end_length": c.end_length.item(),
            "yield_multiple": c.yield_multiple.item() if law != "elastic" else None,
            "matches": [m for m in str(c.matches.item()).split(",") if m],
            "note": str(c.note.item())}
    return out


def end_stiffening(ds) -> dict:
    """The end-stiffened bed's solve for R_k (the fields of
    :class:`...beds.stiffness.EndStiffening`)."""
    return {"target": ds.end_stiffening_target.item(), "ratio": ds.end_stiffening_ratio.item(),
            "exact": ds.end_stiffening_exact.item(),
            "reachable": [float(v) for v in ds.end_stiffening_reachable.values],
            "supremum": ds.end_stiffening_supremum.item(),
            "feasible": bool(ds.end_stiffening_feasible)}


def _dynamic(r: Reading) -> dict:
    ds = r.ds
    peaks, refused = {}, {}
    for run in r.runs:
        key = str(run.attrs["motion"])
        peaks[key] = {str(model): {m: finite_or_none(run[f"peak_{m}"].sel(model=model).item())
                                   for m in DYNAMIC_MEASURES} for model in run.model.values}
        refused.update({f"{key}/{model}": str(why) for model, why in
                        zip(run.model.values, run.refused.values) if str(why)})
    return {"available": bool(ds.attrs["dynamic_available"]),
            "text": str(ds.attrs.get("dynamic_reason", "")), "peaks": peaks, "refused": refused}


def key_numbers(data) -> dict:
    """The key numbers of the study's tree ``data`` (``summary.json``)."""
    r = read(data)
    ds, t = r.ds, r.table
    N, B, N_ult = ds.N.item(), ds.B.item(), ds.N_ult.item()
    return {
        "continuum": {"K_r": ds.K_r.item(), "K_v": ds.K_v.item(),
                      "theta_on": ds.theta_on.item(), "N_ult": N_ult, "q_ult": N_ult / B,
                      "yield_multiple": N_ult / N, "dofs": int(ds.continuum_dofs),
                      "onset": onset(ds), "elastic_onset": onset(ds, "elastic_")},
        "calibrations": _calibrations(ds),
        "end_stiffening": end_stiffening(ds),
        "errors": {c: {q: (float(t.errors[i, j]) if math.isfinite(t.errors[i, j]) else None)
                       for j, q in enumerate(t.quantities)}
                   for i, c in enumerate(t.calibrations)},
        "reference_values": {q: float(t.reference[j]) for j, q in enumerate(t.quantities)},
        "best_per_quantity": r.recommendation.per_quantity,
        "best_per_question": {g: {"pick": v[0], "largest_error": finite_or_none(v[1]),
                                  "next": v[2], "next_largest_error": finite_or_none(v[3])}
                              for g, v in r.recommendation.per_group.items()},
        "anchors": r.anchors,
        "onset_ordering_holds": ordering(r.anchors),
        "dynamic": _dynamic(r),
        "elapsed_s": r.elapsed,
    }
