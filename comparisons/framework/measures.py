"""What the studies measure: one named function per quantity and model.

A name means one thing. Where two studies measure "the edge uplift" or "the residual
settlement" differently, each way has its own function here, and its name says which:

* **edge gap** (:func:`reduced_edge_gap_history`, :func:`reduced_peak_edge_gap`,
  :func:`edge_uplift_history`, :func:`continuum_peak_edge_gap`): the gap between a footing
  edge and the soil surface under it, from the histories;
* **edge uplift from peaks** (:func:`reduced_edge_uplift_from_peaks`): each spring's peak gap
  plus the rigid-base lift to the edge under the peak rotation, from the tracked peaks (exact
  for springs at the edges, an estimate for springs inside them);
* **plastic settlement** (:func:`reduced_plastic_settlement`): Σ k_i ε_p,i / Σ k_i at the end,
  the centre's settlement once the base rests on every spring again;
* **settlement change** (:func:`continuum_settlement_change`): the footing centre's vertical
  displacement from the first to the last step, V(0) − V(end) (down positive);
* **settlement when flattest** (:func:`settlement_when_flattest`): the settlement history at
  the step of the last quarter of the run where |θ| is smallest;
* **residual rotation** (:func:`residual_rotation`): the mean base rotation over the last
  quarter of the run, the tilt the rocking oscillates about;
* **peak story shear** (:func:`peak_story_shear`): the largest |k s + c ṡ| of the story spring
  and its dashpot, from the deformation history s and its rate.

Lengths in the scene's unit; rotations in rad. ``response`` is a reduced-model response
(:func:`upliftlab.reduced.run`); continuum arguments are arrays of a continuum dynamic result.
The module imports neither model (it reads what their results hold).
"""

from __future__ import annotations

import numpy as np

__all__ = ["reduced_edge_gap_history", "reduced_peak_edge_gap", "reduced_edge_uplift_from_peaks",
           "reduced_plastic_settlement", "edge_uplift_history", "continuum_peak_edge_gap",
           "continuum_settlement_change", "settlement_when_flattest", "residual_rotation",
           "peak_story_shear"]


def reduced_edge_gap_history(response) -> np.ndarray:
    """Gaps of the left and right footing edges (x = ∓b) over the stored steps, shape (n, 2):
    V ± bθ − δ₀ + ε_p with δ₀ the static compression and ε_p the plastic settlement of the
    outermost spring on that side. The same measure for every layout, whether or not a spring
    sits at the edge."""
    model = response.model
    found = model.foundation_slice
    x, d0 = model.params["x"][found], model.params["d0"][found]
    ep = response.plastic[:, found]
    b = model.layout.half_width
    left, right = int(np.argmin(x)), int(np.argmax(x))
    return np.column_stack([b * response.theta + response.V - d0[left] + ep[:, left],
                            -b * response.theta + response.V - d0[right] + ep[:, right]])


def reduced_peak_edge_gap(response) -> float:
    """The largest edge gap of :func:`reduced_edge_gap_history` (≥ 0), sampled at the stored
    steps."""
    gap = reduced_edge_gap_history(response)
    return float(max(0.0, gap[:, 0].max(), gap[:, 1].max()))


def reduced_edge_uplift_from_peaks(response) -> float:
    """Peak uplift of the footing edge x = ±b from the tracked peaks: for each spring its peak
    gap (tracked at every step) plus the lift from the spring to the edge on its side under
    the peak base rotation, (b − |x_i|)·θ_peak; the largest over the springs. Exact for springs
    at the edge (two ``edges`` springs; the error of the others vanishes as 1/N for a bed), a
    rigid-base estimate for springs inside it (``equivalent``)."""
    model = response.model
    found = model.foundation_slice
    gaps = np.asarray(response.tracked.opening)[found]
    x = model.params["x"][found]
    b = model.layout.half_width
    theta = response.peaks["theta"]
    return float(max(0.0, np.max(gaps + (b - np.abs(x)) * theta)))


def reduced_plastic_settlement(response) -> float:
    """Σ k_i ε_p,i / Σ k_i at the end of the run (0 for elastic springs): the response's
    ``weighted_plastic_settlement``
    (:func:`upliftlab.reduced.peak_slots.weighted_plastic_settlement`), where the base centre
    would rest if every spring were in contact again. Unlike −V at the end it does not depend
    on how much the base still rocks then; the studies that compare "residual settlement"
    across models name this definition in their measure's label."""
    return float(response.peaks["weighted_plastic_settlement"])


def edge_uplift_history(gap) -> np.ndarray:
    """Uplift of the footing's edges over time: the larger of the first and last column's gap
    (≥ 0). ``gap``: (steps, points) gaps ordered by x: the continuum footing's contact nodes,
    or the two columns of :func:`reduced_edge_gap_history`."""
    gap = np.asarray(gap, dtype=float)
    return np.maximum(np.maximum(gap[:, 0], gap[:, -1]), 0.0)


def continuum_peak_edge_gap(gap, x) -> float:
    """The largest gap (≥ 0) of the two edge nodes (smallest and largest ``x``) over the run."""
    gap, x = np.asarray(gap), np.asarray(x)
    edges = [int(np.argmin(x)), int(np.argmax(x))]
    return float(max(0.0, np.max(gap[:, edges])))


def continuum_settlement_change(footing) -> float:
    """V(0) − V(end) of the footing centre (down positive); ``footing``: (steps, 3) rows of
    (U, V, θ)."""
    footing = np.asarray(footing)
    return float(footing[0, 1] - footing[-1, 1])


def settlement_when_flattest(time, theta, settlement) -> float:
    """The ``settlement`` at the step of the last quarter of the run where |θ| is smallest:
    rocking that goes on at the end (an undamped elastic bed rocks for ever) does not lift it."""
    time, theta = np.asarray(time, dtype=float), np.asarray(theta, dtype=float)
    tail = np.flatnonzero(time >= time[0] + 0.75 * (time[-1] - time[0]))
    flat = tail[int(np.argmin(np.abs(theta[tail])))]
    return float(np.asarray(settlement, dtype=float)[flat])


def residual_rotation(time, theta) -> float:
    """The mean of ``theta`` (rad) over the last quarter of the run, by the trapezoidal rule:
    the tilt left at the end, about which any rocking that goes on oscillates (signed, rad)."""
    time, theta = np.asarray(time, dtype=float), np.asarray(theta, dtype=float)
    tail = np.flatnonzero(time >= time[0] + 0.75 * (time[-1] - time[0]))
    if tail.size < 2:
        return float(theta[-1])
    t, th = time[tail], theta[tail]
    return float(np.sum(0.5 * (th[1:] + th[:-1]) * np.diff(t)) / (t[-1] - t[0]))


def peak_story_shear(deformation, rate, stiffness: float, damping: float) -> float:
    """max |k s + c ṡ| (force) of a story spring ``stiffness`` k and dashpot ``damping`` c over
    the deformation history s and its rate ṡ: the shear at the base of an SDOF structure."""
    s, v = np.asarray(deformation, dtype=float), np.asarray(rate, dtype=float)
    return float(np.max(np.abs(stiffness * s + damping * v)))
