"""The closed-form checks met on the way (anchors §3–4): the continuum's K_r, onset and
capacity, the Winkler bed's rocking curve."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ....anchors import (half_plane_rocking, prandtl_capacity, vm_envelope_moment_ratio,
                         winkler_rocking)
from ...beds.pushover import BedResponse
from .options import WINKLER_ONSET
from .reference import ContinuumReference


def closed_form_checks(ref: ContinuumReference, beds: Sequence[BedResponse]) -> dict:
    """The anchor checks of the package docstring, as numbers."""
    NB = ref.N * ref.B
    out = {"K_r_closed_form": ref.K_r_closed_form,
           "K_r_error_vs_closed_form": ref.K_r / ref.K_r_closed_form - 1.0,
           "K_r_over_K_v": ref.K_r / ref.K_v, "half_width_squared": (0.5 * ref.B) ** 2}
    for which in ("elastic", "monotonic"):
        onset = ref.onset(which)
        out[f"continuum_{which}_onset_e_over_B"] = (onset["e"] / ref.B if "e" in onset
                                                    else math.nan)
    uniform = next(b for b in beds if b.calibration.name == "uniform")
    out["winkler_onset_e_over_B"] = uniform.onset_moment / NB
    out["winkler_onset_closed_form"] = WINKLER_ONSET
    n = uniform.calibration.springs
    out["winkler_onset_discrete_closed_form"] = WINKLER_ONSET * (1.0 + 1.0 / n)
    theta = np.asarray(uniform.monotonic["theta"])
    k = uniform.K_v / ref.B
    closed = winkler_rocking(theta, ref.N, ref.B, k)
    beyond = theta > closed["theta_up"]
    out["winkler_theta_up"] = float(closed["theta_up"])
    out["winkler_M_error_vs_closed_form"] = float(np.max(np.abs(
        uniform.monotonic["M"][1:] / closed["M"][1:] - 1.0)))
    out["winkler_settlement_error"] = float(np.max(np.abs(
        uniform.monotonic["settlement"] - closed["settlement"])) / (ref.N / (k * ref.B)))
    out["winkler_contact_error"] = float(np.max(np.abs(uniform.monotonic["contact"]
                                                       - closed["c"])) / ref.B)
    out["winkler_M_error_after_uplift"] = float(np.max(np.abs(
        uniform.monotonic["M"][beyond] / closed["M"][beyond] - 1.0))) if beyond.any() else None
    el = ref.elastic
    hp = half_plane_rocking(np.asarray(el["theta"]), ref.N, ref.B, ref.G, ref.nu)
    out["half_plane_M_error"] = float(np.max(np.abs(np.asarray(el["M"][1:]) - hp["M"][1:]))
                                      / NB)
    if ref.cu is not None:
        prandtl = prandtl_capacity(ref.cu, ref.B)
        v = ref.N / ref.N_ult
        out["prandtl_N_ult"] = prandtl
        out["N_ult_error_vs_prandtl"] = ref.N_ult / prandtl - 1.0
        out["vm_envelope_M_over_NB"] = vm_envelope_moment_ratio(v)
        out["continuum_M_max_over_NB"] = float(np.max(ref.monotonic["M"]) / NB)
    return out
