"""The handbook formulas for a rigid strip on the elastic half-space (Gazetas 1991), written once,
each coefficient with its source, to set beside the exact and the FE impedance.

Source: G. Gazetas (1991), "Formulas and charts for impedances of surface and embedded
foundations", J. Geotech. Eng. 117(9), 1363–1381, Table 1 (surface foundation of any shape,
half-length L ≥ half-width b, a0 = ω b/V_s). A strip is the limit L/b → ∞, taken per unit
length (the totals divided by 2L). In that limit the closed forms of Table 1 give:

- vertical: K_z = (2GL/(1 − ν))(0.73 + 1.54 χ^0.75), χ = A_b/(4L²) → 0, so
  **K_v = 0.73 G/(1 − ν)** per unit length;
- horizontal (across the strip): K_y = (2GL/(2 − ν))(2 + 2.5 χ^0.85), so **K_h = 2G/(2 − ν)**;
- rocking in the strip's plane (about its long axis x):
  K_rx = (G/(1 − ν)) I_bx^0.75 (L/b)^0.25 (2.4 + 0.5 b/L), I_bx = (4/3) L b³, so
  **K_r = 1.2 (4/3)^0.75 G b²/(1 − ν) = 1.489 G b²/(1 − ν)** (the exact half-plane value is
  π G b²/(2(1 − ν)) = 1.571 G b²/(1 − ν): the fit is 5.2 % low for a strip);
- dynamic stiffness of rocking: **k_rx ≈ 1 − 0.20 a0** (a formula in Table 1);
- dashpots: C_z = ρ V_La A_b c̃_z, C_y = ρ V_s A_b c̃_y, C_rx = ρ V_La I_bx c̃_rx with
  **Lysmer's analog velocity V_La = 3.4 V_s/(π(1 − ν))**; per unit length A_b → B and
  I_bx → I = B³/12. The coefficients c̃_z, c̃_y, c̃_rx and k_z, k_y are *charts* in the paper
  (functions of a0, L/B and ν, drawn for ν = 1/3, and for c̃_y at ν = 0.3 and 0.5), not
  formulas; they tend to about 1 at high frequency. They are not reproduced here:
  :func:`handbook_strip` gives the closed forms and the dashpots at c̃ = 1, which is the
  handbook's high-frequency dashpot.

What the exact solution says instead (:mod:`.halfplane`, and anchors the FE impedance is tested
against): the dashpots tend to ρ V_p B (vertical), ρ V_s B (horizontal) and ρ V_p I (rocking);
V_La is an engineering approximation that is 17 % (ν = 0.25) to 19 % (ν = 1/3) below V_p; and
the 2D vertical and horizontal static stiffnesses do not exist (K_v and K_h tend to zero as
1/ln(1/a0)), so the handbook's K_v and K_h are representative values of a fit, which the FE
and exact impedances are normalised by only for comparison.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["HandbookStrip", "handbook_strip", "lysmer_analog_velocity", "ROCKING_FIT"]

#: K_r of the L/b → ∞ limit of Table 1, per unit length, in units of G b²/(1 − ν):
#: 2.4 (4/3)^0.75 / 2.
ROCKING_FIT = 1.2 * (4.0 / 3.0) ** 0.75


def lysmer_analog_velocity(shear_wave_velocity: float, poisson: float) -> float:
    """V_La = 3.4 V_s/(π(1 − ν)) (Gazetas 1991, Table 1, after Lysmer 1965)."""
    return 3.4 * shear_wave_velocity / (math.pi * (1.0 - poisson))


@dataclass(frozen=True)
class HandbookStrip:
    """The handbook's strip per unit length at frequencies ``a0``: static stiffnesses
    ``K_v``, ``K_h`` (force/length²) and ``K_r`` (force·length/rad per length); the rocking
    stiffness factor ``k_r`` (n); dashpots at c̃ = 1 ``C_v``, ``C_h`` (force·s/length²) and
    ``C_r`` (force·length·s/rad per length). Complex impedances by :meth:`impedance`."""

    a0: np.ndarray
    K_v: float
    K_h: float
    K_r: float
    k_r: np.ndarray
    C_v: float
    C_h: float
    C_r: float
    omega: np.ndarray

    def impedance(self, mode: str) -> np.ndarray:
        """K_j k_j + i ω C_j with the handbook's closed forms (k_v = k_h = 1 where the paper has
        only charts)."""
        K, k, C = {"v": (self.K_v, 1.0, self.C_v), "h": (self.K_h, 1.0, self.C_h),
                   "r": (self.K_r, self.k_r, self.C_r)}[mode]
        return K * k + 1j * self.omega * C


def handbook_strip(a0, *, shear_modulus: float, poisson: float, density: float,
                   width: float) -> HandbookStrip:
    """The closed forms of the module docstring for a strip of ``width`` B on soil of shear
    modulus G, Poisson's ratio ν and ``density`` ρ at a0 = ω (B/2)/V_s."""
    a0 = np.atleast_1d(np.asarray(a0, dtype=float))
    G, nu, rho, B = shear_modulus, poisson, density, width
    b = 0.5 * B
    vs = math.sqrt(G / rho)
    vla = lysmer_analog_velocity(vs, nu)
    return HandbookStrip(a0=a0, K_v=0.73 * G / (1.0 - nu), K_h=2.0 * G / (2.0 - nu),
                         K_r=ROCKING_FIT * G * b * b / (1.0 - nu), k_r=1.0 - 0.20 * a0,
                         C_v=rho * vla * B, C_h=rho * vs * B, C_r=rho * vla * B ** 3 / 12.0,
                         omega=a0 * vs / b)
