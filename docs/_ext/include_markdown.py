"""The benchmarks page: every ``benchmarks/*.md`` of the repository, included as it is.

The tables are the benchmarks' own files (written by ``python benchmarks/NAME.py --write``). A
page holding the block

    ```{benchmark-tables}
    ```

gets, in its place, one MyST ``{include}`` per file (sorted by name, headings one level down),
so that a new table file appears on the page without editing it. The block is replaced in the
page's source as it is read (``source-read``), so the includes are parsed as the page's own.
"""

from __future__ import annotations

from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
MARKER = "```{benchmark-tables}\n```"


def includes(page: Path) -> str:
    """The include blocks of every benchmark table, with paths relative to ``page``."""
    up = "/".join([".."] * len(page.parent.relative_to(REPOSITORY).parts))
    return "\n".join(f"```{{include}} {up}/benchmarks/{path.name}\n:heading-offset: 1\n```\n"
                     for path in sorted((REPOSITORY / "benchmarks").glob("*.md")))


def expand(app, docname, source):
    if MARKER in source[0]:
        page = Path(app.env.doc2path(docname))
        for path in sorted((REPOSITORY / "benchmarks").glob("*.md")):
            app.env.note_dependency(str(path))
        source[0] = source[0].replace(MARKER, includes(page))


def setup(app):
    app.connect("source-read", expand)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
