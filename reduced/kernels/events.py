"""The event stepper (``events``): RK4 in which every spring keeps its mode through a step; a
step that leaves a mode anywhere inside (contact, separation, yield, unloading, clipping, impact
lock) is cut at the switch, located on the step's interpolant, so no error comes from stepping
over a kink. Under error control (``frame[F_RTOL]`` > 0) the steps are chosen between the record's
samples by an embedded third-order estimate.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .codes import (CHATTER, F_ECHECK, F_EXACT, F_H0, F_HMAX, F_ITH, F_OUTDT, F_RTOL, F_SIDE, HOT,
                    NONFINITE, N_ACC, N_PEAK_SCALARS, OK, OVERTURNED, STEP_UNDERFLOW)
from .crossing import condition_crossing, condition_polynomial
from .energy import check_energy, start_energy, static_strain_energy
from .interpolants import finite, quintic
from .laws import initial_modes, past_limit
from .motion import deformation, deformations, geometric_or_nothing, rates
from .outputs import output_row, record, record_between, stop_row
from .peaks import after_step, bed_peaks, start_side, story_peaks, track_peaks
from .stages import advance, copy, error_ratio, frozen_rk4_step, note_magnitudes
from .switches import apply_switches, first_crossing, impact_step_cap, relocate, spring_quintic
from .tables import bed_state, frozen_accelerations, law_tables


@njit(cache=True)
def integrate_events(q0, qd0, clock, system, floor, max_switches, outputs, peaks, counters,
                     impacts, H):
    """RK4 with switch location and, when ``frame[F_RTOL]`` > 0, error control. ``clock``,
    ``system`` and ``outputs`` are the records :data:`~.codes.CLOCK`, :data:`~.codes.SYSTEM`
    and :data:`~.codes.OUTPUTS`.
    ``counters`` (:data:`N_COUNTERS`): steps cut at a switch, springs switched, rhs calls,
    impacts logged, output rows written, trial steps rejected. ``H`` is the spring history
    (:data:`HISTORY_DTYPE`, zeros at rest); it holds the final history on return, as in every
    integrator here. ``floor`` (2n) are the error control's smallest scales of q and q̇.

    ``impacts`` (rows × 5) logs each activation of an impact damper: time of recontact, spring,
    closing velocity v₀, and time and closing velocity when the damper locked (NaN if it never
    did: the spring separated first, or the run ended).

    Within a step every spring keeps its mode (its law tabulated, :func:`law_tables`), so the
    right-hand side is smooth and RK4 keeps its order. A trial step in which a spring leaves
    its mode (:func:`first_crossing`, on the trial's quintic interpolant) is re-integrated from
    its start up to that switch, where every spring past its limit is switched. A cut that falls
    short of the switch is tried once more on the interpolant raised by what it missed
    (:func:`relocate`); if that too falls short, it ends a step without a switch, and the next
    trial finds the switch at its start. With exact kinematics the base's change of pivot
    (sin θ changing sign) is located the same way. Steps meet every multiple of ``dt`` (the
    record's samples and the outputs); between them, under error control, a trial whose local
    error (:func:`error_ratio`) exceeds the tolerance is retried shorter, and the next trial
    grows or shrinks with (tolerance/error)^¼. While impact dashpots act, steps are capped at
    their stable length. The springs off the bed keep (e, ė, ë) in arrays; the bed's follow
    from the state of its two DOFs.
    """
    minv, P, KG, L, ag, dtg, weight, frame, story, base = system
    scene = (minv, P, geometric_or_nothing(KG), L, ag, dtg, weight, frame, story, base)
    ns, n = P.size, q0.size
    modes = np.zeros(ns, dtype=np.int64)
    e_all, ed_all = np.zeros(ns), np.zeros(ns)
    deformations(q0, qd0, P, e_all, ed_all)
    initial_modes(P, H, modes, e_all, ed_all)
    Tg, Tb = law_tables(P, modes, H)
    ng = Tg.shape[1]  # springs off the bed: 0 … ng − 1
    e0, ed0, edd0 = np.zeros(ng), np.zeros(ng), np.zeros(ng)
    e1, ed1, edd1 = np.zeros(ng), np.zeros(ng), np.zeros(ng)
    margin = np.zeros(Tb.shape[1])
    bed = peaks[N_PEAK_SCALARS + 2 * ng:].reshape((Tb.shape[1], 2))  # the bed's peak slots
    open_impact = np.full(ns, -1, dtype=np.int64)
    a0, a1, k2, k3, k4 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    qs, qds, q1, qd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    Mw, qpeak = np.zeros((n, n)), np.zeros(2 * n)
    q, qd = q0.copy(), qd0.copy()
    acc, acc1, acc_s = np.zeros(N_ACC), np.zeros(N_ACC), np.zeros(N_ACC)
    e_ref = static_strain_energy(P)
    start_side(q, qd, frame)
    books = (modes, H, e_ref, e_all, ed_all)
    record(0, 0.0, q, qd, acc, books, scene, outputs)
    counters[4] = 1
    start_energy(q, qd, acc, books, scene, peaks)
    stages = (a0, k2, k3, k4, qs, qds, q1, qd1, acc1, Mw)
    work = (e0, ed0, edd0, e1, ed1, edd1, margin, bed, a1, acc_s, qpeak, open_impact)
    return march_events(q, qd, acc, clock, scene, (floor, max_switches), (Tg, Tb), books,
                        stages, work, outputs, (peaks, counters, impacts))


@njit(cache=True, **HOT)
def march_events(q, qd, acc, clock, system, control, tables, books, stages, work, outputs, log):
    """The time loop of :func:`integrate_events`, in the workspace it allocated (``control``
    the error control's floors and the switch budget, ``tables`` the law tables, ``work`` the
    springs' rates, scratch and the bed's peak slots, ``log`` the peaks, counters and impact
    log); every helper is inlined and nothing is reference-counted (the loop never allocates).
    Under error control the stored states are interpolated within the steps every
    ``frame[F_OUTDT]`` (:func:`record_between`), so that what is stored does not change the
    steps taken."""
    dt, nsteps, stride = clock
    _, P, _, _, _, _, _, frame, story, _ = system
    floor, max_switches = control
    Tg, Tb = tables
    modes, H, _, _, _ = books
    a0, k2, k3, k4, qs, qds, q1, qd1, acc1, Mw = stages
    e0, ed0, edd0, e1, ed1, edd1, margin, bed, a1, acc_s, qpeak, open_impact = work
    out_t = outputs[0]
    peaks, counters, impacts = log
    t = 0.0
    out_dt = frame[F_OUTDT]
    dense = out_dt > 0.0
    row = 1  # the next stored state
    ith = int(frame[F_ITH])
    exact = frame[F_EXACT] > 0.0
    rtol, hmax = frame[F_RTOL], frame[F_HMAX]
    h_adapt = frame[F_H0] if rtol > 0.0 else np.inf
    echeck = max(1, int(frame[F_ECHECK]))
    p0 = frozen_accelerations(t, q, qd, system, Tg, Tb, Mw, a0)
    counters[2] += 1
    rates(q, qd, a0, P, e0, ed0, edd0)
    note_magnitudes(q, qd, qpeak)
    if after_step(0.0, q, P, Tb, frame, story, peaks):
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    for step in range(nsteps):
        t_end = (step + 1) * dt
        t_tol = 1e-10 * dt + 8.0 * np.finfo(np.float64).eps * t_end
        switches = 0
        while t_end - t > t_tol:
            h = min(t_end - t, impact_step_cap(P, H), h_adapt, hmax)
            t1 = t + h if t_end - (t + h) > t_tol else t_end
            frozen_rk4_step(t, h, q, qd, acc, p0, system, Tg, Tb, stages)
            p1 = frozen_accelerations(t1, q1, qd1, system, Tg, Tb, Mw, a1)
            counters[2] += 4
            good = finite(q1, qd1) and finite(a1, a1)
            if rtol > 0.0:
                ratio = error_ratio(h, q, qd, q1, qd1, k3, k4, a1, floor, qpeak, rtol) \
                    if good else np.inf
                if ratio > 1.0:
                    counters[5] += 1
                    h_adapt = h * (max(0.1, 0.9 * ratio ** -0.25) if good else 0.1)
                    if h_adapt <= 1e-12 * max(dt, t_end):
                        counters[0] = step
                        return STEP_UNDERFLOW
                    continue
                grown = h * (min(4.0, 0.9 * ratio ** -0.25) if ratio > 0.0 else 4.0)
                h_adapt = grown if h >= h_adapt else max(h_adapt, grown)
            if not good:
                counters[0] = step
                return NONFINITE
            rates(q1, qd1, a1, P, e1, ed1, edd1)
            x0, y0 = bed_state(P, q, qd, a0)
            x1, y1 = bed_state(P, q1, qd1, a1)
            s, spring = first_crossing(h, P, Tg, Tb, x0, y0, x1, y1, (e0, ed0, edd0),
                                       (e1, ed1, edd1), margin)
            flip = False
            if exact:  # the base changes pivot where sin θ changes sign
                m = quintic(h, q[ith], qd[ith], a0[ith], q1[ith], qd1[ith], a1[ith])
                c = condition_polynomial(0.0, frame[F_SIDE], 0.0, m, h)
                sp = condition_crossing(c, s)
                if sp < s:
                    s, spring, flip = sp, -1, True
            if spring >= 0 or flip:  # re-integrate up to the switch
                if spring >= 0:
                    m = spring_quintic(spring, h, Tb, x0, y0, x1, y1, (e0, ed0, edd0),
                                       (e1, ed1, edd1))
                tau = min(max(s * h, t_tol), h)
                frozen_rk4_step(t, tau, q, qd, acc, p0, system, Tg, Tb, stages)
                counters[2] += 3
                if spring >= 0:
                    e, ed = deformation(P[spring], q1, qd1)
                    if not past_limit(modes[spring], P[spring], e, ed, H[spring]):
                        s = relocate(spring, tau / h, m, h, P, modes, H, Tg, Tb, q1, qd1)
                        if s < 1.0:  # once more, on the interpolant raised by what it missed
                            tau = min(max(s * h, t_tol), h)
                            frozen_rk4_step(t, tau, q, qd, acc, p0, system, Tg, Tb, stages)
                            counters[2] += 3
                h = tau
                t1 = t + h if t_end - (t + h) > t_tol else t_end
                # q̈ at the cut, in the modes of the step: its end for the peaks and outputs
                p1 = frozen_accelerations(t1, q1, qd1, system, Tg, Tb, Mw, a1)
                counters[2] += 1
                rates(q1, qd1, a1, P, e1, ed1, edd1)
                x1, y1 = bed_state(P, q1, qd1, a1)
            track_peaks(h, (q, qd, e0, ed0), (q1, qd1, e1, ed1), P, modes, H, frame, peaks)
            story_peaks(h, Tg, P, e0, ed0, edd0, e1, ed1, edd1, peaks)
            bed_peaks(Tb, h, x0, y0, x1, y1, bed)
            if dense and row < out_t.size and row * out_dt <= t1 + t_tol:
                while row < out_t.size and row * out_dt <= t1 + t_tol:
                    record_between(row, min(row * out_dt, t1), t, h, (q, qd, a0, acc),
                                   (q1, qd1, a1, acc1), p0, p1, (qs, qds, acc_s), books, system,
                                   outputs)
                    row += 1
                counters[4] = row
            t = t1
            if spring < 0 and not flip:  # the whole step, without a switch
                advance((q, qd, a0, acc, e0, ed0, edd0), (q1, qd1, a1, acc1, e1, ed1, edd1))
                p0 = p1
            else:
                copy(q, q1)
                copy(qd, qd1)
                copy(acc, acc1)
                if flip:
                    frame[F_SIDE] = -frame[F_SIDE]
                switched = apply_switches(t, P, modes, H, q, qd, Tg, Tb, impacts, open_impact,
                                          counters)
                counters[0] += 1
                counters[1] += switched
                switches += max(switched, 1)
                if switches > max_switches:
                    counters[1] = step
                    return CHATTER
                p0 = frozen_accelerations(t, q, qd, system, Tg, Tb, Mw, a0)
                counters[2] += 1
                rates(q, qd, a0, P, e0, ed0, edd0)
            note_magnitudes(q, qd, qpeak)
            if after_step(t, q, P, Tb, frame, story, peaks):
                last = row if dense else stop_row(step, stride)
                if last < out_t.size:
                    record(last, t, q, qd, acc, books, system, outputs)
                    counters[4] = last + 1
                check_energy(q, qd, acc, books, system, peaks)
                return OVERTURNED
        if not dense and ((step + 1) % stride == 0 or step == nsteps - 1):
            row = output_row(step, stride)
            record(row, t_end, q, qd, acc, books, system, outputs)
            counters[4] = row + 1
        if (step + 1) % echeck == 0 or step == nsteps - 1:
            check_energy(q, qd, acc, books, system, peaks)
    return OK
