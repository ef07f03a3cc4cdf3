"""The far field of a dynamic run: the soil columns at the box's two sides, their peak shear
strain and their plastic strain by depth, and whether they yielded under the motion.

**Which elements.** The outermost column of elements on each side: every element with a
vertex on the side boundary (x = ±half the box's width). On a structured box (the graded soil
mesh of :mod:`upliftlab.meshes.soil`) that is one column of cells per side, both triangles of a
cell on P1/P2 meshes. These are the elements a free-field boundary makes a one-dimensional
column (``continuum.boundary = 'shear'``: the sides' u_y held, u_x free, exact for a vertically
incident S wave in a layered soil, :mod:`~upliftlab.continuum.dynamics.ground`), and the
farthest soil from the footing: with the box's default width of 10 B, 5 B from its centre.
A distance criterion ("every element beyond X") would mix columns the footing still loads
with the free field; the side column alone is what the boundary condition defines. With
``rollers`` sides (the rigid container) the same column is recorded: it then shows the
container's response, not a free field's.

**What is recorded.** At every recorded row (the rate the run already records at, either
route), for those elements only: the engineering shear strain γxy at their quadrature points
(one sparse product with the rows of B that belong to them), less its value at t = 0 (the
gravity state), so that γ is the motion's; and their equivalent plastic strain ε̄p. Per side
and per layer of cells (depth of its top and bottom, positive down from the surface): the peak
|Δγxy| over the run (``shear_strain``), ε̄p at t = 0 (``plastic_strain_static``) and its
largest value over the run (``plastic_strain``; ε̄p only accumulates). Recording reads the
state and changes no number of the run.

**Yielded.** A layer yielded under the motion where ε̄p grew by more than
:data:`YIELD_THRESHOLD` = 1e-5 over the run: three orders below the elastic shear strain at
yield c_u/G of the map's clay (2.6e-3) and above the round-off of a return map (~1e-12).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["YIELD_THRESHOLD", "FarField", "FarFieldResponse", "FarFieldRecorder", "far_field"]

#: The growth of ε̄p over the run from which a far-field layer counts as yielded (module
#: docstring).
YIELD_THRESHOLD = 1e-5
#: The sides, in the order of the records' first axis.
SIDES = ("left", "right")


@dataclass(frozen=True, eq=False)
class FarField:
    """The far field's elements (:func:`far_field`): ``elements`` (n) their indices, ``side``
    (n) 0 left, 1 right, ``layer`` (n) the index of their layer of cells, ``top`` and
    ``bottom`` (nz) each layer's depth (length, positive down from the surface), ``gamma``
    the sparse rows of B giving γxy at their quadrature points ((n·nqp) × ndofs)."""

    elements: np.ndarray
    side: np.ndarray
    layer: np.ndarray
    top: np.ndarray
    bottom: np.ndarray
    gamma: object


def far_field(model) -> FarField:
    """The :class:`FarField` of ``model`` (module docstring: the outermost column of elements
    on each side)."""
    mesh, disc = model.mesh, model.disc
    x, y = mesh.p
    edge = np.isclose(x, x.min()) | np.isclose(x, x.max())
    elements = np.flatnonzero(edge[mesh.t].any(axis=0))
    side = (x[mesh.t[:, elements]].mean(axis=0) > 0.5 * (x.min() + x.max())).astype(np.int8)
    surface = y.max()
    top, bottom = (surface - y[mesh.t[:, elements]].max(axis=0),
                   surface - y[mesh.t[:, elements]].min(axis=0))
    scale = max(float(np.ptp(y)), 1.0) * 1e-9
    keys = np.round(np.column_stack((top, bottom)) / scale)
    levels, layer = np.unique(keys, axis=0, return_inverse=True)
    levels = levels * scale
    nel, nqp = disc.qp_shape
    rows = (2 * nel * nqp + elements[:, None] * nqp + np.arange(nqp)).ravel()
    return FarField(elements=elements, side=side, layer=np.ravel(layer), top=levels[:, 0],
                    bottom=levels[:, 1], gamma=disc.gradient[rows])


@dataclass(frozen=True, eq=False)
class FarFieldResponse:
    """The far field's response over a run, per side (left, right) and layer: ``top`` and
    ``bottom`` (nz) each layer's depth (length, down from the surface); ``shear_strain``
    (2, nz) the peak |Δγxy| since t = 0; ``plastic_strain`` (2, nz) the largest ε̄p;
    ``plastic_strain_static`` (2, nz) ε̄p at t = 0 (module docstring)."""

    top: np.ndarray
    bottom: np.ndarray
    shear_strain: np.ndarray
    plastic_strain: np.ndarray
    plastic_strain_static: np.ndarray

    @property
    def yielded(self) -> np.ndarray:
        """(nz) whether the layer yielded under the motion on either side (ε̄p grew by more
        than :data:`YIELD_THRESHOLD`)."""
        grown = self.plastic_strain - self.plastic_strain_static
        return np.any(grown > YIELD_THRESHOLD, axis=0)

    def yield_range(self) -> tuple[float, float] | None:
        """(z1, z2): the depths (length) from the top of the shallowest yielded layer to the
        bottom of the deepest; None: the far field stayed elastic under the motion."""
        hit = np.flatnonzero(self.yielded)
        if not hit.size:
            return None
        return float(self.top[hit].min()), float(self.bottom[hit].max())

    def summary(self) -> dict:
        """The summary's ``far_field`` entry: ``peak_shear_strain`` (the largest over sides
        and depths) and its depth ``depth_of_peak`` (the layer's mid-depth), the largest
        ``peak_plastic_strain``, and ``yielded`` ("elastic" or "from z1 to z2") with
        ``yield_top``, ``yield_bottom`` (None when elastic)."""
        peak = np.max(self.shear_strain, axis=0)
        k = int(np.argmax(peak)) if peak.size else 0
        span = self.yield_range()
        return {
            "peak_shear_strain": float(peak[k]) if peak.size else 0.0,
            "depth_of_peak": float(0.5 * (self.top[k] + self.bottom[k])) if peak.size else 0.0,
            "peak_plastic_strain": float(np.max(self.plastic_strain, initial=0.0)),
            "yielded": "elastic" if span is None else f"from {span[0]:.4g} to {span[1]:.4g}",
            "yield_top": None if span is None else span[0],
            "yield_bottom": None if span is None else span[1]}


class FarFieldRecorder:
    """Peaks of the far field (:class:`FarField`) over the recorded rows: :meth:`record` each
    row's soil displacement ``u`` and ε̄p (nel, nqp), :meth:`response` the
    :class:`FarFieldResponse`."""

    def __init__(self, model):
        self.layout = far_field(model)
        nz = self.layout.top.size
        self.nqp = model.disc.qp_shape[1]
        self.gamma0 = None
        self.gamma = np.zeros((2, nz))
        self.ebar = np.zeros((2, nz))
        self.ebar0 = np.zeros((2, nz))

    def _per_layer(self, values: np.ndarray) -> np.ndarray:
        """(2, nz) the largest of ``values`` (n, nqp) per side and layer."""
        out = np.zeros_like(self.gamma)
        np.maximum.at(out, (self.layout.side, self.layout.layer), values.max(axis=1))
        return out

    def record(self, u: np.ndarray, ebar: np.ndarray) -> None:
        """One recorded row: the displacement ``u`` (ndofs) and ε̄p (nel, nqp) of the state."""
        gamma = (self.layout.gamma @ u).reshape(-1, self.nqp)
        points = np.asarray(ebar)[self.layout.elements]
        if self.gamma0 is None:
            self.gamma0 = gamma
            self.ebar0 = self._per_layer(points)
        self.gamma = np.maximum(self.gamma, self._per_layer(np.abs(gamma - self.gamma0)))
        self.ebar = np.maximum(self.ebar, self._per_layer(points))

    def response(self) -> FarFieldResponse:
        return FarFieldResponse(top=self.layout.top, bottom=self.layout.bottom,
                                shear_strain=self.gamma.copy(), plastic_strain=self.ebar.copy(),
                                plastic_strain_static=self.ebar0.copy())
