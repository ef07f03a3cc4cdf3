"""The Winkler map's q–z bed (comparisons/studies/winkler_map/qz_bed.py): what its [foundation]
table
builds in the reduced model.

References:
- capacity identity: Σ q_ult,i of the built springs equals the continuum's V_ult (the table's
  capacity_multiple times the weight, shared over the tributary widths), 1e-12;
- K_v and K_r of the built bed equal Σ k_i and Σ k_i x_i² summed here by hand from the table's
  own stiffnesses and positions (1e-9), and K_r equals the continuum's (the bed keeps K_r: its
  K_r/K_v = 1.57 m² exceeds b² = 1 m², which no bed under the footing reaches), 1e-9;
- the shape: the springs' exponent, elastic range and z_ref are the fit's, which is checked
  against the pushover it was fitted to: its largest misfit is below 5 % of V_ult (a measured
  bound: 0.8 % when written, on this pushover of 10 points).

The fast map's run of the bed (finite measures: a run whose energy balance fails the
project's tolerance is refused, and its measures are NaN) is in tests/test_winkler_map.py,
which shares the fast study.
"""

from dataclasses import replace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.beds import bed_foundation, BedReference
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.comparisons.beds.qz.bed import qz_bed_fit
from upliftlab.reduced import build_model
from upliftlab.reduced.kernels import QZ
from upliftlab.scenes import scene_from_dict

# the clay strip's statics on 16 elements across (B = 2 m): K_v, K_r (kN/m/m, kN m/rad/m), and
# its vertical pushover to 0.05 B (m, kN/m), as the map stored them
K_V, K_R = 27_513.060239261256, 43_146.07016960808
SETTLEMENT = (0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1)
LOAD = (269.0117218521554, 403.7481977334191, 457.80830672895104, 490.57714660331527,
        511.31901739396653, 518.9441093024627, 519.1766976983142, 519.2034919883646,
        519.2094181078637, 519.2117395833355)
V_ULT = LOAD[-1]
N = V_ULT / 3.0


def _reference(**extra):
    return BedReference("clay", N, 2.0, 3.0, K_V, K_R, V_ULT, 19_230.8, 0.3,
                           extra={"density": 1.8, "settlement": SETTLEMENT, "load": LOAD,
                                  **extra})


def _built(table):
    data = {"schema": 1, "units": "kN-m-s",
            "structure": {"weight": N, "height": 3.0, "period": 0.5, "damping_ratio": 0.05,
                          "rotary_inertia": 10.0},
            "foundation": table, "motion": {"type": "free", "velocity": 1.0, "duration": 1.0}}
    return build_model(scene_from_dict(data))


def test_the_qz_bed_has_the_continuums_capacity_and_stiffness():
    table = bed_foundation("qz", _reference(), wm.FAST_OPTIONS)
    model = _built(table)
    qz = model.params[model.params["kind"] == QZ]
    assert qz.size == wm.FAST_OPTIONS.springs
    assert qz["qult"].sum() == pytest.approx(V_ULT, rel=1e-12)
    k, x = np.asarray(table["stiffnesses"]), np.asarray(table["positions"])
    assert model.layout.vertical_stiffness == pytest.approx(float(np.sum(k)), rel=1e-9)
    assert model.layout.rocking_stiffness == pytest.approx(float(np.sum(k * x * x)), rel=1e-9)
    assert model.layout.rocking_stiffness == pytest.approx(K_R, rel=1e-9)
    *_, fit = qz_bed_fit(_reference(), wm.FAST_OPTIONS)
    assert np.all(qz["npow"] == fit.exponent) and np.all(qz["elast"] == fit.elastic_range)
    assert np.all(qz["zref"] == fit.zref)
    assert fit.misfit_max < 0.05


def test_the_qz_bed_needs_the_pushover():
    ref = replace(_reference(), extra={"density": 1.8})
    with pytest.raises(InputError, match="vertical pushover"):
        bed_foundation("qz", ref, wm.FAST_OPTIONS)
