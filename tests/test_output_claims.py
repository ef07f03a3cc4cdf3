"""Output folders claimed (``upliftlab/outdir.py``): ``upliftlab study`` claims its folder as
every command does, the completion marker of any command lists only the files upliftlab made,
and the folder is judged before any work (the impedance's mesh came first).

A study names its files only as it writes them, so a file of the user's at one of their names
is refused when the study comes to write it (``guard``): before, the study replaced it. The
user's file must be left as it was, with or without ``--force``, and the next run, once it is
moved, must write everything.

Reference: the project's rule (upliftlab replaces and lists as its own only the files it made);
each test names the harmful outcome and asserts its absence (a user's file changed, a user's
file listed in the marker, a study's own file refused on the next run).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, replace

import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main
from upliftlab.outdir import MARKER, WRITING, claim

#: The files the stand-in study writes, in its order: a figure in a subfolder, then the
#: summary (:func:`~upliftlab.comparisons.framework.study.write_summary`).
WRITTEN = ["figures/a.png", "summary.md", "summary.json"]


@dataclass(frozen=True)
class _Result:
    study: object = None


def _stand_in(monkeypatch, computed: list, fail_after: str | None = None,
              definition=None):
    """``upliftlab study fixed_vs_uplift`` (or ``definition``'s study, with its own options)
    runs a stand-in that counts its computations in ``computed`` and writes :data:`WRITTEN`
    (stopping with an error after ``fail_after``)."""
    from upliftlab.comparisons.framework.study import StudyResult, write_summary
    from upliftlab.comparisons.studies import registry
    from upliftlab.comparisons.studies.fixed_vs_uplift import DEFINITION
    from upliftlab.results import write_text

    definition = DEFINITION if definition is None else definition

    def compute(scene, context):
        computed.append(context.out)
        return _Result()

    def write(result, context):
        figure = write_text(context.out / "figures" / "a.png", "not a real figure\n")
        if fail_after == "figures/a.png":
            raise InputError("stand-in: stopped on purpose after its first file")
        files = (figure, *write_summary(context.out, "# stand-in\n", {"n": 1}))
        return StudyResult("fixed_vs_uplift", context.fast, context.out, files, "", {"n": 1},
                           {}, 0.0)

    study = replace(definition, compute=compute, write=write, context_from=None,
                    describe=lambda result: (), passed=lambda result: True)
    monkeypatch.setattr(registry, "definition", lambda name: study)


def _study(out, *extra):
    return main(["study", "fixed_vs_uplift", "--fast", "--no-figures", "--workers", "1",
                 "--out", str(out), *extra])


def test_a_study_refuses_to_replace_a_users_file_force_or_not(tmp_path, monkeypatch, capsys):
    """The user's summary.md in the study's folder: exit 2 with one line naming it, the file
    unchanged, with or without --force (before: replaced by the study's summary, exit 0).
    Once it is moved away, the study writes all its files and marks the folder complete."""
    computed: list = []
    _stand_in(monkeypatch, computed)
    out = tmp_path / "out"
    out.mkdir()
    mine = out / "summary.md"
    mine.write_text("my own notes\n")
    for force in ([], ["--force"]):
        assert _study(out, *force) == 2
        err = capsys.readouterr().err
        assert err == (f"upliftlab: error: output {str(mine)!r}: a file upliftlab did not make "
                       "is at this output's name; move it away (or remove it), then run again "
                       "(--force replaces only upliftlab's own files)\n")
        assert mine.read_text() == "my own notes\n"
        assert not (out / MARKER).exists()
    mine.rename(tmp_path / "notes.md")
    assert _study(out) == 0
    marker = json.loads((out / MARKER).read_text())
    assert marker["files"] == sorted(WRITTEN) and marker["settings"]["study"] == "fixed_vs_uplift"
    assert not (out / WRITING).exists()
    assert _study(out) == 0  # its own files: replaced
    assert len(computed) == 4


def test_a_study_into_a_folder_of_another_run_needs_force(tmp_path, monkeypatch, capsys):
    """A complete run without --fast in the folder: a --fast run is refused (exit 2, one line,
    nothing computed) unless --force; where and how it runs (--workers) is the same run."""
    computed: list = []
    _stand_in(monkeypatch, computed)
    out = tmp_path / "out"
    assert main(["study", "fixed_vs_uplift", "--no-figures", "--out", str(out)]) == 0
    assert main(["study", "fixed_vs_uplift", "--no-figures", "--workers", "1",
                 "--out", str(out)]) == 0
    assert len(computed) == 2
    assert _study(out) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "holds a different run" in err and "--force" in err
    assert len(computed) == 2
    assert _study(out, "--force") == 0 and len(computed) == 3


def test_a_studys_own_budget_is_not_a_setting_of_its_run(tmp_path, monkeypatch, capsys):
    """The map's --budget only refuses a run before it starts (it changes no number): the same
    map with another budget is the same run, not refused as another (before: exit 2, "holds a
    different run", so a rerun with a larger budget needed --force). Its grid is a setting."""
    from upliftlab.comparisons.studies.winkler_map.workflow import DEFINITION

    computed: list = []
    _stand_in(monkeypatch, computed, definition=DEFINITION)
    out = tmp_path / "out"

    def run(*extra):
        return main(["study", "winkler_map", "--no-figures", "--out", str(out), *extra])

    assert run("--budget", "100") == 0
    assert run("--budget", "200") == 0, capsys.readouterr().err
    assert run() == 0 and len(computed) == 3
    capsys.readouterr()
    assert run("--grid", "soils=clay") == 2
    assert "holds a different run" in capsys.readouterr().err and len(computed) == 3


def test_a_study_stopped_after_its_first_file_leaves_it_known_as_upliftlabs(
        tmp_path, monkeypatch, capsys):
    """The study fails after writing figures/a.png: no marker, the record of the files being
    written names it, and the next run replaces it (before: no record, so a guard would have
    taken it for the user's)."""
    computed: list = []
    _stand_in(monkeypatch, computed, fail_after="figures/a.png")
    out = tmp_path / "out"
    assert _study(out) == 2
    assert not (out / MARKER).exists()
    assert "figures/a.png" in json.loads((out / WRITING).read_text())["files"]
    _stand_in(monkeypatch, computed)
    capsys.readouterr()
    assert _study(out) == 0, capsys.readouterr().err
    assert json.loads((out / MARKER).read_text())["files"] == sorted(WRITTEN)


def test_a_marker_lists_only_files_upliftlab_made(tmp_path):
    """A command that names every file of its folder on completion (``upliftlab paper`` walks
    its folder) must not list the user's file there: listed, the next run would take it for
    upliftlab's and replace it."""
    from upliftlab.results import write_text

    out = tmp_path / "out"
    out.mkdir()
    mine = out / "notes.txt"
    mine.write_text("mine\n")
    with claim(out, out, settings={"command": "probe"}, outputs=["a.txt"]) as held:
        held.start_writing()
        made = [write_text(out / "a.txt", "a\n"), write_text(out / "b" / "c.txt", "c\n")]
        held.complete([*made, mine, tmp_path / "elsewhere.txt"])
    assert json.loads((out / MARKER).read_text())["files"] == ["a.txt", "b/c.txt"]
    assert mine.read_text() == "mine\n"


def test_a_guarded_claim_refuses_a_users_file_through_the_api(tmp_path):
    """The guard at the writer: ``write_text`` into a guarded folder over a file upliftlab did
    not make raises InputError and leaves the file; a new file is written and recorded."""
    from upliftlab.results import write_text

    out = tmp_path / "out"
    out.mkdir()
    (out / "x.csv").write_text("mine\n")
    with claim(out, out, settings={"command": "probe"}, guard=True) as held:
        with pytest.raises(InputError, match="a file upliftlab did not make"):
            write_text(out / "x.csv", "theirs\n")
        write_text(out / "y.csv", "y\n")
        assert json.loads((out / WRITING).read_text())["files"] == ["y.csv"]
        held.complete([out / "y.csv"])
    assert (out / "x.csv").read_text() == "mine\n"


def test_the_impedance_judges_its_folder_before_it_meshes(tmp_path, monkeypatch, capsys):
    """A user's impedance.png in --out: refused in one line before the mesh is built (it took
    about 2 s before the refusal; here the mesh would raise AssertionError)."""
    import upliftlab.continuum.impedance.analysis as analysis

    def never(*args, **kwargs):
        raise AssertionError("meshed before the output folder was judged")

    monkeypatch.setattr(analysis, "impedance_model", never)
    out = tmp_path / "out"
    out.mkdir()
    (out / "impedance.png").write_text("mine\n")
    assert main(["continuum", "strip_footing_clay", "--analysis", "impedance", "--set",
                 "soil.model=elastic", "--set", "soil.undrained_strength=", "--a0", "0.2",
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "a file upliftlab did not make" in err
    assert (out / "impedance.png").read_text() == "mine\n"


def test_a_run_refused_after_it_removed_what_it_wrote_leaves_the_folder_as_it_was(tmp_path):
    """The map study copies its records, then its budget refuses the run and it removes the
    copies: the folder must hold its earlier complete run as before (its marker back, no
    record of files being written), and a folder the claim made is removed (before: the
    marker was gone and the record stayed, so the empty folder was left)."""
    from upliftlab.results import write_text

    def refused_after_a_copy(out):
        with claim(out, out, settings={"command": "probe"}, guard=True):
            copy = write_text(out / "motions" / "a.txt", "a copied record\n")
            copy.unlink()
            copy.parent.rmdir()
            raise InputError("options.budget = 1 s: refused on purpose")

    out = tmp_path / "out"
    with claim(out, out, settings={"command": "probe"}, guard=True) as held:
        held.complete([write_text(out / "x.csv", "x\n")])
    before = (out / MARKER).read_bytes()
    with pytest.raises(InputError, match="budget"):
        refused_after_a_copy(out)
    assert sorted(p.name for p in out.iterdir()) == [MARKER, "x.csv"]
    assert (out / MARKER).read_bytes() == before
    with pytest.raises(InputError, match="budget"):
        refused_after_a_copy(tmp_path / "new")
    assert not (tmp_path / "new").exists()
