"""The soil's response by the compiled kernels, for the iterations that never read the tangent.

Modified Newton (:class:`~upliftlab.continuum.dynamics.iteration_matrix.FrozenTangent`, the implicit
dynamics of plastic soil) iterates with a frozen matrix: each iteration needs the stress, the
material state it would commit and the residual f_int − f_body, but not the consistent tangent.
The vectorised route (:meth:`~upliftlab.continuum.model.ContinuumModel.respond`) computes all
four, the strain and ∫ Bᵀ σ as sparse products, and it was the largest cost of an implicit step
after the back-substitution. :class:`KernelResponse` computes the first three in one compiled
pass over the elements (:func:`~upliftlab.continuum.dynamics.kernels.internal_force`: strain,
the soil model's compiled point return and Bᵀ σ dx together, the same return maps as
:mod:`~upliftlab.continuum.materials`), and
leaves the tangent to the vectorised route, computed only if a step asks for it (one that
refactorises after :attr:`~upliftlab.continuum.dynamics.iteration_matrix.FrozenTangent.SWITCH`
iterations). The kernel runs on one thread: one evaluation is too short for a second thread to
pay (measured in ``benchmarks/CONTINUUM_DESIGN.md``).

The kernels do not classify the return (``State.region``, a diagnostic of the vectorised maps):
a state from here has region 0 everywhere, as the explicit route's
(:class:`~upliftlab.continuum.dynamics.soil_force.SoilForce`). Its ``equivalent_plastic_strain`` and
``plastic_strain`` are those of the vectorised maps.
"""

from __future__ import annotations

import numpy as np

from . import kernels
from ..materials import State
from .soil_force import four_components, tensor_of

__all__ = ["KernelResponse"]


class KernelResponse:
    """The soil response of ``model`` by the compiled kernels (module docstring). Build it
    with :meth:`of`, which returns None for a material without a compiled return map;
    ``constants`` are what its point return reads (the record's ``kernel_constants()``)."""

    def __init__(self, model, constants):
        self.model, self.constants = model, constants
        self.gain = np.ascontiguousarray(model.material.strength_gain(model.disc.qp_shape))
        self.layout = kernels.layout(model.disc)
        self.work = np.zeros(self.layout.shape[::2] + (2,))
        self.force = np.zeros(model.disc.ndofs)
        self._eigen = (None, None)
        self._history = (None, None, None)

    @classmethod
    def of(cls, model) -> KernelResponse | None:
        """The kernel response of ``model``, or None if its material has no compiled map."""
        constants = model.material.kernel_constants()
        return None if constants is None else cls(model, constants)

    def respond(self, u: np.ndarray, state: State, eigenstrain: np.ndarray | None) -> tuple:
        """(stress (3, 3, nelems, nqp), material state, residual f_int − f_body) for the
        displacement ``u`` from the converged ``state`` and the geostatic ``eigenstrain``."""
        plastic, ebar = self._start(state)
        nel, nqp = self.model.disc.qp_shape
        stress = np.empty((nel, nqp, 4))
        kernels.internal_force(self.layout, u, self._eigenstrain(eigenstrain), plastic, ebar,
                               self.constants, self.gain, stress, self.work, self.force,
                               parallel=False)
        material = State(tensor_of(plastic), ebar, np.zeros((nel, nqp), dtype=np.int8))
        return tensor_of(stress), material, self.force - self.model.body_force

    def _start(self, state: State) -> tuple[np.ndarray, np.ndarray]:
        """Copies of the converged history (plastic strain as components, ε̄p) that one call
        may update; the conversion is kept for the iterations of one step."""
        if self._history[0] is not state:
            self._history = (state, four_components(state.plastic_strain),
                             np.ascontiguousarray(state.equivalent_plastic_strain, dtype=float))
        return self._history[1].copy(), self._history[2].copy()

    def _eigenstrain(self, eigenstrain: np.ndarray | None) -> np.ndarray:
        if self._eigen[0] is not eigenstrain:
            nel, nqp = self.model.disc.qp_shape
            four = np.zeros((nel, nqp, 4)) if eigenstrain is None else \
                four_components(eigenstrain)
            self._eigen = (eigenstrain, four)
        return self._eigen[1]
