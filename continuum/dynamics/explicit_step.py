"""The explicit route's step: the stability limit of central differences on the mesh, the
lumped mass and dashpots it is computed with, and the settings of a run, all checked before any
work.

**Stable step.** Central differences are stable for dt ω_max ≤ 2, ω_max² the largest
eigenvalue of M⁻¹K of the elastic soil on its free DOFs (computed by Lanczos, scipy's
``eigsh``, on M^{-1/2} K M^{-1/2}; a plastic tangent is softer and the exact contact does not
restrict the step). The admissible step is :data:`STABILITY_FRACTION` of that limit; the
default dt is the largest divisor of the record's step below it, and a larger dt is refused
with the limit in the message. A fresh process reads the limit of a mesh, mass and set of free
DOFs from the set-up cache (:mod:`~upliftlab.continuum.setup_cache`) when an earlier one has
computed it (:func:`stable_limit`).

**With Rayleigh damping** (``continuum.damping_ratio``,
:mod:`~upliftlab.continuum.dynamics.rayleigh`): the stiffness-proportional part acts at the
last half-step velocity through a Maxwell arm, and the limit 2/ω_max becomes that of one step
of the mode at ω_max with the arm and α M
(:func:`~upliftlab.continuum.dynamics.rayleigh.damped_critical`, about 2/(ω_max √(1 + β ω_c)));
the settings' ``reduction`` is that factor, the damping's extra cost in steps (1/reduction).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import skfem

from ...checks import InputError
from .. import setup_cache
from .iteration_matrix import elastic_plane_tangent
from .rayleigh import Rayleigh, damped_critical, rayleigh
from .superstructure import check_footing_mass, check_superstructure
from .waves import dashpot_data, full_basis

__all__ = ["STABILITY_FRACTION", "COURANT_ESTIMATE", "ExplicitSettings", "lumped_mass",
           "critical_step", "stable_limit", "recorded_steps",
           "explicit_settings", "explicit_setup"]

#: The admissible step as a fraction of the central-difference limit 2/ω_max.
STABILITY_FRACTION = 0.9
#: V_p dt / h_min of the explicit step, to estimate a run's cost before the mesh exists (the
#: step itself comes from the mesh's largest eigenvalue). Below the measured values so that the
#: estimate errs on the cost's side: Q2, 2×2 reduced, lumped: 0.36 (clay scene, 4 to 16 across).
COURANT_ESTIMATE = 0.3


@dataclass(frozen=True)
class ExplicitSettings:
    """``dt`` (s), ``steps``, ``record_every`` (steps per recorded row), ``base``, ``sides``,
    ``prescribe_u`` (frictionless without a tie: the footing's u follows the base), the
    admissible step ``limit`` = :data:`STABILITY_FRACTION` × ``critical`` (s), the
    central-difference limit of the mesh's highest frequency ``omega_max`` (rad/s): 2/ω_max,
    times ``reduction`` with the soil's Rayleigh ``damping`` (None: none; module docstring)."""

    dt: float
    steps: int
    record_every: int
    base: str
    sides: str
    prescribe_u: bool
    limit: float
    critical: float
    omega_max: float
    damping: Rayleigh | None = None
    reduction: float = 1.0


def lumped_mass(model) -> np.ndarray:
    """Row sums of the consistent soil mass, ∫ ρ φ_i (mass per length, per DOF)."""
    rho = model.soil.density
    return skfem.LinearForm(lambda v, w: rho * (v[0] + v[1])).assemble(full_basis(model))


def row_sums(model, data: np.ndarray) -> np.ndarray:
    """Row sums of a matrix given as CSR ``data`` in the model's pattern."""
    return np.asarray(model.disc.pattern.matrix(data).sum(axis=1)).ravel()


def critical_step(model, mass: np.ndarray, free: np.ndarray) -> tuple[float, float]:
    """(2/ω_max, ω_max): the central-difference limit of the elastic soil with the diagonal
    ``mass`` on the ``free`` DOFs (module docstring)."""
    from scipy import sparse
    from scipy.sparse.linalg import eigsh

    from .. import assembly

    K = assembly.stiffness(model.disc, elastic_plane_tangent(model))[free][:, free]
    scale = sparse.diags(1.0 / np.sqrt(mass[free]))
    A = (scale @ K @ scale).tocsr()
    start = np.random.default_rng(0).standard_normal(free.size)
    top = float(eigsh(A, k=1, which="LA", tol=1e-8, v0=start, return_eigenvectors=False)[0])
    omega = math.sqrt(top)
    return 2.0 / omega, omega


#: The sources of the stable step (as :func:`upliftlab.provenance.code_digest` names them).
STEP_SOURCES = setup_cache.MODEL_SOURCES + ("upliftlab.continuum/dynamics/explicit_step.py",
                                            "upliftlab.continuum/dynamics/iteration_matrix.py")


def stable_limit(model, mass: np.ndarray, free: np.ndarray) -> tuple[float, float]:
    """:func:`critical_step`, read from the set-up cache when a process has computed it for
    this model, ``mass`` and ``free`` DOFs (each by the digest of its values)."""
    inputs = {**setup_cache.model_inputs(model),
              "mass": setup_cache.array_digest({"mass": np.asarray(mass, dtype=float)}),
              "free": setup_cache.array_digest({"free": np.asarray(free, dtype=np.int64)})}

    def build():
        critical, omega = critical_step(model, mass, free)
        return {"critical": np.array(critical), "omega": np.array(omega)}
    arrays, _ = setup_cache.cached("stable_step", inputs, STEP_SOURCES, build)
    return float(arrays["critical"]), float(arrays["omega"])


def recorded_steps(settings: ExplicitSettings) -> np.ndarray:
    """The steps recorded as rows: every ``record_every``-th and the last."""
    return np.unique(np.append(np.arange(0, settings.steps, settings.record_every),
                               settings.steps))


def explicit_setup(model, scene, motion, options, ground) -> tuple[ExplicitSettings,
                                                                   np.ndarray, np.ndarray]:
    """(settings, mass, dashpots) of an explicit run on ``ground`` (a
    :class:`~upliftlab.continuum.dynamics.ground.Ground`): :func:`explicit_settings`, the
    soil's lumped mass scaled by ``options.soil_mass_scale`` and the row sums of the dashpots
    of ``ground.waves`` (per DOF) plus the Rayleigh α M (:mod:`~.rayleigh`), all made here,
    each once."""
    mass = options.soil_mass_scale * lumped_mass(model)
    dashpots = row_sums(model, ground.waves.dashpots)
    free = np.setdiff1d(np.arange(model.disc.ndofs), ground.fixed)
    settings = explicit_settings(model, scene, motion, options, ground, mass, free)
    if settings.damping is not None:
        dashpots = dashpots + settings.damping.alpha * mass
    return settings, mass, dashpots


def explicit_settings(model, scene, motion, options, ground, mass, free) -> ExplicitSettings:
    """The explicit run's step, duration and boundaries (``ground``'s), checked before any
    work."""
    check_superstructure(scene, motion)
    if options.mass not in (None, "lumped"):
        raise InputError(f"DynamicOptions.mass = {options.mass!r}: the explicit route needs a "
                         "diagonal mass; valid: 'lumped' (or continuum.dynamics = 'implicit')")
    bad = free[mass[free] <= 1e-12 * np.abs(mass).max()]  # zero up to round-off
    if bad.size:
        raise InputError(f"continuum.element = {model.disc.element!r}: its row-sum lumped mass "
                         f"is not positive at {bad.size} DOFs; the explicit route needs Q2, Q1 or "
                         "P1 (or continuum.dynamics = 'implicit')")
    check_footing_mass(scene)
    undamped, omega = stable_limit(model, mass, free)
    damping = rayleigh(model)
    critical = undamped if damping is None else damped_critical(omega, damping)
    limit = STABILITY_FRACTION * critical
    if options.dt is None:
        dt = motion.dt / max(1, math.ceil(motion.dt / limit * (1.0 - 1e-12)))
    else:
        dt = options.dt
        if dt > limit:
            what = (f"2/ω_max = {critical:.4g} s" if damping is None else
                    f"{critical:.4g} s = 2/ω_max × {critical * omega / 2.0:.4g} with the "
                    f"Rayleigh damping's Maxwell arm relaxing at "
                    f"ω_c = {damping.relaxation:.4g} rad/s")
            raise InputError(
                f"DynamicOptions.dt = {dt:g} s: beyond the explicit stability limit of the mesh "
                f"({what}, ω_max = {omega:.4g} rad/s); valid range is "
                f"(0, {limit:.4g}] s ({STABILITY_FRACTION:g} of that limit)")
    duration = options.duration or scene.analysis.duration or motion.duration
    steps = max(1, int(round(duration / dt)))
    if options.record_every is not None:
        every = options.record_every
    else:
        implicit = motion.dt / max(1, math.ceil(motion.dt / ground.waves.step_limit
                                                * (1.0 - 1e-12)))
        every = max(1, int(math.floor(implicit / dt * (1.0 + 1e-9))))
    return ExplicitSettings(dt=dt, steps=steps, record_every=min(every, steps), base=ground.base,
                            sides=ground.sides, prescribe_u=ground.prescribe_u,
                            limit=limit, critical=critical, omega_max=omega, damping=damping,
                            reduction=critical / undamped)
