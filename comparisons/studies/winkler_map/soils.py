"""The soils of the Winkler map, as the continuum's ``[soil]`` tables.

Apart from the grid (:mod:`.grid`, which re-exports them) because the continuum's point
functions read them.
"""

from __future__ import annotations

__all__ = ["SOILS", "SOIL_LABELS"]

#: The soils of the map, as the continuum's ``[soil]`` tables (kPa, t/m³, degrees): the clay of
#: ``strip_footing_clay`` (Tresca, c_u) and a frictional soil of the same elastic constants
#: (Mohr–Coulomb, c and φ, associated flow ψ = φ: with ψ = 0 the continuum's vertical pushover
#: does not converge on 4 across). The continuum's soil has one Young's modulus everywhere: its
#: stiffness does not grow with confinement.
SOILS = {
    "clay": {"youngs_modulus": 50.0e3, "poisson_ratio": 0.3, "density": 1.8,
             "model": "tresca", "undrained_strength": 50.0, "interface": "frictionless"},
    "sand": {"youngs_modulus": 50.0e3, "poisson_ratio": 0.3, "density": 1.8,
             "model": "mohr_coulomb", "cohesion": 5.0, "friction_angle": 30.0,
             "dilation_angle": 30.0, "interface": "frictionless"},
}
SOIL_LABELS = {"clay": "clay (Tresca, c_u = 50 kPa)",
               "sand": "frictional soil (Mohr–Coulomb, c = 5 kPa, φ = ψ = 30°)"}
