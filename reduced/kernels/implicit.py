"""The implicit integrators: Newmark average acceleration (``newmark``) and HHT-α (``hht``),
by Newton with a backtracking line search and step halving. The scheme's coefficients are
β = (1 − α)²/4, γ = 1/2 − α (:func:`integrate_newmark`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .base import accept_base, base_internal, base_tangent, committed_power
from .codes import (BASE_FAILED, E_IMPACT, E_INPUT, E_PLASTIC, E_VISCOUS, NONFINITE,
                    NO_CONVERGENCE, N_ACC, OK, OVERTURNED)
from .energy import check_energy, start_energy, static_strain_energy
from .fixed_step import end_fixed_step
from .interpolants import finite
from .laws import commit_all, force_in_mode, from_history, natural_mode, tangent, trial_force
from .motion import deformations, ground_acceleration
from .outputs import record
from .peaks import after_fixed_step, track_peaks


@njit(cache=True)
def internal_force(q, qd, P, KG, H, e, ed, fint, kt, ct, modes, fd, fimp):
    """Internal force A s + K_G q, spring tangents and trial modes (natural laws).

    Also fills ``fd`` (dashpot force of each spring) and ``fimp`` (the impact dashpot's share).
    Returns (viscous power, impact power).
    """
    n = q.size
    deformations(q, qd, P, e, ed)
    for i in range(n):
        fint[i] = 0.0
        for k in range(n):
            fint[i] += KG[i, k] * q[k]
    pv = 0.0
    pi = 0.0
    for j in range(e.size):
        p = P[j]
        h = H[j]
        if from_history(p):
            f, v, fd[j], kt[j], ct[j], modes[j] = trial_force(p, h, e[j], ed[j])
            fimp[j] = 0.0
            pv += v
        else:
            mode = natural_mode(p, e[j], ed[j], h.ep, h.imp)
            modes[j] = mode
            f, v, im, _, fd[j], fimp[j] = force_in_mode(mode, p, e[j], ed[j], h.ep, h.imp)
            pv += v
            pi += im
            kt[j], ct[j] = tangent(mode, p, h.imp)
        fint[p.i0] += p.a0 * f
        fint[p.i1] += p.a1 * f
        if p.nnz == 3:
            fint[p.i2] += p.a2 * f
    return pv, pi


@njit(cache=True)
def newmark_residual(t, h, start, scheme, system, H, modes, e, ed, tangents, end, R):
    """Residual of the HHT-α step at trial q₁ (fills q̇₁, q̈₁, f₁); returns (|R|∞, force scale).
    ``start`` and ``end`` are (q, q̇, q̈, f) at the step's ends, ``scheme`` (α, β, γ),
    ``tangents`` (k_t, c_t, dashpot force, impact share) of every spring."""
    q, qd, qdd, fint0 = start
    q1, qd1, qdd1, fint1 = end
    alpha, beta, gamma = scheme
    minv, P, KG, L, ag, dtg, _, _, _, _ = system
    kt, ct, fd, fimp = tangents
    n = q.size
    a0 = ground_acceleration(t, ag, dtg)
    a1 = ground_acceleration(t + h, ag, dtg)
    for i in range(n):
        qdd1[i] = (q1[i] - q[i] - h * qd[i]) / (beta * h * h) - (0.5 / beta - 1.0) * qdd[i]
        qd1[i] = qd[i] + h * ((1.0 - gamma) * qdd[i] + gamma * qdd1[i])
    internal_force(q1, qd1, P, KG, H, e, ed, fint1, kt, ct, modes, fd, fimp)
    base_internal(q1, qd1, system[9], fint1, R)  # R as scratch: it is filled below
    rnorm = 0.0
    scale = 0.0
    for i in range(n):
        inertia = qdd1[i] / minv[i]
        R[i] = (inertia + (1 + alpha) * fint1[i] - alpha * fint0[i]
                - (1 + alpha) * L[i] * a1 + alpha * L[i] * a0)
        rnorm = max(rnorm, abs(R[i]))
        scale = max(scale, abs(inertia), abs(fint1[i]), abs(L[i] * a1))
    return rnorm, scale


@njit(cache=True)
def newmark_jacobian(h, scheme, minv, P, KG, kt, ct, base, J):
    """J = M/(βh²) + (1+α)(A diag(k_t + γ c_t/(βh)) Aᵀ + K_G + Tᵀ (D + γ C_d/(βh)) T),
    ``scheme`` = (α, β, γ); the last term the base element's (:func:`.base.base_tangent`)."""
    alpha, beta, gamma = scheme
    n = minv.size
    for i in range(n):
        for k in range(n):
            J[i, k] = (1 + alpha) * KG[i, k]
        J[i, i] += 1.0 / (minv[i] * beta * h * h)
    for j in range(P.size):
        stiff = (1 + alpha) * (kt[j] + gamma / (beta * h) * ct[j])
        if stiff == 0.0:
            continue
        p = P[j]
        idx = (p.i0, p.i1, p.i2)
        val = (p.a0, p.a1, p.a2)
        for a in range(p.nnz):
            for b in range(p.nnz):
                J[idx[a], idx[b]] += val[a] * val[b] * stiff
    base_tangent(base, gamma / (beta * h), 1 + alpha, J)


@njit(cache=True)
def newmark_substep(t, h, start, scheme, system, H, modes, e, ed, tangents, newton, end):
    """One HHT-α step (α = 0: Newmark average acceleration) by Newton, from ``start`` to
    ``end`` (q, q̇, q̈, f of each; ``newton`` = (tol, fscale, max_iter)). Returns iterations or
    −1.

    Residual: M q̈₁ + (1+α) f(q₁, q̇₁) − α f(q₀, q̇₀) − (1+α) L a_g(t₁) + α L a_g(t₀) = 0,
    converged when its largest entry is below ``tol`` times the larger of ``fscale`` (the
    weights, m g) and the forces in play, or when the Newton update is at round-off. A
    backtracking line search on |R| stops the active set of the springs from cycling.
    """
    q, qd, qdd, _ = start
    q1 = end[0]
    beta = scheme[1]
    minv, P, KG, _, _, _, _, _, _, _ = system
    kt, ct, _, _ = tangents
    tol, fscale, max_iter = newton
    n = q.size
    R = np.zeros(n)
    J = np.zeros((n, n))
    trial = np.zeros(n)
    qscale = 1e-300
    for i in range(n):
        q1[i] = q[i] + h * qd[i] + h * h * (0.5 - beta) * qdd[i]
        qscale = max(qscale, abs(q[i]), abs(q1[i]))
    rnorm, scale = newmark_residual(t, h, start, scheme, system, H, modes, e, ed, tangents, end,
                                    R)
    for it in range(1, max_iter + 1):
        newmark_jacobian(h, scheme, minv, P, KG, kt, ct, system[9], J)
        dq = np.linalg.solve(J, R)
        step = 1.0
        trial[:] = q1
        for _ in range(8):
            for i in range(n):
                q1[i] = trial[i] - step * dq[i]
            new_norm, scale = newmark_residual(t, h, start, scheme, system, H, modes, e, ed,
                                               tangents, end, R)
            if new_norm <= rnorm or new_norm <= tol * max(scale, fscale):
                break
            step *= 0.5
        rnorm = new_norm
        update = 0.0
        for i in range(n):
            update = max(update, abs(step * dq[i]))
        if rnorm <= tol * max(scale, fscale) or update <= 1e-13 * qscale:
            return it
    return -1


@njit(cache=True)
def integrate_newmark(q0, qd0, clock, system, scheme, newton, max_halvings, outputs, peaks,
                      counters, H):
    """HHT-α (α in [−1/3, 0]; α = 0 is Newmark average acceleration), Newton, step halving;
    ``scheme`` = (α, β, γ) of :func:`upliftlab.time_schemes.hht` (β = (1 − α)²/4,
    γ = 1/2 − α; the step's own constants are formed here, as halving changes the step);
    ``newton`` = (tol, fscale, max_iter) (:data:`~.codes.NEWTON`).

    A step whose Newton iteration fails is split in halves, up to
    ``max_halvings`` times. ``counters`` = [step of failure, halvings, Newton iterations].
    Energy follows the scheme's own identity: the work of each force is the trapezoid
    ½(f₀ + f₁)·Δe over the step, so the balance of Newmark closes to the Newton tolerance away
    from switches; HHT's own numerical dissipation is what its balance leaves open.
    """
    dt, nsteps, _ = clock
    minv, P, KG, L, ag, dtg, _, frame, story, base = system
    ns, n = P.size, q0.size
    e, ed = np.zeros(ns), np.zeros(ns)
    e0, ed0, e1, ed1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    kt, ct = np.zeros(ns), np.zeros(ns)
    fd0, fimp0, fd1, fimp1 = np.zeros(ns), np.zeros(ns), np.zeros(ns), np.zeros(ns)
    q, qd = q0.copy(), qd0.copy()
    q1, qd1, qdd, qdd1 = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    fint0, fint1 = np.zeros(n), np.zeros(n)
    acc = np.zeros(N_ACC)
    modes = np.zeros(ns, dtype=np.int64)
    contact = np.ones(ns, dtype=np.int64)
    internal_force(q, qd, P, KG, H, e0, ed0, fint0, kt, ct, modes, fd0, fimp0)
    scratch = np.zeros(n)
    base_power0 = base_internal(q, qd, base, fint0, scratch)
    a0 = ground_acceleration(0.0, ag, dtg)
    for i in range(n):
        qdd[i] = (L[i] * a0 - fint0[i]) * minv[i]
    e_ref = static_strain_energy(P)
    books = (modes, H, e_ref, e, ed)
    record(0, 0.0, q, qd, acc, books, system, outputs)
    counters[4] = 1
    start_energy(q, qd, acc, books, system, peaks)
    start = (q, qd, qdd, fint0)
    end = (q1, qd1, qdd1, fint1)
    tangents = (kt, ct, fd1, fimp1)
    if after_fixed_step(0.0, q, P, H, e0, frame, story, peaks):
        return OVERTURNED  # released past its toppling angle: the initial row is the result
    for step in range(nsteps):
        t = step * dt
        t_end = (step + 1) * dt
        level = 0
        t_tol = 1e-9 * dt + 8.0 * np.finfo(np.float64).eps * t_end
        while t_end - t > t_tol:
            h = min(dt / 2.0**level, t_end - t)
            if t_end - (t + h) <= t_tol:
                h = t_end - t
            its = newmark_substep(t, h, start, scheme, system, H, modes, e, ed, tangents, newton,
                                  end)
            if its < 0:
                level += 1
                counters[1] += 1
                if level > max_halvings:
                    counters[0] = step
                    return NO_CONVERGENCE
                continue
            counters[2] += its
            deformations(q1, qd1, P, e1, ed1)
            track_peaks(h, (q, qd, e0, ed0), (q1, qd1, e1, ed1), P, modes, H, frame, peaks)
            ga0 = ground_acceleration(t, ag, dtg)
            ga1 = ground_acceleration(t + h, ag, dtg)
            for i in range(n):
                acc[E_INPUT] += 0.5 * (ga0 + ga1) * L[i] * (q1[i] - q[i])
            for j in range(ns):
                work = 0.5 * (fd0[j] + fd1[j]) * (e1[j] - e0[j])
                share = 0.5 * (fimp0[j] + fimp1[j])
                acc[E_VISCOUS] += work * (1.0 - share)
                acc[E_IMPACT] += work * share
            q[:] = q1
            qd[:] = qd1
            qdd[:] = qdd1
            e0[:] = e1
            ed0[:] = ed1
            # the next step starts from the forces this step converged with (pre-commit), as the
            # acceleration it carries does; the commit changes history, not these forces
            fint0[:] = fint1
            fd0[:] = fd1
            fimp0[:] = fimp1
            acc[E_PLASTIC] += commit_all(P, modes, H, contact, e0, ed0)
            if accept_base(q, base, acc, peaks) != 0:
                counters[0] = step
                return BASE_FAILED
            # the element's dashpots: the trapezoid of their power, at the committed end
            base_power1 = committed_power(q, qd, base)
            acc[E_VISCOUS] += 0.5 * (base_power0 + base_power1) * h
            base_power0 = base_power1
            t = t + h if t_end - (t + h) > t_tol else t_end
        if not finite(q, qd):
            counters[0] = step
            return NONFINITE
        if end_fixed_step(step, t_end, clock, q, qd, acc, books, e0, system, outputs, peaks,
                          counters) != OK:
            return OVERTURNED
    check_energy(q, qd, acc, books, system, peaks)
    return OK
