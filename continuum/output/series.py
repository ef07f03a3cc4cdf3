"""Outputs of continuum analyses: the XDMF time series for ParaView (the soil fields and the
contact along the footing's base, :mod:`~upliftlab.continuum.output.xdmf`), the uplift-zone pictures
(through :mod:`upliftlab.meshes.render`), the M–θ figure of a pushover, and one-line summaries.
What a result must offer is :class:`~upliftlab.continuum.output.field_history.FieldHistory`.

**M–θ figure** (:func:`moment_rotation_figure`): M, contact length c/B and settlement against θ,
with the closed forms computed here (``upliftlab.continuum`` never imports the reduced
model): the tensionless uniform Winkler bed of a scene whose foundation is one (the rigid strip on
compression-only springs: M/M_up = 3 − 2√(θ_up/θ), c/B = √(θ_up/θ), θ_up = 2N/(kB²), k = K_v/B),
the rigid strip on an elastic half-plane (M = K_r θ to θ_on = 2N(1 − ν)/(πGB), then M/(NB) = 1/2 −
θ_on/(4θ), c/B = θ_on/θ), and for undrained soil the V–M capacity M = B V_ult v(1 − v)/2 (the
effective-width capacity of a strip on Tresca soil, Meyerhof 1953).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...anchors import half_plane_rocking, prandtl_capacity, winkler_rocking  # noqa: F401
from ...checks import InputError
from ...meshes.render import snapshot_rows
from ...results import atomic_path
from ...scenes.soil import SOIL_MODELS, UNDRAINED
from .field_history import FieldHistory, check_history
from .notebook import figure_title
from .summaries import dynamic_summary, pushover_summary, rotation_schedule, summary_line
from .xdmf import TimeAxis, read_xdmf, time_axis, write_footing_xdmf, write_xdmf

__all__ = ["FieldHistory", "check_history", "TimeAxis", "time_axis", "write_xdmf",
           "write_footing_xdmf", "read_xdmf", "winkler_rocking",
           "half_plane_rocking", "moment_rotation_figure", "save_figure", "rotation_schedule",
           "pushover_summary",
           "dynamic_summary", "summary_line", "figure_title", "write_outputs"]

#: The words before the pictures' CPU time in the line that reports them (benchmarks read it).
PICTURES_SPENT = "the pictures took "


def _soil(metadata: dict) -> dict:
    soil = metadata.get("soil", {})
    if isinstance(soil, str):
        import json
        soil = json.loads(soil)
    return soil or {}


def _units(metadata: dict) -> dict:
    units = metadata.get("units", {})
    if isinstance(units, str):
        import json
        units = json.loads(units)
    return units or {}


def _brackets(unit: str) -> str:
    unit = unit.replace("^2", "²").replace("*", "·")
    return f" [{unit}]" if unit else ""


def moment_rotation_figure(path, scene=None):
    """The matplotlib figure of a rotation (or moment) pushover ``path``: M, c/B and
    settlement against θ, with the closed forms of the module docstring (the Winkler bed only
    if ``scene.foundation`` is a uniform ``winkler`` layout)."""
    from matplotlib.figure import Figure

    if not str(getattr(path, "kind", "")).endswith(("rotation_pushover", "moment_pushover")):
        raise InputError(f"path.kind = {getattr(path, 'kind', None)!r}: the M–θ figure needs a "
                         "rotation or moment pushover")
    theta, N, B = np.asarray(path.theta), float(np.median(path.N)), float(path.width)
    soil, units = _soil(path.metadata), _units(path.metadata)
    fine = np.linspace(min(0.0, theta.min()), theta.max(), 400)
    fig = Figure(figsize=(7.5, 9.0), dpi=100)
    ax_m, ax_c, ax_s = fig.subplots(3, 1, sharex=True)
    ax_m.plot(theta, path.M, "o-", color="black", ms=3, label="continuum (FE)")
    ax_c.plot(theta, path.contact_length / B, "o-", color="black", ms=3, label="continuum (FE)")
    ax_s.plot(theta, -np.asarray(path.v), "o-", color="black", ms=3, label="continuum (FE)")
    if soil.get("youngs_modulus"):
        E, nu = float(soil["youngs_modulus"]), float(soil["poisson_ratio"])
        ref = half_plane_rocking(fine, N, B, E / (2 * (1 + nu)), nu)
        ax_m.plot(fine, ref["M"], ":", color="tab:blue", lw=2, label="elastic half-plane")
        ax_c.plot(fine, ref["c"] / B, ":", color="tab:blue", lw=2, label="elastic half-plane")
    foundation = getattr(scene, "foundation", None)
    if foundation is not None and foundation.layout == "winkler" and foundation.support == "uplift":
        k = foundation.stiffness / foundation.width
        ref = winkler_rocking(fine, N, B, k)
        label = f"tensionless Winkler bed, k = K_v/B = {k:.4g}"
        ax_m.plot(fine, ref["M"], "--", color="tab:red", lw=1.5, label=label)
        ax_c.plot(fine, ref["c"] / B, "--", color="tab:red", lw=1.5, label=label)
        ax_s.plot(fine, ref["settlement"], "--", color="tab:red", lw=1.5, label=label)
    cu = soil.get("undrained_strength")
    uniform = not soil.get("undrained_strength_gradient")  # Prandtl's V–M envelope: uniform c_u
    if SOIL_MODELS.get(soil.get("model")) == UNDRAINED and cu and uniform:
        V_ult = prandtl_capacity(float(cu), B)
        v = N / V_ult
        if 0.0 < v < 1.0:
            ax_m.axhline(B * V_ult * v * (1 - v) / 2, color="tab:green", ls="-.",
                         label=f"V–M capacity at v = {v:.2f}")
    ax_m.set_ylabel(f"M{_brackets(units.get('moment/length', ''))}")
    ax_c.set_ylabel("contact length c/B [–]")
    ax_c.set_ylim(0.0, 1.05)
    ax_s.set_ylabel(f"settlement −v{_brackets(units.get('length', ''))}")
    ax_s.set_xlabel("footing rotation θ [rad]")
    for ax in (ax_m, ax_c, ax_s):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    meta = path.metadata
    fig.suptitle(f"{meta.get('scene', '')}: rotation pushover at N = {N:.4g}"
                 f"{_brackets(units.get('force/length', ''))}\n{meta.get('element', '')}, "
                 f"{meta.get('dofs', '')} DOFs, soil {soil.get('model', '')}", fontsize=11)
    fig.tight_layout()
    return fig


def save_figure(fig, path) -> Path:
    """Write a matplotlib figure to PNG atomically."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png")
    return Path(path)


# ---------------------------------------------------------------------------------------------
# Everything a run writes
# ---------------------------------------------------------------------------------------------


def write_outputs(directory, model, result, *, scene=None, renders: bool = True,
                  scale: float | None = None, progress=None, stop=None,
                  picture_budget: float | None = None) -> dict[str, Path]:
    """Write a run's files into ``directory``: ``result.nc`` (``result.save``), ``fields.xdmf``
    and ``fields.h5`` (the soil), ``footing.xdmf`` and ``footing.h5`` (the contact along the
    base; both time series at the same time values: :mod:`~upliftlab.continuum.output.xdmf`),
    ``uplift.png`` (the snapshot of largest |θ|) and ``uplift.gif`` (the snapshots; skipped if
    not ``renders``, or once ``stop()`` is true: the user asked the run to stop while its data
    were written), and for a pushover ``moment_rotation.png``. ``picture_budget`` (CPU
    seconds, default none) bounds the two pictures together: the GIF gets what the PNG left
    (:func:`~upliftlab.meshes.render.write_pictures`' rule: evenly spaced snapshots, at least
    :data:`~upliftlab.meshes.render.MIN_FRAMES`); without it every snapshot is a frame.
    ``progress(message)`` reports each file. Returns {name: path}."""
    import time

    from ...meshes.render import write_pictures

    check_history(result, model)
    axis = time_axis(result)  # refuses a result of unknown kind before any file is written
    directory = Path(directory)
    say = progress or (lambda message: None)
    written: dict[str, Path] = {}
    written["result.nc"] = Path(result.save(directory / "result.nc"))
    say(f"wrote {written['result.nc']}")
    written["fields.xdmf"] = write_xdmf(directory / "fields.xdmf", model, result)
    written["fields.h5"] = directory / "fields.h5"
    say(f"wrote {written['fields.xdmf']} and fields.h5 ({np.size(result.snapshot_time)} steps, "
        f"time = {axis.description})")
    written["footing.xdmf"] = write_footing_xdmf(directory / "footing.xdmf", model, result)
    written["footing.h5"] = directory / "footing.h5"
    say(f"wrote {written['footing.xdmf']} and footing.h5 (contact pressure and gap along the "
        "base)")
    if str(getattr(result, "kind", "")).endswith(("rotation_pushover", "moment_pushover")):
        fig = moment_rotation_figure(result, scene=scene)
        written["moment_rotation.png"] = save_figure(fig, directory / "moment_rotation.png")
        say(f"wrote {written['moment_rotation.png']}")
    if renders and not (stop is not None and stop()):
        start = time.process_time()
        title = figure_title(result, scene)
        rows = snapshot_rows(result)
        peak = int(np.argmax(np.abs(np.asarray(result.footing)[rows, 2])))
        png, gif = directory / "uplift.png", directory / "uplift.gif"
        count = write_pictures(png, gif, result, model.disc.basis, model.width, snapshot=peak,
                               scale=scale, title=title, budget=picture_budget)
        written["uplift.png"], written["uplift.gif"] = png, gif
        snapshots = np.size(result.snapshot_time)
        spent = time.process_time() - start
        say(f"wrote {png} and {gif} ({count} frames"
            + ("" if count == snapshots else
               f" of {snapshots} snapshots, evenly spaced: the pictures' budget is "
               f"{picture_budget:.2g} s CPU")
            + f"; {PICTURES_SPENT}{spent:.3f} s CPU)")
    return written
