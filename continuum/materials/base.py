"""What every soil model's parameter record shares: the elastic constants, the plug-in's class
attributes (its name, its vectorised return map, its compiled point return's constants), the
input checks, and the frictional family's base record (c, φ, ψ) of Mohr–Coulomb and
Drucker–Prager.

A soil model is a frozen subclass of :class:`Elasticity`, validated on construction and callable
(``material(strain, state) -> (stress, tangent, new_state)``, its pure return map); the
registry (:mod:`~upliftlab.continuum.materials.registry`) finds it by :attr:`Elasticity.name`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ... import checks
from ...checks import InputError
from .returns import State, initial_state

__all__ = ["Elasticity", "Frictional", "check_elastic", "check_undrained", "check_frictional"]


def check_elastic(prefix: str, youngs_modulus, poisson_ratio) -> None:
    """Refuse E ≤ 0 or ν outside (−1, 0.5), naming the field ``prefix`` + name."""
    checks.positive(f"{prefix}youngs_modulus", youngs_modulus)
    nu = checks.finite(f"{prefix}poisson_ratio", poisson_ratio)
    if nu >= 0.5:
        raise InputError(f"{prefix}poisson_ratio = {nu:g}: valid range is (-1, 0.5); ν = 0.5 is "
                         "incompressible, which displacement elements cannot take (use ν ≤ 0.49 "
                         "with a mixed or reduced-integration element)")
    checks.in_range(f"{prefix}poisson_ratio", nu, -1.0, 0.5, low_open=True, high_open=True)


def check_undrained(prefix: str, model: str, undrained_strength) -> None:
    """Refuse a missing or non-positive undrained strength of ``model``."""
    if undrained_strength is None:
        raise InputError(f"{prefix}undrained_strength = None: model {model!r} needs it, "
                         "valid range is > 0")
    checks.positive(f"{prefix}undrained_strength", undrained_strength)


def check_frictional(prefix: str, cohesion, friction_angle, dilation_angle) -> None:
    """Refuse c < 0, φ outside [0, 60)°, ψ outside [0, φ], or no strength at all."""
    checks.nonnegative(f"{prefix}cohesion", cohesion)
    checks.in_range(f"{prefix}friction_angle", friction_angle, 0.0, 60.0, high_open=True)
    checks.finite(f"{prefix}dilation_angle", dilation_angle)
    if not 0.0 <= dilation_angle <= friction_angle:
        raise InputError(f"{prefix}dilation_angle = {dilation_angle:g}: valid range is "
                         f"[0, friction_angle = {friction_angle:g}]")
    if cohesion == 0.0 and friction_angle == 0.0:
        raise InputError(f"{prefix}cohesion = 0 with {prefix}friction_angle = 0: the soil has no "
                         "shear strength; valid range is cohesion > 0 or friction_angle > 0")


class Elasticity:
    """The base of every soil model's parameter record: isotropic elastic constants E (kPa, or
    the scene's stress unit) and ν, and the model's plug-in class attributes:

    - ``name``: the ``[soil] model`` name the registry knows it by;
    - ``update``: its vectorised return map, the pure function
      ``update(strain, state, params) -> (stress, tangent, new_state)``;
    - ``Constants``: the record (a :class:`typing.NamedTuple` of floats) that its compiled
      point return reads, with that return as ``Constants.point``
      (:mod:`~upliftlab.continuum.materials.compiled`); None for a model without one, which the
      explicit route then runs through ``update`` (the same numbers, slower).
    """

    youngs_modulus: float
    poisson_ratio: float
    name: ClassVar[str] = ""
    update: ClassVar = None
    Constants: ClassVar = None
    #: True for a model whose stress is linear in the strain (one tangent for a run).
    linear: ClassVar[bool] = False

    @classmethod
    def from_soil(cls, soil):
        """The record of a scene's :class:`~upliftlab.scenes.Soil` (its elastic constants;
        a model with a strength reads it too), refusing bad values with the ``soil.`` field."""
        return cls(youngs_modulus=float(soil.youngs_modulus),
                   poisson_ratio=float(soil.poisson_ratio))

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def bulk_modulus(self) -> float:
        return self.youngs_modulus / (3.0 * (1.0 - 2.0 * self.poisson_ratio))

    @property
    def lame(self) -> float:
        return self.bulk_modulus - 2.0 * self.shear_modulus / 3.0


    @property
    def symmetric(self) -> bool:
        """True unless the consistent tangent is unsymmetric (non-associated flow)."""
        return True

    def __call__(self, strain, state: State | None = None):
        """``update(strain, state, self)``: (stress, tangent, new_state)."""
        return type(self).update(strain, state, self)

    def initial_state(self, batch_shape=()) -> State:
        return initial_state(batch_shape)

    def at_points(self, depth):
        """This record at points of the given depths below the surface (length, shape
        (nelems, nqp)): itself, unless its strength grows with depth
        (:mod:`~upliftlab.continuum.materials.undrained`)."""
        return self

    def at_surface(self):
        """This record with its strength at the surface, uniform: itself unless its
        strength grows with depth."""
        return self

    def strength_gain(self, batch) -> np.ndarray:
        """The per-point strength added to the constants' by the compiled return, shape
        ``batch``: zeros unless the strength grows with depth."""
        return np.zeros(tuple(batch))

    def kernel_constants(self):
        """The :attr:`Constants` of this record, each field the record's attribute of that
        name as a float (kPa, or a plain number), for the compiled point return; None for a
        model without a compiled point return."""
        if self.Constants is None:
            return None
        return self.Constants(*(float(getattr(self, field)) for field in self.Constants._fields))


@dataclass(frozen=True)
class Frictional(Elasticity):
    """A frictional soil: cohesion c (kPa), friction angle φ and dilation angle ψ (degrees)."""

    youngs_modulus: float
    poisson_ratio: float
    cohesion: float
    friction_angle: float  # degrees
    dilation_angle: float = 0.0  # degrees, 0 <= ψ <= φ

    def __post_init__(self):
        prefix = f"{type(self).__name__}."
        check_elastic(prefix, self.youngs_modulus, self.poisson_ratio)
        check_frictional(prefix, self.cohesion, self.friction_angle, self.dilation_angle)

    @classmethod
    def from_soil(cls, soil):
        check_frictional("soil.", soil.cohesion, soil.friction_angle, soil.dilation_angle)
        return cls(youngs_modulus=float(soil.youngs_modulus),
                   poisson_ratio=float(soil.poisson_ratio), cohesion=float(soil.cohesion),
                   friction_angle=float(soil.friction_angle),
                   dilation_angle=float(soil.dilation_angle))

    @property
    def symmetric(self) -> bool:
        """Associated flow (ψ = φ) keeps the tangent symmetric."""
        return not self.dilation_angle < self.friction_angle

    @property
    def sin_phi(self) -> float:
        return math.sin(math.radians(self.friction_angle))

    @property
    def cos_phi(self) -> float:
        return math.cos(math.radians(self.friction_angle))

    @property
    def sin_psi(self) -> float:
        return math.sin(math.radians(self.dilation_angle))
