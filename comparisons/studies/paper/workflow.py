"""The study's protocol: options, compute, write, run, its definition and its command line."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from ....checks import InputError
from ....motions import ELCENTRO, Motion, load_motion
from ....number_text import number_text
from ....provenance import provenance
from ....study_files import open_study
from ...framework.protocol import Context, Study, run_study
from ...framework.study import StudyResult, write_summary
from .conclusions import (conclusion_decay, conclusion_long_period_peak, conclusion_more_with_c,
                          conclusion_peak_u, conclusion_period, conclusion_settlement,
                          conclusion_two_springs, conclusion_uplift_beneficial)
from .records import STUDY, Conclusion, PaperConclusions
from .responses import paper_responses

#: What an infinite value of a conclusion's evidence means: a decay time of a free vibration
#: whose energy never stays below the fraction within the run (:func:`.reduced.paper.decay_time`).
_UNBOUNDED = "not reached within the run"

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
    conclusion reads the two-spring equivalence study's written folder
    (:func:`upliftlab.open_study`): the one of ``ctx.results["two_spring_equivalence"]`` when
    the report ran it, else that study is run (from its store) beside ``ctx.out`` by its
    registered name (:func:`..registry.definition`), since a study imports no other study's
    code, only reads its written result."""
    if scene is not None:
        raise InputError(f"scene = {scene!r}: this study runs the paper's buildings; pass "
                         "scene=None")
    fast, out = ctx.fast, ctx.out
    options = ctx.options or Options()
    say = ctx.progress or (lambda msg: None)
    record = load_record(options.motion)
    say("reduced runs of the paper's scenes")
    responses = paper_responses(record, output_dt=0.01 if fast else 0.005)
    equivalence = ctx.results.get("two_spring_equivalence")
    if equivalence is None:
        from ..registry import definition
        say("two-spring equivalence maps")
        name = "two_spring_equivalence"
        equivalence = run_study(definition(name), None, Context(
            fast=fast, out=out.parent / (name + ("-fast" if fast else ""))))
    equivalence = open_study(equivalence.study.directory)
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
    numbers = {"conclusions": [conclusion_numbers(c) for c in result.conclusions],
               "record": result.record, "provenance": provenance(study=STUDY, fast=fast)}
    markdown = summary_markdown(result)
    md, js = write_summary(out, markdown, numbers)
    return StudyResult(STUDY, fast, out, (md, js), markdown, numbers, numbers["provenance"],
                       ctx.elapsed())


def run(fast: bool = False, *, out: str | Path | None = None, motion: str | None = None,
        equivalence=None, progress=None) -> PaperConclusions:
    """Decide every conclusion. ``fast``: coarser output sampling and the fast two-spring maps.

    ``motion``: the El Centro record (a name on UPLIFTLAB_MOTIONS or a path; default the
    packaged name, skipped with a note if not found). ``equivalence``: a finished
    :func:`.two_spring_equivalence.run` result (its written folder is read) to reuse (else it
    is run, from its store).
    """
    results = {} if equivalence is None else {"two_spring_equivalence": equivalence}
    return run_study(DEFINITION, None, Context(fast=fast, out=out, options=Options(motion),
                                               progress=progress, results=results))


def load_record(motion: str | None) -> Motion | None:
    if motion is not None:
        return load_motion(motion)
    try:
        return load_motion(ELCENTRO)
    except InputError:
        return None


def conclusion_numbers(c: Conclusion) -> dict:
    return {"number": c.number, "statement": c.statement, "verdict": c.verdict, "note": c.note,
            "why": c.why,
            "evidence": [{"source": e.source, "says": e.says, "supports": e.supports,
                          "unit": e.unit, "values": {k: float(v) for k, v in e.values.items()}}
                         for e in c.evidence]}


def summary_markdown(result: PaperConclusions) -> str:
    lines = ["# The founding study's conclusions, checked", ""]
    verdicts = [c.verdict for c in result.conclusions]
    lines += [f"{verdicts.count('holds')} of {len(verdicts)} conclusions hold, "
              f"{verdicts.count('holds in part')} hold in part, "
              f"{verdicts.count('does not hold')} do not hold and "
              f"{verdicts.count('not tested')} are not tested.", ""]
    for c in result.conclusions:
        lines += [f"## {c.number}. {c.statement}", "", f"**Verdict: {c.verdict}.**", ""]
        for e in c.evidence:
            values = ", ".join(f"{k} = {number_text(v, '.4g', e.unit, unbounded=_UNBOUNDED)}"
                               for k, v in e.values.items())
            mark = "supports" if e.supports else "**contradicts**"
            lines.append(f"- {mark} — {e.source}: {e.says} ({values})")
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
