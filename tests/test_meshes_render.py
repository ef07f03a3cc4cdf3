"""The pictures of a footing on a soil mesh drawn right, checked by numbers
(upliftlab.meshes.page, upliftlab.meshes.gif, upliftlab.meshes.render).

References: a made-up run on a small Q2 mesh whose fields are closed forms chosen here — a
displacement u = (a y, −b x) at every node, a plastic strain in two named elements only, a
contact pressure p = p0 (c − x) for x < c and zero beyond (the footing lifted off beyond c,
where the gap opens as g = g0 (x − c)). What must follow, independently of the renderer:
- the drawn soil cells are the mesh's cells at (x, y) + scale × u(x, y) (to 1e-12 of B);
- the pixel at an element's drawn centre has the colour map's colour of its plastic strain
  (the top for the largest, the palest for none), within 6 of 255 per channel;
- the pressure fill's colour appears above the base where p > 0 and not where the gap opened;
- a GIF frame, decoded, is its page within the fixed palette's error (mean < 2 of 255);
- the budget rule of :func:`~upliftlab.meshes.render.frames_within` (its docstring's formula);
- the picture set's PNG, drawn on the animated page, is the page drawn whole.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import skfem
from matplotlib import colormaps
from PIL import Image

from upliftlab.meshes import soil_mesh
from upliftlab.meshes.page import CMAP, Page
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


def test_gif_frames_are_their_pages(case, tmp_path):
    target = animate_uplift(tmp_path / "u.gif", case.result, case.basis, B, dpi=60)
    gif = Image.open(target)
    assert gif.n_frames == 2
    gif.seek(1)
    decoded = np.asarray(gif.convert("RGB")).astype(int)
    page = _page(case, dpi=60)
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


def test_the_picture_set_draws_the_png_as_a_whole_page_would(case, tmp_path):
    # Reference: the PNG of a page drawn whole (render_uplift, no blitting); the picture set
    # draws its PNG on the GIF's page (background once, changing artists over it): the same
    # picture but for the magnification note's opaque box (mean difference < 0.5 of 255).
    whole = render_uplift(tmp_path / "whole.png", case.result, case.basis, B, snapshot=1)
    count = write_pictures(tmp_path / "set.png", tmp_path / "set.gif", case.result, case.basis,
                           B, snapshot=1)
    a = np.asarray(Image.open(whole).convert("RGB")).astype(int)
    b = np.asarray(Image.open(tmp_path / "set.png").convert("RGB")).astype(int)
    assert count == 2 == Image.open(tmp_path / "set.gif").n_frames
    assert a.shape == b.shape and np.mean(np.abs(a - b)) < 0.5


def test_the_command_line_states_the_rule():
    # Reference: the rule's constants (PICTURE_SHARE, MIN_FRAMES), named in --no-render's help.
    import argparse

    from upliftlab.cli import continuum as command

    parser = argparse.ArgumentParser()
    command.add_continuum(parser.add_subparsers())
    sub = parser._subparsers._group_actions[0].choices["continuum"]
    text = next(a.help for a in sub._actions if "--no-render" in a.option_strings)
    assert f"{command.PICTURE_SHARE:.0%}" in text and f"at least {MIN_FRAMES}" in text
