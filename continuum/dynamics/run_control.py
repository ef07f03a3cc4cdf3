"""What ends a dynamic run early or fails it: an interruption, the energy check, and a bearing
failure of the soil.

**Interruption.** A run stopped by the user (KeyboardInterrupt; the command line turns SIGTERM
into one) raises :class:`Interrupted`, which carries the :class:`DynamicResult` of the rows
computed so far, marked ``incomplete`` with ``completed_until`` (s) in its metadata, so that the
caller can write it.

**Energy.** :func:`balance_error` is the relative error of a run's energy account (the columns
of :data:`~upliftlab.continuum.dynamics.run.ENERGY`): the largest drift of kinetic + strain +
damping + contact − input from its value at t = 0, over the larger of the largest input and the
initial kinetic energy, the measure of the reduced model
(:func:`upliftlab.reduced.response.energy_balance_error`), with a floor of :data:`ENERGY_FLOOR`
N B (the footing's weight times its width): below it an energy is round-off of the sums, e.g.
in the first milliseconds of a pulse. A run whose error exceeds its tolerance
(``continuum.energy_tolerance``) raises :class:`EnergyBalanceError`, which carries the result
and the figure.

**Bearing failure.** A footing that punches into failing soil drives the soil beside it far
beyond the small-strain continuum's range. The explicit route stops there (a displacement
beyond a footing width) and tells it from a blow-up of its scheme: a blow-up grows by a fixed
factor above 1 every step, a mechanism by almost nothing, and in a bearing failure the footing
itself has settled by at least :data:`FAILURE_SETTLEMENT` B, the settlement that load tests
on footings conventionally call failure where the load–settlement curve has no peak. The
implicit route stops where Newton cannot follow a step; its last converged state is sound, so
a footing settled by :data:`FAILURE_SETTLEMENT` B there has failed by the same criterion.
Either run raises :class:`BearingFailure`: an outcome of the physics (the soil cannot carry
the footing through the motion), not a number to compare.
"""

from __future__ import annotations

import contextlib
import math

import numpy as np

from ..statics.newton import ConvergenceError

__all__ = ["ENERGY_FLOOR", "FAILURE_SETTLEMENT", "MECHANISM_GROWTH", "Interrupted",
           "EnergyBalanceError", "BearingFailure", "settled_to_failure", "keeping_what_ran",
           "balance_error", "check_energy", "energy_floor"]

#: The energy below which a balance is round-off, as a fraction of N B (module docstring).
ENERGY_FLOOR = 1e-9
#: The footing settlement, as a fraction of its width B, that counts as a bearing failure
#: (module docstring).
FAILURE_SETTLEMENT = 0.1
#: The largest growth of the largest displacement over one step that is a mechanism and not a
#: blow-up of the scheme: the highest mode's amplification just beyond the stability limit
#: (dt ω_max = 2.0002) is already 1.03 per step, a footing punching into failing soil grows by
#: 1.00003 (measured on the Winkler map's sand at FS_v = 2).
MECHANISM_GROWTH = 1.001


class Interrupted(KeyboardInterrupt):
    """A dynamic run stopped by the user; ``result`` holds what was computed (module
    docstring)."""

    def __init__(self, result):
        until = result.metadata.get("completed_until", math.nan)
        super().__init__(f"interrupted at t = {until:.4g} s")
        self.result = result


class EnergyBalanceError(RuntimeError):
    """A run's energy balance error exceeds its tolerance: ``result``, ``error``,
    ``tolerance``."""

    def __init__(self, result, error: float, tolerance: float):
        super().__init__(
            f"energy balance error {error:.3g} of the input exceeds continuum.energy_tolerance "
            f"= {tolerance:g} ({result.metadata.get('method', '')} dynamics, dt = "
            f"{result.metadata.get('dt', math.nan):.3g} s); the run is not trustworthy: "
            "refine the step or the mesh, or relax the tolerance if the loss is understood")
        self.result, self.error, self.tolerance = result, error, tolerance


class BearingFailure(ConvergenceError):
    """The soil failed in bearing under the footing (module docstring): ``time`` (s) and the
    footing's ``settlement`` (m, downward positive) and ``rotation`` (rad) when the run
    stopped; ``result`` the :class:`DynamicResult` of the rows and snapshots recorded until
    then (marked ``incomplete``, ``failure = "bearing"``), attached by the time loop, so that
    the mechanism can be looked at. A :class:`ConvergenceError` so that every caller that
    stops on one stops on it too; a caller that maps results tells it apart."""

    def __init__(self, message: str, *, step: int, time: float, settlement: float,
                 rotation: float):
        super().__init__(message, step=step)
        self.time, self.settlement, self.rotation = time, settlement, rotation
        self.result = None

    @classmethod
    def of(cls, when: str, settlement: float, width: float, rotation: float, why: str, *,
           step: int, time: float) -> BearingFailure:
        """The failure ``when`` (the steps, in words) of a footing ``width`` wide that has
        settled ``settlement`` and tilted ``rotation``; ``why`` what stopped the run."""
        return cls(f"the soil failed in bearing {when}: the footing had settled "
                   f"{settlement:.3g} ({settlement / width:.3g} B, at least the "
                   f"{FAILURE_SETTLEMENT:g} B of a conventional failure) and tilted "
                   f"{rotation:.3g} rad; {why}", step=step, time=time,
                   settlement=settlement, rotation=rotation)

    def metadata(self) -> dict:
        """What a result records of the failure."""
        return {"failure": "bearing", "failure_time": self.time,
                "failure_settlement": self.settlement, "failure_rotation": self.rotation}


def settled_to_failure(settlement: float, width: float) -> bool:
    """Whether a footing ``width`` wide that has settled ``settlement`` (down positive) has
    reached the conventional failure settlement :data:`FAILURE_SETTLEMENT` B."""
    return settlement >= FAILURE_SETTLEMENT * width


@contextlib.contextmanager
def keeping_what_ran(recorder, model, motion, metadata):
    """Around a time loop: an interruption becomes :class:`Interrupted` and a
    :class:`BearingFailure` gets its ``result``, each carrying the rows ``recorder`` (a
    :class:`~upliftlab.continuum.dynamics.result.Recorder`) holds, with ``metadata()`` (the
    run's settings) and the failure's own."""
    try:
        yield
    except KeyboardInterrupt:
        raise Interrupted(recorder.result(model, motion, metadata(),
                                          rows=recorder.rows)) from None
    except BearingFailure as exc:
        exc.result = recorder.result(model, motion, {**metadata(), **exc.metadata()},
                                     rows=recorder.rows)
        raise


def energy_floor(scene, width: float) -> float:
    """:data:`ENERGY_FLOOR` × the structure's vertical weight × the footing width."""
    return ENERGY_FLOOR * abs(scene.structure.vertical_weight) * width


def balance_error(energy: np.ndarray, floor: float = 0.0) -> float:
    """max_t |E(t) − E(0)| / max(max |input|, initial kinetic energy, ``floor``) with E =
    kinetic + strain + damping + contact − input (rows of the five cumulative columns); NaN
    without an account."""
    energy = np.asarray(energy, dtype=float)
    if energy.size == 0 or not np.isfinite(energy).all():
        return math.nan
    total = energy[:, 0] + energy[:, 1] + energy[:, 2] + energy[:, 4] - energy[:, 3]
    scale = max(float(np.max(np.abs(energy[:, 3]))), abs(float(energy[0, 0])), floor, 1e-300)
    return float(np.max(np.abs(total - total[0])) / scale)


def check_energy(result, tolerance: float, floor: float = 0.0) -> float:
    """The run's :func:`balance_error` (also stored in its metadata as
    ``energy_balance_error``, with ``energy_tolerance`` and ``energy_floor``); raises
    :class:`EnergyBalanceError` beyond ``tolerance``. A NaN error (no energy account) is not
    checked; a NaN in the histories is a failure."""
    result.metadata["energy_floor"] = floor
    error = balance_error(result.energy, floor)
    result.metadata["energy_balance_error"] = error
    result.metadata["energy_tolerance"] = tolerance
    if math.isnan(error) and not np.isnan(result.energy).all():
        raise EnergyBalanceError(result, math.inf, tolerance)
    if error > tolerance:
        raise EnergyBalanceError(result, error, tolerance)
    return error
