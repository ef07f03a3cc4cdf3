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


def test_pdf_given_twice_prints_both(tmp_path, monkeypatch):
    """``--pdf A4 --pdf Letter`` asks for both papers (before the fix: only the last, and the
    report then removed its earlier A4 PDF as stale)."""
    asked: list = []

    def stand_in(fast, folder, scheduler, studies, progress, start, budget, papers):
        asked.append(papers)
        raise RuntimeError("stand-in: nothing built")

    monkeypatch.setattr(rp, "_build", stand_in)
    monkeypatch.setattr("upliftlab.comparisons.report.printing.browser", lambda: "/bin/true")
    main(["report", "--fast", "--pdf", "A4", "--pdf", "Letter", "--out", str(tmp_path / "r")])
    assert asked == [("A4", "Letter")]


def test_a_stale_pdf_once_removed_is_no_longer_upliftlabs(tmp_path):
    """A report removes its earlier Letter PDF and then fails (no completion marker): a
    Letter PDF the user puts there afterwards is theirs, kept by the next report and refused
    as an output (before the fix: the record of the files being written still listed it, so
    the next report removed the user's file). A link at a stale PDF's name is left as it is."""
    from upliftlab.outdir import claim
    from upliftlab.results import write_bytes, write_text

    out = tmp_path / "r"
    with claim(out, out, settings={"command": "report"}, outputs=["report-Letter.pdf"]) as run:
        run.start_writing()
        write_bytes(out / "report-Letter.pdf", b"%PDF upliftlab's\n")
        run.complete([out / "report-Letter.pdf"])
    with pytest.raises(RuntimeError):
        with claim(out, out, settings={"command": "report"}, outputs=["report.html"]) as run:
            run.start_writing()
            write_text(out / "report.html", "<html></html>")
            assert run.remove_own("report-Letter.pdf")
            raise RuntimeError("a section failed")
    (out / "report-Letter.pdf").write_bytes(b"%PDF the user's\n")
    with claim(out, out, settings={"command": "report"}, outputs=["report.html"]) as run:
        run.start_writing()
        assert not run.remove_own("report-Letter.pdf")
    assert (out / "report-Letter.pdf").read_bytes() == b"%PDF the user's\n"
    with pytest.raises(InputError, match="report-Letter.pdf.*did not make"):
        claim(out, out, settings={"command": "report"}, outputs=["report-Letter.pdf"])
    (tmp_path / "mine.pdf").write_bytes(b"%PDF the user's own\n")
    (out / "report-A4.pdf").symlink_to(tmp_path / "mine.pdf")
    with claim(out, out, settings={"command": "report"}, outputs=["report.html"]) as run:
        run.made = {"report-A4.pdf"}  # as if upliftlab had listed it
        assert not run.remove_own("report-A4.pdf")
    assert (out / "report-A4.pdf").is_symlink() and (tmp_path / "mine.pdf").exists()
