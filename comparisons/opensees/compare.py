"""upliftlab and OpenSees side by side on one scene: peaks, histories, and where they differ.

:func:`compare` writes the standalone script, runs upliftlab twice in this process — at the
scene's own settings (the answer a user gets) and with its Newmark at the OpenSees step (the
same time discretisation, so that what remains is the models) — and OpenSees once in a
subprocess. :func:`write_comparison` writes the table (``comparison.md``), both summaries
(``comparison.json``), the histories side by side (``histories.csv``, ``histories.png``) and
upliftlab's own run (``upliftlab.nc``).
"""

from __future__ import annotations

import json
import math
import re
import statistics
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...checks import InputError
from ...log import logger
from ...reduced import Response, build_model, run
from ...reduced.run import plan_run
from ...results import write_csv, write_text
from ...scenes import Scene
from .runner import OpenSeesRun, require_opensees, run_script
from .script import ScriptFiles, modelling_notes, write_script
from .spec import OpenSeesSpec, opensees_spec

__all__ = ["COMPARISON_NAMES", "SUMMARY_KEYS", "PEAK_KEYS", "Comparison", "compare",
           "check_upliftlab_runs", "write_comparison", "summary_of", "comparison_table"]

#: The keys of both models' summaries (the uplift ones only with a foundation of springs).
SUMMARY_KEYS = ("scene", "verdict", "integrator", "dt", "units", "runtime_s", "peak_u",
                "peak_theta", "peak_base_shear", "peak_uplift_left", "final_vertical_position")
PEAK_KEYS = ("peak_u", "peak_theta", "peak_uplift_left", "peak_base_shear",
             "final_vertical_position")
_LABELS = {"peak_u": "peak u", "peak_theta": "peak θ [rad]", "peak_uplift_left":
           "peak uplift, leftmost spring", "peak_base_shear": "peak base shear",
           "final_vertical_position": "final V (up)"}


@dataclass(frozen=True, eq=False)
class Comparison:
    """Both models on one scene: the ``spec`` OpenSees ran, the ``files`` of its script,
    ``upliftlab`` at the scene's settings and ``same_step`` (its Newmark at the OpenSees step),
    each a :data:`SUMMARY_KEYS` summary with its ``response``, the ``opensees`` run, and the
    ``notes`` that say where they differ."""

    spec: OpenSeesSpec
    files: ScriptFiles
    upliftlab: dict
    same_step: dict
    opensees: OpenSeesRun
    response: Response = field(repr=False)
    notes: tuple[str, ...] = ()

    def to_json(self) -> dict:
        """``{"upliftlab": {...}, "opensees": {...}}`` with the same keys in both."""
        return {"upliftlab": self.upliftlab, "opensees": summary_of(self.opensees.summary)}


def summary_of(summary: dict) -> dict:
    """The :data:`SUMMARY_KEYS` of a summary (uplift keys only when present)."""
    return {k: summary[k] for k in SUMMARY_KEYS if k in summary}


def _say(message: str) -> None:
    logger("opensees").info(f"upliftlab opensees: {message}")


def _timed_run(scene: Scene, integrator: str | None, dt: float | None,
               repeats: int = 3) -> tuple[Response, float]:
    """(the response with histories, median runtime of ``repeats`` runs without them, after
    a warm-up that compiles the kernels) (s)."""
    response = run(scene, integrator=integrator, dt=dt)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run(scene, integrator=integrator, dt=dt, histories=False)
        times.append(time.perf_counter() - start)
    return response, statistics.median(times)


def _upliftlab_summary(response: Response, runtime: float) -> dict:
    out = summary_of({**response.summary(), "runtime_s": runtime})
    out["integrator"] = f"upliftlab {out['integrator']}"
    return out


def compare(scene: Scene, out: str | Path, *, dt: float | None = None,
            dashpots: str = "clipped", timeout: float = 3600.0,
            scene_args: Sequence[str] | None = None) -> Comparison:
    """Write the script of ``scene`` into ``out``, run both models and return the comparison.
    ``scene_args``: the command-line arguments that chose the scene (for the command the
    script's ``model.json`` names, :func:`.script.write_script`).

    Every input is checked before any file is written; raises
    :class:`~.runner.OpenSeesError` if the OpenSees run fails and the reduced model's
    :class:`~upliftlab.reduced.IntegrationError` if upliftlab's does.
    """
    spec = opensees_spec(scene, dt=dt, dashpots=dashpots)
    check_upliftlab_runs(scene, spec.dt)
    require_opensees()
    files = write_script(spec, out, scene_args)
    _say(f"wrote {files.script}, {files.numbers}"
         + (f" and {files.motion}" if files.motion else ""))
    started = time.perf_counter()
    response, runtime = _timed_run(scene, None, None)
    same, same_runtime = _timed_run(scene, "newmark", spec.dt)
    _say(f"upliftlab: {response.info['integrator']} and newmark at Δt = {spec.dt:g} s in "
         f"{time.perf_counter() - started:.1f} s; OpenSees: {spec.steps} steps of "
         f"{spec.dt:g} s in a subprocess")
    result = run_script(files.script, timeout=timeout)
    upliftlab = _upliftlab_summary(response, runtime)
    same_step = _upliftlab_summary(same, same_runtime)
    notes = tuple(modelling_notes(spec)) + tuple(_measured_notes(spec, upliftlab, same_step,
                                                                 summary_of(result.summary)))
    return Comparison(spec, files, upliftlab, same_step, result, response, notes)


def check_upliftlab_runs(scene: Scene, step: float) -> None:
    """Every check upliftlab's two runs in :func:`compare` make before they start (integrator,
    step, cost against ``analysis.max_steps``, ``max_memory`` and the time budget), made
    before any file is written or run: refused only when it started, the second run would
    leave the script written and the first run done for nothing. ``step``: the OpenSees
    step (s)."""
    model = build_model(scene)
    motion = scene.build_motion()
    plan_run(model, motion, scene.analysis.integrator)
    plan_run(model, motion, "newmark", dt=step)


def _rel(a: float | None, b: float | None) -> float:
    """(a − b)/|b|, NaN when undefined."""
    if a is None or b is None or b == 0.0:
        return math.nan
    return (a - b) / abs(b)


def _measured_notes(spec: OpenSeesSpec, mine: dict, same: dict, theirs: dict) -> list[str]:
    """What the numbers say: how much of the difference is the time step, how much the models."""
    step = _rel(same["peak_u"], mine["peak_u"])
    models = _rel(theirs["peak_u"], same["peak_u"])
    notes = [f"Measured: upliftlab's Newmark at the OpenSees step Δt = {spec.dt:.4g} s differs "
             f"from upliftlab at the scene's settings by {step:+.3%} in peak u (the time "
             f"discretisation); OpenSees differs from that same-step run by {models:+.3%} "
             "(the models)."]
    if spec.has_dashpots and spec.support == "uplift":
        notes.append("Where the models are the same (no foundation dashpots: --set "
                     "foundation.damping_ratio=0) they agree to 0.5 % in peak u and θ at the "
                     "same step (tests/test_opensees_bridge.py); the difference here comes from "
                     "how the dashpots detach and clip (above).")
    if mine["verdict"] != "completed":
        notes.append(f"upliftlab's run ended {mine['verdict']}: the OpenSees model is in small "
                     "rotations and cannot overturn, so its peaks after that time have no "
                     "counterpart.")
    return notes


def comparison_table(c: Comparison) -> str:
    """The peaks side by side (Markdown)."""
    mine, same, theirs = c.upliftlab, c.same_step, summary_of(c.opensees.summary)
    L = c.spec.length
    head = (f"| quantity | upliftlab ({mine['integrator'].split()[-1]}, Δt = {mine['dt']:.3g} s) "
            f"| upliftlab newmark, Δt = {c.spec.dt:.4g} s | OpenSees newmark, Δt = "
            f"{c.spec.dt:.4g} s | OpenSees vs upliftlab | OpenSees vs same step |")
    lines = [head, "|" + "---|" * 6]
    for key in PEAK_KEYS:
        if key not in mine:
            continue
        unit = "" if key == "peak_theta" else (f" [{c.spec.force}]" if key == "peak_base_shear"
                                                else f" [{L}]")
        lines.append(f"| {_LABELS[key]}{unit} | {mine[key]:.6g} | {same[key]:.6g} | "
                     f"{theirs[key]:.6g} | {_rel(theirs[key], mine[key]):+.3%} | "
                     f"{_rel(theirs[key], same[key]):+.3%} |")
    t = c.opensees.summary["runtime_s"]
    lines.append(f"| runtime [s] | {mine['runtime_s']:.4g} | {same['runtime_s']:.4g} | "
                 f"{t:.4g} | {t / mine['runtime_s']:.0f} × | {t / same['runtime_s']:.0f} × |")
    return "\n".join(lines)


def _histories(c: Comparison) -> dict:
    """Both models on upliftlab's stored times (OpenSees' every-step series interpolated)."""
    r, h = c.response, c.opensees.histories
    t = r.time
    cols = {"time": t, "u_upliftlab": r.u, "u_opensees": np.interp(t, h["time"], h["u"]),
            "theta_upliftlab": r.theta,
            "theta_opensees": np.interp(t, h["time"], h["theta"])}
    if c.spec.has_foundation:
        cols["left_spring_upliftlab"] = r.left_spring_displacement
        cols["left_spring_opensees"] = np.interp(t, h["time"], h["left_spring_displacement"])
    return cols


def difference_panels(c: Comparison) -> list:
    """The comparison plot's panels: for u, θ (mrad) and the leftmost spring, upliftlab minus
    OpenSees on upliftlab's stored times (OpenSees' series interpolated), as
    ``(ylabel, [(label, t, difference)])``."""
    h, L = _histories(c), c.spec.length
    quantities = [("u", f"u [{L}]", 1.0), ("theta", "θ [mrad]", 1e3)]
    if c.spec.has_foundation:
        quantities.append(("left_spring", f"leftmost spring [{L}]", 1.0))
    return [(f"Δ{label}\nupliftlab − OpenSees",
             [("upliftlab − OpenSees", h["time"],
               scale * (h[f"{q}_upliftlab"] - h[f"{q}_opensees"]))])
            for q, label, scale in quantities]


def _curve_panels(c: Comparison) -> list:
    """Both models' histories, overlaid (the plot's optional second column)."""
    r, h, L = c.response, c.opensees.histories, c.spec.length
    mine = f"upliftlab {r.info['integrator']}"
    panels = [(f"u [{L}]", [(mine, r.time, r.u), ("OpenSees", h["time"], h["u"])]),
              ("θ [mrad]", [(mine, r.time, 1e3 * r.theta),
                            ("OpenSees", h["time"], 1e3 * h["theta"])])]
    if c.spec.has_foundation:
        panels.append((f"leftmost spring [{L}]\n(+ compression)",
                       [(mine, r.time, r.left_spring_displacement),
                        ("OpenSees", h["time"], h["left_spring_displacement"])]))
    return panels


def comparison_plot(c: Comparison, curves: bool = True):
    """The comparison plot (a matplotlib figure): the difference upliftlab − OpenSees of each
    history (:func:`difference_panels`), and with ``curves`` both histories overlaid in a
    second column."""
    from ...reduced.figures import comparison_figure

    return comparison_figure(difference_panels(c), f"{c.spec.title}: upliftlab − OpenSees",
                             beside=_curve_panels(c) if curves else None)


def _figure(c: Comparison, path: Path, curves: bool = True) -> Path | None:
    from ...reduced.figures import save

    try:
        fig = comparison_plot(c, curves)
    except InputError as exc:  # matplotlib missing: the numbers are written all the same
        _say(f"no figure: {exc}")
        return None
    return save(fig, path)


#: The files :func:`write_comparison` writes (the figure only where matplotlib is installed).
COMPARISON_NAMES = ("comparison.md", "comparison.json", "histories.csv", "upliftlab.nc",
                    "histories.png")


#: What can begin markup inside a line of Markdown (CommonMark and its GitHub tables): code,
#: emphasis, links and images, HTML and entities, table cells, strike-through.
_MARKUP = re.compile(r"([\\`*_{}\[\]()<>#|!&~])")


def markdown_text(text: str) -> str:
    """``text`` (a scene's title, the user's) as plain text on one line of Markdown: its line
    breaks and tabs become spaces and each character that could begin markup is escaped with a
    backslash (CommonMark escapes any ASCII punctuation so), so that a title cannot end the
    heading, add a link, an image or HTML to the page, or break its table."""
    return _MARKUP.sub(r"\\\1", " ".join(text.split()))


def write_comparison(c: Comparison, out: str | Path, *, curves: bool = True) -> list[Path]:
    """``comparison.md``, ``comparison.json``, ``histories.csv``, ``histories.png`` (the
    difference upliftlab − OpenSees; with ``curves`` both histories beside it) and
    ``upliftlab.nc`` (each atomically)."""
    out = Path(out)
    notes = "\n".join(f"- {n}" for n in c.notes)
    text = (f"# {markdown_text(c.spec.title)}: upliftlab and OpenSees\n\nScene "
            f"`{c.spec.scene_name}`, units {c.spec.units}; OpenSees script "
            f"`{c.files.script.name}` in this folder (run it "
            f"with `python {c.files.script.name}`).\n\n{comparison_table(c)}\n\n"
            f"Runtimes: upliftlab's median of 3 runs without stored histories; OpenSees' "
            "time-step loop in its subprocess (model and gravity excluded). Percentages are "
            "relative to the upliftlab column named.\n\nWhere they differ and why:\n\n"
            f"{notes}\n")
    data = {**c.to_json(), "upliftlab_same_step": c.same_step, "notes": list(c.notes),
            "opensees_wall_s": c.opensees.wall}
    md, data_json, csv, netcdf, png = COMPARISON_NAMES
    written = [write_text(out / md, text),
               write_text(out / data_json, json.dumps(data, indent=1) + "\n"),
               write_csv(out / csv, _histories(c),
                         header=f"{c.spec.title}: upliftlab and OpenSees on upliftlab's stored "
                                f"times; units {c.spec.units}; left spring: compression from "
                                "rest")]
    written += c.response.save(out / netcdf)
    figure = _figure(c, out / png, curves)
    return written + ([figure] if figure else [])
