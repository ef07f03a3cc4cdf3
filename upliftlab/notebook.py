"""What a result shows in a notebook: a new matplotlib figure for its ``plot()``, and the compact
HTML table of its ``_repr_html_``.

**Figures.** :func:`new_figure` gives a figure that shows once wherever it lands: in a
Jupyter kernel a figure outside pyplot's list (the cell shows it as its value, as PNG, and
pyplot's inline backend does not show it a second time), elsewhere a pyplot figure, so that
``plt.show()``, ``fig.savefig(...)`` and the docs gallery's scraper see it. Nothing is written
to a file.

**Tables.** :func:`html_table` lays out (name, value) rows under a title; :func:`digest_line`
is the provenance a table shows: the code's digest (12 hex digits of ``source_sha256``), its
version and when it ran.
"""

from __future__ import annotations

import html
import math

from .checks import InputError
from .progress import in_kernel

__all__ = ["new_figure", "panel_axes", "html_table", "digest_line", "number",
           "check_variables"]


def _matplotlib():
    try:
        import matplotlib
    except ImportError:
        raise InputError("plots need matplotlib: pip install 'upliftlab[plot]'") from None
    return matplotlib


def _show_figures_in_kernel() -> None:
    """Register the PNG display of matplotlib figures in this kernel (what the inline backend
    does), so that a figure outside pyplot shows as a cell's value whatever the backend."""
    from IPython import get_ipython
    from IPython.core.pylabtools import print_figure
    from matplotlib.figure import Figure

    formatter = get_ipython().display_formatter.formatters["image/png"]
    if Figure not in formatter.type_printers:
        formatter.for_type(Figure, lambda fig: print_figure(fig, "png", bbox_inches="tight"))


def new_figure(width: float, height: float, *, dpi: float | None = None,
               layout: str | None = "constrained"):
    """A new matplotlib figure ``width`` × ``height`` inches (module docstring)."""
    _matplotlib()
    if in_kernel():
        from matplotlib.figure import Figure

        _show_figures_in_kernel()
        return Figure(figsize=(width, height), dpi=dpi, layout=layout)
    import matplotlib.pyplot as plt

    return plt.figure(figsize=(width, height), dpi=dpi, layout=layout)


def panel_axes(ax, count: int):
    """(figure, axes): ``count`` stacked panels on a new figure (7 in wide, 1.9 in per
    panel), or the user's ``ax`` (one matplotlib axis per panel, else an InputError)."""
    if ax is None:
        fig = new_figure(7.0, 1.9 * count + 0.6)
        return fig, list(fig.subplots(count, 1, squeeze=False)[:, 0])
    axes = [ax] if hasattr(ax, "plot") else list(ax)
    if len(axes) != count:
        raise InputError(f"ax: {len(axes)} axes for {count} panels (give one axis per "
                         "variable)")
    return axes[0].figure, axes


def check_variables(variables, valid: tuple[str, ...], default: tuple[str, ...]) -> tuple:
    """The panels asked for: ``variables`` (names from ``valid``) or ``default``; an unknown
    name is refused before anything is drawn."""
    if variables is None:
        return default
    chosen = (variables,) if isinstance(variables, str) else tuple(variables)
    unknown = [v for v in chosen if v not in valid]
    if unknown or not chosen:
        raise InputError(f"variables = {variables!r}: valid names are {', '.join(valid)}")
    return chosen


def number(value, unit: str = "", digits: int = 4) -> str:
    """``value`` to ``digits`` significant digits with its unit (``–`` when not finite or
    absent)."""
    if value is None or not math.isfinite(float(value)):
        return "–"
    return f"{float(value):.{digits}g}" + (f" {unit}" if unit else "")


def digest_line(record: dict) -> str:
    """The provenance a table shows (module docstring), from a result's provenance record."""
    digest = str(record.get("source_sha256", ""))[:12] or "?"
    parts = [f"code {digest}"]
    if record.get("upliftlab_version"):
        parts.append(f"upliftlab {record['upliftlab_version']}")
    if record.get("created_utc"):
        parts.append(str(record["created_utc"]))
    return ", ".join(parts)


def html_table(title: str, rows) -> str:
    """An HTML table of ``rows`` ((name, value) text pairs) under ``title``, escaped."""
    body = "".join(f"<tr><th style='text-align:left'>{html.escape(str(name))}</th>"
                   f"<td style='text-align:left'>{html.escape(str(value))}</td></tr>"
                   for name, value in rows)
    return (f"<table><caption style='text-align:left'><b>{html.escape(title)}</b></caption>"
            f"{body}</table>")
