"""The records of the continuum's static analyses: a load path (:class:`StaticPath`), the uplift
onset along a rotation pushover (:class:`UpliftOnset`) and a V–M capacity envelope
(:class:`Envelope`). Each is frozen and saves itself to NetCDF with its provenance.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...results import write_dataset, write_netcdf
from ..output.views import NotebookViews

__all__ = ["StaticPath", "UpliftOnset", "Envelope"]


@dataclass(frozen=True, eq=False)
class StaticPath(NotebookViews):
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
    (nk, nelems) the element-averaged (σ1 − σ3)/2 (force/length²); where they live:
    ``dof_xy`` (ndofs, 2) each DOF's node (length), ``dof_direction`` (0 x, 1 y) and
    ``element_xy`` (nelems, 2) each element's centroid
    (:func:`~upliftlab.continuum.output.fields.field_coordinates`).
    The properties ``time`` (the step number, a pseudo-time), ``footing`` (n, 3) and
    ``snapshot_time`` give a static path the shape of a dynamic result for
    :mod:`~upliftlab.continuum.output.series`.
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
    dof_xy: np.ndarray | None = field(default=None, repr=False)
    dof_direction: np.ndarray | None = field(default=None, repr=False)
    element_xy: np.ndarray | None = field(default=None, repr=False)

    def to_xarray(self):
        """The path as an :class:`xarray.Dataset` over its load step with CF attributes
        (:mod:`~.labelled`); ``ds.swap_dims(step="theta")`` selects a pushover by rotation."""
        from ..output.labelled import path_to_dataset

        return path_to_dataset(self)

    @classmethod
    def from_xarray(cls, dataset, metadata: dict) -> StaticPath:
        """The path a dataset of :meth:`to_xarray` was made from, every array as the dataset
        holds it (the contact states as int8); ``metadata``: the path's own (the dataset's
        attributes hold it flattened, one attribute per key, which cannot be undone in
        general). What a study that keeps its pushover as data writes the pushover's files
        and figures from."""
        d = {name: np.asarray(var.values) for name, var in dataset.variables.items()}
        fields = {}
        if "snapshot_step" in d:
            fields = {name: d[name] for name in ("snapshot_step", "displacement",
                                                 "plastic_strain", "max_shear_stress")}
            if "dof_x" in d:
                fields.update(dof_xy=np.column_stack((d["dof_x"], d["dof_y"])),
                              dof_direction=d["dof_direction"],
                              element_xy=np.column_stack((d["element_x"], d["element_y"])))
        return cls(str(dataset.attrs["kind"]), d["u"], d["v"], d["theta"], d["H"], d["N"],
                   d["M"], d["contact_length"], d["x"], d["pressure"], d["shear"], d["gap"],
                   d["status"], d["iterations"], d["cuts"], float(dataset.attrs["width"]),
                   dict(metadata), **fields)

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

    def __repr__(self) -> str:
        """One line: the kind, the steps, the range of rotation and the loads reached."""
        units = self.metadata.get("units", {})
        force = units.get("force/length", "")
        return (f"<StaticPath {self.kind}: {self.theta.size} steps, theta up to "
                f"{np.max(np.abs(self.theta)):.4g} rad, N up to {np.max(self.N):.4g} {force}, "
                f"M up to {np.max(np.abs(self.M)):.4g} {units.get('moment/length', '')}, "
                f"B = {self.width:g} {units.get('length', '')}>")

    @property
    def capacity(self) -> float:
        """Largest vertical load N reached (force/length)."""
        return float(np.max(self.N))

    def to_dataframe(self):
        """The path's scalar histories (u, v, θ, H, N, M, contact length, iterations) as a
        :class:`pandas.DataFrame` indexed by load step."""
        from ..output.labelled import to_frame

        return to_frame(self.to_xarray(), "step")

    def save(self, path) -> Path:
        """Write the labelled dataset of :meth:`to_xarray` (the path, the contact along the
        base, the soil fields at the snapshots, provenance) to NetCDF-4, atomically (without
        importing xarray)."""
        from ..output.labelled import path_labelled_data

        return write_dataset(path, path_labelled_data(self))


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
        units = self.metadata.get("units", {})
        probe = ("probe",)
        variables = {
            "V": (probe, self.V, {"units": units.get("force/length", ""),
                                  "long_name": "vertical load of the probe"}),
            "M": (probe, self.M, {"units": units.get("moment/length", ""),
                                  "long_name": "largest moment the probe reached"}),
            "v": (probe, self.v, {"units": "1", "long_name": "V / V_ult"}),
            "m": (probe, self.m, {"units": "1", "long_name": "M / (B V_ult)"})}
        return write_netcdf(path, variables, attrs={"V_ult": self.V_ult, "width": self.width,
                                                    **self.metadata})

