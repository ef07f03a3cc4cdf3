"""The soil's Rayleigh damping carried into a bed (upliftlab.comparisons.beds.soil_damping).

Reference: the correspondence principle of linear viscoelasticity: a soil whose stiffness
carries the viscous factor (1 + iωβ) (the continuum's β K₀) has every static footing stiffness
scaled by it, so a bed matched to K_r gains the rocking dashpot β K_r, and one matched to K_v
the vertical dashpot β K_v; the bed's own K_v and K_r (Σ k_i, Σ k_i x_i²) are read back from
the reduced model's spring layout, and K_r is the calibration's target (the clay's
π G B²/(8(1 − ν)), scenes/strip_footing_clay.toml). Off (None), the table is the builder's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.beds import BedReference, bed_foundation
from upliftlab.comparisons.beds.registry import BEDS
from upliftlab.comparisons.beds.soil_damping import with_soil_damping
from upliftlab.comparisons.studies import winkler_map as wm
from upliftlab.reduced.compatibility import layout_for
from upliftlab.scenes.structure import read_foundation
from upliftlab.units import unit_system

G, NU, B = 19230.77, 0.3, 2.0  # the clay scene's soil (kPa) and footing (m)
K_R = math.pi * G * B * B / (8.0 * (1.0 - NU))  # kN m/rad/m
BETA = 8.212e-4  # s: ξ = 2 % at 1.29 and 6.46 Hz (the 20 m box's default pair)


def _reference():
    return BedReference("clay", 171.39, B, 3.0, 3.0 * K_R, K_R, 514.16, G, NU,
                        extra={"density": 1.8})


def _layout(table):
    return layout_for(read_foundation(dict(table), 1.0, unit_system("kN-m-s")))


@pytest.mark.parametrize("name", ["uniform_plastic", "uniform_plastic_gazetas"])
def test_the_bed_gains_beta_times_its_stiffness_as_dashpots(name):
    # Reference: the correspondence principle (module docstring), to 1e-9.
    ref = _reference()
    plain = bed_foundation(name, ref, wm.FAST_OPTIONS)
    damped = bed_foundation(name, ref, wm.FAST_OPTIONS, soil_beta=BETA)
    assert plain == dict(BEDS[name].build(ref, wm.FAST_OPTIONS), **{
        k: plain[k] for k in ("support", "half_width")})  # off: the builder's own table
    layout = _layout(plain)
    added = np.asarray(damped["dashpots"]) - np.asarray(plain.get("dashpots") or 0.0)
    x = layout.positions
    assert added.sum() == pytest.approx(BETA * layout.stiffnesses.sum(), rel=1e-9)
    assert np.sum(added * x * x) == pytest.approx(BETA * K_R, rel=1e-6)  # the bed's K_r
    assert {k: v for k, v in damped.items() if k != "dashpots"} == \
        {k: v for k, v in plain.items() if k != "dashpots"}


def test_a_bed_with_its_own_damping_ratio_or_a_negative_beta_is_refused():
    # Reference: a scene's [foundation] takes dashpots or a damping_ratio, not both
    # (upliftlab/scenes/structure.py).
    table = dict(bed_foundation("uniform_plastic", _reference(), wm.FAST_OPTIONS))
    with pytest.raises(InputError, match="foundation.damping_ratio = 0.05"):
        with_soil_damping({**table, "damping_ratio": 0.05}, BETA)
    with pytest.raises(InputError, match=r"soil_beta = -0\.001: .*valid range is β ≥ 0"):
        with_soil_damping(table, -1e-3)
    assert with_soil_damping(table, None) is table
