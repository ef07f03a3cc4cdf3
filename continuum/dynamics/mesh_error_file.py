"""A :class:`~.mesh_error.MeshErrorEstimate` as an :class:`xarray.Dataset` with CF-1.10
attributes (the file ``error_estimate.nc`` of ``upliftlab continuum --error-estimate``).

Dimension ``mesh`` (coordinate ``elements_across``, finest first, with each run's
``time_step``). Each quantity q (a peak of the summary or a history) has its own variables,
in its own units: ``q(mesh)`` the value on each mesh (a history: its peak), ``q_difference``
(f_n − f_{n/2}; a history: the largest difference), ``q_error`` (the estimated discretisation
error of the finest run), ``q_order`` (the order used; NaN where none) and ``q_flag``
(``flag_values`` / ``flag_meanings``: richardson, order_does_not_hold, no_observed_order,
singular), the order's source as the attribute ``order_source`` of ``q_error``.
"""

from __future__ import annotations

import numpy as np

from ...provenance import provenance
from ...results import cf_attributes

__all__ = ["estimate_dataset", "estimate_lines"]

_LONG = {"peak_theta": "peak |footing rotation|", "peak_structure_u":
         "peak |superstructure deformation|", "peak_edge_uplift": "peak gap at a footing edge",
         "residual_settlement": "settlement left by the motion", "max_contact_loss":
         "largest contact loss 1 - c/B", "max_plastic_strain":
         "largest equivalent plastic strain at a point", "theta_history":
         "footing rotation history", "v_history": "settlement history v - v(0)"}


def estimate_dataset(estimate):
    """The dataset of ``estimate`` (module docstring)."""
    import xarray as xr

    flags, (low, high) = estimate.flags, estimate.order_bounds
    mesh = ("mesh",)
    coords = {"elements_across": (mesh, np.asarray(estimate.across, np.int32),
                                  {"long_name": "elements across the footing", "units": "1"}),
              "time_step": (mesh, np.asarray(estimate.dt, float),
                            {"long_name": "time step of the run", "units": "s"})}
    data = {}
    meanings = " ".join(f.replace(" ", "_") for f in flags)
    for q in estimate.quantities:
        units = q.units or "1"
        what = _LONG.get(q.name, q.name)
        data[q.name] = (mesh, np.asarray(q.values, float),
                        {"long_name": what + (" (its peak)" if q.name.endswith("_history")
                                              else ""), "units": units})
        data[f"{q.name}_difference"] = ((), float(q.differences[0]), {
            "long_name": f"{what}: finest run less the next coarser"
            + (" (largest over time)" if q.name.endswith("_history") else ""),
            "units": units})
        data[f"{q.name}_error"] = ((), float(q.estimate), {
            "long_name": f"{what}: estimated discretisation error of the finest run",
            "units": units, "order_source": q.order_source, "flag": q.flag})
        data[f"{q.name}_order"] = ((), float(q.order), {
            "long_name": f"{what}: order of convergence used (NaN: none)", "units": "1",
            "valid_min": low, "valid_max": high})
        data[f"{q.name}_flag"] = ((), np.int8(flags.index(q.flag)), {
            "long_name": f"{what}: how the error was estimated",
            "flag_values": np.arange(len(flags), dtype=np.int8), "flag_meanings": meanings})
    meta = estimate.metadata
    attrs = cf_attributes({
        "Conventions": "CF-1.10",
        "title": f"discretisation error estimate of {meta.get('scene', 'a run')} "
                 "(upliftlab continuum)",
        "source": "upliftlab continuum model (plane strain), the same run on coarser meshes",
        "comment": "error = |f_n - f_(n/2)| / (2^p - 1) with the order p used; where no order "
                   "holds, the plain difference as a bound. " + estimate.time_note(),
        "kind": "mesh_error_estimate", **provenance(**meta)})
    return xr.Dataset(data, coords=coords, attrs=attrs)


def estimate_lines(estimate) -> list[str]:
    """One line per quantity of ``estimate``: value ± estimate, with its order or flag."""
    out = []
    for q in estimate.quantities:
        how = (f"Richardson, p = {q.order:.2f} ({q.order_source})"
               if q.flag == estimate.flags[0] else f"plain difference as a bound: {q.flag}")
        units = "" if q.units in ("", "1") else f" {q.units}"
        share = "–" if q.relative != q.relative else f"{q.relative:.2%}"  # NaN: a zero value
        if q.name.endswith("_history"):
            out.append(f"{q.name}: ± {q.estimate:.2g}{units} ({share} of its peak; largest "
                       f"difference from {estimate.across[1]} across "
                       f"{abs(q.differences[0]):.3g}{units}; {how})")
        else:
            out.append(f"{q.name}: {q.values[0]:.4g} ± {q.estimate:.2g}{units} ({share}; "
                       f"{estimate.across[1]} across: {q.values[1]:.4g}; {how})")
    return out
