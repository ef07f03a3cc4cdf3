"""Time histories of the soil, the rigid footing and the superstructure under a ground motion.

:func:`run_dynamic` starts from the gravity state and runs one of two routes, chosen by the
scene's ``continuum.dynamics`` or :attr:`DynamicOptions.method`:

- explicit (the default, :mod:`~upliftlab.continuum.dynamics.explicit`): central differences
  with a lumped mass, the footing's contact solved exactly at every step;
- implicit (:mod:`~upliftlab.continuum.dynamics.implicit`): HHT-α with Newton, the contact
  solved exactly at the end of every step by the statics' contact solver.

Both share the unknowns (the soil DOF vector u from the geostatic state, the footing
q = (u, v, θ) and the story deformation s of an SDOF superstructure,
:mod:`~upliftlab.continuum.dynamics.superstructure`), the loads and boundaries
(:mod:`~upliftlab.continuum.dynamics.ground`, :mod:`~upliftlab.continuum.dynamics.waves`), the
options
(:mod:`~upliftlab.continuum.dynamics.options`) and the result with its energy account
(:mod:`~upliftlab.continuum.dynamics.result`). Every run's energy balance error is checked
against ``continuum.energy_tolerance`` (:mod:`~upliftlab.continuum.dynamics.run_control`).

The names of those modules that callers used from here stay importable from here.
"""

from __future__ import annotations

import time as _time

from ...checks import InputError
from ...progress import steps_progress
from ...time_schemes import NewmarkCoefficients, hht
from .options import SCHEMES, DynamicOptions
from .result import ENERGY, DynamicResult
from .ground import Ground, boundaries, dynamic_fixed, dynamic_ground, gravity_state
from .implicit import ImplicitRoute
from .run_control import check_energy, energy_floor
from .step_rules import MIN_SHEAR_COURANT
from .superstructure import StructureMatrices, structure_matrices
from .waves import (COURANT_LIMIT, dashpot_data, incident_load, mass_data, smallest_element,
                    time_step_limit, wave_speeds)

__all__ = ["DynamicOptions", "DynamicResult", "run_dynamic", "COURANT_LIMIT", "SCHEMES",
           "mass_data", "dashpot_data", "incident_load", "wave_speeds", "smallest_element",
           "time_step_limit", "newmark_parameters", "structure_matrices", "StructureMatrices",
           "MIN_SHEAR_COURANT", "ENERGY", "boundaries", "dynamic_fixed", "Ground",
           "dynamic_ground"]


def newmark_parameters(alpha: float, dt: float) -> NewmarkCoefficients:
    """The HHT-α constants of a step ``dt`` (s) (:func:`upliftlab.time_schemes.hht`)."""
    return hht(alpha, dt)


def run_dynamic(model, scene, motion, options: DynamicOptions = DynamicOptions(), *,
                progress=None) -> DynamicResult:
    """Gravity, then ``motion`` on ``model`` (built from ``scene``): see the module docstring.

    ``options.method`` (else the scene's ``continuum.dynamics``) chooses the explicit route
    (:class:`~upliftlab.continuum.dynamics.explicit.ExplicitRoute`) or the implicit one
    (:class:`~upliftlab.continuum.dynamics.implicit.ImplicitRoute`). How the motion enters the
    domain (:func:`~upliftlab.continuum.dynamics.ground.dynamic_ground`) is decided once, the
    route is planned, and then the gravity state is made once for either route. Every input is
    checked before any work
    (InputError naming the field, the value and the valid range). ``progress(k, n, state)`` is
    called after each step (explicit: each recorded row) if given; None shows a bar (elapsed
    time, ETA, θ and N) where someone watches, True always, False never
    (:mod:`upliftlab.progress`). Raises
    :class:`~upliftlab.continuum.statics.newton.ConvergenceError` naming the time if a step fails,
    :class:`~upliftlab.continuum.dynamics.run_control.EnergyBalanceError` if the energy balance
    error
    exceeds the tolerance, and :class:`~upliftlab.continuum.dynamics.run_control.Interrupted` (with
    the
    partial result) on a KeyboardInterrupt.
    """
    method = options.method or model.options.dynamics
    tolerance = options.energy_tolerance or model.options.energy_tolerance
    if method == "explicit" and (options.scheme != "hht" or options.alpha is not None):
        raise InputError(f"DynamicOptions.scheme = {options.scheme!r}, alpha = {options.alpha}: "
                         "the scheme and α are the implicit route's; valid with the explicit "
                         "route: scheme 'hht', alpha None (or method = 'implicit')")
    if method != "explicit" and options.soil_mass_scale != 1.0:
        raise InputError(f"DynamicOptions.soil_mass_scale = {options.soil_mass_scale:g}: only "
                         "the explicit route scales the soil's mass; valid with the implicit "
                         "route: 1 (or method = 'explicit')")
    ground = dynamic_ground(model, options)  # how the motion enters: decided once, for both
    if method == "explicit":  # every check of the route before any work
        from .explicit import ExplicitRoute
        route = ExplicitRoute(model, scene, motion, options, ground)
    else:
        route = ImplicitRoute(model, scene, motion, options, ground)
    started = _time.perf_counter()
    with steps_progress(progress, f"continuum dynamics ({method})",
                        postfix=_postfix) as report:
        static = gravity_state(model, scene, options, not model.footing.interface.tangential)
        result = route.run(static, report)
    result.metadata["wall_time_s"] = _time.perf_counter() - started
    check_energy(result, tolerance, energy_floor(scene, model.width))
    return result


def _postfix(state) -> str:
    return f"θ = {state.q[2]:.3g} rad, N = {state.N:.4g}"
