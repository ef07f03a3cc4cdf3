"""
Two springs against a Winkler bed: a rocking pushover
=====================================================

The wall's base rotated at constant weight, on three foundations of the same total vertical
stiffness K_v: a bed of 200 compression-only springs, two springs at ±b/√3 (they have the bed's
vertical and rocking stiffness) and two springs at the edges ±b. The closed forms (anchors
§2–3): the bed uplifts at M = NB/6 and then follows M/M_up = 3 − 2√(θ_up/θ) towards NB/2; the
pair at ±b/√3 uplifts at NB/(2√3) = 0.2887 NB and can carry no more, 0.577 of the bed's
ultimate moment: equivalent in contact, not after uplift.
"""

# %%
import matplotlib.pyplot as plt
import numpy as np

from upliftlab import load_scene
from upliftlab.reduced import build_model, rocking_pushover


def model(*overrides):
    return build_model(load_scene("wall_free", overrides=list(overrides)))


bed = model("foundation.springs=200")
pair = model('foundation.layout="equivalent"', "foundation.springs=2")
edges = model('foundation.layout="edges"', "foundation.springs=2")

N, B = bed.weight, 2 * bed.layout.half_width
theta_up = 2 * N / (bed.layout.vertical_stiffness * B)  # the bed's uplift rotation
ratios = np.geomspace(0.1, 100.0, 60)
push = {name: rocking_pushover(m, ratios * theta_up)
        for name, m in (("bed", bed), ("±b/√3", pair), ("±b", edges))}

# %%
# The bed against its closed form beyond uplift, and the pair's cap against the bed's
# ultimate moment.
closed = np.where(ratios <= 1, ratios, 3 - 2 / np.sqrt(ratios)) * N * B / 6
after = ratios > 1
bed_error = float(np.max(np.abs(push["bed"].moment[after] / closed[after] - 1)))
pair_cap_over_bed_ultimate = float(push["±b/√3"].moment[-1] / (N * B / 2))
print(f"bed of 200 springs: largest deviation from 3 − 2√(θ_up/θ) = {bed_error:.2%}")
print(f"pair at ±b/√3: capped at {pair_cap_over_bed_ultimate:.4f} of NB/2 (1/√3 = 0.5774)")

fig, ax = plt.subplots(figsize=(6.5, 3.2))
for name, p in push.items():
    ax.semilogx(ratios, p.moment / (N * B), label=name)
ax.semilogx(ratios, closed / (N * B), "k:", label="bed, closed form")
ax.set_xlabel("θ / θ_up of the bed")
ax.set_ylabel("M / (N B)")
ax.legend()
fig.tight_layout()
