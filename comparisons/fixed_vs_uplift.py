"""Fixed base against uplift allowed: Ewing's Figs. 11–12 and a base-shear spectrum.

**Figs. 11–12.** The paper's short-period (T = 0.15 s) and long-period (T = 0.59 s) buildings
under El Centro 1940 N-S, in the reduced model: the ``fixed`` case (θ and V locked) against
Case C (elasto-plastic springs with 10 % damping and impact damping, ε = 0.7; uplift allowed),
on the scenes' Winkler bed of 12 springs, as drawn in Fig. 1(b). The continuum counterpart
(a stiff bonded footing against unilateral contact) runs when
:mod:`upliftlab.continuum.dynamics` exists; the summary says when it was not run.

**Spectrum** (in the manner of Yim and Chopra 1985). The superstructure period T is swept over
0.05–3 s with everything else held (base width, height and so the aspect ratio h/b = 2.8, the
weights, the rotary inertia of each building's base body, the foundation), for the fixed base,
uplift allowed in Case C, and uplift allowed on Case A's elastic springs with 40 % damping (the
model of Yim and Chopra). Peak base shear (as a coefficient V/W) and peak deformation u are
compared as ratios uplift/fixed at each period. The reduced runs go through
:func:`upliftlab.reduced.run_batch`; every run is kept in a content-addressed
:class:`.store.Store`, so running the study again computes nothing already stored. The
summary's statements (the period ranges over which uplift reduces each peak, and by how much)
are computed from the data.

Run it with ``python -m upliftlab.comparisons.fixed_vs_uplift [--fast] [--out DIR]``.
"""

from __future__ import annotations

import copy
import math
import sys
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from .. import checks
from ..checks import InputError
from ..motions import ELCENTRO, find_motion
from ..results import provenance, write_csv
from ..scenes import Scene, load_scene, scene_from_dict
from ..reduced import run as run_reduced
from ..reduced.batch import run_batch
from .protocol import Context, Study, main_for, run_study
from .store import Store, point_key
from .study import StudyResult, file_sha256, require_matplotlib, write_figure, write_summary
from .speed_vs_error import continuum_status

__all__ = ["STUDY", "BUILDINGS", "SUPPORTS", "Grid", "FULL_GRID", "FAST_GRID", "Figure",
           "Spectrum", "Ranges", "FixedVsUplift", "Options", "DEFINITION", "compute", "write",
           "run",
           "main", "figure_run",
           "spectrum_points", "reduction_ranges", "check_grid", "PAPER_FIG11_PEAK_U"]

STUDY = "fixed_vs_uplift"
BUILDINGS = {"short": "short_period_elcentro", "long": "long_period_elcentro"}
FIGURES = {"short": 11, "long": 12}
SUPPORTS = ("fixed", "C", "A")
SUPPORT_LABELS = {"fixed": "fixed base", "C": "uplift allowed, Case C",
                  "A": "uplift allowed, Case A (elastic, 40 %)"}
#: Fig. 11 as read from the paper (in): peak deformation with uplift allowed and fixed base.
PAPER_FIG11_PEAK_U = {"C": 0.055, "fixed": 0.164}
PAPER_PERIODS = (0.15, 0.59)
OUTPUT_DT = 0.005  # s, histories of Figs. 11-12 (peaks are tracked at every step)
NO_CHANGE = 0.02  # ratios within 2 % of one count as "no change" (no or negligible uplift)


@dataclass(frozen=True)
class Grid:
    """``periods`` (s, ascending) of the spectrum, the building ``families`` whose base body is
    kept (``short``: I₀ = 7694, ``long``: I₀ = 1740 kip·in·s²), the ``supports`` (cases), and
    ``figures`` (the buildings of Figs. 11–12 to run)."""

    periods: tuple[float, ...]
    families: tuple[str, ...] = ("short", "long")
    supports: tuple[str, ...] = SUPPORTS
    figures: tuple[str, ...] = ("short", "long")


def _periods(count: int) -> tuple[float, ...]:
    grid = {round(float(t), 4) for t in np.geomspace(0.05, 3.0, count)}
    return tuple(sorted(grid | set(PAPER_PERIODS)))


FULL_GRID = Grid(periods=_periods(30))
FAST_GRID = Grid(periods=_periods(8), families=("short",))


@dataclass(frozen=True)
class Options:
    """``figures``: write the PNGs (needs matplotlib)."""

    figures: bool = True


def check_grid(grid: Grid) -> Grid:
    """Validate the grid; an :class:`InputError` names the field, value and valid range."""
    p = grid.periods
    if isinstance(p, (str, bytes)) or not isinstance(p, Sequence) or len(p) < 2:
        raise InputError(f"grid.periods = {p!r}: expected at least two periods (s)")
    for i, t in enumerate(p):
        checks.in_range(f"grid.periods[{i}]", t, 0.02, 10.0)
    if any(b <= a for a, b in zip(p, p[1:])):
        raise InputError(f"grid.periods = {list(p)!r}: values must strictly ascend")
    for name, values, valid in (("families", grid.families, BUILDINGS),
                                ("supports", grid.supports, SUPPORTS),
                                ("figures", grid.figures, BUILDINGS)):
        if isinstance(values, str) or not isinstance(values, Sequence):
            raise InputError(f"grid.{name} = {values!r}: expected a list from {list(valid)}")
        for i, v in enumerate(values):
            checks.one_of(f"grid.{name}[{i}]", v, tuple(valid))
    if "fixed" not in grid.supports or len(grid.supports) < 2:
        raise InputError(f"grid.supports = {list(grid.supports)!r}: needs 'fixed' and at least "
                         "one uplift case ('C' or 'A') to compare")
    return grid


# ---------------------------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------------------------


def _scene(building: str, support: str) -> Scene:
    return load_scene(BUILDINGS[building], case=support)


def _record() -> dict:
    path = find_motion(ELCENTRO)
    return {"motion_sha256": file_sha256(path), "_motion_path": str(path.resolve())}


def _scene_of(point: Mapping) -> Scene:
    data = copy.deepcopy(point["scene"])
    if "period" in point:
        data["structure"].pop("stiffness", None)
        data["structure"]["period"] = point["period"]
    if "_motion_path" in point:
        data["motion"]["name"] = point["_motion_path"]
    return scene_from_dict(data, merged=True)


def figure_run(point: Mapping) -> dict:
    """One run of Figs. 11–12 with histories: time (s), u (length) and the peaks."""
    response = run_reduced(_scene_of(point), output_dt=OUTPUT_DT)
    pk = response.peaks
    return {"time": response.time.tolist(), "u": response.u.tolist(), "peak_u": pk["u"],
            "base_shear": pk["base_shear"], "theta": pk["theta"],
            "uplift": pk.get("uplift_max", 0.0),
            "weight": response.model.scene.structure.weight}


def _cached(store: Store, name: str, params: dict):
    """The record of function ``name`` (of this module) at ``params``: from the store, or
    computed and stored if missing."""
    key = point_key(STUDY, name, params)
    record = store.get(key)
    if record is None:
        record = globals()[name](params)
        store.put(key, record, {"study": STUDY, "function": name, "params": params})
    return record


def spectrum_points(grid: Grid, record: dict) -> list[dict]:
    """One point per family, support and period: the scene table (period replaced)."""
    points = []
    for family in grid.families:
        for support in grid.supports:
            data = _scene(family, support).data
            for t in grid.periods:
                points.append({"scene": data, "period": float(t), **record,
                               "family": family, "support": support})
    return points


def _batch(points: Sequence[Mapping], workers: int | None) -> list[dict]:
    scenes = [_scene_of(p) for p in points]
    result = run_batch(scenes, workers=workers)
    out = []
    for i, (p, s) in enumerate(zip(points, scenes)):
        row = result.row(i)
        if row["status"] != "ok":
            out.append({"error": row["status"]})
            continue
        out.append({"u": row["u"], "base_shear": row["base_shear"], "theta": row["theta"],
                    "uplift": row["uplift_left"], "weight": s.structure.weight,
                    "dt": row["dt"], "energy_balance_error": row["energy_balance_error"]})
    return out


def _spectrum_records(points, store: Store, workers) -> list[dict]:
    keys = [point_key(STUDY, "run_batch", p) for p in points]
    todo = [i for i, k in enumerate(keys) if not store.has(k)]
    if todo:
        for i, record in zip(todo, _batch([points[i] for i in todo], workers)):
            store.put(keys[i], record, {"study": STUDY, "function": "run_batch",
                                        "params": points[i]})
    return [store.get(k) for k in keys]


# ---------------------------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Figure:
    """Fig. 11 or 12: ``time`` (s) and ``u`` (length) per support, and the peaks."""

    building: str
    number: int
    time: dict
    u: dict
    peak_u: dict
    base_shear: dict
    uplift: dict

    @property
    def ratio_u(self) -> float:
        return self.peak_u["C"] / self.peak_u["fixed"]

    @property
    def ratio_shear(self) -> float:
        return self.base_shear["C"] / self.base_shear["fixed"]


@dataclass(frozen=True)
class Ranges:
    """Where a ratio (uplift/fixed) is below 1 − :data:`NO_CHANGE`: ``reduced`` as (T_from,
    T_to) runs of consecutive grid periods (s), ``increased`` likewise above 1 + NO_CHANGE;
    the smallest ratio ``min_ratio`` at ``min_period``, the largest ``max_ratio`` at
    ``max_period`` and the ``median`` over the grid."""

    reduced: tuple[tuple[float, float], ...]
    increased: tuple[tuple[float, float], ...]
    min_ratio: float
    min_period: float
    max_ratio: float
    max_period: float
    median: float
    count_reduced: int
    total: int


@dataclass(frozen=True, eq=False)
class Spectrum:
    """Peak values against period for one building family: ``u`` (length), ``shear`` (V/W)
    and ``uplifted`` per support (arrays over ``periods``), and the ratio statements."""

    family: str
    periods: np.ndarray
    u: dict
    shear: dict
    uplifted: dict
    ranges: dict  # (support, "shear" | "u") -> Ranges

    def ratio(self, support: str, what: str) -> np.ndarray:
        values = self.shear if what == "shear" else self.u
        return values[support] / values["fixed"]

    def at(self, support: str, what: str, period: float) -> float:
        i = int(np.argmin(np.abs(self.periods - period)))
        return float(self.ratio(support, what)[i])


def _runs(mask: np.ndarray, periods: np.ndarray) -> tuple[tuple[float, float], ...]:
    out, start = [], None
    for i, m in enumerate(mask):
        if m and start is None:
            start = i
        if start is not None and (not m or i == mask.size - 1):
            end = i if m else i - 1
            out.append((float(periods[start]), float(periods[end])))
            start = None
    return tuple(out)


def reduction_ranges(periods: Sequence[float], ratio: Sequence[float]) -> Ranges:
    """The period ranges over which ``ratio`` (uplift/fixed) is below or above one (by more
    than :data:`NO_CHANGE`), and its extremes; NaN ratios (failed runs) belong to neither."""
    t, r = np.asarray(periods, float), np.asarray(ratio, float)
    ok = np.isfinite(r)
    if not ok.any():
        raise InputError("ratio: no finite value; every run failed")
    lo, hi = int(np.nanargmin(r)), int(np.nanargmax(r))
    return Ranges(_runs(ok & (r < 1 - NO_CHANGE), t), _runs(ok & (r > 1 + NO_CHANGE), t),
                  float(r[lo]), float(t[lo]), float(r[hi]), float(t[hi]),
                  float(np.nanmedian(r)), int(np.sum(ok & (r < 1 - NO_CHANGE))), int(ok.sum()))


def _spectrum(family: str, grid: Grid, records: Sequence[Mapping]) -> Spectrum:
    n = len(grid.periods)
    u, shear, up = {}, {}, {}
    for k, support in enumerate(grid.supports):
        rows = records[k * n:(k + 1) * n]
        u[support] = np.array([r.get("u", math.nan) for r in rows])
        shear[support] = np.array([r.get("base_shear", math.nan) / r["weight"]
                                   if "error" not in r else math.nan for r in rows])
        up[support] = np.array([r.get("uplift", 0.0) > 0.0 for r in rows])
    periods = np.array(grid.periods)
    ranges = {}
    for support in grid.supports:
        if support != "fixed":
            for what, values in (("shear", shear), ("u", u)):
                ranges[(support, what)] = reduction_ranges(periods,
                                                           values[support] / values["fixed"])
    return Spectrum(family, periods, u, shear, up, ranges)


@dataclass(frozen=True, eq=False)
class FixedVsUplift:
    """The study's result: files and summary (``study``), Figs. 11–12, the spectra."""

    study: StudyResult
    figures: tuple[Figure, ...]
    spectra: tuple[Spectrum, ...]
    grid: Grid
    continuum: str
    options: Options = None

    def figure(self, building: str) -> Figure:
        return next(f for f in self.figures if f.building == building)

    def spectrum(self, family: str) -> Spectrum:
        return next(s for s in self.spectra if s.family == family)


def _figure(building: str, store: Store, record: dict) -> Figure:
    runs = {s: _cached(store, "figure_run", {"scene": _scene(building, s).data, **record})
            for s in ("fixed", "C")}
    return Figure(building, FIGURES[building], {s: np.array(r["time"]) for s, r in runs.items()},
                  {s: np.array(r["u"]) for s, r in runs.items()},
                  {s: r["peak_u"] for s, r in runs.items()},
                  {s: r["base_shear"] for s, r in runs.items()},
                  {s: r["uplift"] for s, r in runs.items()})


def compute(scene, ctx: Context) -> FixedVsUplift:
    """The figures' runs and the spectra (``scene`` must be None: the study's scenes are the
    paper's buildings); ``ctx.grid`` (default :data:`FAST_GRID` or :data:`FULL_GRID`),
    ``ctx.options`` (:class:`Options`), ``ctx.workers`` processes of
    :func:`~upliftlab.reduced.run_batch`."""
    if scene is not None:
        raise InputError(f"scene = {scene!r}: this study runs the paper's buildings "
                         f"({', '.join(BUILDINGS.values())}); pass scene=None")
    grid = check_grid(ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID))
    options = ctx.options or Options()
    checks.boolean("figures", options.figures)
    if options.figures:
        require_matplotlib(STUDY)
    if ctx.workers is not None:
        checks.integer_at_least("workers", ctx.workers, 1)
    record = _record()
    figs = tuple(_figure(b, ctx.store, record) for b in grid.figures)
    points = spectrum_points(grid, record)
    records = _spectrum_records(points, ctx.store, ctx.workers)
    per = len(grid.supports) * len(grid.periods)
    spectra = tuple(_spectrum(f, grid, records[k * per:(k + 1) * per])
                    for k, f in enumerate(grid.families))
    _, note = continuum_status()
    note = note.replace("continuum points were not run", "the continuum comparison (stiff "
                        "bonded against unilateral-contact footing) was not run")
    return FixedVsUplift(None, figs, spectra, grid, note, options)


def run(scene: None = None, fast: bool = False, *, out: str | Path | None = None,
        store: Store | str | Path | None = None, grid: Grid | None = None,
        figures: bool = True, workers: int | None = None) -> FixedVsUplift:
    """Run the study (``scene`` must be None: the study's scenes are the paper's buildings).

    ``fast`` uses :data:`FAST_GRID` (10 periods, the short-period family) instead of
    :data:`FULL_GRID` (32 periods, both families). ``out``: output directory (default
    ``results/fixed_vs_uplift[-fast]``); ``store``: the results store (default
    ``<out>/store``); ``workers``: processes of :func:`~upliftlab.reduced.run_batch`.
    """
    return run_study(DEFINITION, scene, Context(fast=fast, out=out, store=store, grid=grid,
                                                options=Options(figures=figures),
                                                workers=workers))


# ---------------------------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------------------------


def write(result: FixedVsUplift, ctx: Context) -> StudyResult:
    """Histories, spectra, figures and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, fast=fast, grid=asdict(result.grid), store=str(store.root))
    files = []
    for f in result.figures:
        t = np.arange(0.0, min(f.time["fixed"][-1], f.time["C"][-1]), OUTPUT_DT)
        files.append(write_csv(out / f"fig{f.number}.csv",
                               {"time_s": t, "u_fixed": np.interp(t, f.time["fixed"],
                                                                  f.u["fixed"]),
                                "u_uplift_case_C": np.interp(t, f.time["C"], f.u["C"])},
                               header=f"{STUDY}: Fig. {f.number}, {f.building}-period "
                                      "building, El Centro 1940 N-S; u in inches"))
    for s in result.spectra:
        cols = {"period_s": s.periods}
        for support in result.grid.supports:
            cols[f"u_{support}"] = s.u[support]
            cols[f"shear_coefficient_{support}"] = s.shear[support]
            cols[f"uplifted_{support}"] = s.uplifted[support].astype(float)
        files.append(write_csv(out / f"spectrum_{s.family}.csv", cols,
                               header=f"{STUDY}: peak u (in) and base shear V/W against the "
                                      f"superstructure period, {s.family}-period building's "
                                      "base body, El Centro 1940 N-S"))
    if result.options.figures:
        files += [_plot_figures(result, out / "figures" / "fig11_12.png"),
                  _plot_spectra(result, out / "figures" / "spectrum.png")]
    elapsed = ctx.elapsed()
    numbers = _numbers(result, elapsed)
    text = _markdown(result, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def _plot_figures(result: FixedVsUplift, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(result.figures), 1, figsize=(9, 3.2 * len(result.figures)),
                             constrained_layout=True, squeeze=False)
    for ax, f in zip(axes[:, 0], result.figures):
        for s, style in (("fixed", "k-"), ("C", "C3-")):
            ax.plot(f.time[s], f.u[s], style, lw=0.8,
                    label=f"{SUPPORT_LABELS[s]} (peak {f.peak_u[s]:.3g} in)")
        ax.set_title(f"Fig. {f.number}: {f.building}-period building, El Centro 1940 N-S",
                     fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("u (in)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    return write_figure(path, fig)


def _plot_spectra(result: FixedVsUplift, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
    colours = {"fixed": "k", "C": "C3", "A": "C0"}
    for s, ls in zip(result.spectra, ("-", "--")):
        for support in result.grid.supports:
            lab = f"{s.family}: {SUPPORT_LABELS[support]}"
            axes[0].loglog(s.periods, s.shear[support], ls, color=colours[support], label=lab)
            axes[1].loglog(s.periods, s.u[support], ls, color=colours[support], label=lab)
            if support != "fixed":
                axes[2].semilogx(s.periods, s.ratio(support, "shear"), ls,
                                 color=colours[support], label=f"{lab}: V")
                axes[2].semilogx(s.periods, s.ratio(support, "u"), ls, color=colours[support],
                                 marker=".", alpha=0.6, label=f"{lab}: u")
    axes[2].axhline(1.0, color="grey", lw=0.8)
    for ax, title in zip(axes, ("peak base shear V/W", "peak deformation u (in)",
                                "ratio uplift / fixed")):
        ax.set_xlabel("superstructure period T (s)")
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return write_figure(path, fig)


def _ranges_dict(r: Ranges) -> dict:
    return {"reduced": r.reduced, "increased": r.increased, "min_ratio": r.min_ratio,
            "min_period": r.min_period, "max_ratio": r.max_ratio, "max_period": r.max_period,
            "median_ratio": r.median, "periods_reduced": r.count_reduced, "periods": r.total}


def _numbers(result: FixedVsUplift, elapsed: float) -> dict:
    figs = {f"fig{f.number}": {"building": f.building, "peak_u": f.peak_u,
                                "peak_base_shear": f.base_shear, "peak_uplift": f.uplift,
                                "ratio_u": f.ratio_u, "ratio_base_shear": f.ratio_shear}
            for f in result.figures}
    if "fig11" in figs:
        figs["fig11"]["paper_peak_u"] = PAPER_FIG11_PEAK_U
    spectra = {s.family: {f"{support}_{what}": _ranges_dict(r)
                          for (support, what), r in s.ranges.items()} for s in result.spectra}
    largest = {s.family: {k: float(np.nanmax(v)) for k, v in s.shear.items()}
               for s in result.spectra}
    at = {s.family: {f"{support}_{what}_T{t:g}": s.at(support, what, t)
                     for (support, what) in s.ranges for t in PAPER_PERIODS}
          for s in result.spectra}
    return {"figures": figs, "spectra": spectra, "ratios_at_paper_periods": at,
            "largest_shear_coefficient": largest,
            "periods": list(result.grid.periods), "continuum": result.continuum,
            "elapsed_s": elapsed}


def _span(runs) -> str:
    if not runs:
        return "nowhere on the grid"
    return ", ".join(f"{a:g}–{b:g} s" if a != b else f"{a:g} s" for a, b in runs)


def _markdown(result: FixedVsUplift, fast: bool, elapsed: float) -> str:
    lines = [f"# Fixed base against uplift allowed{' (fast)' if fast else ''}", "",
             f"El Centro 1940 N-S. Wall time {elapsed:.1f} s. Continuum: {result.continuum}.",
             "", "## Figs. 11–12 (reduced model, Winkler bed of 12 springs)", "",
             "The scenes' beds of 12 springs, as drawn in Fig. 1(b). Case C's impact dashpots "
             "are sized per spring, so its peaks depend on N (the speed_vs_error study measures "
             "by how much); the comparison is the paper's, at the paper's N.", "",
             "| figure | building | peak u fixed (in) | peak u uplift C (in) | ratio | "
             "peak V fixed (kip) | peak V uplift C (kip) | ratio |",
             "|---|---|---|---|---|---|---|---|"]
    for f in result.figures:
        lines.append(f"| {f.number} | {f.building}-period | {f.peak_u['fixed']:.4g} | "
                     f"{f.peak_u['C']:.4g} | {f.ratio_u:.3f} | {f.base_shear['fixed']:.4g} | "
                     f"{f.base_shear['C']:.4g} | {f.ratio_shear:.3f} |")
    if any(f.building == "short" for f in result.figures):
        f = result.figure("short")
        p = PAPER_FIG11_PEAK_U
        lines += ["", f"Fig. 11 as read from the paper: {p['C']:g} in (uplift) against "
                  f"{p['fixed']:g} in (fixed); here {f.peak_u['C']:.4g} and "
                  f"{f.peak_u['fixed']:.4g} in ({100 * (f.peak_u['C'] / p['C'] - 1):+.1f} % "
                  f"and {100 * (f.peak_u['fixed'] / p['fixed'] - 1):+.1f} %)."]
    lines += ["", "## Spectrum: uplift / fixed against the superstructure period", "",
              f"{len(result.grid.periods)} periods from {result.grid.periods[0]:g} to "
              f"{result.grid.periods[-1]:g} s; h/b = 2.8, weights, base body and foundation "
              f"held. A ratio within {100 * NO_CHANGE:g} % of one counts as no change.", ""]
    for s in result.spectra:
        peaks = ", ".join(f"{SUPPORT_LABELS[k]} {np.nanmax(v):.3f} (at "
                          f"{s.periods[int(np.nanargmax(v))]:g} s)" for k, v in s.shear.items())
        lines += [f"### {s.family}-period building's base body", "",
                  f"Largest base-shear coefficient V/W over the periods: {peaks}.", "",
                  "| uplift case | quantity | reduced over | by up to (min ratio, at T) | "
                  "median ratio | increased over | max ratio (at T) | at T = 0.15 s | "
                  "at T = 0.59 s |", "|---|---|---|---|---|---|---|---|---|"]
        for (support, what), r in s.ranges.items():
            name = "peak base shear" if what == "shear" else "peak deformation"
            lines.append(f"| {SUPPORT_LABELS[support]} | {name} | {_span(r.reduced)} "
                         f"({r.count_reduced} of {r.total}) | {100 * (1 - r.min_ratio):.0f} % "
                         f"({r.min_ratio:.3f}, {r.min_period:g} s) | {r.median:.3f} | "
                         f"{_span(r.increased)} | {r.max_ratio:.3f} ({r.max_period:g} s) | "
                         f"{s.at(support, what, 0.15):.3f} | {s.at(support, what, 0.59):.3f} |")
        lines.append("")
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _describe(result: FixedVsUplift) -> list[str]:
    lines = [f"Fig. {f.number}: peak u fixed {f.peak_u['fixed']:.4g} in, uplift (C) "
             f"{f.peak_u['C']:.4g} in (ratio {f.ratio_u:.3f}); base shear ratio "
             f"{f.ratio_shear:.3f}" for f in result.figures]
    for s in result.spectra:
        r = s.ranges[("C", "shear")]
        lines.append(f"{s.family}: Case C reduces peak base shear over {_span(r.reduced)} "
                     f"(min ratio {r.min_ratio:.3f} at {r.min_period:g} s)")
    return lines


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(figures=not args.no_figures))


DEFINITION = Study(STUDY, "Fixed base against uplift",
                   "What allowing uplift changes against a fixed base.", Options, compute, write,
                   describe=_describe, context_from=_context_from,
                   help_fast="10 periods, short-period family")
main = main_for(DEFINITION)


if __name__ == "__main__":
    sys.exit(main())
