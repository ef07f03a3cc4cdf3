"""One-line summaries of a continuum run (the command line's output and the report's rows):
the peaks of a rotation pushover and of a dynamic run, and the rotation schedule of a pushover.
"""

from __future__ import annotations

import math

import numpy as np

from ...checks import InputError

__all__ = ["rotation_schedule", "pushover_summary", "dynamic_summary", "summary_line",
           "dynamic_warnings"]


def rotation_schedule(theta_max: float, steps: int, theta_on: float) -> np.ndarray:
    """Rotations 0, θ_max/steps, …, θ_max, plus 0.4 θ_on and 0.8 θ_on (θ_on the elastic
    half-plane's uplift rotation) where the steps are coarser than that, so that
    :func:`~upliftlab.continuum.statics.analyses.uplift_onset` has two full-contact steps to
    extrapolate from."""
    rotations = np.linspace(0.0, theta_max, steps + 1)
    extra = [r for r in (0.4 * theta_on, 0.8 * theta_on)
             if 0.0 < r < theta_max and np.min(np.abs(rotations - r)) > 0.1 * theta_on]
    return np.unique(np.concatenate((rotations, extra)))


def pushover_summary(path) -> dict:
    """Peaks of a rotation pushover: uplift onset (eccentricity e = M/N and θ by
    :func:`~upliftlab.continuum.statics.analyses.uplift_onset`; None if the path never lifts off, or
    lifts off before two full-contact steps: ``lifted`` tells which), peak M, and the largest
    contact loss 1 − c/B."""
    from ..contact.footing import OPEN
    from ..statics.analyses import uplift_onset

    try:
        onset = uplift_onset(path)
    except InputError:
        onset = None
    k = int(np.argmax(path.M))
    fraction = np.asarray(path.contact_length) / path.width
    lifted = np.flatnonzero((np.asarray(path.status) == OPEN).any(axis=1))
    return {
        "scene": path.metadata.get("scene", ""), "analysis": "pushover",
        "steps": int(np.size(path.theta)), "dofs": path.metadata.get("dofs"),
        "N": float(np.median(path.N)), "B": float(path.width),
        "onset_e_over_B": None if onset is None else onset.e / path.width,
        "onset_theta": None if onset is None else onset.theta,
        "lifted": bool(lifted.size),
        "first_open_theta": float(path.theta[lifted[0]]) if lifted.size else None,
        "peak_M": float(path.M[k]), "peak_M_over_NB": float(path.M[k] / (path.N[k] * path.width)),
        "theta_at_peak_M": float(path.theta[k]), "theta_max": float(np.max(path.theta)),
        "max_contact_loss": float(1.0 - fraction.min()),
        "settlement_final": float(-path.v[-1]),
    }


def dynamic_summary(result, width: float | None = None) -> dict:
    """Peaks of a dynamic run: footing θ and superstructure u (absolute value, with times),
    the largest contact loss 1 − c/B (``width`` B defaults to ``result.width`` or
    ``metadata['width']``), the largest gap at either edge of the footing
    (``peak_edge_uplift``), the settlement the motion left (``residual_settlement``, v at
    t = 0 less v at the end, down positive), the energy balance error and its tolerance, the
    largest equivalent plastic strain ε̄p at a quadrature point (``max_plastic_strain``; None
    for a result that did not record it) and the run's ``validity`` against the small-strain
    limit (:mod:`~upliftlab.continuum.dynamics.validity`; None: not judged), the far field's
    response (``far_field``: peak shear strain and where, peak plastic strain, ``yielded``
    "elastic" or "from z1 to z2",
    :meth:`~upliftlab.continuum.dynamics.far_field.FarFieldResponse.summary`; None for a
    result without it) and ``far_field_yielded``, the
    time integration (``method``, ``dt``) and, for an interrupted run, ``completed_until``."""
    time = np.asarray(result.time)
    footing = np.asarray(result.footing)
    theta = footing[:, 2]
    u = np.asarray(result.structure_u).reshape(time.size, -1)
    kt, ku = int(np.argmax(np.abs(theta))), int(np.argmax(np.max(np.abs(u), axis=1)))
    if width is None:
        width = getattr(result, "width", None) or result.metadata.get("width", math.nan)
    width = float(width)
    out = {
        "scene": result.metadata.get("scene", ""), "analysis": "dynamic",
        "duration": float(time[-1] - time[0]), "steps": int(time.size),
        "peak_theta": float(abs(theta[kt])), "time_of_peak_theta": float(time[kt]),
        "peak_structure_u": float(np.max(np.abs(u[ku]))), "time_of_peak_u": float(time[ku]),
        "max_contact_loss": float(1.0 - np.min(result.contact_length) / width)
        if math.isfinite(width) else None,
        "peak_edge_uplift": _edge_uplift(result),
        "residual_settlement": float(footing[0, 1] - footing[-1, 1]),
        "energy_balance_error": _energy_error(result),
        "energy_tolerance": result.metadata.get("energy_tolerance"),
        "max_plastic_strain": _finite_or_none(result.metadata.get("max_plastic_strain")),
        "validity": result.metadata.get("validity"),
        **_far_field(result),
        "method": result.metadata.get("method"), "dt": result.metadata.get("dt"),
    }
    if result.metadata.get("incomplete"):
        out["completed_until"] = result.metadata.get("completed_until")
    return out


def _far_field(result) -> dict:
    far = getattr(result, "far_field", None)
    if far is None:
        return {"far_field": None, "far_field_yielded": None}
    summary = far.summary()
    return {"far_field": summary, "far_field_yielded": summary["yield_top"] is not None}


def _finite_or_none(value) -> float | None:
    return None if value is None or not math.isfinite(float(value)) else float(value)


def _edge_uplift(result) -> float | None:
    gap = np.asarray(getattr(result, "gap", np.zeros((0, 0))))
    if gap.ndim != 2 or gap.shape[1] == 0:
        return None
    return float(max(np.max(gap[:, 0]), np.max(gap[:, -1]), 0.0))


def _energy_error(result) -> float | None:
    error = getattr(result, "energy_balance_error", None)
    if error is None:
        error = result.metadata.get("energy_balance_error")
    return _finite_or_none(error)


def summary_line(summary: dict, units: dict | None = None) -> str:
    """One line of a :func:`pushover_summary` or :func:`dynamic_summary`."""
    units = units or {}
    length = units.get("length", "")
    if summary["analysis"] == "pushover":
        if summary["onset_e_over_B"] is not None:
            onset = (f"uplift onset at e = {summary['onset_e_over_B']:.4f} B "
                     f"(θ = {summary['onset_theta']:.3g} rad)")
        elif summary.get("lifted"):
            onset = (f"uplift onset not resolved (contact lost by θ = "
                     f"{summary['first_open_theta']:.3g} rad; use more steps)")
        else:
            onset = "no uplift"
        return (f"{summary['scene']} pushover: {onset}; peak M = {summary['peak_M']:.4g} "
                f"{units.get('moment/length', '')} ({summary['peak_M_over_NB']:.3f} N B) at "
                f"θ = {summary['theta_at_peak_M']:.3g} rad; max contact loss "
                f"{summary['max_contact_loss']:.0%} of B; settlement "
                f"{summary['settlement_final']:.3g} {length}; {summary['dofs']} DOFs, "
                f"{summary['steps']} steps")
    loss = summary.get("max_contact_loss")
    energy = summary.get("energy_balance_error")
    return (f"{summary['scene']} dynamic: peak footing θ = {summary['peak_theta']:.3g} rad at "
            f"t = {summary['time_of_peak_theta']:.2f} s; peak superstructure u = "
            f"{summary['peak_structure_u']:.3g} {length} at t = "
            f"{summary['time_of_peak_u']:.2f} s"
            + ("" if loss is None else f"; max contact loss {loss:.0%} of B")
            + ("" if energy is None else f"; energy balance error {energy:.2g} of the input")
            + _strain_words(summary.get("max_plastic_strain"))
            + _far_field_words(summary.get("far_field"), length))


def _far_field_words(far: dict | None, length: str) -> str:
    if far is None:
        return ""
    where = ("stayed elastic" if far["yield_top"] is None else
             f"yielded from {far['yield_top']:.3g} to {far['yield_bottom']:.3g} {length} deep")
    return (f"; far field: peak shear strain {far['peak_shear_strain']:.3g} at "
            f"{far['depth_of_peak']:.3g} {length} deep, {where}")


def dynamic_warnings(summary: dict, units: dict | None = None) -> list[str]:
    """The warnings a :func:`dynamic_summary` carries (not errors: a site may yield): the far
    field yielded under the motion (the box's sides are then no longer the elastic free field
    the ground motion was meant to enter through), the run passed the small-strain limit."""
    from ..dynamics.validity import BEYOND, SMALL_STRAIN_LIMIT

    length = (units or {}).get("length", "")
    out = []
    far = summary.get("far_field")
    if far is not None and far["yield_top"] is not None:
        out.append(f"the far field yielded under the motion from {far['yield_top']:.3g} to "
                   f"{far['yield_bottom']:.3g} {length} deep (peak plastic strain "
                   f"{far['peak_plastic_strain']:.3g}): the free field at the box's sides is "
                   "not elastic")
    if summary.get("validity") == BEYOND:
        out.append(f"the largest plastic strain {summary['max_plastic_strain']:.3g} passes "
                   f"the small-strain limit {SMALL_STRAIN_LIMIT:g}: the run is {BEYOND}")
    return out


#: The equivalent plastic strain from which the soil at a point has left small strain. A
#: point value: at a rigid footing's corner it grows as the mesh is refined (the strain is
#: singular there), so it says where to look, not that the footing's response is wrong.
LARGE_STRAIN = 1.0


def _strain_words(peak: float | None) -> str:
    if peak is None:
        return ""
    words = f"; largest plastic strain ε̄p = {peak:.3g}"
    if peak >= LARGE_STRAIN:
        words += (f" (at or above {LARGE_STRAIN:g}: the soil has left small strain at a point "
                  "at least; see the plastic strain in fields.xdmf)")
    return words
