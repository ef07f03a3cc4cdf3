"""One self-contained HTML report of every study: ``upliftlab report [--fast] [--out DIR]``.

The report is a single file, ``<out>/report.html``: plots are embedded as SVG and the rendered
soil frames as PNG (:mod:`.report_figures`), each figure numbered with a caption computed from
its data (:mod:`.figure_record`); the style sheets (screen and print) are inline; there are no
external links or fonts, and one inline script, the uplift animation's frame slider
(:mod:`.report_animation`), so it can be mailed or archived as it is and opened from disk
offline. :mod:`.report_print` prints it to PDF on A4 or Letter. Beside it ``report.json``
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

**Cost.** A study that estimates its runs before it starts them (the Winkler map) is refused
above ``--budget`` (s of one worker, :data:`REPORT_BUDGET` by default): its section fails with
the estimate and the rest of the report is built. In a full build from a checkout the map
resumes the continuum runs kept with the repository (:attr:`.protocol.Study.kept_store`), so
only the runs not kept count; a fast build never touches them.

**Threads.** The studies run one after another in this process with BLAS limited to one thread
(:func:`.verification.single_threaded`), as the sweeps' worker processes are: on a loaded
two-core machine a two-thread BLAS under the continuum's small dense kernels ran the fast
Prandtl check 3–6 times slower.

**Exit status** (:func:`main`): 0 when the report is written, every section has its results
and every verification row passes (skipped rows, e.g. fast mode's costly continuum levels, do
not fail); 1 when the report is written but a section failed or is missing, or a verification
row fails: a report with a failed section is a failed command, whatever the section (the
failures are listed in the report's status box and on stderr); 2 for bad options (nothing
written, nothing run).

**Output folder.** ``--out`` is checked before any section runs (:func:`upliftlab.outdir.claim`:
not a file, writable, not being written by another report), stale temporary files of a killed
report are removed, and ``upliftlab-run.json`` is written last, naming the files, when every
section has its results.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import sys
import time
import traceback
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .. import __version__, checks
from ..checks import InputError
from ..log import logger
from ..results import provenance, write_text
from .protocol import CHECKOUT, Context, EXIT_FAILED, EXIT_INPUT, EXIT_OK, Study, run_study
from .registry import STUDIES, definition
from .report_html import Section, render_html
from .report_markdown import markdown_to_html
from .store import Store, point_key
from .study import StudyResult, json_default
from .uplift_zone import continuum_pushover
from .verification import single_threaded

__all__ = ["STUDIES", "Section", "Report", "build_report", "markdown_to_html", "study_digest",
           "continuum_pushover", "EXIT_OK", "EXIT_FAILED", "EXIT_VERIFICATION", "EXIT_INPUT"]

EXIT_VERIFICATION = EXIT_FAILED  # the earlier name of the same exit code
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
    """The report: its ``path``, the ``sections``, whether the verification ``passed`` and
    the exit ``code``."""

    path: Path
    sections: tuple[Section, ...]
    passed: bool
    code: int
    elapsed: float

    def section(self, name: str) -> Section:
        return next(s for s in self.sections if s.name == name)


_SHARED = ("study", "store", "sweep", "protocol")


def _sources(name: str) -> list[Path]:
    """The files of comparison module ``name``: ``name.py``, or every ``.py`` of the package."""
    here = Path(__file__).parent
    if (here / name).is_dir():
        return sorted((here / name).glob("*.py"))
    return [here / f"{name}.py"] if (here / f"{name}.py").is_file() else []


def _siblings(name: str, seen: set[str] | None = None) -> set[str]:
    """``name`` and the comparison modules it imports, transitively (``from .x import`` in a
    module, ``from ..x import`` in a study package)."""
    seen = set() if seen is None else seen
    files = _sources(name)
    if name in seen or not files:
        return seen
    seen.add(name)
    package = files[0].parent.name == name
    pattern = (r"from \.\.(\w+) import|from \.\. import (\w+)" if package
               else r"from \.(\w+) import|from \. import (\w+)")
    for path in files:
        text = path.read_text(encoding="utf-8", errors="replace")
        for other in re.findall(pattern, text):
            _siblings(other[0] or other[1], seen)
    return seen


def study_digest(name: str) -> str:
    """SHA-256 of the sources study module ``name``'s numbers depend on: the library's (see
    :func:`.verification.source_digest`), the study's module (or package) and the comparison
    modules it imports. Other studies' modules stay out, so editing one study re-runs only
    that one."""
    from .verification import source_digest

    names = (_siblings(name) - {"report", "registry", "verification"}) | set(_SHARED)
    return source_digest([p for n in sorted(names) for p in _sources(n)])


def _record_sha() -> str | None:
    from ..motions import ELCENTRO, find_motion
    from .study import file_sha256

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
    """The comparison module (or package) that defines ``study``'s compute: what its report key
    digests."""
    parts = study.compute.__module__.split(".")
    return parts[2] if parts[:2] == ["upliftlab", "comparisons"] and len(parts) > 2 else study.name


def _run_section(item: str | Study, run: _Run, record_sha: str | None, say) -> Section:
    """One section: ``item`` is a study module's name (imported now) or a Study record."""
    start = time.perf_counter()
    name = item if isinstance(item, str) else item.name
    module = item if isinstance(item, str) else _module_of(item)
    try:
        study = definition(item) if isinstance(item, str) else item
    except ModuleNotFoundError as exc:
        wanted = f"{__package__}.{item}"
        if exc.name != wanted:
            return _failed(name, name, "", start, exc)
        say(f"{name}: module {wanted} does not exist (yet)")
        return Section(name, name, "", "missing", "", time.perf_counter() - start,
                       error=f"The module {wanted} does not exist in this installation: the "
                             "study is not written yet, so this section has no results")
    except Exception as exc:  # an import error of a study under development
        return _failed(name, name, "", start, exc)
    key = point_key(REPORT, f"{study.name}:run", {"fast": run.fast,
                                                  "source": study_digest(module),
                                                  "elcentro_sha256": record_sha})
    if not study.own_store:
        stored = run.store.get(key)
        if stored is not None and all(Path(p).is_file() for p in stored["files"]):
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
    lines = traceback.format_exception(type(exc), exc, exc.__traceback__)
    tail = "".join(lines[-6:])
    message = f"{type(exc).__name__}: {exc}"
    return Section(name, title, intro, "error", "", time.perf_counter() - start,
                   error=f"{message}\n\n{tail}")


def build_report(fast: bool = False, *, out: str | Path | None = None,
                 scheduler: str | None = None, studies: Sequence[str | Study] = STUDIES,
                 progress=None, force: bool = False,
                 budget: float | None = REPORT_BUDGET) -> Report:
    """Run (or read from the stores) every study of ``studies`` (module names under
    ``upliftlab.comparisons``, or :class:`.protocol.Study` records; default the registry's)
    and write ``<out>/report.html`` and ``report.json``. ``budget`` (s of one worker, None: no
    limit) refuses a study whose estimated cost exceeds it (its section fails with the
    estimate). Options and the output folder are checked before anything runs
    (:class:`InputError`)."""
    from ..outdir import claim

    start = time.perf_counter()
    checks.boolean("fast", fast)
    if scheduler is not None and (not isinstance(scheduler, str) or not scheduler.strip()):
        raise InputError(f"--scheduler = {scheduler!r}: expected a Dask scheduler address such "
                         "as tcp://host:8786")
    if budget is not None:
        checks.positive("--budget", budget)
    default = Path("results") / (REPORT + ("-fast" if fast else ""))
    with claim(out, default, settings={"command": "report", "fast": fast},
               force=force) as folder:
        report = _build(fast, folder, scheduler, studies, progress, start, budget)
    return report


def _build(fast, folder, scheduler, studies, progress, start, budget) -> Report:
    out = folder.path
    os.environ.setdefault("MPLBACKEND", "Agg")
    say = progress or (lambda message: None)
    run = _Run(fast, out, Store(out / "store"), scheduler, budget)
    record_sha = _record_sha()
    sections = tuple(_run_section(item, run, record_sha, say) for item in studies)
    verification = next((s for s in sections if s.name == "verification"), None)
    passed = bool(verification and verification.status == "ok"
                  and verification.study.numbers.get("passed"))
    elapsed = time.perf_counter() - start
    failed = [s.name for s in sections if s.status != "ok"]
    page = render_html(sections, fast=fast, passed=passed, elapsed=elapsed)
    folder.start_writing()
    path = write_text(out / "report.html", page)
    summary = write_text(out / "report.json", json.dumps({
        "passed": passed, "fast": fast, "elapsed_s": elapsed, "html": str(path),
        "sections": {s.name: {"status": s.status, "source": s.source,
                                    "seconds": s.seconds,
                                    "error": s.error.split("\n", 1)[0]}
                     for s in sections},
        "provenance": provenance(study=REPORT, fast=fast)}, indent=2, default=str) + "\n")
    ok = passed and not failed
    if ok:
        folder.complete([path, summary])
    return Report(path, sections, passed, EXIT_OK if ok else EXIT_FAILED, elapsed)


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def add_arguments(parser) -> None:
    """The options of ``upliftlab report``."""
    parser.add_argument("--fast", action="store_true",
                        help="small grids and coarse meshes (about a minute)")
    parser.add_argument("--out", help="output directory (default results/report[-fast])")
    parser.add_argument("--scheduler", help="Dask scheduler address for the studies' sweeps")
    parser.add_argument("--force", action="store_true", help="replace a different run in --out")
    parser.add_argument("--budget", default=None, metavar="SECONDS",
                        help="refuse a study whose continuum runs are estimated above this many "
                             f"seconds of one worker (default {REPORT_BUDGET:g}; the Winkler "
                             "map estimates its runs, its kept runs cost nothing)")


def command(args) -> int:
    """``upliftlab report``: build the report; the exit status of the module docstring."""

    def say(message):
        logger("report").info(f"upliftlab report: {message}")

    from ..cli import number

    budget = number("--budget", getattr(args, "budget", None), high=1e9)
    report = build_report(args.fast, out=args.out, scheduler=args.scheduler, progress=say,
                          force=getattr(args, "force", False),
                          budget=REPORT_BUDGET if budget is None else budget)
    failed = [s for s in report.sections if s.status != "ok"]
    for s in failed:
        say(f"section {s.name}: {s.status}: {s.error.split(chr(10), 1)[0]}")
    verdict = "verification passed" if report.passed else "verification FAILED"
    sections = (f"; {len(failed)} of {len(report.sections)} sections FAILED "
                f"({', '.join(s.name for s in failed)})" if failed else "")
    print(f"upliftlab report: wrote {report.path} in {report.elapsed:.1f} s; {verdict}{sections}")
    return report.code


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m upliftlab.comparisons.report [--fast] [--out DIR] [--scheduler ADDR]``"""
    import argparse

    parser = argparse.ArgumentParser(prog=f"python -m upliftlab.comparisons.{REPORT}",
                                     description=__doc__.splitlines()[0])
    add_arguments(parser)
    args = parser.parse_args(argv)
    try:
        return command(args)
    except InputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_INPUT
