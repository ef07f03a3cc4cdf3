"""The macro-element: a rigid strip footing's generalised forces (V, H, M) and displacements
(v, u, θ) at its centre, one law for the whole foundation (Cremer, Pecker and Davenne 2001;
Chatzigogos, Pecker and Salençon 2009): an elastic part, a nonlinear-elastic uplift mechanism
in closed form, and bounding-surface plasticity whose failure surface is the strip's capacity
under combined load.

:mod:`.params` the parameter record; :mod:`.capacity` the failure surface (effective width,
a parabola in H); :mod:`.uplift` the uplift mechanism; :mod:`.plastic` the update, one pure
function (state, displacement) → (forces, tangent, state).
"""

from .capacity import failure_function, failure_gradient, horizontal_capacity, moment_capacity
from .params import MacroElement, MacroStepError, bearing_factors
from .plastic import (LOAD_TOLERANCE, MacroState, MacroStep, at_rest, at_vertical_load,
                      elastic_forces, size, step, stored_energy)
from .uplift import (bed_energy, bed_forces, remainder_compliance, rounding_force,
                     vertical_rocking_forces)

__all__ = ["MacroElement", "MacroStepError", "MacroState", "MacroStep", "at_rest", "step",
           "at_vertical_load", "LOAD_TOLERANCE",
           "size", "elastic_forces", "stored_energy", "bearing_factors", "horizontal_capacity",
           "failure_function", "failure_gradient", "moment_capacity", "bed_forces",
           "bed_energy", "remainder_compliance", "rounding_force", "vertical_rocking_forces"]
