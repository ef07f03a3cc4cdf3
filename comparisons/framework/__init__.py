"""What every study shares: the protocol (:mod:`.protocol`), the store keyed by what was asked
(:mod:`.store`) and the checks of its stale records (:mod:`.freshness`, :mod:`.migrate`),
sweeps (:mod:`.sweep`), what the studies measure (:mod:`.measures`), their results' common
records and helpers (:mod:`.study`), their figures (:mod:`.figure_record`,
:mod:`.map_figures`) and whether the continuum's dynamics can run (:mod:`.availability`)."""
