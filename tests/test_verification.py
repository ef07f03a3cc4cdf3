"""The verification study's bookkeeping (upliftlab.comparisons.studies.verification).

References: the study's contract (its module docstring): a row passes exactly when its error is
within its tolerance; a check that raises becomes a failing row carrying the message; the table
is stored under a content key (inputs, version, a digest of the library's sources) and is
recomputed when, and only when, that key changes. The anchors' numbers themselves are asserted
in tests/test_report.py through the fast report.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from upliftlab.comparisons.studies import verification as vf


def test_rows_pass_exactly_within_their_tolerance():
    # |measured/expected − 1| ≤ tol passes, just beyond fails; bounds are inclusive.
    assert vf.relative_row("g", "a", "q", "r", 1.0 + 0.9e-3, 1.0, 1e-3).passed
    assert not vf.relative_row("g", "a", "q", "r", 1.0 + 1.1e-3, 1.0, 1e-3).passed
    assert vf.absolute_row("g", "a", "q", "r", -0.0204354, -0.0204, 1e-4).passed
    assert not vf.absolute_row("g", "a", "q", "r", -0.0206, -0.0204, 1e-4).passed
    assert vf.bound_row("g", "a", "q", "r", 0.05, 0.0, 0.05).passed
    assert not vf.bound_row("g", "a", "q", "r", -1e-9, 0.0, 0.05).passed
    order = vf.order_row("g", "c", "m", [0.1, 0.05, 0.025], [1e-2, 2.5e-3, 6.25e-4], "2", 1.9, 2.1)
    assert order.slope == pytest.approx(2.0, abs=1e-12) and order.status == vf.PASS


def _counting_checks(calls):
    def good(ctx):
        calls.append("good")
        return [vf.relative_row("reduced", "good", "a right anchor", "none", 2.0, 2.0, 1e-12)]

    def crash(ctx):
        raise ZeroDivisionError("a check that crashes")

    return (("reduced", "good", good), ("reduced", "crash", crash))


def test_store_key_follows_the_sources(tmp_path, monkeypatch):
    # Same key: read from the store, nothing recomputed (the checks are not called again, the
    # computation stamp is kept). A changed source digest: recomputed. A crashing check: a
    # failing row with its message, so the study does not pass.
    calls = []
    monkeypatch.setattr(vf.workflow, "CHECKS", _counting_checks(calls))
    monkeypatch.setattr(vf.workflow, "source_digest", lambda: "sources-v1")
    first = vf.run(True, out=tmp_path / "out", store=tmp_path / "store")
    again = vf.run(True, out=tmp_path / "out", store=tmp_path / "store")
    assert calls == ["good"]
    assert not first.reused and again.reused
    assert again.data.attrs["key"] == first.data.attrs["key"]
    assert again.data.attrs["computed_utc"] == first.data.attrs["computed_utc"]
    assert again.data.status.values.tolist() == [vf.PASS, vf.FAIL]
    assert "ZeroDivisionError: a check that crashes" in str(again.data.note.values[1])
    assert not again.study.numbers["passed"] and "a check that crashes" in again.study.summary
    monkeypatch.setattr(vf.workflow, "source_digest", lambda: "sources-v2")
    edited = vf.run(True, out=tmp_path / "out", store=tmp_path / "store")
    assert calls == ["good", "good"] and not edited.reused
    assert edited.data.attrs["key"] != first.data.attrs["key"]
    full = vf.run(False, out=tmp_path / "out", store=tmp_path / "store")
    assert full.data.attrs["key"] != edited.data.attrs["key"] and calls == ["good"] * 3

def test_the_code_digest_follows_the_bytes_of_the_sources_it_covers(tmp_path, monkeypatch):
    # Reference: SHA-256 over (name, bytes) of the covered files, computed here by hashlib: a
    # covered file's edit changes the digest, an uncovered one's does not.
    import hashlib

    from upliftlab import provenance as pv

    a, b = tmp_path / "a.py", tmp_path / "b.py"
    a.write_text("x = 1\n")
    b.write_text("y = 1\n")
    files = {"upliftlab.reduced/a.py": a, "upliftlab.comparisons/b.py": b}
    monkeypatch.setattr(pv, "package_files", lambda: files)
    pv._digest.cache_clear()
    expected = hashlib.sha256(b"upliftlab.reduced/a.py\0x = 1\n\0").hexdigest()
    assert pv.code_digest(["upliftlab.reduced/"]) == expected
    b.write_text("y = 2\n")
    pv._digest.cache_clear()
    assert pv.code_digest(["upliftlab.reduced/"]) == expected
    assert pv.code_digest() != expected
    monkeypatch.undo()
    pv._digest.cache_clear()  # the real sources again for the tests that follow
    assert len(vf.source_digest()) == 64


def test_drop_mass_damper_alone_is_exact():
    # Anchor §5, c* = 10, spring negligible: Δy = v0 m (1 − ε)/c* = 0.15540 in and
    # Δt = (m/c*) ln(1/ε) = 0.018476 s, energy ½ m v0² (1 − ε²); ratio ε.
    d = vf.drop_mass(10.0, k=1e-6)
    assert d["ratio"] == pytest.approx(0.7, rel=1e-6)
    assert d["dy"] == pytest.approx(10 * 0.518 * 0.3 / 10, rel=1e-6)
    assert d["duration"] == pytest.approx(0.518 / 10 * math.log(1 / 0.7), rel=1e-4)
    assert d["impact_energy"] == pytest.approx(0.5 * 0.518 * 100 * (1 - 0.49), rel=1e-6)


def test_the_stored_table_is_keyed_on_this_packages_own_checks():
    """The key's sources name the package's files (the prefix once matched no file after the
    checks moved under studies/, so an edited check read an old table as current). Reference:
    the package's folder listed by pathlib."""
    from upliftlab.comparisons.studies.verification import workflow
    from upliftlab.provenance import package_files

    named = {n.rsplit("/", 1)[-1] for n in package_files() if n.startswith(workflow.OWN_SOURCES)}
    folder = {p.name for p in Path(workflow.__file__).parent.glob("*.py")}
    assert folder and named == folder


def test_its_file_passes_the_cf_checker(tmp_path, cf_failures):
    # Reference: the IOOS compliance checker, cf:1.10 (tests/test_cf.py says which): no
    # failing required check and no check that raised in verification.nc, built from a store
    # entry of two anchors, one observed order and two checks' times (the text fields, the
    # NaN-padded fit over (order, level)); it reads back as built.
    from dataclasses import asdict

    import numpy as np

    from upliftlab.comparisons.studies.verification.dataset import verification_dataset
    from upliftlab.results import read_dataset, write_dataset

    rows = [vf.relative_row("reduced", "a", "q", "r", 2.0, 2.0, 1e-3),
            vf.absolute_row("continuum", "b", "q", "r", 1.0, 1.0, 1e-3)]
    order = vf.order_row("reduced", "c", "m", [0.1, 0.05], [1e-2, 2.5e-3], "2", 1.9, 2.1)
    entry = {"rows": [asdict(r) for r in rows], "orders": [asdict(order)],
             "seconds": {"one": 1.0, "two": 2.0}}
    ds = verification_dataset(entry, {"fast": True})
    path = write_dataset(tmp_path / "verification.nc", ds)
    assert cf_failures(path) == ([], [])
    back = read_dataset(path)
    for name, var in ds.data_vars.items():
        np.testing.assert_array_equal(back[name].values, var.values, err_msg=name)
