"""Docstrings as reST: the plain-text notation of upliftlab's docstrings, escaped.

The docstrings write mathematics as plain text: ``|error| ≤ tol`` for an absolute value and
``(3, 3, *batch)`` for a shape. In reST the first is a substitution reference and the second
the start of an emphasis, both errors of the strict build. Before autodoc parses a docstring,
a ``|`` and a ``*`` of that notation are escaped (outside double back-quotes; lines of a table
or a line block are left alone). Everything else of a docstring is parsed as it is written.
"""

from __future__ import annotations

import re

_LITERAL = re.compile(r"(``.*?``)")
_STAR_ARG = re.compile(r"(?<=[(,\s\[])\*(?=[A-Za-z_]\w*\s*[),\]])")
#: A grid table's border or row, or a line block: their bars are reST's, not the notation's.
_TABLE = re.compile(r"^\s*(?:\+[-=+]+\+\s*$|\|\s.*\|\s*$|\|\s)")


def escape_line(line: str) -> str:
    """``line`` with the notation's ``|`` and ``*`` escaped outside literals."""
    if _TABLE.match(line):
        return line
    parts = _LITERAL.split(line)
    for i in range(0, len(parts), 2):  # the even parts lie outside double back-quotes
        text = parts[i].replace("|", r"\|")
        parts[i] = _STAR_ARG.sub(r"\*", text)
    return "".join(parts)


def escape(app, what, name, obj, options, lines):
    lines[:] = [escape_line(line) for line in lines]


def setup(app):
    app.connect("autodoc-process-docstring", escape)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
