"""The compiled time loop of the explicit route, for a material with a compiled return map:
the steps between two recorded rows in one call, with no Python in between.

The loop :func:`run_steps` gives performs exactly the steps of
:meth:`upliftlab.continuum.dynamics.explicit._Explicit`'s Python loop (which serves the
materials without a compiled return map; a test runs both on one scene and compares them):
the internal force (:mod:`~upliftlab.continuum.dynamics.kernels`), the diagonal soil update
(:func:`~upliftlab.continuum.dynamics.kernels.soil_predict`), the footing and story form, the
contact forces (:func:`~upliftlab.continuum.contact.step.frictionless_step`, or
:func:`~upliftlab.continuum.contact.step.tangential_step` for a bonded or Coulomb interface) and
the energy increments.

The state lives in rings indexed by the step k, so that nothing is copied from step to step:
``U[k % 3]`` is u_k (``U[(k ± 1) % 3]`` its neighbours), ``V[k % 2]`` is v_{k−½} and
``V[(k + 1) % 2]`` v_{k+½}; the same for the footing and story z (``Z``, ``VZ``); ``FC[k % 2]``
holds the contact forces of step k − 1 (at u_y, then u_x for a tangential interface) and
``ST[k % 2]`` its node status, ``FC[(k + 1) % 2]`` and ``ST[(k + 1) % 2]`` those of step k,
which the recorded row k pairs with u_k and q_k (the forces in the equation of motion at t_k,
:mod:`~upliftlab.continuum.dynamics.explicit`). ``R_prev``,
``F_prev`` and ``Fz_prev`` carry the last step's internal and external forces; ``energy``
(kinetic, strain, damping, input, contact) and ``counters`` (active-set iterations) accumulate
in place.

**Cached on disk.** numba does not cache a function that takes other compiled functions as
arguments (it compiled such a loop again in every process, 10–20 s of CPU). The loop's body,
:func:`_steps`, takes the element and gather kernels as arguments but is inlined (numba IR)
into two loops that name them as globals, :func:`_serial` and :func:`_parallel`; these take
only arrays, numbers and the soil model's constants, and are cached like any other kernel.
numba specialises and caches each for every soil model, by the type of its constants (a named
tuple class, :mod:`~upliftlab.continuum.materials.compiled`). Since a cached loop holds the
kernels it calls from other modules (the element loops, the soil models' returns, the contact
steps), the cache folder is keyed on their sources (:data:`upliftlab.KERNEL_SOURCES`).
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ..contact.step import frictionless_step, tangential_step
from ..contact.footing import OPEN, STICK
from .kernels import compiled_pair, soil_predict, viscous_pair

__all__ = ["run_steps"]

#: The serial and the parallel kernels, as globals of the loops that call them (module
#: docstring: a loop that took them as arguments could not be cached).
_ELEMENTS_SERIAL, _GATHER_SERIAL = compiled_pair(False)
_ELEMENTS_PARALLEL, _GATHER_PARALLEL = compiled_pair(True)
_VISCOUS_SERIAL, _VISCOUS_PARALLEL = viscous_pair(False), viscous_pair(True)


@nb.njit(cache=True)
def _structure_form(M, C, K, K_next, z, vz, Fz, dt, first):
    """(A, b) of the footing and story (A z_{n+1} + b + [Lᵀ f_c; 0] = 0); ``K_next`` the part
    of K taken at n+1 (:func:`~upliftlab.continuum.dynamics.superstructure.
    central_difference_form`)."""
    if first:
        h = 0.5 * dt * dt
        A = M / h + K_next
        b = -(A @ z) - (M @ vz) / (0.5 * dt) - Fz + K @ z + C @ vz
    else:
        h = dt * dt
        A = (M + 0.5 * dt * C) / h + K_next
        b = -(A @ z) - ((M - 0.5 * dt * C) @ vz) / dt - Fz + K @ z
    return A, b


@nb.njit(cache=True)
def _tangential(A, b, prescribed, z, u, u_next, v_next, m_eff, h, dt, uy, ux, x, mu, width,
                status):
    """The bonded or Coulomb contact of one step, applied in place like
    :func:`~upliftlab.continuum.contact.step.frictionless_step`; returns (forces on the soil
    at u_y then u_x, q, s, iterations)."""
    a_ss = A[3, 3]
    K = A[:3, :3] - np.outer(A[:3, 3], A[3, :3]) / a_ss
    o = b[:3] - A[:3, 3] * b[3] / a_ss
    q = z[:3].copy()
    target = np.zeros(3)
    for i in range(3):
        if prescribed[i]:
            target[i] = q[i]
            o[i] = 0.0
            for j in range(3):
                K[i, j] = K[j, i] = 0.0
    rq = K @ q + o
    n = x.size
    s = np.empty(2 * n)
    uc = np.empty(2 * n)
    slip0 = np.empty(n)
    for i in range(n):
        s[i], s[n + i] = m_eff[uy[i]] / h, m_eff[ux[i]] / h
        uc[i], uc[n + i] = u_next[uy[i]], u_next[ux[i]]
        slip0[i] = u[ux[i]] - q[0]
    duc, dq, force, its = tangential_step(s, uc, q, slip0, x, prescribed, target, K, rq, mu,
                                          width, status)
    for i in range(n):
        for j, d in ((uy[i], duc[i]), (ux[i], duc[n + i])):
            u_next[j] += d
            v_next[j] = (u_next[j] - u[j]) / dt
    q = q + dq
    story = -(A[3, 0] * q[0] + A[3, 1] * q[1] + A[3, 2] * q[2] + b[3]) / a_ss
    return force, q, story, its


@nb.njit(inline="always")
def _steps(k0, k1, dt, rings, carry, soil, elements, gather, viscous_elements, loads, structure,
           contact):
    """Steps k0…k1 (module docstring); returns nothing, the rings hold the state. The arrays
    travel in tuples: ``rings`` (U, V, Z, VZ, FC, ST) and ``carry`` (R_prev, F_prev, Fz_prev,
    energy, counters), both updated in place; ``soil`` the compiled soil force's layout, state
    and workspace (:class:`~upliftlab.continuum.dynamics.soil_force.SoilForce`); ``loads``
    (datum, keep, ground, incident, ag_all, vinc_all, mass, damping, m_step, damped, and the
    Rayleigh β K₀ v's tangent β D₀ (3, 3), its Maxwell arm's stress (nel, nqp, 3) and decay a
    per step, element scratch and force: used if ``damped``,
    :mod:`~upliftlab.continuum.dynamics.rayleigh`); ``structure``
    (M, C, K, the part of K taken at n+1, gravity, the footing's and story's ground loads at
    every step, rows); ``contact`` (free, Lf, uy,
    ux, x, μ, width, tangential). ``elements``, ``gather`` and ``viscous_elements``: the serial
    or parallel kernels (:func:`~upliftlab.continuum.dynamics.kernels.compiled_pair`,
    :func:`~upliftlab.continuum.dynamics.kernels.viscous_pair`), named by the caller
    (:func:`_serial`, :func:`_parallel`) into which numba inlines this body."""
    U, V, Z, VZ, FC, ST = rings
    R_prev, F_prev, Fz_prev, energy, counters = carry
    (nodes, dNdx, dNdy, dx, eig, plastic, ebar, constants, gain, stress, work, fint, ptr,
     entries) = soil
    (datum, keep, ground, incident, ag_all, vinc_all, mass, damping, m_step, damped, Dv,
     arm, decay, work_v, viscous) = loads
    Mz, Cz, Kz, Kz_next, gravity_z, ground_all = structure
    free, Lf, uy, ux, x, mu, width, tangential = contact
    nc = uy.size
    prescribed = np.ones(3, dtype=np.bool_)
    for i in free:
        prescribed[i] = False
    for k in range(k0, k1 + 1):
        first = k == 0
        u, u_prev, u_next = U[k % 3], U[(k + 2) % 3], U[(k + 1) % 3]
        v, v_next = V[k % 2], V[(k + 1) % 2]
        z, z_prev = Z[k % 3], Z[(k + 2) % 3]
        vz = VZ[k % 2]
        elements(u.reshape(-1, 2), nodes, dNdx, dNdy, dx, eig, plastic, ebar, constants, gain,
                 stress, work)
        gather(work, nodes, ptr, entries, fint)
        ag = ag_all[k]
        if damped:  # the Rayleigh β K₀ v_{k−½} through its Maxwell arm, element by element
            viscous_elements(v.reshape(-1, 2), nodes, dNdx, dNdy, dx, Dv, arm, decay, work_v)
            gather(work_v, nodes, ptr, entries, viscous)
        strain, work_in, dissipated = soil_predict(
            u, u_prev, v, fint, viscous, datum, keep, ground, incident, ag, vinc_all[k], mass,
            damping, dt, first, R_prev, F_prev, u_next, v_next)
        Fz = ground_all[k] + gravity_z
        A, b = _structure_form(Mz, Cz, Kz, Kz_next, z, vz, Fz, dt, first)
        h = dt * (0.5 * dt if first else dt)
        m_eff = mass if first else m_step
        status = ST[(k + 1) % 2]
        status[:] = ST[k % 2]
        force, force_prev = FC[(k + 1) % 2], FC[k % 2]
        if tangential:
            f, q, s, its = _tangential(A, b, prescribed, z, u, u_next, v_next, m_eff, h, dt, uy,
                                       ux, x, mu, width, status)
            force[:] = f
        else:
            closed = status != OPEN
            P, q, s, its = frictionless_step(A, b, free, Lf, uy, u, u_next, v_next, m_eff, h,
                                             dt, closed)
            for i in range(nc):
                force[i] = -P[i]
                status[i] = STICK if closed[i] else OPEN
        z_next = Z[(k + 1) % 3]
        z_next[0], z_next[1], z_next[2], z_next[3] = q[0], q[1], q[2], s
        vz_next = VZ[(k + 1) % 2]
        for i in range(4):
            vz_next[i] = (z_next[i] - z[i]) / dt
        counters[0] += its
        if not first:
            dz = z - z_prev
            zs = z + z_prev
            energy[1] += strain + 0.5 * ((Kz @ zs) @ dz) - gravity_z @ dz
            energy[2] += dissipated + (Cz @ vz) @ dz
            energy[3] += work_in + 0.5 * ((Fz_prev + Fz - 2.0 * gravity_z) @ dz)
            on_soil = horizontal = vertical = moment = 0.0
            for i in range(nc):
                mean = 0.5 * (force_prev[i] + force[i])
                on_soil += mean * (u[uy[i]] - u_prev[uy[i]])
                vertical += mean
                moment -= x[i] * mean
                if tangential:
                    mean = 0.5 * (force_prev[nc + i] + force[nc + i])
                    on_soil += mean * (u[ux[i]] - u_prev[ux[i]])
                    horizontal += mean
            energy[4] -= on_soil - (horizontal * dz[0] + vertical * dz[1] + moment * dz[2])
        Fz_prev[:] = Fz


@nb.njit(cache=True)
def _serial(k0, k1, dt, rings, carry, soil, loads, structure, contact):
    """:func:`_steps` with the serial kernels."""
    _steps(k0, k1, dt, rings, carry, soil, _ELEMENTS_SERIAL, _GATHER_SERIAL, _VISCOUS_SERIAL,
           loads, structure, contact)


@nb.njit(cache=True)
def _parallel(k0, k1, dt, rings, carry, soil, loads, structure, contact):
    """:func:`_steps` with the parallel kernels."""
    _steps(k0, k1, dt, rings, carry, soil, _ELEMENTS_PARALLEL, _GATHER_PARALLEL,
           _VISCOUS_PARALLEL, loads, structure, contact)


def run_steps(parallel: bool):
    """The compiled loop of steps k0…k1, with the serial or the ``parallel`` kernels:
    ``run_steps(parallel)(k0, k1, dt, rings, carry, soil, loads, structure, contact)``
    (:func:`_steps` says what the tuples hold)."""
    return _parallel if parallel else _serial
