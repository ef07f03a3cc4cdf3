"""The founding study's statements, asserted on its scenes (Ewing, Figs. 7–12).

Where our model agrees with the paper the test asserts the paper's statement. Where it does
not, the test pins what our model gives, with the numbers, so the disagreement stays visible
(it is reported in the summary and the issue note, and not tuned away).
"""

import pytest

from upliftlab.reduced import run
from upliftlab.reduced.paper import claims, decay_time
from upliftlab.scenes import load_scene


@pytest.fixture(scope="module")
def free():
    return {(b, c): run(load_scene(f"{b}_free", case=c), output_dt=0.01)
            for b in ("short_period", "long_period") for c in "ABC"}


@pytest.fixture(scope="module")
def elcentro_runs(elcentro):
    return {(b, c): run(load_scene(f"{b}_elcentro", case=c), motion=elcentro, output_dt=0.01)
            for b in ("short_period", "long_period") for c in ("A", "B", "C", "fixed")}


@pytest.mark.parametrize("building", ["short_period", "long_period"])
def test_case_A_decays_faster_than_case_B(free, building):
    """'Case A has a faster decay than Cases B ...': the free vibration's mechanical energy
    falls below 10 % sooner with 40 % elastic damping than with 10 % and plasticity."""
    assert decay_time(free[building, "A"]) < decay_time(free[building, "B"])


def test_short_period_case_A_gives_the_largest_deformation(free, elcentro_runs):
    """'... but yields larger maximum deformations in the superstructure' (short period,
    Figs. 7–8): peak u of Case A exceeds B and C in free vibration and under El Centro."""
    for runs in (free, elcentro_runs):
        u = {c: runs["short_period", c].peaks["u"] for c in "ABC"}
        assert u["A"] > max(u["B"], u["C"])


@pytest.mark.parametrize("building", ["short_period", "long_period"])
def test_impact_damping_reduces_plastic_settlement(elcentro_runs, building):
    """'The influence of impact damping is also significant in reducing the plastic deformation
    in the soil': mean plastic settlement under El Centro, C < B (measured 0.56 < 0.83 in and
    0.53 < 0.60 in)."""
    b = elcentro_runs[building, "B"].peaks["plastic_settlement_mean"]
    c = elcentro_runs[building, "C"].peaks["plastic_settlement_mean"]
    assert c < b


@pytest.mark.parametrize("building", ["short_period", "long_period"])
def test_uplift_reduces_deformation_against_fixed_base(elcentro_runs, building):
    """Figs. 11–12: 'significant reduction in superstructure deformation' when uplift is allowed
    (Case C) against the fixed base, for both buildings (measured 0.055 vs 0.164 in and
    0.87 vs 2.67 in)."""
    fixed = elcentro_runs[building, "fixed"].peaks["u"]
    uplift = elcentro_runs[building, "C"].peaks["u"]
    assert uplift < 0.5 * fixed


def test_where_our_model_disagrees_with_the_paper(free, elcentro_runs):
    """Two statements our model does not reproduce, pinned with their numbers:
    1. short period: impact damping makes Case C decay about as fast as A (2.68 vs 2.92 s), not
       slower as the paper states for 'Cases B and C';
    2. long period: Case A's peak u is larger than B's and C's (free 0.98 vs 0.87 in; El Centro
       1.22 vs 0.87 in), where the paper reports it lower.
    The summary's claim list marks both 'does not hold'."""
    a, c = decay_time(free["short_period", "A"]), decay_time(free["short_period", "C"])
    assert c == pytest.approx(a, rel=0.15)
    for runs in (free, elcentro_runs):
        u = {k: runs["long_period", k].peaks["u"] for k in "ABC"}
        assert u["A"] > 1.05 * max(u["B"], u["C"])
    responses = {f"{b}_free-{c}": r for (b, c), r in free.items()}
    responses.update({f"{b}_elcentro-{c}": r for (b, c), r in elcentro_runs.items()})
    verdicts = {x["statement"]: x["holds"] for x in claims(responses)}
    failing = [s for s, ok in verdicts.items() if not ok]
    assert any(s.startswith("short_period: Case A decays fastest") for s in failing)
    assert any(s.startswith("long_period, elcentro: Case A gives a smaller") for s in failing)


# The values the statements above order, pinned. The paper gives them only as curves (Figs. 7–12,
# no tables), so the reference is a converged run: the event stepper under error control at
# analysis.rtol = 1e-7, 10⁴ times tighter than the scenes' default; the default runs these tests
# make are within 3e-5 of it in every peak. Tolerances: 1e-4 relative for peaks and settlements
# (three times that distance); 0.01 s for a decay time, the spacing of the stored energy it is
# read from. inf: the energy never falls below 10 % within the run's 5 s.
CONVERGED_FREE = {  # (peak u (in), decay time (s)) in free vibration from Ẋ(0) = 20 in/s
    ("short_period", "A"): (0.141800, 2.93), ("short_period", "B"): (0.135999, float("inf")),
    ("short_period", "C"): (0.135999, 2.68), ("long_period", "A"): (0.976266, 3.60),
    ("long_period", "B"): (0.871549, 4.83), ("long_period", "C"): (0.871549, 4.17)}
CONVERGED_ELCENTRO = {  # (peak u (in), mean plastic settlement (in)) under El Centro 1940 N-S
    ("short_period", "A"): (0.101606, 0.0), ("short_period", "B"): (0.0590895, 0.827265),
    ("short_period", "C"): (0.0552728, 0.564488), ("short_period", "fixed"): (0.163847, None),
    ("long_period", "A"): (1.22310, 0.0), ("long_period", "B"): (0.873867, 0.604228),
    ("long_period", "C"): (0.869558, 0.525461), ("long_period", "fixed"): (2.66818, None)}


def test_measured_values_match_the_converged_runs(free, elcentro_runs):
    """Peak u, decay time and mean plastic settlement of every run above, against the
    converged runs (event stepper, analysis.rtol = 1e-7) to the tolerances stated above."""
    for key, (u, decay) in CONVERGED_FREE.items():
        assert free[key].peaks["u"] == pytest.approx(u, rel=1e-4), key
        assert decay_time(free[key]) == pytest.approx(decay, abs=0.01), key
    for key, (u, settlement) in CONVERGED_ELCENTRO.items():
        peaks = elcentro_runs[key].peaks
        assert peaks["u"] == pytest.approx(u, rel=1e-4), key
        if settlement is not None:
            assert peaks["plastic_settlement_mean"] == pytest.approx(settlement, rel=1e-4,
                                                                      abs=1e-9), key
