"""Fixed base against uplift allowed (fast grid): Ewing's Figs. 11–12 and the base-shear
spectrum.

References: Fig. 11 as read from the paper (peak u 0.164 in fixed, 0.055 in uplift allowed in
Case C); the exact Nigam–Jennings recurrence for the fixed-base spectral displacement (the
fixed base is a linear SDOF with 5 % damping); the single-run path (:func:`reduced.run`)
against the batch path (:func:`reduced.run_batch`) at the paper's periods; ratios computed by
hand for the range statements.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.studies import fixed_vs_uplift as fvu
from upliftlab.comparisons.framework.store import Store
from upliftlab.reduced.exact import hermite_peak, nigam_jennings


@pytest.fixture(scope="module")
def study(elcentro, tmp_path_factory):
    return fvu.run(fast=True, out=tmp_path_factory.mktemp("fixed_vs_uplift"))


def test_fig11_matches_the_paper(study):
    """Fig. 11: peak u 0.164 in fixed (±2 %) and 0.055 in with uplift (±3 %); the uplift-allowed
    peak base shear is at most the fixed base's (here about a third)."""
    f = study.figure("short")
    assert f.peak_u["fixed"] == pytest.approx(0.164, rel=0.02)
    assert f.peak_u["C"] == pytest.approx(0.055, rel=0.03)
    assert f.base_shear["C"] <= f.base_shear["fixed"]
    assert f.ratio_shear == pytest.approx(0.055 / 0.164, rel=0.05)
    assert f.uplift["C"] > 0.0


def test_fig12_uplift_reduces_deformation(study):
    """Fig. 12 ('significant reduction'): uplift allowed at most 60 % of the fixed-base peak u
    and base shear of the long-period building."""
    f = study.figure("long")
    assert f.ratio_u < 0.6 and f.ratio_shear < 0.6


def test_fixed_base_spectrum_is_the_exact_sdof_spectrum(study, elcentro):
    """Fixed base = linear SDOF (5 %): its peak u at every period equals the Nigam–Jennings
    spectral displacement of El Centro (Hermite peak between 2 ms samples) to 0.5 %."""
    s = study.spectrum("short")
    acc = np.append(elcentro.acceleration * 386.09, np.zeros(200))
    fine = 10  # the same piecewise-linear record sampled 10 times finer: NJ stays exact
    t_rec = np.arange(acc.size) * elcentro.dt
    acc = np.interp(np.arange((acc.size - 1) * fine + 1) * elcentro.dt / fine, t_rec, acc)
    for t, u in zip(s.periods, s.u["fixed"]):
        disp, vel = nigam_jennings(acc, elcentro.dt / fine, 2 * math.pi / t, 0.05)
        assert u == pytest.approx(hermite_peak(disp, vel, elcentro.dt / fine), rel=0.005), t


def test_batch_agrees_with_single_runs(study):
    """The spectrum's run_batch point at T = 0.15 s is the Fig. 11 run (single-run path), for
    the fixed base and Case C, to 1e-9."""
    s, f = study.spectrum("short"), study.figure("short")
    i = int(np.argmin(np.abs(s.periods - 0.15)))
    assert s.periods[i] == 0.15
    for support in ("fixed", "C"):
        assert s.u[support][i] == pytest.approx(f.peak_u[support], rel=1e-9)
        assert s.shear[support][i] * 202.0 == pytest.approx(f.base_shear[support], rel=1e-9)


def test_uplift_reduces_base_shear_where_the_summary_says(study):
    """The summary's ranges are the periods where the ratio uplift/fixed is below 0.98; at the
    paper's short period the Case C ratio is the Fig. 11 ratio."""
    s = study.spectrum("short")
    r = s.ranges[("C", "shear")]
    ratio = s.shear["C"] / s.shear["fixed"]
    reduced = s.periods[ratio < 1 - fvu.NO_CHANGE]
    assert fvu.NO_CHANGE == 0.02
    assert r.count_reduced == reduced.size
    assert r.min_ratio == pytest.approx(ratio.min())
    assert r.reduced[0][0] == reduced[0]
    assert s.at("C", "shear", 0.15) == pytest.approx(study.figure("short").ratio_shear,
                                                       rel=1e-9)
    numbers = study.study.numbers["spectra"]["short"]["C_shear"]
    assert numbers["min_ratio"] == pytest.approx(r.min_ratio)
    assert "reduced over" in study.study.summary


def test_reduction_ranges_by_hand():
    r = fvu.reduction_ranges([0.1, 0.2, 0.3, 0.4, 0.5, 0.6], [1.2, 0.8, 0.7, 1.0, 0.5, math.nan])
    assert r.reduced == ((0.2, 0.3), (0.5, 0.5))
    assert r.increased == ((0.1, 0.1),)
    assert (r.min_ratio, r.min_period, r.max_ratio, r.max_period) == (0.5, 0.5, 1.2, 0.1)
    assert (r.count_reduced, r.total) == (3, 5)


def test_rerun_recomputes_nothing(study, tmp_path, monkeypatch):
    """Again on the same store: no batch and no figure run happens, the same numbers come out."""
    store = Store(study.study.directory / "store")
    before = len(store)

    def refuse(*args, **kwargs):
        raise AssertionError("recomputed a stored point")

    monkeypatch.setattr(fvu.runs, "run_spectrum_batch", refuse)
    monkeypatch.setattr(fvu.runs, "figure_run", refuse)
    again = fvu.run(fast=True, out=tmp_path, store=store, figures=False)
    assert len(store) == before
    assert again.spectrum("short").u["C"].tolist() == study.spectrum("short").u["C"].tolist()


@pytest.mark.parametrize("grid, message", [
    (replace(fvu.FAST_GRID, periods=(0.5, 0.1)), "grid.periods"),
    (replace(fvu.FAST_GRID, periods=(0.01, 0.1)), r"grid.periods\[0\] = 0.01: valid range"),
    (replace(fvu.FAST_GRID, supports=("C", "A")), "needs 'fixed'"),
    (replace(fvu.FAST_GRID, families=("medium",)), r"grid.families\[0\] = 'medium'"),
])
def test_bad_grid_is_refused(grid, message, tmp_path):
    with pytest.raises(InputError, match=message):
        fvu.run(fast=True, out=tmp_path, grid=grid)
    assert not any(tmp_path.iterdir())


def test_scene_argument_is_refused(tmp_path):
    with pytest.raises(InputError, match="scene = 'wall_elcentro'"):
        fvu.run("wall_elcentro", out=tmp_path)
