"""Impedance of the rigid strip: the FE (PML or Lysmer box) against the exact half-plane and the
Gazetas (1991) handbook formulas; box-size sensitivity; mesh convergence; the time-domain
rocking decay; the contact length measured where contact ends.

    python benchmarks/impedance.py [--out results/bench/impedance] [--write] [--quick]

Sections, each written to ``--out`` (default ``results/bench/impedance``) as ``impedance.json``,
``IMPEDANCE.md`` and ``figures/impedance.png`` as soon as it ends (``bench_output``): the
impedance tables, the box sensitivity, the mesh convergence, the rocking decay, the contact
length, geofound's cross-check and the figure. ``--write`` also rewrites the committed
``benchmarks/IMPEDANCE.md`` and ``benchmarks/figures/impedance.png``, once every section has
completed. ``--quick`` runs a reduced set (for a smoke check: one ν and interface, two boxes and
one Lysmer box, 8 and 16 across, the decay on 8 across) and cannot be committed.
Runtimes are single runs on a shared machine (one thread): compare ratios. If geofound is
installed, its Gazetas strip dashpots are tabulated beside the exact ones (a cross-check of what
a public code computes); otherwise that table says so.

Cost model (the estimate printed before any work): each planned row costs the runtime recorded
for the same row in the committed ``benchmarks/IMPEDANCE.md``: the solves alone, so the estimate
is a lower bound (meshing, the PML and the references add to it: on 2026-11-28, 1.4 min
estimated, 2.3 min run); a row that table does not record has no estimate.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
from datetime import date
from pathlib import Path

import numpy as np

from upliftlab.continuum import OPEN, build_model, make_model, rotation_pushover, run_dynamic
from upliftlab.continuum.dynamics.run import DynamicOptions
from upliftlab.continuum.impedance.gazetas import handbook_strip, lysmer_analog_velocity
from upliftlab.continuum.impedance.halfplane import strip_impedance
from upliftlab.continuum.impedance.analysis import ImpedanceOptions, impedance, impedance_model
from upliftlab.continuum.impedance.output import impedance_errors, impedance_figure, reference_for
from upliftlab.motions import free_vibration
from upliftlab.scenes import ContinuumOptions, Soil, load_scene

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (HERE, Section, add_output_arguments, committed_tables,  # noqa: E402
                          incomplete_note, missing_section, number, output_folder, run_sections,
                          save_figure, write_text)

NAME = "impedance"
E, RHO, B = 50e3, 1.8, 2.0
TABLE_A0 = (0.1, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0)
BOX_A0 = (0.1, 0.25, 0.5, 1.0, 1.5, 2.0)
STARTED = time.perf_counter()


def say(message: str) -> None:
    print(f"[{time.perf_counter() - STARTED:7.1f} s] {message}", file=sys.stderr, flush=True)


def soil(nu, interface="frictionless"):
    return Soil(youngs_modulus=E, poisson_ratio=nu, density=RHO, interface=interface)


def run(nu, interface, n=16, **options):
    opts = ImpedanceOptions(**options)
    model = impedance_model(soil(nu, interface), B, ContinuumOptions(elements_across=n), opts)
    started = time.perf_counter()
    imp = impedance(model, opts)
    return imp, time.perf_counter() - started


def worst(imp) -> dict:
    return {m: float(np.max(e)) for m, e in impedance_errors(imp, reference_for(imp)).items()}


# ---------------------------------------------------------------------------------------------


#: What each section runs: the full benchmark and ``--quick``.
FULL = {"table": [(nu, i) for nu in (0.25, 1 / 3) for i in ("frictionless", "bonded")],
        "pml": [(6, 3, 1.5), (8, 4, 2.0), (10, 5, 2.5), (14, 7, 3.5), (20, 10, 5.0)],
        "lysmer": [(10, 5), (20, 10), (40, 20), (80, 40)], "mesh": (4, 8, 12, 16, 24),
        "decay": (4, 8, 16), "contact": (8, 16, 32)}
QUICK = {"table": [(0.25, "bonded")], "pml": FULL["pml"][:2], "lysmer": FULL["lysmer"][:1],
         "mesh": (8, 16), "decay": (8,), "contact": (8, 16)}


def impedance_tables(cases) -> list[dict]:
    """k_j, c_j of FE, exact and handbook per a0, for each (ν, interface) of ``cases``."""
    rows = []
    for nu, interface in cases:
        say(f"impedance table ν = {nu:.3g}, {interface}")
        imp, seconds = run(nu, interface, a0=TABLE_A0)
        ref = reference_for(imp)
        G = E / (2 * (1 + nu))
        book = handbook_strip(imp.a0, shear_modulus=G, poisson=nu, density=RHO, width=B)
        norm = imp.normalisers()
        for k, a0 in enumerate(imp.a0):
            row = {"nu": nu, "interface": interface, "a0": float(a0), "runtime_s": seconds,
                   "dofs": imp.dofs}
            for mode, (i, j) in {"v": (1, 1), "h": (0, 0), "r": (2, 2), "hr": (0, 2)}.items():
                exact = ref.matrix[k, i, j]
                if exact == 0:
                    continue
                fe = imp.matrix[k, i, j]
                row[f"k_{mode}"] = fe.real / norm[mode]
                row[f"c_{mode}"] = fe.imag / (a0 * norm[mode])
                row[f"k_{mode}_exact"] = exact.real / norm[mode]
                row[f"c_{mode}_exact"] = exact.imag / (a0 * norm[mode])
                row[f"err_{mode}"] = abs(fe - exact) / abs(exact)
                if mode != "hr":
                    hb = book.impedance(mode)[k]
                    row[f"k_{mode}_gazetas"] = hb.real / norm[mode]
                    row[f"c_{mode}_gazetas"] = hb.imag / (a0 * norm[mode])
            rows.append(row)
    return rows


def box_sensitivity(pml, lysmer) -> list[dict]:
    """Largest error over a0 per mode against the box, PML (width, depth, layer in B) and
    Lysmer (width, depth in B), bonded ν = 1/3."""
    rows = []
    for w, d, layer in pml:
        say(f"box: PML {w}B x {d}B, layer {layer}B")
        imp, seconds = run(1 / 3, "bonded", a0=BOX_A0, domain_width=w, domain_depth=d,
                           pml_thickness=layer)
        rows.append({"boundary": "pml", "box": f"{w}B × {d}B, layer {layer}B",
                     "dofs": imp.dofs, "runtime_s": seconds, **_errors_by_band(imp)})
    for w, d in lysmer:
        say(f"box: Lysmer {w}B x {d}B")
        imp, seconds = run(1 / 3, "bonded", a0=BOX_A0, boundary="lysmer", domain_width=w,
                           domain_depth=d)
        rows.append({"boundary": "lysmer", "box": f"{w}B × {d}B", "dofs": imp.dofs,
                     "runtime_s": seconds, **_errors_by_band(imp)})
    return rows


def _errors_by_band(imp) -> dict:
    errors = impedance_errors(imp, reference_for(imp))
    low = imp.a0 <= 0.5
    out = {}
    for mode, e in errors.items():
        out[f"{mode}_low"] = float(np.max(e[low]))
        out[f"{mode}_all"] = float(np.max(e))
    return out


def mesh_convergence(levels) -> list[dict]:
    """Largest error over a0 per mode on ``levels`` elements across B, bonded ν = 1/3."""
    rows = []
    for n in levels:
        say(f"mesh: {n} across")
        imp, seconds = run(1 / 3, "bonded", n=n, a0=BOX_A0)
        rows.append({"n": n, "dofs": imp.dofs, "runtime_s": seconds, **worst(imp)})
    return rows


DECAY = ["soil.model=elastic", "structure.weight=1.0", "structure.vertical_weight=171.39",
         "structure.period=0.01", "structure.height=2.0", "structure.rotary_inertia=14.0",
         "structure.damping_ratio=0.05", "continuum.domain_width=30",
         "continuum.domain_depth=25"]


def rocking_decay(levels) -> list[dict]:
    """The time-domain free rocking decay against the root predicted from K_r(ω), on
    ``levels`` elements across B, on the implicit route with Newmark's average acceleration
    (α = 0: no numerical damping beside the radiation damping that is measured)."""
    from scipy.optimize import least_squares

    rows = []
    for n in levels:
        say(f"rocking decay, {n} across")
        scene = load_scene("strip_footing_clay",
                           overrides=DECAY + [f"continuum.elements_across={n}"])
        started = time.perf_counter()
        result = run_dynamic(build_model(scene), scene,
                             free_vibration(0.48, 0.005, velocity=0.01),
                             DynamicOptions(method="implicit", scheme="newmark",
                                            sides="lysmer", base="rigid", snapshots=0,
                                            energy=False))
        seconds = time.perf_counter() - started
        t, theta = result.time, result.theta
        w = t >= 0.1
        fit = least_squares(lambda p: p[0] * np.exp(-p[1] * t[w]) * np.cos(p[2] * t[w] + p[3])
                            - theta[w], [np.max(np.abs(theta)), 3.0, 50.0, 0.0])
        row = {"n": n, "runtime_s": seconds, "omega": float(fit.x[2]),
               "sigma": float(fit.x[1]), "contact_lost": bool((result.status == OPEN).any())}
        for source in ("fe", "exact"):
            root = _root(scene, n, source == "exact")
            row[f"omega_{source}"], row[f"sigma_{source}"] = root.real, root.imag
        rows.append(row)
    return rows


def _root(scene, n, exact):
    st = scene.structure
    story = st.stories[0]
    m, h, k = story.weight / scene.g, story.height, story.stiffness
    c = 2 * st.damping_ratio * math.sqrt(k * m)
    options = ImpedanceOptions(a0=tuple(np.linspace(0.3, 0.7, 9)))
    imp = impedance(impedance_model(scene.soil, B, ContinuumOptions(elements_across=n), options),
                    options)
    K_r = reference_for(imp).rocking if exact else imp.K_r
    coef = np.polyfit(imp.omega, K_r, 3)

    def det(w):
        return (np.polyval(coef, w) - w * w * (st.rotary_inertia + m * h * h)) \
            * (k + 1j * w * c - w * w * m) - w ** 4 * (m * h) ** 2

    w = complex(imp.omega[4])
    for _ in range(40):
        d = 1e-6 * abs(w)
        w -= det(w) / ((det(w + d) - det(w - d)) / (2 * d))
    return w


def contact_length(levels) -> list[dict]:
    """Contact length after onset against 4(B/2 − e), in node spacings B/(2n), on ``levels``
    elements across B."""
    rows = []
    nu, N = 0.3, 171.39
    G = E / (2 * (1 + nu))
    theta_on = 2 * N * (1 - nu) / (math.pi * G * B)
    ratios = np.concatenate(([0.5], np.linspace(1.05, 10.0, 24)))
    for n in levels:
        say(f"contact length, {n} across")
        started = time.perf_counter()
        model = make_model(Soil(youngs_modulus=E, poisson_ratio=nu, density=RHO), B,
                           ContinuumOptions(elements_across=n))
        path = rotation_pushover(model, N, ratios * theta_on)
        e = path.M / path.N
        after = e > B / 4
        spacing = B / (2 * n)
        midpoint = np.array([model.footing.contact_length(s != OPEN) for s in path.status])
        new = (path.contact_length - 4 * (B / 2 - e))[after] / spacing
        old = (midpoint - 4 * (B / 2 - e))[after] / spacing
        rows.append({"n": n, "runtime_s": time.perf_counter() - started,
                     "steps": int(after.sum()), "max": float(np.max(np.abs(new))),
                     "rms": float(np.sqrt(np.mean(new ** 2))),
                     "max_midpoint": float(np.max(np.abs(old))),
                     "rms_midpoint": float(np.sqrt(np.mean(old ** 2)))})
    return rows


def geofound_crosscheck() -> dict:
    """geofound's Gazetas strip dashpots (if installed) against the exact ones."""
    try:
        import importlib.metadata

        import sfsimodels
        from geofound.damping import gazetas_1991 as gd
    except ImportError:
        return {"available": False}
    rows = []
    for nu in (0.25, 1 / 3, 0.45):
        G = E / (2 * (1 + nu))
        sl = sfsimodels.Soil()
        sl.g_mod, sl.poissons_ratio, sl.unit_dry_weight = G * 1e3, nu, RHO * 1e3 * 9.8
        fd = sfsimodels.RaftFoundation()
        fd.width, fd.length, fd.depth, fd.height, fd.ip_axis = B, 100.0, 0.0, 1.0, "width"
        exact = strip_impedance(BOX_A0[2:], shear_modulus=G, poisson=nu, width=B,
                                interface="bonded")
        vs = math.sqrt(G / RHO)
        omega = np.asarray(BOX_A0[2:]) * vs / (B / 2)
        for k, a0 in enumerate(BOX_A0[2:]):
            c_h = gd.calc_horz_strip_via_gazetas_1991(sl, fd, a0, ip_axis="width") / 1e3
            rows.append({"nu": nu, "a0": a0, "C_h_geofound": c_h,
                         "cy_geofound": c_h / (RHO * vs * B),
                         "cy_exact": float(exact.horizontal[k].imag / omega[k]) / (RHO * vs * B),
                         "C_h_exact": float(exact.horizontal[k].imag / omega[k]),
                         "C_v_geofound": gd.calc_vert_strip_via_gazetas_1991(
                             sl, fd, a0, ip_axis="width") / 1e3,
                         "C_v_exact": float(exact.vertical[k].imag / omega[k])})
    return {"available": True, "version": importlib.metadata.version("geofound"), "rows": rows}


# ---------------------------------------------------------------------------------------------


def header(data: dict) -> str:
    return ("# Impedance of the rigid strip\n\n"
            f"`python benchmarks/impedance.py{' --quick' if data['quick'] else ''}`, "
            f"{data['date']}, {data['machine']}, one thread. "
            "Soil E = 50 MPa, ρ = 1.8 t/m³, B = 2 m; Q2, 16 elements across B, PML box 6B × 3B "
            "with a 1.5B layer unless stated. Errors are |K − K_exact|/|K_exact|, the exact "
            "impedance from `upliftlab.continuum.impedance.halfplane` (Chebyshev–Galerkin on the "
            "half-plane's Green's function, no FE). K_j = K_j,static [k_j + i a0 c_j], "
            "a0 = ω B/(2V_s); K_static: rocking πGB²/(8(1 − ν)), vertical 0.73G/(1 − ν), "
            "horizontal 2G/(2 − ν) (Gazetas 1991's strip limits; the 2D static K_v, K_h do not "
            "exist), coupling √(K_h K_r). Gazetas: the closed forms of Gazetas (1991, Table 1, "
            "L/B → ∞): static K_j, k_r = 1 − 0.2 a0, k_v = k_h = 1 (charts not reproduced), "
            "dashpots ρV_La B, ρV_s B, ρV_La I (c̃ = 1). DOFs: the unknowns of the harmonic "
            "solve (the soil's DOFs less the PML's fixed back).\n")


def table_text(rows: list[dict]) -> str:
    out = []
    for (nu, interface) in sorted({(r["nu"], r["interface"]) for r in rows}):
        mine = [r for r in rows if r["nu"] == nu and r["interface"] == interface]
        modes = [m for m in ("v", "h", "r", "hr") if f"k_{m}" in mine[0]]
        out.append(f"\n## ν = {nu:.3g}, {interface} ({mine[0]['dofs']} DOFs, "
                   f"{len(mine)} frequencies in {mine[0]['runtime_s']:.1f} s)\n")
        head = "| a0 | " + " | ".join(
            f"k_{m} FE / exact{' / Gazetas' if m != 'hr' else ''} | "
            f"c_{m} FE / exact{' / Gazetas' if m != 'hr' else ''} | err {m}" for m in modes)
        out += [head + " |", "|---" * (1 + 3 * len(modes)) + "|"]
        for r in mine:
            cells = [f"{r['a0']:.2f}"]
            for m in modes:
                g = m != "hr"
                cells.append(f"{r[f'k_{m}']:.3f} / {r[f'k_{m}_exact']:.3f}"
                             + (f" / {r[f'k_{m}_gazetas']:.3f}" if g else ""))
                cells.append(f"{r[f'c_{m}']:.3f} / {r[f'c_{m}_exact']:.3f}"
                             + (f" / {r[f'c_{m}_gazetas']:.3f}" if g else ""))
                cells.append(f"{100 * r[f'err_{m}']:.2f} %")
            out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def box_text(rows: list[dict]) -> str:
    out = ["Largest error over a0 ≤ 0.5 and over a0 = 0.1 … 2 (BOX_A0).\n",
           "| boundary | box | DOFs | runtime | K_v ≤ 0.5 / all | K_h ≤ 0.5 / all | "
           "K_r ≤ 0.5 / all | K_hr ≤ 0.5 / all |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [r["boundary"], r["box"], str(r["dofs"]), f"{r['runtime_s']:.1f} s"]
        for m in ("v", "h", "r", "hr"):
            cells.append(f"{100 * r[f'{m}_low']:.2f} / {100 * r[f'{m}_all']:.2f} %")
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def mesh_text(rows: list[dict]) -> str:
    out = ["| across B | DOFs | runtime (6 frequencies) | K_v | K_h | K_r | K_hr |",
           "|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['n']} | {r['dofs']} | {r['runtime_s']:.1f} s | "
                   + " | ".join(f"{100 * r[m]:.2f} %" for m in ("v", "h", "r", "hr")) + " |")
    return "\n".join(out)


def decay_text(rows: list[dict]) -> str:
    out = ["Footing I₀ = 14 t m²/m, story 1 kN/m at 2 m (T = 0.01 s), frictionless, "
           "elastic clay; implicit route, Newmark, Lysmer sides, rigid base 25B down (its P "
           "reflection returns after the 0.1–0.48 s window). θ(t) = A e^{−σt} cos(ω_d t + φ) "
           "fitted, against the complex root ω_d + iσ of the footing–story system with K_r(ω) "
           "of the impedance analysis (same elements across) and of the exact half-plane.\n",
           "| across B | runtime | ω_d time domain | ω_d from FE K_r | ω_d exact | "
           "σ time domain | σ from FE K_r | σ exact |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['n']} | {r['runtime_s']:.1f} s | {r['omega']:.3f} | "
                   f"{r['omega_fe']:.3f} ({100 * (r['omega'] / r['omega_fe'] - 1):+.2f} %) | "
                   f"{r['omega_exact']:.3f} ({100 * (r['omega'] / r['omega_exact'] - 1):+.2f} %)"
                   f" | {r['sigma']:.4f} | {r['sigma_fe']:.4f} "
                   f"({100 * (r['sigma'] / r['sigma_fe'] - 1):+.2f} %) | {r['sigma_exact']:.4f} "
                   f"({100 * (r['sigma'] / r['sigma_exact'] - 1):+.2f} %) |")
    return "\n".join(out)


def contact_text(rows: list[dict]) -> str:
    out = ["| across B | runtime | steps after onset | largest (separation point) | rms | "
           "largest (midpoint rule) | rms |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['n']} | {r['runtime_s']:.1f} s | {r['steps']} | {r['max']:.2f} | "
                   f"{r['rms']:.2f} | {r['max_midpoint']:.2f} | {r['rms_midpoint']:.2f} |")
    return "\n".join(out)


def geofound_text(geo: dict) -> str:
    if not geo["available"]:
        return "geofound is not installed: not run."
    out = [f"geofound {geo['version']} (`geofound/damping/gazetas_1991.py`): "
           "`calc_horz_strip_via_gazetas_1991` interpolates between "
           "`get_cy_gazetas_v_e_0p3` and `get_cy_gazetas_v_e_0p3` (the ν = 0.3 table "
           "at both ends), so its horizontal strip dashpot is the same at every ν. "
           "kN s/m² per m, bonded exact.\n",
           "| ν | a0 | c̃_y = C_h/(ρV_sB) geofound | exact | C_h geofound | C_h exact | "
           "C_v geofound | C_v exact |", "|---|---|---|---|---|---|---|---|"]
    for r in geo["rows"]:
        out.append(f"| {r['nu']:.3g} | {r['a0']:g} | {r['cy_geofound']:.3f} | "
                   f"{r['cy_exact']:.3f} | {r['C_h_geofound']:.1f} | "
                   f"{r['C_h_exact']:.1f} | {r['C_v_geofound']:.1f} | "
                   f"{r['C_v_exact']:.1f} |")
    return "\n".join(out)


#: Section key: (heading of its table in IMPEDANCE.md, renderer); the tables section brings
#: its own headings (one per ν and interface).
TEXTS = {"table": ("## Impedance tables", table_text),
         "box": ("## Box-size sensitivity (bonded, ν = 1/3, 16 across)", box_text),
         "mesh": ("## Mesh convergence (bonded, ν = 1/3, PML 6B × 3B)", mesh_text),
         "decay": ("## Free rocking decay in the time domain", decay_text),
         "contact": ("## Contact length after uplift against 4(B/2 − e), in node spacings "
                     "B/(2n)", contact_text),
         "geofound": ("## A public code: geofound's Gazetas strip dashpots", geofound_text)}


def markdown(data: dict, done: dict, missing: dict) -> str:
    """IMPEDANCE.md: the header, a note naming the sections that did not complete, then each
    section's tables (or its stand-in)."""
    blocks = [header(data), incomplete_note(missing)]
    for key, (title, render) in TEXTS.items():
        if key in done:
            text = render(done[key]).strip()
            blocks.append(text if key == "table" else f"{title}\n\n{text}")
        elif key in missing:
            blocks.append(missing_section(title, key, missing))
    blocks.append(f"V_La/V_p: {data['vla_over_vp']}")
    return "\n\n".join(b.strip() for b in blocks if b.strip()) + "\n"


def figure_run():
    """The impedance of the figure: ν = 0.3, bonded, 16 across, the default frequencies."""
    imp, _ = run(0.3, "bonded")
    return imp


def publisher(data: dict):
    """Writes impedance.json, IMPEDANCE.md and figures/impedance.png into a folder."""
    def publish(folder: Path, done: dict, missing: dict) -> None:
        record = {**data, **{k: v for k, v in done.items() if k != "figure"},
                  "missing": missing}
        write_text(folder / "impedance.json", json.dumps(record, indent=1, default=float))
        write_text(folder / "IMPEDANCE.md", markdown(data, done, missing))
        if "figure" in done:
            figure(done["figure"], folder / "figures" / "impedance.png")
    return publish


def figure(imp, path: Path) -> Path:
    """The impedance figure of ``imp`` against the exact half-plane, PNG at 150 dpi."""
    return save_figure(impedance_figure(imp, reference_for(imp)), path, dpi=150)


def costs(plan: dict) -> dict:
    """Each section's estimated wall time (s): the runtimes the committed IMPEDANCE.md records
    for the planned rows (module docstring); None where a planned row is not recorded."""
    tables = committed_tables("IMPEDANCE.md")

    def total(found: list[float | None]) -> float | None:
        return None if not found or None in found else sum(found)

    table = []
    for nu, interface in plan["table"]:
        heads = [h for h in tables if h.startswith(f"ν = {nu:.3g}, {interface} (")]
        table.append(number(heads[0].split("frequencies in")[1]) if heads else None)

    def lookup(heading: str, match) -> float | None:
        rows = [r for head, rows in tables.items() if head.startswith(heading) for r in rows]
        hits = [number(r.get("runtime", r.get("runtime (6 frequencies)", "")))
                for r in rows if match(r)]
        return hits[0] if hits and math.isfinite(hits[0]) else None

    box = [lookup("Box-size", lambda r, w=w, d=d, layer=layer:
                  r["boundary"] == "pml" and r["box"] == f"{w}B × {d}B, layer {layer}B")
           for w, d, layer in plan["pml"]]
    box += [lookup("Box-size", lambda r, w=w, d=d:
                   r["boundary"] == "lysmer" and r["box"] == f"{w}B × {d}B")
            for w, d in plan["lysmer"]]
    return {"table": total(table), "box": total(box),
            "mesh": total([lookup("Mesh convergence", lambda r, n=n:
                                  r["across B"] == str(n)) for n in plan["mesh"]]),
            "decay": total([lookup("Free rocking", lambda r, n=n:
                                   r["across B"] == str(n)) for n in plan["decay"]]),
            "contact": total([lookup("Contact length", lambda r, n=n:
                                     r["across B"] == str(n)) for n in plan["contact"]])}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_arguments(p, NAME)
    p.add_argument("--quick", action="store_true", help="a reduced set, for a smoke check")
    args = p.parse_args(argv)
    out = output_folder(args, NAME)
    plan = QUICK if args.quick else FULL
    data = {"date": date.today().isoformat(), "quick": args.quick,
            "machine": f"{platform.machine()}, Python {platform.python_version()}",
            "vla_over_vp": {f"{nu:.3g}": lysmer_analog_velocity(1.0, nu)
                            / math.sqrt(2 * (1 - nu) / (1 - 2 * nu)) for nu in (0.25, 1 / 3)}}
    cost = costs(plan)
    sections = [Section("table", lambda: impedance_tables(plan["table"]), cost["table"]),
                Section("box", lambda: box_sensitivity(plan["pml"], plan["lysmer"]),
                        cost["box"]),
                Section("mesh", lambda: mesh_convergence(plan["mesh"]), cost["mesh"]),
                Section("decay", lambda: rocking_decay(plan["decay"]), cost["decay"]),
                Section("contact", lambda: contact_length(plan["contact"]), cost["contact"]),
                Section("geofound", geofound_crosscheck),
                Section("figure", figure_run)]
    publish = publisher(data)

    def commit(done: dict) -> None:
        write_text(HERE / "IMPEDANCE.md", markdown(data, done, {}))
        figure(done["figure"], HERE / "figures" / "impedance.png")
        say("wrote benchmarks/IMPEDANCE.md and benchmarks/figures/impedance.png")

    status = run_sections(NAME, sections, publish, out, commit=commit if args.write else None,
                          model="runtimes recorded in benchmarks/IMPEDANCE.md")
    if status == 0:
        say(f"wrote {out / 'IMPEDANCE.md'}")
    return status


if __name__ == "__main__":
    sys.exit(main())
