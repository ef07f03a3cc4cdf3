"""Rocking pushovers of the bed and the two-spring layouts against their closed forms
(anchors §2–3): uplift onset, capacity and the ultimate moment."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ....anchors import WINKLER_ONSET_ECCENTRICITY, ultimate_moment_ratio
from ....reduced import build_model, rocking_pushover, uplift_onset_force
from .grid import Options, STATIC_MOTION
from .points import Base, make_point, point_scene


# ---------------------------------------------------------------------------------------------
# Statics
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class StaticLayout:
    """Static response of one foundation, normalised by N B (N the weight, B = 2b).

    ``onset`` uplift-onset moment; ``capacity`` the elastic moment as θ → ∞ (beds: extrapolated
    in θ^(-1/2) from 100 and 400 θ_up); ``ultimate`` the elasto-plastic moment at 1000 θ_up; each
    with its closed form. ``theta`` (θ/θ_up, θ_up = N/(K_v b)) and the ``elastic`` and
    ``plastic`` backbones M/(N B).
    """

    label: str
    bed: str | None
    layout: str
    positions: tuple[float, ...]
    onset: float
    onset_closed_form: float
    capacity: float
    capacity_closed_form: float
    ultimate: float
    ultimate_closed_form: float
    theta: np.ndarray
    elastic: np.ndarray
    plastic: np.ndarray


@dataclass(frozen=True, eq=False)
class Statics:
    """The static comparison at N springs and yield multiple FS_v."""

    springs: int
    yield_multiple: float
    layouts: tuple[StaticLayout, ...]

    def of(self, label: str) -> StaticLayout:
        return next(s for s in self.layouts if s.label == label)

    @property
    def onset_ratio(self) -> float:
        """Uplift-onset moment, equivalent springs over the uniform bed (anchor 1.73)."""
        return self.of("equivalent").onset / self.of("uniform bed").onset

    @property
    def capacity_ratio(self) -> float:
        """Capacity as θ → ∞, equivalent springs over the uniform bed (anchor 0.58)."""
        return self.of("equivalent").capacity / self.of("uniform bed").capacity

    def within(self, label: str, threshold: float, which: str = "elastic") -> float:
        """Largest θ/θ_up up to which ``label``'s backbone stays within ``threshold`` of the
        uniform bed's (0 if not even at the first point)."""
        mine, ref = getattr(self.of(label), which), getattr(self.of("uniform bed"), which)
        bad = np.abs(mine - ref) > threshold * np.abs(ref)
        first = int(np.argmax(bad)) if bad.any() else mine.size
        return float(self.theta[first - 1]) if first > 0 else 0.0

    @property
    def theta(self) -> np.ndarray:
        return self.layouts[0].theta


def static_model(base: Base, bed, layout, springs, options, law):
    point = make_point(base, bed=bed, layout=layout, springs=springs, options=options, case="B",
                       motion=STATIC_MOTION)
    point["foundation"]["law"] = law
    return build_model(point_scene(point))


def _rigid_plastic_moment(model, fs: float) -> float:
    """Limit moment of a rigid base on springs that yield at FS_v × their static force
    (force·length): the compressed side carries the weight at yield from the edge inward."""
    found = model.foundation_slice
    x, f0 = model.params["x"][found], model.params["f0"][found]
    order = np.argsort(-x)
    left, moment = model.weight, 0.0
    for i in order:
        take = min(fs * f0[i], left)
        moment += take * x[i]
        left -= take
        if left <= 0.0:
            break
    return moment


def _static_layout(base, label, bed, layout, springs, options, thetas) -> StaticLayout:
    elastic = static_model(base, bed, layout, springs, options, "elastic")
    plastic = static_model(base, bed, layout, springs, options, "elastoplastic")
    w, b = elastic.weight, elastic.layout.half_width
    nb = w * 2.0 * b
    theta_up = w / (elastic.layout.vertical_stiffness * b)
    x = elastic.layout.positions
    onset = uplift_onset_force(elastic) * float(elastic.heights[-1]) / nb
    far = rocking_pushover(elastic, theta_up * np.array([100.0, 400.0])).moment / nb
    capacity = far[1] if x.size == 2 else 2.0 * far[1] - far[0]
    fs = base.yield_multiple
    if x.size == 2:
        onset_cf = capacity_cf = float(x[1]) / (2.0 * b)
        ultimate_cf = min(1.0, fs - 1.0) * onset_cf
    else:
        k, kv = elastic.layout.stiffnesses, elastic.layout.vertical_stiffness
        outer = float(np.max(x))
        onset_cf = (WINKLER_ONSET_ECCENTRICITY if bed == "uniform"
                    else float(np.sum(k * x**2)) / (kv * outer * 2.0 * b))
        capacity_cf = 0.5
        ultimate_cf = (ultimate_moment_ratio(fs) if bed == "uniform"
                       else _rigid_plastic_moment(plastic, fs) / nb)
    path = rocking_pushover(plastic, theta_up * thetas)
    return StaticLayout(label, bed, layout, tuple(float(v) for v in x / b), onset, onset_cf,
                        float(capacity), capacity_cf, float(path.moment[-1] / nb), ultimate_cf,
                        thetas, rocking_pushover(elastic, theta_up * thetas).moment / nb,
                        path.moment / nb)


def compute_statics(base: Base, springs: int, options: Options, points: int) -> Statics:
    """Pushovers and closed forms of the beds and the two-spring layouts (anchors §2–3)."""
    thetas = np.geomspace(0.05, 1000.0, points)
    rows = [("uniform bed", "uniform", "winkler"), ("end-stiffened bed", "end_stiffened",
                                                    "winkler"),
            ("edges", None, "edges"), ("equivalent", None, "equivalent"),
            ("calibrated (uniform)", "uniform", "calibrated"),
            ("calibrated (end-stiffened)", "end_stiffened", "calibrated")]
    layouts = tuple(_static_layout(base, label, bed, layout, springs, options, thetas)
                    for label, bed, layout in rows)
    return Statics(springs, base.yield_multiple, layouts)
