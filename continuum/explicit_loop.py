"""The compiled time loop of the explicit route, for frictionless contact and a compiled
material: the steps between two recorded rows in one call, with no Python in between.

:func:`run_steps` performs exactly the steps of :meth:`upliftlab.continuum.explicit._Explicit`'s
Python loop (which serves bonded and Coulomb interfaces and the materials without a compiled
return map; a test runs both on one scene and compares them): the internal force
(:mod:`~upliftlab.continuum.kernels`), the diagonal soil update
(:func:`~upliftlab.continuum.kernels.soil_predict`), the footing and story form, the contact
forces (:func:`~upliftlab.continuum.contact_step.frictionless_step`) and the energy increments.

The state lives in rings indexed by the step k, so that nothing is copied from step to step:
``U[k % 3]`` is u_k (``U[(k ± 1) % 3]`` its neighbours), ``V[k % 2]`` is v_{k−½} and
``V[(k + 1) % 2]`` v_{k+½}; the same for the footing and story z (``Z``, ``VZ``); ``FC[k % 2]``
holds the contact forces of step k − 1 and ``CL[k % 2]`` its closed set, which the recorded row
k pairs with the gaps of u_k. ``R_prev``, ``F_prev`` and ``Fz_prev`` carry the last step's
internal and external forces; ``energy`` (kinetic, strain, damping, input, contact) and
``counters`` (active-set iterations) accumulate in place.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .contact_step import frictionless_step
from .kernels import _elements, _elements_parallel, _gather, _gather_serial, soil_predict

__all__ = ["run_steps"]


@nb.njit(cache=True)
def _structure_form(M, C, K, z, vz, Fz, dt, first):
    """(A, b) of the footing and story (A z_{n+1} + b + [Lᵀ f_c; 0] = 0)."""
    if first:
        h = 0.5 * dt * dt
        A = M / h
        b = -(A @ z) - (M @ vz) / (0.5 * dt) - Fz + K @ z + C @ vz
    else:
        h = dt * dt
        A = (M + 0.5 * dt * C) / h
        b = -(A @ z) - ((M - 0.5 * dt * C) @ vz) / dt - Fz + K @ z
    return A, b


@nb.njit(cache=True)
def run_steps(k0, k1, dt, U, V, R_prev, F_prev, Z, VZ, Fz_prev, FC, CL, energy, counters,
              nodes, dNdx, dNdy, dx, eig, plastic, ebar, kind, lam, G, strength, H, stress, work,
              fint, ptr, entries, parallel, datum, keep, ground, incident, ag_all, vinc_all,
              mass, damping, m_step, Mz, Cz, Kz, gravity_z, ground_z, free, Lf, uy, x):
    """Steps k0…k1 (module docstring); returns nothing, the rings hold the state."""
    nc = uy.size
    for k in range(k0, k1 + 1):
        first = k == 0
        u, u_prev, u_next = U[k % 3], U[(k + 2) % 3], U[(k + 1) % 3]
        v, v_next = V[k % 2], V[(k + 1) % 2]
        z, z_prev = Z[k % 3], Z[(k + 2) % 3]
        vz = VZ[k % 2]
        u2 = u.reshape(-1, 2)
        if parallel:
            _elements_parallel(u2, nodes, dNdx, dNdy, dx, eig, plastic, ebar, kind, lam, G,
                               strength, H, stress, work)
            _gather(work, ptr, entries, fint)
        else:
            _elements(0, nodes.shape[0], u2, nodes, dNdx, dNdy, dx, eig, plastic, ebar, kind,
                      lam, G, strength, H, stress, work)
            _gather_serial(work, nodes, fint.reshape(-1, 2))
        ag = ag_all[k]
        strain, work_in, dissipated = soil_predict(
            u, u_prev, v, fint, datum, keep, ground, incident, ag, vinc_all[k], mass, damping,
            dt, first, R_prev, F_prev, u_next, v_next)
        Fz = ground_z * ag + gravity_z
        A, b = _structure_form(Mz, Cz, Kz, z, vz, Fz, dt, first)
        h = dt * (0.5 * dt if first else dt)
        closed = CL[(k + 1) % 2]
        closed[:] = CL[k % 2]
        P, q, s, its = frictionless_step(A, b, free, Lf, uy, u, u_next, v_next,
                                         mass if first else m_step, h, dt, closed)
        z_next = Z[(k + 1) % 3]
        z_next[0], z_next[1], z_next[2], z_next[3] = q[0], q[1], q[2], s
        vz_next = VZ[(k + 1) % 2]
        for i in range(4):
            vz_next[i] = (z_next[i] - z[i]) / dt
        force, force_prev = FC[(k + 1) % 2], FC[k % 2]
        for i in range(nc):
            force[i] = -P[i]
        counters[0] += its
        if not first:
            dz = z - z_prev
            zs = z + z_prev
            energy[1] += strain + 0.5 * ((Kz @ zs) @ dz) - gravity_z @ dz
            energy[2] += dissipated + (Cz @ vz) @ dz
            energy[3] += work_in + 0.5 * ((Fz_prev + Fz - 2.0 * gravity_z) @ dz)
            on_soil = 0.0
            vertical = moment = 0.0
            for i in range(nc):
                mean = 0.5 * (force_prev[i] + force[i])
                on_soil += mean * (u[uy[i]] - u_prev[uy[i]])
                vertical += mean
                moment -= x[i] * mean
            energy[4] -= on_soil - (vertical * dz[1] + moment * dz[2])
        Fz_prev[:] = Fz
