"""The elasto-plastic foundation law (Ewing's Cases B and C, Figs. 3b and 6): its springs at
rest, its builder, and its compiled forms — which are the elastic law's too (Fy = ∞).

A spring of kind ``UPLIFT`` (compression only) or ``BONDED`` (it also carries tension) has a
static compression F0 and a yield force Fy. Elastic compression ``d = F0/k + e − ep``: the
spring is in contact while ``d > 0`` — an elastic spring separates when its tension from static
exceeds the static compression; an elasto-plastic spring separates at that point shifted by its
plastic settlement ``ep``. The spring force ``k d`` is capped at Fy while loading, and the cap
accumulates ``ep``. A parallel dashpot ``c`` (plus Ewing's impact dashpot c* while active)
detaches with the spring, and the total force never pulls: it is clipped at zero while the
spring opens (as OpenSees ``QzSimple``). Contact ends when the displacement returns to the
(settled) surface, not when the force reaches zero. Impact damper (eqs. 10–17): on recontact
with closing velocity v₀ the dashpot c* acts over the stroke ``Δz = v₀ · m_eff (1 − ε)/c*``
(``dzf`` = m_eff (1 − ε)/c*), then locks. Modes: SEPARATED, CONTACT, YIELDING, CLIPPED.

The compiled forms are pure functions of (mode, parameters ``p``, deformation, rate, history
``h``), each for one integrator; :mod:`..kernels.laws` dispatches a spring to them by its kind.
``tests/test_reduced_law_forms.py`` drives random states through every form and checks that
they agree.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ...checks import InputError
from ...scenes.laws import ElastoplasticLaw
from ..compatibility import SpringLayout
from .base import Bed, Law
from .spring import CLIPPED, CONTACT, HOT, SEPARATED, YIELDING

__all__ = ["LAW", "UPLIFT", "BONDED", "springs", "support_kind", "static_forces",
           "bearing_yield_forces", "force_in_mode", "natural_mode", "validity", "switch_mode",
           "commit_step", "tangent", "condition", "law", "current_plastic", "spring_state"]

UPLIFT, BONDED = 1, 2  # compression only; also in tension


# ---------------------------------------------------------------------------------------------
# At rest, and the builder
# ---------------------------------------------------------------------------------------------


def support_kind(support: str) -> int:
    """The spring kind of a foundation's ``support``: UPLIFT or BONDED."""
    return UPLIFT if support == "uplift" else BONDED


def bearing_yield_forces(layout: SpringLayout, capacity: float) -> np.ndarray:
    """Yield forces of a bed with a uniform bearing capacity: ``capacity`` (force) shared over
    the springs' tributary widths, whatever their stiffness (the soil's bearing pressure does
    not grow where a bed is stiffened)."""
    return capacity * layout.widths / layout.widths.sum()


def static_forces(layout: SpringLayout, weight: float,
                  yield_forces: np.ndarray) -> tuple[np.ndarray, float]:
    """Spring compressions F0 at rest under W with each capped at its yield force, and the static
    rotation: the springs stiffer than the load's share reach their cap while the weight is
    applied and carry it there, the others share the rest elastically (with every cap infinite:
    the bonded equilibrium of an elastic bed). Piecewise linear in (θ, V), solved by adding the
    springs beyond their cap to the capped set (and taking back any that would unload) until the
    set holds."""
    k, x, fy = layout.stiffnesses, layout.positions, np.asarray(yield_forces, dtype=float)
    capped = np.zeros(k.size, dtype=bool)
    for _ in range(k.size + 1):
        ke, fc = np.where(capped, 0.0, k), np.where(capped, fy, 0.0)
        Kb = np.array([[np.sum(ke * x * x), -np.sum(ke * x)], [-np.sum(ke * x), np.sum(ke)]])
        if abs(np.linalg.det(Kb)) <= 1e-12 * max(np.sum(k * x * x) * np.sum(k), 1e-300):
            break
        # generalised forces on (θ, V) from compression F_i = k_i (x_i θ − V): −A F; gravity −W
        # on V; a capped spring's F_i = Fy_i moves to the right-hand side
        theta, v = np.linalg.solve(Kb, [-np.sum(fc * x), -(weight - np.sum(fc))])
        trial = k * (x * theta - v)
        now = np.where(capped, trial >= fy * (1.0 - 1e-12), trial > fy)
        if (now == capped).all():
            forces = np.where(capped, fy, trial)
            bad = np.flatnonzero(forces <= 0.0)
            if bad.size:
                i = bad[0]
                raise InputError(f"foundation spring {i} at x = {x[i]:g} would be in tension at "
                                 f"rest (F0 = {forces[i]:g}): the layout cannot carry the weight "
                                 "in compression")
            return forces, float(theta)
        capped = now
    raise InputError(f"foundation: the springs' yield forces (sum {fy.sum():g}) cannot carry the "
                     f"weight {weight:g} at rest with the springs below them sharing the rest; "
                     "valid: a bed whose springs below their cap can balance the load")


def elastic_static_forces(bed: Bed) -> tuple[np.ndarray, float]:
    """F0 of the bonded (elastic) bed at rest, and the static rotation."""
    return static_forces(bed.layout, bed.weight, np.full(bed.layout.stiffnesses.size, np.inf))


def springs(law: ElastoplasticLaw, bed: Bed, table: np.ndarray) -> tuple[np.ndarray, float]:
    """The bed's springs: yield at ``yield_multiple`` × the elastic F0; or at the given
    ``yield_forces`` or the uniform bearing capacity ``capacity_multiple`` · W, with F0 from the
    capped equilibrium (the springs that reach their yield force under the weight start at
    it)."""
    if law.yield_forces is not None:  # one per spring; a custom layout's follow its positions
        fy = bed.in_layout_order(law.yield_forces)
        F0, theta = static_forces(bed.layout, bed.weight, fy)
    elif law.capacity_multiple is not None:
        fy = bearing_yield_forces(bed.layout, law.capacity_multiple * bed.weight)
        F0, theta = static_forces(bed.layout, bed.weight, fy)
    else:
        F0, theta = elastic_static_forces(bed)
        fy = law.yield_multiple * F0
    table["kind"] = support_kind(bed.support)
    table["f0"] = F0
    table["fy"] = fy
    return table, theta


LAW = Law(record=ElastoplasticLaw, springs=springs, kinds=(UPLIFT, BONDED))


# ---------------------------------------------------------------------------------------------
# Compiled forms
# ---------------------------------------------------------------------------------------------


@njit(cache=True)
def force_in_mode(mode, p, e, ed, ep, imp):
    """Force increment F − F0 over the static compression in a mode, and where its work goes:
    (force, viscous power, impact power, plastic power, dashpot force, impact share)."""
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
    """How far a spring is inside its mode (≥ 0 valid): force conditions scaled by F0,
    displacement conditions by δ0, the unloading rate from yield in length/s."""
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
def switch_mode(mode, p, e, ed, h):
    """Switch a spring whose mode was crossed, at the located crossing; updates ``h``; returns
    the new mode, always valid for the state it leaves (plastic deformation is committed so
    that the force is continuous)."""
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
    """End-of-step return map of the fixed-step integrators: yield, recontact, impact lock.
    Returns (plastic work of the step, contact flag 0/1)."""
    ep = h.ep
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
    """Tangent stiffness and damping (dF/de, dF/dė) in a mode (implicit integrators)."""
    if mode == SEPARATED or mode == CLIPPED:
        return 0.0, 0.0
    return (0.0 if mode == YIELDING else p.k), p.c + p.cimp * imp


@njit(cache=True)
def condition(k, mode, p, hist):
    """Condition k of a mode as (α, β, γ), held while α + β e + γ ė ≥ 0 (1 if unused):
    0 the impact stroke; then by mode: gap (separated); loading rate (yielding); contact,
    yield, compression (contact); contact, tension of the clipped force (clipped)."""
    one = (1.0, 0.0, 0.0)
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
    """The law in a mode in affine form (event stepper): (K, C, F) of the force K e + C ė + F;
    (a, b, c) of the viscous power (a + b e + c ė) ė; the same for the impact dashpot; P of
    the plastic power P ė."""
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
    """Plastic settlement now: while yielding, the committed value lags and e sets it."""
    if mode == YIELDING:
        return e + p.d0 - p.dy
    return ep


@njit(cache=True, **HOT)
def spring_state(p, mode, h, e):
    """(settlement now, spring force k d without its dashpot, strain energy ½ k d²); zero
    force and energy while separated."""
    ep = current_plastic(mode, p, e, h.ep)
    d = p.d0 + e - ep
    if mode == SEPARATED or (p.kind == UPLIFT and d <= 0.0):
        return ep, 0.0, 0.0
    return ep, p.k * d, 0.5 * p.k * d * d
