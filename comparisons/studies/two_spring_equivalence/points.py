"""One point of the study: the base scene, the scene of a point (bed or two-spring layout,
motion) and its evaluation by the reduced model (the sweep's point function)."""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass, field


from ....checks import InputError
from ....reduced import IntegrationError, run as run_reduced
from ....reduced.compatibility import layout_for
from ....reduced.response import ENERGY_NAMES
from ....scenes import Scene, load_scene, scene_from_dict
from ...framework.measures import reduced_peak_edge_gap, reduced_plastic_settlement
from ...framework.store import point_function
from .grid import CASES, Options, PULSE_TAIL


# ---------------------------------------------------------------------------------------------
# Points: one reduced-model run each, evaluated in the sweep's workers
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Base:
    """The base scene as a table, and its h/b, period (s) and yield multiple."""

    table: dict = field(repr=False)
    h_over_b: float
    period: float
    yield_multiple: float
    name: str


def load_base(scene: str | Scene) -> Base:
    """The base scene: a one-story structure on an uplifting foundation."""
    scene = scene if isinstance(scene, Scene) else load_scene(scene)
    s, f = scene.structure, scene.foundation
    if len(s.stories) != 1 or s.rigid:
        raise InputError(f"scene {scene.name!r}: the study varies h/b and the period of a "
                         "one-story flexible structure (structure.story is a list, or rigid)")
    if f.support != "uplift":
        raise InputError(f"scene {scene.name!r}: foundation.support = {f.support!r}; the study "
                         "needs 'uplift'")
    table = {k: copy.deepcopy(scene.data[k]) for k in ("schema", "units", "structure",
                                                       "foundation", "analysis")
             if k in scene.data}
    story = s.stories[0]
    period = 2.0 * math.pi * math.sqrt(story.weight / scene.g / story.stiffness)
    return Base(table, story.height / f.half_width, period, f.law.yield_multiple, scene.name)


def _foundation_point(bed: str, layout: str, springs: int, options: Options) -> dict:
    """The foundation entries of a point. Edges and equivalent springs depend on no bed."""
    if layout in ("edges", "equivalent"):
        return {"bed": None, "layout": layout, "springs": None}
    out = {"bed": bed, "layout": layout, "springs": int(springs)}
    if bed == "end_stiffened":
        out.update(end_stiffness_ratio=options.end_stiffness_ratio,
                   end_length=options.end_length)
    return out


def make_point(base: Base, *, bed: str, layout: str, springs: int, options: Options,
               case: str, motion: Mapping, h_over_b: float | None = None,
               period: float | None = None, yield_multiple: float | None = None,
               restitution: float | None = None) -> dict:
    """A point: the base scene, the foundation (layout and case), the structure, the motion."""
    foundation = {**CASES[case], "yield_multiple": yield_multiple or base.yield_multiple}
    if restitution is not None:
        foundation["restitution"] = restitution
    foundation.update(_foundation_point(bed, layout, springs, options))
    structure = {"h_over_b": h_over_b or base.h_over_b, "period": period or base.period}
    return {"scene": base.table, "foundation": foundation, "structure": structure,
            "motion": dict(motion)}


def _layout_table(f: Mapping, table: dict, structure: dict, units: str) -> dict:
    """Foundation table entries for the point's layout (K_v kept; calibrated from the bed)."""
    for key in ("layout", "springs", "end_stiffness_ratio", "end_length", "positions",
                "stiffnesses"):
        table.pop(key, None)
    if f["layout"] in ("edges", "equivalent"):
        return {**table, "layout": f["layout"], "springs": 2}
    bed = {"layout": "winkler", "springs": f["springs"]}
    if f["bed"] == "end_stiffened":
        bed = {"layout": "end_stiffened", "springs": f["springs"],
               "end_stiffness_ratio": f["end_stiffness_ratio"], "end_length": f["end_length"]}
    if f["layout"] == "winkler":
        return {**table, **bed}
    reference = _validated({**table, **bed}, structure, units)
    layout = layout_for(reference.foundation)
    x = math.sqrt(layout.rocking_stiffness / layout.vertical_stiffness)
    kv = layout.vertical_stiffness
    for key in ("stiffness", "vertical_period"):
        table.pop(key, None)
    return {**table, "layout": "custom", "positions": [-x, x], "stiffnesses": [kv / 2, kv / 2]}


def _validated(foundation: dict, structure: dict, units: str) -> Scene:
    data = {"schema": 1, "units": units, "structure": structure, "foundation": foundation,
            "motion": {"type": "free", "velocity": 1.0, "duration": 1.0}}
    return scene_from_dict(data)


def _motion_table(motion: Mapping, b: float, h: float) -> dict:
    """The scene's motion table: intensity × a_up = g·b/(3h), a pulse or a scaled record."""
    if motion["type"] == "free":
        return {"type": "free", "velocity": 1.0, "duration": 1.0}
    amplitude = motion["intensity"] * b / (3.0 * h)  # in g
    if motion["type"] == "record":
        return {"type": "record", "name": motion["_path"], "pga": amplitude}
    table = {"type": motion["type"], "amplitude": amplitude, "period": motion["period"],
             "duration": 3.0 * motion["period"] + PULSE_TAIL}
    if motion["type"] == "sine":
        table["cycles"] = 1.0
    return table


def point_scene(point: Mapping) -> Scene:
    """The validated scene of a point."""
    data = copy.deepcopy(point["scene"])
    structure, foundation = data["structure"], data["foundation"]
    b = foundation["half_width"]
    h = point["structure"]["h_over_b"] * b
    structure["rotary_inertia"] *= (h / structure["height"]) ** 2  # base body scales with h
    structure["height"] = h
    structure.pop("stiffness", None)
    structure["period"] = point["structure"]["period"]
    f = point["foundation"]
    for key in ("law", "damping_ratio", "restitution", "yield_multiple"):
        foundation[key] = f[key]
    data["foundation"] = _layout_table(f, foundation, structure, data["units"])
    data["motion"] = _motion_table(point["motion"], b, h)
    return scene_from_dict(data)


def _scales(model) -> dict:
    """Each measure's value at the uniform bed's quasi-static uplift threshold (floors' basis)."""
    weight, kv = model.weight, model.layout.vertical_stiffness
    b, h = model.layout.half_width, float(model.heights[-1])
    settlement = weight / kv
    shear = weight * b / (3.0 * h)
    return {"u": shear / model.scene.structure.stories[0].stiffness,
            "theta": weight / (kv * b), "uplift": settlement,
            "residual_settlement": settlement, "base_shear": shear,
            "dissipated_energy": 0.5 * weight * settlement}


@point_function("upliftlab.comparisons.two_spring_equivalence:evaluate_point",
                models=("reduced",), tolerance=1e-6)
def evaluate_point(point: Mapping) -> dict:
    """Run one point; its six measures, diagnostics and scales (units of the scene).

    A run the integrator refuses (chattering, divergence) gives ``{"error": message}``.
    """
    scene = point_scene(point)
    try:
        response = run_reduced(scene)
    except IntegrationError as exc:
        return {"error": str(exc)}
    pk, energy = response.peaks, response.energy[-1]
    dissipated = sum(float(energy[ENERGY_NAMES.index(k)]) for k in ("viscous", "impact",
                                                                     "plastic"))
    return {"u": pk["u"], "theta": pk["theta"], "uplift": reduced_peak_edge_gap(response),
            "residual_settlement": reduced_plastic_settlement(response),
            "base_shear": pk["base_shear"],
            "dissipated_energy": dissipated, "spring_uplift": pk["uplift_max"],
            "input_energy": float(energy[0]),
            "energy_balance_error": pk["energy_balance_error"], "scales": _scales(response.model)}
