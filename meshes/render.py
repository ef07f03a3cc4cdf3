"""Off-screen pictures of a footing on a soil mesh: the uplift zone as a PNG and an animated GIF
over a run's snapshots.

**What a picture shows.** Top panel: the soil near the footing (a window of 3B × 1.6B by
default), deformed with its displacements magnified by a stated factor, coloured by the
element-averaged equivalent plastic strain (colour bar with its unit; logarithmic over
:data:`DECADES` decades below the run's largest value, so the whole plastic zone shows and not
only the peak at the footing edge), the element outlines,
and the rigid footing drawn as a block of height B/5 moved by its (u, v, θ) with the same
magnification. Bottom panel, on the same x axis: the contact pressure (filled) and the gap
(line, right axis) along the base. The title names the scene, the step (static) or the time
(dynamic), θ, M, N and the contact length. Axis limits and colour limits are fixed over all
frames of a run, so an animation does not jump.

**How.** pyvista renders the soil off screen (``pyvista.OFF_SCREEN``; when there is no display,
VTK is pointed at EGL through ``VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow`` before it
loads), with a parallel camera fitted to the window so the image maps exactly onto the
window's coordinates. matplotlib lays out the page (axes in the scene's length unit, colour
bar, footing, contact panel). imageio writes the GIF. Files appear complete or not at all.

What is drawn (the linear sub-mesh of quadratic elements, the frames, the view fixed over a
run) is :mod:`~upliftlab.meshes.frames`'; its names are importable from here.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np

from ..checks import InputError
from ..results import atomic_path
from .frames import (Frame, SubMesh, View, frames, linear_submesh, nice_scale,  # noqa: F401
                     snapshot_rows, uplift_view)

__all__ = ["SubMesh", "linear_submesh", "View", "Frame", "uplift_view", "frames",
           "snapshot_rows", "render_frame", "uplift_figure", "render_uplift", "animate_uplift",
           "render_frames", "frame_subset", "nice_scale"]

#: Colour map of the equivalent plastic strain (zero is a pale yellow, distinct from white).
CMAP = "YlOrRd"
#: Footing block height drawn, as a fraction of B.
FOOTING_HEIGHT = 0.2


def _pyvista():
    """pyvista, off screen; EGL when there is no display (set before VTK loads)."""
    if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    try:
        import pyvista
    except ImportError as exc:  # the ``render`` extra
        raise InputError("renders need pyvista and imageio: pip install 'upliftlab[render]'"
                         ) from exc
    pyvista.OFF_SCREEN = True
    return pyvista


#: Decades of equivalent plastic strain the colour map spans below the run's largest value.
DECADES = 3


def _colour_range(view: View) -> tuple[float, float]:
    """(floor, top) of the logarithmic colour scale; (0, 1e-3) linear if nothing yielded."""
    if view.plastic_max > 0.0:
        return view.plastic_max * 10.0 ** -DECADES, view.plastic_max
    return 0.0, 1e-3


def _colour_values(view: View, plastic: np.ndarray) -> np.ndarray:
    """What VTK colours linearly: log10 of ε̄p clipped to the floor (so that VTK's linear map
    equals matplotlib's LogNorm on the colour bar)."""
    floor, _ = _colour_range(view)
    if floor == 0.0:
        return np.asarray(plastic, dtype=float)
    return np.log10(np.maximum(plastic, floor))


def _colour_limits(view: View) -> tuple[float, float]:
    floor, top = _colour_range(view)
    return (0.0, top) if floor == 0.0 else (math.log10(floor), math.log10(top))


class _SoilPainter:
    """A pyvista plotter kept over the frames of a run: the soil grid coloured by plastic
    strain and the element outlines, with a parallel camera fitted to the window."""

    def __init__(self, sub: SubMesh, view: View, width_px: int):
        pv = _pyvista()
        xmin, xmax, ymin, ymax = view.window
        self.height_px = max(2, int(round(width_px * (ymax - ymin) / (xmax - xmin))))
        self.sub, self.view = sub, view
        self.base = np.column_stack((sub.points, np.zeros(len(sub.points))))
        kind = pv.CellType.QUAD if sub.cell_type == "quad" else pv.CellType.TRIANGLE
        k = sub.cells.shape[1]
        connectivity = np.hstack((np.full((len(sub.cells), 1), k), sub.cells)).ravel()
        self.grid = pv.UnstructuredGrid(connectivity, np.full(len(sub.cells), kind),
                                        self.base.copy())
        self.grid.cell_data["plastic"] = np.zeros(len(sub.cells))
        lines = np.hstack((np.full((len(sub.edges), 1), 2), sub.edges)).ravel()
        self.outline = pv.PolyData(self.base.copy(), lines=lines)
        self.plotter = pv.Plotter(off_screen=True, window_size=(width_px, self.height_px))
        self.plotter.set_background("white")
        self.plotter.add_mesh(self.grid, scalars="plastic", cmap=CMAP,
                              clim=_colour_limits(view), lighting=False,
                              show_scalar_bar=False)
        self.plotter.add_mesh(self.outline, color=(0.45, 0.45, 0.45), line_width=1,
                              lighting=False)
        camera = self.plotter.camera
        cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
        camera.position, camera.focal_point, camera.up = (cx, cy, 10.0), (cx, cy, 0.0), (0, 1, 0)
        self.plotter.enable_parallel_projection()
        camera.parallel_scale = 0.5 * (ymax - ymin)
        camera.clipping_range = (1.0, 100.0)

    def paint(self, frame: Frame) -> np.ndarray:
        moved = self.base.copy()
        moved[:, :2] += self.view.scale * frame.displacement
        self.grid.points = moved
        self.outline.points = moved
        self.grid.cell_data["plastic"] = self.sub.cell_values(
            _colour_values(self.view, frame.plastic_strain))
        self.plotter.render()
        return np.asarray(self.plotter.screenshot(return_img=True))

    def close(self) -> None:
        self.plotter.close()


def _footing_outline(frame: Frame, view: View) -> np.ndarray:
    """Corners (5, 2) of the footing block moved by (u, v, θ) × scale: a point (x, y) of the
    rigid footing moves by (u + θ y, v − θ x)."""
    b, h = 0.5 * view.footing_width, FOOTING_HEIGHT * view.footing_width
    corners = np.array([(-b, 0.0), (b, 0.0), (b, h), (-b, h), (-b, 0.0)])
    u, v, theta = frame.footing
    move = np.column_stack((u + theta * corners[:, 1], v - theta * corners[:, 0]))
    return corners + view.scale * move


def _unit(text: str) -> str:
    """`` [unit]`` for a label, with kN*m/m^2 written kN·m/m²."""
    text = text.replace("^2", "²").replace("^3", "³").replace("*", "·")
    return f" [{text}]" if text else ""


#: Page width (in) of a frame unless asked otherwise.
FIGURE_WIDTH_IN = 9.0


def _layout(fig_width: float, view: View):
    """Axes rectangles (figure fractions) and the figure height: the soil panel keeps the
    window's aspect ratio, the contact panel shares its x extent."""
    xmin, xmax, ymin, ymax = view.window
    left_in, right_in = 0.85, 1.35  # axis labels; colour bar with its ticks and label
    left, width = left_in / fig_width, 1.0 - (left_in + right_in) / fig_width
    soil_h_in = width * fig_width * (ymax - ymin) / (xmax - xmin)
    contact_h_in, top_in, gap_in, bottom_in = 0.3 * fig_width, 0.95, 0.6, 0.6
    height = top_in + soil_h_in + gap_in + contact_h_in + bottom_in
    soil = (left, (bottom_in + contact_h_in + gap_in) / height, width, soil_h_in / height)
    contact = (left, bottom_in / height, width, contact_h_in / height)
    bar = (left + width + 0.015, soil[1], 0.022, soil[3])
    return height, soil, contact, bar


def _figure(frame: Frame, image: np.ndarray, view: View, dpi: int,
            fig_width: float = FIGURE_WIDTH_IN, make=None):
    """The page of one frame on a new figure: ``make(width, height, dpi)`` (inches) if given,
    else a matplotlib Figure outside pyplot."""
    import matplotlib
    from matplotlib.figure import Figure

    height, soil_rect, contact_rect, bar_rect = _layout(fig_width, view)
    fig = (Figure(figsize=(fig_width, height), dpi=dpi) if make is None
           else make(fig_width, height, dpi))
    soil = fig.add_axes(soil_rect)
    xmin, xmax, ymin, ymax = view.window
    soil.imshow(image, extent=view.window, origin="upper", interpolation="antialiased")
    foot = _footing_outline(frame, view)
    soil.fill(foot[:, 0], foot[:, 1], facecolor=(0.55, 0.6, 0.7), edgecolor="black",
              linewidth=1.5, alpha=0.9, zorder=3)
    soil.set_xlim(xmin, xmax)
    soil.set_ylim(ymin, ymax)
    soil.set_aspect("equal")
    soil.set_ylabel(f"y{_unit(view.length_unit)}")
    soil.tick_params(labelbottom=False)
    soil.text(0.01, 0.02, f"deformation × {view.scale:g}", transform=soil.transAxes,
              fontsize=10, va="bottom", bbox=dict(facecolor="white", alpha=0.8, lw=0))
    floor, top = _colour_range(view)
    norm = (matplotlib.colors.LogNorm(floor, top) if floor > 0.0
            else matplotlib.colors.Normalize(floor, top))
    mappable = matplotlib.cm.ScalarMappable(norm=norm, cmap=CMAP)
    bar = fig.colorbar(mappable, cax=fig.add_axes(bar_rect), extend="min" if floor else None)
    bar.set_label("plastic strain ε̄ᵖ [–]"
                  + (f"\n(log; < {floor:.1e}: palest)" if floor else "\n(none: elastic)"),
                  fontsize=9)
    _contact_panel(fig.add_axes(contact_rect), frame, view)
    theta = frame.footing[2]
    fig.suptitle(f"{view.title}: {frame.label}\nθ = {theta:.3g} rad,  M = {frame.M:.4g}"
                 f"{_unit(view.moment_unit)},  N = {frame.N:.4g}{_unit(view.force_unit)},  "
                 f"contact {frame.contact_length / view.footing_width:.0%} of B",
                 fontsize=11, y=1.0 - 0.12 / height)
    return fig


def _contact_panel(ax, frame: Frame, view: View) -> None:
    xmin, xmax = view.window[:2]
    ax.fill_between(frame.x, 0.0, frame.pressure, color="tab:blue", alpha=0.35, step=None,
                    label="pressure p")
    ax.plot(frame.x, frame.pressure, color="tab:blue", lw=1.5)
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(0.0, 1.1 * view.pressure_max if view.pressure_max > 0 else 1.0)
    ax.set_xlabel(f"x{_unit(view.length_unit)}")
    ax.set_ylabel(f"contact pressure p{_unit(view.stress_unit)}", color="tab:blue")
    ax.axvspan(-0.5 * view.footing_width, 0.5 * view.footing_width, color="0.93", zorder=0)
    twin = ax.twinx()
    twin.plot(frame.x, frame.gap, color="tab:red", lw=1.8, label="gap g")
    twin.set_ylim(0.0, 1.1 * view.gap_max if view.gap_max > 0 else 1.0)
    twin.set_ylabel(f"gap g{_unit(view.length_unit)}", color="tab:red")
    twin.ticklabel_format(axis="y", style="sci", scilimits=(-2, 3))
    handles = ax.get_legend_handles_labels()[0] + twin.get_legend_handles_labels()[0]
    ax.legend(handles, [h.get_label() for h in handles], loc="upper left", fontsize=9)
    ax.grid(alpha=0.3)


def _pixels(fig) -> np.ndarray:
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[..., :3].copy()


def render_frame(painter: _SoilPainter, frame: Frame, view: View, dpi: int = 100,
                 width_in: float = FIGURE_WIDTH_IN) -> np.ndarray:
    """The RGB page (h, w, 3) of one frame, ``width_in`` inches wide at ``dpi``."""
    return _pixels(_figure(frame, painter.paint(frame), view, dpi, width_in))


def _painter(sub: SubMesh, view: View, dpi: int,
             width_in: float = FIGURE_WIDTH_IN) -> _SoilPainter:
    _, soil_rect, _, _ = _layout(width_in, view)
    return _SoilPainter(sub, view, width_px=int(round(1.5 * soil_rect[2] * width_in * dpi)))


def uplift_figure(result, basis, footing_width: float, *, snapshot: int = -1,
                  scale: float | None = None, title: str = "", dpi: int = 100, make=None):
    """The matplotlib figure of one snapshot (default the last) of a result on ``basis`` (the
    module docstring's picture), nothing written; ``make(width, height, dpi)`` makes the
    figure (default: a Figure outside pyplot)."""
    sub = linear_submesh(basis)
    all_frames = frames(result, sub)
    if not -len(all_frames) <= snapshot < len(all_frames):
        raise InputError(f"snapshot = {snapshot}: valid range is [{-len(all_frames)}, "
                         f"{len(all_frames) - 1}]")
    view = uplift_view(result, sub, footing_width, scale=scale, title=title)
    painter = _painter(sub, view, dpi)
    try:
        return _figure(all_frames[snapshot], painter.paint(all_frames[snapshot]), view, dpi,
                       make=make)
    finally:
        painter.close()


def render_uplift(path, result, basis, footing_width: float, *, snapshot: int = -1,
                  scale: float | None = None, title: str = "", dpi: int = 100):
    """Write the PNG of :func:`uplift_figure` to ``path``. Returns the path."""
    fig = uplift_figure(result, basis, footing_width, snapshot=snapshot, scale=scale,
                        title=title, dpi=dpi)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return path


def animate_uplift(path, result, basis, footing_width: float, *, scale: float | None = None,
                   title: str = "", seconds_per_frame: float = 0.25, dpi: int = 80,
                   progress=None):
    """Write an animated GIF with one frame per snapshot of a result to ``path`` (same view
    and limits in every frame). ``progress(k, n)`` is called after each frame. Returns the
    path."""
    import imageio.v3 as iio

    sub = linear_submesh(basis)
    all_frames = frames(result, sub)
    view = uplift_view(result, sub, footing_width, scale=scale, title=title)
    painter = _painter(sub, view, dpi)
    pages = []
    try:
        for k, frame in enumerate(all_frames):
            pages.append(render_frame(painter, frame, view, dpi))
            if progress is not None:
                progress(k, len(all_frames))
    finally:
        painter.close()
    with atomic_path(path) as tmp:
        iio.imwrite(tmp, np.stack(pages), extension=".gif", loop=0,
                    duration=int(round(1000 * seconds_per_frame)))
    return path


def frame_subset(count: int, limit: int) -> list[int]:
    """Indices of at most ``limit`` (≥ 2) of ``count`` frames, evenly spaced, the first and the
    last always kept."""
    if limit < 2:
        raise InputError(f"limit = {limit}: at least 2 frames (the first and the last)")
    if count <= limit:
        return list(range(count))
    return sorted({int(round(k * (count - 1) / (limit - 1))) for k in range(limit)})


def render_frames(directory, result, basis, footing_width: float, *, limit: int = 24,
                  scale: float | None = None, title: str = "", width_in: float = 6.5,
                  dpi: int = 100, progress=None) -> list[tuple]:
    """Write one PNG page per snapshot of a result, at most ``limit`` of them evenly spaced
    (:func:`frame_subset`), ``width_in`` inches wide, into ``directory`` as
    ``frame_000.png``, … (same view and limits in every page: what an animation or a frame
    slider shows). ``progress(k, n)`` after each page. Returns [(path, :class:`Frame`)]."""
    from pathlib import Path

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    sub = linear_submesh(basis)
    all_frames = frames(result, sub)
    view = uplift_view(result, sub, footing_width, scale=scale, title=title)
    chosen = frame_subset(len(all_frames), limit)
    painter = _painter(sub, view, dpi, width_in)
    written = []
    try:
        for k, index in enumerate(chosen):
            fig = _figure(all_frames[index], painter.paint(all_frames[index]), view, dpi,
                          width_in)
            from matplotlib.backends.backend_agg import FigureCanvasAgg

            FigureCanvasAgg(fig)
            path = directory / f"frame_{k:03d}.png"
            with atomic_path(path) as tmp:
                fig.savefig(tmp, format="png", dpi=dpi)
            written.append((path, all_frames[index]))
            if progress is not None:
                progress(k, len(chosen))
    finally:
        painter.close()
    return written
