"""The El Centro 1940 N-S record that the paper's study expects, and how a copy is checked.

The record is not in the repository: the user supplies it on ``UPLIFTLAB_MOTIONS``
(:mod:`upliftlab.motions`). Several digitizations of the same accelerogram circulate, and they
differ in step, length, sign and peak, so a copy is checked against the one the founding
study's figures and upliftlab's stated numbers were computed on:

* the 1940 El Centro accelerogram, north–south component, as tabulated at 0.02 s in
  A. K. Chopra's *Dynamics of Structures* (Appendix on ground motions); copies of it circulate,
  some shifted by a leading zero sample, and this check tells whether a copy holds the same
  samples;
* its length, step and peak (:data:`EXPECTED`), in g;
* the SHA-256 :data:`SAMPLES_SHA256` of its samples as whole multiples of 1e-5 g
  (little-endian int64), so that a copy with other comments, spacing or columns still matches.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np

__all__ = ["Digitization", "EXPECTED", "SAMPLES_SHA256", "digitization_of", "mismatch"]

#: Resolution of the tabulated digitization (g): its samples are given to five decimals.
RESOLUTION_G = 1e-5

#: SHA-256 of the expected samples in units of :data:`RESOLUTION_G` (module docstring).
SAMPLES_SHA256 = "7720ca42bf0f77d2ad47149a1de727919446612ba50314aad2ed3ee6132e2ae2"


@dataclass(frozen=True)
class Digitization:
    """What identifies a digitization: ``samples`` (count), ``dt`` (s), ``pga`` (g) and the
    ``sha256`` of its samples (module docstring)."""

    samples: int
    dt: float
    pga: float
    sha256: str

    def describe(self) -> str:
        return (f"{self.samples} samples at {self.dt:g} s, PGA {self.pga:.5f} g, samples "
                f"SHA-256 {self.sha256[:12]}…")


#: The digitization the paper's study expects.
EXPECTED = Digitization(samples=1560, dt=0.02, pga=0.31882, sha256=SAMPLES_SHA256)


def digitization_of(motion) -> Digitization:
    """The :class:`Digitization` of a :class:`~upliftlab.motions.Motion` (its samples rounded to
    :data:`RESOLUTION_G` for the digest)."""
    counts = np.rint(np.asarray(motion.acceleration, dtype=float) / RESOLUTION_G)
    digest = hashlib.sha256(counts.astype("<i8").tobytes()).hexdigest()
    return Digitization(samples=int(counts.size), dt=float(motion.dt), pga=float(motion.pga),
                        sha256=digest)


def mismatch(motion) -> str | None:
    """None if ``motion`` is the expected digitization (:data:`EXPECTED`); else one sentence
    saying how it differs."""
    found = digitization_of(motion)
    if found.sha256 == EXPECTED.sha256 and abs(found.dt - EXPECTED.dt) <= 1e-9:
        return None
    return (f"{motion.source or motion.name} is not the El Centro 1940 N-S digitization "
            f"upliftlab expects ({EXPECTED.describe()}); it has {found.describe()}")
