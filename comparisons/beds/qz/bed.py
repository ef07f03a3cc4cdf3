"""The map's hysteretic q–z bed: QzSimple-class springs whose backbone is fitted to the
continuum's whole vertical pushover.

Why a q–z bed: under rocking, the loaded edge's springs yield again on every cycle past their
Masing range, so the settlement accumulates cycle by cycle, as it does in the continuum; an
elasto-plastic spring yields only beyond its largest previous force.

- *capacities*: the continuum's V_ult shared over the springs' equal tributary widths,
  q_ult,i = V_ult · w_i/B (:func:`.calibration.spring_capacities`);
- *stiffnesses*: the end-stiffened bed with the continuum's K_v and K_r, K_r kept where no
  R_k reaches K_r/K_v (:func:`.calibration.qz_stiffnesses`), as the
  elastic and elasto-plastic beds keep it: rocking is what the beds are compared in;
- *shape*: z50, the elastic range and the exponent fitted to the continuum's pushover for
  that bed (:func:`.fit.fit_backbone`).

The table lists the springs' positions and stiffnesses (a ``custom`` layout), so what it
builds can be read off it. The pushover comes in ``reference.extra`` as ``settlement``
(length) and ``load`` (force per length of footing), from the map's statics.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ....checks import InputError
from ....reduced.compatibility import winkler_bed
from .calibration import qz_stiffnesses, spring_capacities
from .fit import QzFit, fit_backbone

__all__ = ["build_qz", "qz_bed_fit"]


@lru_cache(maxsize=64)
def _fit(settlement: tuple, load: tuple, stiffnesses: tuple, capacities: tuple,
         soil: str) -> QzFit:
    return fit_backbone(settlement, load, stiffnesses, capacities, soil)


def qz_bed_fit(reference, options) -> tuple[np.ndarray, np.ndarray, np.ndarray, QzFit]:
    """(positions (length), stiffnesses k_i (force/length), capacities q_ult,i (force), the
    fitted backbone) of the q–z bed at ``reference`` (a :class:`.beds.BedReference`) with the
    map's ``options`` (springs, end length, largest R_k). The fit depends on the soil's statics
    and the bed only, not on N: it is computed once per soil (cached)."""
    settlement = reference.extra.get("settlement")
    load = reference.extra.get("load")
    if settlement is None or load is None:
        raise InputError("the q–z bed needs the continuum's vertical pushover: give "
                         "reference.extra['settlement'] and reference.extra['load']")
    b = 0.5 * reference.B
    k, _, _ = qz_stiffnesses(reference.K_v, reference.K_r, b, options.springs,
                             options.end_length, options.max_end_stiffness_ratio)
    bed = winkler_bed(b, 1.0, options.springs)
    q = spring_capacities(reference.V_ult, bed.widths)
    soil = reference.soil if reference.soil in ("clay", "sand") else "clay"
    fit = _fit(tuple(float(v) for v in settlement), tuple(float(v) for v in load),
               tuple(float(v) for v in k), tuple(float(v) for v in q), soil)
    return np.asarray(bed.positions, dtype=float), k, q, fit


def build_qz(reference, options) -> dict:
    """The ``[foundation]`` table of the q–z bed (module docstring): a custom layout of the
    end-stiffened stiffnesses, capacity V_ult (``capacity_multiple`` = V_ult/N), and the fitted
    z_ref, exponent and elastic range (z_ref rather than z50: a fitted elastic range may carry
    half the capacity on its own, and z50 then does not fix z_ref); no suction (the
    continuum's contact is unilateral)."""
    x, k, _, fit = qz_bed_fit(reference, options)
    soil = reference.soil if reference.soil in ("clay", "sand") else "clay"
    return {"support": "uplift", "half_width": 0.5 * reference.B, "layout": "custom",
            "positions": [float(v) for v in x], "stiffnesses": [float(v) for v in k],
            "law": "qz", "capacity_multiple": reference.V_ult / reference.N, "qz_zref": fit.zref,
            "suction": 0.0, "qz_soil": soil, "qz_exponent": fit.exponent,
            "qz_elastic_range": fit.elastic_range}
