"""The implicit route of the continuum dynamics: HHT-α with Newton, the contact solved exactly
at the end of every step.

**Time stepping.** HHT-α (Hilber, Hughes & Taylor 1977) with β = (1 − α)²/4, γ = 1/2 − α;
α = 0 is Newmark's average acceleration (``scheme = "newmark"``), which conserves the energy of a
linear undamped system exactly. Stiffness, damping, contact and external forces are weighted
(1 + α) at n+1 and −α at n; inertia at n+1. Each step is one call of
:func:`~upliftlab.continuum.statics.newton.equilibrium`: the inertia, the dashpots and the α terms
of the
soil enter as a :class:`~upliftlab.continuum.statics.newton.SoilTerm` (a0 M/(1+α) + c0 C and an
offset; C the boundaries' dashpots plus the soil's Rayleigh damping α M + β K₀ where
``continuum.damping_ratio`` is given, :mod:`~upliftlab.continuum.dynamics.rayleigh`),
the superstructure and the footing's inertia as a
:class:`~upliftlab.continuum.statics.newton.FootingTerm`
(the story DOF s is eliminated exactly: its equation is linear), so the existing exact contact
solver does the rest. No second contact solver.

**Mass.** Consistent (``mass = "consistent"``, the default), integrated exactly (Q2: 3×3 points,
not the stiffness's reduced 2×2, which would make the element mass rank deficient). An implicit
scheme never inverts M, so the consistent mass costs nothing (the stiffness's pattern), and its
overestimate of the high frequencies partly cancels the period elongation of the trapezoidal rule.
``"lumped"`` (row sums; positive for Q2/P1/Q1) is offered for comparison.

**Contact switching.** The contact conditions are enforced exactly at the end-of-step
configuration (gap_{n+1} ≥ 0, P_{n+1} ≥ 0, P g = 0) by the primal–dual active set that
:func:`~upliftlab.continuum.statics.newton.equilibrium` solves at every Newton iteration,
warm-started from
the last converged set; a step converges only with a settled set. A landing is an inelastic
impact of the footing's nodes, absorbed by the implicit scheme in the step where the gap closes
(no penalty, no restitution law, no velocity-jump rule, no set held from step to step). The HHT
dissipation (α < 0, the default: the scene's ``analysis.hht_alpha``) removes the spurious
high-frequency ringing after an impact that makes a node reopen and close again; Newmark's
average acceleration (α = 0) does not, and chatters. A bonded interface whose edge lifts off can
make the active set cycle at a node where P and g both vanish; such a step raises
:class:`ConvergenceError` rather than guess a set.

The step rules are :mod:`~upliftlab.continuum.dynamics.step_rules`', the iteration matrix
:mod:`~upliftlab.continuum.dynamics.iteration_matrix`', the footing and story's equations
:mod:`~upliftlab.continuum.dynamics.superstructure`'.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...time_schemes import NewmarkCoefficients, hht
from ...log import logger
from .rayleigh import describe, metadata, rayleigh, stiffness_data
from .result import DynamicResult, Recorder
from ..contact.footing import ContactError
from .ground import free_field_motion, ground_velocity
from .iteration_matrix import FrozenTangent, dynamic_model, soil_residual
from ..statics.newton import Anderson, Control, ConvergenceError, FootingTerm, SoilTerm, equilibrium
from .run_control import BearingFailure, keeping_what_ran, settled_to_failure
from .step_rules import implicit_settings
from .superstructure import (eliminate_story, hht_form, story_deformation, structure_matrices,
                             structure_work)
from .waves import COURANT_LIMIT, mass_data

__all__ = ["Kinematics", "ImplicitRoute", "ImplicitRun"]


@dataclass(eq=False)
class Kinematics:
    """Displacement, velocity, acceleration of a set of DOFs (mutable loop state)."""

    d: np.ndarray
    v: np.ndarray
    a: np.ndarray

    def advance(self, new: np.ndarray, c: NewmarkCoefficients) -> None:
        """Move to the end-of-step displacement ``new`` by the scheme ``c``."""
        a = c.a0 * (new - self.d) - c.a1 * self.v - c.a2 * self.a
        self.v = self.v + c.dt * ((1.0 - c.gamma) * self.a + c.gamma * a)
        self.d, self.a = new, a

    def predict(self, dt: float) -> np.ndarray:
        """The displacement one step ``dt`` ahead at constant acceleration, d + dt v + dt² a/2:
        the first Newton iterate of the step
        (:mod:`~upliftlab.continuum.dynamics.iteration_matrix`)."""
        return self.d + dt * self.v + (0.5 * dt * dt) * self.a

    def history(self, c: NewmarkCoefficients) -> np.ndarray:
        """The part of (M/(1+α)) ü + C u̇ at n+1 that does not depend on the new d, per matrix:
        (mass vector, damping vector) to multiply."""
        return (-c.a0 * self.d - c.a1 * self.v - c.a2 * self.a,
                -c.c0 * self.d + c.c1 * self.v + c.c2 * self.a)


class ImplicitRoute:
    """The implicit route of a run (module docstring), planned before any work: its settings
    (:func:`~.step_rules.implicit_settings`), checked here; :meth:`run` integrates from the
    gravity state that :func:`~upliftlab.continuum.dynamics.run.run_dynamic` makes for either
    route."""

    def __init__(self, model, scene, motion, options, ground):
        self.model, self.scene, self.motion, self.options = model, scene, motion, options
        self.ground = ground
        self.settings = implicit_settings(model, scene, motion, options, ground)
        damping = rayleigh(model)
        if damping is not None:
            logger("continuum").info("upliftlab: " + describe(damping))

    def run(self, static, progress=None) -> DynamicResult:
        """The time histories from the gravity state ``static`` (``progress`` as
        :func:`~upliftlab.continuum.dynamics.run.run_dynamic` takes it)."""
        model, fixed = self.model, self.ground.fixed
        dyn = dynamic_model(model, fixed)
        frozen = dyn if model.linear else dynamic_model(model, fixed, FrozenTangent)
        run = ImplicitRun(dyn, frozen, self.scene, self.motion, self.options, self.settings,
                          static, self.ground)
        return run.loop(progress)


class ImplicitRun:
    """The time loop's constant pieces and its mutable state."""

    def __init__(self, dyn, frozen, scene, motion, options, settings, static, ground):
        self.dyn, self.frozen, self.scene, self.motion = dyn, frozen, scene, motion
        self.options, self.settings = options, settings
        self.c = hht(settings.alpha, settings.dt)
        c, alpha = self.c, settings.alpha
        pattern = dyn.disc.pattern
        self.M = pattern.matrix(mass_data(dyn, options.mass or "consistent"))
        self.rayleigh = rayleigh(dyn)
        damping = ground.waves.dashpots
        if self.rayleigh is not None:  # C = the boundaries' dashpots + α M + β K₀
            damping = damping + self.rayleigh.alpha * self.M.data \
                + self.rayleigh.beta * stiffness_data(dyn)
        self.C = pattern.matrix(damping)
        self.soil_data = c.a0 / (1.0 + alpha) * self.M.data + c.c0 * self.C.data
        self.soil_matrix = pattern.matrix(self.soil_data)
        self.C = self.C.copy()  # its own index arrays: the pattern's are shared
        self.C.eliminate_zeros()  # a box without dashpots: its products then cost nothing
        R0 = soil_residual(dyn, static.stress)
        self.release = np.zeros(dyn.disc.ndofs)
        self.release[ground.released] = R0[ground.released]
        if ground.waves.incident is None:  # a rigid base: the relative formulation
            r = np.zeros(dyn.disc.ndofs)
            r[ground.x] = 1.0
            self.ground_soil = -(self.M @ r)       # per unit a_g (length/s²)
            self.incident = np.zeros(dyn.disc.ndofs)
        else:
            self.ground_soil = np.zeros(dyn.disc.ndofs)
            self.incident = ground.waves.incident  # per unit incident velocity
        self.z = structure_matrices(scene)
        self.ground_z = -(self.z.M @ self.z.r) if settings.base == "rigid" else np.zeros(4)
        self.g = scene.g
        self.vg = ground_velocity(motion, settings.dt, settings.steps)
        #: the horizontal tie's ground load at every step (ground.py; None: no tie)
        self.tie_load = None
        tie = dyn.options.horizontal_tie
        if tie is not None and settings.base == "compliant":
            c_tie = dyn.options.horizontal_tie_damping or 0.0
            self.z = replace(self.z, K=self.z.K + np.diag([tie, 0.0, 0.0, 0.0]),
                             C=self.z.C + np.diag([c_tie, 0.0, 0.0, 0.0]))
            u_ff, v_ff = free_field_motion(dyn, self.vg * scene.g, settings.dt)
            self.tie_load = tie * u_ff + c_tie * v_ff
        self.static = static
        self.need_R = alpha != 0.0 or options.energy
        self.anderson = Anderson(options.newton.anderson)  # its pairs serve the whole run

    def load(self, k: int):
        """(soil load, footing load) of the ground at step k (time k dt)."""
        t = k * self.settings.dt
        ag = float(self.motion.acceleration_at(t)) * self.g
        soil = self.ground_soil * ag + self.incident * (0.5 * self.vg[k] * self.g)
        footing = self.ground_z * ag + self.z.gravity
        if self.tie_load is not None:
            footing = footing + np.array([self.tie_load[k], 0.0, 0.0, 0.0])
        return soil, footing, ag

    def contact_vector(self, state) -> np.ndarray:
        f = np.zeros(self.dyn.disc.ndofs)
        f[self.dyn.blocks.contact] = state.force
        return f

    def loop(self, progress) -> DynamicResult:
        dyn, st, opts = self.dyn, self.settings, self.options
        n = st.steps
        state = self.static
        soil = Kinematics(state.u.copy(), np.zeros_like(state.u), np.zeros_like(state.u))
        z0 = np.append(state.q, 0.0)
        zv = np.zeros(4)
        zv[3] = self.motion.initial_velocity
        za = np.zeros(4)
        za[3] = -self.z.C[3, 3] * zv[3] / self.z.story_mass
        zk = Kinematics(z0, zv, za)
        ag = self.load(0)[2]
        R = soil_residual(dyn, state.stress) if self.need_R else None
        rec = Recorder(dyn, n, opts.snapshots)
        energy = np.zeros(5) if opts.energy else np.full(5, np.nan)
        rec.record(0, 0.0, state, zk, ag, energy, 0, False,
                   kinetic=self.kinetic(soil.v, zk.v) if opts.energy else math.nan)
        soil_term_data = self.soil_data
        control = Control((st.prescribe_u, False, False), (0.0, 0.0, 0.0))
        with keeping_what_ran(rec, dyn, self.motion, self.metadata):
            self.steps(rec, state, soil, zk, R, energy, soil_term_data, control, progress)
        return rec.result(dyn, self.motion, self.metadata())

    def metadata(self) -> dict:
        """The run's settings for the result's metadata."""
        st, options = self.settings, self.options
        return {"method": "implicit", "scheme": options.scheme, "alpha": st.alpha,
                "dt": st.dt, "steps": st.steps, "base": st.base, "sides": st.sides,
                "wave": options.wave, "mass": options.mass or "consistent",
                "dt_limit": st.limit, "courant_limit": COURANT_LIMIT,
                "newton_rtol": options.newton.rtol, **metadata(self.rayleigh)}

    def steps(self, rec, state, soil, zk, R, energy, soil_term_data, control, progress):
        """Steps 1…n, recorded into ``rec``."""
        dyn, c, st, opts = self.dyn, self.c, self.settings, self.options
        alpha = st.alpha
        w = alpha / (1.0 + alpha)
        n = st.steps
        F_soil, F_z, _ = self.load(0)
        for k in range(1, n + 1):
            F1_soil, F1_z, ag = self.load(k)
            fc = self.contact_vector(state)
            mh, ch = soil.history(c)
            offset = (self.M @ mh) / (1.0 + alpha) + self.C @ ch - self.release - F1_soil
            if alpha != 0.0:
                Xn = self.C @ soil.v + R - self.release - fc - F_soil
                offset = offset - w * Xn
            term = SoilTerm(soil_term_data, offset, self.soil_matrix)
            A, b = self.footing_affine(zk, state, F1_z, F_z)
            fterm = FootingTerm(*eliminate_story(A, b))
            if self.frozen is not self.dyn:
                self.frozen.new_step()
            start = (soil.predict(st.dt), zk.predict(st.dt)[:3]) if opts.predict else None
            new, refactored = self.step(state, control, term, fterm, k, start)
            if self.frozen is not self.dyn and self.frozen.refactored():
                refactored = True
            q = new.q
            s = story_deformation(A, b, q)
            z_old, u_old, v_old, zv_old = zk.d, soil.d, soil.v, zk.v
            soil.advance(new.u, c)
            zk.advance(np.append(q, s), c)
            if self.need_R:
                R1 = soil_residual(dyn, new.stress)
                if opts.energy:
                    energy += self.energy_increment(R, R1, new.u - u_old, v_old, soil.v,
                                                    (z_old, zk.d), zv_old, zk.v,
                                                    F_soil, F1_soil, F_z, F1_z,
                                                    (state.force, new.force))
                R = R1
            state, F_soil, F_z = new, F1_soil, F1_z
            rec.record(k, k * st.dt, state, zk, ag, energy, new.iterations, refactored,
                       kinetic=self.kinetic(soil.v, zk.v) if opts.energy else math.nan)
            if progress is not None:
                progress(k, n, state)

    def footing_affine(self, zk, state, F1, F0):
        """(A, b): A z_{n+1} + b + [Lᵀ f_c; 0] = 0, the footing and story equations
        (:func:`~upliftlab.continuum.dynamics.superstructure.hht_form`)."""
        return hht_form(self.z, self.c, zk.d, zk.v, zk.a, state.reaction, F1, F0)

    def step(self, state, control, term, fterm, k, start=None):
        """One step: modified Newton (for elastic soil the exact tangent), then, for plastic
        soil, the consistent tangent refactorised each iteration. Returns (state, refactored).
        A step that fails both raises :class:`ConvergenceError` naming the time: a contact set
        is never held or guessed. If the footing had by then settled
        :data:`~.run_control.FAILURE_SETTLEMENT` B or more, the error is a
        :class:`~.run_control.BearingFailure`: the run has reached the settlement that load
        tests call failure, whatever stopped Newton."""
        opts, errors = self.options.newton, []
        attempts = [self.frozen] + ([self.dyn] if self.frozen is not self.dyn else [])
        for model in attempts:
            memory = self.anderson if model is self.frozen else None
            if model is self.dyn and self.frozen is not self.dyn:
                opts = replace(opts, anderson=0)  # Newton's own rate needs no acceleration
            try:
                return equilibrium(model, state, control, opts, soil_term=term,
                                   footing_term=fterm, anderson=memory,
                                   start=start if model is self.frozen else None), \
                    model is not self.frozen
            except (ConvergenceError, ContactError, FloatingPointError) as exc:
                errors.append(str(exc))
        when, why = f"time step {k} (t = {k * self.settings.dt:.6g} s)", "; then ".join(errors)
        settlement, width = -float(state.q[1]), self.dyn.width
        if settled_to_failure(settlement, width):
            raise BearingFailure.of(f"at {when}", settlement, width, float(state.q[2]),
                                    f"Newton could not follow the step ({why})", step=k,
                                    time=k * self.settings.dt)
        raise ConvergenceError(f"{when}: {why}", step=k)

    def kinetic(self, v, zv) -> float:
        return 0.5 * float(v @ (self.M @ v)) + 0.5 * float(zv @ self.z.M @ zv)

    def energy_increment(self, R0, R1, du, v0, v1, zz, zv0, zv1, Fs0, Fs1, Fz0, Fz1, forces):
        """(0, strain, damping, input, contact) increments by the trapezoidal rule over the
        free DOFs: soil work of f_int − f_body (less the released reactions), story spring,
        footing weight; dashpot dissipation; work of the ground loads; the work the contact
        forces (``forces`` at both ends, on the soil) take out of the soil and the footing."""
        free = np.concatenate((self.dyn.blocks.interior, self.dyn.blocks.contact))
        d = du[free]
        z = self.z
        dz = zz[1] - zz[0]
        z_strain, z_damping, z_inputs = structure_work(z, zz[0], zz[1], Fz0, Fz1, zv0 + zv1, 0.5)
        strain = 0.5 * float((R0 + R1)[free] @ d) - float(self.release[free] @ d)
        strain += z_strain
        damping = 0.5 * float((self.C @ (v0 + v1))[free] @ d) + z_damping
        inputs = 0.5 * float((Fs0 + Fs1)[free] @ d) + z_inputs
        mean = 0.5 * (forces[0] + forces[1])
        L = self.dyn.footing.kinematics
        contact = -(float(mean @ du[self.dyn.blocks.contact]) - float((L.T @ mean) @ dz[:3]))
        return np.array([0.0, strain, damping, inputs, contact])
