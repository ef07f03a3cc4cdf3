"""The result of a dynamic run of the continuum (either route) and the recorder that fills it.

:class:`DynamicResult` holds one row per recorded step (row 0: the static state at t = 0): the
footing's motion, the story's deformation, the contact forces and status, the solver's
iterations and an energy account; and the soil fields at evenly spaced snapshots.
:class:`Recorder` fills it row by row from any state that has the footing's ``q``, the soil's
``u``, the contact ``force``, ``status`` and ``reaction`` (and, at a snapshot, ``material`` and
``stress``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...results import write_dataset
from ..output.views import NotebookViews
from ..output.fields import (element_average, field_coordinates, max_shear_stress,
                             result_metadata)
from ..contact.footing import OPEN
from .far_field import FarFieldRecorder
from .validity import validity

__all__ = ["ENERGY", "DynamicResult", "Recorder"]

ENERGY = ("kinetic", "strain", "damping", "input", "contact")


@dataclass(frozen=True, eq=False)
class DynamicResult(NotebookViews):
    """Histories of a dynamic run, one row per step (row 0: the static state at t = 0).

    ``time`` (s); ``footing`` (nt, 3) u, v (up), θ (rad) relative to the base (rigid base) or
    absolute (compliant base); ``structure_u`` (nt) the story deformation s (length) and
    ``structure_velocity`` (length/s); ``ground_acceleration`` (nt, length/s²); ``H``, ``N``
    (compression), ``M`` (force/length); ``contact_length`` (length); per contact node at ``x``:
    ``pressure`` (force/length², compression +), ``gap`` (length), ``status``; ``iterations``
    Newton iterations per step (explicit route: contact active-set iterations since the last
    row), ``refactored`` (bool) the steps that refactorised the iteration matrix (plastic soil:
    a slow step, or a retry with the consistent tangent; never on the explicit route);
    ``energy`` (nt, 5): kinetic, strain (soil work ∫(f_int − f_body)·du, story spring, footing
    weight), damping (dissipated by dashpots), input (work of the ground loads), contact (the
    energy the contact forces took out of the soil and the footing), all cumulative from the
    static state by the trapezoidal rule (force·length/length; with ``energy`` off: NaN). For
    Newmark (α = 0), kinetic + strain + damping + contact − input is constant to the Newton
    tolerance; HHT's dissipation and central differences' O(dt²) make it drift
    (:attr:`energy_balance_error`).
    Soil fields at ``snapshot_step``: ``displacement`` (nk, ndofs), ``plastic_strain`` and
    ``max_shear_stress`` (nk, nelems) element averages, where they live: ``dof_xy``,
    ``dof_direction``, ``element_xy``
    (:func:`~upliftlab.continuum.output.fields.field_coordinates`). ``width`` B; ``metadata``
    provenance, with the run's ``validity`` against the small-strain limit
    (:mod:`~upliftlab.continuum.dynamics.validity`). ``far_field``: the response of the soil
    columns at the box's sides, peak shear strain and plastic strain by depth
    (:class:`~upliftlab.continuum.dynamics.far_field.FarFieldResponse`; None for a result made
    before it was recorded).
    """

    #: The names of the energy account's columns (:data:`ENERGY`).
    energy_names = ENERGY

    time: np.ndarray
    footing: np.ndarray
    structure_u: np.ndarray
    structure_velocity: np.ndarray
    ground_acceleration: np.ndarray
    H: np.ndarray
    N: np.ndarray
    M: np.ndarray
    contact_length: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    status: np.ndarray
    iterations: np.ndarray
    refactored: np.ndarray
    energy: np.ndarray
    width: float
    snapshot_step: np.ndarray
    displacement: np.ndarray = field(repr=False)
    plastic_strain: np.ndarray = field(repr=False)
    max_shear_stress: np.ndarray = field(repr=False)
    metadata: dict = field(default_factory=dict, repr=False)
    kind: str = "dynamic"
    dof_xy: np.ndarray | None = field(default=None, repr=False)
    dof_direction: np.ndarray | None = field(default=None, repr=False)
    element_xy: np.ndarray | None = field(default=None, repr=False)
    far_field: object = field(default=None, repr=False)

    @property
    def snapshot_time(self) -> np.ndarray:
        return self.time[self.snapshot_step]

    @property
    def theta(self) -> np.ndarray:
        return self.footing[:, 2]

    @property
    def total_energy(self) -> np.ndarray:
        """kinetic + strain + damping + contact − input (constant for an exact balance)."""
        e = self.energy
        return e[:, 0] + e[:, 1] + e[:, 2] + e[:, 4] - e[:, 3]

    @property
    def energy_balance_error(self) -> float:
        """The balance's relative error
        (:func:`~upliftlab.continuum.dynamics.run_control.balance_error`;
        NaN without an energy account)."""
        from .run_control import balance_error
        return balance_error(self.energy, self.metadata.get("energy_floor", 0.0))

    def switches(self) -> np.ndarray:
        """Open/closed status changes per node over the run (nc)."""
        closed = self.status != OPEN
        return np.sum(closed[1:] != closed[:-1], axis=0)

    def __repr__(self) -> str:
        """One line: the method, the span, the peaks of the footing and the energy balance
        (the arrays are in :meth:`to_xarray`)."""
        length = self.metadata.get("units", {}).get("length", "")
        incomplete = ", INCOMPLETE" if self.metadata.get("incomplete") else ""
        return (f"<DynamicResult {self.metadata.get('method', '?')}: {self.time.size} steps over "
                f"{self.time[-1]:.4g} s, peak |theta| = {np.max(np.abs(self.footing[:, 2])):.4g}"
                f" rad, settlement at the end = {-self.footing[-1, 1]:.4g} {length}, "
                f"{self.snapshot_step.size} snapshots, B = {self.width:g} {length}{incomplete}>")

    def to_xarray(self):
        """The footing's histories and its contact along the base as an
        :class:`xarray.Dataset` with labelled coordinates and CF attributes
        (:mod:`~.labelled`): ``ds.pressure.sel(node=0)``, ``ds.energy.sel(component="input")``."""
        from ..output.labelled import to_dataset

        return to_dataset(self)

    def to_dataframe(self):
        """The footing's and the structure's scalar histories (u, v, θ, H, N, M, contact length,
        story deformation, …) as a :class:`pandas.DataFrame` indexed by time (s)."""
        from ..output.labelled import to_frame

        return to_frame(self.to_xarray(), "time")

    def save(self, path) -> Path:
        """Write the labelled dataset of :meth:`to_xarray` (histories, contact, soil fields at the
        snapshots, provenance) to NetCDF-4, atomically (without importing xarray)."""
        from ..output.labelled import labelled_data

        return write_dataset(path, labelled_data(self))


class Recorder:
    """Per-step histories and the snapshots, and the largest equivalent plastic strain ε̄p at
    any quadrature point of the soil (``peak_plastic_strain``; ε̄p only accumulates, so it is
    the last row's): where the soil left small strain, whatever its footing does; and the far
    field's peaks by depth (``far``, :mod:`~upliftlab.continuum.dynamics.far_field`), read
    from the same rows. The contact length of every row is measured once, when the result is
    made (:meth:`~upliftlab.continuum.contact.footing.Footing.contact_lengths`)."""

    def __init__(self, model, steps: int, snapshots: int):
        f = model.footing
        nt, nc = steps + 1, f.nodes
        self.model, self.f = model, f
        self.time, self.q = np.zeros(nt), np.zeros((nt, 3))
        self.s, self.sv, self.ag = np.zeros(nt), np.zeros(nt), np.zeros(nt)
        self.reaction = np.zeros((nt, 3))
        self.pressure, self.gap = np.zeros((nt, nc)), np.zeros((nt, nc))
        self.status = np.zeros((nt, nc), dtype=np.int8)
        self.iterations = np.zeros(nt, dtype=np.int64)
        self.refactored = np.zeros(nt, dtype=bool)
        self.energy = np.zeros((nt, len(ENERGY)))
        chosen = np.unique(np.round(np.linspace(0, steps, snapshots)).astype(np.int64)) \
            if snapshots else np.zeros(0, dtype=np.int64)
        self.snap_steps = chosen
        self.rows = 0
        self.peak_plastic_strain = 0.0
        self.snap_index = {int(k): i for i, k in enumerate(chosen)}
        ne = model.mesh.nelements
        self.disp = np.zeros((chosen.size, model.disc.ndofs))
        self.eps = np.zeros((chosen.size, ne))
        self.shear = np.zeros((chosen.size, ne))
        self.far = FarFieldRecorder(model)

    def record(self, k, t, state, zk, ag, energy, iterations, refactored, kinetic=0.0):
        f = self.f
        self.rows = k + 1
        self.time[k], self.q[k] = t, state.q
        self.s[k], self.sv[k], self.ag[k] = zk.d[3], zk.v[3], ag
        self.reaction[k] = state.reaction
        self.pressure[k] = -state.force[:f.nodes] / f.weight
        self.gap[k] = f.gap(state.u, state.q)
        self.status[k] = state.status
        self.iterations[k], self.refactored[k] = iterations, refactored
        self.energy[k] = energy
        self.energy[k, 0] = kinetic
        peak = getattr(state, "peak_plastic_strain", None)
        ebar = getattr(state, "equivalent_plastic_strain", None)
        if ebar is None:
            ebar = state.material.equivalent_plastic_strain
        if peak is None:
            peak = float(np.max(ebar)) if np.size(ebar) else 0.0
        self.peak_plastic_strain = max(self.peak_plastic_strain, float(peak))
        self.far.record(state.u, ebar)
        i = self.snap_index.get(int(k))
        if i is not None:
            self.disp[i] = state.u
            self.eps[i] = element_average(self.model, state.material.equivalent_plastic_strain)
            self.shear[i] = element_average(self.model, max_shear_stress(state.stress))

    def result(self, model, motion, extra: dict, rows: int | None = None) -> DynamicResult:
        """The :class:`DynamicResult` with ``extra`` metadata; ``rows``: only the first rows
        were recorded (an interrupted run), marked ``incomplete`` with ``completed_until``."""
        n = self.time.size if rows is None else rows
        far = self.far.response()
        extra = {**extra, "motion": motion.name, "motion_source": motion.source,
                 "width": model.width, "max_plastic_strain": self.peak_plastic_strain,
                 **validity(self.peak_plastic_strain),
                 "far_field": far.summary()["yielded"]}
        if n < self.time.size:
            extra.update(incomplete=True, completed_until=float(self.time[n - 1]))
        snaps = self.snap_steps < n
        length = self.f.contact_lengths(self.status[:n] != OPEN, self.pressure[:n], self.gap[:n])
        return DynamicResult(
            time=self.time[:n], footing=self.q[:n], structure_u=self.s[:n],
            structure_velocity=self.sv[:n], ground_acceleration=self.ag[:n],
            H=self.reaction[:n, 0], N=-self.reaction[:n, 1], M=self.reaction[:n, 2],
            contact_length=length, x=self.f.x, pressure=self.pressure[:n],
            gap=self.gap[:n], status=self.status[:n], iterations=self.iterations[:n],
            refactored=self.refactored[:n], energy=self.energy[:n], width=model.width,
            snapshot_step=self.snap_steps[snaps], displacement=self.disp[snaps],
            plastic_strain=self.eps[snaps], max_shear_stress=self.shear[snaps],
            metadata=result_metadata(model, "dynamic", extra), far_field=far,
            **field_coordinates(model))
