"""The map's foundation energy: each bed's E_F against the continuum's, where the continuum's
energy run of a point is stored (:mod:`.energy_points`, :mod:`.foundation_energy`).

E_F is the energy the structure lost to its foundation over the run: a bed's dashpot, impact and
plastic work and the change of its springs' energy; the continuum soil's plastic work, the
waves the footing sent into it and the change of its elastic energy. Part of it is the work of
the structure's weight as the footing settles (W times the residual settlement); the rest,
E_M = E_F − W s, is what the foundation took of the ground motion's input (the input less
what the structure keeps or its story dashpot takes): the foundation's damping of the motion.
Both are compared (:data:`ENERGIES`). Their error floor is :data:`.grid.FLOOR_FRACTION` × the
strain energy of a uniform bed at its uplift threshold, ½ M_up θ_up = ½ (N B/6)²/K_r
(:func:`energy_scale`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...beds import BEDS
from .parts import point_values

__all__ = ["ENERGIES", "ENERGY_LABELS", "ENERGY_SYMBOLS", "EnergyPick", "energy_scale",
           "energies_of",
           "same_run", "energy_picks", "energy_lines", "energy_numbers", "RUN_TOLERANCE"]

#: The energies compared: E_F, and E_M = E_F less the work of the weight (:func:`energies_of`).
ENERGIES = ("foundation_energy", "motion_energy")
ENERGY_LABELS = {"foundation_energy": "foundation energy E_F",
                 "motion_energy": "E_M, from the motion"}
ENERGY_SYMBOLS = {"foundation_energy": "E_F", "motion_energy": "E_M"}

#: The largest relative difference allowed between a measure of a point's energy run and of
#: its dynamic run: the same run of the same code, deterministic on one thread, so equal.
RUN_TOLERANCE = 1e-9


def energy_scale(N: float, B: float, K_r: float) -> float:
    """½ M_up θ_up = ½ (N B/6)²/K_r: the rocking strain energy of a uniform tensionless bed of
    rocking stiffness K_r at its uplift threshold (force·length per length)."""
    moment = N * B / 6.0
    return 0.5 * moment * moment / K_r


def energies_of(terms: dict) -> tuple[float, float]:
    """(E_F, E_M) of a run's energy terms: ``foundation`` E_F and ``gravity`` the work of the
    weight in it (force·length per length)."""
    return float(terms["foundation"]), float(terms["foundation"] - terms["gravity"])


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
    """One energy of :data:`ENERGIES` over the points with a continuum energy run
    (``points``): each calibration's |error| ``median`` and ``p90`` and its signed median
    ``bias`` (fractions), the ``best`` calibration (smallest median, then p90; None if no bed
    was compared) and per soil (``soils``: {soil: (points, best, median, p90)})."""

    quantity: str
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


def energy_picks(ds) -> tuple[EnergyPick, ...]:
    """The error distribution of each energy of :data:`ENERGIES` per calibration
    (:class:`EnergyPick`) over the points whose continuum energy run is stored, from the map
    dataset ``ds``; empty when the map holds none."""
    if not any(np.isfinite(ds[f"continuum_{q}"].values).any() for q in ENERGIES):
        return ()
    return tuple(_pick(ds, quantity) for quantity in ENERGIES)


def _pick(ds, quantity: str) -> EnergyPick:
    errors = point_values(ds, f"{quantity}_error", "calibration")
    continuum = point_values(ds, f"continuum_{quantity}")
    calibrations = tuple(str(c) for c in ds["calibration"].values)
    median, p90, bias = {}, {}, {}
    for c, name in enumerate(calibrations):
        median[name], p90[name], bias[name] = _stats(errors[..., c].ravel())
    soils = {}
    for s, soil in enumerate(str(v) for v in ds["soil"].values):
        n = int(np.isfinite(continuum[s]).sum())
        if n:
            stats = {name: _stats(errors[s, ..., c].ravel())
                     for c, name in enumerate(calibrations)}
            best = _rank({k: v[0] for k, v in stats.items()},
                         {k: v[1] for k, v in stats.items()}, calibrations)
            soils[soil] = (n, best, stats[best][0] if best else math.nan,
                           stats[best][1] if best else math.nan)
    return EnergyPick(quantity, int(np.isfinite(continuum).sum()), median, p90, bias,
                      _rank(median, p90, calibrations), soils)


def _pct(value: float) -> str:
    return "n/a" if not math.isfinite(value) else f"{100 * value:.1f} %"


def energy_lines(ds, picks: tuple[EnergyPick, ...]) -> list[str]:
    """The summary's section on E_F and E_M (markdown lines) of the map dataset ``ds``."""
    intro = ("E_F is the energy the structure lost to its foundation over the run, from the "
             "structure's own side of the balance (the ground's input less the change of its "
             "kinetic, story and gravity energy and its story dashpot's work): a bed's dashpot, "
             "impact and plastic work and the change of its springs' energy; the continuum "
             "soil's plastic work, the waves the footing sent into it and the change of its "
             "elastic energy. It is the foundation's damping as the structure sees it. E_M is "
             "E_F less the work of the structure's weight as the footing settles (W times the "
             "residual settlement): what the foundation took of the motion's input. The "
             "continuum's own energy account cannot give the soil's dissipation apart: it "
             "books plastic work with stored elastic energy, and the soil's own free-field "
             "response with them. Errors are relative, with the floor "
             "0.1 × ½ (N B/6)²/K_r (a uniform bed's strain energy at its uplift threshold).")
    total = ds["continuum_wall_time"].size
    if not picks:
        return [intro, "", f"No point of this map has a continuum energy run stored (0 of "
                           f"{total}): E_F is not compared. Run the map with --energy to make "
                           "them (one more continuum run per point)."]
    f, m = picks
    lines = [intro, "", f"Points with the continuum's E_F: {f.points} of {total}.", "",
             "| calibration | E_F: median of the error's size (%) | 90th percentile (%) | "
             "signed median (%) | E_M: median of the error's size (%) | 90th percentile (%) | "
             "signed median (%) |", "|---|---|---|---|---|---|---|"]
    for name in (str(c) for c in ds["calibration"].values):
        lines.append(f"| `{name}` | {_pct(f.median[name])} | {_pct(f.p90[name])} | "
                     f"{_pct(f.bias[name])} | {_pct(m.median[name])} | {_pct(m.p90[name])} | "
                     f"{_pct(m.bias[name])} |")
    lines.append("")
    with np.errstate(divide="ignore", invalid="ignore"):
        held = (ds["continuum_energy_left"].values
                / np.abs(ds[f"continuum_{ENERGIES[1]}"].values))
    held = held[np.isfinite(held)]
    if held.size:
        lines += [f"Both are taken at the end of the run. There the continuum's structure "
                  f"still holds (kinetic and story energy) a median {_pct(float(np.median(held)))} "
                  f"of its E_M (90th percentile {_pct(float(np.percentile(held, 90)))}): where "
                  "it still rocks, part of E_F is energy swinging between the structure and its "
                  "foundation, not yet dissipated, in both models.", ""]
    for pick in picks:
        if pick.best is None:
            continue
        label = BEDS[pick.best].label if pick.best in BEDS else pick.best
        lines.append(f"For {ENERGY_LABELS[pick.quantity]}, pick the {label}: |error| median "
                     f"{_pct(pick.median[pick.best])}, 90th percentile "
                     f"{_pct(pick.p90[pick.best])} over {pick.points} points.")
        for soil, (n, best, med, p90) in pick.soils.items():
            if best is not None:
                lines.append(f"- {soil} ({n} points): `{best}`, median {_pct(med)}, 90th "
                             f"percentile {_pct(p90)}.")
        lines.append("")
    return lines


def energy_numbers(picks: tuple[EnergyPick, ...]) -> dict | None:
    """The section's numbers for summary.json (fractions; None: not compared)."""
    if not picks:
        return None

    def clean(mapping):
        return {k: (v if math.isfinite(v) else None) for k, v in mapping.items()}

    return {pick.quantity: {
        "points": pick.points, "best": pick.best, "median": clean(pick.median),
        "p90": clean(pick.p90), "signed_median": clean(pick.bias),
        "by_soil": {soil: {"points": n, "best": best,
                           "median": med if math.isfinite(med) else None,
                           "p90": p90 if math.isfinite(p90) else None}
                    for soil, (n, best, med, p90) in pick.soils.items()}}
        for pick in picks}
