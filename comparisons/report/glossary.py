"""The beds' codes (U, ES, U-p, ES-p-I, ES-f-I, ...) explained where the page first uses them,
from the bed registry (:data:`..beds.BEDS`: each entry's ``short`` code and ``label``).

The page's text outside tags, code and scripts is scanned in order. A code first met in
running text gets its label in parentheses after it; a code first met in a table gets a line
above the table ("Bed codes in this table: ES-b is the ..."; a code and its label are
separated by words, not a colon: a printed "ES-b:" would be another word than the table's
"ES-b"), so the table's cells stay as they are.
Each first use is an ``<abbr>`` whose title is the label.
"""

from __future__ import annotations

import html
import re

from ..beds import BEDS

__all__ = ["bed_codes", "explain_codes"]


def bed_codes() -> dict[str, str]:
    """{short code: label} of every registered bed with a code, longest code first."""
    codes = {e.short: e.label for e in BEDS.values() if e.short}
    return dict(sorted(codes.items(), key=lambda kv: -len(kv[0])))


#: Elements whose text is not prose: nothing in them is explained.
_SKIP = ("code", "pre", "script", "style", "title", "abbr", "svg")
_TOKEN = re.compile(r"(<[^>]*>)")


def _wrapper(out: list[str]) -> int:
    """Where a table's legend goes: before its scroll box when the table has one, else
    before the table."""
    k = len(out) - 1
    while k >= 0 and not out[k].strip():
        k -= 1
    return k if k >= 0 and out[k] == '<div class="scroll">' else len(out)


def explain_codes(page: str) -> str:
    """``page`` (HTML) with each bed code explained at its first use (module docstring)."""
    codes = bed_codes()
    pattern = re.compile(r"(?<![\w-])(" + "|".join(re.escape(c) for c in codes)
                         + r")(?![\w-])")
    seen: set[str] = set()
    out: list[str] = []
    skip = 0
    table_at: int | None = None
    in_table: list[str] = []

    def first(match) -> str:
        code = match.group(1)
        if code in seen:
            return code
        seen.add(code)
        label = html.escape(codes[code])
        if table_at is not None:
            in_table.append(code)
            return f'<abbr title="{label}">{code}</abbr>'
        return f'<abbr title="{label}">{code}</abbr> ({label})'

    for part in _TOKEN.split(page):
        if part.startswith("<"):
            name = re.match(r"</?\s*([a-zA-Z0-9]+)", part)
            tag = name.group(1).lower() if name else ""
            if tag in _SKIP and not part.endswith("/>"):
                skip += -1 if part.startswith("</") else 1
            elif tag == "table" and not part.startswith("</"):
                table_at = _wrapper(out)
            elif tag == "table" and table_at is not None:
                if in_table:
                    legend = "; ".join(f"<strong>{c}</strong> is the {html.escape(codes[c])}"
                                       for c in in_table)
                    out.insert(table_at, f'<p class="legend">Bed codes in this table: '
                                         f"{legend}.</p>")
                table_at, in_table = None, []
            out.append(part)
        elif skip or not part.strip():
            out.append(part)
        else:
            out.append(pattern.sub(first, part))
    return "".join(out)
