"""Static analyses of the continuum: Newton's method for the soil and the footing's contact
(:mod:`.newton`, accelerated by :mod:`.anderson`), the initial geostatic state
(:mod:`.geostatic`), the analyses (:mod:`.analyses`) and their records (:mod:`.results`)."""
