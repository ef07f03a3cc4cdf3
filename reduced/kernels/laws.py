"""Every compiled form of the spring laws, dispatched on a spring's kind: the direct force in a
mode (:func:`force_in_mode`), the trial mode of a state (:func:`natural_mode`), the conditions
that bound a mode (:func:`condition`, least of them :func:`validity`, crossed
:func:`past_limit`), the switch at a located crossing (:func:`switch_mode`), the end-of-step
return map of the fixed-step integrators (:func:`commit_step`), the tangent of the implicit
integrators (:func:`tangent`), the affine coefficients the event stepper tabulates (:func:`law`),
the state read back for output (:func:`current_plastic`, :func:`spring_state`), and the trial
force of a law whose state is its history (:func:`from_history`, :func:`trial_force`).

The story spring (and the sway spring) is the kernels' own: elastic–perfectly plastic
``k(e − ep)`` capped at ±Fy, plus a parallel elastic ``kh·e`` (bilinear kinematic hardening)
and a dashpot ``c``; modes ELASTIC, YIELD_POS, YIELD_NEG. A foundation spring takes the forms
of its law, each written beside the law (:mod:`upliftlab.reduced.laws`): the elasto-plastic
springs (kinds UPLIFT and BONDED, also the elastic law's) in
:mod:`~upliftlab.reduced.laws.elastoplastic`, the hysteretic q–z spring (kind QZ), which keeps
its whole state in its history, in :mod:`~upliftlab.reduced.laws.qz.compiled`: the forms that
take the history dispatch to it, the fixed-step and implicit integrators take its
:func:`trial_force`, and the event stepper refuses it. A law with compiled forms of its own
adds its kind here. ``tests/test_reduced_law_forms.py`` drives random states through every form
and checks that they agree.
"""

from __future__ import annotations

from numba import njit

from ..laws import elastoplastic
from ..laws.qz.compiled import QZ, qz_commit, qz_force, qz_mode, qz_spring_state
from .codes import ELASTIC, HOT, N_CONDITIONS, ROUNDING, STORY, SWITCH_TOL, YIELD_NEG, YIELD_POS


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
    return elastoplastic.force_in_mode(mode, p, e, ed, ep, imp)


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
    return elastoplastic.natural_mode(p, e, ed, ep, imp)


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
    return elastoplastic.validity(mode, p, e, ed, h)


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
    return elastoplastic.switch_mode(mode, p, e, ed, h)


@njit(cache=True)
def commit_step(p, e, ed, h, was_contact):
    """End-of-step update for fixed-step integrators: return mapping, recontact, impact lock.

    Returns (plastic work of the step, contact flag 0/1).
    """
    if p.kind == QZ:
        work = qz_commit(p, h, p.zs + e)
        return work, (0 if h.zg < 0.0 else 1)
    if p.kind == STORY:
        ep = h.ep
        fep = p.k * (e - ep)
        if fep > p.fy:
            h.ep = e - p.dy
        elif fep < -p.fy:
            h.ep = e + p.dy
        return (p.fy * abs(h.ep - ep) if h.ep != ep else 0.0), 1
    return elastoplastic.commit_step(p, e, ed, h, was_contact)


@njit(cache=True)
def tangent(mode, p, imp):
    """Tangent stiffness and damping (dF/de, dF/dė) in a mode, for implicit integration."""
    if p.kind == STORY:
        return p.kh + (p.k if mode == ELASTIC else 0.0), p.c
    return elastoplastic.tangent(mode, p, imp)


@njit(cache=True)
def condition(k, mode, p, hist):
    """Condition k of a spring's mode as (α, β, γ): the spring stays in its mode while
    α + β e + γ ė ≥ 0. :func:`validity` is the least of them; a k the mode does not use gives
    the constant 1. Story: the two yield limits, or the rate; a foundation spring: its law's
    (:func:`upliftlab.reduced.laws.elastoplastic.condition`)."""
    if p.kind == STORY:
        one = (1.0, 0.0, 0.0)
        if mode == ELASTIC:
            s = p.k * p.gs
            if k == 0:
                return 1.0 + s * hist.ep, -s, 0.0
            return (1.0 - s * hist.ep, s, 0.0) if k == 1 else one
        if k == 0:
            return 0.0, 0.0, (1.0 if mode == YIELD_POS else -1.0)
        return one
    return elastoplastic.condition(k, mode, p, hist)


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
    return elastoplastic.law(mode, p, hist)


@njit(cache=True)
def current_plastic(mode, p, e, ep):
    """Plastic deformation now: while yielding, the committed value lags and e sets it."""
    if p.kind == STORY:
        if mode == YIELD_POS:
            return e - p.dy
        if mode == YIELD_NEG:
            return e + p.dy
        return ep
    return elastoplastic.current_plastic(mode, p, e, ep)


@njit(cache=True, **HOT)
def spring_state(j, p, mode, h, e):
    """(plastic deformation now, spring force without its dashpot, strain energy) of spring j
    (foundation: total compression k d and ½ k d² while in contact)."""
    if p.kind == QZ:
        return qz_spring_state(p, h, e)
    if p.kind == STORY:
        ep = current_plastic(mode, p, e, h.ep)
        fep = p.k * (e - ep)
        return ep, p.kh * e + fep, 0.5 * p.kh * e * e + 0.5 * fep * (e - ep)
    return elastoplastic.spring_state(p, mode, h, e)


@njit(cache=True)
def trial_mode(p, h, e, ed):
    """The mode of a trial state from the committed history (:func:`natural_mode`, or the
    q–z spring's :func:`~upliftlab.reduced.laws.qz.compiled.qz_mode`)."""
    if p.kind == QZ:
        return qz_mode(p, h, e)
    return natural_mode(p, e, ed, h.ep, h.imp)


@njit(cache=True)
def from_history(p):
    """True for a spring whose trial force comes from its history alone (q–z), through
    :func:`trial_force`, rather than from its mode (fixed-step and implicit integrators)."""
    return p.kind == QZ


@njit(cache=True)
def trial_force(p, h, e, ed):
    """The trial force of a spring :func:`from_history`: (force increment, viscous power,
    dashpot force, dF/de, dF/dė, mode)."""
    return qz_force(p, h, e, ed)


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
