"""The closed-form checks met on the way (anchors §3–4): the continuum's K_r, onset and
capacity, the Winkler bed's rocking curve, read from the study's ``comparison`` dataset
(:mod:`.dataset`)."""

from __future__ import annotations

import math

import numpy as np

from ....anchors import (half_plane_rocking, half_plane_rocking_stiffness, prandtl_capacity,
                         vm_envelope_moment_ratio, winkler_rocking)
from .options import WINKLER_ONSET


def closed_form_checks(ds) -> dict:
    """The anchor checks of the package docstring, as numbers, from the comparison dataset
    ``ds``: the continuum's scalars, the uniform bed's values in the error table and the
    monotonic paths of the uniform bed and of the elastic continuum."""
    N, B, G, nu = (ds[k].item() for k in ("N", "B", "G", "nu"))
    K_r, K_v, N_ult = (ds[k].item() for k in ("K_r", "K_v", "N_ult"))
    NB = N * B
    closed_form = half_plane_rocking_stiffness(G, B, nu)
    out = {"K_r_closed_form": closed_form, "K_r_error_vs_closed_form": K_r / closed_form - 1.0,
           "K_r_over_K_v": K_r / K_v, "half_width_squared": (0.5 * B) ** 2}
    for which, prefix in (("elastic", "elastic_"), ("monotonic", "")):
        e = ds[f"{prefix}onset_e"].item()
        out[f"continuum_{which}_onset_e_over_B"] = e / B if math.isfinite(e) else math.nan
    uniform = ds.sel(calibration="uniform", model="uniform")
    out["winkler_onset_e_over_B"] = uniform.value_onset_moment.item() / NB
    out["winkler_onset_closed_form"] = WINKLER_ONSET
    n = int(uniform.springs)
    out["winkler_onset_discrete_closed_form"] = WINKLER_ONSET * (1.0 + 1.0 / n)
    theta = ds.monotonic_theta.values
    M, settlement = uniform.M_monotonic.values, uniform.settlement_monotonic.values
    k = uniform.value_K_v.item() / B
    closed = winkler_rocking(theta, N, B, k)
    beyond = theta > closed["theta_up"]
    out["winkler_theta_up"] = float(closed["theta_up"])
    out["winkler_M_error_vs_closed_form"] = float(np.max(np.abs(M[1:] / closed["M"][1:] - 1.0)))
    out["winkler_settlement_error"] = float(np.max(np.abs(settlement - closed["settlement"]))
                                            / (N / (k * B)))
    out["winkler_contact_error"] = float(np.max(np.abs(uniform.contact_monotonic.values
                                                       - closed["c"])) / B)
    out["winkler_M_error_after_uplift"] = float(np.max(np.abs(
        M[beyond] / closed["M"][beyond] - 1.0))) if beyond.any() else None
    elastic = ds.M_monotonic.sel(model="continuum_elastic").values
    hp = half_plane_rocking(theta, N, B, G, nu)
    out["half_plane_M_error"] = float(np.max(np.abs(elastic[1:] - hp["M"][1:])) / NB)
    c_u = ds.c_u.item()
    if math.isfinite(c_u):
        prandtl = prandtl_capacity(c_u, B)
        out["prandtl_N_ult"] = prandtl
        out["N_ult_error_vs_prandtl"] = N_ult / prandtl - 1.0
        out["vm_envelope_M_over_NB"] = vm_envelope_moment_ratio(N / N_ult)
        out["continuum_M_max_over_NB"] = float(
            np.max(ds.M_monotonic.sel(model="continuum").values) / NB)
    return out
