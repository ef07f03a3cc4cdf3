"""The implicit route's iteration matrix: the soil's tangent with the dynamic terms, frozen for
plastic soil (modified Newton), and the model whose blocks a dynamic run holds.

**Newton.** Elastic soil: the tangent (with a0 M/(1+α) + c0 C) is factorised once per run
(constant dt), so each step is one back-substitution per iteration, usually one iteration.
Plastic soil: modified Newton (:class:`FrozenTangent`), accelerated by Anderson mixing
(:class:`~upliftlab.continuum.statics.newton.Anderson`, depth ``NewtonOptions.anderson`` = 4) whose
secant pairs are carried from step to step (the map's Jacobian changes little in one dt);
each step's first iteration is the plain predictor. The iteration starts from the
constant-acceleration extrapolation d + dt v + dt² a/2 of the soil and the footing
(``DynamicOptions.predict``), not from the last converged state. The elastic iteration matrix
of plastic soil is factorised in single precision (:data:`SINGLE`; residuals stay double, so the
converged state is the same), which halves the bytes of its back-substitution, the largest cost
of an iteration. The default tolerance is rtol = 1e-5. Every step starts with that elastic
factorisation; a step still unconverged after ``FrozenTangent.SWITCH`` = 20 iterations
refactorises once at its current consistent tangent and finishes with it. A step that still
fails is retried with the consistent tangent refactorised at every iteration. ``refactored``
records the steps that refactorised. The frozen matrix's residuals come from the compiled
kernels (:mod:`~upliftlab.continuum.dynamics.kernel_response`), which skip the tangent that such an
iteration never reads. What each of these choices saves is measured in
``benchmarks/CONTINUUM_DESIGN.md``.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from .. import assembly
from ..materials import plane_strain_stress, plane_strain_tangent
from .kernel_response import KernelResponse
from ..model import ContinuumModel, Response, evaluated, make_blocks, node_groups

__all__ = ["SINGLE", "FrozenTangent", "elastic_plane_tangent", "dynamic_model", "soil_residual"]

#: Factorise the elastic iteration matrix of plastic soil in single precision (module docstring).
SINGLE = True


@dataclass(frozen=True, eq=False)
class FrozenTangent(ContinuumModel):
    """The model with a frozen iteration matrix (modified Newton for plastic soil).

    Each step starts with the elastic tangent plus the dynamic terms, factorised once per run.
    A step still unconverged after :attr:`SWITCH` iterations refactorises once, at the
    consistent tangent of its current iterate, and finishes with it (nearly Newton's quadratic
    rate); the next step starts from the elastic factorisation again, which contracts for any
    mix of yielding and unloading points. Residuals use the true return map, so the converged
    state is the same as full Newton's."""

    #: Iterations before a slow step refactorises: a refactorisation and Schur condensation
    #: costs tens of iterations (``benchmarks/CONTINUUM_DESIGN.md``), so the elastic matrix is
    #: kept for many iterations.
    SWITCH = 20

    def respond(self, u, state, eigenstrain):
        """The soil's response by the compiled kernels where the material has them
        (:mod:`~upliftlab.continuum.dynamics.kernel_response`: the same numbers as the vectorised
        return map, whose tangent is computed only if a step refactorises), else the model's
        own."""
        kernel = self._cache.get("kernel")
        if kernel is None:
            kernel = self._cache["kernel"] = KernelResponse.of(self) or False
        if not kernel:
            return super().respond(u, state, eigenstrain)
        stress, material, residual = kernel.respond(u, state, eigenstrain)

        def tangent():
            return ContinuumModel.respond(self, u, state, eigenstrain).tangent
        return Response(stress, tangent, material, residual)

    def condense(self, tangent, extra=None):
        cache = self._cache
        cache["calls"] = cache.get("calls", 0) + 1
        if cache["calls"] > self.SWITCH and tangent is not None and not cache.get("fresh"):
            cache["fresh"] = (extra, self._condense(evaluated(tangent), extra, reused=True))
        if cache.get("fresh") and cache["fresh"][0] is extra:
            return cache["fresh"][1]
        hit = cache.get("elastic")
        if hit is None or hit[0] is not extra:
            hit = cache["elastic"] = (extra, self._condense(elastic_plane_tangent(self), extra,
                                                            reused=True, single=SINGLE))
        return hit[1]

    def refactored(self) -> bool:
        """True if the current step has refactorised."""
        return bool(self._cache.get("fresh"))

    def new_step(self) -> bool:
        """Start a step; True if the last step refactorised."""
        fresh = bool(self._cache.pop("fresh", None))
        self._cache["calls"] = 0
        return fresh


def elastic_plane_tangent(model) -> np.ndarray:
    """The plane-strain elastic tangent (3, 3, nelems, nqp) of the model's material at zero
    strain, at every quadrature point."""
    D = plane_strain_tangent(model.material.at_surface()(np.zeros((3, 3, 1)))[1])[..., 0]
    return np.ascontiguousarray(np.broadcast_to(D[..., None, None], (3, 3) + model.disc.qp_shape))


def dynamic_model(model, fixed, cls=ContinuumModel):
    """The model with the blocks of a dynamic run that holds the DOFs ``fixed`` (a
    :class:`~upliftlab.continuum.dynamics.ground.Ground`'s), as ``cls``."""
    contact = model.footing.contact_dofs
    basis = model.disc.basis
    interior = np.setdiff1d(np.arange(model.disc.ndofs), np.union1d(fixed, contact))
    values = {f.name: getattr(model, f.name) for f in fields(model) if f.init}
    values.update(blocks=make_blocks(model.disc.pattern, interior, contact, fixed,
                                 node_groups(basis)), _cache={})
    return cls(**values)


def soil_residual(model, stress) -> np.ndarray:
    """f_int − f_body of a total stress field."""
    return assembly.internal_force(model.disc, plane_strain_stress(stress)) - model.body_force
