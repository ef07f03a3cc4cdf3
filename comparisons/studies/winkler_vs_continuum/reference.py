"""The continuum reference: monotonic, cyclic and elastic rotation paths, the stiffnesses and
the capacity the beds are calibrated to."""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ....anchors import half_plane_onset_rotation, half_plane_rocking_stiffness
from ....scenes import Scene
from ...beds.continuum_points import floats
from ...beds.pushover import cyclic_path, rotation_path
from .options import Options, STATIC_MOTION


# ---------------------------------------------------------------------------------------------
# The continuum reference
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ContinuumReference:
    """The continuum results the beds are calibrated from and compared with.

    ``K_v``, ``K_r`` (full contact, the scene's box); ``theta_on`` the half-plane onset
    rotation; ``monotonic``, ``cyclic`` and ``elastic`` (elastic soil, the onset anchor) rotation
    pushover records; ``vertical`` the vertical pushover; ``N_ult`` its capacity (force/length),
    ``q_ult`` = N_ult/B. ``dofs`` of the mesh.
    """

    N: float
    B: float
    h: float
    G: float
    nu: float
    cu: float | None
    K_v: float
    K_r: float
    theta_on: float
    monotonic: dict = field(repr=False)
    cyclic: dict = field(repr=False)
    elastic: dict = field(repr=False)
    vertical: dict = field(repr=False)
    dofs: int = 0

    @property
    def N_ult(self) -> float:
        return float(self.vertical["capacity"])

    @property
    def q_ult(self) -> float:
        return self.N_ult / self.B

    @property
    def K_r_closed_form(self) -> float:
        """π G B²/(8(1 − ν)) (anchors §4)."""
        return half_plane_rocking_stiffness(self.G, self.B, self.nu)

    def onset(self, which: str = "monotonic") -> dict:
        return getattr(self, which)["onset"]


def continuum_points(scene: Scene, options: Options) -> tuple[list[dict], float]:
    soil, B = scene.soil, scene.foundation.width
    N = scene.structure.vertical_weight
    theta_on = half_plane_onset_rotation(N, B, soil.shear_modulus, soil.poisson_ratio)
    table = {**copy.deepcopy(scene.data), "motion": STATIC_MOTION}  # keys free of the motion
    rotations = floats(rotation_path(theta_on, options))
    points = [
        {"scene": table, "soil": "scene", "analysis": "rotation", "N": N,
         "rotations": floats(cyclic_path(theta_on, options))},
        {"scene": table, "soil": "scene", "analysis": "rotation", "N": N, "rotations": rotations},
        {"scene": table, "soil": "scene", "analysis": "vertical",
         "settlements": floats(np.linspace(0.0, options.settlement_ratio * B,
                                            options.vertical_steps + 1)[1:])},
        {"scene": table, "soil": "elastic", "analysis": "rotation", "N": N,
         "rotations": rotations},
        {"scene": table, "soil": "scene", "analysis": "stiffness"},
    ]
    return points, theta_on


def continuum_reference(scene: Scene, theta_on: float, records: Sequence[dict]
                        ) -> ContinuumReference:
    """The reference from the records of the :func:`continuum_points` (in their order)."""
    cyclic, monotonic, vertical, elastic, stiffness = records
    soil = scene.soil
    cu = soil.undrained_strength if soil.undrained else None
    return ContinuumReference(N=scene.structure.vertical_weight, B=scene.foundation.width,
                              h=scene.structure.height, G=soil.shear_modulus,
                              nu=soil.poisson_ratio, cu=cu, K_v=stiffness["K_v"],
                              K_r=stiffness["K_r"], theta_on=theta_on, monotonic=monotonic,
                              cyclic=cyclic, elastic=elastic, vertical=vertical,
                              dofs=stiffness["dofs"])
