"""The Winkler map's fitted bed (comparisons/studies/winkler_map/fitted_bed.py): its capacity
profile
and the fit of its exponent β to rotation pushovers.

References:
- the profile's two ends: β = 0 is one bearing pressure, V_ult/B over every tributary width
  (by hand); β = 1 is the end-stiffened elasto-plastic bed's yield forces, FS_v times each
  spring's static force, as the reduced model computes them from yield_multiple (another code
  path: its static equilibrium), 1e-12;
- parameter recovery: pushovers made by the bed itself at a known β (0.35, 0.7) are fitted back
  to that β with no misfit (1e-9), over the map's grid of β;
- identifiability: under a load so light that no spring yields on the paths, every β gives the
  same pushovers (the misfits equal to 1e-12) and the fit takes the lowest.
"""

import math

import numpy as np
import pytest

from upliftlab.comparisons.beds import bed_foundation, BedReference
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.comparisons.beds.fitted import (
    BETAS, _bed_table, capacity_profile, fit_capacity_profile)
from upliftlab.comparisons.beds.base import base_table
from upliftlab.comparisons.beds.pushover import bed_rocking
from upliftlab.comparisons.studies.winkler_map.rocking import theta_onset
from upliftlab.comparisons.beds.pushover import cyclic_path, rotation_path
from upliftlab.reduced import build_model
from upliftlab.reduced.compatibility import end_stiffened_bed
from upliftlab.scenes import scene_from_dict

B, V_ULT = 2.0, 519.2  # m and kN/m: the clay's strip and its capacity on 16 across
G, NU = 50.0e3 / 2.6, 0.3
STRUCTURE = {"weight": 100.0, "height": 3.0, "period": 0.5, "damping_ratio": 0.05,
             "rotary_inertia": 10.0}


def reference(N, rocking=None):
    extra = {"density": 1.8, "structure": {**STRUCTURE, "weight": N}}
    if rocking is not None:
        extra["rocking"] = rocking
    return BedReference("clay", N, B, 3.0, 27_513.1, 43_146.1, V_ULT, G, NU, extra=extra)


def built(table, N):
    data = {"schema": 1, "units": "kN-m-s", "structure": {**STRUCTURE, "weight": N},
            "foundation": {"support": "uplift", "half_width": 0.5 * B, **table},
            "motion": {"type": "free", "velocity": 1.0, "duration": 1.0}}
    return build_model(scene_from_dict(data))


def test_the_profiles_ends_are_one_pressure_and_the_stiffness_weighted_yield():
    bed = end_stiffened_bed(1.0, 1.0e5, 48, 10.0, 1.0 / 3.0)
    uniform = capacity_profile(bed.stiffnesses, bed.widths, V_ULT, 0.0)
    np.testing.assert_allclose(uniform / bed.widths, V_ULT / B, rtol=1e-12)
    N = V_ULT / 2.5
    weighted = built(bed_foundation("end_stiffened_plastic", reference(N), wm.FULL_OPTIONS), N)
    table = _bed_table(reference(N), wm.FULL_OPTIONS, 1.0)
    f = weighted.foundation_slice
    np.testing.assert_allclose(table["yield_forces"], weighted.params["fy"][f], rtol=1e-12)
    np.testing.assert_allclose(weighted.params["fy"][f], 2.5 * weighted.params["f0"][f],
                               rtol=1e-12)
    for beta in (0.0, 0.3, 1.0):
        assert sum(_bed_table(reference(N), wm.FULL_OPTIONS, beta)["yield_forces"]) == \
            pytest.approx(V_ULT, rel=1e-12)


def _pushovers(N, beta):
    """The bed's own rotation pushovers at ``beta``, as the continuum's records would be."""
    theta_on = theta_onset(N, "clay", B)
    options = wm.FULL_OPTIONS
    table = {"support": "uplift", "half_width": 0.5 * B,
             **_bed_table(reference(N), options, beta)}
    base = base_table()
    base["structure"] = {**STRUCTURE, "weight": N}
    pushed = bed_rocking(base, N, table, cyclic_path(theta_on, options),
                         rotation_path(theta_on, options))
    return {"cyclic": pushed["cyclic"], "monotonic": pushed["monotonic"], "theta_on": theta_on}


@pytest.mark.parametrize("beta", [0.35, 0.7])
def test_the_fit_recovers_the_exponent_of_its_own_pushovers(beta):
    N = V_ULT / 2.0  # FS_v = 2: the ends yield on the paths, so β shows
    fit = fit_capacity_profile(reference(N, _pushovers(N, beta)), wm.FULL_OPTIONS)
    assert fit.beta == beta and fit.misfit < 1e-9
    assert len(fit.misfits) == len(BETAS) and sorted(fit.misfits)[1] > 1e-3


def test_where_nothing_yields_beta_is_not_identifiable_and_the_fit_takes_the_lowest():
    N = V_ULT / 60.0
    rocking = _pushovers(N, 0.5)
    fit = fit_capacity_profile(reference(N, rocking), wm.FULL_OPTIONS)
    assert np.ptp(fit.misfits) < 1e-12 and fit.beta == 0.0 and fit.misfit < 1e-9
    assert math.isfinite(fit.misfit)


def test_the_fitted_bed_needs_the_continuums_pushovers():
    from upliftlab.checks import InputError

    with pytest.raises(InputError, match=r"extra\['rocking'\] is missing"):
        bed_foundation("end_stiffened_fitted_impedance", reference(100.0), wm.FULL_OPTIONS)
    stopped = reference(100.0, {"error": "monotonic: the rotation pushover stopped: step 9"})
    with pytest.raises(InputError, match=r"^the fitted bed at N = 100 \(clay\): the continuum's "
                                         r"rotation pushover stopped \(monotonic: the rotation "
                                         r"pushover stopped: step 9\)"):
        bed_foundation("end_stiffened_fitted_impedance", stopped, wm.FULL_OPTIONS)
