"""Where a benchmark writes: an output folder by default, the committed tables only on request.

Every script in ``benchmarks/`` writes its tables and figures to ``results/bench/<name>/``
(relative to the working directory; ``--out DIR`` elsewhere) and rewrites the committed files
beside it (``benchmarks/*.md`` and their figures) only with ``--write``, so that running a
benchmark never changes tracked files by accident. A comparison that needs an optional
dependency that is missing stops before any work with one line naming the extra to install
(exit 2), instead of replacing committed rows by "skipped".
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path

__all__ = ["HERE", "add_output_arguments", "output_folder", "require"]

#: The benchmarks folder, which holds the committed tables.
HERE = Path(__file__).resolve().parent


def add_output_arguments(parser: argparse.ArgumentParser, name: str) -> None:
    """``--out DIR`` (default ``results/bench/<name>``) and ``--write`` (the committed files
    in ``benchmarks/``)."""
    parser.add_argument("--out", default=None,
                        help=f"output folder (default results/bench/{name})")
    parser.add_argument("--write", action="store_true",
                        help="update the committed tables and figures in benchmarks/ instead")


def output_folder(args: argparse.Namespace, name: str) -> Path:
    """The folder to write to (created), from ``--out`` and ``--write``."""
    if args.write and args.out is not None:
        raise SystemExit(f"{name}: error: give --out or --write, not both")
    folder = HERE if args.write else Path(args.out or Path("results") / "bench" / name)
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
