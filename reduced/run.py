"""Run a scene through the reduced model: choose the step, integrate, return a
:class:`Response`."""

from __future__ import annotations

import math
import time as _time
import warnings
from dataclasses import dataclass

import numpy as np

from ..budget import REDUCED_BUDGET_SECONDS, time_budget
from ..checks import InputError
from ..log import announce_compilation, logger
from ..motions import Motion, motion_checksum
from ..provenance import provenance
from ..scenes import Scene
from ..time_schemes import hht
from . import kernels as kn
from .cost import check_run_cost
from .integrators import METHODS, StepPlan, method, time_step
from .laws import curved_kinds, initial_history
from .laws.macro.compiled import S_COUNT, W_COUNT, pack
from .laws.macro.plastic import FAILURES as MACRO_FAILURES
from .model import ReducedModel, build_model
from .peak_slots import decode_peaks, start_peaks, static_energy
from .response import Response, ground_displacement
from .static import initial_state

__all__ = ["run", "run_model", "initial_conditions", "IntegrationError", "EnergyBalanceError",
           "ModelWarning",
           "KernelInputs", "integrate", "ground_acceleration", "frame_of", "story_table"]


class IntegrationError(RuntimeError):
    """The integration could not proceed (chattering, divergence, Newton failure)."""


class EnergyBalanceError(IntegrationError):
    """The run finished, but its energy balance is beyond ``analysis.energy_tolerance``: its
    numbers cannot be trusted to that tolerance."""


def initial_conditions(model: ReducedModel, motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    """(q₀, q̇₀) from the motion's free-vibration state; at rest otherwise. The initial velocity
    is the top mass's lateral velocity Ẋ(0)."""
    if model.exact and motion.initial_displacement:
        raise InputError("motion.displacement with structure.kinematics = 'exact': the static "
                         "push that holds it is solved in small rotations only; valid: 0 (use "
                         "motion.rotation or motion.velocity)")
    if model.base is not None and motion.initial_displacement:
        raise InputError("motion.displacement with foundation.law = 'macro': the static push "
                         "that holds the top mass displaced is solved for springs only; valid: "
                         "0 (use motion.rotation, motion.velocity, or a ground motion)")
    q0 = initial_state(model, displacement=motion.initial_displacement,
                       rotation=motion.initial_rotation)
    qd0 = np.zeros_like(q0)
    if motion.initial_velocity:
        d, v0 = model.dofs, motion.initial_velocity
        if d.stories and model.exact:  # Ẋ = ẇ cos θ with the base at rest
            qd0[d.stories[-1]] = v0 / math.cos(motion.initial_rotation)
        elif d.stories:
            qd0[d.stories[-1]] = v0
        elif model.exact:  # Ẋ = (u_O' + h) ṡ for a rigid body on its pivot
            s0 = q0[d.theta]
            lever = model.heights[-1] + (model.layout.half_width * abs(s0)
                                         / math.sqrt(1.0 - s0 * s0))
            qd0[d.theta] = v0 / lever
        elif d.theta < 0:  # a rigid structure sliding on a fixed base: Ẋ = u̇_G
            qd0[d.sway] = v0
        else:
            qd0[d.theta] = v0 / model.heights[-1]
            if d.sway >= 0:  # the base at rest: u̇_G = h_G θ̇
                qd0[d.sway] = model.sway_height * qd0[d.theta]
    return q0, qd0


def run(scene: Scene, *, motion: Motion | None = None, integrator: str | None = None,
        dt: float | None = None, output_dt: float | None = None,
        histories: bool = True, budget: float | None = None) -> Response:
    """Integrate ``scene`` (its motion unless ``motion`` is given) and return the response.

    Every input is checked, and the step chosen or checked against the stability limit, before
    the integration starts. ``histories=False`` stores only the first and last states (peaks
    are tracked at every step either way). A structure that passes its toppling angle ends the
    run there, with ``info["verdict"] = "overturned"``. Raises :class:`EnergyBalanceError` if
    the energy balance ends beyond ``analysis.energy_tolerance``, and
    :class:`IntegrationError` if the integration fails. ``budget``: the run's time budget (s,
    estimated before it starts, :mod:`upliftlab.budget`; None:
    :data:`~upliftlab.budget.REDUCED_BUDGET_SECONDS`); a run estimated above it is refused with
    an :class:`InputError`. It changes no number (it is not part of the scene or its digest).
    """
    time_budget(budget, REDUCED_BUDGET_SECONDS)  # a bad budget is refused before any work
    model = build_model(scene)
    motion = motion if motion is not None else scene.build_motion()
    return run_model(model, motion, integrator=integrator, dt=dt, output_dt=output_dt,
                     histories=histories, budget=budget)


def run_model(model: ReducedModel, motion: Motion, *, integrator: str | None = None,
              dt: float | None = None, output_dt: float | None = None,
              histories: bool = True, budget: float | None = None) -> Response:
    """As :func:`run`, for an already built model."""
    a = model.scene.analysis
    name = integrator or a.integrator
    plan, motion = plan_run(model, motion, name, dt=dt, output_dt=output_dt,
                            histories=histories, budget=budget)
    q0, qd0 = initial_conditions(model, motion)
    timings: dict = {}
    inputs = KernelInputs.of(model, plan, base_state=initial_base_state(model, motion, q0))
    status, out, counters = integrate(inputs, name, plan, q0, qd0,
                                      ground_acceleration(motion.acceleration, model.g),
                                      motion.dt, timings=timings)
    _check_status(status, counters, plan, name, out.pop("base_status"))
    negative_work = out.pop("base_negative_work")
    arrays = out
    t = arrays["time"]
    info = {"integrator": name, "dt": plan.dt, "steps": plan.steps, "output_stride": plan.stride,
            "output_dt": plan.output_dt,
            "stability_limit": plan.limit, "step_choice": plan.reason, "rtol": plan.rtol,
            "energy_tolerance": a.energy_tolerance,
            "kinematics": model.scene.structure.kinematics,
            "verdict": "overturned" if status == kn.OVERTURNED else "completed",
            "overturned_at": (decode_peaks(out["raw_peaks"], stories=model.story_count,
                                           rocks=model.dofs.theta >= 0,
                                           settles=model.dofs.v >= 0,
                                           exact=model.exact,
                                           sways=model.dofs.sway >= 0).overturned_at
                              if status == kn.OVERTURNED else None),
            "notes": list(model.notes),
            "counters": [int(c) for c in counters], "wall_time_s": timings["run_s"],
            "compile_time_s": timings["compile_s"],
            "motion": motion.name, "motion_source": motion.source, "pga_g": motion.pga,
            "motion_sha256": motion_checksum(motion)}
    if model.base is not None:
        info["macro_negative_work"] = negative_work
    prov = provenance(model="reduced", scene=model.scene.name, scene_file=model.scene.source,
                      case=model.scene.case, overrides=list(model.scene.overrides),
                      scene_digest=model.scene.digest, scene_data=model.scene.data)
    xg = ground_displacement(motion.acceleration, motion.dt, model.g, t)
    response = Response(model=model, ground_displacement=xg, info=info, provenance=prov,
                        motion=motion, **arrays)
    check_response(response)
    for note in model.notes:
        warnings.warn(note, ModelWarning, stacklevel=3)
    return response


class ModelWarning(UserWarning):
    """The run's numbers are right for its model, but the model has a property a user should
    know (e.g. a response that does not converge in the number of springs)."""


def plan_run(model: ReducedModel, motion: Motion, name: str, *, dt: float | None = None,
             output_dt: float | None = None, histories: bool = True,
             budget: float | None = None):
    """(StepPlan, the motion extended to the run's duration): every check of integrator, step,
    kinematics and cost (within the time ``budget``, s) a run makes before it starts. Without
    ``histories`` the plan stores the first and last states only."""
    a = model.scene.analysis
    m = method(name)
    if model.exact and not m.explicit:
        raise InputError(f"analysis.integrator = {name!r} with structure.kinematics = 'exact': "
                         "exact kinematics has a mass matrix that changes with θ, integrated by "
                         "the explicit integrators; valid: "
                         + ", ".join(repr(k) for k, v in METHODS.items() if v.explicit))
    if model.base is not None and m.kind not in ("fixed", "implicit"):
        raise InputError(f"analysis.integrator = {name!r} with foundation.law = 'macro': the "
                         "macro-element's state moves with the fixed-step integrators' "
                         "accepted steps; valid: " + ", ".join(
                             repr(k) for k, v in METHODS.items()
                             if v.kind in ("fixed", "implicit")))
    if m.kind == "events" and np.any(np.isin(model.params["kind"], curved_kinds())):
        law = model.scene.foundation.law
        raise InputError(f"analysis.integrator = {name!r} with foundation.law = {law.name!r}: "
                         f"the event stepper tabulates piecewise-affine laws and {law.curved}; "
                         "valid: " + ", ".join(repr(k) for k in METHODS if k != "events"))
    duration = a.duration or motion.duration
    motion = motion.extended(duration)
    plan = time_step(model, name, record_dt=motion.dt, duration=duration,
                     dt=dt if dt is not None else a.dt, subcycle=a.subcycle,
                     output_dt=output_dt if output_dt is not None else a.output_dt)
    plan = plan if histories else plan.without_histories()
    check_run_cost(model, plan, duration, name, histories, budget)  # refused above budget
    return plan, motion


def check_response(response: Response) -> None:
    """Refuse a response whose numbers cannot be trusted: non-finite values, or an energy
    balance beyond ``analysis.energy_tolerance``."""
    tol = response.model.scene.analysis.energy_tolerance
    error = response.energy_balance_error
    info = response.info
    where = f"{info['integrator']}, dt = {info['dt']:.4g} s"
    bad = [k for k, v in response.peaks.items()
           if not np.all(np.isfinite(np.asarray(v, dtype=float)))]
    if bad or not np.all(np.isfinite(response.q)):
        raise IntegrationError(f"{where}: the run produced non-finite values "
                               f"({', '.join(bad) or 'state'}); nothing is reported")
    negative = response.info.get("macro_negative_work", 0.0)
    scale = max(np.max(np.abs(response.energy_of("input"))),
                static_energy(response.model.params, response.model.base), 1e-300)
    if not negative <= tol * scale:
        raise IntegrationError(
            f"{where}: the macro-element did negative plastic work, {negative / scale:.3g} of "
            "the energy scale (beyond analysis.energy_tolerance = "
            f"{tol:g}): its bounding surface's flow created energy (it does where the load "
            "nears the surface's apex, V → 0, as the footing lifts off), so its numbers are "
            "not trusted; nothing is reported")
    if not error <= tol:
        raise EnergyBalanceError(
            f"{where}: the energy balance closes to {error:.3g} of its scale (the largest of "
            "the input, the initial energy and the bed's static strain energy), beyond "
            f"analysis.energy_tolerance = {tol:g}; refine the step (analysis.dt, or "
            "analysis.rtol for the event stepper) or relax the tolerance")


@dataclass(frozen=True, eq=False)
class KernelInputs:
    """What the compiled integrators take from a model: masses, the spring table, K_G, the
    ground load, the frame (:data:`~.kernels.N_FRAME` constants of geometry, kinematics and
    control), the story masses and the error control's floors (no motion)."""

    params: np.ndarray     # one record of SPRING_DTYPE per spring
    minv: np.ndarray       # inverse masses
    geometric: np.ndarray  # K_G
    ground_load: np.ndarray
    weight: float
    theta: int
    v: int
    stories: int
    newmark_scale: float   # force scale of the Newton tolerance: the weights
    hht_alpha: float
    frame: np.ndarray
    story: np.ndarray      # (h, m, W) of each story mass
    floor: np.ndarray      # smallest scales of q and q̇ of the error control
    shortest_period: float = 0.0  # of the bonded system (s): the chattering budget's clock
    base: tuple = ()       # the base element's record (:mod:`.kernels.base`), empty if none

    @classmethod
    def of(cls, model: ReducedModel, plan: StepPlan | None = None,
           base_state=None) -> KernelInputs:
        """The inputs of ``model``'s run with ``plan``; ``base_state`` the base element's state
        at the start (None: at rest)."""
        d = model.dofs
        scale = model.g * float(np.sum(model.mass[list(d.stories)])) + model.weight
        if scale == 0.0:  # a rigid structure sliding on a fixed base: its own weight
            scale = model.scene.structure.vertical_weight
        return cls(model.params, 1.0 / model.mass, model.geometric, model.ground_load,
                   model.weight, d.theta, d.v, model.story_count, scale,
                   model.scene.analysis.hht_alpha, frame_of(model, plan), story_table(model),
                   error_floors(model), float(model.linearised.bonded_periods()[-1]),
                   base_record(model.base, model.dofs.size, base_state))

    @classmethod
    def springs_only(cls, params: np.ndarray, mass: np.ndarray, *, v: int,
                     weight: float = 0.0) -> KernelInputs:
        """Inputs for a system of point masses on springs (no structure, no base to rock or
        overturn): ``mass`` per DOF, V at index ``v`` carrying ``weight``. Used to drive one
        spring law through the integrators (the drop mass of the impact damper)."""
        n = mass.size
        frame = np.zeros(kn.N_FRAME)
        frame[kn.F_ITH], frame[kn.F_IV], frame[kn.F_ECHECK], frame[kn.F_SIDE] = -1, v, 1, 1
        frame[kn.F_ISWAY] = -1
        frame[kn.F_HMAX] = frame[kn.F_H0] = math.inf
        return cls(params, 1.0 / mass, np.zeros((n, n)), np.zeros(n), weight, -1, v, 0, 1.0,
                   0.0, frame, np.zeros((0, 3)), np.full(2 * n, 1e-12), 0.0,
                   base_record(None, n))


def initial_base_state(model: ReducedModel, motion: Motion, q0: np.ndarray):
    """The base element's state at the start of a run from ``q0``: pushed to a free
    vibration's initial rotation (:func:`~.laws.macro.element.held_state`), else None (at
    rest; also without an element)."""
    if model.base is None or not motion.initial_rotation:
        return None
    from .laws.macro.element import held_state

    return held_state(model.base, q0)


def base_record(element, size: int, state=None) -> tuple:
    """The kernels' base-element record (:mod:`.kernels.base`) of a model's ``element`` (a
    :class:`~.laws.macro.element.BaseElement`) on ``size`` DOFs, in ``state`` (None: at
    rest); with no element, its empty form (no parameters), which the kernels pass over.
    :func:`integrate` runs on a copy, so that the record stays as it is given."""
    if element is None:
        return (np.zeros(0), np.zeros(S_COUNT), np.zeros(S_COUNT), np.zeros((3, 3)),
                np.zeros(W_COUNT), np.zeros((3, size)), np.zeros(kn.N_C))
    rest = element.rest
    C = np.zeros(kn.N_C)
    C[kn.C_D0:kn.C_D0 + 3] = rest.displacement
    C[kn.C_Q0:kn.C_Q0 + 3] = rest.forces
    C[kn.C_CV], C[kn.C_CH] = element.dashpot_density, element.sway_dashpot
    C[kn.C_DF], C[kn.C_E0] = element.force_step, element.rest_energy
    S = (rest if state is None else state).packed()
    return (pack(element.law), S, S.copy(), np.zeros((3, 3)), np.zeros(W_COUNT),
            np.ascontiguousarray(element.transform, dtype=float), C)


def story_table(model: ReducedModel) -> np.ndarray:
    """(h_j, m_j, W_j) of each story mass."""
    s = model.scene.structure
    return np.array([[st.height, st.weight / model.g, st.weight] for st in s.stories])


def frame_of(model: ReducedModel, plan: StepPlan | None = None) -> np.ndarray:
    """The kernels' frame (:data:`~.kernels.N_FRAME` constants; see its slots)."""
    s, d = model.scene.structure, model.dofs
    frame = np.zeros(kn.N_FRAME)
    base_weight = max(s.vertical_weight - s.weight, 0.0)
    if model.layout is not None:
        frame[kn.F_B] = model.layout.half_width
    frame[kn.F_EXACT] = 1.0 if model.exact else 0.0
    frame[kn.F_WTOT] = s.weight + base_weight
    frame[kn.F_MB] = base_weight / model.g
    frame[kn.F_IB] = s.rotary_inertia
    frame[kn.F_SIDE] = 1.0
    frame[kn.F_ITH], frame[kn.F_IV] = d.theta, d.v
    frame[kn.F_NFLEX] = len(d.stories)
    frame[kn.F_ISWAY] = d.sway if d.stories else -1
    frame[kn.F_ECHECK] = 1
    frame[kn.F_HMAX] = frame[kn.F_H0] = math.inf
    if plan is not None:
        frame[kn.F_ECHECK] = max(1, min(plan.stride, math.ceil(plan.steps / 2000)))
        if plan.output_dt > 0:  # interpolated outputs: a check every 2000th of the run
            frame[kn.F_ECHECK] = max(1, math.ceil(plan.steps / 2000))
        frame[kn.F_RTOL], frame[kn.F_HMAX], frame[kn.F_H0] = plan.rtol, plan.hmax, plan.h0
        frame[kn.F_OUTDT] = plan.output_dt
    return frame


def error_floors(model: ReducedModel) -> np.ndarray:
    """Smallest scales (q, then q̇) of the error control: 1e-3 of each DOF's static scale —
    the story's drift under its own weight, the base's settlement δ = W/K_v and its rotation
    δ/b — and those over the shortest bonded period for the rates."""
    d, g = model.dofs, model.g
    floor = np.zeros(2 * model.mass.size)
    s = model.scene.structure
    for j, dof in enumerate(d.stories):
        floor[dof] = s.stories[j].weight / s.stories[j].stiffness
    if d.theta >= 0:
        settle = model.weight / model.layout.vertical_stiffness
        floor[d.v] = settle
        floor[d.theta] = settle / model.layout.half_width
    if d.sway >= 0:  # the sway under the weight as a lateral load
        floor[d.sway] = s.vertical_weight / model.scene.foundation.sway_stiffness
    if not np.any(floor[:model.mass.size]):
        floor[:model.mass.size] = g * 1e-6
    floor[:model.mass.size] = np.where(floor[:model.mass.size] > 0, floor[:model.mass.size],
                                       np.max(floor[:model.mass.size]))
    omega = 2.0 * np.pi / float(model.linearised.bonded_periods()[-1])
    floor[model.mass.size:] = floor[:model.mass.size] * omega
    return 1e-3 * floor


def compile_for(kernel, args: tuple) -> float:
    """Compile ``kernel`` (a numba dispatcher) for ``args``, or load it from numba's cache,
    before it runs; returns the seconds taken (0 when this process has it already). Timing the
    call after this times the run alone: a first run's wall time must not include the one-off
    compilation."""
    overloads = getattr(kernel, "overloads", None)
    if overloads is None:  # a plain Python function (numba disabled)
        return 0.0
    import numba

    signature = tuple(numba.typeof(a) for a in args)
    if signature in overloads:
        return 0.0
    start = _time.perf_counter()
    kernel.compile(signature)
    return _time.perf_counter() - start


def integrate(inputs: KernelInputs, name: str, plan: StepPlan, q0: np.ndarray,
              qd0: np.ndarray, ag: np.ndarray, dtg: float, *, impacts: bool = True,
              timings: dict | None = None):
    """Run the compiled integrator ``name``; returns (status, output arrays, counters).

    ``ag`` is the ground acceleration (length/s², samples dtg apart, an appended zero). The
    arrays: histories at every ``plan.stride`` steps (rows up to ``counters[4]`` written),
    ``raw_peaks`` and, for the event stepper when ``impacts``, the impact log. ``timings``, if
    given, receives ``compile_s`` (compiling or loading the kernel, s) and ``run_s`` (the
    integration alone, s).
    """
    P = inputs.params
    n, ns = q0.size, P.size
    nout = plan.rows + 1  # a row more for a run that ends between outputs
    out = {
        "time": np.zeros(nout), "q": np.zeros((nout, n)), "qd": np.zeros((nout, n)),
        "deformation": np.zeros((nout, ns)), "force": np.zeros((nout, ns)),
        "mode": np.zeros((nout, ns), np.int64), "plastic": np.zeros((nout, ns)),
        "energy": np.zeros((nout, kn.N_ENERGY)),
        "base": np.zeros((nout, kn.N_BASE_OUT if inputs.base[0].size else 0)),
    }
    peaks = start_peaks(P, inputs.stories, _initial_values(P, inputs, q0))
    counters = np.zeros(kn.N_COUNTERS, np.int64)
    params = P.view(np.recarray)  # records read as p.k in compiled and plain code
    history = initial_history(P).view(np.recarray)
    frame = inputs.frame.copy()  # its pivot side changes during a run
    base = tuple(a.copy() for a in inputs.base)  # its state changes during a run
    system = (inputs.minv, params, inputs.geometric, inputs.ground_load, ag, dtg, inputs.weight,
              frame, inputs.story, base)  # the kernels' SYSTEM record
    clock = (plan.dt, plan.steps, plan.stride)
    outputs = (out["time"], out["q"], out["qd"], out["deformation"], out["force"], out["mode"],
               out["plastic"], out["energy"], out["base"])
    log = np.zeros((0, 5))
    m = method(name)
    announce_compilation("the reduced model's kernels", m.kernel, COMPILE_TIME)
    logger("reduced").debug(f"upliftlab: {name}: dt = {plan.dt:.6g} s, {plan.steps} steps, "
                            f"{ns} springs, {q0.size} DOFs")
    if m.kind == "events":
        max_switches = switch_budget(ns, plan.dt, inputs.shortest_period)
        rows = max(1000, 20 * ns * int(plan.steps * plan.dt + 1)) if impacts else 0
        log = np.full((rows, 5), np.nan)
        args = (q0, qd0, clock, system, inputs.floor, max_switches, outputs, peaks, counters,
                log, history)
    elif m.kind == "fixed":
        args = (q0, qd0, clock, system, outputs, peaks, counters, history)
    else:
        c = hht(m.alpha if m.alpha is not None else inputs.hht_alpha, plan.dt)
        newton = (NEWTON_TOL, inputs.newmark_scale, NEWTON_ITERATIONS)
        args = (q0, qd0, clock, system, (c.alpha, c.beta, c.gamma), newton, NEWTON_HALVINGS,
                outputs, peaks, counters, history)
    compile_s = compile_for(m.kernel, args)
    start = _time.perf_counter()
    status = m.kernel(*args)
    if timings is not None:
        timings.update(compile_s=compile_s, run_s=_time.perf_counter() - start)
    rows = int(counters[4])  # the run may end between outputs (overturned, failed)
    out = {k: v[:rows] for k, v in out.items()}
    out["raw_peaks"] = peaks
    out["base_status"] = int(base[6][kn.C_STATUS])
    out["base_negative_work"] = float(base[6][kn.C_NEGATIVE])
    out["impacts"] = log[:min(int(counters[3]), log.shape[0])].copy()
    return status, out, counters


#: How long compiling an integrator takes the first time (what the notice says): 60–100 s for
#: the event stepper on a loaded two-core machine (the main job's first run, measured with
#: ``compile_time_s``, benchmarks/REDUCED.md).
COMPILE_TIME = "about 1–2 minutes on a two-core machine"


#: The implicit integrators' Newton: tolerance on the residual (relative to the forces in play),
#: iterations per step, and halvings of a step whose Newton iteration fails.
NEWTON_TOL, NEWTON_ITERATIONS, NEWTON_HALVINGS = 1e-10, 50, 12


def switch_budget(springs: int, dt: float, shortest_period: float) -> int:
    """Switches the event stepper allows within one step of ``dt`` before it calls the run
    chattering: 50 per spring and 1000, plus 20 per spring for every shortest bonded period
    the step spans (a stiff bed bounces legitimately that often). A spring that switches
    without end (a Zeno cycle) exhausts any finite budget."""
    periods = dt / shortest_period if shortest_period > 0 else 0.0
    return int(50 * springs + 1000 + 20 * springs * math.ceil(periods))


def _initial_values(P: np.ndarray, inputs: KernelInputs, q0: np.ndarray) -> list[float]:
    """(u, u, θ, θ, V, V) at the initial state: the top deformation as the sum of the story
    springs' e = aᵀq₀, the base's θ (or sin θ) and V (0 for a fixed base)."""
    u = sum(P["a0"][j] * q0[P["i0"][j]] + P["a1"][j] * q0[P["i1"][j]]
            + (P["a2"][j] * q0[P["i2"][j]] if P["nnz"][j] == 3 else 0.0)
            for j in range(inputs.stories))
    th = q0[inputs.theta] if inputs.theta >= 0 else 0.0
    v = q0[inputs.v] if inputs.v >= 0 else 0.0
    return [u, u, th, th, v, v]


def ground_acceleration(acceleration: np.ndarray, g: float) -> np.ndarray:
    """The ground acceleration the kernels take, from samples in g: length/s², with an
    appended zero."""
    return np.append(acceleration * g, 0.0)


def _check_status(status: int, counters: np.ndarray, plan: StepPlan, name: str,
                  base_status: int = 0) -> None:
    if status in (kn.OK, kn.OVERTURNED):
        return
    if status == kn.BASE_FAILED:
        t = (counters[0] + 1) * plan.dt
        raise IntegrationError(f"{name}: the macro-element's step to t = {t:.6g} s failed: "
                               f"{MACRO_FAILURES.get(base_status, 'unknown reason')}; nothing "
                               "is reported")
    if status == kn.CHATTER:
        t = counters[1] * plan.dt
        raise IntegrationError(
            f"{name}: more than the allowed number of contact switches within one step at "
            f"t = {t:.6g} s (chattering); refine analysis.dt or add foundation damping")
    if status == kn.NONFINITE:
        t = counters[0] * plan.dt
        raise IntegrationError(f"{name}: the state became non-finite at t = {t:.6g} s "
                               f"(dt = {plan.dt:g} s, stability limit {plan.limit:.4g} s)")
    if status == kn.NO_CONVERGENCE:
        t = counters[0] * plan.dt
        raise IntegrationError(f"{name}: Newton did not converge at t = {t:.6g} s even after "
                               f"{NEWTON_HALVINGS} step halvings")
    if status == kn.STEP_UNDERFLOW:
        t = counters[0] * plan.dt
        raise IntegrationError(f"{name}: the error control cut the step to round-off at "
                               f"t = {t:.6g} s (analysis.rtol = {plan.rtol:g}); relax "
                               "analysis.rtol or check the scene's stiffness")
    raise IntegrationError(f"{name}: unknown status {status}")

