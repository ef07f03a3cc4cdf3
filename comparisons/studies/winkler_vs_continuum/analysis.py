"""The error table of each bed against the continuum, and the recommendation drawn from it."""

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


def _quantities(ref: ContinuumReference, options: Options) -> list[tuple[str, str, str, float]]:
    """(key, label, group, floor) of every compared quantity."""
    NB, s0 = ref.N * ref.B, abs(ref.monotonic["settlement"][0])
    q = [("K_r", "K_r", "bonded stiffness", 0.0), ("K_v", "K_v", "bonded stiffness", 0.0),
         ("onset_moment", "uplift-onset M", "uplift onset", FLOORS["moment"] * NB)]
    for r in options.theta_ratios:
        q.append((f"M_{r:g}", f"M at {r:g} θ_on", "monotonic M–θ", FLOORS["moment"] * NB))
    for r in options.theta_ratios:
        q.append((f"contact_{r:g}", f"c at {r:g} θ_on", "contact length",
                  FLOORS["contact"] * ref.B))
    q.append(("settlement_0", "settlement under N", "settlement", FLOORS["settlement"] * s0))
    for r in options.theta_ratios:
        q.append((f"settlement_{r:g}", f"settlement at {r:g} θ_on", "settlement",
                  FLOORS["settlement"] * s0))
    q += [("N_ult", "N_ult", "capacity", 0.0),
          ("M_max", "largest M (pushover)", "capacity", FLOORS["moment"] * NB),
          ("cyclic_M", "cyclic peak M (worst)", "cyclic M–θ", FLOORS["moment"] * NB),
          ("cyclic_energy", "cyclic dissipated energy", "cyclic M–θ",
           FLOORS["energy"] * NB * ref.theta_on),
          ("cyclic_settlement", "settlement over the cycles", "cyclic M–θ",
           FLOORS["settlement"] * s0)]
    return q


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


def dynamic_quantities(ref: ContinuumReference, scene: Scene, dynamics) -> list[tuple]:
    """(key, label, group, floor) of the dynamic peaks; floors 0.1 × θ_on (θ), 0.1 × the
    story deformation at the Winkler bed's quasi-static uplift, (N B/6)/(h k) (u), and 0.1 ×
    the continuum's settlement under N (uplift, residual settlement)."""
    s0 = abs(ref.monotonic["settlement"][0])
    k = scene.structure.stories[-1].stiffness
    floors = {"theta": 0.1 * ref.theta_on, "u": 0.1 * ref.N * ref.B / (6.0 * ref.h * k),
              "uplift": 0.1 * s0, "residual_settlement": 0.1 * s0}
    return [(f"{run.key}_{m}", f"{DYNAMIC_LABELS[m]} ({run.key})", f"dynamics ({run.key})",
             floors[m]) for run in dynamics.runs for m in DYNAMIC_MEASURES]


def error_table(ref: ContinuumReference, beds: Sequence[BedResponse],
                options: Options, dynamic: Sequence[tuple] = (), runs: Sequence = ()
                ) -> ErrorTable:
    """The error table of every calibration against the continuum (package docstring), with
    the ``dynamic`` quantities (:func:`dynamic_quantities`) of the dynamic ``runs``."""
    spec = _quantities(ref, options) + list(dynamic)
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
