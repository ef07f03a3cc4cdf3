"""The perfectly matched layer of the impedance analysis: a complex stretch of the coordinates
normal to the box's sides and bottom in their outer ``pml_thickness`` (module docstring of
:mod:`~upliftlab.continuum.impedance.analysis`), as corrections to the stiffness and mass data at
each
frequency."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checks import InputError
from ..dynamics.waves import full_basis, wave_speeds

__all__ = ["check_layer", "PmlLayer", "layer_depths", "pml_layer", "stretch", "gradient_rows",
           "lame_gradient_matrix", "PmlCorrections", "pml_corrections"]


def check_layer(thickness: float, half_width: float, depth: float) -> None:
    """The layer (all lengths in B) must leave soil around the footing."""
    if not (half_width - thickness > 0.5 and depth - thickness > 0.0):
        raise InputError(f"impedance pml_thickness = {thickness:g} B: the layer must leave soil "
                         f"around the footing inside a box of half-width {half_width:g} B and "
                         f"depth {depth:g} B; valid range is (0, {min(half_width - 0.5, depth):g})"
                         " B")


@dataclass(frozen=True, eq=False)
class PmlLayer:
    """Where the PML is: ξ_x, ξ_y ∈ [0, 1] at the quadrature points of the stiffness (``k``)
    and mass (``m``) rules of the elements that reach into it (``elements``), and f₀."""

    elements: np.ndarray
    xi_k: tuple
    xi_m: tuple
    strength: float
    order: int


def layer_depths(coords: np.ndarray, inner_x: float, inner_y: float, thickness: float):
    """Normalised depth into the side (x) and bottom (y) layers, 0 outside them."""
    x, y = coords
    xi_x = np.clip((np.abs(x) - inner_x) / thickness, 0.0, 1.0)
    xi_y = np.clip((-y - inner_y) / thickness, 0.0, 1.0)
    return xi_x, xi_y


def pml_layer(model, options, full) -> PmlLayer:
    """Where the layer of ``options`` (an ImpedanceOptions) lies in ``model``'s mesh, and f₀."""
    B = model.width
    half_width = 0.5 * float(np.ptp(model.mesh.p[0]))
    depth = -float(model.mesh.p[1].min())
    L = options.pml_thickness * B
    check_layer(options.pml_thickness, half_width / B, depth / B)
    inner_x, inner_y = half_width - L, depth - L
    xk = layer_depths(model.disc.qp_coordinates, inner_x, inner_y, L)
    xm = layer_depths(np.asarray(full.mapping.F(full.X)), inner_x, inner_y, L)
    inside = ((xk[0] > 0) | (xk[1] > 0)).any(axis=1) | ((xm[0] > 0) | (xm[1] > 0)).any(axis=1)
    elements = np.flatnonzero(inside)
    vp, vs = wave_speeds(model.soil)
    m = options.pml_order
    strength = (m + 1) * 0.5 * B * math.log(1.0 / options.pml_reflection) * vp / (2.0 * vs * L)
    pick = lambda pair: (pair[0][elements], pair[1][elements])  # noqa: E731
    return PmlLayer(elements=elements, xi_k=pick(xk), xi_m=pick(xm), strength=strength, order=m)


def stretch(xi: np.ndarray, layer: PmlLayer, a0: float) -> np.ndarray:
    """λ(ξ) = 1 + f₀ ξ^m − i f₀ ξ^m / a0."""
    f = layer.strength * xi ** layer.order
    return 1.0 + f - 1j * f / a0


def gradient_rows(basis) -> np.ndarray:
    """(4, nloc, nelems, nqp): u_x,x, u_y,y, u_x,y, u_y,x of each local vector function."""
    return np.stack([np.stack((g[0, 0], g[1, 1], g[0, 1], g[1, 0]))
                     for g in (phi[0].grad for phi in basis.basis)], axis=1)


def lame_gradient_matrix(soil) -> np.ndarray:
    """C on the displacement gradient (u_x,x, u_y,y, u_x,y, u_y,x), plane strain."""
    G, nu = soil.shear_modulus, soil.poisson_ratio
    lam = 2.0 * G * nu / (1.0 - 2.0 * nu)
    return np.array([[lam + 2 * G, lam, 0, 0], [lam, lam + 2 * G, 0, 0],
                     [0, 0, G, G], [0, 0, G, G]], dtype=float)


@dataclass(frozen=True, eq=False)
class PmlCorrections:
    """The layer's corrections to the stiffness and mass data at one frequency are
    ΔK = ∫ Gᵀ (Λ C Λ λ_x λ_y − C) G and ΔM = ∫ ρ (λ_x λ_y − 1) u·v over its elements."""

    layer: PmlLayer
    grad: np.ndarray
    dx_k: np.ndarray
    values: np.ndarray
    dx_m: np.ndarray
    C: np.ndarray
    rho: float
    scatter: np.ndarray
    nnz: int

    def corrections(self, a0: float) -> tuple[np.ndarray, np.ndarray]:
        """(ΔK, ΔM) as CSR data (complex) at a0."""
        lx, ly = (stretch(x, self.layer, a0) for x in self.layer.xi_k)
        inv = np.stack((1 / lx, 1 / ly, 1 / ly, 1 / lx))
        Ct = np.einsum("aep,ab,bep->abep", inv, self.C, inv) * (lx * ly) \
            - self.C[:, :, None, None]
        CG = np.einsum("abep,bjep->ajep", Ct, self.grad)
        Ke = np.einsum("aiep,ajep->eij", self.grad, CG * self.dx_k)
        mx, my = (stretch(x, self.layer, a0) for x in self.layer.xi_m)
        w = self.rho * (mx * my - 1.0) * self.dx_m
        Me = np.einsum("ciep,cjep->eij", self.values, self.values * w)
        return self._scatter(Ke), self._scatter(Me)

    def _scatter(self, Ae: np.ndarray) -> np.ndarray:
        flat = Ae.ravel()
        return np.bincount(self.scatter, weights=flat.real, minlength=self.nnz) \
            + 1j * np.bincount(self.scatter, weights=flat.imag, minlength=self.nnz)


def pml_corrections(model, options) -> PmlCorrections:
    """The :class:`PmlCorrections` of ``model`` for the layer of ``options``."""
    full = full_basis(model)
    layer = pml_layer(model, options, full)
    e = layer.elements
    nloc = model.disc.dofs.shape[0]
    scatter = model.disc.pattern.scatter.reshape(-1, nloc, nloc)[e].ravel()
    values = np.stack([np.asarray(phi[0]) for phi in full.basis], axis=1)[:, :, e]
    return PmlCorrections(layer=layer, grad=gradient_rows(model.disc.basis)[:, :, e],
                dx_k=model.disc.dx[e], values=values, dx_m=np.asarray(full.dx)[e],
                C=lame_gradient_matrix(model.soil), rho=model.soil.density,
                scatter=scatter, nnz=model.disc.pattern.nnz)
