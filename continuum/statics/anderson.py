"""Anderson acceleration of the modified Newton iteration (a frozen iteration matrix converges
linearly; mixing the last few iterates recovers most of Newton's rate)."""

from __future__ import annotations

import numpy as np

__all__ = ["Anderson"]


class Anderson:
    """Anderson acceleration (type II, Walker & Ni, SIAM J. Numer. Anal. 49(4), 2011) of the
    fixed-point iteration x ← x + d(x) of modified Newton: the next iterate is x + d − ΔG γ,
    with γ the least-squares fit of d by the recorded differences ΔD of d and ΔG of x + d,
    ``depth`` pairs at most. With a frozen iteration matrix the iteration converges linearly,
    and this recovers most of Newton's rate at the cost of a small least-squares problem.

    The contact forces are combined with the same weights, so the combination keeps zero gaps
    at closed nodes and zero forces at open ones. The pairs are secant information about the
    map's Jacobian, which changes little from one time step to the next: one instance can serve
    a whole run (:meth:`new_step` keeps the pairs, forgets the last point; the first iteration
    of a step, the predictor, is always the plain step). The pairs are dropped whenever the
    contact status or the iteration matrix changes."""

    def __init__(self, depth: int):
        self.depth = depth
        self.status = self.matrix = self.last = None
        self.pairs = []

    def clear(self) -> None:
        self.pairs, self.last = [], None

    def new_step(self) -> None:
        self.last = None

    def mix(self, x, d, force, status, matrix=None):
        """The combined (x + d, force), or None (take the plain step)."""
        if self.depth == 0:
            return None
        if self.matrix is not matrix or self.status is None \
                or not np.array_equal(status, self.status):
            self.clear()
            self.status, self.matrix = np.array(status), matrix
        g = x + d
        first, last = self.last is None, self.last
        self.last = (g, d, force)
        if first:  # a step's predictor: the plain step
            return None
        self.pairs.append(tuple(a - b for a, b in zip((g, d, force), last)))
        del self.pairs[:-self.depth]
        dG, dD, dF = (np.array(column).T for column in zip(*self.pairs))
        # the k×k normal equations (k = depth ≤ 10), cheaper than an SVD of the (n, k) block
        # (benchmarks/CONTINUUM_DESIGN.md); the mixed iterate is only taken if it lowers the
        # residual (_mixed_step), so their poorer conditioning costs no accuracy
        gamma = np.linalg.lstsq(dD.T @ dD, dD.T @ d, rcond=None)[0]
        return g - dG @ gamma, force - dF @ gamma
