"""The implicit route's time step: the largest step the P wave allows, the smallest the
contact tolerates, and the settings of a run, all checked before any work.

**Time step.** The fastest wave must not cross more than
:data:`~upliftlab.continuum.dynamics.waves.COURANT_LIMIT` = 2 of the mesh's smallest elements per
step: dt ≤
2 h_min/V_p. At ν = 0.3, V_p ≈ 1.87 V_s, so this is a shear-wave Courant number ≤ 1.07: the shear
waves that carry the input and the rocking radiation advance about one element per step, and the
implicit scheme (unconditionally stable) only smooths the faster P waves in the fine elements under
the footing. h_min is the shortest element edge. The default dt is the largest divisor of the
record's step below that limit. A step in which the waves cross several elements is what the rule
exists to refuse.

**A smallest step.** The step must not fall below :data:`MIN_SHEAR_COURANT` h_min/V_s either. Below
it the end-of-step contact resolves the footing nodes' own ringing after a landing (their period is
set by the shear stiffness of the locking-free element), the HHT dissipation no longer removes it,
the nodes chatter and the contact pumps energy into the system. This is what made nearly
incompressible soil gain energy: the P-wave rule shrinks the step as V_p/V_s grows. The bound,
0.21, lies above every case measured to fail and admits ν = 0.49. The two rules leave no step once
V_p/V_s > 2/:data:`MIN_SHEAR_COURANT` = 9.5, i.e. ν > 0.494 (somewhat less where the step is
rounded down to a divisor of the record's): such soil is refused here (InputError naming ν) and
runs on the explicit route (:mod:`~upliftlab.continuum.dynamics.explicit`), whose contact only
dissipates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...checks import InputError
from .superstructure import check_superstructure
from .waves import COURANT_LIMIT

__all__ = ["MIN_SHEAR_COURANT", "ImplicitSettings", "implicit_settings", "check_smallest_step"]

#: Smallest shear-wave Courant number V_s dt / h_min of the implicit route (module docstring).
MIN_SHEAR_COURANT = 0.21


@dataclass(frozen=True)
class ImplicitSettings:
    """HHT ``alpha``, step ``dt`` (s), ``steps``, ``base``, ``sides``, ``prescribe_u`` (the
    footing's u follows the base: a frictionless interface) and the step ``limit`` (s)."""

    alpha: float
    dt: float
    steps: int
    base: str
    sides: str
    prescribe_u: bool
    limit: float


def implicit_settings(model, scene, motion, options, ground) -> ImplicitSettings:
    """The step, duration and boundaries of an implicit run of ``options`` (a
    :class:`~upliftlab.continuum.dynamics.options.DynamicOptions`) on ``ground`` (its
    :class:`~upliftlab.continuum.dynamics.ground.Ground`), checked before any work."""
    check_superstructure(scene, motion)
    base, sides = ground.base, ground.sides
    alpha = 0.0 if options.scheme == "newmark" else (
        scene.analysis.hht_alpha if options.alpha is None else options.alpha)
    if not -1.0 / 3.0 <= alpha <= 0.0:
        raise InputError(f"analysis.hht_alpha = {alpha:g}: valid range is [-1/3, 0]")
    waves = ground.waves
    limit = waves.step_limit
    if options.dt is None:
        dt = motion.dt / max(1, math.ceil(motion.dt / limit * (1.0 - 1e-12)))
    else:
        dt = options.dt
        if dt > limit:
            vp = waves.speeds[0]
            raise InputError(
                f"DynamicOptions.dt = {dt:g} s: too coarse for the mesh's shortest wave transit "
                f"(h_min = {waves.smallest_element:.4g}, V_p = {vp:.4g}, h_min/V_p = "
                f"{limit / COURANT_LIMIT:.4g} s); valid range is (0, {limit:.4g}] s "
                f"(V_p dt/h_min ≤ {COURANT_LIMIT:g})")
    check_smallest_step(model.soil, waves, dt, automatic=options.dt is None)
    duration = options.duration or scene.analysis.duration or motion.duration
    steps = max(1, int(round(duration / dt)))
    return ImplicitSettings(alpha=alpha, dt=dt, steps=steps, base=base, sides=sides,
                            prescribe_u=ground.prescribe_u, limit=limit)


def check_smallest_step(soil, waves, dt: float, automatic: bool) -> None:
    """Refuse a step below :data:`MIN_SHEAR_COURANT` h_min/V_s (module docstring) of the
    domain's ``waves`` (:class:`~upliftlab.continuum.dynamics.waves.DomainWaves`): naming the
    ``soil``'s ν when the P-wave rule forced it, else the step."""
    vp, vs = waves.speeds
    limit = waves.step_limit
    floor = MIN_SHEAR_COURANT * waves.smallest_element / vs
    if dt >= floor * (1.0 - 1e-12):
        return
    why = (f"below {floor:.4g} s = {MIN_SHEAR_COURANT:g} h_min/V_s the implicit route's "
           "end-of-step contact chatters and gains energy")
    if automatic:
        nu = soil.poisson_ratio
        raise InputError(
            f"soil.poisson_ratio = {nu:g}: the implicit step follows the P wave (dt = {dt:.4g} "
            f"s ≤ {limit:.4g} s, V_p/V_s = {vp / vs:.3g}) and {why}; valid range for "
            f"continuum.dynamics = 'implicit' is V_p/V_s ≤ {2.0 / MIN_SHEAR_COURANT:.3g} "
            "(ν ≤ 0.494, less where the step rounds down to the record's); use "
            "continuum.dynamics = 'explicit'")
    valid = (f"[{floor:.4g}, {limit:.4g}] s" if floor <= limit else
             "empty for this soil (use continuum.dynamics = 'explicit')")
    raise InputError(f"DynamicOptions.dt = {dt:g} s: {why}; valid range is {valid}")
