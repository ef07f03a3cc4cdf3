"""What a continuum result shows in a notebook: :meth:`plot`, :meth:`render` and its HTML table,
one set of methods that a dynamic result and a static path share (the figures and the table
themselves are :mod:`~upliftlab.continuum.output.notebook`'s)."""

from __future__ import annotations

__all__ = ["NotebookViews"]


class NotebookViews:
    """The notebook's views of a continuum result (a mix-in of its record classes)."""

    def plot(self, variables=None, ax=None):
        """A matplotlib figure of the run (nothing written): the panels ``variables`` (names
        of :data:`~upliftlab.continuum.output.notebook.PANELS`; default by kind), on new axes
        or on ``ax`` (one axis per panel)."""
        from .notebook import result_plot

        return result_plot(self, variables, ax)

    def render(self, model, snapshot: int | None = None, *, scale: float | None = None,
               title: str | None = None):
        """A matplotlib figure of the soil picture at snapshot index ``snapshot`` (default:
        the one of largest |θ|): the deformed soil coloured by plastic strain, the footing,
        and the contact pressure and gap along the base; ``model`` is the model the result was
        computed on (:func:`~upliftlab.continuum.output.notebook.render_result`)."""
        from .notebook import render_result

        return render_result(self, model, snapshot, scale=scale, title=title)

    def _repr_html_(self) -> str:
        """The notebook's table: kind, scene, span, peaks with units, code digest."""
        from .notebook import result_html

        return result_html(self)
