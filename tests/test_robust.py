"""Results that were wrong and looked right, each tested on the path that exposed it.

Overrides that did nothing, a unit system swapped under the numbers, scenes whose digest and
provenance described another scene, names that said more than they measured, output folders
that lost or mixed runs, and a report that exited 0 with failed sections. References: an
independent path to the same number (a case override against the same field set directly; a
scene edited by ``Scene.replace`` against the same scene loaded with the override), closed
forms (a conservative system never comes to rest), and the files on disk.
"""

from __future__ import annotations

import dataclasses
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main as cli
from upliftlab.outdir import LOCK, read_marker
from upliftlab.reduced import run
from upliftlab.results import read_netcdf
from upliftlab.scenes import load_scene

TWO_COLUMNS = "# t a\n0.00 0.0\n0.02 0.1\n0.04 -0.1\n0.06 0.05\n0.08 0.0\n"


def _json(capsys) -> dict:
    return json.loads(capsys.readouterr().out.strip().splitlines()[-1])


def _error(capsys) -> str:
    lines = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert len(lines) == 1, lines
    return lines[0]


# ---------------------------------------------------------------------------------------------
# Overrides that did nothing
# ---------------------------------------------------------------------------------------------


def test_an_override_of_the_running_case_changes_the_run(tmp_path, capsys, elcentro):
    """``--set cases.C.foundation.restitution=0.0 --case C`` left peak u at 0.05527 in. Now it
    gives exactly the run with ``foundation.restitution=0.0`` set directly (the same scene
    reached by another path; tolerance 0: same inputs, same arithmetic)."""
    base = ["run", "short_period_elcentro", "--case", "C", "--no-figure", "--json"]
    assert cli([*base, "--out", str(tmp_path / "a")]) == 0
    plain = _json(capsys)["peak_u"]
    assert cli([*base, "--set", "cases.C.foundation.restitution=0.0",
                "--out", str(tmp_path / "b")]) == 0
    via_case = _json(capsys)["peak_u"]
    assert cli([*base, "--set", "foundation.restitution=0.0", "--out", str(tmp_path / "c")]) == 0
    direct = _json(capsys)["peak_u"]
    assert via_case == direct
    assert abs(via_case / plain - 1) > 0.1  # the override matters: the issue measured +51 %


def test_case_overrides_that_cannot_take_effect_are_refused(tmp_path, capsys):
    base = ["run", "short_period_free", "--no-figure", "--out", str(tmp_path / "o")]
    assert cli([*base, "--case", "C", "--set", "cases.C.foundation.law='bogus'"]) == 2
    assert "foundation.law = 'bogus': must be one of" in _error(capsys)
    assert cli([*base, "--case", "C", "--set", "cases.A.foundation.restitution=0.0"]) == 2
    assert "has no effect: this run uses case 'C'" in _error(capsys)
    assert cli([*base, "--set", "cases.C.foundation.restitution=0.0"]) == 2
    assert "has no effect: this run uses no case" in _error(capsys)
    assert not (tmp_path / "o").exists()


def test_motion_dt_is_refused_on_a_record_with_its_own_step(tmp_path, capsys):
    record = tmp_path / "two.txt"
    record.write_text(TWO_COLUMNS)
    args = ["run", "short_period_free", "--motion", str(record), "--no-figure",
            "--out", str(tmp_path / "o")]
    assert cli([*args, "--set", "motion.dt=0.01"]) == 2
    assert "gives its own time step (0.02 s)" in _error(capsys)
    one = tmp_path / "one.txt"
    one.write_text("0.0\n0.1\n-0.1\n0.0\n")
    scene = load_scene("short_period_free", motion=str(one), overrides=["motion.dt=0.01"])
    assert scene.build_motion().dt == 0.01


def test_motion_duration_cuts_or_pads_a_record_exactly(elcentro):
    """``motion.duration`` on a record was accepted and ignored; now it is the motion's
    length: 5 s of the 31.2 s record are its first 250 samples (reference: the record)."""
    scene = load_scene("short_period_elcentro", case="C", overrides=["motion.duration=5"])
    motion = scene.build_motion()
    assert motion.duration == pytest.approx(5.0, rel=1e-12)
    np.testing.assert_array_equal(motion.acceleration, elcentro.acceleration[:250])
    response = run(scene, histories=False)
    assert response.time[-1] == pytest.approx(5.0, rel=1e-12)
    longer = load_scene("short_period_elcentro", overrides=["motion.duration=40"]).build_motion()
    assert longer.duration == pytest.approx(40.0, rel=1e-12)
    with pytest.raises(InputError, match=r"motion.duration = 5.01 s: not a whole number of the "
                                         r"motion's steps of 0.02 s; use 5 or 5.02 s"):
        load_scene("short_period_elcentro", overrides=["motion.duration=5.01"]).build_motion()


def test_a_free_vibration_lasts_exactly_its_duration():
    """A free vibration of 1e-9 s ran 0.01 s. A duration below 1 µs is refused; any other is
    kept exactly (the default step shortens to divide it)."""
    with pytest.raises(InputError, match=r"motion.duration = 1e-09: outside the physical range "
                                         r"\[1e-06, 1e\+06\] s"):
        load_scene("wall_free", overrides=["motion.duration=1e-9"])
    response = run(load_scene("wall_free", overrides=["motion.duration=0.015"]))
    assert response.time[-1] == pytest.approx(0.015, rel=1e-12)


def test_a_duration_shorter_than_one_step_runs_exactly_that_long():
    """A run of 1e-5 s took a whole step (about 1 ms) and said nothing. The step now shortens
    to end the run at its duration: one step of 1e-5 s, ending at 1e-5 s (every integrator)."""
    scene = load_scene("wall_free", overrides=["analysis.duration=1e-5"])
    for name in ("events", "rk4", "newmark"):
        response = run(scene.with_overrides(f"analysis.integrator='{name}'"))
        assert response.time[-1] == pytest.approx(1e-5, rel=1e-12), name
        assert response.info["steps"] == 1


def test_changing_the_unit_system_by_override_is_refused():
    """``--set units=kN-m-s`` on a kip-in-s scene reinterpreted every number."""
    with pytest.raises(InputError, match="units = 'kN-m-s': every number of this scene is in "
                                         "'kip-in-s'; an override cannot convert them"):
        load_scene("short_period_free", overrides=["units='kN-m-s'"])
    assert load_scene("short_period_free", overrides=["units='kip-in-s'"]).units.name == \
        "kip-in-s"


def test_overrides_the_command_ignores_are_refused(tmp_path, capsys):
    assert cli(["run", "strip_footing_clay", "--set", "soil.youngs_modulus=1e4",
                "--out", str(tmp_path / "o")]) == 2
    assert "has no effect: the reduced model does not use soil.youngs_modulus" in \
        _error(capsys)
    assert cli(["continuum", "strip_footing_clay", "--set", "motion.amplitude=0.5",
                "--out", str(tmp_path / "o")]) == 2
    assert "has no effect: the continuum pushover does not use motion.amplitude" in \
        _error(capsys)
    assert cli(["continuum", "strip_footing_clay", "--analysis", "dynamic",
                "--set", "foundation.springs=40", "--out", str(tmp_path / "o")]) == 2
    assert "the continuum dynamic does not use foundation.springs" in _error(capsys)
    assert not (tmp_path / "o").exists()


# ---------------------------------------------------------------------------------------------
# Scenes that drifted from their provenance
# ---------------------------------------------------------------------------------------------


def test_a_replaced_scene_carries_its_own_digest_and_provenance(tmp_path):
    """``dataclasses.replace`` ran 40 springs while the file said 12. Now the digest and the
    provenance follow the fields: the replaced scene has the digest of the scene loaded with
    ``foundation.springs=40`` (an independent path) and its result file says 40."""
    scene = load_scene("short_period_free", case="B")
    changed = dataclasses.replace(scene, foundation=dataclasses.replace(scene.foundation,
                                                                        springs=40))
    loaded = load_scene("short_period_free", case="B", overrides=["foundation.springs=40"])
    assert changed.digest == loaded.digest != scene.digest
    assert changed.overrides == ("foundation.springs=40",)
    assert changed.replace("foundation", springs=40).digest == loaded.digest
    response = run(changed.with_overrides("motion.duration=0.1"))
    path = response.save(tmp_path / "r.nc")[0]
    _, attrs = read_netcdf(path)
    assert json.loads(attrs["provenance_scene_data"])["foundation"]["springs"] == 40
    assert response.model.params.size == 40 + 1  # 40 foundation springs and the story
    assert "foundation.springs=40" in attrs["provenance_overrides"]


def test_a_replaced_continuum_scene_carries_its_own_digest_into_the_result():
    """The continuum's provenance takes the scene's digest: a soil changed in code by
    ``dataclasses.replace`` or by the typed ``Scene.replace`` must give the digest of the scene
    loaded with the same change as an override (the independent path), never the old one."""
    from upliftlab.continuum import build_model
    from upliftlab.continuum.output.fields import result_metadata

    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4"])
    loaded = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                         "soil.youngs_modulus=60000.0"])
    by_fields = dataclasses.replace(scene, soil=dataclasses.replace(scene.soil,
                                                                    youngs_modulus=60e3))
    typed = scene.replace("soil", youngs_modulus=60e3)
    assert by_fields.digest == typed.digest == loaded.digest != scene.digest
    assert typed.overrides[-1] == "soil.youngs_modulus=60000.0"
    assert by_fields.data["soil"]["youngs_modulus"] == typed.data["soil"]["youngs_modulus"] == 60e3
    metadata = result_metadata(build_model(typed), "pushover", {})
    assert metadata["scene_digest"] == loaded.digest
    assert metadata["soil"]["youngs_modulus"] == 60e3
    with pytest.raises(InputError, match="soil.model = 'granite'"):
        scene.replace("soil", model="granite")


def test_replace_validates_like_a_file():
    scene = load_scene("short_period_free")
    with pytest.raises(InputError, match="foundation.springs = -3: must be an integer >= 2"):
        scene.replace("foundation", springs=-3)
    with pytest.raises(InputError, match="foundation.colour: not a field of Foundation"):
        scene.replace("foundation", colour="red")
    with pytest.raises(InputError, match=r"motion.amplitude = 0.3: does not apply to this "
                                         r"scene"):
        scene.replace("motion", amplitude=0.3)
    with pytest.raises(InputError, match="structure.weight = -1"):
        dataclasses.replace(scene, structure=dataclasses.replace(
            scene.structure, stories=(dataclasses.replace(scene.structure.stories[0],
                                                          weight=-1.0),)))
    story = scene.replace("story", stiffness=500.0)
    assert story.structure.stories[0].stiffness == 500.0
    assert story.overrides == ("structure.stiffness=500.0",)


# ---------------------------------------------------------------------------------------------
# Names that say what they measure
# ---------------------------------------------------------------------------------------------


def test_the_paper_summary_says_whether_a_run_ended_at_rest(tmp_path):
    """The summary's "residual settlement" was the final −V of a wall still rocking. The
    undamped elastic wall (Fig. 4, ε = 1) conserves its energy, so it can never be at rest
    (closed form: a conservative system); Case A with 40 % damping run for 20 s is (its kinetic
    energy falls as exp(−2ζωt), below 1e-10 of its peak in the last 2 s)."""
    from upliftlab.reduced.paper import at_rest, paper_study

    wall = run(load_scene("wall_free", case="e10"), output_dt=0.005)
    assert not at_rest(wall)
    damped = run(load_scene("short_period_free", case="A", overrides=["motion.duration=20"]))
    assert at_rest(damped)
    summary = paper_study(tmp_path, None)
    row = summary["runs"]["wall_free-e10"]
    assert row["at_rest"] is False and "residual_settlement" not in row
    assert row["final_settlement"] == pytest.approx(-float(wall.V[-1]), rel=1e-12)
    text = (tmp_path / "summary.md").read_text()
    assert "| settlement −V at the end [in] |" in text and "residual settlement [in]" not in text
    line = next(x for x in text.splitlines() if x.startswith("| wall_free-e10 |"))
    assert f"{row['final_settlement']:.4f} (moving)" in line


def test_advice_says_what_it_was_certified_against():
    from upliftlab.comparisons.advise.ladder import ReferenceCheck, certified_against

    ref = ReferenceCheck(1.0, 160, 0.005, 0.1, 0.0, 0.0, 1e-6)
    clay = certified_against(load_scene("strip_footing_clay"), ref)
    assert "Winkler bed of N = 160 springs" in clay and "NOT against the soil" in clay
    wall = certified_against(load_scene("wall_free"), ref)
    assert "N = 80" in wall and "soil" not in wall


# ---------------------------------------------------------------------------------------------
# Physical and resource bounds
# ---------------------------------------------------------------------------------------------


def test_a_run_above_its_budget_is_refused_with_its_cost(tmp_path, capsys, elcentro):
    """``--dt 1e-12`` ran for days. The steps are counted before the run (31.2 s / 1e-12 s =
    3.12e13, exactly) and the run refused, naming the key that raises the limit."""
    assert cli(["run", "short_period_elcentro", "--case", "C", "--dt", "1e-12", "--no-figure",
                "--out", str(tmp_path / "o")]) == 2
    line = _error(capsys)
    assert "analysis.max_steps = 10000000: the reduced run would take 3.12e+13 steps" in line
    assert not (tmp_path / "o").exists()
    from upliftlab.budget import GIB, Cost, check
    with pytest.raises(InputError, match=r"analysis.max_memory = 1 GiB: .* 2 GiB .*"
                                         r"--set analysis.max_memory=2\)"):
        check(Cost("a run", 10, 0.1, 2 * GIB, 1.0, "x"), 100, 1.0)


def test_continuum_physics_is_checked_before_meshing(tmp_path, capsys):
    base = ["continuum", "strip_footing_clay", "--no-render", "--out", str(tmp_path / "o")]
    assert cli([*base, "--theta-max", "3"]) == 2
    assert "--theta-max = 3: valid range is (0, 0.1]" in _error(capsys)
    assert cli([*base, "--set", "soil.youngs_modulus=1e300"]) == 2
    assert "soil.youngs_modulus = 1e+300: outside the physical range" in _error(capsys)
    # FS_v = 3 on (2 + π) c_u B: a load of 3.1 times the scene's is beyond the capacity
    assert cli([*base, "--set", "structure.vertical_weight=540"]) == 2
    assert "at or above the strip's bearing capacity (2 + π) c_u B = 514.2" in _error(capsys)
    # N/(E B) = 1e-9/(5e4 * 2) = 1e-14: below the 1e-12 the pushover resolves
    assert cli([*base, "--set", "structure.vertical_weight=1e-9"]) == 2
    assert "1e-14 of the soil's E·B = 1e+05; below 1e-12 the footing's response" in \
        _error(capsys)
    assert cli([*base, "--analysis", "dynamic", "--set", "soil.density="]) == 2
    assert "soil.density = 0 (0 when it is missing)" in _error(capsys)
    assert cli([*base, "--mesh", "elements_across=1024"]) == 2
    assert "analysis.max_memory = 4 GiB: the continuum pushover would take" in _error(capsys)
    assert not (tmp_path / "o").exists()


def test_commands_name_the_extra_they_need(tmp_path, capsys, monkeypatch):
    import importlib.util

    real = importlib.util.find_spec
    missing = {"skfem", "matplotlib", "openseespy"}
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name in missing else real(name, *a))
    assert cli(["continuum", "strip_footing_clay", "--no-render",
                "--out", str(tmp_path / "o")]) == 2
    assert "pip install 'upliftlab[continuum]'" in _error(capsys)
    assert cli(["run", "wall_free", "--out", str(tmp_path / "o")]) == 2
    assert "pip install 'upliftlab[plot]'; or add --no-figure" in _error(capsys)
    assert cli(["paper", "--out", str(tmp_path / "o")]) == 2
    assert "pip install 'upliftlab[plot]'" in _error(capsys)
    assert cli(["report", "--fast", "--out", str(tmp_path / "o")]) == 2
    assert "pip install 'upliftlab[continuum,plot]'" in _error(capsys)
    assert not (tmp_path / "o").exists()


# ---------------------------------------------------------------------------------------------
# Output folders: checked first, claimed, marked complete, never mixed
# ---------------------------------------------------------------------------------------------


def test_a_run_is_marked_complete_and_a_different_run_needs_force(tmp_path, capsys):
    out = tmp_path / "o"
    args = ["run", "wall_free", "--no-figure", "--set", "analysis.duration=0.1", "--out",
            str(out)]
    assert cli(args) == 0
    marker = read_marker(out)
    assert marker["complete"] and marker["files"] == ["wall_free.nc"]
    assert not (out / LOCK).exists()
    assert cli(args) == 0  # the same run again: replaced
    capsys.readouterr()
    other = ["run", "wall_free", "--no-figure", "--set", "analysis.duration=0.2", "--out",
             str(out)]
    assert cli(other) == 2
    assert "holds a different run (overrides ['analysis.duration=0.1'])" in _error(capsys)
    assert read_marker(out) == marker
    assert cli([*other, "--force"]) == 0
    assert read_marker(out)["settings"]["overrides"] == ["analysis.duration=0.2"]


def test_the_default_folder_carries_the_case_and_a_digest_of_the_overrides(tmp_path,
                                                                            monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli(["run", "wall_free", "--case", "e07", "--no-figure", "--set",
                "analysis.duration=0.1"]) == 0
    assert cli(["run", "wall_free", "--case", "e07", "--no-figure", "--set",
                "analysis.duration=0.2"]) == 0
    folders = sorted(p.name for p in (tmp_path / "results").iterdir())
    assert len(folders) == 2 and all(f.startswith("wall_free-e07-") for f in folders)


def test_a_live_writer_is_named_before_the_folders_old_run_is_judged(tmp_path, capsys):
    """A folder holding a finished run of other settings *and* a live writer's lock: the live
    writer is the reason given (it is what the user must wait for), and its lock stays."""
    out = tmp_path / "o"
    args = ["run", "wall_free", "--no-figure", "--out", str(out), "--set"]
    assert cli([*args, "analysis.duration=0.1"]) == 0
    capsys.readouterr()
    (out / LOCK).write_text(str(os.getpid()))
    assert cli([*args, "analysis.duration=0.2"]) == 2
    error = _error(capsys)
    assert "another upliftlab run is writing to it" in error and "different run" not in error
    assert (out / LOCK).read_text() == str(os.getpid())
    (out / LOCK).unlink()
    assert cli([*args, "analysis.duration=0.2"]) == 2
    assert "holds a different run" in _error(capsys) and not (out / LOCK).exists()


def test_stale_temporary_files_are_cleaned_and_live_locks_refused(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    (out / LOCK).write_text(str(os.getpid()))  # a live process (this one) holds it
    args = ["run", "wall_free", "--no-figure", "--set", "analysis.duration=0.1", "--out",
            str(out)]
    assert cli(args) == 2
    assert f"another upliftlab run is writing to it (process {os.getpid()})" in _error(capsys)
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True).stdout.strip()
    (out / LOCK).write_text(dead)  # a process that has ended: a stale lock
    (out / f".wall_free.nc.upliftlab-{dead}-abc123.part").write_text("half a file")
    assert cli(args) == 0
    assert not list(out.glob("*.part")) and not (out / LOCK).exists()
    assert read_marker(out)["complete"]


@pytest.mark.parametrize("content", ["99999999999999999999", "-1", "0", "nobody"])
def test_a_lock_holding_no_process_id_is_stale(content, tmp_path, capsys):
    """A lock whose content no upliftlab run writes (a number beyond any process id, -1, 0, a
    word) is taken as stale: the run proceeds and leaves no lock (it used to fail with an
    OverflowError, or stay locked for good by 'process -1')."""
    out = tmp_path / "locked"
    out.mkdir()
    (out / LOCK).write_text(content + "\n")
    assert cli(["run", "wall_free", "--no-figure", "--set", "analysis.duration=0.1", "--out",
                str(out)]) == 0, capsys.readouterr().err
    assert read_marker(out)["complete"] and not (out / LOCK).exists()


def test_an_empty_lock_is_refused_with_what_to_do(tmp_path, capsys):
    """An empty lock is a run that has not yet written its id (or a crash's): refused, kept."""
    out = tmp_path / "locked"
    out.mkdir()
    (out / LOCK).write_text("")
    assert cli(["run", "wall_free", "--no-figure", "--out", str(out)]) == 2
    assert _error(capsys) == (f"upliftlab: error: --out = {str(out)!r}: another upliftlab run "
                              "is writing to it (lock file .upliftlab.lock, empty or "
                              "unreadable; if no upliftlab run is writing there, a crash left "
                              "it: remove it)")
    assert (out / LOCK).read_text() == ""


def test_a_killed_run_leaves_no_marker_and_the_next_run_recovers(tmp_path):
    """Kill a run (SIGKILL, so nothing is cleaned up) and check the folder says it is
    incomplete; the next run takes the folder over and completes it."""
    out = tmp_path / "o"
    cmd = [sys.executable, "-m", "upliftlab", "run", "short_period_free", "--case", "C",
           "--no-figure", "--dt", "2e-6", "--integrator", "rk4", "--set",
           "analysis.max_steps=100000000", "--out", str(out)]
    env = {**os.environ, "MPLBACKEND": "Agg"}
    proc = subprocess.Popen(cmd, env=env, cwd=tmp_path, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while not (out / LOCK).exists() and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.05)
    assert (out / LOCK).exists(), proc.stderr.read() if proc.poll() is not None else ""
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    assert read_marker(out) is None and (out / LOCK).exists()
    killed = out / f".short_period_free-C.nc.upliftlab-{proc.pid}-x.part"
    killed.write_text("what a killed writer leaves")
    assert cli(["run", "short_period_free", "--case", "C", "--no-figure", "--set",
                "analysis.duration=0.1", "--out", str(out)]) == 0
    assert read_marker(out)["complete"] and not list(out.glob(".*.part"))


def test_sweep_workers_die_with_their_parent(tmp_path):
    """Kill a process that holds a pool of sweep workers; the workers must end within a few
    seconds (they polled for their parent every 0.5 s), instead of computing on."""
    script = tmp_path / "pool.py"
    script.write_text(textwrap.dedent("""
        import sys, time
        from upliftlab.comparisons.framework.sweep import sweep_executor

        if __name__ == "__main__":
            with sweep_executor(workers=2) as pool:
                futures = [pool.submit(time.sleep, 600) for _ in range(2)]
                time.sleep(3)
                print(" ".join(str(p) for p in pool._processes), flush=True)
                time.sleep(600)
    """))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    pids = [int(p) for p in proc.stdout.readline().split()]
    assert len(pids) == 2
    proc.kill()
    proc.wait(timeout=30)
    deadline = time.monotonic() + 20
    alive = pids
    while alive and time.monotonic() < deadline:
        time.sleep(0.2)
        alive = [p for p in pids if _running(p)]
    assert not alive, f"workers {alive} outlived their parent"


def _running(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().split()[2] != "Z"
    except FileNotFoundError:
        return False


def test_default_continuum_folder_without_options_is_the_plain_name(tmp_path, monkeypatch,
                                                                    capsys):
    """Only what the user gives names a digest: the default pushover goes to
    results/<scene>-continuum-pushover, a run with --steps to a folder of its own."""
    import upliftlab.cli.continuum as cc

    folders = []

    def record(out, default, **_):
        folders.append(Path(default))
        raise InputError("stop before any work")

    monkeypatch.setattr(cc, "claim", record)
    assert cli(["continuum", "strip_footing_clay", "--no-render"]) == 2
    assert cli(["continuum", "strip_footing_clay", "--no-render", "--steps", "6"]) == 2
    assert folders[0] == Path("results") / "strip_footing_clay-continuum-pushover"
    assert folders[1].name.startswith("strip_footing_clay-continuum-pushover-")
    assert len(folders[1].name) == len(folders[0].name) + 9  # "-" and 8 hex digits


@pytest.mark.parametrize("case, extra", [("A", ()), ("B", ("foundation.law=qz",
                                                            "foundation.capacity_multiple=3",
                                                            "foundation.z50=0.2"))])
def test_a_yield_multiple_override_without_an_elastoplastic_law_is_refused(case, extra):
    # Reference: the spring laws (reduced/laws/elastoplastic.py, reduced/laws/qz/): only the
    # elasto-plastic spring reads the yield multiple; an override elsewhere would change nothing.
    with pytest.raises(InputError, match=r"has no effect: the yield multiple acts only with "):
        load_scene("short_period_free", case=case,
                   overrides=[*extra, "foundation.yield_multiple=5"])
    assert load_scene("short_period_free", case="C",
                      overrides=["foundation.yield_multiple=5"]).foundation.law.yield_multiple == 5


def test_a_step_that_runs_as_another_is_said(tmp_path, capsys):
    """A run's steps are whole numbers in its duration: ``--dt 0.7`` on a 3 s run ran as 0.6 s,
    ``--dt 10`` as 3 s and ``analysis.output_dt = 0.07`` on 0.2 s as 0.0667 s, with no word
    (the reference: 3/0.7 → 5 steps of 0.6 s; 0.2/0.07 → 3 outputs of 0.2/3 s)."""
    cases = [(["--dt", "0.7"], "--dt = 0.7 s runs as 0.6 s, a whole number of steps in the "
                               "run's 3 s"),
             (["--dt", "10"], "--dt = 10 s runs as 3 s"),
             (["--set", "analysis.output_dt=0.07", "--set", "motion.duration=0.2"],
              "analysis.output_dt = 0.07 s runs as 0.0666667 s"),
             (["--set", "analysis.dt=0.07", "--set", "motion.duration=0.2"],
              "analysis.dt = 0.07 s runs as 0.0666667 s")]
    for i, (extra, note) in enumerate(cases):
        assert cli(["run", "wall_free", "--case", "e07", "--no-figure", "--json",
                    "--out", str(tmp_path / str(i)), *extra]) == 0
        assert note in capsys.readouterr().err, extra
    assert cli(["run", "wall_free", "--case", "e07", "--no-figure", "--json", "--dt", "0.5",
                "--out", str(tmp_path / "even")]) == 0
    assert "runs as" not in capsys.readouterr().err  # 0.5 s divides 3 s: nothing to say
