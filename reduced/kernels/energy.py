"""The energy balance of a run: kinetic, strain and gravity energy at a state, the balance
stored + dissipated − input (constant for an exact integration) and its largest residual. The
accumulators (input, viscous, impact, plastic) are integrated alongside the state
(``E_*`` of :mod:`.codes`).
"""

from __future__ import annotations

from numba import njit

from .codes import (E_IMPACT, E_INPUT, E_PLASTIC, E_VISCOUS, F_EXACT, F_IV, HOT, P_ERES, P_ESCALE,
                    P_ETOT0, STORY)
from .base import base_energy
from .laws import spring_state
from .motion import deformations
from .rocking import exact_energy


@njit(cache=True)
def kinetic_gravity(q, qd, minv, KG, weight, frame, story):
    """(kinetic, gravity) energy: ½ q̇ᵀ M q̇ and W V + ½ qᵀ K_G q, or exact kinematics'."""
    if frame[F_EXACT] > 0.0:
        return exact_energy(q, qd, frame, story, weight)
    kinetic = 0.0
    for i in range(q.size):
        kinetic += 0.5 * qd[i] * qd[i] / minv[i]
    iv = int(frame[F_IV])
    gravity = weight * q[iv] if iv >= 0 else 0.0
    for i in range(q.size):
        for m in range(KG.shape[1]):
            gravity += 0.5 * q[i] * KG[i, m] * q[m]
    return kinetic, gravity


@njit(cache=True, **HOT)
def energy_balance(q, qd, acc, books, system):
    """Stored + dissipated − input energy at a state: constant for an exact integration.
    ``books`` and ``system`` are the records :data:`~.codes.BOOKS` and
    :data:`~.codes.SYSTEM`."""
    modes, H, e_ref, e, ed = books
    minv, P, KG, _, _, _, weight, frame, story, base = system
    deformations(q, qd, P, e, ed)
    strain = 0.0
    for j in range(e.size):
        strain += spring_state(j, P[j], modes[j], H[j], e[j])[2]
    strain += base_energy(base)
    kinetic, gravity = kinetic_gravity(q, qd, minv, KG, weight, frame, story)
    return (kinetic + strain - e_ref + gravity + acc[E_VISCOUS] + acc[E_IMPACT] + acc[E_PLASTIC]
            - acc[E_INPUT])


@njit(cache=True, **HOT)
def check_energy(q, qd, acc, books, system, peaks):
    """Update the largest residual of the energy balance and its scale (the largest |input|)."""
    total = energy_balance(q, qd, acc, books, system)
    peaks[P_ERES] = max(peaks[P_ERES], abs(total - peaks[P_ETOT0]))
    peaks[P_ESCALE] = max(peaks[P_ESCALE], abs(acc[E_INPUT]))


@njit(cache=True, **HOT)
def start_energy(q, qd, acc, books, system, peaks):
    """The balance's datum at the start, and its scale: the initial stored energy."""
    total = energy_balance(q, qd, acc, books, system)
    peaks[P_ETOT0] = total
    peaks[P_ESCALE] = max(peaks[P_ESCALE], abs(total))


@njit(cache=True, **HOT)
def static_strain_energy(P):
    """Σ ½ k δ0² of the foundation springs at static equilibrium (the energy datum)."""
    total = 0.0
    for j in range(P.size):
        if P[j].kind != STORY:
            total += 0.5 * P[j].f0 * P[j].d0
    return total
