"""The Markdown the studies write, as HTML, by markdown-it-py (CommonMark with GFM's pipe
tables): headings with ids that links can point to, paragraphs, tables, lists, code and
emphasis; no raw HTML and no links (their text only), so the report refers to nothing outside
itself.

A table is wrapped in a scroll box (``<div class="scroll">``), a cell that is one short
hyphenated name (a bed's code, "ES-f-I") is kept on one line, a cell or list item that is only
a verdict ("pass", "holds") is coloured, and so is a bold verdict ("Verdict: holds.").
A literal bar inside a table cell is written ``\\|`` (GFM): an unescaped one starts a cell.
"""

from __future__ import annotations

import html
import re
from functools import lru_cache

from markdown_it import MarkdownIt

__all__ = ["markdown_to_html", "slug"]


def slug(text: str) -> str:
    """A heading's text as an id: lower case, words joined by ``-``, only letters, digits,
    ``-`` and ``_`` ("§2 Ewing's stiffness matrix" -> "2-ewing-s-stiffness-matrix")."""
    words = re.findall(r"[^\W_]+|_", text.lower())
    return "-".join(w for w in words if w != "_") or "section"


def _no_link(self, tokens, idx, options, env) -> str:
    """A link keeps its text only (the report names nothing outside itself)."""
    return ""


def _image_as_text(self, tokens, idx, options, env) -> str:
    return html.escape(tokens[idx].content)


def _table_open(self, tokens, idx, options, env) -> str:
    return '<div class="scroll"><table>'


def _table_close(self, tokens, idx, options, env) -> str:
    return "</table></div>"


def _heading_open(self, tokens, idx, options, env) -> str:
    """``<hN id=...>``: the level moved down by the converter's shift (at most 6), the id the
    heading's slug with the caller's prefix, made unique within the page by a suffix."""
    token = tokens[idx]
    level = min(6, int(token.tag[1]) + env.get("shift", 0))
    text = tokens[idx + 1].content if idx + 1 < len(tokens) else ""
    ident = env.get("prefix", "") + slug(text)
    seen = env.setdefault("ids", set())
    base, k = ident, 2
    while ident in seen:
        ident, k = f"{base}-{k}", k + 1
    seen.add(ident)
    return f'<h{level} id="{ident}">'


def _heading_close(self, tokens, idx, options, env) -> str:
    return f"</h{min(6, int(tokens[idx].tag[1]) + env.get('shift', 0))}>\n"


@lru_cache(maxsize=1)
def _parser() -> MarkdownIt:
    """CommonMark with pipe tables and strikethrough; raw HTML is escaped (``html`` off)."""
    md = MarkdownIt("commonmark", {"html": False}).enable(["table", "strikethrough"])
    rules = md.add_render_rule
    for name, rule in (("link_open", _no_link), ("link_close", _no_link),
                       ("image", _image_as_text), ("table_open", _table_open),
                       ("table_close", _table_close), ("heading_open", _heading_open),
                       ("heading_close", _heading_close)):
        rules(name, rule)
    return md


_VERDICT = re.compile(r"<strong>(Verdict: (.*?)\.?)</strong>")
_CELL = re.compile(r"<(td|th)>(.*?)</\1>", flags=re.S)
_ITEM = re.compile(r"<li>(.*?)</li>", flags=re.S)


def _verdict(match) -> str:
    kind = {"holds": "ok", "does not hold": "bad"}.get(match.group(2), "skip")
    return f'<strong class="{kind}">{match.group(1)}</strong>'


def _badge(inner: str) -> str:
    """A cell or item that is only a verdict, coloured; else as it is."""
    plain = re.sub(r"<[^>]+>", "", inner).strip().lower()
    if plain in ("pass", "holds"):
        return f'<span class="ok">{inner}</span>'
    if plain in ("fail", "does not hold"):
        return f'<span class="bad">{inner}</span>'
    return inner


def _cell(match) -> str:
    """A table cell: one short hyphenated name is kept on one line (a browser breaks after a
    hyphen: a narrow printed column showed "ES-f-" over "I"); a body cell that is only a
    verdict is coloured."""
    tag, inner = match.groups()
    plain = re.sub(r"<[^>]+>", "", inner).strip()
    name = re.fullmatch(r"[\w.]+(-[\w.]+)+", plain) and len(plain) <= 10
    attribute = ' class="name"' if name else ""
    return f"<{tag}{attribute}>{_badge(inner) if tag == 'td' else inner}</{tag}>"


def markdown_to_html(text: str, shift: int = 0, prefix: str = "") -> str:
    """``text`` (Markdown) as HTML: headings moved down ``shift`` levels (at most ``<h6>``)
    with ids ``prefix`` + their slug, paragraphs, lists, pipe tables, code, emphasis. Raw HTML
    is escaped; links and images keep their text only."""
    env = {"shift": shift, "prefix": prefix}
    out = _parser().render(text.replace("\r\n", "\n"), env)
    out = _VERDICT.sub(_verdict, out)
    out = _CELL.sub(_cell, out)
    return _ITEM.sub(lambda m: f"<li>{_badge(m.group(1))}</li>", out)
