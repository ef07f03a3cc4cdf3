"""Time histories of the soil, the rigid footing and the superstructure under a ground motion:
the entry point :func:`.run.run_dynamic`, its options and result, the ground motion's entry
(:mod:`.ground`, :mod:`.waves`), the superstructure, the implicit HHT-α route
(:mod:`.implicit`) and the explicit central-difference route (:mod:`.explicit`) with its
compiled loop, and what ends a run early (:mod:`.run_control`)."""
