"""The result of a reduced-model run: time histories, peaks, energy balance and provenance.

A :class:`Response` is a record of arrays. Derived histories (u, θ, V, base shear, overturning
moment, uplift, contact length) are properties computed from the stored state, so that one
stored set of arrays serves every figure and summary. :meth:`Response.save` writes one
self-describing NetCDF-4 file (and CSV on request), atomically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from ..paths import check_target
from ..results import write_csv, write_dataset
from .model import ReducedModel
from .peak_slots import TrackedPeaks, decode_peaks, static_energy, weighted_plastic_settlement
from .static import contact_lengths

__all__ = ["Response", "ENERGY_NAMES", "BASE_NAMES", "energy_balance_error"]

ENERGY_NAMES = ("input", "kinetic", "strain", "gravity", "viscous", "impact", "plastic")
#: The columns of a base element's stored states (:mod:`.kernels.base`): its forces without
#: the dashpots (force, force, force·length), plastic displacement (length, length, rad), the
#: contact from ``contact_from`` to ``contact_to`` (length, from O), the rounding ρ of the
#: soil's surface (length) and the energy it dissipated (force·length); their descriptions are
#: :data:`~.labelled.BASE_STATES`, in this order (a test holds the two alike).
BASE_NAMES = ("V", "H", "M", "v_p", "u_p", "theta_p", "contact_from", "contact_to",
              "rounding", "dissipated")


@dataclass(frozen=True, eq=False)
class Response:
    """Time histories of a run (units of the scene).

    ``time`` (nt); ``q``, ``qd`` (nt × n) DOFs relative to the ground; per spring (nt × n_spring):
    ``deformation`` e, ``force`` (story shear without its dashpot; foundation total compression),
    ``mode`` and ``plastic`` deformation; ``energy`` (nt × 7, :data:`ENERGY_NAMES`, cumulative).
    ``peaks`` are tracked at every step (with cubic interpolation between steps), not only at
    the stored times. ``info`` holds the integrator, step and counters; ``provenance`` the rest.
    ``base`` (nt × :data:`BASE_NAMES`): a base element's states (the macro-element; no columns
    without one).
    """

    #: The names of the energy account's columns (:data:`ENERGY_NAMES`).
    energy_names = ENERGY_NAMES

    model: ReducedModel
    time: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    deformation: np.ndarray
    force: np.ndarray
    mode: np.ndarray
    plastic: np.ndarray
    energy: np.ndarray
    raw_peaks: np.ndarray
    ground_displacement: np.ndarray
    impacts: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)))
    info: dict = field(default_factory=dict)
    provenance: dict = field(default_factory=dict)
    motion: object = field(default=None, repr=False)  # the Motion the run read (for its file)
    base: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))

    # ---- histories --------------------------------------------------------------------------
    @property
    def dofs(self):
        return self.model.dofs

    @property
    def u(self) -> np.ndarray:
        """Superstructure deformation at the top, u = X − X_g − hθ (eq. 7) (length)."""
        n = self.model.story_count
        return self.deformation[:, :n].sum(axis=1) if n else np.zeros(self.time.size)

    @property
    def x(self) -> np.ndarray:
        """Lateral displacement of the top mass relative to the ground, X − X_g (length).
        Exact kinematics: u_O + w cos θ + h sin θ, the base's centre moving by u_O = ±b (1 −
        cos θ) as it rocks on the edge it leans towards."""
        d = self.dofs
        if self.model.exact:
            s = self.q[:, d.theta]
            c = np.sqrt(1.0 - s * s)
            w = self.q[:, d.stories[-1]] if d.stories else 0.0
            return (self.model.layout.half_width * np.sign(s) * (1.0 - c) + w * c
                    + self.model.heights[-1] * s)
        if d.stories:
            return self.q[:, d.stories[-1]]
        if d.sway >= 0:  # u_G + (h − h_G) θ
            lever = self.model.heights[-1] - self.model.sway_height
            return self.q[:, d.sway] + lever * self.theta
        return self.model.heights[-1] * self.theta

    @property
    def sway(self) -> np.ndarray:
        """Horizontal displacement of the base relative to the ground, u_b: the sway spring's
        deformation, its sliding included, or a base element's sway u (length; zero without
        either)."""
        if self.model.base is not None:
            return self.q @ self.model.base.transform[1]
        j = self.model.sway_spring
        return self.deformation[:, j] if j >= 0 else np.zeros(self.time.size)

    @property
    def X(self) -> np.ndarray:
        """Absolute lateral displacement of the top mass (length)."""
        return self.x + self.ground_displacement

    @property
    def theta(self) -> np.ndarray:
        """Base rotation θ (rad) (exact kinematics: arcsin of the DOF sin θ)."""
        i = self.dofs.theta
        if i < 0:
            return np.zeros(self.time.size)
        return np.arcsin(self.q[:, i]) if self.model.exact else self.q[:, i]

    @property
    def V(self) -> np.ndarray:
        """Vertical displacement of the base centre O, up (length)."""
        i = self.dofs.v
        return self.q[:, i] if i >= 0 else np.zeros(self.time.size)

    @property
    def story_shear(self) -> np.ndarray:
        """Story shears including the story dashpots (nt × stories) (force)."""
        n = self.model.story_count
        rate = self.qd @ self.model.A[:, :n]
        return self.force[:, :n] + rate * self.model.params["c"][:n]

    @property
    def base_shear(self) -> np.ndarray:
        """Shear at the base of the superstructure (force)."""
        if self.model.story_count == 0:
            return np.zeros(self.time.size)
        return self.story_shear[:, 0]

    @property
    def overturning_moment(self) -> np.ndarray:
        """Moment of the story shears about the base, Σ V_j (h_j − h_{j−1}) (force·length)."""
        n = self.model.story_count
        if n == 0:
            return np.zeros(self.time.size)
        h = self.model.heights
        lever = np.diff(np.concatenate([[0.0], h]))
        return self.story_shear @ lever

    @property
    def foundation_slice(self) -> slice:
        return self.model.foundation_slice

    @property
    def spring_positions(self) -> np.ndarray:
        return self.model.params["x"][self.foundation_slice]

    @property
    def uplift(self) -> np.ndarray:
        """Gap under each foundation spring, max(0, −d) (nt × N) (length)."""
        f = self.foundation_slice
        d = self.model.params["d0"][f] + self.deformation[:, f] - self.plastic[:, f]
        return np.maximum(-d, 0.0)

    @property
    def leftmost(self) -> int:
        """Index (among foundation springs) of the spring at the most negative x."""
        return int(np.argmin(self.spring_positions))

    @property
    def left_spring_displacement(self) -> np.ndarray:
        """Downward displacement of the base over the leftmost spring, from rest (length).

        Negative when the base rises there (uplift), as plotted in Ewing's Figs. 4, 5, 7–10.
        A base element has no springs: its left edge, x = −b, moves down by −b θ − V.
        """
        if self.model.base is not None:
            return -self.model.layout.half_width * self.theta - self.V
        return self.deformation[:, self.foundation_slice][:, self.leftmost]

    @cached_property
    def contact_length(self) -> np.ndarray:
        """Length of base in contact (length)."""
        if self.model.layout is None:
            return np.zeros(self.time.size)
        if self.model.base is not None:
            return self.base[:, 7] - self.base[:, 6]
        f = self.foundation_slice
        return contact_lengths(self.model, self.deformation[:, f], self.plastic[:, f])

    @property
    def settlement(self) -> np.ndarray:
        """Settlement of the base centre, −V (length, down)."""
        return -self.V

    @property
    def impact_log(self) -> dict[str, np.ndarray]:
        """Each activation of an impact damper (event stepper only): ``time`` of recontact (s),
        ``spring`` (index among foundation springs), closing velocity ``v0`` (length/s), and
        ``lock_time``/``lock_velocity`` when the stroke Δz was done (NaN if the spring separated
        first). ``ratio`` = lock_velocity / v0 is the realised coefficient of restitution."""
        im = self.impacts
        spring = im[:, 1].astype(int) - self.model.foundation_start
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = im[:, 4] / im[:, 2]
        return {"time": im[:, 0], "spring": spring, "v0": im[:, 2], "lock_time": im[:, 3],
                "lock_velocity": im[:, 4], "ratio": ratio}

    # ---- energy -----------------------------------------------------------------------------
    def energy_of(self, name: str) -> np.ndarray:
        return self.energy[:, ENERGY_NAMES.index(name)]

    @property
    def energy_residual(self) -> np.ndarray:
        """Stored + dissipated − input − initial total: zero for a closed balance (energy)."""
        e = self.energy
        total = e[:, 1:].sum(axis=1) - e[:, 0]
        return total - total[0]

    @property
    def energy_balance_error(self) -> float:
        """max |residual| / max(max input, initial energy, static strain energy of the bed):
        the balance's relative error, over the stored states and the checks the integrator
        made between them (:func:`energy_balance_error`)."""
        return max(energy_balance_error(self.energy, static_energy(self.model.params,
                                                                   self.model.base)),
                   self.tracked.energy_residual)

    @property
    def verdict(self) -> str:
        """``completed``, or ``overturned``: the structure passed its toppling angle (its
        centre of weight over the edge of the base) and the run ended there."""
        return self.info.get("verdict", "completed")

    # ---- peaks ------------------------------------------------------------------------------
    @cached_property
    def tracked(self) -> TrackedPeaks:
        """The peaks the integrator tracked at every step (:func:`~.peak_slots.decode_peaks`)."""
        return decode_peaks(self.raw_peaks, stories=self.model.story_count,
                            rocks=self.dofs.theta >= 0, settles=self.dofs.v >= 0,
                            exact=self.model.exact, sways=self.dofs.sway >= 0,
                            static=static_energy(self.model.params, self.model.base))

    @cached_property
    def peaks(self) -> dict[str, float]:
        """Peak values over the whole run, tracked at every step whatever is stored: u, θ, V,
        the gaps and (event stepper) the story shears and the overturning moment with cubic
        interpolation inside the steps; with the fixed-step integrators the shears and moment
        at the step ends; the least contact length at the step ends. Of the last state: the
        plastic settlements (``weighted_plastic_settlement`` Σkε_p/Σk,
        :func:`~.peak_slots.weighted_plastic_settlement`), ``final_vertical_position`` (V
        at the end, up positive, whether or not the base still moves) and, only when the
        run ends at rest (:meth:`at_rest`), ``residual_settlement`` (−V then, down
        positive): the settlement the structure came to rest at. A run that ends still
        moving has no residual settlement (before, its −V was reported as one: −0.42 in, an
        upward "settlement", for an elastic wall still rocking)."""
        pk = self.tracked
        f = self.foundation_slice
        gap = pk.opening[f]
        out = {
            "u": pk.u,
            "theta": pk.theta,
            "V_min": pk.v_min,
            "V_max": pk.v_max,
            "base_shear": pk.base_shear,
            "overturning_moment": pk.overturning_moment,
        }
        if self.model.story_count:
            out["story_drift"] = pk.story_drift
        if self.model.sway_spring >= 0:
            j = self.model.sway_spring
            out["sway"] = pk.sway
            out["sway_force"] = pk.sway_force
            out["residual_sway"] = float(self.deformation[-1, j])
            out["sliding"] = float(self.plastic[-1, j])
        if self.model.base is not None:
            out.update(self._base_peaks(pk))
        elif self.model.layout is not None:
            out["uplift_left"] = max(float(gap[self.leftmost]), 0.0)
            out["uplift_max"] = max(float(np.max(gap)), 0.0)
            out["spring_force_max"] = float(np.max(pk.force[f]))
            out["final_vertical_position"] = float(self.V[-1])
            out["weighted_plastic_settlement"] = weighted_plastic_settlement(
                self.model.params, self.plastic[-1])
            if self.at_rest():
                out["residual_settlement"] = float(-self.V[-1])
            out["plastic_settlement_max"] = float(np.max(self.plastic[-1, f]))
            out["plastic_settlement_mean"] = float(np.mean(self.plastic[-1, f]))
            out["min_contact_length"] = pk.min_contact_length
        out["energy_balance_error"] = self.energy_balance_error
        return {k: (float(v) if not isinstance(v, list) else v) for k, v in out.items()}

    def _base_peaks(self, pk: TrackedPeaks) -> dict[str, float]:
        """The peaks of a base element: its sway and horizontal force, the larger gap under its
        edges, the least contact length (each at the steps' ends), and of the last state its
        plastic settlement and, at rest, the residual settlement."""
        sway_row = self.model.base.transform[1]
        out = {"sway": pk.base_sway, "sway_force": pk.base_force,
               "residual_sway": float(sway_row @ self.q[-1]),
               "uplift_max": pk.base_gap, "min_contact_length": pk.min_contact_length,
               "final_vertical_position": float(self.V[-1]),
               "plastic_settlement": float(self.base[-1, 3])}
        if self.at_rest():
            out["residual_settlement"] = float(-self.V[-1])
        return out

    def summary(self) -> dict:
        """One-line summary: the peaks that matter, with units and provenance essentials."""
        u = self.model.scene.units
        pk = self.peaks
        out = {
            "scene": self.model.scene.name,
            "verdict": self.verdict,
            "overturned_at": self.info.get("overturned_at"),
            "kinematics": self.model.scene.structure.kinematics,
            "integrator": self.info.get("integrator"),
            "dt": self.info.get("dt"),
            "rtol": self.info.get("rtol"),
            "stability_limit": self.info.get("stability_limit"),
            "energy_tolerance": self.info.get("energy_tolerance"),
            "units": u.name,
            "peak_u": pk["u"],
            "peak_theta": pk["theta"],
            "peak_base_shear": pk["base_shear"],
        }
        if "sway" in pk:
            out["peak_sway"] = pk["sway"]
        if "uplift_left" in pk:
            out["peak_uplift_left"] = pk["uplift_left"]
            out["at_rest"] = self.at_rest()
            out["residual_settlement"] = pk.get("residual_settlement")  # None: still moving
            out["final_vertical_position"] = pk["final_vertical_position"]
            out["weighted_plastic_settlement"] = pk["weighted_plastic_settlement"]
        out["energy_balance_error"] = pk["energy_balance_error"]
        out["notes"] = list(self.info.get("notes", []))
        # valid JSON: an unbounded limit (implicit integrators) is null, never Infinity
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                for k, v in out.items()}

    def __repr__(self) -> str:
        """One line: the scene, the integrator, the stored span and the verdict with the peaks
        (the arrays are in :meth:`to_xarray`)."""
        return (f"<Response {self.summary_line()}; {self.info.get('integrator', '?')}, "
                f"{self.time.size} stored times over {self.time[-1]:.4g} s, "
                f"{self.model.params.size} springs, {self.verdict}>")

    def summary_line(self) -> str:
        s = self.summary()
        u = self.model.scene.units
        text = f"{s['scene']}: "
        if s["verdict"] == "overturned":
            text += f"OVERTURNED at t = {s['overturned_at']:.4g} s (peaks up to then): "
        text += (f"peak u = {s['peak_u']:.4g} {u.length}, "
                 f"peak theta = {s['peak_theta']:.4g} rad")
        if "peak_sway" in s:
            text += f", peak sway = {s['peak_sway']:.4g} {u.length}"
        if "peak_uplift_left" in s:
            text += (f", uplift of leftmost spring = {s['peak_uplift_left']:.4g} {u.length}, "
                     + (f"residual settlement (at rest) = {s['residual_settlement']:.4g} "
                        f"{u.length}" if s["residual_settlement"] is not None else
                        f"still moving at the end (final V = "
                        f"{s['final_vertical_position']:.4g} {u.length}, up positive)"))
        return text

    def at_rest(self, fraction: float = 1e-3, tail: float = 0.1) -> bool:
        """Whether the run ends at rest: its kinetic energy over the last ``tail`` of the run
        (at least ten stored states) stays below ``fraction`` of its largest. Only then is
        −V at the end a residual settlement. A run stored at its ends only cannot tell."""
        kinetic = self.energy[:, 1]
        last = self.time >= self.time[-1] * (1.0 - tail)
        if np.count_nonzero(last) < 10:
            return False
        peak = float(np.max(kinetic))
        return peak == 0.0 or float(np.max(kinetic[last])) <= fraction * peak

    # ---- notebook ---------------------------------------------------------------------------
    def plot(self, variables=None, ax=None):
        """A matplotlib figure of the run (nothing written): θ, the largest uplift, the
        settlement and the M–θ loops by default, or the panels ``variables`` (names of
        :data:`~.notebook.PANELS`), on new axes or on ``ax`` (one axis per panel)."""
        from .notebook import response_plot

        return response_plot(self, variables, ax)

    def _repr_html_(self) -> str:
        """The notebook's table of the run: scene, span, verdict, peaks with units, energy
        balance, code digest (:func:`~.notebook.response_html`)."""
        from .notebook import response_html

        return response_html(self)

    # ---- labelled data ----------------------------------------------------------------------
    def to_xarray(self):
        """The response as an :class:`xarray.Dataset` with labelled coordinates and CF
        attributes (:mod:`~.labelled`): ``ds.spring_force.sel(spring=3)``,
        ``ds.energy.sel(component="input")``."""
        from .labelled import to_dataset

        return to_dataset(self)

    def to_dataframe(self):
        """The scalar histories (u, x, X, θ, V, base shear, overturning moment, contact length)
        as a :class:`pandas.DataFrame` indexed by time (:mod:`~.labelled`)."""
        from .labelled import to_frame

        return to_frame(self)

    # ---- files ------------------------------------------------------------------------------
    def save(self, path: str | Path, *, csv: bool = False) -> list[Path]:
        """Write one NetCDF-4 file, the labelled dataset of :meth:`to_xarray` (and a CSV of the
        scalar histories if ``csv``); atomic, without importing xarray."""
        path = Path(path)
        for target in (path, path.with_suffix(".csv")) if csv else (path,):
            check_target(target)  # both refused before either is written
        u = self.model.scene.units
        from .labelled import labelled_data

        written = [write_dataset(path, labelled_data(self))]
        if csv:
            cols = {"time": self.time, "u": self.u, "x": self.x, "theta": self.theta,
                    "V": self.V, "base_shear": self.base_shear,
                    "overturning_moment": self.overturning_moment,
                    "contact_length": self.contact_length}
            if self.model.sway_spring >= 0:
                cols["sway"] = self.sway
            if self.model.layout is not None:
                cols["left_spring_displacement"] = self.left_spring_displacement
            written.append(write_csv(path.with_suffix(".csv"), cols,
                                     header=f"{self.model.scene.title}\nunits {u.name}"))
        return written


def energy_balance_error(energy: np.ndarray, static: float = 0.0) -> float:
    """Relative error of an energy balance (rows of cumulative :data:`ENERGY_NAMES`): the
    largest residual, stored + dissipated − input − initial total, over the largest of the
    largest input, the initial energy and ``static``, the bed's static strain energy
    (:func:`~.peak_slots.static_energy`)."""
    total = energy[:, 1:].sum(axis=1) - energy[:, 0]
    scale = max(np.max(np.abs(energy[:, 0])), abs(energy[0, 1:].sum()), static, 1e-300)
    return float(np.max(np.abs(total - total[0])) / scale)


def ground_displacement(acceleration_g: np.ndarray, dt: float, g: float,
                        times: np.ndarray) -> np.ndarray:
    """X_g at ``times`` for piecewise-linear acceleration (exact at the samples) (length)."""
    a = np.append(acceleration_g, 0.0) * g
    v = np.concatenate([[0.0], np.cumsum(0.5 * dt * (a[1:] + a[:-1]))])
    d = np.concatenate([[0.0], np.cumsum(dt * v[:-1] + dt * dt * (2 * a[:-1] + a[1:]) / 6.0)])
    tk = np.arange(a.size) * dt
    if math.isclose(float(tk[-1]), 0.0):
        return np.zeros_like(times)
    last = tk[-1]
    extra = np.clip(times - last, 0.0, None)
    return np.interp(times, tk, d) + extra * v[-1]
