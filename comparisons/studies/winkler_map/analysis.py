"""What the map says, computed from its ``map`` dataset (:mod:`.dataset`): each bed's region,
the calibration to pick per quantity with its error distribution, the share of the map a
calibrated bed covers, the speed of each bed against the continuum, and whether one bed is
enough (:mod:`.goal`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...framework.study import Axis, Region, corner_region
from ...beds import BEDS
from .energy import EnergyPick, energy_picks
from .goal import Goal, goal, hits
from .parts import (bearing_failures, errors_of, names, options_of, point_array,
                    point_values)
from .grid import MEASURES, SOIL_LABELS

__all__ = ["BedRegion", "Pick", "Share", "Speed", "Analysis", "analyse", "cell_passes",
           "missed_failures", "bearing_failures", "errors_of", "names",
           "median_over_motions", "signed_bias", "BIAS_MEASURES", "subject", "record_motions"]

#: The measures whose signed error is summarised by FS_v (:func:`signed_bias`).
BIAS_MEASURES = ("theta", "uplift", "residual_settlement")

RECORD_KINDS = ("elcentro", "fema_p695")


def record_motions(ds) -> np.ndarray:
    """(motion,) booleans: the motion is a record (El Centro or a FEMA P695 component)."""
    return np.array([str(k) in RECORD_KINDS for k in ds["motion_kind"].values])


def median_over_motions(ds) -> np.ndarray:
    """|error| (soil, fs_v, h_over_B, period, intensity, calibration, measure): the median
    over the motions (NaN runs left out; NaN if every run was refused)."""
    with np.errstate(all="ignore"):
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            return np.nanmedian(np.abs(errors_of(ds)), axis=5)


def missed_failures(ds) -> np.ndarray:
    """(…, motion, calibration): the continuum's soil failed in bearing and the bed's did not
    (:func:`bearing_failures`): a bed that misses the outcome misses the point."""
    failed, bed = bearing_failures(ds)
    return failed[..., None] & ~bed


def cell_passes(ds) -> np.ndarray:
    """(soil, fs_v, h_over_B, period, intensity, calibration): the median |error| over the
    motions is within ``theta_tolerance`` in peak θ and in peak edge uplift and within
    ``settlement_tolerance`` in residual settlement (NaN fails), and the bed fails in
    bearing wherever the continuum does (:func:`missed_failures`)."""
    med = np.nan_to_num(median_over_motions(ds), nan=np.inf)
    o = options_of(ds)
    q = MEASURES.index
    return ((med[..., q("theta")] <= o["theta_tolerance"])
            & (med[..., q("uplift")] <= o["theta_tolerance"])
            & (med[..., q("residual_settlement")] <= o["settlement_tolerance"])
            & ~missed_failures(ds).any(axis=5))


@dataclass(frozen=True)
class BedRegion:
    """Where a calibration passes on one soil's FS_v × h/B map (at every period and intensity
    of the grid): the largest corner rectangle (``region``), its sentence, and how many cells
    pass anywhere (``passing`` of ``total``)."""

    calibration: str
    soil: str
    text: str
    region: Region
    passing: int
    total: int


@dataclass(frozen=True)
class Pick:
    """For one measure: each calibration's |error| ``median`` and ``p90`` (90th percentile)
    over every point of the map (all motions), the same over the records only
    (``record_median``, ``record_p90``; NaN without records), ``refused`` runs per
    calibration, and the ``best`` calibration (smallest median, then smallest p90)."""

    measure: str
    median: dict
    p90: dict
    record_median: dict
    record_p90: dict
    refused: dict
    points: int
    best: str


@dataclass(frozen=True)
class Share:
    """Shares of the map's points (cells × motions) within ``threshold`` in peak θ and in peak
    edge uplift: per calibration (``by_bed``), for the best single calibration (``best``,
    ``best_share``) and for the best calibration chosen point by point (``any_share``). Of
    the ``points``, ``bearing_failures`` ended in a bearing failure of the continuum's soil:
    each counts as a hit for a bed that fails in bearing too (``called``, per calibration)
    and as a miss for the others."""

    threshold: float
    points: int
    by_bed: dict
    best: str
    best_share: float
    any_share: float
    bearing_failures: int = 0
    called: dict | None = None


@dataclass(frozen=True)
class Speed:
    """Wall time of the continuum over each bed's, point by point (same machine; the continuum
    time stored with its run, the bed's measured in this run): ``median`` and ``minimum``
    ratio per calibration; ``continuum_median`` and ``bed_median`` wall times (s)."""

    median: dict
    minimum: dict
    continuum_median: float
    bed_median: dict


@dataclass(frozen=True)
class Analysis:
    regions: tuple[BedRegion, ...]
    picks: tuple[Pick, ...]
    share: Share
    speed: Speed
    goal: Goal
    energy: tuple[EnergyPick, ...] = ()

    def pick(self, measure: str) -> Pick:
        return next(p for p in self.picks if p.measure == measure)

    def region(self, calibration: str, soil: str) -> BedRegion:
        return next(r for r in self.regions if (r.calibration, r.soil) == (calibration, soil))


def subject(name: str) -> str:
    """What a calibration is, in a sentence (its registry label, or its name)."""
    return BEDS[name].label if name in BEDS else name


def regions(ds) -> list[BedRegion]:
    """Per calibration and soil: the corner region of the FS_v × h/B map where
    :func:`cell_passes` holds at every period and intensity."""
    ok = cell_passes(ds).all(axis=(3, 4))  # (soil, fs_v, h_over_B, calibration)
    x = Axis("fs_v", "FS_v", names(ds, "fs_v"))
    y = Axis("h_over_B", "h/B", names(ds, "h_over_B"))
    o = options_of(ds)
    out = []
    for c, name in enumerate(names(ds, "calibration")):
        for s, soil in enumerate(names(ds, "soil")):
            cells = ok[s, :, :, c].T  # (h_over_B, fs_v)
            region = corner_region(cells, x, y, x_sides=(">=", "<="), y_sides=("<=", ">="))
            where = region.condition
            where = ("nowhere on the map" if not cells.any() else where
                     if region.count == 0 or where == "over the whole map" else f"for {where}")
            text = (f"On {SOIL_LABELS[soil]}, the {subject(name)} is within "
                    f"{100 * o['theta_tolerance']:g} % in peak θ and edge uplift and "
                    f"{100 * o['settlement_tolerance']:g} % in residual settlement (median over "
                    f"the motions, at every period and intensity) {where} ({region.count} of "
                    f"{cells.size} cells; {int(cells.sum())} pass anywhere)")
            out.append(BedRegion(name, soil, text, region, int(cells.sum()), cells.size))
    return out


def _stats(values: np.ndarray) -> tuple[float, float]:
    values = values[np.isfinite(values)]
    if values.size == 0:
        return math.nan, math.nan
    return float(np.median(values)), float(np.percentile(values, 90))


def picks(ds) -> list[Pick]:
    """Per measure: each calibration's error distribution and the one to pick."""
    records = record_motions(ds)
    calibrations = names(ds, "calibration")
    out = []
    for measure in MEASURES:
        med, p90, rmed, rp90, refused = {}, {}, {}, {}, {}
        for name in calibrations:
            err = np.abs(point_array(ds["error"].sel(calibration=name, measure=measure)))
            med[name], p90[name] = _stats(err.ravel())
            rmed[name], rp90[name] = (_stats(err[..., records].ravel()) if records.any()
                                      else (math.nan, math.nan))
            refused[name] = int(np.isnan(err).sum())
        best = min(calibrations, key=lambda n: (_inf(med[n]), _inf(p90[n])))
        out.append(Pick(measure, med, p90, rmed, rp90, refused, int(err.size), best))
    return out


def _inf(value: float) -> float:
    return value if math.isfinite(value) else math.inf


def share(ds) -> Share:
    """Shares of points within ``theta_tolerance`` in peak θ and edge uplift (:class:`Share`),
    over the points whose continuum run finished or ended in a bearing failure (there, a bed
    that fails too is a hit; :func:`.goal.hits`)."""
    calibrations = names(ds, "calibration")
    nb = len(calibrations)
    hit, counted, failed, called = hits(ds)
    ok = hit[counted]  # (points, calibration)
    by_bed = {name: float(ok[:, c].mean()) if ok.size else math.nan
              for c, name in enumerate(calibrations)}
    best = max(calibrations, key=lambda n: (_inf(by_bed[n]), -calibrations.index(n)))
    called = called.reshape(-1, nb)[failed.ravel()]
    return Share(options_of(ds)["theta_tolerance"], ok.shape[0], by_bed, best, by_bed[best],
                 float(ok.any(axis=1).mean()) if ok.size else math.nan, int(failed.sum()),
                 {name: int(called[:, c].sum()) for c, name in enumerate(calibrations)})


def speed(ds) -> Speed:
    """The continuum's wall time over each bed's, point by point (:class:`Speed`)."""
    median, minimum, bed_median = {}, {}, {}
    cw = point_values(ds, "continuum_wall_time")
    for name in names(ds, "calibration"):
        bw = point_array(ds["bed_wall_time"].sel(calibration=name))
        ratio = (cw / bw).ravel()
        ratio = ratio[np.isfinite(ratio)]
        median[name] = float(np.median(ratio)) if ratio.size else math.nan
        minimum[name] = float(np.min(ratio)) if ratio.size else math.nan
        bed_median[name] = float(np.nanmedian(bw))
    ran = cw[np.isfinite(cw)]
    return Speed(median, minimum, float(np.median(ran)) if ran.size else math.nan, bed_median)


def signed_bias(ds) -> np.ndarray:
    """(soil, fs_v, calibration, measure of :data:`BIAS_MEASURES`): the median of the signed
    error over h/B, period, intensity and motion (NaN runs left out). Where the |error| is
    large, its sign says whether a bed overshoots or falls short everywhere at that FS_v (a
    missing mechanism) or scatters both ways (a mismatch of timing)."""
    q = [MEASURES.index(m) for m in BIAS_MEASURES]
    e = np.moveaxis(errors_of(ds)[..., q], 6, 2)  # (soil, fs_v, cal, h, T, I, motion, 3)
    flat = e.reshape(e.shape[:3] + (-1, len(q)))  # (soil, fs_v, calibration, points, 3)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmedian(flat, axis=3)


def analyse(ds) -> Analysis:
    """Every statement of the summary, from the map dataset ``ds`` (``tree["map"]``)."""
    covered, fast = share(ds), speed(ds)
    return Analysis(tuple(regions(ds)), tuple(picks(ds)), covered, fast,
                    goal(ds, covered.by_bed, fast.median), energy_picks(ds))
