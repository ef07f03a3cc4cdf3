"""The error table of each bed against the continuum (:func:`error_table`, computed from the
runs; :func:`table_of`, read back from the study's dataset), and the recommendation drawn from
it (:func:`recommend`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ....scenes import Scene
from ...framework.study import relative_error
from ...beds.pushover import FLOORS, BedResponse, path_values
from .dynamics import DYNAMIC_LABELS, DYNAMIC_MEASURES
from .options import Options
from .reference import ContinuumReference


# ---------------------------------------------------------------------------------------------
# Error table and recommendation
# ---------------------------------------------------------------------------------------------


def quantity_names(theta_ratios, motions=()) -> list[tuple[str, str, str]]:
    """(key, label, group) of every compared quantity, in the error table's order: the static
    ones at ``theta_ratios`` (θ/θ_on), then the peaks of each dynamic run of ``motions``."""
    q = [("K_r", "K_r", "bonded stiffness"), ("K_v", "K_v", "bonded stiffness"),
         ("onset_moment", "uplift-onset M", "uplift onset")]
    q += [(f"M_{r:g}", f"M at {r:g} θ_on", "monotonic M–θ") for r in theta_ratios]
    q += [(f"contact_{r:g}", f"c at {r:g} θ_on", "contact length") for r in theta_ratios]
    q.append(("settlement_0", "settlement under N", "settlement"))
    q += [(f"settlement_{r:g}", f"settlement at {r:g} θ_on", "settlement") for r in theta_ratios]
    q += [("N_ult", "N_ult", "capacity"), ("M_max", "largest M (pushover)", "capacity"),
          ("cyclic_M", "cyclic peak M (worst)", "cyclic M–θ"),
          ("cyclic_energy", "cyclic dissipated energy", "cyclic M–θ"),
          ("cyclic_settlement", "settlement over the cycles", "cyclic M–θ")]
    q += [(f"{key}_{m}", f"{DYNAMIC_LABELS[m]} ({key})", f"dynamics ({key})")
          for key in motions for m in DYNAMIC_MEASURES]
    return q


def quantity_floors(ref: ContinuumReference, scene: Scene, theta_ratios, motions=()
                    ) -> list[float]:
    """The error floor of each quantity of :func:`quantity_names` (same order): moments
    0.01 N B, contact 0.05 B, settlements 0.1 × the continuum's settlement under N, energy
    0.01 N B θ_on (:data:`FLOORS`); dynamic peaks 0.1 × θ_on (θ), 0.1 × the story deformation
    at the Winkler bed's quasi-static uplift, (N B/6)/(h k) (u), and 0.1 × the settlement
    under N (uplift, residual settlement); none for K_r, K_v, N_ult."""
    NB, s0, n = ref.N * ref.B, abs(ref.monotonic["settlement"][0]), len(theta_ratios)
    moment, settle = FLOORS["moment"] * NB, FLOORS["settlement"] * s0
    floors = ([0.0, 0.0, moment] + [moment] * n + [FLOORS["contact"] * ref.B] * n
              + [settle] * (n + 1) + [0.0, moment, moment,
                                      FLOORS["energy"] * NB * ref.theta_on, settle])
    k = scene.structure.stories[-1].stiffness
    dynamic = {"theta": 0.1 * ref.theta_on, "u": 0.1 * ref.N * ref.B / (6.0 * ref.h * k),
               "uplift": 0.1 * s0, "residual_settlement": 0.1 * s0}
    return floors + [dynamic[m] for _ in motions for m in DYNAMIC_MEASURES]


@dataclass(frozen=True, eq=False)
class ErrorTable:
    """Signed relative errors (bed − continuum)/max(|continuum|, floor) of each calibration
    (rows, :data:`...beds.CALIBRATIONS` order) in each quantity (columns): ``errors`` (ncal, nq),
    ``values`` (ncal, nq) the beds' values and ``reference`` (nq) the continuum's (units of the
    scene; N_ult of elastic springs is inf, its error NaN: no capacity)."""

    calibrations: tuple[str, ...]
    quantities: tuple[str, ...]
    labels: tuple[str, ...]
    groups: tuple[str, ...]
    floors: np.ndarray
    reference: np.ndarray
    values: np.ndarray
    errors: np.ndarray

    def error(self, calibration: str, quantity: str) -> float:
        return float(self.errors[self.calibrations.index(calibration),
                                 self.quantities.index(quantity)])


def error_table(ref: ContinuumReference, beds: Sequence[BedResponse], options: Options,
                scene: Scene, runs: Sequence = ()) -> ErrorTable:
    """The error table of every calibration against the continuum (package docstring), with
    the peaks of the dynamic ``runs`` (:class:`.dynamics.DynamicRun`) on ``scene``."""
    motions = [run.key for run in runs]
    spec = [(*names, floor) for names, floor in zip(
        quantity_names(options.theta_ratios, motions),
        quantity_floors(ref, scene, options.theta_ratios, motions))]
    mono = dict(ref.monotonic, _theta_on=ref.theta_on)
    cont = {"K_r": ref.K_r, "K_v": ref.K_v, "onset_moment": _onset_moment(ref),
            "N_ult": ref.N_ult, **path_values(mono, ref.cyclic, options.theta_ratios)}
    for run in runs:
        cont.update({f"{run.key}_{m}": run.continuum["peaks"][m] for m in DYNAMIC_MEASURES})
    rows, vals = [], []
    for bed in beds:
        v = {"K_r": bed.K_r, "K_v": bed.K_v, "onset_moment": bed.onset_moment,
             "N_ult": bed.N_ult,
             **path_values(dict(bed.monotonic, _theta_on=ref.theta_on), bed.cyclic,
                           options.theta_ratios)}
        for run in runs:
            peaks = run.beds[bed.calibration.name]["peaks"]
            v.update({f"{run.key}_{m}": peaks[m] for m in DYNAMIC_MEASURES})
        err = []
        for key, _, _, floor in spec:
            if key == "cyclic_M":
                e = [relative_error(a, c, floor) for a, c in zip(v["_cyclic_peaks"],
                                                                 cont["_cyclic_peaks"])]
                k = int(np.argmax(np.abs(e)))
                err.append(e[k])
                v["cyclic_M"] = float(v["_cyclic_peaks"][k])
                continue
            err.append(relative_error(v[key], cont[key], floor) if math.isfinite(v[key])
                       else math.nan)
        rows.append(err)
        vals.append([v[key] for key, *_ in spec])
    peaks = cont["_cyclic_peaks"]
    cont["cyclic_M"] = float(peaks[int(np.argmax(np.abs(peaks)))])
    return ErrorTable(tuple(b.calibration.name for b in beds), tuple(s[0] for s in spec),
                      tuple(s[1] for s in spec), tuple(s[2] for s in spec),
                      np.array([s[3] for s in spec]),
                      np.array([cont[key] for key, *_ in spec], dtype=float),
                      np.array(vals, dtype=float), np.array(rows, dtype=float))


def table_of(ds) -> ErrorTable:
    """The error table held by the study's ``comparison`` dataset (:mod:`.dataset`): its
    arrays as written, the labels and groups of :func:`quantity_names` (the dataset's are
    ASCII)."""
    quantities = tuple(str(q) for q in ds.quantity.values)
    motions = texts(ds.attrs.get("motions", ""))
    names = quantity_names(np.atleast_1d(ds.attrs["theta_ratios"]).tolist(), motions)
    if tuple(n[0] for n in names) != quantities:
        raise ValueError(f"the dataset's quantities {quantities} are not the study's")
    return ErrorTable(tuple(str(c) for c in ds.calibration.values), quantities,
                      tuple(n[1] for n in names), tuple(n[2] for n in names),
                      np.array([ds[f"reference_{q}"].attrs["error_floor"] for q in quantities],
                               dtype=float),
                      np.array([ds[f"reference_{q}"].item() for q in quantities], dtype=float),
                      np.stack([ds[f"value_{q}"].values for q in quantities], axis=1),
                      np.asarray(ds.error.transpose("calibration", "quantity").values))


def texts(value) -> list[str]:
    """A list-of-text attribute as a list (NetCDF gives one item back as text, none as '')."""
    if isinstance(value, str):
        return [value] if value else []
    return [str(v) for v in np.atleast_1d(value)]


def _onset_moment(ref: ContinuumReference) -> float:
    onset = ref.onset("monotonic")
    return float(onset["M"]) if "M" in onset else math.nan


@dataclass(frozen=True)
class Recommendation:
    """Which calibration to pick: ``per_quantity`` quantity -> the best calibrations (ties
    within 1e-9), ``per_group`` question -> (best calibration, its largest |error| over the
    question's quantities, runner-up, its largest |error|), and the ``text``."""

    per_quantity: dict
    per_group: dict
    text: str


def recommend(table: ErrorTable, adequate: float = 0.10) -> Recommendation:
    """The calibration with the smallest |error| per quantity, and per question (group) the
    calibration whose largest |error| over the group's quantities is smallest; the text says
    whether that error is within ``adequate``. NaN (no value) counts as worse than any
    number."""
    e = np.where(np.isfinite(table.errors), np.abs(table.errors), np.inf)
    per_quantity = {}
    for j, q in enumerate(table.quantities):
        best = e[:, j].min()
        per_quantity[q] = [c for i, c in enumerate(table.calibrations)
                           if e[i, j] <= best + 1e-9] if math.isfinite(best) else []
    per_group, lines = {}, []
    for group in dict.fromkeys(table.groups):
        cols = [j for j, g in enumerate(table.groups) if g == group]
        worst = e[:, cols].max(axis=1)
        order = np.argsort(worst, kind="stable")
        first, second = int(order[0]), int(order[1]) if order.size > 1 else int(order[0])
        per_group[group] = (table.calibrations[first], float(worst[first]),
                            table.calibrations[second], float(worst[second]))
        names = ", ".join(table.labels[j] for j in cols)
        if not math.isfinite(worst[first]):
            lines.append(f"- **{group}** ({names}): no calibration gives every quantity.")
            continue
        tied = [table.calibrations[i] for i in order if worst[i] <= worst[first] + 1e-9]
        pick = " or ".join(f"`{c}`" for c in tied)
        tail = (f"; next `{table.calibrations[second]}` at {pct(worst[second])}"
                if len(tied) == 1 and order.size > 1 else "")
        verdict = (f"within {pct(adequate)}" if worst[first] <= adequate else
                   f"no calibration within {pct(adequate)}")
        lines.append(f"- **{group}** ({names}): pick {pick}, largest error "
                     f"{pct(worst[first])} ({verdict}){tail}.")
    return Recommendation(per_quantity, per_group, "\n".join(lines))


def pct(value: float) -> str:
    return "—" if not math.isfinite(value) else f"{100 * value:.3g} %"


def signed_pct(value: float) -> str:
    return "—" if not math.isfinite(value) else f"{100 * value:+.3g} %"
