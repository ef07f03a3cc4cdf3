"""The study's protocol: options, compute, write, run, its definition and its command line."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from ....checks import InputError
from ....motions import ELCENTRO, Motion, load_motion
from ....provenance import provenance
from ....study_files import open_study
from ...framework.protocol import Context, Study, StudyRun, run_study
from ...framework.study import StudyResult, with_attributes, write_data, write_summary
from .conclusions import (conclusion_decay, conclusion_long_period_peak, conclusion_more_with_c,
                          conclusion_peak_u, conclusion_period, conclusion_settlement,
                          conclusion_two_springs, conclusion_uplift_beneficial)
from .dataset import conclusions_dataset, conclusions_of
from .records import STUDY
from .responses import paper_responses
from .summary import key_numbers, summarise

# ---------------------------------------------------------------------------------------------
# Study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Options:
    """``motion``: the El Centro record (a name on UPLIFTLAB_MOTIONS or a path; None: the
    packaged name, skipped with a note if not found)."""

    motion: str | None = None


def compute(scene: None, ctx: Context):
    """Decide every conclusion (``scene`` must be None: the paper's buildings) and return them
    as the study's dataset (:func:`.dataset.conclusions_dataset`). The two-spring
    conclusion reads the two-spring equivalence study's written folder
    (:func:`upliftlab.open_study`): the one of ``ctx.results["two_spring_equivalence"]`` when
    the report ran it, else that study is run (from its store, without its figures) beside
    ``ctx.out`` by its
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
        study = definition(name)
        # its data is what the conclusion reads: its figures (most of its time) are left to
        # its own run
        equivalence = run_study(study, None, Context(
            fast=fast, out=out.parent / (name + ("-fast" if fast else "")),
            options=study.options(figures=False)))
    equivalence = open_study(equivalence.study.directory)
    conclusions = (
        conclusion_peak_u(responses, record), conclusion_long_period_peak(responses, record),
        conclusion_decay(responses, record),
        conclusion_settlement(responses, record), conclusion_two_springs(equivalence),
        conclusion_uplift_beneficial(responses, record), conclusion_more_with_c(responses, record),
        conclusion_period(responses, record))
    return conclusions_dataset(conclusions, None if record is None else record.source)


def write(ds, ctx: Context) -> StudyResult:
    """The dataset (``paper.nc``), ``summary.md`` and ``summary.json`` (the numbers of
    :func:`.summary.key_numbers` beside the provenance, as the study always wrote them) into
    ``ctx.out``; both summaries read the dataset alone."""
    fast, out = ctx.fast, Path(ctx.out)
    prov = provenance(study=STUDY, fast=fast)
    elapsed = ctx.elapsed()
    files = write_data(out, with_attributes(ds, {"elapsed_s": elapsed, "provenance": prov}),
                       STUDY)
    numbers = {**key_numbers(ds), "provenance": prov}
    markdown = summarise(ds)
    files += list(write_summary(out, markdown, numbers))
    return StudyResult(STUDY, fast, out, tuple(files), markdown, numbers, prov, elapsed)


def run(fast: bool = False, *, out: str | Path | None = None, motion: str | None = None,
        equivalence=None, progress=None) -> StudyRun:
    """Decide every conclusion. ``fast``: coarser output sampling and the fast two-spring maps.
    Returns the dataset (``.data``; :func:`.dataset.conclusions_of` gives the records) and
    what was written (``.study``).

    ``motion``: the El Centro record (a name on UPLIFTLAB_MOTIONS or a path; default the
    packaged name, skipped with a note if not found). ``equivalence``: a finished
    two-spring equivalence run (its written folder is read) to reuse (else it is run, from
    its store).
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


def _arguments(parser) -> None:
    parser.add_argument("--motion", help="the El Centro record: a name or a path")


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(args.motion), progress=say)


DEFINITION = Study(STUDY, "The founding paper's conclusions",
                   "Each conclusion of Ewing's study, decided from runs of our models.", Options,
                   compute, write,
                   describe=lambda run: [f"{c.number}. {c.verdict}: {c.statement}"
                                         for c in conclusions_of(run.data)],
                   arguments=_arguments, context_from=_context_from,
                   help_fast="fast two-spring maps")
