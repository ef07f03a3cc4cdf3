"""The study's figures: backbones, convergence and the error maps, each at page width with a
caption whose conclusion is computed from the plotted numbers (:mod:`..figure_record`).

Error maps: for each map and case one figure asks where each layout stays within 10 % and 20 %
of the bed over all six measures (the largest of the six per cell); the all-measures grid of
the same map is a second, dense figure the report keeps behind an expandable section."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...framework.figure_record import Caption, page_figure, print_style, save
from ...framework.map_figures import (dense_maps, layout_maps, rows_per_figure, share_within,
                                      worst_cell)
from . import statics as st
from .grid import METRICS, METRIC_LABELS
from .views import STATICS, cases, convergence, error, heading, layouts, map_axes, maps, \
    study_attrs


def write_figures(tree, directory: Path) -> list[Path]:
    """Every figure of the study's data ``tree`` (records, SVG and PNG) into ``directory``;
    the files."""
    conv, threshold = convergence(tree), float(study_attrs(tree)["threshold"])
    files = save(directory / "backbones.png", *_backbone_figure(tree[STATICS].to_dataset()))
    files += save(directory / "convergence.png", *_convergence_figure(conv))
    levels = tuple(sorted({0.10, 0.20, threshold}))
    for ds in maps(tree):
        y = map_axes(ds)[1]
        for case in cases(ds):
            slug = f"{ds.attrs['name']}_{case.replace('/', '')}"
            files += save(directory / f"{slug}_all.png",
                          *_map_figure(ds, conv["springs"], threshold, case, levels))
            pages = -(-len(METRICS) // rows_per_figure(y))
            per = -(-len(METRICS) // pages)  # as many rows in each figure as can be
            for k in range(0, len(METRICS), per):
                name = f"{slug}.png" if k == 0 else f"{slug}_{k // per + 1}.png"
                files += save(directory / name, *_dense_figure(
                    ds, conv["springs"], threshold, case, levels, METRICS[k:k + per]))
    return files


def _pct(value: float) -> str:
    return "—" if not np.isfinite(value) else f"{100 * value:.0f} %"


def _map_figure(ds, springs: int, threshold: float, case: str, levels):
    (x, y), title = map_axes(ds), heading(ds)
    panels = [(layout, error(ds, case, layout)) for layout in layouts(ds)]
    with print_style():
        fig = layout_maps(x, y, panels, levels)
    shares = {layout: share_within(e, threshold) for layout, e in panels}
    best = max(shares, key=lambda k: -1 if not np.isfinite(shares[k]) else shares[k])
    worst = [(worst_cell(e, x, y), layout) for layout, e in panels]
    (value, where), layout = max(worst, key=lambda w: -1 if not np.isfinite(w[0][0])
                                 else w[0][0])
    others = ", ".join(f"{k} {_pct(v)}" for k, v in shares.items() if k != best)
    conclusion = (f"Case {case}'s {best} springs stay within {100 * threshold:g} % of the bed "
                  f"in all six measures over {_pct(shares[best])} of the map ({others}); "
                  f"the largest error is {_pct(value)} ({layout}, {where}).")
    shown = (f"|two-spring − bed| / bed (%), the largest of the six measures (peak u, θ, edge "
             f"gap, plastic settlement, base shear, dissipated energy) per cell, for each layout "
             f"against the {ds.attrs['bed'].replace('_', '-')} Winkler bed of N = {springs} "
             f"springs: {title}, Case {case}. Contours at "
             f"{', '.join(f'{100 * v:g}' for v in levels)} %; grey: a failed run.")
    return fig, Caption(f"Where do two springs replace the bed? {title}, Case {case}",
                        shown, conclusion)


def _dense_figure(ds, springs: int, threshold: float, case: str, levels, metrics):
    (x, y), title, columns = map_axes(ds), heading(ds), layouts(ds)
    rows = [(METRIC_LABELS[m], [error(ds, case, layout, m) for layout in columns])
            for m in metrics]
    with print_style():
        fig = dense_maps(x, y, columns, rows, levels)
    shares = {m: np.nanmean([share_within(error(ds, case, layout, m), threshold)
                             for layout in columns]) for m in metrics}
    hardest = min(shares, key=lambda m: shares[m] if np.isfinite(shares[m]) else 2.0)
    others = ", ".join(f"{METRIC_LABELS[m]} {_pct(v)}" for m, v in shares.items()
                       if m != hardest)
    conclusion = (f"Of these measures the hardest to match is {METRIC_LABELS[hardest]}: within "
                  f"{100 * threshold:g} % over {_pct(shares[hardest])} of the map on average "
                  f"over the layouts ({others or 'the only one shown'}).")
    shown = (f"{', '.join(METRIC_LABELS[m] for m in metrics)} (rows) for every layout "
             f"(columns): |two-spring − bed| / bed (%), {title}, Case {case}, "
             f"N = {springs}.")
    return fig, Caption(f"Each measure on its own: {title}, Case {case}", shown,
                        conclusion, dense=True)


def _backbone_figure(statics):
    t = statics.theta_over_theta_up.values
    closed = np.where(t <= 1.0, t / 6.0, (3.0 - 2.0 * np.sqrt(1.0 / np.maximum(t, 1.0))) / 6.0)
    with print_style():
        fig, axes = page_figure(3.4, 1, 2, sharey=True)
        for ax, which in zip(axes, ("elastic", "plastic")):
            for label in (str(v) for v in statics.foundation.values):
                ax.semilogx(t, statics[which].sel(foundation=label).values, label=label)
            if which == "elastic":
                ax.semilogx(t, closed, "k:", label="closed form (anchor §3)")
            else:
                fs = float(statics.attrs["yield_multiple"])
                ax.axhline(0.5 * (1 - 1 / fs), color="k", ls=":",
                           label=f"M_ult, FS_v = {fs:g}")
            ax.set_xlabel("θ / θ_up (–)")
            ax.set_title(f"{which} springs, N = {int(statics.attrs['springs'])}")
            ax.grid(True, which="both", alpha=0.3)
        axes[0].set_ylabel("M / (N B) (–)")
        handles, labels = axes[0].get_legend_handles_labels()
        extra = axes[1].get_legend_handles_labels()
        handles.append(extra[0][-1])
        labels.append(extra[1][-1])
        fig.legend(handles, labels, loc="outside lower center", ncols=3, frameon=False)
    equivalent = st.within(statics, "equivalent", 0.10)
    conclusion = (f"The equivalent springs start to uplift at {st.onset_ratio(statics):.2f} × "
                  f"the bed's onset moment and end at {st.capacity_ratio(statics):.2f} × its "
                  "capacity; "
                  f"their elastic backbone stays within 10 % of the bed up to θ = "
                  f"{equivalent:.3g} θ_up.")
    shown = ("Static moment–rotation backbones M/(N B) against θ/θ_up (θ_up = N/(K_v b)) of "
             "the uniform bed and the two-spring layouts; left elastic springs, right "
             "elasto-plastic springs.")
    return fig, Caption("Do two springs carry the bed's moment?", shown, conclusion)


def _convergence_figure(conv: dict):
    """``conv``: the convergence check as :func:`.views.convergence` reads it."""
    import matplotlib.ticker

    shown_cases = list(conv["dynamic"])
    n = np.array(conv["candidates"])
    with print_style():
        fig, axes = page_figure(3.2, 1, len(shown_cases) + 1, sharey=True)
        for key, values in conv["static"].items():
            v = np.array(values)
            axes[0].semilogx(n, v / v[-1], "s--", label=key)
        axes[0].set_title("statics")
        for ax, case in zip(axes[1:], shown_cases):
            for m, values in conv["dynamic"][case].items():
                v = np.array(values, dtype=float)
                ax.semilogx(n, v / v[-1] if v[-1] else v, "o-", label=METRIC_LABELS[m])
            ax.set_title(f"Case {case}")
        axes[0].set_ylabel("value / value at largest N (–)")
        for ax in axes:
            ax.axvline(conv["springs"], color="k", ls=":")
            ax.set_xlabel("N springs")
            ax.set_xticks(n, [str(k) for k in conv["candidates"]], rotation=90)
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.grid(True, which="both", alpha=0.3)
        handles, labels = axes[0].get_legend_handles_labels()
        if len(axes) > 1:
            more = axes[1].get_legend_handles_labels()
            handles, labels = handles + more[0], labels + more[1]
        fig.legend(handles, labels, loc="outside lower center", ncols=3, frameon=False)
    verdict = ("converged" if conv["converged"] else
               "not converged: N is the largest candidate")
    last = "; ".join(f"{'statics' if k == 'static' else 'Case ' + k} {100 * v[-1]:.2g} %"
                     for k, v in conv["changes"].items() if len(v))
    n_list, springs = conv["candidates"], conv["springs"]
    conclusion = (f"The study uses N = {springs} springs ({verdict}: from N on, every "
                  f"doubling changes the static measures by at most "
                  f"{100 * conv['static_tolerance']:g} % and Cases A and B by at most "
                  f"{100 * conv['tolerance']:g} %). Largest change over the last doubling, "
                  f"{n_list[-2] if len(n_list) > 1 else springs} to "
                  f"{n_list[-1]}: {last}.")
    shown = (f"Measures of the uniform Winkler bed against its number of springs N, each "
             f"divided by its value at the largest N; dynamics under {conv['motion']}. The "
             "dotted line marks the N the study uses.")
    return fig, Caption("How many springs does the bed need?", shown, conclusion)
