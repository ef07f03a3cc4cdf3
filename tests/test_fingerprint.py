"""The code fingerprint in store keys (``comparisons/fingerprint.py``, ``comparisons/store.py``).

References: a throw-away package written here (its import graph and its edits are known by
construction), and the repository's own import graph for the map's continuum point functions.
"""

from __future__ import annotations

import sys
import textwrap

import pytest

from upliftlab.comparisons import fingerprint as fp
from upliftlab.comparisons import store as st
from upliftlab.comparisons.store import Store, point_key
from upliftlab.comparisons.sweep import run_sweep

FILES = {
    "__init__.py": "",
    "a.py": """
        '''Module a.'''
        from typing import TYPE_CHECKING
        if TYPE_CHECKING:
            from .c import Unused
        def f(x):
            '''Uses b, imported inside the function.'''
            from .b import g
            return g(x)
        """,
    "b.py": """
        '''Module b.'''
        from . import d
        def g(x):
            return d.SCALE * x  # doubled
        """,
    "c.py": "class Unused: pass\n",
    "d.py": "SCALE = 2.0\n",
    "e.py": "from .a import f\n",
}


@pytest.fixture
def package(tmp_path, monkeypatch):
    """A package ``fp_pkg`` on sys.path; returns a function that rewrites one of its files."""
    root = tmp_path / "fp_pkg"
    root.mkdir()
    for name, text in FILES.items():
        (root / name).write_text(textwrap.dedent(text))
    monkeypatch.syspath_prepend(str(tmp_path))

    def write(name, text):
        (root / name).write_text(textwrap.dedent(text))
    yield write
    for name in [m for m in sys.modules if m == "fp_pkg" or m.startswith("fp_pkg.")]:
        del sys.modules[name]


def test_closure_follows_imports_inside_functions_and_skips_annotations(package):
    # a imports b inside f, b imports d as a submodule; c only under TYPE_CHECKING, e
    # imports a (nothing imports e)
    assert sorted(fp.import_closure("fp_pkg.a")) == ["fp_pkg.a", "fp_pkg.b", "fp_pkg.d"]


def test_digest_sees_statements_not_docstrings_or_comments(package):
    before = fp.closure_digest("fp_pkg.a")
    package("b.py", """
        '''Module b, its docstring reworded.'''
        from . import d
        def g(x):
            '''A new docstring.'''
            return d.SCALE * x  # a different comment
        """)
    assert fp.closure_digest("fp_pkg.a") == before
    package("d.py", "SCALE = 3.0\n")  # a constant two imports away
    assert fp.closure_digest("fp_pkg.a") != before
    package("d.py", "SCALE = 2.0\n")
    package("c.py", "class Unused:\n    x = 1\n")  # outside the closure
    package("e.py", "from .a import f\nY = 1\n")
    assert fp.closure_digest("fp_pkg.a") == before


def test_the_maps_continuum_runs_do_not_depend_on_the_reduced_model_or_the_grid():
    # The committed map store (benchmarks/winkler_map_store) stays valid while the beds and
    # the grid change; it must be invalidated by the continuum, the measures and the scenes.
    for module in ("upliftlab.comparisons.winkler_map.points",
                   "upliftlab.comparisons.winkler_map.statics",
                   "upliftlab.comparisons.winkler_map.impedance_points",
                   "upliftlab.comparisons.winkler_vs_continuum.points"):
        closure = fp.import_closure(module)
        assert not [m for m in closure if m.startswith("upliftlab.reduced")], module
        assert "upliftlab.comparisons.winkler_map.grid" not in closure, module
        assert "upliftlab.comparisons.winkler_map.beds" not in closure, module
        for needed in ("upliftlab.continuum.explicit", "upliftlab.continuum.materials",
                       "upliftlab.meshes.soil", "upliftlab.scenes",
                       "upliftlab.comparisons.measures"):
            assert needed in closure, (module, needed)


def _double(point):
    return {"y": 2.0 * point["x"]}


def test_a_package_function_keys_with_its_code(monkeypatch, tmp_path):
    from upliftlab.comparisons.winkler_map.points import evaluate_dynamic

    point = {"x": 1.0}
    with_code = point_key("s", evaluate_dynamic, point)
    assert with_code != point_key("s", "upliftlab.comparisons.winkler_map:evaluate_dynamic",
                                  point)  # a bare name keys by the version alone
    monkeypatch.setattr(st, "code_fingerprint", lambda module: "0" * 64)
    assert point_key("s", evaluate_dynamic, point) != with_code
    # a function outside the package: the version alone, as before
    assert point_key("s", _double, point) == point_key("s", st.function_name(_double), point)


def test_a_sweep_recomputes_what_other_code_stored(monkeypatch, tmp_path):
    # a package function (its module's code is fingerprinted): the first sweep stores its
    # records with their code; under other code the same points are run again
    calls = []

    def seen(point):
        calls.append(point["x"])
        return {"y": 3.0 * point["x"]}

    seen.__module__ = "upliftlab.comparisons.measures"  # keyed with that module's code
    seen.__qualname__ = "seen"
    store = Store(tmp_path / "store")
    points = [{"x": 1.0}, {"x": 2.0}]
    monkeypatch.setattr(st, "code_fingerprint", lambda module: "a" * 64)
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(1) as pool:
        first = run_sweep(seen, points, store, executor=pool, progress=False)
        again = run_sweep(seen, points, store, executor=pool, progress=False)
        assert calls == [1.0, 2.0] and first == again == [{"y": 3.0}, {"y": 6.0}]
        key = point_key("measures", seen, points[0])
        assert store.entry(key)["code"] == "a" * 64
        monkeypatch.setattr(st, "code_fingerprint", lambda module: "b" * 64)
        run_sweep(seen, points, store, executor=pool, progress=False)
    assert calls == [1.0, 2.0, 1.0, 2.0]
