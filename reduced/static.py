"""Static analyses of the reduced model: equilibrium states, pushovers and uplift onset.

They use the same spring laws as the dynamics (no dashpots, since velocities are zero), with the
history (plastic settlement) committed after each converged increment.

* :func:`rocking_pushover` — rigid base rotated by θ at constant vertical load (on a Winkler
  bed: an elastic bed uplifts at M = W b/3 and tends to W b):
  moment, settlement and contact length against θ, monotonic or cyclic.
* :func:`uplift_onset_force` — the lateral force at the top mass that first separates a spring.
* :func:`initial_state` — the state a free vibration starts from: a base rotation with the
  superstructure undeformed, or a top displacement held by a lateral force.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..checks import InputError
from . import kernels as kn
from . import springs as sp
from .laws import initial_history
from .model import ReducedModel

__all__ = ["Pushover", "rocking_pushover", "uplift_onset_force", "initial_state",
           "contact_length", "contact_lengths", "foundation_moment"]


def _forces(model: ReducedModel, q: np.ndarray, hist: np.ndarray):
    """(A s + K_G q, spring tangents, total spring forces, deformations) at rest."""
    ns, n = model.spring_count, model.mass.size
    fint, kt, ct = np.zeros(n), np.zeros(ns), np.zeros(ns)
    e, ed = np.zeros(ns), np.zeros(ns)
    modes = np.zeros(ns, np.int64)
    kn.internal_force(q, np.zeros(n), model.params, model.geometric, hist, e, ed, fint, kt, ct,
                      modes, np.zeros(ns), np.zeros(ns))
    P = model.params
    law = [kn.trial_force(P[j], hist[j], e[j], 0.0)[0] if kn.from_history(P[j]) else
           kn.force_in_mode(m, P[j], e[j], 0.0, hist[j]["ep"], 0.0)[0]
           for j, m in enumerate(modes)]
    total = np.array(law) + np.where(P["kind"] == sp.STORY, 0.0, P["f0"])
    return fint, kt, total, e, modes


def foundation_moment(model: ReducedModel, spring_forces: np.ndarray) -> float:
    """M = Σ x_i F_i of the foundation springs about O (force·length), positive against +θ."""
    found = model.foundation_slice
    return float(np.sum(model.params["x"][found] * spring_forces[found]))


def contact_length(model: ReducedModel, e: np.ndarray, ep: np.ndarray) -> float:
    """Length of base in contact (length): where d(x) > 0, d linear between springs.

    d_i = δ0_i + e_i − ep_i at each spring; beyond the outer springs d is held constant to the
    edge. Exact for a rigid base on a uniform elastic bed away from the edge strips.
    """
    return float(contact_lengths(model, np.atleast_2d(e), np.atleast_2d(ep))[0])


def contact_lengths(model: ReducedModel, e: np.ndarray, ep: np.ndarray) -> np.ndarray:
    """:func:`contact_length` of many states at once: rows of foundation deformations ``e`` and
    plastic settlements ``ep`` (length)."""
    layout = model.layout
    d = model.params["d0"][model.foundation_slice] + e - ep
    b = layout.half_width
    xs = np.concatenate([[-b], layout.positions, [b]])
    ds = np.concatenate([d[:, :1], d, d[:, -1:]], axis=1)
    d0, d1, width = ds[:, :-1], ds[:, 1:], np.diff(xs)
    both = (d0 > 0) & (d1 > 0)
    one = (d0 > 0) ^ (d1 > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        frac = np.where(one, np.maximum(d0, d1) / (np.abs(d0) + np.abs(d1)), 0.0)
    return np.sum(np.where(both, 1.0, frac) * width, axis=1)


@dataclass(frozen=True)
class Pushover:
    """A rocking pushover: rotation θ (rad), moment M (force·length), vertical displacement V
    (length, up), contact length (length), plastic settlement per spring (length)."""

    theta: np.ndarray
    moment: np.ndarray
    vertical: np.ndarray
    contact: np.ndarray
    plastic: np.ndarray
    weight: float
    width: float


def _vertical_equilibrium(model: ReducedModel, q: np.ndarray, hist: np.ndarray) -> float:
    """V at which the foundation carries exactly the weight, for the other DOFs in q."""
    iv = model.dofs.v

    def residual(v):
        q[iv] = v
        return _forces(model, q, hist)[0][iv]  # = −Σ(F − F0): zero at equilibrium

    scale = model.weight / model.layout.vertical_stiffness
    lo, hi = -scale, scale
    for _ in range(200):
        if residual(lo) < 0:
            break
        lo *= 2.0
    for _ in range(200):
        if residual(hi) > 0:
            break
        hi *= 2.0
    return brentq(residual, lo, hi, xtol=1e-14 * scale, rtol=1e-14, maxiter=500)


def rocking_pushover(model: ReducedModel, thetas) -> Pushover:
    """Rotate the base through ``thetas`` (rad, a path: monotonic or cyclic) at constant weight.

    The superstructure is carried along undeformed (x_j = h_j θ). Plastic settlement is committed
    after every increment, so the path matters for elasto-plastic springs.
    """
    if model.layout is None:
        raise InputError("foundation.support = 'fixed': a fixed base cannot rock")
    d = model.dofs
    thetas = np.asarray(thetas, dtype=float)
    ns = model.spring_count
    hist = initial_history(model.params)
    q = np.zeros(model.mass.size)
    out = {k: [] for k in ("moment", "vertical", "contact", "plastic")}
    for theta in thetas:
        _carry(model, q, theta)
        q[d.v] = _vertical_equilibrium(model, q, hist)
        _, _, total, e, _ = _forces(model, q, hist)
        for j in range(model.foundation_start, ns):
            kn.commit_step(model.params[j], e[j], 0.0, hist[j], 1)
        found = model.foundation_slice
        out["moment"].append(foundation_moment(model, total))
        out["vertical"].append(q[d.v])
        out["contact"].append(contact_length(model, e[found], hist["ep"][found]))
        out["plastic"].append(hist["ep"][found].copy())
    return Pushover(thetas, np.array(out["moment"]), np.array(out["vertical"]),
                    np.array(out["contact"]), np.array(out["plastic"]), model.weight,
                    2.0 * model.layout.half_width)


def uplift_onset_force(model: ReducedModel) -> float:
    """Lateral force at the top mass (force) at which the first spring separates (quasi-static).

    In the bonded range the response is linear: q = K⁻¹ P. The first spring to reach d = 0 sets
    the force. For two edge springs this is W b/h; for a uniform bed W b/(3h) as N → ∞.
    """
    if model.layout is None:
        raise InputError("foundation.support = 'fixed': a fixed base has no uplift")
    K, _ = model.bonded_matrices()
    load = np.zeros(model.mass.size)
    top = model.dofs.stories[-1] if model.dofs.stories else model.dofs.theta
    load[top] = 1.0 if model.dofs.stories else model.heights[-1]
    if not model.dofs.stories and model.dofs.sway >= 0:  # the top moves by u_G + (h − h_G) θ
        load[model.dofs.sway] = 1.0
        load[top] = model.heights[-1] - model.sway_height
    q = np.linalg.solve(K, load)
    e = model.A.T @ q
    rate = e[model.foundation_slice]  # compression per unit force
    opening = rate < 0
    delta0 = model.params["d0"][model.foundation_slice]
    return float(np.min(delta0[opening] / -rate[opening]))


def initial_state(model: ReducedModel, *, displacement: float = 0.0,
                  rotation: float = 0.0) -> np.ndarray:
    """Displacements a free vibration starts from, at rest.

    ``rotation`` θ₀ (rad): the base rotated with the superstructure undeformed, V from vertical
    equilibrium (e.g. a block released on its corner; exact kinematics holds sin θ₀; a
    macro-element is pushed there from rest, :func:`_element_equilibrium`).
    ``displacement`` (length): the top mass
    displaced relative to the ground and held there by a lateral force at the top, every other
    DOF in static equilibrium.
    """
    q = np.zeros(model.mass.size)
    d = model.dofs
    if rotation:
        if d.theta < 0:
            raise InputError("motion.rotation needs a rocking base (foundation.support is "
                             "'fixed')")
        if model.exact:  # q holds sin θ and the deflections in the rotated frame (zero)
            if not abs(rotation) < 0.5 * np.pi:
                raise InputError(f"motion.rotation = {rotation:g} rad: valid range is "
                                 "(-pi/2, pi/2) with exact kinematics")
            q[d.theta] = np.sin(rotation)
        else:
            _carry(model, q, rotation)
        if model.base is not None:
            q[d.v] = _element_equilibrium(model, q, rotation)
        elif model.layout is not None:
            q[d.v] = _vertical_equilibrium(model, q, initial_history(model.params))
    if displacement:
        if not d.stories:
            raise InputError("motion.displacement needs a flexible structure; use "
                             "motion.rotation for a rigid one")
        q = _displaced(model, q, displacement)
    return q


def _element_equilibrium(model: ReducedModel, q: np.ndarray, rotation: float) -> float:
    """V at which a base element (the macro-element) pushed to the rotation of q carries the
    weight (:func:`~.laws.macro.element.held_state`)."""
    from .laws.macro import MacroStepError
    from .laws.macro.element import held_state

    element, iv = model.base, model.dofs.v
    q[iv] = 0.0
    try:
        state = held_state(element, q)
    except MacroStepError as exc:
        raise InputError(f"motion.rotation = {rotation:g} rad: the macro-element cannot carry "
                         f"the weight on the way there ({exc}); valid: a rotation it holds "
                         "(smaller)") from None
    row = element.transform[0]
    return float((state.displacement[0] - element.rest.displacement[0] - row @ q) / row[iv])


def _carry(model: ReducedModel, q: np.ndarray, theta: float) -> None:
    """The base rotated by θ with the superstructure undeformed and the base's sway u_b at
    zero (x_j = h_j θ; a rigid structure on a sway spring: u_G = h_G θ), in place."""
    d = model.dofs
    q[d.theta] = theta
    for j, dof in enumerate(d.stories):
        q[dof] = model.heights[j] * theta
    if d.sway >= 0:
        q[d.sway] = 0.0 if d.stories else model.sway_height * theta


def _displaced(model: ReducedModel, q: np.ndarray, displacement: float) -> np.ndarray:
    """Static equilibrium with the top mass held at ``displacement`` (Newton, free DOFs)."""
    top = model.dofs.stories[-1]
    free = np.array([i for i in range(q.size) if i != top])
    hist = initial_history(model.params)
    q = q.copy()
    q[top] = displacement
    scale = max(model.weight, model.g * float(np.sum(model.mass[list(model.dofs.stories)])))
    for iteration in range(100):
        fint, kt, *_ = _forces(model, q, hist)
        r = fint[free]
        if np.max(np.abs(r)) <= 1e-10 * scale and iteration > 0:
            return q
        Kt = (model.A * kt) @ model.A.T + model.geometric
        q[free] -= np.linalg.solve(Kt[np.ix_(free, free)], r)
    raise InputError(f"motion.displacement = {displacement:g}: no static equilibrium found "
                     "(the structure may overturn under the force that holds it there)")
