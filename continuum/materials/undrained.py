"""What the undrained models (Tresca, von Mises) share: an undrained strength that may grow
with depth, c_u(z) = c_u + k z, and the way it reaches their two return maps.

z is the depth below the ground surface (the footing's base level, y = 0 of the soil mesh;
the same depth as the geostatic stress's, :func:`~upliftlab.continuum.statics.geostatic.
k0_stress`). A record holds c_u at the surface (``undrained_strength``, kPa) and the gradient k
(``undrained_strength_gradient``, kPa per length; 0 for a uniform soil). The model puts its
record at its quadrature points (:meth:`Undrained.at_points`, their depths (nelems, nqp)):

- the vectorised map reads :meth:`Undrained.strength` of its batch: the float c_u when k = 0
  (exactly the arithmetic of a uniform soil), else c_u + k z per point;
- the compiled point return reads the constants' c_u plus a per-point ``gain`` k z that the
  element loop passes it (:meth:`~upliftlab.continuum.materials.base.Elasticity.strength_gain`,
  zeros when k = 0: c_u + 0 is c_u, bit for bit; else c_u + (k z), the vectorised map's
  sum of the same two numbers).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ... import checks

__all__ = ["Undrained", "check_gradient"]


def check_gradient(prefix: str, gradient) -> None:
    """Refuse a negative or non-finite strength gradient, naming ``prefix`` + the field."""
    checks.nonnegative(f"{prefix}undrained_strength_gradient", gradient)


class Undrained:
    """The depth-dependent undrained strength of a record with the fields
    ``undrained_strength`` c_u (kPa at the surface), ``undrained_strength_gradient`` k
    (kPa per length) and ``depth`` (None, or the depths (nelems, nqp) of the points the
    record is evaluated at: :meth:`at_points`)."""

    @property
    def graded(self) -> bool:
        """True if the strength grows with depth (k > 0)."""
        return self.undrained_strength_gradient != 0.0

    def at_points(self, depth):
        """This record at points of the given depths (length, any batch shape); itself when
        the strength is uniform."""
        if not self.graded:
            return self
        depth = np.ascontiguousarray(depth, dtype=float)
        checks.nonnegative("depth (smallest)", float(depth.min()) if depth.size else 0.0)
        return dataclasses.replace(self, depth=depth)

    def at_surface(self):
        """This record with a uniform strength c_u (its value at the surface): for what does
        not depend on the strength, e.g. the elastic tangent at zero strain."""
        if not self.graded:
            return self
        return dataclasses.replace(self, undrained_strength_gradient=0.0, depth=None)

    def strength(self, batch):
        """c_u at the points of a return map's ``batch`` (shape): the float c_u when uniform,
        else c_u + k z flattened (N,) from the record's depths, which must have that shape."""
        if not self.graded:
            return self.undrained_strength
        if self.depth is None or self.depth.shape != tuple(batch):
            have = None if self.depth is None else self.depth.shape
            raise ValueError(f"a strength that grows with depth needs the depths of the "
                             f"points: batch {tuple(batch)}, depths {have} (use at_points)")
        return (self.undrained_strength + self.undrained_strength_gradient * self.depth).ravel()

    def strength_gain(self, batch) -> np.ndarray:
        """k z at the points of ``batch`` (contiguous, that shape), the compiled return's
        per-point addition to the constants' c_u; zeros when uniform."""
        if not self.graded:
            return np.zeros(tuple(batch))
        self.strength(batch)  # refuses depths of another shape
        return self.undrained_strength_gradient * self.depth
