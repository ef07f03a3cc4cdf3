"""A continuum result (:class:`~upliftlab.continuum.dynamics.result.DynamicResult` or
:class:`~upliftlab.continuum.statics.results.StaticPath`) in a notebook: its ``plot()`` and
``render()`` (matplotlib figures, nothing written) and its ``_repr_html_`` (a compact table).

**Panels** (``variables``), every axis labelled with its unit: against time (s; a static
path's load step): ``theta`` the footing's rotation, ``settlement`` −v, ``uplift`` the largest
gap under the base, ``contact`` the contact length, ``N`` and ``M``; and ``moment_rotation``
M against θ, ``load_settlement`` N against −v. Default: θ, settlement, uplift and M–θ for a
dynamic run; M–θ, uplift and settlement for a rotation or moment pushover; N against −v and
the contact for a vertical pushover.

**The soil picture** (:func:`render_result`): the deformed soil near the footing coloured by
plastic strain, the footing, and the contact pressure and gap along the base, at one snapshot
(:func:`~upliftlab.meshes.render.uplift_figure`, the picture a run writes as ``uplift.png``). It
needs the model the result was computed on (its mesh: a result keeps the fields, not the mesh).
"""

from __future__ import annotations

import numpy as np

from ...checks import InputError
from ...meshes.frames import snapshot_rows, units_of
from ...notebook import (check_variables, digest_line, html_table, new_figure, number,
                         panel_axes)

__all__ = ["PANELS", "panel_data", "result_plot", "result_html", "render_result",
           "figure_title"]

PANELS = ("theta", "settlement", "uplift", "contact", "N", "M", "moment_rotation",
          "load_settlement")


def _static(result) -> bool:
    return getattr(result, "kind", "dynamic") != "dynamic"


def _default(result) -> tuple[str, ...]:
    if not _static(result):
        return ("theta", "settlement", "uplift", "moment_rotation")
    if str(result.kind).endswith(("rotation_pushover", "moment_pushover")):
        return ("moment_rotation", "uplift", "settlement")
    return ("load_settlement", "contact")


def _unit(text: str) -> str:
    text = text.replace("^2", "²").replace("*", "·")
    return f" [{text}]" if text else ""


def panel_data(result, name: str) -> tuple[np.ndarray, np.ndarray, str, str]:
    """(x, y, x label, y label) of panel ``name`` (module docstring)."""
    units = units_of(result.metadata)
    length, force, moment = units["length_unit"], units["force_unit"], units["moment_unit"]
    footing = np.asarray(result.footing)
    time = np.asarray(result.time)
    xlabel = "load step" if _static(result) else "time [s]"
    if name == "theta":
        return time, footing[:, 2], xlabel, "θ [rad]"
    if name == "settlement":
        return time, -footing[:, 1], xlabel, f"settlement −v{_unit(length)}"
    if name == "uplift":
        gap = np.asarray(result.gap)
        y = gap.max(axis=1) if gap.shape[1] else np.zeros(time.size)
        return time, y, xlabel, f"largest gap{_unit(length)}"
    if name == "contact":
        return time, np.asarray(result.contact_length), xlabel, f"contact length{_unit(length)}"
    if name in ("N", "M"):
        unit = force if name == "N" else moment
        return time, np.asarray(getattr(result, name)), xlabel, f"{name}{_unit(unit)}"
    if name == "moment_rotation":
        return footing[:, 2], np.asarray(result.M), "θ [rad]", f"M{_unit(moment)}"
    return -footing[:, 1], np.asarray(result.N), f"settlement −v{_unit(length)}", \
        f"N{_unit(force)}"


def result_plot(result, variables=None, ax=None):
    """The figure of ``result``'s panels ``variables`` (module docstring), on new axes or on
    ``ax`` (one matplotlib axis per variable)."""
    chosen = check_variables(variables, PANELS, _default(result))
    fig, axes = panel_axes(ax, len(chosen))
    static = _static(result)
    for axis, name in zip(axes, chosen):
        x, y, xlabel, ylabel = panel_data(result, name)
        axis.plot(x, y, "o-" if static else "-", lw=0.9, ms=3, label=name)
        axis.set_xlabel(xlabel)
        axis.set_ylabel(ylabel)
        axis.grid(True, lw=0.3)
    if ax is None:
        meta = result.metadata
        fig.suptitle(f"{meta.get('scene', '')} (continuum, "
                     f"{meta.get('method', result.kind)})", fontsize=10)
    return fig


def result_html(result) -> str:
    """The HTML table of ``result``: kind, scene, span, the peaks with their units (θ,
    settlement, gap, least contact, N, M), the energy balance of a dynamic run, whether it is
    incomplete, and the code's digest."""
    meta = result.metadata
    units = {k: v.replace("^2", "²").replace("*", "·") for k, v in units_of(meta).items()}
    length = units["length_unit"]
    footing = np.asarray(result.footing)
    gap = np.asarray(result.gap)
    if _static(result):
        kind, span = f"continuum {result.kind}", f"{footing.shape[0]} load steps"
    else:
        kind = f"continuum dynamic ({meta.get('method', '?')})"
        span = f"{result.time.size} rows over {float(result.time[-1]):.4g} s"
    rows = [("kind", kind), ("scene", meta.get("scene", "")), ("span", span),
            ("peak |θ|", number(np.max(np.abs(footing[:, 2])), "rad")),
            ("peak settlement −v", number(np.max(-footing[:, 1]), length)),
            ("final settlement −v", number(-footing[-1, 1], length)),
            ("peak gap", number(np.max(gap, initial=0.0), length)),
            ("least contact length", number(np.min(result.contact_length), length)),
            ("peak N", number(np.max(result.N), units["force_unit"])),
            ("peak |M|", number(np.max(np.abs(result.M)), units["moment_unit"]))]
    if not _static(result):
        rows.append(("energy balance error", number(result.energy_balance_error, digits=3)))
    if meta.get("incomplete"):
        rows.append(("INCOMPLETE", f"until t = {number(meta.get('completed_until'), 's')}"))
    rows += [("snapshots", str(np.size(result.snapshot_time))),
             ("B", number(result.width, length)), ("provenance", digest_line(meta))]
    return html_table(f"{type(result).__name__}: {meta.get('scene', '')}", rows)


def render_result(result, model, snapshot: int | None = None, *, scale: float | None = None,
                  title: str | None = None):
    """The figure of the soil picture (module docstring) of ``result`` computed on ``model``
    at snapshot index ``snapshot`` (default: the one of largest |θ|, as ``uplift.png``);
    ``scale`` magnifies the displacements (default: chosen from the largest); ``title``
    (default: the scene, and why a run that did not finish stopped)."""
    from ...meshes.render import uplift_figure
    from .field_history import check_history

    check_history(result, model)
    if snapshot is None:
        rows = snapshot_rows(result)
        snapshot = int(np.argmax(np.abs(np.asarray(result.footing)[rows, 2])))
    elif isinstance(snapshot, bool) or not isinstance(snapshot, (int, np.integer)):
        raise InputError(f"snapshot = {snapshot!r}: an index of the result's snapshots")
    return uplift_figure(result, model.disc.basis, model.width, snapshot=int(snapshot),
                         scale=scale, title=figure_title(result) if title is None else title,
                         make=lambda width, height, dpi: new_figure(width, height, dpi=dpi,
                                                                    layout=None))


def figure_title(result, scene=None) -> str:
    """The title of a run's figures: the scene, and for a run that did not finish, why and
    when it stopped (a bearing failure, or an interruption), so that a picture of a failed
    run is never taken for a finished one."""
    meta = result.metadata
    title = meta.get("scene", "") or (scene.name if scene else "")
    if meta.get("failure") == "bearing":
        title += f" (failed in bearing at t = {float(meta['failure_time']):.4g} s)"
    elif meta.get("incomplete"):
        title += f" (incomplete: until t = {float(meta['completed_until']):.4g} s)"
    return title
