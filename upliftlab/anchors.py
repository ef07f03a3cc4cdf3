"""The closed forms used as references: each once, with its source and its tolerance.

The prose and derivations are in ``upliftlab/docs/anchors.md`` (sections §1–§5, shipped with
the package and printed as the report's appendix); this module is their code. Tests and the
report's verification table both take a reference from here, so that a reference and the
tolerance it is checked to exist in one place. Units follow the arguments (plane strain: per
unit length of footing).
"""

from __future__ import annotations

import math

__all__ = ["half_plane_onset_rotation"]


def half_plane_onset_rotation(N: float, B: float, G: float, nu: float) -> float:
    """θ_on = 2N(1 − ν)/(πGB) (rad): the rotation at which a rigid strip of width B under N on
    an elastic half-plane (shear modulus G, Poisson's ratio ν) starts to lift off
    (anchor §4)."""
    return 2.0 * N * (1.0 - nu) / (math.pi * G * B)
