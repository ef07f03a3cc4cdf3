"""The footing's H–M capacity at constant vertical load: radial probes in (u, θ) and the
envelope they trace (issue 36 §2), on an interface that carries shear (``bonded`` or
``coulomb``).

A probe holds V and moves the footing along one direction of the (u, B θ) plane,
(u, B θ) = s (cos φ, sin φ), s growing to ``reach``; for a perfectly plastic soil its last
load is a point of the H–M section of the failure surface at that V, the point whose normal
(with the work-conjugate pair (H, M/B)) is the direction of the plastic flow. Directions over
a half turn trace the section's half; the other half is its image under (H, M) → (−H, −M)
(the footing and the soil are symmetric about the footing's axis).

The reference it is held to, for a rough strip that cannot take tension on undrained clay:
Green's (1954) inclined load on the effective width B′ = B − 2|M|/V (Meyerhof),

    V/(c B′) = 1 + π − arcsin(h) + √(1 − h²),   H = h c B′,   (h = 1 where V/(c B′) ≤ 1 + π/2)

which Houlsby and Puzrin (1999) show to be a lower bound of the H–M section
(:func:`green_effective_width`). Sign conventions are :mod:`.analyses`'.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ... import checks
from ...checks import InputError
from .analyses import _apply_n, _follow, _path
from .geostatic import geostatic
from .newton import Control, NewtonOptions
from .results import StaticPath

__all__ = ["combined_pushover", "hm_envelope", "HMEnvelope", "green_effective_width"]


def combined_pushover(model, N: float, direction: float, reach: float, steps: int, *,
                      state=None, load_steps: int = 4,
                      options: NewtonOptions = NewtonOptions()) -> StaticPath:
    """At constant vertical load ``N`` (force/length, applied first in ``load_steps`` with u
    and θ held), the footing moved along the ray (u, B θ) = s (cos φ, sin φ), φ = ``direction``
    (rad), s = ``reach`` (length) k/``steps``. Returns the path (H and M against u and θ)."""
    if not model.footing.interface.tangential:
        raise InputError("soil.interface = 'frictionless' in an H–M probe: the footing is "
                         "pushed sideways through its interface's shear; valid: 'bonded', "
                         "'coulomb'")
    checks.positive("N", N)
    checks.positive("reach", reach)
    steps = checks.integer_at_least("steps", steps, 1)
    state = geostatic(model) if state is None else state
    state = _apply_n(model, state, N, load_steps, options)
    B = model.width
    controls = [Control((True, False, True),
                        (s * math.cos(direction), -N, s * math.sin(direction) / B))
                for s in reach * np.arange(1, steps + 1) / steps]
    states = _follow(model, state, controls, options, None)
    return _path(model, "combined_pushover", states, {"N_applied": N,
                                                      "direction": float(direction)})


@dataclass(frozen=True, eq=False)
class HMEnvelope:
    """The H–M section at ``V`` (force/length) by radial probes: per direction φ (rad) the
    last ``H`` (force/length) and ``M`` (force·length/length) of its probe; ``width`` B and
    ``probes`` (their :class:`StaticPath`)."""

    V: float
    directions: np.ndarray
    H: np.ndarray
    M: np.ndarray
    width: float
    probes: tuple = field(repr=False, default=())


def hm_envelope(model, V: float, directions, reach: float, steps: int, *,
                load_steps: int = 4, options: NewtonOptions = NewtonOptions()
                ) -> HMEnvelope:
    """The H–M section at constant ``V`` (module docstring): one :func:`combined_pushover`
    per direction of ``directions`` (rad), each to ``reach`` (length) in ``steps``."""
    directions = np.atleast_1d(np.asarray(directions, dtype=float))
    if directions.ndim != 1 or directions.size == 0 or not np.isfinite(directions).all():
        raise InputError(f"directions = {directions!r}: expected a non-empty 1-D list of "
                         "finite angles (rad)")
    probes = tuple(combined_pushover(model, V, phi, reach, steps, load_steps=load_steps,
                                     options=options) for phi in directions)
    return HMEnvelope(V=float(V), directions=directions,
                      H=np.array([p.H[-1] for p in probes]),
                      M=np.array([p.M[-1] for p in probes]), width=model.width,
                      probes=probes)


def green_effective_width(V: float, cohesion: float, width: float, reduced) -> tuple:
    """(H, M) of Green's inclined load on the effective widths ``reduced`` B′ (module
    docstring; force/length, force·length/length), at vertical load ``V`` on a strip of
    ``width`` B on clay of undrained strength ``cohesion``; a B′ too narrow to carry V
    (V/(c B′) > 2 + π) is refused."""
    from scipy.optimize import brentq  # here: a dynamic run imports the continuum, not this

    reduced = np.atleast_1d(np.asarray(reduced, dtype=float))
    load = V / (cohesion * reduced)
    if np.any(load > 2.0 + math.pi) or np.any(reduced > width) or np.any(reduced <= 0.0):
        raise InputError(f"effective widths {reduced.tolist()}: valid range is "
                         f"[{V / ((2.0 + math.pi) * cohesion):.6g}, {width:g}]")

    def ratio(x: float) -> float:
        if x <= 1.0 + math.pi / 2.0:
            return 1.0
        return brentq(lambda t: 1.0 + math.pi - math.asin(t) + math.sqrt(1.0 - t * t) - x,
                      0.0, 1.0, xtol=1e-14)

    h = np.array([ratio(x) for x in load])
    return h * cohesion * reduced, V * (width - reduced) / 2.0
