"""The pictures of a footing on a soil mesh drawn right, checked by numbers
(upliftlab.meshes.colours, .sheet, .raster, .page, .gif, .render).

References: a made-up run on a small Q2 mesh whose fields are closed forms chosen here — a
displacement u = (a y, −b x) at every node, a plastic strain in two named elements only, a
contact pressure p = p0 (c − x) for x < c and zero beyond (the footing lifted off beyond c,
where the gap opens as g = g0 (x − c)) — and matplotlib, an independent drawing library: its
``YlOrRd`` colour map and ``LogNorm``, and the axes transforms of the matplotlib page (the
notebook's figure, same layout) for where a data point lands on the raster. What must follow:
- the colour table is matplotlib's YlOrRd through its norm (to one table step, 1.4 of 255);
- the drawn soil cells of the figure are the mesh's cells at (x, y) + scale × u (to 1e-12 B);
- the pixel at an element's drawn centre in the PNG has the colour map's colour of its plastic
  strain (the top for the largest, the palest for none), within 6 of 255 per channel, and the
  colour bar's pixel at that strain (from the layout: log scale over 3 decades) the same;
- the footing block's pixels lie inside its corners moved by (u + θ y, v − θ x) × scale;
- the pressure fill's colour appears above the base where p > 0 and not where the gap opened;
- a GIF frame, decoded, is its page within the fixed palette's error (mean < 2 of 255);
- the budget rule of :func:`~upliftlab.meshes.render.frames_within` (its docstring's formula);
- the picture set's PNG is :func:`~upliftlab.meshes.render.render_uplift`'s, pixel for pixel;
- writing the pictures never imports matplotlib (a fresh interpreter's ``sys.modules``).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import skfem
from matplotlib import colormaps
from matplotlib.colors import LogNorm
from PIL import Image

from upliftlab.meshes import soil_mesh
from upliftlab.meshes.colours import colours_of
from upliftlab.meshes.page import CMAP, FOOTING_HEIGHT, Page, layout
from upliftlab.meshes.sheet import FOOTING, Sheet
from upliftlab.meshes.render import (MIN_FRAMES, animate_uplift, frames, frames_within,
                                     linear_submesh, render_uplift, uplift_view,
                                     write_pictures)

B, A, BB, C = 2.0, 2e-3, 1e-3, 0.3  # footing width; u = (A y, -BB x); lift-off beyond x = C
HOT, WARM, FAR = (0.9, -0.1), (-0.7, -0.5), (-2.5, -1.0)  # two yielded elements, one not


@pytest.fixture(scope="module")
def case():
    mesh = soil_mesh(B, element="Q2", elements_across=4, domain_width=4, domain_depth=3)
    basis = skfem.Basis(mesh.mesh, skfem.ElementVector(mesh.skfem_element))
    xdof, ydof = basis.split_indices()
    at = basis.doflocs  # (2, ndofs): the node of each DOF
    u = np.zeros((2, basis.N))
    u[1, xdof] = A * at[1, xdof]
    u[1, ydof] = -BB * at[0, ydof]
    centres = mesh.mesh.p[:, mesh.mesh.t].mean(axis=1)  # (2, nelems)

    def element_at(point):
        return int(np.argmin(np.hypot(centres[0] - point[0], centres[1] - point[1])))

    hot, warm = element_at(HOT), element_at(WARM)
    plastic = np.zeros((2, mesh.mesh.nelements))
    plastic[1, hot], plastic[1, warm] = 1e-2, 1e-4
    x = np.linspace(-0.5 * B, 0.5 * B, 41)
    pressure = np.vstack((np.full_like(x, 50.0), np.where(x < C, 200.0 * (C - x), 0.0)))
    gap = np.vstack((np.zeros_like(x), np.where(x > C, 4e-3 * (x - C), 0.0)))
    result = SimpleNamespace(
        kind="dynamic", time=np.array([0.0, 1.0]), snapshot_time=np.array([0.0, 1.0]),
        footing=np.array([[0.0, 0.0, 0.0], [0.0, -1e-4, 2e-3]]), x=x, pressure=pressure,
        gap=gap, M=np.array([0.0, 10.0]), N=np.array([100.0, 100.0]),
        contact_length=np.array([B, 0.5 * B + C]), displacement=u, plastic_strain=plastic,
        metadata={"scene": "made-up", "units": {"length": "m"}})
    sub = linear_submesh(basis)
    view = uplift_view(result, sub, B)
    return SimpleNamespace(mesh=mesh, basis=basis, result=result, sub=sub, view=view,
                           frame=frames(result, sub)[1], hot=hot, warm=warm,
                           far=element_at(FAR), centres=centres)


def _page(case, **kw):
    reach = case.view.scale * float(np.max(np.abs(case.frame.displacement)))
    page = Page(case.sub, case.view, reach, **kw)
    page.show(case.frame)
    return page


def test_drawn_cells_are_the_deformed_mesh(case):
    page = _page(case)
    drawn = np.array([p.vertices[:4] for p in page.faces.get_paths()])  # closed: 5 vertices
    corners = case.sub.points[page.cells]  # (n, 4, 2) undeformed
    s = case.view.scale
    expected = corners + s * np.stack((A * corners[..., 1], -BB * corners[..., 0]), axis=-1)
    assert s >= 1.0 and len(drawn) > 100
    assert np.max(np.abs(drawn - expected)) <= 1e-12 * B
    # every sub-cell that can enter the window is drawn
    xmin, xmax, ymin, ymax = case.view.window
    inside = ((case.sub.points[:, 0] > xmin) & (case.sub.points[:, 0] < xmax)
              & (case.sub.points[:, 1] > ymin))
    assert set(np.flatnonzero(inside.reshape(-1)[case.sub.cells].any(axis=1))) <= set(page.rows)


def _pixel(page, ax, x, y):
    """The (row, column) of data point (x, y) of ``ax`` in the page's pixels."""
    px, py = ax.transData.transform((x, y))
    return int(round(page.figure.bbox.height - py)), int(round(px))


def test_pixels_show_the_plastic_zone_and_the_lift_off(case, tmp_path):
    target = render_uplift(tmp_path / "u.png", case.result, case.basis, B, snapshot=1)
    image = np.asarray(Image.open(target).convert("RGB")).astype(int)
    page = _page(case)  # the same page, for its axes' transforms
    cmap = colormaps[CMAP]
    s = case.view.scale
    for element, level in ((case.hot, 1.0), (case.warm, 1.0 / 3.0), (case.far, 0.0)):
        cx, cy = case.centres[:, element]
        row, col = _pixel(page, page.soil_axes, cx + s * A * cy, cy - s * BB * cx)
        colour = np.rint(255 * np.asarray(cmap(level)[:3]))  # LogNorm over 3 decades
        assert np.max(np.abs(image[row, col] - colour)) <= 6, (element, image[row, col])
    blue = image[..., 2] - image[..., 0] > 25  # the pressure fill (even under a grid line)
    contact, lifted = np.linspace(-0.9, C - 0.15, 8), np.linspace(C + 0.1, 0.95, 8)
    top = page.contact_axes.get_ylim()[1]
    for x in np.concatenate((contact, lifted)):
        rows = [_pixel(page, page.contact_axes, x, f * top)[0] for f in (0.02, 0.05)]
        col = _pixel(page, page.contact_axes, x, 0.0)[1]
        assert blue[min(rows):max(rows) + 1, col].all() == (x < C), x


def test_the_colour_table_is_matplotlibs_colour_map():
    # Reference: matplotlib's YlOrRd, linear and through LogNorm over 3 decades
    cmap = colormaps[CMAP]
    s = np.linspace(-0.1, 1.1, 2001)
    assert np.max(np.abs(colours_of(s, 0.0, 1.0) - cmap(s)[:, :3])) <= 1e-12
    strain = np.logspace(-6.0, -1.0, 2001)
    logged = cmap(LogNorm(1e-5, 1e-2)(strain))[:, :3]
    assert np.max(np.abs(colours_of(strain, 1e-5, 1e-2) - logged)) <= 1.4 / 255


def test_the_colour_bar_agrees_with_the_cells(case, tmp_path):
    target = render_uplift(tmp_path / "u.png", case.result, case.basis, B, snapshot=1)
    image = np.asarray(Image.open(target).convert("RGB")).astype(int)
    page = _page(case)  # the matplotlib page: the axes' transforms
    height, _, _, bar = layout(9.0, case.view)
    h, w = image.shape[:2]
    assert (h, w) == (int(round(100 * height)), 900)
    col = int(round((bar[0] + 0.5 * bar[2]) * w))
    s = case.view.scale
    for element, level in ((case.hot, 1.0), (case.warm, 1.0 / 3.0)):  # 1e-2, 1e-4 of 1e-5..1e-2
        cx, cy = case.centres[:, element]
        cell = image[_pixel(page, page.soil_axes, cx + s * A * cy, cy - s * BB * cx)]
        row = int(round((1.0 - bar[1] - min(level, 0.99) * bar[3]) * h))
        assert np.max(np.abs(cell - image[row, col])) <= 6, (element, cell, image[row, col])


def test_the_footing_block_is_drawn_where_it_moved(case, tmp_path):
    # Reference: the block's corners (±B/2, 0), (±B/2, B/5) moved by (u + θ y, v − θ x) ×
    # scale (a rigid footing's small motion), with u, v, θ set here large enough (θ = 0.02:
    # 0.4 rad drawn) that the block leaves where it stood; the matplotlib page's transform
    moved = SimpleNamespace(**vars(case.result))
    moved.footing = np.array([[0.0, 0.0, 0.0], [0.0, -2e-3, 2e-2]])
    target = render_uplift(tmp_path / "f.png", moved, case.basis, B, snapshot=1)
    image = np.asarray(Image.open(target).convert("RGB")).astype(int)
    page = _page(case)
    s, (u, v, theta) = case.view.scale, moved.footing[1]
    colour = np.rint(255 * np.asarray(FOOTING))
    h = FOOTING_HEIGHT * B
    for fx, fy in ((-0.4, 0.5), (0.0, 0.5), (0.4, 0.5), (0.4, 0.15), (-0.4, 0.85)):
        x, y = fx * B, fy * h
        inside = _pixel(page, page.soil_axes, x + s * (u + theta * y), y + s * (v - theta * x))
        assert np.max(np.abs(image[inside] - colour)) <= 1, (fx, fy, image[inside])
    for x, y in ((0.0, 1.3 * h), (0.4 * B, 0.5 * h), (0.62 * B, -0.5 * h)):  # it stood there
        outside = _pixel(page, page.soil_axes, x, y)
        assert np.max(np.abs(image[outside] - colour)) > 20, (x, y)


def test_writing_the_pictures_never_imports_matplotlib(tmp_path):
    # Reference: a fresh interpreter's sys.modules after render_uplift and animate_uplift
    import subprocess
    import sys
    import textwrap

    script = textwrap.dedent(f"""
        import sys
        import numpy as np
        import skfem
        from types import SimpleNamespace
        from upliftlab.meshes import soil_mesh
        from upliftlab.meshes.render import animate_uplift, render_uplift
        mesh = soil_mesh(2.0, element="Q2", elements_across=2, domain_width=4, domain_depth=3)
        basis = skfem.Basis(mesh.mesh, skfem.ElementVector(mesh.skfem_element))
        x = np.linspace(-1.0, 1.0, 5)
        result = SimpleNamespace(
            kind="dynamic", time=np.array([0.0, 1.0]), snapshot_time=np.array([0.0, 1.0]),
            footing=np.zeros((2, 3)), x=x, pressure=np.ones((2, 5)), gap=np.zeros((2, 5)),
            M=np.zeros(2), N=np.ones(2), contact_length=np.full(2, 2.0),
            displacement=np.full((2, basis.N), 1e-3), metadata={{}},
            plastic_strain=np.zeros((2, mesh.mesh.nelements)))
        render_uplift(r"{tmp_path / 'a.png'}", result, basis, 2.0)
        animate_uplift(r"{tmp_path / 'a.gif'}", result, basis, 2.0, dpi=30)
        print(sorted(m for m in sys.modules if m.split(".")[0] == "matplotlib"))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"
    assert Image.open(tmp_path / "a.gif").n_frames == 2


def test_gif_frames_are_their_pages(case, tmp_path):
    target = animate_uplift(tmp_path / "u.gif", case.result, case.basis, B, dpi=60)
    gif = Image.open(target)
    assert gif.n_frames == 2
    gif.seek(1)
    decoded = np.asarray(gif.convert("RGB")).astype(int)
    reach = case.view.scale * float(np.max(np.abs(case.frame.displacement)))
    page = Sheet(case.sub, case.view, reach, dpi=60)
    page.show(case.frame)
    expected = page.pixels().astype(int)
    assert decoded.shape == expected.shape
    assert np.mean(np.abs(decoded - expected)) < 2.0


def test_the_budget_rule():
    # frames_within: 1 + (budget - spent) / per_frame, within [min(MIN_FRAMES, count), count]
    assert frames_within(2.0, 0.5, 0.125, 41) == 13
    assert frames_within(0.1, 0.5, 0.1, 41) == MIN_FRAMES
    assert frames_within(100.0, 0.5, 0.1, 41) == 41
    assert frames_within(0.0, 1.0, 0.1, 3) == 3


def test_a_budget_limits_the_gif(case, tmp_path):
    two = SimpleNamespace(**vars(case.result))
    n = 2 * MIN_FRAMES  # snapshots: the same two fields repeated
    two.snapshot_time = np.linspace(0.0, 1.0, n)
    two.time = two.snapshot_time
    for name in ("footing", "pressure", "gap", "M", "N", "contact_length", "displacement",
                 "plastic_strain"):
        values = getattr(case.result, name)
        setattr(two, name, values[np.arange(n) % 2])
    counts = []
    animate_uplift(tmp_path / "b.gif", two, case.basis, B, dpi=40, budget=0.0,
                   progress=lambda k, m: counts.append(m))
    assert Image.open(tmp_path / "b.gif").n_frames == MIN_FRAMES == counts[-1]


def test_the_picture_set_draws_the_png_as_render_uplift_does(case, tmp_path):
    # Reference: render_uplift's PNG of the same snapshot, a page of its own; the picture set
    # draws its PNG on the page that then draws the GIF's frames: pixel for pixel the same
    whole = render_uplift(tmp_path / "whole.png", case.result, case.basis, B, snapshot=1)
    count = write_pictures(tmp_path / "set.png", tmp_path / "set.gif", case.result, case.basis,
                           B, snapshot=1)
    a = np.asarray(Image.open(whole).convert("RGB")).astype(int)
    b = np.asarray(Image.open(tmp_path / "set.png").convert("RGB")).astype(int)
    assert count == 2 == Image.open(tmp_path / "set.gif").n_frames
    assert a.shape == b.shape and np.array_equal(a, b)


def test_the_command_line_states_the_rule():
    # Reference: the rule's constants (PICTURE_SHARE, MIN_FRAMES), named in --no-render's help.
    import argparse

    from upliftlab.cli import continuum as command

    parser = argparse.ArgumentParser()
    command.add_continuum(parser.add_subparsers())
    sub = parser._subparsers._group_actions[0].choices["continuum"]
    text = next(a.help for a in sub._actions if "--no-render" in a.option_strings)
    assert f"{command.PICTURE_SHARE:.0%}" in text and f"at least {MIN_FRAMES}" in text
