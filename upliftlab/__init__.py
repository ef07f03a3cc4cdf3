"""upliftlab: a verification suite for structures that rock and uplift on flexible foundations.

Core (this package): units, motions, scenes, results, checks and the command line.
Models: :mod:`upliftlab.reduced` (Ewing's compatibility-matrix model) and
:mod:`upliftlab.continuum` (plane-strain soil in scikit-fem). Studies:
:mod:`upliftlab.comparisons`.

The names below are imported on first use, so that ``import upliftlab.cli`` loads no numpy
before the command line has set its thread counts (:mod:`upliftlab.cli`).
"""

from .version import __version__

#: SIGINT and SIGTERM (numbers) that came while the ``upliftlab`` command loaded, before
#: :func:`upliftlab.cli.main` set its own handlers (:func:`_hold_signals_while_loading`).
COMMAND_SIGNALS: list[int] = []


def _started_as_the_command() -> bool:
    """Whether this process is the ``upliftlab`` command: its script, or ``python -m
    upliftlab`` (read from the command line the interpreter was given, ``sys.orig_argv``, which
    a spawned worker does not share even where it takes its parent's ``sys.argv``)."""
    import os
    import sys

    given = getattr(sys, "orig_argv", [])
    if os.path.basename(sys.argv[0]) == "upliftlab" and sys.argv[0] in given[1:2]:
        return True
    return "-m" in given and given[given.index("-m") + 1:][:1] == ["upliftlab"]


def _hold_signals_while_loading() -> None:
    """In the ``upliftlab`` command only (not in a program that imports upliftlab), record
    SIGINT and SIGTERM from this first line of the package until the command's ``main`` takes
    them over (:meth:`upliftlab.cli.stop.StopFlag.adopt`) and ends with its one line: loading
    numpy and the code digest take a few tenths of a second, in which Python's own handling
    printed a traceback (SIGINT) or nothing at all (SIGTERM, exit 143). After ``main``, the
    same recorder holds any signal until the process has exited with the code ``main`` chose.
    A signal the process inherited as ignored stays ignored."""
    import signal

    if not _started_as_the_command():
        return
    for number in (signal.SIGINT, signal.SIGTERM):
        if signal.getsignal(number) is not signal.SIG_IGN:
            signal.signal(number, lambda signum, frame: COMMAND_SIGNALS.append(signum))


_hold_signals_while_loading()


#: The compiled kernels' sources (as :func:`upliftlab.provenance.package_files` names them), the
#: reduced laws' and the soil models' compiled forms among them: the numba cache folder is keyed
#: by their digest.
KERNEL_SOURCES = ("upliftlab.reduced/kernels/", "upliftlab.reduced/laws/",
                  "upliftlab.continuum/dynamics/kernels.py",
                  "upliftlab.continuum/dynamics/explicit_loop.py",
                  "upliftlab.continuum/contact/", "upliftlab.continuum/materials/")


#: numba's cache locators (``NUMBA_CACHE_LOCATOR_CLASSES``): upliftlab's
#: (:class:`upliftlab.kernel_cache.PackageLocator`: a kernel's folder named by its place in the
#: package) first, then numba's own in numba's order.
KERNEL_LOCATORS = ",".join(["upliftlab.kernel_cache.PackageLocator", "UserProvidedCacheLocator",
                            "InTreeCacheLocator", "UserWideCacheLocator",
                            "IPythonCacheLocator", "ZipCacheLocator"])


def _numba_cache_outside_the_package() -> None:
    """Compiled kernels are cached in ``$XDG_CACHE_HOME/upliftlab/numba/<digest>``
    (``~/.cache/...``; ``NUMBA_CACHE_DIR`` if set), not beside the installed sources: a cache
    written inside an installed ``site-packages/upliftlab`` survives ``pip uninstall`` and
    leaves a folder that shadows a later install as an empty namespace package (the README's
    test command after its first command failed so). ``<digest>`` is the code digest of the
    kernels' sources (:data:`KERNEL_SOURCES`, :func:`upliftlab.provenance.code_digest`): numba
    keys a cached function on its own file only (numba issue 1833), so an edit to a spring law
    must compile every kernel afresh instead of loading integrators cached with the old law,
    an edit to a continuum soil model's point return (each model's module in ``materials/``)
    the element loops that inline it, and an edit to the element loops or the contact steps
    the explicit time loop that holds them (``explicit_loop.py``).
    Left alone when the folder cannot be written. Each kernel's folder in it is named by its
    place in the package, not by the path it is installed at (:data:`KERNEL_LOCATORS`)."""
    import os
    import sys

    os.environ.setdefault("NUMBA_CACHE_LOCATOR_CLASSES", KERNEL_LOCATORS)
    if "numba" in sys.modules:  # imported before upliftlab: its config has been read
        sys.modules["numba"].config.CACHE_LOCATOR_CLASSES = \
            os.environ["NUMBA_CACHE_LOCATOR_CLASSES"]
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    from .provenance import code_digest

    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    folder = os.path.join(base, "upliftlab", "numba", code_digest(KERNEL_SOURCES)[:16])
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError:
        return
    if not os.access(folder, os.W_OK):
        return
    os.environ["NUMBA_CACHE_DIR"] = folder
    if "numba" in sys.modules:  # imported before upliftlab: its config has been read
        sys.modules["numba"].config.CACHE_DIR = folder


_numba_cache_outside_the_package()

_LAZY = {"InputError": "checks", "Motion": "motions", "load_motion": "motions",
         "Scene": "scenes", "load_scene": "scenes", "open_study": "study_files",
         "open_result": "result_files"}

__all__ = ["__version__", "InputError", "Motion", "load_motion", "Scene", "load_scene",
           "open_study", "open_result"]


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
