"""What the Winkler map's stored records depend on (comparisons/framework/sources.py): each of
its point functions declares the sources its records' digest covers, derived from its module's
imports, so that a kept store stays current when only the map's summary, figures or analysis
change, and goes stale when a module that computes its records changes.

Reference: the code digest (:func:`upliftlab.provenance.code_digest`) of copies of the
package's sources, one copy edited at a time (a comment appended): an edit changes the digest
exactly when the edited file is among the declared sources.
"""

from __future__ import annotations

import shutil

import pytest

from upliftlab import provenance as P
from upliftlab.comparisons.beds.continuum_points import evaluate_continuum
from upliftlab.comparisons.framework.sources import import_closure, source_name
from upliftlab.comparisons.framework.store import DEFAULT_SOURCES
from upliftlab.comparisons.studies.winkler_map import (evaluate_dynamic, evaluate_energy,
                                                       evaluate_impedance, evaluate_static)

MAP = "upliftlab.comparisons/studies/winkler_map/"
FUNCTIONS = (evaluate_dynamic, evaluate_energy, evaluate_impedance, evaluate_static,
             evaluate_continuum)
#: The map's modules that read records and never make one.
READERS = ("summary.py", "sections.py", "figures.py", "analysis.py", "workflow.py",
           "dataset.py", "statics_dataset.py", "parts.py", "goal.py", "maps.py")


@pytest.fixture
def copies(tmp_path, monkeypatch):
    """The package's sources copied into ``tmp_path``, the digest reading the copies."""
    files = {}
    for name, path in P.package_files().items():
        target = tmp_path / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(path, target)
        files[name] = target
    monkeypatch.setattr(P, "package_files", lambda: files)
    P._digest.cache_clear()
    yield files
    P._digest.cache_clear()


def _digests() -> list[str]:
    P._digest.cache_clear()
    return [P.code_digest(f.point.depends_on()) for f in FUNCTIONS]


def _edited(files, name: str) -> list[bool]:
    """Which functions' digests an appended comment in source ``name`` changes."""
    before = _digests()
    with open(files[name], "a") as fh:
        fh.write("\n# an edit\n")
    return [a != b for a, b in zip(before, _digests())]


def test_the_map_point_functions_declare_their_own_sources():
    for f in FUNCTIONS:
        sources = f.point.depends_on()
        assert sources != DEFAULT_SOURCES and "upliftlab.comparisons/" not in sources
        assert set(P.MODEL_SOURCES) <= set(sources)
        assert "upliftlab.comparisons/framework/" in sources
    closure = import_closure("upliftlab.comparisons.studies.winkler_map.energy_points",
                             "upliftlab.comparisons.studies.winkler_map")
    assert "upliftlab.comparisons.studies.winkler_map.points" in closure  # imported by it
    assert source_name("upliftlab.comparisons.studies.winkler_map.points") == \
        MAP + "points.py"


@pytest.mark.parametrize("reader", READERS)
def test_editing_a_module_that_reads_the_records_keeps_the_store_current(copies, reader):
    assert _edited(copies, MAP + reader) == [False] * len(FUNCTIONS)


@pytest.mark.parametrize("module, changed", [
    # evaluate_dynamic, evaluate_energy, evaluate_impedance, evaluate_static, evaluate_continuum
    ("points.py", [True, True, False, False, False]),  # the energy run reuses the dynamic's
    ("statics.py", [False, False, True, True, False]),  # the impedance builds its scene there
    ("energy_points.py", [False, True, False, False, False]),
    ("impedance_points.py", [False, False, True, False, False]),
])
def test_editing_a_point_module_makes_its_records_stale(copies, module, changed):
    assert _edited(copies, MAP + module) == changed


@pytest.mark.parametrize("source", ["upliftlab.comparisons/beds/continuum_points.py",
                                    "upliftlab.comparisons/framework/measures.py",
                                    "upliftlab.continuum/model.py"])
def test_editing_a_shared_layer_or_a_model_makes_every_record_stale(copies, source):
    if source not in copies:
        pytest.fail(f"{source} is not a source of the package: update the test")
    assert _edited(copies, source) == [True] * len(FUNCTIONS)


@pytest.mark.parametrize("source, stale", [
    ("upliftlab.reduced/laws/macro/plastic.py", True),  # the law it fits
    ("upliftlab.comparisons/beds/macro.py", True),  # the fit
    (MAP + "macro_points.py", True),  # its point
    ("upliftlab.continuum/model.py", False),  # the pushovers enter as numbers
    ("upliftlab.comparisons/beds/macro_bed.py", False),  # the bed built on it, live
    (MAP + "points.py", False),
])
def test_the_macro_fits_records_depend_on_the_fit_and_the_law_alone(copies, source, stale):
    """The macro-element's fit (a stored point of the map that takes minutes) goes stale when
    the law or the fit changes, and not when the continuum or the map's dynamic runs do."""
    from upliftlab.comparisons.studies.winkler_map.macro_points import evaluate_macro_fit

    def digest():
        P._digest.cache_clear()
        return P.code_digest(evaluate_macro_fit.point.depends_on())

    before = digest()
    with open(copies[source], "a") as fh:
        fh.write("\n# an edit\n")
    assert (digest() != before) == stale
