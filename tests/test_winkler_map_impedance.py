"""The Winkler map's bed with radiation dashpots from the continuum's own impedance
(``uniform_plastic_impedance``): its dashpots, its frequency, its cost and the fast map with it.

References:
- the bed's dashpots: Σ c_i must be the FE impedance's C_v and Σ c_i x_i² its C_r at the chosen
  frequency, both read here from an :class:`~upliftlab.continuum.impedance.analysis.Impedance`
  computed in
  the test (4 across) by its own accessor ``dashpot`` at a frequency of its grid (no
  interpolation), the sums taken over the reduced model's own spring layout (1e-12);
- the chosen frequency: the lower root of the two-degree-of-freedom (story, rocking) frequency
  equation written by hand, m I ω⁴ − [k I + m(k h² + K_r)] ω² + k K_r = 0 with k = m (2π/T)²
  and K_r the continuum's (the bed's, by the calibration identity of anchors §4) (1e-9);
- the cost of a soil's impedance: P·dofs·frequencies written by hand (1e-12);
- the fast map with the new bed: every measure finite and the impedance stored once per soil
  at the frequencies of ``IMPEDANCE_A0`` (exact), the footing's rocking a0 inside them.
"""

from __future__ import annotations

import concurrent.futures as cf
import math
from dataclasses import replace

import numpy as np
import pytest

from upliftlab.anchors import prandtl_capacity
from upliftlab.checks import InputError
from upliftlab.comparisons.beds import bed_foundation, BedReference
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.comparisons.studies.winkler_map.cost import (IMPEDANCE_SECONDS_PER_DOF_FREQUENCY,
                                                            estimate_cost)
from upliftlab.comparisons.beds.dashpots import (
    bed_rocking_frequency, impedance_dashpots_of)
from upliftlab.comparisons.studies.winkler_map.impedance_points import IMPEDANCE_A0, elastic_soil
from upliftlab.comparisons.beds.base import base_table
from upliftlab.comparisons.studies.winkler_map.points import point_table
from upliftlab.continuum.impedance.analysis import ImpedanceOptions, impedance, impedance_model
from upliftlab.continuum.dynamics.waves import wave_speeds
from upliftlab.reduced import build_model as build_reduced
from upliftlab.scenes import ContinuumOptions, Soil, load_scene, scene_from_dict

G_ACC = load_scene("strip_footing_clay").g
B = 2.0
SOIL = Soil(**elastic_soil("clay"))
K_R = math.pi * SOIL.shear_modulus * B * B / (8.0 * (1.0 - SOIL.poisson_ratio))  # anchors §4
V_ULT = prandtl_capacity(50.0, B)


def reference(h_over_B=1.5, period=0.5, fs_v=3.0, impedance_record=None):
    """A point's BedReference: the clay's elastic K_r, Prandtl's capacity, its structure."""
    N = V_ULT / fs_v
    structure = point_table(base_table(), "clay", 4, N, h_over_B, period, G_ACC)["structure"]
    extra = {"density": SOIL.density, "structure": structure}
    if impedance_record is not None:
        extra["impedance"] = impedance_record
    return BedReference("clay", N, B, h_over_B * B, 3.0 * K_R, K_R, V_ULT,
                           SOIL.shear_modulus, SOIL.poisson_ratio, extra=extra)


def fe_impedance(a0):
    options = ImpedanceOptions(a0=tuple(a0))
    return impedance(impedance_model(SOIL, B, ContinuumOptions(elements_across=4), options),
                     options)


def hand_frequency(ref) -> float:
    """The lower root of m I ω⁴ − [k I + m (k h² + K_r)] ω² + k K_r = 0 (module docstring)."""
    s = ref.extra["structure"]
    m = s["weight"] / G_ACC
    k = m * (2.0 * math.pi / s["period"]) ** 2
    h, I, K = s["height"], s["rotary_inertia"], ref.K_r
    a, b, c = m * I, k * I + m * (k * h * h + K), k * K
    return math.sqrt((b - math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a))


@pytest.mark.parametrize("h_over_B, period, fs_v", [(1.5, 0.5, 3.0), (1.0, 0.2, 10.0),
                                                    (2.5, 0.5, 2.0)])
def test_the_chosen_frequency_is_the_flexible_base_root_by_hand(h_over_B, period, fs_v):
    ref = reference(h_over_B, period, fs_v)
    omega = bed_rocking_frequency(ref, wm.FAST_OPTIONS)
    assert omega == pytest.approx(hand_frequency(ref), rel=1e-9)
    assert omega < 2.0 * math.pi / period  # lengthened by the rocking spring


@pytest.mark.parametrize("h_over_B, period, fs_v", [(1.5, 0.5, 3.0), (1.0, 0.2, 10.0)])
def test_on_the_half_plane_the_frequency_is_the_swaying_flexible_bases_by_hand(h_over_B, period,
                                                                                fs_v):
    """On the half-plane reference the footing sways on its tie K_h with its own mass m_b
    (1 % of N): ω is the lowest root of the 3-DOF flexible base written out here, DOFs
    (u_story, u_base, θ), K = [[k, −k, −k h], [−k, k + K_h, k h], [−k h, k h, k h² + K_r]],
    M = diag(m, m_b, I) (Veletsos & Meek's base with its inertia), solved by numpy's
    eigvals; the sway lowers it below the rocking-only root (3.5 % and 6.7 % on these points)."""
    N = V_ULT / fs_v
    table = point_table(base_table(), "clay", 4, N, h_over_B, period, G_ACC, "half_plane")
    structure, tie = table["structure"], table["continuum"]["horizontal_tie"]
    ref = BedReference("clay", N, B, h_over_B * B, 3.0 * K_R, K_R, V_ULT, SOIL.shear_modulus,
                       SOIL.poisson_ratio, extra={"density": SOIL.density,
                                                  "structure": structure,
                                                  "sway_stiffness": tie})
    omega = bed_rocking_frequency(ref, wm.FAST_OPTIONS)
    m, m_b = structure["weight"] / G_ACC, (structure["vertical_weight"] - structure["weight"]) / G_ACC
    k = m * (2.0 * math.pi / period) ** 2
    h, I = structure["height"], structure["rotary_inertia"]
    K = np.array([[k, -k, -k * h], [-k, k + tie, k * h], [-k * h, k * h, k * h * h + K_R]])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(np.diag([m, m_b, I]), K)).real)
    assert omega == pytest.approx(math.sqrt(w2[0]), rel=1e-9)
    rocking_only = hand_frequency(ref)
    assert 0.92 * rocking_only < omega < 0.975 * rocking_only


def test_the_beds_dashpots_reproduce_the_fe_impedance_at_the_rocking_frequency():
    """Σ c_i = C_v and Σ c_i x_i² = C_r of the FE impedance at the point's rocking frequency,
    which is a node of the impedance's grid here, so C_j is the accessor's value itself."""
    options = wm.FAST_OPTIONS
    omega = bed_rocking_frequency(reference(), options)
    vs = wave_speeds(SOIL)[1]
    a0 = omega * 0.5 * B / vs
    record = fe_impedance([0.8 * a0, a0, 1.25 * a0])
    assert record.omega[1] == pytest.approx(omega, rel=1e-14)
    C_v, C_r = record.dashpot("v")[1], record.dashpot("r")[1]
    ref = reference(impedance_record=record)
    table = bed_foundation("uniform_plastic_impedance", ref, options)
    data = {k: v for k, v in base_table().items() if k not in ("soil", "continuum")}
    data.update(structure=ref.extra["structure"], foundation=table,
                motion={"type": "free", "velocity": 1.0, "duration": 1.0})
    layout = build_reduced(scene_from_dict(data, merged=True)).layout
    c = np.asarray(table["dashpots"])
    assert c.size == layout.count == options.springs and (c >= 0.0).all()
    assert float(np.sum(c)) == pytest.approx(C_v, rel=1e-12)
    assert float(np.sum(c * layout.positions ** 2)) == pytest.approx(C_r, rel=1e-12)
    assert "sway_stiffness" not in table and "sway_damping" not in table
    # the same numbers as the bed reports
    reported = impedance_dashpots_of(ref, options)
    assert (reported.C_v, reported.C_r) == pytest.approx((C_v, C_r), rel=1e-12)


def test_a_rocking_frequency_outside_the_impedance_is_refused():
    ref = reference(impedance_record=fe_impedance([1.0, 1.5]))
    with pytest.raises(InputError, match="outside the impedance's frequencies"):
        bed_foundation("uniform_plastic_impedance", ref, wm.FAST_OPTIONS)
    with pytest.raises(InputError, match=r"extra\['impedance'\] is missing"):
        bed_foundation("uniform_plastic_impedance", reference(), wm.FAST_OPTIONS)


def test_a_soils_impedance_is_one_static_run_costed_per_dof_and_frequency():
    """An impedance not yet stored costs P·dofs·frequencies and is one static run of its own
    (its soil's statics stored)."""
    scene = load_scene("strip_footing_clay")
    estimate = estimate_cost([("clay", scene, True)], [], [], [],
                             [("clay", 1000, 19, False)], [])
    assert (estimate.static, estimate.stored, estimate.runs) == (1, 1, 1)
    assert estimate.seconds == pytest.approx(IMPEDANCE_SECONDS_PER_DOF_FREQUENCY * 1000 * 19,
                                             rel=1e-12)
    stored = estimate_cost([("clay", scene, True)], [], [], [], [("clay", 1000, 19, True)], [])
    assert (stored.static, stored.stored, stored.seconds) == (0, 2, 0.0)


@pytest.fixture(scope="module")
def fast_map(tmp_path_factory):
    out = tmp_path_factory.mktemp("winkler_map_impedance")
    options = replace(wm.FAST_OPTIONS, beds=("uniform_plastic", "uniform_plastic_impedance"),
                      figures=False)
    with cf.ThreadPoolExecutor(1) as pool:
        return wm.run(fast=True, out=out, options=options, executor=pool, progress=False)


def test_the_fast_map_runs_with_the_impedance_bed(fast_map):
    from upliftlab.comparisons.studies.winkler_map.parts import estimate_of, map_of, statics_of

    d, statics = map_of(fast_map.data), statics_of(fast_map.data)
    assert tuple(d.calibration.values) == ("uniform_plastic", "uniform_plastic_impedance")
    for q in wm.MEASURES:
        assert np.isfinite(d[f"continuum_{q}"]).all() and np.isfinite(d[f"bed_{q}"]).all()
    assert np.isfinite(d.error).all()
    assert list(statics.soil.values) == ["clay"]
    assert tuple(statics.impedance_a0.sel(soil="clay").values) == IMPEDANCE_A0
    # the statics pair, the impedance, a cyclic and a monotonic rotation pushover per FS_v;
    # each dynamic point twice (its run and, the fast options making E_F, its energy run)
    estimate = estimate_of(d)
    assert (estimate.runs, estimate.static, estimate.dynamic) == (10, 6, 4)
    text = (fast_map.study.directory / "summary.md").read_text()
    assert "No bed has a sway spring" in text and "U-p-I" in text
    assert fast_map.study.numbers["impedance"]["clay"]["a0"] == list(IMPEDANCE_A0)


def test_the_continuum_footing_does_not_sway_on_the_maps_frictionless_soil(fast_map):
    """Why the bed has no sway spring: on the map's frictionless interface the explicit route
    prescribes the footing's u to follow the rigid base (``ExplicitSettings.prescribe_u``), so
    its u relative to the base is zero at every recorded step (exactly) while it rocks."""
    from upliftlab.continuum import build_model
    from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
    from upliftlab.comparisons.studies.winkler_map.points import point_scene

    table = point_table(base_table(), "clay", 4, float(fast_map.data["map"].vertical_load.sel(soil="clay", fs_v=2.0)), 1.5, 0.2, G_ACC)
    point = {"scene": table, "motion": {"type": "ricker", "period": 0.2, "duration": 0.4,
                                        "name": "ricker"}, "intensity": 3.0}
    scene = point_scene(point)
    model = build_model(scene)
    assert scene.soil.interface == "frictionless" and not model.footing.interface.tangential
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(snapshots=0, energy=False))
    footing = np.asarray(result.footing)
    assert np.max(np.abs(footing[:, 0])) == 0.0
    assert np.max(np.abs(footing[:, 2])) > 1e-4  # it rocks
