"""The soil's internal force for explicit time stepping, with the material history it commits.

:class:`SoilForce` evaluates ∫ Bᵀ σ(u) at every step and keeps the quadrature-point state
(plastic strain, ε̄p) between steps: an explicit step commits every evaluation, there are no
iterations to roll back. A soil model with a compiled point return (its record's
``Constants``, :mod:`~upliftlab.continuum.materials.compiled`) runs in the compiled kernels of
:mod:`~upliftlab.continuum.dynamics.kernels`; any other falls back to its vectorised return map
through :meth:`~upliftlab.continuum.model.ContinuumModel.respond` (the same numbers, slower).
"""

from __future__ import annotations

import numpy as np

from . import kernels
from ..materials import State

__all__ = ["SoilForce", "four_components", "tensor_of"]


def four_components(tensor: np.ndarray) -> np.ndarray:
    """(nel, nqp, 4) components xx, yy, zz, xy of a tensor field (3, 3, nel, nqp)."""
    return np.ascontiguousarray(np.stack([tensor[0, 0], tensor[1, 1], tensor[2, 2],
                                          tensor[0, 1]], axis=-1))


def tensor_of(four: np.ndarray) -> np.ndarray:
    """The (3, 3, nel, nqp) tensor of (nel, nqp, 4) components."""
    out = np.zeros((3, 3) + four.shape[:2])
    out[0, 0], out[1, 1], out[2, 2] = four[..., 0], four[..., 1], four[..., 2]
    out[0, 1] = out[1, 0] = four[..., 3]
    return out


class SoilForce:
    """∫ Bᵀ σ(u) of ``model`` from the converged ``state`` (a
    :class:`~upliftlab.continuum.statics.newton.ContinuumState`: its material history and geostatic
    eigenstrain), committing the material state at every call (module docstring).
    ``compiled`` says whether the compiled kernel serves this material; ``constants`` are what
    its point return reads (None: the vectorised fallback)."""

    def __init__(self, model, state):
        self.model = model
        nel, nqp = model.disc.qp_shape
        eig = state.eigenstrain
        self.eigenstrain = np.zeros((nel, nqp, 4)) if eig is None else four_components(eig)
        self.constants = model.material.kernel_constants()
        self.compiled = self.constants is not None
        #: the per-point strength gain of the compiled return (zeros: a uniform strength)
        self.gain = np.ascontiguousarray(model.material.strength_gain((nel, nqp)))
        self.out = np.zeros(model.disc.ndofs)
        if self.compiled:
            self.layout = kernels.layout(model.disc)
            self.plastic = four_components(state.material.plastic_strain)
            self.ebar = np.ascontiguousarray(state.material.equivalent_plastic_strain, float)
            self.stress = four_components(state.stress)
            self.work = np.zeros(self.layout.shape[::2] + (2,))
        else:
            self._material, self._stress = state.material, state.stress
            self._eigen = eig

    def __call__(self, u: np.ndarray) -> np.ndarray:
        """∫ Bᵀ σ(u) (ndofs; a buffer reused by the next call) and commit the state."""
        if self.compiled:
            return kernels.internal_force(self.layout, u, self.eigenstrain, self.plastic,
                                          self.ebar, self.constants, self.gain, self.stress,
                                          self.work, self.out)
        response = self.model.respond(u, self._material, self._eigen)
        self._material, self._stress = response.material, response.stress
        np.add(response.residual, self.model.body_force, out=self.out)
        return self.out

    @property
    def material(self) -> State:
        """The committed quadrature-point state (a copy)."""
        if not self.compiled:
            return self._material
        shape = self.ebar.shape
        return State(tensor_of(self.plastic), self.ebar.copy(),
                     np.zeros(shape, dtype=np.int8))

    @property
    def equivalent_plastic_strain(self) -> np.ndarray:
        """The committed ε̄p (nel, nqp), not a copy: read it before the next call."""
        return self.ebar if self.compiled else self._material.equivalent_plastic_strain

    @property
    def peak_plastic_strain(self) -> float:
        """The largest committed equivalent plastic strain ε̄p at a quadrature point."""
        ebar = self.ebar if self.compiled else self._material.equivalent_plastic_strain
        return float(np.max(ebar)) if np.size(ebar) else 0.0

    @property
    def stress_tensor(self) -> np.ndarray:
        """The stress of the last call, (3, 3, nel, nqp) (a copy)."""
        return tensor_of(self.stress) if self.compiled else self._stress.copy()
