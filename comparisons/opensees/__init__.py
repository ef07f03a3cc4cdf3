"""upliftlab.comparisons.opensees: the scene as a standalone OpenSeesPy script, and both models
side by side.

* :mod:`.spec` — the reduced model's numbers for OpenSees, and what OpenSees cannot represent;
* :mod:`.qz` — a q–z bed as QzSimple2 springs: the mapping, both backbones, where they differ;
* :mod:`.model_script` — the standalone script itself, a real module written unchanged as
  ``model.py``: readable and runnable without upliftlab, a BNWF model (zeroLength springs
  under a rigid footing, the scene's superstructure, gravity then the motion, Newmark with
  Newton);
* :mod:`.script` — writes it beside the scene's numbers (``model.json``) and its motion
  (``motion.txt``);
* :mod:`.runner` — runs the script in a subprocess with a timeout and reads its output;
* :mod:`.compare` — peaks, histories and a note per difference (``upliftlab opensees --run``);
  its plot draws upliftlab − OpenSees, the two histories beside it.
"""

from .compare import SUMMARY_KEYS, Comparison, compare, comparison_table, write_comparison
from .runner import (OPENSEES_EXTRA, OpenSeesError, OpenSeesRun, opensees_available,
                     require_opensees, run_script)
from .script import ScriptFiles, modelling_notes, write_script
from .spec import DASHPOT_MODELS, OpenSeesSpec, check_representable, opensees_spec

__all__ = ["SUMMARY_KEYS", "Comparison", "compare", "comparison_table", "write_comparison",
           "OPENSEES_EXTRA", "OpenSeesError", "OpenSeesRun", "opensees_available",
           "require_opensees", "run_script", "ScriptFiles", "modelling_notes", "write_script",
           "DASHPOT_MODELS", "OpenSeesSpec", "check_representable", "opensees_spec"]
