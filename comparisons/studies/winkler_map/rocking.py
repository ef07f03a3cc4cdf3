"""The map's statics rows: every bed's rocking pushovers against the continuum's, per soil and
FS_v — the M–θ backbone, the uplift-onset moment, the contact length and the settlement against
θ, and one cycle per amplitude (its dissipated work ∮ M dθ and the settlement it leaves).

The continuum's pushovers are two stored points per (soil, FS_v) (:func:`rocking_points`,
evaluated by the beds' continuum point function, :mod:`...beds.continuum_points`, so that both
Winkler studies push over the footing alike): a monotonic rotation path through θ_on to
max(``theta_ratios``) θ_on, and one full cycle at each of ``cycle_ratios`` θ_on, at N =
V_ult/FS_v; θ_on = 2N(1 − ν)/(π G B) is the elastic half-plane's uplift rotation, the scale of
every path. Each bed is pushed over on the same rotations by the reduced model
(:func:`...beds.pushover.bed_rocking`, live: milliseconds). The quantities, their floors and the
error measure are those of the Winkler-against-continuum study (:data:`QUANTITY_GROUPS`): a
quantity smaller than its floor is compared against the floor.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ....anchors import half_plane_onset_rotation
from ...framework.study import relative_error
from ...beds.continuum_points import floats
from ...beds.pushover import FLOORS, cyclic_path, path_values, rotation_path
from .grid import SOILS, Options
from .reference import reference_soil

__all__ = ["QUANTITY_GROUPS", "RockingData", "group_worst", "rocking_points",
           "pushover_points",
           "rocking_quantities", "rocking_data"]

#: The groups of statics quantities the issue names, and the quantity keys in each (``{r}``:
#: one per θ ratio).
QUANTITY_GROUPS = {"uplift onset": ("onset_moment",),
                   "M–θ backbone": ("M_{r}", "M_max"),
                   "contact length against θ": ("contact_{r}",),
                   "settlement against θ": ("settlement_0", "settlement_{r}"),
                   "cyclic dissipation": ("cyclic_energy",),
                   "cyclic settlement": ("cyclic_settlement",)}
_FREE = {"type": "free", "velocity": 1.0, "duration": 1.0}  # a scene's motion, unused


def theta_onset(N: float, soil: str, B: float) -> float:
    """θ_on = 2N(1 − ν)/(π G B) of ``soil`` (:data:`.grid.SOILS`) under N (rad)."""
    table = SOILS[soil]
    E, nu = table["youngs_modulus"], table["poisson_ratio"]
    return half_plane_onset_rotation(N, B, E / (2.0 * (1.0 + nu)), nu)


def _scene_table(base: Mapping, soil: str, options: Options, N: float) -> dict:
    data = copy.deepcopy(dict(base))
    data["soil"] = reference_soil(soil, options.reference)
    data["continuum"] = {**data.get("continuum", {}),
                         "elements_across": int(options.elements_across)}
    data["structure"] = {**data["structure"], "weight": float(N)}
    data["motion"] = dict(_FREE)
    return data


def rocking_points(base: Mapping, soil: str, N: float, options: Options) -> list[dict]:
    """The continuum's two rotation pushovers of ``soil`` under N (kN/m) on the options' mesh,
    as points of :func:`evaluate_continuum`: the cyclic path, then the monotonic one."""
    B = 2.0 * base["foundation"]["half_width"]
    return pushover_points(_scene_table(base, soil, options, N), N,
                           theta_onset(N, soil, B), options)


def pushover_points(table: Mapping, N: float, theta_on: float, options: Options) -> list[dict]:
    """The two rotation pushovers of a scene ``table`` (with its soil and mesh) under N, as
    points of :func:`evaluate_continuum`: one cycle per amplitude of ``options.cycle_ratios``,
    then the monotonic path, both scaled by ``theta_on`` (rad)."""
    return [{"scene": table, "soil": "scene", "analysis": "rotation", "N": float(N),
             "rotations": floats(path(theta_on, options))}
            for path in (cyclic_path, rotation_path)]


def rocking_quantities(options: Options) -> list[tuple[str, str]]:
    """(key, group) of every compared quantity, in :data:`QUANTITY_GROUPS` order."""
    out = []
    for group, keys in QUANTITY_GROUPS.items():
        for key in keys:
            out += ([(key.format(r=f"{r:g}"), group) for r in options.theta_ratios]
                    if "{r}" in key else [(key, group)])
    return out


def _floors(N: float, B: float, settlement_0: float, theta_on: float) -> dict:
    """The floor of each group (the Winkler-against-continuum study's): moments 0.01 N B,
    contact 0.05 B, settlement 0.1 × the continuum's settlement under N, dissipated work
    0.01 N B θ_on."""
    s0 = abs(settlement_0)
    return {"uplift onset": FLOORS["moment"] * N * B, "M–θ backbone": FLOORS["moment"] * N * B,
            "contact length against θ": FLOORS["contact"] * B,
            "settlement against θ": FLOORS["settlement"] * s0,
            "cyclic dissipation": FLOORS["energy"] * N * B * theta_on,
            "cyclic settlement": FLOORS["settlement"] * s0}


def _values(onset_moment: float, cyclic: Mapping, monotonic: Mapping, theta_on: float,
            options: Options) -> dict:
    values = path_values(dict(monotonic, _theta_on=theta_on), cyclic, options.theta_ratios)
    values["onset_moment"] = onset_moment
    return values


@dataclass(frozen=True, eq=False)
class RockingData:
    """The statics rows (module docstring): ``quantities`` and their ``groups``; ``continuum``
    (soil, fs_v, quantity) and ``beds`` (soil, fs_v, calibration, quantity) the values (kN m/m,
    m, kN m rad/m), ``floors`` (soil, fs_v, quantity), ``errors`` like ``beds``; ``theta_on``
    (soil, fs_v) the paths' scale (rad); ``failures`` the continuum pushovers that did not
    reach the path's end or find an onset (text)."""

    quantities: tuple[str, ...]
    groups: tuple[str, ...]
    continuum: np.ndarray
    beds: np.ndarray
    floors: np.ndarray
    errors: np.ndarray
    theta_on: np.ndarray
    failures: tuple[str, ...]

    def group_worst(self) -> np.ndarray:
        """(soil, calibration, group) the largest |error| over FS_v and the group's quantities
        (:func:`group_worst`)."""
        return group_worst(self.errors, self.groups)


def group_worst(errors: np.ndarray, groups, names=tuple(QUANTITY_GROUPS)) -> np.ndarray:
    """(soil, calibration, group) the largest |error| over FS_v and the group's quantities
    (NaN where none is finite), of ``errors`` (soil, fs_v, calibration, quantity) whose
    quantities belong to ``groups``; the groups in the order of ``names`` (those of
    :data:`QUANTITY_GROUPS`, as ``groups`` spells them)."""
    names = list(names)
    out = np.full(errors.shape[:1] + errors.shape[2:3] + (len(names),), np.nan)
    for g, name in enumerate(names):
        cols = [i for i, grp in enumerate(groups) if grp == name]
        block = np.abs(errors[..., cols])  # soil, fs, cal, q
        block = np.moveaxis(block, 1, 2).reshape(block.shape[0], block.shape[2], -1)
        with np.errstate(all="ignore"):
            finite = np.isfinite(block).any(axis=2)
            worst = np.nanmax(np.where(np.isfinite(block), block, -np.inf), axis=2)
        out[..., g] = np.where(finite, worst, np.nan)
    return out


def rocking_data(soils: Sequence[str], fs_v: Sequence[float], loads: np.ndarray,
                 records: Sequence[Mapping], bed_records: Sequence[Sequence[Mapping]],
                 B: float, options: Options, calibrations: int | None = None) -> RockingData:
    """The :class:`RockingData` from the continuum's ``records`` (two per (soil, fs_v), in
    :func:`rocking_points` order) and ``bed_records[i][c]``
    (:func:`...beds.pushover.bed_rocking` of bed c at the i-th (soil, fs_v); empty where the
    continuum's path stopped); ``loads`` (soil, fs_v) the vertical loads N; ``calibrations`` how many beds (default: the longest row)."""
    spec = rocking_quantities(options)
    keys, groups = tuple(k for k, _ in spec), tuple(g for _, g in spec)
    ns, nf = len(soils), len(fs_v)
    nc = calibrations if calibrations is not None else max(map(len, bed_records), default=0)
    cont = np.full((ns, nf, len(keys)), np.nan)
    floors = np.full_like(cont, np.nan)
    beds = np.full((ns, nf, nc, len(keys)), np.nan)
    theta_on = np.full((ns, nf), np.nan)
    failures = []
    for i in range(ns * nf):
        s, f = divmod(i, nf)
        N = float(loads[s, f])
        theta_on[s, f] = theta_onset(N, soils[s], B)
        cyclic, monotonic = records[2 * i], records[2 * i + 1]
        stopped = [f"{kind}: {r['error']}" for kind, r in (("cyclic", cyclic),
                                                             ("monotonic", monotonic))
                   if "error" in r]
        if stopped:
            failures.append(f"{soils[s]}, FS_v = {fs_v[f]:g}: the continuum's rotation "
                            f"pushover did not reach the path's end, so no statics row "
                            f"({'; '.join(stopped)})")
            continue
        onset = monotonic.get("onset", {})
        if "M" not in onset:
            failures.append(f"{soils[s]}, FS_v = {fs_v[f]:g}: no uplift onset on the continuum's "
                            f"monotonic path ({onset.get('error', 'not found')})")
        c_values = _values(float(onset.get("M", math.nan)), cyclic, monotonic, theta_on[s, f],
                           options)
        floor = _floors(N, B, c_values["settlement_0"], theta_on[s, f])
        cont[s, f] = [c_values[k] for k in keys]
        floors[s, f] = [floor[g] for g in groups]
        for c, bed in enumerate(bed_records[i]):
            b_values = _values(bed["onset_moment"], bed["cyclic"], bed["monotonic"],
                               theta_on[s, f], options)
            beds[s, f, c] = [b_values[k] for k in keys]
    errors = np.full_like(beds, np.nan)
    for idx in np.ndindex(*beds.shape[:3]):
        for q in range(len(keys)):
            value, ref = beds[idx + (q,)], cont[idx[:2] + (q,)]
            if math.isfinite(value) and math.isfinite(ref):
                errors[idx + (q,)] = relative_error(value, ref, floors[idx[:2] + (q,)])
    return RockingData(keys, groups, cont, beds, floors, errors, theta_on, tuple(failures))
