"""The study's figures: monotonic and cyclic paths, errors and dynamic histories, each at page
width with a caption whose conclusion is computed from the plotted numbers
(:mod:`..figure_record`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....anchors import half_plane_rocking, winkler_rocking
from ....units import unit_system
from ...beds.stiffness import LABELS
from ...framework.figure_record import Caption, page_figure, print_style, save
from ...framework.map_figures import MAX_HEIGHT_IN
from .analysis import ErrorTable, table_of
from .dataset import PATH_MODELS, comparison, dynamic_runs


# colour-blind-safe (Okabe–Ito) and told apart by line style as well
_COLORS = {"uniform": "#D55E00", "end_stiffened": "#0072B2", "uniform_plastic": "#E69F00",
           "end_stiffened_plastic": "#56B4E9"}
_STYLES = {"uniform": "-", "end_stiffened": "--", "uniform_plastic": "-.",
           "end_stiffened_plastic": ":"}


def write_figures(data, directory: Path) -> list[Path]:
    """Every figure of the study's tree ``data`` (records, SVG and PNG) into ``directory``;
    the files."""
    ds = comparison(data)
    files = save(directory / "monotonic.png", *_monotonic_figure(ds))
    files += save(directory / "cyclic.png", *_cyclic_figure(ds))
    files += save(directory / "errors.png", *_error_figure(table_of(ds)))
    for run in dynamic_runs(data):
        files += save(directory / f"dynamic_{run.attrs['motion']}.png",
                      *_dynamic_figure(ds, run))
    return files


def _beds(ds) -> list[str]:
    """The beds among the paths' models."""
    return [str(m) for m in ds.model.values if m not in PATH_MODELS]


def _length(ds) -> str:
    return unit_system(str(ds.attrs["units"])).length


def _ratio_text(ratios: dict) -> str:
    return "; ".join(f"{LABELS[k]} {v:.2f}" for k, v in ratios.items())


def _dynamic_figure(ds, run):
    length, label = _length(ds), run.attrs["label"]
    beds = [str(m) for m in run.model.values[1:]]
    panels = (("theta", "θ (rad)"), ("u", f"u ({length})"), ("uplift", f"edge uplift ({length})"),
              ("settlement", f"settlement ({length})"))
    with print_style():
        fig, axes = page_figure(7.6, 4, 1, sharex=True)
        for ax, (key, ylabel) in zip(axes, panels):
            ax.plot(run.time, run[key].sel(model="continuum"), "k-", lw=1.6, label="continuum")
            for name in beds:
                ax.plot(run.time, run[key].sel(model=name), _STYLES[name], lw=1.0,
                        color=_COLORS[name], label=LABELS[name])
            ax.set_ylabel(ylabel)
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time (s)")
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    peak = float(np.max(np.abs(run.theta.sel(model="continuum").values)))
    ratios = {name: float(np.max(np.abs(run.theta.sel(model=name).values))) / peak
              for name in beds if peak > 0}
    conclusion = (f"Peak θ of each bed ÷ the continuum's ({peak:.3g} rad): "
                  f"{_ratio_text(ratios)}.")
    shown = (f"{ds.attrs['scene']} under {label}: rotation θ, story deformation u, edge "
             "uplift and settlement of the footing's centre from rest against time, continuum "
             "(black) and the Winkler beds.")
    return fig, Caption(f"Do the beds follow the continuum in time? {label}", shown,
                        conclusion)


def _monotonic_figure(ds):
    N, B, G, nu, theta_on = (ds[k].item() for k in ("N", "B", "G", "nu", "theta_on"))
    NB = N * B
    t = ds.monotonic_theta.values / theta_on
    with print_style():
        fig, axes = page_figure(7.4, 3, 1, sharex=True)
        for key, ax, scale in (("M", axes[0], NB), ("contact", axes[1], B),
                               ("settlement", axes[2], 1.0)):
            path = ds[f"{key}_monotonic"]
            ax.plot(t, path.sel(model="continuum").values / scale, "ko-", ms=3,
                    label="continuum (scene soil)")
            if key != "settlement":
                ax.plot(t, path.sel(model="continuum_elastic").values / scale, "k:",
                        label="continuum (elastic)")
            for name in _beds(ds):
                ax.plot(t, path.sel(model=name).values / scale, _STYLES[name],
                        color=_COLORS[name], label=LABELS[name])
        fine = np.linspace(0.0, t.max(), 400) * theta_on
        hp = half_plane_rocking(fine, N, B, G, nu)
        wk = winkler_rocking(fine, N, B, ds.value_K_v.sel(calibration="uniform").item() / B)
        axes[0].plot(fine / theta_on, hp["M"] / NB, "--", color="#009E73", lw=1,
                     label="half-plane closed form")
        axes[0].plot(fine / theta_on, wk["M"] / NB, "--", color="#CC79A7", lw=1,
                     label="Winkler closed form (anchor §3)")
        axes[0].set_ylabel("M / (N B) (–)")
        axes[1].set_ylabel("contact c / B (–)")
        axes[2].set_ylabel(f"settlement ({_length(ds)})")
        axes[2].set_xlabel("θ / θ_on (–)")
        for ax in axes:
            ax.set_xscale("symlog", linthresh=1.0)
            ax.grid(True, alpha=0.3)
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    M = ds.M_monotonic
    last = float(M.sel(model="continuum").values[-1])
    ratios = {name: float(M.sel(model=name).values[-1]) / last
              for name in _beds(ds)} if last else {}
    conclusion = (f"At θ = {t[-1]:.3g} θ_on each bed's moment ÷ the continuum's: "
                  f"{_ratio_text(ratios)}.")
    shown = (f"{ds.attrs['scene']}: monotonic rocking at constant N = {N:g}: moment "
             "M/(N B), contact length c/B and settlement against θ/θ_on (symmetric-log axis), "
             "continuum against the calibrated Winkler beds and two closed forms.")
    return fig, Caption("How far do the beds follow the continuum's backbone?", shown,
                        conclusion)


def _cyclic_figure(ds):
    NB = ds.N.item() * ds.B.item()
    t = ds.cyclic_theta.values / ds.theta_on.item()
    M, settlement = ds.M_cyclic, ds.settlement_cyclic
    with print_style():
        fig, (ax, bx) = page_figure(3.8, 1, 2)
        ax.plot(t, M.sel(model="continuum").values / NB, "ko-", ms=3, label="continuum")
        bx.plot(settlement.sel(model="continuum").values, "ko-", ms=3, label="continuum")
        for name in _beds(ds):
            c, ls = _COLORS[name], _STYLES[name]
            ax.plot(t, M.sel(model=name).values / NB, ls, color=c, label=LABELS[name])
            bx.plot(settlement.sel(model=name).values, ls, color=c)
        ax.set_xlabel("θ / θ_on (–)")
        ax.set_ylabel("M / (N B) (–)")
        bx.set_xlabel("step of the cyclic path")
        bx.set_ylabel(f"settlement ({_length(ds)})")
        for a in (ax, bx):
            a.grid(True, alpha=0.3)
        fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    final = float(settlement.sel(model="continuum").values[-1])
    beds = {name: float(settlement.sel(model=name).values[-1]) for name in _beds(ds)}
    unit = _length(ds)
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
