"""Every conclusion of Ewing's study, one by one, with the evidence from our models.

The founding study (R. D. Ewing, "Influence of foundation model on uplifting of structures",
1988) states these in its Conclusions, Results and Introduction. Each becomes a :class:`Conclusion` whose verdict is
computed from runs:

1. Case A (elastic spring, 40 % viscous damping) overestimates the peak superstructure
   deformation (Conclusions) ...
2. ... except for the long-period building, where A's is lower (Results, Figs. 9-10).
3. Case A overestimates the rate of decay of the response (free vibration).
4. Impact damping (Case C) reduces the plastic deformation of the soil against Case B.
5. A Winkler bed is necessary and cannot be replaced by an equivalent two-spring system once the
   foundation is nonlinear (from :mod:`.two_spring_equivalence`).
6. Uplift reduces the superstructure deformation against a fixed base ...
7. ... and more so with the recommended model (Case C) than with Case A.
8. Uplift elongates the fundamental response period (Introduction; measured from the zero
   crossings of u).

Reduced-model evidence comes from :func:`upliftlab.reduced.paper.paper_study` (the paper's own
scenes and El Centro); the two-spring evidence from the fast or full equivalence maps. A
conclusion that needs El Centro says so when the record is missing, instead of deciding.

``python -m upliftlab.comparisons.paper [--fast] [--out DIR]``
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..checks import InputError
from ..motions import ELCENTRO, MOTIONS_ENV, Motion, load_motion
from ..reduced.paper import decay_time
from ..reduced.run import run as run_reduced
from ..results import provenance
from ..scenes import load_scene
from .protocol import Context, Study, main_for, run_study
from .study import StudyResult, write_summary

__all__ = ["Evidence", "Conclusion", "PaperConclusions", "Options", "DEFINITION", "compute",
           "write", "run", "main", "apparent_period"]

STUDY = "paper"
BUILDINGS = ("short_period", "long_period")


@dataclass(frozen=True)
class Evidence:
    """One measured fact for a conclusion: ``source`` (model and scene), what it ``says``, the
    ``values`` that decide it (``unit``), and whether it ``supports`` the conclusion."""

    source: str
    says: str
    values: Mapping[str, float]
    unit: str
    supports: bool


@dataclass(frozen=True)
class Conclusion:
    """A statement of the paper and the evidence for it. ``verdict``: ``holds`` (all evidence
    supports it), ``does not hold`` (none does), ``holds in part``, or ``not tested`` (no
    evidence: ``note`` says why). ``why``: where our results differ, the reason found."""

    number: int
    statement: str
    evidence: tuple[Evidence, ...]
    note: str = ""
    why: str = ""

    @property
    def verdict(self) -> str:
        if not self.evidence:
            return "not tested"
        support = [e.supports for e in self.evidence]
        return "holds" if all(support) else "does not hold" if not any(support) \
            else "holds in part"


@dataclass(frozen=True)
class PaperConclusions:
    """The conclusions and the study record (files, summary, numbers)."""

    conclusions: tuple[Conclusion, ...]
    record: str | None
    study: StudyResult | None = field(default=None, repr=False)


# ---------------------------------------------------------------------------------------------
# Measures
# ---------------------------------------------------------------------------------------------


def apparent_period(time_s: np.ndarray, signal: np.ndarray, *, window: float | None = None
                    ) -> float:
    """Mean period (s) from the upward zero crossings of ``signal`` (linearly interpolated)
    within the first ``window`` seconds (all of it if None); NaN with fewer than two."""
    t, x = np.asarray(time_s, float), np.asarray(signal, float)
    if window is not None:
        keep = t <= t[0] + window
        t, x = t[keep], x[keep]
    up = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    if up.size < 2:
        return math.nan
    crossing = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    return float(np.mean(np.diff(crossing)))


def _ratio(a: float, b: float) -> float:
    return a / b if b else math.inf


# ---------------------------------------------------------------------------------------------
# The conclusions
# ---------------------------------------------------------------------------------------------


def _responses(record: Motion | None, output_dt: float) -> dict:
    """The runs the conclusions read: free vibration and (with the record) El Centro of both
    buildings in Cases A, B, C and, on El Centro, the fixed base."""
    out = {}
    for building in BUILDINGS:
        for case in "ABC":
            out[f"{building}_free-{case}"] = run_reduced(
                load_scene(f"{building}_free", case=case), output_dt=output_dt)
        if record is None:
            continue
        for case in ("A", "B", "C", "fixed"):
            out[f"{building}_elcentro-{case}"] = run_reduced(
                load_scene(f"{building}_elcentro", case=case), motion=record,
                output_dt=output_dt)
    return out


def _reduced(building: str) -> str:
    return f"reduced model (Winkler bed, 12 springs), {building.replace('_', '-')} building"


def conclusion_peak_u(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        for motion in ("free", "elcentro"):
            keys = [f"{building}_{motion}-{c}" for c in "ABC"]
            if not all(k in r for k in keys):
                continue
            u = {c: r[k].peaks["u"] for c, k in zip("ABC", keys)}
            larger = u["A"] > max(u["B"], u["C"])
            ev.append(Evidence(f"{_reduced(building)}, {motion}",
                               f"peak u of A is {'larger' if larger else 'not larger'} than B "
                               f"and C (A/B = {_ratio(u['A'], u['B']):.2f})", u, "in", larger))
    return Conclusion(1, "The elastic spring with high viscous damping (Case A) overestimates "
                         "the maximum superstructure deformation.", tuple(ev),
                      _record_note(record))


def conclusion_long_period_peak(r: Mapping, record: Motion | None) -> Conclusion:
    """The results section's exception for the long-period building (Figs. 9-10): Case A's
    superstructure deformation is lower, its foundation displacement higher."""
    ev, measured = [], []
    for motion in ("free", "elcentro"):
        keys = [f"long_period_{motion}-{c}" for c in "ABC"]
        if not all(k in r for k in keys):
            continue
        u = {c: r[k].peaks["u"] for c, k in zip("ABC", keys)}
        gap = {c: r[k].peaks["uplift_left"] for c, k in zip("ABC", keys)}
        ev.append(Evidence(f"{_reduced('long_period')}, {motion}",
                           f"peak u of A is {'lower' if u['A'] < min(u['B'], u['C']) else 'not lower'}"
                           f" than B and C; peak uplift of the left spring A/B = "
                           f"{_ratio(gap['A'], gap['B']):.2f}", u, "in",
                           u["A"] < min(u["B"], u["C"])))
        measured.append(f"{motion}: θ_A/θ_B = "
                        f"{_ratio(r[keys[0]].peaks['theta'], r[keys[1]].peaks['theta']):.2f}")
    why = ""
    if any(not e.supports for e in ev):
        why = ("Our long-period runs give A the larger superstructure deformation, as the "
               "paper's general conclusion 1 says, not the lower one its results section reports "
               "for Figs. 9-10 (" + "; ".join(measured) + "). The paper tabulates no peaks, and "
               "the long-period building's rotary inertia (1740 kip in s²) and coupled weight "
               "(16 kip) are all it specifies beyond the short-period one. Left unresolved.")
    return Conclusion(2, "Results, long-period building (Figs. 9-10): Case A reaches lower "
                         "maximum deformations in the superstructure than B and C.", tuple(ev),
                      _record_note(record), why)


def conclusion_decay(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = [f"{building}_free-{c}" for c in "ABC"]
        t10 = {c: decay_time(r[k]) for c, k in zip("ABC", keys)}
        fastest = t10["A"] < min(t10["B"], t10["C"])
        ev.append(Evidence(f"{_reduced(building)}, free vibration",
                           "time for the mechanical energy to stay below 10 % of its initial "
                           f"value: A is {'the shortest' if fastest else 'not the shortest'}",
                           t10, "s", fastest))
    why = ""
    failed = [b for b, e in zip(BUILDINGS, ev) if not e.supports]
    if failed:
        parts = []
        for building in failed:
            dissipated = r[f"{building}_free-C"].energy[-1]  # ENERGY_NAMES order
            viscous, impact, plastic = dissipated[4], dissipated[5], dissipated[6]
            total = viscous + impact + plastic
            parts.append(f"{building.replace('_', '-')} C: impact {100 * impact / total:.0f} %, "
                         f"viscous {100 * viscous / total:.0f} %, plastic "
                         f"{100 * plastic / total:.0f} % of the energy dissipated")
        why = ("Besides its 10 % dashpots, Case C dissipates by yielding of the bed and by "
               "impact at every recontact, and in large free rocking these together decay the "
               "response as fast as A's 40 % dashpots (" + "; ".join(parts) + "). The paper "
               "shows the histories only; we cannot tell which of these terms is smaller in "
               "its model.")
    return Conclusion(3, "Case A overestimates the rate of decay of the response.", tuple(ev),
                      "", why)


def conclusion_settlement(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = [f"{building}_elcentro-{c}" for c in "BC"]
        if not all(k in r for k in keys):
            continue
        s = {c: r[k].peaks["plastic_settlement_mean"] for c, k in zip("BC", keys)}
        ev.append(Evidence(f"{_reduced(building)}, El Centro",
                           f"mean plastic settlement C/B = {_ratio(s['C'], s['B']):.2f}", s,
                           "in", s["C"] < s["B"]))
    return Conclusion(4, "Impact damping reduces the plastic deformation in the soil.",
                      tuple(ev), _record_note(record))


def conclusion_two_springs(equivalence) -> Conclusion:
    if equivalence is None:
        return Conclusion(5, _TWO_SPRING, (), "the two-spring equivalence study did not run")
    e = equivalence.ewing
    ev = []
    if e.holds is not None:
        layout, share = e.best("C")
        ev.append(Evidence("reduced model, two-spring equivalence maps (Case C)",
                           f"best two-spring layout ({layout}) within {100 * e.threshold:g} % "
                           f"of the Winkler bed in all six measures at {100 * share:.0f} % of "
                           "the uplifting points", {"share_within": share,
                                                    "points": e.points["C"]}, "-",
                           bool(e.holds)))
    return Conclusion(5, _TWO_SPRING, tuple(ev), "" if ev else "no Case C point uplifted",
                      "" if all(x.supports for x in ev) else e.text)


_TWO_SPRING = ("With foundation nonlinearity and impact damping, a Winkler foundation is "
               "necessary and cannot be replaced with an equivalent two-spring system.")


def conclusion_uplift_beneficial(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = [f"{building}_elcentro-{c}" for c in ("fixed", "C")]
        if not all(k in r for k in keys):
            continue
        u = {"fixed": r[keys[0]].peaks["u"], "uplift (C)": r[keys[1]].peaks["u"]}
        ev.append(Evidence(f"{_reduced(building)}, El Centro",
                           f"peak u with uplift / fixed base = "
                           f"{_ratio(u['uplift (C)'], u['fixed']):.2f}", u, "in",
                           u["uplift (C)"] < u["fixed"]))
    return Conclusion(6, "Uplift reduces the structural deformation against a fixed base.",
                      tuple(ev), _record_note(record))


def conclusion_more_with_c(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = {c: f"{building}_elcentro-{c}" for c in ("fixed", "A", "C")}
        if not all(k in r for k in keys.values()):
            continue
        ratio = {c: _ratio(r[keys[c]].peaks["u"], r[keys["fixed"]].peaks["u"]) for c in "AC"}
        ev.append(Evidence(f"{_reduced(building)}, El Centro",
                           f"peak u over the fixed base's: A {ratio['A']:.2f}, C "
                           f"{ratio['C']:.2f}", ratio, "-", ratio["C"] < ratio["A"]))
    why = ""
    return Conclusion(7, "Uplift is even more beneficial in reducing structural deformation "
                         "with the recommended model (Case C).", tuple(ev),
                      _record_note(record), why)


def conclusion_period(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = {c: f"{building}_elcentro-{c}" for c in ("fixed", "C")}
        if not all(k in r for k in keys.values()):
            continue
        period = {c: apparent_period(r[k].time, r[k].u) for c, k in keys.items()}
        scene = load_scene(f"{building}_elcentro")
        story = scene.structure.stories[0]
        nominal = 2.0 * math.pi * math.sqrt(story.weight / scene.units.gravity / story.stiffness)
        ev.append(Evidence(f"{_reduced(building)}, El Centro",
                           "mean period between upward zero crossings of u: "
                           f"{period['C']:.3f} s with uplift, {period['fixed']:.3f} s fixed "
                           f"(nominal fixed-base period {nominal:g} s)",
                           {"uplift (C)": period["C"], "fixed": period["fixed"]}, "s",
                           period["C"] > period["fixed"]))
    return Conclusion(8, "Uplift elongates the fundamental response period (introduction).",
                      tuple(ev), _record_note(record))


def _record_note(record: Motion | None) -> str:
    if record is not None:
        return ""
    return (f"El Centro runs skipped: the record {ELCENTRO}.txt was not found; set "
            f"{MOTIONS_ENV} to its directory or pass --motion PATH.")


# ---------------------------------------------------------------------------------------------
# Study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Options:
    """``motion``: the El Centro record (a name on UPLIFTLAB_MOTIONS or a path; None: the
    packaged name, skipped with a note if not found)."""

    motion: str | None = None


def compute(scene: None, ctx: Context) -> PaperConclusions:
    """Decide every conclusion (``scene`` must be None: the paper's buildings). The two-spring
    conclusion reuses ``ctx.results["two_spring_equivalence"]`` when the report computed it,
    else runs that study (from its store) beside ``ctx.out``."""
    if scene is not None:
        raise InputError(f"scene = {scene!r}: this study runs the paper's buildings; pass "
                         "scene=None")
    fast, out = ctx.fast, ctx.out
    options = ctx.options or Options()
    say = ctx.progress or (lambda msg: None)
    record = _record(options.motion)
    say("reduced runs of the paper's scenes")
    responses = _responses(record, output_dt=0.01 if fast else 0.005)
    equivalence = ctx.results.get("two_spring_equivalence")
    if equivalence is None:
        from . import two_spring_equivalence
        say("two-spring equivalence maps")
        equivalence = two_spring_equivalence.run(
            fast=fast, out=out.parent / ("two_spring_equivalence" + ("-fast" if fast else "")))
    conclusions = (
        conclusion_peak_u(responses, record), conclusion_long_period_peak(responses, record),
        conclusion_decay(responses, record),
        conclusion_settlement(responses, record), conclusion_two_springs(equivalence),
        conclusion_uplift_beneficial(responses, record), conclusion_more_with_c(responses, record),
        conclusion_period(responses, record))
    return PaperConclusions(conclusions, None if record is None else record.source)


def write(result: PaperConclusions, ctx: Context) -> StudyResult:
    """``summary.md`` and ``summary.json`` into ``ctx.out``."""
    fast, out = ctx.fast, ctx.out
    numbers = {"conclusions": [_numbers(c) for c in result.conclusions],
               "record": result.record, "provenance": provenance(study=STUDY, fast=fast)}
    markdown = _markdown(result)
    md, js = write_summary(out, markdown, numbers)
    return StudyResult(STUDY, fast, out, (md, js), markdown, numbers, numbers["provenance"],
                       ctx.elapsed())


def run(fast: bool = False, *, out: str | Path | None = None, motion: str | None = None,
        equivalence=None, progress=None) -> PaperConclusions:
    """Decide every conclusion. ``fast``: coarser output sampling and the fast two-spring maps.

    ``motion``: the El Centro record (a name on UPLIFTLAB_MOTIONS or a path; default the
    packaged name, skipped with a note if not found). ``equivalence``: a finished
    :func:`.two_spring_equivalence.run` result to reuse (else it is run, from its store).
    """
    results = {} if equivalence is None else {"two_spring_equivalence": equivalence}
    return run_study(DEFINITION, None, Context(fast=fast, out=out, options=Options(motion),
                                               progress=progress, results=results))


def _record(motion: str | None) -> Motion | None:
    if motion is not None:
        return load_motion(motion)
    try:
        return load_motion(ELCENTRO)
    except InputError:
        return None


def _numbers(c: Conclusion) -> dict:
    return {"number": c.number, "statement": c.statement, "verdict": c.verdict, "note": c.note,
            "why": c.why,
            "evidence": [{"source": e.source, "says": e.says, "supports": e.supports,
                          "unit": e.unit, "values": {k: float(v) for k, v in e.values.items()}}
                         for e in c.evidence]}


def _markdown(result: PaperConclusions) -> str:
    lines = ["# The founding study's conclusions, checked", ""]
    verdicts = [c.verdict for c in result.conclusions]
    lines += [f"{verdicts.count('holds')} of {len(verdicts)} conclusions hold, "
              f"{verdicts.count('holds in part')} hold in part, "
              f"{verdicts.count('does not hold')} do not hold and "
              f"{verdicts.count('not tested')} are not tested.", ""]
    for c in result.conclusions:
        lines += [f"## {c.number}. {c.statement}", "", f"**Verdict: {c.verdict}.**", ""]
        for e in c.evidence:
            values = ", ".join(f"{k} = {v:.4g}" for k, v in e.values.items())
            mark = "supports" if e.supports else "**contradicts**"
            lines.append(f"- {mark} — {e.source}: {e.says} ({values} {e.unit})")
        if c.note:
            lines += ["", f"Note: {c.note}"]
        if c.why:
            lines += ["", f"Where we differ, and why: {c.why}"]
        lines.append("")
    return "\n".join(lines)


def _arguments(parser) -> None:
    parser.add_argument("--motion", help="the El Centro record: a name or a path")


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(args.motion), progress=say)


DEFINITION = Study(STUDY, "The founding paper's conclusions",
                   "Each conclusion of Ewing's study, decided from runs of our models.", Options,
                   compute, write,
                   describe=lambda result: [f"{c.number}. {c.verdict}: {c.statement}"
                                            for c in result.conclusions],
                   arguments=_arguments, context_from=_context_from,
                   help_fast="fast two-spring maps")
main = main_for(DEFINITION)


if __name__ == "__main__":
    sys.exit(main())
