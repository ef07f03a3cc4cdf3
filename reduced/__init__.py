"""Ewing's compatibility-matrix model of a superstructure on compression-only foundation springs.

Build a model from a scene with :func:`build_model`, integrate it with :func:`run`, and read the
:class:`Response`. Static analyses live in :mod:`.static`; the foundation laws in :mod:`.laws`
(one module each, found by name); the spring table in :mod:`.springs`; the compiled integrators
in :mod:`.kernels`.
"""

#: The reduced model's revision: part of the key of every stored record made with it
#: (:mod:`upliftlab.comparisons.framework.store`). Raise it on purpose, in the commit that changes
# the
#: model's numbers, so that stored records of the old numbers are no longer read; an edit that
#: changes no number leaves it (stored records are then checked by a re-run sample instead).
REVISION = 3
# 3: the macro-element remembers the largest mobilisation each side (the sign of M) has
#    reached, and reloading below it is up to 1 + μ times stiffer in its plastic part (μ fitted, to
#    repeated cycles besides the others), so that a footing cycled at one amplitude shakes
#    down; its fits move; the other laws' numbers do not (μ = 0 is revision 2's law).
# 2: the macro-element's flow keeps a fitted share δ of the normal's heave and scales its
#    settlement coupling by s^ε (both fitted; δ = 1, ε = 0 is revision 1's law), so its fits
#    move; the other laws' numbers do not.


from .compatibility import (SpringLayout, compatibility_matrix, custom_springs, edge_springs,
                            end_stiffened_bed, equivalent_springs, stiffness_matrix, winkler_bed)
from .integrators import (METHODS, resolution_limit, stability_boundary, stability_limit,
                          time_step)
from .model import ReducedModel, build_model
from .response import Response
from .run import EnergyBalanceError, IntegrationError, run, run_model
from .static import rocking_pushover, uplift_onset_force

__all__ = [
    "REVISION",
    "SpringLayout", "compatibility_matrix", "custom_springs", "edge_springs",
    "end_stiffened_bed", "equivalent_springs", "stiffness_matrix", "winkler_bed",
    "METHODS", "stability_limit", "stability_boundary", "resolution_limit", "time_step",
    "ReducedModel", "build_model", "Response", "IntegrationError", "EnergyBalanceError", "run",
    "run_model", "rocking_pushover", "uplift_onset_force",
]
