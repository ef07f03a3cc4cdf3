"""The far field of a dynamic run (upliftlab.continuum.dynamics.far_field) and the small-strain
validity limit (upliftlab.continuum.dynamics.validity).

References, one per test:
- the far field's elements: the mesh's grid lines (the outermost column of cells, one per
  layer of cells on each side);
- an elastic column (shear sides, rigid base) under a slow, smooth base acceleration a: the
  quasi-static closed form of a one-dimensional column, τ(z) = ρ a z, so γ(z) = ρ a z / G,
  at the deepest Gauss point of each layer (two-point rule: mid-depth + h/(2√3)), within 1 %
  (the ramp's residual oscillation: the ramp lasts 8 periods of the column, 4H/V_s = 0.19 s);
- a Tresca column (c_u, K0 = 1, so the geostatic stress is isotropic and yield is at |τ| = c_u):
  the same closed form puts the largest shear stress at the base, ρ a H, so the column stays
  elastic for a < a_y = c_u/(ρ H) and, above a_y, yields first at the base; the base then
  carries at most c_u and caps the acceleration it passes up near a_y (Newmark's sliding block,
  Géotechnique 15, 1965), so the yielded range is the bottom layer of cells only;
- the validity flag: the limit ε̄p = 0.10 stated in continuum/dynamics/validity.py, on a run far
  below it (elastic, ε̄p = 0) and one far above it (the yielding base, ε̄p ≈ 0.24);
- the map's use of it: the rule stated in comparisons/studies/winkler_map/assemble.py (a
  stored verdict "beyond" leaves the point out; a record without one reads as before).

Routes: the elastic column on both (explicit, implicit); the Tresca column on the explicit one.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics.far_field import YIELD_THRESHOLD, far_field
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.continuum.dynamics.validity import (BEYOND, SMALL_STRAIN_LIMIT, WITHIN,
                                                   beyond_small_strain, validity)
from upliftlab.continuum.output.summaries import dynamic_summary, dynamic_warnings
from upliftlab.meshes.soil import grid_lines
from upliftlab.motions import Motion
from upliftlab.scenes import load_scene

G_ACC = 9.80665  # m/s², the kN-m-s scene's g
DEPTH = 5.0  # m: continuum.domain_depth = 2.5 B with B = 2 m
# A column: shear sides, a light footing (its rocking would shake the closed box), 4 elements
# across the footing (Q2), 2.5 B deep.
COLUMN = ["continuum.elements_across=4", "continuum.boundary=shear", "continuum.domain_depth=2.5",
          "structure.weight=1", "structure.rotary_inertia=0.1"]


def _ramp(a: float, ramp: float, dt: float = 0.01) -> Motion:
    """A half-cosine rise to ``a`` (g) over ``ramp`` (s), then held for ``ramp``/2."""
    t = np.arange(int(1.5 * ramp / dt)) * dt
    acc = np.where(t < ramp, 0.5 * a * (1.0 - np.cos(np.pi * t / ramp)), a)
    return Motion("ramp", dt, acc, source="builtin:ramp")


def _sine(a: float, period: float, dt: float = 0.01) -> Motion:
    """One slow half sine of peak ``a`` (g) lasting ``period`` (s)."""
    t = np.arange(int(period / dt) + 1) * dt
    return Motion("half sine", dt, a * np.sin(np.pi * t / period), source="builtin:half-sine")


def _run(overrides, motion, method="explicit"):
    scene = load_scene("strip_footing_clay", overrides=COLUMN + overrides)
    model = build_model(scene)
    return scene, model, run_dynamic(model, scene, motion,
                                     DynamicOptions(method=method, snapshots=0), progress=False)


def _deepest_gauss_point(top, bottom):
    return 0.5 * (top + bottom) + 0.5 * (bottom - top) / math.sqrt(3.0)


def test_the_far_field_is_the_outermost_column_of_cells_on_each_side():
    # Reference: the mesh's grid lines (meshes/soil.py grid_lines): one layer per interval of
    # y lines, one cell per layer and side on a quad mesh.
    scene = load_scene("strip_footing_clay", overrides=COLUMN)
    model = build_model(scene)
    layout = far_field(model)
    x, y = grid_lines(scene.foundation.width, scene.continuum, scene.soil.layer_depth)
    depths = np.sort(y.max() - y)
    assert np.allclose(layout.top, depths[:-1], atol=1e-9)
    assert np.allclose(layout.bottom, depths[1:], atol=1e-9)
    assert layout.elements.size == 2 * (y.size - 1)
    centres = model.mesh.p[0][model.mesh.t[:, layout.elements]].mean(axis=0)
    outer = 0.5 * (x[0] + x[1]), 0.5 * (x[-2] + x[-1])
    assert np.allclose(np.where(layout.side == 0, outer[0], outer[1]), centres, atol=1e-9)


@pytest.fixture(scope="module")
def elastic_column():
    return {method: _run(["soil.model=elastic"], _ramp(0.1, 1.5), method)
            for method in ("explicit", "implicit")}


@pytest.mark.parametrize("method", ["explicit", "implicit"])
def test_an_elastic_column_strains_as_rho_a_z_over_g(elastic_column, method):
    # Reference: γ(z) = ρ a z / G (module docstring), to 1 %, on both sides and routes.
    scene, _, result = elastic_column[method]
    far = result.far_field
    G = scene.soil.youngs_modulus / (2.0 * (1.0 + scene.soil.poisson_ratio))
    z = _deepest_gauss_point(far.top, far.bottom)
    expected = scene.soil.density * 0.1 * G_ACC * z / G
    assert np.allclose(far.shear_strain, expected[None, :], rtol=0.01)
    assert far.bottom[-1] == pytest.approx(DEPTH, rel=1e-12)
    assert far.yield_range() is None and not far.yielded.any()
    summary = dynamic_summary(result)
    assert summary["far_field"]["yielded"] == "elastic"
    assert summary["far_field_yielded"] is False
    assert summary["far_field"]["peak_shear_strain"] == pytest.approx(expected[-1], rel=0.01)
    assert dynamic_warnings(summary) == []


def test_an_elastic_run_is_within_the_small_strain_reference(elastic_column):
    # Reference: the stated limit 0.10; an elastic soil has ε̄p = 0.
    _, _, result = elastic_column["explicit"]
    assert result.metadata["max_plastic_strain"] == 0.0
    assert result.metadata["validity"] == WITHIN
    ds = result.to_xarray()
    assert ds.attrs["validity"] == WITHIN
    assert ds.attrs["small_strain_limit"] == SMALL_STRAIN_LIMIT
    assert ds.attrs["far_field"] == "elastic"
    for name in ("far_field_shear_strain", "far_field_plastic_strain",
                 "far_field_plastic_strain_static"):
        assert ds[name].dims == ("side", "layer")
        assert ds[name].attrs["units"] == "1" and ds[name].attrs["long_name"]
    assert np.array_equal(ds.far_field_shear_strain.sel(side="right").values,
                          result.far_field.shear_strain[1])
    assert ds.layer_bottom.attrs["units"] == "m"


CU = 4.0  # kPa: a_y = c_u/(ρ g H) = 0.0453 g on the 5 m column of ρ = 1.8 t/m³


def _a_y(scene) -> float:
    return CU / (scene.soil.density * G_ACC * DEPTH)  # in g


@pytest.fixture(scope="module")
def tresca_columns():
    scene = load_scene("strip_footing_clay", overrides=COLUMN)
    a_y = _a_y(scene)
    strength = [f"soil.undrained_strength={CU}"]
    return {"below": _run(strength, _sine(0.9 * a_y, 1.5)),
            "above": _run(strength, _sine(0.1, 1.5))}


def test_a_tresca_column_stays_elastic_below_a_y(tresca_columns):
    # Reference: the largest shear stress ρ a H < c_u for a = 0.9 a_y (module docstring).
    _, _, result = tresca_columns["below"]
    far = result.far_field
    assert np.max(far.plastic_strain - far.plastic_strain_static) <= YIELD_THRESHOLD
    assert far.yield_range() is None
    assert result.metadata["far_field"] == "elastic"


def test_a_tresca_column_yields_at_its_base_above_a_y(tresca_columns):
    # Reference: above a_y = c_u/(ρ H) (here a = 2.2 a_y) the base yields first and caps what
    # the column above carries: the yielded range is the bottom layer of cells, from its top
    # to the base (within the element at the base), and the layers above stay below c_u.
    scene, _, result = tresca_columns["above"]
    far = result.far_field
    assert 0.1 / _a_y(scene) == pytest.approx(2.21, abs=0.01)
    top, bottom = far.yield_range()
    assert top == pytest.approx(far.top[-1], rel=1e-12)
    assert bottom == pytest.approx(DEPTH, rel=1e-12)
    G = scene.soil.youngs_modulus / (2.0 * (1.0 + scene.soil.poisson_ratio))
    assert np.all(G * far.shear_strain[:, :-1] < CU)
    summary = dynamic_summary(result)
    assert summary["far_field_yielded"] is True
    assert summary["far_field"]["yield_top"] == pytest.approx(far.top[-1], rel=1e-12)
    warnings = dynamic_warnings(summary, {"length": "m"})
    assert any(w.startswith("the far field yielded") for w in warnings)
    assert result.to_xarray().far_field_yielded.values.tolist() == [0] * (far.top.size - 1) + [1]


def test_a_run_past_the_limit_is_beyond_the_small_strain_reference(tresca_columns):
    # Reference: the stated limit 0.10 against the run's largest ε̄p, which the yielding base
    # takes far past it (the strain localises in one layer of cells).
    _, _, result = tresca_columns["above"]
    peak = result.metadata["max_plastic_strain"]
    assert peak > 2 * SMALL_STRAIN_LIMIT
    assert peak >= np.max(result.far_field.plastic_strain) > 2 * SMALL_STRAIN_LIMIT
    assert result.metadata["validity"] == BEYOND
    assert result.to_xarray().attrs["validity"] == BEYOND
    summary = dynamic_summary(result)
    assert summary["validity"] == BEYOND
    assert any(BEYOND in w for w in dynamic_warnings(summary))


@pytest.mark.parametrize("value, beyond", [(0.0, False), (0.0999, False), (0.1, False),
                                           (0.1001, True), (8.05, True), (None, False),
                                           (math.nan, False)])
def test_the_limit_is_strictly_above_ten_percent(value, beyond):
    # Reference: the limit stated in continuum/dynamics/validity.py, ε̄p > 0.10; a run that
    # did not record ε̄p (None, NaN) is not judged beyond it.
    assert beyond_small_strain(value) is beyond
    assert validity(value if value is not None else math.nan)["validity"] == (
        BEYOND if beyond else WITHIN)


def _stored_run(**extra) -> dict:
    """A finished continuum record of the map (comparisons/studies/winkler_map/points.py)."""
    from upliftlab.comparisons.studies.winkler_map.grid import MEASURES

    return {"measures": {q: 0.01 * (i + 1) for i, q in enumerate(MEASURES)},
            "wall_time_s": 1.0, "steps": 10, "energy_balance_error": 0.0, "dofs": 100,
            "max_plastic_strain": 0.5, **extra}


@pytest.mark.parametrize("extra, kept", [({"validity": BEYOND}, False),
                                         ({"validity": WITHIN}, True), ({}, True)])
def test_the_map_leaves_out_a_run_that_stored_beyond_and_reads_old_records_as_before(extra,
                                                                                       kept):
    # Reference: the rule stated in comparisons/studies/winkler_map/assemble.py: a record whose
    # stored verdict is BEYOND is left out (a refusal, flagged, its measures NaN); a record
    # without the verdict (the kept store's, made before it) is used whatever its ε̄p (0.5).
    from upliftlab.comparisons.studies.winkler_map.assemble import _continuum_into
    from upliftlab.comparisons.studies.winkler_map.dataset import PointArrays

    a, refusals, at = PointArrays.empty((1, 1, 1, 1, 1, 1), 2), [], (0,) * 6
    assert _continuum_into(a, at, _stored_run(**extra), None, "here", refusals) is kept
    assert bool(a.beyond[at]) is not kept and bool(a.bearing[at]) is False
    assert bool(np.isfinite(a.continuum[at]).all()) is kept
    assert bool(np.isnan(a.continuum[at]).all()) is not kept
    assert (len(refusals) == 1 and BEYOND in refusals[0]) is not kept
