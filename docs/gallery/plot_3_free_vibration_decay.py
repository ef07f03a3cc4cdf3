"""
Free-vibration decay
====================

The wall on a fixed base with 5 % damping of its story, released with Ẋ(0) = 20 in/s. Its
deformation is the damped oscillator's closed form u(t) = (v₀/ω_d) e^{−ζωt} sin ω_d t, and the
logarithmic decrement of successive peaks gives back ζ. Then the same wall on its uplifting
bed with Ewing's impact damper (ε = 0.7), whose decay comes from the landings, not a dashpot.
"""

# %%
import matplotlib.pyplot as plt
import numpy as np

from upliftlab import load_scene
from upliftlab.reduced import run

ZETA = 0.05
scene = load_scene("wall_free", overrides=['foundation.support="fixed"',
                                           f"structure.damping_ratio={ZETA}"])
response = run(scene)

g = scene.units.gravity
k, m, v0 = 500.0, 200.0 / g, 20.0               # kip/in, kip·s²/in, in/s (the scene's)
omega = np.sqrt(k / m)
omega_d = omega * np.sqrt(1 - ZETA**2)
t = response.time
closed = v0 / omega_d * np.exp(-ZETA * omega * t) * np.sin(omega_d * t)
history_error = float(np.max(np.abs(response.u - closed)) / np.max(np.abs(closed)))

# %%
# The decrement over the positive peaks of the run's own history.
u = response.u
peaks = np.flatnonzero((u[1:-1] > u[:-2]) & (u[1:-1] >= u[2:]) & (u[1:-1] > 0)) + 1
delta = np.log(u[peaks[0]] / u[peaks[-1]]) / (len(peaks) - 1)
zeta_from_decrement = float(delta / np.sqrt(4 * np.pi**2 + delta**2))
print(f"largest |u − closed form| = {history_error:.1e} of the peak")
print(f"ζ from the logarithmic decrement over {len(peaks)} peaks: {zeta_from_decrement:.4f}")

rocking = run(load_scene("wall_free", case="e07"))
energy = rocking.to_xarray().energy
mechanical = (energy.sel(component="kinetic") + energy.sel(component="strain")
              + energy.sel(component="gravity"))
impact_share = float(energy.sel(component="impact")[-1] / mechanical[0])
print(f"on the bed, ε = 0.7: the impacts took {impact_share:.0%} of the initial energy in 3 s")

fig, (a, b) = plt.subplots(2, 1, figsize=(6.5, 4.5), sharex=True)
a.plot(t, u, label="fixed base, ζ = 5 %")
a.plot(t, closed, "k:", label="closed form")
a.set_ylabel("u (in)")
a.legend()
b.plot(rocking.time, mechanical / mechanical[0], label="on the bed, ε = 0.7")
b.set_xlabel("time (s)")
b.set_ylabel("mechanical energy / initial")
b.legend()
fig.tight_layout()
