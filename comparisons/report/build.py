"""One self-contained HTML report of every study: ``upliftlab report [--fast] [--out DIR]``.

The report is a single file, ``<out>/report.html``: plots are embedded as SVG and the rendered
soil frames as PNG (:mod:`.figures`), each figure numbered with a caption computed from its
data (:mod:`..framework.figure_record`); the style sheets (screen and print) are inline; there
are no external links or fonts, and one inline script, the uplift animation's frame slider
(:mod:`.animation`), so it can be mailed or archived as it is and opened from disk
offline. :mod:`.printing` prints it to PDF on A4 or Letter. Beside it ``report.json``
records what each section did.

Sections, in order: the verification anchors (measured error, tolerance, pass/fail) and the
observed convergence orders (:mod:`.verification`); the two-spring equivalence maps and tables
(:mod:`.two_spring_equivalence`); Winkler against the continuum (:mod:`.winkler_vs_continuum`)
and its map over soil, FS_v, h/B, period, intensity and motion (:mod:`.winkler_map`);
speed against error (:mod:`.speed_vs_error`); fixed base against uplift
(:mod:`.fixed_vs_uplift`); the founding paper's conclusions (:mod:`.paper`); and the uplift
zone of a continuum rotation pushover (:mod:`.uplift_zone`: a coarse mesh in fast mode).

**Discovery.** The report walks :data:`.registry.STUDIES` (module names) and runs each
study through the protocol (:func:`.protocol.run_study`), importing its module when its turn
comes. A module that does not exist yet, or that fails, leaves a section that says so with the
error message; the rest of the report is still built.

**Nothing is re-run.** Each study keeps its own store (the sweeps' points), and the report
keeps one more record per study in ``<out>/store`` under a content key: the study, fast or
full, the package version, the SHA-256 of the El Centro file and a SHA-256 of the source files
its numbers depend on (``reduced/``, ``continuum/``, ``meshes/``, the core modules, the scenes,
the study's module or package and the comparison modules it imports). While the key is
unchanged and the study's files are still on disk, the section is built from the record without
calling the study; any edit to those sources makes a new key and the study runs again. The
verification table is cached the same way by :mod:`.verification`. ``report.json`` says for
each section whether it was ``computed`` or read from the ``store``.

**Cost.** Before any section runs the report says, in one line of its progress (stderr on the
command line), what it expects the whole report to take and each section's share
(:func:`estimate_report`): a section the report's store holds costs a read
(:data:`STORE_SECONDS`); the Winkler map costs its own estimate of the continuum runs it still
has to make (:func:`.winkler_map.estimate_map`, as it makes it before its first run) plus its
measured beds and figures (:data:`MAP_REST_SECONDS`); every other section its measured wall
time from empty stores (:data:`SECTION_SECONDS`, a documented rate per section run, fast and
full). After each section a line gives its time against its estimate, the elapsed time and the
time left by the estimates of the sections still to run. A study that estimates its runs
before it starts them (the Winkler map) is refused
above ``--budget`` (s of one worker, :data:`REPORT_BUDGET` by default): its section fails with
the estimate and the rest of the report is built. In a full build from a checkout the map
resumes the continuum runs kept with the repository (:attr:`.protocol.Study.kept_store`), so
only the runs not kept count; a fast build never touches them.

**Threads.** The studies run one after another in this process with BLAS limited to one thread
(:func:`upliftlab.workers.single_threaded`), as the sweeps' worker processes are: on a loaded
two-core machine a two-thread BLAS under the continuum's small dense kernels ran the fast
Prandtl check 3–6 times slower.

**Its verdict** (:class:`Report`): ``ok`` when the report is written, every section has its
results and every verification row passes (skipped rows, e.g. fast mode's costly continuum
levels, do not fail); a report with a failed section is not ok, whatever the section (the
failures are listed in the report's status box). The command line turns it into its exit code
(:mod:`upliftlab.cli.report`).

**Output folder.** ``--out`` is checked before any section runs (:func:`upliftlab.outdir.claim`:
not a file, writable, not being written by another report), and ``upliftlab-run.json`` is written
last, naming the files, when every
section has its results.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import time
import traceback
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ... import __version__, checks
from ...checks import InputError
from ...provenance import provenance
from ...paths import disk_full
from ...results import write_text
from ..framework.protocol import CHECKOUT, Context, Study, run_study
from ..studies.registry import STUDIES, definition
from .html import Section, render_html
from .markdown import markdown_to_html
from ..framework.store import Store, point_key
from ..framework.study import StudyResult, json_default
from ..studies.uplift_zone import continuum_pushover
from ...workers import single_threaded

__all__ = ["STUDIES", "Section", "Report", "build_report", "markdown_to_html", "study_digest",
           "continuum_pushover", "SectionEstimate", "ReportEstimate", "estimate_report",
           "REPORT_BUDGET", "REPORT_NAMES"]

REPORT = "report"
#: The report's default budget (s of one worker) for a study that estimates its runs' cost
#: before it starts them (the Winkler map): above it the study's section is refused with its
#: estimate, and the rest of the report is built.
REPORT_BUDGET = 3600.0


# ---------------------------------------------------------------------------------------------
# Running the sections
# ---------------------------------------------------------------------------------------------


@dataclass
class _Run:
    """What the sections of one report share: fast or full, the report's folder and store,
    the scheduler, and the results computed so far (by study name)."""

    fast: bool
    out: Path
    store: Store
    scheduler: str | None
    budget: float | None = None
    results: dict = field(default_factory=dict)

    def study_dir(self, name: str) -> Path:
        return self.out / "studies" / (name + ("-fast" if self.fast else ""))

    def study_store(self, study: Study, say) -> Store | None:
        """The store ``study``'s sweeps use: the report's own for a study that keys its whole
        result (``own_store``); in a full build the study's points kept with the repository
        when the checkout has them (:attr:`.protocol.Study.kept_store`); else None (the
        study's own under its folder)."""
        if study.own_store:
            return self.store
        if self.fast or study.kept_store is None:
            return None
        kept = CHECKOUT / study.kept_store
        if not kept.is_dir():
            say(f"{study.name}: no kept runs at {kept} (not a checkout): its runs start "
                "from nothing")
            return None
        say(f"{study.name}: resuming the runs kept in {kept}")
        return Store(kept)


@dataclass(frozen=True)
class Report:
    """The report: its ``path``, the ``sections``, whether the verification ``passed``, and
    whether it is ``ok`` (passed, and every section built)."""

    path: Path
    sections: tuple[Section, ...]
    passed: bool
    ok: bool
    elapsed: float
    #: The PDFs printed beside the page (:mod:`.printing`), one per paper asked for.
    pdfs: tuple[Path, ...] = ()

    def section(self, name: str) -> Section:
        return next(s for s in self.sections if s.name == name)


#: What every study's numbers depend on besides its own sources (prefixes of
#: :func:`upliftlab.provenance.code_digest`).
_SHARED = ("upliftlab.comparisons/framework/", "upliftlab.comparisons/beds/")
_STUDIES = Path(__file__).resolve().parents[1] / "studies"


def _sources(name: str) -> list[Path]:
    """The files of study ``name``: its module, or every ``.py`` of its package."""
    if (_STUDIES / name).is_dir():
        return sorted((_STUDIES / name).glob("*.py"))
    return [_STUDIES / f"{name}.py"] if (_STUDIES / f"{name}.py").is_file() else []


def _siblings(name: str, seen: set[str] | None = None) -> set[str]:
    """``name`` and the studies it imports, transitively (``from ..x`` in a study package,
    ``from .x`` in a study module)."""
    seen = set() if seen is None else seen
    files = _sources(name)
    if name in seen or not files:
        return seen
    seen.add(name)
    package = files[0].parent.name == name
    pattern = r"from \.\.(\w+)[ .]" if package else r"from \.(\w+)[ .]"
    for path in files:
        for other in re.findall(pattern, path.read_text(encoding="utf-8", errors="replace")):
            _siblings(other, seen)
    return seen


def study_digest(name: str) -> str:
    """The code digest of the sources study ``name``'s numbers depend on: the models'
    (:data:`upliftlab.provenance.MODEL_SOURCES`), the studies' framework and beds, the study's
    module (or package) and the studies it imports. Other studies stay out, so editing one
    study re-runs only that one."""
    from ...provenance import MODEL_SOURCES, code_digest

    own = tuple(f"upliftlab.comparisons/studies/{p.relative_to(_STUDIES).as_posix()}"
                for n in sorted(_siblings(name) - {"registry", "verification"})
                for p in _sources(n))
    return code_digest(MODEL_SOURCES + _SHARED + own)


def _record_sha() -> str | None:
    from ...motions import ELCENTRO, find_motion
    from ..framework.study import file_sha256

    try:
        return file_sha256(find_motion(ELCENTRO))
    except InputError:
        return None


def _study_record(study: StudyResult) -> dict:
    """A StudyResult as plain JSON types."""
    plain = json.loads(json.dumps({
        "name": study.name, "fast": study.fast, "directory": str(study.directory),
        "files": [str(p) for p in study.files], "summary": study.summary,
        "numbers": study.numbers, "provenance": study.provenance, "elapsed": study.elapsed},
        default=json_default, allow_nan=True))
    return plain


def _study_from(record: Mapping) -> StudyResult:
    return StudyResult(record["name"], record["fast"], Path(record["directory"]),
                       tuple(Path(p) for p in record["files"]), record["summary"],
                       record["numbers"], record["provenance"], record["elapsed"])


def _module_of(study: Study) -> str:
    """The study module (or package) that defines ``study``'s compute: what its report key
    digests."""
    parts = study.compute.__module__.split(".")
    prefix = ["upliftlab", "comparisons", "studies"]
    return parts[3] if parts[:3] == prefix and len(parts) > 3 else study.name


def _section_key(study: Study, module: str, fast: bool, record_sha: str | None) -> str:
    """The report's content key of ``study``'s section (module docstring: Nothing is re-run)."""
    return point_key(REPORT, f"{study.name}:run", {"fast": fast, "source": study_digest(module),
                                                  "elcentro_sha256": record_sha})


def _stored_section(study: Study, key: str, run: _Run) -> dict | None:
    """The report's record of ``study`` under ``key`` while its files are still on disk, else
    None (always None for a study that keys its whole result itself, ``own_store``)."""
    if study.own_store:
        return None
    stored = run.store.get(key)
    if stored is not None and all(Path(p).is_file() for p in stored["files"]):
        return stored
    return None


def _run_section(item: str | Study, run: _Run, record_sha: str | None, say) -> Section:
    """One section: ``item`` is a study module's name (imported now) or a Study record."""
    start = time.perf_counter()
    name = item if isinstance(item, str) else item.name
    module = item if isinstance(item, str) else _module_of(item)
    try:
        study = definition(item) if isinstance(item, str) else item
    except ModuleNotFoundError as exc:
        wanted = f"upliftlab.comparisons.studies.{item}"
        if exc.name != wanted:
            return _failed(name, name, "", start, exc)
        say(f"{name}: module {wanted} does not exist (yet)")
        return Section(name, name, "", "missing", "", time.perf_counter() - start,
                       error=f"The module {wanted} does not exist in this installation: the "
                             "study is not written yet, so this section has no results")
    except Exception as exc:  # an import error of a study under development
        return _failed(name, name, "", start, exc)
    key = _section_key(study, module, run.fast, record_sha)
    stored = _stored_section(study, key, run)
    if stored is not None:
        say(f"{study.name}: read from the store")
        return Section(study.name, study.title, study.intro, "ok", "store",
                       time.perf_counter() - start, _study_from(stored))
    say(f"{study.name}: running")
    context = Context(fast=run.fast, out=run.study_dir(study.name),
                      store=run.study_store(study, say),
                      scheduler=None if study.own_store else run.scheduler,
                      results=run.results, started=start, budget=run.budget)
    try:
        with single_threaded():
            result = run_study(study, None, context)
    except Exception as exc:
        return _failed(study.name, study.title, study.intro, start, exc)
    run.results[study.name] = result
    if not study.own_store:
        with contextlib.suppress(InputError, TypeError, ValueError):
            run.store.put(key, _study_record(result.study), {"study": REPORT,
                                                             "section": study.name,
                                                             "version": __version__})
    say(f"{study.name}: done in {time.perf_counter() - start:.1f} s")
    source = "store" if getattr(result, "reused", False) else "computed"
    return Section(study.name, study.title, study.intro, "ok", source,
                   time.perf_counter() - start, result.study, result)


def _failed(name: str, title: str, intro: str, start: float, exc: BaseException) -> Section:
    """The section of a study that failed; a full disk is not the study's failure: it ends the
    report (:func:`upliftlab.paths.disk_full`)."""
    if disk_full(exc):
        raise exc
    lines = traceback.format_exception(type(exc), exc, exc.__traceback__)
    tail = "".join(lines[-6:])
    message = f"{type(exc).__name__}: {exc}"
    return Section(name, title, intro, "error", "", time.perf_counter() - start,
                   error=f"{message}\n\n{tail}")


#: The files :func:`build_report` writes in its folder (its studies write under ``studies/``
#: and ``store/``, each in a folder of its own), and the PDF of each paper asked for
#: (:func:`pdf_name`).
REPORT_NAMES = ("report.html", "report.json")


def pdf_name(paper: str) -> str:
    """The name of the report's PDF on ``paper``, beside the page."""
    return f"report-{paper}.pdf"


def _check_papers(papers) -> tuple[str, ...]:
    """The papers to print on, each once, in their order; InputError before any work for a
    paper not in :data:`.printing.PAPERS`, or for any paper when no browser can print."""
    from .printing import PAPERS, browser, need_browser

    if isinstance(papers, (str, bytes)) or not isinstance(papers, Sequence):
        raise InputError(f"--pdf = {papers!r}: expected a list of papers "
                         f"({', '.join(PAPERS)})")
    for paper in papers:
        if not isinstance(paper, str) or paper not in PAPERS:
            raise InputError(f"--pdf = {paper!r}: expected one of {', '.join(PAPERS)}")
    if papers and browser() is None:
        need_browser()
    return tuple(dict.fromkeys(papers))


def build_report(fast: bool = False, *, out: str | Path | None = None,
                 scheduler: str | None = None, studies: Sequence[str | Study] = STUDIES,
                 progress=None, force: bool = False,
                 budget: float | None = REPORT_BUDGET, papers: Sequence[str] = ()) -> Report:
    """Run (or read from the stores) every study of ``studies`` (module names under
    ``upliftlab.comparisons``, or :class:`.protocol.Study` records; default the registry's)
    and write ``<out>/report.html`` and ``report.json``, then print the page to a PDF on each
    of ``papers`` (A4, Letter: :func:`pdf_name`). ``budget`` (s of one worker, None: no limit)
    refuses a study whose estimated cost exceeds it (its section fails with the estimate).
    Options and the output folder (a PDF of the user's at a PDF's name included) are checked
    before anything runs (:class:`InputError`). A PDF upliftlab printed here before on a paper
    not asked for now is removed: it shows the report this one replaces."""
    from ...outdir import claim

    start = time.perf_counter()
    checks.boolean("fast", fast)
    if scheduler is not None:
        scheduler = checks.scheduler_address("--scheduler", scheduler)
    if budget is not None:
        checks.positive("--budget", budget)
    papers = _check_papers(papers)
    default = Path("results") / (REPORT + ("-fast" if fast else ""))
    with claim(out, default, settings={"command": "report", "fast": fast}, force=force,
               outputs=REPORT_NAMES + tuple(pdf_name(p) for p in papers)) as folder:
        report = _build(fast, folder, scheduler, studies, progress, start, budget, papers)
    return report


def _build(fast, folder, scheduler, studies, progress, start, budget, papers) -> Report:
    out = folder.path
    os.environ.setdefault("MPLBACKEND", "Agg")
    say = progress or (lambda message: None)
    run = _Run(fast, out, Store(out / "store"), scheduler, budget)
    record_sha = _record_sha()
    estimate = estimate_report(run, studies, record_sha)
    say(estimate.text())
    sections = []
    for item in studies:
        sections.append(_run_section(item, run, record_sha, say))
        say(estimate.progress(sections, time.perf_counter() - start))
    sections = tuple(sections)
    verification = next((s for s in sections if s.name == "verification"), None)
    passed = bool(verification and verification.status == "ok"
                  and verification.study.numbers.get("passed"))
    elapsed = time.perf_counter() - start
    failed = [s.name for s in sections if s.status != "ok"]
    page = render_html(sections, fast=fast, passed=passed, elapsed=elapsed)
    folder.start_writing()
    html, data = REPORT_NAMES
    path = write_text(out / html, page)
    summary = write_text(out / data, json.dumps({
        "passed": passed, "fast": fast, "elapsed_s": elapsed, "html": str(path),
        "sections": {s.name: {"status": s.status, "source": s.source,
                                    "seconds": s.seconds,
                                    "error": s.error.split("\n", 1)[0]}
                     for s in sections},
        "provenance": provenance(study=REPORT, fast=fast)}, indent=2, default=str) + "\n")
    pdfs = tuple(_print(path, out / pdf_name(paper), paper, say) for paper in papers)
    _remove_stale_pdfs(folder, papers)
    ok = passed and not failed
    if ok:
        folder.complete([path, summary, *pdfs])
    return Report(path, sections, passed, ok, elapsed, pdfs)


def _print(page: Path, pdf: Path, paper: str, say) -> Path:
    from .printing import print_pdf

    say(f"printing {pdf.name}")
    return print_pdf(page, pdf, paper)


def _remove_stale_pdfs(folder, papers) -> None:
    """Remove the PDFs upliftlab printed in ``folder`` before on a paper not in ``papers``."""
    from .printing import PAPERS

    for paper in PAPERS:
        if paper not in papers:
            folder.remove_own(pdf_name(paper))


# ---------------------------------------------------------------------------------------------
# The cost estimate, made before any section runs
# ---------------------------------------------------------------------------------------------

#: The documented rate of a section whose study estimates nothing itself: its wall time (s) when
#: computed from empty stores, (fast, full), on the project's shared 2-core machine on 2026-11-28
#: with the numba kernels cached. Fast: ``upliftlab report --fast`` into an empty folder (140.7 s
#: in all); full: :func:`build_report` of two or three sections at a time into empty folders,
#: at the lowest priority (nice 19) beside other jobs, so rather long than short (the
#: verification and the uplift zone; then fixed base, two-spring and paper; then Winkler against
#: the continuum and speed against error).
SECTION_SECONDS = {"verification": (11.9, 49.2), "two_spring_equivalence": (34.7, 425.2),
                   "winkler_vs_continuum": (25.9, 420.8), "speed_vs_error": (27.5, 1830.0),
                   "fixed_vs_uplift": (5.5, 11.2), "paper": (0.3, 0.2),
                   "uplift_zone": (13.5, 134.6)}
#: The Winkler map beyond the continuum runs its own estimate counts (s; fast, full): the beds'
#: runs, the analysis, the figures and the explicit loop's compilation. Fast: the fast map again
#: with every continuum run stored (18.5 s); full: the kept build, 18 minutes (README).
MAP_REST_SECONDS = (18.5, 1080.0)
#: A section read back from the report's store (s): 0.004–0.19 s measured per section.
STORE_SECONDS = 0.2


@dataclass(frozen=True)
class SectionEstimate:
    """One section's estimated wall time ``seconds`` (s), made before the report starts, and
    its ``source``: where the number comes from."""

    name: str
    seconds: float
    source: str


@dataclass(frozen=True)
class ReportEstimate:
    """The report's estimate, one :class:`SectionEstimate` per section in the report's order."""

    sections: tuple[SectionEstimate, ...]

    @property
    def seconds(self) -> float:
        """The whole report (s): the sum of the sections'."""
        return sum(s.seconds for s in self.sections)

    def text(self) -> str:
        """The estimate in one line: the total, then each section with its source."""
        parts = "; ".join(f"{s.name} {s.seconds:.0f} s ({s.source})" for s in self.sections)
        return (f"estimated {self.seconds:.0f} s{_longer(self.seconds)} of wall time before any "
                f"section runs: {parts}")

    def progress(self, done: Sequence[Section], elapsed: float) -> str:
        """One line once ``done`` (the sections so far, in order) has grown by one: the last
        section's time against its estimate, the ``elapsed`` wall time (s) and the estimates of
        the sections still to run as the time left, with the clock time it points to."""
        last, planned = done[-1], self.sections[len(done) - 1]
        left = sum(s.seconds for s in self.sections[len(done):])
        eta = time.strftime("%H:%M:%S", time.localtime(time.time() + left))
        return (f"{len(done)}/{len(self.sections)} sections done ({last.name}: "
                f"{last.seconds:.1f} s, estimated {planned.seconds:.0f} s); {elapsed:.0f} s "
                f"elapsed, about {left:.0f} s left by the estimates (ETA {eta})")


def _longer(seconds: float) -> str:
    """`` (x min)`` or `` (x h)`` beside a number of seconds from two minutes on, else ``""``."""
    minutes = seconds / 60
    if minutes < 2:
        return ""
    if minutes < 120:
        return f" ({minutes:.{1 if minutes < 10 else 0}f} min)"
    return f" ({minutes / 60:.1f} h)"


def estimate_report(run: _Run, studies: Sequence[str | Study],
                    record_sha: str | None) -> ReportEstimate:
    """Every section's estimate, before any of them runs (nothing is run or written)."""
    return ReportEstimate(tuple(_estimate_section(item, run, record_sha) for item in studies))


def _estimate_section(item: str | Study, run: _Run, record_sha: str | None) -> SectionEstimate:
    """A section's estimate: a read when the report's store holds it, else the study's own
    estimate (the Winkler map's), else its documented rate (:data:`SECTION_SECONDS`)."""
    name = item if isinstance(item, str) else item.name
    try:
        study = definition(item) if isinstance(item, str) else item
    except Exception as exc:  # missing or failing: its section says so, and costs nothing
        return SectionEstimate(name, 0.0, f"not run: {type(exc).__name__}")
    module = item if isinstance(item, str) else _module_of(item)
    key = _section_key(study, module, run.fast, record_sha)
    if _stored_section(study, key, run) is not None or _verification_stored(study, run,
                                                                            record_sha):
        return SectionEstimate(study.name, STORE_SECONDS, "read from the report's store")
    if study.name == "winkler_map":
        return _map_estimate(study, run)
    rate = SECTION_SECONDS.get(study.name, (None, None))[0 if run.fast else 1]
    if rate is None:
        return SectionEstimate(study.name, 0.0, f"no estimate: never timed in "
                                                f"{'fast' if run.fast else 'full'} mode")
    return SectionEstimate(study.name, rate, "its measured rate")


def _verification_stored(study: Study, run: _Run, record_sha: str | None) -> bool:
    """Whether the report's store holds the verification's own record, under the key its
    :func:`.verification.workflow.compute_or_read` makes (it keys its whole result itself)."""
    if study.name != "verification" or not study.own_store:
        return False
    from ..studies.verification import STUDY as VERIFICATION, source_digest

    params = {"fast": bool(run.fast), "elcentro_sha256": record_sha, "source": source_digest()}
    return run.store.has(point_key(VERIFICATION, "upliftlab.comparisons.verification:compute",
                                   params))


def _map_estimate(study: Study, run: _Run) -> SectionEstimate:
    """The Winkler map: its own estimate of the continuum runs not yet in the store the report
    will give it (:func:`.winkler_map.estimate_map`), plus :data:`MAP_REST_SECONDS`; nothing
    when it will refuse them (over the report's ``--budget``, or its motions missing)."""
    import tempfile

    from ...paths import output_root
    from ..beds import bed_names
    from ..studies.winkler_map import (FAST_GRID, FAST_OPTIONS, FULL_GRID, FULL_OPTIONS,
                                       estimate_map, study_motions)

    grid, options = (FAST_GRID, FAST_OPTIONS) if run.fast else (FULL_GRID, FULL_OPTIONS)
    store = (run.study_store(study, lambda message: None)
             or Store(run.study_dir(study.name) / "store"))
    try:
        with tempfile.TemporaryDirectory() as folder, output_root(folder):  # upliftlab's own
            motions = study_motions(grid, options, Path(folder))  # the records it would export
            estimate = estimate_map(grid, options, bed_names(options), motions, store)
    except InputError as exc:
        return SectionEstimate(study.name, 0.0, f"refused before any run: {exc}")
    if run.budget is not None and estimate.seconds > run.budget:
        return SectionEstimate(study.name, 0.0, f"refused before any run: its continuum runs "
                                                f"are estimated at {estimate.seconds:.0f} s, "
                                                f"over --budget = {run.budget:g} s")
    rest = MAP_REST_SECONDS[0 if run.fast else 1]
    return SectionEstimate(study.name, estimate.seconds + rest,
                           f"its own estimate of {estimate.runs} continuum runs to make, "
                           f"{estimate.seconds:.0f} s, and {rest:.0f} s measured for its beds "
                           "and figures")
