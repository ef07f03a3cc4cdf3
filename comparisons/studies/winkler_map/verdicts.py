"""The continuum reference a map was made on and the verdicts on its runs, counted apart: the
points left out as beyond the small-strain reference
(:mod:`upliftlab.continuum.dynamics.validity`) and the runs whose far field (the box's side
columns, :mod:`upliftlab.continuum.dynamics.far_field`) yielded under the motion. Read from
the map dataset alone (maps written before a variable existed count it as not recorded)."""

from __future__ import annotations

import numpy as np

from .parts import options_of
from .sections import SWAY_NOTE

__all__ = ["verdict_counts", "verdict_lines", "sway_note", "REFERENCE_TEXTS"]

#: What each continuum reference is (:mod:`.reference`), for the summary.
REFERENCE_TEXTS = {
    "box": "the closed box (10 B wide and deep) on a rigid base with free-field shear sides",
    "half_plane": "the half-plane: the same box with a compliant base (the motion entering as "
                  "an incident S wave), free-field shear sides, the footing held horizontally "
                  "by a tie of the handbook strip's K_h = 2G/(2 − ν) and C_h = ρ V_s B, the "
                  "clay's undrained strength growing 1.7 kPa/m with depth, and the soil's "
                  "small-strain damping, Rayleigh ξ = 1 % at f₁ = V_s/(4H) and 5 f₁, carried "
                  "into every bed as a dashpot β k_i beside each spring (into the "
                  "macro-element as its dashpot density β K_v/B)"}


#: The half-plane's footing sways: what the beds leave out (the box's note is
#: :data:`.sections.SWAY_NOTE`).
HALF_PLANE_SWAY_NOTE = ("On the half-plane reference the continuum's footing is held to the "
                        "free field's surface by the handbook strip's sway spring and dashpot "
                        "(the tie, K_h = 2G/(2 − ν), C_h = ρ V_s B), and every bed sways on the "
                        "same spring and dashpot (its foundation's sway_stiffness and "
                        "sway_damping), so both let the footing move against the ground alike.")


def sway_note(m) -> str:
    """The summary's note on the footing's sway for the map's reference."""
    return HALF_PLANE_SWAY_NOTE if options_of(m)["reference"] == "half_plane" else SWAY_NOTE


def verdict_counts(m) -> dict:
    """The continuum ``reference`` and, over the map's ``points``: ``beyond_small_strain``
    (points left out), ``far_field_yielded`` (runs whose far field yielded, compared all the
    same unless beyond), ``far_field_yielded_compared`` (of those, the ones compared),
    ``far_field_elastic`` and ``far_field_not_recorded`` (failed runs and records made before
    the far field was stored; all of them on a map without the variable)."""
    points = int(m.continuum_wall_time.size)
    shape = m.continuum_wall_time.shape
    beyond = (m.continuum_beyond_small_strain.values.astype(bool)
              if "continuum_beyond_small_strain" in m else np.zeros(shape, bool))
    if "continuum_far_field_yielded" in m:
        far = m.continuum_far_field_yielded.values.astype(int)  # the same dims
    else:
        far = np.full(beyond.shape, -1)
    return {"reference": options_of(m)["reference"], "points": points,
            "beyond_small_strain": int(beyond.sum()),
            "far_field_yielded": int((far == 1).sum()),
            "far_field_yielded_compared": int(((far == 1) & ~beyond).sum()),
            "far_field_elastic": int((far == 0).sum()),
            "far_field_not_recorded": int((far == -1).sum())}


def verdict_lines(m) -> list[str]:
    """The summary's section on the continuum reference and its runs' verdicts."""
    c = verdict_counts(m)
    text = (f"The continuum reference is {REFERENCE_TEXTS.get(c['reference'], c['reference'])} "
            f"(`{c['reference']}`). Of its {c['points']} runs, {c['beyond_small_strain']} went "
            "beyond the small-strain reference (a largest plastic strain over 10 %): those "
            "points are left out of every error, like a refused run. The far field (the box's "
            f"side columns) yielded under the motion in {c['far_field_yielded']} runs "
            f"({c['far_field_yielded_compared']} of them compared: a yielding far field is "
            f"reported, not left out), stayed elastic in {c['far_field_elastic']}")
    if c["far_field_not_recorded"]:
        text += (f", and was not recorded in {c['far_field_not_recorded']} (runs that failed, "
                 "or records made before the far field was stored)")
    return ["## The continuum reference and its runs' verdicts", "", text + ".", ""]
