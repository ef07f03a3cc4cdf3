"""Fixed base against uplift allowed (fast grid): Ewing's Figs. 11–12 and the base-shear
spectrum.

The study's result is one labelled dataset (``study.data``), selected by building, support,
family and period. References: Fig. 11 as read from the paper (peak u 0.164 in fixed, 0.055 in
uplift allowed in Case C); the exact Nigam–Jennings recurrence for the fixed-base spectral
displacement (the fixed base is a linear SDOF with 5 % damping); the single-run path
(:func:`reduced.run`) against the batch path (:func:`reduced.run_batch`) at the paper's periods;
ratios computed by hand for the range statements.
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
def study(elcentro, tmp_path_factory, fast_stores):
    """The fast study, its points published for the report's test (conftest.FastStores)."""
    out = tmp_path_factory.mktemp("fixed_vs_uplift")
    made = fvu.run(fast=True, out=out)
    fast_stores.publish("fixed_vs_uplift", out / "store")
    return made


def test_fig11_matches_the_paper(study):
    """Fig. 11: peak u 0.164 in fixed (±2 %) and 0.055 in with uplift (±3 %); the uplift-allowed
    peak base shear is at most the fixed base's (here about a third)."""
    f = study.data.sel(building="short")
    assert float(f.peak_u.sel(support="fixed")) == pytest.approx(0.164, rel=0.02)
    assert float(f.peak_u.sel(support="C")) == pytest.approx(0.055, rel=0.03)
    assert f.peak_base_shear.sel(support="C") <= f.peak_base_shear.sel(support="fixed")
    assert fvu.figure_ratio(study.data, "short", "shear") == pytest.approx(0.055 / 0.164,
                                                                          rel=0.05)
    assert float(f.peak_uplift.sel(support="C")) > 0.0


def test_fig12_uplift_reduces_deformation(study):
    """Fig. 12 ('significant reduction'): uplift allowed at most 60 % of the fixed-base peak u
    and base shear of the long-period building."""
    ds = study.data
    assert fvu.figure_ratio(ds, "long", "u") < 0.6 and fvu.figure_ratio(ds, "long", "shear") < 0.6


def test_fixed_base_spectrum_is_the_exact_sdof_spectrum(study, elcentro):
    """Fixed base = linear SDOF (5 %): its peak u at every period equals the Nigam–Jennings
    spectral displacement of El Centro (Hermite peak between 2 ms samples) to 0.5 %."""
    s = study.data.sel(family="short")
    acc = np.append(elcentro.acceleration * 386.09, np.zeros(200))
    fine = 10  # the same piecewise-linear record sampled 10 times finer: NJ stays exact
    t_rec = np.arange(acc.size) * elcentro.dt
    acc = np.interp(np.arange((acc.size - 1) * fine + 1) * elcentro.dt / fine, t_rec, acc)
    for t, u in zip(s.period.values, s.spectrum_peak_u.sel(support="fixed").values):
        disp, vel = nigam_jennings(acc, elcentro.dt / fine, 2 * math.pi / t, 0.05)
        assert u == pytest.approx(hermite_peak(disp, vel, elcentro.dt / fine), rel=0.005), t


def test_batch_agrees_with_single_runs(study):
    """The spectrum's run_batch point at T = 0.15 s is the Fig. 11 run (single-run path), for
    the fixed base and Case C, to 1e-9."""
    s = study.data.sel(family="short", period=0.15)
    f = study.data.sel(building="short")
    assert float(s.period) == 0.15
    for support in ("fixed", "C"):
        assert float(s.spectrum_peak_u.sel(support=support)) == pytest.approx(
            float(f.peak_u.sel(support=support)), rel=1e-9)
        assert float(s.spectrum_shear_coefficient.sel(support=support)) * 202.0 == \
            pytest.approx(float(f.peak_base_shear.sel(support=support)), rel=1e-9)


def test_uplift_reduces_base_shear_where_the_summary_says(study):
    """The summary's ranges are the periods where the ratio uplift/fixed is below 0.98; at the
    paper's short period the Case C ratio is the Fig. 11 ratio."""
    s = study.data.sel(family="short")
    r = fvu.spectrum_ranges(study.data, "short")[("C", "shear")]
    shear = s.spectrum_shear_coefficient
    ratio = shear.sel(support="C").values / shear.sel(support="fixed").values
    reduced = s.period.values[ratio < 1 - fvu.NO_CHANGE]
    assert fvu.NO_CHANGE == 0.02
    assert r.count_reduced == reduced.size
    assert r.min_ratio == pytest.approx(ratio.min())
    assert r.reduced[0][0] == reduced[0]
    assert fvu.at(study.data, "short", "C", "shear", 0.15) == pytest.approx(
        fvu.figure_ratio(study.data, "short", "shear"), rel=1e-9)
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
    peak = {"family": "short", "support": "C"}
    assert (again.data.spectrum_peak_u.sel(peak).values.tolist()
            == study.data.spectrum_peak_u.sel(peak).values.tolist())


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


def test_the_folder_opens_again_as_the_same_labelled_data(study):
    """:func:`upliftlab.open_study` of the study's folder: the dataset it wrote, selected by
    label, holds the numbers of ``summary.json`` (bit for bit) and of the CSV tables (to their
    ten digits), with units; the summary computed from it is the ``summary.md`` written."""
    import json

    from upliftlab import open_study

    folder = study.study.directory
    tree = open_study(folder)
    ds = tree["fixed_vs_uplift"].to_dataset()
    numbers = json.loads((folder / "summary.json").read_text())["numbers"]
    assert tree.attrs["figures"] == numbers["figures"]
    for key, fig in numbers["figures"].items():
        for support in ("fixed", "C"):
            at = ds.sel(building=fig["building"], support=support)
            assert float(at.peak_u) == fig["peak_u"][support]
            assert float(at.peak_base_shear) == fig["peak_base_shear"][support]
    assert ds.peak_u.attrs["units"] == "in" and ds.period.attrs["units"] == "s"
    lines = [x for x in (folder / "spectrum_short.csv").read_text().splitlines()
             if not x.startswith("#")]
    table = np.genfromtxt(lines, delimiter=",", names=True)
    one = ds.sel(family="short", support="C")
    assert table["period_s"].tolist() == ds.period.values.tolist()
    assert table["shear_coefficient_C"].tolist() == pytest.approx(
        one.spectrum_shear_coefficient.values.tolist(), rel=1e-9)
    r = numbers["spectra"]["short"]["C_shear"]
    assert fvu.spectrum_ranges(ds, "short")[("C", "shear")].min_ratio == r["min_ratio"]
    assert fvu.summarise(ds) == (folder / "summary.md").read_text()


def test_its_files_pass_the_cf_checker(study, cf_failures):
    # Reference: the IOOS compliance checker, cf:1.10 (tests/test_cf.py says which): no
    # failing required check and no check that raised, in every NetCDF file of the folder.
    from upliftlab.study_files import study_files

    files = study_files(study.study.directory)
    assert files
    for name, path in files.items():
        assert cf_failures(path) == ([], []), name
