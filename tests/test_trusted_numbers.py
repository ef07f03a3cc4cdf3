"""Numbers a result reports are the numbers of what ran, under names that say what they are
(issue 37, "wrong numbers with exit 0"), each class tried through several cases:

* a scene's ``data`` (what a result's provenance records) cannot be changed after the scene is
  made, through any path of mutation, so the provenance is always what ran;
* ``residual_settlement`` is a settlement (−V, down positive) of a run that has come to rest,
  and nothing else: a run still moving has none; V at the end is ``final_vertical_position``
  and Σkε_p/Σk ``weighted_plastic_settlement`` (advise's quantity of that name);
* a motion far too small to lift the base runs (the energy check measures its residual against
  the bed's static strain energy too), and its response is the linear one;
* a run the estimate says will take long is announced with its time before any step.

References: the closed forms named in each test (a linear elastic bed at rest returns to its
static equilibrium V = 0; an undamped conservative system never comes to rest; superposition
of a linear system).
"""

from __future__ import annotations

import copy
import logging

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main as cli
from upliftlab.reduced import run
from upliftlab.scenes import load_scene, scene_from_dict

# ---------------------------------------------------------------------------------------------
# The scene's data is what ran
# ---------------------------------------------------------------------------------------------

MUTATIONS = [
    lambda d: d.__setitem__("title", "changed"),
    lambda d: d["structure"].__setitem__("weight", 1.0),
    lambda d: d["foundation"].update(springs=2),
    lambda d: d["foundation"].pop("springs"),
    lambda d: d.setdefault("soil", {}),
    lambda d: d["structure"].clear(),
    lambda d: d.__delitem__("motion"),
    lambda d: d["structure"]["story"].append({"weight": 1.0}),
    lambda d: d["structure"]["story"].__setitem__(0, {}),
    lambda d: d["structure"]["story"][0].__setitem__("weight", 1.0),
]


@pytest.mark.parametrize("mutate", MUTATIONS)
def test_a_scenes_data_cannot_be_changed_after_it_is_made(mutate):
    """Before, ``scene.data["structure"]["weight"] = 1`` made a result's provenance claim a
    weight that never ran. Every way to change it now raises; a deep copy is a plain,
    mutable table (how a caller derives a changed scene)."""
    scene = load_scene("three_story_frame")
    before = copy.deepcopy(scene.data)
    with pytest.raises(TypeError, match="read-only"):
        mutate(scene.data)
    assert scene.data == before
    mutable = copy.deepcopy(scene.data)
    mutate(mutable)
    assert mutable != before


def test_the_table_a_scene_was_made_from_is_not_shared_with_it():
    """Changing the caller's table after ``scene_from_dict`` changes neither the scene nor its
    provenance; the provenance of a run is the scene's data and digest."""
    import tomllib
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "scenes" / "wall_free.toml"
    table = tomllib.loads(path.read_text())
    scene = scene_from_dict(table, source=str(path), case="e07",
                            overrides=("motion.duration=0.2",))
    table["structure"]["weight"] = 1.0
    response = run(scene, histories=False)
    assert response.provenance["scene_data"] == scene.data
    assert response.provenance["scene_data"]["structure"]["weight"] != 1.0
    assert response.provenance["scene_digest"] == scene.digest


# ---------------------------------------------------------------------------------------------
# Residual settlement, final vertical position, weighted plastic settlement
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("scene, case, overrides", [
    ("wall_free", "e10", ()),
    ("wall_free", "e07", ()),
    ("short_period_free", "A", ("motion.duration=1",)),
])
def test_a_run_still_moving_has_no_residual_settlement(scene, case, overrides, tmp_path,
                                                       monkeypatch, capsys):
    """The elastic wall (ε = 1) is a conservative system (closed form: it can never come to
    rest); ε = 0.7 and Case A at 1 s are still moving too. Before, each reported −V at the end
    as a residual settlement (−0.42 in for the first: an upward "settlement")."""
    import json

    response = run(load_scene(scene, case=case, overrides=list(overrides)), output_dt=0.005)
    assert not response.at_rest()
    assert "residual_settlement" not in response.peaks
    assert response.peaks["final_vertical_position"] == float(response.V[-1])
    monkeypatch.chdir(tmp_path)
    assert cli(["run", scene, "--case", case, *[a for o in overrides for a in ("--set", o)],
                "--no-figure", "--json", "--out", "o"]) == 0
    summary = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert summary["residual_settlement"] is None and summary["at_rest"] is False
    assert summary["final_vertical_position"] == pytest.approx(float(response.V[-1]), rel=1e-9)


@pytest.mark.parametrize("scene, case, duration", [
    ("short_period_free", "A", 20), ("long_period_free", "A", 30)])
def test_an_elastic_bed_at_rest_has_no_residual_settlement(scene, case, duration):
    """Case A (elastic, 40 % damping) at rest: a linear elastic bed returns to its static
    equilibrium, V = 0 (closed form), so the residual settlement is 0 to 1e-9 of the peak V."""
    response = run(load_scene(scene, case=case, overrides=[f"motion.duration={duration}"]),
                   output_dt=0.005)
    assert response.at_rest()
    peak = max(abs(response.peaks["V_min"]), abs(response.peaks["V_max"]))
    assert abs(response.peaks["residual_settlement"]) <= 1e-9 * peak
    assert response.peaks["weighted_plastic_settlement"] == 0.0


def test_a_yielded_bed_at_rest_settles_less_than_its_weighted_plastic_settlement():
    """Case B at rest after 30 s: the residual settlement is −V then (> 0, down); the
    stiffness-weighted plastic settlement Σkε_p/Σk is another quantity, larger (the edges
    settled more, the base rests on the middle springs: gaps stay open under the edges)."""
    response = run(load_scene("long_period_free", case="B", overrides=["motion.duration=30"]),
                   output_dt=0.005)
    assert response.at_rest()
    settled = response.peaks["residual_settlement"]
    assert settled == -float(response.V[-1]) and settled > 0.0
    assert np.max(response.uplift[-1]) > 0.0  # springs open at rest
    assert response.peaks["weighted_plastic_settlement"] > 1.2 * settled


# ---------------------------------------------------------------------------------------------
# Tiny motions run, and are linear
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("tiny", [1e-12, 1e-100, 1e-200])
def test_a_tiny_free_vibration_runs_and_is_linear(tiny):
    """Refused before after the work (exit 3: "1.57e+84 of the input" for 1e-200 in/s): the
    balance's rounding residual, about 1e-16 of the bed's static strain energy, was measured
    against an input energy of 1e-400. Reference: superposition: the run at v0 = 1e-3 in/s,
    which lifts no spring, scaled by tiny/1e-3 (to 1e-9; fixed-step RK4, the same steps)."""
    def peaks(v):
        scene = load_scene("wall_free", case="e07", overrides=[f"motion.velocity={v}",
                                                               "motion.duration=1",
                                                               "analysis.integrator='rk4'"])
        return run(scene, histories=False).peaks

    linear, small = peaks(1e-3), peaks(tiny)
    assert linear["uplift_left"] == 0.0
    for key in ("u", "theta", "base_shear"):
        assert small[key] == pytest.approx(linear[key] * tiny / 1e-3, rel=1e-9)


@pytest.mark.parametrize("scale", [1e-10, 1e-100])
@pytest.mark.parametrize("case", ["A", "C"])
def test_a_tiny_record_runs_and_is_linear(scale, case, tmp_path):
    """A record scaled by 1e-10 was refused after the work ("1.67e+05 of the input" for Case
    C). Reference: superposition against the same record scaled by 1e-3, which lifts no
    spring (to 1e-6: the event stepper's error control picks its own steps)."""
    record = tmp_path / "pulse.txt"
    t = np.arange(0.0, 1.0, 0.01)
    record.write_text("".join(f"{a:.3f} {0.3 * np.sin(2 * np.pi * a / 0.4):.6f}\n" for a in t))

    def peaks(s):
        scene = load_scene("short_period_elcentro", case=case, motion=str(record),
                           overrides=[f"motion.scale={s}", "analysis.duration=1.5"])
        return run(scene, histories=False).peaks

    linear, small = peaks(1e-3), peaks(scale)
    assert linear["uplift_left"] == 0.0
    for key in ("u", "theta"):
        assert small[key] == pytest.approx(linear[key] * scale / 1e-3, rel=1e-6)


# ---------------------------------------------------------------------------------------------
# A long run is announced with its estimate before it starts
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("springs", [20_000, 50_000, 100_000])
def test_a_run_of_many_springs_is_announced_with_its_time_before_any_step(springs, caplog,
                                                                          monkeypatch):
    """100 000 springs ran for hours with nothing said: the event stepper's located switches
    (about 20 per spring and second) each pass over every spring, so its time grows as N²
    (measured 0.37, 5.2, 133 s at 250, 1000, 4000 springs on wall_free e07). The estimate
    says so before the first step (the integration is stopped here at its start). Above the
    default time budget such a run is refused instead (tests/test_budget.py); here the budget
    is raised on purpose."""
    import sys

    run_module = sys.modules["upliftlab.reduced.run"]

    class Started(Exception):
        pass

    def stop(*args, **kwargs):
        raise Started

    monkeypatch.setattr(run_module, "integrate", stop)
    scene = load_scene("wall_free", case="e07", overrides=[f"foundation.springs={springs}"])
    with caplog.at_level(logging.WARNING, logger="upliftlab"), pytest.raises(Started):
        run(scene, histories=False, budget=1e9)  # beyond the default budget: asked for
    warned = [r.getMessage() for r in caplog.records if "roughly" in r.getMessage()]
    assert len(warned) == 1 and f"{springs + 1} springs" in warned[0], warned
    assert "located switches" in warned[0] and (" h " in warned[0] or "min" in warned[0])


def test_a_short_run_is_not_announced(caplog):
    with caplog.at_level(logging.WARNING, logger="upliftlab"):
        run(load_scene("wall_free", case="e07", overrides=["motion.duration=0.2"]),
            histories=False)
    assert not [r for r in caplog.records if "roughly" in r.getMessage()]


def test_a_scene_with_a_subnormal_field_is_refused_in_code():
    with pytest.raises(InputError, match="structure.weight = .*subnormal"):
        load_scene("wall_free", case="e07", overrides=["structure.weight=1e-310"])
