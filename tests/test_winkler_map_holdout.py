"""The map's out-of-sample scores (:mod:`upliftlab.comparisons.studies.winkler_map.holdout`):
each record held out in turn, the picks made on the other motions and scored on it.

References:
- a hand-counted case (one cell, a pulse and three records, two beds), every share and pick
  worked out in the docstring;
- an independent implementation: plain loops over a random map (two soils, 12 cells, a pulse,
  El Centro and eleven FEMA P695 components, the eleventh a further record, four beds, some
  refused runs and bearing failures), picking by the rule as the module's docstring states it,
  with :func:`statistics.median`; the shares must agree exactly (1e-12).
"""

from __future__ import annotations

import itertools
import math
import statistics

import numpy as np
import pytest
import xarray as xr

from upliftlab.comparisons.studies.winkler_map.grid import MEASURES
from upliftlab.comparisons.studies.winkler_map.holdout import (further_records, out_of_sample,
                                                               pick_bed)
from upliftlab.comparisons.studies.winkler_map.parts import POINT_DIMS

TOL = 0.10  # the map's θ tolerance
ATTRS = {"options_elements_across": 4, "options_springs": 8, "options_settlement_ratio": 0.05,
         "options_theta_ratios": [2.0], "options_cycle_ratios": [2.0],
         "options_theta_tolerance": TOL, "options_settlement_tolerance": 0.2,
         "options_figures": 0}


def _map(errors, kinds, theta=None, failed=None, bed_failed=None, soils=("clay",), fs_v=(2.0,),
         uplift=None):
    """A map dataset with the variables the analysis reads: ``errors`` (soil, fs_v, motion,
    bed), the same in every measure but edge uplift where ``uplift`` (the same shape) is given;
    one h/B, period and intensity."""
    errors = np.asarray(errors, dtype=float)
    ns, nf, nm, nb = errors.shape
    shape = (ns, nf, 1, 1, 1, nm)
    e = np.repeat(errors.reshape(shape + (nb, 1)), len(MEASURES), axis=-1)
    if uplift is not None:
        e[..., MEASURES.index("uplift")] = np.asarray(uplift, float).reshape(shape + (nb,))
    theta = np.ones(shape) if theta is None else np.asarray(theta, float).reshape(shape)
    failed = np.zeros(shape, int) if failed is None else np.asarray(failed, int).reshape(shape)
    bed_failed = (np.zeros(shape + (nb,), int) if bed_failed is None
                  else np.asarray(bed_failed, int).reshape(shape + (nb,)))
    coords = {"soil": list(soils), "fs_v": list(fs_v), "h_over_B": [1.5], "period": [0.5],
              "intensity": [3.0], "motion": [f"m{i}" for i in range(nm)],
              "calibration": [f"bed{c}" for c in range(nb)], "measure": list(MEASURES)}
    return xr.Dataset({"error": (POINT_DIMS + ("calibration", "measure"), e),
                       "continuum_theta": (POINT_DIMS, theta),
                       "continuum_bearing_failure": (POINT_DIMS, failed),
                       "bed_bearing_failure": (POINT_DIMS + ("calibration",), bed_failed),
                       "motion_kind": ("motion", list(kinds))}, coords=coords, attrs=ATTRS)


def test_a_pick_that_holds_in_sample_and_not_out_of_it():
    """One cell; motions: a pulse and three records; two beds, |error| in θ and uplift alike:
    pulse (A 0, B 0.5), r1 (0, 0.05), r2 (0.5, 0.05), r3 (0.5, 0.05). On every motion A hits
    2 of 4 and B 3 of 4: B, which hits all three records (in sample 1.0). Held out: without
    r1, A 1/3 and B 2/3: B, which hits r1; without r2, A 2/3 (pulse, r1) and B 2/3 (r1, r3)
    tie, and the medians of the larger |error| are A 0 and B 0.05: A, which misses r2; r3
    likewise. Out of sample 1/3; the held-out pick is B's once in three."""
    e = [[[[0.0, 0.5], [0.0, 0.05], [0.5, 0.05], [0.5, 0.05]]]]
    scores = out_of_sample(_map(e, ["ricker", "elcentro", "fema_p695", "fema_p695"]))
    assert [(s.level, s.soil) for s in scores] == [
        ("map", "all"), ("map", "clay"), ("soil", "all"), ("soil", "clay"), ("cell", "all"),
        ("cell", "clay")]
    for s in scores:  # one cell in one soil: every level picks alike
        assert (s.in_sample, s.points, s.unpicked) == (1.0, 3, 0)
        assert s.out_of_sample == pytest.approx(1 / 3, abs=1e-12)
        assert s.kept == pytest.approx(1 / 3, abs=1e-12)
        assert math.isnan(s.further) and s.further_points == 0


def test_nothing_to_hold_out_with_fewer_than_two_records():
    e = [[[[0.0, 0.5], [0.0, 0.05]]]]
    assert out_of_sample(_map(e, ["ricker", "elcentro"])) == ()


def test_a_map_whose_every_run_was_refused_has_no_pick_and_no_share():
    """Nothing counts: no pick is made, so no share and no kept pick (NaN), every held-out
    point unscored."""
    e = np.full((1, 1, 3, 2), np.nan)
    scores = out_of_sample(_map(e, ["ricker", "elcentro", "fema_p695"],
                                theta=np.full((1, 1, 3), np.nan)))
    for s in scores:
        assert math.isnan(s.in_sample) and math.isnan(s.out_of_sample) and math.isnan(s.kept)
        assert (s.points, s.unpicked) == (0, 0)


def test_a_tie_goes_to_the_smaller_median_error_then_to_the_first_bed():
    """Reference by hand: both beds hit one of two points; medians 0.3 and 0.2, then equal."""
    hit = np.array([[True, False], [False, True]])
    counted = np.array([True, True])
    assert pick_bed(hit, counted, np.array([[0.0, 0.4], [0.6, 0.0]])) == 1
    assert pick_bed(hit, counted, np.array([[0.0, 0.5], [0.5, 0.0]])) == 0
    assert pick_bed(hit, np.array([False, False]), np.zeros((2, 2))) == -1


def _naive(ds, level):
    """Leave one record out, by plain loops (the module docstring's rule): {soil or 'all':
    (in-sample share, out-of-sample share, further share, scored points, kept share)}."""
    soils = [str(s) for s in ds.soil.values]
    kinds = [str(k) for k in ds.motion_kind.values]
    fema = 0
    further = []
    for k in kinds:
        fema += k == "fema_p695"
        further.append(k == "fema_p695" and fema > 10)
    records = [m for m, k in enumerate(kinds) if k in ("elcentro", "fema_p695") and
               not further[m]]
    e = ds.error.transpose(*POINT_DIMS, "calibration", "measure").values
    th, up = MEASURES.index("theta"), MEASURES.index("uplift")
    beds = ds.calibration.size
    cells = list(itertools.product(range(ds.soil.size), range(ds.fs_v.size)))

    def point(cell, m):  # (counts, [hit per bed], [worst per bed])
        s, f = cell
        failed = bool(ds.continuum_bearing_failure.values[s, f, 0, 0, 0, m])
        ran = math.isfinite(float(ds.continuum_theta.values[s, f, 0, 0, 0, m]))
        hits, worst = [], []
        for b in range(beds):
            if failed:
                called = bool(ds.bed_bearing_failure.values[s, f, 0, 0, 0, m, b])
                hits.append(called)
                worst.append(0.0 if called else math.inf)
            else:
                a, u = abs(e[s, f, 0, 0, 0, m, b, th]), abs(e[s, f, 0, 0, 0, m, b, up])
                w = math.inf if (math.isnan(a) or math.isnan(u)) else max(a, u)
                hits.append(w <= TOL)
                worst.append(w)
        return ran or failed, hits, worst

    def unit(cell):
        return {"map": 0, "soil": cell[0], "cell": cell}[level]

    def pick(u, motions):
        pts = [point(c, m) for c in cells if unit(c) == u for m in motions]
        pts = [p for p in pts if p[0]]
        if not pts:
            return None
        shares = [sum(p[1][b] for p in pts) / len(pts) for b in range(beds)]
        medians = [statistics.median(p[2][b] for p in pts) for b in range(beds)]
        return sorted(range(beds), key=lambda b: (-shares[b], medians[b], b))[0]

    usable = [m for m in range(len(kinds)) if not further[m]]
    out = {}
    for soil in ["all", *soils]:
        mine = [c for c in cells if soil == "all" or soils[c[0]] == soil]
        full = {unit(c): pick(unit(c), usable) for c in mine}

        def share(pairs):
            got = [point(c, m)[1][b] for c, m, b in pairs if b is not None and point(c, m)[0]]
            return sum(got) / len(got) if got else math.nan

        held = {(unit(c), r): pick(unit(c), [m for m in usable if m != r])
                for c in mine for r in records}
        both = [(c, r) for c in mine for r in records
                if full[unit(c)] is not None and held[unit(c), r] is not None]
        inside = share([(c, r, full[unit(c)]) for c, r in both])
        outside = share([(c, r, held[unit(c), r]) for c, r in both])
        fresh = share([(c, m, full[unit(c)]) for c in mine for m in range(len(kinds))
                       if further[m]])
        scored = sum(1 for c, r in both if point(c, r)[0])
        kept = [held[u, r] == full[u] for u, r in held if full[u] is not None]
        out[soil] = (inside, outside, fresh, scored,
                     sum(kept) / len(kept) if kept else math.nan)
    return out


def test_leave_one_record_out_agrees_with_plain_loops_on_a_random_map():
    rng = np.random.default_rng(35)
    kinds = ["ricker", "elcentro"] + ["fema_p695"] * 11
    ns, nf, nm, nb = 2, 6, len(kinds), 4
    values = [0.0, 0.04, 0.08, 0.2, 0.6, -0.09, -0.3]
    errors = rng.choice(values, size=(ns, nf, nm, nb))
    uplift = np.where(rng.random((ns, nf, nm, nb)) < 0.7, errors,
                      rng.choice(values, size=(ns, nf, nm, nb)))
    uplift[0, 3, 4, 1] = np.nan  # one measure missing: a miss, its worst error infinite
    theta = np.ones((ns, nf, nm))
    theta[0, 1, 3] = np.nan  # a refused run
    errors[0, 1, 3] = np.nan
    theta[1, 2] = np.nan  # a cell whose every run was refused: no pick there
    errors[1, 2] = np.nan
    refused = [m for m in range(nm) if m != 3]  # a cell with one run: no pick without it
    theta[0, 5, refused] = np.nan
    errors[0, 5, refused] = np.nan
    failed = np.zeros((ns, nf, nm), int)
    failed[1, 4, [2, 5, 9]] = 1  # bearing failures: errors NaN, called by beds 0 and 2
    errors[1, 4, [2, 5, 9]] = np.nan
    bed_failed = np.zeros((ns, nf, nm, nb), int)
    bed_failed[1, 4, [2, 5, 9]] = [1, 0, 1, 0]
    uplift[np.isnan(errors)] = np.nan
    ds = _map(errors, kinds, theta, failed, bed_failed, soils=("clay", "sand"),
              fs_v=tuple(float(v) for v in range(2, 2 + nf)), uplift=uplift)
    assert further_records(ds).tolist() == [False] * 12 + [True]
    scores = {(s.level, s.soil): s for s in out_of_sample(ds)}
    for level in ("map", "soil", "cell"):
        for soil, (inside, outside, fresh, scored, kept) in _naive(ds, level).items():
            s = scores[level, soil]
            assert s.in_sample == pytest.approx(inside, abs=1e-12)
            assert s.out_of_sample == pytest.approx(outside, abs=1e-12)
            assert s.further == pytest.approx(fresh, abs=1e-12)
            assert (s.points - s.unpicked, s.kept) == (scored, pytest.approx(kept, abs=1e-12))
    clay, sand = scores["cell", "clay"], scores["cell", "sand"]
    assert (clay.points, clay.unpicked) == (5 * 11 - 1 + 1, 1)  # its one run, unscored
    assert (sand.points, sand.unpicked) == (5 * 11, 0)  # the refused cell counts nothing
    assert scores["cell", "all"].further_points == 12 - 2  # two cells refused it
