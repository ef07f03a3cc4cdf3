"""A store keyed by what was asked, checked against what ran (``comparisons/framework/store.py``,
``comparisons/framework/freshness.py``, ``upliftlab/provenance.py``).

References: the keys' definition (SHA-256 of the study, the function's declared name, the
parameters and the models' revisions, recomputed here with hashlib), records written here with
known values, and a point function whose calls are counted: what it is asked to make again is
known by construction.
"""

from __future__ import annotations

import gzip
import hashlib
import json
import math
from concurrent.futures import ThreadPoolExecutor

import pytest

import upliftlab.continuum as continuum
from upliftlab import provenance as pv
from upliftlab.comparisons.framework import freshness as fr
from upliftlab.comparisons.framework import store as st
from upliftlab.comparisons.framework.store import Store, point_function, point_key
from upliftlab.comparisons.framework.sweep import run_sweep

CALLS: list[float] = []
FACTOR = {"value": 3.0}


@point_function("tests:triple", models=("continuum",), tolerance=1e-9)
def triple(point):
    """A point function whose calls are counted: y = FACTOR · x, with a timing to ignore."""
    CALLS.append(point["x"])
    return {"y": FACTOR["value"] * point["x"], "wall_time_s": 0.1 * len(CALLS)}


@pytest.fixture
def code(monkeypatch):
    """Set today's code digest: ``code("a")`` makes every provenance say "a" × 64."""
    CALLS.clear()
    FACTOR["value"] = 3.0

    def set_to(letter):
        monkeypatch.setattr(st, "code_digest", lambda names=None: letter * 64)
        monkeypatch.setattr(pv, "code_digest", lambda names=None: letter * 64)
    set_to("a")
    return set_to


def _sweep(store, points, **kw):
    with ThreadPoolExecutor(1) as pool:
        return run_sweep(triple, points, store, study="s", executor=pool, progress=False, **kw)


def test_a_key_is_what_was_asked_and_not_the_code(code, monkeypatch):
    """The key is SHA-256 over the study, the name, the canonical parameters and the models'
    revisions; a locator (``_path``) stays out; today's code digest does not enter; a raised
    revision gives a new key."""
    point = {"x": 1.5, "_path": "/somewhere/on/this/machine"}
    expected = hashlib.sha256("\n".join([
        '"s"', '"tests:triple"', '{"x":1.5}', '{"continuum":%d}' % continuum.REVISION]).encode())
    assert point_key("s", triple, point) == expected.hexdigest()
    code("b")
    assert point_key("s", triple, point) == expected.hexdigest()
    monkeypatch.setattr(continuum, "REVISION", continuum.REVISION + 1)
    assert point_key("s", triple, point) != expected.hexdigest()


def test_a_record_carries_its_provenance_and_no_machine_path(code, tmp_path):
    store = Store(tmp_path / "store")
    _sweep(store, [{"x": 1.0, "_path": "/home/someone/record.txt"}])
    entry = store.entry(point_key("s", triple, {"x": 1.0}))
    assert entry["provenance"]["source_sha256"] == "a" * 64
    assert entry["models"] == {"continuum": continuum.REVISION}
    assert {"numpy", "scipy", "numba", "upliftlab_version"} <= set(entry["provenance"])
    assert "/home/someone" not in json.dumps(entry)


def test_stale_records_are_checked_by_a_sample_and_then_accepted(code, tmp_path):
    """Records of code "a", read under code "b": three of the five (seeded) are made again;
    they reproduce, the store accepts "a" for "b", and a second read makes nothing again."""
    store = Store(tmp_path / "store")
    points = [{"x": float(i)} for i in range(5)]
    first = _sweep(store, points)
    assert len(CALLS) == 5
    code("b")
    CALLS.clear()
    again = _sweep(store, points)
    sample = fr.seeded_sample([point_key("s", triple, p) for p in points], 3)
    assert len(CALLS) == 3 and again == first
    assert sorted(CALLS) == sorted(next(p["x"] for p in points
                                        if point_key("s", triple, p) == k) for k in sample)
    assert store.accepted() == {"tests:triple": {"b" * 64: ["a" * 64]}}
    CALLS.clear()
    _sweep(store, points)
    assert CALLS == []


def test_stale_records_that_moved_stop_the_study_and_say_which(code, tmp_path):
    """Under code "b" the function gives 4x where "a" gave 3x: the check names the points, the
    field and the change (1/3), and accepts nothing."""
    store = Store(tmp_path / "store")
    points = [{"x": 1.0}, {"x": 2.0}]
    _sweep(store, points)
    code("b")
    FACTOR["value"] = 4.0
    with pytest.raises(fr.StaleStoreError, match=r"moved beyond the tolerance 1e-09: .* by "
                                                 r"0\.25 in y"):
        _sweep(store, points)
    assert store.accepted() == {}


def test_the_sample_is_seeded_by_the_keys():
    keys = [hashlib.sha256(str(i).encode()).hexdigest() for i in range(20)]
    one = fr.seeded_sample(keys, 3)
    assert one == fr.seeded_sample(list(reversed(keys)), 3) and len(set(one)) == 3
    assert fr.seeded_sample(keys[:2], 3) == sorted(keys[:2])


def test_record_change_compares_field_by_field():
    """Reference: the definition |a - b| / max(|a|, |b|), computed by hand."""
    old = {"m": {"theta": 0.002, "u": 0.01}, "wall_time_s": 1.0, "kind": "ok", "v": [1.0, 2.0]}
    new = {"m": {"theta": 0.002002, "u": 0.01}, "wall_time_s": 9.0, "kind": "ok",
           "v": [1.0, 2.0]}
    change, where = fr.record_change(old, new, ignore=("wall_time_s",))
    assert change == pytest.approx(0.002 / 2.002, rel=1e-12) and where == "m.theta"
    assert fr.record_change(old, {**new, "kind": "failed"}, ("wall_time_s",))[0] == math.inf
    assert fr.record_change({"v": [1.0]}, {"v": [1.0, 2.0]})[0] == math.inf
    assert fr.record_change({"x": math.nan}, {"x": math.nan}) == (0.0, "")


def test_round_off_of_a_field_is_no_change():
    """Reference: the box store's impedance record, whose vertical–rocking coupling (zero by
    symmetry) came out as −4.6e-11 and, in another environment, 7.3e-12, beside entries of
    4.3e4 in the same field: below 1e-12 of the field's largest number it is round-off (no
    change); the same difference in a field whose numbers are that small is a change (1.16,
    by the definition), and so is a change of 1e-9 of the field's largest number."""
    old = {"real": [[0.0, -1.22e-10, 43031.02941166112]], "imag": [[0.0, -4.64e-11, 82.9]]}
    new = {"real": [[0.0, -1.91e-10, 43031.02941166109]], "imag": [[0.0, 7.28e-12, 82.9]]}
    assert fr.record_change(old, new)[0] == pytest.approx(0.0, abs=1e-15)
    alone = fr.record_change({"c": [-4.64e-11]}, {"c": [7.28e-12]})
    assert alone[0] == pytest.approx((4.64e-11 + 7.28e-12) / 4.64e-11, rel=1e-12)
    moved = {**new, "real": [[0.0, -1.22e-10 + 4.3e-5, 43031.02941166112]]}
    assert fr.record_change(old, moved)[1] == "real[0][1]"


def test_a_field_only_the_new_record_has_is_an_addition_not_a_change():
    """A field today's code adds (the run's validity verdict) changes no stored number: it is
    listed, not counted; a field today's code no longer makes is a change (inf)."""
    old = {"m": {"theta": 0.002}, "dofs": 10}
    new = {"m": {"theta": 0.002, "uplift": 0.1}, "dofs": 10, "validity": "within"}
    assert fr.record_change(old, new) == (0.0, "")
    assert fr.added_fields(old, new) == ["validity", "m.uplift"]
    assert fr.record_change(new, old)[0] == math.inf
    assert fr.record_change({**old, "dofs": 11}, new)[0] == pytest.approx(1 / 11)


def test_a_pack_holds_the_records_and_reads_them_back(code, tmp_path):
    store = Store(tmp_path / "store")
    points = [{"x": float(i)} for i in range(4)]
    records = _sweep(store, points)
    keys = sorted(store.keys())
    pack = store.pack("kept")
    assert pack.name == "kept.jsonl.gz" and not list((tmp_path / "store").glob("??/*.json"))
    again = Store(tmp_path / "store")
    assert sorted(again.keys()) == keys
    CALLS.clear()
    assert _sweep(again, points) == records and CALLS == []


def test_store_verify_checks_every_functions_stale_records(code, tmp_path, capsys):
    """``upliftlab store verify DIR --sample 2``: the stale records of a declared function
    are checked and accepted (exit 0), with progress after each one made again; a store whose
    records moved ends with exit 3."""
    from upliftlab.cli import main

    store = Store(tmp_path / "store")
    _sweep(store, [{"x": float(i)} for i in range(4)])
    code("b")
    CALLS.clear()
    assert main(["store", "verify", str(tmp_path / "store"), "--sample", "2"]) == 0
    out = capsys.readouterr().out
    assert len(CALLS) == 2 and "accepted" in out
    # progress after each record made again: count, elapsed time, and the time left until the last
    assert ": 1 of 2 made again, " in out and "s left" in out.split(": 2 of 2")[0]
    assert ": 2 of 2 made again, " in out
    code("c")
    FACTOR["value"] = 5.0
    assert main(["store", "verify", str(tmp_path / "store"), "--sample", "2"]) == 3
    assert "moved beyond the tolerance" in capsys.readouterr().err


def test_store_verify_leaves_records_of_another_revision_as_data(code, tmp_path, capsys,
                                                                 monkeypatch):
    """Reference: the key holds the models' revisions, so a record of an earlier revision is
    never read again. ``store verify`` after a raised revision and a code change makes only
    today's revision's stale records again (2 of them, the sample) and says how many of the
    other it left (3), exit 0; it does not make the earlier revision's with today's code."""
    import upliftlab.continuum as continuum
    from upliftlab.cli import main

    store = Store(tmp_path / "store")
    _sweep(store, [{"x": float(i)} for i in range(3)])
    monkeypatch.setattr(continuum, "REVISION", continuum.REVISION + 1)
    _sweep(store, [{"x": float(i)} for i in range(10, 14)])
    assert len(list(store.keys())) == 7
    code("b")
    CALLS.clear()
    assert main(["store", "verify", str(tmp_path / "store"), "--sample", "2"]) == 0
    out = capsys.readouterr().out
    assert len(CALLS) == 2 and all(x >= 10 for x in CALLS)
    assert "tests:triple: 3 records of another model revision" in out


NOTE = "this is my precious note\n"
ANY_KEY = "ab" + "c" * 62


def _refused_by_the_store(argv, capsys, *names):
    """``upliftlab ARGV`` ends with exit 2 and one line naming ``names``, no traceback."""
    from upliftlab.cli import main

    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    for name in names:
        assert name in err, (name, err)
    return err


def test_store_pack_refuses_a_loose_file_it_cannot_read_and_keeps_it(tmp_path, capsys):
    """Reviewer's case: ``store pack`` packed a note in place of a record as ``null`` (exit 0),
    deleted the note and its folder, and every later verify, migrate or pack ended in a
    TypeError traceback. Now each refuses in one line naming the file (exit 2), nothing is
    moved, written or deleted."""
    root = tmp_path / "st"
    note = root / "ab" / f"{ANY_KEY}.json"
    note.parent.mkdir(parents=True)
    note.write_text(NOTE)
    for action in (["pack", str(root), "--name", "p1"], ["verify", str(root)],
                   ["migrate", str(root)]):
        err = _refused_by_the_store(["store", *action], capsys, f"store record '{note}'")
        assert ": not JSON (" in err and "a record is a JSON table with its 'key'" in err
    assert note.read_text() == NOTE
    assert sorted(p.relative_to(root).as_posix() for p in root.rglob("*")) == [
        "ab", f"ab/{ANY_KEY}.json"]


def test_store_pack_refuses_a_record_of_another_key_and_a_file_not_named_as_one(tmp_path,
                                                                               capsys):
    """A loose file under another key's name, or a ``??/*.json`` not named as a record: the
    old store packed the first as ``null`` and failed on the second with a key error that
    named no file."""
    root = tmp_path / "st"
    other = root / "cd" / f"cd{'c' * 62}.json"
    other.parent.mkdir(parents=True)
    other.write_text(json.dumps({"key": ANY_KEY, "record": 1}))
    err = _refused_by_the_store(["store", "pack", str(root), "--name", "p"], capsys, str(other))
    assert f"holds the record of key '{ANY_KEY}', not of its file name's" in err
    other.unlink()
    stray = root / "cd" / "notes.json"
    stray.write_text("{}")
    err = _refused_by_the_store(["store", "pack", str(root), "--name", "p"], capsys,
                                f"store file '{stray}': not named as a record")
    assert stray.read_text() == "{}" and not (root / "packs").exists()


@pytest.mark.parametrize("data, where", [
    (b"garbage\n", ": cannot be read as gzip-compressed JSON lines (Not a gzipped file"),
    (gzip.compress(mtime=0, data=b'{"a":1}\n'), ", line 1: not a record; "),
    (gzip.compress(mtime=0, data=b'{"key":"' + ANY_KEY.encode() + b'","record":1}\nnull\n'),
     ", line 2: not a record; "),
    (gzip.compress(mtime=0, data=b'{"key":"' + ANY_KEY.encode() + b'","record":1}\n{"key":\n'),
     ", line 2: not JSON ("),
    (gzip.compress(mtime=0, data=b'{"key":"' + ANY_KEY.encode() + b'","record":1}\n')[:-9],
     ": cannot be read as gzip-compressed JSON lines ("),
], ids=["not gzip", "a table without key", "null", "not JSON", "cut short"])
def test_a_pack_that_is_not_one_is_refused_naming_it_and_its_line(data, where, code, tmp_path,
                                                                  capsys):
    """``store verify`` of a pack of 'garbage' raised BadGzipFile, of a line '{"a":1}' a
    KeyError; a ``null`` line (what the old ``pack`` wrote) a TypeError. Each command now
    refuses in one line naming the pack (and the line); ``pack`` moves no loose record."""
    root = tmp_path / "st"
    _sweep(Store(root), [{"x": 1.0}])
    loose = sorted(root.glob("??/*.json"))
    pack = root / "packs" / "x.jsonl.gz"
    pack.parent.mkdir()
    pack.write_bytes(data)
    for action in (["verify", str(root)], ["migrate", str(root)],
                   ["pack", str(root), "--name", "x"], ["pack", str(root), "--name", "y"]):
        _refused_by_the_store(["store", *action], capsys, f"store pack '{pack}'{where}")
    assert pack.read_bytes() == data and sorted(root.glob("??/*.json")) == loose
    assert sorted(p.name for p in pack.parent.iterdir()) == ["x.jsonl.gz"]


def test_a_study_refuses_a_corrupt_record_before_any_work(code, tmp_path):
    """A sweep read a loose file that is not its record as missing, made the point again and
    wrote over the file. It now stops before any work with the file's name, the file kept."""
    store = Store(tmp_path / "store")
    key = point_key("s", triple, {"x": 1.0})
    store.path(key).parent.mkdir(parents=True)
    store.path(key).write_text(NOTE)
    with pytest.raises(st.InputError, match=f"store record '{store.path(key)}': not JSON"):
        _sweep(store, [{"x": 0.0}, {"x": 1.0}])
    assert CALLS == [] and store.path(key).read_text() == NOTE
    assert [p.name for p in (tmp_path / "store").rglob("*.json")] == [f"{key}.json"]


@pytest.mark.parametrize("text, said", [
    ("{not json", "not JSON ("),
    ('["accepted"]', "not a table of accepted code digests"),
    ('{"accepted": 3}', "not a table of accepted code digests"),
])
def test_a_provenance_file_that_is_not_one_is_refused_not_written_over(text, said, code,
                                                                       tmp_path):
    """A ``provenance.json`` that could not be read was taken as empty, and the next check's
    stamp wrote over it: the checks it held were lost. Now it is refused naming it, and kept."""
    store = Store(tmp_path / "store")
    _sweep(store, [{"x": 1.0}])
    (tmp_path / "store" / st.STAMPS).write_text(text)
    code("b")
    with pytest.raises(st.InputError) as refused:
        _sweep(store, [{"x": 1.0}])
    assert f"provenance.json': {said}" in str(refused.value)
    assert (tmp_path / "store" / st.STAMPS).read_text() == text
