"""Which model and discretization does THIS scene need for a quantity within a tolerance?

:func:`advise` measures, it does not guess. It runs the scene's converged reference (the event
stepper on the finest Winkler bed at the finest step, checked against the next-finer levels),
then a ladder of candidates from cheap to expensive — two springs at ±b and ±b/√3, Winkler
beds of growing N, each with the event stepper and fixed-step RK4 at the coarsest stable steps —
and recommends, of the candidates whose error plus the reference's own uncertainty (its change
from the next-finer level) is within the tolerance, the one of least modelled cost
(:data:`PICK_RULE`): the work its run counted (evaluations of the equations of motion × springs,
at a per-integrator rate measured once), not its measured runtime, so that the same scene gets
the same recommendation on every run of a noisy shared machine. Runtimes are still measured
fresh in this process (median of repeats after a warm-up) and reported; nothing is stored.

For a scene with ``[soil]`` it also ladders the continuum (:mod:`.advise_continuum`): the
Winkler map's calibrated beds certified against the continuum's own finest mesh, and the map's
evidence where the scene falls inside a Winkler map (:mod:`.advise_map`). Its cost is estimated
before any run; above ``budget`` it is refused, unless a map covers the scene.

Used by ``upliftlab advise SCENE --quantity peak_u --tol 5% [--case C] [--set K=V] [--fast]
[--budget SECONDS] [--map PATH]``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass

from ... import checks
from ...checks import InputError
from ...scenes import Scene, load_scene
from ..studies import speed_vs_error as sve
from .continuum import (COST_MODEL, NOT_TIMED, ContinuumAdvice, Work, format_continuum,
                        plan_continuum, run_continuum, work_of)

__all__ = ["QUANTITIES", "Candidate", "Measured", "ReferenceCheck", "Advice", "advise",
           "parse_tolerance", "ladder", "format_advice", "select", "PICK_RULE", "Work"]

#: ``--quantity`` -> the speed-vs-error study's measure. ``weighted_plastic_settlement`` is
#: Σkε_p/Σk, the response's quantity of that name (``upliftlab run`` reports it under the same
#: name); a run's ``residual_settlement`` (−V at rest) is another quantity, which advise does
#: not ladder (a candidate need not end at rest).
QUANTITIES = {"peak_u": "u", "peak_theta": "theta", "peak_uplift": "uplift",
              "weighted_plastic_settlement": "residual_settlement"}
FULL = {"reference_springs": 640, "ladder_springs": (10, 20, 40, 80, 160, 320)}
FAST = {"reference_springs": 160, "ladder_springs": (10, 20, 40, 80)}
LADDER_INTEGRATORS = ("events", "rk4")
RANKS = (0, 1)
RECHECK_FACTOR = 2.0  # after the first pass, also run candidates estimated this much costlier
#: The ladder's models in their fixed order (the last tie-break of the pick).
MODELS = ("edges", "equivalent", "winkler")
#: How the reduced ladder picks (stated in the advice, text and JSON).
PICK_RULE = ("of the candidates that meet the tolerance, the least modelled cost (" + COST_MODEL
             + "); ties go to fewer springs, then the larger step, then the integrator order "
             + ", ".join(LADDER_INTEGRATORS) + ", then the model order " + ", ".join(MODELS)
             + "; " + NOT_TIMED)


@dataclass(frozen=True)
class Candidate:
    """A model and discretization: ``model`` (edges, equivalent, winkler) with ``springs``,
    ``integrator`` and ladder level ``rank`` (Δt = record Δt / 2^(k₀ + rank), k₀ the first
    stable level), or an explicit step ``dt`` (s)."""

    model: str
    springs: int
    integrator: str
    rank: int | None = None
    dt: float | None = None

    def step(self) -> dict:
        return {"dt": self.dt} if self.dt is not None else {"rank": self.rank}

    @property
    def name(self) -> str:
        model = {"edges": "2 springs at ±b", "equivalent": "2 springs at ±b/√3"}.get(
            self.model, f"Winkler N = {self.springs}")
        return f"{model}, {self.integrator}"


@dataclass(frozen=True)
class Measured:
    """A candidate as run: ``value`` (units of the scene), signed relative ``error``,
    ``dt`` (s), ``runtime`` (s, median of ``repeats``), whether it ``meets`` the tolerance
    (|error| + reference uncertainty ≤ tol), or ``failure``; ``work`` the counted work and
    modelled cost of a candidate that meets it (None otherwise), what the pick ranks by."""

    candidate: Candidate
    value: float
    error: float
    dt: float
    runtime: float
    repeats: int
    meets: bool
    failure: str | None = None
    work: Work | None = None


@dataclass(frozen=True)
class ReferenceCheck:
    """The reference: ``value``, ``springs``, ``dt`` (s), ``runtime`` (s); the relative
    changes from half the springs and from twice the step; ``uncertainty`` the larger."""

    value: float
    springs: int
    dt: float
    runtime: float
    change_springs: float
    change_dt: float
    floor: float

    @property
    def uncertainty(self) -> float:
        return max(self.change_springs, self.change_dt)


@dataclass(frozen=True)
class Advice:
    """What :func:`advise` measured and recommends (``recommendation`` None when nothing can be
    certified: ``reason`` says why). ``certified_against`` says what the errors are measured
    against: the reduced model's own finest bed; for a scene with ``[soil]``,
    ``continuum_advice`` holds the beds certified against the continuum itself. ``units``:
    the quantity's unit (rad for peak θ, the scene's length otherwise); ``rule`` how the
    recommendation is picked (:data:`PICK_RULE`)."""

    scene: str
    quantity: str
    tolerance: float
    units: str
    reference: ReferenceCheck | None
    measured: tuple[Measured, ...]
    skipped: tuple[Candidate, ...]
    recommendation: Measured | None
    reason: str
    continuum: str
    fast: bool
    certified_against: str = ""
    continuum_advice: ContinuumAdvice | None = None
    rule: str = PICK_RULE

    def to_dict(self) -> dict:
        out = asdict(self)
        if self.reference is not None:
            out["reference"]["uncertainty"] = self.reference.uncertainty
        if self.continuum_advice is not None:
            out["continuum_advice"] = self.continuum_advice.to_dict()
        return out

    @property
    def certified(self) -> bool:
        """Whether something was certified: against the continuum for a scene with
        ``[soil]``, else against the reduced model's finest bed."""
        if self.continuum_advice is not None:
            return self.continuum_advice.recommendation is not None
        return self.recommendation is not None


def parse_tolerance(text) -> float:
    """A tolerance as a fraction: ``"5%"`` → 0.05, ``0.05`` → 0.05; valid range (0, 100 %)."""
    raw = text
    if isinstance(text, str):
        s = text.strip()
        percent = s.endswith("%")
        try:
            value = float(s[:-1] if percent else s)
        except ValueError:
            raise InputError(f"--tol = {raw!r}: expected a percentage such as 5% or a "
                             "fraction such as 0.05; valid range (0 %, 100 %)") from None
        value = value / 100.0 if percent else value
    else:
        value = checks.finite("--tol", text)
    if not (math.isfinite(value) and 0.0 < value < 1.0):
        raise InputError(f"--tol = {raw}: valid range is (0 %, 100 %) (a fraction in (0, 1))")
    return value


def _quantity(name: str) -> str:
    if name == "residual_settlement":
        raise InputError("--quantity = 'residual_settlement': a run's residual settlement is −V "
                         "once it has come to rest, which a candidate of the ladder need not; "
                         "advise ladders 'weighted_plastic_settlement' (Σ k_i ε_p,i / Σ k_i)")
    if name not in QUANTITIES:
        raise InputError(f"--quantity = {name!r}: must be one of "
                         f"{', '.join(map(repr, QUANTITIES))}")
    return QUANTITIES[name]


def ladder(springs: Sequence[int]) -> list[Candidate]:
    """The candidates, two springs first, then beds of growing N; each with the ladder's
    integrators at ranks 0 and 1."""
    models = [("edges", 2), ("equivalent", 2)] + [("winkler", n) for n in springs]
    return [Candidate(m, n, name, rank) for m, n in models for name in LADDER_INTEGRATORS
            for rank in RANKS]


def _estimate(c: Candidate) -> float:
    """A priori cost for ordering the runs only: (springs + 3) × relative steps (RK4's smaller
    stable step on large beds is not known before running; the pick ranks by the work each
    run counted, :func:`select`)."""
    return (c.springs + 3) * 2.0 ** c.rank * (1.5 if c.integrator == "events" else 1.0)


def _run(scene: Scene, data: Mapping, c: Candidate, repeats: int) -> dict:
    point = {"scene": data["scene"], **data["motion"], "model": c.model, "springs": c.springs,
             "integrator": c.integrator, "step": c.step(), "repeats": repeats,
             "repeat_budget": 0.5}
    return sve.evaluate_point(point)


def _reference(scene, data, q, springs, dt, floor, repeats) -> ReferenceCheck:
    runs = [_run(scene, data, Candidate("winkler", n, "events", dt=d), r) for n, d, r in
            ((springs, dt, repeats), (springs // 2, dt, 1), (springs, 2 * dt, 1))]
    for r in runs:
        if "error" in r:
            raise InputError(f"the reference runs of this scene failed: {r['error']}")
    ref = runs[0][q]
    change = [abs(r[q] - ref) / max(abs(ref), floor) for r in runs[1:]]
    return ReferenceCheck(ref, springs, dt, runs[0]["runtime"], change[0], change[1], floor)


def _measure(scene, data, c, q, ref: ReferenceCheck, tol, repeats) -> Measured:
    """Run candidate ``c`` (timed); one that meets the tolerance has its work counted too."""
    r = _run(scene, data, c, repeats)
    if "error" in r:
        return Measured(c, math.nan, math.nan, math.nan, math.nan, 0, False, r["error"])
    error = (r[q] - ref.value) / max(abs(ref.value), ref.floor)
    meets = abs(error) + ref.uncertainty <= tol
    work = _work(data, c, r["dt"]) if meets else None
    return Measured(c, r[q], error, r["dt"], r["runtime"], len(r["runtimes"]), meets,
                    work=work)


def _work(data: Mapping, c: Candidate, dt: float) -> Work:
    """Candidate ``c``'s work at step ``dt`` (s), counted on one more, untimed run: the timed
    runs report their time, not the integrator's counters (the counts are the same on every
    run of the same inputs)."""
    from ...reduced import run as run_reduced

    point = {"scene": data["scene"], **data["motion"], "model": c.model, "springs": c.springs}
    response = run_reduced(sve.point_scene(point), integrator=c.integrator, dt=dt,
                           histories=False)
    return work_of(response)


def _pick_key(m: Measured) -> tuple:
    """The order of :data:`PICK_RULE`: modelled cost, springs, larger step, integrator,
    model, ladder level."""
    c = m.candidate
    return (m.work.seconds, m.work.springs, -m.dt, LADDER_INTEGRATORS.index(c.integrator),
            MODELS.index(c.model), c.rank if c.rank is not None else -1)


def select(measured: Sequence[Measured]) -> Measured | None:
    """The recommendation among ``measured`` (:data:`PICK_RULE`): of the candidates that meet
    the tolerance, the least modelled cost, ties broken by the fixed order of
    :func:`_pick_key`; None when none meets it. Measured runtimes do not enter, so the same
    candidates give the same pick whatever their timings."""
    passing = [m for m in measured if m.meets]
    return min(passing, key=_pick_key) if passing else None


def advise(scene: str | Scene, quantity: str = "peak_u", tol="5%", *, case: str | None = None,
           overrides: Sequence[str] = (), fast: bool = False, repeats: int = 3,
           budget: float | None = None, map_path=None, macro_calibration=None) -> Advice:
    """Measure the ladder on ``scene`` and recommend the candidate within ``tol`` of least
    modelled cost (:func:`select`, :data:`PICK_RULE`).

    ``quantity``: one of :data:`QUANTITIES`; ``tol``: ``"5%"`` or a fraction in (0, 1).
    ``fast`` uses a reference bed of 160 springs and a ladder up to N = 80 (seconds) instead of
    640 and 320, and continuum meshes of 2, 4, 8 elements across instead of 4, 8, 16. For a
    scene with ``[soil]``: ``budget`` (s) caps the continuum ladder's estimated cost,
    ``map_path`` a Winkler map's ``map.nc`` (:mod:`.advise_continuum`), ``macro_calibration``
    ``upliftlab calibrate``'s ``calibration.json`` of the scene's soil, which puts the
    macro-element in the continuum ladder (:mod:`.macro`). Every input is checked,
    and the continuum's cost estimated, before any run.
    """
    q = _quantity(quantity)
    tol = parse_tolerance(tol)
    checks.boolean("fast", fast)
    checks.integer_at_least("repeats", repeats, 1)
    if budget is not None:
        checks.in_range("--budget", budget, 0.0, 1e9, low_open=True)
    if not isinstance(scene, Scene):
        scene = load_scene(scene, case=case, overrides=list(overrides))
    if scene.foundation.support != "uplift" or len(scene.structure.stories) != 1:
        raise InputError(f"scene {scene.name!r}: foundation.support = "
                         f"{scene.foundation.support!r} with {len(scene.structure.stories)} "
                         "stories; the advisor compares foundations of a one-story structure "
                         "that may uplift (support = 'uplift')")
    if scene.foundation.law.name == "macro":
        raise InputError("foundation.law = 'macro': the advisor ladders beds of springs "
                         "(their number and the integrator) and the continuum; the "
                         "macro-element has no springs to ladder; valid: 'elastic', "
                         "'elastoplastic', 'qz'")
    if scene.foundation.dashpots is not None:
        raise InputError("foundation.dashpots: the advisor changes the number of springs, "
                         "and these dashpots are given one per spring; use "
                         "foundation.damping_ratio")
    if scene.soil is None and (budget is not None or map_path is not None
                               or macro_calibration is not None):
        option = ("--budget" if budget is not None else "--map" if map_path is not None
                  else "--macro-calibration")
        raise InputError(f"{option}: has no effect: "
                         f"scene {scene.name!r} has no [soil] table, so the advisor ladders "
                         "the reduced model only (no continuum run to budget, no map to read)")
    plan = (plan_continuum(scene, q, tol, fast=fast, budget=budget, map_path=map_path,
                           macro_calibration=macro_calibration)
            if scene.soil is not None else None)
    sizes = FAST if fast else FULL
    data = {"scene": scene.data, "motion": sve.motion_entry(scene)}
    floor = sve.FLOOR_FRACTION * sve.scales(scene)[q]
    available, why = sve.continuum_status()
    continuum = ("not in the ladder: the scene has no [soil] table" if scene.soil is None else
                 "in the ladder: the map's calibrated beds against the continuum, below"
                 if plan.run else "not run (over --budget): the Winkler map's evidence, below")
    if not available:
        continuum = why
    try:
        ref = _reference(scene, data, q, sizes["reference_springs"],
                         sve.FULL_GRID.reference_dt, floor, repeats)
    except InputError as exc:  # the reduced reference's runs failed: with soil, go on
        if plan is None:
            raise
        advice_c = run_continuum(scene, quantity, q, tol, plan, fast=fast)
        return Advice(scene.name, quantity, tol, _unit(scene, q), None, (), (), None,
                      f"the reduced ladder was not run: {exc}", continuum, fast,
                      "nothing (the reduced ladder's reference failed)", advice_c)
    against = certified_against(scene, ref)
    advice_c = (run_continuum(scene, quantity, q, tol, plan, fast=fast)
                if plan is not None else None)
    if ref.uncertainty > tol / 2:
        return Advice(scene.name, quantity, tol, _unit(scene, q), ref, (), (), None,
                      f"the reference is not converged to what {100 * tol:g} % needs: it "
                      f"changes by {100 * ref.uncertainty:.3g} % from the next-finer level "
                      f"(more than half the tolerance); no candidate can be certified. Use a "
                      "larger tolerance, or a scene whose reference converges (Case C's impact "
                      "dashpots are sized per spring and do not converge in N)",
                      continuum, fast, against, advice_c)
    measured, skipped, cap = [], [], math.inf
    for c in sorted(ladder(sizes["ladder_springs"]), key=_estimate):
        if _estimate(c) > cap:
            skipped.append(c)
            continue
        m = _measure(scene, data, c, q, ref, tol, repeats)
        measured.append(m)
        if m.meets and cap == math.inf:
            cap = RECHECK_FACTOR * _estimate(c)
    best = select(measured)
    reason = ("of the candidates whose |error| plus the reference's uncertainty is within the "
              "tolerance, the one of least modelled cost (the pick's rule, below)" if best else
              f"no candidate up to N = {sizes['ladder_springs'][-1]} is within the tolerance; "
              f"use the reference discretization (Winkler N = {ref.springs}, events, "
              f"Δt = {ref.dt:g} s)")
    return Advice(scene.name, quantity, tol, _unit(scene, q), ref, tuple(measured),
                  tuple(skipped), best, reason, continuum, fast, against, advice_c)


def _unit(scene: Scene, measure: str) -> str:
    """The unit of a measure's value: rad for θ, the scene's length for the others."""
    return "rad" if measure == "theta" else scene.units.length


def certified_against(scene: Scene, ref: ReferenceCheck) -> str:
    """What the reduced ladder's recommendation is certified against, in words: the reduced
    model's finest bed (for a scene with soil, not the soil: the continuum ladder's beds are
    certified against the continuum, :func:`.advise_continuum.certified_against_continuum`)."""
    text = (f"the reduced model's own Winkler bed of N = {ref.springs} springs (events, "
            f"Δt = {ref.dt:g} s), itself checked against N = {ref.springs // 2} and "
            f"Δt = {2 * ref.dt:g} s")
    if scene.soil is not None:
        text += ("; NOT against the soil of the scene's [soil] table (that is the continuum "
                 "ladder's part, below)")
    return text


def _pct(v: float) -> str:
    return "n/a" if not math.isfinite(v) else f"{100 * v:.3g} %"


def format_advice(a: Advice) -> str:
    """The advice as text: the reference, every measured candidate, the recommendation."""
    r = a.reference
    head = (f"upliftlab advise: {a.scene}, {a.quantity} within {_pct(a.tolerance)}"
            f"{' (fast)' if a.fast else ''}")
    if r is None:
        lines = [head, f"reduced ladder: none — {a.reason}", f"continuum: {a.continuum}"]
        return "\n".join(lines + format_continuum(a.continuum_advice))
    lines = [head,
             f"reference: Winkler N = {r.springs}, events, dt = {r.dt:g} s: {a.quantity} = "
             f"{r.value:.6g} {a.units}, runtime {r.runtime * 1e3:.4g} ms; change from "
             f"N = {r.springs // 2}: {_pct(r.change_springs)}, from dt = {2 * r.dt:g} s: "
             f"{_pct(r.change_dt)}",
             "measured (cheap to expensive):"]
    for m in a.measured:
        c = m.candidate
        if m.failure:
            lines.append(f"  {c.name:34s} refused: {m.failure}")
            continue
        model = f"modelled {m.work.seconds * 1e3:8.3f} ms" if m.work else " " * 20
        lines.append(f"  {c.name:34s} dt = {m.dt:<9.4g} error {_pct(m.error):>10s}  {model}  "
                     f"runtime {m.runtime * 1e3:8.3f} ms  {'meets' if m.meets else 'fails'}")
    if a.skipped:
        lines.append(f"not run: {len(a.skipped)} candidates estimated more than "
                     f"{RECHECK_FACTOR:g}× costlier than the first that met the tolerance")
    lines.append(f"certified against: {a.certified_against}")
    if a.recommendation is None:
        lines.append(f"recommendation: none — {a.reason}")
    else:
        m = a.recommendation
        lines.append(f"recommendation: {m.candidate.name}, dt = {m.dt:.4g} s: error "
                     f"{_pct(m.error)} (+ reference uncertainty {_pct(r.uncertainty)}) "
                     f"≤ {_pct(a.tolerance)}, modelled {m.work.seconds * 1e3:.3g} ms (measured "
                     f"{m.runtime * 1e3:.3g} ms, {r.runtime / m.runtime:.3g}× faster than the "
                     "reference)")
    lines.append(f"pick: {a.rule}")
    lines.append(f"continuum: {a.continuum}")
    if a.continuum_advice is not None:
        lines += format_continuum(a.continuum_advice)
    return "\n".join(lines)
