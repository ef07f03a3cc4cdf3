"""The macro-element scene for users of Tcl OpenSees (``upliftlab opensees`` on a scene with
``foundation.law = "macro"``): the fixed ``model.tcl`` on Gajan and Kutter's
``soilFootingSection2d``, its numbers and where the models correspond.

No Tcl OpenSees runs here (none on the machine; openseespy has no such section). The script is
sourced in ``tclsh``, an independent interpreter, with every OpenSees command it calls recorded
by a stub: references are the scene's own inputs in closed form (FS = V_ult/W_v is the scene's
``capacity_multiple``; the story's k = (2π/T)² W/g and a guided column's 12 E I/h³; the
masses W/g), the run's step count ⌈duration/dt⌉ and the record's samples.
"""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import pytest

from upliftlab import cli
from upliftlab.scenes import load_scene

SETS = ["foundation.law=macro", "foundation.capacity_multiple=3.0",
        "foundation.sway_stiffness=38000", "structure.vertical_weight=180",
        "foundation.sway_damping=200", "foundation.rocking_stiffness=60000"]
STUB = r"""
set commands {model node fix mass section element uniaxialMaterial geomTransf equalDOF region
              timeSeries load constraints numberer system test algorithm integrator analysis
              loadConst remove wipeAnalysis recorder wipe}
foreach name $commands {
    proc $name {args} "puts \[concat $name \$args\]"
}
proc pattern {args} {
    puts [concat pattern [lrange $args 0 end-1]]
    if {[lindex $args 0] eq "Plain"} {uplevel #0 [lindex $args end]}
}
proc analyze {args} {puts [concat analyze $args]; return 0}
"""


def _tclsh() -> str:
    path = shutil.which("tclsh")
    if path is None:
        pytest.fail("tclsh is missing: the Tcl model's test sources it (Debian/Ubuntu: "
                    "apt-get install tcl)")
    return path


def _write(tmp_path, *extra) -> Path:
    out = tmp_path / "tcl"
    args = ["opensees", "strip_footing_clay", "--out", str(out)]
    for item in SETS + list(extra):
        args += ["--set", item]
    assert cli.main(args) == 0
    return out


def _source(folder: Path):
    prelude = folder.parent / "stub.tcl"
    prelude.write_text(STUB + f"\nsource {{{folder / 'model.tcl'}}}\n")
    done = subprocess.run([_tclsh(), str(prelude)], capture_output=True, text=True,
                          timeout=120)
    calls = []
    for line in done.stdout.splitlines():
        name, _, rest = line.partition(" ")
        calls.append((name, rest.split()))
    return done, calls


def test_the_section_and_the_structure_are_the_scenes(tmp_path):
    scene = load_scene("strip_footing_clay", overrides=SETS)
    folder = _write(tmp_path)
    done, calls = _source(folder)
    assert done.returncode == 0, done.stderr
    section = [args for name, args in calls if name == "section"]
    assert len(section) == 1 and section[0][:2] == ["soilFootingSection2d", "1"]
    FS, Vult, L, Kv, Kh, Rv, dL = map(float, section[0][2:])
    W_v, W = 180.0, scene.structure.stories[0].weight
    assert FS == pytest.approx(3.0, rel=1e-12)  # V_ult/W_v: the scene's capacity_multiple
    assert Vult == pytest.approx(3.0 * W_v, rel=1e-12)
    assert L == pytest.approx(2.0, rel=1e-12) and dL == pytest.approx(2.0 / 40, rel=1e-12)
    # the section rocks like a uniform bed of Kv/L² (contact_interface.py measures it): Kv
    # = 12 K_r/L² gives it the scene's K_r at its uplift onset
    assert Kv == pytest.approx(12.0 * 60000.0 / L ** 2, rel=1e-12)
    assert Kh == pytest.approx(38000.0, rel=1e-12) and Rv == pytest.approx(0.1)
    g = scene.g
    masses = {args[0]: list(map(float, args[1:])) for name, args in calls if name == "mass"}
    assert masses["2"] == pytest.approx([(W_v - W) / g, W_v / g, 29.13], rel=1e-12)
    assert masses["3"] == pytest.approx([W / g, 0.0, 0.0], abs=1e-12)
    column = next(args for name, args in calls if name == "element"
                  and args[0] == "elasticBeamColumn")
    E, I = float(column[5]), float(column[6])
    k = (2.0 * math.pi / 0.3) ** 2 * W / g
    assert 12.0 * E * I / 4.0 ** 3 == pytest.approx(k, rel=1e-9)
    orient = next(args for name, args in calls if name == "element"
                  and args[0] == "zeroLengthSection")
    assert orient[-7:] == ["-orient", "0.0", "-1.0", "0.0", "1.0", "0.0", "0.0"]
    motion = scene.build_motion()
    path = next(args for name, args in calls if name == "timeSeries" and args[0] == "Path")
    assert float(path[path.index("-dt") + 1]) == pytest.approx(motion.dt, rel=1e-12)
    samples = [float(v) for v in (folder / "motion_g.txt").read_text().split()]
    assert samples == pytest.approx(motion.acceleration.tolist(), rel=1e-15)
    numbers = dict(line.split() for line in (folder / "model_numbers.txt").read_text()
                   .splitlines())
    dt = float(numbers["dt"])
    transient = [args for name, args in calls if name == "analyze" and len(args) == 2]
    assert len(transient) == math.ceil(motion.duration / dt - 1e-9)
    assert [args for name, args in calls if name == "analyze"][:3] == [["10"], ["1"], ["1"]]
    notes = (folder / "model.md").read_text()
    assert f"Kv = 12 K_r/L² = {Kv:.6g}" in notes
    assert f"{Kv / scene.foundation.stiffness:.3g} times the element's K_v" in notes


@pytest.mark.parametrize("line", ["Kv 1e5;exit", "Kv [exec touch PWNED]", "Kv 1 2",
                                  "Kw 1.0"])
def test_a_tampered_number_stops_the_script_before_any_model(tmp_path, line):
    folder = _write(tmp_path)
    numbers = folder / "model_numbers.txt"
    text = numbers.read_text().splitlines()
    text = [line if row.startswith("Kv ") else row for row in text]
    numbers.write_text("\n".join(text) + "\n")
    done, calls = _source(folder)
    assert done.returncode != 0 and "model_numbers.txt" in done.stderr
    assert not calls  # nothing built
    assert not (folder / "PWNED").exists() and not (tmp_path / "PWNED").exists()


@pytest.mark.parametrize("args, words", [
    (["--run"], "only Tcl OpenSees has"),
    (["--dashpots", "parallel"], "no springs to put dashpots on"),
    (["--set", "motion.type=free", "--set", "motion.amplitude=", "--set", "motion.period=",
      "--set", "motion.velocity=0.1"], "needs a ground motion"),
])
def test_what_the_tcl_model_cannot_do_is_refused_before_any_file(tmp_path, capsys, args,
                                                                  words):
    out = tmp_path / "out"
    argv = ["opensees", "strip_footing_clay", "--out", str(out)] + args
    for item in SETS:
        argv += ["--set", item]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0]
    assert not out.exists()


def test_step_count_above_max_steps_refused(tmp_path, capsys):
    """A Tcl model of more Newmark steps than analysis.max_steps is refused with one line, exit
    2, before any file is written (as the OpenSeesPy script's)."""
    out = tmp_path / "tcl"
    args = ["opensees", "strip_footing_clay", "--out", str(out), "--dt", "1e-12"]
    for item in SETS:
        args += ["--set", item]
    assert cli.main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "analysis.max_steps = 10000000: the OpenSees run would take " in err[0]
    assert "Newmark steps of 1e-12 s" in err[0]
    assert not out.exists()
