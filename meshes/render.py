"""Off-screen pictures of a footing on a soil mesh: the uplift zone as a PNG and an animated GIF
over a run's snapshots.

**What a picture shows.** Top panel: the soil near the footing (a window of 3B × 1.6B by
default), deformed with its displacements magnified by a stated factor, coloured by the
element-averaged equivalent plastic strain (colour bar with its unit; logarithmic over
:data:`~upliftlab.meshes.page.DECADES` decades below the run's largest value, so the whole
plastic zone shows and not only the peak at the footing edge), the element outlines,
and the rigid footing drawn as a block of height B/5 moved by its (u, v, θ) with the same
magnification. Bottom panel, on the same x axis: the contact pressure (filled) and the gap
(line, right axis) along the base: where the footing has lifted off, the pressure is zero and
the gap opens. The title names the scene, the step (static) or the time (dynamic), θ, M, N and
the contact length. Axis limits and colour limits are fixed over all frames of a run, so an
animation does not jump.

**How.** The files (PNG, GIF frames, the report's frame pages) are drawn with Pillow alone,
without importing matplotlib (whose import and first draw cost a run more than its frames): the
raster page is built once per picture set and redrawn per frame
(:mod:`~upliftlab.meshes.sheet`); the GIF is written frame by frame against one fixed palette
(:mod:`~upliftlab.meshes.gif`). Files appear complete or not at all. :func:`uplift_figure`
(a notebook's picture) draws the same page as a matplotlib figure
(:mod:`~upliftlab.meshes.page`, same layout, colour table and norm).

**A budget for the animation.** :func:`animate_uplift` with ``budget`` (CPU seconds) writes
as many of the snapshots, evenly spaced with the first and the last, as fit in that budget:
it times the page's set-up and its first frame, then takes
``1 + (budget − spent) / (CPU of one frame)`` frames, at least :data:`MIN_FRAMES` (so a run
whose solve is very short still gets an animation; its pictures then cost more than the
budget) and at most every snapshot. Without a budget every snapshot is a frame.
:func:`write_pictures` writes a run's default set — the PNG of one snapshot and the GIF, both
from one page drawn once, at the PNG's resolution — under one budget.

What is drawn (the linear sub-mesh of quadratic elements, the frames, the view fixed over a
run) is :mod:`~upliftlab.meshes.frames`'; its names are importable from here.
"""

from __future__ import annotations

import time

import numpy as np

from ..checks import InputError
from ..results import atomic_path
from .frames import (Frame, SubMesh, View, frames, linear_submesh, nice_scale,  # noqa: F401
                     snapshot_rows, uplift_view)
from .page import FIGURE_WIDTH_IN, Page

__all__ = ["SubMesh", "linear_submesh", "View", "Frame", "uplift_view", "frames",
           "snapshot_rows", "Page", "uplift_figure", "render_uplift", "animate_uplift",
           "write_pictures", "render_frames", "frame_subset", "frames_within", "nice_scale",
           "MIN_FRAMES"]

#: Fewest frames of a budgeted animation (module docstring).
MIN_FRAMES = 9


def _page(result, basis, footing_width: float, *, scale, title, dpi, width_in=FIGURE_WIDTH_IN,
          make=None, figure=False):
    """(page, frames) of a result: the view and the page built once; the raster
    :class:`~upliftlab.meshes.sheet.Sheet`, or with ``figure`` the matplotlib :class:`Page`."""
    sub = linear_submesh(basis)
    all_frames = frames(result, sub)
    view = uplift_view(result, sub, footing_width, scale=scale, title=title)
    largest = max(float(np.max(np.abs(f.displacement), initial=0.0)) for f in all_frames)
    if figure:
        return Page(sub, view, view.scale * largest, dpi=dpi, width_in=width_in,
                    make=make), all_frames
    from .sheet import Sheet

    return Sheet(sub, view, view.scale * largest, dpi=dpi, width_in=width_in), all_frames


def _write_png(path, picture, dpi: int):
    """Write a Pillow RGB ``picture`` to ``path`` as a PNG stamped with ``dpi``."""
    with atomic_path(path) as tmp:
        picture.save(tmp, format="PNG", dpi=(dpi, dpi))
    return path


def uplift_figure(result, basis, footing_width: float, *, snapshot: int = -1,
                  scale: float | None = None, title: str = "", dpi: int = 100, make=None):
    """The matplotlib figure of one snapshot (default the last) of a result on ``basis`` (the
    module docstring's picture, drawn by matplotlib), nothing written; ``make(width, height,
    dpi)`` makes the figure (default: a Figure outside pyplot)."""
    _check_snapshot(result, snapshot)
    page, all_frames = _page(result, basis, footing_width, scale=scale, title=title, dpi=dpi,
                             make=make, figure=True)
    page.show(all_frames[snapshot])
    return page.figure


def render_uplift(path, result, basis, footing_width: float, *, snapshot: int = -1,
                  scale: float | None = None, title: str = "", dpi: int = 100):
    """Write the PNG of one snapshot (default the last; the module docstring's picture, the
    raster page) to ``path``. Returns the path."""
    _check_snapshot(result, snapshot)
    page, all_frames = _page(result, basis, footing_width, scale=scale, title=title, dpi=dpi)
    page.show(all_frames[snapshot])
    return _write_png(path, page.picture(), dpi)


def _check_snapshot(result, snapshot: int) -> None:
    """Refuse a ``snapshot`` index the result does not have, naming the valid range."""
    count = np.size(result.snapshot_time)
    if not -count <= snapshot < count:
        raise InputError(f"snapshot = {snapshot}: valid range is [{-count}, {count - 1}]")


def frames_within(budget: float, spent: float, per_frame: float, count: int) -> int:
    """How many of ``count`` snapshots a budgeted animation draws (module docstring):
    ``1 + (budget − spent) / per_frame`` (all CPU seconds) within [min(MIN_FRAMES, count),
    count]."""
    fits = 1 + int((budget - spent) // per_frame) if per_frame > 0.0 else count
    return max(min(MIN_FRAMES, count), min(count, fits))


def _animate(page, all_frames, path, *, seconds_per_frame: float, budget, start: float,
             progress) -> int:
    """Write the GIF of ``all_frames`` on a raster ``page`` (module docstring's budget rule,
    ``start`` the CPU time the budget counts from). Returns the number of frames."""
    from .gif import write_gif

    chosen = list(range(len(all_frames)))
    with write_gif(path, seconds_per_frame) as gif:
        ready = time.process_time()
        page.show(all_frames[0])
        gif.add(page.picture())
        if budget is not None and len(all_frames) > 1:
            now = time.process_time()
            count = frames_within(budget, now - start, now - ready, len(all_frames))
            chosen = frame_subset(len(all_frames), count)
        for k, index in enumerate(chosen):
            if k:
                page.show(all_frames[index])
                gif.add(page.picture())
            if progress is not None:
                progress(k, len(chosen))
    return len(chosen)


def animate_uplift(path, result, basis, footing_width: float, *, scale: float | None = None,
                   title: str = "", seconds_per_frame: float = 0.25, dpi: int = 80,
                   budget: float | None = None, progress=None):
    """Write an animated GIF of a result's snapshots to ``path`` (same view and limits in every
    frame): every snapshot, or with ``budget`` (CPU seconds) as many evenly spaced ones as
    the module docstring's rule gives. ``progress(k, n)`` is called after each of the ``n``
    frames. Returns the path."""
    start = time.process_time()
    page, all_frames = _page(result, basis, footing_width, scale=scale, title=title, dpi=dpi)
    _animate(page, all_frames, path, seconds_per_frame=seconds_per_frame, budget=budget,
             start=start, progress=progress)
    return path


def write_pictures(png, gif, result, basis, footing_width: float, *, snapshot: int = -1,
                   scale: float | None = None, title: str = "", dpi: int = 100,
                   seconds_per_frame: float = 0.25, budget: float | None = None,
                   progress=None) -> int:
    """The default picture set of a run on one page drawn once: the PNG of ``snapshot``
    (:func:`render_uplift`'s picture) at ``png`` and the GIF (:func:`animate_uplift`'s, same
    ``dpi``) at ``gif``; ``budget`` (CPU seconds) bounds both together (module docstring).
    Returns the number of GIF frames."""
    start = time.process_time()
    _check_snapshot(result, snapshot)
    page, all_frames = _page(result, basis, footing_width, scale=scale, title=title, dpi=dpi)
    page.show(all_frames[snapshot])
    _write_png(png, page.picture(), dpi)
    return _animate(page, all_frames, gif, seconds_per_frame=seconds_per_frame, budget=budget,
                    start=start, progress=progress)


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
    page, all_frames = _page(result, basis, footing_width, scale=scale, title=title, dpi=dpi,
                             width_in=width_in)
    chosen = frame_subset(len(all_frames), limit)
    written = []
    for k, index in enumerate(chosen):
        page.show(all_frames[index])
        path = _write_png(directory / f"frame_{k:03d}.png", page.picture(), dpi)
        written.append((path, all_frames[index]))
        if progress is not None:
            progress(k, len(chosen))
    return written
