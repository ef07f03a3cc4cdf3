"""What the maps say, read from their datasets (:mod:`.views`): the corner regions where a
layout stays within the threshold, and Ewing's conclusion, decided from the maps."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from .... import checks
from ...framework.study import Region, corner_region, region_text
from .grid import CASES, LAYOUTS, METRICS, METRIC_LABELS
from .views import cases, error, layouts, map_axes, uplifted


# ---------------------------------------------------------------------------------------------
# Conclusions computed from the data
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class RegionStatement:
    """Where one layout stays within the threshold of the bed, in the map's own parameters."""

    map: str
    case: str
    layout: str
    metric: str
    text: str
    region: Region | None
    passing: int
    total: int


def _subject(layout: str) -> str:
    return {"edges": "edge springs (±b)", "equivalent": "equivalent springs (±b/√3)",
            "calibrated": "calibrated springs (±√(K_θ/K_v))"}[layout]


def _record_statement(x, ok: np.ndarray, subject: str, threshold: float) -> str:
    """Per record, the highest intensity (axis ``x``) up to which every lower one passes."""
    limits = []
    for row in ok:
        n = int(np.argmin(row)) if not row.all() else row.size
        limits.append(n)
    every = sum(1 for n in limits if n == len(x.values))
    none = sum(1 for n in limits if n == 0)
    parts = [f"at every intensity (≤ {x.format(x.values[-1])}) for {every} of {len(limits)} "
             "records"]
    for n in range(len(x.values) - 1, 0, -1):
        count = sum(1 for v in limits if v == n)
        if count:
            parts.append(f"up to {x.format(x.values[n - 1])} for {count}")
    parts.append(f"not even at {x.format(x.values[0])} for {none}")
    return f"{subject} stay within {100 * threshold:g} % " + ", ".join(parts)


def equivalence_regions(maps: Sequence, threshold: float) -> list[RegionStatement]:
    """For each map (a dataset of :func:`.views.maps`), case, layout and measure (and all six):
    where |error| ≤ ``threshold``."""
    checks.in_range("threshold", threshold, 0.0, 10.0, low_open=True)
    out = []
    for ds in maps:
        name, (x, y) = ds.attrs["name"], map_axes(ds)
        for case in cases(ds):
            for layout in layouts(ds):
                for metric in (*METRICS, "all"):
                    ok = np.nan_to_num(error(ds, case, layout, metric), nan=np.inf) <= threshold
                    subject = f"{_subject(layout)} [{METRIC_LABELS[metric]}]"
                    if name == "records":
                        text, region = _record_statement(x, ok, subject, threshold), None
                    else:
                        y_sides = ("<=", ">=") if y.key == "intensity" else (">=", "<=")
                        region = corner_region(ok, x, y, y_sides=y_sides)
                        text = region_text(region, subject, threshold)
                    out.append(RegionStatement(name, case, layout, metric, text, region,
                                               int(ok.sum()), ok.size))
    return out


@dataclass(frozen=True)
class EwingConclusion:
    """Ewing's conclusion quantified over the uniform-bed maps that have a case axis.

    ``share[case][layout][measure]``: the fraction of the points where the bed uplifts at which
    the layout stays within ``threshold`` (measure ``all``: in all six at once);
    ``median[case][layout][measure]`` the median |error| there; ``points[case]`` how many such
    points. ``bonded_error[layout]``: the largest error (all measures) where the bed never
    separated (``bonded_points``). ``holds``: in Case C no layout stays within the threshold in
    all six measures at most uplifting points (None without Case C points). ``elastic_holds``:
    the same already in the elastic Case A. ``text`` says it with the numbers.
    """

    threshold: float
    share: dict
    median: dict
    points: dict
    bonded_error: dict
    bonded_points: int
    holds: bool | None
    elastic_holds: bool | None
    text: str

    def best(self, case: str, measure: str = "all") -> tuple[str, float]:
        """(layout, share) of the layout most often within the threshold."""
        shares = {k: v[measure] for k, v in self.share[case].items()}
        preference = ("equivalent", "calibrated", "edges")  # on ties
        layout = max(shares, key=lambda k: (shares[k], -preference.index(k)))
        return layout, shares[layout]


def _pooled(maps: Sequence, case: str, layout: str, metric: str, lifted: bool):
    """Errors at the cells whose bed run is usable and did (not) uplift, over ``maps``."""
    values = []
    for ds in maps:
        if case in cases(ds):
            usable = np.isfinite(ds[f"reference_{METRICS[0]}"].sel(case=case).values)
            cells = (uplifted(ds, case) == lifted) & usable
            values.append(error(ds, case, layout, metric)[cells])
    return np.concatenate(values) if values else np.zeros(0)


def ewing_conclusion(maps: Sequence, threshold: float) -> EwingConclusion:
    """Shares of uplifting points where each two-spring layout stays within ``threshold``,
    over the maps (datasets of :func:`.views.maps`) of the uniform bed with a case axis."""
    checks.in_range("threshold", threshold, 0.0, 10.0, low_open=True)
    pooled = [m for m in maps if m.attrs["bed"] == "uniform"
              and m.attrs["name"] != "yield_restitution"]
    found = tuple(c for c in CASES if any(c in cases(m) for m in pooled))
    share = {c: {k: {} for k in LAYOUTS} for c in found}
    median = {c: {k: {} for k in LAYOUTS} for c in found}
    points = {}
    for c in found:
        for layout in LAYOUTS:
            for metric in (*METRICS, "all"):
                errors = _pooled(pooled, c, layout, metric, True)
                share[c][layout][metric] = _share(errors, threshold)
                median[c][layout][metric] = (float(np.nanmedian(errors)) if errors.size
                                             else math.nan)
                points[c] = int(errors.size)
    bonded = {k: np.concatenate([_pooled(pooled, c, k, "all", False) for c in found])
              if found else np.zeros(0) for k in LAYOUTS}
    bonded_error = {k: float(np.nanmax(v)) if v.size else math.nan for k, v in bonded.items()}
    verdict = {c: (max(share[c][k]["all"] for k in LAYOUTS) < 0.5 if points.get(c) else None)
               for c in ("A", "C")}
    conclusion = EwingConclusion(threshold, share, median, points, bonded_error,
                                 int(bonded[LAYOUTS[0]].size), verdict["C"], verdict["A"], "")
    return replace(conclusion, text=_ewing_text(conclusion, found))


def _share(errors: np.ndarray, threshold: float) -> float:
    if errors.size == 0:
        return math.nan
    return float(np.mean(np.nan_to_num(errors, nan=np.inf) <= threshold))


def _pct(value: float, digits: int = 0) -> str:
    if not math.isfinite(value):
        return "n/a"
    return f"{100 * value:.{digits}f} %" if digits or value == 0 or value >= 0.01 \
        else f"{100 * value:.1g} %"


_CASE_NAMES = {"A": "Case A (elastic, 40 % damping)", "B": "Case B (elasto-plastic, 10 %)",
               "C": "Case C (elasto-plastic with impact, ε = 0.7)"}


def _ewing_text(e: EwingConclusion, found) -> str:
    thr = f"{100 * e.threshold:g} %"
    lines = [f"Where the Winkler bed never separates ({e.bonded_points} points), the largest "
             "error over the six measures is "
             + ", ".join(f"{_pct(e.bonded_error[k])} for {k}" for k in LAYOUTS) + "."]
    for c in found:
        if not e.points[c]:
            continue
        sh = e.share[c]
        weakest = min(METRICS, key=lambda m: sh["equivalent"][m])
        lines.append(
            f"Once the bed uplifts, in {_CASE_NAMES[c]} ({e.points[c]} points), the share within "
            f"{thr} in all six measures is "
            + ", ".join(f"{_pct(sh[k]['all'])} for {k}" for k in LAYOUTS)
            + "; in peak u alone " + ", ".join(_pct(sh[k]["u"]) for k in LAYOUTS)
            + " (median |error| in peak u " + ", ".join(_pct(e.median[c][k]["u"]) for k in LAYOUTS)
            + f"); the equivalent springs fail most often in {METRIC_LABELS[weakest]} (within "
            f"{thr} at {_pct(sh['equivalent'][weakest])}).")
    if e.holds is None:
        lines.append("Ewing's conclusion is not tested: no Case C point uplifts on these maps.")
        return " ".join(lines)
    best, value = e.best("C")
    lines.append(
        f"Ewing's conclusion {'holds' if e.holds else 'does not hold on these maps'}: once the "
        f"foundation is nonlinear and impact matters (Case C), the best two-spring layout "
        f"({best}) stays within {thr} in all six measures at {_pct(value)} of the uplifting "
        "points.")
    if e.elastic_holds is not None:
        best_a, value_a = e.best("A")
        trend = ", ".join(f"{_pct(e.best(c)[1])} in {c}" for c in found)
        trend_u = ", ".join(f"{_pct(e.best(c, 'u')[1])} in {c}" for c in found)
        if e.elastic_holds:
            lines.append(
                f"The equivalence is already lost in the elastic Case A (best: {best_a}, "
                f"{_pct(value_a)}): uplift itself breaks it in these measures. Across the cases "
                f"the best share in all six measures is {trend}; in peak u alone {trend_u}.")
        else:
            lines.append(
                f"In the elastic Case A the equivalence survives uplift at most points (best: "
                f"{best_a}, {_pct(value_a)}): plasticity and impact are what break it (best "
                f"share {trend}).")
    return " ".join(lines)
