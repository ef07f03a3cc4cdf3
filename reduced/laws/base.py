"""What a foundation law is to the reduced model (:class:`Law`, the registry's entry) and what
its builder is given (:class:`Bed`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ...scenes.laws import LawRecord
from ..compatibility import SpringLayout

__all__ = ["Bed", "Base", "Law"]


@dataclass(frozen=True)
class Bed:
    """The foundation springs a law's builder fills: their ``layout`` (positions, stiffnesses
    and tributary widths, from −b to +b), the ``weight`` they carry at rest (force), the
    foundation's ``support`` and, for a custom layout, ``order``: the permutation from the
    scene's spring order (its ``positions``) to the layout's (None: the same)."""

    layout: SpringLayout
    weight: float
    support: str
    order: np.ndarray | None = None

    def in_layout_order(self, values) -> np.ndarray:
        """One value per spring, given in the scene's order, in the layout's."""
        values = np.asarray(values, dtype=float)
        return values if self.order is None else values[self.order]


@dataclass(frozen=True)
class Base:
    """What an element law's builder is given: the ``layout`` of the scene's springs (its
    half-width, and the bonded K_v and K_θ the element takes unless told otherwise), the
    ``weight`` it carries at rest (force), the sway's ``sway_stiffness`` K_h (force/length),
    the dashpots (``dashpot_density`` c′, force·s/length² per unit length of contact, and the
    sway's ``sway_dashpot``, force·s/length) and ``transform`` T (3 × n): the element's
    displacement (v, u, θ) from rest is T q."""

    layout: SpringLayout
    weight: float
    sway_stiffness: float
    dashpot_density: float
    sway_dashpot: float
    transform: np.ndarray


@dataclass(frozen=True)
class Law:
    """A foundation law of the reduced model.

    ``record`` the law's scene record class (:mod:`upliftlab.scenes.laws`: its name and keys).
    ``springs(record, bed, table)`` the builder: it fills the bed's rows of a spring table
    (``k``, ``x`` and ``c`` set) with their ``kind``, F0 (``f0``), ``fy`` and the law's own
    columns, and returns (the table, the static rotation of the base, rad). ``kinds`` the
    spring kinds its rows carry (the compiled forms in :mod:`..kernels.laws` dispatch on them).
    ``columns`` and ``history`` its own fields of the spring record and of the history (name,
    dtype), added to :data:`~upliftlab.reduced.laws.SPRING_DTYPE` and ``HISTORY_DTYPE``.
    ``start(p, h)`` puts a spring's history at its state at rest (None: zeros).

    A law that is one element on the base's three DOFs rather than a bed of springs (the
    macro-element) has no ``springs`` and no kinds: ``element(record, base)`` builds it
    from the base's :class:`Base` (the kernels take it as their base element,
    :mod:`upliftlab.reduced.kernels.base`).
    """

    record: type[LawRecord]
    springs: Callable | None
    kinds: tuple[int, ...]
    columns: tuple[tuple[str, type], ...] = ()
    history: tuple[tuple[str, type], ...] = ()
    start: Callable | None = None
    element: Callable | None = None

    @property
    def name(self) -> str:
        return self.record.name

    @property
    def tabulated(self) -> bool:
        """Whether the event stepper can tabulate the law (piecewise affine in each mode)."""
        return not self.record.curved
