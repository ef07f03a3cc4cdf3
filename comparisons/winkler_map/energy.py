"""The map's foundation energy: each bed's E_F against the continuum's, where the continuum's
energy run of a point is stored (:mod:`.energy_points`, :mod:`.foundation_energy`).

E_F is the energy the structure lost to its foundation over the run: a bed's dashpot, impact and
plastic work and the change of its springs' energy; the continuum soil's plastic work, the
waves the footing sent into it and the change of its elastic energy. Its error floor is
:data:`.grid.FLOOR_FRACTION` × the strain energy of a uniform bed at its uplift threshold,
½ M_up θ_up = ½ (N B/6)²/K_r (:func:`energy_scale`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .beds import BEDS

__all__ = ["EnergyPick", "energy_scale", "same_run", "energy_pick", "energy_lines",
           "energy_numbers", "RUN_TOLERANCE"]

#: The largest relative difference allowed between a measure of a point's energy run and of
#: its dynamic run: the same run of the same code, deterministic on one thread, so equal.
RUN_TOLERANCE = 1e-9


def energy_scale(N: float, B: float, K_r: float) -> float:
    """½ M_up θ_up = ½ (N B/6)²/K_r: the rocking strain energy of a uniform tensionless bed of
    rocking stiffness K_r at its uplift threshold (force·length per length)."""
    moment = N * B / 6.0
    return 0.5 * moment * moment / K_r


def same_run(energy_record: dict, dynamic_record: dict, where: str) -> None:
    """Refuse (RuntimeError) an energy run whose measures are not its point's dynamic run's
    (within :data:`RUN_TOLERANCE`): its E_F would not belong to the run the map compares."""
    for name, value in dynamic_record["measures"].items():
        other = energy_record["measures"].get(name, math.nan)
        if not abs(other - value) <= RUN_TOLERANCE * max(abs(value), 1e-300):
            raise RuntimeError(
                f"{where}: the energy run's {name} = {other!r} differs from the dynamic run's "
                f"{value!r} (allowed {RUN_TOLERANCE:g} relative): the two stored runs are not "
                "the same run; remake the energy run")


@dataclass(frozen=True)
class EnergyPick:
    """E_F over the points with a continuum energy run (``points``): each calibration's
    |error| ``median`` and ``p90`` and its signed median ``bias`` (fractions), the ``best``
    calibration (smallest median, then p90; None if no bed was compared) and per soil
    (``soils``: {soil: (points, best, median, p90)})."""

    points: int
    median: dict
    p90: dict
    bias: dict
    best: str | None
    soils: dict


def _stats(values: np.ndarray) -> tuple[float, float, float]:
    values = values[np.isfinite(values)]
    if values.size == 0:
        return math.nan, math.nan, math.nan
    return (float(np.median(np.abs(values))), float(np.percentile(np.abs(values), 90)),
            float(np.median(values)))


def _rank(median: dict, p90: dict, names) -> str | None:
    finite = [n for n in names if math.isfinite(median[n])]
    return min(finite, key=lambda n: (median[n], p90[n])) if finite else None


def energy_pick(data) -> EnergyPick | None:
    """The error distribution of E_F per calibration (:class:`EnergyPick`) over the points
    whose continuum energy run is stored; None when the map holds none."""
    if data.energy_errors is None or not np.isfinite(data.continuum_energy).any():
        return None
    median, p90, bias = {}, {}, {}
    for c, name in enumerate(data.calibrations):
        median[name], p90[name], bias[name] = _stats(data.energy_errors[..., c].ravel())
    soils = {}
    for s, soil in enumerate(data.grid.soils):
        n = int(np.isfinite(data.continuum_energy[s]).sum())
        if n:
            stats = {name: _stats(data.energy_errors[s, ..., c].ravel())
                     for c, name in enumerate(data.calibrations)}
            best = _rank({k: v[0] for k, v in stats.items()},
                         {k: v[1] for k, v in stats.items()}, data.calibrations)
            soils[soil] = (n, best, stats[best][0] if best else math.nan,
                           stats[best][1] if best else math.nan)
    return EnergyPick(int(np.isfinite(data.continuum_energy).sum()), median, p90, bias,
                      _rank(median, p90, data.calibrations), soils)


def _pct(value: float) -> str:
    return "n/a" if not math.isfinite(value) else f"{100 * value:.1f} %"


def energy_lines(data, pick: EnergyPick | None) -> list[str]:
    """The summary's section on E_F (markdown lines)."""
    intro = ("E_F is the energy the structure lost to its foundation over the run, from the "
             "structure's own side of the balance (the ground's input less the change of its "
             "kinetic, story and gravity energy and its story dashpot's work): a bed's dashpot, "
             "impact and plastic work and the change of its springs' energy; the continuum "
             "soil's plastic work, the waves the footing sent into it and the change of its "
             "elastic energy. It is the foundation's damping as the structure sees it. The "
             "continuum's own energy account cannot give the soil's dissipation apart: it "
             "books plastic work with stored elastic energy, and the soil's own free-field "
             "response with them. Errors are relative, with the floor "
             "0.1 × ½ (N B/6)²/K_r (a uniform bed's strain energy at its uplift threshold).")
    total = data.continuum_wall.size
    if pick is None:
        return [intro, "", f"No point of this map has a continuum energy run stored (0 of "
                           f"{total}): E_F is not compared. Run the map with --energy to make "
                           "them (one more continuum run per point)."]
    lines = [intro, "", f"Points with the continuum's E_F: {pick.points} of {total}.", "",
             "| calibration | median |error| | 90th percentile | signed median |",
             "|---|---|---|---|"]
    for name in data.calibrations:
        lines.append(f"| `{name}` | {_pct(pick.median[name])} | {_pct(pick.p90[name])} | "
                     f"{_pct(pick.bias[name])} |")
    lines.append("")
    if pick.best is not None:
        label = BEDS[pick.best].label if pick.best in BEDS else pick.best
        lines.append(f"For E_F, pick the {label}: |error| median {_pct(pick.median[pick.best])}, 90th percentile "
                     f"{_pct(pick.p90[pick.best])} over {pick.points} points.")
    for soil, (n, best, med, p90) in pick.soils.items():
        if best is not None:
            lines.append(f"- {soil} ({n} points): `{best}`, median {_pct(med)}, 90th "
                         f"percentile {_pct(p90)}.")
    return lines


def energy_numbers(pick: EnergyPick | None) -> dict | None:
    """The section's numbers for summary.json (fractions; None: not compared)."""
    if pick is None:
        return None

    def clean(mapping):
        return {k: (v if math.isfinite(v) else None) for k, v in mapping.items()}

    return {"points": pick.points, "best": pick.best, "median": clean(pick.median),
            "p90": clean(pick.p90), "signed_median": clean(pick.bias),
            "by_soil": {soil: {"points": n, "best": best,
                               "median": med if math.isfinite(med) else None,
                               "p90": p90 if math.isfinite(p90) else None}
                        for soil, (n, best, med, p90) in pick.soils.items()}}
