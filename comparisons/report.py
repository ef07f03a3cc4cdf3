"""One self-contained HTML report of every study: ``upliftlab report [--fast] [--out DIR]``.

The report is a single file, ``<out>/report.html``: figures are embedded as base64 PNG, the
style sheet is inline, and there are no scripts, external links or fonts, so it can be mailed
or archived as it is. Beside it ``report.json`` records what each section did.

Sections, in order: the verification anchors (measured error, tolerance, pass/fail) and the
observed convergence orders (:mod:`.verification`); the two-spring equivalence maps and tables
(:mod:`.two_spring_equivalence`); Winkler against the continuum (:mod:`.winkler_vs_continuum`);
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

import base64
import contextlib
import html
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
from ..results import provenance, write_text
from .protocol import EXIT_FAILED, EXIT_INPUT, EXIT_OK, Context, Study, run_study
from .registry import STUDIES, definition
from .store import Store, point_key
from .study import StudyResult, json_default
from .uplift_zone import continuum_pushover
from .verification import single_threaded

__all__ = ["STUDIES", "Section", "Report", "build_report", "markdown_to_html", "study_digest",
           "continuum_pushover",
           "EXIT_OK", "EXIT_FAILED", "EXIT_VERIFICATION", "EXIT_INPUT"]

EXIT_VERIFICATION = EXIT_FAILED  # the earlier name of the same exit code
REPORT = "report"


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
    results: dict = field(default_factory=dict)

    def study_dir(self, name: str) -> Path:
        return self.out / "studies" / (name + ("-fast" if self.fast else ""))


@dataclass(frozen=True)
class Section:
    """What one section shows: its ``name``, ``title`` and ``intro``; ``status`` ok, missing
    (module absent) or error; ``source`` computed or store; the study record (``study``) or
    the ``error`` text."""

    name: str
    title: str
    intro: str
    status: str
    source: str
    seconds: float
    study: StudyResult | None = None
    result: object = None
    error: str = ""


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


def _run_section(item: str | Study, run: _Run, record_sha: str | None, say) -> Section:
    """One section: ``item`` is a study module's name (imported now) or a Study record."""
    start = time.perf_counter()
    name = item if isinstance(item, str) else item.name
    module = item if isinstance(item, str) else item.compute.__module__.rsplit(".", 1)[-1]
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
                      store=run.store if study.own_store else None,
                      scheduler=None if study.own_store else run.scheduler,
                      results=run.results, started=start)
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
                 progress=None, force: bool = False) -> Report:
    """Run (or read from the stores) every study of ``studies`` (module names under
    ``upliftlab.comparisons``, or :class:`.protocol.Study` records; default the registry's)
    and write ``<out>/report.html`` and ``report.json``. Options and the output folder are
    checked before anything runs (:class:`InputError`)."""
    from ..outdir import claim

    start = time.perf_counter()
    checks.boolean("fast", fast)
    if scheduler is not None and (not isinstance(scheduler, str) or not scheduler.strip()):
        raise InputError(f"--scheduler = {scheduler!r}: expected a Dask scheduler address such "
                         "as tcp://host:8786")
    default = Path("results") / (REPORT + ("-fast" if fast else ""))
    with claim(out, default, settings={"command": "report", "fast": fast},
               force=force) as folder:
        report = _build(fast, folder, scheduler, studies, progress, start)
    return report


def _build(fast, folder, scheduler, studies, progress, start) -> Report:
    out = folder.path
    os.environ.setdefault("MPLBACKEND", "Agg")
    say = progress or (lambda message: None)
    run = _Run(fast, out, Store(out / "store"), scheduler)
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
# Markdown to HTML (the subset the studies write)
# ---------------------------------------------------------------------------------------------


def _inline(text: str) -> str:
    """Escape, then `code`, **bold**, *italic*; links keep their text only (no references)."""
    parts = re.split(r"(`[^`]+`)", text)
    out = []
    for part in parts:
        if len(part) > 1 and part.startswith("`") and part.endswith("`"):
            out.append(f"<code>{html.escape(part[1:-1])}</code>")
            continue
        part = re.sub(r"\[([^\]]+)\]\([^)]*\)", r"\1", part)
        part = html.escape(part, quote=False)
        part = re.sub(r"\*\*(.+?)\*\*", _strong, part)
        part = re.sub(r"(?<![\w*])\*(?!\s)([^*]+?)(?<!\s)\*(?![\w*])", r"<em>\1</em>", part)
        out.append(part)
    return "".join(out)


def _strong(match) -> str:
    """Bold text; a verdict ("Verdict: holds.") is coloured."""
    text = match.group(1)
    verdict = re.match(r"Verdict: (.*?)\.?$", text)
    if verdict:
        kind = {"holds": "ok", "does not hold": "bad"}.get(verdict.group(1), "skip")
        return f'<strong class="{kind}">{text}</strong>'
    return f"<strong>{text}</strong>"


def _cells(line: str) -> list[str]:
    line = line.strip()
    if line.startswith("|"):
        line = line[1:]
    if line.endswith("|") and not line.endswith("\\|"):
        line = line[:-1]
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", line)]


def _fit(cells: list[str], columns: int) -> list[str]:
    """Mend a row split on the bars of an absolute value (``| |error| |`` gives '', 'error',
    ''): merge such triples while the row has more cells than the table has columns."""
    cells = list(cells)
    k = 0
    while len(cells) > columns and k + 2 < len(cells):
        if cells[k] == "" and cells[k + 1] and cells[k + 2] == "":
            cells[k:k + 3] = [f"|{cells[k + 1]}|"]
        else:
            k += 1
    return cells


_RULE = re.compile(r"^\s*\|?\s*:?-{3,}:?\s*(\|\s*:?-{3,}:?\s*)*\|?\s*$")


def _table(lines: list[str]) -> str:
    columns = len(_cells(lines[1]))
    head, body = _fit(_cells(lines[0]), columns), [_fit(_cells(x), columns) for x in lines[2:]]
    rows = ["<tr>" + "".join(f"<th>{_inline(c)}</th>" for c in head) + "</tr>"]
    for cells in body:
        rows.append("<tr>" + "".join(f"<td>{_badge(_inline(c))}</td>" for c in cells) + "</tr>")
    return ('<div class="scroll"><table>' + "<thead>" + rows[0] + "</thead><tbody>"
            + "".join(rows[1:]) + "</tbody></table></div>")


def _badge(cell: str) -> str:
    """Colour a cell that is only a verdict."""
    plain = re.sub(r"<[^>]+>", "", cell).strip().lower()
    if plain in ("pass", "holds"):
        return f'<span class="ok">{cell}</span>'
    if plain in ("fail", "does not hold"):
        return f'<span class="bad">{cell}</span>'
    return cell


def markdown_to_html(text: str, shift: int = 0) -> str:
    """A small Markdown subset as HTML: ATX headings (levels moved down by ``shift``),
    paragraphs, ``-``/``*`` and numbered lists, pipe tables, fenced code, inline code, bold,
    italics. Raw HTML is escaped; links keep their text only."""
    lines = text.replace("\r\n", "\n").split("\n")
    out: list[str] = []
    para: list[str] = []
    i = 0

    def flush():
        if para:
            out.append(f"<p>{_inline(' '.join(x.strip() for x in para))}</p>")
            para.clear()

    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        if stripped.startswith("```"):
            flush()
            j = i + 1
            while j < len(lines) and not lines[j].strip().startswith("```"):
                j += 1
            out.append("<pre><code>" + html.escape("\n".join(lines[i + 1:j])) + "</code></pre>")
            i = j + 1
            continue
        heading = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if heading:
            flush()
            level = min(6, len(heading.group(1)) + shift)
            out.append(f"<h{level}>{_inline(heading.group(2))}</h{level}>")
            i += 1
            continue
        if stripped.startswith("|") and i + 1 < len(lines) and _RULE.match(lines[i + 1]):
            flush()
            j = i + 2
            while j < len(lines) and lines[j].strip().startswith("|"):
                j += 1
            out.append(_table(lines[i:j]))
            i = j
            continue
        item = re.match(r"^\s*([-*]|\d+[.)])\s+(.*)$", line)
        if item:
            flush()
            ordered = item.group(1)[0].isdigit()
            items, j = [], i
            while j < len(lines):
                m = re.match(r"^\s*([-*]|\d+[.)])\s+(.*)$", lines[j])
                if m and m.group(1)[0].isdigit() == ordered:
                    items.append(m.group(2))
                elif lines[j].strip() and lines[j].startswith(("  ", "\t")) and items:
                    items[-1] += " " + lines[j].strip()
                else:
                    break
                j += 1
            tag = "ol" if ordered else "ul"
            out.append(f"<{tag}>" + "".join(f"<li>{_badge(_inline(x))}</li>" for x in items)
                       + f"</{tag}>")
            i = j
            continue
        if not stripped:
            flush()
        else:
            para.append(line)
        i += 1
    flush()
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------
# HTML
# ---------------------------------------------------------------------------------------------

_CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;
 margin:0;background:#f4f5f7;color:#1d2330;line-height:1.45;font-size:15px}
main{max-width:1180px;margin:0 auto;padding:24px 28px 60px;background:#fff;
 box-shadow:0 0 12px rgba(0,0,0,.06)}
h1{font-size:26px;margin:0 0 4px}h2{font-size:21px;margin:36px 0 8px;padding-top:10px;
 border-top:2px solid #dde1e8}h3{font-size:17px;margin:22px 0 6px}h4,h5,h6{font-size:15px;
 margin:16px 0 4px}
p{margin:6px 0 10px}.meta{color:#5a6272;font-size:13px}
.scroll{overflow-x:auto;margin:8px 0 14px}
table{border-collapse:collapse;font-size:12.5px;width:100%}
th,td{border:1px solid #d6dae1;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#eef1f5;position:sticky;top:0}tbody tr:nth-child(even){background:#fafbfc}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
td.tol{white-space:nowrap}
.ok{color:#12733a;font-weight:600}.bad{color:#b3261e;font-weight:700}.skip{color:#8a6d00}
tr.fail td{background:#fdecea}tr.skipped td{color:#6b6f78;background:#fffbea}
.status{border:1px solid #d6dae1;border-left:6px solid #12733a;padding:10px 14px;
 margin:14px 0;background:#f6fbf8}.status.failing{border-left-color:#b3261e;background:#fdf3f2}
.notice{border-left:5px solid #c98a00;background:#fff8e6;padding:8px 12px;margin:10px 0}
.error{border-left:5px solid #b3261e;background:#fdf3f2;padding:8px 12px;margin:10px 0}
pre{background:#f3f4f6;padding:8px 10px;overflow-x:auto;font-size:12px;white-space:pre-wrap}
code{font-family:"DejaVu Sans Mono",Menlo,Consolas,monospace;font-size:12.5px}
figure{margin:12px 0 18px}figure img{max-width:100%;height:auto;border:1px solid #e3e6eb}
figcaption{font-size:12px;color:#5a6272}
nav ol{columns:2;font-size:14px;margin:6px 0}small.note{color:#5a6272}
.grid2{display:grid;grid-template-columns:1fr 1fr;gap:14px}
"""


def _png(path: Path) -> str:
    data = base64.b64encode(Path(path).read_bytes()).decode("ascii")
    return f"data:image/png;base64,{data}"


def _figures(study: StudyResult, pair: bool = False) -> str:
    pngs = [Path(p) for p in study.files if str(p).endswith(".png") and Path(p).is_file()]
    if not pngs:
        return ""
    blocks = []
    for p in pngs:
        caption = html.escape(p.relative_to(study.directory).as_posix()
                              if p.is_relative_to(study.directory) else p.name)
        blocks.append(f'<figure><img alt="{caption}" src="{_png(p)}">'
                      f"<figcaption>{caption}</figcaption></figure>")
    if pair and len(blocks) == 2:
        return '<div class="grid2">' + "".join(blocks) + "</div>"
    return "\n".join(blocks)


def _verification_tables(study: StudyResult) -> str:
    from .verification import Order, Row, error_text, fmt

    numbers = study.numbers
    rows = [Row(**r) for r in numbers["rows"]]
    orders = [Order(**o) for o in numbers["orders"]]
    counts = numbers["counts"]
    mark = {"pass": '<span class="ok">pass</span>', "fail": '<span class="bad">FAIL</span>',
            "skipped": '<span class="skip">skipped</span>'}
    head = ('<p>A reference "anchor §N" is section N of the appendix <a href="#anchors">'
            "the verification anchors</a> at the end of this report.</p>"
            f"<p>{counts['pass']} pass, {counts['fail']} fail, {counts['skipped']} skipped "
            f"(rows and orders). Computed {html.escape(str(numbers['computed_utc']))} in "
            f"{numbers['compute_seconds']:.1f} s"
            + (", read from the store: nothing was recomputed." if numbers.get("reused")
               else ".")
            + " Errors are relative (measured/reference − 1) unless marked abs; a bound row "
            "shows the measured value itself.</p>")
    if study.fast:
        head += ('<p class="notice">Fast mode: the costly continuum levels (Prandtl on 16 '
                 "elements across B, its Richardson extrapolation and observed order) are "
                 "skipped and marked so; Prandtl is checked on 8 across with its own 5 % "
                 "tolerance.</p>")
    table = ['<div class="scroll"><table><thead><tr><th>group</th><th>quantity</th>'
             "<th>reference</th><th>measured</th><th>expected</th><th>error</th>"
             "<th>tolerance</th><th>result</th></tr></thead><tbody>"]
    for r in rows:
        note = f'<br><small class="note">{html.escape(r.note)}</small>' if r.note else ""
        table.append(f'<tr class="{r.status}"><td>{r.group}</td><td>{html.escape(r.quantity)}'
                     f"{note}</td><td>{html.escape(r.reference)}</td>"
                     f'<td class="num">{fmt(r.measured)}</td><td class="num">'
                     f"{fmt(r.expected)}</td>"
                     f'<td class="num">{html.escape(error_text(r))}</td>'
                     f'<td class="tol">{html.escape(r.tolerance)}</td>'
                     f"<td>{mark[r.status]}</td></tr>")
    table.append("</tbody></table></div>")
    order_html = ['<div class="scroll"><table><thead><tr><th>group</th><th>case</th>'
                  "<th>method</th><th>steps (Δt in s, or h/B)</th><th>observed order</th>"
                  "<th>expected</th><th>band</th><th>result</th></tr></thead><tbody>"]
    for o in orders:
        steps = ", ".join(f"{s:g}" for s in o.steps) or "—"
        slope = "—" if o.slope is None else f"{o.slope:.2f}"
        note = f'<br><small class="note">{html.escape(o.note)}</small>' if o.note else ""
        order_html.append(
            f'<tr class="{o.status}"><td>{o.group}</td><td>{html.escape(o.case)}</td>'
            f"<td>{html.escape(o.method)}</td><td>{steps}</td>"
            f'<td class="num">{slope}</td><td>{html.escape(o.expected)}</td>'
            f"<td>[{o.low:g}, {o.high:g}]</td><td>{mark[o.status]}{note}</td></tr>")
    order_html.append("</tbody></table></div>")
    return (head + "".join(table) + '<h2 id="orders">Observed convergence orders</h2>'
            "<p>Slope of log(error) against log(step), fitted by least squares "
            "(np.polyfit): the reduced integrators against the matrix exponential (smooth, "
            "bonded) and against the event stepper at Δt = 25 µs (the uplifting wall); the "
            "continuum against the closed forms under mesh refinement.</p>"
            + "".join(order_html))


def _section_html(s: Section) -> str:
    parts = [f'<h2 id="{s.name}">{html.escape(s.title)}</h2>',
             f"<p>{html.escape(s.intro)}</p>" if s.intro else ""]
    if s.status == "missing":
        return "".join(parts) + f'<p class="notice">{html.escape(s.error)}</p>'
    if s.status == "error":
        first, _, rest = s.error.partition("\n")
        return "".join(parts) + (f'<div class="error"><p><strong>This study failed:</strong> '
                                 f"{html.escape(first)}</p><pre>{html.escape(rest.strip())}"
                                 "</pre></div>")
    study = s.study
    where = ("read from the store (no study was re-run)" if s.source == "store"
             else f"computed in {s.seconds:.1f} s")
    parts.append(f'<p class="meta">Output: <code>{html.escape(str(study.directory))}</code>; '
                 f"{where}.</p>")
    if s.name == "verification":
        return "".join(parts) + _verification_tables(study)
    parts.append(markdown_to_html(_without_title(study.summary), shift=2))
    parts.append(_figures(study, pair=s.name == "uplift_zone"))
    return "".join(parts)


def anchors_text() -> str:
    """The verification anchors (``upliftlab/docs/anchors.md``, shipped with the package): the
    closed forms that the verification table's "anchor §N" references name."""
    from importlib import resources

    return resources.files("upliftlab").joinpath("docs/anchors.md").read_text(encoding="utf-8")


def _anchors_appendix() -> str:
    """The anchors as the report's last section, so that the report names no document it does
    not contain."""
    return ('<h2 id="anchors">Appendix: the verification anchors</h2>'
            '<p class="meta">"anchor §N" in the tables refers to the sections below.</p>'
            + markdown_to_html(_without_title(anchors_text()), shift=1))


def _without_title(markdown: str) -> str:
    """The summary without its first ``# `` heading (the section has its own)."""
    lines = markdown.lstrip().split("\n")
    return "\n".join(lines[1:]) if lines and lines[0].startswith("# ") else markdown


def render_html(sections: Sequence[Section], *, fast: bool, passed: bool,
                elapsed: float) -> str:
    """The whole page."""
    prov = provenance()
    problems = [s for s in sections if s.status != "ok"]
    status_lines = [f"<strong>Verification {'passed' if passed else 'FAILED'}.</strong>"]
    verification = next((s for s in sections if s.name == "verification"), None)
    if verification is not None and verification.status == "ok":
        n = verification.study.numbers["counts"]
        status_lines.append(f"{n['pass']} anchors and orders pass, {n['fail']} fail, "
                            f"{n['skipped']} skipped.")
        failures = verification.study.numbers.get("failures", [])
        if failures:
            status_lines.append("<br>Failing: " + html.escape("; ".join(failures)))
    stored = sum(s.source == "store" for s in sections)
    status_lines.append(f"<br>{len(sections) - len(problems)} of {len(sections)} sections have "
                        f"results ({stored} read from the stores, "
                        f"{sum(s.source == 'computed' for s in sections)} computed now).")
    for s in problems:
        kind = "missing" if s.status == "missing" else "failed"
        status_lines.append(f"<br>Section “{html.escape(s.title)}”: {kind} "
                            f"({html.escape(s.error.split(chr(10), 1)[0][:200])}).")
    items = []
    for s in sections:
        flag = "" if s.status == "ok" else f' <small class="note">({s.status})</small>'
        items.append(f'<li><a href="#{s.name}">{html.escape(s.title)}</a>{flag}</li>')
        if s.name == "verification" and s.status == "ok":
            items.append('<li><a href="#orders">Observed convergence orders</a></li>')
    items.append('<li><a href="#anchors">Appendix: the verification anchors</a></li>')
    nav = "".join(items)
    body = "".join(_section_html(s) for s in sections) + _anchors_appendix()
    return (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
        f"<title>upliftlab report{' (fast)' if fast else ''}</title>"
        f"<style>{_CSS}</style></head><body><main>"
        f"<h1>upliftlab verification report{' (fast)' if fast else ''}</h1>"
        f'<p class="meta">upliftlab {html.escape(__version__)}, built '
        f"{html.escape(str(prov['created_utc']))} on {html.escape(str(prov['platform']))} "
        f"(Python {html.escape(str(prov['python']))}, numpy {html.escape(str(prov['numpy']))})"
        f" in {elapsed:.1f} s. {'Fast mode: small grids and coarse meshes.' if fast else ''}"
        "</p>"
        f'<div class="status{"" if passed else " failing"}">{" ".join(status_lines)}</div>'
        f"<nav><ol>{nav}</ol></nav>{body}</main></body></html>\n")


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


def command(args) -> int:
    """``upliftlab report``: build the report; the exit status of the module docstring."""

    def say(message):
        print(f"upliftlab report: {message}", file=sys.stderr, flush=True)

    report = build_report(args.fast, out=args.out, scheduler=args.scheduler, progress=say,
                          force=getattr(args, "force", False))
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


if __name__ == "__main__":
    sys.exit(main())
