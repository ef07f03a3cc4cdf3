"""The report's figures: each study's caption records (:mod:`.figure_record`) as numbered
``<figure>`` elements.

A plot is embedded as SVG (``data:image/svg+xml;base64``: vector, prints sharp at any size,
and its ids cannot collide with another figure's as inline SVG's could); a rendered soil
picture as PNG; an animation as its frames with a frame slider (:mod:`.report_animation`).
The caption is the record's: the question in bold, what is shown, then the conclusion. A
dense all-panel figure sits in a ``<details>`` section, closed on screen and opened for
printing. Figures are numbered by a CSS counter, so a figure inside a closed section still
keeps the numbers of those after it.
"""

from __future__ import annotations

import html
from pathlib import Path

from ..framework.figure_record import FigureRecord, is_record, read
from .animation import animation_html
from .images import data_uri
from ..framework.study import StudyResult

__all__ = ["records_of", "figure_id", "figure_html", "figures_html"]



def records_of(study: StudyResult) -> list[FigureRecord]:
    """The figure records among ``study``'s files, in the study's order."""
    return [read(p) for p in study.files if is_record(p) and Path(p).is_file()]


def caption_html(record: FigureRecord) -> str:
    """The caption: the question in bold, what is shown, the conclusion."""
    c = record.caption
    title = c.title if c.title.rstrip().endswith(("?", ".", "!")) else c.title + "."
    return (f"<figcaption><strong>{html.escape(title)}</strong> {html.escape(c.shown)} "
            f'<span class="conclusion">{html.escape(c.conclusion)}</span></figcaption>')


def figure_id(study: str, record: FigureRecord) -> str:
    """The id of ``record``'s figure in ``study``'s section: ``fig-<study>-<file stem>``,
    unique in the page (a study's figures are files of one folder), so a link can name it."""
    return f"fig-{study}-{record.image.stem}".replace("_", "-").replace(" ", "-")


def _anchored(caption: str, ident: str) -> str:
    """The caption with a link to its own figure at its end (to copy the figure's address)."""
    return caption.replace("</figcaption>", f' <a class="anchor" href="#{ident}" '
                           f'title="link to this figure">#</a></figcaption>')


def figure_html(record: FigureRecord, ident: str = "") -> str:
    """One ``<figure>`` (with the id ``ident``, and a link to itself in its caption, when
    given): the image (or the animation) and its caption; a notice if the image file is
    gone."""
    caption = _anchored(caption_html(record), ident) if ident else caption_html(record)
    if record.frames:
        return (f'<span id="{ident}"></span>' if ident else "") + animation_html(record, caption)
    if not record.image.is_file():
        return (f'<p class="notice">Figure “{html.escape(record.caption.title)}”: its file '
                f"{html.escape(record.image.name)} is missing.</p>")
    kind = "plot" if record.vector else "render"
    where = f' id="{ident}"' if ident else ""
    return (f'<figure{where}><img class="{kind}" alt="{html.escape(record.caption.title)}" '
            f'src="{data_uri(record.image)}">{caption}</figure>')


def figures_html(study: StudyResult) -> str:
    """Every figure of ``study``, each with its id (:func:`figure_id`): the readable ones in
    order, then the dense ones behind one expandable section."""
    records = records_of(study)
    main = [figure_html(r, figure_id(study.name, r)) for r in records if not r.caption.dense]
    dense = [figure_html(r, figure_id(study.name, r)) for r in records if r.caption.dense]
    out = "\n".join(main)
    if dense:
        out += (f'\n<details class="dense"><summary>All panels, measure by measure '
                f"({len(dense)} figure{'s' if len(dense) != 1 else ''})</summary>"
                + "\n".join(dense) + "</details>")
    return out
