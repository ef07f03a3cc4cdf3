"""upliftlab: a verification suite for structures that rock and uplift on flexible foundations.

Core (this package): units, motions, scenes, results, checks and the command line.
Models: :mod:`upliftlab.reduced` (Ewing's compatibility-matrix model) and
:mod:`upliftlab.continuum` (plane-strain soil in scikit-fem). Studies: :mod:`upliftlab.comparisons`.

The names below are imported on first use, so that ``import upliftlab.cli`` loads no numpy
before the command line has set its thread counts (:mod:`upliftlab.cli`).
"""

__version__ = "0.1.0"

_LAZY = {"InputError": "checks", "Motion": "motions", "load_motion": "motions",
         "Scene": "scenes", "load_scene": "scenes"}

__all__ = ["__version__", "InputError", "Motion", "load_motion", "Scene", "load_scene"]


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
