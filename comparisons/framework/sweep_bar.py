"""A sweep's progress as a tqdm bar (:mod:`upliftlab.progress`): in a notebook, or wherever a
caller asks for one (``run_sweep(progress=True)``)."""

from __future__ import annotations

from ...progress import bar, in_kernel

__all__ = ["BarProgress", "sweep_report"]


class BarProgress:
    """A progress bar over a sweep's points: done of total, elapsed time, the rate and ETA of
    the points computed in this call (those already stored start the bar), closed when the
    last point is stored."""

    def __init__(self):
        self._bar = None

    def __call__(self, p) -> None:
        if self._bar is None:
            self._bar = bar(p.total, f"{p.study} sweep", unit="point")
            self._bar.update(p.done)
            self._bar.unpause()  # the stored points came at once: the rate counts from here
        self._bar.update(p.done - self._bar.n)
        if p.done >= p.total:
            self._bar.close()


def sweep_report(progress, lines):
    """What reports a sweep's progress, from ``run_sweep``'s ``progress``: True a bar, False
    nothing, a callable itself, None a bar in a Jupyter kernel and else ``lines()`` (the
    sweep's lines on stderr)."""
    if progress is True or (progress is None and in_kernel()):
        return BarProgress()
    if progress is None:
        return lines()
    return progress or None
