"""Figures of reduced-model responses (matplotlib, the ``plot`` extra).

Figures are artefacts to look at; tests compare numbers. Every axis is labelled with its unit.
"""

from __future__ import annotations

from pathlib import Path

from ..checks import InputError
from ..results import atomic_path

__all__ = ["pyplot", "response_figure", "comparison_figure", "save"]


def pyplot():
    """matplotlib.pyplot with a file-only backend, or a clear error naming the extra."""
    try:
        import matplotlib
    except ImportError:
        raise InputError("figures need matplotlib: pip install 'upliftlab[plot]'") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, path: str | Path) -> Path:
    """Write a figure atomically (PNG, 150 dpi) and close it."""
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=150, format=path.suffix.lstrip(".") or "png")
    pyplot().close(fig)
    return path


def response_figure(response, title: str | None = None):
    """Four panels of one run: u, θ, the leftmost spring's displacement, contact length."""
    plt = pyplot()
    u = response.model.scene.units
    fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True)
    t = response.time
    axes[0].plot(t, response.u, lw=0.8)
    axes[0].set_ylabel(f"u [{u.length}]")
    axes[1].plot(t, response.theta * 1e3, lw=0.8)
    axes[1].set_ylabel("θ [mrad]")
    if response.model.layout is not None:
        axes[2].plot(t, response.left_spring_displacement, lw=0.8)
        axes[2].axhline(0.0, color="0.6", lw=0.5)
        axes[3].plot(t, response.contact_length, lw=0.8)
    axes[2].set_ylabel(f"left spring [{u.length}]\n(+ compression)")
    axes[3].set_ylabel(f"contact [{u.length}]")
    axes[3].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, lw=0.3)
    fig.suptitle(title or response.model.scene.title, fontsize=10)
    fig.tight_layout()
    return fig


def comparison_figure(panels, title: str, beside=None):
    """Stacked panels, each ``(ylabel, [(label, t, y), ...])``, sharing the time axis; with
    ``beside`` (panels of the same form, as many) a second column of them."""
    plt = pyplot()
    columns = [panels] if beside is None else [panels, beside]
    fig, axes = plt.subplots(len(panels), len(columns), figsize=(8 * len(columns),
                             3.0 * len(panels)), sharex=True, squeeze=False)
    for col, column in enumerate(columns):
        for ax, (ylabel, curves) in zip(axes[:, col], column):
            for label, t, y in curves:
                ax.plot(t, y, lw=0.8, label=label)
            ax.axhline(0.0, color="0.6", lw=0.5)
            ax.set_ylabel(ylabel)
            ax.grid(True, lw=0.3)
            ax.legend(fontsize=8, loc="upper right")
        axes[-1, col].set_xlabel("time [s]")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig

