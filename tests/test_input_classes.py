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
             "dt")
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
