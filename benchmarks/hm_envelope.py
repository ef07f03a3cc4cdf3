"""The continuum's H–M section at constant V on the clay, against Green's load on the effective
width (the lower bound of Houlsby and Puzrin 1999) and the macro-element's elliptic section
(issue 36 §2).

    python benchmarks/hm_envelope.py [--meshes 8,16] [--v 0.25,0.5,0.75] [--quick]
                                     [--out DIR] [--write]

A rough rigid strip B = 2 m that cannot take tension (a Coulomb interface, μ = 1: its shear
never limits before the clay's) on Tresca clay, c_u = 50 kPa, E = 50 MPa, ν = 0.3, in the
default 10 B box. Per mesh: V_ult from a vertical pushover to 0.05 B (the mesh's own, so that
its overshoot cancels: every load is normalised by the strength c* = V_ult/((2 + π) B) it
implies); then at each V = v V_ult, seven probes over a half turn of (u, B θ)
(:func:`upliftlab.continuum.hm_envelope`, to 0.1 m in 12 steps), each giving a point (H, M)
of the section; the half turn's image under (H, M) → (−H, −M) is the other half.

Each point is compared along its own ray in (H/(c* B), M/(c* B²)):

- with the lower bound, Green's (1954) inclined load on B′ = B − 2|M|/V
  (:func:`upliftlab.continuum.statics.combined.green_effective_width`): the ratio of the
  point's distance from the origin to the bound's (≥ 1: outside it, as a lower bound must
  leave the true section);
- with the macro-element's section (:mod:`upliftlab.reduced.laws.macro.capacity`: the
  effective-width moment capacity, elliptic in (H, M) with H_max = t_h V (1 − V/V_ult),
  t_h = 4/(2 + π) through Green's peak), of the clay with c*: the same ratio (1: on it).

Cost model: a probe of 12 steps about 1.5 s on 8 across and 12 s on 16 (this machine,
measured); 7 probes per V. Writes ``HM_ENVELOPE.md`` to ``--out`` (default
``results/bench/hm_envelope``); ``--write`` also the committed table. ``--quick``: 4 across,
v = 0.5 (the tests' path).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, output_folder,  # noqa: E402
                          run_sections, write_text)

NAME = "hm_envelope"
B, CU = 2.0, 50.0
DIRECTIONS = np.linspace(0.0, math.pi, 7)
REACH, STEPS = 0.1, 12
SECONDS_PER_PROBE = {4: 0.5, 8: 1.5, 16: 12.0}


def bound_ratio(h: float, m: float, V: float, c: float) -> float:
    """|(h, m)| over the Green–effective-width section's along the same ray (normalised
    (H/(c B), M/(c B²)); by symmetry the ray's |h|, |m|)."""
    from scipy.optimize import brentq

    from upliftlab.continuum.statics.combined import green_effective_width

    narrowest = V / ((2.0 + math.pi) * c)
    angle = math.atan2(abs(m), abs(h))

    def point(reduced):
        H, M = green_effective_width(V, c, B, [reduced])
        return float(H[0]) / (c * B), float(M[0]) / (c * B * B)

    def gap(reduced):
        hb, mb = point(reduced)
        return math.atan2(mb, hb) - angle

    low, high = narrowest * (1.0 + 1e-12), B
    if gap(low) * gap(high) > 0.0:  # the ray meets the section at an end
        hb, mb = point(low if abs(gap(low)) < abs(gap(high)) else high)
    else:
        hb, mb = point(brentq(gap, low, high, xtol=1e-12))
    return math.hypot(h, m) / math.hypot(hb, mb)


def element_ratio(H: float, M: float, V: float, c: float) -> float:
    """The factor λ that puts (λ H, λ M) on the macro-element's section at V (1/λ: how far
    outside it the point is, as a ratio of distances along the ray)."""
    from scipy.optimize import brentq

    from upliftlab.reduced.laws.macro import MacroElement
    from upliftlab.reduced.laws.macro.capacity import failure_function

    law = MacroElement(width=B, vertical_stiffness=1.0, horizontal_stiffness=1.0,
                       rocking_stiffness=1.0, cohesion=c)
    f = lambda s: failure_function(law, np.array([V, s * H, s * M]))  # noqa: E731
    s = brentq(f, 1e-6, 10.0, xtol=1e-12)
    return 1.0 / s


def measure(across: int, v_ratios) -> dict:
    from upliftlab.continuum import hm_envelope, make_model
    from upliftlab.continuum.statics.analyses import vertical_pushover
    from upliftlab.scenes import ContinuumOptions, Soil

    soil = Soil(youngs_modulus=50e3, poisson_ratio=0.3, density=1.8, model="tresca",
                undrained_strength=CU, interface="coulomb", interface_friction=1.0)
    model = make_model(soil, B, ContinuumOptions(elements_across=across))
    V_ult = vertical_pushover(model, np.linspace(0.01, 0.1, 10)).capacity
    c = V_ult / ((2.0 + math.pi) * B)
    rows = []
    for v in v_ratios:
        V = v * V_ult
        env = hm_envelope(model, V, DIRECTIONS, REACH, STEPS)
        for phi, H, M, probe in zip(env.directions, env.H, env.M, env.probes):
            h, m = H / (c * B), M / (c * B * B)
            rows.append({"v": v, "phi": phi, "h": h, "m": m,
                         "bound": bound_ratio(h, m, V, c),
                         "element": element_ratio(H, M, V, c),
                         "last_step": max(abs(probe.H[-1] / probe.H[-2] - 1.0)
                                          if abs(probe.H[-2]) > 1e-9 * c * B else 0.0,
                                          abs(probe.M[-1] / probe.M[-2] - 1.0)
                                          if abs(probe.M[-2]) > 1e-9 * c * B * B else 0.0)})
    return {"across": across, "dofs": int(model.dofs), "V_ult": V_ult, "c": c, "rows": rows}


def publish(folder: Path, done: dict, missing: dict) -> None:
    lines = ["# The continuum's H–M section at constant V on the clay",
             "", "Command `python benchmarks/hm_envelope.py`; what is run and compared: the "
             "script's docstring. h = H/(c* B), m = M/(c* B²) with c* = V_ult/((2 + π) B) of "
             "each mesh; φ the probe's direction in (u, B θ); 'bound' the point's distance "
             "over the Green–effective-width lower bound's along its ray (Houlsby and Puzrin "
             "1999: ≥ 1 outside it); 'element' over the macro-element's section (1: on it); "
             "'last step' the probe's largest relative change of H or M over its last step "
             "(how flat it ended).", ""]
    for key in sorted(done):
        r = done[key]
        lines += [f"## {r['across']} elements across ({r['dofs']} DOFs)", "",
                  f"V_ult = {r['V_ult']:.2f} kN/m (c* = {r['c']:.3f} kPa).", "",
                  "| v | φ (°) | h | m | bound | element | last step |",
                  "|---|---|---|---|---|---|---|"]
        for row in r["rows"]:
            lines.append(f"| {row['v']:g} | {math.degrees(row['phi']):.0f} | {row['h']:+.4f} "
                         f"| {row['m']:+.4f} | {row['bound']:.3f} | {row['element']:.3f} | "
                         f"{row['last_step']:.1e} |")
        lines.append("")
    for key, why in missing.items():
        lines += [f"({key}: not measured: {why})", ""]
    write_text(folder / "HM_ENVELOPE.md", "\n".join(lines))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_output_arguments(parser, NAME)
    parser.add_argument("--meshes", default="8,16")
    parser.add_argument("--v", default="0.25,0.5,0.75")
    parser.add_argument("--quick", action="store_true", help="4 across, v = 0.5")
    args = parser.parse_args(argv)
    try:
        meshes = [int(x) for x in args.meshes.split(",")]
        v_ratios = [float(x) for x in args.v.split(",")]
    except ValueError:
        parser.error(f"--meshes {args.meshes!r} / --v {args.v!r}: comma-separated numbers")
    if any(n not in SECONDS_PER_PROBE for n in meshes):
        parser.error(f"--meshes: {args.meshes!r}; valid: {', '.join(map(str, SECONDS_PER_PROBE))}")
    if not all(0.0 < v < 1.0 for v in v_ratios):
        parser.error(f"--v: {args.v!r}; valid range is (0, 1)")
    if args.quick:
        if args.write:
            parser.error("--write: a quick run never updates the committed table")
        meshes, v_ratios = [4], [0.5]
    folder = output_folder(args, NAME)
    sections = [Section(f"mesh {n:02d}", lambda n=n: measure(n, v_ratios),
                        SECONDS_PER_PROBE[n] * len(DIRECTIONS) * len(v_ratios))
                for n in meshes]

    def commit(done):
        write_text(HERE / "HM_ENVELOPE.md", (folder / "HM_ENVELOPE.md").read_text())

    return run_sections(NAME, sections, publish, folder, commit=commit if args.write else None,
                        model="a probe 1.5 s on 8 across, 12 s on 16")


if __name__ == "__main__":
    raise SystemExit(main())
