"""The compiled kernels as a package: the one registry of integrators, and a numba cache that
follows an edit to any kernel source.

References: the integrator names the scene schema and the command line accept (the registry
must list exactly those); the closed-form amplification of classical RK4 on y' = λy; and, for
the cache, the changed law itself (a run after the edit must give the edited law's number).
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from upliftlab import cli, scenes
from upliftlab.reduced import kernels as kn
from upliftlab.reduced.integrators import METHODS


def test_the_registry_lists_the_integrators_the_scene_and_the_cli_accept():
    """The registry of integrators is the list the schema (``analysis.integrator``) and
    ``upliftlab run --integrator`` accept, in the same order; each names its compiled kernel."""
    assert tuple(METHODS) == scenes.INTEGRATORS
    run_parser = next(a for a in cli.parser()._subparsers._group_actions[0].choices["run"]
                      ._actions if a.dest == "integrator")
    assert tuple(run_parser.choices) == tuple(METHODS)
    kernels = {m.name: m.kernel for m in METHODS.values()}
    assert kernels == {"events": kn.integrate_events, "rk4": kn.integrate_rk4,
                       "abm4": kn.integrate_abm4, "newmark": kn.integrate_newmark,
                       "hht": kn.integrate_newmark}
    assert [m.name for m in METHODS.values() if m.locates_switches] == ["events"]


def test_registry_growth_is_rk4_amplification():
    """|R(z)| of classical RK4, R = 1 + z + z²/2 + z³/6 + z⁴/24 (closed form), at points on
    the imaginary axis and inside the left half-plane, to 1e-15; ABM4's growth at z = 0 is 1
    (consistency) and the implicit methods never grow."""
    z = np.array([0.5j, 2.0j, -1.0 + 1.0j, -2.7])
    exact = np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)
    np.testing.assert_allclose(METHODS["rk4"].growth(z), exact, rtol=1e-15)
    np.testing.assert_allclose(METHODS["events"].growth(z), exact, rtol=1e-15)
    assert METHODS["abm4"].growth(np.array([0.0]))[0] == pytest.approx(1.0, abs=1e-12)
    assert np.all(METHODS["hht"].growth(z) == 0.0)


#: One foundation spring through the implicit integrators' ``internal_force`` (a probe run
#: in a fresh process on a copy of the package).
_ONE_SPRING = """
import os, sys
import numpy as np
import upliftlab.reduced as reduced
from upliftlab.reduced import kernels as kn, springs as sp
table = sp.spring_table(1)
table["kind"], table["k"], table["f0"], table["nnz"] = sp.UPLIFT, 1000.0, 10.0, 2
table["i0"], table["a0"], table["i1"], table["a1"] = 0, -1.0, 0, 0.0
P = sp.derive_columns(table).view(np.recarray)
H = np.zeros(1, dtype=sp.HISTORY_DTYPE).view(np.recarray)
z = np.zeros(1)
fint = np.zeros(1)
kn.internal_force(np.array([-0.002]), np.zeros(1), P, np.zeros((1, 1)), H, np.zeros(1),
                  np.zeros(1), fint, np.zeros(1), np.zeros(1), np.zeros(1, np.int64),
                  np.zeros(1), np.zeros(1))
"""
_FORCE_OF_ONE_SPRING = _ONE_SPRING + (
    'print(repr(float(fint[0])), os.environ["NUMBA_CACHE_DIR"], reduced.__file__)\n')
#: numba's own counters of that function: cache hits, cache misses, and the package run.
_CACHE_COUNTS = _ONE_SPRING + (
    "stats = kn.internal_force.stats\n"
    "print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()), "
    "reduced.__file__)\n")


def _force_in(copy: Path, env: dict) -> tuple[float, str, str]:
    out = subprocess.run([sys.executable, "-c", _FORCE_OF_ONE_SPRING], cwd=copy, env=env,
                         capture_output=True, text=True, check=True, timeout=600).stdout.split()
    return float(out[0]), out[1], out[2]


def test_an_edited_law_is_compiled_afresh(tmp_path):
    """numba caches a compiled function keyed on its own file only, so the implicit
    integrators' ``internal_force`` (in ``kernels/implicit.py``) cached with a foundation law
    (in its module, ``laws/elastoplastic.py``) would outlive an edit to the law. The cache
    folder is keyed on a digest of the kernels' and the laws' sources
    (``upliftlab.KERNEL_SOURCES``), so the edit is seen. Two processes on a copy of the
    package: a foundation spring (k = 1000, F0 = 10, so δ0 = 0.01; e = −V) compressed by
    e = 0.002 puts on V the internal force −(k e) = −2 before the edit (the force increment
    over F0), and −(2 k (δ0 + e) − F0) = −14 after the law's spring force is doubled (closed
    forms, to 1e-12). A control process on the first process's cache folder, as numba alone
    would use it, still gives the stale −2."""
    copy = tmp_path / "checkout"
    _copy_package(copy)
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR",
                                                            "NUMBA_DISABLE_JIT")}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    before, folder_before, package = _force_in(copy, env)
    assert Path(package).resolve().is_relative_to(copy.resolve())  # the copy ran, not the repo
    assert before == pytest.approx(-1000.0 * 0.002, rel=1e-12)
    assert any(Path(folder_before).rglob("*.nbi"))  # the compiled kernels were cached

    laws = copy / "upliftlab" / "reduced" / "laws" / "elastoplastic.py"
    text = laws.read_text()
    old = "        fs = p.k * (p.d0 + e - ep)\n"
    assert text.count(old) == 1
    laws.write_text(text.replace(old, "        fs = 2.0 * p.k * (p.d0 + e - ep)\n"))
    after, folder_after, _ = _force_in(copy, env)
    assert folder_after != folder_before
    assert after == pytest.approx(-(2.0 * 1000.0 * (0.01 + 0.002) - 10.0), rel=1e-12)

    stale, _, _ = _force_in(copy, dict(env, NUMBA_CACHE_DIR=folder_before))
    assert stale == pytest.approx(before, rel=1e-12)


def _copy_package(copy: Path) -> None:
    """The package in the installed layout (the core with the reduced model nested in it)."""
    root = Path(__file__).resolve().parents[1]
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    shutil.copytree(root / "upliftlab", copy / "upliftlab", ignore=ignore)
    shutil.copytree(root / "reduced", copy / "upliftlab" / "reduced", ignore=ignore)


def test_the_same_kernels_installed_elsewhere_are_read_not_compiled(tmp_path):
    """Two copies of the package at two paths (the README's main job installs one in
    ``site-packages``, its tests run another from the checkout; a CI clone lands at a new
    path), one cache folder: the first process compiles ``internal_force`` (numba's own
    counters: a cache miss, no hit), the second, from the other copy, reads it (a hit, no
    miss). With numba's own locator, which names the folder by the source's absolute path, the
    second compiled it again."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR",
                                                            "NUMBA_DISABLE_JIT")}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    counts = []
    for name in ("first", "second"):
        _copy_package(tmp_path / name)
        out = subprocess.run([sys.executable, "-c", _CACHE_COUNTS], cwd=tmp_path / name,
                             env=env, capture_output=True, text=True, check=True,
                             timeout=600).stdout.split()
        assert Path(out[2]).resolve().is_relative_to((tmp_path / name).resolve())
        counts.append((int(out[0]), int(out[1])))
    assert counts[0][0] == 0 and counts[0][1] >= 1
    assert counts[1][0] >= 1 and counts[1][1] == 0


def test_the_registry_holds_every_integrator_the_scene_accepts():
    # Reference: the names a scene and the command line accept (upliftlab.scenes.motion); the
    # registry must describe each of them, in the same order, and nothing else.
    from upliftlab.reduced.integrators import METHODS
    from upliftlab.scenes.motion import INTEGRATORS

    assert tuple(METHODS) == INTEGRATORS
    assert {m.order for m in METHODS.values()} == {2, 4}
