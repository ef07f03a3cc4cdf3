"""
A tiny continuum pushover against Prandtl
=========================================

A rigid rough strip 2 m wide pushed into Tresca clay (c_u = 50 kPa) on the plane-strain
continuum, on coarse meshes of 4 and 8 Q2 elements across the footing. The capacity converges
from above at O(h) to Prandtl's (2 + π) c_u B (anchor §4), so the Richardson extrapolation
2 q(8) − q(4) lands close to it.
"""

# %%
import matplotlib.pyplot as plt
import numpy as np

from upliftlab.anchors import prandtl_capacity
from upliftlab.continuum import make_model, vertical_pushover
from upliftlab.scenes import ContinuumOptions, Soil

B, CU = 2.0, 50.0                                    # m, kPa
soil = Soil(youngs_modulus=50e3, poisson_ratio=0.3, density=1.8, model="tresca",
            undrained_strength=CU, interface="bonded")
settlements = np.linspace(0.0, 0.1, 11)[1:]          # to 5 % of B
reference = prandtl_capacity(CU, B)                  # (2 + π) c_u B, kN/m
paths = {n: vertical_pushover(make_model(soil, B, ContinuumOptions(elements_across=n)),
                              settlements) for n in (4, 8)}
error = {n: float(p.N[-1] / reference - 1) for n, p in paths.items()}
richardson_error = 2 * error[8] - error[4]
print(f"Prandtl: {reference:.1f} kN/m; 4 across {error[4]:+.2%}, 8 across {error[8]:+.2%}, "
      f"Richardson {richardson_error:+.3%}")

# %%
fig, ax = plt.subplots(figsize=(6.5, 3))
for n, p in paths.items():
    ax.plot(settlements * 1000, p.N, "o-", label=f"{n} elements across")
ax.axhline(reference, color="k", ls=":", label="Prandtl, (2 + π) c_u B")
ax.set_xlabel("settlement (mm)")
ax.set_ylabel("N (kN/m)")
ax.legend()
fig.tight_layout()
