"""The founding study's conclusions, each decided from runs (comparisons/paper.py).

References: the paper's Conclusions and Results sections
(``../shared/reference/ewing-foundation-model-uplift.md``); the closed-form period of a sine for
the zero-crossing measure; :func:`upliftlab.reduced.paper.claims` (the reduced model's claim
checks, computed independently in tests/test_reduced_paper.py) for the verdicts.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from pathlib import Path

from upliftlab.comparisons.studies import paper
from upliftlab.comparisons.studies.paper import (Conclusion, Evidence, apparent_period,
                                                 conclusions_dataset, conclusions_of)
from upliftlab.study_files import open_study
from upliftlab.reduced.paper import claims


@pytest.fixture(scope="module")
def run(elcentro, tmp_path_factory):
    out = tmp_path_factory.mktemp("paper")
    return paper.run(fast=True, out=out / "paper", motion=elcentro.source)


@pytest.fixture(scope="module")
def study(run):
    """The conclusions as records, read back from the study's dataset."""
    return conclusions_of(run.data)


def test_apparent_period_of_a_sine_is_its_period():
    """Closed form: sin(2πt/T) crosses zero upwards every T."""
    t = np.linspace(0.0, 10.0, 20001)
    for period in (0.15, 0.59, 1.7):
        assert apparent_period(t, np.sin(2 * np.pi * t / period + 0.3)) == pytest.approx(
            period, rel=1e-6)
    assert math.isnan(apparent_period(t, np.ones_like(t)))


def test_verdict_follows_the_evidence():
    yes = Evidence("a", "", {}, "-", True)
    no = Evidence("b", "", {}, "-", False)
    assert Conclusion(1, "s", (yes, yes)).verdict == "holds"
    assert Conclusion(1, "s", (yes, no)).verdict == "holds in part"
    assert Conclusion(1, "s", (no,)).verdict == "does not hold"
    assert Conclusion(1, "s", ()).verdict == "not tested"


def test_two_spring_conclusion_reads_the_written_tree():
    """Conclusion 5 reads the two-spring study's folder as open_study gives it: the summary's
    numbers at the root, the threshold on the statics node. Made-up numbers: Case C shares
    tie at 0.25 between equivalent and calibrated (the equivalent pair is named, as the
    two-spring study's own statement breaks ties), 12 points; holds."""
    import xarray as xr

    from upliftlab.comparisons.studies.paper import conclusion_two_springs

    tree = xr.DataTree.from_dict({"statics": xr.Dataset(attrs={"threshold": 0.2})})
    tree.attrs = {"ewing": {"holds": True, "text": "t", "uplifting_points": {"C": 12},
                            "share": {"C": {"edges": {"all": 0.0}, "equivalent": {"all": 0.25},
                                            "calibrated": {"all": 0.25}}}}}
    c = conclusion_two_springs(tree)
    (e,) = c.evidence
    assert c.verdict == "holds" and e.values == {"share_within": 0.25, "points": 12}
    assert "(equivalent) within 20 %" in e.says and "at 25 %" in e.says
    assert conclusion_two_springs(None).verdict == "not tested"


def test_every_conclusion_is_decided_from_runs(study):
    """With the record, every statement has evidence; none is left untested."""
    assert [c.number for c in study] == list(range(1, 9))
    assert all(c.evidence for c in study)
    assert all(c.why for c in study if c.verdict != "holds")


def test_verdicts_agree_with_the_reduced_claim_checks(study, elcentro):
    """Conclusions 1, 4 and 6 say what reduced.paper.claims says on the same scenes."""
    from upliftlab.reduced.run import run
    from upliftlab.scenes import load_scene

    record = elcentro
    runs = {f"short_period_elcentro-{c}": run(load_scene("short_period_elcentro", case=c),
                                              motion=record, histories=False)
            for c in ("A", "B", "C", "fixed")}
    reference = {c["statement"]: c for c in claims(runs)}
    by_number = {c.number: c for c in study}
    short = lambda c: next(e for e in c.evidence if "short-period" in e.source  # noqa: E731
                           and "free" not in e.source)
    peak = next(v for k, v in reference.items() if "gives a larger peak" in k)
    assert short(by_number[1]).supports == peak["holds"]
    assert short(by_number[1]).values["A"] == pytest.approx(peak["values"]["A"], rel=1e-9)
    settle = next(v for k, v in reference.items() if "impact damping" in k)
    assert short(by_number[4]).supports == settle["holds"]
    assert short(by_number[4]).values["C"] == pytest.approx(settle["values"]["C"], rel=1e-9)
    fixed = next(v for k, v in reference.items() if "uplift reduces" in k)
    assert short(by_number[6]).values["fixed"] == pytest.approx(fixed["values"]["fixed"],
                                                                rel=1e-9)


def test_fixed_base_period_is_the_nominal_period(study):
    """Conclusion 8's fixed-base measure recovers the superstructure's fixed-base period
    2π√(m/k) (0.15 s and 0.59 s in the paper) within 15 % — the forced response of a 5 %-damped
    oscillator crosses zero near its own period — and the uplifting period is longer."""
    c8 = next(c for c in study if c.number == 8)
    for e, nominal in zip(c8.evidence, (0.15, 0.59)):
        assert e.values["fixed"] == pytest.approx(nominal, rel=0.15)
        assert e.values["uplift (C)"] > e.values["fixed"]


def test_summary_files_carry_the_verdicts(run, study):
    numbers = json.loads((run.study.directory / "summary.json").read_text())
    assert [c["verdict"] for c in numbers["conclusions"]] == [c.verdict for c in study]
    text = (run.study.directory / "summary.md").read_text()
    assert all(f"## {c.number}." in text for c in study)


def test_the_dataset_selects_by_label_and_reads_back_from_disk(run, study):
    """The written ``paper.nc`` opened again (open_study) holds the same conclusions, values
    bit for bit, and the summary written from it is the one on disk (issue 34 §4: one
    compute → Dataset, one summarise(Dataset) → Markdown)."""
    ds = run.data
    assert list(ds.conclusion.values) == list(range(1, 9))
    assert ds.verdict.sel(conclusion=8).item() == study[7].verdict
    first = ds.value_number.where(ds.value_evidence == 0, drop=True).values
    assert list(first) == list(study[0].evidence[0].values.values())
    tree = open_study(run.study.directory)
    again = tree["paper"].to_dataset()
    assert json.dumps(paper.key_numbers(again)) == json.dumps(paper.key_numbers(ds))
    assert paper.summarise(tree["paper"].to_dataset()) == (
        run.study.directory / "summary.md").read_text()


def test_dataset_round_trip_keeps_every_value():
    """Made-up conclusions: one without evidence, one with two pieces (values in order, a
    NaN kept), read back equal; the verdicts as the records decide them."""
    yes = Evidence("reduced A", "larger", {"A": 1.5, "B": float("nan")}, "in", True)
    no = Evidence("reduced C", "smaller", {"C": -2.0}, "m", False)
    made = (Conclusion(1, "s1", (yes, no), why="w"), Conclusion(2, "s2", (), note="n"))
    ds = conclusions_dataset(made, None)
    back = conclusions_of(ds)
    assert [c.verdict for c in back] == ["holds in part", "not tested"]
    assert back[0].evidence[1] == no and back[1] == made[1]
    assert list(back[0].evidence[0].values) == ["A", "B"]
    assert math.isnan(back[0].evidence[0].values["B"]) and "record" not in ds.attrs


def test_without_the_record_el_centro_conclusions_say_what_to_supply(run, tmp_path,
                                                                     monkeypatch):
    """No record on UPLIFTLAB_MOTIONS: free-vibration conclusions are still decided; El Centro
    ones are not tested and name the file and the variable. Written beside the module's run,
    so that the two-spring study it reads comes from that run's store."""
    monkeypatch.setenv("UPLIFTLAB_MOTIONS", str(tmp_path))
    result = paper.run(fast=True, out=Path(run.study.directory).parent / "no-record")
    by_number = {c.number: c for c in conclusions_of(result.data)}
    assert by_number[3].evidence and by_number[1].evidence  # free vibration
    assert by_number[6].verdict == "not tested"
    assert "UPLIFTLAB_MOTIONS" in by_number[6].note and "elcentro_1940_ns" in by_number[6].note
