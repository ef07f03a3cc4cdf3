"""The report's PDFs (``upliftlab report --pdf A4 Letter``) are outputs of the report's own run:
declared before any work, so that a PDF of the user's at their name is refused before the
report is built (before: the report ran, then its PDF replaced the user's file, exit 0); listed
in the completion marker as upliftlab's, so that the next run replaces them; and removed by a
later report that does not print them, since they show the report it replaces.

Reference: the project's rule (upliftlab replaces and removes only the files it made, and bad
input is refused before any work); the PDFs' pages are checked against the page in
``test_report.py``. The verification section here has one anchor, an exact ratio of 1, so that
the report is complete in seconds.
"""

from __future__ import annotations

import json

import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main
from upliftlab.comparisons.report import build as rp
from upliftlab.outdir import MARKER


def test_a_users_pdf_is_refused_before_the_report_is_built(tmp_path, monkeypatch, capsys):
    """The user's report-A4.pdf in the report's folder: exit 2 with one line naming it,
    nothing built, the file unchanged."""
    built: list = []

    def stand_in(*args):
        built.append(args)
        raise RuntimeError("the report was built")

    monkeypatch.setattr(rp, "_build", stand_in)
    out = tmp_path / "report"
    out.mkdir()
    mine = out / "report-A4.pdf"
    mine.write_bytes(b"%PDF-1.4 my own report\n")
    assert main(["report", "--fast", "--pdf", "A4", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and repr(str(mine)) in err and "did not make" in err
    assert built == [] and mine.read_bytes() == b"%PDF-1.4 my own report\n"


def test_a_paper_that_is_not_one_is_refused_through_the_api(tmp_path):
    with pytest.raises(InputError, match=r"--pdf = 'A3': expected one of A4, Letter"):
        rp.build_report(True, out=tmp_path / "r", studies=(), papers=("A3",))
    with pytest.raises(InputError, match="--pdf = 'A4': expected a list"):
        rp.build_report(True, out=tmp_path / "r", studies=(), papers="A4")
    assert not (tmp_path / "r").exists()


def test_the_pdfs_are_the_reports_own_files(tmp_path, monkeypatch):
    """Printed on A4 and Letter: both listed in the marker; printed again on A4: its own PDF
    replaced (not refused), the Letter one removed and no longer listed."""
    from upliftlab.comparisons.report.printing import browser
    from upliftlab.comparisons.studies import verification as vf

    if browser() is None:
        pytest.fail("printing needs chromium (apt-get install chromium)")

    def exact(ctx):
        return [vf.relative_row("reduced", "one", "an exact ratio", "1 = 1", 1.0, 1.0, 1e-12)]

    monkeypatch.setattr(vf.workflow, "CHECKS", (("reduced", "one", exact),))
    out = tmp_path / "r"
    first = rp.build_report(True, out=out, studies=("verification",), papers=("A4", "Letter"))
    assert first.ok and [p.name for p in first.pdfs] == ["report-A4.pdf", "report-Letter.pdf"]
    marker = json.loads((out / MARKER).read_text())
    assert marker["files"] == ["report-A4.pdf", "report-Letter.pdf", "report.html",
                               "report.json"]
    assert all((out / name).read_bytes().startswith(b"%PDF") for name in marker["files"][:2])
    again = rp.build_report(True, out=out, studies=("verification",), papers=("A4",))
    assert again.ok and (out / "report-A4.pdf").read_bytes().startswith(b"%PDF")
    assert not (out / "report-Letter.pdf").exists()
    assert json.loads((out / MARKER).read_text())["files"] == ["report-A4.pdf", "report.html",
                                                               "report.json"]
