"""Tests of upliftlab.meshes: graded soil meshes, named boundaries, meshio I/O, mesh quality.

References are geometry (exact coordinates of the box and footing), closed forms of the grading
law stated in ``meshes/soil.py``, hand-counted element numbers, elementary trigonometry for the
quality measures, and mirror symmetry for the rocking-relevant checks.
"""

from __future__ import annotations

import inspect
import math

import meshio
import numpy as np
import pytest
import skfem
from skfem.helpers import dot
from skfem.models.elasticity import lame_parameters, linear_elasticity

from upliftlab.checks import InputError
from upliftlab.meshes import (BOUNDARIES, check_quality, element_areas, footing_dofs,
                              from_options, max_aspect_ratio, min_angle, quality, read_mesh,
                              soil_mesh, write_mesh)
from upliftlab.scenes import ELEMENTS, ContinuumOptions

EXACT = 1e-12


def small(element="Q1", **kw):
    """A small mesh: B = 2, W = 4B, D = 2B, 4 elements across unless overridden."""
    params = dict(domain_width=4.0, domain_depth=2.0, element=element, elements_across=4)
    params.update(kw)
    return soil_mesh(2.0, **params)


def grid_lines(soil):
    """Sorted x of the surface nodes and sorted y of the nodes on the left side."""
    p = soil.mesh.p
    return np.unique(p[0, p[1] == 0.0]), np.unique(p[1, p[0] == -0.5 * soil.width])


# ---------------------------------------------------------------------------------------------
# Geometry of the soil domain
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("element", ELEMENTS)
@pytest.mark.parametrize("n", [4, 5, 16])
def test_footing_nodes_on_surface_with_nodes_at_edges(element, n):
    # Reference: geometry, footing base is y = 0, -B/2 <= x <= B/2 with n elements across.
    soil = soil_mesh(2.0, element=element, elements_across=n)
    x = soil.footing_x
    assert x.size == n + 1
    assert abs(x[0] + 1.0) <= EXACT and abs(x[-1] - 1.0) <= EXACT
    assert np.all(np.diff(x) > 0.0)
    nodes = np.unique(soil.mesh.facets[:, soil.mesh.boundaries["footing"]])
    assert np.max(np.abs(soil.mesh.p[1, nodes])) <= EXACT


@pytest.mark.parametrize("element", ELEMENTS)
def test_domain_area_equals_width_times_depth(element):
    # Reference: the box is W x D = (10 B) x (10 B) with B = 2 -> 400; and 8 x 3.5 with a layer.
    for soil, area in ((soil_mesh(2.0, element=element), 400.0),
                       (soil_mesh(2.0, element=element, domain_width=4, layer_depth=3.5), 28.0)):
        assert abs(element_areas(soil).sum() - area) <= EXACT * area
        p0 = skfem.Basis(soil.mesh, skfem.ElementTriP0() if element[0] == "P"
                         else skfem.ElementQuad0())
        skfem_area = skfem.Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(p0)
        assert abs(skfem_area - area) <= EXACT * area
        assert soil.mesh.p[1].min() == -soil.depth and soil.mesh.p[0].max() == 0.5 * soil.width


@pytest.mark.parametrize("element", ELEMENTS)
@pytest.mark.parametrize("n", [4, 5])
def test_mesh_is_mirror_symmetric_about_footing_centre(element, n):
    # Reference: mirror symmetry x -> -x of nodes, elements and every named boundary.
    mesh = soil_mesh(2.0, element=element, elements_across=n, grading=3.0).mesh
    nodes, mirrored = mesh.p.T, mesh.p.T * [-1.0, 1.0]
    order, order_m = np.lexsort(nodes.T[::-1]), np.lexsort(mirrored.T[::-1])
    assert np.max(np.abs(nodes[order] - mirrored[order_m])) <= EXACT
    image = np.empty(len(nodes), dtype=int)
    image[order_m] = order  # node i mirrors onto node image[i]
    cells = {tuple(sorted(c)) for c in mesh.t.T}
    assert {tuple(sorted(c)) for c in image[mesh.t].T} == cells
    for name in BOUNDARIES:
        facets = {tuple(sorted(f)) for f in mesh.facets[:, mesh.boundaries[name]].T}
        assert {tuple(sorted(f)) for f in image[mesh.facets[:, mesh.boundaries[name]]].T} == facets


@pytest.mark.parametrize("element", ["P1", "Q1"])
def test_boundary_counts_and_facets_on_their_lines(element):
    # Reference: hand count with the grading rule, n = 4, B = 2, W = 8, D = 4:
    # per side ceil(2 log2(1 + 3/1)) = 4 surface elements, ceil(2 log2(1 + 4/1)) = 5 rows.
    soil = small(element)
    b = soil.mesh.boundaries
    assert {k: len(v) for k, v in b.items()} == {"footing": 4, "surface": 8, "sides": 10,
                                                 "bottom": 12}
    x, y = (soil.mesh.p[k][soil.mesh.facets] for k in (0, 1))
    assert np.all(np.abs(y[:, b["footing"]]) <= EXACT)
    assert np.all(np.abs(x[:, b["footing"]]) <= 1.0 + EXACT)
    assert np.all(np.abs(y[:, b["surface"]]) <= EXACT)
    assert np.all(np.abs(x[:, b["surface"]]) >= 1.0 - EXACT)
    assert np.all(np.abs(np.abs(x[:, b["sides"]]) - 4.0) <= EXACT)
    assert np.all(np.abs(y[:, b["bottom"]] + 4.0) <= EXACT)
    union = np.concatenate([b[name] for name in BOUNDARIES])
    assert np.array_equal(np.sort(union), soil.mesh.boundary_facets())  # disjoint and complete


@pytest.mark.parametrize("element", ELEMENTS)
def test_identical_parameters_give_identical_mesh(element):
    # Reference: determinism; two builds compare bit for bit.
    a, b = (soil_mesh(1.5, element=element, elements_across=7, grading=2.5) for _ in range(2))
    assert a == b
    assert np.array_equal(a.mesh.p, b.mesh.p) and np.array_equal(a.mesh.t, b.mesh.t)
    for name in BOUNDARIES:
        assert np.array_equal(a.mesh.boundaries[name], b.mesh.boundaries[name])


def test_refinement_halves_edge_element_and_every_size():
    # Reference: uniform footing (grading 1) has edge size B/n exactly; the outer counts grow in
    # proportion to n, so the largest elements halve too (within the rounding of one element).
    coarse, fine = (soil_mesh(2.0, elements_across=n, element="Q1") for n in (16, 32))
    assert abs(coarse.edge_size - 2.0 / 16) <= EXACT and abs(fine.edge_size - 2.0 / 32) <= EXACT
    for k in (0, 1):
        ratio = np.diff(grid_lines(fine)[k]).max() / np.diff(grid_lines(coarse)[k]).max()
        assert 0.45 <= ratio <= 0.55


@pytest.mark.parametrize("n", [16, 32])
def test_grading_ratio_centre_to_edge(n):
    # Reference: closed form of the grading law. Across the footing sizes are h0 q^k, k the
    # number of elements from the nearer edge, q = g^(1/(n/2 - 1)), h0 = (B/2) / sum q^k.
    g, half = 4.0, n // 2
    soil = soil_mesh(2.0, elements_across=n, grading=g, element="Q1")
    sizes = np.diff(soil.footing_x)
    q = g ** (1.0 / (half - 1))
    h0 = 1.0 / np.sum(q ** np.arange(half))
    assert abs(sizes[0] - h0) <= EXACT and abs(sizes[-1] - h0) <= EXACT
    assert abs(sizes[half] / sizes[0] - g) <= 1e-12 * g
    assert np.allclose(sizes[1:half] / sizes[:half - 1], q, rtol=1e-12, atol=0.0)


def test_outer_elements_grow_geometrically_from_edge_size():
    # Reference: grading law beyond the edges: first size = edge size h0, constant ratio q >= 1,
    # the sizes summing to the distance to the side (or the depth) exactly.
    soil = soil_mesh(2.0, grading=2.0, element="Q1")
    x, y = grid_lines(soil)
    outer = np.diff(x[x >= 1.0])
    rows = np.diff(y)[::-1]  # from the surface down
    for sizes, length in ((outer, 9.0), (rows, 20.0)):
        assert abs(sizes[0] - soil.edge_size) <= EXACT
        ratios = sizes[1:] / sizes[:-1]
        assert np.all(ratios >= 1.0) and np.ptp(ratios[:-1]) <= 1e-9  # last absorbs rounding
        assert abs(sizes.sum() - length) <= EXACT * length


def test_layer_depth_overrides_domain_depth():
    # Reference: a finite layer 3 (length units) deep, whatever domain_depth says.
    soil = small(layer_depth=3.0, domain_depth=50.0)
    assert soil.depth == 3.0
    bottom = soil.mesh.facets[:, soil.mesh.boundaries["bottom"]]
    assert np.all(soil.mesh.p[1, bottom] == -3.0)


def test_skfem_element_matches_name():
    # Reference: the element table in the brief (P1/P2 triangles, Q1/Q2 quads).
    expected = {"P1": (skfem.MeshTri1, skfem.ElementTriP1), "P2": (skfem.MeshTri1,
                skfem.ElementTriP2), "Q1": (skfem.MeshQuad1, skfem.ElementQuad1),
                "Q2": (skfem.MeshQuad1, skfem.ElementQuad2)}
    for name, (mesh_type, element_type) in expected.items():
        soil = small(name)
        assert type(soil.mesh) is mesh_type and type(soil.skfem_element) is element_type


def test_from_options_and_defaults_follow_continuum_options():
    # Reference: ContinuumOptions in upliftlab.scenes (the scene's [continuum] defaults).
    defaults = ContinuumOptions()
    signature = inspect.signature(soil_mesh).parameters
    for name in ("domain_width", "domain_depth", "element", "elements_across", "grading"):
        assert signature[name].default == getattr(defaults, name)
    options = ContinuumOptions(domain_width=3.0, domain_depth=2.0, element="P2",
                               elements_across=6, grading=2.0)
    a, b = from_options(2.0, options), soil_mesh(2.0, domain_width=3.0, domain_depth=2.0,
                                                  element="P2", elements_across=6, grading=2.0)
    assert a == b and np.array_equal(a.mesh.p, b.mesh.p)
    assert a.parameters["elements_across"] == 6


@pytest.mark.parametrize("field, value", [
    ("footing_width", 0.0), ("footing_width", -1.0), ("footing_width", math.nan),
    ("domain_width", 1.0), ("domain_width", 0.5), ("domain_depth", 0.0),
    ("element", "Q3"), ("elements_across", 1), ("elements_across", 2.5),
    ("grading", 0.5), ("grading", 101.0), ("layer_depth", 0.0), ("layer_depth", -2.0),
])
def test_bad_parameters_raise_input_error_naming_the_field(field, value):
    # Reference: the project's input rule: bad input names the field, the value and the valid range.
    kwargs = {"footing_width": 2.0, field: value}
    with pytest.raises(InputError, match=f"^{field} = ") as error:
        soil_mesh(kwargs.pop("footing_width"), **kwargs)
    assert ("must" in str(error.value)) or ("range" in str(error.value)) \
        or ("expected" in str(error.value))


# ---------------------------------------------------------------------------------------------
# Footing DOFs for the contact code
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("element, per_facet", [("P1", 0), ("Q1", 0), ("P2", 1), ("Q2", 1)])
def test_footing_dofs_count_and_locations(element, per_facet):
    # Reference: a Lagrange basis has one DOF per node and component, plus one per facet and
    # component for P2/Q2 (at the facet midpoint).
    soil = small(element, elements_across=5)
    basis = skfem.Basis(soil.mesh, skfem.ElementVector(soil.skfem_element), intorder=2)
    dofs = soil.footing_dofs(basis)
    nodes, facets = soil.footing_x, len(soil.mesh.boundaries["footing"])
    assert len(dofs) == 2 * (nodes.size + per_facet * facets)
    midpoints = 0.5 * (nodes[1:] + nodes[:-1])
    expected = np.sort(np.concatenate((nodes, midpoints))) if per_facet else nodes
    assert np.max(np.abs(dofs.x - expected)) <= EXACT
    assert np.array_equal(basis.doflocs[:, dofs.ux], basis.doflocs[:, dofs.uy])
    assert np.max(np.abs(basis.doflocs[1, dofs.ux])) <= EXACT
    assert np.intersect1d(dofs.ux, dofs.uy).size == 0


def test_p2_settlement_is_rigid_along_the_whole_footing():
    # Reference: prescribing a uniform settlement d on the helper's DOFs must give u = (0, -d)
    # at every point of the footing facets (midside DOFs included), and by mirror symmetry the
    # horizontal force and the moment about x = 0 vanish.
    soil = small("P2", elements_across=6)
    element = skfem.ElementVector(soil.skfem_element)
    basis = skfem.Basis(soil.mesh, element, intorder=4)
    dofs = footing_dofs(basis)
    stiffness = skfem.asm(linear_elasticity(*lame_parameters(50e3, 0.3)), basis)
    u = np.zeros(basis.N)
    u[dofs.uy] = -0.01
    fixed = np.concatenate((dofs.all, basis.get_dofs("bottom").all()))
    u = skfem.solve(*skfem.condense(stiffness, np.zeros(basis.N), x=u, D=fixed))
    facet_basis = skfem.FacetBasis(soil.mesh, element, facets="footing", intorder=4)
    trace = facet_basis.interpolate(u)
    assert np.max(np.abs(trace[0] - 0.0)) <= EXACT
    assert np.max(np.abs(trace[1] + 0.01)) <= EXACT
    force = stiffness @ u
    vertical = force[dofs.uy].sum()
    assert vertical < 0.0  # sign convention: footing DOF forces are negative in compression
    assert abs(force[dofs.ux].sum()) <= 1e-9 * abs(vertical)
    assert abs(np.dot(dofs.x, force[dofs.uy])) <= 1e-9 * abs(vertical)
    work = skfem.Functional(lambda w: dot(w["u"], w["u"])).assemble(facet_basis,
                                                                     u=facet_basis.interpolate(u))
    assert abs(work - 0.01 ** 2 * 2.0) <= 1e-12  # |u|^2 integrated over the footing, B = 2


def test_footing_dofs_refuses_scalar_basis_and_foreign_mesh():
    # Reference: the helper needs a 2-component vector basis on the same mesh.
    soil = small("P2")
    with pytest.raises(InputError, match="ElementVector"):
        footing_dofs(skfem.Basis(soil.mesh, soil.skfem_element))
    other = small("P2").mesh
    with pytest.raises(InputError, match="another mesh"):
        soil.footing_dofs(skfem.Basis(other, skfem.ElementVector(soil.skfem_element)))


# ---------------------------------------------------------------------------------------------
# Mesh quality
# ---------------------------------------------------------------------------------------------


def one_triangle(points):
    return skfem.MeshTri1(np.array(points, dtype=float).T, np.array([[0], [1], [2]]))


def one_quad(points):
    return skfem.MeshQuad1(np.array(points, dtype=float).T, np.array([[0], [1], [2], [3]]))


@pytest.mark.parametrize("mesh, angle, aspect", [
    (one_triangle([(0, 0), (1, 0), (0, 1)]), 45.0, math.sqrt(3.0)),  # right isosceles
    (one_triangle([(0, 0), (2, 0), (1, math.sqrt(3.0))]), 60.0, 1.0),  # equilateral
    (one_quad([(0, 0), (1, 0), (1, 1), (0, 1)]), 90.0, 1.0),  # unit square
    (one_quad([(0, 0), (4, 0), (4, 1), (0, 1)]), 90.0, 4.0),  # 4 x 1 rectangle
])
def test_quality_of_known_elements(mesh, angle, aspect):
    # Reference: trigonometry; aspect ratio = (ideal element area on the longest edge) / area,
    # i.e. (sqrt(3)/4) 2 / (1/2) = sqrt(3) for the right isosceles triangle, a/b for a rectangle.
    assert abs(min_angle(mesh) - angle) <= 1e-12 * angle
    assert abs(max_aspect_ratio(mesh) - aspect) <= 1e-12 * aspect
    assert check_quality(mesh).elements == 1


@pytest.mark.parametrize("element", ELEMENTS)
def test_default_soil_meshes_pass_quality_check(element):
    # Reference: measured worst values of the default tensor grid (tall narrow elements deep
    # under the footing): min angle 4.83 degrees (triangles), aspect 11.8 (quads), 10.3 (tris).
    result = check_quality(soil_mesh(2.0, element=element))
    assert result.min_angle >= 4.8 and result.max_aspect <= 12.0


def two_triangles(moved):
    p = np.array([(0, 0), (1, 0), (1, 1), moved], dtype=float).T
    return skfem.MeshTri1(p, np.array([[0, 0], [1, 2], [2, 3]]))


@pytest.mark.parametrize("mesh, message", [
    (two_triangles((0.5, 0.5)), r"mesh element 1: area = 0: must be > 0"),  # collinear
    (one_quad([(0, 0), (1, 1), (1, 0), (0, 1)]), r"mesh element 0: area = 0"),  # bowtie
    (one_quad([(0, 0), (2, 1), (0, 2), (0.5, 1)]), r"mesh element 0: corner angle = -"),  # dart
    (two_triangles((1.0, 0.5)), r"mesh element \d: folded over element \d"),  # inverted
    (one_triangle([(0, 0), (1, 0), (0, 0.005)]), r"mesh element 0: minimum angle = 0\.286"),
])
def test_degenerate_meshes_are_refused(mesh, message):
    # Reference: each mesh is built degenerate by hand (zero area, self-intersecting, reflex
    # corner, overlapping neighbours, an angle of atan(0.005) = 0.29 degrees).
    with pytest.raises(InputError, match=message):
        check_quality(mesh)


def test_quality_thresholds_are_parameters():
    # Reference: the sliver's worst angle is atan(0.005/1) = 0.2865 degrees.
    sliver = one_triangle([(0, 0), (1, 0), (0, 0.005)])
    result = check_quality(sliver, min_angle=0.25, max_aspect=1e3)
    assert abs(result.min_angle - math.degrees(math.atan(0.005))) <= 1e-10
    assert result.min_angle_element == quality(sliver).min_angle_element == 0
    with pytest.raises(InputError, match=r"aspect ratio = \d+.*valid range is \[1, 10\]"):
        check_quality(small("Q1", grading=20.0), max_aspect=10.0)


# ---------------------------------------------------------------------------------------------
# I/O
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf", ".msh"])
@pytest.mark.parametrize("element", ["P1", "Q2"])
def test_round_trip_keeps_nodes_cells_and_boundaries(tmp_path, suffix, element):
    # Reference: the written mesh itself; a round trip must be exact.
    soil = small(element, elements_across=5, grading=3.0)
    path = write_mesh(tmp_path / f"soil{suffix}", soil)
    mesh = read_mesh(path)
    assert type(mesh) is type(soil.mesh)
    assert np.array_equal(mesh.p, soil.mesh.p) and np.array_equal(mesh.t, soil.mesh.t)
    assert sorted(mesh.boundaries) == sorted(BOUNDARIES)
    for name in BOUNDARIES:
        assert np.array_equal(mesh.boundaries[name], soil.mesh.boundaries[name])


def test_xdmf_writes_its_h5_beside_the_file_and_nothing_else(tmp_path, monkeypatch):
    # Reference: meshio names the heavy data <stem>.h5 and refers to it by base name.
    monkeypatch.chdir(tmp_path)
    target = tmp_path / "out" / "mesh.xdmf"
    write_mesh(target, small())
    assert sorted(p.name for p in target.parent.iterdir()) == ["mesh.h5", "mesh.xdmf"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert "mesh.h5:/" in target.read_text()


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf", ".msh"])
def test_failed_write_keeps_previous_file(tmp_path, monkeypatch, suffix):
    # Reference: the project's rule for output: nothing already written is lost or half-written.
    target = tmp_path / f"mesh{suffix}"
    write_mesh(target, small())
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def broken(path, *args, **kwargs):
        with open(path, "w") as file:
            file.write("half")
        raise RuntimeError("disk full")

    monkeypatch.setattr(meshio, "write", broken)
    with pytest.raises(RuntimeError, match="disk full"):
        write_mesh(target, small("P1"))
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf", ".msh"])
def test_mesh_without_named_boundaries_is_refused(tmp_path, suffix):
    # Reference: read_mesh requires footing, surface, sides and bottom.
    bare = skfem.MeshQuad1().refined(2)
    partial = bare.with_boundaries({"footing": lambda x: x[1] == 1.0})
    write_mesh(tmp_path / f"bare{suffix}", bare)
    write_mesh(tmp_path / f"partial{suffix}", partial)
    with pytest.raises(InputError, match="footing, surface, sides, bottom are missing"):
        read_mesh(tmp_path / f"bare{suffix}")
    with pytest.raises(InputError, match=r"surface, sides, bottom are missing \(found \['footing"):
        read_mesh(tmp_path / f"partial{suffix}")
    assert len(read_mesh(tmp_path / f"partial{suffix}", required=["footing"])
               .boundaries["footing"]) == 4


GMSH_41 = """$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
5
1 1 "footing"
1 2 "surface"
1 3 "sides"
1 4 "bottom"
2 5 "soil"
$EndPhysicalNames
$Entities
1 6 1 0
1 5 5 0 0
1 -0.5 0 0 0.5 0 0 1 1 0
2 -1.5 0 0 -0.5 0 0 1 2 0
3 0.5 0 0 1.5 0 0 1 2 0
4 -1.5 -1 0 -1.5 0 0 1 3 0
5 1.5 -1 0 1.5 0 0 1 3 0
6 -1.5 -1 0 1.5 -1 0 1 4 0
1 -1.5 -1 0 1.5 0 0 1 5 0
$EndEntities
$Nodes
2 9 1 9
0 1 0 1
9
5 5 0
2 1 0 8
1
2
3
4
5
6
7
8
-1.5 0 0
-0.5 0 0
0.5 0 0
1.5 0 0
-1.5 -1 0
-0.5 -1 0
0.5 -1 0
1.5 -1 0
$EndNodes
$Elements
7 11 1 11
1 1 1 1
1 2 3
1 2 1 1
2 1 2
1 3 1 1
3 3 4
1 4 1 1
4 1 5
1 5 1 1
5 4 8
1 6 1 3
6 5 6
7 6 7
8 7 8
2 1 3 3
9 5 6 2 1
10 6 7 3 2
11 7 8 4 3
$EndElements
"""


def test_reads_a_gmsh_41_mesh_with_physical_groups(tmp_path):
    # Reference: a hand-written Gmsh 4.1 file, B = 1, W = 3, D = 1, three quads, an unused
    # geometry node at (5, 5) and the four boundaries as line physical groups.
    path = tmp_path / "user.msh"
    path.write_text(GMSH_41)
    mesh = read_mesh(path)
    assert type(mesh) is skfem.MeshQuad1 and mesh.p.shape == (2, 8) and mesh.t.shape == (4, 3)
    counts = {name: len(facets) for name, facets in mesh.boundaries.items()}
    assert counts == {"footing": 1, "surface": 2, "sides": 2, "bottom": 3}
    footing = mesh.p[:, mesh.facets[:, mesh.boundaries["footing"]]]
    assert np.array_equal(np.sort(footing[0].ravel()), [-0.5, 0.5]) and np.all(footing[1] == 0)
    assert abs(element_areas(mesh).sum() - 3.0) <= EXACT


def test_bad_files_raise_input_error(tmp_path):
    # Reference: the project's input rule: errors name the path and what is wrong.
    with pytest.raises(InputError, match=r"suffix '\.stl' must be one of \.vtu, \.xdmf, \.msh"):
        write_mesh(tmp_path / "mesh.stl", small())
    with pytest.raises(InputError, match="no such file"):
        read_mesh(tmp_path / "absent.vtu")
    (tmp_path / "junk.msh").write_text("not a mesh")
    with pytest.raises(InputError, match=r"junk\.msh: not a readable \.msh mesh"):
        read_mesh(tmp_path / "junk.msh")
    points = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], dtype=float)
    cells = [("quad", np.array([[0, 1, 2, 3]])), ("line", np.array([[0, 2]]))]
    flags = {f"boundary:{name}": [np.zeros(1, np.int8), np.ones(1, np.int8)]
             for name in BOUNDARIES}
    meshio.write(tmp_path / "diagonal.vtu", meshio.Mesh(points, cells, cell_data=flags))
    with pytest.raises(InputError, match=r"line with nodes \[0, 2\] is not an edge"):
        read_mesh(tmp_path / "diagonal.vtu")
