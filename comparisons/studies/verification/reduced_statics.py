"""The reduced model's static and impact anchors: stiffness entries, reactions, bonded
periods, the fixed base, the Winkler pushover, uplift onset, yield, the ultimate moment and
the impact damper."""

from __future__ import annotations

import math

import numpy as np

from ....anchors import (TOLERANCES, edge_springs_onset_force, equivalent_springs_onset_force,
                         first_yield_rotation_ratio, ultimate_moment_ratio, winkler_contact_ratio,
                         winkler_moment_ratio, winkler_onset_force)
from .records import R, Row, absolute_row, relative_row, skipped_row


def stiffness_entries(ctx) -> list[Row]:
    """Anchor §2, eq. 6: h = 288, b = 72, k1 = k2 = 3000, k3 = 500 (kip, in)."""
    from ....reduced import compatibility_matrix, custom_springs, edge_springs, stiffness_matrix
    from ....reduced.compatibility import DofMap

    dofs = DofMap.build(1, rigid=False, fixed=False)  # (x, θ, V)
    h, b = 288.0, 72.0
    K = stiffness_matrix(compatibility_matrix(dofs, [h], edge_springs(b, 6000.0)),
                         [500.0, 3000.0, 3000.0])
    k1, k2 = 1000.0, 4000.0
    Ku = stiffness_matrix(compatibility_matrix(dofs, [h], custom_springs(b, [-b, b], [k1, k2])),
                          [500.0, k1, k2])
    ref = "anchor §2, eq. 6"
    return [relative_row(R, "K_thth", "two-spring K_θθ = h²k₃ + b²(k₁ + k₂)", ref, K[1, 1],
                         7.2576e7, 1e-12),
            relative_row(R, "K_Xth", "two-spring K_Xθ = −h k₃", ref, K[0, 1], -1.44e5, 1e-12),
            relative_row(R, "K_thV", "K_θV = b(k₁ − k₂), k₁ = 1000, k₂ = 4000", ref, Ku[1, 2],
                         b * (k1 - k2), 1e-12),
            relative_row(R, "K_VV", "K_VV = k₁ + k₂", ref, Ku[2, 2], k1 + k2, 1e-12)]


def static_reactions(ctx) -> list[Row]:
    """At rest the spring compressions carry the weight: Σ F0 = W, Σ x F0 = 0."""
    from ....reduced import build_model
    from ....scenes import load_scene

    rows = []
    for name in ("wall_free", "short_period_free"):
        model = build_model(load_scene(name))
        f = model.params[model.foundation_slice]
        b = model.layout.half_width
        rows += [relative_row(R, f"reaction_{name}", f"{name}: Σ F0 = W", "statics", f["f0"].sum(),
                              model.weight, 1e-12),
                 absolute_row(R, f"moment_{name}", f"{name}: Σ x F0 / (W b) = 0", "statics",
                              np.sum(f["x"] * f["f0"]) / (model.weight * b), 0.0, 1e-12)]
    return rows


def bonded_periods(ctx) -> list[Row]:
    """Bonded periods against eig(K, M), and the first one measured on a free vibration."""
    import scipy.linalg

    from ....reduced import build_model, run
    from ....scenes import load_scene

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
    return [relative_row(R, "bonded_periods", "bonded periods (worst of 3) vs eig(K, M)",
                         "scipy.linalg.eigh", mine[worst], periods[worst], 1e-12),
            relative_row(R, "bonded_T1_measured", "first bonded period from a free vibration's "
                         "zero crossings", "eig(K, M)", measured, periods[0], 2e-3)]


def fixed_base(ctx) -> list[Row]:
    """Fixed base on El Centro against Nigam–Jennings, evaluated 200 times per record step,
    its peak refined on the exact cubic (0.01 % in peak u at the default Δt)."""
    from ....reduced import run
    from ....reduced.exact import hermite_peak, nigam_jennings
    from ....scenes import load_scene

    rows = []
    for name in ("short_period_elcentro", "long_period_elcentro", "wall_elcentro"):
        what = f"{name}, fixed base: peak u"
        if ctx.record is None:
            rows.append(skipped_row(R, f"nj_{name}", what, "Nigam–Jennings", "abs(rel) ≤ 0.0001",
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
        rows.append(relative_row(R, f"nj_{name}", what, "Nigam–Jennings exact recurrence",
                                 response.peaks["u"], reference, 1e-4,
                                 f"Δt = {response.info['dt']:.3g} s "
                                 f"({response.info['integrator']})"))
    return rows


def winkler_pushover(ctx) -> list[Row]:
    """Anchor §3 with 200 springs: M/M_up = 3 − 2√(θ_up/θ), c/B = √(θ_up/θ) (0.5 %)."""
    from ....reduced import build_model, rocking_pushover
    from ....scenes import load_scene

    model = build_model(load_scene("wall_free", overrides=["foundation.springs=200"]))
    N, B = model.weight, 2 * model.layout.half_width
    theta_up = 2 * N / (model.layout.vertical_stiffness * B)
    ratios = np.array([0.5, 1.5, 3.0, 10.0])
    push = rocking_pushover(model, ratios * theta_up)
    closed_m = winkler_moment_ratio(ratios)
    closed_c = winkler_contact_ratio(ratios)
    em = push.moment / (N * B / 6) / closed_m - 1
    ec = push.contact / B / closed_c - 1
    km, kc = int(np.argmax(np.abs(em))), int(np.argmax(np.abs(ec)))
    ref = "anchor §3 (θ/θ_up = 0.5, 1.5, 3, 10; worst shown)"
    return [relative_row(R, "pushover_M", f"M/M_up, 200 springs (worst at θ = {ratios[km]:g} θ_up)",
                         ref, push.moment[km] / (N * B / 6), closed_m[km],
                         TOLERANCES["winkler_pushover"].value),
            relative_row(R, "pushover_c", f"contact c/B, 200 springs (worst at θ = {ratios[kc]:g} "
                         "θ_up)", ref, push.contact[kc] / B, closed_c[kc],
                         TOLERANCES["winkler_pushover"].value)]


def reduced_uplift_onset(ctx) -> list[Row]:
    """Anchor §2: W b/h (edges), W b/(√3 h) (±b/√3), W b/(3h)(1 + 1/N) for N strips."""
    from ....reduced import build_model, uplift_onset_force
    from ....scenes import load_scene

    base = load_scene("wall_free")
    W, b, h = 200.0, 72.0, 288.0
    two = "foundation.springs=2"

    def onset(*sets):
        return uplift_onset_force(build_model(base.with_overrides(*sets)))

    ref = "anchor §2 (wall: W = 200 kip, b = 72 in, h = 288 in)"
    n = 200
    p200 = onset(f"foundation.springs={n}")
    return [relative_row(R, "onset_edges", "uplift onset, edge springs: W b/h = 50 kip", ref,
                         onset("foundation.layout='edges'", two), edge_springs_onset_force(W, b, h),
                         1e-12),
            relative_row(R, "onset_equivalent", "uplift onset, ±b/√3: W b/(√3 h) = 28.868 kip", ref,
                         onset("foundation.layout='equivalent'", two),
                         equivalent_springs_onset_force(W, b, h), 1e-12),
            relative_row(R, "onset_winkler_N", f"uplift onset, {n} strips: W b/(3h)(1 + 1/N)",
                         "outer strip centre at b(1 − 1/N)", p200, winkler_onset_force(W, b, h, n),
                         1e-12),
            relative_row(R, "onset_winkler", "uplift onset, 400 strips vs W b/(3h) = 16.667 kip",
                         ref, onset("foundation.springs=400"), winkler_onset_force(W, b, h), 5e-3,
                         "N → ∞ limit; the bed's excess is 1/N")]


def _first_yield(model, theta_up, low, high) -> float:
    """θ/θ_up of first yield by bisection between an elastic ``low`` and a yielded ``high``
    (monotonic pushovers are path independent until the first spring yields)."""
    from ....reduced import rocking_pushover

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


def ultimate_moment(ctx) -> list[Row]:
    """Anchor §3: M → M_ult = (NB/2)(1 − 1/FS_v) (0.2 %) and first yield at (FS²/4) θ_up
    (2 %), 400 springs, FS_v = 3, pushed to 2000 θ_up."""
    from ....reduced import build_model, rocking_pushover
    from ....scenes import load_scene

    model = build_model(load_scene("short_period_free", overrides=["foundation.springs=400"]))
    N, B, fs = model.weight, 2 * model.layout.half_width, 3.0
    theta_up = 2 * N / (model.layout.vertical_stiffness * B)
    ratios = np.geomspace(0.1, 2000.0, 120 if ctx.fast else 400)
    push = rocking_pushover(model, theta_up * ratios)
    m_ult = N * B * ultimate_moment_ratio(fs)
    k = int(np.flatnonzero(push.plastic.max(axis=1) > 0)[0])
    first = _first_yield(model, theta_up, ratios[k - 1], ratios[k])
    ref = "anchor §3 (FS_v = 3, 400 springs)"
    return [relative_row(R, "M_ult", "elasto-plastic bed: M(2000 θ_up) / M_ult, M_ult = "
                         "(NB/2)(1 − 1/FS_v)", ref, push.moment[-1], m_ult,
                         TOLERANCES["ultimate_moment"].value,
                         f"{ratios.size} pushover steps"),
            relative_row(R, "yield_rotation", "first yield rotation θ_y/θ_up = FS_v²/4", ref, first,
                         first_yield_rotation_ratio(fs), TOLERANCES["first_yield"].value,
                         "bisection of the pushover to 1e-6")]


def drop_mass(cstar: float, *, k: float, m: float = 0.518, v0: float = 10.0,
              eps: float = 0.7, dt: float | None = None) -> dict:
    """Anchor §5: a mass ``m`` meeting a compression-only spring ``k`` with Ewing's impact
    damper ``cstar`` at closing velocity ``v0``, integrated by the event stepper
    (:func:`upliftlab.reduced.run.integrate`). One DOF V (up); no gravity, a negligible
    preload (F0 = 1e-9 k). Returns the realised ``ratio`` v_lock/v0, the stroke ``dy``, its
    duration ``duration`` and the energy the damper removed (``impact_energy``)."""
    from ....reduced import kernels as kn
    from ....reduced import springs as sp
    from ....reduced.integrators import StepPlan
    from ....reduced.model import impact_step
    from ....reduced.run import KernelInputs, integrate

    table = sp.spring_table(1)
    table["kind"], table["k"], table["f0"], table["nnz"] = sp.UPLIFT, k, 1e-9 * k, 2
    table["i0"], table["a0"], table["i1"], table["a1"] = 0, -1.0, 0, 0.0  # e = −V
    table["cimp"], table["dzf"] = cstar, m * (1 - eps) / cstar
    table["imph"] = impact_step(m, cstar, k)
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


def impact_damper(ctx) -> list[Row]:
    """Anchor §5: drop mass m = 0.518, v0 = 10, ε = 0.7 (kip, in, s)."""
    m, v0, eps = 0.518, 10.0, 0.7
    rows = []
    ref = "anchor §5 table"
    for cstar, dy, dt in ((1.0, 1.5540, 0.18476), (10.0, 0.15540, 0.018476),
                          (100.0, 0.015540, 0.0018476)):
        d = drop_mass(cstar, k=1e-6, m=m, v0=v0, eps=eps)
        rows += [relative_row(R, f"drop_dy_{cstar:g}", f"damper alone, c* = {cstar:g}: stroke Δy",
                              ref, d["dy"], dy, 1e-4),
                 relative_row(R, f"drop_dt_{cstar:g}", f"damper alone, c* = {cstar:g}: duration Δt",
                              ref, d["duration"], dt, 1e-4)]
        if cstar == 10.0:
            rows.append(relative_row(R, "drop_energy", "energy removed, c* = 10: ½ m v0² (1 − ε²)",
                                     "anchor §5", d["impact_energy"],
                                     0.5 * m * v0 ** 2 * (1 - eps ** 2), 1e-6))
    k = 6000.0
    ccr = 2 * math.sqrt(k * m)
    for multiple, anchor in ((1, -0.0204), (2, -0.0051), (5, -0.0008), (10, -0.0002)):
        d = drop_mass(multiple * ccr, k=k, m=m, v0=v0, eps=eps, dt=1e-4)
        rows.append(absolute_row(R, f"drop_eps_{multiple}", f"k = 6000 active, c* = {multiple} "
                                 "c_cr: (v_lock/v0)/ε − 1", ref, d["ratio"] / eps - 1, anchor,
                                 1e-4))
    return rows
