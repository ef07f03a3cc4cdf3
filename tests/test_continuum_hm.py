"""The footing's H–M section at constant V (upliftlab.continuum.statics.combined): radial
probes in (u, B θ) on a rough strip that cannot take tension on Tresca clay.

References: Green's (1954) inclined load on Meyerhof's effective width, the lower bound of the
H–M section that Houlsby and Puzrin (1999) prove for this strip (a point of the continuum's
section lies on or outside it; the mesh's own strength c* = V_ult/((2 + π) B) normalises both,
so that the mesh's overshoot in V_ult cancels), in closed form; the problem's symmetry
(directions φ and φ + π give (H, M) and (−H, −M)); Green's sliding load H = c B′ at the widest
effective width, checked on the closed form itself against its defining equation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import hm_envelope, make_model
from upliftlab.continuum.statics.analyses import vertical_pushover
from upliftlab.continuum.statics.combined import green_effective_width
from upliftlab.scenes import ContinuumOptions, Soil

import hm_envelope as bench  # benchmarks/hm_envelope.py: the ray ratios

B, CU = 2.0, 50.0


def _model(interface="coulomb", across=4):
    soil = Soil(youngs_modulus=50e3, poisson_ratio=0.3, density=1.8, model="tresca",
                undrained_strength=CU, interface=interface, interface_friction=1.0)
    return make_model(soil, B, ContinuumOptions(elements_across=across))


def test_green_on_the_effective_width_is_its_closed_form():
    """At B′ = B and V ≤ (1 + π/2) c B the strip slides: H = c B; beyond, H solves
    V/(c B′) = 1 + π − arcsin(h) + √(1 − h²) (1e-10); the narrowest B′ carries V alone
    (H = 0, M = V (B − B′)/2)."""
    H, M = green_effective_width(2.0 * CU * B, CU, B, [B])
    assert H[0] == pytest.approx(CU * B, rel=1e-12) and M[0] == 0.0
    V = 0.8 * (2.0 + math.pi) * CU * B
    reduced = np.array([0.85, 1.0, 1.5]) * B
    reduced = reduced[reduced <= B]
    H, M = green_effective_width(V, CU, B, reduced)
    h = H / (CU * reduced)
    assert np.allclose(1 + math.pi - np.arcsin(h) + np.sqrt(1 - h * h),
                       V / (CU * reduced), rtol=1e-10)
    narrowest = V / ((2.0 + math.pi) * CU)
    H, M = green_effective_width(V, CU, B, [narrowest])
    assert H[0] == pytest.approx(0.0, abs=1e-6) and M[0] == pytest.approx(
        V * (B - narrowest) / 2.0, rel=1e-12)
    with pytest.raises(InputError, match="effective widths"):
        green_effective_width(V, CU, B, [0.5 * narrowest])


def test_the_section_lies_outside_the_lower_bound_and_is_symmetric():
    """On 4 across at v = 0.5: every probe's point is outside Green–effective-width's section
    (distance ratio ≥ 1; measured 1.09–1.36, the coarse mesh over-estimating as displacement
    elements do, and the bound being a bound), and φ = π mirrors φ = 0 to 1e-6."""
    model = _model()
    V_ult = vertical_pushover(model, np.linspace(0.01, 0.1, 10)).capacity
    c = V_ult / ((2.0 + math.pi) * B)
    V = 0.5 * V_ult
    env = hm_envelope(model, V, np.linspace(0.0, math.pi, 7), 0.1, 12)
    for H, M in zip(env.H, env.M):
        assert bench.bound_ratio(H / (c * B), M / (c * B * B), V, c) >= 1.0
    assert env.H[-1] == pytest.approx(-env.H[0], rel=1e-6)
    assert env.M[-1] == pytest.approx(-env.M[0], rel=1e-6)


def test_a_frictionless_interface_is_refused():
    with pytest.raises(InputError, match="^soil.interface = 'frictionless' in an H–M probe"):
        hm_envelope(_model("frictionless"), 100.0, [0.0], 0.01, 1)
