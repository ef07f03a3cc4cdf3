"""The study's figures: monotonic and cyclic paths, errors and dynamic histories."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...anchors import half_plane_rocking, winkler_rocking
from ..study import write_figure
from .analysis import ErrorTable
from .dynamics import DynamicRun
from .options import LABELS
from .result import WinklerVsContinuum


_COLORS = {"uniform": "tab:red", "end_stiffened": "tab:blue", "uniform_plastic": "tab:orange",
           "end_stiffened_plastic": "tab:cyan"}


def write_figures(result: WinklerVsContinuum, directory: Path) -> list[Path]:
    files = [_monotonic_figure(result, directory / "monotonic.png"),
             _cyclic_figure(result, directory / "cyclic.png"),
             _error_figure(result.table, directory / "errors.png")]
    for run in result.dynamics.runs:
        files.append(_dynamic_figure(result, run, directory / f"dynamic_{run.key}.png"))
    return files


def _dynamic_figure(result: WinklerVsContinuum, run: DynamicRun, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    length = result.scene.units.length
    fig, axes = plt.subplots(4, 1, figsize=(10, 10), sharex=True, constrained_layout=True)
    panels = (("theta", "θ [rad]"), ("u", f"u [{length}]"), ("uplift", f"edge uplift [{length}]"),
              ("settlement", f"settlement from rest [{length}]"))
    for ax, (key, label) in zip(axes, panels):
        ax.plot(run.time, run.continuum[key], "k-", lw=1.5, label="continuum")
        for name, bed in run.beds.items():
            ax.plot(run.time, bed[key], "-", lw=0.9, color=_COLORS[name], label=LABELS[name])
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[0].set_title(f"{result.scene.name}: {run.label}")
    axes[-1].set_xlabel("time [s]")
    return write_figure(path, fig)


def _monotonic_figure(result: WinklerVsContinuum, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ref = result.reference
    NB, B = ref.N * ref.B, ref.B
    fig, axes = plt.subplots(3, 1, figsize=(8, 10), sharex=True, constrained_layout=True)
    t = np.asarray(ref.monotonic["theta"]) / ref.theta_on
    for key, ax, scale in (("M", axes[0], NB), ("contact", axes[1], B),
                           ("settlement", axes[2], 1.0)):
        ax.plot(t, np.asarray(ref.monotonic[key]) / scale, "ko-", ms=3,
                label="continuum (scene soil)")
        if key != "settlement":
            ax.plot(t, np.asarray(ref.elastic[key]) / scale, "k:", label="continuum (elastic)")
        for bed in result.beds:
            ax.plot(t, np.asarray(bed.monotonic[key]) / scale, "-",
                    color=_COLORS[bed.calibration.name], label=bed.calibration.label)
    fine = np.linspace(0.0, t.max(), 400) * ref.theta_on
    hp = half_plane_rocking(fine, ref.N, B, ref.G, ref.nu)
    uni = result.bed("uniform")
    wk = winkler_rocking(fine, ref.N, B, uni.K_v / B)
    axes[0].plot(fine / ref.theta_on, hp["M"] / NB, "g--", lw=1, label="half-plane closed form")
    axes[0].plot(fine / ref.theta_on, wk["M"] / NB, "m--", lw=1,
                 label="Winkler closed form (anchor §3)")
    axes[0].set_ylabel("M / (N B)")
    axes[1].set_ylabel("contact length c / B")
    axes[2].set_ylabel(f"settlement [{result.scene.units.length}]")
    axes[2].set_xlabel("θ / θ_on")
    axes[0].set_title(f"{result.scene.name}: monotonic rocking at N = {ref.N:g}")
    for ax in axes:
        ax.set_xscale("symlog", linthresh=1.0)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    return write_figure(path, fig)


def _cyclic_figure(result: WinklerVsContinuum, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ref = result.reference
    NB = ref.N * ref.B
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
    t = np.asarray(ref.cyclic["theta"]) / ref.theta_on
    ax.plot(t, np.asarray(ref.cyclic["M"]) / NB, "ko-", ms=3, label="continuum")
    bx.plot(np.asarray(ref.cyclic["settlement"]), "ko-", ms=3, label="continuum")
    for bed in result.beds:
        c = _COLORS[bed.calibration.name]
        ax.plot(t, np.asarray(bed.cyclic["M"]) / NB, "-", color=c, label=bed.calibration.label)
        bx.plot(np.asarray(bed.cyclic["settlement"]), "-", color=c, label=bed.calibration.label)
    ax.set_xlabel("θ / θ_on")
    ax.set_ylabel("M / (N B)")
    bx.set_xlabel("step of the cyclic path")
    bx.set_ylabel(f"settlement [{result.scene.units.length}]")
    for a in (ax, bx):
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    return write_figure(path, fig)


def _error_figure(table: ErrorTable, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    percent = np.clip(100.0 * np.abs(table.errors), 0.01, 1000.0)
    fig, ax = plt.subplots(figsize=(1.0 + 0.45 * len(table.quantities), 3.2),
                           constrained_layout=True)
    image = ax.imshow(percent, norm=LogNorm(0.01, 1000.0), cmap="viridis", aspect="auto")
    for i, j in zip(*np.nonzero(np.isfinite(table.errors))):
        ax.text(j, i, f"{100 * table.errors[i, j]:+.2g}", ha="center", va="center", fontsize=5,
                color="white" if percent[i, j] < 10 else "black")
    ax.set_xticks(range(len(table.quantities)), table.labels, rotation=90, fontsize=6)
    ax.set_yticks(range(len(table.calibrations)), table.calibrations, fontsize=7)
    fig.colorbar(image, ax=ax, label="|error| (%)")
    ax.set_title("Winkler beds against the continuum: (bed − continuum)/continuum (%)",
                 fontsize=8)
    return write_figure(path, fig)
