"""The OpenSeesPy bridge: the standalone script of a scene, its run, and the comparison.

References: the numbers the script holds are checked against upliftlab's own model of the
scene (``build_model``: the bridge must transfer them exactly); the OpenSees run is an
independent implementation (zeroLength springs, OpenSees' materials and Newmark) that must
agree with upliftlab's Newmark at the same step where the two models are the same (no
foundation dashpots): within 0.5 % in peak u and θ. A missing or broken openseespy (the test
extra installs it) fails the run tests, as a missing El Centro record does.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main
from upliftlab.comparisons.opensees import (OpenSeesError, compare, opensees_available,
                                            opensees_spec, run_script, write_script)
from upliftlab.comparisons.opensees import runner
from upliftlab.comparisons.opensees.script import script_numbers, script_text
from upliftlab.reduced import build_model
from upliftlab.scenes import load_scene

AGREEMENT = 0.005  # peak u and θ, OpenSees against upliftlab's Newmark at the same step
STEP = 0.002       # s: the step both use in the run tests

# scene, case, overrides: Cases A and B, every layout, an MDOF frame, fixed and bonded bases,
# a rigid wall with P-Δ in free vibration
SCENES = {
    "A": ("short_period_elcentro", "A", []),
    "B": ("short_period_elcentro", "B", []),
    "edges": ("short_period_elcentro", "A", ["foundation.layout=edges", "foundation.springs=2"]),
    "equivalent": ("short_period_elcentro", "B", ["foundation.layout=equivalent",
                                                  "foundation.springs=2"]),
    "end_stiffened": ("short_period_elcentro", "B", [
        "foundation.layout=end_stiffened", "foundation.springs=20",
        "foundation.end_stiffness_ratio=3", "foundation.end_length=0.2"]),
    "custom": ("short_period_elcentro", "A", [
        "foundation.layout=custom", "foundation.positions=[-120.0, -40.0, 60.0, 120.0]",
        "foundation.stiffnesses=[1500.0, 1200.0, 1500.0, 1537.0]", "foundation.springs=",
        "foundation.vertical_period="]),
    "mdof": ("three_story_frame", None, ["foundation.restitution=1"]),
    "mdof_fixed": ("three_story_frame", "fixed", ["foundation.restitution=1"]),
    "bonded": ("short_period_elcentro", "A", ["foundation.support=bonded"]),
    "rigid_wall": ("wall_free", None, ["structure.rigid=true", "structure.p_delta=true"]),
}
RECORD_FREE = {"rigid_wall"}


@pytest.fixture(scope="session")
def opensees():
    """openseespy importable (in a subprocess, as the bridge runs it); the test extra installs
    it, so its absence is a failure that says what to install."""
    if not opensees_available():
        pytest.fail(f"openseespy does not import here ({runner.OPENSEES_EXTRA})")


def _scene(key, request, extra=()):
    name, case, overrides = SCENES[key]
    if key not in RECORD_FREE:
        request.getfixturevalue("elcentro")
    return load_scene(name, case=case, overrides=[*overrides, *extra])


@pytest.mark.parametrize("key", list(SCENES))
def test_script_holds_the_reduced_model_and_compiles(key, request, tmp_path):
    """Every spring and story of upliftlab's model is in the script's numbers exactly
    (reference: ``build_model`` of the same scene), the script compiles and is the package's
    own file, and the motion file reads back to the scene's samples exactly."""
    scene = _scene(key, request)
    spec = opensees_spec(scene, dt=0.001)
    files = write_script(spec, tmp_path)
    text = files.script.read_text()
    compile(text, str(files.script), "exec")
    assert text == script_text()
    data = json.loads(files.numbers.read_text())
    model = build_model(scene)
    found = model.params[model.foundation_slice]
    table = np.array(data["FOUNDATION"], dtype=float).reshape(-1, 5)
    assert table.shape[0] == found.size
    for column, field in enumerate(("x", "k", "c", "f0", "fy")):
        np.testing.assert_array_equal(table[:, column], found[field])
    stories = scene.structure.stories
    assert len(data["STORIES"]) == len(stories)
    for row, st in zip(data["STORIES"], stories):
        assert (row[0], row[1], row[2], row[4]) == (st.height, st.weight, st.stiffness,
                                                   st.yield_force)
    if not scene.structure.rigid and model.story_count:
        np.testing.assert_array_equal([r[3] for r in data["STORIES"]],
                                      model.params["c"][:model.story_count])
    assert data["VERTICAL_WEIGHT"] == scene.structure.vertical_weight
    assert data["ROTARY_INERTIA"] == scene.structure.rotary_inertia
    assert data["SUPPORT"] == scene.foundation.support
    assert data["P_DELTA"] == scene.structure.p_delta and data["RIGID"] == scene.structure.rigid
    motion = scene.build_motion()
    if files.motion is None:
        assert motion.is_free_vibration and data["INITIAL_VELOCITY"] == motion.initial_velocity
    else:
        rows = np.loadtxt(files.motion)
        np.testing.assert_array_equal(rows[:, 1], motion.acceleration)
        assert rows[1, 0] - rows[0, 0] == motion.dt


def test_script_names_its_modelling_choices(request):
    """The notes say how each part compares with upliftlab (what a reviewer reads; the script
    prints them), and the script needs no upliftlab."""
    spec = opensees_spec(_scene("A", request), dt=0.001)
    notes = " ".join(script_numbers(spec, "motion.txt")["NOTES"])
    for phrase in ("zeroLength", "TensionOnly", "β = c_i/k_i", "Newmark average acceleration",
                   "upliftlab's clip"):
        assert phrase in notes, phrase
    assert script_numbers(spec, "motion.txt")["UNITS"] == "kip-in-s"
    text = script_text()
    assert "import upliftlab" not in text and "from upliftlab" not in text


@pytest.mark.parametrize("overrides, field, reason", [
    ([], "foundation.restitution = 0.7", "no equivalent in OpenSees"),
    (["foundation.restitution=1", "structure.kinematics=exact"], "structure.kinematics",
     "small rotations"),
])
def test_case_c_and_exact_kinematics_refused(overrides, field, reason, request, tmp_path,
                                             capsys):
    """Case C (Ewing's impact damper) and exact kinematics end with one line, exit code 2,
    before any file is written."""
    request.getfixturevalue("elcentro")
    out = tmp_path / "out"
    code = main(["opensees", "short_period_elcentro", "--case", "C", "--out", str(out),
                 *[f"--set={o}" for o in overrides]])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert field in err[0] and reason in err[0]
    assert not out.exists()


def test_initial_push_and_tilted_p_delta_refused():
    """An initial rotation (upliftlab's static push) and P-Δ on a foundation that tilts at rest
    are refused by name."""
    scene = load_scene("wall_free", overrides=["motion.velocity=0", "motion.rotation=0.001"])
    with pytest.raises(InputError, match="motion.rotation"):
        opensees_spec(scene)
    scene = load_scene("wall_free", overrides=[
        "structure.p_delta=true", "foundation.layout=custom",
        "foundation.positions=[-72.0, 0.0, 50.0]", "foundation.stiffnesses=[2000.0, 2000.0, "
        "2000.0]", "foundation.springs=", "foundation.stiffness="])
    with pytest.raises(InputError, match="tilts at rest"):
        opensees_spec(scene)


def test_missing_openseespy_names_the_extra(monkeypatch, request, tmp_path, capsys):
    """--run without openseespy: one line naming the extra, exit 2, nothing written."""
    request.getfixturevalue("elcentro")
    monkeypatch.setattr(runner, "opensees_available", lambda: False)
    out = tmp_path / "out"
    code = main(["opensees", "short_period_elcentro", "--case", "A", "--run", "--out",
                 str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and 'pip install "upliftlab[opensees]"' in err[0]
    assert not out.exists()


def test_runner_reports_a_failed_or_hung_script(tmp_path):
    """A script that exits without a summary, or runs past its timeout, raises with the
    reason (no openseespy needed)."""
    bad = tmp_path / "bad" / "model.py"
    bad.parent.mkdir()
    bad.write_text("import sys\nprint('no model here', file=sys.stderr)\nsys.exit(3)\n")
    with pytest.raises(OpenSeesError, match="exited with code 3.*no model here"):
        run_script(bad, echo=False)
    slow = tmp_path / "slow" / "model.py"
    slow.parent.mkdir()
    slow.write_text("import time\ntime.sleep(30)\n")
    with pytest.raises(OpenSeesError, match="timed out after 0.5 s"):
        run_script(slow, timeout=0.5, echo=False)


@pytest.mark.parametrize("key, duration", [("A", 4.0), ("B", 4.0), ("mdof", 3.0)])
def test_opensees_agrees_without_foundation_dashpots(key, duration, opensees, request,
                                                     tmp_path):
    """Without foundation dashpots the two models are the same: OpenSees' Newmark and
    upliftlab's Newmark at Δt = 2 ms agree within 0.5 % in peak u and θ (measured: 0.04 % or
    better) on the first seconds of El Centro, with uplift (and, for the three-story frame,
    yielding stories and P-Δ)."""
    scene = _scene(key, request, ["foundation.damping_ratio=0",
                                  f"analysis.duration={duration}"])
    c = compare(scene, tmp_path, dt=STEP)
    same, theirs = c.same_step, c.opensees.summary
    assert same["dt"] == theirs["dt"] == STEP
    assert same["peak_uplift_left"] > 10 * scene.structure.vertical_weight / (
        scene.foundation.stiffness)  # it uplifts: well beyond the static settlement
    for quantity in ("peak_u", "peak_theta"):
        assert theirs[quantity] == pytest.approx(same[quantity], rel=AGREEMENT), quantity


def test_run_json_has_the_same_keys_for_both(opensees, tmp_path, capsys):
    """``--run --json`` prints one object {"upliftlab", "opensees"} with the same summary keys;
    free vibration of the wall (no record, no dashpots) agrees within 0.5 % in peak u and θ."""
    out = tmp_path / "wall"
    code = main(["opensees", "wall_free", "--set", "motion.duration=1.0", "--dt", "0.001",
                 "--run", "--json", "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    lines = [line for line in captured.out.splitlines() if line.strip()]
    data = json.loads(lines[-1])
    assert set(data) == {"upliftlab", "opensees"}
    keys = {"peak_u", "peak_theta", "peak_base_shear", "peak_uplift_left",
            "final_vertical_position", "dt", "runtime_s", "verdict"}
    assert keys <= set(data["upliftlab"]) and set(data["upliftlab"]) == set(data["opensees"])
    assert all(math.isfinite(data["opensees"][k]) for k in keys - {"verdict"})
    for quantity in ("peak_u", "peak_theta"):
        assert data["opensees"][quantity] == pytest.approx(data["upliftlab"][quantity],
                                                           rel=AGREEMENT)
    for name in ("model.py", "comparison.md", "comparison.json", "histories.csv",
                 "opensees_summary.json", "upliftlab.nc"):
        assert (out / name).is_file(), name


def test_timeout_without_run_refused(tmp_path, capsys):
    """--timeout without --run (no OpenSees run to limit) is refused as --json is: one line
    naming the option and its value, exit 2, nothing written."""
    out = tmp_path / "out"
    code = main(["opensees", "wall_free", "--timeout", "5", "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "--timeout = '5': only with --run" in err[0]
    assert not out.exists()


def _hostile_scene(tmp_path, title):
    """long_period_free (Case A) from a copy whose title is ``title`` (a TOML basic string)."""
    from pathlib import Path

    text = (Path(__file__).parents[1] / "scenes" / "long_period_free.toml").read_text()
    line = next(x for x in text.splitlines() if x.startswith("title = "))
    path = tmp_path / "evil.toml"
    path.write_text(text.replace(line, f"title = {title}"))
    return path


def test_script_outputs_keep_a_titles_lines_out_of_the_data(tmp_path, capsys):
    """A title with line breaks: every header line of the script's histories CSV is a comment
    (as upliftlab's own CSV), so the title adds no row to what pandas or the bridge's reader
    read; on stderr the title is one escaped line. A terminal escape cannot come from a scene
    (its text refuses control characters but tabs and line breaks: test_inputs), but the
    script escapes whatever its numbers file holds: one is put in its title here. The script
    is imported, not run: no OpenSees needed."""
    import importlib.util
    from types import SimpleNamespace

    import pandas as pd

    path = _hostile_scene(tmp_path, '"x\\"\\"\\"; import os\\n1,2,3,4,5,6\\nred"')
    files = write_script(opensees_spec(load_scene(str(path), case="A")), tmp_path / "m")
    loaded = importlib.util.spec_from_file_location("hostile_model", files.script)
    model = importlib.util.module_from_spec(loaded)
    loaded.loader.exec_module(model)
    model.load_scene_numbers()
    assert model.TITLE == 'x"""; import os\n1,2,3,4,5,6\nred'
    model.TITLE = model.TITLE.replace("red", "\x1b[31mred")
    rows = [(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (0.01, 0.5, 1e-4, -0.1, 0.2, 3.0)]
    observer = SimpleNamespace(rows=rows, peak={"u": 0.5, "theta": 1e-4, "uplift": 0.0,
                                                "shear": 3.0})
    model.write_outputs(observer, "completed", 1.0, 0.1, 1)
    csv_path = tmp_path / "m" / "opensees_histories.csv"
    lines = csv_path.read_text().splitlines()
    names = "time,u,theta,V,left_spring_displacement,base_shear"
    header = lines[:lines.index(names)]
    assert header == ['# x"""; import os', "# 1,2,3,4,5,6",
                      "# \x1b[31mred: OpenSees histories; units kip-in-s; theta as "
                      "upliftlab's; left_spring_displacement is the compression from rest"]
    table = pd.read_csv(csv_path, comment="#")
    assert list(table.columns) == names.split(",")
    np.testing.assert_array_equal(table.to_numpy(), np.array(rows))
    histories = runner.read_histories(csv_path)
    np.testing.assert_array_equal(histories["base_shear"], [0.0, 3.0])
    capsys.readouterr()
    model.announce()
    err = capsys.readouterr().err
    assert err.splitlines()[0] == ('OpenSees model of evil-A: x"""; import os\\n1,2,3,4,5,6'
                                   '\\n\\x1b[31mred (kip-in-s)')
    assert len(err.splitlines()) == 1 + len(model.NOTES) and "\x1b" not in err


def test_command_in_model_json_is_shell_quoted_and_reproduces_the_run(tmp_path, capsys):
    """model.json's COMMAND is the shell-quoted command that writes the model again: the scene
    path as given (not its stem), --case, each --set, then the resolved --dt and --dashpots.
    A shell splits it back into exactly those arguments and runs nothing of a path or an
    override with quotes, $(...), backquotes, ; or globs."""
    import shlex
    import subprocess

    marker = tmp_path / "INJECTED"
    scene = tmp_path / "s" / "e'v\"il$(id);[x]{y}.toml"
    scene.parent.mkdir()
    scene.write_text(_hostile_scene(tmp_path, '"plain"').read_text())
    override = f"title=a; $(touch {marker}) `touch {marker}` \" x"
    out = tmp_path / "out"
    code = main(["opensees", str(scene), "--case", "A", "--set", override, "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    data = json.loads((out / "model.json").read_text())
    expected = ["upliftlab", "opensees", str(scene), "--case", "A", "--set", override,
                "--dt", repr(data["DT"]), "--dashpots", "clipped"]
    assert shlex.split(data["COMMAND"]) == expected
    shell = subprocess.run(["sh", "-c", f"set -- {data['COMMAND']}; printf '%s\\0' \"$@\""],
                           capture_output=True, text=True, cwd=tmp_path, check=True)
    assert shell.stdout.split("\0")[:-1] == expected
    assert not marker.exists()


@pytest.mark.parametrize("options, message", [
    (["--dt", "1e-12"], "analysis.max_steps = 10000000: the OpenSees run would take 8e+12 "
                        "Newmark steps of 1e-12 s (8 s); raise it (--set "
                        "analysis.max_steps=8000000000000) to write it anyway"),
    (["--run", "--dt", "1e-9"], "analysis.max_steps = 10000000: the OpenSees run would take "
                                "8e+09 Newmark steps of 1e-09 s (8 s)"),
    (["--dt", "5e-324"], "analysis.max_steps = 10000000: the OpenSees run would take inf "
                         "Newmark steps of 4.94e-324 s (8 s); take a larger step (--dt)"),
    # the OpenSees run within the limit, upliftlab's own run (analysis.dt) above it
    (["--run", "--dt", "1e-3", "--set", "analysis.dt=1e-5", "--set",
      "analysis.max_steps=100000"], "analysis.max_steps = 100000: the reduced run would take "
                                    "8e+05 steps of 1e-05 s"),
])
def test_step_count_refused_before_anything_is_written_or_run(options, message, monkeypatch,
                                                              tmp_path, capsys):
    """A run above analysis.max_steps (the OpenSees script's Newmark steps, with or without
    --run; with --run, upliftlab's runs beside it too) ends with one line naming the limit and
    the steps, exit 2, before any file is written or any model run."""
    import importlib

    compare_module = importlib.import_module("upliftlab.comparisons.opensees.compare")
    monkeypatch.setattr(compare_module, "run", lambda *a, **k: pytest.fail("upliftlab ran"))
    out = tmp_path / "out"
    code = main(["opensees", "long_period_free", "--case", "A", *options, "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    assert message in err[0]
    assert not out.exists()
