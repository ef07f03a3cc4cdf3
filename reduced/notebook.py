"""A reduced-model :class:`~.response.Response` in a notebook: its ``plot()`` (a matplotlib
figure, nothing written) and its ``_repr_html_`` (a compact table: scene, integrator, span,
verdict, the peaks with their units, the energy balance and the code's digest).

Panels (``variables``), each against time but the last, every axis labelled with its unit:
``u`` the superstructure's deformation, ``theta`` the base rotation, ``uplift`` the largest gap
under the base (max over the springs of :attr:`~.response.Response.uplift`), ``settlement``
−V, ``contact`` the contact length, ``base_shear``, and ``moment_rotation`` the overturning
moment against θ (the M–θ loops). Default: θ, uplift, settlement and M–θ on a foundation;
u and the base shear on a fixed base.
"""

from __future__ import annotations

import numpy as np

from ..notebook import check_variables, digest_line, html_table, number, panel_axes

__all__ = ["PANELS", "panel_data", "response_plot", "response_html"]

PANELS = ("u", "theta", "uplift", "settlement", "contact", "base_shear", "moment_rotation")
FOUNDATION_DEFAULT = ("theta", "uplift", "settlement", "moment_rotation")
FIXED_DEFAULT = ("u", "base_shear")


def panel_data(response, name: str) -> tuple[np.ndarray, np.ndarray, str, str]:
    """(x, y, x label, y label) of panel ``name`` (module docstring)."""
    u = response.model.scene.units
    time = "time [s]"
    if name == "u":
        return response.time, response.u, time, f"u [{u.length}]"
    if name == "theta":
        return response.time, response.theta, time, "θ [rad]"
    if name == "uplift":
        gap = response.uplift
        y = gap.max(axis=1) if gap.shape[1] else np.zeros(response.time.size)
        return response.time, y, time, f"largest uplift [{u.length}]"
    if name == "settlement":
        return response.time, response.settlement, time, f"settlement −V [{u.length}]"
    if name == "contact":
        return response.time, response.contact_length, time, f"contact length [{u.length}]"
    if name == "base_shear":
        return response.time, response.base_shear, time, f"base shear [{u.force}]"
    return (response.theta, response.overturning_moment, "θ [rad]",
            f"overturning moment M [{u.force}·{u.length}]")


def response_plot(response, variables=None, ax=None):
    """The figure of ``response``'s panels ``variables`` (module docstring), drawn on new axes
    or on ``ax`` (one matplotlib axis per variable)."""
    fixed = response.model.layout is None
    chosen = check_variables(variables, PANELS, FIXED_DEFAULT if fixed else FOUNDATION_DEFAULT)
    fig, axes = panel_axes(ax, len(chosen))
    for axis, name in zip(axes, chosen):
        x, y, xlabel, ylabel = panel_data(response, name)
        axis.plot(x, y, lw=0.9, label=name)
        axis.set_xlabel(xlabel)
        axis.set_ylabel(ylabel)
        axis.grid(True, lw=0.3)
    if ax is None:
        fig.suptitle(f"{response.model.scene.name} (reduced model, "
                     f"{response.info.get('integrator', '?')})", fontsize=10)
    return fig


def response_html(response) -> str:
    """The HTML table of ``response`` (module docstring)."""
    u = response.model.scene.units
    pk = response.peaks
    rows = [("kind", f"reduced model ({response.info.get('integrator', '?')}), "
                     f"{response.model.params.size} springs"),
            ("scene", response.model.scene.name),
            ("span", f"{response.time.size} stored times over {response.time[-1]:.4g} s"),
            ("verdict", response.verdict),
            ("peak u", number(pk["u"], u.length)),
            ("peak θ", number(pk["theta"], "rad")),
            ("peak base shear", number(pk["base_shear"], u.force))]
    if "uplift_max" in pk:
        rows += [("peak uplift", number(pk["uplift_max"], u.length)),
                 ("final V (up)", number(pk["final_vertical_position"], u.length))]
    rows += [("energy balance error", number(pk["energy_balance_error"], digits=3)),
             ("provenance", digest_line(response.provenance))]
    return html_table(f"Response: {response.model.scene.title}", rows)
