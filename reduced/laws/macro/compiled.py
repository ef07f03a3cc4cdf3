"""The macro-element's bounding-surface update, compiled (numba, ``cache=True``), on the
forms of :mod:`.bed_forms` (uplift) and :mod:`.surface_forms` (failure surface), with the
slots of :mod:`.slots`; :mod:`.plastic` is its readable entry point (the equations are
there), and each function's ``.py_func`` is its interpreted reference. Every compiled form of
the law is found here by name, so that the reduced model's kernels import one module.

A step that cannot be completed returns a status (``STEP_…``), never a number. The update
(:func:`step_into`) allocates nothing: its vectors are slots of a scratch array (``W_COUNT``
floats), so that the reduced model's compiled loops, which never allocate, can call it.
:func:`step` is the allocating entry point for everything else.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..spring import HOT
from .bed_forms import (bed, bed_energy, bed_length, bed_moments, contact, elastic,  # noqa: F401
                        flat_bed_displacement, rounding_force, rounding_sensitivity, solve2,
                        vertical_rocking)
from .slots import (MAX_NEWTON, P_B, P_CEXP, P_CHI, P_COUNT, P_CXT, P_CXV,  # noqa: F401
                    P_DIL, P_GEXP, P_H0, P_KH, P_KREF, P_KV, P_KW, P_MEM, P_RHO, P_VU, P_Z0,
                    S_C, S_COUNT, S_D, S_KAPPA, S_MEM, S_P, S_Q, S_ROUND, S_W, STEP_CONTACT,
                    STEP_FLOW, STEP_OK, STEP_SUBSTEPS, STEP_SURFACE, W_CENTRE, W_COUNT, W_DE,
                    W_DE0, W_DIR, W_FLOW, W_G, W_NORMAL, W_PLASTIC, W_Q, W_Q0, W_START,
                    W_TARGET, W_TRIAL, pack)
from .surface_forms import (RIDGE, failure, failure_at, failure_gradient,  # noqa: F401
                            failure_size_derivative, failure_value, horizontal_capacity,
                            image, mobilisation, moment_capacity, size)

__all__ = ["pack", "P_COUNT", "S_COUNT", "W_COUNT", "STEP_OK", "STEP_CONTACT",
           "STEP_SURFACE", "STEP_SUBSTEPS", "STEP_FLOW", "RIDGE", "MAX_NEWTON", "MAX_SUBSTEPS",
           "step", "step_into"]

MAX_SUBSTEPS = 200_000
#: The share of nᵀDn the flow's settlement beyond the normal's may take from the load's
#: stiffness along the flow (:func:`_held_flow`).
FLOW_MARGIN = 0.5


@njit(cache=True, **HOT)
def plastic_modulus(P, kappa, load, flow_v, s, zeta, memory):
    """K_p at distance ratio s: the bounding surface's K_b (its ∂F/∂ζ at ``load``) plus the
    interior term times ``memory`` (:func:`memory_factor`, 1 outside the memory): the memory
    stiffens the interior term only, which vanishes at the surface, so that a load that
    reaches the surface does so at the surface's own modulus."""
    grow = (1.0 - P[P_Z0]) / P[P_KREF] * math.exp(-kappa / P[P_KREF])
    bound = -failure_size_derivative(P, load, zeta) * grow * max(flow_v, 0.0)
    if s <= 0.0:
        return math.inf
    if s >= 1.0:
        return bound
    interior = P[P_H0] * P[P_KV] / P[P_VU] ** 2
    return bound + memory * interior * ((1.0 - s) / s) ** P[P_GEXP]


@njit(cache=True, **HOT)
def memory_factor(P, mobilised, at_centre, remembered):
    """1 + μ w: the interior modulus's factor for a load of mobilisation ``mobilised`` whose
    side remembers ``remembered`` and whose projection centre is at ``at_centre``, w =
    (ζ_m − ζ_Q)/(ζ_m − ζ_c) the share of the way from the load back to its reversal: 1 + μ
    at the reversal, falling to 1 as the load reaches its side's memory (continuous, so that
    the update stays a continuous function of the displacement), 1 beyond it or where the
    centre lies beyond the memory."""
    if P[P_MEM] == 0.0 or not mobilised < remembered or not at_centre < remembered:
        return 1.0
    return 1.0 + P[P_MEM] * min((remembered - mobilised) / (remembered - at_centre), 1.0)


@njit(cache=True, **HOT)
def settlement_flow(P, normal, s):
    """The flow's settlement part m_V at a load whose surface's normal is ``normal`` and whose
    distance ratio is ``s``: n_V where the normal points to more V, δ n_V where it points to
    less (δ the flow's dilatancy), plus χ s^ε |(n_H, B n_M)| (the settlement coupling)."""
    flow = normal[0] if normal[0] >= 0.0 else P[P_DIL] * normal[0]
    weight = 1.0 if P[P_CEXP] == 0.0 else s ** P[P_CEXP]
    return flow + P[P_CHI] * weight * math.hypot(normal[1], normal[2] * P[P_B])


@njit(cache=True, **HOT)
def _held_flow(D, normal, flow_v):
    """The flow's settlement part ``flow_v`` held so that the load keeps its stiffness along
    the flow: the part beyond the normal's, a = m_V − n_V, lowers nᵀDm by a (−nᵀD e_V) where
    that is negative, and is kept to at most half of nᵀDn's worth, so that
    K_p + nᵀDm ≥ K_p + ½ nᵀDn > 0 (D the trial's tangent, positive definite)."""
    extra = flow_v - normal[0]
    if extra <= 0.0:
        return flow_v
    nDn, nDe = 0.0, 0.0
    for i in range(3):
        nDe += normal[i] * D[i, 0]
        for j in range(3):
            nDn += normal[i] * D[i, j] * normal[j]
    if nDe < 0.0 and extra * -nDe > FLOW_MARGIN * nDn:
        return normal[0] + FLOW_MARGIN * nDn / -nDe
    return flow_v


@njit(cache=True, **HOT)
def _rounding_force(P, de, Q, rho):
    """F_ρ of the bed at elastic displacement ``de`` carrying ``Q`` (the bed's own displacement
    is de less the remainder's C_x Q)."""
    return rounding_force(P[P_KW], 0.5 * P[P_B], de[0] - P[P_CXV] * Q[0],
                          de[2] - P[P_CXT] * Q[2], rho)


@njit(cache=True, **HOT)
def _rounding_forces(P, de, Q, rho, g):
    """∂Q/∂ρ at fixed elastic displacement ``de`` (carrying Q) into ``g``: the bed's own,
    through the series with the remainder, (I + K_b C_x)⁻¹ ∂(N, M)_bed/∂ρ."""
    k, b, cv, ct = P[P_KW], 0.5 * P[P_B], P[P_CXV], P[P_CXT]
    v, theta = de[0] - cv * Q[0], de[2] - ct * Q[2]
    _, _, k11, k12, k22 = bed(k, b, v, theta, rho)
    h0, h2 = rounding_sensitivity(k, b, v, theta, rho)
    g[0], g[2] = solve2(1.0 + k11 * cv, k12 * ct, k12 * cv, 1.0 + k22 * ct, h0, h2)
    g[1] = 0.0


@njit(cache=True, **HOT)
def _invert(P, W, de, rho):
    """The elastic (v, θ) in ``de`` (from its value) at which the mechanism on a surface
    rounded by ρ carries W_Q's (V, M): Newton's method, each step halved until the residual
    falls with the bed still in contact. Returns whether it converged."""
    target_n, target_m, scale = W[W_Q], W[W_Q + 2], P[P_VU]
    n, m, t00, t01, t10, t11, _, ok = vertical_rocking(P, de[0], de[2], target_n, target_m, rho)
    for _ in range(MAX_NEWTON):  # from the flat bed's answer, settle until the rounded one bears
        if not ok or t00 * t11 - t01 * t10 > 0.0:
            break
        de[0] += rho
        n, m, t00, t01, t10, t11, _, ok = vertical_rocking(P, de[0], de[2], n, m, rho)
    r0, r1 = n - target_n, (m - target_m) / P[P_B]
    for _ in range(MAX_NEWTON):
        size0 = abs(r0) + abs(r1)
        if ok and size0 <= 1e-12 * scale:
            return True
        det = t00 * t11 - t01 * t10
        if not ok or det <= 0.0:
            return False
        d0, d2 = solve2(t00, t01, t10, t11, r0, r1 * P[P_B])
        v0, th0, step = de[0], de[2], 1.0
        for _ in range(40):
            de[0], de[2] = v0 - step * d0, th0 - step * d2
            n, m, t00, t01, t10, t11, _, ok = vertical_rocking(P, de[0], de[2], n, m, rho)
            r0, r1 = n - target_n, (m - target_m) / P[P_B]
            if ok and abs(r0) + abs(r1) < size0 and t00 * t11 - t01 * t10 > 0.0:
                break  # smaller, and still in contact (the load is carried somewhere)
            step *= 0.5
    return False


@njit(cache=True, **HOT)
def _return_to_surface(P, W, target, zeta, D, rho):
    """The forces W_Q beyond the surface returned radially towards (ζ V_ult/2, 0, 0), and the
    plastic displacement W_PLASTIC that leaves the elastic part carrying them (the mechanism
    inverted in closed form on a flat surface, by :func:`_invert` on a rounded one). Returns
    the status."""
    inner = 0.5 * zeta * P[P_VU]
    for i in range(3):
        W[W_DIR + i] = W[W_Q + i] - (inner if i == 0 else 0.0)
        W[W_TRIAL + i] = inner if i == 0 else 0.0  # W_TRIAL holds the inner point here
    t, found = image(P, W[W_TRIAL:W_TRIAL + 3], W[W_DIR:W_DIR + 3], zeta)
    if not found:
        return STEP_SURFACE
    for i in range(3):
        W[W_Q + i] = W[W_TRIAL + i] + t * W[W_DIR + i]
    de = W[W_DE:W_DE + 3]
    de[1] = W[W_Q + 1] / P[P_KH]
    k, b = P[P_KW], 0.5 * P[P_B]
    v, theta = flat_bed_displacement(k, b, W[W_Q], W[W_Q + 2])  # exact for a flat surface
    de[0], de[2] = v + P[P_CXV] * W[W_Q], theta + P[P_CXT] * W[W_Q + 2]
    if rho > 0.0 and not _invert(P, W, de, rho):
        return STEP_CONTACT
    for i in range(3):
        W[W_PLASTIC + i] = target[i] - de[i]
    _, ok = elastic(P, de, W[W_Q:W_Q + 3], W[W_Q:W_Q + 3], D, rho)
    return STEP_OK if ok else STEP_CONTACT


@njit(cache=True, **HOT)
def substep(P, S, target, D, W):
    """One sub-step of state S (in place) to total displacement ``target``; D is set to the
    tangent; W is scratch (``W_COUNT``). Returns a status."""
    Q0, trial = W[W_Q0:W_Q0 + 3], W[W_TRIAL:W_TRIAL + 3]
    centre = W[W_CENTRE:W_CENTRE + 3]
    normal, flow = W[W_NORMAL:W_NORMAL + 3], W[W_FLOW:W_FLOW + 3]
    plastic, Q, de = W[W_PLASTIC:W_PLASTIC + 3], W[W_Q:W_Q + 3], W[W_DE:W_DE + 3]
    de0, g = W[W_DE0:W_DE0 + 3], W[W_G:W_G + 3]
    rho = S[S_ROUND]
    for i in range(3):
        Q0[i] = S[S_Q + i]
        de0[i] = S[S_D + i] - S[S_P + i]  # the start's elastic displacement
        de[i] = target[i] - S[S_P + i]
        plastic[i] = S[S_P + i]
    _, ok = elastic(P, de, Q0, trial, D, rho)
    if not ok:
        return STEP_CONTACT
    for i in range(3):
        S[S_D + i] = target[i]
    if trial[0] <= 0.0:  # lifted off: no load, the sway free; what it stored is not returned
        stored, _ = elastic(P, de0, Q0, g, D, rho)
        work = stored
        for i in range(3):  # the work done on it over the sub-step, its force falling to 0
            work += 0.5 * Q0[i] * (target[i] - de0[i] - S[S_P + i])
        S[S_W] += work
        S[S_P + 1] = target[1]
        for i in range(3):
            S[S_Q + i] = 0.0
            for j in range(3):
                D[i, j] = 0.0
        return STEP_OK
    zeta = size(P, S[S_KAPPA])
    kappa = S[S_KAPPA]
    for i in range(3):
        Q[i] = trial[i]
    modulus, lam, rate, loading = math.inf, 0.0, 0.0, 0.0
    # the load the flow is taken at: the start's, or the trial's when the footing lands
    # (lifted off, it carried none)
    source = Q0 if Q0[0] > 0.0 else trial
    mobilised = mobilisation(P, source, zeta)
    if mobilised > 0.0:
        # the memory of the load's side (the sign of M): the largest mobilisation it reached
        side = S_MEM if source[2] >= 0.0 else S_MEM + 1
        remembered = S[side]
        S[side] = max(S[side], mobilised)
        # the normal, at the load, of the surface of the size that passes through it
        failure_gradient(P, source, mobilised, normal)
        loading = normal[0] * (trial[0] - Q0[0]) + normal[1] * (trial[1] - Q0[1]) \
            + normal[2] * (trial[2] - Q0[2])
        if loading < 0.0:  # the mobilisation falls: a reversal, the centre moves here
            for i in range(3):
                S[S_C + i] = Q0[i]
        for i in range(3):
            centre[i] = S[S_C + i]
            flow[i] = normal[i]
        at_centre = mobilisation(P, centre, zeta)
        span = zeta - at_centre
        s = 1.0 if mobilised >= zeta or span <= 1e-12 * zeta else \
            max(mobilised - at_centre, 0.0) / span
        flow[0] = _held_flow(D, normal, settlement_flow(P, normal, s))
        modulus = plastic_modulus(P, kappa, source, flow[0], s, zeta,
                                  memory_factor(P, mobilised, at_centre, remembered))
        if math.isfinite(modulus) and loading > 0.0:
            nDm = 0.0
            for i in range(3):
                for j in range(3):
                    nDm += normal[i] * D[i, j] * flow[j]
            if not modulus + nDm > 0.0:  # no stiffness along the flow: no multiplier
                return STEP_FLOW
            lam = loading / (modulus + nDm)
            force0 = _rounding_force(P, de0, Q0, rho)
            if force0 > 0.0:  # the edges pressed harder than the middle: the surface rounds
                rate = P[P_RHO] * 0.5 * P[P_B] * abs(flow[2])
            for i in range(3):
                plastic[i] = S[S_P + i] + lam * flow[i]
                de[i] = target[i] - plastic[i]
            rho += rate * lam
            _, ok = elastic(P, de, trial, Q, D, rho)
            if not ok:
                return STEP_CONTACT
            kappa += max(lam * flow[0], 0.0)
            zeta = size(P, kappa)
    if failure_value(P, Q, zeta) > 0.0:  # beyond the surface: returned radially onto it
        before = plastic[0]
        status = _return_to_surface(P, W, target, zeta, D, rho)
        if status != STEP_OK:
            return status
        kappa += max(plastic[0] - before, 0.0)
    work = 0.0
    if rho != S[S_ROUND]:
        work = 0.5 * (_rounding_force(P, de0, Q0, S[S_ROUND]) + _rounding_force(P, de, Q, rho)) \
            * (rho - S[S_ROUND])
    for i in range(3):
        work += 0.5 * (Q0[i] + Q[i]) * (plastic[i] - S[S_P + i])
    S[S_W] += work
    for i in range(3):
        S[S_P + i] = plastic[i]
        S[S_Q + i] = Q[i]
    S[S_KAPPA] = kappa
    S[S_ROUND] = rho
    if lam > 0.0 and math.isfinite(modulus):
        _rounding_forces(P, de, Q, rho, g)
        _plastic_tangent(D, normal, flow, modulus, g, rate)
    return STEP_OK


@njit(cache=True, **HOT)
def _plastic_tangent(D, normal, flow, modulus, g, rate):
    """The update's tangent, in place: D − (D m − r g) nᵀ D / (K_p + nᵀ D m), r g the
    rounding's share (dρ = r dλ, g = ∂Q/∂ρ at fixed elastic displacement); D left as it is
    where the denominator vanishes (the contact lost, the load perfectly plastic)."""
    a0 = D[0, 0] * flow[0] + D[0, 1] * flow[1] + D[0, 2] * flow[2]
    a1 = D[1, 0] * flow[0] + D[1, 1] * flow[1] + D[1, 2] * flow[2]
    a2 = D[2, 0] * flow[0] + D[2, 1] * flow[1] + D[2, 2] * flow[2]
    denominator = modulus + normal[0] * a0 + normal[1] * a1 + normal[2] * a2
    if not denominator > 0.0:
        return
    a0, a1, a2 = a0 - rate * g[0], a1 - rate * g[1], a2 - rate * g[2]
    nD0 = normal[0] * D[0, 0] + normal[1] * D[1, 0] + normal[2] * D[2, 0]
    nD1 = normal[0] * D[0, 1] + normal[1] * D[1, 1] + normal[2] * D[2, 1]
    nD2 = normal[0] * D[0, 2] + normal[1] * D[1, 2] + normal[2] * D[2, 2]
    D[0, 0] -= a0 * nD0 / denominator
    D[0, 1] -= a0 * nD1 / denominator
    D[0, 2] -= a0 * nD2 / denominator
    D[1, 0] -= a1 * nD0 / denominator
    D[1, 1] -= a1 * nD1 / denominator
    D[1, 2] -= a1 * nD2 / denominator
    D[2, 0] -= a2 * nD0 / denominator
    D[2, 1] -= a2 * nD1 / denominator
    D[2, 2] -= a2 * nD2 / denominator


@njit(cache=True, **HOT)
def substeps(P, S, target, max_force_step, D, W):
    """How many sub-steps a step of S to ``target`` takes (≥ 1; 0 if its elastic trial
    fails), so that none changes the trial force by more than ``max_force_step``
    (V_ult-scaled)."""
    for i in range(3):
        W[W_DE + i] = target[i] - S[S_P + i]
    _, ok = elastic(P, W[W_DE:W_DE + 3], S[S_Q:S_Q + 3], W[W_TRIAL:W_TRIAL + 3], D,
                    S[S_ROUND])
    if not ok:
        return 0
    vu = P[P_VU]
    largest = max(abs(W[W_TRIAL] - S[S_Q]) / vu, abs(W[W_TRIAL + 1] - S[S_Q + 1]) / vu,
                  abs(W[W_TRIAL + 2] - S[S_Q + 2]) / (P[P_B] * vu))
    return max(1, int(math.ceil(min(largest / max_force_step, 1e18))))


@njit(cache=True, **HOT)
def step_into(P, S, target, max_force_step, count, D, W):
    """State S (in place) moved to total displacement ``target`` in ``count`` equal sub-steps
    (0: as many as keep each within ``max_force_step`` of trial force, V_ult-scaled); D is
    set to the tangent; W is scratch (``W_COUNT``). Returns a status. Allocates nothing."""
    if count <= 0:
        count = substeps(P, S, target, max_force_step, D, W)
        if count == 0:
            return STEP_CONTACT
    if count > MAX_SUBSTEPS:
        return STEP_SUBSTEPS
    for i in range(3):
        W[W_START + i] = S[S_D + i]
    for k in range(1, count + 1):
        for i in range(3):
            W[W_TARGET + i] = W[W_START + i] + (target[i] - W[W_START + i]) * (k / count)
        status = substep(P, S, W[W_TARGET:W_TARGET + 3], D, W)
        if status != STEP_OK:
            return status
    return STEP_OK


@njit(cache=True)
def step(P, S, target, max_force_step, D):
    """:func:`step_into` with its own scratch and the automatic sub-step count."""
    return step_into(P, S, target, max_force_step, 0, D, np.empty(W_COUNT))
