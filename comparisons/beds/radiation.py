"""Radiation dashpots for a Winkler bed, from the continuum's impedance or Gazetas' formulas.

A footing on soil radiates energy: its impedance K_j(ω) = K_j + iω C_j has dashpots C_v
(vertical), C_h (horizontal) and C_r (rocking), taken at one frequency ω. A bed of N vertical
springs at x_i with dashpots c_i has the vertical dashpot Σ c_i and the rocking dashpot
Σ c_i x_i² (about O, the bed being symmetric or not). Dashpots proportional to the springs'
stiffnesses (``foundation.damping_ratio``) cannot give both: their ratio is fixed by the
stiffness distribution, so matching C_v over- or under-damps rocking. Here they are
distributed as a **uniform part plus a concentration**,

    c_i = α w_i + β ε_i,

w_i the tributary width of spring i, with α, β ≥ 0 solved in closed form from Σ c_i = C_v and
Σ c_i x_i² = C_r (:func:`distribute`). The uniform part alone has the ratio
ρ_u = Σ w x²/Σ w (b²/3 for a fine uniform bed). Where C_r/C_v ≥ ρ_u the concentration sits at
the two outermost springs (ε_i = 1 there), up to the ends' ratio (x_first² + x_last²)/2; where
it is lower it sits at the spring or the two springs nearest the centre O, down to their ratio.
Outside these bounds no non-negative dashpots of this form exist (above the ends' ratio of a
symmetric bed, none under the footing at all), and the request is refused with the range. A
continuum's impedance
usually needs the centre: a 2D strip radiates much more vertically than in rocking at the low
frequencies of rocking structures (the clay strip of the scenes: C_r/C_v ≈ 0.02–0.05 b² at
a0 = 0.1–0.2, where the handbook's high-frequency dashpots give B²/12 = b²/3). A pair of
springs (N = 2) has no uniform part to split: its two dashpots are solved directly, which needs
x_1² ≠ x_2² (a symmetric pair at ±x has Σ c x² = x² Σ c, so it reproduces both only when
C_r/C_v = x²).

The dashpots come from the continuum's :class:`~upliftlab.continuum.impedance.analysis.Impedance`
(C_j = Im K_j/ω, linear in ω between its frequencies: :func:`impedance_dashpots`) or from the
handbook strip of :mod:`upliftlab.continuum.impedance.gazetas` (:func:`gazetas_dashpots`: the
high-frequency dashpots c̃ = 1, the same at every ω). The frequency is by default the
structure's rocking frequency on the bed (:func:`rocking_frequency`: its fundamental bonded mode
other than the vertical one). The horizontal dashpot C_h goes on the sway spring
(``foundation.sway_damping``); a frictionless interface has no horizontal impedance (C_h = 0);
the coupling Im K_hr has no element in the reduced model and is left out. Everything is per unit
length for a strip, as the
continuum's impedance and the strip scenes are. The result is plain numbers for the reduced
scene (:meth:`RadiationDashpots.foundation_keys`, :func:`with_radiation`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ...checks import InputError
from ...continuum.impedance.gazetas import handbook_strip
from ...reduced import build_model
from ...scenes import Scene

__all__ = ["RadiationDashpots", "distribute", "impedance_at", "impedance_dashpots",
           "gazetas_dashpots", "rocking_frequency", "radiation_dashpots", "with_radiation"]


@dataclass(frozen=True)
class RadiationDashpots:
    """Radiation dashpots of a bed at the circular frequency ``omega`` (rad/s): the targets
    ``C_v``, ``C_h`` (force·s/length) and ``C_r`` (force·length·s/rad), the bed's ``dashpots``
    c_i (force·s/length, from −b to +b), the uniform part ``uniform`` α (force·s/length per
    length of base), the ``concentrated`` β added at each spring ``where`` (``ends``,
    ``centre``, or ``pair`` for two springs solved directly, α and β NaN), and their
    ``source`` (``impedance`` or ``gazetas``)."""

    omega: float
    C_v: float
    C_h: float
    C_r: float
    dashpots: tuple[float, ...]
    uniform: float
    concentrated: float
    where: str
    source: str

    def foundation_keys(self, *, horizontal: bool = True) -> dict:
        """The ``[foundation]`` keys that put these dashpots into a reduced scene: every
        spring's dashpot (and ``damping_ratio`` 0), and C_h on the sway spring."""
        keys = {"dashpots": list(self.dashpots), "damping_ratio": 0.0}
        if horizontal:
            keys["sway_damping"] = self.C_h
        return keys


def distribute(positions, widths, C_v: float,
               C_r: float) -> tuple[np.ndarray, float, float, str]:
    """(c_i, α, β, where): dashpots c_i = α w_i + β ε_i at the springs ``positions`` x_i
    (sorted) with tributary ``widths`` w_i whose sum is C_v and whose Σ c_i x_i² is C_r, the
    concentration β at the ``ends`` or the ``centre`` (module docstring); an
    :class:`InputError` when no non-negative distribution of this form exists. A pair is
    solved directly (α, β NaN, ``pair``)."""
    x = np.asarray(positions, dtype=float)
    w = np.asarray(widths, dtype=float)
    if x.size < 2 or w.shape != x.shape or np.any(np.diff(x) <= 0) or np.any(w <= 0):
        raise InputError("radiation dashpots: expected at least 2 springs at increasing "
                         "positions with positive widths")
    if not (math.isfinite(C_v) and C_v > 0.0 and math.isfinite(C_r) and C_r >= 0.0):
        raise InputError(f"radiation dashpots: C_v = {C_v:g}, C_r = {C_r:g}; valid: C_v > 0, "
                         "C_r >= 0, finite")
    ratio = C_r / C_v
    if x.size == 2:
        return _pair(x, C_v, C_r, ratio)
    ends = np.zeros(x.size)
    ends[[0, -1]] = 1.0
    centre = (np.abs(x) <= np.min(np.abs(x)) + 1e-12 * np.max(np.abs(x))).astype(float)
    uniform = float(np.sum(w * x * x) / np.sum(w))      # the uniform part's C_r/C_v
    low = float(np.sum(centre * x * x) / np.sum(centre))  # the centre concentration's
    high = float(np.sum(ends * x * x) / 2.0)             # the end concentration's
    if not low * (1.0 - 1e-12) <= ratio <= high * (1.0 + 1e-12):  # a bound, to round-off
        where = "above the ends'" if ratio > high else "below the centre springs'"
        raise InputError(f"radiation dashpots: C_r/C_v = {ratio:.6g} (length²) is outside "
                         f"[{low:.6g}, {high:.6g}], the range of a uniform part plus a "
                         f"concentration at the centre or the ends of these {x.size} springs "
                         f"({where})")
    where = "ends" if ratio >= uniform else "centre"
    e = ends if where == "ends" else centre
    # Σ c = α W + β n = C_v, Σ c x² = α A + β E = C_r, solved by Cramer's rule
    W, A = float(np.sum(w)), float(np.sum(w * x * x))
    n, E = float(np.sum(e)), float(np.sum(e * x * x))
    det = W * E - n * A
    alpha = (C_v * E - n * C_r) / det
    beta = (W * C_r - A * C_v) / det
    alpha, beta = max(alpha, 0.0), max(beta, 0.0)  # −0 or round-off at either end of the range
    return alpha * w + beta * e, alpha, beta, where


def _pair(x: np.ndarray, C_v: float, C_r: float, ratio: float):
    """Two dashpots: c_1 + c_2 = C_v, c_1 x_1² + c_2 x_2² = C_r."""
    a, b = x[0] ** 2, x[1] ** 2
    if abs(a - b) <= 1e-12 * max(a, b):
        if abs(ratio / a - 1.0) > 1e-12:
            raise InputError(f"radiation dashpots: a pair at ±{math.sqrt(a):.6g} has "
                             f"Σ c x² = x² Σ c, so it reproduces C_r/C_v = {ratio:.6g} (length²)"
                             f" only at ±{math.sqrt(ratio):.6g}")
        return np.array([0.5 * C_v, 0.5 * C_v]), math.nan, math.nan, "pair"
    c2 = (C_r - a * C_v) / (b - a)
    c = np.array([C_v - c2, c2])
    if np.any(c < 0.0):
        raise InputError(f"radiation dashpots: C_r/C_v = {ratio:.6g} (length²) is outside "
                         f"[{min(a, b):.6g}, {max(a, b):.6g}], what two non-negative dashpots "
                         f"at {x[0]:g} and {x[1]:g} reach")
    return c, math.nan, math.nan, "pair"


def impedance_at(impedance, omega: float, columns, what: str) -> tuple[float, ...]:
    """Each of ``columns`` (arrays over the :class:`~upliftlab.continuum.impedance.analysis.
    Impedance`'s frequencies) at ``omega`` (rad/s), linear in ω between them. A frequency
    outside its grid is refused, naming ``what`` was asked for (no extrapolation)."""
    grid = np.asarray(impedance.omega, dtype=float)
    if not (math.isfinite(omega) and grid[0] <= omega <= grid[-1]):
        a0 = omega * float(impedance.a0[0]) / float(grid[0])
        raise InputError(f"{what}: ω = {omega:.6g} rad/s (a0 = {a0:.4g}) is outside the "
                         f"impedance's frequencies [{grid[0]:.6g}, {grid[-1]:.6g}] rad/s (a0 "
                         f"{impedance.a0[0]:g} to {impedance.a0[-1]:g}); compute it over a "
                         "wider a0")
    return tuple(float(np.interp(omega, grid, column)) for column in columns)


def impedance_dashpots(impedance, omega: float) -> tuple[float, float, float]:
    """(C_v, C_h, C_r) of an :class:`~upliftlab.continuum.impedance.analysis.Impedance` at
    ``omega`` (rad/s): C_j = Im K_j/ω at each of its frequencies, linear in ω between them
    (:func:`impedance_at`)."""
    return impedance_at(impedance, omega, [impedance.dashpot(mode) for mode in "vhr"],
                        "radiation dashpots")


def gazetas_dashpots(*, shear_modulus: float, poisson: float, density: float,
                     width: float) -> tuple[float, float, float]:
    """(C_v, C_h, C_r) of the handbook strip
    (:func:`~upliftlab.continuum.impedance.gazetas.handbook_strip`:
    ρ V_La B, ρ V_s B, ρ V_La B³/12, the high-frequency dashpots, the same at every ω)."""
    strip = handbook_strip([1.0], shear_modulus=shear_modulus, poisson=poisson,
                           density=density, width=width)
    return strip.C_v, strip.C_h, strip.C_r


def rocking_frequency(model) -> float:
    """The circular frequency (rad/s) of the structure rocking on its bed: the lowest bonded
    mode of the reduced ``model`` that is not a vertical one (at most half of its kinetic
    energy in V; the shares of V over the modes sum to one, so there is always one). For a rigid
    structure its rocking mode (with the sway, if any); for a
    flexible one the fundamental mode on the flexible base, the frequency at which
    soil–structure interaction practice takes the foundation's dashpots."""
    if model.dofs.theta < 0:
        raise InputError("foundation.support = 'fixed': a fixed base has no rocking frequency")
    K, _ = model.bonded_matrices()
    w2, modes = scipy.linalg.eigh(K, np.diag(model.mass))
    energy = model.mass[:, None] * modes**2
    vertical = energy[model.dofs.v] / energy.sum(axis=0)
    return float(math.sqrt(w2[int(np.flatnonzero(vertical <= 0.5)[0])]))


def radiation_dashpots(scene: Scene, *, impedance=None,
                       omega: float | None = None) -> RadiationDashpots:
    """The radiation dashpots of ``scene``'s bed: from ``impedance`` at ``omega`` (default: the
    structure's rocking frequency on the scene's bed), or without it from the handbook strip
    on the scene's ``[soil]`` (shear modulus, ν, density)."""
    model = build_model(scene)
    if model.layout is None:
        raise InputError("foundation.support = 'fixed': no bed to put dashpots on")
    omega = rocking_frequency(model) if omega is None else float(omega)
    if impedance is not None:
        C_v, C_h, C_r = impedance_dashpots(impedance, omega)
        source = "impedance"
    else:
        soil = scene.soil
        if soil is None or soil.density <= 0.0:
            raise InputError("soil.density: the handbook's dashpots need the scene's [soil] "
                             "with a density > 0")
        C_v, C_h, C_r = gazetas_dashpots(shear_modulus=soil.shear_modulus,
                                         poisson=soil.poisson_ratio, density=soil.density,
                                         width=scene.foundation.width)
        source = "gazetas"
    c, alpha, beta, where = distribute(model.layout.positions, model.layout.widths, C_v, C_r)
    return RadiationDashpots(omega, C_v, C_h, C_r, tuple(float(v) for v in c), alpha, beta,
                             where, source)


def with_radiation(scene: Scene, dashpots: RadiationDashpots, *,
                   horizontal: bool = True) -> Scene:
    """``scene`` with the bed's dashpots replaced by ``dashpots`` and, if ``horizontal``, C_h on
    its sway spring (which it must have: ``foundation.sway_stiffness``)."""
    f = scene.foundation
    if horizontal and not f.sways:
        raise InputError("foundation.sway_stiffness is missing: the horizontal radiation "
                         "dashpot C_h acts on the sway spring; give one (e.g. Re K_h), or "
                         "leave C_h out (horizontal=False)")
    if f.layout == "custom":  # the scene lists its dashpots in the order of its positions
        order = np.argsort(np.argsort(f.positions, kind="stable"), kind="stable")
        keys = dashpots.foundation_keys(horizontal=horizontal)
        keys["dashpots"] = [keys["dashpots"][i] for i in order]
        return scene.replace("foundation", **_fields(keys))
    return scene.replace("foundation", **_fields(dashpots.foundation_keys(horizontal=horizontal)))


def _fields(keys: dict) -> dict:
    """Foundation keys as the record's field values (lists become tuples)."""
    return {k: tuple(v) if isinstance(v, list) else v for k, v in keys.items()}
