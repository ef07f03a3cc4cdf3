"""Which model and discretization does one scene need for a quantity within a tolerance?
The reduced model's ladder (:mod:`.ladder`), the continuum's (:mod:`.continuum`) and the
Winkler map's evidence for the scene (:mod:`.map_evidence`)."""
