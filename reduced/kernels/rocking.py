"""Exact rocking kinematics (``structure.kinematics = "exact"``) and the toppling test.

The base rotation enters through s = sin θ, which keeps every spring deformation linear in q
(foundation: e = x s − V; story: the drift w_j − w_{j−1} in the base's rotated frame), so the
laws, their tables and the switch location are those of small rotations. The base rotates about
the edge it leans towards (x = ±b, the pivot of a rigid block): its centre O moves by
u_O = ±b (1 − cos θ) horizontally and V vertically, story mass j sits at
X_j = u_O + w_j cos θ + h_j sin θ, Y_j = V + h_j (cos θ − 1) − w_j sin θ, and the base body (mass
m_b at O, rotary inertia I_b about O) with it. Lagrange's equations in q give
M(q) q̈ = Q − (velocity terms); gravity acts on the exact configuration (P-Δ exact). The static
compressions carry the weight, so the springs' force increments and gravity's vertical part
cancel at rest, as in small rotations.
"""

from __future__ import annotations

import math

from numba import njit

from .codes import F_B, F_EXACT, F_IB, F_ISWAY, F_ITH, F_IV, F_MB, F_NFLEX, F_SIDE, F_WTOT


@njit(cache=True, inline="always")
def pivot(s, frame):
    """cos θ, and the base centre's horizontal displacement u_O = side·b (1 − cos θ) with its
    first and second derivatives in s = sin θ."""
    c = math.sqrt(max(1.0 - s * s, 1e-300))
    sb = frame[F_SIDE] * frame[F_B]
    return c, sb * (1.0 - c), sb * s / c, sb / (c * c * c)


@njit(cache=True, inline="always")
def exact_dynamics(a, q, qd, frame, story, R, M):
    """Add to R (the springs' generalised forces) the inertia, gravity and ground terms of
    exact kinematics and fill the mass matrix M(q); returns the ground's input power.

    ``story`` rows are (h_j, m_j, W_j) of each story mass; ``a`` the ground acceleration."""
    n = q.size
    ith, iv, nflex = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    s, sd = q[ith], qd[ith]
    c, _, u1, u2 = pivot(s, frame)
    c3 = c * c * c
    for i in range(n):
        for k in range(n):
            M[i, k] = 0.0
    mb, ib = frame[F_MB], frame[F_IB]
    M[ith, ith] += mb * u1 * u1 + ib / (c * c)
    M[iv, iv] += mb
    R[ith] -= mb * u1 * u2 * sd * sd + ib * sd * sd * s / (c3 * c) + a * mb * u1
    pin = -a * mb * u1 * sd
    for j in range(story.shape[0]):
        h, m, W = story[j, 0], story[j, 1], story[j, 2]
        w = q[j] if j < nflex else 0.0
        wd = qd[j] if j < nflex else 0.0
        xs = u1 - w * s / c + h      # ∂X_j/∂s
        ys = -h * s / c - w          # ∂Y_j/∂s
        gx = (u2 - w / c3) * sd * sd - 2.0 * (s / c) * sd * wd   # the rest of Ẍ_j
        gy = -h / c3 * sd * sd - 2.0 * sd * wd                    # the rest of Ÿ_j
        M[ith, ith] += m * (xs * xs + ys * ys)
        M[ith, iv] += m * ys
        M[iv, ith] += m * ys
        M[iv, iv] += m
        R[ith] -= m * (xs * gx + ys * gy) + a * m * xs + W * ys
        R[iv] -= m * gy
        pin -= a * m * xs * sd
        if j < nflex:
            cross = m * (c * xs - s * ys)
            M[j, j] += m
            M[j, ith] += cross
            M[ith, j] += cross
            M[j, iv] -= m * s
            M[iv, j] -= m * s
            R[j] -= m * (c * gx - s * gy) + a * m * c - W * s
            pin -= a * m * c * wd
    return pin


@njit(cache=True, inline="always")
def solve_spd(M, r):
    """Solve M x = r for a small symmetric positive definite M by Cholesky, in place: M is
    overwritten by its factor and r by x."""
    n = r.size
    for k in range(n):
        d = M[k, k]
        for p in range(k):
            d -= M[k, p] * M[k, p]
        d = math.sqrt(d)
        M[k, k] = d
        for i in range(k + 1, n):
            v = M[i, k]
            for p in range(k):
                v -= M[i, p] * M[k, p]
            M[i, k] = v / d
    for i in range(n):
        v = r[i]
        for p in range(i):
            v -= M[i, p] * r[p]
        r[i] = v / M[i, i]
    for i in range(n - 1, -1, -1):
        v = r[i]
        for p in range(i + 1, n):
            v -= M[p, i] * r[p]
        r[i] = v / M[i, i]


@njit(cache=True, inline="always")
def finish_accelerations(a, q, qd, minv, frame, story, M, qdd):
    """Turn the generalised forces in qdd into accelerations: M⁻¹ for small rotations (M
    diagonal); the exact kinematics' terms and its M(q) otherwise. Returns the extra input
    power (exact kinematics: the ground's; small: none, L a q̇ is counted by the caller)."""
    if frame[F_EXACT] > 0.0:
        pin = exact_dynamics(a, q, qd, frame, story, qdd, M)
        solve_spd(M, qdd)
        return pin
    for i in range(q.size):
        qdd[i] *= minv[i]
    return 0.0


@njit(cache=True)
def exact_energy(q, qd, frame, story, weight):
    """(kinetic, gravity) energy of exact kinematics: ½ Σ m |Ẋ|² + ½ I_b θ̇², and
    W V + Σ W_j (h_j (cos θ − 1) − w_j sin θ) (W the weight on the foundation)."""
    ith, iv, nflex = int(frame[F_ITH]), int(frame[F_IV]), int(frame[F_NFLEX])
    s, sd, vd = q[ith], qd[ith], qd[iv]
    c, _, u1, _ = pivot(s, frame)
    mb, ib = frame[F_MB], frame[F_IB]
    kinetic = 0.5 * mb * ((u1 * sd) ** 2 + vd * vd) + 0.5 * ib * (sd / c) ** 2
    gravity = weight * q[iv]
    for j in range(story.shape[0]):
        h, m, W = story[j, 0], story[j, 1], story[j, 2]
        w = q[j] if j < nflex else 0.0
        wd = qd[j] if j < nflex else 0.0
        xd = c * wd + (u1 - w * s / c + h) * sd
        yd = -s * wd + (-h * s / c - w) * sd + vd
        kinetic += 0.5 * m * (xd * xd + yd * yd)
        gravity += W * (h * (c - 1.0) - w * s)
    return kinetic, gravity


@njit(cache=True)
def overturn_ratio(q, frame, story):
    """|x_G − x_O|/b, x_G the lateral position of the centre of the weight (the stories' and the
    base's) in the exact geometry of the state, and x_O the base centre's rest position. At 1
    the centre is over the edge the base rocks about: past the toppling angle (a rigid block:
    θ = α = atan(b/h)). Small rotations are judged on the same geometry, their state read as
    θ and deflections w_j = x_j − h_j θ − u_b (u_b the base's sway, when it has one): the
    model's own restoring moment vanishes only at θ = b/h, past the real structure's
    toppling."""
    b = frame[F_B]
    if b <= 0.0:
        return 0.0
    ith, nflex, isway = int(frame[F_ITH]), int(frame[F_NFLEX]), int(frame[F_ISWAY])
    exact = frame[F_EXACT] > 0.0
    s = q[ith] if exact else math.sin(q[ith])
    c = math.sqrt(max(1.0 - s * s, 0.0))
    moment = frame[F_WTOT] * b * (1.0 - c) * (1.0 if s >= 0.0 else -1.0)  # u_O of every weight
    for j in range(story.shape[0]):
        h = story[j, 0]
        w = 0.0
        if j < nflex:
            w = q[j] if exact else q[j] - h * q[ith]
            if isway >= 0:
                w -= q[isway]
        moment += story[j, 2] * (w * c + h * s)
    return abs(moment / frame[F_WTOT]) / b
