"""The impedance analysis checked against the exact half-plane, summarised and drawn.

:func:`reference_for` computes the exact impedance (:mod:`.halfplane`) of the same soil,
footing, interface and frequencies; :func:`impedance_errors` the relative error |K − K_ref|/|K_ref|
of each mode at each a0; :func:`verify` refuses a result outside :data:`TOLERANCE` (a
:class:`ImpedanceAccuracyError` naming the mode, the frequency and the error), so that the
command never prints an impedance it has not checked; :func:`impedance_figure` draws k_j and c_j
of the FE, the exact solution and the handbook (:mod:`.gazetas`) against a0.
"""

from __future__ import annotations

import numpy as np

from .gazetas import handbook_strip
from .halfplane import BONDED, RELAXED, strip_impedance

__all__ = ["TOLERANCE", "ImpedanceAccuracyError", "reference_for", "impedance_errors", "verify",
           "impedance_summary", "impedance_figure"]

#: Largest relative error |K − K_exact|/|K_exact| accepted per mode (the coupling is reported,
#: not judged: it is small and crosses zero).
TOLERANCE = {"v": 0.05, "h": 0.03, "r": 0.03}
_INDEX = {"v": (1, 1), "h": (0, 0), "r": (2, 2), "hr": (0, 2)}


class ImpedanceAccuracyError(RuntimeError):
    """The FE impedance differs from the exact half-plane by more than :data:`TOLERANCE`."""


def reference_for(imp):
    """The exact :class:`~upliftlab.continuum.impedance.halfplane.StripImpedance` matching
    ``imp``."""
    soil = imp.soil
    interface = BONDED if imp.interface == "bonded" else RELAXED
    return strip_impedance(imp.a0, shear_modulus=soil.shear_modulus, poisson=soil.poisson_ratio,
                           width=imp.width, interface=interface,
                           terms=24 if interface == BONDED else 12)


def impedance_errors(imp, reference) -> dict:
    """Relative error per mode (v, h, r, hr) and frequency; modes that vanish exactly (h, hr of
    a frictionless footing) are left out."""
    out = {}
    for mode, (i, j) in _INDEX.items():
        ref = reference.matrix[:, i, j]
        if np.all(ref == 0.0):
            continue
        out[mode] = np.abs(imp.matrix[:, i, j] - ref) / np.abs(ref)
    return out


def verify(imp, reference) -> dict:
    """:func:`impedance_errors`, raising :class:`ImpedanceAccuracyError` if a judged mode is
    outside :data:`TOLERANCE` at any frequency."""
    errors = impedance_errors(imp, reference)
    for mode, tol in TOLERANCE.items():
        if mode in errors and np.max(errors[mode]) > tol:
            k = int(np.argmax(errors[mode]))
            raise ImpedanceAccuracyError(
                f"impedance K_{mode} at a0 = {imp.a0[k]:g} is {100 * errors[mode][k]:.2f} % off "
                f"the exact half-plane (tolerance {100 * tol:g} %): refine the mesh "
                f"(continuum.elements_across = {imp.mesh.get('elements_across')}) or lower the "
                "highest a0")
    return errors


def impedance_summary(imp, reference, errors) -> dict:
    """The JSON summary: the impedance (:meth:`Impedance.to_dict`), the exact one and the
    largest error of each mode."""
    pairs = lambda z: [[float(x.real), float(x.imag)] for x in z]  # noqa: E731
    out = imp.to_dict()
    out["exact"] = {f"K_{m}": pairs(reference.matrix[:, i, j]) for m, (i, j) in _INDEX.items()}
    out["max_error"] = {f"K_{m}": float(np.max(e)) for m, e in errors.items()}
    out["wall_time_s"] = float(imp.metadata.get("wall_time_s", 0.0))
    return out


def impedance_figure(imp, reference):
    """k_j and c_j (K_j = K_j,static [k_j + i a0 c_j]) against a0: FE, exact, handbook."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    soil = imp.soil
    book = handbook_strip(imp.a0, shear_modulus=soil.shear_modulus, poisson=soil.poisson_ratio,
                          density=soil.density, width=imp.width)
    norm = imp.normalisers()
    modes = [m for m in ("v", "h", "r") if not np.all(reference.matrix[:, _INDEX[m][0],
                                                                        _INDEX[m][1]] == 0)]
    fig, axes = plt.subplots(2, len(modes), figsize=(4 * len(modes), 6), squeeze=False)
    for col, mode in enumerate(modes):
        i, j = _INDEX[mode]
        k_fe, c_fe = imp.coefficients(mode)
        ref = reference.matrix[:, i, j]
        hb = book.impedance(mode)
        for row, (fe, exact, hand) in enumerate((
                (k_fe, ref.real / norm[mode], hb.real / norm[mode]),
                (c_fe, ref.imag / (imp.a0 * norm[mode]), hb.imag / (imp.a0 * norm[mode])))):
            ax = axes[row, col]
            ax.plot(imp.a0, exact, "-", color="black", label="exact half-plane")
            ax.plot(imp.a0, fe, "o", color="tab:blue", ms=4, label="FE")
            ax.plot(imp.a0, hand, "--", color="tab:red", label="Gazetas (1991), c̃ = 1")
            ax.set_xlabel("a0 = ω B/(2 V_s)")
            ax.set_ylabel(f"{'k' if row == 0 else 'c'}_{mode}")
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(f"Impedance of the strip, {imp.interface} interface, ν = "
                 f"{soil.poisson_ratio:g} ({imp.options.boundary}, {imp.dofs} DOFs)")
    fig.tight_layout()
    return fig
