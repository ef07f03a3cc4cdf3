"""The continuum's start-up from disk: the set-up cache (upliftlab.continuum.setup_cache) and
the explicit time loop in numba's cache.

References: the set-up built afresh in the same process (the cache must give it back bit for
bit: ``np.array_equal``, no tolerance), a run without the cache (the same histories, bit for
bit), numba's own cache counters and index files (a loop loaded from the cache is not
compiled: ``cache_hits`` 1, ``cache_misses`` 0), and a fresh interpreter's ``sys.modules`` at
the first step of a warm run (what it has not imported it has not paid for).
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from upliftlab.continuum import build_model, setup_cache
from upliftlab.continuum.dynamics import explicit_step, ground
from upliftlab.continuum.dynamics.options import DynamicOptions
from upliftlab.continuum.model import evaluated
from upliftlab.scenes import load_scene


@pytest.fixture
def cache_home(tmp_path, monkeypatch):
    """A private ``$XDG_CACHE_HOME``: the set-up cache starts empty."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    return tmp_path / "cache" / "upliftlab" / "setup"


def _clay(*overrides):
    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                        *overrides])
    return scene, build_model(scene)


def _free(model):
    fixed = ground.dynamic_fixed(model, "rigid", "rollers")
    return np.setdiff1d(np.arange(model.disc.ndofs), fixed)


def _same_state(a, b) -> None:
    assert a.eigenstrain is not None and b.eigenstrain is not None
    for name in ("u", "q", "force", "status", "stress", "reaction", "eigenstrain"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
        assert getattr(a, name).dtype == getattr(b, name).dtype, name
    for name in ("plastic_strain", "equivalent_plastic_strain", "region"):
        assert np.array_equal(getattr(a.material, name), getattr(b.material, name)), name
    assert (a.iterations, a.cuts) == (b.iterations, b.cuts)


def test_the_cached_setup_equals_a_fresh_one(cache_home):
    scene, model = _clay()
    options = DynamicOptions()
    fresh = ground._gravity_state(model, scene.structure.vertical_weight, options, True)
    first = ground.gravity_state(model, scene, options, True)  # built and written
    assert len(list((cache_home / "gravity").glob("*.npz"))) == 1
    scene, model = _clay()  # another model of the same inputs
    again = ground.gravity_state(model, scene, options, True)  # read
    _same_state(first, fresh)
    _same_state(again, fresh)
    assert np.array_equal(again.tangent, evaluated(fresh.tangent))

    mass, free = explicit_step.lumped_mass(model), _free(model)
    reference = explicit_step.critical_step(model, mass, free)
    assert explicit_step.stable_limit(model, mass, free) == reference  # built and written
    assert explicit_step.stable_limit(model, mass, free) == reference  # read
    assert len(list((cache_home / "stable_step").glob("*.npz"))) == 1


def test_the_key_holds_exactly_the_inputs(cache_home):
    scene, model = _clay()
    base = setup_cache.model_inputs(model)
    # the route, the motion and the side boundary of a dynamic run do not make the model
    _, other = _clay("continuum.dynamics=implicit", "continuum.boundary=lysmer",
                     "motion.amplitude=0.1")
    assert setup_cache.model_inputs(other) == base
    # the soil and the mesh do
    _, softer = _clay("soil.youngs_modulus=40000")
    assert setup_cache.model_inputs(softer) != base
    _, graded = _clay("continuum.grading=2")
    assert setup_cache.model_inputs(graded)["mesh_digest"] != base["mesh_digest"]
    sources = ("upliftlab.continuum/model.py",)
    assert setup_cache.entry_key("gravity", base, sources) != setup_cache.entry_key(
        "gravity", {**base, "weight": 1.0}, sources)
    assert setup_cache.entry_key("gravity", base, sources) != setup_cache.entry_key(
        "gravity", base, ("upliftlab.continuum/assembly.py",))


@pytest.mark.parametrize("harm", ["truncated", "altered", "not a zip"])
def test_a_corrupt_entry_is_built_again_never_trusted(cache_home, harm):
    arrays = {"a": np.arange(5.0), "b": np.array(3)}
    built = []

    def build():
        built.append(1)
        return {k: v.copy() for k, v in arrays.items()}

    setup_cache.cached("probe", {"x": 1}, ("upliftlab.continuum/model.py",), build)
    (entry,) = (cache_home / "probe").glob("*.npz")
    data = entry.read_bytes()
    if harm == "truncated":
        entry.write_bytes(data[:len(data) // 2])
    elif harm == "altered":  # one byte of a's values: the zip's CRC or the digest catch it
        start = data.index(np.arange(5.0).tobytes())
        entry.write_bytes(data[:start + 3] + bytes([data[start + 3] ^ 0xFF]) + data[start + 4:])
    else:
        entry.write_bytes(b"garbage")
    out, hit = setup_cache.cached("probe", {"x": 1}, ("upliftlab.continuum/model.py",), build)
    assert not hit and len(built) == 2
    assert all(np.array_equal(out[k], arrays[k]) for k in arrays)
    out, hit = setup_cache.cached("probe", {"x": 1}, ("upliftlab.continuum/model.py",), build)
    assert hit and len(built) == 2  # the entry was written again, whole
    assert all(np.array_equal(out[k], arrays[k]) for k in arrays)


def test_an_entry_of_another_key_is_not_read(cache_home):
    key = setup_cache.entry_key("probe", {"x": 1}, ())
    other = setup_cache.entry_key("probe", {"x": 2}, ())
    assert setup_cache.write("probe", key, {"a": np.ones(2)})
    (cache_home / "probe" / f"{key}.npz").rename(cache_home / "probe" / f"{other}.npz")
    assert setup_cache.read("probe", other) is None


def test_a_run_with_the_cache_gives_the_numbers_of_a_run_without_it(cache_home):
    from upliftlab.continuum.dynamics.run import run_dynamic

    def run():
        scene, model = _clay("analysis.duration=0.05")
        return run_dynamic(model, scene, scene.build_motion(), DynamicOptions(snapshots=1))

    cold = run()
    # the gravity state, the stable step and the mesh's grid lines
    assert len(list(cache_home.rglob("*.npz"))) == 3
    warm = run()
    for name in ("time", "footing", "gap", "energy"):
        assert np.array_equal(np.asarray(getattr(cold, name)), np.asarray(getattr(warm, name)))
    assert cold.metadata["dt"] == warm.metadata["dt"]


_LOOP_PROBE = """
from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics import explicit_loop
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.scenes import load_scene
scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                    "analysis.duration=0.004"])
run_dynamic(build_model(scene), scene, scene.build_motion(), DynamicOptions(threads=1))
stats = explicit_loop.run_steps(False).stats
print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))
"""


def test_the_explicit_loop_is_read_from_numbas_cache_in_a_fresh_process(tmp_path):
    # Reference: numba's own counters and index file. The first process compiles the loop and
    # writes it to an empty cache; a second process loads it and compiles nothing.
    from upliftlab import log
    from upliftlab.continuum.dynamics.explicit_loop import run_steps

    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR",
                                                            "NUMBA_DISABLE_JIT")}
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "numba")
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    runs = [subprocess.run([sys.executable, "-c", _LOOP_PROBE], env=env, capture_output=True,
                           text=True, check=True, timeout=1200).stdout.split()
            for _ in range(2)]
    assert runs == [["0", "1"], ["1", "0"]]
    assert log.kernels_cached(tmp_path / "numba", run_steps(False))


@pytest.mark.parametrize("overrides", [(), ("continuum.grading=3",),
                                       ("soil.layer_depth=7", "continuum.elements_across=6")])
def test_the_cached_grid_lines_are_the_computed_ones(cache_home, overrides):
    # Reference: upliftlab.meshes.soil.grid_lines in this process, without the cache: the
    # entry written by the first call and read by the second give its arrays bit for bit
    from upliftlab.meshes.soil import grid_lines
    from upliftlab.scenes import ContinuumOptions

    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                        *overrides])
    args = (scene.foundation.width, scene.continuum or ContinuumOptions(),
            scene.soil.layer_depth)
    x, y = grid_lines(*args)
    built = setup_cache.grid_lines(*args)
    assert len(list((cache_home / "grid_lines").glob("*.npz"))) == 1
    read = setup_cache.grid_lines(*args)
    for lines in (built, read):
        assert np.array_equal(lines[0], x) and np.array_equal(lines[1], y)
        assert lines[0].dtype == x.dtype and lines[1].dtype == y.dtype
    mesh = build_model(scene).mesh  # the model's mesh stands on the same lines
    assert np.array_equal(np.unique(mesh.p[0]), x) and np.array_equal(np.unique(mesh.p[1]), y)


#: A fresh ``upliftlab continuum`` process that prints, at its first progress row (written
#: after the first time step), which of the libraries below it has imported by then, and at
#: its end (its result.nc written) whether it has imported xarray, dask or pandas at all.
_FIRST_STEP_PROBE = """
import re, sys
from upliftlab import cli

LATER = ("scipy.optimize", "meshio", "xarray", "dask", "matplotlib", "PIL", "pyvista",
         "h5netcdf", "h5py")
FIRST = re.compile(r" t = [0-9.]+ of ")


class Tap:
    seen = None

    def __init__(self, stream):
        self.stream = stream

    def write(self, text):
        if Tap.seen is None and FIRST.search(text):
            Tap.seen = sorted(m for m in LATER if m in sys.modules)
        return self.stream.write(text)

    def flush(self):
        self.stream.flush()


sys.stderr = Tap(sys.stderr)
code = cli.main(sys.argv[1:])
print(code, Tap.seen, sorted(m for m in ("xarray", "dask", "pandas") if m in sys.modules))
"""


def test_a_warm_process_takes_its_first_step_without_the_libraries_of_its_output(tmp_path):
    # Reason: a fresh process pays the import of every library it loads before its first step
    # (issue 35: the first step within 2 s of the process start). The mesh's grid lines need
    # scipy.optimize (brentq, 0.13-0.19 s of CPU to import on the shared 2-core machine) only
    # when they are not in the set-up cache; meshio (0.04 s) only for mesh files; xarray,
    # h5netcdf/h5py, dask (which xarray's array checks import) and the pictures' libraries only
    # for the output, after the last step; and xarray, dask and pandas not at all: the result
    # file is written from a LabelledData (upliftlab.netcdf_file), and importing xarray, which
    # imports dask and dask.distributed when they are installed, cost about 1 s. Reference: the
    # fresh interpreter's sys.modules at the first progress row, and at the end, of the second
    # of two runs with one cache folder.
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_DISABLE_JIT"}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")  # numba's cache: NUMBA_CACHE_DIR, as set
    command = [sys.executable, "-c", _FIRST_STEP_PROBE, "continuum", "strip_footing_clay",
               "--analysis", "dynamic", "-v", "--no-render", "--force", "--out",
               str(tmp_path / "run"), "--set", "continuum.elements_across=4", "--set",
               "analysis.duration=0.004"]
    runs = [subprocess.run(command, env=env, capture_output=True, text=True, timeout=1200,
                           check=False)
            for _ in range(2)]
    assert all(run.returncode == 0 for run in runs), runs[-1].stderr
    assert runs[1].stdout.split("\n")[-2] == "0 [] []", runs[1].stdout
