"""The discretisation error of a dynamic run's peaks, estimated from the same run on coarser
meshes (Richardson extrapolation where the observed order holds).

A run on ``n`` elements across the footing and the same run on ``n/2`` give for each peak f the
estimate e ≈ |f_n − f_{n/2}| / (2^p − 1) of f_n's own error, for an order of convergence p:

- **two meshes**: p is the order observed in the committed study
  ``benchmarks/CONTINUUM_CONVERGENCE.md`` (10 s of El Centro on the clay scene, the explicit
  route on 8, 16 and 32 across: :data:`STUDY_DIFFERENCES`, its rows "mesh: explicit 8 across
  against 32" and "mesh: explicit 16 across against 32"), computed here from those numbers by
  :func:`observed_order`; a peak the study does not report has no order;
- **three meshes** (``n/4`` as well): p is observed on the run's own meshes,
  p = log₂(|f_{n/4} − f_{n/2}| / |f_{n/2} − f_n|).

An order is used where it holds: both differences of the same sign (monotone convergence:
an oscillating sequence has no asymptotic order) and p in [:data:`MIN_ORDER`,
:data:`MAX_ORDER`]. Elsewhere the estimate is the plain difference |f_n − f_{n/2}| as a
bound, flagged (:data:`FLAGS`): ``order does not hold``, or ``no observed order``, or
``singular`` for the largest plastic strain at a point (singular at the footing's corner: it
grows as the mesh is refined and has no converged value). The histories of θ and of the
settlement v − v(0) are compared as the largest difference over the time axis of the finer run
(the coarser interpolated linearly), unsigned.

Time: the explicit route's step is set by stability, dt ∝ h_min, so halving the mesh halves
the step as well and the estimate covers the error in time too; where the record's own step
bounds dt (or on the implicit route) the record says by how much the step changed
(:attr:`MeshErrorEstimate.step_ratio`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

__all__ = ["QuantityError", "MeshErrorEstimate", "observed_order", "richardson",
           "mesh_error", "history_differences", "STUDY_DIFFERENCES", "STUDY_ORDERS", "FLAGS",
           "QUANTITIES", "MIN_ORDER", "MAX_ORDER"]

#: The sane range of an observed order: outside it the differences are not in the
#: asymptotic range (or cancel by chance) and the order is not used.
MIN_ORDER, MAX_ORDER = 0.5, 4.0
#: The least ratio of the coarser run's step to the finer's for the pair to count as refined
#: in time with the mesh (2 exactly where no record step rounds it: an explicit step is the
#: record's step divided by a whole number).
MIN_STEP_RATIO = 1.5
#: The flags of an estimate, by code (the NetCDF's ``flag_values``).
FLAGS = ("richardson", "order does not hold", "no observed order", "singular")
#: (summary key, units kind: "angle", "length" or "1", signed) of each peak estimated; the
#: histories are ``theta_history`` and ``v_history``.
QUANTITIES = (("peak_theta", "angle", True), ("peak_structure_u", "length", True),
              ("peak_edge_uplift", "length", True), ("residual_settlement", "length", True),
              ("max_contact_loss", "1", True), ("max_plastic_strain", "1", True),
              ("theta_history", "angle", False), ("v_history", "length", False))
#: The committed study's differences of the 8- and the 16-across run from the 32-across
#: run, relative to it (``benchmarks/CONTINUUM_CONVERGENCE.md``; tests/test_mesh_error.py
#: reads them back from the table): signed for the peaks, the largest difference over the
#: peak for the histories.
STUDY_DIFFERENCES = {"peak_theta": (-1.137e-2, 0.242e-2),
                     "peak_edge_uplift": (-1.078e-2, 0.060e-2),
                     "residual_settlement": (-6.993e-2, -1.381e-2),
                     "theta_history": (36.575e-2, 10.397e-2),
                     "v_history": (39.425e-2, 7.764e-2)}
_SINGULAR = ("max_plastic_strain",)


def observed_order(coarse: float, fine: float, signed: bool = True) -> float:
    """The order p = log₂(|coarse| / |fine|) of two successive differences (``coarse`` =
    f_{n/4} − f_{n/2}, ``fine`` = f_{n/2} − f_n, refinement ratio 2), or NaN where it does not
    hold: a ``signed`` pair of opposite signs (the sequence oscillates), a zero difference, or
    p outside [MIN_ORDER, MAX_ORDER]."""
    if not (math.isfinite(coarse) and math.isfinite(fine)) or coarse == 0.0 or fine == 0.0:
        return math.nan
    if signed and (coarse > 0.0) != (fine > 0.0):
        return math.nan
    p = math.log2(abs(coarse) / abs(fine))
    return p if MIN_ORDER <= p <= MAX_ORDER else math.nan


def _study_orders() -> dict[str, float]:
    """The orders of :data:`STUDY_DIFFERENCES`: with e₈, e₁₆ the differences from the
    32-across run, f₈ − f₁₆ = e₈ − e₁₆ and f₁₆ − f₃₂ = e₁₆ (in units of f₃₂)."""
    signed = {name: s for name, _, s in QUANTITIES}
    return {name: observed_order(e8 - e16, e16, signed[name])
            for name, (e8, e16) in STUDY_DIFFERENCES.items()}


#: The order of each quantity in the committed study (NaN where it does not hold there).
STUDY_ORDERS = _study_orders()


def richardson(difference: float, order: float) -> float:
    """The estimated error |difference| / (2^order − 1) of the finer of two meshes (ratio 2);
    the plain |difference| (a bound, not an estimate) where ``order`` is NaN."""
    return abs(difference) / (2.0 ** order - 1.0) if math.isfinite(order) else abs(difference)


@dataclass(frozen=True)
class QuantityError:
    """One peak (or history) and its estimated discretisation error: ``values`` on each mesh
    (finest first; for a history its peak), ``differences`` f_n − f_{n/2} (and f_{n/2} −
    f_{n/4}; a history's largest difference), the ``estimate`` (same units), the ``order`` used
    (NaN: none), where it comes from (``order_source``) and the ``flag`` (:data:`FLAGS`)."""

    name: str
    units: str
    values: tuple[float, ...]
    differences: tuple[float, ...]
    estimate: float
    order: float
    order_source: str
    flag: str

    @property
    def relative(self) -> float:
        """The estimate over |value| on the finest mesh (NaN for a zero value)."""
        return self.estimate / abs(self.values[0]) if self.values[0] else math.nan


@dataclass(frozen=True)
class MeshErrorEstimate:
    """The estimate of a run on ``across[0]`` elements across from the coarser meshes
    ``across[1:]`` (each half the one before), their time steps ``dt`` (s) and the
    ``quantities``; ``metadata``: the scene, its units and the route. ``flags`` and
    ``order_bounds`` are the module's :data:`FLAGS` and [:data:`MIN_ORDER`,
    :data:`MAX_ORDER`]."""

    flags: ClassVar[tuple[str, ...]] = FLAGS
    order_bounds: ClassVar[tuple[float, float]] = (MIN_ORDER, MAX_ORDER)

    across: tuple[int, ...]
    dt: tuple[float, ...]
    quantities: tuple[QuantityError, ...]
    metadata: dict = field(default_factory=dict)

    @property
    def step_ratio(self) -> float:
        """dt of the next coarser run over dt of this one: 2 where the mesh pair refines the
        time step with the mesh (module docstring)."""
        return self.dt[1] / self.dt[0]

    def time_note(self) -> str:
        """What the mesh pair says of the error in time."""
        ratio = self.step_ratio
        if ratio >= MIN_STEP_RATIO:
            return (f"the time step is refined with the mesh ({ratio:.3g}× coarser on the "
                    "coarser mesh: set by stability, rounded to divide the record's step), so "
                    "the estimate covers the error in time too")
        return (f"the time step changes by only {ratio:.3g}× between the meshes (the record's "
                "step or the route bounds it), so the estimate covers the error in time only "
                "in part")

    def __getitem__(self, name: str) -> QuantityError:
        return next(q for q in self.quantities if q.name == name)

    def to_dict(self) -> dict:
        """A JSON-ready record (NaN as None)."""
        def plain(x):
            return None if isinstance(x, float) and not math.isfinite(x) else x
        return {"elements_across": list(self.across), "dt": list(self.dt),
                "time": self.time_note(), "order_bounds": [MIN_ORDER, MAX_ORDER],
                "quantities": {q.name: {"units": q.units, "value": plain(q.values[0]),
                                        "coarse_value": plain(q.values[1]),
                                        "coarser_value": plain(q.values[2])
                                        if len(q.values) > 2 else None,
                                        "difference": plain(q.differences[0]),
                                        "estimate": plain(q.estimate),
                                        "relative_estimate": plain(q.relative),
                                        "order": plain(q.order),
                                        "order_source": q.order_source, "flag": q.flag}
                               for q in self.quantities}}

    def to_xarray(self):
        """An :class:`xarray.Dataset` with CF attributes (written by :meth:`save`)."""
        from .mesh_error_file import estimate_dataset
        return estimate_dataset(self)

    def save(self, path):
        """Write :meth:`to_xarray` to ``path`` (NetCDF-4, CF-1.10); returns the path."""
        from ...results import write_dataset
        return write_dataset(path, self.to_xarray())

    def lines(self) -> list[str]:
        """One line per quantity: value ± estimate, with its order or flag."""
        from .mesh_error_file import estimate_lines
        return estimate_lines(self)


def history_differences(fine: dict, coarse: dict) -> dict[str, float]:
    """The largest difference of the θ and v − v(0) histories of ``fine`` and ``coarse``
    ({"time", "theta", "v"}), over ``fine``'s time axis within both runs."""
    t = np.asarray(fine["time"])
    t = t[t <= np.asarray(coarse["time"])[-1]]
    out = {}
    for key, name in (("theta", "theta_history"), ("v", "v_history")):
        a, b = np.asarray(fine[key], float), np.asarray(coarse[key], float)
        if key == "v":
            a, b = a - a[0], b - b[0]
        out[name] = float(np.max(np.abs(a[:t.size] - np.interp(t, coarse["time"], b))))
    return out


def _peak(history: dict, name: str) -> float:
    x = np.asarray(history["theta" if name == "theta_history" else "v"], float)
    return float(np.max(np.abs(x - (x[0] if name == "v_history" else 0.0))))


def mesh_error(summaries, histories, across, dt, units: dict | None = None,
               metadata: dict | None = None) -> MeshErrorEstimate:
    """The estimate (module docstring) from two or three runs, finest first: their
    ``summaries`` (:func:`~upliftlab.continuum.output.summaries.dynamic_summary`), their
    ``histories`` ({"time", "theta", "v"} arrays), ``across`` (elements across, each half
    the one before) and ``dt`` (s). ``units`` maps "angle", "length" and "1" to unit names."""
    if len(summaries) not in (2, 3) or not len(summaries) == len(histories) == len(across):
        raise ValueError("mesh_error: two or three runs, with a summary, history and mesh each")
    if any(a != 2 * b for a, b in zip(across, across[1:])):
        raise ValueError(f"mesh_error: elements across {list(across)}: each must be half the "
                         "one before")
    units = {"angle": "rad", "length": "", "1": "1", **(units or {})}
    pairs = [history_differences(histories[k], histories[k + 1])
             for k in range(len(across) - 1)]
    quantities = []
    for name, kind, signed in QUANTITIES:
        if name.endswith("_history"):
            values = tuple(_peak(h, name) for h in histories)
            differences = tuple(p[name] for p in pairs)
        else:
            values = tuple(math.nan if s.get(name) is None else float(s[name])
                           for s in summaries)
            differences = tuple(values[k] - values[k + 1] for k in range(len(values) - 1))
        if not all(math.isfinite(v) for v in values):
            continue  # not reported by this run (an elastic soil's plastic strain)
        if name in _SINGULAR:
            order, source, flag = math.nan, "none", FLAGS[3]
        elif len(differences) == 2:
            order, source = observed_order(differences[1], differences[0], signed), \
                f"observed on {across[2]}, {across[1]} and {across[0]} across"
            flag = FLAGS[0] if math.isfinite(order) else FLAGS[1]
        elif name in STUDY_ORDERS:
            order, source = STUDY_ORDERS[name], \
                "benchmarks/CONTINUUM_CONVERGENCE.md, explicit 8, 16 and 32 across"
            flag = FLAGS[0] if math.isfinite(order) else FLAGS[1]
        else:
            order, source, flag = math.nan, "none", FLAGS[2]
        quantities.append(QuantityError(name, units[kind], values, differences,
                                        richardson(differences[0], order), order, source,
                                        flag))
    return MeshErrorEstimate(tuple(int(a) for a in across), tuple(float(d) for d in dt),
                             tuple(quantities), dict(metadata or {}))
