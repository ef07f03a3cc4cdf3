"""Static analyses of the continuum model: geostatic stress, footing stiffness, vertical,
rotation and moment pushovers, and the V–M capacity envelope.

Sign conventions (those of the reduced model; see :mod:`~upliftlab.continuum.contact.footing`):
v is the footing's vertical displacement (up; settlement = −v), θ its rotation (+θ pushes the
right edge down), N the vertical compression, M the moment about the base centre (+ resisting
+θ), H the horizontal force (+x). Forces are per unit out-of-plane length.

The geostatic state is :mod:`~upliftlab.continuum.statics.geostatic`'s, the soil fields the
pushovers
record on request (``record_fields``) are :mod:`~upliftlab.continuum.output.fields`', the result
records are :mod:`~upliftlab.continuum.statics.results`'. All are importable from here.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

import numpy as np

from ... import checks
from ...checks import InputError
from ...progress import steps_progress
from ..contact.footing import OPEN
from ..output.fields import (element_average, field_snapshots, max_shear_stress, result_metadata,
                             snapshot_steps)
from .geostatic import elastic_gravity_stress, elastic_tangent, geostatic, k0_stress
from ..materials import plane_strain_tangent
from .results import Envelope, StaticPath, UpliftOnset
from .newton import ContinuumState, Control, ConvergenceError, NewtonOptions, follow

__all__ = ["geostatic", "k0_stress", "elastic_gravity_stress", "FootingStiffness",
           "footing_stiffness", "StaticPath", "vertical_pushover", "rotation_pushover",
           "moment_pushover", "Envelope", "vm_envelope", "UpliftOnset", "uplift_onset",
           "element_average", "max_shear_stress"]


@dataclass(frozen=True)
class FootingStiffness:
    """Static stiffness of the footing in full (tied) contact with the elastic soil: ``matrix``
    (3, 3) for (u, v, θ) (the u row is zero for a frictionless interface), and the box it was
    computed in (its vertical and horizontal entries depend on the box size in 2D)."""

    matrix: np.ndarray = field(repr=False)
    domain_width: float
    domain_depth: float

    @property
    def vertical(self) -> float:
        """K_v (force/length per length)."""
        return float(self.matrix[1, 1])

    @property
    def rocking(self) -> float:
        """K_r = M/θ (force·length/rad per length)."""
        return float(self.matrix[2, 2])

    @property
    def horizontal(self) -> float:
        return float(self.matrix[0, 0])


def footing_stiffness(model) -> FootingStiffness:
    """Lᵀ S L of the elastic soil with every contact node tied to the footing."""
    if model.linear:
        cond = model.condense(None)
    else:
        D = np.broadcast_to(plane_strain_tangent(elastic_tangent(model))[..., None, None],
                            (3, 3) + model.disc.qp_shape)
        cond = model.condense(np.ascontiguousarray(D))
    L = model.footing.kinematics
    depth = model.mesh_parameters.get("domain_depth", math.nan)
    if model.soil.layer_depth is not None:
        depth = model.soil.layer_depth / model.width
    return FootingStiffness(matrix=L.T @ cond.S @ L,
                            domain_width=model.mesh_parameters.get("domain_width", math.nan),
                            domain_depth=depth)


def _follow(model, state, controls, options, progress) -> list[ContinuumState]:
    """:func:`follow`, calling ``progress(k, n, state)`` after each step (the steps are the
    same: :func:`follow` takes its controls one after the other); ``progress`` None shows a
    bar where someone watches, True always, False never (:mod:`upliftlab.progress`)."""
    with steps_progress(progress, "continuum pushover", offset=1, postfix=_postfix) as report:
        if report is None:
            return follow(model, state, controls, options)
        states = []
        for k, control in enumerate(controls):
            try:
                state = follow(model, state, [control], options)[0]
            except ConvergenceError as exc:
                raise ConvergenceError(f"step {k} of {len(controls)}: {exc}", step=k,
                                       fraction=exc.fraction, residual=exc.residual,
                                       iterations=exc.iterations) from exc
            states.append(state)
            report(k, len(controls), state)
        return states


def _postfix(state) -> str:
    return f"θ = {state.q[2]:.3g} rad, N = {state.N:.4g}"


def _path(model, kind: str, states, extra=None, snapshots=None) -> StaticPath:
    f = model.footing
    normal = np.array([-s.force[:f.nodes] for s in states])
    shear = np.array([s.force[f.nodes:] if f.interface.tangential else np.zeros(f.nodes)
                      for s in states])
    q = np.array([s.q for s in states])
    reaction = np.array([s.reaction for s in states])
    status = np.array([s.status for s in states])
    pressure = normal / f.weight
    gap = np.array([f.gap(s.u, s.q) for s in states])
    return StaticPath(
        kind=kind, u=q[:, 0], v=q[:, 1], theta=q[:, 2], H=reaction[:, 0], N=-reaction[:, 1],
        M=reaction[:, 2],
        contact_length=f.contact_lengths(status != OPEN, pressure, gap),
        x=f.x, pressure=pressure, shear=shear / f.weight,
        gap=gap, status=status,
        iterations=np.array([s.iterations for s in states]),
        cuts=np.array([s.cuts for s in states]), width=f.width,
        metadata=result_metadata(model, kind, extra), **field_snapshots(model, states, snapshots))


def _u_control(model) -> tuple[bool, float]:
    """u is prescribed (0) on a frictionless interface, else free with H = 0."""
    return (not model.footing.interface.tangential), 0.0


RecordFields = bool | Iterable[int]
#: ``progress(k, n, state)`` after each step, or None (a bar where someone watches), True (a
#: bar) or False (nothing): :mod:`upliftlab.progress`.
Progress = Callable[[int, int, ContinuumState], None] | bool | None


def vertical_pushover(model, settlements, *, state: ContinuumState | None = None,
                      options: NewtonOptions = NewtonOptions(),
                      record_fields: RecordFields = False, progress: Progress = None
                      ) -> StaticPath:
    """Displacement-controlled vertical loading: the footing is pushed down to each of
    ``settlements`` (length, positive down) with u = 0 and θ = 0 held. Returns the
    load–settlement history (``N`` against ``settlement``; ``capacity`` its maximum).
    ``record_fields`` keeps soil fields (module docstring); ``progress(k, n, state)`` is
    called after each step."""
    settlements = _history("settlements", settlements)
    snapshots = snapshot_steps(record_fields, settlements.size)
    state = geostatic(model) if state is None else state
    controls = [Control((True, True, True), (0.0, -s, 0.0)) for s in settlements]
    states = _follow(model, state, controls, options, progress)
    return _path(model, "vertical_pushover", states, snapshots=snapshots)


def _apply_n(model, state, N: float, steps: int, options) -> ContinuumState:
    """Ramp the vertical load from the state's to ``N`` in ``steps``, θ held."""
    steps = checks.integer_at_least("load_steps", steps, 1)
    fixed_u, H = _u_control(model)
    loads = state.N + (N - state.N) * np.arange(1, steps + 1) / steps
    controls = [Control((fixed_u, False, True), (H, -load, state.q[2])) for load in loads]
    return follow(model, state, controls, options)[-1]


def rotation_pushover(model, N: float, rotations, *, state: ContinuumState | None = None,
                      load_steps: int = 4, options: NewtonOptions = NewtonOptions(),
                      record_fields: RecordFields = False, progress: Progress = None
                      ) -> StaticPath:
    """Rotation-controlled pushover at constant vertical load ``N`` (force/length, compression):
    N is applied first in ``load_steps`` with θ held, then θ follows ``rotations`` (rad, any
    history: monotonic or cyclic) while N stays constant and H = 0 (u = 0 held on a
    frictionless interface). Returns M–θ, settlement, contact length and pressures per θ step.
    ``record_fields`` keeps soil fields of the θ steps (module docstring);
    ``progress(k, n, state)`` is called after each θ step.
    """
    return _rocking(model, N, "rotations", rotations, True, state, load_steps, options,
                    record_fields, progress)


def moment_pushover(model, N: float, moments, *, state: ContinuumState | None = None,
                    load_steps: int = 4, options: NewtonOptions = NewtonOptions(),
                    record_fields: RecordFields = False, progress: Progress = None
                    ) -> StaticPath:
    """Moment-controlled pushover at constant ``N``: like :func:`rotation_pushover` with M
    (force·length/length) prescribed. It cannot pass the moment capacity; use
    :func:`rotation_pushover` to follow the plateau."""
    return _rocking(model, N, "moments", moments, False, state, load_steps, options,
                    record_fields, progress)


def _rocking(model, N, name, values, by_rotation, state, load_steps, options,
             record_fields=False, progress=None) -> StaticPath:
    checks.positive("N", N)
    values = _history(name, values)
    snapshots = snapshot_steps(record_fields, values.size)
    state = geostatic(model) if state is None else state
    state = _apply_n(model, state, N, load_steps, options)
    fixed_u, H = _u_control(model)
    controls = [Control((fixed_u, False, by_rotation), (H, -N, x)) for x in values]
    kind = "rotation_pushover" if by_rotation else "moment_pushover"
    states = _follow(model, state, controls, options, progress)
    return _path(model, kind, states, {"N_applied": N}, snapshots)


def _history(name: str, values) -> np.ndarray:
    values = np.atleast_1d(np.asarray(values, dtype=float))
    if values.ndim != 1 or values.size == 0 or not np.isfinite(values).all():
        raise InputError(f"{name} = {values!r}: expected a non-empty 1-D list of finite numbers")
    return values


def uplift_onset(path: StaticPath) -> UpliftOnset:
    """The :class:`UpliftOnset` of a rotation pushover that starts with at least two
    full-contact steps and later loses contact."""
    closed = (path.status != OPEN).all(axis=1)
    opened = np.flatnonzero(~closed)
    if opened.size == 0 or opened[0] < 2:
        raise InputError("path: uplift onset needs two full-contact steps before the first "
                         f"open node (first open step: {opened[:1].tolist()})")
    k = int(opened[0]) - 1
    drop = path.pressure[k - 1] - path.pressure[k]
    with np.errstate(divide="ignore", invalid="ignore"):
        reach = np.where(drop > 0.0, path.pressure[k] / drop, np.inf)
    s = float(reach.min())  # steps beyond k (extrapolated) at which the first node unloads
    theta = path.theta[k] + s * (path.theta[k] - path.theta[k - 1])
    M = path.M[k] + s * (path.M[k] - path.M[k - 1])
    N = float(path.N[k])
    return UpliftOnset(theta=float(theta), M=float(M), N=N, e=float(M / N))


def probe_loads(model, v_ratios, V_ult, settlements, options) -> tuple[np.ndarray, float]:
    """(the ratios v in (0, 1), checked, and V_ult) of an envelope's constant-V probes:
    ``V_ult`` given, or the capacity of a vertical pushover to ``settlements`` on the same
    model (so the mesh's own overshoot cancels in the normalised envelope)."""
    v_ratios = _history("v_ratios", v_ratios)
    if not ((v_ratios > 0.0) & (v_ratios < 1.0)).all():
        raise InputError(f"v_ratios = {v_ratios.tolist()}: valid range is (0, 1)")
    if V_ult is None:
        if settlements is None:
            raise InputError("settlements = None: give V_ult or the settlements of the "
                             "vertical pushover that finds it")
        V_ult = vertical_pushover(model, settlements, options=options).capacity
    checks.positive("V_ult", V_ult)
    return v_ratios, V_ult


def vm_envelope(model, v_ratios, rotations, *, V_ult: float | None = None,
                settlements=None, load_steps: int = 4,
                options: NewtonOptions = NewtonOptions()) -> Envelope:
    """V–M envelope by constant-V probes: for each v in ``v_ratios`` (in (0, 1)), apply
    V = v V_ult, then rotate through ``rotations`` (rad, increasing) at constant V; M_ult(V) is
    the largest moment reached. ``V_ult`` defaults to the capacity of a vertical pushover to
    ``settlements`` on the same model (so the mesh's own overshoot cancels in v and m). A probe
    whose V the soil cannot carry raises :class:`~upliftlab.continuum.ConvergenceError`."""
    v_ratios, V_ult = probe_loads(model, v_ratios, V_ult, settlements, options)
    probes = tuple(rotation_pushover(model, v * V_ult, rotations, load_steps=load_steps,
                                     options=options) for v in v_ratios)
    return Envelope(V=v_ratios * V_ult, M=np.array([p.M.max() for p in probes]), V_ult=V_ult,
                    width=model.width, probes=probes,
                    metadata=result_metadata(model, "vm_envelope",
                                       {"rotations": np.asarray(rotations).tolist()}))
