"""The four base beds calibrated from the continuum's stiffness: uniform and end-stiffened,
elastic and elasto-plastic (:func:`calibrate`), and the end-stiffness ratio R_k that matches
both of the continuum footing's stiffnesses K_v and K_r (:func:`end_stiffening`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ... import checks
from ...checks import InputError
from ...reduced.compatibility import end_stiffened_bed, winkler_bed

__all__ = ["CALIBRATIONS", "LABELS", "EndStiffening", "end_zone", "end_stiffening",
           "Calibration", "calibrate"]

#: The base beds, in the order both Winkler studies list them, and their labels.
CALIBRATIONS = ("uniform", "end_stiffened", "uniform_plastic", "end_stiffened_plastic")
LABELS = {"uniform": "uniform bed (K_r)", "end_stiffened": "end-stiffened bed (K_r, K_v)",
          "uniform_plastic": "uniform bed, elasto-plastic (K_r, q_ult)",
          "end_stiffened_plastic": "end-stiffened bed, elasto-plastic (K_r, K_v, q_ult)"}


# ---------------------------------------------------------------------------------------------
# Calibration
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class EndStiffening:
    """R_k solving K_θ/K_v = ``target`` (length²) for a bed of ``springs`` with end length R_e:
    ``ratio`` the R_k used, ``exact`` the unbounded solution (inf or negative when no R_k
    exists), ``reachable`` the (low, high) K_θ/K_v over R_k ∈ [1, R_k,max], ``feasible``
    whether ``target`` lies in it."""

    target: float
    ratio: float
    exact: float
    reachable: tuple[float, float]
    supremum: float
    feasible: bool


def _moment_ratio(half_width: float, springs: int, ratio: float, end_length: float) -> float:
    """K_θ/K_v (length²) of the end-stiffened bed of :mod:`upliftlab.reduced.compatibility`."""
    bed = end_stiffened_bed(half_width, 1.0, springs, ratio, end_length)
    return bed.rocking_stiffness / bed.vertical_stiffness


def end_zone(half_width: float, springs: int, end_length: float) -> np.ndarray:
    """Which springs of the end-stiffened bed are end springs (its own rule, probed); an
    :class:`InputError` if none or all are."""
    unit = winkler_bed(half_width, 1.0, springs)
    probe = end_stiffened_bed(half_width, 1.0, springs, 2.0, end_length)
    end = probe.stiffnesses > unit.stiffnesses * (1.0 + 1e-9)
    if not end.any() or end.all() or (end != end[::-1]).any():
        raise InputError(f"options.end_length = {end_length:g}: with options.springs = "
                         f"{springs} the end zones hold {int(end.sum()) or '0 (or all)'} of "
                         f"{springs} springs; "
                         "valid is a length whose end zones each hold the same number (≥ 1) of "
                         f"strip centres and leave one between, within [{2 / springs:g}, "
                         f"{1 - 2 / springs:g}] away from a strip centre (strips of "
                         f"{2 / springs:g} b)")
    return end


def end_stiffening(target: float, half_width: float, springs: int, end_length: float,
                   max_ratio: float) -> EndStiffening:
    """Solve for the end-stiffness ratio R_k whose bed has K_θ/K_v = ``target``.

    K_θ/K_v = (R_k A_e + A_m)/(R_k W_e + W_m), with W and A the summed strip widths and
    width·x² of the end (e) and middle (m) springs, so R_k = (A_m − ρ W_m)/(ρ W_e − A_e) in
    closed form; R_k → ∞ reaches A_e/W_e < b² at most. Outside [1, ``max_ratio``] the nearest
    bound is used and ``feasible`` is False. The bed is built by
    :func:`~upliftlab.reduced.compatibility.end_stiffened_bed` (its end-zone rule).
    """
    checks.positive("target K_r/K_v", target)
    unit = winkler_bed(half_width, 1.0, springs)
    end = end_zone(half_width, springs, end_length)
    w, x2 = unit.widths, unit.positions ** 2
    W_e, W_m, A_e, A_m = w[end].sum(), w[~end].sum(), (w * x2)[end].sum(), (w * x2)[~end].sum()
    denominator = target * W_e - A_e
    exact = (A_m - target * W_m) / denominator if denominator < 0 else math.inf
    low = _moment_ratio(half_width, springs, 1.0, end_length)
    high = _moment_ratio(half_width, springs, max_ratio, end_length)
    feasible = bool(low <= target <= high)
    ratio = float(min(max(exact, 1.0), max_ratio))
    if feasible:
        got = _moment_ratio(half_width, springs, ratio, end_length)
        if abs(got / target - 1.0) > 1e-9:
            raise RuntimeError(f"end stiffening: R_k = {ratio:g} gives K_θ/K_v = {got:.12g}, "
                               f"not {target:.12g}")
    return EndStiffening(float(target), ratio, float(exact), (low, high), float(A_e / W_e),
                         feasible)


@dataclass(frozen=True)
class Calibration:
    """A bed calibrated from the continuum: ``layout`` (``winkler`` or ``end_stiffened``),
    ``law``, total ``vertical_stiffness`` K_v and bonded ``rocking_stiffness`` K_θ of the bed
    (as built), ``end_stiffness_ratio`` R_k and ``end_length`` R_e (fraction of b),
    ``yield_multiple`` FS_v (elasto-plastic), ``matches`` the continuum quantities it was
    calibrated to, and ``note`` (e.g. why K_v is missed)."""

    name: str
    label: str
    layout: str
    law: str
    springs: int
    half_width: float
    vertical_stiffness: float
    rocking_stiffness: float
    end_stiffness_ratio: float = 1.0
    end_length: float = 0.0
    yield_multiple: float = 3.0
    matches: tuple[str, ...] = ()
    note: str = ""
    stiffening: EndStiffening | None = None

    def foundation_table(self) -> dict:
        """The reduced model's ``[foundation]`` table of this bed."""
        table = {"support": "uplift", "half_width": self.half_width, "layout": self.layout,
                 "springs": self.springs, "stiffness": self.vertical_stiffness,
                 "law": self.law, "yield_multiple": self.yield_multiple}
        if self.layout == "end_stiffened":
            table.update(end_stiffness_ratio=self.end_stiffness_ratio,
                         end_length=self.end_length)
        return table


def _bed_stiffnesses(layout: str, b: float, springs: int, K_v: float, R_k: float,
                     R_e: float) -> tuple[float, float]:
    bed = (winkler_bed(b, K_v, springs) if layout == "winkler"
           else end_stiffened_bed(b, K_v, springs, R_k, R_e))
    return bed.vertical_stiffness, bed.rocking_stiffness


def calibrate(ref, options) -> tuple[Calibration, ...]:
    """The four base beds, calibrated from the continuum: ``ref`` has the footing width ``B``
    (length), the vertical load ``N`` and capacity ``N_ult`` (force/length) and the footing's
    stiffnesses in full contact ``K_v`` (force/length²) and ``K_r`` (force·length/rad per
    length); ``options`` the beds' ``springs``, ``end_length`` R_e (a fraction of b) and
    ``max_end_stiffness_ratio`` R_k,max. The uniform beds match K_r, the end-stiffened ones
    K_r and K_v where an R_k reaches both; the elasto-plastic ones yield at FS_v = N_ult/N
    times their static force."""
    b, n = 0.5 * ref.B, options.springs
    uniform = winkler_bed(b, 1.0, n)
    Kv_uniform = ref.K_r / uniform.rocking_stiffness
    fs = ref.N_ult / ref.N
    stiff = end_stiffening(ref.K_r / ref.K_v, b, n, options.end_length,
                           options.max_end_stiffness_ratio)
    Kv_end = ref.K_r / _moment_ratio(b, n, stiff.ratio, options.end_length)
    if stiff.feasible:
        note, end_matches = "", ("K_r", "K_v")
    else:
        note = (f"no R_k in [1, {options.max_end_stiffness_ratio:g}] reaches K_r/K_v = "
                f"{stiff.target:.4g} (reachable {stiff.reachable[0]:.4g} to "
                f"{stiff.reachable[1]:.4g}; R_k → ∞ gives {stiff.supremum:.4g}, and no bed under "
                f"the footing exceeds b² = {b * b:.4g}): R_k = {stiff.ratio:g} is used, K_r is "
                f"matched and K_v is {Kv_end / ref.K_v:.3g} × the domain's")
        end_matches = ("K_r",)
    rows = []
    for name, layout, Kv, R_k, matches in (
            ("uniform", "winkler", Kv_uniform, 1.0, ("K_r",)),
            ("end_stiffened", "end_stiffened", Kv_end, stiff.ratio, end_matches)):
        for plastic in (False, True):
            kv, kr = _bed_stiffnesses(layout, b, n, Kv, R_k, options.end_length)
            key = f"{name}_plastic" if plastic else name
            rows.append(Calibration(
                key, LABELS[key], layout, "elastoplastic" if plastic else "elastic", n, b, kv,
                kr, R_k, options.end_length if layout == "end_stiffened" else 0.0,
                fs if plastic else 3.0, matches + (("N_ult",) if plastic else ()),
                note if layout == "end_stiffened" else "",
                stiff if layout == "end_stiffened" else None))
    return tuple(sorted(rows, key=lambda c: CALIBRATIONS.index(c.name)))
