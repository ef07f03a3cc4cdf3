"""A study's figure as the report prints it: drawn at the printed page width with text of at
least 9 pt, saved as SVG (vector, what the report embeds) and PNG (a quick look), with its
caption beside it in ``<stem>.figure.json``.

The caption has three parts: a ``title`` (the one question the figure answers), ``shown``
(what is drawn, with units) and ``conclusion`` (what to conclude). The conclusion is written by
the code that draws the figure, from the same numbers it plots, so a caption cannot say
something the figure does not show. ``dense`` marks an all-panel figure that the report keeps
behind an expandable section.

Print size: :data:`PAGE_WIDTH_IN` (6.5 in) fits the text width of A4 (210 mm − 2 × 14 mm =
7.2 in) and of Letter (8.5 in − 2 × 14 mm = 7.4 in), so a figure prints at its own size and its
text at its own point size; :func:`save` refuses a figure wider than that or with visible text
below :data:`MIN_FONT_PT`. The SVG keeps text as text (``svg.fonttype = none``): one SVG
user unit is one point, so the sizes can be read back from the file.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass
from pathlib import Path

from ...results import atomic_path, write_text

__all__ = ["PAGE_WIDTH_IN", "MIN_FONT_PT", "Caption", "FigureRecord", "print_style",
           "page_figure", "small_text", "plain_log_ticks", "save", "save_frames", "read",
           "is_record", "RECORD_SUFFIX"]

#: Width (in) every figure is drawn at: the printed text width with a margin on A4 and Letter.
PAGE_WIDTH_IN = 6.5
#: Smallest text size (pt) a figure may carry.
MIN_FONT_PT = 9.0
#: File name ending of a figure's caption record.
RECORD_SUFFIX = ".figure.json"

_RC = {"font.size": 9.0, "axes.titlesize": 9.5, "axes.labelsize": 9.0, "xtick.labelsize": 9.0,
       "ytick.labelsize": 9.0, "legend.fontsize": 9.0, "legend.title_fontsize": 9.0,
       "figure.titlesize": 10.0, "svg.fonttype": "none", "svg.hashsalt": "upliftlab",
       "image.cmap": "viridis"}


@dataclass(frozen=True)
class Caption:
    """What a figure answers (``title``), what it shows (``shown``, with units) and what to
    conclude from it (``conclusion``, numbers computed from the plotted data); ``dense``: an
    all-panel figure kept behind an expandable section."""

    title: str
    shown: str
    conclusion: str
    dense: bool = False


@dataclass(frozen=True)
class FigureRecord:
    """A figure on disk: its ``image`` (SVG), the ``png`` beside it and its :class:`Caption`;
    an animation has its ``frames`` instead, (PNG, label) pairs in order (``image`` is then the
    last frame and ``png`` None)."""

    image: Path
    png: Path | None
    caption: Caption
    frames: tuple[tuple[Path, str], ...] = ()

    @property
    def vector(self) -> bool:
        return self.image.suffix == ".svg"


def print_style():
    """The matplotlib settings figures are drawn under (9 pt text, text kept as text in SVG,
    viridis); a context manager."""
    import matplotlib

    return matplotlib.rc_context(_RC)


def page_figure(height_in: float, nrows: int = 1, ncols: int = 1, **kwargs):
    """``(figure, axes)`` of :data:`PAGE_WIDTH_IN` × ``height_in`` inches, constrained layout;
    call inside :func:`print_style`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kwargs.setdefault("layout", "constrained")
    return plt.subplots(nrows, ncols, figsize=(PAGE_WIDTH_IN, height_in), **kwargs)


def small_text(fig) -> list[tuple[str, float]]:
    """The visible, non-empty texts of ``fig`` smaller than :data:`MIN_FONT_PT`: (text, pt)."""
    from matplotlib.text import Text

    found = []
    for t in fig.findobj(Text):
        if t.get_visible() and t.get_text().strip() and _shown(t):
            if t.get_fontsize() < MIN_FONT_PT - 1e-9:
                found.append((t.get_text(), float(t.get_fontsize())))
    return found


def _shown(artist) -> bool:
    """False when the artist or an axes that holds it is hidden."""
    axes = getattr(artist, "axes", None)
    return axes is None or axes.get_visible()


def _plain(value: float, _position=None) -> str:
    return f"{value:g}"


def plain_log_ticks(fig) -> None:
    """Label the log and symlog axes of ``fig`` (colour bars included) 0.1, 1, 10, 1e-06 —
    plain text at the tick size — instead of 10⁻¹, whose exponent prints at 70 % of it; no
    minor labels."""
    from matplotlib.ticker import FuncFormatter, NullFormatter

    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() in ("log", "symlog"):
                axis.set_major_formatter(FuncFormatter(_plain))
                axis.set_minor_formatter(NullFormatter())


def _check(fig, path: Path) -> None:
    width, _ = fig.get_size_inches()
    if width > PAGE_WIDTH_IN + 1e-9:
        raise ValueError(f"{path.name}: figure is {width:.2f} in wide; the printed page takes "
                         f"{PAGE_WIDTH_IN} in")
    small = small_text(fig)
    if small:
        listed = "; ".join(f"{t[:30]!r} {s:g} pt" for t, s in small[:5])
        raise ValueError(f"{path.name}: text below {MIN_FONT_PT:g} pt: {listed}")


def _record_path(path: Path) -> Path:
    return path.with_name(path.stem + RECORD_SUFFIX)


def _write_record(path: Path, image: Path, png: Path | None, caption: Caption,
                  frames: tuple = ()) -> Path:
    record = {"image": Path(image).relative_to(path.parent).as_posix(),
              "png": png.name if png else None, **asdict(caption)}
    if frames:
        record["frames"] = [{"image": Path(p).relative_to(path.parent).as_posix(),
                             "label": label} for p, label in frames]
    return write_text(_record_path(path), json.dumps(record, indent=1, ensure_ascii=False) + "\n")


def save(path, fig, caption: Caption, *, png_dpi: int = 110) -> list[Path]:
    """Label log axes in plain numbers (:func:`plain_log_ticks`), check ``fig`` prints
    readably (width, text sizes: ValueError otherwise), then write
    ``<stem>.svg``, ``<stem>.png`` and the caption record ``<stem>.figure.json`` beside
    ``path`` (any suffix); close the figure. Returns [record, svg, png]."""
    import matplotlib.pyplot as plt

    path = Path(path)
    svg, png = path.with_suffix(".svg"), path.with_suffix(".png")
    try:
        plain_log_ticks(fig)
        _check(fig, path)
        path.parent.mkdir(parents=True, exist_ok=True)
        with print_style():
            with atomic_path(svg) as tmp:
                fig.savefig(tmp, format="svg", metadata={"Date": None,
                                                         "Description": caption.title})
            # the layout the SVG's draw found is kept for the PNG (a figure's constrained
            # layout is most of its drawing time: its text extents, measured again)
            fig.set_layout_engine("none")
            with atomic_path(png) as tmp:
                fig.savefig(tmp, format="png", dpi=png_dpi)
    finally:
        plt.close(fig)
    return [_write_record(path, svg, png, caption), svg, png]


def save_frames(path, frames, caption: Caption) -> Path:
    """The caption record ``<stem>.figure.json`` of an animation whose ``frames`` are (PNG
    path, label) pairs in order, under ``path``'s folder; its path."""
    path, frames = Path(path), tuple((Path(p), str(label)) for p, label in frames)
    if not frames:
        raise ValueError(f"{path.name}: an animation needs at least one frame")
    return _write_record(path, frames[-1][0], None, caption, frames)


def read(record: str | Path) -> FigureRecord:
    """The :class:`FigureRecord` of a ``*.figure.json`` file (images beside it)."""
    record = Path(record)
    data = json.loads(record.read_text(encoding="utf-8"))
    png = record.parent / data["png"] if data.get("png") else None
    caption = Caption(data["title"], data["shown"], data["conclusion"],
                      bool(data.get("dense", False)))
    frames = tuple((record.parent / f["image"], f["label"]) for f in data.get("frames", ()))
    return FigureRecord(record.parent / data["image"], png, caption, frames)


def is_record(path: str | Path) -> bool:
    """Whether ``path`` names a caption record."""
    return str(path).endswith(RECORD_SUFFIX)

