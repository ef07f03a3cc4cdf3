"""The reduced model's dynamic anchors: the rigid block, the energy balance and the observed
orders of the integrators."""

from __future__ import annotations

import math

import numpy as np

from ....anchors import HOUSNER_PERIOD_HB5, TOLERANCES, rocking_restitution_rectangle
from ....reduced.integrators import METHODS
from .records import Order, R, Row, bound_row, order_row, relative_row, skipped_row


def _block_scene(eps: float, duration: float, hb: float = 5.0, R_: float = 1.0):
    """A uniform rigid block (R = 1 m, h/b = 5) on two very stiff edge springs (vertical
    period 2 ms), P-Δ on, released from rest at θ0 = 0.5 α (anchor §1)."""
    from ....scenes import scene_from_dict

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


def rigid_block(ctx) -> list[Row]:
    """Anchor §1, h/b = 5, θ0 = 0.5 α: T_exact = 1.944300 s (4 × time to first impact, 1 %);
    rocking restitution e = 1 − 1.5 sin²α from successive peak energies (1 %)."""
    from ....reduced import run

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
    e = rocking_restitution_rectangle(alpha)
    worst = ratios[int(np.argmax(np.abs(ratios / e - 1)))]
    return [relative_row(R, "housner_period", "rigid block h/b = 5, θ0 = 0.5α: 4 × time to first "
                         "impact", "anchor §1, T_exact = 1.944300 s", 4 * t_cross,
                         HOUSNER_PERIOD_HB5, TOLERANCES["housner_period"].value),
            relative_row(R, "housner_restitution",
                         "rocking restitution (worst of 3 impacts, ε = 0.9)",
                         "anchor §1, 1 − 1.5 sin²α = 0.9423", worst, e,
                         TOLERANCES["housner_restitution"].value)]


def energy_balance(ctx) -> list[Row]:
    """Input = kinetic + strain + gravity + viscous + impact + plastic, to 0.1 % of the input."""
    from ....reduced import run
    from ....scenes import load_scene

    rows = []
    for case in "ABC":
        what = f"energy balance, short-period building, Case {case}, El Centro"
        if ctx.record is None:
            rows.append(skipped_row(R, f"energy_{case}", what, "conservation", "≤ 0.001",
                                    ctx.record_note))
            continue
        r = run(load_scene("short_period_elcentro", case=case), motion=ctx.record,
                output_dt=0.02)
        rows.append(bound_row(R, f"energy_{case}", what, "conservation (error / input)",
                              r.energy_balance_error, -math.inf, 1e-3))
    return rows


#: The order studies take fixed steps (no error control) and judge them against the exact
#: solution, not the energy balance: their coarsest steps are beyond the energy-aware limit.
FIXED_STEPS = ["analysis.rtol=0", "analysis.energy_tolerance=1"]


def _end_error(scene, reference, name, dt) -> float:
    from ....reduced import run

    q = run(scene, integrator=name, dt=dt, output_dt=1.0).q[-1]
    return float(np.abs(q - reference).max() / np.abs(reference).max())


def orders_smooth(ctx) -> list[Order]:
    """Bonded linear free vibration against the matrix exponential: 4, 4, 4, 2, 2."""
    import scipy.linalg

    from ....reduced import build_model
    from ....reduced.run import initial_conditions
    from ....scenes import load_scene

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
    for name, p in ((m.name, m.order) for m in METHODS.values()):
        errors = [_end_error(scene, exact, name, dt) for dt in dts]
        out.append(order_row(R, case, name, dts, errors, f"{p}", p - 0.15, p + 0.15))
    return out


def orders_uplift(ctx) -> list[Order]:
    """The wall (Fig. 4, ε = 1), 39 uplifts in 1 s, against the event stepper at Δt = 25 µs:
    events keeps 4, fixed-step RK4 drops to about 2, Newmark stays 2."""
    from ....reduced import run
    from ....scenes import load_scene

    scene = load_scene("wall_free", case="e10", overrides=["motion.duration=1.0"] + FIXED_STEPS)
    reference = run(scene, integrator="events", dt=2.5e-5, output_dt=1.0).q[-1]
    dts = np.array([0.002, 0.001, 0.0005, 0.00025])
    case = "uplifting wall (events at Δt = 25 µs)"
    out = []
    for name, expected, low, high in (("events", "4 (> 3.7)", 3.7, 4.6),
                                      ("rk4", "≈ 2 (kinks)", 1.5, 2.7),
                                      ("newmark", "2", 1.8, 2.2)):
        errors = [_end_error(scene, reference, name, dt) for dt in dts]
        out.append(order_row(R, case, name, dts, errors, expected, low, high))
    return out
