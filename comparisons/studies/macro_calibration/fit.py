"""A user's macro-element: the continuum runs of :mod:`.plan`, swept into a store, then the fit
of :func:`~upliftlab.comparisons.beds.macro.calibrate_macro` to them, each step a check.

The steps, in order, and what each is held to:

1. the statics (K_v, K_r, V_ult): V_ult is the vertical pushover's largest load, and the last
   step's load may not exceed the one before by more than :data:`PLATEAU_TOLERANCE` (a path
   still climbing has not found the capacity: refused, with the depth to push to);
2. the rotation pushovers at every FS_v: one the soil cannot follow (the continuum's Newton
   gives up: a mechanism at that N) is left out and named; a monotonic one at least must
   remain;
3. the fit (the capacity line, then the plastic parameters by least squares), whose law must
   hold N on every pushover (:data:`~...beds.macro.LOAD_TOLERANCE`).

Nothing dynamic enters: the user's own dynamic runs are the test, as the map is for the
calibration of its two soils.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from ....checks import InputError
from ...beds.continuum_points import evaluate_continuum
from ...beds.macro import MacroCalibration, RotationPushover, calibrate_macro
from ...framework.store import Store, point_key
from ...framework.sweep import run_sweep
from .plan import (check_weight, macro_strength, pushover_kinds, pushover_points,
                   statics_points)

__all__ = ["SceneCalibration", "calibrate_scene", "FitCache", "fit_stamp", "PLATEAU_TOLERANCE",
           "STUDY", "CARRY_CEILING"]

#: The study name in the store's keys.
STUDY = "macro_calibration"
#: The largest W/V_ult the element may carry at rest: its initial surface (ζ0 ≤ 0.999) less the
#: fit's margin of 2 % (:func:`calibrate_macro`).
CARRY_CEILING = 0.999 / 1.02
#: The largest rise of the vertical pushover's load over its last step, as a share of V_ult,
#: for V_ult to count as the capacity (the map's clay and sand: 0.0 % and 0.6 %).
PLATEAU_TOLERANCE = 0.02


class FitCache(dict):
    """The fit's evaluations (residuals by the exact point), kept in a file of the output folder
    so that an interrupted fit resumes: :func:`calibrate_macro` is deterministic and replays
    them. The file is read only when its stamp matches this fit's (:meth:`bind`: a digest of
    the pushovers, the statics, the options and the code the residuals come from)."""

    def __init__(self, path) -> None:
        super().__init__()
        self.path, self.stamp = path, ""

    def bind(self, stamp: str) -> FitCache:
        """Take the evaluations the file keeps for ``stamp`` (none for another's)."""
        self.stamp = stamp
        try:
            with np.load(self.path, allow_pickle=False) as data:
                if str(data["stamp"]) == stamp:
                    self.update({k: data[k] for k in data.files if k != "stamp"})
        except (OSError, ValueError, KeyError):
            pass
        return self

    def save(self) -> None:
        """Write the evaluations so far (atomically; nothing before :meth:`bind`)."""
        import io

        from ....results import write_bytes

        if not self.stamp:
            return
        buffer = io.BytesIO()
        np.savez(buffer, stamp=np.array(self.stamp), **self)
        write_bytes(self.path, buffer.getvalue())


def fit_stamp(pushovers, statics, options) -> str:
    """The digest a :class:`FitCache` is bound to."""
    import hashlib
    import json

    from ....provenance import MODEL_SOURCES, code_digest

    digest = hashlib.sha256(json.dumps([statics, options], sort_keys=True).encode())
    for p in pushovers:
        for array in (p.theta, p.M, p.settlement):
            digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
        digest.update(repr(float(p.N)).encode())
    digest.update(code_digest((*MODEL_SOURCES, "upliftlab.comparisons/beds/")).encode())
    return digest.hexdigest()


@dataclass(frozen=True)
class SceneCalibration:
    """A scene's macro-element and the runs it came from: ``K_v`` (force/length per length),
    ``K_r`` (force·length/rad per length), ``V_ult`` (force per length) and ``plateau`` (the
    vertical pushover's last rise, of V_ult); ``fs_v`` of the pushovers fitted, ``left_out``
    those the soil could not follow (FS_v, kind, why); ``fit`` the calibration with its
    residuals; ``keys`` the store keys of every continuum run."""

    scene: str
    scene_digest: str
    width: float
    K_v: float
    K_r: float
    V_ult: float
    plateau: float
    fs_v: tuple[float, ...]
    fit: MacroCalibration
    pushovers: tuple[RotationPushover, ...] = field(repr=False)
    left_out: tuple[tuple[float, str, str], ...] = ()
    keys: tuple[str, ...] = ()
    seconds: dict = field(default_factory=dict)


def _sweep(points, store: Store, workers: int, progress) -> list[dict]:
    return run_sweep(evaluate_continuum, points, store, study=STUDY, workers=workers,
                     chunk=1, progress=progress)


def _statics(scene, store: Store, workers: int, progress) -> tuple[float, float, float, float]:
    stiffness, vertical = _sweep(statics_points(scene), store, workers, progress)
    loads = np.asarray(vertical["N"], dtype=float)
    V_ult = float(vertical["capacity"])
    plateau = float((loads[-1] - loads[-2]) / V_ult) if loads.size > 1 else math.inf
    if not plateau <= PLATEAU_TOLERANCE:
        raise InputError(f"scene {scene.name!r}: the vertical pushover's load still rose "
                         f"{plateau:.2%} of its largest over its last step (valid: at most "
                         f"{PLATEAU_TOLERANCE:.2%}): the capacity lies beyond the path's "
                         "settlement of 0.05 B; the soil is too soft for its strength to "
                         "reach it there")
    return float(stiffness["K_v"]), float(stiffness["K_r"]), V_ult, plateau


def calibrate_scene(scene, store: Store, *, fs_v: Sequence[float], evaluations: int,
                    workers: int = 1, progress=None, fit_progress: Callable | None = None,
                    cache=None) -> SceneCalibration:
    """The macro-element of ``scene``'s soil and footing (module docstring). The continuum runs
    go to ``store`` (kept: an interrupted calibration resumes from them) on ``workers``
    processes, ``progress`` as :func:`run_sweep` takes it; ``fit_progress(evaluations,
    at_most, lowest_cost)`` follows the fit and ``cache`` keeps its evaluations
    (:func:`calibrate_macro`). The structure's weight and the paths' reach are checked as
    soon as the statics give V_ult, before the pushovers."""
    strength = macro_strength(scene)  # refused before any run
    started = time.perf_counter()
    K_v, K_r, V_ult, plateau = _statics(scene, store, workers, progress)
    check_weight(scene, V_ult, CARRY_CEILING)
    points = pushover_points(scene, V_ult, fs_v)
    statics_time = time.perf_counter() - started
    records = _sweep(points, store, workers, progress)
    pushovers, left_out, kept_fs = [], [], []
    for (fs, kind), point, record in zip(pushover_kinds(fs_v), points, records):
        if "error" in record:
            left_out.append((fs, kind, str(record["error"])))
            continue
        pushovers.append(RotationPushover(
            float(point["N"]), np.asarray(record["theta"], dtype=float),
            np.asarray(record["M"], dtype=float), np.asarray(record["settlement"], dtype=float),
            f"FS_v {fs:g}, {kind}"))
        kept_fs.append(fs)
    if not any(np.all(np.diff(p.theta) >= 0.0) for p in pushovers):
        raise InputError(f"--fs-v = {','.join(f'{v:g}' for v in fs_v)}: the soil could not "
                         "follow any monotonic pushover (" + "; ".join(
                             f"FS_v {f:g} {kind}: {why}" for f, kind, why in left_out)
                         + "); valid: at least one FS_v whose pushover the soil carries "
                         "(a larger FS_v)")
    pushes = sorted(pushovers, key=lambda p: (p.N, len(p.theta)))
    runs_time = time.perf_counter() - started
    if isinstance(cache, FitCache):
        cache.bind(fit_stamp(pushes, [K_v, K_r, V_ult, strength], [
            evaluations, scene.structure.vertical_weight, scene.units.metres,
            scene.foundation.width]))
    fit = calibrate_macro(pushes, width=scene.foundation.width, V_ult=V_ult, K_v=K_v, K_r=K_r,
                          max_evaluations=evaluations, progress=fit_progress,
                          carry=scene.structure.vertical_weight,
                          length_unit=scene.units.metres, cache=cache, **strength)
    all_points = statics_points(scene) + points
    keys = tuple(point_key(STUDY, evaluate_continuum, p) for p in all_points)
    return SceneCalibration(scene.name, scene.digest, scene.foundation.width, K_v, K_r, V_ult,
                            plateau, tuple(sorted(set(kept_fs), reverse=True)), fit,
                            tuple(pushes), tuple(left_out), keys,
                            {"statics": statics_time, "pushovers": runs_time - statics_time,
                             "fit": time.perf_counter() - started - runs_time})
