"""A bed's run of a map point: the reduced model on the point's scene and motion, measured as
the continuum's run of it is (:func:`.points.measured`). Live, never stored: a bed runs in
milliseconds, and its module is kept apart from the continuum's point function, whose stored
runs are of the continuum alone."""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Mapping

import numpy as np

from ....scenes import scene_from_dict
from ...framework.measures import edge_uplift_history, reduced_edge_gap_history
from .grid import MEASURES
from .points import measured, motion_table, point_scene

__all__ = ["run_bed", "bed_scene", "bed_sway", "bed_soil_damping", "reduced_measures",
           "reduced_energy_terms"]


def bed_sway(continuum: Mapping) -> dict:
    """The ``[foundation]`` sway fields of a bed on a point whose continuum ``[continuum]``
    table is ``continuum``: the half-plane reference holds its footing to the free field by a
    tie (``horizontal_tie``, force/length per length, and ``horizontal_tie_damping``,
    force·time/length per length: :func:`.reference.reference_continuum`), and a bed then
    sways on the same spring and dashpot (``sway_stiffness``, ``sway_damping``) so that both
    models let the footing move against the ground alike; none on the box, whose footing
    does not sway."""
    tie = continuum.get("horizontal_tie")
    if tie is None:
        return {}
    damping = continuum.get("horizontal_tie_damping")
    return {"sway_stiffness": float(tie),
            **({"sway_damping": float(damping)} if damping else {})}


def bed_soil_damping(point: Mapping, foundation: Mapping) -> dict:
    """The bed's ``[foundation]`` table ``foundation`` with the soil damping of ``point``:
    where the continuum's soil has Rayleigh damping (``continuum.damping_ratio``, the
    half-plane reference's), a dashpot β k_i beside each spring, β (s) the continuum's own
    (:func:`~upliftlab.continuum.dynamics.rayleigh.scene_rayleigh` of the point's scene,
    :mod:`comparisons.beds.soil_damping`); ``foundation`` unchanged otherwise."""
    if point["scene"].get("continuum", {}).get("damping_ratio") is None:
        return dict(foundation)
    from ....continuum.dynamics.rayleigh import scene_rayleigh
    from ...beds.soil_damping import with_soil_damping

    scene = point_scene(point)
    return with_soil_damping(dict(foundation), scene_rayleigh(scene).beta,
                             vertical_mass=scene.structure.vertical_weight / scene.g)


def run_bed(point: Mapping, foundation: Mapping, analysis: Mapping | None = None) -> dict:
    """A bed's run of a point's motion (reduced model, live, not stored): the measures of
    :func:`measured`, its ``peak_settlement`` (the base centre's largest settlement, down),
    its wall time ``wall_time_s`` (the run alone, s), its foundation energy E_F and the
    work of gravity in it (``energy``, :func:`reduced_energy_terms`), or ``refused`` with the
    reason: the integrator's, or the reduced model's own cost check (a run above its
    ``analysis.max_steps`` is refused before it starts, as it would be for a user: on the
    half-plane a bed whose footing carries its own mass has a stiff mode the error-controlled
    integrator's first step resolves, and the q–z bed's on a record of a minute is above it).
    One bed's refusal leaves its error NaN at that point and the map goes on. ``analysis``:
    ``[analysis]`` keys of the bed's run over the point's (the macro-element's integrator and
    step, :func:`element_analysis`)."""
    from ....checks import InputError
    from ....reduced import IntegrationError, run as run_reduced

    scene = bed_scene(point, foundation, analysis)
    if analysis:
        scene = _resolved(scene)
    started = time.perf_counter()
    try:
        response = run_reduced(scene)
    except (IntegrationError, InputError) as exc:
        return {"refused": str(exc), "measures": dict.fromkeys(MEASURES, math.nan),
                "wall_time_s": time.perf_counter() - started}
    wall = time.perf_counter() - started
    return {"measures": reduced_measures(response), "wall_time_s": wall,
            "energy": reduced_energy_terms(response),
            "peak_settlement": float(np.max(response.settlement)),
            "energy_balance_error": float(response.peaks["energy_balance_error"])}


def element_analysis(options) -> dict:
    """The ``[analysis]`` keys of the macro-element's runs on the map: ``options.
    macro_integrator`` at steps of at most ``options.macro_dt`` (Newmark at 0.25 ms by default:
    on the half-plane the footing's own mass on the tie's dashpot is an overdamped mode that
    holds RK4 to about 2e-5 s; Newmark carries the element at 0.25 ms within 1e-3 of RK4,
    ``tests/test_winkler_map_macro.py``; at 1 ms revision 3's sharp reloading moved the clay's
    residual settlement by 2.1e-3), shortened where an implicit integrator could not
    resolve the point's shortest bonded period (:func:`_resolved`)."""
    return {"integrator": options.macro_integrator, "dt": float(options.macro_dt)}


def _resolved(scene):
    """``scene`` with its implicit step shortened to 0.95 of what resolves its shortest bonded
    period (:func:`~upliftlab.reduced.integrators.resolution_limit`: a light structure's
    footing sways faster), unchanged otherwise."""
    from ....reduced import build_model
    from ....reduced.integrators import method, resolution_limit

    a = scene.analysis
    if a.dt is None or method(a.integrator).explicit:
        return scene
    largest, _ = resolution_limit(build_model(scene))
    if a.dt <= largest:
        return scene
    data = copy.deepcopy(scene.data)
    data["analysis"] = {**data.get("analysis", {}), "dt": 0.95 * largest}
    return scene_from_dict(data, merged=True)


def bed_scene(point: Mapping, foundation: Mapping, analysis: Mapping | None = None):
    """The reduced model's scene of a bed (its ``[foundation]`` table ``foundation``) on a
    point: the point's structure and motion, the bed's foundation with the sway of
    :func:`bed_sway` and the soil damping of :func:`bed_soil_damping`, no soil or continuum
    tables."""
    data = copy.deepcopy(point["scene"])
    data["foundation"] = {**bed_soil_damping(point, foundation),
                          **bed_sway(data.get("continuum", {}))}
    if analysis:
        data["analysis"] = {**data.get("analysis", {}), **analysis}
    B = 2.0 * data["foundation"]["half_width"]
    data["motion"] = motion_table(point["motion"], point["intensity"], B,
                                  data["structure"]["height"])
    for table in ("soil", "continuum"):
        data.pop(table, None)
    return scene_from_dict(data, merged=True)


def reduced_measures(response) -> dict:
    """The measures of :func:`measured` of a reduced model's ``response`` (its peaks where the
    event stepper caught a peak between recorded steps). A base element (the macro-element)
    has no springs to read edge gaps from: its edge uplift is its own tracked peak, the larger
    gap under its edges at the steps' ends (``peaks["uplift_max"]``)."""
    t = np.asarray(response.time, dtype=float)
    if response.model.base is not None:
        uplift = float(response.peaks["uplift_max"])
    else:
        uplift = float(np.max(edge_uplift_history(reduced_edge_gap_history(response))))
    u_peak = max(float(np.max(np.abs(response.u))), float(response.peaks["u"]))
    theta = np.asarray(response.theta, dtype=float)
    out = measured(t - t[0], theta, uplift, np.asarray(response.settlement, dtype=float), u_peak,
                   np.max(np.abs(response.base_shear)))
    out["theta"] = max(out["theta"], float(response.peaks["theta"]))
    return out


def reduced_energy_terms(response) -> dict:
    """``foundation``: E_F of a reduced model's run (:mod:`.foundation_energy`: the energy its
    structure lost to the foundation, force·length per length) from the integrator's own
    energy account: the foundation's books, its springs' change of strain energy and its
    dashpot, impact and plastic work. The account books the story with them, so the story's
    strain energy ½ k u² and its dashpot's work ∫ c u̇² dt (trapezoidal over the stored rows)
    are taken out. ``gravity``: the work of the structure's weight over the run (its loss of
    gravity energy: W times the settlement)."""
    from ....reduced.response import ENERGY_NAMES

    e = np.asarray(response.energy, dtype=float)
    change = {name: e[-1, i] - e[0, i] for i, name in enumerate(ENERGY_NAMES)}
    model = response.model
    n = model.story_count
    k, c = model.params["k"][:n], model.params["c"][:n]
    s = np.asarray(response.deformation, dtype=float)[:, :n]
    story_strain = float(np.sum(0.5 * k * (s[-1] ** 2 - s[0] ** 2)))
    rate = np.asarray(response.qd, dtype=float) @ model.A[:, :n]
    power = (rate * rate) @ c
    t = np.asarray(response.time, dtype=float)
    story_dashpot = float(np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t)))
    foundation = (change["strain"] - story_strain + change["viscous"] - story_dashpot
                  + change["impact"] + change["plastic"])
    return {"foundation": float(foundation), "gravity": float(-change["gravity"])}
