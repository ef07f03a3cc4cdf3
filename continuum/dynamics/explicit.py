"""Explicit time histories of the soil, the rigid footing and the superstructure: central
differences with a lumped mass and the footing's contact solved exactly at every step.

**Scheme.** Central differences (Newmark β = 0, γ = 1/2) with the velocity at half steps:
M (v_{n+½} − v_{n−½})/dt + C (v_{n+½} + v_{n−½})/2 = F_n − R(u_n) + f_c,n and
u_{n+1} = u_n + dt v_{n+½}, started by a half step v_{½} = v_0 + (dt/2) a_0 from the static
state at rest. M is the soil's row-sum lumped mass (∫ ρ φ_i, positive for Q2, Q1 and P1; a
basis with a non-positive lumped mass, e.g. P2, is refused) and C the row sums of the
Lysmer–Kuhlemeyer dashpots, so each step is one evaluation of the internal force R(u_n) with
the return map (:class:`~upliftlab.continuum.dynamics.soil_force.SoilForce`, compiled) and a
diagonal
update: no Newton iteration and no factorisation. The loads and the unknowns are those of the
implicit route (:mod:`~upliftlab.continuum.dynamics.run`): the same gravity state, relative motion
on a rigid base (−M r a_g) or the incident-wave traction on a compliant one, released static
reactions as constant loads, and the footing with the story DOF of an SDOF superstructure.

**Contact.** The contact forces of step n are those that make the positions at n+1 satisfy the
contact conditions exactly (:mod:`~upliftlab.continuum.contact.step`): with a lumped mass this
couples only the footing nodes, the footing's (u, v, θ) and the story DOF, a complementarity
problem of the size of the footing. A node that lands stops with the footing in that step (an
inelastic impact of its lumped mass), and the contact forces only ever dissipate. The recorded
contact forces of row n (the pressure, the status, and the reactions H, N, M they add up to)
are those of step n, f_c,n: the ones in the equation of motion at t_n, in equilibrium with the
displacement u_n and the footing's q_n recorded in the same row, as the implicit route records
them. They close the gaps at t_{n+1}, so the complementarity g ≥ 0, P ≥ 0, P g = 0 holds to
round-off between the pressure of row n and the gap of row n + 1 (the forward-increment
Lagrange multipliers of Carpenter, Taylor & Katona, IJNME 32, 1991). Row 0 is the static state.

:mod:`~upliftlab.continuum.dynamics.explicit_step` sets the stable step, the lumped mass and
dashpots and
checks a run's settings; its names are importable from here.

**Horizontal tie** (:mod:`~upliftlab.continuum.dynamics.ground`): its stiffness is taken at
n+1 (in the footing's and story's matrix A) and its anchor's displacement u_ff at t_{n+1}, so
that a footing with no horizontal mass of its own (the whole weight in the story) stays
determined: its u row is then a spring balancing the story's force. Its dashpot acts at the
mid-step velocity like the story's, against the anchor's velocity v_ff at t_n. The energy
account books the tie's force with the other footing loads at n, which is off by O(dt) in the
tie's share: the balance error of the clay scene's pulse (4 across, compliant base, shear
sides) is 6.1e-3 of the input with the tie at the default step and 3.1e-3 at half of it
(bonded, without a tie: 1.6e-4 and 3.7e-5), within ``continuum.energy_tolerance``.

**Energy.** Kinetic energy ½ v̄ᵀ M v̄ at whole steps (v̄_n the mean of the half-step velocities);
the work of the soil's internal force less its weight, the story spring and the footing weight
(``strain``), of the dashpots and the soil's Rayleigh damping (``damping``,
:mod:`~upliftlab.continuum.dynamics.rayleigh`), of the ground loads (``input``) and of the contact
forces (``contact``, the energy they take out) by the trapezoidal rule over each step, as in
the implicit route. For a stable central-difference run the balance closes to O(dt²).

**Recording.** Every ``record_every`` steps (default: the implicit route's step for the same
mesh, so both give histories on comparable grids and of comparable size); soil fields at
``snapshots`` evenly spaced recorded rows.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math

import numba
import numpy as np

from ...checks import InputError
from ...log import announce_compilation, logger
from ...workers import single_threaded
from . import explicit_step
from ..contact.step import footing_schur, frictionless_step, tangential_step
from .result import DynamicResult, Recorder
from .explicit_loop import run_steps
from .explicit_step import (COURANT_ESTIMATE, STABILITY_FRACTION, ExplicitSettings, critical_step,
                            explicit_settings, explicit_setup, lumped_mass,
                            recorded_steps)
from ..contact.footing import OPEN, STICK
from .ground import free_field_motion, ground_velocity
from .iteration_matrix import soil_residual
from .kernels import layout, soil_predict, viscous_force
from .rayleigh import describe, metadata as damping_metadata, viscous_tangent
from ..statics.newton import ConvergenceError
from .run_control import MECHANISM_GROWTH, BearingFailure, keeping_what_ran, settled_to_failure
from .soil_force import SoilForce
from .superstructure import (MIN_ROTARY_INERTIA, central_difference_form, check_footing_mass,
                             structure_matrices, structure_work)

__all__ = ["STABILITY_FRACTION", "ExplicitSettings", "lumped_mass",
           "critical_step", "check_footing_mass", "MIN_ROTARY_INERTIA", "explicit_settings",
           "ExplicitRoute", "COURANT_ESTIMATE", "recorded_steps"]

#: Run frictionless contact with a compiled material in the compiled loop
#: (:mod:`~upliftlab.continuum.dynamics.explicit_loop`; False: the Python loop, for comparison).
COMPILED_LOOP = True


class _Row:
    """What :class:`~upliftlab.continuum.dynamics.result.Recorder` reads of a state (duck type);
    the material and the stress are formed only for a snapshot."""

    iterations = 0

    def __init__(self, u, q, force, status, reaction, soil):
        self.u, self.q, self.force, self.status, self.reaction = u, q, force, status, reaction
        self._soil = soil

    @property
    def N(self) -> float:
        return float(-self.reaction[1])

    @property
    def M(self) -> float:
        return float(self.reaction[2])

    @property
    def material(self):
        return self._soil.material

    @property
    def peak_plastic_strain(self) -> float:
        return self._soil.peak_plastic_strain

    @property
    def equivalent_plastic_strain(self):
        return self._soil.equivalent_plastic_strain

    @property
    def stress(self):
        return self._soil.stress_tensor


class _Structure:
    def __init__(self, z, v):
        self.d, self.v = z, v


class ExplicitRoute:
    """The explicit route of a run (module docstring), planned before any work: its settings,
    the soil's lumped mass and the dashpots (:func:`~.explicit_step.explicit_setup`), all
    checked here; :meth:`run` integrates from the gravity state that
    :func:`~upliftlab.continuum.dynamics.run.run_dynamic` makes for either route."""

    def __init__(self, model, scene, motion, options, ground):
        base, sides = ground.base, ground.sides
        if options.soil_mass_scale != 1.0 and (base != "rigid" or sides == "lysmer"):
            raise InputError(f"DynamicOptions.soil_mass_scale = {options.soil_mass_scale:g}: "
                             f"a scaled soil mass with base {base!r} and sides {sides!r} would "
                             "keep the dashpots of the unscaled soil; valid there: 1 (a scaled "
                             "mass needs a rigid base and sides without dashpots)")
        self.model, self.scene, self.motion, self.options = model, scene, motion, options
        self.ground = ground
        self.settings, self.mass, self.dashpots = explicit_setup(model, scene, motion, options,
                                                                 ground)
        if self.settings.damping is not None:  # its cost, before any work
            logger("continuum").info("upliftlab: " + describe(self.settings.damping,
                                                              self.settings.reduction))

    def run(self, static, progress=None) -> DynamicResult:
        """The time histories from the gravity state ``static`` (``progress`` as
        :func:`~upliftlab.continuum.dynamics.run.run_dynamic` takes it)."""
        threads = numba.get_num_threads()
        numba.set_num_threads(min(self.options.threads, numba.config.NUMBA_NUM_THREADS))
        try:
            run = _Explicit(self.model, self.scene, self.motion, self.options, self.settings,
                            static, self.mass, self.dashpots, self.ground)
            with single_threaded():  # the loop's small BLAS calls (upliftlab.workers)
                return run.loop(progress)
        finally:
            numba.set_num_threads(threads)


class _Explicit:
    """The time loop's constant pieces (module docstring)."""

    def __init__(self, model, scene, motion, options, settings, static, mass, dashpots,
                 ground):
        self.model, self.scene, self.motion = model, scene, motion
        self.options, self.settings, self.static = options, settings, static
        n = model.disc.ndofs
        self.keep = np.ones(n)
        self.keep[ground.fixed] = 0.0
        self.mass = np.where(self.keep > 0.0, mass, 1.0)
        self.c = dashpots * self.keep
        R0 = soil_residual(model, static.stress)
        release = np.zeros(n)
        release[ground.released] = R0[ground.released]
        self.datum = model.body_force + release  # R = f_int − datum
        if ground.waves.incident is None:  # a rigid base: the relative formulation
            r = np.zeros(n)
            r[ground.x] = 1.0
            self.ground_soil = -(mass * r) * self.keep
            self.incident = np.zeros(n)
        else:
            self.ground_soil = np.zeros(n)
            self.incident = ground.waves.incident * self.keep
        self.z = structure_matrices(scene)
        ground_z = -(self.z.M @ self.z.r) if settings.base == "rigid" else np.zeros(4)
        self.vg = ground_velocity(motion, settings.dt, settings.steps + 1)
        ag = np.asarray(motion.acceleration_at(np.arange(settings.steps + 1) * settings.dt),
                        dtype=float) * scene.g
        #: the footing's and story's ground loads at every step (rows)
        self.ground_all = np.outer(ag, ground_z)
        #: the part of the footing's and story's stiffness taken at n+1 (the tie)
        self.K_next = np.zeros((4, 4))
        tie = model.options.horizontal_tie
        if tie is not None and settings.base == "compliant":  # ground.py's horizontal tie
            c_tie = model.options.horizontal_tie_damping or 0.0
            self.K_next[0, 0] = tie
            self.z = dataclasses.replace(self.z, K=self.z.K + self.K_next,
                                         C=self.z.C + np.diag([c_tie, 0.0, 0.0, 0.0]))
            u_ff, v_ff = free_field_motion(model, self.vg[:settings.steps + 2] * scene.g,
                                                  settings.dt)
            self.ground_all[:, 0] += tie * u_ff[1:] + c_tie * v_ff[:-1]
        f = model.footing
        self.contact = f.contact_dofs
        self.L = f.kinematics
        self.free_q = np.array([not settings.prescribe_u, True, True])
        self.soil = SoilForce(model, static)
        #: the Rayleigh β K₀ v through a Maxwell arm of tangent β D₀ (None without it), the
        #: arm's stress at each point and decay per step (:mod:`~.rayleigh`), its force and
        #: the element scratch of :func:`~.kernels.viscous_force`
        self.viscous_D, self.viscous = None, np.zeros(n)
        self.arm, self.arm_decay = np.zeros((0, 0, 3)), 0.0
        if settings.damping is not None and settings.damping.beta > 0.0:
            self.viscous_D = viscous_tangent(model, settings.damping)
            self.viscous_layout = self.soil.layout if self.soil.compiled else \
                layout(model.disc)
            nel, nqp, _ = self.viscous_layout.shape
            self.arm = np.zeros((nel, nqp, 3))
            self.arm_decay = settings.damping.arm_decay(settings.dt)
            self.viscous_work = np.zeros(self.viscous_layout.shape[::2] + (2,))
        #: the compiled loop serves every interface with a compiled material
        self.compiled = COMPILED_LOOP and self.soil.compiled

    def structure_affine(self, zn, vz, Fz, first: bool):
        """(A, b): A z_{n+1} + b + [Lᵀ f_c; 0] = 0 for the footing and story
        (:func:`~upliftlab.continuum.dynamics.superstructure.central_difference_form`)."""
        return central_difference_form(self.z, self.settings.dt, zn, vz, Fz, first,
                                       self.K_next)

    def loop(self, progress) -> DynamicResult:
        st = self.settings
        rec = Recorder(self.model, recorded_steps(st).size - 1, self.options.snapshots)
        with keeping_what_ran(rec, self.model, self.motion, self.metadata):
            if self.compiled:
                self.compiled_steps(rec, progress)
            else:
                self.steps(rec, progress)
        return rec.result(self.model, self.motion, self.metadata())

    def steps(self, rec, progress) -> None:
        """Steps 0…n (the last only to complete row n), recorded into ``rec``."""
        st, z, f = self.settings, self.z, self.model.footing
        dt, n_steps, every = st.dt, st.steps, st.record_every
        times = np.arange(n_steps + 1) * dt
        ag_all = np.asarray(self.motion.acceleration_at(times), dtype=float) * self.scene.g
        vinc_all = 0.5 * self.vg[:n_steps + 1] * self.scene.g
        u = self.static.u.copy()
        u_prev, u_next = u.copy(), np.empty_like(u)
        v, v_next = np.zeros_like(u), np.empty_like(u)
        R_prev, F_prev = np.zeros_like(u), np.zeros_like(u)
        m_first, m_step = self.mass, self.mass + 0.5 * dt * self.c
        zn = np.append(self.static.q, 0.0)
        vz = np.zeros(4)
        vz[3] = self.motion.initial_velocity
        force = self.static.force.copy()
        status = self.static.status.copy()
        closed = status != OPEN
        energy = np.zeros(5)
        z_prev, Fz_prev, iterations = zn, None, 0
        free = np.flatnonzero(self.free_q)
        Lf = np.ascontiguousarray(self.L[:f.nodes][:, self.free_q])
        uy = np.asarray(f.uy, dtype=np.int64)
        for k in range(n_steps + 1):
            first = k == 0
            with self.diverging(k, k, u, u_prev, zn[:3]):
                fint = self.soil(u)
            ag = ag_all[k]
            Fz = self.ground_all[k] + z.gravity
            if self.viscous_D is not None:
                viscous_force(self.viscous_layout, v, self.viscous_D, self.arm,
                              self.arm_decay, self.viscous_work, self.viscous)
            increments = soil_predict(u, u_prev, v, fint, self.viscous, self.datum, self.keep,
                                      self.ground_soil, self.incident, ag, vinc_all[k],
                                      self.mass, self.c, dt, first, R_prev, F_prev, u_next,
                                      v_next)
            A, b = self.structure_affine(zn, vz, Fz, first)
            h = dt * (0.5 * dt if first else dt)
            m_eff = m_first if first else m_step
            force_prev = force
            if not f.interface.tangential:
                P, q, s, its = frictionless_step(A, b, free, Lf, uy, u, u_next, v_next,
                                                 m_eff, h, dt, closed)
                force = -P
                z_new = np.array([q[0], q[1], q[2], s])
            else:
                force, q, status, its = self.contact_step(A, b, zn, u_next, m_eff, h,
                                                          status, u)
                c = self.contact
                u_next[c] += h * force / m_eff[c]
                v_next[c] = (u_next[c] - u[c]) / dt
                z_new = np.append(q, -(A[3, :3] @ q + b[3]) / A[3, 3])
                closed = status != OPEN
            vz_new = (z_new - zn) / dt
            if not first:
                strain, work, dissipated = increments
                energy[1:4] += (strain, dissipated, work)
                energy[1:] += self.structure_increment(z_prev, zn, Fz_prev, Fz, vz)
                energy[4] += self.contact_work(force_prev, force, u_prev, u, z_prev, zn)
            iterations += its
            if k % every == 0 or k == n_steps:
                vbar = v if first else 0.5 * (v + v_next)
                zbar = vz if first else 0.5 * (vz + vz_new)
                energy[0] = 0.5 * float(np.dot(self.mass * vbar, vbar)) + 0.5 * float(
                    zbar @ z.M @ zbar)
                recorded = np.where(closed, STICK, OPEN).astype(np.int8) \
                    if not f.interface.tangential else status.copy()
                state = self.static if first else _Row(
                    u, zn[:3], force, recorded, self.L.T @ force, self.soil)
                rec.record(rec.rows, k * dt, state, _Structure(zn, zbar), ag, energy,
                           iterations, False, kinetic=energy[0])
                if progress is not None:
                    progress(k, n_steps, state)
                iterations = 0
            if k == n_steps:
                break
            z_prev, Fz_prev = zn, Fz
            u_prev, u, u_next = u, u_next, u_prev
            v, v_next = v_next, v
            zn, vz = z_new, vz_new

    def compiled_steps(self, rec, progress) -> None:
        """The steps of :meth:`steps` in the compiled loop
        (:func:`~upliftlab.continuum.dynamics.explicit_loop.run_steps`), called once per
        recorded row."""
        st, z, f, soil = self.settings, self.z, self.model.footing, self.soil
        dt, n_steps = st.dt, st.steps
        times = np.arange(n_steps + 1) * dt
        ag_all = np.asarray(self.motion.acceleration_at(times), dtype=float) * self.scene.g
        vinc_all = 0.5 * self.vg[:n_steps + 1] * self.scene.g
        n, nc = self.model.disc.ndofs, f.nodes
        U = np.empty((3, n))
        U[:] = self.static.u
        V = np.zeros((2, n))
        R_prev, F_prev, fint = np.zeros(n), np.zeros(n), np.zeros(n)
        Z = np.empty((3, 4))
        Z[:] = np.append(self.static.q, 0.0)
        VZ = np.zeros((2, 4))
        VZ[0, 3] = self.motion.initial_velocity
        FC = np.zeros((2, self.contact.size))
        FC[0] = self.static.force
        ST = np.zeros((2, nc), dtype=np.int8)
        ST[0] = self.static.status
        energy, counters = np.zeros(5), np.zeros(1, dtype=np.int64)
        lay, m_step = soil.layout, self.mass + 0.5 * dt * self.c
        free = np.flatnonzero(self.free_q)
        Lf = np.ascontiguousarray(self.L[:nc][:, self.free_q])
        loop = run_steps(numba.get_num_threads() > 1)
        done, Fz_prev = -1, np.zeros(4)
        rings, carry = (U, V, Z, VZ, FC, ST), (R_prev, F_prev, Fz_prev, energy, counters)
        soil_data = (lay.nodes, lay.dNdx, lay.dNdy, lay.dx, soil.eigenstrain, soil.plastic,
                     soil.ebar, soil.constants, soil.gain, soil.stress, soil.work, fint,
                     lay.ptr, lay.entries)
        damped = self.viscous_D is not None
        D, work_v = (self.viscous_D, self.viscous_work) if damped else \
            (np.zeros((3, 3)), np.zeros((0, 0, 2)))
        loads = (self.datum, self.keep, self.ground_soil, self.incident, ag_all, vinc_all,
                 self.mass, self.c, m_step, damped, D, self.arm, self.arm_decay, work_v,
                 self.viscous)
        structure = (z.M, z.C, z.K, self.K_next, z.gravity, self.ground_all)
        contact = (free, Lf, f.uy.astype(np.int64), f.ux.astype(np.int64), f.x,
                   f.interface.mu, f.width, f.interface.tangential)
        announce_compilation("the continuum's explicit kernels", loop, "about 20–60 s")
        for k in recorded_steps(st):
            with self.diverging(done + 1, k, U[k % 3], U[(k - 1) % 3], Z[k % 3][:3]):
                loop(done + 1, k, dt, rings, carry, soil_data, loads, structure, contact)
            done = k
            self.record(rec, progress, k, U, V, Z, VZ, FC, ST, energy, counters, ag_all[k])

    @contextlib.contextmanager
    def diverging(self, k0, k1, u, u_prev, footing):
        """Turn a diverged solution in steps k0…k1 (a failed contact solve, or ``u``, the
        displacement after them, not finite or beyond a footing width) into a
        :class:`ConvergenceError` naming the time, and for a displacement beyond a footing
        width where it is, how fast it grew over the last step (``u_prev`` the step before)
        and where the footing (u, v, θ) was: a blow-up of the scheme grows by a fixed factor
        above 1 every step (about 1.5 just beyond the stability limit), a footing punching
        into a failing soil by almost nothing, and both leave the small-strain continuum.
        The second, with the footing settled by :data:`~.run_control.FAILURE_SETTLEMENT` B or
        more, is a :class:`~.run_control.BearingFailure`."""
        st = self.settings
        why = None
        try:
            yield
        except (np.linalg.LinAlgError, RuntimeError, FloatingPointError, ZeroDivisionError) as exc:
            why = f"{type(exc).__name__}: {exc}"
        top = math.nan if why is not None else float(np.max(np.abs(u)))  # NaN if any entry is
        if top <= self.model.width:
            return
        when = f"explicit steps {k0}…{k1} (t = {k0 * st.dt:.6g}…{k1 * st.dt:.6g} s)"
        limit = (f"dt = {st.dt:.4g} s is {st.dt / st.critical:.3g} of the stability limit "
                 f"2/ω_max = {st.critical:.4g} s")
        if why is None:
            top = top if math.isfinite(top) else math.inf
            why = f"a displacement of {top:.3g} (the footing is {self.model.width:g} wide)"
            if math.isfinite(top):
                where, growth = self._where(u, u_prev, footing)
                settlement = -float(footing[1])
                if growth <= MECHANISM_GROWTH and settled_to_failure(settlement,
                                                                     self.model.width):
                    raise BearingFailure.of(
                        f"in {when}", settlement, self.model.width, float(footing[2]),
                        f"{why}{where}; a mechanism, not a blow-up of the scheme ({limit})",
                        step=k1, time=k1 * st.dt) from None
                why += where
        raise ConvergenceError(f"{when} diverged: {why}; {limit}", step=k1) from None

    def _where(self, u, u_prev, footing) -> tuple[str, float]:
        """Where the largest displacement of ``u`` is, its growth over the step from
        ``u_prev``, and the footing's (u, v, θ): the words that tell a blow-up from a bearing
        failure; and the growth."""
        j = int(np.argmax(np.abs(u)))
        x, y = self.model.disc.basis.doflocs[:, j]
        before = float(np.max(np.abs(u_prev)))
        growth = float(np.max(np.abs(u))) / before if before > 0.0 else math.inf
        return (f" at x = {x:.3g}, y = {y:.3g}, grown ×{growth:.6g} over the last step, with "
                f"the footing at v = {footing[1]:.3g}, θ = {footing[2]:.3g} rad: beyond the "
                f"small-strain continuum's range"), growth

    def record(self, rec, progress, k, U, V, Z, VZ, FC, ST, energy, counters, ag) -> None:
        """Row of step k from the rings of :meth:`compiled_steps`."""
        st, z = self.settings, self.z
        u, zk = U[k % 3], Z[k % 3].copy()
        vbar = V[0] if k == 0 else 0.5 * (V[k % 2] + V[(k + 1) % 2])
        zbar = VZ[0] if k == 0 else 0.5 * (VZ[k % 2] + VZ[(k + 1) % 2])
        energy[0] = 0.5 * float(np.dot(self.mass * vbar, vbar)) + 0.5 * float(zbar @ z.M @ zbar)
        if k == 0:
            state = self.static
        else:  # the contact forces of step k, in the equation of motion at t_k
            force = FC[(k + 1) % 2].copy()
            status = ST[(k + 1) % 2].copy()
            state = _Row(u, zk[:3], force, status, self.L.T @ force, self.soil)
        rec.record(rec.rows, k * st.dt, state, _Structure(zk, zbar), ag, energy,
                   int(counters[0]), False, kinetic=energy[0])
        counters[0] = 0
        if progress is not None:
            progress(k, st.steps, state)

    def structure_increment(self, z0, z1, F0, F1, vz):
        """(strain, damping, input, 0) of the footing and story over one step: story spring
        and footing weight; story dashpot at the mid-step velocity; ground loads."""
        strain, damping, inputs = structure_work(self.z, z0, z1, F0, F1, vz, 1.0)
        return np.array([strain, damping, inputs, 0.0])

    def contact_work(self, f0, f1, u0, u1, z0, z1) -> float:
        """The energy the contact forces (``f0``, ``f1`` on the soil at both ends of a step)
        take out of the soil and the footing over it (trapezoidal rule)."""
        mean = 0.5 * (f0 + f1)
        c = self.contact
        return -(float(mean @ (u1[c] - u0[c])) - float((self.L.T @ mean) @ (z1[:3] - z0[:3])))

    def contact_step(self, A, b, zn, u_star, m_eff, h, status, u):
        """Bonded or Coulomb: (force on the soil at the contact DOFs, footing q at n+1,
        status, iterations)."""
        f = self.model.footing
        Kq, o = footing_schur(A, b, self.free_q)
        K3, o3 = np.zeros((3, 3)), np.zeros(3)
        K3[np.ix_(self.free_q, self.free_q)] = Kq
        o3[self.free_q] = o
        q = zn[:3].copy()
        prescribed = ~self.free_q
        status = status.copy()
        duc, dq, force, its = tangential_step(
            m_eff[self.contact] / h, u_star[self.contact], q, f.slip(u, q), f.x, prescribed,
            np.where(prescribed, q, 0.0), K3, K3 @ q + o3, f.interface.mu, f.width, status)
        return force, q + dq, status, its

    def metadata(self) -> dict:
        """The run's settings for the result's metadata."""
        st = self.settings
        return {"method": "explicit", "scheme": "central_difference", "dt": st.dt,
                "steps": st.steps, "record_every": st.record_every, "base": st.base,
                "sides": st.sides, "wave": self.options.wave, "mass": "lumped",
                "dt_limit": st.limit, "dt_critical": st.critical,
                "stability_fraction": explicit_step.STABILITY_FRACTION, "omega_max": st.omega_max,
                "compiled": self.soil.compiled, "threads": numba.get_num_threads(),
                **damping_metadata(st.damping, st.reduction)}

