"""What a run will cost, estimated before it starts, and refused above the scene's budget.

A scene can be valid and still ask for a run of 10¹³ steps or an array of 700 GiB (a step of
1e-12 s, a foundation a million times too stiff, 100 000 elements across a footing). Such a
run used to end in a memory error after minutes, or run for days with no end in sight. Here
the steps and the memory of a run are estimated from its sizes before any of it is done, and
a run above ``analysis.max_steps`` steps or ``analysis.max_memory`` GiB is refused with an
:class:`~upliftlab.checks.InputError` that says what it would cost and which key raises the
limit (``--set analysis.max_steps=...``). A run estimated to take more than
:data:`LONG_RUN_SECONDS` is announced with its estimated time before it starts (the event
stepper's time grows as the square of the springs: :data:`EVENTS_PER_SPRING_SECOND`), and one
estimated above its time budget is refused: :data:`REDUCED_BUDGET_SECONDS` for the reduced
model (100 000 springs on 1 s of a pulse: about 14 h), :data:`CONTINUUM_BUDGET_SECONDS` for
the continuum, raised on purpose by the caller (``--budget SECONDS`` on the command line,
``budget=`` in the API). The time budget is an option of the run, not a field of the scene:
it changes no number, so neither a scene's digest nor a store key.

The memory is that of the arrays the run keeps (histories, snapshots, a factorisation's fill,
estimated); the time is a rough figure from per-step rates measured on the project's 2-core
machine (``benchmarks/REDUCED.md``, ``benchmarks/CONTINUUM.md``,
``benchmarks/CONTINUUM_STARTUP.md``), by route, erring on the long side; the time budget is
held against it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .checks import InputError
from .log import logger

__all__ = ["Cost", "check", "reduced_cost", "continuum_cost", "in_sequence", "GIB",
           "time_budget",
           "REDUCED_BUDGET_SECONDS", "CONTINUUM_BUDGET_SECONDS", "MAX_BUDGET_SECONDS"]

GIB = 2.0 ** 30

#: Seconds per step of the reduced model: a fixed part and a part per spring (event stepper:
#: 6 µs per step with 40 springs, 22 µs with 160).
REDUCED_SECONDS_PER_STEP = (1.0e-6, 1.3e-7)
#: Seconds per step of a macro-element under the base (``foundation.law = "macro"``): its
#: update runs at every stage of a step (five a step with RK4), in sub-steps of at most
#: ``force_step`` of trial force each, so its cost follows the load's path: a wall at FS_v 3
#: under a 0.6 g Ricker pulse took 270 µs a step at the default force step, 46 µs at ten times
#: it (``benchmarks/MACRO_SPEED.md``); far from its capacity it takes a few µs.
MACRO_SECONDS_PER_STEP = 3.0e-4
#: Switches (separations and recontacts) the event stepper locates per spring and second of
#: a rocking run (the figure its event log is sized by): each is a step of its own over every
#: spring, so the run's time grows as springs² (measured on wall_free e07, 3 s: 250, 1000 and
#: 4000 springs took 0.37, 5.2 and 133 s; this estimate gives 0.5, 7.9 and 125 s).
EVENTS_PER_SPRING_SECOND = 20
#: A run estimated to take longer than this (s) is announced with its estimate (a warning on
#: stderr) before it starts.
LONG_RUN_SECONDS = 600.0
#: Seconds per step and DOF of the continuum, by route: the implicit dynamics (HHT, Newton:
#: 509 s for 8000 steps on 20 160 DOFs; benchmarks/CONTINUUM_STARTUP.md, 3 s of El Centro:
#: 2.6e-6), the explicit dynamics' compiled loop (the same table: a 9.8 s CPU solve of 12 766
#: steps on 20 160 DOFs, 3.8e-8, taken with a 1.6x margin for a loaded machine's wall clock)
#: and a pushover, whose step takes several Newton iterations (31.5 s for 42 steps on 20 160
#: DOFs).
CONTINUUM_SECONDS_PER_DOF_STEP = {"implicit": 3.2e-6, "explicit": 6.0e-8, "pushover": 3.7e-5}
#: Default time budget (s, estimated) of a reduced run: the model takes milliseconds to
#: seconds per earthquake; a run estimated above an hour asks for more springs than resolve
#: anything (``--budget`` raises it).
REDUCED_BUDGET_SECONDS = 3600.0
#: Default time budget (s, estimated) of a continuum run: a day (the map's finest dynamic
#: runs, 12 100 steps on about 20 000 DOFs, are estimated at about 13 min).
CONTINUUM_BUDGET_SECONDS = 86400.0
#: The largest time budget a caller may give (s): about 30 years, i.e. no budget.
MAX_BUDGET_SECONDS = 1e9


@dataclass(frozen=True)
class Cost:
    """The estimated cost of a run: ``steps`` of ``step`` (s; 0 for load steps), ``memory``
    (bytes), ``seconds`` (rough), what was counted (``sizes``, e.g. "12 springs") and what
    makes the run ``smaller``."""

    what: str
    steps: int
    step: float
    memory: float
    seconds: float
    sizes: str
    smaller: str = "a coarser model or a shorter duration"


def _time(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.2g} s"
    if seconds < 7200:
        return f"{seconds / 60:.3g} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 86400:.3g} days"


def time_budget(budget: float | None, default: float) -> float:
    """The time budget (s) of a run: ``budget`` as the caller gave it (``--budget``,
    ``budget=``), checked, or ``default``."""
    if budget is None:
        return default
    try:
        value = float(budget)
    except (TypeError, ValueError):
        value = math.nan
    if not 0.0 < value <= MAX_BUDGET_SECONDS:  # NaN fails too
        raise InputError(f"--budget = {budget!r}: the estimated run time allowed, in seconds; "
                         f"valid range is (0, {MAX_BUDGET_SECONDS:g}]")
    return value


def check(cost: Cost, max_steps: int, max_memory: float,
          max_seconds: float | None = None, api: str = "") -> Cost:
    """Refuse ``cost`` above ``max_steps`` steps or ``max_memory`` GiB (the scene's
    ``analysis.max_steps`` and ``analysis.max_memory``) or an estimated time above
    ``max_seconds`` (the run's time budget, :func:`time_budget`; None: not checked; ``api``
    names the argument that raises it in the API besides ``--budget``); return it
    otherwise."""
    step = f" of {cost.step:.3g} s" if cost.step else ""
    about = (f"{cost.what} would take {cost.steps:.4g} steps{step} ({cost.sizes}), "
             f"{cost.memory / GIB:.3g} GiB and roughly {_time(cost.seconds)}")
    if cost.steps > max_steps:
        raise InputError(f"analysis.max_steps = {max_steps}: {about}; raise it (--set "
                         f"analysis.max_steps={cost.steps:.0f}) to run it anyway, or take a "
                         "larger step or a shorter duration" if cost.steps < 1e15 else
                         f"analysis.max_steps = {max_steps}: {about}; take a larger step or a "
                         "shorter duration")
    if cost.memory > max_memory * GIB:
        need = math.ceil(cost.memory / GIB * 10) / 10
        raise InputError(f"analysis.max_memory = {max_memory:g} GiB: {about}; raise it "
                         f"(--set analysis.max_memory={need:g}) if the machine has the "
                         "memory, or make the run smaller")
    if max_seconds is not None and cost.seconds > max_seconds:
        raise InputError(f"--budget = {max_seconds:g} s: {about}, estimated before it starts; "
                         f"valid: a run estimated within the budget; raise it (--budget "
                         f"{_raise_to(cost.seconds)}{', ' + api if api else ''}) to run it "
                         "anyway, "
                         f"or make the run smaller ({cost.smaller})")
    if cost.seconds > LONG_RUN_SECONDS:
        logger("budget").warning(f"upliftlab: warning: {about} (estimated before it starts; "
                                 f"{cost.smaller} make it shorter)")
    return cost


def _raise_to(seconds: float) -> str:
    """A budget (s) a little above ``seconds``, as a short number."""
    return f"{float(f'{seconds * 1.1:.2g}'):.0f}" if seconds * 1.1 <= MAX_BUDGET_SECONDS \
        else f"{MAX_BUDGET_SECONDS:g}"


def reduced_cost(*, steps: int, step: float, stride: int, dofs: int, springs: int,
                 events: bool, histories: bool = True, element: bool = False) -> Cost:
    """The reduced model's run: ``steps`` of ``step`` (s), histories every ``stride`` steps
    (only the ends without ``histories``), ``dofs`` and ``springs`` (story springs included);
    the event stepper (``events``) keeps a log of impacts; ``element``: a macro-element under
    the base (:data:`MACRO_SECONDS_PER_STEP`)."""
    outputs = (steps // max(stride, 1) + 1) if histories else 2
    per_output = 8.0 * (2 * dofs + 6 * springs + 8)  # q, q̇, spring arrays, derived, energy
    duration = steps * step
    switches = EVENTS_PER_SPRING_SECOND * springs * int(duration + 1) if events else 0
    log = 40.0 * max(1000, switches) if events else 0.0
    memory = outputs * per_output + log + 8.0 * dofs * springs + 200.0 * springs
    a, b = REDUCED_SECONDS_PER_STEP
    located = f", up to {switches:.3g} located switches" if events else ""
    seconds = (steps + switches) * (a + b * springs) + (MACRO_SECONDS_PER_STEP * steps
                                                          if element else 0.0)
    sizes = (f"{springs} springs, " if not element else "a macro-element, ") + f"{dofs} DOFs"
    return Cost("the reduced run", int(steps), float(step), memory, seconds, sizes + located,
                "fewer springs or a shorter duration" if not element
                else "a larger force_step or a shorter duration")


def continuum_cost(*, analysis: str, steps: int, step: float, dofs: int,
                   snapshots: int, route: str = "implicit") -> Cost:
    """The continuum's run (``analysis`` pushover or dynamic, a dynamic one by ``route``,
    explicit or implicit): ``steps`` on ``dofs`` DOFs, ``snapshots`` of the soil fields kept.
    A factorisation's fill is taken as 150 numbers per DOF and a kept state as 12 per DOF
    (stresses and plastic state at the quadrature points)."""
    memory = 8.0 * dofs * (150 + 12 * snapshots) + 400.0 * steps
    rate = CONTINUUM_SECONDS_PER_DOF_STEP[route if analysis == "dynamic" else analysis]
    return Cost(f"the continuum {analysis}", int(steps), float(step), memory,
                rate * steps * dofs, f"{dofs} DOFs", "a coarser mesh or a shorter duration"
                if analysis == "dynamic" else "a coarser mesh or fewer steps")


def in_sequence(costs, what: str) -> Cost:
    """Runs done one after another as one cost: their times add up; the steps and the memory
    are the largest run's (each run is held to ``analysis.max_steps`` and ``max_memory`` on
    its own, and frees its memory before the next starts)."""
    costs = list(costs)
    largest = max(costs, key=lambda c: c.steps)
    return Cost(what, largest.steps, largest.step, max(c.memory for c in costs),
                sum(c.seconds for c in costs), ", then ".join(c.sizes for c in costs),
                costs[0].smaller)
