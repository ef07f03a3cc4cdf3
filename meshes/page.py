"""The page of :mod:`~upliftlab.meshes.render`'s pictures, built once per run and redrawn per
frame: what it shows is that module's docstring.

**Built once.** A :class:`Page` makes the figure, its axes, the colour bar, the axis labels and
every artist of a frame once (matplotlib only, outside pyplot): the soil's sub-cells as one
``PolyCollection`` coloured through the colour bar's own norm (so the picture and its colour
bar cannot disagree), the element outlines as one ``LineCollection``, the footing and the
contact pressure as polygons, the gap as a line, the title as a text. Sub-cells that no frame
can bring into the window (the window grown by the largest magnified displacement ``reach``)
are left out. :meth:`Page.show` moves and recolours those artists for a frame (``set_array``,
``set_xy``, ``set_data``, ``set_text``; the cells' and outlines' paths are views of one array
each, rewritten in place); axes are never re-created.

The files a run writes are drawn by the raster :class:`~upliftlab.meshes.sheet.Sheet` (same
:func:`layout`, colour table and norm); this page is the notebook's figure
(:func:`~upliftlab.meshes.render.uplift_figure`).
"""

from __future__ import annotations

import numpy as np

from .frames import Frame, SubMesh, View

__all__ = ["Page", "CMAP", "DECADES", "FOOTING_HEIGHT", "FIGURE_WIDTH_IN", "colour_range",
           "footing_outline", "layout", "visible_cells"]

#: Colour map of the equivalent plastic strain (zero is a pale yellow, distinct from white).
CMAP = "YlOrRd"
#: Decades of equivalent plastic strain the colour map spans below the run's largest value.
DECADES = 3
#: Footing block height drawn, as a fraction of B.
FOOTING_HEIGHT = 0.2
#: Page width (in) of a frame unless asked otherwise.
FIGURE_WIDTH_IN = 9.0
#: Colour of the element outlines (grey level) and their width (points).
OUTLINE_GREY, OUTLINE_WIDTH = 0.45, 0.5


def colour_range(view: View) -> tuple[float, float]:
    """(floor, top) of the logarithmic colour scale; (0, 1e-3) linear if nothing yielded."""
    if view.plastic_max > 0.0:
        return view.plastic_max * 10.0 ** -DECADES, view.plastic_max
    return 0.0, 1e-3


def footing_outline(frame: Frame, view: View) -> np.ndarray:
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


def layout(fig_width: float, view: View):
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


def visible_cells(points: np.ndarray, cells: np.ndarray, window, reach: float) -> np.ndarray:
    """Indices of the polygons ``cells`` (n, k) on ``points`` whose bounding box meets the
    ``window`` (xmin, xmax, ymin, ymax) grown by ``reach`` on every side (length)."""
    xmin, xmax, ymin, ymax = window
    xy = points[cells]  # (n, k, 2)
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    meets = ((hi[:, 0] >= xmin - reach) & (lo[:, 0] <= xmax + reach)
             & (hi[:, 1] >= ymin - reach) & (lo[:, 1] <= ymax + reach))
    return np.flatnonzero(meets)


def _shared_paths(collection, polygons: np.ndarray, closed: bool) -> np.ndarray:
    """Give ``collection`` one path per polygon of ``polygons`` (n, k, 2), each a view of one
    array (n, k + closed, 2) that is returned: writing into it moves every path at once."""
    from matplotlib.collections import Collection
    from matplotlib.path import Path

    n, k, _ = polygons.shape
    xy = np.empty((n, k + int(closed), 2))
    xy[:, :k] = polygons
    codes = None
    if closed:
        xy[:, k] = polygons[:, 0]
        codes = np.full(k + 1, Path.LINETO, dtype=Path.code_type)
        codes[0], codes[-1] = Path.MOVETO, Path.CLOSEPOLY
    Collection.set_paths(collection, [Path(row, codes) for row in xy])  # the paths as given
    return xy


class Page:
    """The page of a run's frames (module docstring): ``sub`` the drawn sub-mesh, ``view`` the
    run's fixed view, ``reach`` the largest magnified nodal displacement of any frame (length),
    ``dpi`` and ``width_in`` the raster size, ``make(width, height, dpi)`` the figure maker
    (default a Figure outside pyplot)."""

    def __init__(self, sub: SubMesh, view: View, reach: float, *, dpi: int = 100,
                 width_in: float = FIGURE_WIDTH_IN, make=None):
        import matplotlib
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.collections import LineCollection, PolyCollection
        from matplotlib.figure import Figure
        from matplotlib.patches import Polygon

        self.sub, self.view = sub, view
        height, soil_rect, contact_rect, bar_rect = layout(width_in, view)
        fig = (Figure(figsize=(width_in, height), dpi=dpi) if make is None
               else make(width_in, height, dpi))
        self.figure, self.height_in = fig, height
        if make is None:  # the user's figure keeps its own canvas
            FigureCanvasAgg(fig)
        soil = self.soil_axes = fig.add_axes(soil_rect)
        xmin, xmax, ymin, ymax = view.window
        self.rows = visible_cells(sub.points, sub.cells, view.window, reach)
        self.cells = sub.cells[self.rows]
        edges = sub.edges[visible_cells(sub.points, sub.edges, view.window, reach)]
        self.edge_points = edges
        floor, top = colour_range(view)
        self.floor = floor
        norm = (matplotlib.colors.LogNorm(floor, top) if floor > 0.0
                else matplotlib.colors.Normalize(floor, top))
        self.faces = PolyCollection([], cmap=CMAP, norm=norm, edgecolors="none",
                                    linewidths=0.0, antialiaseds=False)
        self._cell_xy = _shared_paths(self.faces, sub.points[self.cells], closed=True)
        self.faces.set_array(np.full(len(self.cells), max(floor, 0.0)))
        soil.add_collection(self.faces)
        self.outlines = LineCollection([], colors=[(OUTLINE_GREY,) * 3],
                                       linewidths=OUTLINE_WIDTH)
        self._edge_xy = _shared_paths(self.outlines, sub.points[edges], closed=False)
        soil.add_collection(self.outlines)
        self.footing = Polygon(np.zeros((5, 2)), closed=True, facecolor=(0.55, 0.6, 0.7),
                               edgecolor="black", linewidth=1.5, alpha=0.9, zorder=3)
        soil.add_patch(self.footing)
        soil.set_xlim(xmin, xmax)
        soil.set_ylim(ymin, ymax)
        soil.set_aspect("equal")
        soil.set_ylabel(f"y{_unit(view.length_unit)}")
        soil.tick_params(labelbottom=False)
        self.note = soil.text(0.01, 0.02, f"deformation × {view.scale:g}",
                              transform=soil.transAxes, fontsize=10, va="bottom", zorder=4,
                              bbox=dict(facecolor="white", alpha=1.0, lw=0))
        bar = fig.colorbar(self.faces, cax=fig.add_axes(bar_rect),
                           extend="min" if floor else None)
        bar.set_label("plastic strain ε̄ᵖ [–]"
                      + (f"\n(log; < {floor:.1e}: palest)" if floor else "\n(none: elastic)"),
                      fontsize=9)
        self._contact_panel(fig.add_axes(contact_rect))
        self.title = fig.suptitle("", fontsize=11, y=1.0 - 0.12 / height)

    def _contact_panel(self, ax) -> None:
        from matplotlib.patches import Polygon

        view = self.view
        self.contact_axes = ax
        xmin, xmax = view.window[:2]
        self.pressure_fill = Polygon(np.zeros((3, 2)), closed=True, color="tab:blue",
                                     alpha=0.35, lw=1.0, label="pressure p")
        ax.add_patch(self.pressure_fill)
        (self.pressure_line,) = ax.plot([], [], color="tab:blue", lw=1.5)
        ax.set_xlim(xmin, xmax)
        ax.set_ylim(0.0, 1.1 * view.pressure_max if view.pressure_max > 0 else 1.0)
        ax.set_xlabel(f"x{_unit(view.length_unit)}")
        ax.set_ylabel(f"contact pressure p{_unit(view.stress_unit)}", color="tab:blue")
        ax.axvspan(-0.5 * view.footing_width, 0.5 * view.footing_width, color="0.93", zorder=0)
        twin = self.gap_axes = ax.twinx()
        (self.gap_line,) = twin.plot([], [], color="tab:red", lw=1.8, label="gap g")
        twin.set_ylim(0.0, 1.1 * view.gap_max if view.gap_max > 0 else 1.0)
        twin.set_ylabel(f"gap g{_unit(view.length_unit)}", color="tab:red")
        twin.ticklabel_format(axis="y", style="sci", scilimits=(-2, 3))
        handles = [self.pressure_fill, self.gap_line]
        # on the twin (drawn above the pressure): the legend stays on top of both curves
        self.legend = twin.legend(handles, [h.get_label() for h in handles], loc="upper left",
                                  fontsize=9)
        ax.grid(alpha=0.3)

    def show(self, frame: Frame) -> None:
        """Move and recolour the page's artists to ``frame``."""
        view = self.view
        moved = self.sub.points + view.scale * frame.displacement
        k = self.cells.shape[1]
        self._cell_xy[:, :k] = moved[self.cells]
        self._cell_xy[:, k] = self._cell_xy[:, 0]
        self.faces.stale = True
        values = self.sub.cell_values(frame.plastic_strain)[self.rows]
        self.faces.set_array(np.maximum(values, self.floor) if self.floor > 0.0 else values)
        self._edge_xy[...] = moved[self.edge_points]
        self.outlines.stale = True
        self.footing.set_xy(footing_outline(frame, view))
        x, p = np.asarray(frame.x, dtype=float), np.asarray(frame.pressure, dtype=float)
        self.pressure_fill.set_xy(np.vstack(([x[0], 0.0], np.column_stack((x, p)),
                                             [x[-1], 0.0])))
        self.pressure_line.set_data(x, p)
        self.gap_line.set_data(x, frame.gap)
        theta = frame.footing[2]
        self.title.set_text(
            f"{view.title}: {frame.label}\nθ = {theta:.3g} rad,  M = {frame.M:.4g}"
            f"{_unit(view.moment_unit)},  N = {frame.N:.4g}{_unit(view.force_unit)},  "
            f"contact {frame.contact_length / view.footing_width:.0%} of B")
