"""The continuum's dynamic impedance of a soil, one stored static-like point of the map.

A bed with radiation dashpots from the continuum (:mod:`...beds.dashpots`) needs the footing's
impedance K_j(ω) = K_j + iω C_j of the map's soil. It depends neither on the vertical load nor
on the structure, so, like the statics (:mod:`.statics`), one point per soil and mesh serves
every point of the map: :func:`impedance_point` describes it, :func:`evaluate_impedance` (the
sweep's point function, stored) computes it with
:func:`upliftlab.continuum.impedance.analysis.impedance`
and :func:`soil_impedance` turns the stored record back into an
:class:`~upliftlab.continuum.impedance.analysis.Impedance`.

The impedance is of the linear elastic half-plane with the soil's elastic constants, density
and interface (a frictionless strip on the map's soils), on the map's mesh options (element,
elements across, grading) in the impedance's own box: the PML box of
:class:`~upliftlab.continuum.impedance.analysis.ImpedanceOptions`' defaults (6B × 3B, a 1.5B layer,
R = 1e-4, m = 2), the box the project's impedance benchmark validates against the exact
half-plane (within 0.69 % for a0 = 0.1 to 2 on 16 across; within 0.03 % in K_v and 0.13 % in
K_r of the frictionless strip at a0 = 0.02 to 0.4, measured when this point was added). The
plasticity of the map's soils is not in it: radiation is a small-strain property.

The frequencies :data:`IMPEDANCE_A0` (a0 = ω (B/2)/V_s, 0.02 to 0.5) cover the rocking
frequencies of the map's grid with room on both sides (the clay's full grid on its 16-across
statics: a0 = 0.064 to 0.25; a soil of larger V_ult carries heavier structures, whose a0 is
lower); a point outside them is refused before any dynamic run. They are geometrically spaced,
19 of them (a ratio of 1.196), because C_j is taken linear in ω between them
(:func:`...beds.radiation.impedance_dashpots`) and the 2D C_v grows steeply as
a0 falls: at the geometric midpoints (16 across) the interpolated C_v is within 0.41 % and C_r
within 0.58 % of their values computed there (a ratio of 1.5 put C_v up to 2 % off).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import asdict
from typing import TYPE_CHECKING

import numpy as np

from ...framework.sources import point_sources
from ...framework.store import point_function
from .statics import static_scene
from .soils import SOILS

if TYPE_CHECKING:  # annotations only: the stored runs do not depend on the grid
    from .grid import Options

__all__ = ["IMPEDANCE_A0", "impedance_point", "impedance_point_of", "evaluate_impedance",
           "soil_impedance", "elastic_soil", "impedance_box_scene"]

#: The dimensionless frequencies a0 = ω (B/2)/V_s of the map's impedance (module docstring).
IMPEDANCE_A0 = tuple(float(v) for v in np.round(np.geomspace(0.02, 0.5, 19), 6))

_ELASTIC_KEYS = ("youngs_modulus", "poisson_ratio", "density", "interface")


def elastic_soil(soil: str) -> dict:
    """The ``[soil]`` table of the map's ``soil`` made linear elastic: its Young's modulus
    (kPa), Poisson ratio, density (t/m³) and interface, no strength."""
    return impedance_point_of(SOILS[soil], {}, 0.0)["soil"]


def _options(a0=IMPEDANCE_A0):
    from ....continuum.impedance.analysis import ImpedanceOptions

    return ImpedanceOptions(a0=tuple(a0))


def impedance_point(soil: str, options: Options, half_width: float) -> dict:
    """The impedance point of the map's ``soil`` on the options' mesh: the elastic soil, the
    mesh, the footing's half-width (m), the frequencies and every impedance option (so that
    the stored point's key names them)."""
    return impedance_point_of(SOILS[soil], {"elements_across": int(options.elements_across)},
                              half_width)


def impedance_point_of(soil_table: Mapping, continuum_table: Mapping,
                       half_width: float) -> dict:
    """The impedance point of any ``[soil]`` table (made linear elastic: its Young's modulus,
    Poisson ratio, density and interface) on the ``[continuum]`` table's mesh, under a footing
    of ``half_width`` (m)."""
    opts = asdict(_options())
    opts["a0"] = list(opts["a0"])
    return {"soil": {**{k: soil_table[k] for k in _ELASTIC_KEYS if k in soil_table},
                     "model": "elastic"},
            "continuum": dict(continuum_table),
            "half_width": float(half_width), "analysis": "impedance", "impedance": opts}


def _scene(point: Mapping):
    return static_scene(point)


def _impedance_options(point: Mapping):
    from ....continuum.impedance.analysis import ImpedanceOptions

    opts = dict(point["impedance"])
    opts["a0"] = tuple(opts["a0"])
    return ImpedanceOptions(**opts)


@point_function("upliftlab.comparisons.winkler_map:evaluate_impedance",
                models=("continuum",), tolerance=1e-4,
                sources=point_sources(__name__, __package__))
def evaluate_impedance(point: Mapping) -> dict:
    """The footing's impedance on the point's elastic soil (module docstring): ``a0``,
    ``omega`` (rad/s), the 3×3 complex impedance per frequency as ``real`` and ``imag`` (n × 3
    × 3, (u, v, θ) → (H, −N, M), kN/m/m, kN/rad/m, kN m/rad/m; e^{+iωt}), the DOFs and the
    run's own wall time ``wall_time_s`` (s)."""
    from ....continuum.impedance.analysis import impedance, impedance_model

    started = time.perf_counter()
    scene = _scene(point)
    options = _impedance_options(point)
    model = impedance_model(scene.soil, scene.foundation.width, scene.continuum, options,
                            scene=scene)
    result = impedance(model, options)
    return {"a0": [float(v) for v in result.a0], "omega": [float(v) for v in result.omega],
            "real": result.matrix.real.tolist(), "imag": result.matrix.imag.tolist(),
            "dofs": int(result.dofs), "wall_time_s": time.perf_counter() - started}


def soil_impedance(point: Mapping, record: Mapping):
    """The :class:`~upliftlab.continuum.impedance.analysis.Impedance` of a stored impedance
    point."""
    from ....continuum.impedance.analysis import Impedance

    scene = _scene(point)
    matrix = np.asarray(record["real"], dtype=float) + 1j * np.asarray(record["imag"],
                                                                       dtype=float)
    return Impedance(a0=np.asarray(record["a0"], dtype=float), matrix=matrix, soil=scene.soil,
                     width=scene.foundation.width, interface=scene.soil.interface,
                     mesh={"elements_across": point["continuum"]["elements_across"]},
                     options=_impedance_options(point), dofs=int(record["dofs"]),
                     metadata={"wall_time_s": float(record["wall_time_s"])})


def impedance_box_scene(point: Mapping):
    """The point's scene with the impedance's own box (its width and depth), as the impedance
    meshes it (for the cost estimate: :func:`.cost.impedance_dofs`)."""
    from dataclasses import replace

    scene = _scene(point)
    options = _impedance_options(point)
    continuum = replace(scene.continuum, domain_width=options.domain_width,
                        domain_depth=options.domain_depth)
    return replace(scene, continuum=continuum)
