"""Out of sample: how well the map's picks hold on records they were not picked from.

The map picks a bed by its share of hits: the points at which it is within the θ tolerance in
peak θ and in peak edge uplift, a bearing failure of the continuum being a hit for a bed that
fails too (:func:`.goal.hits`). A share counted on the motions a pick was made from flatters
the pick. So each record of the map is held out in turn (leave one record out): the picks are
made on every other motion of the map, the pulses included, and scored on the held-out record's
points alone; the out-of-sample share pools every record's held-out points. The in-sample
share is the same count on the same points (those that have both picks) for the picks made on
every motion. FEMA P695 components beyond the full map's ten (:func:`further_records`,
:data:`.grid.FULL_GRID`), which the full map never ran, are never in a pick's motions here:
they are scored apart, for the picks made on every other motion.

Three levels of pick, coarse to fine (:data:`LEVELS`):

- ``map``: one bed for the whole map (among every bed: :mod:`.goal`'s verdict picks among the
  beds at least 1000 times faster than the continuum, and breaks a tie by the beds' order);
- ``soil``: one bed per soil;
- ``cell``: one bed per cell (soil, FS_v, h/B, period, intensity), the cell's evidence that
  ``upliftlab advise`` reads for a scene on it.

A pick is the bed of the largest share of hits on its points, a tie broken by the smaller median
over those points of the larger of its |error| in peak θ and edge uplift (a missing one counting as
infinite, as it counts as a miss), then by the beds' order. A cell none of whose points counts
(every continuum run there refused) has no pick, and its held-out points are left unscored
(``unpicked``). """

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .analysis import record_motions
from .goal import hits
from .grid import FULL_GRID, MEASURES
from .parts import errors_of, labels
from .sections import finite, pct

__all__ = ["LEVELS", "Score", "further_records", "record_motions", "out_of_sample",
           "pick_bed", "holdout_lines", "holdout_numbers"]

#: The levels a bed is picked at, coarse to fine (module docstring).
LEVELS = ("map", "soil", "cell")


@dataclass(frozen=True)
class Score:
    """How one level's picks hold, on ``soil`` (a soil of the map, or ``all``): the share of
    hits on the record points for the picks made on every motion (``in_sample``), for the
    picks made without the record scored (``out_of_sample``, leave one record out, over
    ``points`` held-out points, ``unpicked`` of them left unscored for want of a pick) and on
    the further records (``further``, over ``further_points``; NaN without them);
    ``kept`` the share of the held-out picks (one per record and unit that has an in-sample
    pick) that are the in-sample pick of their unit (NaN: no unit has one)."""

    level: str
    soil: str
    in_sample: float
    out_of_sample: float
    points: int
    unpicked: int
    further: float
    further_points: int
    kept: float


def further_records(ds) -> np.ndarray:
    """(motion,) booleans: a FEMA P695 component beyond the first ``FULL_GRID.fema_components``
    of the map's (the full map's records are the first ones, :mod:`.motions`), which no pick
    of the full map was made from."""
    kinds = [str(k) for k in ds["motion_kind"].values]
    fema = np.cumsum([k == "fema_p695" for k in kinds])
    return np.array([k == "fema_p695" and n > FULL_GRID.fema_components
                     for k, n in zip(kinds, fema)])


def pick_bed(hit: np.ndarray, counted: np.ndarray, worst: np.ndarray) -> int:
    """The bed to pick from the points of ``hit`` (points, bed) and ``worst`` (points, bed:
    the larger |error| in peak θ and edge uplift, inf where a bed misses a bearing failure)
    where ``counted`` (points,): the largest share of hits, then the smaller median of
    ``worst``, then the first bed; -1 when no point counts."""
    if not counted.any():
        return -1
    share = hit[counted].mean(axis=0)
    median = np.median(worst[counted], axis=0)
    order = np.lexsort((np.arange(share.size), median, -share))
    return int(order[0])


def _worst(ds, hit: np.ndarray, failed: np.ndarray) -> np.ndarray:
    """(…, motion, bed) the larger |error| in peak θ and edge uplift, a missing one infinite;
    where the continuum failed in bearing (``failed``, …, motion), 0 for a bed that failed too
    (a hit) and inf for the others."""
    e = np.nan_to_num(np.abs(errors_of(ds)), nan=np.inf)
    q = MEASURES.index
    worst = np.maximum(e[..., q("theta")], e[..., q("uplift")])
    return np.where(failed[..., None], np.where(hit, 0.0, np.inf), worst)


def _units(level: str, cells: int, soils: int) -> np.ndarray:
    """(cell,) the unit each cell is picked in at ``level``."""
    if level == "map":
        return np.zeros(cells, dtype=int)
    if level == "soil":
        return np.repeat(np.arange(soils), cells // soils)
    return np.arange(cells)


def _picks(units, hit, counted, worst, motions: np.ndarray) -> dict:
    """{unit: bed index} of the picks made on ``motions`` (booleans over the motion axis)."""
    out = {}
    for u in np.unique(units):
        at = units == u
        h, k, w = hit[at][:, motions], counted[at][:, motions], worst[at][:, motions]
        out[int(u)] = pick_bed(h.reshape(-1, h.shape[-1]), k.ravel(),
                               w.reshape(-1, w.shape[-1]))
    return out


def _scored(units, picks: dict, hit, counted, motion: int) -> tuple[np.ndarray, np.ndarray]:
    """(cell,) booleans for one ``motion``: the point counts and has a pick (``scored``), and
    its pick hits there."""
    bed = np.array([picks[int(u)] for u in units])
    scored = counted[:, motion] & (bed >= 0)
    got = np.zeros(bed.size, dtype=bool)
    got[scored] = hit[np.flatnonzero(scored), motion, bed[scored]]
    return scored, got


def _share(got: np.ndarray, scored: np.ndarray) -> float:
    return float(got[scored].mean()) if scored.any() else math.nan


def out_of_sample(ds) -> tuple[Score, ...]:
    """Every level's :class:`Score`, per soil of the map dataset ``ds`` and over ``all``
    (empty when the map has fewer than two records: nothing to hold out)."""
    hit, counted, failed, _ = hits(ds)
    worst = _worst(ds, hit, failed)
    motions, beds = hit.shape[-2], hit.shape[-1]
    hit, worst = hit.reshape(-1, motions, beds), worst.reshape(-1, motions, beds)
    counted = counted.reshape(-1, motions)
    soils = labels(ds, "soil")
    soil_of = np.repeat(np.arange(len(soils)), counted.shape[0] // len(soils))
    records, further = record_motions(ds), further_records(ds)
    held = np.flatnonzero(records & ~further)
    if held.size < 2:
        return ()
    out = []
    for level in LEVELS:
        units = _units(level, counted.shape[0], len(soils))
        full = _picks(units, hit, counted, worst, ~further)
        inside, outside, kept = [], [], []  # kept: (unit, the held-out pick is the full one)
        for r in held:
            picks = _picks(units, hit, counted, worst, ~further & (np.arange(motions) != r))
            (s_in, g_in), (s_out, g_out) = (_scored(units, full, hit, counted, r),
                                            _scored(units, picks, hit, counted, r))
            both = s_in & s_out  # in and out of sample on the same points
            inside.append((both, g_in))
            outside.append((both, g_out))
            kept += [(u, picks[u] == full[u]) for u in picks if full[u] >= 0]
        fresh = [_scored(units, full, hit, counted, r) for r in np.flatnonzero(further)]
        for s, soil in [(None, "all"), *enumerate(soils)]:
            at = np.ones(soil_of.size, dtype=bool) if s is None else soil_of == s
            mine = [same for u, same in kept if at[units == u].any()]
            out.append(_score(level, soil, at, counted[:, held], inside, outside, fresh,
                              float(np.mean(mine)) if mine else math.nan))
    return tuple(out)


def _score(level, soil, at, held_counted, inside, outside, fresh, kept) -> Score:
    def pooled(pairs):
        scored = np.concatenate([s[at] for s, _ in pairs]) if pairs else np.zeros(0, bool)
        got = np.concatenate([g[at] for _, g in pairs]) if pairs else np.zeros(0, bool)
        return _share(got, scored), int(scored.sum())

    in_share, _ = pooled(inside)
    out_share, points = pooled(outside)
    fresh_share, fresh_points = pooled(fresh)
    counted = int(held_counted[at].sum())
    return Score(level, soil, in_share, out_share, counted, counted - points, fresh_share,
                 fresh_points, kept)


_LEVEL_TEXT = {"map": "one bed for the map", "soil": "one bed per soil",
               "cell": "one bed per cell"}


def holdout_numbers(scores: tuple[Score, ...]) -> list[dict]:
    """The scores as ``summary.json`` keeps them (NaN as None)."""
    return [{k: finite(v) if isinstance(v, float) else v for k, v in vars(s).items()}
            for s in scores]


def holdout_lines(ds, scores: tuple[Score, ...]) -> list[str]:
    """The summary's out-of-sample section: what was held out, and a table of every level's
    shares per soil (every number from ``scores``)."""
    if not scores:
        return ["With fewer than two records the map holds nothing out: its picks are scored "
                "only on the motions they were picked from.", ""]
    records = int((record_motions(ds) & ~further_records(ds)).sum())
    further = int(further_records(ds).sum())
    tol = f"{100 * float(ds.attrs['options_theta_tolerance']):g} %"
    lines = [f"Each of the map's {records} records held out in turn: the beds are picked on "
             "every other motion (the pulses included) and scored on the held-out record's "
             f"points alone. A pick is the bed of the largest share within {tol} of the "
             "continuum in peak θ and edge uplift (a bearing failure is a hit for a bed that "
             "fails too), made for the whole map, per soil, or per cell (soil, FS_v, h/B, "
             "period, intensity: the cells `upliftlab advise` reads for a scene). In sample is "
             "the same share on the same points for the picks made on every motion; the last "
             "column is the share of the held-out picks that are the in-sample one."]
    if further:
        lines[0] += (f" {further} further FEMA P695 components, beyond the full map's "
                     f"{FULL_GRID.fema_components}, were never in a pick's motions: they are "
                     "scored for the picks made on every other motion.")
    lines += ["", "| pick | soil | in sample | out of sample | held-out points (unscored) "
              f"|{' further records |' if further else ''} pick kept |",
              f"|---|---|---|---|---|{'---|' if further else ''}---|"]
    for s in scores:
        extra = f" {pct(s.further)} of {s.further_points} |" if further else ""
        lines.append(f"| {_LEVEL_TEXT[s.level]} | {s.soil} | {pct(s.in_sample)} | "
                     f"**{pct(s.out_of_sample)}** | {s.points} ({s.unpicked}) |{extra} "
                     f"{pct(s.kept)} |")
    return lines + [""]
