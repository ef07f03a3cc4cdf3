"""The macro-element's compiled layout: the slots of its parameter array (``P_…``, filled by
:func:`pack` from a :class:`~.params.MacroElement`), of its state (``S_…``: displacement
(v, u, θ), plastic displacement, forces (V, H, M), projection centre, accumulated plastic
settlement κ, dissipated energy, rounding ρ, and the memory: the largest mobilisation reached
with M ≥ 0 and with M < 0) and of the update's scratch array (``W_…``, three
floats a vector), and the statuses a step ends with (``STEP_…``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["pack", "P_COUNT", "S_COUNT", "W_COUNT", "STEP_OK", "STEP_CONTACT",
           "STEP_SURFACE", "STEP_SUBSTEPS", "STEP_FLOW", "MAX_NEWTON"]

(P_B, P_KV, P_KH, P_KR, P_KW, P_CXV, P_CXT, P_A1, P_A2, P_VU, P_TH, P_Z0, P_KREF, P_H0,
 P_GEXP, P_CHI, P_RHO, P_DIL, P_CEXP, P_MEM) = range(20)
P_COUNT = 20
S_D, S_P, S_Q, S_C, S_KAPPA, S_W, S_ROUND, S_MEM = 0, 3, 6, 9, 12, 13, 14, 15
S_COUNT = 17
# the scratch array: the update's vectors, three floats each
(W_Q0, W_TRIAL, W_CENTRE, W_DIR, W_NORMAL, W_FLOW, W_PLASTIC, W_Q, W_START, W_TARGET, W_DE,
 W_DE0, W_G) = range(0, 39, 3)
W_COUNT = 39
STEP_OK, STEP_CONTACT, STEP_SURFACE, STEP_SUBSTEPS, STEP_FLOW = 0, 1, 2, 3, 4
#: Newton iterations of the contact's solutions, at most.
MAX_NEWTON = 100


def pack(law) -> np.ndarray:
    """The parameter array of a :class:`~.params.MacroElement`."""
    P = np.zeros(P_COUNT)
    P[[P_B, P_KV, P_KH, P_KR, P_KW]] = (law.width, law.vertical_stiffness,
                                        law.horizontal_stiffness, law.rocking_stiffness,
                                        law.winkler_modulus)
    P[[P_CXV, P_CXT]] = law.remainder_compliance
    P[[P_A1, P_A2, P_VU, P_TH]] = (law.cohesive_pressure, law.frictional_modulus,
                                   law.ultimate_load, law.sliding_ratio)
    P[[P_Z0, P_KREF, P_H0, P_GEXP, P_CHI, P_RHO, P_DIL, P_CEXP, P_MEM]] = (
        law.initial_size, law.hardening_settlement, law.interior_modulus,
        law.interior_exponent, law.settlement_coupling, law.rounding_ratio,
        law.flow_dilatancy, law.coupling_exponent, law.memory_modulus)
    return P
