"""The base element in the kernels: a foundation law that is one element on the base's three
DOFs rather than a row of springs (the macro-element, :mod:`upliftlab.reduced.laws.macro`).

It travels as the SYSTEM record's last entry, ``base`` = (P, S, St, D, W, T, C):

- ``P`` the law's parameters (``pack``; empty: the model has no base element, and every
  function here does nothing);
- ``S`` its committed state, changed only at the end of an accepted step (:func:`commit_base`),
  ``St`` a trial copy, ``D`` (3×3) and ``W`` the update's scratch;
- ``T`` (3 × n): the element's displacement (v, u, θ) (settlement down, sway, rotation) is
  d = d_rest + T q;
- ``C`` the element's constants and scratch (slots ``C_…``): its displacement and forces at
  rest, the dashpots, the sub-step size, the status of a step that failed and its stored energy
  at rest.

Like a q–z spring, the element's trial force comes from its committed state: every right-hand
side moves a copy of it to the trial displacement (:func:`base_force`), and the accepted step
moves the state itself (:func:`commit_base`). The weight is balanced by the forces at rest, so
the element acts on q with −Tᵀ (Q − Q_rest + Q_dashpot).

The dashpots act where the footing is in contact, as a bed of dashpots under it would (the
springs' dashpots detach with them): a density c′ (force·s/length², per unit length of the
contact) gives V_d = c′ (I0 v̇ + I1 θ̇), M_d = c′ (I1 v̇ + I2 θ̇), with I_j = ∫ xʲ over the
contact; the sway's dashpot c_h is scaled by the contact's share of the width.
"""

from __future__ import annotations

from numba import njit

from ..laws.macro.compiled import (P_B, P_CXT, P_CXV, S_D, S_P, S_Q, S_ROUND, S_W, STEP_OK,
                                   W_DE, W_Q, bed_moments, elastic, step_into)
from .codes import E_PLASTIC, HOT, P_BGAP, P_BGAPL, P_BH, P_BU, P_CMIN

# slots of C: the displacement at rest (3), the forces at rest (3), the dashpot density c′ and
# the sway's dashpot c_h, the largest trial force step of a sub-step (V_ult-scaled), the status
# of the first step that failed (0: none), the stored energy at rest, scratch: the trial
# displacement (3) and its rate (3), and the plastic work of the steps that did negative
# plastic work, summed (a dissipation that a sound law never makes negative)
C_D0, C_Q0, C_CV, C_CH, C_DF, C_STATUS, C_E0, C_TARGET, C_RATE, C_NEGATIVE = (
    0, 3, 6, 7, 8, 9, 10, 11, 14, 17)
N_C = 18
# columns of the stored base states: forces (V, H, M) without the dashpots, plastic
# displacement (v_p, u_p, θ_p), contact from x = lo to hi (length; lo = hi: lifted off), the
# rounding ρ of the soil's surface, the energy dissipated so far
N_BASE_OUT = 10


@njit(cache=True, **HOT)
def _target(base, q, qd):
    """The element's displacement d_rest + T q and rate T q̇, into C's scratch."""
    T, C = base[5], base[6]
    for i in range(3):
        d = C[C_D0 + i]
        r = 0.0
        for k in range(q.size):
            d += T[i, k] * q[k]
            r += T[i, k] * qd[k]
        C[C_TARGET + i] = d
        C[C_RATE + i] = r


@njit(cache=True, **HOT)
def contact_moments(P, S):
    """(lo, hi, I0, I1, I2) of the contact of the bed in state S: its own displacement is the
    elastic part less the remainder's C_x Q; none when the footing carries no load."""
    if S[S_Q] <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    b = 0.5 * P[P_B]
    v = S[S_D] - S[S_P] - P[P_CXV] * S[S_Q]
    theta = S[S_D + 2] - S[S_P + 2] - P[P_CXT] * S[S_Q + 2]
    A, Cc, R, I0, I1, I2, _, _ = bed_moments(b, v, theta, S[S_ROUND])
    if I0 <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    # the contact's ends from its moments: centre I1/I0, length I0
    centre = I1 / I0
    return centre - 0.5 * I0, centre + 0.5 * I0, I0, I1, I2


@njit(cache=True, **HOT)
def base_force(q, qd, base, qdd):
    """Subtract the element's generalised forces from ``qdd`` at the trial state (q, q̇);
    returns the dashpots' power. A step that fails is noted in C (the first one) and leaves the
    committed forces acting, so that the integrator stops at the step's end."""
    P, S, St, D, W, T, C = base
    if P.size == 0:
        return 0.0
    _target(base, q, qd)
    for i in range(S.size):
        St[i] = S[i]
    status = step_into(P, St, C[C_TARGET:C_TARGET + 3], C[C_DF], 0, D, W)
    if status != STEP_OK:
        if C[C_STATUS] == 0.0:
            C[C_STATUS] = status
        for i in range(S.size):
            St[i] = S[i]
    _, _, I0, I1, I2 = contact_moments(P, St)
    vd, ud, td = C[C_RATE], C[C_RATE + 1], C[C_RATE + 2]
    cv = C[C_CV]
    fv = St[S_Q] - C[C_Q0] + cv * (I0 * vd + I1 * td)
    fh = St[S_Q + 1] - C[C_Q0 + 1] + C[C_CH] * I0 / P[P_B] * ud
    fm = St[S_Q + 2] - C[C_Q0 + 2] + cv * (I1 * vd + I2 * td)
    for k in range(q.size):
        qdd[k] -= T[0, k] * fv + T[1, k] * fh + T[2, k] * fm
    return _dashpot_power(P, C, I0, I1, I2)


@njit(cache=True, **HOT)
def _dashpot_power(P, C, I0, I1, I2):
    """The dashpots' power at the rates in C's scratch over a contact of moments I0, I1, I2."""
    vd, ud, td = C[C_RATE], C[C_RATE + 1], C[C_RATE + 2]
    cv = C[C_CV]
    return cv * (I0 * vd * vd + 2.0 * I1 * vd * td + I2 * td * td) \
        + C[C_CH] * I0 / P[P_B] * ud * ud


@njit(cache=True, **HOT)
def committed_power(q, qd, base):
    """The dashpots' power at rates q̇ over the committed state's contact (0 without a base
    element): after :func:`commit_base` moved the state to an accepted step's end, the power
    there without moving the element again."""
    P, S = base[0], base[1]
    if P.size == 0:
        return 0.0
    _target(base, q, qd)
    _, _, I0, I1, I2 = contact_moments(P, S)
    return _dashpot_power(P, base[6], I0, I1, I2)


@njit(cache=True, **HOT)
def accept_base(q, base, acc, peaks):
    """The base element at an accepted step's end q: its state committed there, its plastic
    work booked in ``acc``, its peaks tracked; returns the status (0, or why it failed)."""
    work, status = commit_base(q, base)
    if status != 0:
        return status
    acc[E_PLASTIC] += work
    track_base(base, peaks)
    return 0


@njit(cache=True, **HOT)
def commit_base(q, base):
    """Move the committed state to the accepted step's end q; returns (the plastic work of the
    step, the status: STEP_OK, or why the step failed, noted in C)."""
    P, S, St, D, W, T, C = base
    if P.size == 0:
        return 0.0, STEP_OK
    if C[C_STATUS] != 0.0:
        return 0.0, int(C[C_STATUS])
    _target(base, q, q)
    before = S[S_W]
    status = step_into(P, S, C[C_TARGET:C_TARGET + 3], C[C_DF], 0, D, W)
    if status != STEP_OK:
        C[C_STATUS] = status
    work = S[S_W] - before
    if work < 0.0:
        C[C_NEGATIVE] -= work
    return work, status


@njit(cache=True, **HOT)
def base_energy(base):
    """The energy the committed state stores, less the stored energy at rest (0 without a
    base element)."""
    P, S, St, D, W, T, C = base
    if P.size == 0:
        return 0.0
    for i in range(3):
        W[W_DE + i] = S[S_D + i] - S[S_P + i]
    energy, _ = elastic(P, W[W_DE:W_DE + 3], S[S_Q:S_Q + 3], W[W_Q:W_Q + 3], D, S[S_ROUND])
    return energy - C[C_E0]


@njit(cache=True, **HOT)
def edge_gaps(base):
    """The gaps under the footing's left and right edges, (⟨−w(−b)⟩, ⟨−w(b)⟩), of the
    committed state (length): the bed's compression at the edges, w(±b) = v_b ± θ_b b − 2ρ/3."""
    P, S = base[0], base[1]
    b = 0.5 * P[P_B]
    v = S[S_D] - S[S_P] - P[P_CXV] * S[S_Q] - 2.0 * S[S_ROUND] / 3.0
    theta = S[S_D + 2] - S[S_P + 2] - P[P_CXT] * S[S_Q + 2]
    return max(theta * b - v, 0.0), max(-v - theta * b, 0.0)


@njit(cache=True, **HOT)
def base_gap(base):
    """The larger gap under the footing's two edges (length, :func:`edge_gaps`)."""
    left, right = edge_gaps(base)
    return max(left, right)


@njit(cache=True, **HOT)
def record_base(k, base, out):
    """Store the committed state in row k of the base's outputs (``N_BASE_OUT`` columns)."""
    P, S = base[0], base[1]
    if P.size == 0:
        return
    lo, hi, _, _, _ = contact_moments(P, S)
    for i in range(3):
        out[k, i] = S[S_Q + i]
        out[k, 3 + i] = S[S_P + i]
    out[k, 6], out[k, 7], out[k, 8], out[k, 9] = lo, hi, S[S_ROUND], S[S_W]


@njit(cache=True, **HOT)
def track_base(base, peaks):
    """The base element's peaks at a committed state: its least contact length (P_CMIN), the
    larger gap under its edges and the gap under its left edge, its largest |u − u_rest| and
    |H|."""
    P, S, C = base[0], base[1], base[6]
    if P.size == 0:
        return
    length = contact_moments(P, S)[2]
    peaks[P_CMIN] = min(peaks[P_CMIN], length)
    left, right = edge_gaps(base)
    peaks[P_BGAP] = max(peaks[P_BGAP], left, right)
    peaks[P_BGAPL] = max(peaks[P_BGAPL], left)
    peaks[P_BU] = max(peaks[P_BU], abs(S[S_D + 1] - C[C_D0 + 1]))
    peaks[P_BH] = max(peaks[P_BH], abs(S[S_Q + 1]))


@njit(cache=True, **HOT)
def base_internal(q, qd, base, fint, scratch):
    """Add the element's generalised forces at the trial state (q, q̇) to ``fint`` (an
    implicit step's internal force; ``scratch`` a vector of q's size); returns the dashpots'
    power. Each call starts from the committed state with no failure noted, so that a Newton
    iterate that the element cannot reach does not outlive a later one it can: what counts is
    the iterate the step converges to (:func:`commit_base` moves the state there, or fails)."""
    P, C = base[0], base[6]
    if P.size == 0:
        return 0.0
    C[C_STATUS] = 0.0
    for k in range(q.size):
        scratch[k] = 0.0
    power = base_force(q, qd, base, scratch)
    for k in range(q.size):
        fint[k] -= scratch[k]
    return power


@njit(cache=True, **HOT)
def base_tangent(base, damping, scale, J):
    """Add ``scale`` Tᵀ (D + ``damping`` C_d) T to ``J``: D the element's tangent at its last
    trial (:func:`base_force`), C_d its dashpots over the trial's contact (the contact's own
    change with the displacement left out: a Newton iteration's tangent, not the update's)."""
    P, St, D, T, C = base[0], base[2], base[3], base[5], base[6]
    if P.size == 0:
        return
    _, _, I0, I1, I2 = contact_moments(P, St)
    cv, ch = C[C_CV], C[C_CH] * I0 / P[P_B]
    n = T.shape[1]
    for a in range(3):
        for b in range(3):
            k = D[a, b]
            if a == 0 and b == 0:
                k += damping * cv * I0
            elif (a == 0 and b == 2) or (a == 2 and b == 0):
                k += damping * cv * I1
            elif a == 2 and b == 2:
                k += damping * cv * I2
            elif a == 1 and b == 1:
                k += damping * ch
            if k == 0.0:
                continue
            for i in range(n):
                if T[a, i] == 0.0:
                    continue
                for j in range(n):
                    J[i, j] += scale * T[a, i] * k * T[b, j]
