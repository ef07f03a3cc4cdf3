"""Print the report to PDF on A4 or Letter with headless Chromium: what a reader gets from the
browser's "Print to PDF", done from the command line.

``upliftlab report --pdf A4 Letter`` writes ``report-A4.pdf`` / ``report-Letter.pdf`` beside
the report (:func:`print_pdf`).

The paper size is a CSS ``@page {size: …}`` rule added to a temporary copy of the page (the
report itself leaves the size to the printer); the print style sheet of the report does the
rest. Chromium runs with no network, no sync and a throw-away profile, and without the
browser's header and footer. Needs ``chromium`` (Debian/Ubuntu package ``chromium``); the
checks of the printed pages use ``pdfinfo``/``pdftotext`` (package ``poppler-utils``).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from ...checks import InputError
from ...results import write_bytes
from ...workers import dying_with_this_process

__all__ = ["PAPERS", "browser", "need_browser", "with_page_size", "print_pdf"]

#: CSS page size and (width, height) in PostScript points of each paper.
PAPERS = {"A4": ("A4", (595.28, 841.89)), "Letter": ("letter", (612.0, 792.0))}
_BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def browser() -> str | None:
    """The path of a Chromium (or Chrome) executable, or None."""
    for name in _BROWSERS:
        found = shutil.which(name)
        if found:
            return found
    return None


def need_browser():
    """Raise the one-line InputError that says how to install a browser that can print."""
    raise InputError("printing needs Chromium: apt-get install chromium (Debian/Ubuntu; "
                     "chromium-browser or google-chrome on the PATH also do)")


def with_page_size(page: str, paper: str) -> str:
    """The report's HTML with ``@page {size: <paper>}`` added to its head."""
    if paper not in PAPERS:
        raise InputError(f"paper = {paper!r}: expected one of {', '.join(PAPERS)}")
    rule = f"<style>@page{{size:{PAPERS[paper][0]}}}</style>"
    head = page.find("</head>")
    if head < 0:
        raise InputError("the page has no </head>: not a report")
    return page[:head] + rule + page[head:]


def print_pdf(html_path: str | os.PathLike, pdf_path: str | os.PathLike, paper: str = "A4",
              *, executable: str | None = None, timeout: float = 300.0) -> Path:
    """Print ``html_path`` to ``pdf_path`` on ``paper`` (A4 or Letter) with headless Chromium;
    the PDF's path. InputError if there is no browser or the page is not a report;
    RuntimeError if Chromium fails or writes nothing."""
    html_path, pdf_path = Path(html_path), Path(pdf_path)
    exe = executable or browser()
    if exe is None:
        need_browser()
    page = with_page_size(html_path.read_text(encoding="utf-8"), paper)
    pdf_path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="upliftlab-print-") as tmp:
        copy = Path(tmp) / "page.html"
        copy.write_text(page, encoding="utf-8")
        out = Path(tmp) / "page.pdf"
        command = [exe, "--headless", "--no-sandbox", "--disable-gpu",
                   "--disable-background-networking", "--disable-component-update",
                   "--disable-sync", "--no-first-run", "--disable-extensions",
                   f"--user-data-dir={Path(tmp) / 'profile'}", "--no-pdf-header-footer",
                   f"--print-to-pdf={out}", copy.as_uri()]
        done = subprocess.run(dying_with_this_process(command), capture_output=True,
                              text=True, timeout=timeout)
        if done.returncode != 0 or not out.is_file() or out.stat().st_size == 0:
            raise RuntimeError(f"{Path(exe).name} could not print {html_path.name} "
                               f"(exit {done.returncode}): {done.stderr.strip()[-500:]}")
        # in place at once or not at all (a full disk leaves no part of a PDF), a regular file
        # or none there before, inside the output folder (write_bytes' check_target)
        write_bytes(pdf_path, out.read_bytes())
    return pdf_path
