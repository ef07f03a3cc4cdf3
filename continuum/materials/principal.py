"""The return in principal stress space shared by Tresca and Mohr–Coulomb (perfectly plastic):
a closed-form return to the main plane, either edge or the apex (de Souza Neto, Perić & Owen,
*Computational Methods for Plasticity*, 2008, ch. 8) and the spectral consistent tangent.

:func:`principal_return` is the vectorised map of the yield function
(σ1 − σ3) + (σ1 + σ3) sin φ ≤ 2c cos φ with the plastic potential (σ1 − σ3) + (σ1 + σ3) sin ψ;
Tresca is the case φ = ψ = 0, c = c_u.
"""

from __future__ import annotations

import math

import numpy as np

from .returns import (EYE3, PAIRS, RTOL, SQ2, Piecewise, Region, elastic_mandel,
                      elastic_stress, finish, mandel, prepare)

__all__ = ["principal_return"]


def principal_return(strain, state, params, sin_phi, cos_phi, sin_psi, cohesion):
    """(stress, tangent, new state) of the principal-space return (module docstring) of
    ``strain`` from ``state`` with the elastic constants of ``params`` and the strength
    ``cohesion`` (kPa; a float, or one per point (N,) of the flattened batch), sin φ, cos φ
    and sin ψ."""
    eps, eps_p, ebar, batch = prepare(strain, state)
    n = len(eps)
    sig_trial = elastic_stress(eps - eps_p, params)
    k = 2.0 * cohesion * cos_phi
    high, low = _extreme_principal(sig_trial)
    f_trial = (high - low) + (high + low) * sin_phi - k
    plastic = f_trial > RTOL * (k + np.maximum(np.abs(high), np.abs(low)))
    stress = sig_trial
    tangent = Piecewise(elastic_mandel(params), plastic, None)
    eps_p_new, ebar_new = eps_p.copy(), ebar.copy()
    region = np.zeros(n, dtype=np.int8)
    if plastic.any():
        values, vectors = np.linalg.eigh(sig_trial[plastic])
        values, vectors = values[:, ::-1], vectors[:, :, ::-1]  # σ1 >= σ2 >= σ3
        sig, d3, spin, reg = _mc_principal(values, params, sin_phi, cos_phi, sin_psi,
                                           _at(cohesion, plastic))
        d_eps_p = (values - sig) @ np.linalg.inv(_principal_elasticity(params))
        stress[plastic] = np.einsum("nia,na,nja->nij", vectors, sig, vectors)
        eps_p_new[plastic] += np.einsum("nia,na,nja->nij", vectors, d_eps_p, vectors)
        ebar_new[plastic] += math.sqrt(2.0 / 3.0) * np.linalg.norm(d_eps_p, axis=1)
        tangent = Piecewise(tangent.constant, plastic, _spectral_tangent(vectors, d3, spin))
        region[plastic] = reg
    return finish(batch, stress, tangent, eps_p_new, ebar_new, region)


def _at(value, mask):
    """A per-point ``value`` (float, or an array over the points) at the points of ``mask``."""
    return value if np.ndim(value) == 0 else value[mask]


def _extreme_principal(sig):
    """(σ1, σ3): the largest and smallest principal values of symmetric (n, 3, 3) tensors. In
    plane strain (σxz = σyz = 0 everywhere) in closed form: σzz and the in-plane pair
    (σxx + σyy)/2 ± √(((σxx − σyy)/2)² + σxy²); otherwise by LAPACK."""
    if np.any(sig[:, 0, 2]) or np.any(sig[:, 1, 2]):
        w = np.linalg.eigvalsh(sig)  # ascending
        return w[:, 2], w[:, 0]
    centre = 0.5 * (sig[:, 0, 0] + sig[:, 1, 1])
    radius = np.hypot(0.5 * (sig[:, 0, 0] - sig[:, 1, 1]), sig[:, 0, 1])
    zz = sig[:, 2, 2]
    return np.maximum(centre + radius, zz), np.minimum(centre - radius, zz)


def _principal_elasticity(params) -> np.ndarray:
    return params.lame * np.ones((3, 3)) + 2.0 * params.shear_modulus * EYE3


def _plane(i: int, j: int, s: float) -> np.ndarray:
    """Gradient of (σ_i − σ_j) + (σ_i + σ_j) s in principal space."""
    v = np.zeros(3)
    v[i], v[j] = 1.0 + s, -(1.0 - s)
    return v


def _return_to_planes(trial, ce, grads, flows, k):
    """Closed-form return onto the active planes grads·σ = k (perfect plasticity, linear).

    Returns the principal stresses (n, 3) and the principal tangent D3 (3, 3), which maps
    principal strain increments to principal stress increments."""
    grads, flows = np.atleast_2d(grads), np.atleast_2d(flows)
    k = k if np.ndim(k) == 0 else k[:, None]  # one strength per point: one per row
    c_flow, c_grad = flows @ ce, grads @ ce  # rows: Ce·N (Ce is symmetric)
    m_inv = np.linalg.inv(grads @ ce @ flows.T)
    dgamma = (trial @ grads.T - k) @ m_inv.T
    return trial - dgamma @ c_flow, ce - c_flow.T @ m_inv @ c_grad


def _mc_principal(trial, params, sin_phi, cos_phi, sin_psi, cohesion):
    """Mohr–Coulomb return in principal space for trial principal stresses (n, 3), descending.

    Returns stresses (n, 3), principal tangents (n, 3, 3), spin coefficients (n, 3) for the
    pairs (12, 13, 23) and the region codes (n,)."""
    n = len(trial)
    G = params.shear_modulus
    ce = _principal_elasticity(params)
    k = 2.0 * cohesion * cos_phi
    main_sig, main_d = _return_to_planes(trial, ce, _plane(0, 2, sin_phi), _plane(0, 2, sin_psi), k)
    main_ok = (main_sig[:, 0] >= main_sig[:, 1]) & (main_sig[:, 1] >= main_sig[:, 2])
    # Which edge when the main plane fails: the extension edge σ2 = σ3 when this is > 0
    # (the larger of the two ordering violations, weighted by the flow vector).
    extension = ((1.0 - sin_psi) * trial[:, 0] - 2.0 * trial[:, 1]
                 + (1.0 + sin_psi) * trial[:, 2]) > 0.0
    comp_sig, comp_d = _return_to_planes(
        trial, ce, [_plane(0, 2, sin_phi), _plane(1, 2, sin_phi)],
        [_plane(0, 2, sin_psi), _plane(1, 2, sin_psi)], k)
    ext_sig, ext_d = _return_to_planes(
        trial, ce, [_plane(0, 2, sin_phi), _plane(0, 1, sin_phi)],
        [_plane(0, 2, sin_psi), _plane(0, 1, sin_psi)], k)
    comp_sig[:, :2] = comp_sig[:, :2].mean(axis=1, keepdims=True)  # exact ties on the edge
    ext_sig[:, 1:] = ext_sig[:, 1:].mean(axis=1, keepdims=True)
    edge_sig = np.where(extension[:, None], ext_sig, comp_sig)
    edge_ok = (edge_sig[:, 0] >= edge_sig[:, 2]) | (sin_phi == 0.0)
    apex = ~main_ok & ~edge_ok
    region = np.select([main_ok, apex, extension],
                       [Region.SMOOTH, Region.APEX, Region.EDGE_EXTENSION],
                       Region.EDGE_COMPRESSION)
    sig = np.where(main_ok[:, None], main_sig, edge_sig)
    d3 = np.where(main_ok[:, None, None], main_d,
                  np.where(extension[:, None, None], ext_d, comp_d))
    if apex.any():
        sig[apex] = np.reshape(_at(cohesion * cos_phi / sin_phi, apex), (-1, 1))
        d3[apex] = 0.0
    spin = np.empty((n, 3))
    scale = k + np.abs(trial).max(axis=1)
    for col, (a, b) in enumerate(PAIRS):
        gap = trial[:, a] - trial[:, b]
        tiny = np.abs(gap) <= 1e-10 * scale
        spin[:, col] = np.where(tiny, d3[:, a, a] - d3[:, a, b],
                                2.0 * G * (sig[:, a] - sig[:, b]) / np.where(tiny, 1.0, gap))
    spin[region == Region.EDGE_COMPRESSION, 0] = 0.0  # σ1 = σ2 on the edge
    spin[region == Region.EDGE_EXTENSION, 2] = 0.0  # σ2 = σ3 on the edge
    spin[apex] = 0.0
    return sig, d3, spin, region


def _spectral_tangent(vectors, d3, spin):
    """Mandel tangent of an isotropic return map from its principal form.

    With the orthonormal eigenbasis E_a = v_a⊗v_a and N_ab = (v_a⊗v_b + v_b⊗v_a)/√2, the tangent
    is block diagonal: D3 on the E_a and (σ_a − σ_b)/(εtr_a − εtr_b) on each N_ab."""
    n = len(vectors)
    basis = np.empty((n, 6, 6))
    for a in range(3):
        v = vectors[:, :, a]
        basis[:, :, a] = mandel(v[:, :, None] * v[:, None, :])
    for col, (a, b) in enumerate(PAIRS, start=3):
        va, vb = vectors[:, :, a], vectors[:, :, b]
        outer = va[:, :, None] * vb[:, None, :]
        basis[:, :, col] = mandel(outer + outer.transpose(0, 2, 1)) / SQ2
    block = np.zeros((n, 6, 6))
    block[:, :3, :3] = d3
    block[:, [3, 4, 5], [3, 4, 5]] = spin
    return basis @ block @ basis.transpose(0, 2, 1)

