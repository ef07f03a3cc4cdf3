"""What a scene's calibration gives its user: the ``--set`` overrides that put the calibrated
macro-element under the scene's structure in the reduced model, the record of the law with the
runs it came from (JSON), and the table of its checks (Markdown)."""

from __future__ import annotations

import dataclasses

from ....scenes.laws.macro import MacroLaw
from ....scenes.structure import Foundation
from ...beds.macro_bed import element_keys, gazetas_sway_stiffness
from .fit import PLATEAU_TOLERANCE, SceneCalibration
from .plan import PATHS, SETTLEMENT_RATIO, VERTICAL_STEPS

__all__ = ["law_table", "scene_overrides", "fitting_items", "check_reduced_scene",
           "calibration_record", "calibration_markdown"]

_FOUNDATION_KEYS = {f.name for f in dataclasses.fields(Foundation)} | {"vertical_period"}
_MACRO_KEYS = {f.name for f in dataclasses.fields(MacroLaw)}


def _number(value: float) -> str:
    return repr(float(value))


def scene_overrides(cal: SceneCalibration, scene) -> list[str]:
    """``--set`` items that make ``scene``'s foundation the calibrated element: the law and
    its keys (:func:`~...beds.macro_bed.element_keys`: K_v and K_r from the continuum, the
    capacity as a multiple of the scene's vertical weight, the plastic parameters); and what
    :func:`fitting_items` adds."""
    keys = element_keys(cal.fit.law, scene.structure.vertical_weight)
    items = [f"foundation.{key}={value if key == 'law' else _number(value)}"
             for key, value in keys.items()]
    return items + fitting_items(scene, items)


def fitting_items(scene, items: list[str]) -> list[str]:
    """The ``--set`` items besides ``items`` that the element needs of ``scene``: Gazetas'
    static sway stiffness 2G/(2 − ν) where the scene has none, a support that lifts off, no
    impact damper, and the removal of what the element refuses or does not read (another
    law's keys, a vertical period, sliding, per-spring dashpots)."""
    extra, data = [], scene.data.get("foundation", {})
    if scene.foundation.support != "uplift":
        extra.append("foundation.support=uplift")
    if scene.foundation.restitution != 1.0:
        extra.append("foundation.restitution=1")
    if scene.foundation.sway_stiffness is None:
        soil = scene.soil
        G = soil.youngs_modulus / (2.0 * (1.0 + soil.poisson_ratio))
        K_h = gazetas_sway_stiffness(G, soil.poisson_ratio)
        extra.append(f"foundation.sway_stiffness={_number(K_h)}")
    set_here = {item.split("=", 1)[0].split(".", 1)[1] for item in [*items, *extra]}
    for key in sorted(data):
        removed = key in ("vertical_period", "sliding_friction", "dashpots") or (
            key not in _FOUNDATION_KEYS and key not in _MACRO_KEYS and key != "law")
        if removed and key not in set_here:
            extra.append(f"foundation.{key}=")
    return extra


def check_reduced_scene(scene) -> None:
    """Refuse, before any run, a scene that cannot carry the element in the reduced model
    whatever the fit gives (its structure, say, has no base mass to sway): the scene is
    validated with the element's fixed items and a placeholder capacity."""
    from ....checks import InputError

    items = ["foundation.law=macro", "foundation.capacity_multiple=3.0"]
    try:
        scene.with_overrides(*items, *fitting_items(scene, items))
    except InputError as exc:
        raise InputError(f"{exc} (the scene with the macro-element in the reduced model; "
                         "--set it)") from None


def calibration_record(cal: SceneCalibration, overrides: list[str]) -> dict:
    """The calibration as JSON values: the law's fields, the statics, the checks per pushover,
    the pushovers left out, the store keys of the runs, the overrides and the timings (s)."""
    fit = cal.fit
    return {
        "scene": cal.scene, "scene_digest": cal.scene_digest, "width": cal.width,
        "statics": {"K_v": cal.K_v, "K_r": cal.K_r, "V_ult": cal.V_ult,
                    "plateau": cal.plateau},
        "law": {k: float(v) for k, v in dataclasses.asdict(fit.law).items()},
        "capacity_line": {**{k: float(v) for k, v in fit.details["capacity"].items()},
                          "residuals": [float(r) for r in fit.capacity_residuals]},
        "pushovers": [{"label": p.source, "N": p.N, "moment_rms": float(m),
                       "settlement_rms": float(s), "load_miss": float(miss)}
                      for p, m, s, miss in zip(cal.pushovers, fit.moment_rms,
                                               fit.settlement_rms, fit.load_misses)],
        "left_out": [{"fs_v": fs, "kind": kind, "why": why} for fs, kind, why in cal.left_out],
        "fit": {"cost": fit.cost, "evaluations": fit.evaluations,
                **fit.details.get("least_squares", {})},
        "overrides": overrides, "store_keys": list(cal.keys),
        "seconds": {k: round(float(v), 3) for k, v in cal.seconds.items()},
    }


def law_table(law, length_unit: str = "") -> list[str]:
    """The fitted plastic parameters of ``law`` (a
    :class:`~upliftlab.reduced.laws.macro.MacroElement`) as a Markdown table's three lines;
    ``length_unit`` is κ_ref's, written in its header when given."""
    kappa = f"κ_ref ({length_unit})" if length_unit else "κ_ref"
    return [f"| ζ0 | {kappa} | h0 | γ | χ | λ_ρ | δ | ε | μ |",
            "|---|---|---|---|---|---|---|---|---|",
            f"| {law.initial_size:.3f} | {law.hardening_settlement:.3g} | "
            f"{law.interior_modulus:.3g} | {law.interior_exponent:.3f} | "
            f"{law.settlement_coupling:.3f} | {law.rounding_ratio:.3f} | "
            f"{law.flow_dilatancy:.3f} | {law.coupling_exponent:.3f} | "
            f"{law.memory_modulus:.3g} |"]


def calibration_markdown(cal: SceneCalibration, run_line: str, command: str) -> str:
    """The calibration's checks as a page: the statics, the capacity line and its residuals,
    the law, and per pushover the rms misfit of the moment (of its largest) and of the
    settlement (of its range, at least N/(10 K_v)) and the largest miss of N; ``run_line`` runs the
    scene with the element, ``command`` made the calibration."""
    fit, law = cal.fit, cal.fit.law
    cap = fit.details["capacity"]
    lines = [f"# The macro-element of `{cal.scene}`", "",
             f"Command `{command}`. The continuum's statics on the scene's own soil, footing "
             f"and mesh: the stiffness in full contact, a vertical pushover to "
             f"{SETTLEMENT_RATIO:g} B in {VERTICAL_STEPS} steps, and at each FS_v a monotonic "
             f"rotation pushover to {max(PATHS.theta_ratios):g} θ_on and cycles at "
             f"{', '.join(f'{r:g}' for r in PATHS.cycle_ratios)} θ_on, and at FS_v "
             f"{' and '.join(f'{v:g}' for v in PATHS.repeat_fs_v)} {PATHS.repeat_cycles} "
             f"cycles at {PATHS.repeat_ratio:g} θ_on. Nothing dynamic "
             "enters: the scene's own dynamic runs are the test.", "",
             f"K_v {cal.K_v:.6g}, K_r {cal.K_r:.6g}, V_ult {cal.V_ult:.6g} (the vertical "
             f"pushover's last step rose {cal.plateau:.2%} of it; at most "
             f"{PLATEAU_TOLERANCE:.0%}); capacity line q(B′) = {cap['q0']:.6g} + "
             f"{cap['q1']:.6g} B′, residuals "
             f"{', '.join(f'{r:+.1%}' for r in fit.capacity_residuals)}; fit: "
             f"{fit.evaluations} evaluations, cost {fit.cost:.3g}.", "",
             *law_table(law), "",
             "| pushover | moment rms (of its largest) | settlement rms (of its range) | "
             "largest miss of V (of N) |", "|---|---|---|---|"]
    for p, m, s, miss in zip(cal.pushovers, fit.moment_rms, fit.settlement_rms,
                             fit.load_misses):
        lines.append(f"| {p.source} | {m:.1%} | {s:.1%} | {miss:.1e} |")
    for fs, kind, why in cal.left_out:
        lines.append(f"| FS_v {fs:g}, {kind}: left out | {why} | | |")
    lines += ["", "In the reduced model:", "", "```", run_line, "```", ""]
    return "\n".join(lines)
