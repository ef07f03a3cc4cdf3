"""The continuum ladder of ``upliftlab advise``: for a scene with ``[soil]``, certify the
Winkler map's calibrated beds against the continuum itself, not against a finer bed.

The reference is the continuum's dynamic run of the scene (explicit route, no snapshots, the
kernels compiled before the clock starts, as :func:`.winkler_map.points.evaluate_dynamic` runs
a map point) on a mesh ladder — 4, 8, 16 elements across (``fast``: 2, 4, 8) — measured as the
map measures both models (:func:`.winkler_map.points.measured`). The finest mesh is the
reference; its uncertainty is its relative change from the next-coarser mesh. Each bed of
:data:`..beds.BEDS` is built from the continuum statics of the scene's soil on the
finest mesh (K_v, K_r with every contact node tied; V_ult and the load–settlement path from a
vertical pushover, :func:`.winkler_map.statics.evaluate_static`; the elastic soil's dynamic
impedance for the beds with the continuum's dashpots, :mod:`.winkler_map.impedance_points`;
the two rotation pushovers at the scene's N, a cycle per amplitude and a monotonic path, for
the bed whose capacity profile is fitted to them, :mod:`..beds.fitted`), the scene's
N, B, h and ``[structure]``, and run on the
scene's own motion (the reduced model, the median of a few timed runs after an untimed one).
A bed is certified when |error| + the reference's uncertainty ≤ tol; the advisor recommends the
certified bed of least modelled cost (:data:`PICK_RULE`: the work its run counted, not its
measured runtime, so the pick is the same on every run), with its speed ratio against the
reference run.
Errors are (bed − continuum)/max(|continuum|, floor), the floor the map's: a tenth of the
measure's value at a uniform bed's uplift threshold (:func:`.winkler_map.points.scales`).

The cost of the continuum runs is estimated before any of them (:mod:`.winkler_map.cost`), at
the rates of the map's runs kept with the repository when the package runs from a checkout
(this machine's measured rates, as the map's own estimate), else at the defaults; above
``budget`` the ladder is refused, unless the scene falls inside a Winkler map
(:mod:`.advise_map`), whose evidence is then reported in place of runs that were not made.
"""

from __future__ import annotations

import copy
import math
import statistics
import time
from dataclasses import asdict, dataclass

import numpy as np

from ...anchors import half_plane_onset_rotation
from ...budget import MACRO_SECONDS_PER_STEP
from ...checks import InputError
from ...log import logger
from ...scenes import Scene, scene_from_dict
from ...units import unit_system
from .macro import MACRO_NEEDS, read_macro_calibration
from .map_evidence import MapEvidence, find_map, format_evidence, map_evidence
from ..framework.protocol import CHECKOUT
from ..framework.store import Store
from ..framework.study import relative_error
from ..beds import BEDS, BedReference, base_table, bed_foundation
from ..beds.continuum_points import evaluate_continuum
from ..studies.winkler_map import (FAST_OPTIONS, FLOOR_FRACTION, FULL_OPTIONS, KEPT_STORE,
                                   Estimate, continuum_measures, estimate_cost, evaluate_impedance,
                                   evaluate_static, impedance_dofs, impedance_point_of,
                                   pushover_points, reduced_measures, scales, soil_impedance,
                                   story_constants, timed_dynamic_runs)

__all__ = ["FULL_MESHES", "FAST_MESHES", "MeshRun", "ContinuumReference", "SoilNumbers",
           "BedCheck", "ContinuumPlan", "ContinuumAdvice", "plan_continuum", "run_continuum",
           "continuum_run", "bed_run", "soil_numbers", "scene_impedance", "scene_pushovers",
           "bed_reference", "kept_timings", "format_continuum", "Work", "work_of", "select_bed",
           "COST_MODEL", "PICK_RULE"]

FULL_MESHES = (4, 8, 16)
FAST_MESHES = (2, 4, 8)
BED_REPEATS = 3

#: The modelled cost of a reduced run (s): RUN_SECONDS + SPRING_CALL_SECONDS[integrator] × rhs
#: calls × (springs + SPRING_OFFSET). Fitted (least squares of the relative error) to 92 runs
#: timed on the project's shared 2-core machine on 2026-11-28: short_period_elcentro Cases A
#: and B under the advisor tests' one-cycle sine pulse (2.9 s), N = 2 to 320 springs, each
#: integrator at the ladder's first two stable steps, the fastest of 7 runs after a warm-up.
#: RMS relative error of the fit 24 % (events), 22 % (rk4), 23–24 % (newmark, hht), 50 % (abm4,
#: whose fixed cost it lacks); the same runs' repeats spread by up to 40 % on the loaded machine.
RUN_SECONDS = 8.3e-3
#: Per rhs call and spring (s); an rhs call of the event stepper is cheaper than RK4's.
SPRING_CALL_SECONDS = {"events": 6.6e-9, "rk4": 1.47e-8, "abm4": 4.9e-8, "newmark": 7.8e-8,
                       "hht": 8.2e-8}
#: The part of an rhs call that does not grow with N (the DOFs, the ground motion), in springs.
SPRING_OFFSET = 25
#: The cost model in words, as both ladders state it.
COST_MODEL = (f"modelled cost = {RUN_SECONDS * 1e3:g} ms + s(integrator) × rhs calls × (springs "
              f"+ {SPRING_OFFSET}), the rhs calls (evaluations of the equations of motion) and "
              "the springs counted on the candidate's own run, the same on every run of the "
              "scene; s(integrator) measured once on this machine (events "
              f"{SPRING_CALL_SECONDS['events'] * 1e9:g} ns, rk4 "
              f"{SPRING_CALL_SECONDS['rk4'] * 1e9:g} ns); a macro-element's run adds "
              f"{MACRO_SECONDS_PER_STEP * 1e6:g} µs a step")
#: Why a measured runtime does not decide, as both ladders state it.
NOT_TIMED = ("measured runtimes are reported beside it and do not decide: on this shared "
             "machine a run's repeats spread by tens of percent, enough to swap candidates from "
             "one run of the advisor to the next")
#: How the continuum ladder picks a bed (stated in its advice).
PICK_RULE = ("of the beds that meet the tolerance, the least modelled cost (" + COST_MODEL
             + "); ties go to fewer springs, then the map's order of the beds; " + NOT_TIMED)


@dataclass(frozen=True)
class Work:
    """What a reduced run computed, counted (the same on every run with the same inputs): its
    ``integrator``, ``springs`` (every spring of the model, the stories' included), ``steps``
    and ``rhs_calls`` (evaluations of the equations of motion, ``info["counters"][2]``);
    ``seconds`` the modelled cost (s, :data:`RUN_SECONDS` and the rates beside it)."""

    integrator: str
    springs: int
    steps: int
    rhs_calls: int
    seconds: float


def work_of(response) -> Work:
    """The counted work of a reduced run's ``response``, with its modelled cost (s)."""
    info = response.info
    springs, calls = int(response.model.spring_count), int(info["counters"][2])
    rate = SPRING_CALL_SECONDS[info["integrator"]]
    element = (MACRO_SECONDS_PER_STEP * int(info["steps"])
               if response.model.base is not None else 0.0)  # a macro-element's steps
    return Work(info["integrator"], springs, int(info["steps"]), calls,
                RUN_SECONDS + rate * calls * (springs + SPRING_OFFSET) + element)


@dataclass(frozen=True)
class MeshRun:
    """One continuum run of the ladder: ``elements_across``, ``dofs``, the quantity's
    ``value`` (scene units), ``steps``, ``dt`` (s), ``wall_time_s`` (model, gravity and time
    loop, s) and ``energy_balance_error`` (fraction of the input)."""

    elements_across: int
    dofs: int
    value: float
    steps: int
    dt: float
    wall_time_s: float
    energy_balance_error: float


@dataclass(frozen=True)
class ContinuumReference:
    """The ladder's runs, coarse to fine; the reference is the finest, its ``uncertainty`` the
    relative change from the next-coarser mesh (over max(|value|, ``floor``))."""

    runs: tuple[MeshRun, ...]
    floor: float

    @property
    def finest(self) -> MeshRun:
        return self.runs[-1]

    @property
    def value(self) -> float:
        return self.finest.value

    @property
    def uncertainty(self) -> float:
        return abs(relative_error(self.runs[-2].value, self.value, self.floor))


@dataclass(frozen=True)
class SoilNumbers:
    """The continuum statics of the scene's soil the beds are built from, on
    ``elements_across``: ``K_v`` (force/length/length), ``K_r`` (force·length/rad/length),
    ``V_ult`` (force/length), ``fs_v`` = V_ult/N, the vertical pushover's ``settlement``
    (length) and ``load`` (force/length), ``wall_time_s`` of both analyses (s)."""

    elements_across: int
    K_v: float
    K_r: float
    V_ult: float
    fs_v: float
    wall_time_s: float
    settlement: tuple[float, ...] = ()
    load: tuple[float, ...] = ()


@dataclass(frozen=True)
class BedCheck:
    """A bed against the continuum reference: ``value``, signed relative ``error``,
    ``wall_time_s`` (median of the timed runs, s), ``speed_ratio`` (reference run's wall time
    over the bed's), ``meets`` (|error| + reference uncertainty ≤ tol), or ``failure``;
    ``work`` its run's counted work and modelled cost (None when refused), what the pick
    ranks by (:data:`PICK_RULE`)."""

    name: str
    label: str
    value: float
    error: float
    wall_time_s: float
    speed_ratio: float
    meets: bool
    failure: str | None = None
    work: Work | None = None


@dataclass(frozen=True)
class ContinuumPlan:
    """What the ladder will run and what it should cost, decided before any run: ``meshes``,
    ``estimate`` (seconds of one worker, the statics included, the explicit loop's one-off
    compilation not), ``run`` (False: over ``budget``, the map's evidence stands in),
    ``map`` the map's evidence (None: no map), ``macro`` the macro-element's calibration of
    the scene's soil (``upliftlab calibrate``'s record; None: the ``macro`` bed is not
    built)."""

    meshes: tuple[int, ...]
    estimate: Estimate
    budget: float | None
    run: bool
    map: MapEvidence | None
    map_path: str | None
    macro: dict | None = None


@dataclass(frozen=True)
class ContinuumAdvice:
    """The continuum ladder's outcome for ``quantity`` (the map's ``measure``) within
    ``tolerance``: the ``plan``, the ``reference`` and ``statics`` (None when not run), each
    bed's check, the ``recommendation`` (None: ``reason`` says why) and the map's evidence;
    ``rule`` how the recommendation is picked (:data:`PICK_RULE`)."""

    quantity: str
    measure: str
    tolerance: float
    plan: ContinuumPlan
    reference: ContinuumReference | None
    statics: SoilNumbers | None
    beds: tuple[BedCheck, ...]
    recommendation: BedCheck | None
    reason: str
    map: MapEvidence | None
    rule: str = PICK_RULE

    def to_dict(self) -> dict:
        out = asdict(self)
        out["certified_against"] = certified_against_continuum(self)
        out["plan"]["estimate"] = {"seconds": self.plan.estimate.seconds,
                                   "text": self.plan.estimate.text()}
        if self.reference is not None:
            out["reference"].update(value=self.reference.value,
                                    uncertainty=self.reference.uncertainty,
                                    elements_across=self.reference.finest.elements_across)
        return out


def _at_mesh(scene: Scene, elements_across: int) -> Scene:
    """The scene on ``elements_across`` (its ``[continuum]`` table made if it has none)."""
    return scene.with_overrides(f"continuum.elements_across={int(elements_across)}")


def _duration(scene: Scene) -> float:
    return float(scene.analysis.duration or scene.build_motion().duration)


def kept_timings() -> list[dict]:
    """The timed dynamic runs of the Winkler map kept with the repository under the current
    code (:data:`.winkler_map.workflow.KEPT_STORE`), when the package runs from a checkout that
    has them; else none (the estimate's default rates)."""
    kept = CHECKOUT / KEPT_STORE
    return timed_dynamic_runs(Store(kept)) if kept.is_dir() else []


def plan_continuum(scene: Scene, measure: str, tol: float, *, fast: bool = False,
                   budget: float | None = None, map_path=None,
                   macro_calibration=None) -> ContinuumPlan:
    """Check the scene, estimate the ladder's cost and read the map, before any run; over
    ``budget`` (s) refuse (:class:`InputError`) unless the scene falls inside the map.
    ``macro_calibration``: ``upliftlab calibrate``'s file (:mod:`.macro`)."""
    macro = (read_macro_calibration(macro_calibration, scene)
             if macro_calibration is not None else None)
    base_units = unit_system(base_table()["units"])
    if scene.units != base_units:
        raise InputError(f"units = {scene.data.get('units')!r}: the continuum ladder builds its "
                         f"beds from the map's statics, in {base_table()['units']!r}; write the "
                         "scene in those units")
    meshes = FAST_MESHES if fast else FULL_MESHES
    scenes = [_at_mesh(scene, n) for n in meshes]
    soil = scene.soil.model
    impedance = _impedance_point(scene, meshes[-1])
    options = FAST_OPTIONS if fast else FULL_OPTIONS
    rotations = [(soil, scenes[-1], False, len(p["rotations"]) / (options.vertical_steps + 1))
                 for p in _pushover_points(scene, meshes[-1], fast)]
    estimate = estimate_cost([(soil, scenes[-1], False), *rotations],
                             [(soil, s, _duration(scene), False) for s in scenes], [],
                             kept_timings(),
                             [(soil, impedance_dofs(impedance),
                               len(impedance["impedance"]["a0"]), False)], [])
    path = find_map(map_path)
    evidence = map_evidence(path, scene, measure, tol) if path is not None else None
    ladder = ", ".join(map(str, meshes))
    logger("advise").info(f"advise: continuum ladder on {ladder} elements across: "
                          f"{estimate.text()}")
    run = budget is None or estimate.seconds <= budget
    if not run and not (evidence is not None and evidence.inside):
        where = ("no Winkler map to fall back on (--map, or results/winkler_map/map.nc)"
                 if evidence is None else f"the scene is outside the map: {evidence.outside}")
        raise InputError(f"--budget = {budget:g} s: the continuum ladder ({ladder} elements "
                         f"across) is estimated at {estimate.seconds:.0f} s; valid range is "
                         f"[{math.ceil(estimate.seconds)}, ...) s"
                         f"{'' if fast else ', or --fast'}; {where}")
    return ContinuumPlan(tuple(meshes), estimate, budget, run, evidence,
                         None if path is None else str(path), macro)


# ---------------------------------------------------------------------------------------------
# The runs: the continuum on one mesh, a bed, the statics
# ---------------------------------------------------------------------------------------------

def _dynamic(scene: Scene, duration: float | None = None):
    from ...continuum import build_model
    from ...continuum.dynamics.run import DynamicOptions, run_dynamic

    started = time.perf_counter()
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(snapshots=0, energy=False, method="explicit",
                                        duration=duration))
    return model, result, time.perf_counter() - started


def continuum_run(scene: Scene) -> dict:
    """One continuum dynamic run of ``scene`` (explicit route, no snapshots): the measures of
    :func:`.winkler_map.points.measured` from every recorded step, ``dofs``, ``steps``, ``dt``
    (s), ``energy_balance_error`` and its wall time ``wall_time_s`` (s), the explicit loop
    compiled before (an untimed run of 0.02 s on 2 elements across)."""
    _dynamic(_at_mesh(scene, 2), duration=0.02)
    model, result, wall = _dynamic(scene)
    t, *_, measures = continuum_measures(scene, result)
    return {"measures": measures,
            "dofs": int(model.dofs), "steps": int(result.metadata.get("steps", t.size - 1)),
            "dt": float(result.metadata.get("dt", math.nan)),
            "energy_balance_error": float(result.metadata.get("energy_balance_error",
                                                              math.nan)),
            "wall_time_s": wall}


def bed_scene(scene: Scene, foundation: dict) -> Scene:
    """The reduced model's scene of a bed: ``scene`` with the bed's ``[foundation]`` table and
    without ``[soil]`` and ``[continuum]``."""
    data = copy.deepcopy(scene.data)
    data["foundation"] = dict(foundation)
    for table in ("soil", "continuum"):
        data.pop(table, None)
    return scene_from_dict(data, merged=True)


def bed_run(scene: Scene, foundation: dict, repeats: int = BED_REPEATS) -> dict:
    """A bed's run of the scene's motion, measured as :func:`.winkler_map.bed_runs.run_bed`
    measures it: ``measures``, ``wall_time_s`` (median of ``repeats`` timed runs after an
    untimed one, s) and its counted ``work`` (:class:`Work`), or ``refused`` with the
    integrator's reason."""
    from ...reduced import IntegrationError, run as run_reduced

    reduced_scene = bed_scene(scene, foundation)
    walls = []
    try:
        for i in range(repeats + 1):
            started = time.perf_counter()
            response = run_reduced(reduced_scene)
            if i:
                walls.append(time.perf_counter() - started)
    except IntegrationError as exc:
        return {"refused": str(exc)}
    return {"measures": reduced_measures(response), "wall_time_s": statistics.median(walls),
            "work": work_of(response)}


def soil_numbers(scene: Scene, elements_across: int, fast: bool) -> SoilNumbers:
    """The continuum statics of the scene's soil on ``elements_across``: stiffness in full
    contact and a vertical pushover to 5 % of B (the map's, in its fast or full steps)."""
    options = FAST_OPTIONS if fast else FULL_OPTIONS
    B = scene.foundation.width
    point = {"soil": copy.deepcopy(scene.data["soil"]),
             "continuum": {**copy.deepcopy(scene.data.get("continuum", {})),
                           "elements_across": int(elements_across)},
             "half_width": 0.5 * B}
    settlements = np.linspace(0.0, options.settlement_ratio * B, options.vertical_steps + 1)[1:]
    stiffness = evaluate_static({**point, "analysis": "stiffness"})
    vertical = evaluate_static({**point, "analysis": "vertical",
                                "settlements": [float(s) for s in settlements]})
    V_ult = vertical["capacity"]
    return SoilNumbers(int(elements_across), stiffness["K_v"], stiffness["K_r"], V_ult,
                       V_ult / scene.structure.weight,
                       stiffness["wall_time_s"] + vertical["wall_time_s"],
                       tuple(vertical["settlement"]), tuple(vertical["N"]))


def _impedance_point(scene: Scene, elements_across: int) -> dict:
    continuum = {**copy.deepcopy(scene.data.get("continuum", {})),
                 "elements_across": int(elements_across)}
    return impedance_point_of(scene.data["soil"], continuum, 0.5 * scene.foundation.width)


def scene_impedance(scene: Scene, elements_across: int):
    """The footing's dynamic impedance (:class:`~upliftlab.continuum.impedance.analysis.Impedance`)
    on
    the scene's soil made linear elastic, on ``elements_across``, at the map's frequencies."""
    point = _impedance_point(scene, elements_across)
    return soil_impedance(point, evaluate_impedance(point))


def _onset_rotation(scene: Scene) -> float:
    """θ_on = 2N(1 − ν)/(π G B), the elastic half-plane's uplift rotation of the scene (rad)."""
    soil = scene.soil
    return half_plane_onset_rotation(scene.structure.weight, scene.foundation.width,
                                     soil.shear_modulus, soil.poisson_ratio)


def _pushover_points(scene: Scene, elements_across: int, fast: bool) -> list[dict]:
    table = {k: copy.deepcopy(v) for k, v in scene.data.items() if k != "motion"}
    table["continuum"] = {**table.get("continuum", {}), "elements_across": int(elements_across)}
    table["motion"] = {"type": "free", "velocity": 1.0, "duration": 1.0}  # unused
    return pushover_points(table, scene.structure.weight, _onset_rotation(scene),
                           FAST_OPTIONS if fast else FULL_OPTIONS)


def scene_pushovers(scene: Scene, elements_across: int, fast: bool) -> dict:
    """The continuum's two rotation pushovers of the scene under its N on ``elements_across``
    (the map's paths, scaled by θ_on): ``cyclic``, ``monotonic`` and ``theta_on``, or
    ``error`` when the soil could not follow a path (the fitted bed is then refused, with
    it)."""
    cyclic, monotonic = (evaluate_continuum(p) for p in
                         _pushover_points(scene, elements_across, fast))
    errors = [f"{name}: {r['error']}" for name, r in (("cyclic", cyclic),
                                                      ("monotonic", monotonic)) if "error" in r]
    if errors:
        return {"error": "; ".join(errors)}
    return {"cyclic": cyclic, "monotonic": monotonic, "theta_on": _onset_rotation(scene)}


def bed_reference(scene: Scene, statics: SoilNumbers, impedance,
                  pushovers: dict | None = None, macro: dict | None = None) -> BedReference:
    """The continuum numbers the beds are built from: the statics, the scene's N, B, h,
    density and ``[structure]``, the pushover, the impedance and the rotation pushovers; the
    macro-element's calibration (``macro``, :func:`read_macro_calibration`) and the scene's
    own sway stiffness where it has them."""
    soil = scene.soil
    extra = {"density": soil.density, "structure": copy.deepcopy(scene.data["structure"]),
             "settlement": statics.settlement, "load": statics.load, "impedance": impedance}
    if pushovers is not None:
        extra["rocking"] = pushovers
    if macro is not None:
        extra["macro"] = macro
    if scene.foundation.sway_stiffness is not None:
        extra["sway_stiffness"] = float(scene.foundation.sway_stiffness)
    return BedReference(soil.model, scene.structure.weight, scene.foundation.width,
                        scene.structure.height, statics.K_v, statics.K_r, statics.V_ult,
                        soil.shear_modulus, soil.poisson_ratio, extra=extra)


# ---------------------------------------------------------------------------------------------
# The ladder
# ---------------------------------------------------------------------------------------------

def _progress(step: str, started: float, done: float, total: float) -> None:
    elapsed = time.perf_counter() - started
    left = max(0.0, total - done)
    logger("advise").info(f"advise: {step}; {elapsed:.0f} s elapsed, about {left:.0f} s of "
                          "continuum runs left (estimate)")


def run_continuum(scene: Scene, quantity: str, measure: str, tol: float, plan: ContinuumPlan,
                  *, fast: bool = False) -> ContinuumAdvice:
    """Run the plan: the mesh ladder, the statics, every bed; certify and recommend."""
    if not plan.run:
        return ContinuumAdvice(quantity, measure, tol, plan, None, None, (), None,
                               f"the continuum was not run: its ladder is estimated at "
                               f"{plan.estimate.seconds:.0f} s, above --budget = "
                               f"{plan.budget:g} s; the map's evidence below is the map's, not "
                               "a measurement of this scene, and certifies nothing", plan.map)
    started = time.perf_counter()
    per_run = plan.estimate.seconds / (len(plan.meshes) + 1)
    runs = []
    for i, n in enumerate(plan.meshes):
        _progress(f"continuum on {n} elements across ({i + 1}/{len(plan.meshes)})", started,
                  i * per_run, plan.estimate.seconds)
        r = continuum_run(_at_mesh(scene, n))
        runs.append(MeshRun(n, r["dofs"], r["measures"][measure], r["steps"], r["dt"],
                            r["wall_time_s"], r["energy_balance_error"]))
    _progress(f"continuum statics on {plan.meshes[-1]} elements across", started,
              len(plan.meshes) * per_run, plan.estimate.seconds)
    statics = soil_numbers(scene, plan.meshes[-1], fast)
    pushovers = scene_pushovers(scene, plan.meshes[-1], fast)
    reference_numbers = bed_reference(scene, statics, scene_impedance(scene, plan.meshes[-1]),
                                      pushovers, plan.macro)
    B, h, N = scene.foundation.width, scene.structure.height, scene.structure.weight
    floor = FLOOR_FRACTION * scales(N, B, h, statics.K_v, statics.K_r,
                                    story_constants(scene)[0])[measure]
    ref = ContinuumReference(tuple(runs), floor)
    options = FAST_OPTIONS if fast else FULL_OPTIONS
    beds = []
    for name, entry in BEDS.items():
        try:
            if name == "macro" and plan.macro is None:
                raise InputError(MACRO_NEEDS)
            table = bed_foundation(name, reference_numbers, options)
            r = bed_run(scene, table)
        except InputError as exc:  # e.g. a rocking frequency outside the impedance's a0
            r = {"refused": f"cannot be built for this scene: {exc}"}
        if "refused" in r:
            beds.append(BedCheck(name, entry.label, math.nan, math.nan, math.nan, math.nan,
                                 False, r["refused"]))
            continue
        value = r["measures"][measure]
        error = relative_error(value, ref.value, floor)
        beds.append(BedCheck(name, entry.label, value, error, r["wall_time_s"],
                             ref.finest.wall_time_s / r["wall_time_s"],
                             abs(error) + ref.uncertainty <= tol, work=r["work"]))
    evidence = plan.map
    if plan.map_path is not None and evidence is not None and evidence.soil and \
            not evidence.coordinates:  # no statics.nc beside the map: FS_v on this capacity
        evidence = map_evidence(plan.map_path, scene, measure, tol, V_ult=statics.V_ult)
    best = select_bed(beds)
    if best is not None:
        reason = ("the certified bed (|error| plus the continuum reference's uncertainty within "
                  "the tolerance) of least modelled cost, by the rule below")
    elif ref.uncertainty >= tol:
        reason = (f"the continuum reference is not converged to what {100 * tol:g} % needs: "
                  f"it changes by {100 * ref.uncertainty:.3g} % from {runs[-2].elements_across}"
                  f" to {runs[-1].elements_across} elements across; no bed can be certified")
    else:
        finite = [b for b in beds if math.isfinite(b.error)]
        closest = min(finite, key=lambda b: abs(b.error)) if finite else None
        reason = ("no bed is within the tolerance" + (
            f"; the closest, {closest.name}, is off by {100 * closest.error:.3g} % (+ the "
            f"reference's uncertainty {100 * ref.uncertainty:.3g} %)" if closest else "")
                  + "; use the continuum")
    return ContinuumAdvice(quantity, measure, tol, plan, ref, statics, tuple(beds), best,
                           reason, evidence)


def select_bed(beds) -> BedCheck | None:
    """The pick among ``beds`` (:data:`PICK_RULE`): of those that meet the tolerance, the least
    modelled cost, ties to fewer springs, then the order of :data:`..beds.BEDS`.
    Runtimes do not enter, so the same checks give the same pick on every run."""
    order = list(BEDS)

    def key(b: BedCheck) -> tuple:
        rank = order.index(b.name) if b.name in order else len(order)
        return (b.work.seconds, b.work.springs, rank, b.name)

    passing = [b for b in beds if b.meets]
    return min(passing, key=key) if passing else None


def certified_against_continuum(a: ContinuumAdvice) -> str:
    """What the bed errors are measured against, in words."""
    if a.reference is None:
        return ("nothing: the continuum was not run (over --budget); the map's numbers are "
                "the map's own measurements on its scenes")
    r, prev = a.reference.finest, a.reference.runs[-2]
    return (f"the continuum (plane strain, explicit route) on {r.elements_across} elements "
            f"across ({r.dofs} DOFs), with an uncertainty of {100 * a.reference.uncertainty:.3g}"
            f" % (its change from {prev.elements_across} across)")


def format_continuum(a: ContinuumAdvice) -> list[str]:
    """The continuum ladder as text lines."""
    e = a.plan.estimate
    lines = [f"continuum ladder: {', '.join(map(str, a.plan.meshes))} elements across, "
             f"estimated {e.seconds:.0f} s before running (plus the explicit loop's "
             "compilation once per process)"]
    if a.reference is not None:
        for r in a.reference.runs:
            lines.append(f"  {r.elements_across:3d} across ({r.dofs:6d} DOFs, {r.steps} steps "
                         f"of {r.dt:.3g} s): {a.quantity} = {r.value:.6g}, {r.wall_time_s:.3g} "
                         f"s, energy balance {100 * r.energy_balance_error:.2g} %")
        s = a.statics
        lines.append(f"  reference: {a.quantity} = {a.reference.value:.6g} on "
                     f"{a.reference.finest.elements_across} across, uncertainty "
                     f"{100 * a.reference.uncertainty:.3g} %; statics on {s.elements_across} "
                     f"across: K_v = {s.K_v:.6g}, K_r = {s.K_r:.6g}, V_ult = {s.V_ult:.6g} "
                     f"(FS_v = {s.fs_v:.3g})")
        lines.append("beds against the continuum (measured on this scene):")
        for b in a.beds:
            if b.failure:
                lines.append(f"  {b.name:26s} refused: {b.failure}")
                continue
            lines.append(f"  {b.name:26s} error {100 * b.error:8.3g} %  modelled "
                         f"{b.work.seconds * 1e3:8.3f} ms  runtime {b.wall_time_s * 1e3:8.3f} ms"
                         f"  {b.speed_ratio:8.4g}× faster  {'meets' if b.meets else 'fails'}")
        lines.append(f"certified against: {certified_against_continuum(a)}")
    if a.recommendation is None:
        lines.append(f"continuum recommendation: none — {a.reason}")
    else:
        b = a.recommendation
        lines.append(f"continuum recommendation: {b.name} ({b.label}): error "
                     f"{100 * b.error:.3g} % (+ reference uncertainty "
                     f"{100 * a.reference.uncertainty:.3g} %) ≤ {100 * a.tolerance:g} %, "
                     f"modelled {b.work.seconds * 1e3:.3g} ms (measured "
                     f"{b.wall_time_s * 1e3:.3g} ms, {b.speed_ratio:.4g}× faster than the "
                     "continuum reference run)")
    if a.reference is not None:
        lines.append(f"continuum pick: {a.rule}")
    if a.map is not None:
        lines += format_evidence(a.map, a.tolerance)
    else:
        lines.append("map: none (give --map PATH to a winkler_map map.nc, or run the study "
                     "into results/winkler_map)")
    return lines
