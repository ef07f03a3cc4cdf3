"""Stored states: the output row of a step, and the state written into the output arrays
(directly, or interpolated inside an accepted step of the event stepper).
"""

from __future__ import annotations

from numba import njit

from .codes import E_IMPACT, E_INPUT, E_PLASTIC, E_VISCOUS, HOT, N_ACC
from .base import base_energy, record_base
from .energy import kinetic_gravity
from .interpolants import hermite, quintic, quintic_at
from .laws import spring_state
from .motion import deformations


@njit(cache=True, **HOT)
def record(k, t, q, qd, acc, books, system, outputs):
    """Store the state at output index k (the records :data:`~.codes.BOOKS`,
    :data:`~.codes.SYSTEM` and :data:`~.codes.OUTPUTS`)."""
    modes, H, e_ref, e, ed = books
    minv, P, KG, _, _, _, weight, frame, story, base = system
    out_t, out_q, out_qd, out_e, out_f, out_mode, out_ep, out_energy, out_base = outputs
    n = q.size
    deformations(q, qd, P, e, ed)
    out_t[k] = t
    for i in range(n):
        out_q[k, i] = q[i]
        out_qd[k, i] = qd[i]
    strain = 0.0
    for j in range(e.size):
        ep, f, w = spring_state(j, P[j], modes[j], H[j], e[j])
        out_e[k, j] = e[j]
        out_mode[k, j] = modes[j]
        out_ep[k, j] = ep
        out_f[k, j] = f
        strain += w
    strain += base_energy(base)
    record_base(k, base, out_base)
    kinetic, gravity = kinetic_gravity(q, qd, minv, KG, weight, frame, story)
    out_energy[k, 0] = acc[E_INPUT]
    out_energy[k, 1] = kinetic
    out_energy[k, 2] = strain - e_ref
    out_energy[k, 3] = gravity
    out_energy[k, 4] = acc[E_VISCOUS]
    out_energy[k, 5] = acc[E_IMPACT]
    out_energy[k, 6] = acc[E_PLASTIC]


@njit(cache=True, inline="always")
def output_row(step, stride):
    """Output row of the state after step ``step``: every ``stride`` steps, and the last state
    in the row after them when ``stride`` does not divide the run."""
    return (step + 1) // stride + (0 if (step + 1) % stride == 0 else 1)


@njit(cache=True, inline="always")
def stop_row(step, stride):
    """Output row for a state that ends the run inside macro step ``step``: the next row."""
    return step // stride + 1


@njit(cache=True, **HOT)
def record_between(row, t_out, t, h, start, end, p0, p1, scratch, books, system, outputs):
    """Store the state at time t_out inside the accepted step [t, t + h], in which every spring
    kept its mode: q and q̇ on the step's quintic interpolant (``start`` and ``end`` hold q, q̇,
    q̈ and the energy accumulators at both ends), the energy accumulators on the cubic through
    their values and rates (the powers p0, p1). ``scratch`` is (q, q̇, acc) to fill."""
    q, qd, a0, acc = start
    q1, qd1, a1, acc1 = end
    qs, qds, acc_s = scratch
    s = (t_out - t) / h
    for i in range(q.size):
        m = quintic(h, q[i], qd[i], a0[i], q1[i], qd1[i], a1[i])
        qs[i], qds[i] = quintic_at(m, s, h)
    for c in range(N_ACC):
        acc_s[c] = hermite(s, h, acc[c], p0[c], acc1[c], p1[c])[0]
    record(row, t_out, qs, qds, acc_s, books, system, outputs)
