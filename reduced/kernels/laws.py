"""The spring laws, every form of each side by side: the direct force in a mode
(:func:`force_in_mode`), the trial mode of a state (:func:`natural_mode`), the conditions that
bound a mode (:func:`condition`, least of them :func:`validity`, crossed :func:`past_limit`),
the switch at a located crossing (:func:`switch_mode`), the end-of-step return map of the
fixed-step integrators (:func:`commit_step`), the tangent of the implicit integrators
(:func:`tangent`), the affine coefficients the event stepper tabulates (:func:`law`), and the
state read back for output (:func:`current_plastic`, :func:`spring_state`).

Two families, chosen by ``p.kind``: a story spring (elastic–perfectly plastic with parallel
hardening ``kh`` and a dashpot; modes ELASTIC, YIELD_POS, YIELD_NEG) and a foundation spring
(compression-only UPLIFT or BONDED, static compression F0, yield force Fy, viscous dashpot and
Ewing's impact dashpot; modes SEPARATED, CONTACT, YIELDING, CLIPPED). A third, the hysteretic
q–z spring (``QZ``, :mod:`.qz_law`), keeps its whole state in its history: the forms that take
the history (:func:`commit_step`, :func:`spring_state`, :func:`trial_mode`) dispatch to it, and
the integrators that accept it call its force and tangent directly; the event stepper refuses
it. :mod:`..springs` documents
the laws and exports them; ``tests/test_reduced_law_forms.py`` drives random states through every
form and checks that they agree.
"""

from __future__ import annotations

from numba import njit

from .codes import (BONDED, CLIPPED, CONTACT, ELASTIC, HOT, N_CONDITIONS, QZ, ROUNDING, SEPARATED,
                    STORY, SWITCH_TOL, UPLIFT, YIELDING, YIELD_NEG, YIELD_POS)
from .qz_law import qz_commit, qz_mode, qz_spring_state


@njit(cache=True)
def force_in_mode(mode, p, e, ed, ep, imp):
    """Force conjugate to e in a mode, and where its work goes.

    Returns (force, viscous power, impact power, plastic power, dashpot force, impact share):
    the story shear, or the foundation force increment F − F0 over the static compression.
    """
    if p.kind == STORY:
        fd = p.c * ed
        if mode == ELASTIC:
            return p.kh * e + p.k * (e - ep) + fd, fd * ed, 0.0, 0.0, fd, 0.0
        fep = p.fy if mode == YIELD_POS else -p.fy
        return p.kh * e + fep + fd, fd * ed, 0.0, fep * ed, fd, 0.0
    if mode == SEPARATED:
        return -p.f0, 0.0, 0.0, 0.0, 0.0, 0.0
    plastic = 0.0
    if mode == YIELDING:
        fs = p.fy
        plastic = fs * ed
    else:
        fs = p.k * (p.d0 + e - ep)
    if mode == CLIPPED:
        fd = -fs
    else:
        fd = (p.c + p.cimp * imp) * ed
    power = fd * ed
    share = p.share * imp
    return fs + fd - p.f0, power * (1.0 - share), power * share, plastic, fd, share


@njit(cache=True)
def natural_mode(p, e, ed, ep, imp):
    """The mode a trial state (e, ė) with committed history falls in (return-map predictor)."""
    if p.kind == STORY:
        fep = p.k * (e - ep)
        if fep > p.fy:
            return YIELD_POS
        if fep < -p.fy:
            return YIELD_NEG
        return ELASTIC
    d = p.d0 + e - ep
    if p.kind == UPLIFT and d <= 0.0:
        return SEPARATED
    fs = p.k * d
    yielding = fs > p.fy
    if yielding:
        fs = p.fy
    if p.kind == UPLIFT and fs + (p.c + p.cimp * imp) * ed < 0.0:
        return CLIPPED
    return YIELDING if yielding else CONTACT


@njit(cache=True)
def validity(mode, p, e, ed, h):
    """How far a spring is inside its mode: ≥ 0 valid, < 0 means a switch was crossed.

    Force conditions are scaled by F0 (story: Fy), displacement conditions by δ0, so that the
    location tolerance means the same for every spring; velocity conditions (unloading from
    yield) are left in length/s, since only their sign matters.
    """
    if p.kind == STORY:
        if mode == ELASTIC:
            return 1.0 - abs(p.k * (e - h.ep)) * p.gs
        return ed if mode == YIELD_POS else -ed
    d = e + p.d0 - h.ep
    g = (h.dz - (e - h.e0)) * p.gd if h.imp > 0.0 else 1.0
    if mode == SEPARATED:
        return min(g, -d * p.gd)
    if mode == YIELDING:
        return min(g, ed)
    if p.kind == BONDED:
        return min(g, (p.fy - p.k * d) * p.gs)
    force = (p.k * d + (p.c + p.cimp * h.imp) * ed) * p.gs
    if mode == CLIPPED:
        return min(g, d * p.gd, -force)
    return min(g, d * p.gd, (p.fy - p.k * d) * p.gs, force)


@njit(cache=True)
def past_limit(mode, p, e, ed, h):
    """True if a spring has crossed a limit of its mode: one of its conditions α + β e + γ ė
    (:func:`condition`) below −SWITCH_TOL by more than its rounding, ROUNDING times the size
    of its terms. The crossing search (:func:`column_crossing`) allows the same."""
    for k in range(N_CONDITIONS):
        alpha, beta, gamma = condition(k, mode, p, h)
        value = alpha + beta * e + gamma * ed
        size = abs(alpha) + abs(beta * e) + abs(gamma * ed)
        if value + ROUNDING * size < -SWITCH_TOL:
            return True
    return False


@njit(cache=True)
def switch_mode(mode, p, e, ed, h):
    """Switch a spring whose mode was crossed; updates its history ``h``; returns the new mode.

    Called at the located switch time, so the state is continuous: only the law changes.
    Plastic deformation is committed so that the force is continuous, and the new mode is
    always valid for the state it leaves (a spring that grazed its yield force and turned within
    the location tolerance gets the infinitesimal plastic step that puts it back on the limit).
    """
    if p.kind == STORY:
        if mode == ELASTIC:
            if e - h.ep > 0.0:
                h.ep = e - p.dy
                return YIELD_POS
            h.ep = e + p.dy
            return YIELD_NEG
        h.ep = e - p.dy if mode == YIELD_POS else e + p.dy
        return ELASTIC
    if h.imp > 0.0 and e - h.e0 >= h.dz:
        h.imp = 0.0  # the impact damper has run its stroke: lock
    if mode == YIELDING:
        if ed >= 0.0:
            return YIELDING  # still loading: only the impact damper changed
        h.ep = e + p.d0 - p.dy  # unloading: commit the plastic settlement
    d = e + p.d0 - h.ep
    if p.kind == UPLIFT and d <= 0.0:
        h.imp = 0.0
        return SEPARATED
    if mode == SEPARATED and p.dzf > 0.0:
        h.imp = 1.0  # recontact: the impact damper acts for Δz = v₀·m_eff(1 − ε)/c*
        h.e0 = e
        h.dz = p.dzf * max(ed, 0.0)
    if p.k * d >= p.fy:
        h.ep = e + p.d0 - p.dy
        d = p.dy
        if ed > 0.0:
            return YIELDING
    if p.kind == UPLIFT and p.k * d + (p.c + p.cimp * h.imp) * ed < 0.0:
        return CLIPPED
    return CONTACT


@njit(cache=True)
def commit_step(p, e, ed, h, was_contact):
    """End-of-step update for fixed-step integrators: return mapping, recontact, impact lock.

    Returns (plastic work of the step, contact flag 0/1).
    """
    if p.kind == QZ:
        work = qz_commit(p, h, p.zs + e)
        return work, (0 if h.zg < 0.0 else 1)
    ep = h.ep
    if p.kind == STORY:
        fep = p.k * (e - ep)
        if fep > p.fy:
            h.ep = e - p.dy
        elif fep < -p.fy:
            h.ep = e + p.dy
        return (p.fy * abs(h.ep - ep) if h.ep != ep else 0.0), 1
    d = e + p.d0 - ep
    if p.kind == UPLIFT and d <= 0.0:
        h.imp = 0.0
        return 0.0, 0
    work = 0.0
    if p.k * d > p.fy:
        h.ep = e + p.d0 - p.dy
        work = p.fy * (h.ep - ep)
    if was_contact == 0 and p.dzf > 0.0:
        h.imp = 1.0
        h.e0 = ep - p.d0  # the deformation at which the spring touched the surface
        h.dz = p.dzf * max(ed, 0.0)
    elif h.imp > 0.0 and e - h.e0 >= h.dz:
        h.imp = 0.0
    return work, 1


@njit(cache=True)
def tangent(mode, p, imp):
    """Tangent stiffness and damping (dF/de, dF/dė) in a mode, for implicit integration."""
    if p.kind == STORY:
        return p.kh + (p.k if mode == ELASTIC else 0.0), p.c
    if mode == SEPARATED or mode == CLIPPED:
        return 0.0, 0.0
    return (0.0 if mode == YIELDING else p.k), p.c + p.cimp * imp


@njit(cache=True)
def condition(k, mode, p, hist):
    """Condition k of a spring's mode as (α, β, γ): the spring stays in its mode while
    α + β e + γ ė ≥ 0. :func:`validity` is the least of them; a k the mode does not use gives
    the constant 1. Foundation condition 0 is the impact stroke; the others, by mode: gap
    (separated); loading rate (yielding); contact, yield, compression (contact); contact,
    tension of the clipped force (clipped). Story: the two yield limits, or the rate."""
    one = (1.0, 0.0, 0.0)
    if p.kind == STORY:
        if mode == ELASTIC:
            s = p.k * p.gs
            if k == 0:
                return 1.0 + s * hist.ep, -s, 0.0
            return (1.0 - s * hist.ep, s, 0.0) if k == 1 else one
        if k == 0:
            return 0.0, 0.0, (1.0 if mode == YIELD_POS else -1.0)
        return one
    if k == 0:
        return ((hist.dz + hist.e0) * p.gd, -p.gd, 0.0) if hist.imp > 0.0 else one
    r = p.d0 - hist.ep  # d = e + r
    cd = (p.c + p.cimp * hist.imp) * p.gs
    if mode == SEPARATED:
        return (-r * p.gd, -p.gd, 0.0) if k == 1 else one
    if mode == YIELDING:
        return (0.0, 0.0, 1.0) if k == 1 else one
    if p.kind == BONDED:
        return ((p.fy - p.k * r) * p.gs, -p.k * p.gs, 0.0) if k == 1 else one
    if k == 1:
        return r * p.gd, p.gd, 0.0
    if mode == CLIPPED:
        return (-p.k * r * p.gs, -p.k * p.gs, -cd) if k == 2 else one
    if k == 2:
        return (p.fy - p.k * r) * p.gs, -p.k * p.gs, 0.0
    return (p.k * r * p.gs, p.k * p.gs, cd) if k == 3 else one


@njit(cache=True)
def law(mode, p, hist):
    """A spring's law in a mode, in the affine form of :func:`force_in_mode`: (K, C, F) of the
    force K e + C ė + F; (a, b, c) of the viscous power (a + b e + c ė) ė; the same for the
    impact dashpot; P of the plastic power P ė."""
    if p.kind == STORY:
        if mode == ELASTIC:
            return p.kh + p.k, p.c, -p.k * hist.ep, 0.0, 0.0, p.c, 0.0, 0.0, 0.0, 0.0
        fep = p.fy if mode == YIELD_POS else -p.fy
        return p.kh, p.c, fep, 0.0, 0.0, p.c, 0.0, 0.0, 0.0, fep
    if mode == SEPARATED:
        return 0.0, 0.0, -p.f0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    share = p.share * hist.imp
    cd = p.c + p.cimp * hist.imp
    if mode == CLIPPED:  # the dashpot cancels the spring: its power is −k d ė
        kr = -p.k * (p.d0 - hist.ep)
        return (0.0, 0.0, -p.f0, kr * (1.0 - share), -p.k * (1.0 - share), 0.0, kr * share,
                -p.k * share, 0.0, 0.0)
    if mode == YIELDING:
        return 0.0, cd, p.fy - p.f0, 0.0, 0.0, cd * (1.0 - share), 0.0, 0.0, cd * share, p.fy
    return (p.k, cd, p.k * (p.d0 - hist.ep) - p.f0, 0.0, 0.0, cd * (1.0 - share), 0.0, 0.0,
            cd * share, 0.0)


@njit(cache=True)
def current_plastic(mode, p, e, ep):
    """Plastic deformation now: while yielding, the committed value lags and e sets it."""
    if p.kind == STORY:
        if mode == YIELD_POS:
            return e - p.dy
        if mode == YIELD_NEG:
            return e + p.dy
        return ep
    if mode == YIELDING:
        return e + p.d0 - p.dy
    return ep


@njit(cache=True, **HOT)
def spring_state(j, p, mode, h, e):
    """(plastic deformation now, spring force without its dashpot, strain energy) of spring j
    (foundation: total compression k d and ½ k d² while in contact)."""
    if p.kind == QZ:
        return qz_spring_state(p, h, e)
    ep = current_plastic(mode, p, e, h.ep)
    if p.kind == STORY:
        fep = p.k * (e - ep)
        return ep, p.kh * e + fep, 0.5 * p.kh * e * e + 0.5 * fep * (e - ep)
    d = p.d0 + e - ep
    if mode == SEPARATED or (p.kind == UPLIFT and d <= 0.0):
        return ep, 0.0, 0.0
    return ep, p.k * d, 0.5 * p.k * d * d


@njit(cache=True)
def trial_mode(p, h, e, ed):
    """The mode of a trial state from the committed history (:func:`natural_mode`, or the
    q–z spring's :func:`.qz_law.qz_mode`)."""
    if p.kind == QZ:
        return qz_mode(p, h, e)
    return natural_mode(p, e, ed, h.ep, h.imp)


@njit(cache=True, **HOT)
def initial_modes(P, H, modes, e, ed):
    for j in range(e.size):
        modes[j] = trial_mode(P[j], H[j], e[j], ed[j])


@njit(cache=True, **HOT)
def commit_all(P, modes, H, contact, e, ed):
    """End-of-step return mapping of every spring (fixed-step methods); returns plastic work."""
    work = 0.0
    for j in range(e.size):
        w, contact[j] = commit_step(P[j], e[j], ed[j], H[j], contact[j])
        work += w
        modes[j] = trial_mode(P[j], H[j], e[j], ed[j])
    return work
