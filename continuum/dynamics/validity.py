"""The small-strain validity limit of a continuum run: the largest equivalent plastic strain
ε̄p the model's small-strain kinematics can carry before its answer stops being a reference.

**The limit.** :data:`SMALL_STRAIN_LIMIT` = 0.10 on the run's largest ε̄p at any quadrature point
of the soil (``max_plastic_strain``, :class:`~upliftlab.continuum.dynamics.result.Recorder`).
A run above it ends as :data:`BEYOND` ("beyond the small-strain reference"): not a failure of the
run, and not a number a reduced model is held to (the map treats it like a bearing failure,
:mod:`upliftlab.comparisons.studies.winkler_map`).

**Why 10 %.** The continuum uses the linearised strain ε = sym ∇u on the fixed mesh, with the
footing's contact on the undeformed base. In simple shear of amount γ the Green–Lagrange strain
is E = [[0, γ/2], [γ/2, γ²/2]]: the linearised strain drops the term γ²/2, whose ratio to the
shear term γ/2 is γ itself; a rigid rotation ω gives a spurious linear strain of about ω²/2.
At γ = 10 % the neglected terms are 10 % of the strain the model reports, the usual bound of
a reference (Belytschko, Liu, Moran & Elkhodary, *Nonlinear Finite Elements for Continua and
Structures*, 2nd ed., 2014, §3.3: the Green strain and its small-displacement limit; Bathe,
*Finite Element Procedures*, 2014, §6.2.2). Plastic strain is where the soil's strain
concentrates; an ε̄p of 10 % means total strains at least that large there. The limit is
a closed-form bound on the kinematics, not a measured convergence: no large-deformation run
of this code exists to measure the error against.

**Caveat.** ε̄p at one quadrature point is singular at a rigid footing's corner and grows as
the mesh is refined there, so a run near the limit on a fine mesh may cross it on a finer one;
the verdict is of the run as meshed.
"""

from __future__ import annotations

import math

__all__ = ["SMALL_STRAIN_LIMIT", "WITHIN", "BEYOND", "validity", "beyond_small_strain"]

#: The largest equivalent plastic strain ε̄p (1) of a small-strain reference (module docstring).
SMALL_STRAIN_LIMIT = 0.10
#: The run's verdicts.
WITHIN = "within the small-strain reference"
BEYOND = "beyond the small-strain reference"


def validity(max_plastic_strain: float) -> dict:
    """The metadata of a run whose largest ε̄p is ``max_plastic_strain``: ``validity``
    (:data:`WITHIN` or :data:`BEYOND`) and the ``small_strain_limit`` it was judged by."""
    return {"validity": BEYOND if beyond_small_strain(max_plastic_strain) else WITHIN,
            "small_strain_limit": SMALL_STRAIN_LIMIT}


def beyond_small_strain(max_plastic_strain) -> bool:
    """Whether a largest ε̄p (None or NaN: not recorded, so not beyond) passes
    :data:`SMALL_STRAIN_LIMIT`."""
    if max_plastic_strain is None:
        return False
    value = float(max_plastic_strain)
    return math.isfinite(value) and value > SMALL_STRAIN_LIMIT
