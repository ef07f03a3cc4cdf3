"""The fixed-step explicit integrators: classical RK4 (``rk4``) and Adams–Bashforth–Moulton
PECE (``abm4``, started by RK4), both with trial spring laws and an end-of-step return map, and
what they share after a step (outputs, contact length, toppling, the energy check).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .base import accept_base, track_base
from .codes import (BASE_FAILED, E_PLASTIC, F_ECHECK, HOT, NONFINITE, N_ACC, OK,
                    OVERTURNED)
from .energy import check_energy, start_energy, static_strain_energy
from .interpolants import finite
from .laws import commit_all, initial_modes
from .motion import accelerations, deformations, geometric_or_nothing
from .outputs import output_row, record, stop_row
from .peaks import after_fixed_step, start_side, track_peaks
from .stages import copy, rk4_step


@njit(cache=True, inline="always")
def fixed_start(q0, qd0, system, outputs, peaks, counters, H):
    """What both fixed-step integrators do before their first step: the workspace, the initial
    modes, the first stored state and the energy datum. Returns (system with K_G or an empty
    K_G, books, stages, (contact, e0, ė0), the state q, q̇, acc, and whether the structure is
    released past its toppling angle)."""
    minv, P, KG, L, ag, dtg, weight, frame, story, base = system
    scene = (minv, P, geometric_or_nothing(KG), L, ag, dtg, weight, frame, story, base)
    ns, n = P.size, q0.size
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    k1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    Mw = np.zeros((n, n))
    q, qd = q0.copy(), qd0.copy()
    acc, acc1 = np.zeros(N_ACC), np.zeros(N_ACC)
    modes = np.zeros(ns, dtype=np.int64)
    contact = np.ones(ns, dtype=np.int64)
    deformations(q, qd, P, e0, ed0)
    initial_modes(P, H, modes, e0, ed0)
    e_ref = static_strain_energy(P)
    start_side(q, qd, frame)
    books = (modes, H, e_ref, e1, ed1)
    record(0, 0.0, q, qd, acc, books, scene, outputs)
    counters[4] = 1
    start_energy(q, qd, acc, books, scene, peaks)
    deformations(q, qd, P, e0, ed0)
    track_base(base, peaks)
    toppled = after_fixed_step(0.0, q, P, H, e0, frame, story, peaks)
    stages = (k1, k2, k3, k4, qs, qds, q1, qd1, acc1, Mw)
    return scene, books, stages, (contact, e0, ed0), q, qd, acc, toppled


@njit(cache=True)
def integrate_rk4(q0, qd0, clock, system, outputs, peaks, counters, H):
    """Classical RK4 with trial spring laws and end-of-step return mapping (``clock``,
    ``system``, ``outputs``: the records :data:`~.codes.CLOCK`, :data:`~.codes.SYSTEM`,
    :data:`~.codes.OUTPUTS`)."""
    scene, books, stages, fixed, q, qd, acc, toppled = fixed_start(q0, qd0, system, outputs,
                                                                    peaks, counters, H)
    if toppled:
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    return march_rk4(q, qd, acc, clock, scene, books, fixed, stages, outputs, peaks, counters)


@njit(cache=True, **HOT)
def end_fixed_step(step, t, clock, q, qd, acc, books, e0, system, outputs, peaks, counters):
    """After a fixed step (committed): contact length, overturning, outputs and the energy
    check (``e0`` the springs' deformations at the step's end). Returns OVERTURNED if the run
    ends here, else OK."""
    _, nsteps, stride = clock
    _, P, _, _, _, _, _, frame, story, _ = system
    H = books[1]
    if after_fixed_step(t, q, P, H, e0, frame, story, peaks):
        row = stop_row(step, stride)
        record(row, t, q, qd, acc, books, system, outputs)
        counters[4] = row + 1
        check_energy(q, qd, acc, books, system, peaks)
        return OVERTURNED
    if (step + 1) % stride == 0 or step == nsteps - 1:
        row = output_row(step, stride)
        record(row, t, q, qd, acc, books, system, outputs)
        counters[4] = row + 1
    if (step + 1) % max(1, int(frame[F_ECHECK])) == 0:
        check_energy(q, qd, acc, books, system, peaks)
    return OK


@njit(cache=True, **HOT)
def accept_fixed_step(step, clock, state, trial, system, books, fixed, outputs, peaks, counters):
    """Make a fixed step's trial end ``trial`` = (q₁, q̇₁, energy₁) the state ``state``: refuse
    non-finite values, track the peaks over the step, apply the springs' end-of-step return map,
    store the row and test toppling (:func:`end_fixed_step`). Shared by RK4 and ABM4."""
    dt = clock[0]
    q, qd, acc = state
    q1, qd1, acc1 = trial
    _, P, _, _, _, _, _, frame, _, base = system
    modes, H, _, e1, ed1 = books
    contact, e0, ed0 = fixed
    if not finite(q1, qd1):
        counters[0] = step
        return NONFINITE
    deformations(q1, qd1, P, e1, ed1)
    track_peaks(dt, (q, qd, e0, ed0), (q1, qd1, e1, ed1), P, modes, H, frame, peaks)
    copy(q, q1)
    copy(qd, qd1)
    copy(acc, acc1)
    copy(e0, e1)
    copy(ed0, ed1)
    acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
    if accept_base(q, base, acc, peaks) != 0:
        counters[0] = step
        return BASE_FAILED
    if end_fixed_step(step, (step + 1) * dt, clock, q, qd, acc, books, e0, system, outputs,
                      peaks, counters) != OK:
        return OVERTURNED
    return OK


@njit(cache=True, **HOT)
def march_rk4(q, qd, acc, clock, system, books, fixed, stages, outputs, peaks, counters):
    """The time loop of :func:`integrate_rk4`, in the workspace it allocated."""
    dt, nsteps, _ = clock
    modes, H = books[0], books[1]
    q1, qd1, acc1 = stages[6], stages[7], stages[8]
    for step in range(nsteps):
        rk4_step(step * dt, dt, q, qd, acc, True, system, modes, H, stages)
        counters[2] += 4
        status = accept_fixed_step(step, clock, (q, qd, acc), (q1, qd1, acc1), system, books,
                                   fixed, outputs, peaks, counters)
        if status != OK:
            return status
    check_energy(q, qd, acc, books, system, peaks)
    return OK


@njit(cache=True)
def integrate_abm4(q0, qd0, clock, system, outputs, peaks, counters, H):
    """Adams–Bashforth–Moulton 4 (PECE) on y = (q, q̇, energy), started by three RK4 steps.

    Predictor AB4: y* = yₙ + h/24 (55fₙ − 59fₙ₋₁ + 37fₙ₋₂ − 9fₙ₋₃).
    Corrector AM4: yₙ₊₁ = yₙ + h/24 (9f* + 19fₙ − 5fₙ₋₁ + fₙ₋₂).
    """
    m = 2 * q0.size + N_ACC
    F = np.zeros((4, m))  # derivative history, F[0] newest
    ystar = np.zeros(m)
    fstar = np.zeros(m)
    scene, books, stages, fixed, q, qd, acc, toppled = fixed_start(q0, qd0, system, outputs,
                                                                    peaks, counters, H)
    if toppled:
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    return march_abm4(q, qd, acc, clock, scene, books, fixed, stages, (F, ystar, fstar), outputs,
                      peaks, counters)


@njit(cache=True, **HOT)
def march_abm4(q, qd, acc, clock, system, books, fixed, stages, history, outputs, peaks,
               counters):
    """The time loop of :func:`integrate_abm4`, in the workspace it allocated; ``history`` is
    (F, y*, f*): the derivative history (F[0] newest), the predictor and its derivative."""
    dt, nsteps, _ = clock
    modes, H = books[0], books[1]
    k1, k2, _, _, qs, qds, q1, qd1, acc1, Mw = stages
    F, ystar, fstar = history
    n, m = q.size, F.shape[1]
    for step in range(nsteps):
        t = step * dt
        pw = accelerations(t, q, qd, True, system, modes, H, Mw, k1)
        counters[2] += 1
        for r in range(3, 0, -1):
            for c in range(m):
                F[r, c] = F[r - 1, c]
        for i in range(n):
            F[0, i] = qd[i]
            F[0, n + i] = k1[i]
        for c in range(N_ACC):
            F[0, 2 * n + c] = pw[c]
        if step < 3:
            rk4_step(t, dt, q, qd, acc, True, system, modes, H, stages)
            counters[2] += 4
        else:
            for c in range(m):
                y = q[c] if c < n else (qd[c - n] if c < 2 * n else acc[c - 2 * n])
                ystar[c] = y + dt / 24.0 * (55 * F[0, c] - 59 * F[1, c] + 37 * F[2, c]
                                            - 9 * F[3, c])
            for i in range(n):
                qs[i] = ystar[i]
                qds[i] = ystar[n + i]
            pw = accelerations(t + dt, qs, qds, True, system, modes, H, Mw, k2)
            counters[2] += 1
            for i in range(n):
                fstar[i] = qds[i]
                fstar[n + i] = k2[i]
            for c in range(N_ACC):
                fstar[2 * n + c] = pw[c]
            for c in range(m):
                incr = dt / 24.0 * (9 * fstar[c] + 19 * F[0, c] - 5 * F[1, c] + F[2, c])
                if c < n:
                    q1[c] = q[c] + incr
                elif c < 2 * n:
                    qd1[c - n] = qd[c - n] + incr
                else:
                    acc1[c - 2 * n] = acc[c - 2 * n] + incr
        status = accept_fixed_step(step, clock, (q, qd, acc), (q1, qd1, acc1), system, books,
                                   fixed, outputs, peaks, counters)
        if status != OK:
            return status
    check_energy(q, qd, acc, books, system, peaks)
    return OK
