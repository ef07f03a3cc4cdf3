"""The driver of OpenSees's contact interface model (``benchmarks/contact_interface.py``): the
Tcl model's structure, its Newmark and Newton, and the compiled interface, held to an
independent solution with a stand-in section.

OpenSees's source is not at hand in the tests, so a linear elastic stand-in of the section (the
same class name, constructor and members that the C interface reads) is compiled through the
same path, :func:`contact_interface.compile_section`, from a fake source tree. On it the
driver's model is linear, and its response to a Ricker pulse is held to scipy's ``solve_ivp``
(DOP853, rtol 1e-10) of the same masses, stiffness and damping written out here from the Tcl
model's description: an independent algorithm. The benchmark's fast path is run on the stand-in
too, and its beds' errors held to the committed table (they do not depend on OpenSees).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import bench_output
import contact_interface as ci

ROOT = Path(__file__).resolve().parents[1]

#: A linear section: V = Kv (−v), H = Kh u, M = Kt θ with Kt = Kv L³/12 (the real section's
#: elastic rocking stiffness), three points along the footing for the gaps.
STAND_IN_H = """
#ifndef SoilFootingSection2d_h
#define SoilFootingSection2d_h
#include <SectionForceDeformation.h>
class SoilFootingSection2d : public SectionForceDeformation {
 public:
  SoilFootingSection2d(int tag, double fs, double vult, double l, double kv, double kh,
                       double rv, double deltaL);
  ~SoilFootingSection2d();
  int commitState();
  int setTrialSectionDeformation(const Vector &e);
  const Vector &getStressResultant();
  const Matrix &getSectionTangent();
  const Matrix &getInitialTangent();
 private:
  double L, Kv, Kh, Kt;
  int noNodes;
  double **foot, **soilMin;
  Vector s;
  Matrix ks;
};
#endif
"""
STAND_IN_CPP = """
#include <SoilFootingSection2d.h>
SoilFootingSection2d::SoilFootingSection2d(int tag, double fs, double vult, double l,
    double kv, double kh, double rv, double deltaL)
    : SectionForceDeformation(tag, 1), L(l), Kv(kv), Kh(kh), Kt(kv * l * l * l / 12.0),
      noNodes(2), s(3), ks(3, 3) {
  foot = new double *[3];
  soilMin = new double *[3];
  for (int i = 0; i < 3; i++) {
    foot[i] = new double[3]();
    soilMin[i] = new double[3]();
  }
  ks(0, 0) = Kv; ks(1, 1) = Kh; ks(2, 2) = Kt;
}
SoilFootingSection2d::~SoilFootingSection2d() {
  for (int i = 0; i < 3; i++) { delete[] foot[i]; delete[] soilMin[i]; }
  delete[] foot; delete[] soilMin;
}
int SoilFootingSection2d::commitState() { return 0; }
int SoilFootingSection2d::setTrialSectionDeformation(const Vector &e) {
  s(0) = Kv * e(0); s(1) = Kh * e(1); s(2) = Kt * e(2);
  for (int i = 0; i < 3; i++) foot[i][0] = e(0) + (i - 1) * 0.5 * L * e(2);
  return 0;
}
const Vector &SoilFootingSection2d::getStressResultant() { return s; }
const Matrix &SoilFootingSection2d::getSectionTangent() { return ks; }
const Matrix &SoilFootingSection2d::getInitialTangent() { return ks; }
"""

#: A structure whose every mode has ω Δt ≤ 0.04 at Δt = 0.5 ms (so Newmark's period error is
#: below 1.5e-4 of a cycle), in kN, m, s.
NUMBERS = {"g": 9.81, "story_weight": 100.0, "vertical_weight": 150.0, "height": 3.0,
           "story_stiffness": 1610.0, "story_damping_beta": 0.0, "rotary_inertia": 50.0,
           "FS": 5.0, "Vult": 750.0, "L": 2.0, "Kv": 2.75e4, "Kh": 2.26e4, "Rv": 0.1,
           "dL": 0.05, "sway_damping": 60.0, "dt": 5e-4, "steps": 4000.0, "motion_dt": 0.01,
           "motion_points": 201.0, "has_motion": 1.0, "gravity_steps": 10.0,
           "tolerance": 1e-12, "p_delta": 0.0}


@pytest.fixture(scope="module")
def stand_in(tmp_path_factory) -> Path:
    """The stand-in's source tree and the library compiled from it by the driver's path."""
    tree = tmp_path_factory.mktemp("opensees")
    source = tree / ci.SECTION
    source.mkdir(parents=True)
    (source / "SoilFootingSection2d.h").write_text(STAND_IN_H)
    (source / "SoilFootingSection2d.cpp").write_text(STAND_IN_CPP)
    return tree


def _pulse() -> np.ndarray:
    """A Ricker pulse of 0.4 s centred at 0.6 s, 0.3 g, at 0.01 s for 2 s (g)."""
    t = np.arange(int(NUMBERS["motion_points"])) * NUMBERS["motion_dt"]
    x = (np.pi * (t - 0.6) / 0.4) ** 2
    return 0.3 * (1.0 - 2.0 * x) * np.exp(-x)


def _reference(accel_g: np.ndarray, times: np.ndarray) -> np.ndarray:
    """The linear model's (u2, v2, θ2, u3) from rest by DOP853: M ẍ + C ẋ + K x = −M r a_g,
    the massless v3 condensed out (it carries only the column's axial spring)."""
    n = NUMBERS
    h, k = n["height"], n["story_stiffness"]
    Kt = n["Kv"] * n["L"] ** 3 / 12.0
    # the story: an Euler-Bernoulli column of E I = k h³/12 whose two ends turn with θ2
    EI = k * h ** 3 / 12.0
    beam = EI * np.array([[12 / h ** 3, 6 / h ** 2, -12 / h ** 3, 6 / h ** 2],
                          [6 / h ** 2, 4 / h, -6 / h ** 2, 2 / h],
                          [-12 / h ** 3, -6 / h ** 2, 12 / h ** 3, -6 / h ** 2],
                          [6 / h ** 2, 2 / h, -6 / h ** 2, 4 / h]])
    # beam DOFs (w_i, φ_i, w_j, φ_j) with w = −u (the column's transverse axis is −x) and
    # φ_i = φ_j = θ: w_i = −u2, w_j = −u3
    T = np.zeros((4, 4))
    T[0, 0], T[1, 2], T[2, 3], T[3, 2] = -1.0, 1.0, -1.0, 1.0
    K = T.T @ beam @ T
    K[0, 0] += n["Kh"]
    K[1, 1] += n["Kv"]
    K[2, 2] += Kt
    M = np.diag([(n["vertical_weight"] - n["story_weight"]) / n["g"],
                 n["vertical_weight"] / n["g"], n["rotary_inertia"], n["story_weight"] / n["g"]])
    C = np.zeros((4, 4))
    C[0, 0] = n["sway_damping"]
    r = np.array([1.0, 0.0, 0.0, 1.0])
    t_motion = np.arange(accel_g.size) * n["motion_dt"]
    Minv = np.linalg.inv(M)

    def rate(t, y):
        x, v = y[:4], y[4:]
        ag = n["g"] * np.interp(t, t_motion, accel_g, right=0.0)
        return np.concatenate([v, Minv @ (-M @ r * ag - C @ v - K @ x)])

    sol = solve_ivp(rate, (0.0, times[-1]), np.zeros(8), method="DOP853", rtol=1e-10,
                    atol=1e-14, t_eval=times, max_step=n["motion_dt"] / 2)
    return sol.y[:4].T


def test_the_driver_matches_an_independent_solution_of_the_linear_model(stand_in, tmp_path):
    """θ, the footing's sway and the story deformation from the driver on the linear stand-in
    within 0.5 % of their peaks of DOP853's (reference: scipy's solve_ivp, module docstring);
    the gravity state within 1e-9 of the closed form W_v/K_v."""
    library = ci.compile_section(stand_in, tmp_path)
    accel = _pulse()
    out = ci.run_numbers(library, NUMBERS, accel)
    assert "failed_at" not in out
    assert -out["static"][1] == pytest.approx(NUMBERS["vertical_weight"] / NUMBERS["Kv"],
                                              rel=1e-9)
    ref = _reference(accel, out["t"])
    theta, sway = out["theta"] - out["static"][2], out["u"] - out["static"][0]
    s = out["s"] - (out["static"][3] - out["static"][0] + NUMBERS["height"] * out["static"][2])
    s_ref = ref[:, 3] - ref[:, 0] + NUMBERS["height"] * ref[:, 2]
    for got, want in ((theta, ref[:, 2]), (sway, ref[:, 0]), (s, s_ref)):
        assert np.max(np.abs(want)) > 0.0
        assert np.max(np.abs(got - want)) <= 5e-3 * np.max(np.abs(want))


def test_the_stand_in_gaps_are_the_footing_s_own(stand_in, tmp_path):
    """The edge gaps the driver records are the section's (surface − footing, ≥ 0) at its two
    ends: on the stand-in, max(0, −(−v ∓ L θ/2)) from the same run's v and θ."""
    library = ci.compile_section(stand_in, tmp_path)
    out = ci.run_numbers(library, NUMBERS, _pulse())
    e0, half = -out["v"], 0.5 * NUMBERS["L"] * out["theta"]
    assert np.allclose(out["gap_left"], np.maximum(0.0, -(e0 - half)), atol=1e-15)
    assert np.allclose(out["gap_right"], np.maximum(0.0, -(e0 + half)), atol=1e-15)
    # the pulse lifts both edges in turn, so neither comparison is of zeros alone
    assert np.max(out["gap_left"]) > 0.0 and np.max(out["gap_right"]) > 0.0


def test_a_tree_without_the_section_is_refused_in_one_line(tmp_path):
    with pytest.raises(SystemExit, match="SoilFootingSection2d.cpp is not a file"):
        ci.compile_section(tmp_path, tmp_path / "build")


def test_the_benchmark_runs_on_the_stand_in_and_its_beds_match_the_committed_table(stand_in,
                                                                                     tmp_path):
    """``opensees_contact_interface.py --quick`` on the stand-in's tree: exit 0, its table, and
    the ES-f-I and macro-element errors at its point equal to the committed table's (reference:
    the committed run, made with OpenSees's own section; the beds do not depend on it)."""
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "benchmarks")}
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" /
                                               "opensees_contact_interface.py"),
                           "--opensees", str(stand_in), "--quick", "--out", str(out)],
                          capture_output=True, text=True, timeout=600, cwd=tmp_path, env=env)
    assert done.returncode == 0, done.stderr[-2000:]
    quick = bench_output.markdown_tables((out / "OPENSEES_CONTACT_INTERFACE.md").read_text())
    kept = bench_output.committed_tables("OPENSEES_CONTACT_INTERFACE.md")
    key = "Per point"
    row = quick[key][0]
    committed = next(r for r in kept[key] if all(r[c] == row[c] for c in
                                                 ("soil", "FS_v", "a/a_up", "motion")))
    for model in ("ES-f-I", "macro"):
        assert row[model] == committed[model]
    assert all("did not converge" not in row[m] for m in ("CIM, Kv = K_v", "CIM, Kv = 12 K_r/L²"))
