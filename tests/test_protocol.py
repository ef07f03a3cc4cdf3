"""The study protocol (upliftlab.comparisons.framework.protocol) and the registry the report walks.

References: the names under which earlier versions stored results (a study's name is its
module's name and its output folder ``results/<name>[-fast]``; a sweep's point function is keyed
by the ``module:qualname`` it had when it was written, before the studies became packages), and
the command line's contract (exit code 2 and one line for bad input, nothing written).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from upliftlab.checks import InputError
from upliftlab.comparisons.framework import protocol
from upliftlab.comparisons.studies.registry import STUDIES, definition
from upliftlab.comparisons.framework.store import function_name

#: Point functions and the key names their stores were written under (before the move).
#: (Winkler-against-continuum's continuum point function is the beds' now: both Winkler
#: studies run it.)
KEY_NAMES = {
    "studies.two_spring_equivalence": (
        "evaluate_point", "upliftlab.comparisons.two_spring_equivalence:evaluate_point"),
    "studies.speed_vs_error": ("evaluate_point",
                               "upliftlab.comparisons.speed_vs_error:evaluate_point"),
    "beds.continuum_points": ("evaluate_continuum",
                              "upliftlab.comparisons.winkler_vs_continuum:evaluate_continuum"),
    "studies.winkler_map": ("evaluate_dynamic",
                            "upliftlab.comparisons.winkler_map:evaluate_dynamic"),
}


def test_every_registered_study_keeps_its_name():
    # Eight studies (winkler_map joined in issue 13), in the report's order; each is named
    # after its module, so its output folder and its report key are those of earlier versions.
    assert len(STUDIES) == 8 and STUDIES[0] == "verification" and STUDIES[-1] == "uplift_zone"
    for module in STUDIES:
        study = definition(module)
        assert study.name == module
        assert protocol.default_out(study.name, True) == Path("results") / f"{module}-fast"
        assert callable(study.compute) and callable(study.write)


def test_point_functions_keep_their_store_key_names():
    # Moving a point function into a package must not change the keys of the stored points.
    import importlib

    for module, (function, key) in KEY_NAMES.items():
        fn = getattr(importlib.import_module(f"upliftlab.comparisons.{module}"), function)
        assert function_name(fn) == key
        assert fn.__module__ != key.split(":")[0]  # it did move: the declared name is what keys


def test_run_study_computes_then_writes_into_the_resolved_folder(tmp_path):
    # compute sees the resolved folder and a store under it; write's record becomes .study.
    from dataclasses import dataclass

    from upliftlab.comparisons.framework.study import StudyResult

    @dataclass(frozen=True)
    class Probe:
        study: object = None

    seen = {}

    def compute(scene, context):
        seen["compute"] = (scene, context.out, context.store.root)
        return Probe()

    def write(result, context):
        return StudyResult("probe", context.fast, context.out, (), "", {"n": 3}, {}, 0.0)

    study = protocol.Study("probe", "Probe", "", None, compute, write, scene="a_scene")
    result = protocol.run_study(study, None, protocol.Context(fast=True, out=tmp_path / "o"))
    assert seen["compute"] == ("a_scene", tmp_path / "o", tmp_path / "o" / "store")
    assert result.study.numbers == {"n": 3}
    with pytest.raises(InputError, match="fast"):
        protocol.run_study(study, None, protocol.Context(fast="yes"))


def _as_the_study(monkeypatch, study):
    """``upliftlab study fixed_vs_uplift`` runs ``study`` instead of the registered one."""
    from upliftlab.comparisons.studies import registry

    monkeypatch.setattr(registry, "definition", lambda name: study)


def test_a_study_command_refuses_bad_input_in_one_line(tmp_path, capsys, monkeypatch):
    # --workers 0: exit 2, one line on stderr naming the option, nothing computed or written.
    from upliftlab.cli import main
    from upliftlab.comparisons.studies.fixed_vs_uplift import DEFINITION

    def never(scene, context):
        raise AssertionError("computed despite bad input")

    _as_the_study(monkeypatch, replace(DEFINITION, compute=never))
    out = tmp_path / "out"
    assert main(["study", "fixed_vs_uplift", "--fast", "--workers", "0", "--out",
                 str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--workers" in err
    assert not out.exists()


@pytest.mark.parametrize("option, value, message", [
    ("--out", "m/empty.txt", "--out = 'm/empty.txt': is a file, not a folder"),
    ("--store", "m/empty.txt", "--store = 'm/empty.txt': is a file, not a folder"),
    ("--store", "m/empty.txt/s", "--store = 'm/empty.txt/s': lies under 'm/empty.txt', "
                                 "which is a file, not a folder"),
    ("--store", "/proc/1/x", "--store = '/proc/1/x': cannot write there (No such file or "
                             "directory)"),
], ids=["out is a file", "store is a file", "store under a file", "store in /proc"])
def test_a_study_command_refuses_an_unusable_out_or_store_before_work(option, value, message,
                                                                      tmp_path, capsys,
                                                                      monkeypatch):
    # Reviewer's cases: --out or --store an existing file was refused (exit 2) only after the
    # first point was computed, naming m/empty.txt/store/7b/7b9d….json, not the option;
    # --store /proc/1/x was a FileNotFoundError traceback (exit 1). Now: one line naming the
    # option and the value, exit 2, nothing computed, nothing left behind.
    from upliftlab.cli import main
    from upliftlab.comparisons.studies.fixed_vs_uplift import DEFINITION

    def never(scene, context):
        raise AssertionError("computed despite an unusable folder")

    _as_the_study(monkeypatch, replace(DEFINITION, compute=never))
    monkeypatch.chdir(tmp_path)
    (tmp_path / "m").mkdir()
    (tmp_path / "m" / "empty.txt").write_text("")
    assert main(["study", "fixed_vs_uplift", "--fast", "--no-figures", "--workers", "1",
                 option, value]) == 2
    assert capsys.readouterr().err == f"upliftlab: error: {message}\n"
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*")) == [
        "m", "m/empty.txt"]


def test_run_study_refuses_a_file_as_its_out_or_store_before_compute(tmp_path):
    # The library's own check (the command's default store is OUT/store): named as the
    # Context's fields, before compute.
    def never(scene, context):
        raise AssertionError("computed despite an unusable folder")

    study = protocol.Study("probe", "Probe", "", None, never, never, scene="a_scene")
    (tmp_path / "o").mkdir()
    (tmp_path / "o" / "store").write_text("")
    (tmp_path / "f").write_text("")
    for context, message in [
            (protocol.Context(out=tmp_path / "f"), f"out = '{tmp_path / 'f'}': is a file"),
            (protocol.Context(out=tmp_path / "o"), f"store = '{tmp_path / 'o' / 'store'}': is "
                                                   "a file"),
            (protocol.Context(out=tmp_path / "p", store=tmp_path / "f" / "s"),
             f"store = '{tmp_path / 'f' / 's'}': lies under '{tmp_path / 'f'}'")]:
        with pytest.raises(InputError) as refused:
            protocol.run_study(study, None, context)
        assert str(refused.value).startswith(message)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f", "o"]


def test_a_study_command_reports_a_solver_failure_in_one_line(tmp_path, capsys, monkeypatch):
    # A solver that gave up (here a stand-in ConvergenceError with a two-line message): exit 3,
    # one line on stderr naming the study, the error's kind and its message; no traceback.
    from upliftlab.cli import main
    from upliftlab.comparisons.studies.fixed_vs_uplift import DEFINITION
    from upliftlab.continuum import ConvergenceError

    def gives_up(scene, context):
        raise ConvergenceError("load step 3: gave up\nafter bisecting it")

    _as_the_study(monkeypatch, replace(DEFINITION, compute=gives_up))
    assert main(["study", "fixed_vs_uplift", "--fast", "--out", str(tmp_path / "out")]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert f"{DEFINITION.name} failed (ConvergenceError): load step 3: gave up after " in err
