"""``upliftlab report --fast``: one self-contained HTML file from stored results.

References: the verification anchors (upliftlab/docs/anchors.md, each row's own reference and
tolerance, recomputed by upliftlab.comparisons.studies.verification), anchor §2's two-spring ratios
(uplift onset 0.288675/(1/6) = 1.73 reduced by the N-strip bed's (1 + 1/N); capacity
0.288675/0.5 = 0.58), and the report's contract (comparisons/report/build.py): no external
references,
nothing re-run when the inputs are unchanged (asserted through the stores' records, never
through time), exit 2 on bad options, 1 when a verification row or any section fails, else 0.
"""

from __future__ import annotations

import base64
import html
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main as cli_main
from upliftlab.comparisons.report import build as rp


def _cli() -> list[str]:
    script = Path(sys.executable).with_name("upliftlab")
    found = script if script.is_file() else shutil.which("upliftlab")
    return [str(found)] if found else [sys.executable, "-m", "upliftlab"]


def _report(out: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    return subprocess.run(_cli() + ["report", "--fast", "--out", str(out)], env=env,
                          capture_output=True, text=True, timeout=900)


def _digests() -> list[str]:
    """The content keys' source digests of every section (verification and studies)."""
    from upliftlab.comparisons.studies.verification import source_digest

    return [source_digest()] + [rp.study_digest(name) for name in rp.STUDIES]


def _records(store: Path) -> dict[str, str]:
    """{record file: its text} of a store directory."""
    return {str(p.relative_to(store)): p.read_text() for p in sorted(store.glob("??/*.json"))}


#: The fast studies whose points this module shares with the modules that make them.
SHARED_STUDIES = ("two_spring_equivalence", "winkler_vs_continuum", "winkler_map",
                  "speed_vs_error", "fixed_vs_uplift")


@pytest.fixture(scope="module")
def reports(tmp_path_factory, elcentro, fast_stores):
    """The fast report built twice into one directory (the El Centro rows need the record:
    the ``elcentro`` fixture fails without it). The studies' points that their own modules
    have made in this session are read, not made again; those made here are published for
    them (conftest.FastStores): the report's own records, which the tests below count, are
    in its store, not the studies'."""
    out = tmp_path_factory.mktemp("report") / "fast"
    folders = {name: out / "studies" / f"{name}-fast" / "store" for name in SHARED_STUDIES}
    for name, store in folders.items():
        fast_stores.seed(name, store)
    digests = [_digests()]
    first = _report(out)
    for name, store in folders.items():
        fast_stores.publish(name, store)
    after_first = _records(out / "store")
    first_json = json.loads((out / "report.json").read_text())
    second = _report(out)
    digests.append(_digests())
    return {"out": out, "sources_changed": digests[0] != digests[1], "first": first,
            "second": second, "first_json": first_json,
            "second_json": json.loads((out / "report.json").read_text()),
            # the whole report's page, before a test writes a smaller report in its folder
            "page": (out / "report.html").read_text(),
            "records_first": after_first, "records_second": _records(out / "store")}


def test_report_writes_one_self_contained_html(reports):
    # Contract: exit 0 (verification passed), exactly one HTML file, every image embedded (SVG
    # plots, PNG frames of the rendered soil), no style sheets, fonts or links that leave the
    # page, and one inline script (the frame slider's) with no source and no URL.
    first, out = reports["first"], reports["out"]
    assert first.returncode == 0, first.stderr[-3000:]
    htmls = list(out.rglob("*.html"))
    assert htmls == [out / "report.html"]
    page = htmls[0].read_text()
    sources = re.findall(r'src="([^"]*)"', page)
    assert len(sources) >= 10  # the two-spring maps, the frames and the M–θ figure
    assert all(s.startswith(("data:image/svg+xml;base64,", "data:image/png;base64,"))
               for s in sources)
    assert all(h.startswith("#") for h in re.findall(r'href="([^"]*)"', page))
    for forbidden in ("<link", "<iframe", "@import", "url(", "srcset", "<script src"):
        assert forbidden not in page.lower(), forbidden
    scripts = re.findall(r"<script>(.*?)</script>", page, flags=re.S)
    assert len(scripts) == 1 and page.lower().count("<script") == 1
    assert "://" not in scripts[0] and "fetch" not in scripts[0] and "import" not in scripts[0]
    for section in ("verification", "orders", "two_spring_equivalence", "paper",
                    "uplift_zone", "winkler_vs_continuum", "speed_vs_error", "fixed_vs_uplift",
                    "anchors"):
        assert f'id="{section}"' in page, section
    assert "Prandtl's bearing capacity" in page.split('id="anchors"')[1]
    # figures are numbered (a CSS counter, in print too) and printing keeps wide tables and
    # figures whole: a print style sheet that lets the tables' scroll boxes grow
    assert 'content:"Figure " counter(figure)' in page
    printing = page.split("@media print{", 1)[1].split("\n}", 1)[0]
    assert ".scroll{overflow:visible}" in printing and "break-inside:avoid" in printing
    # the size the README states: the fast report stays under 8 MB
    assert (out / "report.html").stat().st_size < 8e6


def test_report_names_no_document_outside_the_repository(reports):
    # The report names no document it does not hold: its "anchor §N" are in its appendix, and
    # no link, path or file name points at the shared notes or another Markdown file.
    page = (reports["out"] / "report.html").read_text()
    text = re.sub(r'src="data:[^"]*"', "", page)
    for name in ("shared/", "reference/", "verification-anchors", "design.md",
                 "continuum-notes", "ewing-foundation"):
        assert name not in text, name
    assert re.findall(r"[\w./-]+\.md\b", text) == []
    assert "anchor §" in text and 'id="anchors"' in text


def test_every_table_states_its_units(reports):
    # Every table of the page names a unit in a header cell, in parentheses or as a unit
    # column; every verification anchor has its unit (kip, in, s for the reduced anchors; kN,
    # m per metre of strip for the continuum; "–" for ratios).
    page = (reports["out"] / "report.html").read_text()
    tables = re.findall(r"<thead>(.*?)</thead>", page, flags=re.S)
    assert len(tables) >= 12
    for head in tables:
        cells = [re.sub(r"<[^>]+>", "", c) for c in re.findall(r"<th>(.*?)</th>", head)]
        assert any(re.search(r"\([^)]+\)", c) or c.strip() == "unit" for c in cells), cells
    numbers = json.loads((reports["out"] / "studies" / "verification-fast" / "summary.json")
                         .read_text())["numbers"]
    assert all(r["unit"] for r in numbers["rows"]), [r["id"] for r in numbers["rows"]
                                                    if not r["unit"]]
    units = {r["id"]: r["unit"] for r in numbers["rows"]}
    assert units["K_thth"] == "kip·in/rad" and units["nj_wall_elcentro"] == "in"
    assert units["K_r"] == "kN·m/m per rad" and units["onset_e"] == "–"


def _figures(page: str) -> list[str]:
    return re.findall(r"<figure[ >].*?</figure>", page, flags=re.S)


def _svgs(block: str) -> list[str]:
    return [base64.b64decode(d).decode("utf-8")
            for d in re.findall(r'src="data:image/svg\+xml;base64,([^"]+)"', block)]


def test_every_figure_is_captioned_vector_and_readable_in_print(reports):
    # Each <figure> has a caption with a conclusion that states a number; each plot is an SVG
    # of at most the page width (6.5 in = 468 pt: A4 and Letter less 14 mm margins hold
    # 7.2 in) and 8.6 in high (Letter's text height 9.9 in less a caption), whose every text
    # is at least 9 pt (one SVG unit is one point); the error maps
    # are split: the readable ones in the page, the all-panel ones behind <details>.
    from upliftlab.comparisons.framework.figure_record import MIN_FONT_PT, PAGE_WIDTH_IN
    from upliftlab.comparisons.framework.map_figures import MAX_HEIGHT_IN

    page = (reports["out"] / "report.html").read_text()
    figures = _figures(page)
    assert len(figures) >= 25
    plots = 0
    for block in figures:
        conclusion = re.search(r'<span class="conclusion">(.*?)</span>', block, flags=re.S)
        assert conclusion and re.search(r"\d", conclusion.group(1)), block[-400:]
        for svg in _svgs(block):
            plots += 1
            width = float(re.search(r'<svg[^>]*\bwidth="([\d.]+)pt"', svg).group(1))
            height = float(re.search(r'<svg[^>]*\bheight="([\d.]+)pt"', svg).group(1))
            assert width <= 72 * PAGE_WIDTH_IN + 1e-6
            assert height <= 72 * MAX_HEIGHT_IN + 1e-6  # printed whole, never scaled down
            sizes = [float(x) for x in re.findall(r"font-size:\s*([\d.]+)px", svg)]
            assert sizes and min(sizes) >= MIN_FONT_PT
    assert plots == len(figures) - page.count('class="anim"') >= 24
    dense = page.split('<details class="dense">', 1)[1].split("</details>", 1)[0]
    assert len(_figures(dense)) >= 9  # one all-measures grid per map and case
    assert "Where do two springs replace the bed?" in page.split('<details class="dense">')[0]


def test_captions_state_the_studies_own_numbers(reports):
    # The conclusions are computed from the data each figure plots; the studies' summaries
    # compute the same numbers by their own code (summary.json): the two-spring onset and
    # capacity ratios (anchor §2: 1.73/(1 + 1/N) and 0.58) and Figs. 11–12's peaks.
    out = reports["out"]
    page = html.unescape((out / "report.html").read_text())
    two = json.loads((out / "studies" / "two_spring_equivalence-fast" / "summary.json")
                     .read_text())["numbers"]
    assert (f"start to uplift at {two['onset_ratio_equivalent_vs_winkler']:.2f} × the bed's "
            f"onset moment and end at {two['capacity_ratio_equivalent_vs_winkler']:.2f} × its "
            "capacity") in page
    fixed = json.loads((out / "studies" / "fixed_vs_uplift-fast" / "summary.json")
                       .read_text())["numbers"]["figures"]
    for fig in fixed.values():
        peaks = fig["peak_u"]
        assert (f"changes the peak deformation from {peaks['fixed']:.3g} in to "
                f"{peaks['C']:.3g} in (× {fig['ratio_u']:.2f})") in page


def test_the_uplift_animation_has_a_frame_slider_with_contact_and_gap(reports):
    # The pushover's frames (PNG renders with the contact pressure and gap panel) behind an
    # <input type=range> spanning them, the last frame shown, at most MAX_FRAMES frames.
    from upliftlab.comparisons.studies.uplift_figures import MAX_FRAMES

    page = (reports["out"] / "report.html").read_text()
    anim = [b for b in _figures(page) if 'class="anim"' in b]
    assert len(anim) == 1
    frames = re.findall(r"<img [^>]*>", anim[0])
    assert 2 <= len(frames) <= MAX_FRAMES
    assert all('src="data:image/png;base64,' in f for f in frames)
    assert sum(" hidden" in f for f in frames) == len(frames) - 1 and " hidden" not in frames[-1]
    slider = re.search(r'<input type="range" min="0" max="(\d+)" step="1" value="(\d+)"',
                       anim[0])
    assert slider and int(slider.group(1)) == int(slider.group(2)) == len(frames) - 1
    assert "contact pressure p" in anim[0] and "gap g" in anim[0]
    assert re.search(r"contact shrinks from 100% of B .* to \d+%", anim[0])


def _need_printing_tools() -> None:
    """Chromium and poppler, which the print test needs (the README names them): their
    absence is a failure that says what to install."""
    from upliftlab.comparisons.report.printing import browser

    if browser() is None or shutil.which("pdftotext") is None:
        pytest.fail("printing needs chromium and poppler-utils (apt-get install chromium "
                    "poppler-utils)")


def test_frame_slider_script_shows_the_chosen_frame_offline(reports, tmp_path):
    # The page opened from disk in headless Chromium (no network) with the slider set to
    # frame 0: the inline script shows frame 0 only and writes frame 0's label (the DOM
    # after the script ran; reference: the frame labels in the page itself).
    from upliftlab.comparisons.report.printing import browser

    _need_printing_tools()
    page = (reports["out"] / "report.html").read_text()
    moved = re.sub(r'(<input type="range" min="0" max="\d+" step="1" value=")\d+"',
                   r'\g<1>0"', page)
    assert moved != page
    copy = tmp_path / "slider.html"
    copy.write_text(moved)
    done = subprocess.run([browser(), "--headless", "--no-sandbox", "--disable-gpu",
                           "--disable-background-networking", "--no-first-run",
                           f"--user-data-dir={tmp_path / 'profile'}", "--dump-dom",
                           copy.as_uri()], capture_output=True, text=True, timeout=300)
    anim = re.search(r'<figure class="anim">.*?</figure>', done.stdout, flags=re.S).group(0)
    frames = re.findall(r"<img [^>]*>", anim)
    assert [" hidden" in f for f in frames] == [False] + [True] * (len(frames) - 1)
    first = html.unescape(re.search(r'data-label="([^"]*)"', frames[0]).group(1))
    assert html.unescape(re.search(r"<output>(.*?)</output>", anim).group(1)) == first


def _pdf_words(pdf: Path) -> list[tuple[float, float, list[tuple[float, float, str]]]]:
    """Per page: (width, height, [(xMin, xMax, word)]) from pdftotext -bbox."""
    done = subprocess.run(["pdftotext", "-bbox", str(pdf), "-"], capture_output=True,
                          text=True, check=True)
    pages = []
    for chunk in done.stdout.split("<page ")[1:]:
        w, h = (float(v) for v in re.search(r'width="([\d.]+)" height="([\d.]+)"',
                                              chunk).groups())
        words = [(float(a), float(b), html.unescape(t)) for a, b, t in re.findall(
            r'<word xMin="([\d.]+)" yMin="[\d.]+" xMax="([\d.]+)" yMax="[\d.]+">(.*?)</word>',
            chunk)]
        pages.append((w, h, words))
    return pages


def test_report_prints_on_a4_and_letter_with_every_column_and_figure(reports, tmp_path):
    # Printed by headless Chromium (comparisons/report/printing.py): the page size is the
    # paper's (A4 595.28 × 841.89 pt, Letter 612 × 792 pt, within 1 pt); every table header
    # cell's words and every figure's number ("Figure k.") are in the PDF's text; no word
    # lies outside the page's 14 mm margins (a cut table column or figure would).
    from upliftlab.comparisons.report.printing import PAPERS, print_pdf

    _need_printing_tools()
    page = (reports["out"] / "report.html").read_text()
    headers = {re.sub(r"<[^>]+>", "", html.unescape(h)).strip()
               for h in re.findall(r"<th>(.*?)</th>", page, flags=re.S)}
    figures = len(_figures(page))
    frame = re.search(r'<figure class="anim">.*?src="data:image/png;base64,([^"]+)"', page,
                      flags=re.S).group(1)
    frame_size = struct.unpack(">II", base64.b64decode(frame)[16:24])  # PNG IHDR width, height
    body = re.sub(r"<(style|script|head|output)\b.*?</\1>", " ", page, flags=re.S)
    shown = Counter(html.unescape(re.sub(r"<[^>]+>", " ", body)).split())
    margin = 14 / 25.4 * 72
    counts = {}
    for paper, (_, (width, height)) in PAPERS.items():
        pdf = print_pdf(reports["out"] / "report.html", tmp_path / f"{paper}.pdf", paper)
        pages = _pdf_words(pdf)
        counts[paper] = len(pages)
        assert pages, paper
        for w, h, words in pages:
            assert (w, h) == pytest.approx((width, height), abs=1.0), paper
            assert all(margin - 3 <= a and b <= w - margin + 3 for a, b, _ in words), (
                paper, [t for a, b, t in words if a < margin - 3 or b > w - margin + 3][:5])
        printed = Counter(t for _, _, words in pages for _, _, t in words)
        joined = " ".join(t for _, _, words in pages for _, _, t in words)
        # every word of a table header is printed at least as often as the page shows it: a
        # column cut off the page would take its header's words with it
        for word in {w for header in headers for w in header.split()}:
            assert printed[word] >= shown[word], (paper, word, printed[word], shown[word])
        for k in range(1, figures + 1):
            assert f"Figure {k}." in joined, (paper, k)
        # the animation prints one frame (the one shown), not its whole stack of frames
        listed = subprocess.run(["pdfimages", "-list", str(pdf)], capture_output=True,
                                text=True, check=True).stdout.splitlines()[2:]
        sizes = Counter((int(r.split()[3]), int(r.split()[4])) for r in listed)
        assert sizes[frame_size] == 1, (paper, frame_size, sizes)
    print(f"pages: {counts}")

def test_every_verification_row_passes_with_its_tolerance(reports):
    # Each row carries its measured value, reference and tolerance; every one passes. Only the
    # continuum levels that fast mode skips by design may be skipped, and they say so.
    numbers = json.loads((reports["out"] / "studies" / "verification-fast" / "summary.json")
                         .read_text())["numbers"]
    rows = {r["id"]: r for r in numbers["rows"]}
    assert numbers["passed"] and numbers["counts"]["fail"] == 0
    skipped = {k for k, r in rows.items() if r["status"] == "skipped"}
    assert skipped == {"prandtl_16", "prandtl_richardson"}
    assert all("full mode only" in rows[k]["note"] for k in skipped)
    for r in rows.values():
        if r["status"] == "skipped":
            continue
        assert r["status"] == "pass", r
        if r["kind"] in ("relative", "absolute"):
            tol = float(re.findall(r"[\d.e+-]+$", r["tolerance"])[0])
            assert abs(r["error"]) <= tol, r
    # numbers that must come through unchanged (anchor §2, §3, §5, §1, §4)
    assert rows["K_thth"]["measured"] == pytest.approx(7.2576e7, rel=1e-12)
    assert rows["K_Xth"]["measured"] == pytest.approx(-1.44e5, rel=1e-12)
    assert rows["onset_edges"]["measured"] == pytest.approx(50.0, rel=1e-12)
    assert abs(rows["pushover_M"]["error"]) <= 5e-3
    assert rows["drop_dy_10"]["measured"] == pytest.approx(0.15540, rel=1e-4)
    assert rows["housner_period"]["measured"] == pytest.approx(1.944300, rel=0.01)
    for name in ("nj_short_period_elcentro", "nj_long_period_elcentro", "nj_wall_elcentro"):
        assert abs(rows[name]["error"]) <= 1e-4
    assert rows["K_r"]["expected"] == pytest.approx(math.pi * 50e3 / 2.6 * 4 / (8 * 0.7))
    assert 0.0 <= rows["prandtl_8"]["measured"] <= 0.05
    orders = {(o["case"].split(" ")[0], o["method"]): o for o in numbers["orders"]}
    assert orders["smooth", "rk4"]["slope"] == pytest.approx(4.0, abs=0.15)
    assert orders["uplifting", "events"]["slope"] > 3.7



def verification_folder_matches_its_tables(folder: Path) -> None:
    """A consistency check, not an accuracy one: the dataset that upliftlab.open_study reads
    back from a verification folder (verification.nc) holds the anchors and orders that
    anchors.csv and orders.csv of the same folder list, id for id (the CSV header) and value
    for value (the CSV keeps 10 significant digits: 1e-9 relative)."""
    import numpy as np

    import upliftlab

    ds = upliftlab.open_study(folder)["verification"].to_dataset()
    anchors = np.loadtxt(folder / "anchors.csv", delimiter=",", comments="#", skiprows=2,
                         ndmin=2)
    header = (folder / "anchors.csv").read_text().splitlines()[0].split(": ", 1)[1]
    assert [item.split("=", 1)[1] for item in header.split("; ")] == ds.anchor.values.tolist()
    for column, name in ((1, "measured"), (2, "expected"), (3, "error")):
        np.testing.assert_allclose(ds[name].values, anchors[:, column], rtol=1e-9, atol=0,
                                   equal_nan=True)
    passed = np.where(ds.status.values == "pass", 1.0,
                      np.where(ds.status.values == "fail", 0.0, np.nan))
    np.testing.assert_array_equal(passed, anchors[:, 4])
    orders = np.loadtxt(folder / "orders.csv", delimiter=",", comments="#", skiprows=2,
                        ndmin=2)
    np.testing.assert_allclose(ds.order_slope.values, orders[:, 1], rtol=1e-9, equal_nan=True)
    numbers = json.loads((folder / "summary.json").read_text())["numbers"]
    assert numbers["counts"]["pass"] == int((ds.status == "pass").sum()) + int(
        (ds.order_status == "pass").sum())


def test_the_verification_folder_opens_as_the_dataset_of_its_tables(reports):
    # The fast report's verification folder, opened again (consistency of its files).
    verification_folder_matches_its_tables(reports["out"] / "studies" / "verification-fast")

def test_two_spring_ratios_come_through(reports):
    # Anchor §2: equivalent springs uplift at 0.288675 N B, the uniform bed at (1/6)(1 + 1/N)
    # N B with N strips, so the onset ratio is 1.7321/(1 + 1/N); the capacity ratio as θ → ∞
    # is 0.288675/0.5 = 0.5774 (the bed's extrapolated in θ^(-1/2)).
    out = reports["out"]
    numbers = json.loads((out / "studies" / "two_spring_equivalence-fast" / "summary.json")
                         .read_text())["numbers"]
    n = numbers["springs"]
    onset = numbers["onset_ratio_equivalent_vs_winkler"]
    capacity = numbers["capacity_ratio_equivalent_vs_winkler"]
    assert onset == pytest.approx(math.sqrt(3) / (1 + 1 / n), rel=1e-3)
    assert onset == pytest.approx(1.73, rel=0.02)
    assert capacity == pytest.approx(0.58, rel=0.01)
    page = (out / "report.html").read_text()
    assert f"{onset:.4f}" in page and f"{capacity:.4f}" in page


def test_second_report_reuses_stored_results(reports):
    # The second run computes nothing: every section is read from a store, the verification
    # record is the one written by the first run (same computation time stamp), and no record
    # was added or rewritten. (Markers and records, never wall time.)
    assert reports["second"].returncode == 0, reports["second"].stderr[-3000:]
    # The comparison below needs the same sources for both runs; a working tree edited while
    # the test runs fails here, with the reason, rather than passing by skipping.
    assert not reports["sources_changed"], "upliftlab's sources changed during the test: rerun"
    first, second = reports["first_json"]["sections"], reports["second_json"]["sections"]
    ok = [name for name, s in first.items() if s["status"] == "ok"]
    assert {"verification", "two_spring_equivalence", "paper", "uplift_zone"} <= set(ok)
    assert all(second[name]["source"] == "store" for name in ok), second
    assert first["verification"]["source"] == "computed"
    assert reports["records_second"] == reports["records_first"]
    numbers = json.loads((reports["out"] / "studies" / "verification-fast" / "summary.json")
                         .read_text())["numbers"]
    assert numbers["reused"] is True
    assert "read from the store" in (reports["out"] / "report.html").read_text()


def test_missing_or_failing_study_is_reported_and_fails_the_command(reports, capsys):
    # A study module that does not exist and one that raises each leave a section with the
    # message, and make the command fail: `upliftlab report` exited 0 with 3 of 7 sections
    # failed (an unreachable scheduler). The verification is read from the same store: cheap.
    from dataclasses import replace

    from upliftlab.comparisons.studies.fixed_vs_uplift import DEFINITION

    def broken(scene, context):
        raise RuntimeError("deliberately broken study")

    studies = ("verification", "no_such_study_module",
               replace(DEFINITION, name="broken", title="Broken", compute=broken))
    report = rp.build_report(True, out=reports["out"], studies=studies)
    assert not report.ok and report.passed
    assert report.section("verification").source == "store"
    assert report.section("no_such_study_module").status == "missing"
    assert report.section("broken").status == "error"
    page = report.path.read_text()
    assert "upliftlab.comparisons.studies.no_such_study_module does not exist" in page
    assert "deliberately broken study" in page
    from upliftlab.outdir import read_marker
    assert read_marker(reports["out"]) is None  # a failed report is not marked complete
    ok = rp.build_report(True, out=reports["out"], studies=studies[:1])
    assert ok.ok and read_marker(reports["out"])["complete"]


def test_a_failing_verification_gives_exit_1(tmp_path, monkeypatch):
    # The exit status is 1 when a verification row fails (a check that reports a failure).
    from upliftlab.comparisons.studies import verification as vf

    def wrong(ctx):
        return [vf.relative_row("reduced", "wrong", "a deliberately wrong anchor", "none", 1.1,
                                1.0, 0.01)]

    monkeypatch.setattr(vf.workflow, "CHECKS", (("reduced", "wrong", wrong),))
    report = rp.build_report(True, out=tmp_path / "r", studies=("verification",))
    assert not report.ok and not report.passed
    assert "a deliberately wrong anchor" in report.path.read_text()


def test_bad_options_are_refused_with_exit_code_2(tmp_path, capsys):
    # Bad input: a clear message naming the option, exit code 2, nothing written.
    afile = tmp_path / "a_file"
    afile.write_text("")
    assert cli_main(["report", "--fast", "--out", str(afile)]) == 2
    assert "--out" in capsys.readouterr().err
    assert cli_main(["report", "--fast", "--scheduler", " ", "--out",
                     str(tmp_path / "x")]) == 2
    assert "--scheduler" in capsys.readouterr().err
    assert not (tmp_path / "x").exists()
    assert cli_main(["report", "--fast", "--budget", "0", "--out", str(tmp_path / "x")]) == 2
    assert "--budget = 0" in capsys.readouterr().err
    assert not (tmp_path / "x").exists()
    assert cli_main(["report", "--no-such-option"]) == 2
    assert capsys.readouterr().err.count("\n") == 1  # one line, not the usage
    assert cli_main(["report", "--fast", "--out", str(afile / "under")]) == 2
    assert "lies under" in capsys.readouterr().err
    with pytest.raises(InputError, match="fast"):
        rp.build_report("yes", out=tmp_path / "y")


def test_markdown_subset():
    # The converter (markdown-it-py, CommonMark with pipe tables): headings shifted with ids,
    # tables (a literal bar escaped as GFM has it), lists, code, no raw HTML, no links (their
    # text only).
    text = ("# T\n\nA *b* **c** `d<e>` [x](https://example.org)\n\n- one\n- two\n\n"
            "| a | \\|err\\| |\n|---|---|\n| 1 | pass |\n\n```\n<raw>\n```\n<b>no</b>")
    out = rp.markdown_to_html(text, shift=2)
    assert '<h3 id="t">T</h3>' in out and "<em>b</em>" in out and "<strong>c</strong>" in out
    assert "<code>d&lt;e&gt;</code>" in out and "https" not in out and ">x<" not in out
    assert re.search(r"<ul>\s*<li>one</li>\s*<li>two</li>\s*</ul>", out)
    assert "<th>|err|</th>" in out and '<span class="ok">pass</span>' in out
    assert "&lt;raw&gt;" in out and "<b>" not in out


def test_a_table_with_bars_and_code_keeps_its_cells():
    # A GFM table whose cells hold escaped bars, inline code with a bar and a bed's code: one
    # <table> of 1 header row and 2 body rows of exactly 3 cells each (reference: the GFM
    # specification's tables extension, example 200: "\\|" inside a cell, code included).
    text = ("| bed | rule | \\|error\\| (%) |\n|---|---|---:|\n"
            "| `ES-f-I` | `a \\| b` | 1.5 |\n| U-p-G | *k*/w | 12 |\n")
    out = rp.markdown_to_html(text)
    assert out.count("<table>") == 1 and out.startswith('<div class="scroll"><table>')
    rows = re.findall(r"<tr>(.*?)</tr>", out, flags=re.S)
    assert [len(re.findall(r"<t[hd][ >]", r)) for r in rows] == [3, 3, 3]
    assert "<code>a | b</code>" in out and "|error| (%)" in out
    assert '<td class="name">U-p-G</td>' in out


def test_headings_get_unique_ids_that_links_can_use():
    # Each heading's id is its slug (after the caller's prefix), unique within one call.
    from upliftlab.comparisons.report.markdown import slug

    assert slug("§2 Ewing's stiffness matrix") == "2-ewing-s-stiffness-matrix"
    out = rp.markdown_to_html("## Results\n\n## Results\n\n### Peak θ", prefix="map-")
    assert re.findall(r'id="([^"]+)"', out) == ["map-results", "map-results-2", "map-peak-θ"]


def test_every_link_of_the_report_lands_on_an_element(reports):
    # Every in-page link (the contents, the findings, the anchors, the figures) names an id
    # that the page holds, and no id is given twice.
    page = reports["page"]
    ids = re.findall(r'\sid="([^"]+)"', page)
    assert len(ids) == len(set(ids)), [i for i, n in Counter(ids).items() if n > 1][:5]
    targets = {h[1:] for h in re.findall(r'href="(#[^"]*)"', page)}
    assert targets and targets <= set(ids), sorted(targets - set(ids))[:5]


def test_a_cell_that_is_one_hyphenated_name_stays_on_one_line():
    # A browser breaks after a hyphen: the printed map table showed "ES-f-" over "I". A cell that
    # is one short hyphenated name is kept whole; a cell of words is free to wrap.
    out = rp.markdown_to_html("| pick | note |\n|---|---|\n| ES-f-I | a well-kept bed |")
    assert '<td class="name">ES-f-I</td>' in out and "<td>a well-kept bed</td>" in out
    assert '<th>pick</th>' in out


def test_a_full_build_finds_every_map_run_in_the_kept_store(tmp_path):
    # The full build's Winkler map resumes the continuum runs kept with the repository
    # (benchmarks/winkler_map_store), which hold its whole grid: estimated as the full build
    # estimates it before its first run, no continuum run is left to make, so the report's
    # budget refuses nothing. The whole grid is 1268 runs by hand (2 soils × 4 FS_v × 3 h/B ×
    # 2 periods × 2 intensities × 13 motions = 1248 dynamic, and 20 static), all of them
    # stored; the docs say so (docs/comparisons.md). Reading the store writes nothing to it.
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.beds import bed_names
    from upliftlab.comparisons.studies.winkler_map import (DEFINITION, FULL_GRID, FULL_OPTIONS,
                                                           estimate_map)
    from upliftlab.comparisons.studies.winkler_map.motions import study_motions

    kept = rp.CHECKOUT / DEFINITION.kept_store
    if not kept.is_dir():  # the README's test command installs the checkout (-e)
        pytest.fail(f"no kept map runs at {kept}: the tests run from a checkout")
    before = {p.name: p.read_bytes() for p in kept.rglob("*") if p.is_file()}
    motions = study_motions(FULL_GRID, FULL_OPTIONS, tmp_path)
    estimate = estimate_map(FULL_GRID, FULL_OPTIONS, bed_names(FULL_OPTIONS), motions,
                            Store(kept))
    assert (estimate.runs, estimate.stored) == (0, 1268)
    # at most a sample of each point function's records made by earlier code is made again
    # to check them (three of each of the five), at their own recorded wall times
    assert estimate.checks <= 15 and estimate.seconds == estimate.check_seconds
    page = " ".join((rp.CHECKOUT / "docs" / "comparisons.md").read_text().split())
    assert "every one of its 1,268 continuum runs is kept" in page
    assert {p.name: p.read_bytes() for p in kept.rglob("*") if p.is_file()} == before


def test_a_fast_build_keeps_to_its_own_stores():
    # The kept runs are the full grid's on the reference mesh: a fast build (4 elements
    # across) never reads or writes them.
    from upliftlab.comparisons.studies.winkler_map import DEFINITION

    run = rp._Run(True, Path("unused"), None, None, 3600.0)
    assert DEFINITION.kept_store and run.study_store(DEFINITION, print) is None


#: The README's full build (after ``upliftlab``; the test adds the value of the last --out).
README_FULL = ["report", "--out", "results/report", "--out"]


@pytest.mark.slow
def test_the_readmes_full_build_builds_every_section(tmp_path, elcentro):
    # The README's `upliftlab report --out results/report` from a checkout: every section is
    # built, the Winkler map's from the kept continuum runs (its whole grid is kept, so the
    # default budget refuses nothing and no continuum run is made); the command exits 0.
    from upliftlab.comparisons.studies.winkler_map import DEFINITION

    kept = rp.CHECKOUT / DEFINITION.kept_store
    before = sorted(p.name for p in kept.rglob("*.json"))
    out = tmp_path / "report"
    assert cli_main([*README_FULL, str(out)]) == 0
    sections = json.loads((out / "report.json").read_text())["sections"]
    assert {name: s["status"] for name, s in sections.items() if s["status"] != "ok"} == {}
    assert "winkler_map" in sections and (out / "report.html").is_file()
    assert sorted(p.name for p in kept.rglob("*.json")) == before


def test_the_estimate_is_printed_before_the_first_section_starts(tmp_path, monkeypatch, capsys):
    # `upliftlab report --fast` into an empty folder, each section's run replaced by a stub
    # that only notes on stderr that it started: the estimate is one stderr line printed before
    # the first section starts, and its total equals the sum of its per-section estimates
    # within rounding (each printed to the second: 0.5 s per section, and 0.5 s for the
    # total). References: the report's documented rates (rp.SECTION_SECONDS, fast column) for
    # the sections without an estimate of their own, and for the Winkler map its own estimate
    # (winkler_map.estimate_map on the map's empty store, as the map makes it before its first
    # run) plus rp.MAP_REST_SECONDS. After each section a progress line gives the time left.
    from upliftlab.comparisons.report.html import Section
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.beds import bed_names
    from upliftlab.comparisons.studies.winkler_map import FAST_GRID, FAST_OPTIONS, estimate_map
    from upliftlab.comparisons.studies.winkler_map.motions import study_motions

    def stub(item, run, record_sha, say):
        name = item if isinstance(item, str) else item.name
        sys.stderr.write(f"<section {name} starts>\n")
        return Section(name, name, "", "error", "", 0.0, error="not run in this test")

    monkeypatch.setattr(rp, "_run_section", stub)
    out = tmp_path / "fast"
    code = cli_main(["report", "--fast", "--out", str(out)])
    err = capsys.readouterr().err.splitlines()
    assert code == 1  # every section stubbed as failed
    first = next(i for i, line in enumerate(err) if line.startswith("<section "))
    lines = [i for i, line in enumerate(err) if "before any section runs" in line]
    assert len(lines) == 1 and lines[0] < first
    line = err[lines[0]]
    total = float(re.search(r"estimated (\d+) s \(", line).group(1))
    parts = dict(re.match(r"(\w+) (\d+) s \(", part).groups()
                 for part in line.split("before any section runs: ", 1)[1].split("; "))
    printed = {name: float(value) for name, value in parts.items()}
    assert list(printed) == list(rp.STUDIES)
    assert abs(total - sum(printed.values())) <= 0.5 * (len(printed) + 1)
    for name, (fast, _) in rp.SECTION_SECONDS.items():
        assert printed[name] == pytest.approx(fast, abs=0.5)
    motions = study_motions(FAST_GRID, FAST_OPTIONS, tmp_path / "motions")
    own = estimate_map(FAST_GRID, FAST_OPTIONS, bed_names(FAST_OPTIONS), motions,
                       Store(tmp_path / "empty"))
    assert own.runs > 0 and own.stored == 0
    assert printed["winkler_map"] == pytest.approx(own.seconds + rp.MAP_REST_SECONDS[0],
                                                   abs=0.5)
    progress = [line for line in err if "sections done" in line]
    assert len(progress) == len(rp.STUDIES)
    assert f"{len(progress)}/{len(progress)} sections done" in progress[-1]
    assert "about 0 s left" in progress[-1]


def _visible(page: str) -> str:
    """The page's text as a reader sees it (no tags, styles, scripts or embedded images)."""
    body = re.sub(r"<(style|script|head)\b.*?</\1>", " ", page, flags=re.S)
    return html.unescape(re.sub(r"<[^>]+>", " ", body))


def test_a_missing_number_is_said_not_printed():
    # The class of "Δt = nan s": a value that is not a finite number is never formatted as
    # one. number_text says what is missing; a refused run's label has no step.
    import math

    from upliftlab.number_text import number_text
    from upliftlab.comparisons.studies.speed_vs_error.analysis import Run
    from upliftlab.comparisons.studies.speed_vs_error.summary import short_label

    assert number_text(0.0123456, ".3g", "s") == "0.0123 s"
    assert number_text(math.nan, ".3g", "s") == "not measured" and number_text(None) == \
        "not measured"
    assert number_text(math.inf, unbounded="never") == "never"
    assert number_text(-math.inf) == "−unbounded"
    refused = Run("edges", 2, "newmark", math.nan, math.nan, 0, {}, {}, "refused")
    assert short_label(refused) == "2 springs ±b, newmark, Δt not recorded (the run was refused)"
    ran = Run("winkler", 10, "events", 0.0025, 0.01, 5, {}, {})
    assert short_label(ran) == "N = 10, events, Δt = 0.0025 s"


def test_no_number_of_the_report_is_printed_as_nan_or_inf(reports):
    # Whatever section writes it, the page a reader sees holds no "nan" or "inf" where a
    # number was meant to be (it printed "Δt = nan s" for refused runs, "R_k = inf" and
    # "B = inf" for a decay never reached).
    text = _visible(reports["page"])
    found = [text[max(0, m.start() - 60):m.end() + 20]
             for m in re.finditer(r"(?i)(?<![\w-])[+−-]?(nan|inf|infinity)(?![\w-])", text)]
    assert found == []


def test_the_report_opens_with_the_three_findings(reports):
    # The findings come first, above the verification's status box: three paragraphs, each
    # with the numbers its study wrote (summary.json, read here independently of the report's
    # code) and a figure with an id that a link names.
    from upliftlab.comparisons.beds import BEDS

    page = reports["page"]
    assert page.index('id="findings"') < page.index('class="status')
    opening = page.split('<section id="findings">', 1)[1].split("</section>", 1)[0]
    text = " ".join(_visible(opening).split())
    studies = reports["out"] / "studies"

    def numbers(name):
        return json.loads((studies / f"{name}-fast" / "summary.json").read_text())["numbers"]

    two, area, speed = (numbers(n) for n in ("two_spring_equivalence", "winkler_map",
                                             "speed_vs_error"))
    for k in (1, 2, 3):
        assert f'id="finding-{k}"' in opening
    assert f"uplifts at {two['onset_ratio_equivalent_vs_winkler']:.2f} times" in text
    assert f"caps the moment at {two['capacity_ratio_equivalent_vs_winkler']:.2f}" in text
    best = BEDS[area["share"]["best"]].short
    assert f"the best bed, {best}" in text
    assert f"at {100 * area['share']['best_share']:.1f} % of the points" in text
    front = text.split("points by integrator: ", 1)[1].split(".", 1)[0].split(", ")
    assert sorted(front) == sorted(f"{k} {v}" for k, v in
                                   speed["pareto_points_by_integrator"].items())
    figures = re.findall(r'<figure id="(finding-fig-[^"]+)"', opening)
    assert len(figures) == 3, figures
    for ident in figures:
        assert f'id="{ident.removeprefix("finding-")}"' in page  # its own copy in its section


def test_every_bed_code_is_explained_at_its_first_use(reports):
    # Every registered bed code that the page uses (in its prose: code spans hold the beds'
    # long names, "qz" among them) is, at its first use, an <abbr> titled with the registry's
    # label followed by the label in parentheses, or first in the legend line above the table
    # that first uses it, where the table's cell is the <abbr>.
    from upliftlab.comparisons.beds import BEDS

    page = reports["page"]
    body = page.split("<body>", 1)[1]
    used = 0
    for entry in BEDS.values():
        label = html.escape(entry.label)
        first = re.search(r"(?<![\w-])" + re.escape(entry.short) + r"(?![\w-])",
                          re.sub(r"<code>.*?</code>|<[^>]+>", lambda m: " " * len(m.group(0)),
                                 body, flags=re.S))
        if first is None:
            continue
        used += 1
        before, after = body[:first.start()], body[first.end():]
        in_text = (before.endswith(f'<abbr title="{label}">')
                   and after.startswith(f"</abbr> ({label})"))
        legend = before.rsplit('<p class="legend">', 1)
        in_legend = (len(legend) == 2 and "</p>" not in legend[1]
                     and before.endswith("<strong>")
                     and after.startswith(f"</strong> is the {label}")
                     and after.split("</p>", 1)[1].lstrip().startswith(
                         ('<div class="scroll"><table>', "<table>")))
        assert in_text or in_legend, (entry.short, before[-120:], after[:120])
        if in_legend:  # and in the table under it, its first use is titled with the label
            table = body[first.end():].split('<div class="scroll"><table>', 1)[1]
            assert f'<abbr title="{label}">{entry.short}</abbr>' in table.split("</table>")[0]
    assert used >= 8
