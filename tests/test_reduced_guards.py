"""Never a wrong number with exit code 0: the reduced model's guards.

References: the geometry of the toppling block (the centre of the weight over the edge of the
base), energy conservation (the balance every run checks), the eigenvalues of the bonded
system (stability and resolution limits), and densely stored histories of the same run (the
peaks tracked at every step).
"""

import json
import math

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main
from upliftlab.reduced import (EnergyBalanceError, build_model, resolution_limit, run,
                               stability_boundary, stability_limit)
from upliftlab.reduced.run import ModelWarning
from upliftlab.scenes import load_scene, scene_from_dict

WALL_2G = ["motion.pga=2", "structure.p_delta=true"]


def _centre_over_edge(response) -> np.ndarray:
    """|x_G|/b from the stored histories, in the exact geometry: the wall's weight at height h,
    deflected by u in the frame of a base rotated by θ about the edge it leans towards."""
    theta, u = response.theta, response.u
    b, h = response.model.layout.half_width, response.model.heights[-1]
    pivot = b * np.sign(theta) * (1 - np.cos(theta))
    return np.abs(pivot + u * np.cos(theta) + h * np.sin(theta)) / b


def test_overturning_ends_the_run_with_a_verdict(elcentro):
    """The wall (Figs. 3–5) under El Centro scaled to 2 g with P-Δ passes its toppling angle
    (measured at 12.62 s): the run ends there, says so, and every number it reports is
    finite. The last stored state has the centre of the weight over the edge
    (|x_G|/b ≥ 1), the stored states before the reported time (to 1 ms, its interpolation
    within a step) have it inside."""
    response = run(load_scene("wall_elcentro", case="e07", overrides=WALL_2G))
    assert response.verdict == "overturned"
    ratio = _centre_over_edge(response)
    t_over = response.info["overturned_at"]
    assert ratio[-1] >= 1.0 - 1e-9
    assert np.all(ratio[response.time < t_over - 1e-3] < 1.0)
    assert t_over <= response.time[-1]
    assert 10.0 < t_over < 15.0
    assert all(np.isfinite(v) for v in response.summary().values() if isinstance(v, float))


def test_overturning_in_the_json_summary(tmp_path, capsys, elcentro):
    """``upliftlab run --json`` reports the verdict and the time, as valid JSON (exit 0: the
    toppling is the result), and the summary line says OVERTURNED."""
    code = main(["run", "wall_elcentro", "--case", "e07", "--set", "motion.pga=2", "--set",
                 "structure.p_delta=true", "--json", "--no-figure", "--out", str(tmp_path)])
    summary = json.loads(capsys.readouterr().out)
    assert code == 0
    assert summary["verdict"] == "overturned" and summary["overturned_at"] > 10.0
    assert summary["stability_limit"] > 0 and summary["energy_tolerance"] == 1e-3
    main(["run", "wall_elcentro", "--case", "e07", "--set", "motion.pga=2", "--set",
          "structure.p_delta=true", "--no-figure", "--out", str(tmp_path)])
    assert "OVERTURNED at t = " in capsys.readouterr().out


def test_peaks_are_tracked_at_every_step_whatever_is_stored(elcentro):
    """Short-period building, Case A, N = 40, El Centro: the peaks with histories off are
    those with histories on, exactly (the same steps), and the overturning moment and the
    least contact length agree within 0.5 % with the extremes of the same run stored every
    millisecond (interpolated states), which the tracked peaks bound. Without tracking they
    came from two stored states: 38.4 instead of 35 951 kip·in, 240 instead of 35.6 in."""
    scene = load_scene("short_period_elcentro", case="A", overrides=["foundation.springs=40"])
    light = run(scene, histories=False)
    dense = run(scene, output_dt=1e-3)
    for key in ("u", "theta", "overturning_moment", "min_contact_length", "base_shear"):
        assert light.peaks[key] == dense.peaks[key], key
    assert light.peaks["overturning_moment"] == pytest.approx(
        np.abs(dense.overturning_moment).max(), rel=5e-3)
    assert light.peaks["min_contact_length"] == pytest.approx(dense.contact_length.min(),
                                                              rel=5e-3, abs=1e-6)
    # the tracked peaks (cubic through the step's ends) bound the stored quintic interpolants
    # to the interpolants' difference, O(h⁴)
    assert light.peaks["overturning_moment"] >= np.abs(dense.overturning_moment).max() * (1 - 1e-5)
    assert light.peaks["base_shear"] >= np.abs(dense.base_shear).max() * (1 - 1e-5)
    assert light.peaks["overturning_moment"] > 3e4
    assert light.peaks["min_contact_length"] < 60.0


def _block(duration: float, **analysis):
    """A uniform block (h/b = 5, R = 1 m) on edge springs with a 0.1 ms vertical period,
    released at half its toppling angle: the rigid-block limit."""
    alpha = math.atan(0.2)
    return scene_from_dict({
        "schema": 1, "units": "N-m-s",
        "structure": {"weight": 9810.0, "height": math.cos(alpha), "stiffness": 1.0,
                      "rotary_inertia": 1000.0 / 3, "rigid": True, "p_delta": True},
        "foundation": {"half_width": math.sin(alpha), "layout": "edges",
                       "vertical_period": 1e-4},
        "motion": {"type": "free", "rotation": 0.5 * alpha, "duration": duration},
        "analysis": analysis})


def test_an_energy_balance_beyond_tolerance_fails_the_run(capsys):
    """Newmark on the rigid-block limit at 10 steps per vertical period, 3 s: its balance
    ends 2.2 % open (measured), beyond the default 0.1 %: the run raises with the figure, the
    CLI exits 3 with it in one line; relaxing the tolerance to 5 % lets the same run through."""
    with pytest.raises(EnergyBalanceError, match=r"closes to 0.0\d+ of its scale \(the "
                                                  r"largest of the input, .*\), beyond "
                                                  r"analysis.energy_tolerance = 0.001"):
        run(_block(3.0), integrator="newmark", dt=1e-5, histories=False)
    relaxed = run(_block(3.0, energy_tolerance=0.05), integrator="newmark", dt=1e-5,
                  histories=False)
    assert 1e-3 < relaxed.energy_balance_error < 0.05


def test_an_implicit_step_that_cannot_resolve_the_scene_is_refused(capsys):
    """``--dt 1000`` with Newmark (one step, −97 % in peak u, balance "closed" before): refused
    with exit 2 before any work, naming the shortest bonded mode (here the rocking one,
    T = 0.046 s) and the largest admissible step (10 steps per period of eig(K, M)'s
    shortest)."""
    model = build_model(load_scene("short_period_elcentro", case="B"))
    largest, what = resolution_limit(model)
    assert what.startswith("the bonded rocking mode")
    K, _ = model.bonded_matrices()
    w2 = np.linalg.eigvals(np.linalg.solve(np.diag(model.mass), K)).real
    assert largest == pytest.approx(2 * math.pi / math.sqrt(w2.max()) / 10, rel=1e-9)
    code = main(["run", "short_period_elcentro", "--case", "B", "--integrator", "newmark",
                 "--dt", "1000"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert f"valid range is (0, {largest:.4g}] s" in err[0] and what in err[0]


@pytest.mark.parametrize("name", ["rk4", "abm4"])
def test_the_stated_stability_limit_keeps_the_energy_within_tolerance(name):
    """At 0.99 of the stated limit a fixed-step explicit run closes its energy balance within
    the tolerance (the short-period building's free vibration, Case C with every impact
    dashpot, 2 s); at 1.01 it is refused with the limit in the message. The limit is a
    fraction of the stability boundary (where RK4 stops diverging, and at 0.99 of which its
    balance was 28.6 % open)."""
    scene = load_scene("short_period_free", case="C", overrides=["motion.duration=2.0"])
    model = build_model(scene)
    limit = stability_limit(model, name)
    assert limit < stability_boundary(model, name)
    inside = run(scene, integrator=name, dt=0.99 * limit, histories=False)
    assert inside.energy_balance_error <= scene.analysis.energy_tolerance
    with pytest.raises(InputError, match=f"stability limit {limit:.4g} s"):
        run(scene, integrator=name, dt=1.01 * limit)


def test_the_paper_damper_on_many_springs_is_warned_about():
    """Case C's per-spring impact damper on more springs than the paper's 12 does not
    converge in N: the run says so (a ModelWarning, and the note in the summary)."""
    scene = load_scene("short_period_free", case="C", overrides=["foundation.springs=40",
                                                                 "motion.duration=0.5"])
    with pytest.warns(ModelWarning, match="does not converge in N"):
        response = run(scene, histories=False)
    assert any("impact_mass = 'tributary'" in note for note in response.summary()["notes"])
    quiet = run(scene.with_overrides("foundation.impact_mass='tributary'"), histories=False)
    assert quiet.summary()["notes"] == []
