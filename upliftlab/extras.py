"""The optional dependencies: which extra installs what, and a refusal that names it.

The core install runs the reduced model and writes every result file; the rest comes with an
extra (``pip install 'upliftlab[continuum]'``). A command or a study that needs one calls
:func:`need_extra` before any work, so that a missing package ends with one line naming the
extra to install instead of an ImportError deep inside a run.
"""

from __future__ import annotations

import importlib.util

from .checks import InputError

__all__ = ["EXTRAS", "need_extra"]

#: The optional dependencies: import name -> the extra that installs it.
EXTRAS = {"matplotlib": "plot", "skfem": "continuum", "meshio": "continuum",
          "PIL": "render", "openseespy": "opensees",
          "distributed": "dask"}


def need_extra(command: str, *modules: str, why: str = "") -> None:
    """Refuse, in one line naming the extra to install, ``command`` whose optional
    dependencies ``modules`` are missing."""
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        extras = sorted({EXTRAS[m] for m in missing})
        spec = ",".join(extras)
        raise InputError(f"{command} needs {', '.join(missing)} (the optional extra "
                         f"{' and '.join(extras)}): pip install 'upliftlab[{spec}]'"
                         + (f"; {why}" if why else ""))
