"""Messages through logging (upliftlab.log): the command line's --quiet and --verbose, and the
first run's compilation notice.

References: the levels of Python's logging (WARNING for --quiet, INFO by default, DEBUG for
--verbose) and numba's cache layout (an index file ``<module>.<function>-<line>.py311.nbi`` per
cached function).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from upliftlab import cli, log


@pytest.mark.parametrize("flag, wrote, details", [("--quiet", False, False), (None, True, False),
                                                   ("--verbose", True, True)])
def test_quiet_and_verbose_choose_what_reaches_stderr(flag, wrote, details, tmp_path, capsys):
    argv = ["run", "wall_free", "--no-figure", "--out", str(tmp_path / "run")]
    assert cli.main(argv + ([flag] if flag else [])) == 0
    captured = capsys.readouterr()
    assert ("upliftlab run: wrote" in captured.err) is wrote
    assert ("events: dt = 0.01 s, 300 steps" in captured.err) is details
    assert "peak u = 0.1808 in" in captured.out  # the result itself is never silenced


def test_quiet_and_verbose_together_are_refused(capsys):
    assert cli.main(["run", "wall_free", "--quiet", "--verbose"]) == 2
    assert "not allowed with" in capsys.readouterr().err


def test_compilation_is_announced_once_and_only_without_a_cache(tmp_path, monkeypatch,
                                                                 capsys):
    from upliftlab.reduced.integrators import METHODS

    kernel = METHODS["events"].kernel
    log.configure(0)
    monkeypatch.delenv("NUMBA_DISABLE_JIT", raising=False)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(log, "_announced", set())
    log.announce_compilation("the kernels", kernel)
    log.announce_compilation("the kernels", kernel)  # once per process
    assert capsys.readouterr().err.count("compiling the kernels") == 1
    # another checkout's cache of the same kernel is not this source's cache
    other = tmp_path / "kernels_0000000000000000000000000000000000000000"
    other.mkdir()
    (other / "events.integrate_events-40.py311.nbi").write_bytes(b"")
    monkeypatch.setattr(log, "_announced", set())
    log.announce_compilation("the kernels", kernel)
    assert capsys.readouterr().err.count("compiling the kernels") == 1
    folder, _ = log.cache_index(kernel)
    (tmp_path / folder).mkdir()
    (tmp_path / folder / "events.integrate_events-40.py311.nbi").write_bytes(b"")
    monkeypatch.setattr(log, "_announced", set())
    log.announce_compilation("the kernels", kernel)  # cached: nothing to say
    assert "compiling" not in capsys.readouterr().err


def test_the_cache_index_is_where_numba_writes_it():
    # Reference: numba's own locator for the kernel (the dispatcher's cache path, chosen by
    # numba through NUMBA_CACHE_LOCATOR_CLASSES): upliftlab's names the folder by the kernel's
    # place in the package, whatever the path it is installed at, and the index is
    # <module>.<function>-<line>.nbi.
    from upliftlab.reduced.integrators import METHODS

    kernel = METHODS["hht"].kernel
    folder, pattern = log.cache_index(kernel)
    assert str(folder) == "upliftlab.reduced_kernels"
    assert Path(kernel._cache._cache_path).name == str(folder)
    assert pattern == "implicit.integrate_newmark-*.nbi"


def test_a_kernel_outside_the_package_keeps_numbas_own_cache_folder(tmp_path, monkeypatch):
    # Reference: numba's own name for a source folder, <folder name>_<sha1 of its absolute
    # path>: upliftlab's locator takes upliftlab's sources only. (Cached in this test's folder.)
    import hashlib
    import importlib.util

    from numba.core import config

    monkeypatch.setattr(config, "CACHE_DIR", str(tmp_path / "cache"))

    source = tmp_path / "elsewhere" / "outside.py"
    source.parent.mkdir()
    source.write_text("from numba import njit\n\n@njit(cache=True)\ndef twice(x):\n"
                      "    return 2 * x\n")
    spec = importlib.util.spec_from_file_location("outside", source)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.twice(2.0) == 4.0
    folder, pattern = log.cache_index(module.twice)
    assert str(folder) == f"elsewhere_{hashlib.sha1(str(source.parent).encode()).hexdigest()}"
    assert Path(module.twice._cache._cache_path).name == str(folder)


def test_provenance_names_the_code_the_libraries_and_the_motion(elcentro):
    # References: hashlib's SHA-256 of the record file itself, and the installed versions of
    # scipy and numba (importlib.metadata); the source digest changes with any source byte.
    import hashlib
    from importlib import metadata
    from pathlib import Path

    from upliftlab.reduced import run
    from upliftlab.provenance import code_digest
    from upliftlab.scenes import load_scene

    record = Path(elcentro.source)
    scene = load_scene("short_period_elcentro", case="A", overrides=["analysis.duration=0.5"])
    response = run(scene)
    assert response.info["motion_sha256"] == hashlib.sha256(record.read_bytes()).hexdigest()
    assert response.provenance["scipy"] == metadata.version("scipy")
    assert response.provenance["numba"] == metadata.version("numba")
    assert response.provenance["source_sha256"] == code_digest()
    assert len(code_digest()) == 64


def test_an_uncached_kernel_is_announced_as_compiled_in_every_process(monkeypatch, tmp_path,
                                                                      capsys):
    # Reference: numba's own cache object of a function jitted with cache=False (numba gives
    # it a NullCache): "once" would be untrue there.
    import numba

    @numba.njit(cache=False)
    def uncached(x):
        return x

    assert type(uncached._cache).__name__ == "NullCache"
    log.configure(0)
    monkeypatch.delenv("NUMBA_DISABLE_JIT", raising=False)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(log, "_announced", set())
    log.announce_compilation("the loop", uncached)
    err = capsys.readouterr().err
    assert "compiling the loop (in every new process" in err and "once" not in err


def test_the_explicit_loop_is_announced_as_compiled_once(monkeypatch, tmp_path, capsys):
    # Reference: numba's cache object of the continuum's explicit time loop, a disk cache
    # (cache=True; issue 35: it was compiled in every process); without its index in the
    # cache folder the notice says it is compiled once.
    from upliftlab.continuum.dynamics.explicit_loop import run_steps

    for parallel in (False, True):
        assert type(run_steps(parallel)._cache).__name__ != "NullCache"
    log.configure(0)
    monkeypatch.delenv("NUMBA_DISABLE_JIT", raising=False)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(log, "_announced", set())
    log.announce_compilation("the loop", run_steps(False), "about 20–60 s")
    err = capsys.readouterr().err
    assert "compiling the loop (about 20–60 s, once" in err
