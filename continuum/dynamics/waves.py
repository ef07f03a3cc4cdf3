"""The soil's waves on the mesh: wave speeds, the step they allow, and the matrices through
which the soil's inertia, its radiation and an incident wave enter a dynamic run.

The mass is integrated exactly (twice the element's degree: for Q2 3×3 points, not the
stiffness's reduced 2×2, which would make the element mass rank deficient). The
Lysmer–Kuhlemeyer dashpots (normal ρ V_p, tangential ρ V_s) absorb a plane wave that reaches a
boundary at normal incidence exactly; a vertically incident wave of velocity u̇_inc enters
through the bottom's dashpots as the traction 2 ρ V u̇_inc (V = V_s for an S wave, V_p for a P
wave). :data:`COURANT_LIMIT` bounds the implicit route's step (its module docstring says why).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import skfem

__all__ = ["COURANT_LIMIT", "wave_speeds", "smallest_element", "time_step_limit", "full_basis",
           "mass_data", "dashpot_data", "incident_load", "DomainWaves", "domain_waves"]

#: Largest P-wave Courant number V_p dt / h_min (:mod:`~upliftlab.continuum.dynamics.implicit`).
COURANT_LIMIT = 2.0


def wave_speeds(soil) -> tuple[float, float]:
    """(V_p, V_s) (length/s) of the soil; (inf, inf) for massless soil."""
    if soil.density <= 0.0:
        return math.inf, math.inf
    G, nu = soil.shear_modulus, soil.poisson_ratio
    vs = math.sqrt(G / soil.density)
    return vs * math.sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu)), vs


def smallest_element(model) -> float:
    """The shortest element edge of the linear mesh (length)."""
    p, t = model.mesh.p, model.mesh.t
    edges = p[:, np.roll(t, -1, axis=0)] - p[:, t]
    return float(np.sqrt((edges ** 2).sum(axis=0)).min())


def time_step_limit(model) -> float:
    """The largest admissible dt (s): :data:`COURANT_LIMIT` h_min / V_p."""
    return COURANT_LIMIT * smallest_element(model) / wave_speeds(model.soil)[0]


def full_basis(model) -> skfem.CellBasis:
    """The model's element with quadrature exact for the mass (twice the degree)."""
    basis = model.disc.basis
    order = 2 * max(basis.elem.elem.maxdeg, 1)
    return skfem.Basis(model.mesh, basis.elem, intorder=order)


def mass_data(model, kind: str = "consistent") -> np.ndarray:
    """The soil mass matrix ∫ ρ u·v (mass/length per length²) as CSR data in the model's pattern,
    ``consistent`` or ``lumped`` (row sums on the diagonal)."""
    rho = model.soil.density
    M = skfem.BilinearForm(lambda u, v, w: rho * (u[0] * v[0] + u[1] * v[1])).assemble(
        full_basis(model))
    if kind == "lumped":
        from scipy import sparse
        M = sparse.diags(np.asarray(M.sum(axis=1)).ravel())
    return model.disc.pattern.gather(M)


def facet_basis(model, names) -> skfem.FacetBasis | None:
    """The facets of the named boundaries with quadrature exact for a dashpot (None: no facet)."""
    facets = np.concatenate([model.mesh.boundaries[n] for n in names]) if names else []
    if len(facets) == 0:
        return None
    basis = model.disc.basis
    return skfem.FacetBasis(model.mesh, basis.elem, facets=np.asarray(facets),
                            intorder=2 * max(basis.elem.elem.maxdeg, 1))


def dashpot_data(model, boundaries) -> np.ndarray:
    """Lysmer–Kuhlemeyer dashpots ∫ (ρ V_p u_n v_n + ρ V_s u_t v_t) ds on the named
    ``boundaries`` (force·s/length per length²) as CSR data in the model's pattern."""
    vp, vs = wave_speeds(model.soil)
    rho = model.soil.density
    fb = facet_basis(model, list(boundaries))
    if fb is None or rho == 0.0:
        return np.zeros(model.disc.pattern.nnz)

    def form(u, v, w):
        n = w.n
        un, vn = u[0] * n[0] + u[1] * n[1], v[0] * n[0] + v[1] * n[1]
        return rho * (vp * un * vn + vs * (u[0] * v[0] + u[1] * v[1] - un * vn))

    return model.disc.pattern.gather(skfem.BilinearForm(form).assemble(fb))


def incident_load(model, wave: str = "S") -> np.ndarray:
    """The bottom's nodal force per unit incident velocity of a vertically incident ``wave``:
    2 ρ V ∫ v_k ds (k = x for S, y for P), force per (length/s)."""
    vp, vs = wave_speeds(model.soil)
    fb = facet_basis(model, ["bottom"])
    k, speed = (0, vs) if wave == "S" else (1, vp)
    scale = 2.0 * model.soil.density * speed
    return skfem.LinearForm(lambda v, w: scale * v[k]).assemble(fb)


@dataclass(frozen=True, eq=False)
class DomainWaves:
    """What the soil's waves make of a run's domain, computed once for either route:
    ``speeds`` (V_p, V_s) (length/s), the mesh's ``smallest_element`` h_min (length), the
    P-wave ``step_limit`` (s, :func:`time_step_limit`), the ``dashpots`` on the run's
    absorbing boundaries (CSR data in the model's pattern, :func:`dashpot_data`) and the
    ``incident`` load per unit incident velocity (:func:`incident_load`; None without a
    compliant base)."""

    speeds: tuple[float, float]
    smallest_element: float
    step_limit: float
    dashpots: np.ndarray
    incident: np.ndarray | None


def domain_waves(model, dashpots, wave: str | None) -> DomainWaves:
    """The :class:`DomainWaves` of ``model`` with dashpots on the boundaries ``dashpots`` and
    a vertically incident ``wave`` (``"S"`` or ``"P"``) through a compliant base (None: a rigid
    base, no incident wave)."""
    speeds, h_min = wave_speeds(model.soil), smallest_element(model)
    return DomainWaves(speeds, h_min, COURANT_LIMIT * h_min / speeds[0],
                       dashpot_data(model, dashpots),
                       None if wave is None else incident_load(model, wave))
