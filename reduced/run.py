"""Run a scene through the reduced model: choose the step, integrate, return a :class:`Response`."""

from __future__ import annotations

import time as _time
from dataclasses import dataclass

import numpy as np

from ..motions import Motion
from ..results import provenance
from ..scenes import Scene
from . import kernels as kn
from . import springs as sp
from .cost import check_run_cost
from .integrators import StepPlan, method, time_step
from .model import ReducedModel, build_model
from .response import Response, ground_displacement
from .static import initial_state

__all__ = ["run", "run_model", "initial_conditions", "IntegrationError", "KernelInputs",
           "integrate", "ground_acceleration"]


class IntegrationError(RuntimeError):
    """The integration could not proceed (chattering, divergence, Newton failure)."""


def initial_conditions(model: ReducedModel, motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    """(q₀, q̇₀) from the motion's free-vibration state; at rest otherwise."""
    q0 = initial_state(model, displacement=motion.initial_displacement,
                       rotation=motion.initial_rotation)
    qd0 = np.zeros_like(q0)
    if motion.initial_velocity:
        d = model.dofs
        if d.stories:
            qd0[d.stories[-1]] = motion.initial_velocity
        else:
            qd0[d.theta] = motion.initial_velocity / model.heights[-1]
    return q0, qd0


def run(scene: Scene, *, motion: Motion | None = None, integrator: str | None = None,
        dt: float | None = None, output_dt: float | None = None,
        histories: bool = True) -> Response:
    """Integrate ``scene`` (its motion unless ``motion`` is given) and return the response.

    Every input is checked, and the step chosen or checked against the stability limit, before
    the integration starts. ``histories=False`` stores only the first and last states (peaks
    are tracked at every step either way).
    """
    model = build_model(scene)
    motion = motion if motion is not None else scene.build_motion()
    return run_model(model, motion, integrator=integrator, dt=dt, output_dt=output_dt,
                     histories=histories)


def run_model(model: ReducedModel, motion: Motion, *, integrator: str | None = None,
              dt: float | None = None, output_dt: float | None = None,
              histories: bool = True) -> Response:
    """As :func:`run`, for an already built model."""
    a = model.scene.analysis
    name = integrator or a.integrator
    method(name)
    duration = a.duration or motion.duration
    motion = motion.extended(duration)
    plan = time_step(model, name, record_dt=motion.dt, duration=duration,
                     dt=dt if dt is not None else a.dt, subcycle=a.subcycle,
                     output_dt=output_dt if output_dt is not None else a.output_dt)
    if not histories:
        plan = StepPlan(plan.dt, plan.steps, plan.steps, plan.limit, plan.substeps, plan.reason)
    check_run_cost(model, plan, duration, name, histories)  # refused above the scene's budget
    q0, qd0 = initial_conditions(model, motion)
    start = _time.perf_counter()
    arrays, counters = _integrate(model, motion, name, plan, q0, qd0)
    elapsed = _time.perf_counter() - start
    t = arrays["time"]
    info = {"integrator": name, "dt": plan.dt, "steps": plan.steps, "output_stride": plan.stride,
            "stability_limit": plan.limit, "step_choice": plan.reason,
            "counters": [int(c) for c in counters], "wall_time_s": elapsed,
            "motion": motion.name, "motion_source": motion.source, "pga_g": motion.pga}
    prov = provenance(model="reduced", scene=model.scene.name, scene_file=model.scene.source,
                      case=model.scene.case, overrides=list(model.scene.overrides),
                      scene_digest=model.scene.digest, scene_data=model.scene.data)
    xg = ground_displacement(motion.acceleration, motion.dt, model.g, t)
    return Response(model=model, ground_displacement=xg, info=info, provenance=prov, **arrays)


@dataclass(frozen=True, eq=False)
class KernelInputs:
    """What the compiled integrators take from a model: masses, the spring table, K_G, the
    ground load and the DOFs that peaks are tracked on (no motion, no step)."""

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

    @classmethod
    def of(cls, model: ReducedModel) -> KernelInputs:
        d = model.dofs
        scale = model.g * float(np.sum(model.mass[list(d.stories)])) + model.weight
        return cls(model.params, 1.0 / model.mass, model.geometric, model.ground_load,
                   model.weight, d.theta, d.v, model.story_count, scale,
                   model.scene.analysis.hht_alpha)


def integrate(inputs: KernelInputs, name: str, plan: StepPlan, q0: np.ndarray,
              qd0: np.ndarray, ag: np.ndarray, dtg: float, *, impacts: bool = True):
    """Run the compiled integrator ``name``; returns (status, output arrays, counters).

    ``ag`` is the ground acceleration (length/s², samples dtg apart, an appended zero). The
    arrays: histories at every ``plan.stride`` steps, ``raw_peaks`` and, for the event stepper
    when ``impacts``, the impact log.
    """
    P = inputs.params
    n, ns = q0.size, P.size
    nout = plan.steps // plan.stride + 1
    out = {
        "time": np.zeros(nout), "q": np.zeros((nout, n)), "qd": np.zeros((nout, n)),
        "deformation": np.zeros((nout, ns)), "force": np.zeros((nout, ns)),
        "mode": np.zeros((nout, ns), np.int64), "plastic": np.zeros((nout, ns)),
        "energy": np.zeros((nout, kn.N_ENERGY)),
    }
    peaks = np.zeros(kn.N_PEAK_SCALARS + 2 * ns)
    peaks[[kn.P_UMIN, kn.P_THMIN, kn.P_VMIN]] = np.inf
    peaks[[kn.P_UMAX, kn.P_THMAX, kn.P_VMAX]] = -np.inf
    gaps = peaks[kn.N_PEAK_SCALARS::2]  # a view: the gap at rest is −δ0
    gaps[inputs.stories:] = -P["d0"][inputs.stories:]
    counters = np.zeros(4, np.int64)
    params = P.view(np.recarray)  # records read as p.k in compiled and plain code
    history = np.zeros(ns, dtype=sp.HISTORY_DTYPE).view(np.recarray)
    common = (q0, qd0, plan.dt, plan.steps, plan.stride, inputs.minv, params, inputs.geometric,
              inputs.ground_load, ag, dtg, inputs.weight, inputs.theta, inputs.v, inputs.stories)
    outs = (out["time"], out["q"], out["qd"], out["deformation"], out["force"], out["mode"],
            out["plastic"], out["energy"], peaks, counters)
    log = np.zeros((0, 5))
    if name == "events":
        max_switches = 50 * ns + 1000
        rows = max(1000, 20 * ns * int(plan.steps * plan.dt + 1)) if impacts else 0
        log = np.full((rows, 5), np.nan)
        status = kn.integrate_events(*common, max_switches, *outs, log, history)
    elif name == "rk4":
        status = kn.integrate_rk4(*common, *outs, history)
    elif name == "abm4":
        status = kn.integrate_abm4(*common, *outs, history)
    else:
        alpha = 0.0 if name == "newmark" else inputs.hht_alpha
        status = kn.integrate_newmark(*common, alpha, 1e-10, inputs.newmark_scale, 50, 12,
                                      *outs, history)
    out["raw_peaks"] = peaks
    out["impacts"] = log[:min(int(counters[3]), log.shape[0])].copy()
    return status, out, counters


def ground_acceleration(acceleration: np.ndarray, g: float) -> np.ndarray:
    """The ground acceleration the kernels take, from samples in g: length/s², with an
    appended zero."""
    return np.append(acceleration * g, 0.0)


def _integrate(model: ReducedModel, motion: Motion, name: str, plan: StepPlan,
               q0: np.ndarray, qd0: np.ndarray):
    status, out, counters = integrate(KernelInputs.of(model), name, plan, q0, qd0,
                                      ground_acceleration(motion.acceleration, model.g),
                                      motion.dt)
    _check_status(status, counters, plan, name)
    return out, counters


def _check_status(status: int, counters: np.ndarray, plan: StepPlan, name: str) -> None:
    if status == kn.OK:
        return
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
                               "12 step halvings")
    raise IntegrationError(f"{name}: unknown status {status}")

