"""The reduced model's run, costed before it starts (:mod:`upliftlab.budget`).

:func:`check_run_cost` is called by :func:`~.run.run_model` once the step is chosen and before
anything is integrated: it refuses a duration shorter than one step (the run would silently
last a whole step) and a run above the scene's ``analysis.max_steps`` or
``analysis.max_memory``, or estimated to take longer than its time budget (the caller's
``budget``, :data:`~upliftlab.budget.REDUCED_BUDGET_SECONDS` by default), saying what it would
cost. Under error control the event stepper's
steps are counted at its first trial step (40 per shortest bonded period), an upper estimate
on the paper's scenes (measured: 2 to 5 times the steps it takes).
"""

from __future__ import annotations

import math

from ..budget import REDUCED_BUDGET_SECONDS, Cost, check, reduced_cost, time_budget
from ..checks import InputError
from .integrators import StepPlan, method
from .model import ReducedModel

__all__ = ["check_run_cost"]


def check_run_cost(model: ReducedModel, plan: StepPlan, duration: float, name: str,
                   histories: bool = True, budget: float | None = None) -> Cost:
    """The cost of integrating ``model`` for ``duration`` (s) with ``plan`` and integrator
    ``name``; an :class:`InputError` if it is above the scene's budget or its estimated time
    above ``budget`` (s; None: :data:`~upliftlab.budget.REDUCED_BUDGET_SECONDS`)."""
    if duration < 0.5 * plan.dt:
        raise InputError(f"analysis.duration = {duration:g} s: shorter than one time step "
                         f"({plan.dt:.4g} s); give a duration of at least one step")
    steps, step = plan.steps, plan.dt
    if plan.rtol > 0:  # error control: its first trial step (40 per shortest bonded period)
        step = min(plan.h0, plan.dt)
        steps = max(plan.steps, math.ceil(duration / step))
    stride = max(1, steps // max(plan.rows - 1, 1))
    cost = reduced_cost(steps=steps, step=step, stride=stride, dofs=model.mass.size,
                        springs=model.spring_count, events=method(name).locates_switches,
                        histories=histories, element=model.base is not None)
    a = model.scene.analysis
    return check(cost, a.max_steps, a.max_memory, time_budget(budget, REDUCED_BUDGET_SECONDS),
                 api="budget= of upliftlab.reduced.run")
