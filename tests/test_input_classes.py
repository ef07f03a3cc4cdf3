"""Classes of bad input, each tried through more than one field or path: refused with one line
naming the field and the value, exit 2, before any work and with nothing written.

* integers beyond the range of a float (a scene file's field, a ``--set`` override, a list);
* tables or lists nested far deeper than any scene (a file, an override);
* a quantity that is not zero and yet below anything physical (a subnormal rotary inertia, a
  subnormal sway dashpot) — it would make a matrix singular instead of leaving a term out;
* a ground-motion step below a nanosecond (a two-column file, a PEER header, ``motion.dt``);
* an output folder that cannot be one: a name longer than the file system allows, or with a
  control character, through several commands.

Reference: the rule for bad input (one line ``upliftlab: error: <field> = <value>: ...``, exit
2, nothing left behind) and, for the bounds, ``upliftlab/bounds.py``'s stated ranges.
"""

from __future__ import annotations

import pytest

from upliftlab.cli import main as cli

SHORT = ["--set", "analysis.duration=0.2", "--no-figure"]
HUGE = "1" + "0" * 400


def _refused(argv, capsys, *words) -> str:
    code = cli(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and err[0].startswith("upliftlab: error:"), (code, err)
    for word in words:
        assert word in err[0], err[0]
    return err[0]


def _scene(tmp_path, name: str, lines: str):
    """``wall_free.toml`` with ``lines`` added at its end (after its last table)."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "scenes" / "wall_free.toml").read_text()
    path = tmp_path / name
    path.write_text(text + "\n" + lines + "\n")
    return path


@pytest.mark.parametrize("argv_tail, field", [
    (["--set", f"structure.weight={HUGE}"], "structure.weight"),
    (["--set", f"foundation.stiffness={HUGE}"], "foundation.stiffness"),
    (["--set", f"motion.duration={HUGE}"], "motion.duration"),
    (["--set", f"foundation.springs={HUGE}"], "foundation.springs"),
])
def test_an_integer_beyond_a_float_is_refused(argv_tail, field, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    _refused(["run", "wall_free", "--case", "e07", *SHORT, *argv_tail, "--out", "o"], capsys,
             field, "1.8e308")
    assert not (tmp_path / "o").exists()


def test_an_integer_beyond_a_float_in_a_file_or_a_list_is_refused(tmp_path, monkeypatch,
                                                                 capsys):
    monkeypatch.chdir(tmp_path)
    scene = _scene(tmp_path, "big.toml", f"[analysis]\nduration = {HUGE}\n")
    _refused(["run", str(scene), "--case", "e07", "--no-figure", "--out", "o"], capsys,
             "analysis.duration", "1.8e308")
    _refused(["run", "wall_free", "--case", "e07", *SHORT, "--set",
              f"foundation.dashpots=[1, {HUGE}]", "--out", "o"], capsys, "foundation.dashpots")


def test_tables_nested_far_too_deep_are_refused(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    for depth, name in ((30, "deep.toml"), (20000, "deeper.toml")):
        path = tmp_path / name
        path.write_text("schema = 1\nx = " + "[" * depth + "]" * depth + "\n")
        _refused(["run", str(path), "--no-figure", "--out", "o"], capsys, "nested")
    _refused(["run", "wall_free", "--case", "e07", *SHORT, "--set",
              "motion.x=" + "[" * 30 + "]" * 30, "--out", "o"], capsys, "nested")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("override, field", [
    ("structure.rotary_inertia=1e-310", "structure.rotary_inertia"),
    ("foundation.sway_stiffness=1000", None),  # with the next, a sway dashpot
])
def test_a_subnormal_quantity_is_not_a_quantity(override, field, tmp_path, monkeypatch, capsys):
    """1e-310 kip·in·s² is 1.1e-307 kg·m²: below bounds' tiny 1e-9 kg·m², refused; a sway
    dashpot of 1e-310 likewise (1e-9 N·s/m)."""
    monkeypatch.chdir(tmp_path)
    if field is None:
        argv = ["run", "wall_free", "--case", "e07", *SHORT, "--set", override, "--set",
                "structure.vertical_weight=250", "--set", "foundation.sway_damping=1e-310",
                "--out", "o"]
        field = "foundation.sway_damping"
    else:
        argv = ["run", "wall_free", "--case", "e07", *SHORT, "--set", override, "--out", "o"]
    _refused(argv, capsys, field, "not zero")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("how", ["columns", "at2", "one column"])
def test_a_motion_step_below_a_nanosecond_is_refused(how, tmp_path, monkeypatch, capsys):
    """A record whose step is 5e-324 s gave an all-zero response with exit 0."""
    monkeypatch.chdir(tmp_path)
    if how == "columns":
        (tmp_path / "m.txt").write_text("0 0\n5e-324 0.1\n1e-323 0.2\n")
        argv = ["--motion", "m.txt"]
    elif how == "at2":
        (tmp_path / "m.AT2").write_text("PEER NGA\nx\nACCELERATION TIME SERIES IN UNITS OF G\n"
                                         "NPTS=   3, DT=   1E-320 SEC\n0.0 0.1 0.2\n")
        argv = ["--motion", "m.AT2"]
    else:
        (tmp_path / "m.txt").write_text("0.0\n0.1\n0.2\n")
        argv = ["--motion", "m.txt", "--set", "motion.dt=1e-12"]
    _refused(["run", "wall_free", "--case", "e07", "--no-figure", *argv, "--out", "o"], capsys,
             "DT" if how == "at2" else "dt")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("command", [
    ["run", "wall_free", "--case", "e07", *SHORT],
    ["opensees", "wall_free", "--case", "e10"],
    ["continuum", "strip_footing_clay", "--steps", "2", "--no-render"],
])
@pytest.mark.parametrize("out", ["a" * 300, "x\ny", "tab\there"])
def test_an_output_folder_that_cannot_be_one_is_refused(command, out, tmp_path, monkeypatch,
                                                        capsys):
    monkeypatch.chdir(tmp_path)
    _refused([*command, "--out", out], capsys, "--out")
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------------------------
# Issue 37: more classes, each through several cases
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("field", ["foundation.damping_ratio", "motion.velocity",
                                   "structure.weight", "foundation.restitution",
                                   "foundation.stiffness"])
@pytest.mark.parametrize("value", ["1e-310", "-4e-320", "5e-324"])
def test_any_subnormal_number_is_refused_whatever_the_field(field, value, tmp_path, monkeypatch,
                                                           capsys):
    """A subnormal number (0 < |x| < 2.2e-308, the smallest normal double) in any field, by
    ``--set`` or in the file, is refused by name: a damping ratio of 1e-310 ran, and a motion
    velocity of 1e-310 gave a response of 1e-312 in."""
    monkeypatch.chdir(tmp_path)
    _refused(["run", "wall_free", "--case", "e07", *SHORT, "--set", f"{field}={value}", "--out",
              "o"], capsys, field, "subnormal")
    table, key = field.split(".")
    scene = _scene(tmp_path, "s.toml", "")
    lines = [line for line in scene.read_text().splitlines()  # the key set in its own table
             if not line.startswith(f"{key} ")]
    lines.insert(lines.index(f"[{table}]") + 1, f"{key} = {value}")
    scene.write_text("\n".join(lines) + "\n")
    _refused(["run", str(scene), "--case", "e07", "--no-figure", "--out", "o"], capsys, field,
             "subnormal")
    assert not (tmp_path / "o").exists()


def test_a_subnormal_number_is_refused_through_the_api():
    """The typed API (``Scene.replace``) goes through the same check."""
    from upliftlab.checks import InputError
    from upliftlab.scenes import load_scene

    scene = load_scene("wall_free", case="e07")
    for table, field in (("foundation", "damping_ratio"), ("structure", "rotary_inertia"),
                         ("motion", "velocity")):
        with pytest.raises(InputError, match=f"{table}.{field} = .*subnormal"):
            scene.replace(table, **{field: 3e-315})


@pytest.mark.parametrize("index", ["²", "٠", "１", "৩", "0x1", "1e0", "9" * 30])
def test_a_list_index_not_in_ascii_digits_is_refused(index, tmp_path, monkeypatch, capsys):
    """``str.isdigit`` takes '²' (``int`` then raised: a traceback) and '٠'/'１' (read as 0
    and 1: another story changed than the user wrote); only 0-9 index a list."""
    monkeypatch.chdir(tmp_path)
    _refused(["run", "three_story_frame", *SHORT, "--set", f"structure.story.{index}.weight=1",
              "--out", "o"], capsys, "structure.story", "0-9")
    assert not (tmp_path / "o").exists()


_AT2 = "PEER NGA\nx\nACCELERATION TIME SERIES IN UNITS OF G\n{header}\n0.0 0.1 0.2 -0.1 0.0\n"


@pytest.mark.parametrize("header", [
    "NPTS=5, DT=1.2.3", "NPTS=5, DT=.", "NPTS=5, DT=e", "NPTS=5, DT=--1",
    "NPTS=" + "9" * 5000 + ", DT=.02", "NPTS=٥, DT=.02", "NPTS=5, DT=.0٢", "NPTS=5, DT=.02abc",
    "NPTS=5, DT=.02, NPTS=9", "NPTS=5.5, DT=.02", "DT=.02 NPTS=5"])
def test_a_malformed_at2_header_is_refused_naming_the_file_and_line(header, tmp_path,
                                                                    monkeypatch, capsys):
    """Each of these gave a traceback (ValueError from float or int), or read another number
    than written (DT=.0٢ as 0, DT=.02abc as 0.02): one line naming the file and line 4."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "m.AT2").write_text(_AT2.format(header=header))
    _refused(["run", "wall_free", "--case", "e07", *SHORT, "--motion", "m.AT2", "--out", "o"],
             capsys, "m.AT2", "line 4")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("name, text, line", [
    ("m.txt", "0 0\n0.02 ٠.١\n0.04 0\n", 2),
    ("m.txt", "0 0\n0.02 0.1\n0.04 1_0\n", 3),
    ("m.txt", "0 0\n0.02 １\n", 2),
    ("m.AT2", _AT2.format(header="NPTS=5, DT=.02").replace("0.2 -0.1", "0.2 ٣"), 5),
    ("m.AT2", _AT2.format(header="NPTS=5, DT=.02").replace("0.2 -0.1", "0.2\nabc -0.1"), 6),
])
def test_record_data_not_in_ascii_numbers_is_refused_naming_the_line(name, text, line, tmp_path,
                                                                    monkeypatch, capsys):
    """``float`` reads '٠.١' and '1_0': a record in another script ran as other numbers."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / name).write_text(text)
    _refused(["run", "wall_free", "--case", "e07", *SHORT, "--motion", name, "--out", "o"],
             capsys, name, f"line {line}")


@pytest.mark.parametrize("command", [
    ["study", "verification"], ["study", "speed_vs_error", "--fast"],
    ["report", "--fast"], ["paper"]])
@pytest.mark.parametrize("out", ["a" * 300, "x\ny", "nul\x00here", "b/" + "c" * 256,
                                 "/".join(["d" * 200] * 25)])
def test_an_output_folder_that_cannot_be_one_is_refused_by_every_command(command, out, tmp_path,
                                                                         monkeypatch, capsys):
    """``study`` wrote into 'x\\ny' and raised OSError on a long name after its work; every
    command checks the folder's text first (NAME_MAX, PATH_MAX, control characters)."""
    monkeypatch.chdir(tmp_path)
    _refused([*command, "--out", out], capsys, "--out")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command", [["study", "verification"], ["report", "--fast"]])
@pytest.mark.parametrize("address", ["not an address", "::::", "tcp://h:99999", "http://h:1",
                                     "h:", "tcp://:8786", "a b:1"])
def test_a_scheduler_address_that_is_not_one_is_refused_before_work(command, address, tmp_path,
                                                                    monkeypatch, capsys):
    """``report --scheduler 'not an address'`` started its sections; ``study`` raised a
    ValueError traceback from distributed."""
    monkeypatch.chdir(tmp_path)
    _refused([*command, "--scheduler", address, "--out", "o"], capsys, "--scheduler")
    assert list(tmp_path.iterdir()) == []


def test_a_scheduler_address_is_checked_in_the_api_and_the_environment(monkeypatch):
    from upliftlab.checks import InputError, scheduler_address
    from upliftlab.comparisons.framework.sweep import sweep_executor

    for good in ("tcp://host:8786", "host:8786", "[::1]:8786", "tls://10.0.0.1:8786",
                 "localhost"):
        assert scheduler_address("s", good) == good
    with pytest.raises(InputError, match="scheduler = 'nope nope'"):
        with sweep_executor("nope nope"):
            pass
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "::::")
    with pytest.raises(InputError, match="DASK_SCHEDULER_ADDRESS = '::::'"):
        with sweep_executor():
            pass
