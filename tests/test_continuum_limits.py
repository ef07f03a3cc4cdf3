"""Where the continuum model stops: nearly incompressible soil (ν → 1/2) and the coarsest mesh
(2 elements across the footing), in statics and dynamics. Each works or is refused cleanly.

References, one per test:
- rocking stiffness of a frictionless strip on the elastic half-plane, K_r = π G B²/(8(1 − ν))
  (Muskhelishvili's rigid punch), which holds up to ν = 1/2: the reduced-integration Q2 does not
  lock;
- the incompressible limit of the dynamic response: the footing's peak rotation is continuous
  as ν → 1/2 (ν = 0.499 against 0.4999, measured 0.02 %), with the energy balance closing;
- bad input is refused with one line naming the field, the value and the valid range (exit 2).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab import cli
from upliftlab.checks import InputError
from upliftlab.continuum import build_model, footing_stiffness, make_model
from upliftlab.continuum.dynamics import run as dyn
from upliftlab.continuum.dynamics import ground
from upliftlab.continuum.dynamics.ground import dynamic_ground
from upliftlab.continuum.dynamics.step_rules import implicit_settings
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.scenes import ContinuumOptions, Soil, load_scene

SCENE = "strip_footing_clay"


@pytest.mark.parametrize("n, tolerance", [(2, 0.04), (4, 0.01)])
def test_rocking_stiffness_holds_to_nearly_incompressible_soil(n, tolerance):
    # Reference: K_r = π G B²/(8(1 − ν)) at ν = 0.4999 (measured +3.2 % at 2 across, +0.78 % at
    # 4 across: the same as at ν = 0.3, so no locking).
    nu = 0.4999
    soil = Soil(youngs_modulus=50e3, poisson_ratio=nu, density=1.8, model="elastic")
    model = make_model(soil, 2.0, ContinuumOptions(elements_across=n))
    G = 50e3 / (2.0 * (1.0 + nu))
    reference = math.pi * G * 2.0 ** 2 / (8.0 * (1.0 - nu))
    error = footing_stiffness(model).rocking / reference - 1.0
    print(f"{n} across, ν = {nu}: K_r error {error:+.3%}")
    assert 0.0 < error < tolerance


def test_explicit_dynamics_reaches_the_incompressible_limit():
    # Reference: continuity in ν of the response of a locking-free element, ν = 0.499 against
    # 0.4999 on the coarsest mesh, 1 s of the Ricker pulse (the footing lifts off a quarter of
    # its width); the energy balance closes (measured 5e-6).
    runs = {}
    for nu in (0.499, 0.4999):
        scene = load_scene(SCENE, overrides=["continuum.elements_across=2",
                                             f"soil.poisson_ratio={nu}", "motion.duration=1.0"])
        model = build_model(scene)
        runs[nu] = run_dynamic(model, scene, scene.build_motion(),
                               DynamicOptions(method="explicit", snapshots=0))
    a, b = runs[0.499], runs[0.4999]
    assert b.contact_length.min() < 0.8 * model.width
    assert b.energy_balance_error < 1e-4
    assert np.abs(b.theta).max() == pytest.approx(np.abs(a.theta).max(), rel=2e-3)


def test_implicit_dynamics_refuses_nearly_incompressible_soil(monkeypatch):
    # The implicit route's step rules leave no step beyond ν = 0.494 (dynamics module
    # docstring): refused before any work, naming ν and the explicit route.
    scene = load_scene(SCENE, overrides=["continuum.elements_across=2",
                                         "soil.poisson_ratio=0.4999"])
    model = build_model(scene)
    monkeypatch.setattr(ground, "gravity_state", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(InputError) as info:
        run_dynamic(model, scene, scene.build_motion(), DynamicOptions(method="implicit"))
    text = str(info.value)
    assert text.startswith("soil.poisson_ratio = 0.4999:")
    assert "ν ≤ 0.494" in text and "continuum.dynamics = 'explicit'" in text


def test_implicit_step_below_the_shear_floor_is_refused():
    scene = load_scene(SCENE, overrides=["continuum.elements_across=4"])
    model = build_model(scene)
    floor = dyn.MIN_SHEAR_COURANT * dyn.smallest_element(model) / dyn.wave_speeds(model.soil)[1]
    with pytest.raises(InputError) as info:
        run_dynamic(model, scene, scene.build_motion(),
                    DynamicOptions(method="implicit", dt=0.5 * floor))
    assert f"valid range is [{floor:.4g}, {dyn.time_step_limit(model):.4g}] s" in str(info.value)


@pytest.mark.parametrize("analysis", ["pushover", "dynamic"])
def test_incompressible_soil_is_refused_in_one_line(analysis, tmp_path, capsys):
    # ν = 1/2 has no displacement formulation: exit 2, one line, nothing written.
    code = cli.main(["continuum", SCENE, "--analysis", analysis, "--set",
                     "continuum.elements_across=2", "--set", "soil.poisson_ratio=0.5",
                     "--out", str(tmp_path / "out"), "--no-render"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert err[-1].startswith("upliftlab: error: soil.poisson_ratio = 0.5: valid range")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("method", ["explicit", "implicit"])
def test_two_elements_across_run_statics_and_dynamics(method, tmp_path, capsys):
    # The coarsest mesh the scene allows (continuum.elements_across >= 2) runs a pushover and a
    # dynamic run; its dynamic peak θ is within 2 % of 4 across (measured +1.4 % explicit,
    # +1.5 % implicit, 1 s of the Ricker pulse).
    out = tmp_path / method
    code = cli.main(["continuum", SCENE, "--analysis", "dynamic", "--json", "--set",
                     "continuum.elements_across=2", "--set", f"continuum.dynamics={method}",
                     "--set", "analysis.duration=1.0", "--out", str(out), "--no-render"])
    import json
    coarse = json.loads(capsys.readouterr().out)
    assert code == 0 and coarse["method"] == method
    scene = load_scene(SCENE, overrides=["continuum.elements_across=4", "motion.duration=1.0"])
    model = build_model(scene)
    finer = run_dynamic(model, scene, scene.build_motion(),
                        DynamicOptions(method=method, snapshots=0))
    assert coarse["peak_theta"] == pytest.approx(np.abs(finer.theta).max(), rel=0.02)
    assert cli.main(["continuum", SCENE, "--set", "continuum.elements_across=2", "--steps", "4",
                     "--out", str(tmp_path / "push"), "--no-render"]) == 0


def test_fewer_than_two_elements_across_are_refused(capsys):
    code = cli.main(["continuum", SCENE, "--set", "continuum.elements_across=1"])
    assert code == 2
    assert "continuum.elements_across" in capsys.readouterr().err


def test_implicit_dynamics_accepts_nu_049():
    # ν = 0.49 ran within 1e-3 of energy at V_s dt/h_min = 0.24 (dynamics module docstring):
    # the smallest-step rule must not refuse it.
    scene = load_scene(SCENE, overrides=["continuum.elements_across=4", "soil.model=elastic",
                                         "soil.poisson_ratio=0.49"])
    model = build_model(scene)
    options = DynamicOptions(method="implicit")
    settings = implicit_settings(model, scene, scene.build_motion(), options,
                                 dynamic_ground(model, options))
    vs = dyn.wave_speeds(model.soil)[1]
    assert vs * settings.dt / dyn.smallest_element(model) == pytest.approx(0.2414, rel=1e-3)
