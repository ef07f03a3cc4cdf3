"""The continuum runs a user's macro-element is calibrated from, planned from the user's own
scene before any of them starts (issue 36 §2, ``upliftlab calibrate SCENE``).

They are the runs the map keeps for its two soils (:mod:`...winkler_map.statics`,
:mod:`...winkler_map.rocking`), made on the scene's own soil, footing and mesh: the footing's
stiffness in full contact (K_v, K_r), a vertical pushover to :data:`SETTLEMENT_RATIO` B in
:data:`VERTICAL_STEPS` steps (its largest load is V_ult), then at each FS_v a monotonic rotation
pushover and one of cycles at growing amplitude under N = V_ult/FS_v, on the map's paths
(:data:`PATHS`, scaled by the elastic half-plane's uplift rotation θ_on = 2N(1 − ν)/(π G B)).
Each is a point of :func:`~upliftlab.comparisons.beds.continuum_points.evaluate_continuum`,
so a store keeps them by content and a second command finds them. The scene's motion is
replaced by a free one (the statics read none) so that a scene on a record needs no record.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass

from ....anchors import half_plane_onset_rotation
from ....checks import InputError
from ....scenes.soil import SOIL_MODELS, UNDRAINED
from ...beds.continuum_points import floats
from ...beds.macro import macro_strength
from ...beds.pushover import cyclic_path, repeated_cycles, rotation_path

__all__ = ["PathOptions", "PATHS", "DEFAULT_FS_V", "SETTLEMENT_RATIO", "VERTICAL_STEPS",
           "MAX_ROTATION", "macro_strength", "check_fs_v", "statics_points", "pushover_points",
           "pushover_kinds",
           "rotation_steps", "estimated_capacity", "check_reach", "check_weight",
           "MAX_CAPACITY_MULTIPLE"]

#: The largest V_ult/W a scene's element may have (the macro law's ``capacity_multiple``).
MAX_CAPACITY_MULTIPLE = 1e6


@dataclass(frozen=True)
class PathOptions:
    """The rotation paths (:func:`~...beds.pushover.rotation_path`, :func:`cyclic_path`):
    ``theta_ratios`` θ/θ_on on the monotonic path, reached in ``monotonic_steps`` geometric
    steps beyond 1.5 θ_on; ``cycle_ratios`` the amplitudes of the cycles, ``cycle_steps``
    steps per quarter cycle; at each FS_v of ``repeat_fs_v`` that the calibration pushes
    over, also ``repeat_cycles`` full cycles at ``repeat_ratio`` θ_on (whether the footing
    shakes down: the element's memory)."""

    theta_ratios: tuple[float, ...] = (2.0, 5.0, 10.0, 30.0)
    monotonic_steps: int = 14
    cycle_ratios: tuple[float, ...] = (2.0, 5.0, 10.0)
    cycle_steps: int = 4
    repeat_fs_v: tuple[float, ...] = (3.0, 5.0)
    repeat_cycles: int = 6
    repeat_ratio: float = 2.0


#: The map's paths (its ``Options`` defaults): the calibration of its two soils was made on
#: them (``benchmarks/MACRO_CALIBRATION.md``).
PATHS = PathOptions()
#: The FS_v = V_ult/N of the rotation pushovers (the map's).
DEFAULT_FS_V = (10.0, 5.0, 3.0, 2.0)
#: The vertical pushover's depth (× B) and steps (the map's).
SETTLEMENT_RATIO, VERTICAL_STEPS = 0.05, 10
#: Largest rotation of a path (rad): the continuum is small-rotation
#: (``upliftlab continuum``'s bound).
MAX_ROTATION = 0.1
#: The valid FS_v of a pushover: above 1 with a margin (N near V_ult: the soil cannot carry
#: the path), and at most where the footing barely yields.
FS_V_RANGE = (1.5, 50.0)
_FREE = {"type": "free", "velocity": 1.0, "duration": 1.0}


def estimated_capacity(scene) -> float:
    """V_ult of the scene's footing from a closed form, before any run: Prandtl's, or Davis
    and Booker's with a strength gradient, on an undrained soil; B (c N_c + ½ γ B N_γ) with
    Vesić's factors on a frictional one (force per length)."""
    from ....anchors import undrained_capacity
    from ....reduced.laws.macro.params import bearing_factors

    soil, B = scene.soil, scene.foundation.width
    if SOIL_MODELS.get(soil.model) == UNDRAINED:
        return undrained_capacity(soil.undrained_strength, soil.undrained_strength_gradient, B,
                                  rough=soil.interface == "bonded")
    n_c, _, n_gamma = bearing_factors(soil.friction_angle)
    return B * (soil.cohesion * n_c + 0.5 * soil.density * scene.g * B * n_gamma)


def check_reach(scene, V_ult: float, fs_v: Sequence[float], paths: PathOptions = PATHS,
                estimated: bool = False) -> None:
    """Refuse an FS_v whose monotonic path would reach beyond :data:`MAX_ROTATION` under
    N = V_ult/FS_v (``estimated``: V_ult from :func:`estimated_capacity`, before any run)."""
    top = max(paths.theta_ratios)
    for fs in fs_v:
        reach = top * _onset(scene, V_ult / fs)
        if not reach <= MAX_ROTATION:
            least = fs * reach / MAX_ROTATION
            raise InputError(f"--fs-v = {fs:g}: the monotonic pushover would reach "
                             f"{reach:.3g} rad ({top:g} θ_on under N = V_ult/FS_v, V_ult "
                             f"{'estimated at ' if estimated else ''}{V_ult:.4g}), beyond the "
                             f"continuum's small rotations ({MAX_ROTATION:g} rad); valid on "
                             f"this soil: FS_v ≥ {least:.3g}")


def check_fs_v(values: Sequence[float]) -> tuple[float, ...]:
    """The FS_v of the pushovers, checked: 1 to 8 distinct values in :data:`FS_V_RANGE`."""
    low, high = FS_V_RANGE
    values = tuple(float(v) for v in values)
    if not 1 <= len(values) <= 8 or len(set(values)) != len(values):
        raise InputError(f"--fs-v = {','.join(f'{v:g}' for v in values)!r}: 1 to 8 distinct "
                         "values")
    for v in values:
        if not low <= v <= high:  # NaN fails too
            raise InputError(f"--fs-v = {v:g}: valid range is [{low:g}, {high:g}]")
    return tuple(sorted(values, reverse=True))


def _table(scene) -> dict:
    """The scene's own data (case and overrides merged in) with a free motion."""
    data = copy.deepcopy(scene.data)
    data["motion"] = dict(_FREE)
    data.pop("analysis", None)
    return data


def statics_points(scene) -> list[dict]:
    """The footing's stiffness and its vertical pushover, as points of
    :func:`~...beds.continuum_points.evaluate_continuum`."""
    table = _table(scene)
    B = scene.foundation.width
    steps = [SETTLEMENT_RATIO * B * (k + 1) / VERTICAL_STEPS for k in range(VERTICAL_STEPS)]
    return [{"scene": table, "soil": "scene", "analysis": "stiffness"},
            {"scene": table, "soil": "scene", "analysis": "vertical",
             "settlements": floats(steps)}]


def _onset(scene, N: float) -> float:
    soil = scene.soil
    G = soil.youngs_modulus / (2.0 * (1.0 + soil.poisson_ratio))
    return half_plane_onset_rotation(N, scene.foundation.width, G, soil.poisson_ratio)


def pushover_kinds(fs_v: Sequence[float], paths: PathOptions = PATHS) -> list[tuple]:
    """(FS_v, kind) of each of :func:`pushover_points`, in their order: per FS_v
    ``monotonic``, ``cycles`` and, at an FS_v of ``paths.repeat_fs_v``, ``repeated``."""
    return [(fs, kind) for fs in fs_v for kind in
            ("monotonic", "cycles", *(("repeated",) if fs in paths.repeat_fs_v else ()))]


def _path(kind: str, theta_on: float, paths: PathOptions):
    if kind == "monotonic":
        return rotation_path(theta_on, paths)
    if kind == "cycles":
        return cyclic_path(theta_on, paths)
    return cyclic_path(theta_on, repeated_cycles(paths, paths.repeat_ratio, paths.repeat_cycles))


def pushover_points(scene, V_ult: float, fs_v: Sequence[float],
                    paths: PathOptions = PATHS) -> list[dict]:
    """The rotation pushovers of :func:`pushover_kinds` under N = V_ult/FS_v, as points of
    :func:`evaluate_continuum`. A path beyond :data:`MAX_ROTATION` is refused."""
    table = _table(scene)
    check_reach(scene, V_ult, fs_v, paths)
    return [{"scene": table, "soil": "scene", "analysis": "rotation", "N": float(V_ult / fs),
             "rotations": floats(_path(kind, _onset(scene, V_ult / fs), paths))}
            for fs, kind in pushover_kinds(fs_v, paths)]


def check_weight(scene, V_ult: float, ceiling: float) -> None:
    """Refuse a structure whose vertical weight W the calibrated element cannot carry at rest
    with V_ult (its ``capacity_multiple`` V_ult/W in (1, 10⁶]; W below ``ceiling`` × V_ult,
    the initial surface's largest size less a margin, so that it rests elastic)."""
    W = scene.structure.vertical_weight
    low, high = V_ult / MAX_CAPACITY_MULTIPLE, ceiling * V_ult
    if not low <= W < high:
        raise InputError(f"structure.vertical_weight = {W:g}: the element's V_ult is "
                         f"{V_ult:.4g} on this soil; valid range is [{low:.4g}, {high:.4g})")


def rotation_steps(fs_v: Sequence[float], paths: PathOptions = PATHS) -> int:
    """The steps of every rotation pushover at the FS_v values ``fs_v`` (their lengths do not
    depend on N)."""
    return sum(len(_path(kind, 1.0, paths)) for _, kind in pushover_kinds(fs_v, paths))
