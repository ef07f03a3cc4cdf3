"""The half-plane's stiffness at each map structure's rocking frequency, against the box's
statics the beds are calibrated to today (issue 35 §1).

    python benchmarks/halfplane_stiffness.py [--store DIR] [--across N] [--quick] [--out DIR]
                                             [--write]

For every structure of the Winkler map's full grid (clay and sand, FS_v 2–10, h/B 1–2.5,
T 0.2 and 0.5 s; N = V_ult/FS_v with the soil's V_ult from the kept store's statics) it finds
the rocking frequency ω̃ on the soil's PML half-plane impedance
(:func:`upliftlab.comparisons.beds.rocking_stiffness.rocking_stiffness`: the flexible-base
fixed point with the map's rotary inertia, the footing held horizontally) and reports
Re K_v(ω̃) and Re K_r(ω̃) against the box's static K_v and K_r (the map's 20 m box), the target
K_r/K_v an end-stiffened bed would need, and what the beds give: the end-stiffened bed's K_v at
the largest R_k (``max_end_stiffness_ratio``) and the uniform bed's, both calibrated to K_r(ω̃),
over K_v(ω̃). The impedance is computed here on ``--across`` elements (default 16, the map's;
``--quick`` 8, whose Re K_v and Re K_r are within 0.07 % and 0.45 % of the exact half-plane at
a0 ≤ 0.5, measured), in the map's PML box and frequencies
(:mod:`upliftlab.comparisons.studies.winkler_map.impedance_points`).

Writes ``HALFPLANE_STIFFNESS.md`` and ``halfplane_stiffness.json`` to ``--out`` (default
``results/bench/halfplane_stiffness``); ``--write`` also the committed
``benchmarks/HALFPLANE_STIFFNESS.md``. Cost: one impedance per soil (1–4 s on 8 across, 2–110 s on
16 across, from an idle to a loaded machine), the rest milliseconds.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import replace
from datetime import date
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, incomplete_note,  # noqa: E402
                          missing_section, output_folder, run_sections, write_text)

NAME = "halfplane_stiffness"


def _statics(soil: str, store, options):
    """The soil's box statics (:class:`SoilStatics`), read from the kept store."""
    from upliftlab.comparisons.beds import base_table
    from upliftlab.comparisons.studies.winkler_map.plan import point_key_of
    from upliftlab.comparisons.studies.winkler_map.statics import (evaluate_static,
                                                                   soil_statics, static_points)

    b = base_table()["foundation"]["half_width"]
    records = [store.get(point_key_of(p, evaluate_static))
               for p in static_points(soil, options, b)]
    if any(r is None for r in records):
        raise SystemExit(f"{NAME}: error: the store {store.root} does not hold the {soil}'s "
                         f"statics on {options.elements_across} across; give --store")
    return soil_statics(soil, records)


def _impedance(soil: str, options) -> dict:
    """The soil's impedance computed on ``options``' mesh (the map's PML box and frequencies)
    and its wall time (s)."""
    from upliftlab.comparisons.beds import base_table
    from upliftlab.comparisons.studies.winkler_map.impedance_points import (
        evaluate_impedance, impedance_point, soil_impedance)

    point = impedance_point(soil, options, base_table()["foundation"]["half_width"])
    started = time.perf_counter()
    imp = soil_impedance(point, evaluate_impedance(point))
    return {"impedance": imp, "seconds": time.perf_counter() - started}


def measure(soil: str, data: dict, grid, options) -> list[dict]:
    """One row per structure of the grid on ``soil``."""
    from upliftlab.comparisons.beds import base_table, end_stiffening
    from upliftlab.comparisons.beds.rocking_stiffness import rocking_stiffness
    from upliftlab.comparisons.studies.winkler_map.points import point_table
    from upliftlab.reduced.compatibility import end_stiffened_bed, winkler_bed
    from upliftlab.scenes import load_scene

    base = base_table()
    b, g = base["foundation"]["half_width"], load_scene("strip_footing_clay").g
    n, R_e, R_max = options.springs, options.end_length, options.max_end_stiffness_ratio
    uniform = winkler_bed(b, 1.0, n).rocking_stiffness
    stiff_max = end_stiffened_bed(b, 1.0, n, R_max, R_e)
    es_ratio = stiff_max.rocking_stiffness / stiff_max.vertical_stiffness
    st, imp = data["statics"], data["impedance"]
    rows = []
    for fs in grid.fs_v:
        for hb in grid.h_over_B:
            for T in grid.periods:
                s = point_table(base, soil, options.elements_across, st.V_ult / fs, hb, T,
                                g)["structure"]
                at = rocking_stiffness(imp, mass=s["weight"] / g, period=T, height=s["height"],
                                       rotary_inertia=s["rotary_inertia"])
                target = at.K_r / at.K_v
                es = end_stiffening(target, b, n, R_e, R_max)
                rows.append({"soil": soil, "fs_v": fs, "h_over_B": hb, "period": T,
                             "omega": at.omega, "a0": at.a0, "period_flexible": at.period,
                             "iterations": at.iterations, "K_v": at.K_v, "K_r": at.K_r,
                             "K_v_box": st.K_v, "K_r_box": st.K_r, "target": target,
                             "reachable": es.feasible,
                             "es_K_v": at.K_r / es_ratio / at.K_v,
                             "uniform_K_v": at.K_r / uniform / at.K_v})
    return rows


def document(rows: list[dict], soils: dict, options, missing: dict, command: str) -> str:
    """HALFPLANE_STIFFNESS.md."""
    b2 = 1.0
    out = ["# The half-plane's stiffness at the rocking frequency, against the box's statics", "",
           f"Measured {date.today().isoformat()}; command `{command}`. What each column is: "
           "the script's docstring. K_v,box and K_r,box: the map's 20 m box statics (kept "
           "store); K(ω̃): Re K of the PML half-plane impedance on "
           f"{options.elements_across} across at the structure's rocking frequency ω̃ (a0 = "
           "ω̃ b/V_s, T̃ = 2π/ω̃). 'ES reaches both': an end-stiffened bed with R_k ≤ "
           f"{options.max_end_stiffness_ratio:g} matching K_v(ω̃) and K_r(ω̃); any bed under "
           f"the footing has K_r/K_v ≤ b² = {b2:g} m².", ""]
    if missing:
        out += [incomplete_note(missing).strip(), ""]
    for soil, d in soils.items():
        st = d["statics"]
        out.append(f"- {soil}: K_v,box = {st.K_v:,.0f} kN/m/m, K_r,box = {st.K_r:,.0f} kN m/rad/m "
                   f"(K_r/K_v = {st.K_r / st.K_v:.3f} m²), V_ult = {st.V_ult:.1f} kN/m; "
                   f"impedance {d['seconds']:.1f} s")
    out += ["", "| soil | FS_v | h/B | T (s) | ω̃ (rad/s) | a0 | T̃ (s) | K_v(ω̃)/K_v,box | "
            "K_r(ω̃)/K_r,box | K_r/K_v at ω̃ (m²) | ES reaches both | ES K_v/K_v(ω̃) at R_k,max "
            "| U K_v/K_v(ω̃) |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['soil']} | {r['fs_v']:g} | {r['h_over_B']:g} | {r['period']:g} | "
                   f"{r['omega']:.2f} | {r['a0']:.3f} | {r['period_flexible']:.3f} | "
                   f"{r['K_v'] / r['K_v_box']:.3f} | {r['K_r'] / r['K_r_box']:.3f} | "
                   f"{r['target']:.3f} | {'yes' if r['reachable'] else 'no'} | "
                   f"{r['es_K_v']:.2f} | {r['uniform_K_v']:.2f} |")
    if rows:
        col = lambda k: [r[k] for r in rows]  # noqa: E731
        ratio = [r["K_v"] / r["K_v_box"] for r in rows]
        out += ["", f"Over the {len(rows)} structures: a0 {min(col('a0')):.3f}–"
                f"{max(col('a0')):.3f}; K_v(ω̃)/K_v,box {min(ratio):.3f}–{max(ratio):.3f}; "
                f"K_r/K_v at ω̃ {min(col('target')):.3f}–{max(col('target')):.3f} m²; the "
                f"end-stiffened bed reaches both at {sum(col('reachable'))}; its K_v is "
                f"{min(col('es_K_v')):.2f}–{max(col('es_K_v')):.2f} × K_v(ω̃), the uniform "
                f"bed's {min(col('uniform_K_v')):.2f}–{max(col('uniform_K_v')):.2f} ×."]
    return "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    from upliftlab.comparisons.framework.store import Store
    from upliftlab.comparisons.studies import winkler_map as wm

    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--store", default=str(HERE / "winkler_map_store"),
                   help="the store holding the map's statics (default: the kept store)")
    p.add_argument("--across", type=int, default=None,
                   help="elements across B of the impedance (default 16, the map's)")
    p.add_argument("--quick", action="store_true", help="8 across (a smoke check)")
    add_output_arguments(p, NAME)
    args = p.parse_args(argv)
    out = output_folder(args, NAME)
    grid = wm.FULL_GRID
    options = wm.FULL_OPTIONS
    across = args.across or (8 if args.quick else options.elements_across)
    store = Store(args.store)
    given = [a for a in (argv if argv is not None else sys.argv[1:])]
    if "--out" in given:  # the folder is the machine's, not part of the measurement
        i = given.index("--out")
        del given[i:i + 2]
    command = " ".join(["python benchmarks/halfplane_stiffness.py", *given])
    soils: dict = {}
    rows: list[dict] = []

    def soil_section(soil: str) -> bool:
        data = {"statics": _statics(soil, store, options),  # the map's statics (16 across)
                **_impedance(soil, replace(options, elements_across=across))}
        soils[soil] = data
        rows.extend(measure(soil, data, grid, options))
        return True

    def publish(folder: Path, done: dict, missing: dict) -> None:
        shown = replace(options, elements_across=across)
        write_text(folder / "HALFPLANE_STIFFNESS.md", document(rows, soils, shown, missing,
                                                                command))
        write_text(folder / f"{NAME}.json", json.dumps(rows, indent=1) + "\n")

    def commit(done: dict) -> None:
        write_text(HERE / "HALFPLANE_STIFFNESS.md",
                   document(rows, soils, replace(options, elements_across=across), {}, command))

    sections = [Section(soil, lambda soil=soil: soil_section(soil)) for soil in grid.soils]
    return run_sections(NAME, sections, publish, out, commit=commit if args.write else None)


if __name__ == "__main__":
    sys.exit(main())
