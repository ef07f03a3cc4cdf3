"""Peaks of a run, tracked at every step: displacement, rotation, settlement, story drifts
and shears, the overturning moment, the foundation gaps and compressions (refined inside a step
on its interpolants), the least contact length of the base, and the toppling test. The slots of
the peak array are named in :mod:`.codes` (``P_*``, then two per spring) and decoded in one place,
:func:`upliftlab.reduced.peak_slots.decode_peaks`.
"""

from __future__ import annotations

from numba import njit

from .codes import (FAST, F_B, F_EXACT, F_ITH, F_IV, F_NFLEX, F_SIDE, HOT, N_PEAK_SCALARS, P_CMIN,
                    P_MOT, P_RPREV, P_THMAX, P_THMIN, P_TOVER, P_TPREV, P_UMAX, P_UMIN, P_VMAX,
                    P_VMIN, SEPARATED, STORY, T_A0, T_A1, T_C, T_F, T_FY, T_GAP, T_K, T_KC)
from .interpolants import hermite_extreme
from .rocking import overturn_ratio
from .tables import bed_rates


@njit(cache=True, **HOT)
def track_peaks(h, start, end, P, modes, H, frame, peaks):
    """Update peaks over a step [t, t+h], refining interior extrema by Hermite interpolation;
    ``start`` and ``end`` are (q, q̇, e, ė) at the step's ends.

    Scalars: top deformation u (sum of story drifts), θ, V, and at the step's end the
    overturning moment Σ arm·shear of the stories. Per spring j: slot A = max opening
    (foundation: gap −d; story: |drift|), slot B = max |force| at the step ends (foundation:
    spring compression; story: its shear, dashpot included, so story 0 gives the base shear).
    """
    q0, qd0, e0, ed0 = start
    q1, qd1, e1, ed1 = end
    ith, iv, n_story = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    if n_story > 0:
        u0 = ud0 = u1 = ud1 = 0.0
        for j in range(n_story):
            u0 += e0[j]
            ud0 += ed0[j]
            u1 += e1[j]
            ud1 += ed1[j]
        peaks[P_UMIN] = hermite_extreme(u0, ud0, u1, ud1, h, min(peaks[P_UMIN], u1), False)
        peaks[P_UMAX] = hermite_extreme(u0, ud0, u1, ud1, h, max(peaks[P_UMAX], u1), True)
    if ith >= 0:
        a, b, c, d = q0[ith], qd0[ith], q1[ith], qd1[ith]
        peaks[P_THMIN] = hermite_extreme(a, b, c, d, h, min(peaks[P_THMIN], c), False)
        peaks[P_THMAX] = hermite_extreme(a, b, c, d, h, max(peaks[P_THMAX], c), True)
        a, b, c, d = q0[iv], qd0[iv], q1[iv], qd1[iv]
        peaks[P_VMIN] = hermite_extreme(a, b, c, d, h, min(peaks[P_VMIN], c), False)
        peaks[P_VMAX] = hermite_extreme(a, b, c, d, h, max(peaks[P_VMAX], c), True)
    moment = 0.0
    for j in range(e0.size):
        p = P[j]
        a = N_PEAK_SCALARS + 2 * j
        if p.kind == STORY:
            top = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h, max(e1[j], peaks[a]), True)
            low = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h, min(e1[j], -peaks[a]), False)
            peaks[a] = max(top, -low)
            fep = min(max(p.k * (e1[j] - H[j].ep), -p.fy), p.fy)  # after the return map
            shear = p.kh * e1[j] + fep + p.c * ed1[j]
            peaks[a + 1] = max(peaks[a + 1], abs(shear))
            moment += p.arm * shear
        else:
            # gap = −d = (ep − δ0) − e, largest where e is smallest
            offset = H[j].ep - p.d0
            e_min = hermite_extreme(e0[j], ed0[j], e1[j], ed1[j], h,
                                    min(e1[j], offset - peaks[a]), False)
            peaks[a] = max(peaks[a], offset - e_min)
            if modes[j] != SEPARATED:
                d1 = p.d0 + e1[j] - H[j].ep
                peaks[a + 1] = max(peaks[a + 1], min(p.k * max(d1, 0.0), p.fy))
    peaks[P_MOT] = max(peaks[P_MOT], abs(moment))


@njit(cache=True, **HOT)
def story_peaks(h, T, P, e0, ed0, edd0, e1, ed1, edd1, peaks):
    """Refine the story shears' and the overturning moment's peaks inside an event-stepper
    step, where every story keeps its tabulated law f = K e + C ė + F: the extremes of the
    cubic through f and ḟ = K ė + C ë at the step's ends (:func:`track_peaks` has the ends)."""
    m0 = md0 = m1 = md1 = 0.0
    for j in range(T.shape[1]):
        if P[j].kind != STORY:
            continue
        f0 = T[T_K, j] * e0[j] + T[T_C, j] * ed0[j] + T[T_F, j]
        f1 = T[T_K, j] * e1[j] + T[T_C, j] * ed1[j] + T[T_F, j]
        fd0 = T[T_K, j] * ed0[j] + T[T_C, j] * edd0[j]
        fd1 = T[T_K, j] * ed1[j] + T[T_C, j] * edd1[j]
        a = N_PEAK_SCALARS + 2 * j + 1
        top = hermite_extreme(f0, fd0, f1, fd1, h, peaks[a], True)
        low = hermite_extreme(f0, fd0, f1, fd1, h, -peaks[a], False)
        peaks[a] = max(top, -low)
        arm = P[j].arm
        m0 += arm * f0
        m1 += arm * f1
        md0 += arm * fd0
        md1 += arm * fd1
    top = hermite_extreme(m0, md0, m1, md1, h, peaks[P_MOT], True)
    low = hermite_extreme(m0, md0, m1, md1, h, -peaks[P_MOT], False)
    peaks[P_MOT] = max(top, -low)


@njit(cache=True, fastmath=FAST, **HOT)
def bed_peaks(T, h, x0, y0, x1, y1, peaks):
    """:func:`track_peaks` for the springs of the bed (its slots: ``peaks[k, 0]`` the gap,
    ``peaks[k, 1]`` the compression), from the state of its two DOFs at the step's ends."""
    for k in range(T.shape[1]):
        a0, a1 = T[T_A0, k], T[T_A1, k]
        e0, ed0, _ = bed_rates(a0, a1, x0, y0)
        e1, ed1, _ = bed_rates(a0, a1, x1, y1)
        offset = T[T_GAP, k]
        e_min = hermite_extreme(e0, ed0, e1, ed1, h, min(e1, offset - peaks[k, 0]), False)
        peaks[k, 0] = max(peaks[k, 0], offset - e_min)
        peaks[k, 1] = max(peaks[k, 1], min(T[T_KC, k] * max(e1 - offset, 0.0), T[T_FY, k]))


@njit(cache=True, inline="always")
def segment_contact(x0, x1, d0, d1):
    """Length in contact of a piece of base between two springs, d linear between them."""
    if d0 > 0.0 and d1 > 0.0:
        return x1 - x0
    if d0 > 0.0 or d1 > 0.0:
        return max(d0, d1) / (abs(d0) + abs(d1)) * (x1 - x0)
    return 0.0


@njit(cache=True, **HOT)
def bed_contact_length(T, x, y, b):
    """Contact length of the bed (its springs by increasing x): where d = e − T_GAP > 0, d
    linear between springs and constant beyond the outer ones to the edges ±b."""
    total = 0.0
    x_prev, d_prev = -b, 0.0
    for k in range(T.shape[1]):
        xk = T[T_A0, k]
        dk = T[T_A0, k] * x + T[T_A1, k] * y - T[T_GAP, k]
        if k == 0:
            d_prev = dk
        total += segment_contact(x_prev, xk, d_prev, dk)
        x_prev, d_prev = xk, dk
    return total + segment_contact(x_prev, b, d_prev, d_prev)


@njit(cache=True, **HOT)
def springs_contact_length(P, H, e, first, b):
    """:func:`bed_contact_length` from the springs' records (foundation springs from
    ``first`` on, by increasing x) and their deformations e."""
    total = 0.0
    x_prev, d_prev = -b, 0.0
    for j in range(first, P.size):
        dk = P[j].d0 + e[j] - H[j].ep
        if j == first:
            d_prev = dk
        total += segment_contact(x_prev, P[j].x, d_prev, dk)
        x_prev, d_prev = P[j].x, dk
    return total + segment_contact(x_prev, b, d_prev, d_prev)


@njit(cache=True, **HOT)
def start_side(q, qd, frame):
    """Exact kinematics: the edge the base starts rocking about, from the sign of θ (or θ̇)."""
    if frame[F_EXACT] > 0.0:
        ith = int(frame[F_ITH])
        lean = q[ith] if q[ith] != 0.0 else qd[ith]
        frame[F_SIDE] = -1.0 if lean < 0.0 else 1.0


@njit(cache=True, **HOT)
def toppled(t, q, frame, story, peaks):
    """True if the state at time t is past the toppling angle (:func:`overturn_ratio` ≥ 1),
    with the time it got there, interpolated from the last accepted state, in P_TOVER."""
    ratio = overturn_ratio(q, frame, story)
    if ratio >= 1.0:
        r0, t0 = peaks[P_RPREV], peaks[P_TPREV]
        peaks[P_TOVER] = t0 + (1.0 - r0) / (ratio - r0) * (t - t0) if ratio > r0 else t
        return True
    peaks[P_RPREV], peaks[P_TPREV] = ratio, t
    return False


@njit(cache=True, **HOT)
def after_step(t, q, P, Tb, frame, story, peaks):
    """Contact length of the bed at an accepted state at time t, into its least; True if the
    state is past the toppling angle (:func:`toppled`)."""
    b = frame[F_B]
    if b <= 0.0:
        return False
    if Tb.shape[1] > 0:
        last = P[P.size - 1]
        peaks[P_CMIN] = min(peaks[P_CMIN], bed_contact_length(Tb, q[last.i0], q[last.i1], b))
    return toppled(t, q, frame, story, peaks)


@njit(cache=True, **HOT)
def after_fixed_step(t, q, P, H, e, frame, story, peaks):
    """:func:`after_step` for the fixed-step integrators, whose springs keep e in an array."""
    b = frame[F_B]
    if b <= 0.0:
        return False
    first = P.size
    while first > 0 and P[first - 1].kind != STORY:
        first -= 1
    if first < P.size:
        peaks[P_CMIN] = min(peaks[P_CMIN], springs_contact_length(P, H, e, first, b))
    return toppled(t, q, frame, story, peaks)
