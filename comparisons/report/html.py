"""The report's page: the style sheet (screen and print), each section's HTML (its summary, its
figures from :mod:`.report_figures`, the verification tables), the anchors appendix, the status
box and the frame slider's one inline script (:mod:`.report_animation`)."""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass

from ... import __version__
from ...provenance import provenance
from .animation import SCRIPT
from .figures import figures_html
from .findings import findings_html
from .glossary import explain_codes
from .markdown import markdown_to_html
from ..framework.study import StudyResult


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
td.name,th.name{white-space:nowrap}
.ok{color:#12733a;font-weight:600}.bad{color:#b3261e;font-weight:700}.skip{color:#8a6d00}
tr.fail td{background:#fdecea}tr.skipped td{color:#6b6f78;background:#fffbea}
.status{border:1px solid #d6dae1;border-left:6px solid #12733a;padding:10px 14px;
 margin:14px 0;background:#f6fbf8}.status.failing{border-left-color:#b3261e;background:#fdf3f2}
.notice{border-left:5px solid #c98a00;background:#fff8e6;padding:8px 12px;margin:10px 0}
.error{border-left:5px solid #b3261e;background:#fdf3f2;padding:8px 12px;margin:10px 0}
pre{background:#f3f4f6;padding:8px 10px;overflow-x:auto;font-size:12px;white-space:pre-wrap}
code{font-family:"DejaVu Sans Mono",Menlo,Consolas,monospace;font-size:12.5px}
[hidden]{display:none!important}
figure{margin:14px 0 22px}figure img{display:block;max-width:100%;height:auto}
figure img.plot{width:100%;max-width:840px}figure img.render{border:1px solid #e3e6eb}
figcaption{font-size:13px;color:#3d4452;max-width:840px;margin-top:4px}
figcaption .conclusion{color:#1d2330;font-weight:600}
figcaption a.anchor{color:#8a93a3;text-decoration:none}p.legend{font-size:13px;color:#3d4452}
abbr[title]{text-decoration:underline dotted}
details.dense{margin:10px 0 18px;border:1px solid #d6dae1;padding:6px 12px;background:#fafbfc}
details.dense>summary{cursor:pointer;font-weight:600}
figure.anim .slider{display:flex;gap:12px;align-items:center;font-size:13px;margin:6px 0}
figure.anim input{width:min(420px,60vw)}figure.anim output{font-variant-numeric:tabular-nums}
nav ol{columns:2;font-size:14px;margin:6px 0}small.note{color:#5a6272}
body{counter-reset:figure}figure{counter-increment:figure}
figcaption::before{content:"Figure " counter(figure) ". ";font-weight:600;color:#1d2330}
@media print{
 @page{margin:14mm}
 body{background:#fff;font-size:10pt}main{max-width:none;box-shadow:none;padding:0}
 h2{break-after:avoid}h3{break-after:avoid}
 .scroll{overflow:visible}table{font-size:8pt;table-layout:auto}
 th,td{overflow-wrap:break-word;padding:2px 4px}td.num,td.tol{white-space:normal}
 th{position:static}figure,tr,.status,.notice,.error{break-inside:avoid}
 figure img.plot{width:auto;max-width:100%;max-height:235mm}
 figure img.render{max-width:100%;max-height:200mm;border:none}figcaption{font-size:9pt}
 details.dense{border:none;padding:0;background:none}details.dense>summary{list-style:none}
 details::details-content{content-visibility:visible;display:block}
 figure.anim .slider{display:none}
 pre{white-space:pre-wrap;word-break:break-word}code{word-break:break-all}nav ol{columns:1}
}
"""


def _verification_tables(study: StudyResult) -> str:
    from ..studies.verification import Order, Row, error_text, fmt

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
             "<th>reference</th><th>unit</th><th>measured</th><th>expected</th>"
             "<th>error (–, or in the unit if abs)</th><th>tolerance</th><th>result</th></tr>"
             "</thead><tbody>"]
    for r in rows:
        note = f'<br><small class="note">{html.escape(r.note)}</small>' if r.note else ""
        table.append(f'<tr class="{r.status}"><td>{r.group}</td><td>{html.escape(r.quantity)}'
                     f"{note}</td><td>{html.escape(r.reference)}</td>"
                     f"<td>{html.escape(getattr(r, 'unit', '') or '—')}</td>"
                     f'<td class="num">{fmt(r.measured)}</td><td class="num">'
                     f"{fmt(r.expected)}</td>"
                     f'<td class="num">{html.escape(error_text(r))}</td>'
                     f'<td class="tol">{html.escape(r.tolerance)}</td>'
                     f"<td>{mark[r.status]}</td></tr>")
    table.append("</tbody></table></div>")
    order_html = ['<div class="scroll"><table><thead><tr><th>group</th><th>case</th>'
                  "<th>method</th><th>steps (Δt in s, or h/B)</th><th>observed order (–)</th>"
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
    parts.append(markdown_to_html(_without_title(study.summary), shift=2, prefix=f"{s.name}-"))
    parts.append(figures_html(study))
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
            + markdown_to_html(_without_title(anchors_text()), shift=1, prefix="anchor-"))


def _without_title(markdown: str) -> str:
    """The summary without its first ``# `` heading (the section has its own)."""
    lines = markdown.lstrip().split("\n")
    return "\n".join(lines[1:]) if lines and lines[0].startswith("# ") else markdown


_SPLIT = "<!-- the opening ends here -->"


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
    items = ['<li><a href="#findings">What the studies found</a></li>']
    for s in sections:
        flag = "" if s.status == "ok" else f' <small class="note">({s.status})</small>'
        items.append(f'<li><a href="#{s.name}">{html.escape(s.title)}</a>{flag}</li>')
        if s.name == "verification" and s.status == "ok":
            items.append('<li><a href="#orders">Observed convergence orders</a></li>')
    items.append('<li><a href="#anchors">Appendix: the verification anchors</a></li>')
    nav = "".join(items)
    # the findings open the page, above the status box; bed codes are explained at their
    # first use in the page's order
    opening, body = explain_codes(findings_html(sections) + _SPLIT + "".join(
        _section_html(s) for s in sections) + _anchors_appendix()).split(_SPLIT, 1)
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
        f"{opening}"
        f'<div class="status{"" if passed else " failing"}">{" ".join(status_lines)}</div>'
        f"<nav><ol>{nav}</ol></nav>{body}</main>"
        + (SCRIPT if 'class="anim"' in body else "") + "</body></html>\n")
