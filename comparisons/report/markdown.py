"""The Markdown the studies write, as HTML: headings, paragraphs, tables, lists, code and
emphasis; no raw HTML and no links (their text only), so the report refers to nothing outside
itself."""

from __future__ import annotations

import html
import re


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
    rows = ["<tr>" + "".join(f"<th{_name_class(c)}>{_inline(c)}</th>" for c in head) + "</tr>"]
    for cells in body:
        rows.append("<tr>" + "".join(f"<td{_name_class(c)}>{_badge(_inline(c))}</td>"
                                     for c in cells) + "</tr>")
    return ('<div class="scroll"><table>' + "<thead>" + rows[0] + "</thead><tbody>"
            + "".join(rows[1:]) + "</tbody></table></div>")


def _name_class(cell: str) -> str:
    """A cell that is one short hyphenated name (a bed's abbreviation, "ES-f-I") is kept on one
    line: a browser breaks after a hyphen, and a narrow printed column showed "ES-f-" over "I"."""
    return ' class="name"' if re.fullmatch(r"[\w.]+(-[\w.]+)+", cell) and len(cell) <= 10 else ""


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
