"""Static analyses of the continuum model: geostatic stress, footing stiffness, vertical,
rotation and moment pushovers, and the V–M capacity envelope.

Sign conventions (those of the reduced model; see :mod:`~upliftlab.continuum.footing`):
v is the footing's vertical displacement (up; settlement = −v), θ its rotation (+θ pushes the
right edge down), N the vertical compression, M the moment about the base centre (+ resisting
+θ), H the horizontal force (+x). Forces are per unit out-of-plane length.

**Geostatic stress.** :func:`geostatic` uses the K0 procedure by default: σ_yy = ρ g y
(y ≤ 0), σ_xx = σ_zz = K0 σ_yy, σ_xy = 0 (:func:`~upliftlab.continuum.model.default_k0`). On a
flat surface with roller sides this is in exact equilibrium with the soil's weight, so the
displacements start at zero. ``method="elastic"`` instead solves one elastic gravity step (soil
alone, no footing) and keeps its stress, resetting the displacement to zero; under roller sides
it gives K0 = ν/(1 − ν), which the tests use to cross-check the two routes.

**Soil fields (opt-in).** The pushovers take ``record_fields``: ``True`` records every step,
a sequence of step indices records those (negative indices count from the end). Each recorded
step keeps the soil displacement DOF vector (the model basis's ordering), and the
element averages (quadrature weights × Jacobians) of the equivalent plastic strain and of the
maximum shear stress (σ1 − σ3)/2 of the total stress (geostatic included). They are what
:mod:`~upliftlab.continuum.output` writes to XDMF and renders. Recording changes no result.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from scipy.sparse.linalg import splu

from .. import checks
from ..checks import InputError
from ..results import provenance, write_netcdf
from . import assembly
from .footing import OPEN
from .materials import Elastic, Region, plane_strain, plane_strain_tangent
from .newton import (ContinuumState, Control, ConvergenceError, NewtonOptions, follow,
                     start_state)

__all__ = ["geostatic", "k0_stress", "elastic_gravity_stress", "FootingStiffness",
           "footing_stiffness", "StaticPath", "vertical_pushover", "rotation_pushover",
           "moment_pushover", "Envelope", "vm_envelope", "UpliftOnset", "uplift_onset",
           "element_average", "max_shear_stress"]


# ---------------------------------------------------------------------------------------------
# Geostatic stress
# ---------------------------------------------------------------------------------------------


def k0_stress(model) -> np.ndarray:
    """The K0 stress (3, 3, nelems, nqp) at the quadrature points (module docstring)."""
    y = model.disc.qp_coordinates[1]
    vertical = model.soil.density * model.gravity * np.minimum(y, 0.0)
    stress = np.zeros((3, 3) + y.shape)
    stress[0, 0] = stress[2, 2] = model.k0 * vertical
    stress[1, 1] = vertical
    return stress


def elastic_gravity_stress(model) -> np.ndarray:
    """The stress (3, 3, nelems, nqp) of one elastic gravity step: the soil alone (free surface,
    roller sides, fixed bottom) under its weight."""
    D = plane_strain_tangent(_elastic_tangent(model))
    K = assembly.stiffness(model.disc, D)
    free = np.setdiff1d(np.arange(model.disc.ndofs), model.blocks.fixed)
    u = np.zeros(model.disc.ndofs)
    u[free] = splu(K[free][:, free].tocsc()).solve(model.body_force[free])
    strain = plane_strain(assembly.strain_tensor(assembly.strain(model.disc, u)))
    return _elastic(model)(strain)[0]


def _elastic(model) -> Elastic:
    return Elastic(model.soil.youngs_modulus, model.soil.poisson_ratio)


def _elastic_tangent(model) -> np.ndarray:
    """The 6×6 elastic tangent of the soil."""
    return _elastic(model)(np.zeros((3, 3, 1)))[1][..., 0]


def _compliance(model, stress: np.ndarray) -> np.ndarray:
    """Elastic strain C⁻¹σ of a stress field."""
    E, nu = model.soil.youngs_modulus, model.soil.poisson_ratio
    trace = np.einsum("ii...->...", stress)
    eye = np.eye(3).reshape(3, 3, *([1] * trace.ndim))
    return ((1 + nu) * stress - nu * trace * eye) / E


def geostatic(model, method: str = "k0") -> ContinuumState:
    """The initial state: geostatic stress (``k0`` or ``elastic``, module docstring), zero
    displacement, the footing resting on the surface with no load.

    Raises :class:`InputError` if the geostatic stress violates the yield criterion somewhere.
    """
    checks.one_of("geostatic method", method, ("k0", "elastic"))
    if model.soil.density == 0.0:
        return start_state(model, None, None)
    stress = k0_stress(model) if method == "k0" else elastic_gravity_stress(model)
    eigenstrain = _compliance(model, stress)
    _, _, trial = model.material(eigenstrain, model.initial_material_state())
    plastic = np.asarray(trial.region) != Region.ELASTIC
    if plastic.any():
        depth = -model.disc.qp_coordinates[1][plastic]
        field = f"soil.k0 = {model.k0:g}" if method == "k0" else "geostatic method = 'elastic'"
        raise InputError(f"{field}: the geostatic stress violates the yield criterion of "
                         f"soil.model = {model.soil.model!r} at depths {depth.min():.3g} to "
                         f"{depth.max():.3g}; choose a K0 inside the yield surface")
    return start_state(model, stress, eigenstrain)


# ---------------------------------------------------------------------------------------------
# Footing stiffness (elastic, full contact)
# ---------------------------------------------------------------------------------------------


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
        D = np.broadcast_to(plane_strain_tangent(_elastic_tangent(model))[..., None, None],
                            (3, 3) + model.disc.qp_shape)
        cond = model.condense(np.ascontiguousarray(D))
    L = model.footing.kinematics
    depth = model.mesh_parameters.get("domain_depth", math.nan)
    if model.soil.layer_depth is not None:
        depth = model.soil.layer_depth / model.width
    return FootingStiffness(matrix=L.T @ cond.S @ L,
                            domain_width=model.mesh_parameters.get("domain_width", math.nan),
                            domain_depth=depth)


# ---------------------------------------------------------------------------------------------
# Pushover histories
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class StaticPath:
    """Histories of a static analysis, one entry per converged step.

    ``u``, ``v`` (length), ``theta`` (rad) of the footing; ``H``, ``N``, ``M`` it carries;
    ``contact_length`` (length); per node at ``x``: ``pressure`` (force/length²), ``shear``
    traction on the soil (+x), ``gap`` (length) and ``status``; ``iterations`` (Newton, last
    sub-step) and ``cuts`` (bisections) per step.
    ``width`` B; ``metadata`` provenance.

    Soil fields, when the pushover was asked to ``record_fields`` (else None):
    ``snapshot_step`` (nk) the recorded step indices; ``displacement`` (nk, ndofs) the soil
    displacement DOF vector in the model basis's ordering (length); ``plastic_strain``
    (nk, nelems) the element-averaged equivalent plastic strain; ``max_shear_stress``
    (nk, nelems) the element-averaged (σ1 − σ3)/2 (force/length²).
    The properties ``time`` (the step number, a pseudo-time), ``footing`` (n, 3) and
    ``snapshot_time`` give a static path the shape of a dynamic result for
    :mod:`~upliftlab.continuum.output`.
    """

    kind: str
    u: np.ndarray
    v: np.ndarray
    theta: np.ndarray
    H: np.ndarray
    N: np.ndarray
    M: np.ndarray
    contact_length: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    shear: np.ndarray
    gap: np.ndarray
    status: np.ndarray
    iterations: np.ndarray
    cuts: np.ndarray
    width: float
    metadata: dict = field(default_factory=dict, repr=False)
    snapshot_step: np.ndarray | None = None
    displacement: np.ndarray | None = field(default=None, repr=False)
    plastic_strain: np.ndarray | None = field(default=None, repr=False)
    max_shear_stress: np.ndarray | None = field(default=None, repr=False)

    @property
    def time(self) -> np.ndarray:
        """The load-step number 1, 2, …, n: the pseudo-time of a static path."""
        return np.arange(1.0, self.theta.size + 1.0)

    @property
    def footing(self) -> np.ndarray:
        """(n, 3): u, v, θ of the footing per step."""
        return np.column_stack((self.u, self.v, self.theta))

    @property
    def has_fields(self) -> bool:
        """True if soil fields were recorded."""
        return self.snapshot_step is not None

    @property
    def snapshot_time(self) -> np.ndarray:
        """The pseudo-time (step number) of each recorded step; empty if none."""
        if self.snapshot_step is None:
            return np.zeros(0)
        return self.time[self.snapshot_step]

    @property
    def settlement(self) -> np.ndarray:
        """−v (length, positive down)."""
        return -self.v

    @property
    def eccentricity(self) -> np.ndarray:
        """e = M/N (length)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.M / self.N

    @property
    def contact_fraction(self) -> np.ndarray:
        return self.contact_length / self.width

    @property
    def capacity(self) -> float:
        """Largest vertical load N reached (force/length)."""
        return float(np.max(self.N))

    def save(self, path) -> Path:
        """Write the histories to NetCDF (atomically), with provenance."""
        step, node = ("step",), ("step", "node")
        units = self.metadata.get("units", {})
        variables = {
            "u": (step, self.u, {"units": units.get("length", "")}),
            "v": (step, self.v, {"units": units.get("length", ""), "positive": "up"}),
            "theta": (step, self.theta, {"units": "rad"}),
            "H": (step, self.H, {"units": units.get("force/length", "")}),
            "N": (step, self.N, {"units": units.get("force/length", ""),
                                 "positive": "compression"}),
            "M": (step, self.M, {"units": units.get("moment/length", ""),
                                 "positive": "resisting +theta"}),
            "contact_length": (step, self.contact_length, {"units": units.get("length", "")}),
            "x": (("node",), self.x, {"units": units.get("length", "")}),
            "pressure": (node, self.pressure, {"positive": "compression"}),
            "shear": (node, self.shear, {}),
            "gap": (node, self.gap, {}),
            "status": (node, self.status, {"values": "0 open, 1 stick, 2/3 slip +/-"}),
            "iterations": (step, self.iterations, {}),
            "cuts": (step, self.cuts, {}),
        }
        if self.has_fields:
            variables.update(self._field_variables(units))
        return write_netcdf(path, variables, attrs={"kind": self.kind, "width": self.width,
                                                    **self.metadata})

    def _field_variables(self, units: dict) -> dict:
        snap = ("snapshot",)
        return {
            "snapshot_step": (snap, self.snapshot_step, {"meaning": "index of the step"}),
            "snapshot_time": (snap, self.snapshot_time, {"meaning": "load-step number"}),
            "displacement": (snap + ("dof",), self.displacement,
                             {"units": units.get("length", ""),
                              "meaning": "soil DOF vector, model basis ordering"}),
            "plastic_strain": (snap + ("element",), self.plastic_strain,
                               {"meaning": "element-averaged equivalent plastic strain"}),
            "max_shear_stress": (snap + ("element",), self.max_shear_stress,
                                 {"units": units.get("stress", ""),
                                  "meaning": "element-averaged (s1 - s3)/2"}),
        }


def element_average(model, values: np.ndarray) -> np.ndarray:
    """The area-weighted average per element of a quadrature-point field (…, nelems, nqp)."""
    dx = model.disc.dx
    return np.sum(values * dx, axis=-1) / np.sum(dx, axis=-1)


def max_shear_stress(stress: np.ndarray) -> np.ndarray:
    """(σ1 − σ3)/2 of a stress field (3, 3, …), from its principal values."""
    batch = stress.shape[2:]
    flat = np.moveaxis(stress.reshape(3, 3, -1), -1, 0)
    principal = np.linalg.eigvalsh(0.5 * (flat + np.swapaxes(flat, 1, 2)))
    return (0.5 * (principal[:, -1] - principal[:, 0])).reshape(batch)


def _snapshot_steps(record_fields, steps: int) -> np.ndarray | None:
    """The step indices ``record_fields`` asks for (None: none), checked before any work."""
    if record_fields is None or record_fields is False:
        return None
    if record_fields is True:
        return np.arange(steps)
    try:
        chosen = np.asarray(list(record_fields))
    except TypeError:
        chosen = np.asarray([record_fields])
    if chosen.ndim != 1 or chosen.size == 0 or chosen.dtype.kind not in "iu":
        raise InputError(f"record_fields = {record_fields!r}: expected True, False or a "
                         "non-empty list of step indices")
    if chosen.min() < -steps or chosen.max() >= steps:
        raise InputError(f"record_fields = {chosen.tolist()}: step indices must lie in "
                         f"[{-steps}, {steps - 1}] for {steps} steps")
    return np.unique(np.where(chosen < 0, chosen + steps, chosen))


def _fields(model, states, snapshots: np.ndarray | None) -> dict:
    if snapshots is None:
        return {}
    chosen = [states[k] for k in snapshots]
    return dict(
        snapshot_step=snapshots,
        displacement=np.array([s.u for s in chosen]),
        plastic_strain=np.array([element_average(model, s.material.equivalent_plastic_strain)
                                 for s in chosen]),
        max_shear_stress=np.array([element_average(model, max_shear_stress(s.stress))
                                   for s in chosen]))


def _follow(model, state, controls, options, progress) -> list[ContinuumState]:
    """:func:`follow`, calling ``progress(k, n, state)`` after each step if given (the steps
    are the same: :func:`follow` takes its controls one after the other)."""
    if progress is None:
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
        progress(k, len(controls), state)
    return states


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
        contact_length=np.array([f.contact_length(st != OPEN, p, g)
                                 for st, p, g in zip(status, pressure, gap)]),
        x=f.x, pressure=pressure, shear=shear / f.weight,
        gap=gap, status=status,
        iterations=np.array([s.iterations for s in states]),
        cuts=np.array([s.cuts for s in states]), width=f.width,
        metadata=_metadata(model, kind, extra), **_fields(model, states, snapshots))


def _metadata(model, kind: str, extra) -> dict:
    scene = model.scene
    units = {}
    if scene is not None:
        u = scene.units
        units = {"length": u.length, "force/length": f"{u.force}/{u.length}",
                 "moment/length": f"{u.force}*{u.length}/{u.length}",
                 "stress": f"{u.force}/{u.length}^2"}
    return provenance(analysis=kind, model="continuum", scene=scene.name if scene else "",
                      scene_digest=scene.digest if scene else "", soil=asdict(model.soil),
                      options=asdict(model.options), mesh=model.mesh_parameters,
                      element=model.disc.element, intorder=model.disc.intorder,
                      dofs=model.dofs, k0=model.k0, units=units, **(extra or {}))


def _u_control(model) -> tuple[bool, float]:
    """u is prescribed (0) on a frictionless interface, else free with H = 0."""
    return (not model.footing.interface.tangential), 0.0


RecordFields = bool | Iterable[int]
Progress = Callable[[int, int, ContinuumState], None] | None


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
    snapshots = _snapshot_steps(record_fields, settlements.size)
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
    snapshots = _snapshot_steps(record_fields, values.size)
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


# ---------------------------------------------------------------------------------------------
# Uplift onset
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class UpliftOnset:
    """First loss of contact along a rotation pushover: ``theta`` (rad), ``M``, ``N`` and the
    eccentricity ``e`` = M/N (length), found where the smallest nodal normal force reaches zero
    by linear interpolation between the last full-contact step and the next (exact for elastic
    soil, whose full-contact response is linear in θ)."""

    theta: float
    M: float
    N: float
    e: float


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


# ---------------------------------------------------------------------------------------------
# V–M envelope
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Envelope:
    """A V–M capacity envelope by constant-V rotation probes: for each ``V`` (force/length) the
    largest moment ``M`` reached; ``V_ult`` the vertical capacity it is normalised by, ``width`` B.
    ``probes`` are the :class:`StaticPath` of each probe."""

    V: np.ndarray
    M: np.ndarray
    V_ult: float
    width: float
    probes: tuple = field(repr=False, default=())
    metadata: dict = field(default_factory=dict, repr=False)

    @property
    def v(self) -> np.ndarray:
        """V/V_ult."""
        return self.V / self.V_ult

    @property
    def m(self) -> np.ndarray:
        """M/(B V_ult)."""
        return self.M / (self.width * self.V_ult)

    def save(self, path) -> Path:
        """Write V, M, v, m per probe to NetCDF (atomically), with provenance."""
        variables = {"V": (("probe",), self.V, {}), "M": (("probe",), self.M, {}),
                     "v": (("probe",), self.v, {}), "m": (("probe",), self.m, {})}
        return write_netcdf(path, variables, attrs={"V_ult": self.V_ult, "width": self.width,
                                                    **self.metadata})


def vm_envelope(model, v_ratios, rotations, *, V_ult: float | None = None,
                settlements=None, load_steps: int = 4,
                options: NewtonOptions = NewtonOptions()) -> Envelope:
    """V–M envelope by constant-V probes: for each v in ``v_ratios`` (in (0, 1)), apply
    V = v V_ult, then rotate through ``rotations`` (rad, increasing) at constant V; M_ult(V) is
    the largest moment reached. ``V_ult`` defaults to the capacity of a vertical pushover to
    ``settlements`` on the same model (so the mesh's own overshoot cancels in v and m). A probe
    whose V the soil cannot carry raises :class:`~upliftlab.continuum.ConvergenceError`."""
    v_ratios = _history("v_ratios", v_ratios)
    if not ((v_ratios > 0.0) & (v_ratios < 1.0)).all():
        raise InputError(f"v_ratios = {v_ratios.tolist()}: valid range is (0, 1)")
    if V_ult is None:
        if settlements is None:
            raise InputError("settlements = None: give V_ult or the settlements of the "
                             "vertical pushover that finds it")
        V_ult = vertical_pushover(model, settlements, options=options).capacity
    checks.positive("V_ult", V_ult)
    probes = tuple(rotation_pushover(model, v * V_ult, rotations, load_steps=load_steps,
                                     options=options) for v in v_ratios)
    return Envelope(V=v_ratios * V_ult, M=np.array([p.M.max() for p in probes]), V_ult=V_ult,
                    width=model.width, probes=probes,
                    metadata=_metadata(model, "vm_envelope",
                                       {"rotations": np.asarray(rotations).tolist()}))
