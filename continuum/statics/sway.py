"""The footing pushed sideways: a sway pushover at constant vertical load and the V–H capacity
envelope it gives, on an interface that carries shear (``bonded`` or ``coulomb``).

Sign conventions are :mod:`.analyses`'. The footing is free to rotate with M = 0 (a load whose
line of action passes through the base centre, as Green's (1954) inclined central load), or
held at θ = 0 (``hold_rotation``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ... import checks
from ...checks import InputError
from ...results import write_netcdf
from ..output.fields import result_metadata
from .analyses import _apply_n, _follow, _history, _path, probe_loads
from .geostatic import geostatic
from .newton import Control, NewtonOptions
from .results import StaticPath

__all__ = ["sway_pushover", "vh_envelope", "SwayEnvelope"]


def sway_pushover(model, N: float, displacements, *, state=None, load_steps: int = 4,
                  hold_rotation: bool = False, options: NewtonOptions = NewtonOptions()
                  ) -> StaticPath:
    """Displacement-controlled horizontal loading at constant vertical load ``N``
    (force/length): N first in ``load_steps`` with θ held and H = 0, then u follows
    ``displacements`` (length, +x) with N constant and M = 0 (or θ = 0 held). Returns the
    path (``H`` against ``u``)."""
    if not model.footing.interface.tangential:
        raise InputError("soil.interface = 'frictionless' in a sway pushover: the footing is "
                         "pushed sideways through its interface's shear; valid: 'bonded', "
                         "'coulomb'")
    checks.positive("N", N)
    displacements = _history("displacements", displacements)
    state = geostatic(model) if state is None else state
    state = _apply_n(model, state, N, load_steps, options)
    controls = [Control((True, False, bool(hold_rotation)), (u, -N, 0.0))
                for u in displacements]
    states = _follow(model, state, controls, options, None)
    return _path(model, "sway_pushover", states, {"N_applied": N,
                                                  "hold_rotation": bool(hold_rotation)})


@dataclass(frozen=True, eq=False)
class SwayEnvelope:
    """A V–H capacity envelope by constant-V sway probes: for each ``V`` (force/length) the
    largest horizontal force ``H`` reached; ``V_ult`` the vertical capacity it is normalised
    by, ``width`` B; ``probes`` the :class:`StaticPath` of each probe."""

    V: np.ndarray
    H: np.ndarray
    V_ult: float
    width: float
    probes: tuple = field(repr=False, default=())
    metadata: dict = field(default_factory=dict, repr=False)

    @property
    def v(self) -> np.ndarray:
        """V/V_ult."""
        return self.V / self.V_ult

    @property
    def h(self) -> np.ndarray:
        """H/V_ult."""
        return self.H / self.V_ult

    def save(self, path) -> Path:
        """Write V, H, v, h per probe to NetCDF (atomically), with provenance."""
        units = self.metadata.get("units", {})
        probe = ("probe",)
        force = units.get("force/length", "")
        variables = {
            "V": (probe, self.V, {"units": force, "long_name": "vertical load of the probe"}),
            "H": (probe, self.H, {"units": force,
                                  "long_name": "largest horizontal force the probe reached"}),
            "v": (probe, self.v, {"units": "1", "long_name": "V / V_ult"}),
            "h": (probe, self.h, {"units": "1", "long_name": "H / V_ult"})}
        return write_netcdf(path, variables, attrs={"V_ult": self.V_ult, "width": self.width,
                                                    **self.metadata})


def vh_envelope(model, v_ratios, displacements, *, V_ult: float | None = None,
                settlements=None, load_steps: int = 4, hold_rotation: bool = False,
                options: NewtonOptions = NewtonOptions()) -> SwayEnvelope:
    """V–H envelope by constant-V sway probes: for each v in ``v_ratios`` (in (0, 1)) a
    :func:`sway_pushover` at V = v V_ult through ``displacements``; H_ult(V) is the largest H
    reached. ``V_ult`` defaults to the capacity of a vertical pushover to ``settlements`` on
    the same model (the mesh's own overshoot cancels in v and h)."""
    v_ratios, V_ult = probe_loads(model, v_ratios, V_ult, settlements, options)
    probes = tuple(sway_pushover(model, v * V_ult, displacements, load_steps=load_steps,
                                 hold_rotation=hold_rotation, options=options)
                   for v in v_ratios)
    return SwayEnvelope(V=v_ratios * V_ult, H=np.array([np.abs(p.H).max() for p in probes]),
                        V_ult=V_ult, width=model.width, probes=probes,
                        metadata=result_metadata(model, "vh_envelope",
                                                 {"displacements":
                                                  np.asarray(displacements).tolist(),
                                                  "hold_rotation": bool(hold_rotation)}))
