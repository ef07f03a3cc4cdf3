"""Every verification anchor, computed by the library, with its measured error and verdict.

Each row of the table is one number of the verification anchors (``upliftlab/docs/anchors.md``,
the report's appendix; or a closed form the tests name) recomputed through the public APIs of
:mod:`upliftlab.reduced` and :mod:`upliftlab.continuum`: the measured value, the reference, the
error, the tolerance and whether it passes. The observed convergence orders (slopes of ``np.polyfit(log Δt, log
error)`` for the reduced integrators, ``log h`` for the continuum) are a second table.

Reduced model: the two-spring K entries (eq. 6), static reactions, bonded periods against
eig(K, M), the fixed base against Nigam–Jennings (0.01 % in peak u at the default Δt), the
tensionless Winkler pushover with 200 springs (0.5 %), the uplift-onset forces, M_ult and the
yield rotation of the elasto-plastic bed, Ewing's impact damper on a drop mass (anchor §5),
the rigid-block period and restitution (anchor §1), the energy balance of Cases A, B, C on El
Centro (0.1 %) and the integrators' orders on a smooth bonded and an uplifting case.

Continuum: the rocking stiffness K_r = πGB²/(8(1 − ν)) (1 %) and its O(h) convergence with full
integration, the Flamant slope of the vertical compliance (2 %), Prandtl's (2 + π) c_u (2 % on
16 elements across B; **fast mode** uses 8 across with a 5 % tolerance and skips the 16-across
level, the Richardson check and the observed order, each listed as skipped), the uplift-onset
eccentricity B/4 of the elastic half-plane (1 %) and the locking of constant-strain triangles
against Q2.

**Caching.** The whole table is one record of a :class:`.store.Store` under a content key: the
study's inputs (fast or full, the El Centro file's SHA-256), the package version and a SHA-256
of the source files of ``reduced/``, ``continuum/``, ``meshes/``, the core modules (but not the
command line) and this module. A second run with the same key reads the record and recomputes
nothing (``Verification.reused``); editing any of those sources gives a new key, so a stale
table is never shown. A check that raises becomes a failing row that carries the message.

``python -m upliftlab.comparisons.verification [--fast] [--out DIR] [--store DIR]``
(exit 1 if a row fails).
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import __version__
from ..checks import InputError
from ..motions import ELCENTRO, find_motion, load_motion
from ..results import provenance, write_csv
from .protocol import Context, Study, main_for, run_study
from .store import Store, point_key
from .study import StudyResult, file_sha256, write_summary

__all__ = ["STUDY", "Row", "Order", "Verification", "DEFINITION", "compute_or_read", "write",
           "run", "main", "source_digest",
           "drop_mass"]

STUDY = "verification"
PASS, FAIL, SKIP = "pass", "fail", "skipped"


# ---------------------------------------------------------------------------------------------
# Records
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Row:
    """One anchor: ``measured`` against ``expected`` (None for a bound), the ``error`` as
    ``kind`` (``relative`` (measured/expected − 1), ``absolute`` (measured − expected) or
    ``value``: the measured value itself against a bound), the ``tolerance`` text and
    ``status`` (pass, fail, skipped)."""

    group: str
    id: str
    quantity: str
    reference: str
    measured: float | None
    expected: float | None
    error: float | None
    kind: str
    tolerance: str
    status: str
    note: str = ""

    @property
    def passed(self) -> bool:
        return self.status == PASS


@dataclass(frozen=True)
class Order:
    """An observed convergence order: ``slope`` of log error against log step (Δt or h)
    fitted over ``steps``/``errors``, against ``expected`` with the band [low, high]."""

    group: str
    case: str
    method: str
    steps: tuple[float, ...]
    errors: tuple[float, ...]
    slope: float | None
    expected: str
    low: float
    high: float
    status: str
    note: str = ""


@dataclass(frozen=True, eq=False)
class Verification:
    """The table (``rows``), the orders, whether the record was ``reused`` from the store, its
    ``key`` and the study record (files, Markdown summary, numbers)."""

    rows: tuple[Row, ...]
    orders: tuple[Order, ...]
    reused: bool
    key: str
    computed_utc: str
    compute_seconds: float
    study: StudyResult | None = None
    inputs: Mapping = dataclasses.field(default_factory=dict)
    check_seconds: Mapping = dataclasses.field(default_factory=dict)

    @property
    def failures(self) -> list[str]:
        bad = [f"{r.group}: {r.quantity} ({r.note or r.status})" for r in self.rows
               if r.status == FAIL]
        bad += [f"{o.group}: order of {o.method} on {o.case} ({o.note or o.status})"
                for o in self.orders if o.status == FAIL]
        return bad

    @property
    def passed(self) -> bool:
        return not self.failures

    def row(self, id: str) -> Row:
        return next(r for r in self.rows if r.id == id)

    def order(self, case: str, method: str) -> Order:
        return next(o for o in self.orders if (o.case, o.method) == (case, method))


def _rel(group, id, quantity, reference, measured, expected, tol, note="") -> Row:
    err = float(measured) / float(expected) - 1.0
    ok = abs(err) <= tol
    return Row(group, id, quantity, reference, float(measured), float(expected), err,
               "relative", f"abs(rel) ≤ {tol:.3g}", PASS if ok else FAIL, note)


def _abs(group, id, quantity, reference, measured, expected, tol, note="") -> Row:
    err = float(measured) - float(expected)
    ok = abs(err) <= tol
    return Row(group, id, quantity, reference, float(measured), float(expected), err,
               "absolute", f"abs(err) ≤ {tol:.3g}", PASS if ok else FAIL, note)


def _bound(group, id, quantity, reference, measured, low, high, note="") -> Row:
    """The measured value itself within [low, high] (either may be ±inf)."""
    ok = low <= measured <= high
    text = (f"≤ {high:.3g}" if low == -math.inf else f"≥ {low:.3g}" if high == math.inf
            else f"in [{low:.3g}, {high:.3g}]")
    return Row(group, id, quantity, reference, float(measured), None, float(measured), "value",
               text, PASS if ok else FAIL, note)


def _skip(group, id, quantity, reference, tolerance, note) -> Row:
    return Row(group, id, quantity, reference, None, None, None, "", tolerance, SKIP, note)


def _order(group, case, method, steps, errors, expected, low, high, note="") -> Order:
    slope = float(np.polyfit(np.log(steps), np.log(errors), 1)[0])
    ok = low <= slope <= high
    return Order(group, case, method, tuple(float(s) for s in steps),
                 tuple(float(e) for e in errors), slope, expected, low, high,
                 PASS if ok else FAIL, note)


# ---------------------------------------------------------------------------------------------
# Reduced model
# ---------------------------------------------------------------------------------------------

R = "reduced"
C = "continuum"


def _stiffness_entries(ctx) -> list[Row]:
    """Anchor §2, eq. 6: h = 288, b = 72, k1 = k2 = 3000, k3 = 500 (kip, in)."""
    from ..reduced import compatibility_matrix, custom_springs, edge_springs, stiffness_matrix
    from ..reduced.compatibility import DofMap

    dofs = DofMap.build(1, rigid=False, fixed=False)  # (x, θ, V)
    h, b = 288.0, 72.0
    K = stiffness_matrix(compatibility_matrix(dofs, [h], edge_springs(b, 6000.0)),
                         [500.0, 3000.0, 3000.0])
    k1, k2 = 1000.0, 4000.0
    Ku = stiffness_matrix(compatibility_matrix(dofs, [h], custom_springs(b, [-b, b], [k1, k2])),
                          [500.0, k1, k2])
    ref = "anchor §2, eq. 6"
    return [_rel(R, "K_thth", "two-spring K_θθ = h²k₃ + b²(k₁ + k₂)", ref, K[1, 1],
                 7.2576e7, 1e-12),
            _rel(R, "K_Xth", "two-spring K_Xθ = −h k₃", ref, K[0, 1], -1.44e5, 1e-12),
            _rel(R, "K_thV", "K_θV = b(k₁ − k₂), k₁ = 1000, k₂ = 4000", ref, Ku[1, 2],
                 b * (k1 - k2), 1e-12),
            _rel(R, "K_VV", "K_VV = k₁ + k₂", ref, Ku[2, 2], k1 + k2, 1e-12)]


def _static_reactions(ctx) -> list[Row]:
    """At rest the spring compressions carry the weight: Σ F0 = W, Σ x F0 = 0."""
    from ..reduced import build_model
    from ..scenes import load_scene

    rows = []
    for name in ("wall_free", "short_period_free"):
        model = build_model(load_scene(name))
        f = model.params[model.foundation_slice]
        b = model.layout.half_width
        rows += [_rel(R, f"reaction_{name}", f"{name}: Σ F0 = W", "statics", f["f0"].sum(),
                      model.weight, 1e-12),
                 _abs(R, f"moment_{name}", f"{name}: Σ x F0 / (W b) = 0", "statics",
                      np.sum(f["x"] * f["f0"]) / (model.weight * b), 0.0, 1e-12)]
    return rows


def _bonded_periods(ctx) -> list[Row]:
    """Bonded periods against eig(K, M), and the first one measured on a free vibration."""
    import scipy.linalg

    from ..reduced import build_model, run
    from ..scenes import load_scene

    scene = load_scene("short_period_free", overrides=[
        "foundation.support='bonded'", "foundation.law='elastic'",
        "foundation.damping_ratio=0.0", "foundation.restitution=1.0",
        "structure.damping_ratio=0.0", "motion.duration=3.0"])
    model = build_model(scene)
    K, _ = model.bonded_matrices()
    lam = scipy.linalg.eigh(K, np.diag(model.mass), eigvals_only=True)
    periods = np.sort(2.0 * np.pi / np.sqrt(lam))[::-1]
    mine = np.sort(model.bonded_periods())[::-1]
    worst = int(np.argmax(np.abs(mine / periods - 1.0)))
    r = run(scene, output_dt=1e-3)
    x, t = r.q[:, 0], r.time
    up = np.flatnonzero(np.diff(np.sign(x)) > 0)
    crossing = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    measured = float(np.median(np.diff(crossing)))
    return [_rel(R, "bonded_periods", "bonded periods (worst of 3) vs eig(K, M)",
                 "scipy.linalg.eigh", mine[worst], periods[worst], 1e-12),
            _rel(R, "bonded_T1_measured", "first bonded period from a free vibration's zero "
                 "crossings", "eig(K, M)", measured, periods[0], 2e-3)]


def _fixed_base(ctx) -> list[Row]:
    """Fixed base on El Centro against Nigam–Jennings, evaluated 200 times per record step,
    its peak refined on the exact cubic (0.01 % in peak u at the default Δt)."""
    from ..reduced import run
    from ..reduced.exact import hermite_peak, nigam_jennings
    from ..scenes import load_scene

    rows = []
    for name in ("short_period_elcentro", "long_period_elcentro", "wall_elcentro"):
        what = f"{name}, fixed base: peak u"
        if ctx.record is None:
            rows.append(_skip(R, f"nj_{name}", what, "Nigam–Jennings", "abs(rel) ≤ 0.0001",
                              ctx.record_note))
            continue
        scene = load_scene(name, case="fixed")
        story = scene.structure.stories[0]
        omega = math.sqrt(story.stiffness * scene.g / story.weight)
        sub, rec = 200, ctx.record
        t = np.arange(rec.acceleration.size * sub + 1) * rec.dt / sub
        u, v = nigam_jennings(rec.acceleration_at(t) * scene.g, rec.dt / sub, omega,
                              scene.structure.damping_ratio)
        reference = hermite_peak(u, v, rec.dt / sub)
        response = run(scene, motion=rec, histories=False)
        rows.append(_rel(R, f"nj_{name}", what, "Nigam–Jennings exact recurrence",
                         response.peaks["u"], reference, 1e-4,
                         f"Δt = {response.info['dt']:.3g} s ({response.info['integrator']})"))
    return rows


def _winkler_pushover(ctx) -> list[Row]:
    """Anchor §3 with 200 springs: M/M_up = 3 − 2√(θ_up/θ), c/B = √(θ_up/θ) (0.5 %)."""
    from ..reduced import build_model, rocking_pushover
    from ..scenes import load_scene

    model = build_model(load_scene("wall_free", overrides=["foundation.springs=200"]))
    N, B = model.weight, 2 * model.layout.half_width
    theta_up = 2 * N / (model.layout.vertical_stiffness * B)
    ratios = np.array([0.5, 1.5, 3.0, 10.0])
    push = rocking_pushover(model, ratios * theta_up)
    closed_m = np.where(ratios <= 1, ratios, 3 - 2 * np.sqrt(1 / ratios))
    closed_c = np.where(ratios <= 1, 1.0, np.sqrt(1 / ratios))
    em = push.moment / (N * B / 6) / closed_m - 1
    ec = push.contact / B / closed_c - 1
    km, kc = int(np.argmax(np.abs(em))), int(np.argmax(np.abs(ec)))
    ref = "anchor §3 (θ/θ_up = 0.5, 1.5, 3, 10; worst shown)"
    return [_rel(R, "pushover_M", f"M/M_up, 200 springs (worst at θ = {ratios[km]:g} θ_up)",
                 ref, push.moment[km] / (N * B / 6), closed_m[km], 5e-3),
            _rel(R, "pushover_c", f"contact c/B, 200 springs (worst at θ = {ratios[kc]:g} "
                 "θ_up)", ref, push.contact[kc] / B, closed_c[kc], 5e-3)]


def _uplift_onset(ctx) -> list[Row]:
    """Anchor §2: W b/h (edges), W b/(√3 h) (±b/√3), W b/(3h)(1 + 1/N) for N strips."""
    from ..reduced import build_model, uplift_onset_force
    from ..scenes import load_scene

    base = load_scene("wall_free")
    W, b, h = 200.0, 72.0, 288.0
    two = "foundation.springs=2"

    def onset(*sets):
        return uplift_onset_force(build_model(base.with_overrides(*sets)))

    ref = "anchor §2 (wall: W = 200 kip, b = 72 in, h = 288 in)"
    n = 200
    p200 = onset(f"foundation.springs={n}")
    return [_rel(R, "onset_edges", "uplift onset, edge springs: W b/h = 50 kip", ref,
                 onset("foundation.layout='edges'", two), W * b / h, 1e-12),
            _rel(R, "onset_equivalent", "uplift onset, ±b/√3: W b/(√3 h) = 28.868 kip", ref,
                 onset("foundation.layout='equivalent'", two), W * b / (math.sqrt(3) * h),
                 1e-12),
            _rel(R, "onset_winkler_N", f"uplift onset, {n} strips: W b/(3h)(1 + 1/N)",
                 "outer strip centre at b(1 − 1/N)", p200, W * b / (3 * h) * (1 + 1 / n), 1e-12),
            _rel(R, "onset_winkler", "uplift onset, 400 strips vs W b/(3h) = 16.667 kip",
                 ref, onset("foundation.springs=400"), W * b / (3 * h), 5e-3,
                 "N → ∞ limit; the bed's excess is 1/N")]


def _first_yield(model, theta_up, low, high) -> float:
    """θ/θ_up of first yield by bisection between an elastic ``low`` and a yielded ``high``
    (monotonic pushovers are path independent until the first spring yields)."""
    from ..reduced import rocking_pushover

    for _ in range(40):
        mid = math.sqrt(low * high)
        push = rocking_pushover(model, [low * theta_up, mid * theta_up])
        if push.plastic[-1].max() > 0:
            high = mid
        else:
            low = mid
        if high / low - 1 < 1e-6:
            break
    return math.sqrt(low * high)


def _ultimate_moment(ctx) -> list[Row]:
    """Anchor §3: M → M_ult = (NB/2)(1 − 1/FS_v) (0.2 %) and first yield at (FS²/4) θ_up
    (2 %), 400 springs, FS_v = 3, pushed to 2000 θ_up."""
    from ..reduced import build_model, rocking_pushover
    from ..scenes import load_scene

    model = build_model(load_scene("short_period_free", overrides=["foundation.springs=400"]))
    N, B, fs = model.weight, 2 * model.layout.half_width, 3.0
    theta_up = 2 * N / (model.layout.vertical_stiffness * B)
    ratios = np.geomspace(0.1, 2000.0, 120 if ctx.fast else 400)
    push = rocking_pushover(model, theta_up * ratios)
    m_ult = N * B / 2 * (1 - 1 / fs)
    k = int(np.flatnonzero(push.plastic.max(axis=1) > 0)[0])
    first = _first_yield(model, theta_up, ratios[k - 1], ratios[k])
    ref = "anchor §3 (FS_v = 3, 400 springs)"
    return [_rel(R, "M_ult", "elasto-plastic bed: M(2000 θ_up) / M_ult, M_ult = "
                 "(NB/2)(1 − 1/FS_v)", ref, push.moment[-1], m_ult, 2e-3,
                 f"{ratios.size} pushover steps"),
            _rel(R, "yield_rotation", "first yield rotation θ_y/θ_up = FS_v²/4", ref, first,
                 fs ** 2 / 4, 0.02, "bisection of the pushover to 1e-6")]


def drop_mass(cstar: float, *, k: float, m: float = 0.518, v0: float = 10.0,
              eps: float = 0.7, dt: float | None = None) -> dict:
    """Anchor §5: a mass ``m`` meeting a compression-only spring ``k`` with Ewing's impact
    damper ``cstar`` at closing velocity ``v0``, integrated by the event stepper
    (:func:`upliftlab.reduced.run.integrate`). One DOF V (up); no gravity, a negligible
    preload (F0 = 1e-9 k). Returns the realised ``ratio`` v_lock/v0, the stroke ``dy``, its
    duration ``duration`` and the energy the damper removed (``impact_energy``)."""
    from ..reduced import kernels as kn
    from ..reduced import springs as sp
    from ..reduced.integrators import StepPlan
    from ..reduced.model import _impact_step
    from ..reduced.run import KernelInputs, integrate

    table = sp.spring_table(1)
    table["kind"], table["k"], table["f0"], table["nnz"] = sp.UPLIFT, k, 1e-9 * k, 2
    table["i0"], table["a0"], table["i1"], table["a1"] = 0, -1.0, 0, 0.0  # e = −V
    table["cimp"], table["dzf"] = cstar, m * (1 - eps) / cstar
    table["imph"] = _impact_step(m, cstar, k)
    P = sp.derive_columns(table)
    inputs = KernelInputs.springs_only(P, np.array([m]), v=0, weight=1.0)
    stroke = m / cstar * math.log(1 / eps)  # its duration with the dashpot alone
    dt = dt or stroke / 2000
    steps = int(3 * stroke / dt) + 50
    status, out, _ = integrate(inputs, "events", StepPlan(dt, steps, 1, math.inf, 1, "drop"),
                               np.array([P[0]["d0"]]), np.array([-v0]), np.zeros(2), 1.0)
    if status != kn.OK or not len(out["impacts"]):
        raise RuntimeError(f"drop mass, c* = {cstar:g}: status {status}, "
                           f"{len(out['impacts'])} impacts")
    t0, _, vin, t1, vout = out["impacts"][0]
    V = np.interp([t0, t1], out["time"], out["q"][:, 0])
    return {"ratio": vout / vin, "v0": vin, "dy": float(V[0] - V[1]), "duration": t1 - t0,
            "impact_energy": float(out["energy"][-1, 5])}


def _impact_damper(ctx) -> list[Row]:
    """Anchor §5: drop mass m = 0.518, v0 = 10, ε = 0.7 (kip, in, s)."""
    m, v0, eps = 0.518, 10.0, 0.7
    rows = []
    ref = "anchor §5 table"
    for cstar, dy, dt in ((1.0, 1.5540, 0.18476), (10.0, 0.15540, 0.018476),
                          (100.0, 0.015540, 0.0018476)):
        d = drop_mass(cstar, k=1e-6, m=m, v0=v0, eps=eps)
        rows += [_rel(R, f"drop_dy_{cstar:g}", f"damper alone, c* = {cstar:g}: stroke Δy",
                      ref, d["dy"], dy, 1e-4),
                 _rel(R, f"drop_dt_{cstar:g}", f"damper alone, c* = {cstar:g}: duration Δt",
                      ref, d["duration"], dt, 1e-4)]
        if cstar == 10.0:
            rows.append(_rel(R, "drop_energy", "energy removed, c* = 10: ½ m v0² (1 − ε²)",
                             "anchor §5", d["impact_energy"], 0.5 * m * v0 ** 2 * (1 - eps ** 2),
                             1e-6))
    k = 6000.0
    ccr = 2 * math.sqrt(k * m)
    for multiple, anchor in ((1, -0.0204), (2, -0.0051), (5, -0.0008), (10, -0.0002)):
        d = drop_mass(multiple * ccr, k=k, m=m, v0=v0, eps=eps, dt=1e-4)
        rows.append(_abs(R, f"drop_eps_{multiple}", f"k = 6000 active, c* = {multiple} c_cr: "
                         "(v_lock/v0)/ε − 1", ref, d["ratio"] / eps - 1, anchor, 1e-4))
    return rows


def _block_scene(eps: float, duration: float, hb: float = 5.0, R_: float = 1.0):
    """A uniform rigid block (R = 1 m, h/b = 5) on two very stiff edge springs (vertical
    period 2 ms), P-Δ on, released from rest at θ0 = 0.5 α (anchor §1)."""
    from ..scenes import scene_from_dict

    alpha = math.atan(1 / hb)
    mass = 1000.0
    data = {"schema": 1, "units": "N-m-s",
            "structure": {"weight": mass * 9.81, "height": R_ * math.cos(alpha),
                          "stiffness": 1.0, "rotary_inertia": mass * R_ * R_ / 3,
                          "rigid": True, "p_delta": True},
            "foundation": {"half_width": R_ * math.sin(alpha), "layout": "edges",
                           "vertical_period": 0.002, "restitution": eps},
            "motion": {"type": "free", "rotation": 0.5 * alpha, "duration": duration},
            "analysis": {"output_dt": 1e-4}}
    return scene_from_dict(data), alpha


def _rigid_block(ctx) -> list[Row]:
    """Anchor §1, h/b = 5, θ0 = 0.5 α: T_exact = 1.944300 s (4 × time to first impact, 1 %);
    rocking restitution e = 1 − 1.5 sin²α from successive peak energies (1 %)."""
    from ..reduced import run

    scene, alpha = _block_scene(1.0, 0.8)
    r = run(scene)
    th, t = r.theta, r.time
    k = int(np.flatnonzero(np.sign(th[1:]) != np.sign(th[:-1]))[0])
    t_cross = t[k] - th[k] * (t[k + 1] - t[k]) / (th[k + 1] - th[k])
    scene, alpha = _block_scene(0.9, 3.5)
    th = run(scene).theta
    flips = np.flatnonzero(np.sign(th[1:]) != np.sign(th[:-1]))
    peaks = [np.abs(s).max() for s in np.split(th, flips + 1) if s.size > 100][:4]
    b, h = math.sin(alpha), math.cos(alpha)
    energy = np.array([b * a - h * a * a / 2 for a in peaks])
    ratios = np.sqrt(energy[1:] / energy[:-1])
    e = 1 - 1.5 * math.sin(alpha) ** 2
    worst = ratios[int(np.argmax(np.abs(ratios / e - 1)))]
    return [_rel(R, "housner_period", "rigid block h/b = 5, θ0 = 0.5α: 4 × time to first "
                 "impact", "anchor §1, T_exact = 1.944300 s", 4 * t_cross, 1.944300, 0.01),
            _rel(R, "housner_restitution", "rocking restitution (worst of 3 impacts, ε = 0.9)",
                 "anchor §1, 1 − 1.5 sin²α = 0.9423", worst, e, 0.01)]


def _energy_balance(ctx) -> list[Row]:
    """Input = kinetic + strain + gravity + viscous + impact + plastic, to 0.1 % of the input."""
    from ..reduced import run
    from ..scenes import load_scene

    rows = []
    for case in "ABC":
        what = f"energy balance, short-period building, Case {case}, El Centro"
        if ctx.record is None:
            rows.append(_skip(R, f"energy_{case}", what, "conservation", "≤ 0.001",
                              ctx.record_note))
            continue
        r = run(load_scene("short_period_elcentro", case=case), motion=ctx.record,
                output_dt=0.02)
        rows.append(_bound(R, f"energy_{case}", what, "conservation (error / input)",
                           r.energy_balance_error, -math.inf, 1e-3))
    return rows


#: The order studies take fixed steps (no error control) and judge them against the exact
#: solution, not the energy balance: their coarsest steps are beyond the energy-aware limit.
FIXED_STEPS = ["analysis.rtol=0", "analysis.energy_tolerance=1"]


def _end_error(scene, reference, name, dt) -> float:
    from ..reduced import run

    q = run(scene, integrator=name, dt=dt, output_dt=1.0).q[-1]
    return float(np.abs(q - reference).max() / np.abs(reference).max())


def _orders_smooth(ctx) -> list[Order]:
    """Bonded linear free vibration against the matrix exponential: 4, 4, 4, 2, 2."""
    import scipy.linalg

    from ..reduced import build_model
    from ..reduced.run import initial_conditions
    from ..scenes import load_scene

    scene = load_scene("short_period_free", case="A",
                       overrides=["foundation.support='bonded'", "motion.duration=1.0"]
                       + FIXED_STEPS)
    model = build_model(scene)
    K, Cm = model.bonded_matrices()
    n = model.mass.size
    J = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-K / model.mass[:, None], -Cm / model.mass[:, None]]])
    q0, qd0 = initial_conditions(model, scene.build_motion())
    exact = (scipy.linalg.expm(J) @ np.concatenate([q0, qd0]))[:n]
    dts = np.array([0.004, 0.002, 0.001, 0.0005])
    case = "smooth bonded (matrix exponential)"
    out = []
    for name, p in (("events", 4), ("rk4", 4), ("abm4", 4), ("newmark", 2), ("hht", 2)):
        errors = [_end_error(scene, exact, name, dt) for dt in dts]
        out.append(_order(R, case, name, dts, errors, f"{p}", p - 0.15, p + 0.15))
    return out


def _orders_uplift(ctx) -> list[Order]:
    """The wall (Fig. 4, ε = 1), 39 uplifts in 1 s, against the event stepper at Δt = 25 µs:
    events keeps 4, fixed-step RK4 drops to about 2, Newmark stays 2."""
    from ..reduced import run
    from ..scenes import load_scene

    scene = load_scene("wall_free", case="e10", overrides=["motion.duration=1.0"] + FIXED_STEPS)
    reference = run(scene, integrator="events", dt=2.5e-5, output_dt=1.0).q[-1]
    dts = np.array([0.002, 0.001, 0.0005, 0.00025])
    case = "uplifting wall (events at Δt = 25 µs)"
    out = []
    for name, expected, low, high in (("events", "4 (> 3.7)", 3.7, 4.6),
                                      ("rk4", "≈ 2 (kinks)", 1.5, 2.7),
                                      ("newmark", "2", 1.8, 2.2)):
        errors = [_end_error(scene, reference, name, dt) for dt in dts]
        out.append(_order(R, case, name, dts, errors, expected, low, high))
    return out


# ---------------------------------------------------------------------------------------------
# Continuum
# ---------------------------------------------------------------------------------------------

E_SOIL, NU, B = 50e3, 0.3, 2.0  # kPa, -, m (the strip_footing_clay scene's soil)
G_SOIL = E_SOIL / (2 * (1 + NU))
CU = 50.0
N_SCENE = 171.39  # kN/m, FS_v = 3


def _elastic_soil(interface="frictionless", **kw):
    from ..scenes import Soil

    return Soil(youngs_modulus=E_SOIL, poisson_ratio=NU, density=1.8, model="elastic",
                interface=interface, **kw)


def _model(soil, **options):
    from ..continuum import make_model
    from ..scenes import ContinuumOptions

    return make_model(soil, B, ContinuumOptions(**options))


def _rocking_stiffness(ctx) -> tuple[list[Row], list[Order]]:
    """K_r = πGB²/(8(1 − ν)) on the default mesh (Q2 reduced, 16 across, 10B box), 1 %; and
    the O(h) convergence of full 3×3 integration at 4, 8, 16 across."""
    from ..continuum import footing_stiffness

    k_r = math.pi * G_SOIL * B ** 2 / (8 * (1 - NU))
    soil = _elastic_soil()
    default = footing_stiffness(_model(soil, elements_across=16)).rocking
    ns = np.array([4, 8, 16])
    full = np.array([footing_stiffness(_model(soil, elements_across=int(n), intorder=4)).rocking
                     for n in ns])
    rows = [_rel(C, "K_r", "rocking stiffness K_r, Q2 (2×2), 16 across B",
                 "anchor §4, πGB²/(8(1 − ν))", default, k_r, 0.01),
            _rel(C, "K_r_richardson", "K_r, full integration, Richardson 2K(16) − K(8)",
                 "anchor §4", 2 * full[-1] - full[-2], k_r, 0.002)]
    orders = [_order(C, "K_r, Q2 full integration (h = B/n)", "Q2 3×3", 1.0 / ns,
                     full / k_r - 1.0, "1 (edge singularity)", 0.85, 1.15)]
    return rows, orders


def _flamant(ctx) -> list[Row]:
    """d(1/K_v)/d ln L = (1 − ν)/(π G) over boxes 5B … 40B (Q2 8 across), 2 %."""
    from ..continuum import footing_stiffness

    sizes = np.array([5.0, 10.0, 20.0, 40.0])
    compliance = [1.0 / footing_stiffness(_model(_elastic_soil(), elements_across=8,
                                                 domain_width=s, domain_depth=s)).vertical
                  for s in sizes]
    slope = np.polyfit(np.log(sizes), compliance, 1)[0]
    return [_rel(C, "flamant", "vertical compliance slope d(1/K_v)/d ln L, boxes 5B–40B",
                 "anchor §4 (Flamant), (1 − ν)/(πG)", slope, (1 - NU) / (math.pi * G_SOIL),
                 0.02)]


def _prandtl_error(element: str, n: int) -> np.ndarray:
    from ..continuum import vertical_pushover
    from ..scenes import Soil

    soil = Soil(youngs_modulus=E_SOIL, poisson_ratio=NU, density=1.8, model="tresca",
                undrained_strength=CU, interface="bonded")
    path = vertical_pushover(_model(soil, element=element, elements_across=n),
                             np.linspace(0.0, 0.1, 11)[1:])
    return path.N / (B * (2 + math.pi) * CU) - 1.0


def _prandtl(ctx) -> tuple[list[Row], list[Order]]:
    """(2 + π) c_u for a rough strip on Tresca clay, settlement to 0.1 m in 10 steps; FE
    converges from above at O(h). P1 on the same grid locks."""
    ref = "anchor §4, (2 + π) c_u = 257.08 kPa"
    q8 = _prandtl_error("Q2", 8)
    rows = [_bound(C, "prandtl_8", "Prandtl q_u, Q2, 8 across B (error, from above)", ref,
                   q8[-1], 0.0, 0.05, "coarse mesh: O(h) overshoot, own tolerance 5 %")]
    orders = []
    if ctx.fast:
        rows += [_skip(C, "prandtl_16", "Prandtl q_u, Q2, 16 across B (error, from above)",
                       ref, "in [0, 0.02]", "full mode only (22 s); fast mode checks 8 "
                       "across at 5 %"),
                 _skip(C, "prandtl_richardson", "Prandtl, Richardson 2q(16) − q(8)", ref,
                       "abs(rel) ≤ 0.005", "full mode only")]
        orders.append(Order(C, "Prandtl q_u, Q2 (h = B/n)", "Q2 2×2", (), (), None,
                            "1 (O(h))", 0.7, 1.5, SKIP, "full mode only (8 and 16 across)"))
        p1 = _prandtl_error("P1", 8)
        q_ref, n = q8[-1], 8
    else:
        q16 = _prandtl_error("Q2", 16)
        rows += [_bound(C, "prandtl_16", "Prandtl q_u, Q2, 16 across B (error, from above)",
                        ref, q16[-1], 0.0, 0.02),
                 _abs(C, "prandtl_richardson", "Prandtl, Richardson 2q(16) − q(8) (rel. "
                      "error)", ref, 2 * q16[-1] - q8[-1], 0.0, 0.005)]
        orders.append(_order(C, "Prandtl q_u, Q2 (h = B/n)", "Q2 2×2", B / np.array([8.0, 16.0]),
                             [q8[-1], q16[-1]], "1 (O(h))", 0.7, 1.5))
        p1 = _prandtl_error("P1", 16)
        q_ref, n = q16[-1], 16
    rows.append(_bound(C, "p1_locking", f"P1 locks: P1 error / Q2 error, {n} across B "
                       f"(P1 {100 * p1[-1]:.1f} %, Q2 {100 * q_ref:.2f} %)",
                       "volumetric locking of constant-strain triangles", p1[-1] / q_ref,
                       5.0, math.inf, f"P1 error {p1[-1]:.3f} must also be > 0.10"
                       if p1[-1] > 0.10 else f"P1 error {p1[-1]:.3f} ≤ 0.10: no locking"))
    if p1[-1] <= 0.10:
        rows[-1] = dataclasses.replace(rows[-1], status=FAIL)
    return rows, orders


def _uplift_eccentricity(ctx) -> list[Row]:
    """Elastic half-plane: uplift starts at e = M/N = B/4 (1 %), not Winkler's B/6."""
    from ..continuum import rotation_pushover, uplift_onset

    theta_on = 2 * N_SCENE * (1 - NU) / (math.pi * G_SOIL * B)
    ratios = np.array([0.25, 0.5, 1.5, 2.0, 3.0, 5.0, 10.0])
    path = rotation_pushover(_model(_elastic_soil(), elements_across=16), N_SCENE,
                             ratios * theta_on)
    onset = uplift_onset(path)
    return [_rel(C, "onset_e", "uplift-onset eccentricity e/B, Q2 16 across, 10B box",
                 "half-plane (Johnson 1985): 1/4", onset.e / B, 0.25, 0.01,
                 f"{100 * (onset.e / B / (1 / 6) - 1):.0f} % above Winkler's B/6"),
            _rel(C, "onset_theta", "uplift-onset rotation θ_on", "2N(1 − ν)/(πGB)",
                 onset.theta, theta_on, 0.01)]


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------

#: (group, title, check): each check returns rows, orders, or (rows, orders).
CHECKS: tuple[tuple[str, str, Callable], ...] = (
    (R, "two-spring K (eq. 6)", _stiffness_entries),
    (R, "static reactions", _static_reactions),
    (R, "bonded periods", _bonded_periods),
    (R, "fixed base vs Nigam–Jennings", _fixed_base),
    (R, "Winkler pushover", _winkler_pushover),
    (R, "uplift onset", _uplift_onset),
    (R, "elasto-plastic bed", _ultimate_moment),
    (R, "impact damper", _impact_damper),
    (R, "rigid block", _rigid_block),
    (R, "energy balance", _energy_balance),
    (R, "orders, smooth case", _orders_smooth),
    (R, "orders, uplifting case", _orders_uplift),
    (C, "rocking stiffness", _rocking_stiffness),
    (C, "Flamant slope", _flamant),
    (C, "Prandtl and locking", _prandtl),
    (C, "uplift-onset eccentricity", _uplift_eccentricity),
)


@dataclass(frozen=True)
class _Context:
    fast: bool
    record: object | None
    record_note: str


def _record() -> tuple[object | None, str | None, str]:
    """(motion, SHA-256 of its file, note): El Centro from UPLIFTLAB_MOTIONS, or None."""
    try:
        path = find_motion(ELCENTRO)
    except InputError as exc:
        return None, None, f"El Centro record not found: {exc}"
    return load_motion(ELCENTRO), file_sha256(path), ""


def source_digest(extra: Sequence[str | Path] = ()) -> str:
    """SHA-256 of the source files that decide the verification's numbers: every ``.py`` of
    ``reduced/``, ``continuum/``, ``meshes/`` and the core package (but the command line), the
    packaged scenes, this module and ``extra`` files. Paths and bytes both enter."""
    import upliftlab
    from .. import continuum, meshes, reduced
    from .. import scene_files

    digest = hashlib.sha256()
    core = Path(upliftlab.__file__).parent
    files = [p for p in sorted(core.glob("*.py")) if p.name not in ("cli.py", "__main__.py")]
    for package in (reduced, continuum, meshes):
        files += sorted(Path(package.__file__).parent.rglob("*.py"))
    files += sorted(Path(scene_files.__file__).parent.glob("*.toml"))
    files += [Path(__file__)] + [Path(p) for p in extra]
    for path in files:
        digest.update(f"{path.parent.name}/{path.name}\n".encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def single_threaded():
    """A context that limits BLAS/OpenMP pools to one thread (``threadpoolctl``, if installed;
    else nothing). On a shared or loaded machine a two-thread BLAS under the continuum's small
    dense kernels oversubscribes the cores and runs several times slower; the sweeps' workers
    are single-threaded for the same reason (:data:`.sweep.SINGLE_THREAD_ENVIRONMENT`)."""
    import contextlib

    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return contextlib.nullcontext()
    import scipy.linalg  # noqa: F401  (load scipy's own BLAS first: limits apply to loaded
    import scipy.sparse.linalg  # noqa: F401  libraries only)
    return threadpool_limits(limits=1)


def compute(fast: bool, progress=None) -> dict:
    """Run every check (no store): {"rows": [...], "orders": [...], "seconds": {...}}."""
    with single_threaded():
        return _compute(fast, progress)


def _compute(fast: bool, progress=None) -> dict:
    say = progress or (lambda message: None)
    record, _, note = _record()
    ctx = _Context(fast, record, note)
    rows, orders, seconds = [], [], {}
    for group, title, check in CHECKS:
        start = time.perf_counter()
        try:
            out = check(ctx)
        except Exception as exc:  # a crashing check is a failing row with its message
            out = [Row(group, f"error_{check.__name__.strip('_')}", f"{title}: the check "
                       "raised", "", None, None, None, "", "", FAIL,
                       f"{type(exc).__name__}: {exc}")]
        rs, os_ = out if isinstance(out, tuple) else (out, [])
        for item in rs:
            (orders if isinstance(item, Order) else rows).append(item)
        orders += list(os_)
        seconds[title] = time.perf_counter() - start
        say(f"{title}: {seconds[title]:.1f} s")
    return {"rows": [dataclasses.asdict(r) for r in rows],
            "orders": [dataclasses.asdict(o) for o in orders], "seconds": seconds}


def compute_or_read(scene: None, ctx: Context) -> Verification:
    """Every anchor, computed or read from ``ctx.store`` under the content key of the module
    docstring (``scene`` must be None: the checks build their own)."""
    if scene is not None:
        raise InputError(f"scene = {scene!r}: the verification builds its own scenes; pass "
                         "scene=None")
    fast, store = ctx.fast, ctx.store
    _, record_sha, _ = _record()
    params = {"fast": bool(fast), "elcentro_sha256": record_sha, "source": source_digest()}
    key = point_key(STUDY, "upliftlab.comparisons.verification:compute", params)
    entry = store.get(key)
    reused = entry is not None
    if entry is None:
        t0 = time.perf_counter()
        entry = compute(fast, ctx.progress)
        entry["compute_seconds"] = time.perf_counter() - t0
        entry["computed_utc"] = provenance()["created_utc"]
        store.put(key, entry, {"study": STUDY, "params": params, "version": __version__})
    rows = tuple(Row(**r) for r in entry["rows"])
    orders = tuple(Order(**{**o, "steps": tuple(o["steps"]), "errors": tuple(o["errors"])})
                   for o in entry["orders"])
    return Verification(rows, orders, reused, key, entry["computed_utc"],
                        entry["compute_seconds"], None, params, entry.get("seconds", {}))


def run(fast: bool = False, *, out: str | Path | None = None,
        store: Store | str | Path | None = None, progress=None, **_ignored) -> Verification:
    """Compute (or read from ``store``) every anchor; write ``anchors.csv``, ``orders.csv``,
    ``summary.md`` and ``summary.json`` into ``out`` (default ``results/verification[-fast]``).

    ``store`` defaults to ``<out>/store``. Keyword arguments other studies take (``scheduler``)
    are accepted and ignored: the checks run in this process.
    """
    return run_study(DEFINITION, None, Context(fast=fast, out=out, store=store,
                                               progress=progress))


def write(result: Verification, ctx: Context) -> StudyResult:
    """``anchors.csv``, ``orders.csv`` and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, fast=fast, key=result.key, store=str(store.root),
                      computed_utc=result.computed_utc, reused=result.reused,
                      inputs=dict(result.inputs))
    files = [_rows_csv(result.rows, out / "anchors.csv"),
             _orders_csv(result.orders, out / "orders.csv")]
    elapsed = ctx.elapsed()
    numbers = {"passed": result.passed, "failures": result.failures,
               "counts": _counts(result), "reused": result.reused, "key": result.key,
               "computed_utc": result.computed_utc,
               "compute_seconds": result.compute_seconds,
               "check_seconds": dict(result.check_seconds),
               "rows": [dataclasses.asdict(r) for r in result.rows],
               "orders": [dataclasses.asdict(o) for o in result.orders], "elapsed_s": elapsed}
    text = markdown(result, fast)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def _counts(result: Verification) -> dict:
    items = [r.status for r in result.rows] + [o.status for o in result.orders]
    return {s: items.count(s) for s in (PASS, FAIL, SKIP)}


def _rows_csv(rows, path: Path) -> Path:
    nan = math.nan
    return write_csv(path, {
        "row": np.arange(len(rows)),
        "measured": [nan if r.measured is None else r.measured for r in rows],
        "expected": [nan if r.expected is None else r.expected for r in rows],
        "error": [nan if r.error is None else r.error for r in rows],
        "passed": [{PASS: 1, FAIL: 0}.get(r.status, nan) for r in rows]},
        header="verification anchors (row order as in summary.json): " +
        "; ".join(f"{i}={r.id}" for i, r in enumerate(rows)))


def _orders_csv(orders, path: Path) -> Path:
    nan = math.nan
    return write_csv(path, {
        "row": np.arange(len(orders)),
        "slope": [nan if o.slope is None else o.slope for o in orders],
        "low": [o.low for o in orders], "high": [o.high for o in orders],
        "passed": [{PASS: 1, FAIL: 0}.get(o.status, nan) for o in orders]},
        header="observed orders: " + "; ".join(f"{i}={o.group}/{o.case}/{o.method}"
                                               for i, o in enumerate(orders)))


def fmt(value: float | None, digits: int = 6) -> str:
    """A number for the tables (— for none)."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    return f"{value:.{digits}g}"


def error_text(row: Row) -> str:
    if row.error is None:
        return "—"
    if row.kind == "relative":
        return f"{row.error:+.2e}"
    if row.kind == "absolute":
        return f"{row.error:+.2e} (abs)"
    return f"{row.error:.4g}"


def markdown(result: Verification, fast: bool) -> str:
    """The summary: counts, the anchors table and the orders table."""
    n = _counts(result)
    lines = [f"# Verification anchors{' (fast)' if fast else ''}", "",
             f"{n[PASS]} pass, {n[FAIL]} fail, {n[SKIP]} skipped. Computed "
             f"{result.computed_utc} in {result.compute_seconds:.1f} s"
             + (" (read from the store: nothing recomputed)." if result.reused else "."), "",
             "Errors are relative (measured/reference − 1) unless marked abs; a bound row "
             "shows the measured value itself." + (" Fast mode skips the costly continuum "
                                                    "levels (rows marked skipped)."
                                                    if fast else ""), "",
             "| group | quantity | reference | measured | expected | error | tolerance | "
             "result |", "|---|---|---|---|---|---|---|---|"]
    for r in result.rows:
        status = r.status if r.status != FAIL else "**FAIL**"
        note = f" — {r.note}" if r.note else ""
        lines.append(f"| {r.group} | {r.quantity}{note} | {r.reference} | {fmt(r.measured)} | "
                     f"{fmt(r.expected)} | {error_text(r)} | {r.tolerance} | {status} |")
    lines += ["", "## Observed convergence orders", "",
              "Slope of log(error) against log(step) by least squares (np.polyfit).", "",
              "| group | case | method | steps | observed order | expected | band | result |",
              "|---|---|---|---|---|---|---|---|"]
    for o in result.orders:
        steps = ", ".join(f"{s:g}" for s in o.steps) or "—"
        status = o.status if o.status != FAIL else "**FAIL**"
        note = f" — {o.note}" if o.note else ""
        lines.append(f"| {o.group} | {o.case} | {o.method} | {steps} | "
                     f"{fmt(o.slope, 3)} | {o.expected} | [{o.low:g}, {o.high:g}] | "
                     f"{status}{note} |")
    if result.failures:
        lines += ["", "## Failures", ""] + [f"- {f}" for f in result.failures]
    return "\n".join(lines) + "\n"


def _context_from(args, ctx: Context, say) -> Context:
    return dataclasses.replace(ctx, progress=say)


DEFINITION = Study(STUDY, "Verification anchors",
                   "Every verification anchor (closed forms, published values and converged "
                   "runs, listed in the table with their references) recomputed through the "
                   "library, with its measured error against its tolerance.", None,
                   compute_or_read, write, describe=lambda result: [result.study.summary],
                   passed=lambda result: result.passed, context_from=_context_from,
                   own_store=True, help_fast="skip the costly continuum levels")
main = main_for(DEFINITION)


if __name__ == "__main__":
    sys.exit(main())
