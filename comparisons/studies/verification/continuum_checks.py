"""The continuum's anchors: rocking stiffness, Flamant's compliance, Prandtl's capacity and
the uplift-onset eccentricity."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ....anchors import (HALF_PLANE_ONSET_ECCENTRICITY, TOLERANCES, WINKLER_ONSET_ECCENTRICITY,
                         flamant_compliance_slope, half_plane_onset_rotation,
                         half_plane_rocking_stiffness, prandtl_capacity)
from .records import (C, FAIL, Order, Row, SKIP, absolute_row, bound_row, order_row, relative_row,
                      skipped_row)


# ---------------------------------------------------------------------------------------------
# Continuum
# ---------------------------------------------------------------------------------------------

E_SOIL, NU, B = 50e3, 0.3, 2.0  # kPa, -, m (the strip_footing_clay scene's soil)
G_SOIL = E_SOIL / (2 * (1 + NU))
CU = 50.0
N_SCENE = 171.39  # kN/m, FS_v = 3


def _elastic_soil(interface="frictionless", **kw):
    from ....scenes import Soil

    return Soil(youngs_modulus=E_SOIL, poisson_ratio=NU, density=1.8, model="elastic",
                interface=interface, **kw)


def _model(soil, **options):
    from ....continuum import make_model
    from ....scenes import ContinuumOptions

    return make_model(soil, B, ContinuumOptions(**options))


def rocking_stiffness(ctx) -> tuple[list[Row], list[Order]]:
    """K_r = πGB²/(8(1 − ν)) on the default mesh (Q2 reduced, 16 across, 10B box), 1 %; and
    the O(h) convergence of full 3×3 integration at 4, 8, 16 across."""
    from ....continuum import footing_stiffness

    k_r = half_plane_rocking_stiffness(G_SOIL, B, NU)
    soil = _elastic_soil()
    default = footing_stiffness(_model(soil, elements_across=16)).rocking
    ns = np.array([4, 8, 16])
    full = np.array([footing_stiffness(_model(soil, elements_across=int(n), intorder=4)).rocking
                     for n in ns])
    rows = [relative_row(C, "K_r", "rocking stiffness K_r, Q2 (2×2), 16 across B",
                         "anchor §4, πGB²/(8(1 − ν))", default, k_r,
                         TOLERANCES["rocking_stiffness"].value),
            relative_row(C, "K_r_richardson", "K_r, full integration, Richardson 2K(16) − K(8)",
                         "anchor §4", 2 * full[-1] - full[-2], k_r, 0.002)]
    orders = [order_row(C, "K_r, Q2 full integration (h = B/n)", "Q2 3×3", 1.0 / ns,
                        full / k_r - 1.0, "1 (edge singularity)", 0.85, 1.15)]
    return rows, orders


def flamant(ctx) -> list[Row]:
    """d(1/K_v)/d ln L = (1 − ν)/(π G) over boxes 5B … 40B (Q2 8 across), 2 %."""
    from ....continuum import footing_stiffness

    sizes = np.array([5.0, 10.0, 20.0, 40.0])
    compliance = [1.0 / footing_stiffness(_model(_elastic_soil(), elements_across=8,
                                                 domain_width=s, domain_depth=s)).vertical
                  for s in sizes]
    slope = np.polyfit(np.log(sizes), compliance, 1)[0]
    return [relative_row(C, "flamant", "vertical compliance slope d(1/K_v)/d ln L, boxes 5B–40B",
                         "anchor §4 (Flamant), (1 − ν)/(πG)", slope,
                         flamant_compliance_slope(G_SOIL, NU), TOLERANCES["flamant"].value)]


def _prandtl_error(element: str, n: int) -> np.ndarray:
    from ....continuum import vertical_pushover
    from ....scenes import Soil

    soil = Soil(youngs_modulus=E_SOIL, poisson_ratio=NU, density=1.8, model="tresca",
                undrained_strength=CU, interface="bonded")
    path = vertical_pushover(_model(soil, element=element, elements_across=n),
                             np.linspace(0.0, 0.1, 11)[1:])
    return path.N / prandtl_capacity(CU, B) - 1.0


def prandtl(ctx) -> tuple[list[Row], list[Order]]:
    """(2 + π) c_u for a rough strip on Tresca clay, settlement to 0.1 m in 10 steps; FE
    converges from above at O(h). P1 on the same grid locks."""
    ref = "anchor §4, (2 + π) c_u = 257.08 kPa"
    q8 = _prandtl_error("Q2", 8)
    rows = [bound_row(C, "prandtl_8", "Prandtl q_u, Q2, 8 across B (error, from above)", ref,
                      q8[-1], 0.0, TOLERANCES["prandtl_coarse"].value,
                      "coarse mesh: O(h) overshoot, own tolerance 5 %")]
    orders = []
    if ctx.fast:
        rows += [skipped_row(C, "prandtl_16", "Prandtl q_u, Q2, 16 across B (error, from above)",
                             ref, "in [0, 0.02]", "full mode only (22 s); fast mode checks 8 "
                             "across at 5 %"),
                 skipped_row(C, "prandtl_richardson", "Prandtl, Richardson 2q(16) − q(8)", ref,
                             "abs(rel) ≤ 0.005", "full mode only")]
        orders.append(Order(C, "Prandtl q_u, Q2 (h = B/n)", "Q2 2×2", (), (), None,
                            "1 (O(h))", 0.7, 1.5, SKIP, "full mode only (8 and 16 across)"))
        p1 = _prandtl_error("P1", 8)
        q_ref, n = q8[-1], 8
    else:
        q16 = _prandtl_error("Q2", 16)
        rows += [bound_row(C, "prandtl_16", "Prandtl q_u, Q2, 16 across B (error, from above)",
                           ref, q16[-1], 0.0, TOLERANCES["prandtl"].value),
                 absolute_row(C, "prandtl_richardson", "Prandtl, Richardson 2q(16) − q(8) (rel. "
                              "error)", ref, 2 * q16[-1] - q8[-1], 0.0, 0.005)]
        orders.append(order_row(C, "Prandtl q_u, Q2 (h = B/n)", "Q2 2×2", B / np.array([8.0, 16.0]),
                                [q8[-1], q16[-1]], "1 (O(h))", 0.7, 1.5))
        p1 = _prandtl_error("P1", 16)
        q_ref, n = q16[-1], 16
    rows.append(bound_row(C, "p1_locking", f"P1 locks: P1 error / Q2 error, {n} across B "
                          f"(P1 {100 * p1[-1]:.1f} %, Q2 {100 * q_ref:.2f} %)",
                          "volumetric locking of constant-strain triangles", p1[-1] / q_ref,
                          5.0, math.inf, f"P1 error {p1[-1]:.3f} must also be > 0.10"
                          if p1[-1] > 0.10 else f"P1 error {p1[-1]:.3f} ≤ 0.10: no locking"))
    if p1[-1] <= 0.10:
        rows[-1] = dataclasses.replace(rows[-1], status=FAIL)
    return rows, orders


def uplift_eccentricity(ctx) -> list[Row]:
    """Elastic half-plane: uplift starts at e = M/N = B/4 (1 %), not Winkler's B/6."""
    from ....continuum import rotation_pushover, uplift_onset

    theta_on = half_plane_onset_rotation(N_SCENE, B, G_SOIL, NU)
    ratios = np.array([0.25, 0.5, 1.5, 2.0, 3.0, 5.0, 10.0])
    path = rotation_pushover(_model(_elastic_soil(), elements_across=16), N_SCENE,
                             ratios * theta_on)
    onset = uplift_onset(path)
    return [relative_row(C, "onset_e", "uplift-onset eccentricity e/B, Q2 16 across, 10B box",
                         "half-plane (Johnson 1985): 1/4", onset.e / B,
                         HALF_PLANE_ONSET_ECCENTRICITY, TOLERANCES["half_plane_onset"].value,
                         f"{100 * (onset.e / B / WINKLER_ONSET_ECCENTRICITY - 1):.0f} % above "
                         "Winkler's B/6"),
            relative_row(C, "onset_theta", "uplift-onset rotation θ_on", "2N(1 − ν)/(πGB)",
                         onset.theta, theta_on, TOLERANCES["half_plane_onset"].value)]
