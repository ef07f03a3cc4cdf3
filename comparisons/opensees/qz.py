"""A q–z bed as OpenSees ``QzSimple2`` springs: the mapping of upliftlab's q–z spring
(:mod:`upliftlab.reduced.laws.qz`) onto QzSimple2's parameters, both backbones in closed form,
and where they differ.

QzSimple2 (OpenSees ``SRC/material/uniaxial/PY/QzSimple2.cpp``, Boulanger et al. 1999, as
modified by Raychowdhury) is a far field (elastic, ``c_far``·q_ult/z50), a near field (rigid,
10⁴ q_ult/z50, over an elastic range ±``elast``·q_ult, then the hyperbola q = q_ult −
(q_ult − q₀)[z_ref/(z_ref + z − z₀)]ⁿ with z_ref = ``c_ref``·z50) and a gap (closure
10³ q_ult/z50 in compression, a drag of ``suction``·q_ult with reference z50/2) in series, and
a dashpot c on the far field's velocity. Its constants per type (the file's
``revertToStart``): type 1 (Reese and O'Neill, clay) n = 1.2, elast = 0.22, c_ref = 0.5,
c_far = 0.525; type 2 (Vijayvergiya, sand) n = 5.5, elast = 0.36, c_ref = 9.29, c_far = 1.39;
the elastic range grows on reversals to at most 0.7 q_ult; the suction at most 0.1.
OpenSees' compression is negative.

**Mapping** (:func:`qzsimple2_springs`): the type whose exponent is the spring's (clay 1.2 →
1, sand 5.5 → 2; another exponent, e.g. fitted, has no QzSimple2 type and is refused);
q_ult the spring's; z50 such that QzSimple2's initial stiffness (far field, near field and
closure in series) is the spring's k, so that the bed's vertical and rocking stiffnesses and
its periods are upliftlab's; suction the spring's drag over q_ult (reference z50/2 in both);
c the spring's dashpot.

**Where they differ.** Only two of QzSimple2's numbers are free, so past the elastic range
its backbone is not upliftlab's: the elastic range is 0.36 (sand) or 0.22 (clay) of q_ult
against the bed's (0.3 or 0.2 unless fitted), and z_ref is c_ref·z50 of QzSimple2's own z50
(set by k) against the bed's z_ref (set by the bed's z50 under a centred load): the test
(``tests/test_opensees_qz.py``) measures the difference at points. QzSimple2's near field and
closure are stiff, not rigid; its dashpot acts on the far field's velocity and is not clipped
at zero force; its springs settle on its own backbone under the weight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checks import InputError

__all__ = ["QzSimple2Type", "QZSIMPLE2_TYPES", "QzSimple2Spring", "qzsimple2_springs",
           "flexibility", "qzsimple2_compression", "qzsimple2_force", "NEAR_STIFFNESS",
           "CLOSED_STIFFNESS", "SUCTION_CAP"]


@dataclass(frozen=True)
class QzSimple2Type:
    """QzSimple2's constants of one soil type (dimensionless): hyperbola exponent ``n``,
    initial elastic half-range ``elast``·q_ult, z_ref = ``c_ref``·z50, far-field stiffness
    ``c_far``·q_ult/z50."""

    n: float
    elast: float
    c_ref: float
    c_far: float


#: QzSimple2.cpp, ``revertToStart``: type 1 clay, type 2 sand.
QZSIMPLE2_TYPES = {1: QzSimple2Type(n=1.2, elast=0.22, c_ref=0.5, c_far=0.525),
                   2: QzSimple2Type(n=5.5, elast=0.36, c_ref=9.29, c_far=1.39)}
#: The near field's stiffness inside its elastic range and the closed gap's, × q_ult/z50.
NEAR_STIFFNESS, CLOSED_STIFFNESS = 1.0e4, 1.0e3
#: The largest suction QzSimple2 takes (it sets a larger one to this, with a message).
SUCTION_CAP = 0.1


@dataclass(frozen=True)
class QzSimple2Spring:
    """One ``uniaxialMaterial QzSimple2 tag qz_type qult z50 suction c``: ``qz_type`` 1 or 2,
    ``qult`` (force), ``z50`` (length), ``suction`` (fraction of q_ult), ``c``
    (force·s/length)."""

    qz_type: int
    qult: float
    z50: float
    suction: float
    c: float

    def args(self) -> list:
        """The material's arguments after its tag, as numbers (never text)."""
        return [int(self.qz_type), float(self.qult), float(self.z50), float(self.suction),
                float(self.c)]


def _type_of(n: float) -> int:
    for key, t in QZSIMPLE2_TYPES.items():
        if math.isclose(n, t.n, rel_tol=1e-12):
            return key
    raise InputError(f"foundation.qz_exponent = {n:g}: QzSimple2 has the exponents "
                     f"{QZSIMPLE2_TYPES[1].n:g} (clay, type 1) and {QZSIMPLE2_TYPES[2].n:g} "
                     "(sand, type 2) only; valid: no qz_exponent (the soil's)")


def flexibility(qz_type: int) -> float:
    """q_ult/(z50·k) of a QzSimple2 spring of initial stiffness k (its flexibility in units
    of z50/q_ult): far field, near field and closed gap in series."""
    t = QZSIMPLE2_TYPES[qz_type]
    return 1.0 / t.c_far + 1.0 / NEAR_STIFFNESS + 1.0 / CLOSED_STIFFNESS


def qzsimple2_springs(rows) -> tuple[QzSimple2Spring, ...]:
    """The QzSimple2 springs of a q–z bed's spring records ``rows`` (fields ``k``, ``c``,
    ``qult``, ``npow``, ``qd``: :mod:`upliftlab.reduced.laws.qz`), mapped as the module
    docstring says. A suction beyond :data:`SUCTION_CAP` is an :class:`InputError`."""
    out = []
    for r in rows:
        qz_type = _type_of(float(r["npow"]))
        qult, k = float(r["qult"]), float(r["k"])
        suction = float(r["qd"]) / qult
        if suction > SUCTION_CAP:
            raise InputError(f"foundation.suction = {suction:g}: QzSimple2 takes at most "
                             f"{SUCTION_CAP:g}; valid range is [0, {SUCTION_CAP:g}]")
        out.append(QzSimple2Spring(qz_type, qult, qult / (flexibility(qz_type) * k),
                                   suction, float(r["c"])))
    return tuple(out)


def qzsimple2_compression(q, spring: QzSimple2Spring) -> np.ndarray:
    """The compression z (length, positive) of a QzSimple2 spring on its virgin backbone at
    force q (0 ≤ q < q_ult), in closed form: the series' parts at one force, the drag left
    out (it adds at most suction·q_ult)."""
    t = QZSIMPLE2_TYPES[spring.qz_type]
    q = np.asarray(q, dtype=float)
    qult, z50 = spring.qult, spring.z50
    q0 = t.elast * qult
    with np.errstate(divide="ignore", invalid="ignore"):
        near = np.where(q > q0, t.c_ref * z50 * (((qult - q0) / (qult - q)) ** (1.0 / t.n)
                                                 - 1.0), 0.0)
    return q * flexibility(spring.qz_type) * z50 / qult + near


def qzsimple2_force(z, spring: QzSimple2Spring, iterations: int = 200) -> np.ndarray:
    """The force (positive in compression) of a QzSimple2 spring on its virgin backbone at
    compression z (length), by bisection on :func:`qzsimple2_compression`."""
    z = np.asarray(z, dtype=float)
    lo, hi = np.zeros(z.shape), np.full(z.shape, spring.qult)
    for _ in range(iterations):
        q = 0.5 * (lo + hi)
        low = qzsimple2_compression(q, spring) < z
        lo, hi = np.where(low, q, lo), np.where(low, hi, q)
    return 0.5 * (lo + hi)
