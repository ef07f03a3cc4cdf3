"""Options of a dynamic run of the continuum
(:func:`~upliftlab.continuum.dynamics.run.run_dynamic`),
checked when they are made: the route (explicit or implicit), the scheme, the step, the
boundaries, the mass and what is recorded."""

from __future__ import annotations

from dataclasses import dataclass

from ... import checks
from ...checks import InputError
from ..statics.newton import NewtonOptions

__all__ = ["DynamicOptions", "SCHEMES", "BASES", "SIDES", "WAVES", "MASSES", "METHODS"]

SCHEMES = ("newmark", "hht")
BASES = ("rigid", "compliant")
SIDES = ("rollers", "shear", "lysmer")
WAVES = ("S", "P")
MASSES = ("consistent", "lumped")
METHODS = ("explicit", "implicit")


@dataclass(frozen=True)
class DynamicOptions:
    """Options of :func:`~upliftlab.continuum.dynamics.run.run_dynamic`.

    ``scheme`` newmark (average acceleration) or hht; ``alpha`` HHT α in [−1/3, 0] (None: the
    scene's ``analysis.hht_alpha``; newmark is α = 0); ``dt`` (s; None: automatic, the route's
    module docstring); ``duration`` (s; None: the scene's ``analysis.duration``, else the
    motion's);
    ``base`` rigid or compliant and ``sides`` rollers, shear or lysmer (None: from the scene's
    ``continuum.base`` and ``continuum.boundary``: lysmer -> lysmer; shear -> shear; fixed ->
    rollers on a rigid base, shear on a compliant one, where rollers would block the S wave);
    ``wave`` S or P (compliant base: the incident wave); ``mass`` consistent or lumped (None:
    consistent for the implicit route, lumped for the explicit one, which needs it);
    ``snapshots`` soil-field snapshots, evenly spaced (0: none); ``energy`` records the energy
    account (implicit: one internal-force assembly per step; the explicit route always keeps
    it, at no cost); ``load_steps`` of the gravity ramp;
    ``predict`` starts each step's Newton iteration from the constant-acceleration
    extrapolation d + dt v + dt² a/2 instead of the last converged state
    (:mod:`~upliftlab.continuum.dynamics.implicit`);
    ``newton`` the Newton options of each step. ``method`` explicit (central differences,
    :mod:`~upliftlab.continuum.dynamics.explicit`) or implicit (HHT-α,
    :mod:`~upliftlab.continuum.dynamics.implicit`); None: the scene's ``continuum.dynamics``.
    ``record_every`` (explicit route): steps per recorded row (None: the implicit route's step).
    ``energy_tolerance``: the largest admissible energy balance error
    (:func:`~upliftlab.continuum.dynamics.run_control.balance_error`; None: the scene's
    ``continuum.energy_tolerance``); a run beyond it raises
    :class:`~upliftlab.continuum.dynamics.run_control.EnergyBalanceError`. ``threads`` (explicit
    route):
    numba threads of the internal-force kernels (1: serial; more split the elements, which pays
    only on an otherwise idle machine; at most numba's ``NUMBA_NUM_THREADS``).
    ``soil_mass_scale`` (explicit route, rigid base without dashpots): the soil's lumped mass
    times this factor in (0, 1], its weight unchanged. A diagnostic, not a speed-up: below 1
    the soil's own inertia (its site response, the seismic load on the soil and the footing's
    radiation) shrinks while its weight, stiffness and strength stay, so the run tells how much
    of an answer the soil's dynamics make; the step shrinks as √scale, the cost grows as
    1/√scale.
    """

    scheme: str = "hht"
    alpha: float | None = None
    dt: float | None = None
    duration: float | None = None
    base: str | None = None
    sides: str | None = None
    wave: str = "S"
    mass: str | None = None
    snapshots: int = 41
    energy: bool = True
    load_steps: int = 4
    predict: bool = True
    newton: NewtonOptions = NewtonOptions(rtol=1e-5, max_iterations=60, anderson=4)
    method: str | None = None
    record_every: int | None = None
    energy_tolerance: float | None = None
    threads: int = 1
    soil_mass_scale: float = 1.0

    def __post_init__(self):
        checks.one_of("DynamicOptions.scheme", self.scheme, SCHEMES)
        if self.alpha is not None:
            alpha = checks.finite("DynamicOptions.alpha", self.alpha)
            if not -1.0 / 3.0 <= alpha <= 0.0:
                raise InputError(f"DynamicOptions.alpha = {alpha:g}: HHT α must lie in "
                                 "[-1/3, 0] (0 is Newmark's average acceleration)")
            if self.scheme == "newmark" and alpha != 0.0:
                raise InputError(f"DynamicOptions.alpha = {alpha:g}: scheme 'newmark' is α = 0; "
                                 "use scheme = 'hht' for α in [-1/3, 0)")
        for name in ("dt", "duration"):
            value = getattr(self, name)
            if value is not None:
                value = checks.finite(f"DynamicOptions.{name}", value)
                if not value > 0.0:
                    raise InputError(f"DynamicOptions.{name} = {value:g} s: must be > 0")
        if self.base is not None:
            checks.one_of("DynamicOptions.base", self.base, BASES)
        if self.sides is not None:
            checks.one_of("DynamicOptions.sides", self.sides, SIDES)
        checks.one_of("DynamicOptions.wave", self.wave, WAVES)
        if self.mass is not None:
            checks.one_of("DynamicOptions.mass", self.mass, MASSES)
        if self.method is not None:
            checks.one_of("DynamicOptions.method", self.method, METHODS)
        if self.record_every is not None:
            checks.integer_at_least("DynamicOptions.record_every", self.record_every, 1)
        if self.energy_tolerance is not None:
            checks.in_range("DynamicOptions.energy_tolerance", self.energy_tolerance, 0.0, 1.0,
                            low_open=True)
        checks.integer_at_least("DynamicOptions.threads", self.threads, 1)
        checks.in_range("DynamicOptions.soil_mass_scale", self.soil_mass_scale, 0.0, 1.0,
                        low_open=True)
        checks.integer_at_least("DynamicOptions.snapshots", self.snapshots, 0)
        checks.integer_at_least("DynamicOptions.load_steps", self.load_steps, 1)
        if not isinstance(self.predict, bool):
            raise InputError(f"DynamicOptions.predict = {self.predict!r}: must be true or false")
