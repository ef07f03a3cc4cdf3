"""The footing's unilateral contact in one explicit step: a small complementarity problem.

With a diagonal (lumped) mass, one central-difference step moves every soil DOF independently:
u_{n+1} = u*_{n+1} + h f_c/m̃ (u* the displacement without contact forces, h = dt·dt_v the
step's force-to-displacement factor, m̃ the mass plus half a step of the DOF's dashpot). The
footing and the story obey A z_{n+1} + b + [Lᵀ f_c; 0] = 0, the same affine form as the
implicit scheme's (:func:`~upliftlab.continuum.dynamics.run.structure_matrices`), with A = M̃/h.
Eliminating the story DOF s (its row carries no contact force) leaves K_q q + o + Lᵀ f_c = 0
on the footing (K_q the Schur complement of A, ``o`` its offset). The contact forces of the
step are those for which the positions at n+1 satisfy the contact conditions exactly — the
forward-increment Lagrange multiplier method of Carpenter, Taylor & Katona (*Int. J. Numer.
Meth. Engng* 32, 1991) — so no penalty and no interpenetration.

**Frictionless** (:func:`normal_forces`, compiled): the unknowns are the normal forces P ≥ 0
at the footing nodes (the soil's u_y receives −P). The gaps at n+1 are affine in P,
g = g* + W P with W = diag(h/m̃_y) + L K_q⁻¹ Lᵀ (L rows (1, −x_i) on the footing's (v, θ)),
a symmetric positive definite matrix, so the complementarity problem g ≥ 0, P ≥ 0, P g = 0
has exactly one solution. It is found by a primal–dual active set (each set solved exactly by
the Sherman–Morrison–Woodbury form of W, the footing's 2×2 system), warm-started from the last
step's set, and by Murty's least-index rule if the sets cycle (finite for P-matrices).

**Bonded or Coulomb** (:func:`tangential_step`): the same conditions with tangential forces:
the primal–dual active set of :func:`~upliftlab.continuum.contact.footing.solve_contact` (closed,
sticking or slipping nodes; bonded is Coulomb with μ = 1000), compiled for the diagonal
"stiffness" S = m̃/h of the contact DOFs, with the footing's motion as unknowns (a footing
without horizontal mass of its own, once the story is eliminated, is no obstacle).
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .footing import OPEN, RTOL_CONTACT, SLIP_NEGATIVE, SLIP_POSITIVE, STICK

__all__ = ["normal_forces", "frictionless_step", "tangential_step", "footing_schur"]

#: Active-set sweeps before the least-index rule takes over.
_SWEEPS = 50


def footing_schur(A: np.ndarray, b: np.ndarray, free: np.ndarray):
    """(K_q, o) of the footing after eliminating the story DOF (the last of z = (u, v, θ, s))
    from A z + b + [Lᵀ f_c; 0] = 0, restricted to the ``free`` footing components (bool (3,)):
    K_q q_f + o + L_fᵀ f_c = 0."""
    a_ss = A[3, 3]
    K = A[:3, :3] - np.outer(A[:3, 3], A[3, :3]) / a_ss
    o = b[:3] - A[:3, 3] * b[3] / a_ss
    return K[np.ix_(free, free)], o[free]


@nb.njit(cache=True)
def _solve_set(closed, gstar, d, L, Kq):
    """P on the ``closed`` nodes (0 elsewhere) with zero gaps there: (D + L K⁻¹ Lᵀ)_CC P_C =
    −g*_C by Woodbury, P_C = D_C⁻¹(−g*_C − L_C y), (K + L_Cᵀ D_C⁻¹ L_C) y = −L_Cᵀ D_C⁻¹ g*_C."""
    n, k = L.shape
    S = Kq.copy()
    rhs = np.zeros(k)
    for i in range(n):
        if closed[i]:
            w = 1.0 / d[i]
            for a in range(k):
                rhs[a] -= L[i, a] * gstar[i] * w
                for c in range(k):
                    S[a, c] += L[i, a] * L[i, c] * w
    y = np.linalg.solve(S, rhs)
    P = np.zeros(n)
    for i in range(n):
        if closed[i]:
            t = -gstar[i]
            for a in range(k):
                t -= L[i, a] * y[a]
            P[i] = t / d[i]
    return P


@nb.njit(cache=True)
def _gaps(P, gstar, d, L, Kinv):
    n, k = L.shape
    LP = np.zeros(k)
    for i in range(n):
        for a in range(k):
            LP[a] += L[i, a] * P[i]
    y = Kinv @ LP
    g = np.empty(n)
    for i in range(n):
        t = gstar[i] + d[i] * P[i]
        for a in range(k):
            t += L[i, a] * y[a]
        g[i] = t
    return g


@nb.njit(cache=True)
def normal_forces(gstar, d, L, Kq, closed):
    """Solve g = g* + W P ≥ 0, P ≥ 0, P g = 0 with W = diag(d) + L K_q⁻¹ Lᵀ (module docstring).

    ``gstar`` (n) gaps without contact forces, ``d`` (n) > 0, ``L`` (n, k), ``Kq`` (k, k) SPD;
    ``closed`` (n, bool) the guess, overwritten with the solution's set. Returns (P, g,
    iterations); g is exactly 0 (to round-off) on the closed set and P exactly 0 off it."""
    n = gstar.size
    Kinv = np.linalg.inv(Kq)
    scale = 0.0
    for i in range(n):
        scale += d[i]
    c = n / scale if scale > 0.0 else 1.0
    if not closed.any():
        for i in range(n):
            closed[i] = gstar[i] < 0.0
    least_index = False
    for iteration in range(1, 10 * n + _SWEEPS + 2):
        P = _solve_set(closed, gstar, d, L, Kq)
        g = _gaps(P, gstar, d, L, Kinv)
        top = 0.0
        for i in range(n):
            top = max(top, abs(P[i]), c * abs(gstar[i]))
        tol = 1e-12 * top
        first = -1
        changes = 0
        for i in range(n):
            want = P[i] - c * g[i] > tol if closed[i] else -c * g[i] > tol
            if want != closed[i]:
                changes += 1
                if first < 0:
                    first = i
        if changes == 0:
            return P, g, iteration
        if iteration > _SWEEPS:
            least_index = True
        if least_index:
            closed[first] = not closed[first]
        else:
            for i in range(n):
                closed[i] = P[i] - c * g[i] > tol if closed[i] else -c * g[i] > tol
    raise RuntimeError("normal contact forces: the active set did not settle")


@nb.njit(cache=True)
def frictionless_step(A, b, free, Lf, uy, u, u_next, v_next, m_eff, h, dt, closed):
    """The frictionless contact of one step (module docstring), applied in place: the soil's
    ``u_next``, ``v_next`` at the footing's u_y DOFs ``uy`` get the normal forces' effect.
    ``A``, ``b`` (4, 4), (4): the footing and story form; ``free`` the footing's free
    components (int, of u, v, θ); ``Lf`` (n, len(free)) their kinematics at the nodes;
    ``closed`` the warm start, overwritten. Returns (P, q (3) at n+1, story s at n+1,
    iterations)."""
    a_ss = A[3, 3]
    K = A[:3, :3] - np.outer(A[:3, 3], A[3, :3]) / a_ss
    o = b[:3] - A[:3, 3] * b[3] / a_ss
    k = free.size
    Kq = np.empty((k, k))
    of = np.empty(k)
    for i in range(k):
        of[i] = o[free[i]]
        for j in range(k):
            Kq[i, j] = K[free[i], free[j]]
    q_star = -np.linalg.solve(Kq, of)
    n = uy.size
    gstar = Lf @ q_star
    d = np.empty(n)
    for i in range(n):
        gstar[i] -= u_next[uy[i]]
        d[i] = h / m_eff[uy[i]]
    P, g, its = normal_forces(gstar, d, Lf, Kq, closed)
    qf = q_star + np.linalg.solve(Kq, Lf.T @ P)
    q = np.zeros(3)
    for i in range(k):
        q[free[i]] = qf[i]
    for i in range(n):
        j = uy[i]
        u_next[j] -= d[i] * P[i]
        v_next[j] = (u_next[j] - u[j]) / dt
    s = -(A[3, 0] * q[0] + A[3, 1] * q[1] + A[3, 2] * q[2] + b[3]) / a_ss
    return P, q, s, its


@nb.njit(cache=True)
def _tangential_system(s, uc, q, slip0, x, prescribed, target, Kq, rq, mu, status):
    """The linear system of :func:`~upliftlab.continuum.contact.footing.solve_contact` for the sets
    ``status`` with a diagonal soil S = diag(s) and r = 0 (contact DOFs: u_y then u_x of
    each node; unknowns Δu_c then Δq)."""
    n = x.size
    m = 2 * n
    A = np.zeros((m + 3, m + 3))
    b = np.zeros(m + 3)
    for i in range(n):
        closed = status[i] != OPEN
        t = n + i
        if closed:  # zero gap after the step: Δuy − (Δv − x Δθ) = (v − x θ) − uy
            A[i, i] = 1.0
            A[i, m + 1] = -1.0
            A[i, m + 2] = x[i]
            b[i] = q[1] - x[i] * q[2] - uc[i]
        else:  # no normal force
            A[i, i] = s[i]
        if status[i] == STICK:  # no slip relative to the start of the step
            A[t, t] = 1.0
            A[t, m] = -1.0
            b[t] = slip0[i] - (uc[t] - q[0])
        elif status[i] == OPEN:
            A[t, t] = s[t]
        else:  # slip: T + μ σ (−P) ... f_x + μ σ f_y = 0
            sign = 1.0 if status[i] == SLIP_POSITIVE else -1.0
            A[t, t] = s[t]
            A[t, i] = mu * sign * s[i]
    for k in range(3):
        row = m + k
        if prescribed[k]:
            A[row, row] = 1.0
            b[row] = target[k] - q[k]
        else:
            for i in range(n):
                if k == 0:
                    A[row, n + i] = s[n + i]
                elif k == 1:
                    A[row, i] = s[i]
                else:
                    A[row, i] = -x[i] * s[i]
            for j in range(3):
                A[row, m + j] += Kq[k, j]
            b[row] = target[k] - rq[k]
    return A, b


@nb.njit(cache=True)
def _tangential_sets(s, uc, q, slip0, x, mu, width, duc, dq, force):
    n = x.size
    c_n = 0.0
    c_t = 0.0
    top = 0.0
    for i in range(n):
        c_n += abs(s[i]) / n
        c_t += abs(s[n + i]) / n
    for j in range(2 * n):
        top = max(top, abs(force[j]))
    tol = RTOL_CONTACT * max(top, 1e-6 * c_n * width)
    status = np.empty(n, dtype=np.int8)
    for i in range(n):
        pressure = -force[i]
        gap = (q[1] + dq[1]) - x[i] * (q[2] + dq[2]) - (uc[i] + duc[i])
        if pressure - c_n * gap >= -tol:
            trial = force[n + i] - c_t * ((uc[n + i] + duc[n + i] - q[0] - dq[0]) - slip0[i])
            if abs(trial) > mu * pressure + tol:
                status[i] = SLIP_POSITIVE if trial > 0.0 else SLIP_NEGATIVE
            else:
                status[i] = STICK
        else:
            status[i] = OPEN
    return status


@nb.njit(cache=True)
def tangential_step(s, uc, q, slip0, x, prescribed, target, Kq, rq, mu, width, status):
    """:func:`~upliftlab.continuum.contact.footing.solve_contact` compiled for the explicit step's
    diagonal soil S = diag(``s``) (r = 0): a bonded (μ = 1000) or Coulomb interface. Contact
    DOFs are u_y then u_x of the nodes at ``x``; ``status`` (int8) is the warm start,
    overwritten. As there, a set seen before switches to Murty's least-index rule. Returns
    (Δu_c, Δq, the forces on the soil S Δu_c, iterations)."""
    n = x.size
    m = 2 * n
    any_closed = False
    for i in range(n):
        any_closed = any_closed or status[i] != OPEN
    if not any_closed:
        status[:] = STICK
    least_index = False
    limit = 100 + 10 * n
    seen = np.empty((limit, n), dtype=np.int8)
    for iteration in range(1, limit + 1):
        A, b = _tangential_system(s, uc, q, slip0, x, prescribed, target, Kq, rq, mu, status)
        z = np.linalg.solve(A, b)
        duc, dq = z[:m], z[m:]
        force = s * duc
        new = _tangential_sets(s, uc, q, slip0, x, mu, width, duc, dq, force)
        first = -1
        for i in range(n):
            if new[i] != status[i]:
                first = i
                break
        if first < 0:
            return duc, dq, force, iteration
        for j in range(iteration - 1):  # a set seen before: the sets cycle
            if not least_index and np.array_equal(seen[j], new):
                least_index = True
        seen[iteration - 1] = new
        if least_index:
            status[first] = new[first]
        else:
            status[:] = new
    raise RuntimeError("tangential contact forces: the active set did not settle")
