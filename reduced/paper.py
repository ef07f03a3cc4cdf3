"""Ewing's reduced-model study, reproduced: every case of Figs. 4, 5 and 7–12, with figures and a
Markdown summary whose statements are computed from the runs.

``upliftlab paper [--out DIR] [--motion PATH]`` calls :func:`main`. The El Centro figures (5, 8,
10–12) need the record; without it the free-vibration figures (4, 7, 9) are still made and the
summary says which file to supply and how.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks import InputError
from ..elcentro import mismatch
from ..log import logger
from ..motions import ELCENTRO, ELCENTRO_DESCRIPTION, MOTIONS_ENV, Motion, load_motion
from ..results import write_text
from ..scenes import load_scene
from .response import Response
from .run import run

__all__ = ["Case", "FIGURES", "paper_study", "claims", "main", "record_for", "at_rest"]


@dataclass(frozen=True)
class Case:
    """One run of the study: a packaged scene, its case, and a plot label."""

    scene: str
    case: str
    label: str

    @property
    def key(self) -> str:
        return f"{self.scene}-{self.case}"

    @property
    def needs_record(self) -> bool:
        return self.scene.endswith("elcentro")


@dataclass(frozen=True)
class Figure:
    """A figure of the paper: its cases and panels (quantity, axis label)."""

    number: int
    title: str
    cases: tuple[Case, ...]
    panels: tuple[tuple[str, str], ...]

    @property
    def needs_record(self) -> bool:
        return any(c.needs_record for c in self.cases)


def _abc(scene: str) -> tuple[Case, ...]:
    return tuple(Case(scene, c, f"Case {c}") for c in "ABC")


LEFT = ("left", "left spring displacement [in]\n(+ compression, − uplift)")
TOTAL = ("x", "total displacement of the\nsuperstructure, X − X_g [in]")
DEFORMATION = ("u", "superstructure deformation u [in]")
WALL_EPS = (Case("wall_free", "e10", "ε = 1.0"), Case("wall_free", "e07", "ε = 0.7"))
WALL_EC = (Case("wall_elcentro", "e10", "ε = 1.0"), Case("wall_elcentro", "e07", "ε = 0.7"))

FIGURES = (
    Figure(4, "Fig. 4 — wall on a Winkler bed, free vibration from Ẋ(0) = 20 in/s",
           WALL_EPS, (LEFT, TOTAL)),
    Figure(5, "Fig. 5 — wall on a Winkler bed, El Centro 1940 N-S", WALL_EC, (LEFT, TOTAL)),
    Figure(7, "Fig. 7 — short-period building, free vibration, Cases A, B, C",
           _abc("short_period_free"), (LEFT, DEFORMATION)),
    Figure(8, "Fig. 8 — short-period building, El Centro 1940, Cases A, B, C",
           _abc("short_period_elcentro"), (LEFT, DEFORMATION)),
    Figure(9, "Fig. 9 — long-period building, free vibration, Cases A, B, C",
           _abc("long_period_free"), (DEFORMATION, LEFT)),
    Figure(10, "Fig. 10 — long-period building, El Centro 1940, Cases A, B, C",
           _abc("long_period_elcentro"), (DEFORMATION, LEFT)),
    Figure(11, "Fig. 11 — short-period building, fixed base and uplift allowed (Case C)",
           (Case("short_period_elcentro", "fixed", "fixed base"),
            Case("short_period_elcentro", "C", "uplift allowed")), (DEFORMATION,)),
    Figure(12, "Fig. 12 — long-period building, fixed base and uplift allowed (Case C)",
           (Case("long_period_elcentro", "fixed", "fixed base"),
            Case("long_period_elcentro", "C", "uplift allowed")), (DEFORMATION,)),
)


def _history(response: Response, quantity: str) -> np.ndarray:
    if quantity == "left":
        if response.model.layout is None:
            return np.zeros(response.time.size)
        return response.left_spring_displacement
    return getattr(response, quantity)


def decay_time(response: Response, fraction: float = 0.1) -> float:
    """Time (s) after which the mechanical energy (kinetic + strain + gravity, above rest)
    stays below ``fraction`` of its initial value: how fast a free vibration decays."""
    e = response.energy
    mechanical = e[:, 1] + e[:, 2] + e[:, 3]
    above = np.flatnonzero(mechanical > fraction * mechanical[0])
    if above.size == mechanical.size:
        return float("inf")
    return float(response.time[above[-1] + 1]) if above.size else 0.0


def at_rest(response: Response, fraction: float = 1e-3, tail: float = 0.1) -> bool:
    """Whether a run ends at rest (:meth:`~.response.Response.at_rest`). Only then is the
    final settlement a residual one."""
    return response.at_rest(fraction, tail)


def paper_study(out: Path, record: Motion | None, progress=None) -> dict:
    """Run every case the record allows; write runs, figures and the summary under ``out``.

    Returns the summary as a dictionary (also written as ``summary.json``).
    """
    out = Path(out)
    say = progress or (lambda msg: None)
    cases = {c.key: c for f in FIGURES for c in f.cases if record is not None or not c.needs_record}
    responses: dict[str, Response] = {}
    for i, (key, case) in enumerate(cases.items(), start=1):
        say(f"[{i}/{len(cases)}] {key}")
        scene = load_scene(case.scene, case=case.case)
        responses[key] = run(scene, motion=record if case.needs_record else None,
                             output_dt=0.005)
        responses[key].save(out / "runs" / f"{key}.nc")
    figures = _figures(out, responses, say)
    summary = _summary(responses, figures, record)
    write_text(out / "summary.json", json.dumps(summary, indent=2, default=float))
    write_text(out / "summary.md", _markdown(summary))
    return summary


def _figures(out: Path, responses: dict[str, Response], say) -> list[int]:
    from .figures import comparison_figure, save
    made = []
    for fig in FIGURES:
        if not all(c.key in responses for c in fig.cases):
            continue
        panels = []
        for quantity, label in fig.panels:
            curves = [(c.label, responses[c.key].time, _history(responses[c.key], quantity))
                      for c in fig.cases]
            panels.append((label, curves))
        save(comparison_figure(panels, fig.title), out / f"fig{fig.number:02d}.png")
        say(f"wrote fig{fig.number:02d}.png")
        made.append(fig.number)
    return made


def _peaks(response: Response) -> dict:
    pk = response.peaks
    row = {"peak_u": pk["u"], "peak_theta": pk["theta"], "peak_base_shear": pk["base_shear"],
           "energy_balance_error": pk["energy_balance_error"],
           "integrator": response.info["integrator"], "dt": response.info["dt"],
           "wall_time_s": response.info["wall_time_s"],
           "compile_time_s": response.info["compile_time_s"]}
    if "uplift_left" in pk:
        row.update(peak_uplift_left=pk["uplift_left"],
                   final_settlement=float(-response.V[-1]), at_rest=at_rest(response),
                   plastic_settlement_mean=pk["plastic_settlement_mean"])
    return row


def claims(responses: dict[str, Response]) -> list[dict]:
    """The paper's statements, each with the numbers that decide it (only where the runs exist)."""
    out = []

    def have(*keys):
        return all(k in responses for k in keys)

    for building in ("short_period", "long_period"):
        free = [f"{building}_free-{c}" for c in "ABC"]
        if have(*free):
            t10 = {c: decay_time(responses[k]) for c, k in zip("ABC", free)}
            out.append(_claim(f"{building}: Case A decays fastest in free vibration (time for "
                              "the mechanical energy to stay below 10 % of its initial value; "
                              "inf: not within the run)",
                              t10["A"] < min(t10["B"], t10["C"]), t10, "s"))
        for motion in ("free", "elcentro"):
            keys = [f"{building}_{motion}-{c}" for c in "ABC"]
            if have(*keys):
                u = {c: responses[k].peaks["u"] for c, k in zip("ABC", keys)}
                claimed = "larger" if building == "short_period" else "smaller"
                holds = (u["A"] > max(u["B"], u["C"]) if claimed == "larger"
                         else u["A"] < min(u["B"], u["C"]))
                out.append(_claim(f"{building}, {motion}: Case A gives a {claimed} peak "
                                  "superstructure deformation u than Cases B and C", holds, u,
                                  "in"))
        ec = [f"{building}_elcentro-{c}" for c in "BC"]
        if have(*ec):
            s = {c: responses[k].peaks["plastic_settlement_mean"] for c, k in zip("BC", ec)}
            out.append(_claim(f"{building}, El Centro: impact damping (C) reduces the plastic "
                              "settlement of the soil against B (mean over the springs)",
                              s["C"] < s["B"], s, "in"))
        fx = [f"{building}_elcentro-fixed", f"{building}_elcentro-C"]
        if have(*fx):
            u = {"fixed": responses[fx[0]].peaks["u"], "uplift (C)": responses[fx[1]].peaks["u"]}
            out.append(_claim(f"{building}, El Centro: uplift reduces the peak superstructure "
                              "deformation against the fixed base", u["uplift (C)"] < u["fixed"],
                              u, "in"))
    return out


def _claim(statement: str, holds: bool, values: dict, unit: str) -> dict:
    return {"statement": statement, "holds": bool(holds),
            "values": {k: float(v) for k, v in values.items()}, "unit": unit}


def _summary(responses: dict[str, Response], figures: list[int], record: Motion | None) -> dict:
    missing = [f.number for f in FIGURES if f.number not in figures]
    note = ""
    if record is None:
        note = (f"Figures {', '.join(map(str, missing))} need the El Centro record: "
                f"{ELCENTRO_DESCRIPTION}. Supply it with `upliftlab paper --motion PATH`, or set "
                f"{MOTIONS_ENV} to the directory that holds {ELCENTRO}.txt.")
    return {"figures": figures, "missing_figures": missing, "note": note,
            "runs": {k: _peaks(r) for k, r in responses.items()},
            "claims": claims(responses),
            "record": None if record is None else record.source}


def _markdown(summary: dict) -> str:
    lines = ["# Ewing's reduced-model study, reproduced by upliftlab", ""]
    if summary["note"]:
        lines += [f"**Missing record.** {summary['note']}", ""]
    lines += ["Figures: " + ", ".join(f"`fig{n:02d}.png`" for n in summary["figures"]), "",
              "## Peaks (kip-in-s)", "",
              "| run | peak u [in] | peak θ [rad] | uplift, left spring [in] | settlement −V "
              "at the end [in] | plastic settlement, mean [in] | base shear [kip] | energy "
              "balance | Δt [s] | run time [ms] |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for key, r in summary["runs"].items():
        uplift = f"{r['peak_uplift_left']:.4f}" if "peak_uplift_left" in r else "—"
        settle = (f"{r['final_settlement']:.4f} ({'at rest' if r['at_rest'] else 'moving'})"
                  if "final_settlement" in r else "—")
        plastic = f"{r['plastic_settlement_mean']:.4f}" if "final_settlement" in r else "—"
        lines.append(f"| {key} | {r['peak_u']:.4f} | {r['peak_theta']:.3e} | {uplift} | "
                     f"{settle} | {plastic} | {r['peak_base_shear']:.1f} | "
                     f"{r['energy_balance_error']:.1e} | {r['dt']:.2e} | "
                     f"{1e3 * r['wall_time_s']:.1f} |")
    compiled = sum(r["compile_time_s"] for r in summary["runs"].values())
    lines += ["", "The settlement at the end is −V when the run stops; it is the residual "
              "settlement only where the run ends at rest (kinetic energy over its last 10 % "
              "below 0.1 % of its peak), and the wall or building is still moving where it "
              "says so. The plastic settlement is the mean permanent deformation of the "
              "springs.", "",
              "Run times are the integration alone. Compiling the integrators (numba), or "
              "reading them from the cache where an earlier run compiled them, took "
              f"{compiled:.1f} s more in this process, apart from these times.", "",
              "## The paper's statements, checked", ""]
    for c in summary["claims"]:
        values = ", ".join(f"{k}: {v:.4g}" for k, v in c["values"].items())
        lines.append(f"- {'holds' if c['holds'] else '**does not hold**'}: {c['statement']} "
                     f"({values} {c['unit']})")
    return "\n".join(lines) + "\n"


_UNSET = object()


def main(out: str | Path = "results/paper", motion: str | None = None, *, record=_UNSET,
         claim=None) -> dict:
    """The main job: the whole study into ``out``; returns the summary. ``record``: the El
    Centro record already read (:func:`record_for`); ``claim``: the output folder's claim
    (:mod:`upliftlab.outdir`), completed with the files written."""
    record = record_for(motion) if record is _UNSET else record
    start = time.perf_counter()

    def say(msg):
        logger("paper").info(f"upliftlab paper: {msg}")

    if record is None:
        say(f"El Centro record not found ({MOTIONS_ENV}); making Figs. 4, 7 and 9 only")
    if claim is not None:
        claim.start_writing()
    summary = paper_study(Path(out), record, progress=say)
    if claim is not None:
        claim.complete(sorted(p for p in Path(out).rglob("*") if p.is_file()
                              and not p.name.startswith(".")))
    say(f"done in {time.perf_counter() - start:.1f} s: {Path(out) / 'summary.md'}")
    return summary


def record_for(motion: str | None) -> Motion | None:
    """The El Centro record: ``motion`` (a name or path; an error if it cannot be read), or
    the packaged name on UPLIFTLAB_MOTIONS, or None when that is not found. A record that is
    not the digitization the study expects (:mod:`upliftlab.elcentro`) is refused: the
    paper's statements would be judged on another motion."""
    if motion is not None:
        record = load_motion(motion)
    else:
        try:
            record = load_motion(ELCENTRO)
        except InputError:
            return None
    different = mismatch(record)
    if different:  # the paper's figures and statements are of this record, and no other
        raise InputError(f"--motion: {different}; the paper's study runs only on that record "
                         "(upliftlab run takes any)")
    return record
