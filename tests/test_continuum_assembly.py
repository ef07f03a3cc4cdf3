"""Tests of upliftlab.continuum.assembly: the plane-strain B-matrix assembly.

References: the patch test (a linear displacement field is reproduced exactly by every
conforming element), scikit-fem's own ``linear_elasticity`` form (an independent assembly of
the same matrix), and h-convergence against a manufactured solution with the a-priori rates of
Lagrange elements (L2 error O(h^(p+1)), energy error O(h^p)), fitted with ``np.polyfit``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import skfem
from skfem.models.elasticity import lame_parameters, linear_elasticity

from upliftlab.checks import InputError
from upliftlab.continuum.assembly import (DEFAULT_INTORDER, body_force, discretise,
                                          internal_force, stiffness, strain)
from upliftlab.continuum.materials import Elastic, plane_strain_tangent
from upliftlab.meshes import soil_mesh

E, NU = 1.0, 0.3
LAM, MU = lame_parameters(E, NU)  # plane strain Lamé constants
ELEMENTS = ("P1", "P2", "Q1", "Q2")


def elastic_D(E=E, nu=NU):
    """Plane-strain 3×3 tangent (xx, yy, xy) with engineering shear, from materials.py."""
    return plane_strain_tangent(Elastic(E, nu)(np.zeros((3, 3, 1)))[1])[..., 0]


def test_plane_tangent_is_hooke_in_plane_strain():
    # Reference: Hooke's law in plane strain, D = [[λ+2μ, λ, 0], [λ, λ+2μ, 0], [0, 0, μ]].
    expected = np.array([[LAM + 2 * MU, LAM, 0.0], [LAM, LAM + 2 * MU, 0.0], [0.0, 0.0, MU]])
    assert np.max(np.abs(elastic_D() - expected)) <= 1e-14


@pytest.mark.parametrize("element", ELEMENTS)
def test_stiffness_equals_scikit_fem_linear_elasticity(element):
    # Reference: skfem.models.elasticity.linear_elasticity assembled on the same basis
    # (an independent assembly path); agreement to round-off, relative 1e-12.
    soil = soil_mesh(2.0, element=element, elements_across=4, domain_width=3, domain_depth=2,
                     grading=2.0)
    disc = discretise(soil.mesh, element)
    ours = stiffness(disc, elastic_D()).toarray()
    theirs = linear_elasticity(LAM, MU).assemble(disc.basis).toarray()
    assert np.max(np.abs(ours - theirs)) <= 1e-12 * np.max(np.abs(theirs))


def test_pattern_gathers_a_scikit_fem_mass_matrix():
    # Reference: scikit-fem's own assembly of ∫ ρ u·v (a matrix for dynamics): gathered into
    # the stiffness pattern and rebuilt, it is unchanged (exact); a matrix coupling DOFs
    # outside the pattern is refused.
    soil = soil_mesh(2.0, element="Q2", elements_across=4, domain_width=3, domain_depth=2)
    disc = discretise(soil.mesh, "Q2")
    fine = skfem.Basis(soil.mesh, disc.basis.elem, intorder=4)
    M = skfem.BilinearForm(lambda u, v, w: 1.8 * (u[0] * v[0] + u[1] * v[1])).assemble(fine)
    rebuilt = disc.pattern.matrix(disc.pattern.gather(M))
    assert abs(rebuilt - M).max() == 0.0
    outside = M.tolil()
    outside[0, disc.ndofs - 1] = 1.0
    with pytest.raises(InputError, match="outside the sparsity pattern"):
        disc.pattern.gather(outside)


def test_default_intorder_is_explicit_and_q2_is_reduced():
    # Reference: DEFAULT_INTORDER; skfem's tensor Gauss rule of order 2 has 2×2 points,
    # its default for Q2 (intorder 4) has 3×3.
    soil = soil_mesh(2.0, element="Q2", elements_across=2, domain_width=2, domain_depth=1)
    assert discretise(soil.mesh, "Q2").dx.shape[1] == 4 and DEFAULT_INTORDER["Q2"] == 2
    assert discretise(soil.mesh, "Q2", intorder=4).dx.shape[1] == 9


@pytest.mark.parametrize("element", ELEMENTS)
def test_patch_test_reproduces_constant_strain(element):
    # Reference: patch test. u = A x + c on the boundary of a graded patch; the interior
    # displacement and every quadrature-point strain are exact to 1e-10.
    soil = soil_mesh(2.0, element=element, elements_across=5, domain_width=3, domain_depth=1.5,
                     grading=3.0)
    disc = discretise(soil.mesh, element)
    A, c = np.array([[2e-3, -1e-3], [4e-3, -3e-3]]), np.array([0.1, -0.2])
    exact = _linear_field(disc, A, c)
    K = stiffness(disc, elastic_D())
    boundary = disc.basis.get_dofs().all()
    u = skfem.solve(*skfem.condense(K, np.zeros(disc.ndofs), x=exact, D=boundary))
    assert np.max(np.abs(u - exact)) <= 1e-10 * np.max(np.abs(exact))
    eps = strain(disc, u)
    target = np.array([A[0, 0], A[1, 1], A[0, 1] + A[1, 0]])
    assert np.max(np.abs(eps - target[:, None, None])) <= 1e-10 * np.max(np.abs(A))


def _linear_field(disc, A, c):
    """The linear field A x + c at every DOF of the vector basis."""
    comp = np.zeros(disc.ndofs, dtype=int)
    for table in (disc.basis.nodal_dofs, disc.basis.facet_dofs, disc.basis.interior_dofs):
        if table.size:
            comp[table[1::2].ravel()] = 1  # rows alternate u^1, u^2 for each local DOF
    x = disc.basis.doflocs
    return np.einsum("ni,in->n", A[comp], x) + c[comp]


def test_internal_force_of_uniform_stress_is_boundary_traction():
    # Reference: divergence theorem. ∫ Bᵀ σ for a constant σ equals the nodal forces of the
    # traction σ·n on the boundary, so the interior nodes carry none (to 1e-12), and the top
    # face carries ∫ σ_yy = σ_yy × width.
    soil = soil_mesh(2.0, element="Q2", elements_across=4, domain_width=3, domain_depth=1)
    disc = discretise(soil.mesh, "Q2")
    sigma = np.array([1.0, -2.0, 0.5])[:, None, None] * np.ones(disc.qp_shape)
    f = internal_force(disc, sigma)
    interior = np.setdiff1d(np.arange(disc.ndofs), disc.basis.get_dofs().all())
    assert np.max(np.abs(f[interior])) <= 1e-12
    top = np.union1d(disc.basis.get_dofs("footing").all("u^2"),
                     disc.basis.get_dofs("surface").all("u^2"))
    assert abs(f[top].sum() - (-2.0) * soil.width) <= 1e-12 * soil.width


def test_body_force_sums_to_weight():
    # Reference: the total of ∫ Nᵀ b is b × area (partition of unity), W × D = 6 × 2.
    soil = soil_mesh(2.0, element="Q2", elements_across=4, domain_width=3, domain_depth=1)
    disc = discretise(soil.mesh, "Q2")
    f = body_force(disc, (0.0, -17.0))
    assert abs(f.sum() + 17.0 * 12.0) <= 1e-10 * 17.0 * 12.0


def test_element_and_mesh_must_match():
    # Reference: the project's input rule: bad input names the field and the valid range.
    soil = soil_mesh(2.0, element="Q1", elements_across=2, domain_width=2, domain_depth=1)
    with pytest.raises(InputError, match="^element = 'P2': needs a MeshTri1"):
        discretise(soil.mesh, "P2")
    with pytest.raises(InputError, match="^intorder = 0: valid range"):
        discretise(soil.mesh, "Q1", intorder=0)


# ---------------------------------------------------------------------------------------------
# Manufactured solution on the unit square
# ---------------------------------------------------------------------------------------------
# u1 = u2 = sin(πx) sin(πy) (zero on the boundary); Navier's equation f = −(λ+μ)∇(∇·u) − μΔu:
# f1 = f2 = (λ+μ)π² (sin πx sin πy − cos πx cos πy) + 2μπ² sin πx sin πy.


def _exact(x, y):
    return np.sin(np.pi * x) * np.sin(np.pi * y)


def _exact_grad(x, y):
    return (np.pi * np.cos(np.pi * x) * np.sin(np.pi * y),
            np.pi * np.sin(np.pi * x) * np.cos(np.pi * y))


def _load(x, y):
    s, c = np.sin(np.pi * x) * np.sin(np.pi * y), np.cos(np.pi * x) * np.cos(np.pi * y)
    return (LAM + MU) * np.pi ** 2 * (s - c) + 2 * MU * np.pi ** 2 * s


def _square(element, n):
    x = np.linspace(0.0, 1.0, n + 1)
    mesh = skfem.MeshQuad1.init_tensor(x, x)
    return mesh.to_meshtri(style="x") if element[0] == "P" else mesh


def _errors(element, n):
    """(h, L2 error, energy error) of the manufactured solution on an n × n mesh."""
    disc = discretise(_square(element, n), element)
    K = stiffness(disc, elastic_D())
    f = skfem.LinearForm(lambda v, w: _load(*w.x) * (v[0] + v[1])).assemble(disc.basis)
    u = skfem.solve(*skfem.condense(K, f, D=disc.basis.get_dofs().all()))
    fine = skfem.Basis(disc.basis.mesh, disc.basis.elem, intorder=8)
    uh = fine.interpolate(u)
    D = elastic_D()

    def l2(w):
        ex = _exact(*w.x)
        return (w.uh[0] - ex) ** 2 + (w.uh[1] - ex) ** 2

    def energy(w):
        gx, gy = _exact_grad(*w.x)
        g = w.uh.grad
        de = np.stack((g[0, 0] - gx, g[1, 1] - gy, g[0, 1] + g[1, 0] - gx - gy))
        return np.einsum("a...,ab,b...->...", de, D, de)

    e2 = math.sqrt(skfem.Functional(l2).assemble(fine, uh=uh))
    ee = math.sqrt(skfem.Functional(energy).assemble(fine, uh=uh))
    return 1.0 / n, e2, ee


@pytest.mark.parametrize("element, sizes, l2_rate, energy_rate", [
    ("P1", (8, 16, 32), 2.0, 1.0),
    ("P2", (4, 8, 16), 3.0, 2.0),
    ("Q1", (8, 16, 32), 2.0, 1.0),
    ("Q2", (4, 8, 16), 3.0, 2.0),
])
def test_manufactured_solution_converges_at_the_a_priori_rates(element, sizes, l2_rate,
                                                               energy_rate):
    # Reference: a-priori estimates for Lagrange elements of degree p on a smooth solution:
    # L2 error O(h^(p+1)), energy error O(h^p). Fitted slopes within 0.15 of the rate.
    h, e2, ee = np.array([_errors(element, n) for n in sizes]).T
    slope_l2 = np.polyfit(np.log(h), np.log(e2), 1)[0]
    slope_energy = np.polyfit(np.log(h), np.log(ee), 1)[0]
    assert abs(slope_l2 - l2_rate) <= 0.15, (element, slope_l2, e2)
    assert abs(slope_energy - energy_rate) <= 0.15, (element, slope_energy, ee)
