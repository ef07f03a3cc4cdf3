"""Spring laws as small pure functions of their state (numba-compiled, also callable from Python).

Each spring has parameters (a record: stiffness ``k``, dashpot ``c``, impact dashpot ``cimp``,
static compression ``f0``, yield force ``fy``, …) and a state: its ``mode`` and history.
Deformation ``e`` comes from ``e = Aᵀ q``; the returned force is conjugate to ``e``. For foundation springs ``e`` is the compression measured from static equilibrium and the
force returned is the *increment* ``F − F0`` over the static compression F0 (Ewing's equations
are written about the static state; eq. 6 note).

Foundation spring (Figs. 3b, 6). Elastic compression ``d = F0/k + e − ep``: the spring is in
contact while ``d > 0`` — an elastic spring separates when its tension from static exceeds the
static compression; an elasto-plastic spring separates at that point shifted by its plastic
settlement ``ep``. The spring force ``k d`` is capped at ``Fy`` (``yield_multiple`` · F0) while
loading, and the cap accumulates ``ep``. A parallel dashpot ``c`` (plus the impact dashpot c*
while active) detaches with the spring, and the total force never pulls: it is clipped at zero
while the spring opens (as OpenSees ``QzSimple``). Contact ends when the displacement returns to
the (settled) surface, not when the force reaches zero.

Story spring: elastic–perfectly-plastic ``k(e − ep)`` capped at ±Fy, plus a parallel elastic
``kh·e`` (bilinear kinematic hardening) and a dashpot ``c``.

Impact damper (eqs. 10–17): on recontact with closing velocity v₀ the dashpot c* acts over the
stroke ``Δz = v₀ · m_eff (1 − ε)/c*`` (``DZF`` = m_eff (1 − ε)/c*), then locks.

The compiled laws are defined in :mod:`.kernels` (with the integrators that inline them, so
that numba's per-file cache can never pair an edited law with stale integrators) and exported
here under their names. Each is a pure function of (mode, parameters, deformation, rate,
history): parameters ``p`` are one record of :data:`SPRING_DTYPE` and history ``h`` one record
of :data:`HISTORY_DTYPE` (fields ``ep`` plastic deformation, ``imp`` impact damper on,
``e0`` deformation at recontact, ``dz`` impact stroke).

Hysteretic q–z spring (kind ``QZ``, :mod:`.kernels.qz_law`): an elastic far field, a Masing
near field with a hyperbolic backbone to its capacity and a gap with optional drag, in series;
its state is the rest of the history record (``zc``, ``qc``, ``zp``, …), its parameters the
``qult``, ``zref``, ``npow``, ``elast``, ``emax``, ``qd``, ``zd`` and ``zs`` fields
(:mod:`.qz` builds them).
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
