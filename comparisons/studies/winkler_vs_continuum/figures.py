"""The study's figures: monotonic and cyclic paths, errors and dynamic histories, each at page
width with a caption whose conclusion is computed from the plotted numbers
(:mod:`..figure_record`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....anchors import half_plane_rocking, winkler_rocking
from ...beds.stiffness import LABELS
from ...framework.figure_record import Caption, page_figure, print_style, save
from ...framework.map_figures import MAX_HEIGHT_IN
from .analysis import ErrorTable
from .dynamics import DynamicRun
from .result import WinklerVsContinuum


# colour-blind-safe (Okabe–Ito) and told apart by line style as well
_COLORS = {"uniform": "#D55E00", "end_stiffened": "#0072B2", "uniform_plastic": "#E69F00",
           "end_stiffened_plastic": "#56B4E9"}
_STYLES = {"uniform": "-", "end_stiffened": "--", "uniform_plastic": "-.",
           "end_stiffened_plastic": ":"}


def write_figures(result: WinklerVsContinuum, directory: Path) -> list[Path]:
    """Every figure (records, SVG and PNG) into ``directory``; the files."""
    files = save(directory / "monotonic.png", *_monotonic_figure(result))
    files += save(directory / "cyclic.png", *_cyclic_figure(result))
    files += save(directory / "errors.png", *_error_figure(result.table))
    for run in result.dynamics.runs:
        files += save(directory / f"dynamic_{run.key}.png", *_dynamic_figure(result, run))
    return files


def _ratio_text(ratios: dict) -> str:
    return "; ".join(f"{LABELS[k]} {v:.2f}" for k, v in ratios.items())


def _dynamic_figure(result: WinklerVsContinuum, run: DynamicRun):
    length = result.scene.units.length
    panels = (("theta", "θ (rad)"), ("u", f"u ({length})"), ("uplift", f"edge uplift ({length})"),
              ("settlement", f"settlement ({length})"))
    with print_style():
        fig, axes = page_figure(7.6, 4, 1, sharex=True)
        for ax, (key, label) in zip(axes, panels):
            ax.plot(run.time, run.continuum[key], "k-", lw=1.6, label="continuum")
            for name, bed in run.beds.items():
                ax.plot(run.time, bed[key], _STYLES[name], lw=1.0, color=_COLORS[name],
                        label=LABELS[name])
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time (s)")
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    peak = float(np.max(np.abs(run.continuum["theta"])))
    ratios = {name: float(np.max(np.abs(bed["theta"]))) / peak for name, bed in run.beds.items()
              if peak > 0}
    conclusion = (f"Peak θ of each bed ÷ the continuum's ({peak:.3g} rad): "
                  f"{_ratio_text(ratios)}.")
    shown = (f"{result.scene.name} under {run.label}: rotation θ, story deformation u, edge "
             "uplift and settlement of the footing's centre from rest against time, continuum "
             "(black) and the Winkler beds.")
    return fig, Caption(f"Do the beds follow the continuum in time? {run.label}", shown,
                        conclusion)


def _monotonic_figure(result: WinklerVsContinuum):
    ref = result.reference
    NB, B = ref.N * ref.B, ref.B
    t = np.asarray(ref.monotonic["theta"]) / ref.theta_on
    with print_style():
        fig, axes = page_figure(7.4, 3, 1, sharex=True)
        for key, ax, scale in (("M", axes[0], NB), ("contact", axes[1], B),
                               ("settlement", axes[2], 1.0)):
            ax.plot(t, np.asarray(ref.monotonic[key]) / scale, "ko-", ms=3,
                    label="continuum (scene soil)")
            if key != "settlement":
                ax.plot(t, np.asarray(ref.elastic[key]) / scale, "k:",
                        label="continuum (elastic)")
            for bed in result.beds:
                name = bed.calibration.name
                ax.plot(t, np.asarray(bed.monotonic[key]) / scale, _STYLES[name],
                        color=_COLORS[name], label=bed.calibration.label)
        fine = np.linspace(0.0, t.max(), 400) * ref.theta_on
        hp = half_plane_rocking(fine, ref.N, B, ref.G, ref.nu)
        uni = result.bed("uniform")
        wk = winkler_rocking(fine, ref.N, B, uni.K_v / B)
        axes[0].plot(fine / ref.theta_on, hp["M"] / NB, "--", color="#009E73", lw=1,
                     label="half-plane closed form")
        axes[0].plot(fine / ref.theta_on, wk["M"] / NB, "--", color="#CC79A7", lw=1,
                     label="Winkler closed form (anchor §3)")
        axes[0].set_ylabel("M / (N B) (–)")
        axes[1].set_ylabel("contact c / B (–)")
        axes[2].set_ylabel(f"settlement ({result.scene.units.length})")
        axes[2].set_xlabel("θ / θ_on (–)")
        for ax in axes:
            ax.set_xscale("symlog", linthresh=1.0)
            ax.grid(True, alpha=0.3)
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    last = float(np.asarray(ref.monotonic["M"])[-1])
    ratios = {bed.calibration.name: float(np.asarray(bed.monotonic["M"])[-1]) / last
              for bed in result.beds} if last else {}
    conclusion = (f"At θ = {t[-1]:.3g} θ_on each bed's moment ÷ the continuum's: "
                  f"{_ratio_text(ratios)}.")
    shown = (f"{result.scene.name}: monotonic rocking at constant N = {ref.N:g}: moment "
             "M/(N B), contact length c/B and settlement against θ/θ_on (symmetric-log axis), "
             "continuum against the calibrated Winkler beds and two closed forms.")
    return fig, Caption("How far do the beds follow the continuum's backbone?", shown,
                        conclusion)


def _cyclic_figure(result: WinklerVsContinuum):
    ref = result.reference
    NB = ref.N * ref.B
    t = np.asarray(ref.cyclic["theta"]) / ref.theta_on
    with print_style():
        fig, (ax, bx) = page_figure(3.8, 1, 2)
        ax.plot(t, np.asarray(ref.cyclic["M"]) / NB, "ko-", ms=3, label="continuum")
        bx.plot(np.asarray(ref.cyclic["settlement"]), "ko-", ms=3, label="continuum")
        for bed in result.beds:
            name = bed.calibration.name
            c, ls = _COLORS[name], _STYLES[name]
            ax.plot(t, np.asarray(bed.cyclic["M"]) / NB, ls, color=c, label=bed.calibration.label)
            bx.plot(np.asarray(bed.cyclic["settlement"]), ls, color=c)
        ax.set_xlabel("θ / θ_on (–)")
        ax.set_ylabel("M / (N B) (–)")
        bx.set_xlabel("step of the cyclic path")
        bx.set_ylabel(f"settlement ({result.scene.units.length})")
        for a in (ax, bx):
            a.grid(True, alpha=0.3)
        fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    final = float(np.asarray(ref.cyclic["settlement"])[-1])
    beds = {bed.calibration.name: float(np.asarray(bed.cyclic["settlement"])[-1])
            for bed in result.beds}
    unit = result.scene.units.length
    conclusion = (f"After the cycles the continuum has settled {final:.3g} {unit}; the beds "
                  + "; ".join(f"{LABELS[k]} {v:.3g} {unit}" for k, v in beds.items()) + ".")
    shown = ("Cyclic rocking: moment M/(N B) against θ/θ_on (left) and the settlement at each "
             "step of the path (right), continuum against the beds.")
    return fig, Caption("Do the beds accumulate the continuum's settlement?", shown,
                        conclusion)


def _cell_text(value: float) -> str:
    return f"{value:+.0f}" if abs(value) >= 9.95 else f"{value:+.1f}"


def _error_figure(table: ErrorTable):
    from matplotlib.colors import LogNorm

    percent = np.clip(100.0 * np.abs(table.errors.T), 0.01, 1000.0)  # (quantity, calibration)
    nq, nc = percent.shape
    with print_style():
        fig, ax = page_figure(min(MAX_HEIGHT_IN, 1.6 + 0.25 * nq))
        image = ax.pcolormesh(np.arange(nc + 1) - 0.5, np.arange(nq + 1) - 0.5,
                              np.ma.masked_invalid(percent), norm=LogNorm(0.01, 1000.0),
                              cmap="viridis")
        ax.set_facecolor("0.85")
        for i, j in zip(*np.nonzero(np.isfinite(table.errors.T))):
            ax.text(j, i, _cell_text(100 * table.errors[j, i]), ha="center", va="center",
                    color="white" if percent[i, j] < 10 else "black")
        ax.set_xticks(range(nc), [c.replace("end_stiffened", "end-stiffened")
                                  .replace("_plastic", ",\nplastic") for c in table.calibrations])
        ax.set_yticks(range(nq), table.labels)
        ax.set_ylim(nq - 0.5, -0.5)
        fig.colorbar(image, ax=ax, label="|error| (%)")
    within = {c: float(np.nanmean(np.abs(table.errors[k]) <= 0.10)
                       if np.isfinite(table.errors[k]).any() else np.nan)
              for k, c in enumerate(table.calibrations)}
    best = max(within, key=lambda c: within[c] if np.isfinite(within[c]) else -1)
    counts = {c: int(np.sum(np.abs(table.errors[k]) <= 0.10))
              for k, c in enumerate(table.calibrations)}
    finite = {c: int(np.isfinite(table.errors[k]).sum()) for k, c in
              enumerate(table.calibrations)}
    conclusion = ("Within 10 % of the continuum: "
                  + "; ".join(f"{LABELS[c]} {counts[c]} of {finite[c]}" for c in counts)
                  + f" quantities; the closest overall is the {LABELS[best]}.")
    shown = ("Signed error (bed − continuum)/continuum (%) of each Winkler calibration "
             "(columns: uniform, end-stiffened, and both with elasto-plastic springs) in each "
             "quantity (rows); colour: |error| on a log scale; grey: not defined (elastic "
             "springs have no capacity).")
    return fig, Caption("Which calibration matches the continuum in which quantity?", shown,
                        conclusion)
