"""The Winkler map's evidence for one scene: where the scene falls in the map, and how far each
calibrated bed was from the continuum in the map's cells nearest to it.

The map (``map.nc`` of :mod:`.winkler_map`, with its ``statics.nc`` beside it) spans soil ×
FS_v × h/B × period × intensity × motion. A scene falls inside it when its soil is one of the
map's soils (the same validated ``[soil]`` record), its box has the map's sides
(``continuum.boundary``, the map's ``continuum_boundary``; a map without it had a rigid
container, ``fixed``) and base (``continuum.base``: ``rigid`` on the map's ``box`` reference,
``compliant`` on its ``half_plane`` one, whose clay's strength grows with depth, with the
footing's tie and its dashpot and the soil's small-strain damping of that reference, the map's
``options_reference``), and its FS_v (on the map's own continuum
capacity V_ult of that soil, ``statics.nc``), h/B, fixed-base period and intensity (PGA over
a_up = g B/(6h); a Ricker pulse's amplitude, as the map sets it) lie within the ranges of the
map's axes. The nearest cells are, per axis, the grid value the scene sits on or the two that
bracket it; every motion of the map counts. The evidence is the map's, measured on the map's
scenes and mesh, not on this scene: :func:`..advise_continuum.advise_continuum` labels it so
and certifies only by its own direct runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from ...checks import InputError
from ...paths import NO_SUCH_FILE, REGULAR_FILE, file_kind
from ...scenes import ContinuumOptions, Scene, scene_from_dict
from ..studies.winkler_map import reference_continuum, reference_soil

__all__ = ["DEFAULT_MAP", "BedEvidence", "MapEvidence", "scene_coordinates", "map_evidence",
           "find_map", "format_evidence"]

#: Where the map study writes its full map (relative to the working directory).
DEFAULT_MAP = Path("results") / "winkler_map" / "map.nc"
#: Relative slack on an axis's ends, so that a scene on a grid value is inside.
EDGE = 1e-9
AXES = ("fs_v", "h_over_B", "period", "intensity")


@dataclass(frozen=True)
class BedEvidence:
    """One bed's |error| against the continuum in the nearest cells (every motion):
    ``median`` and ``p90`` (90th percentile) of |error|, ``share_within`` the fraction of
    runs with |error| ≤ tol, ``count`` the runs with a value (refused runs have none).
    ``bearing_failures`` the runs where the continuum's soil failed in bearing (no error:
    they count in ``share_within`` as a hit where the bed's base settled the failure
    settlement too, ``called`` of them, and as a miss otherwise, as the map counts them)."""

    name: str
    median: float
    p90: float
    share_within: float
    count: int
    bearing_failures: int = 0
    called: int = 0

    @property
    def missed(self) -> int:
        """Bearing failures of the continuum that the bed did not fail with."""
        return self.bearing_failures - self.called


@dataclass(frozen=True)
class MapEvidence:
    """Where the scene falls in the map at ``path``: ``inside``, else ``outside`` (which
    parameter, its value, the map's range and by how much); ``soil`` the map's soil it
    matched; ``coordinates`` the scene's FS_v, h/B, period (s) and intensity; ``cells`` the grid
    values used per axis; ``beds`` the evidence per calibration; ``elements_across`` the map's
    continuum mesh; ``motions`` the map's motions."""

    path: str
    inside: bool
    outside: str
    soil: str
    coordinates: dict
    cells: dict
    beds: tuple[BedEvidence, ...]
    elements_across: int
    motions: tuple[str, ...]

    @property
    def best(self) -> BedEvidence | None:
        """The bed of least median |error| in the nearest cells (None: outside, or no
        values)."""
        beds = [b for b in self.beds if b.count]
        return min(beds, key=lambda b: b.median) if beds else None


def find_map(path: str | Path | None) -> Path | None:
    """The map to read: ``path`` (refused when it is not a file), else :data:`DEFAULT_MAP` if
    it exists, else None."""
    if path is not None:
        p = Path(path)
        kind = file_kind(p, f"--map = {str(path)!r}")  # not opened: a named pipe would block
        if kind != REGULAR_FILE:
            what = kind if kind == NO_SUCH_FILE else f"{kind}, not a regular file"
            raise InputError(f"--map = {str(path)!r}: {what}; give a map.nc written by "
                             "upliftlab study winkler_map")
        return p
    return DEFAULT_MAP if DEFAULT_MAP.is_file() else None


def _intensity(scene: Scene) -> float:
    """PGA over a_up = g B/(6h): a Ricker pulse's amplitude (g), as the map sets its pulses;
    otherwise the built motion's peak (g)."""
    B, h = scene.foundation.width, scene.structure.height
    pga = scene.motion.amplitude if scene.motion.type == "ricker" else scene.build_motion().pga
    return float(pga) * 6.0 * h / B


def _period(scene: Scene) -> float:
    """The one-story structure's fixed-base period 2π √(m/k) (s), m = weight/g."""
    story = scene.structure.stories[0]
    return 2.0 * math.pi * math.sqrt(story.weight / scene.g / story.stiffness)


def scene_coordinates(scene: Scene, V_ult: float) -> dict:
    """The scene's place on the map's axes: FS_v = V_ult/N (N the whole weight on the footing,
    ``structure.vertical_weight``), h/B, period (s), intensity."""
    return {"fs_v": V_ult / scene.structure.vertical_weight,
            "h_over_B": scene.structure.height / scene.foundation.width,
            "period": _period(scene), "intensity": _intensity(scene)}


def _soil_match(scene: Scene, soils, reference: str = "box") -> tuple[str, str]:
    """(map soil name, "") when the scene's soil record equals one of ``soils`` (as the map's
    continuum ``reference`` has them), else ("", the differences from the map's soil of the
    same model, or the models the map has)."""
    differences = []
    for name in soils:
        mapped = scene_from_dict({**scene.data, "soil": reference_soil(name, reference)},
                                 merged=True).soil
        if mapped == scene.soil:
            return name, ""
        if mapped.model == scene.soil.model:
            diff = [f"soil.{f.name} = {getattr(scene.soil, f.name)!r} (the map's {name}: "
                    f"{getattr(mapped, f.name)!r})" for f in fields(mapped)
                    if getattr(mapped, f.name) != getattr(scene.soil, f.name)]
            differences.append("; ".join(diff))
    if differences:
        return "", "soil: " + " / ".join(differences)
    models = ", ".join(f"{n} ({reference_soil(n)['model']})" for n in soils)
    return "", f"soil.model = {scene.soil.model!r}: the map's soils are {models}"


def _reference_mismatch(scene: Scene, soil: str, reference: str) -> str:
    """Where the scene's ``[continuum]`` differs from the map's ``reference`` for its ``soil``
    (the base, the footing's tie and its dashpot, the soil's damping: the fields
    :func:`~..studies.winkler_map.reference_continuum` sets; on the box none of them but the
    rigid base), as one reason, or "" where it does not."""
    expected = {"base": "rigid", "horizontal_tie": None, "horizontal_tie_damping": None,
                "damping_ratio": None}
    expected.update(reference_continuum(reference_soil(soil, reference),
                                        scene.foundation.width, reference))
    options = scene.continuum or ContinuumOptions()
    for name, value in expected.items():
        mine = getattr(options, name)
        same = (mine == value if value is None or isinstance(value, str)
                else mine is not None and math.isclose(mine, value, rel_tol=1e-9))
        if not same:
            return (f"continuum.{name} = {mine!r}: the map's runs have {value!r} (its "
                    f"{reference!r} reference)")
    return ""


def _outside(name: str, value: float, axis: np.ndarray) -> str:
    lo, hi = float(axis.min()), float(axis.max())
    if value < lo * (1 - EDGE):
        by = f"{lo - value:.3g} below"
    elif value > hi * (1 + EDGE):
        by = f"{value - hi:.3g} above"
    else:
        return ""
    return f"{name} = {value:.4g} is {by} the map's range [{lo:g}, {hi:g}]"


def _nearest(value: float, axis: np.ndarray) -> list[int]:
    """Indices of the grid value ``value`` sits on, or of the two that bracket it."""
    on = np.flatnonzero(np.abs(axis - value) <= EDGE * np.maximum(np.abs(axis), 1.0))
    if on.size:
        return [int(on[0])]
    above = int(np.searchsorted(axis, value))
    return [above - 1, above]


def map_evidence(path: str | Path, scene: Scene, measure: str, tol: float,
                 V_ult: float | None = None) -> MapEvidence:
    """The map's evidence for ``scene`` in ``measure`` (a name of :data:`.winkler_map.MEASURES`)
    at tolerance ``tol`` (fraction). FS_v uses the map's V_ult (``statics.nc`` beside the map);
    without that file, ``V_ult`` (the caller's continuum capacity of the scene's soil)."""
    from ...results import read_dataset

    path = Path(path)
    try:
        ds = read_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(f"--map = {str(path)!r}: not a readable NetCDF file ({exc})") from None
    missing = [n for n in ("error", "soil", "motion", "calibration", "measure", *AXES)
               if n not in ds.variables]
    if missing:
        raise InputError(f"--map = {str(path)!r}: not a Winkler map (no {', '.join(missing)}); "
                         "give a map.nc written by upliftlab study winkler_map")
    soils = [str(s) for s in ds["soil"].values]
    motions = tuple(str(m) for m in ds["motion"].values)
    mesh = int(ds.attrs.get("elements_across", 0))
    reference = str(ds.attrs.get("options_reference", "box"))
    soil, why = _soil_match(scene, soils, reference)
    statics = path.with_name("statics.nc")
    if soil and statics.is_file():
        st = read_dataset(statics)
        V_ult = float(st["V_ult"].sel(soil=soil).values)
    if not soil or V_ult is None:
        why = why or f"FS_v: no statics.nc beside {path} and no continuum capacity to place it"
        return MapEvidence(str(path), False, why, soil, {}, {}, (), mesh, motions)
    sides = str(ds.attrs.get("continuum_boundary", "fixed"))
    boundary = scene.continuum.boundary if scene.continuum is not None else "fixed"
    if boundary != sides:
        return MapEvidence(str(path), False, f"continuum.boundary = {boundary!r}: the map's "
                           f"runs have the box's sides {sides!r}", soil, {}, {}, (), mesh,
                           motions)
    why = _reference_mismatch(scene, soil, reference)
    if why:
        return MapEvidence(str(path), False, why, soil, {}, {}, (), mesh, motions)
    coords = scene_coordinates(scene, V_ult)
    axes = {a: np.asarray(ds[a].values, dtype=float) for a in AXES}
    reasons = [r for r in (_outside(a, coords[a], axes[a]) for a in AXES) if r]
    if reasons:
        return MapEvidence(str(path), False, "; ".join(reasons), soil, coords, {}, (), mesh,
                           motions)
    index = {a: _nearest(coords[a], axes[a]) for a in AXES}
    cells = {a: [float(axes[a][i]) for i in index[a]] for a in AXES}
    error = ds["error"].sel(soil=soil, measure=measure).isel(**index)
    failed = (int(ds["continuum_bearing_failure"].sel(soil=soil).isel(**index).values.sum())
              if "continuum_bearing_failure" in ds.variables else 0)
    beds = []
    for name in (str(c) for c in ds["calibration"].values):
        values = np.abs(np.asarray(error.sel(calibration=name).values, dtype=float)).ravel()
        values = values[np.isfinite(values)]
        called = (int(ds["bed_bearing_failure"].sel(soil=soil, calibration=name)
                      .isel(**index).values.sum()) if failed else 0)
        runs = values.size + failed
        share = (float(np.sum(values <= tol) + called) / runs) if runs else math.nan
        if values.size == 0:
            beds.append(BedEvidence(name, math.nan, math.nan, share, 0, failed, called))
            continue
        beds.append(BedEvidence(name, float(np.median(values)),
                                float(np.percentile(values, 90)), share, int(values.size),
                                failed, called))
    return MapEvidence(str(path), True, "", soil, coords, cells, tuple(beds), mesh, motions)


def format_evidence(e: MapEvidence, tol: float) -> list[str]:
    """The evidence as text lines, labelled as the map's."""
    if not e.inside:
        return [f"map ({e.path}): the scene is outside it: {e.outside}"]
    c = e.coordinates
    lines = [f"map's evidence ({e.path}; the map's scenes on {e.elements_across} elements "
             f"across, {len(e.motions)} motion(s), not this scene's runs): soil {e.soil}, "
             f"FS_v = {c['fs_v']:.3g}, h/B = {c['h_over_B']:.3g}, T = {c['period']:.3g} s, "
             f"intensity = {c['intensity']:.3g} a_up; nearest cells "
             + ", ".join(f"{a} ∈ {v}" for a, v in e.cells.items())]
    for b in e.beds:
        failures = (f"; the continuum failed in bearing in {b.bearing_failures} run(s) here, "
                    f"this bed with it in {b.called}" if b.bearing_failures else "")
        if b.count == 0:
            lines.append(f"  {b.name:26s} no value (every run refused or failed){failures}")
            continue
        lines.append(f"  {b.name:26s} |error| median {100 * b.median:.3g} %, 90th percentile "
                     f"{100 * b.p90:.3g} %, within {100 * tol:g} % in {100 * b.share_within:.0f}"
                     f" % of {b.count + b.bearing_failures} runs{failures}")
    if e.best is not None:
        b = e.best
        verdict = (f"map's verdict (evidence, not a certification): {b.name} has the least "
                   f"median |error|, {100 * b.median:.3g} %, "
                   f"{'within' if b.median <= tol else 'above'} {100 * tol:g} %")
        if b.missed:
            verdict += (f", but the continuum failed in bearing in {b.missed} run(s) of these "
                        "cells where this bed did not: near this scene the soil may not carry "
                        "the footing through the motion, which no error of a bed measures")
        lines.append(verdict)
    return lines
