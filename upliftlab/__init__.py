"""upliftlab: a verification suite for structures that rock and uplift on flexible foundations.

Core (this package): units, motions, scenes, results, checks and the command line.
Models: :mod:`upliftlab.reduced` (Ewing's compatibility-matrix model) and
:mod:`upliftlab.continuum` (plane-strain soil in scikit-fem). Studies: :mod:`upliftlab.comparisons`.
"""

__version__ = "0.1.0"

from .checks import InputError  # noqa: E402
from .motions import Motion, load_motion  # noqa: E402
from .scenes import Scene, load_scene  # noqa: E402

__all__ = ["__version__", "InputError", "Motion", "load_motion", "Scene", "load_scene"]
