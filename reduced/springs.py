"""The spring table of a model and the spring laws' compiled forms, callable from Python.

Each spring has parameters (a record of :data:`SPRING_DTYPE`: stiffness ``k``, dashpot ``c``,
impact dashpot ``cimp``, static compression ``f0``, yield force ``fy``, …) and a state: its
``mode`` and history (a record of :data:`HISTORY_DTYPE`). Deformation ``e`` comes from
``e = Aᵀ q``; the returned force is conjugate to ``e``. For foundation springs ``e`` is the
compression measured from static equilibrium and the force returned is the *increment*
``F − F0`` over the static compression F0 (Ewing's equations are written about the static
state; eq. 6 note).

The laws are written where they live: the story spring (elastic–perfectly plastic ``k(e − ep)``
capped at ±Fy, plus a parallel elastic ``kh·e`` and a dashpot ``c``) in
:mod:`.kernels.laws`, which dispatches every other spring to its foundation law's forms —
each law one module of :mod:`.laws` (:mod:`.laws.elastoplastic`, also the elastic law's;
:mod:`.laws.qz`). The dispatching forms are exported here under their names: each is a pure
function of (mode, parameters, deformation, rate, history).
"""

from __future__ import annotations

import numpy as np

from .kernels import (BONDED, CLIPPED, CONTACT, ELASTIC, HISTORY_DTYPE, QZ, SEPARATED,
                      SPRING_DTYPE, STORY, UPLIFT, YIELD_NEG, YIELD_POS, YIELDING, commit_step,
                      force_in_mode, natural_mode, switch_mode, tangent, validity)

MODE_NAMES = {
    STORY: {ELASTIC: "elastic", YIELD_POS: "yielding+", YIELD_NEG: "yielding-"},
    UPLIFT: {SEPARATED: "separated", CONTACT: "contact", YIELDING: "yielding",
             CLIPPED: "clipped"},
}


def spring_table(count: int) -> np.ndarray:
    """An empty parameter table for ``count`` springs: elastic, no dashpot, no impact."""
    table = np.zeros(count, dtype=SPRING_DTYPE)
    table["fy"] = np.inf
    table["imph"] = np.inf
    return table


def derive_columns(table: np.ndarray) -> np.ndarray:
    """Fill the derived fields d0 = F0/k, dy = Fy/k, gs = 1/F0 (story 1/Fy), gd = 1/δ0 and
    share = c*/(c + c*), so that the compiled laws never divide. Returns a copy."""
    P = np.array(table, dtype=SPRING_DTYPE)
    story = P["kind"] == STORY
    with np.errstate(divide="ignore", invalid="ignore"):
        P["d0"] = np.where(story, 0.0, P["f0"] / P["k"])
        P["dy"] = P["fy"] / P["k"]
        scale = np.where(story, P["fy"], P["f0"])
        P["gs"] = np.where(np.isfinite(scale), 1.0 / scale, 0.0)
        P["gd"] = np.where(story, 0.0, 1.0 / P["d0"])
        cc = P["c"] + P["cimp"]
        P["share"] = np.where(cc > 0, P["cimp"] / cc, 0.0)
    return P


__all__ = [
    "SPRING_DTYPE", "HISTORY_DTYPE", "spring_table", "derive_columns",
    "STORY", "UPLIFT", "BONDED", "QZ",
    "SEPARATED", "CONTACT", "YIELDING", "CLIPPED", "ELASTIC", "YIELD_POS", "YIELD_NEG",
    "force_in_mode", "natural_mode", "validity", "switch_mode", "commit_step", "tangent",
    "MODE_NAMES",
]
