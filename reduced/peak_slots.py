"""The peak array of the compiled integrators, written and read in one place.

The kernels track the peaks of a run in one float array: :data:`~.kernels.N_PEAK_SCALARS`
scalars (slots ``P_*`` of :mod:`.kernels.codes`), then two slots per spring: A, its largest
opening (foundation: the gap −d; story: |drift|), and B, its largest |force| (foundation: the
compression; story: the shear, dashpot included, so story 0 gives the base shear).
:func:`start_peaks` fills the array a run starts from; :func:`decode_peaks` reads it back.
Two scalars of a run come from its spring table alone, for the response and the batch alike:
:func:`static_energy` (the floor of the energy balance's scale) and
:func:`weighted_plastic_settlement`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import kernels as kn

__all__ = ["TrackedPeaks", "decode_peaks", "start_peaks", "static_energy",
           "weighted_plastic_settlement"]


@dataclass(frozen=True, eq=False)
class TrackedPeaks:
    """The peaks a run tracked at every step, in the scene's units."""

    u: float                    # largest |top deformation| (length; 0 without stories)
    theta: float                # largest |θ| (rad; 0 for a fixed base)
    v_min: float                # least and largest V (length; 0 for a fixed base)
    v_max: float
    overturning_moment: float   # largest |Σ arm·shear| of the stories (force·length)
    min_contact_length: float   # least contact length of the base (length; inf: not tracked)
    energy_residual: float      # largest |energy balance residual| over its scale
    overturned_at: float        # time the toppling angle was reached (s; if overturned)
    opening: np.ndarray         # slot A of every spring (length)
    force: np.ndarray           # slot B of every spring (force)
    stories: int                # story springs: the first ``stories`` of each slot
    sways: bool = False         # a sway spring follows the story springs
    base_gap: float = 0.0       # a base element's larger gap under its edges (length)
    base_sway: float = 0.0      # its largest |u − u_rest| (length)
    base_force: float = 0.0     # its largest |H| without the dashpot (force)
    base_gap_left: float = 0.0  # its largest gap under its left edge, x = −b (length)

    @property
    def sway(self) -> float:
        """The largest |horizontal displacement| of the base relative to the ground, the sway
        spring's deformation (length; 0 without a sway spring)."""
        return float(self.opening[self.stories]) if self.sways else 0.0

    @property
    def sway_force(self) -> float:
        """The largest |force| of the sway spring, its dashpot included (force; 0 without)."""
        return float(self.force[self.stories]) if self.sways else 0.0

    @property
    def base_shear(self) -> float:
        """The largest |shear| of story 0 (force; 0 without stories)."""
        return float(self.force[0]) if self.stories else 0.0

    @property
    def story_drift(self) -> list[float]:
        """The largest |drift| of each story (length)."""
        return [float(v) for v in self.opening[:self.stories]]


def static_energy(params: np.ndarray, base=None) -> float:
    """Σ ½ F0 δ0 over the foundation springs (the story springs carry no static force): the
    strain energy the weight stores in the bed at rest, ½ W δ0 for a bed of linear springs
    (force × length). The energy balance is measured against it as well as the input: the
    balance subtracts it from the springs' strain energy at every check, which leaves a
    rounding residual of about 1e-16 of it, and a motion whose input is smaller than it (a
    tiny motion, far too weak to lift the base: lifting it takes of the order of ½ W δ0) would
    otherwise be refused for that rounding (1.3e285 "of the input" for a record scaled by
    1e-150). A ``base`` element adds the energy it stores at rest."""
    found = params["kind"] != 0  # laws.spring.STORY
    springs = float(0.5 * np.sum(params["f0"][found] * params["d0"][found]))
    return springs + (base.rest_energy if base is not None else 0.0)


def weighted_plastic_settlement(params: np.ndarray, plastic: np.ndarray) -> float:
    """Σ k_i ε_p,i / Σ k_i over the foundation springs (length, down positive), ``plastic``
    their plastic settlements ε_p at the end of the run (one row, every spring): where O
    would rest if every spring were in contact again (vertical balance of a bed symmetric
    about O), whatever the base does when the run stops; 0 on elastic springs, NaN without a
    foundation. It is not the residual settlement: after rocking the edges have settled more
    than the middle and the base comes to rest on the middle springs, higher (long_period_free
    B, 30 s, at rest: 0.078 in here against 0.045 in of −V at rest)."""
    found = params["kind"] != 0  # laws.spring.STORY
    k = params["k"][found]
    if not k.size:
        return math.nan
    return float(np.sum(k * np.asarray(plastic)[found]) / np.sum(k))


def decode_peaks(raw: np.ndarray, *, stories: int, rocks: bool, settles: bool,
                 exact: bool, sways: bool = False, static: float = 0.0) -> TrackedPeaks:
    """Read the kernels' peak array ``raw`` of a model with ``stories`` story springs (then a
    sway spring if it ``sways``), a base that ``rocks`` (θ among its DOFs) and ``settles`` (V
    among them), in ``exact`` rocking kinematics (whose θ slots hold sin θ); ``static`` the
    bed's :func:`static_energy`, a floor of the energy residual's scale."""
    n0 = kn.N_PEAK_SCALARS
    theta = max(abs(raw[kn.P_THMIN]), abs(raw[kn.P_THMAX])) if rocks else 0.0
    if exact:
        theta = math.asin(min(theta, 1.0))
    return TrackedPeaks(
        u=max(abs(raw[kn.P_UMIN]), abs(raw[kn.P_UMAX])) if stories else 0.0,
        theta=theta,
        v_min=raw[kn.P_VMIN] if settles else 0.0,
        v_max=raw[kn.P_VMAX] if settles else 0.0,
        overturning_moment=float(raw[kn.P_MOT]),
        min_contact_length=float(raw[kn.P_CMIN]),
        energy_residual=float(raw[kn.P_ERES] / max(raw[kn.P_ESCALE], static, 1e-300)),
        overturned_at=float(raw[kn.P_TOVER]),
        opening=raw[n0::2], force=raw[n0 + 1::2], stories=stories, sways=sways,
        base_gap=float(raw[kn.P_BGAP]), base_sway=float(raw[kn.P_BU]),
        base_force=float(raw[kn.P_BH]), base_gap_left=float(raw[kn.P_BGAPL]))


def start_peaks(params: np.ndarray, stories: int, start: list[float]) -> np.ndarray:
    """The peak array a run starts from: the extremes of u, θ and V at the initial state
    ``start`` = (u, u, θ, θ, V, V), the foundation gaps at rest (−δ0), the least contact length
    at infinity and every other slot at zero."""
    peaks = np.zeros(kn.N_PEAK_SCALARS + 2 * params.size)
    peaks[kn.P_CMIN] = np.inf
    peaks[[kn.P_UMIN, kn.P_UMAX, kn.P_THMIN, kn.P_THMAX, kn.P_VMIN, kn.P_VMAX]] = start
    gaps = peaks[kn.N_PEAK_SCALARS::2]  # a view: the gap at rest is −δ0
    gaps[stories:] = -params["d0"][stories:]
    return peaks
