"""Runge–Kutta stages (classical RK4, Nyström form) and the step bookkeeping the explicit
integrators share: the trial laws' step (:func:`rk4_step`), the event stepper's step in frozen
modes (:func:`frozen_rk4_step`), its local error estimate (:func:`error_ratio`) and the copies
that make the end of a step the start of the next.
"""

from __future__ import annotations

from numba import njit

from .codes import HOT, N_ACC
from .motion import accelerations
from .tables import frozen_accelerations


@njit(cache=True, inline="always")
def rk4_stage_state(stage, h, q, qd, k1, k2, k3, qs, qds):
    """The state at which classical RK4 (Nyström form, q̈ = f(t, q, q̇)) evaluates its stage
    2, 3 or 4, from the stages before it."""
    for i in range(q.size):
        if stage == 2:
            qs[i] = q[i] + 0.5 * h * qd[i]
            qds[i] = qd[i] + 0.5 * h * k1[i]
        elif stage == 3:
            qs[i] = q[i] + 0.5 * h * qd[i] + 0.25 * h * h * k1[i]
            qds[i] = qd[i] + 0.5 * h * k2[i]
        else:
            qs[i] = q[i] + h * qd[i] + 0.5 * h * h * k2[i]
            qds[i] = qd[i] + h * k3[i]


@njit(cache=True, inline="always")
def rk4_combine(h, q, qd, acc, p1, p2, p3, p4, stages):
    """The end of an RK4 step (q₁, q̇₁ and acc₁ of ``stages``) from its four stages; the energy
    accumulators ``acc`` ride along as extra components, with the powers p1…p4 as their rates."""
    k1, k2, k3, k4, _, _, q1, qd1, acc1, _ = stages
    for i in range(q.size):
        q1[i] = q[i] + h * qd[i] + h * h / 6.0 * (k1[i] + k2[i] + k3[i])
        qd1[i] = qd[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    for c in range(N_ACC):
        acc1[c] = acc[c] + h / 6.0 * (p1[c] + 2.0 * p2[c] + 2.0 * p3[c] + p4[c])


@njit(cache=True, **HOT)
def rk4_step(t, h, q, qd, acc, natural, system, modes, H, stages):
    """One classical RK4 step of size h with the laws of :func:`accelerations`, in the
    workspace ``stages`` (:data:`~.codes.STAGES`), which receives the step's end."""
    k1, k2, k3, k4, qs, qds, _, _, _, Mw = stages
    p1 = accelerations(t, q, qd, natural, system, modes, H, Mw, k1)
    rk4_stage_state(2, h, q, qd, k1, k2, k3, qs, qds)
    p2 = accelerations(t + 0.5 * h, qs, qds, natural, system, modes, H, Mw, k2)
    rk4_stage_state(3, h, q, qd, k1, k2, k3, qs, qds)
    p3 = accelerations(t + 0.5 * h, qs, qds, natural, system, modes, H, Mw, k3)
    rk4_stage_state(4, h, q, qd, k1, k2, k3, qs, qds)
    p4 = accelerations(t + h, qs, qds, natural, system, modes, H, Mw, k4)
    rk4_combine(h, q, qd, acc, p1, p2, p3, p4, stages)


@njit(cache=True, **HOT)
def frozen_rk4_step(t, h, q, qd, acc, p1, system, Tg, Tb, stages):
    """RK4 step of the event stepper, every spring in its tabulated mode, from its first stage
    (the first array of ``stages``, with its powers p1): the acceleration at the end of the step
    before (three right-hand sides a step, with the one at its end)."""
    k1, k2, k3, k4, qs, qds, _, _, _, Mw = stages
    rk4_stage_state(2, h, q, qd, k1, k2, k3, qs, qds)
    p2 = frozen_accelerations(t + 0.5 * h, qs, qds, system, Tg, Tb, Mw, k2)
    rk4_stage_state(3, h, q, qd, k1, k2, k3, qs, qds)
    p3 = frozen_accelerations(t + 0.5 * h, qs, qds, system, Tg, Tb, Mw, k3)
    rk4_stage_state(4, h, q, qd, k1, k2, k3, qs, qds)
    p4 = frozen_accelerations(t + h, qs, qds, system, Tg, Tb, Mw, k4)
    rk4_combine(h, q, qd, acc, p1, p2, p3, p4, stages)


@njit(cache=True, inline="always")
def copy(a, b):
    """a[:] = b, without the temporary numba may make when the two could overlap."""
    for i in range(a.size):
        a[i] = b[i]


@njit(cache=True, inline="always")
def advance(start, end):
    """Make the end of an accepted step the start of the next: each is (q, q̇, q̈, acc, e, ė,
    ë), the springs' off the bed."""
    q, qd, a, acc, e, ed, edd = start
    q1, qd1, a1, acc1, e1, ed1, edd1 = end
    for i in range(q.size):
        q[i] = q1[i]
        qd[i] = qd1[i]
        a[i] = a1[i]
    for c in range(N_ACC):
        acc[c] = acc1[c]
    for j in range(e.size):
        e[j] = e1[j]
        ed[j] = ed1[j]
        edd[j] = edd1[j]


@njit(cache=True, inline="always")
def error_ratio(h, q, qd, q1, qd1, k3, k4, a1, floor, qpeak, rtol):
    """The trial step's local error over its tolerance (≤ 1: accept). RK4 and its embedded
    third-order companion that replaces the last stage by the acceleration at the step's end
    (first same as last) differ by y₁ − y₁* = h/6 (F₄ − F₅): h/6 (q̇ + h k₃ − q̇₁) in q and
    h/6 (k₄ − q̈₁) in q̇. Each component is measured against ``rtol`` times the largest
    magnitude it has had in the run (or its floor, the scene's static scale)."""
    n = q.size
    worst = 0.0
    for i in range(n):
        eq = h / 6.0 * abs(qd[i] + h * k3[i] - qd1[i])
        ev = h / 6.0 * abs(k4[i] - a1[i])
        sq = rtol * max(abs(q1[i]), qpeak[i], floor[i])
        sv = rtol * max(abs(qd1[i]), qpeak[n + i], floor[n + i])
        worst = max(worst, eq / sq, ev / sv)
    return worst


@njit(cache=True, inline="always")
def note_magnitudes(q, qd, qpeak):
    """Largest |q| and |q̇| so far, per component (the error control's scale)."""
    n = q.size
    for i in range(n):
        qpeak[i] = max(qpeak[i], abs(q[i]))
        qpeak[n + i] = max(qpeak[n + i], abs(qd[i]))
