"""The exact impedance of a rigid strip on the elastic half-plane, independent of the FE code.

This is the reference the finite-element impedance (:mod:`.impedance`) is tested against. It
shares nothing with the FE code (no mesh, no basis, no boundary): only numpy and scipy.

**The half-plane's surface Green's function** (Lamb's problem in the wavenumber domain). Plane
strain, depth z ≥ 0 (down), time factor e^{+iωt}, shear modulus μ, wavenumbers k_s = ω/V_s and
k_p = ω/V_p. A surface traction (p_x, p_z) on the soil, Fourier-transformed as
P(k) = ∫ p(x) e^{ikx} dx, gives the surface displacement U(k) = G(k) P(k) with

    μ R G = [[−ν_s k_s²,            i k (F − 2ν_pν_s)],
             [−i k (F − 2ν_pν_s),   −ν_p k_s²         ]],

F = 2k² − k_s², ν_α = √(k² − k_α²), R = F² − 4k²ν_pν_s (the Rayleigh function). It follows
from the Lamé potentials with the traction conditions at z = 0 (derived in the docstring of
:func:`green`). For large |k| it tends to the static (Flamant/Cerruti) kernel:
G_xx, G_zz → (1 − ν)/(μ|k|), G_xz → −i(1 − 2ν)/(2μk).

**Radiation.** ν_α uses the principal square root, and the wavenumber integrals run on a path
above the real axis where the branch points k_p, k_s and the Rayleigh pole k_R lie: the path
that a vanishing material damping (k_α slightly below the real axis for e^{+iωt}) selects. So
the waves are outgoing, and no damping is added.

**The mixed problem.** The contact tractions under the strip |x| ≤ b are expanded in the
Chebyshev series p(x) = Σ a_n T_n(x/b)/√(1 − x²/b²), n < ``terms``, which carries the edge's
inverse-square-root singularity exactly (the bonded interface's weak oscillation,
(b − |x|)^{−1/2 ± iε} with ε = ln(3 − 4ν)/(2π), is approximated by the series). The displacement
conditions (rigid motion under the strip) are imposed by Galerkin projection on the same
functions. Their transforms are Bessel functions, ∫ T_n(x/b)(1 − x²/b²)^{−1/2} e^{ikx} dx =
π b iⁿ J_n(kb), so every matrix entry is one integral ∫₀^∞ J_m(kb) J_n(kb) G(k) dk. The static
part of each kernel is subtracted and integrated exactly (Weber–Schafheitlin:
∫₀^∞ J_m J_n dt/t = 2 sin((m − n)π/2)/(π(m² − n²)), 1/(2n) for m = n; and
∫₀^∞ J₀(t)² t/(t² + 1) dt = I₀(1)K₀(1)), so the numerical remainder decays as k⁻⁴; it is
integrated by Gauss–Legendre panels along the deformed path and then the real axis.

**Interfaces.** ``bonded``: the footing ties both displacement components (u_x = U, u_z = Δ + φx);
``relaxed`` (frictionless): no shear traction, u_z = Δ + φx only (Luco & Westmann's "relaxed"
contact); its horizontal impedance is zero.

**Result.** :func:`strip_impedance` returns the impedance per unit length in the conventions of
the continuum model: generalised displacements (u, v, θ) of the base centre (v up, θ pushing the
right edge down), forces (H, −N, M) — the FE's ``L.T @ S @ L`` — as a complex 3×3 matrix,
e^{+iωt}, so Im K ≥ 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import special

from ...checks import InputError, finite, integer_at_least, one_of, positive

__all__ = ["StripImpedance", "strip_impedance", "green", "RELAXED", "BONDED"]

RELAXED, BONDED = "relaxed", "bonded"

#: Gauss–Legendre points per panel.
_POINTS = 16


@dataclass(frozen=True, eq=False)
class StripImpedance:
    """The exact impedance of the rigid strip: ``a0`` (n), ``matrix`` (n, 3, 3) complex per unit
    length for (u, v, θ) → (H, −N, M) in the continuum model's conventions, the soil's ``G``
    (force/length²), ``poisson`` ν, the ``width`` B, the ``interface`` and the series ``terms``."""

    a0: np.ndarray
    matrix: np.ndarray = field(repr=False)
    shear_modulus: float
    poisson: float
    width: float
    interface: str
    terms: int

    @property
    def vertical(self) -> np.ndarray:
        return self.matrix[:, 1, 1]

    @property
    def horizontal(self) -> np.ndarray:
        """K_h with θ held (zero for the relaxed interface)."""
        return self.matrix[:, 0, 0]

    @property
    def rocking(self) -> np.ndarray:
        """K_r with the horizontal motion held."""
        return self.matrix[:, 2, 2]

    @property
    def coupling(self) -> np.ndarray:
        """K_hr = ∂H/∂θ = ∂M/∂u (force/rad per length)."""
        return self.matrix[:, 0, 2]


def _slowness(poisson: float) -> float:
    """V_s/V_p."""
    return math.sqrt((1.0 - 2.0 * poisson) / (2.0 * (1.0 - poisson)))


def green(s, a0: float, poisson: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(g_xx, g_zz, g_xz) of the half-plane at dimensionless wavenumbers ``s`` = k b (complex
    allowed) for a0 = ω b/V_s, per μ = 1, b = 1: G_αβ(k) = b g_αβ(kb)/μ.

    Derivation: potentials φ = A e^{−ν_p z − ikx}, ψ = B e^{−ν_s z − ikx}, u_x = φ,x − ψ,z,
    u_z = φ,z + ψ,x; at z = 0, σ_zz = μ[F A + 2ikν_s B] and σ_xz = μ[2ikν_p A − F B]; the
    surface traction on the soil is (p_x, p_z) = (−σ_xz, −σ_zz). Solving for A, B and
    evaluating u at z = 0 gives the matrix of the module docstring."""
    s = np.asarray(s, dtype=complex)
    sp = a0 * _slowness(poisson)
    nu_p, nu_s = np.sqrt(s * s - sp * sp), np.sqrt(s * s - a0 * a0)
    F = 2.0 * s * s - a0 * a0
    R = F * F - 4.0 * s * s * nu_p * nu_s
    return -nu_s * a0 * a0 / R, -nu_p * a0 * a0 / R, 1j * s * (F - 2.0 * nu_p * nu_s) / R


def _panels(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on consecutive panels between ``edges``."""
    x, w = np.polynomial.legendre.leggauss(_POINTS)
    lo, hi = edges[:-1, None], edges[1:, None]
    return (0.5 * (hi - lo) * x + 0.5 * (hi + lo)).ravel(), (0.5 * (hi - lo) * w).ravel()


def _path(a0: float, poisson: float, s_max: float) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature nodes s (complex) and weights ds on the path 0 → T above the real axis, then
    T → ``s_max`` on it. The arc s = t + iH sin(πt/T) clears k_p, k_s and the Rayleigh pole
    (k_R < 1.1 k_s for ν ≥ 0); its panels are graded towards 0, where the small-a0 features
    sit."""
    T = max(2.4 * a0, a0 + 1.5)
    H = min(0.5, 0.4 * T)
    start = min(1e-3, 1e-2 * a0 * _slowness(poisson))
    arc_edges = np.concatenate(([0.0], np.geomspace(start, T, 48)))
    t, wt = _panels(arc_edges)
    s_arc = t + 1j * H * np.sin(math.pi * t / T)
    ds_arc = wt * (1.0 + 1j * H * math.pi / T * np.cos(math.pi * t / T))
    count = int(math.ceil((s_max - T) / 1.0))
    s_line, ds_line = _panels(np.linspace(T, s_max, count + 1))
    return np.concatenate((s_arc, s_line)), np.concatenate((ds_arc, ds_line))


def _static_integrals(terms: int, kind: str) -> np.ndarray:
    """Exact ∫₀^∞ J_m(t) J_n(t) h(t) dt of the subtracted static kernels (module docstring):
    h = 1/t, except h = t/(t² + 1) for m = n = 0 of the even (``"even"``) kernels. Only the
    parity that the kernel couples (m + n even for even kernels, odd for the odd one) is
    filled."""
    m, n = np.meshgrid(np.arange(terms), np.arange(terms), indexing="ij")
    out = np.zeros((terms, terms))
    parity = 0 if kind == "even" else 1
    pick = ((m + n) % 2 == parity) & (m != n)
    out[pick] = 2.0 * np.sin((m[pick] - n[pick]) * math.pi / 2.0) / (
        math.pi * (m[pick] ** 2 - n[pick] ** 2))
    if kind == "even":
        diag = np.arange(1, terms)
        out[diag, diag] = 1.0 / (2.0 * diag)
        out[0, 0] = float(special.i0(1.0) * special.k0(1.0))
    return out


def _bessel_integrals(a0: float, poisson: float, terms: int, s_max: float) -> dict:
    """I_mn = ∫₀^∞ J_m J_n g ds for the three kernels (dimensionless, μ = b = 1)."""
    s, ds = _path(a0, poisson, s_max)
    J = special.jv(np.arange(terms)[:, None], s[None, :])
    gxx, gzz, gxz = green(s, a0, poisson)
    even_inf, odd_inf = 1.0 - poisson, -0.5j * (1.0 - 2.0 * poisson)
    out = {}
    for name, g, g_inf, kind in (("xx", gxx, even_inf, "even"), ("zz", gzz, even_inf, "even"),
                                 ("xz", gxz, odd_inf, "odd")):
        remainder = (J * (ds * (g - g_inf / s))) @ J.T
        if kind == "even":
            remainder[0, 0] = np.sum(J[0] ** 2 * ds * (g - g_inf * s / (s * s + 1.0)))
        out[name] = remainder + g_inf * _static_integrals(terms, kind)
    return out


def _galerkin(a0: float, poisson: float, terms: int, interface: str, s_max: float):
    """The Galerkin matrix A on the unknowns [a_z (terms), a_x (terms) if bonded], divided by
    π b²/μ: (1/2π)∫ Φ_m(−k) G(k) Φ_n(k) dk with Φ_n(k) = π b iⁿ J_n(kb) is
    (π b²/μ) i^{n−m} I_mn, the whole k axis giving twice the integral over k > 0 for the parity
    each kernel couples (the other parity's integrand is odd and vanishes)."""
    I = _bessel_integrals(a0, poisson, terms, s_max)
    m, n = np.meshgrid(np.arange(terms), np.arange(terms), indexing="ij")
    phase = (1j) ** ((n - m) % 4)
    even = ((m + n) % 2 == 0)
    A_zz = np.where(even, phase * I["zz"], 0.0)
    if interface == RELAXED:
        return A_zz
    A_xx = np.where(even, phase * I["xx"], 0.0)
    A_xz = np.where(~even, phase * I["xz"], 0.0)
    # the zx kernel is g_xz(−k): its integrals are −I_xz (J_m J_n of odd m + n is odd in k)
    A_zx = np.where(~even, -phase * I["xz"], 0.0)
    return np.block([[A_zz, A_zx], [A_xz, A_xx]])


def _dimensionless(a0: float, poisson: float, terms: int, interface: str,
                   s_max: float) -> np.ndarray:
    """The impedance (3, 3) for μ = b = 1 in the half-plane's own variables
    (U, Δ down, φ) -> (P_x, P_z, M)."""
    A = _galerkin(a0, poisson, terms, interface, s_max)
    size = A.shape[0]
    # right-hand sides: ∫ φ_m (rigid displacement) dx / π = δ_m0 (unit Δ or U), δ_m1/2 (unit φ)
    rhs = np.zeros((size, 3), dtype=complex)
    rhs[0, 1] = 1.0            # Δ: u_z = 1
    rhs[1, 2] = 0.5            # φ: u_z = x
    if interface == BONDED:
        rhs[terms, 0] = 1.0    # U: u_x = 1
    a = np.linalg.solve(A, rhs)
    K = np.zeros((3, 3), dtype=complex)
    # resultants: ∫ φ_n dx = π δ_n0, ∫ x φ_n dx = (π/2) δ_n1; with A carrying no π the
    # coefficients a are per π, so the forces are π · a · π-integrals / π = π a_0, (π/2) a_1
    K[1] = math.pi * a[0]
    K[2] = 0.5 * math.pi * a[1]
    if interface == BONDED:
        K[0] = math.pi * a[terms]
    return K


def strip_impedance(a0, *, shear_modulus: float, poisson: float, width: float,
                    interface: str = RELAXED, terms: int = 24,
                    s_max: float = 400.0) -> StripImpedance:
    """The exact impedance of a rigid strip of ``width`` B on the elastic half-plane at the
    dimensionless frequencies ``a0`` = ω (B/2)/V_s (> 0), for the ``interface`` ``relaxed``
    (frictionless) or ``bonded``. ``terms`` Chebyshev functions per traction component;
    ``s_max`` ends the wavenumber integrals (the remainder beyond it is O(s_max⁻³))."""
    G = positive("shear_modulus", shear_modulus)
    nu = finite("poisson", poisson)
    if not -1.0 < nu < 0.5:
        raise InputError(f"poisson = {nu:g}: valid range is (-1, 0.5)")
    B = positive("width", width)
    one_of("interface", interface, (RELAXED, BONDED))
    terms = integer_at_least("terms", terms, 2)
    a0 = np.atleast_1d(np.asarray(a0, dtype=float))
    if a0.ndim != 1 or not (np.isfinite(a0).all() and (a0 > 0.0).all()):
        raise InputError(f"a0 = {a0!r}: expected positive finite frequencies")
    b = 0.5 * B
    # half-plane (U, Δ down, φ; P_x, P_z, M) -> model (u, v up, θ; H, −N, M): Δ = −v and
    # P_z = N, so the v row and column change sign; θ = φ (u_z = xθ − v)
    flip = np.diag([1.0, -1.0, 1.0])
    scale = np.array([[1.0, 1.0, b], [1.0, 1.0, b], [b, b, b * b]]) * G
    mats = np.array([flip @ _dimensionless(float(x), nu, terms, interface, s_max) @ flip
                     for x in a0]) * scale
    return StripImpedance(a0=a0, matrix=mats, shear_modulus=G, poisson=nu, width=B,
                          interface=interface, terms=terms)
