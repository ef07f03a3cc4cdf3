"""Every conclusion of Ewing's study, one by one, with the evidence from our models.

The founding study (R. D. Ewing, "Influence of foundation model on uplifting of structures",
1988) states these in its Conclusions, Results and Introduction. Each becomes a :class:`Conclusion`
whose verdict is computed from runs; the study's result is their :class:`xarray.Dataset`
(:mod:`.dataset`, written as ``paper.nc``):

1. Case A (elastic spring, 40 % viscous damping) overestimates the peak superstructure
   deformation (Conclusions) ...
2. ... except for the long-period building, where A's is lower (Results, Figs. 9-10).
3. Case A overestimates the rate of decay of the response (free vibration).
4. Impact damping (Case C) reduces the plastic deformation of the soil against Case B.
5. A Winkler bed is necessary and cannot be replaced by an equivalent two-spring system once the
   foundation is nonlinear (from :mod:`.two_spring_equivalence`).
6. Uplift reduces the superstructure deformation against a fixed base ...
7. ... and more so with the recommended model (Case C) than with Case A.
8. Uplift elongates the fundamental response period (Introduction; measured from the zero
   crossings of u).

Reduced-model evidence comes from :func:`upliftlab.reduced.paper.paper_study` (the paper's own
scenes and El Centro); the two-spring evidence from the fast or full equivalence maps. A
conclusion that needs El Centro says so when the record is missing, instead of deciding.

``upliftlab study paper [--fast] [--out DIR]``
"""

from __future__ import annotations

from .conclusions import (conclusion_decay, conclusion_long_period_peak, conclusion_more_with_c,
                          conclusion_peak_u, conclusion_period, conclusion_settlement,
                          conclusion_two_springs, conclusion_uplift_beneficial)
from .dataset import conclusions_dataset, conclusions_of
from .records import BUILDINGS, Conclusion, Evidence, STUDY
from .responses import apparent_period
from .summary import key_numbers, summarise
from .workflow import DEFINITION, Options, compute, run, write

__all__ = ["Evidence", "Conclusion", "Options", "DEFINITION", "compute", "write", "run",
           "conclusions_dataset", "conclusions_of", "summarise", "key_numbers", "apparent_period", "STUDY", "BUILDINGS", "conclusion_peak_u",
           "conclusion_long_period_peak", "conclusion_decay", "conclusion_settlement",
           "conclusion_two_springs", "conclusion_uplift_beneficial", "conclusion_more_with_c",
           "conclusion_period"]
