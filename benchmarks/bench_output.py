"""Where a benchmark writes, section by section, and what it commits.

Every script in ``benchmarks/`` writes its tables and figures to ``results/bench/<name>/``
(relative to the working directory; ``--out DIR`` elsewhere), so that running a benchmark never
changes tracked files by accident. A benchmark is a list of :class:`Section` s run in order by
:func:`run_sections`:

- each section's result is written to the output folder as soon as the section ends (every
  file atomically: a temporary file beside its target, then ``os.replace``), so a failure or an
  interrupt later keeps what the earlier sections computed;
- a table written before the end, or after a failure, says which sections did not complete
  (:func:`incomplete_note`, :func:`missing_section`): never a partial table presented as whole;
- a failing section ends the run with one line on stderr naming the section and the error
  (the traceback goes to ``<out>/<name>-error.txt``) and exit status 1; Ctrl-C ends it with
  exit status 130, the finished sections on disk;
- ``--write`` also updates the committed files in ``benchmarks/``, and only after every
  section completed; a quick run never updates them.

Before any work a benchmark whose sections carry a cost (seconds, from a cost model each script
states in its docstring) prints the estimated wall time on stderr; after each section it prints
the elapsed time and an ETA (the remaining estimate scaled by how the finished sections kept to
theirs). A comparison that needs an optional dependency that is missing stops before any work
with one line naming the extra to install (exit 2).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import sys
import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["HERE", "Section", "add_output_arguments", "output_folder", "require", "write_text",
           "atomic_file", "save_figure", "run_sections", "incomplete_note", "missing_section",
           "markdown_tables", "committed_tables", "number", "duration", "say"]

#: The benchmarks folder, which holds the committed tables.
HERE = Path(__file__).resolve().parent


def say(message: str) -> None:
    """One progress line on stderr, flushed at once."""
    print(message, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------------------------
# Arguments and folders
# ---------------------------------------------------------------------------------------------


def add_output_arguments(parser: argparse.ArgumentParser, name: str,
                         committed: bool = True) -> None:
    """``--out DIR`` (default ``results/bench/<name>``) and, for a benchmark with committed
    tables (``committed``), ``--write``."""
    parser.add_argument("--out", default=None,
                        help=f"output folder, written section by section (default "
                             f"results/bench/{name})")
    if committed:
        parser.add_argument("--write", action="store_true",
                            help="also update the committed tables and figures in benchmarks/ "
                                 "once every section has completed")


def output_folder(args: argparse.Namespace, name: str) -> Path:
    """The folder the sections are written to (created), from ``--out``. Refuses ``--write``
    with ``--quick``: a quick run is a smoke check, not the committed benchmark."""
    if getattr(args, "write", False) and getattr(args, "quick", False):
        raise SystemExit(f"{name}: error: --write updates the committed tables: run every "
                         "section (no --quick)")
    folder = Path(args.out or Path("results") / "bench" / name)
    if folder.exists() and not folder.is_dir():
        raise SystemExit(f"{name}: error: --out = {str(folder)!r} is a file, not a folder")
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def require(module: str, extra: str, name: str) -> None:
    """Stop (exit 2, one line) when ``module`` cannot be imported."""
    if importlib.util.find_spec(module) is None:
        print(f"{name}: error: needs {module} (pip install 'upliftlab[{extra}]'); nothing was "
              "run or written", file=sys.stderr)
        raise SystemExit(2)


# ---------------------------------------------------------------------------------------------
# Atomic files
# ---------------------------------------------------------------------------------------------


def atomic_file(path: str | os.PathLike):
    """A temporary path beside ``path``, moved onto it only if the block succeeds: a reader
    sees the old file or the new one, never half of one (upliftlab's own writer,
    :func:`upliftlab.results.atomic_path`)."""
    from upliftlab.results import atomic_path

    return atomic_path(path)


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_file(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def save_figure(fig, path: str | os.PathLike, dpi: int = 120) -> Path:
    """Save a matplotlib figure as PNG to ``path`` atomically and close it."""
    import matplotlib.pyplot as plt

    with atomic_file(path) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    plt.close(fig)
    return Path(path)


# ---------------------------------------------------------------------------------------------
# Sections
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Section:
    """One part of a benchmark that completes on its own: ``key`` names it (on stderr and in a
    table's list of missing sections), ``compute()`` returns its result, ``cost`` is its
    estimated wall time (s; None: no estimate)."""

    key: str
    compute: Callable[[], Any]
    cost: float | None = None


#: What a publisher gets: the results of the completed sections by key, and the reason each
#: other section is missing ("not run yet", "failed: ...", "not run: ... failed first").
Publish = Callable[[Path, dict, dict], None]


def duration(seconds: float) -> str:
    """``seconds`` as a short human duration: 42 s, 3.5 min, 1.2 h."""
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.1f} min"
    return f"{seconds / 3600:.1f} h"


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or "(no message)"
    return f"{type(exc).__name__}: {text[:300]}"


def _estimate(name: str, sections: Sequence[Section], model: str) -> None:
    known = [s.cost for s in sections if s.cost is not None]
    if not known:
        return
    unknown = len(sections) - len(known)
    more = f", {unknown} of them without an estimate" if unknown else ""
    source = f" ({model})" if model else ""
    say(f"{name}: estimated wall time {duration(sum(known))} for {len(sections)} "
        f"sections{more}{source}")


def _eta(sections: Sequence[Section], done: int, elapsed: float) -> str:
    """The remaining estimate, scaled by actual/estimated time of the finished sections
    (without costs: the mean time per finished section)."""
    left = sections[done:]
    if not left:
        return "done"
    finished = [s.cost for s in sections[:done]]
    if all(c is not None for c in finished) and all(s.cost is not None for s in left) \
            and sum(finished) > 0:
        return duration(elapsed / sum(finished) * sum(s.cost for s in left))
    return duration(elapsed / done * len(left))


def _record(folder: Path, name: str, sections, status: dict, seconds: dict) -> None:
    """``<name>-sections.json``: each section's status and wall time, and whether the run is
    complete (what a test or a script reads instead of parsing the tables)."""
    data = {"benchmark": name, "complete": all(status[s.key] == "done" for s in sections),
            "sections": [{"key": s.key, "status": status[s.key],
                          "seconds": seconds.get(s.key)} for s in sections]}
    write_text(folder / f"{name}-sections.json", json.dumps(data, indent=1) + "\n")


def run_sections(name: str, sections: Sequence[Section], publish: Publish, folder: Path, *,
                 commit: Callable[[dict], None] | None = None, model: str = "") -> int:
    """Run ``sections`` in order; after each, ``publish(folder, done, missing)`` writes the
    benchmark's files (module docstring). ``commit(done)`` (``--write``) runs only when every
    section completed. ``model`` says where the costs come from. Returns the exit status: 0,
    1 after a failed section (one line on stderr), 130 after Ctrl-C."""
    keys = [s.key for s in sections]
    if len(set(keys)) != len(keys):
        raise ValueError(f"{name}: section keys must be unique: {keys}")
    error_file = folder / f"{name}-error.txt"
    if error_file.exists():
        error_file.unlink()
    status = {s.key: "not run yet" for s in sections}
    seconds: dict[str, float] = {}
    done: dict[str, Any] = {}
    _estimate(name, sections, model)
    started = time.perf_counter()
    for i, section in enumerate(sections):
        began = time.perf_counter()
        try:
            done[section.key] = section.compute()
        except (Exception, KeyboardInterrupt) as exc:
            interrupted = isinstance(exc, KeyboardInterrupt)
            why = "interrupted" if interrupted else f"failed: {_one_line(exc)}"
            status[section.key] = why
            for later in sections[i + 1:]:
                status[later.key] = f"not run: {section.key!r} {why.split(':')[0]} first"
            write_text(error_file, "".join(traceback.format_exception(exc)))
            missing = {k: v for k, v in status.items() if v != "done"}
            publish(folder, dict(done), missing)
            _record(folder, name, sections, status, seconds)
            kept = ", ".join(repr(k) for k in done) or "none"
            say(f"{name}: error: section {section.key!r} {why}; completed sections ({kept}) "
                f"are in {folder}, the committed files are unchanged (traceback: "
                f"{error_file})")
            return 130 if interrupted else 1
        seconds[section.key] = time.perf_counter() - began
        status[section.key] = "done"
        missing = {k: v for k, v in status.items() if v != "done"}
        publish(folder, dict(done), missing)
        _record(folder, name, sections, status, seconds)
        elapsed = time.perf_counter() - started
        say(f"{name}: [{duration(elapsed)}] {section.key}: done in "
            f"{duration(seconds[section.key])} ({i + 1}/{len(sections)}); ETA "
            f"{_eta(sections, i + 1, elapsed)}")
    if commit is not None:
        commit(done)
    return 0


def incomplete_note(missing: dict) -> str:
    """The paragraph a table puts under its title while sections are missing ('' when none
    is): which ones, and why."""
    if not missing:
        return ""
    items = "; ".join(f"`{key}` ({why})" for key, why in missing.items())
    return (f"**Incomplete run: {len(missing)} section(s) did not complete, and their tables "
            f"are missing below: {items}.** Not a result of this benchmark as a whole.\n\n")


def missing_section(title: str, key: str, missing: dict) -> str:
    """The stand-in for the table of section ``key`` that did not complete."""
    return f"{title}\n\nNot completed (section `{key}`: {missing[key]}).\n"


# ---------------------------------------------------------------------------------------------
# Reading committed tables (cost models, tests)
# ---------------------------------------------------------------------------------------------


def _unused(name: str, taken) -> str:
    """``name``, or the first of 'name (2)', 'name (3)', … not in ``taken``."""
    key, k = name, 2
    while key in taken:
        key, k = f"{name} ({k})", k + 1
    return key


def markdown_tables(text: str) -> dict[str, list[dict[str, str]]]:
    """Every pipe table of a Markdown text as rows of {header: cell}, keyed by the heading
    (``## ...``/``### ...``) above it; a second table under one heading gets ' (2)' and so
    on, and so does a second column of one name in a table (``ratio``, ``ratio (2)``). Cells
    are stripped text."""
    tables: dict[str, list[dict[str, str]]] = {}
    heading, lines = "", text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i].strip()
        if line.startswith("#"):
            heading = line.lstrip("#").strip()
        elif line.startswith("|") and i + 1 < len(lines) and \
                lines[i + 1].strip().startswith("|---"):
            header: list[str] = []
            for cell in line.strip("|").split("|"):
                header.append(_unused(cell.strip(), header))
            rows, i = [], i + 2
            while i < len(lines) and lines[i].strip().startswith("|"):
                cells = [c.strip() for c in lines[i].strip().strip("|").split("|")]
                rows.append(dict(zip(header, cells)))
                i += 1
            tables[_unused(heading, tables)] = rows
            continue
        i += 1
    return tables


def committed_tables(filename: str) -> dict[str, list[dict[str, str]]]:
    """:func:`markdown_tables` of the committed ``benchmarks/<filename>`` ({} if absent)."""
    path = HERE / filename
    return markdown_tables(path.read_text(encoding="utf-8")) if path.exists() else {}


def number(cell: str) -> float:
    """The first number in a table cell ('2.7 s', '+0.763 %', '10580'); NaN if none."""
    import re

    found = re.search(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?", cell.replace("−", "-"))
    return float(found.group()) if found else float("nan")
