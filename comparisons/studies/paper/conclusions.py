"""Each conclusion of Ewing's study, decided from the runs: one function per conclusion."""

from __future__ import annotations

import math
from collections.abc import Mapping

from ....motions import Motion
from ....reduced.paper import decay_time
from ....scenes import load_scene
from .responses import apparent_period, peak_ratio, record_note, reduced_label
from .records import BUILDINGS, Conclusion, Evidence


def conclusion_peak_u(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        for motion in ("free", "elcentro"):
            keys = [f"{building}_{motion}-{c}" for c in "ABC"]
            if not all(k in r for k in keys):
                continue
            u = {c: r[k].peaks["u"] for c, k in zip("ABC", keys)}
            larger = u["A"] > max(u["B"], u["C"])
            ev.append(Evidence(f"{reduced_label(building)}, {motion}",
                               f"peak u of A is {'larger' if larger else 'not larger'} than B "
                               f"and C (A/B = {peak_ratio(u['A'], u['B']):.2f})", u, "in", larger))
    return Conclusion(1, "The elastic spring with high viscous damping (Case A) overestimates "
                         "the maximum superstructure deformation.", tuple(ev),
                      record_note(record))


def conclusion_long_period_peak(r: Mapping, record: Motion | None) -> Conclusion:
    """The results section's exception for the long-period building (Figs. 9-10): Case A's
    superstructure deformation is lower, its foundation displacement higher."""
    ev, measured = [], []
    for motion in ("free", "elcentro"):
        keys = [f"long_period_{motion}-{c}" for c in "ABC"]
        if not all(k in r for k in keys):
            continue
        u = {c: r[k].peaks["u"] for c, k in zip("ABC", keys)}
        gap = {c: r[k].peaks["uplift_left"] for c, k in zip("ABC", keys)}
        ev.append(Evidence(f"{reduced_label('long_period')}, {motion}",
                           f"peak u of A is "
                           f"{'lower' if u['A'] < min(u['B'], u['C']) else 'not lower'}"
                           f" than B and C; peak uplift of the left spring A/B = "
                           f"{peak_ratio(gap['A'], gap['B']):.2f}", u, "in",
                           u["A"] < min(u["B"], u["C"])))
        measured.append(f"{motion}: θ_A/θ_B = "
                        f"{peak_ratio(r[keys[0]].peaks['theta'], r[keys[1]].peaks['theta']):.2f}")
    why = ""
    if any(not e.supports for e in ev):
        why = ("Our long-period runs give A the larger superstructure deformation, as the "
               "paper's general conclusion 1 says, not the lower one its results section reports "
               "for Figs. 9-10 (" + "; ".join(measured) + "). The paper tabulates no peaks, and "
               "the long-period building's rotary inertia (1740 kip in s²) and coupled weight "
               "(16 kip) are all it specifies beyond the short-period one. Left unresolved.")
    return Conclusion(2, "Results, long-period building (Figs. 9-10): Case A reaches lower "
                         "maximum deformations in the superstructure than B and C.", tuple(ev),
                      record_note(record), why)


def conclusion_decay(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = [f"{building}_free-{c}" for c in "ABC"]
        t10 = {c: decay_time(r[k]) for c, k in zip("ABC", keys)}
        fastest = t10["A"] < min(t10["B"], t10["C"])
        ev.append(Evidence(f"{reduced_label(building)}, free vibration",
                           "time for the mechanical energy to stay below 10 % of its initial "
                           f"value: A is {'the shortest' if fastest else 'not the shortest'}",
                           t10, "s", fastest))
    why = ""
    failed = [b for b, e in zip(BUILDINGS, ev) if not e.supports]
    if failed:
        parts = []
        for building in failed:
            dissipated = r[f"{building}_free-C"].energy[-1]  # ENERGY_NAMES order
            viscous, impact, plastic = dissipated[4], dissipated[5], dissipated[6]
            total = viscous + impact + plastic
            parts.append(f"{building.replace('_', '-')} C: impact {100 * impact / total:.0f} %, "
                         f"viscous {100 * viscous / total:.0f} %, plastic "
                         f"{100 * plastic / total:.0f} % of the energy dissipated")
        why = ("Besides its 10 % dashpots, Case C dissipates by yielding of the bed and by "
               "impact at every recontact, and in large free rocking these together decay the "
               "response as fast as A's 40 % dashpots (" + "; ".join(parts) + "). The paper "
               "shows the histories only; we cannot tell which of these terms is smaller in "
               "its model.")
    return Conclusion(3, "Case A overestimates the rate of decay of the response.", tuple(ev),
                      "", why)


def conclusion_settlement(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = [f"{building}_elcentro-{c}" for c in "BC"]
        if not all(k in r for k in keys):
            continue
        s = {c: r[k].peaks["plastic_settlement_mean"] for c, k in zip("BC", keys)}
        ev.append(Evidence(f"{reduced_label(building)}, El Centro",
                           f"mean plastic settlement C/B = {peak_ratio(s['C'], s['B']):.2f}", s,
                           "in", s["C"] < s["B"]))
    return Conclusion(4, "Impact damping reduces the plastic deformation in the soil.",
                      tuple(ev), record_note(record))


def conclusion_two_springs(equivalence) -> Conclusion:
    """Conclusion 5 from the two-spring equivalence study's written folder, opened as its tree
    (:func:`upliftlab.open_study`; None: the study did not run): its summary's numbers (the
    root's attributes: Ewing's conclusion quantified, ``ewing``) and its threshold (the
    attribute of its ``statics`` node)."""
    if equivalence is None:
        return Conclusion(5, TWO_SPRING_STATEMENT, (),
                          "the two-spring equivalence study did not run")
    e = equivalence.attrs["ewing"]
    threshold = float(equivalence["statics"].attrs["threshold"])
    ev = []
    if e["holds"] is not None:
        layout, share = best_layout(e["share"]["C"])
        ev.append(Evidence("reduced model, two-spring equivalence maps (Case C)",
                           f"best two-spring layout ({layout}) within {100 * threshold:g} % "
                           f"of the Winkler bed in all six measures at {100 * share:.0f} % of "
                           "the uplifting points", {"share_within": share,
                                                    "points": e["uplifting_points"]["C"]}, "-",
                           bool(e["holds"])))
    return Conclusion(5, TWO_SPRING_STATEMENT, tuple(ev), "" if ev else "no Case C point uplifted",
                      "" if all(x.supports for x in ev) else e["text"])


def best_layout(shares: Mapping, measure: str = "all") -> tuple[str, float]:
    """(layout, share) of the two-spring layout most often within the threshold, from the
    two-spring study's shares {layout: {measure: share}}; ties go to ``equivalent``, then
    ``calibrated``, then ``edges``, as that study's own statement decides them."""
    values = {k: v[measure] for k, v in shares.items()}
    preference = ("equivalent", "calibrated", "edges")
    layout = max(values, key=lambda k: (values[k], -preference.index(k)))
    return layout, values[layout]


TWO_SPRING_STATEMENT = ("With foundation nonlinearity and impact damping, a Winkler foundation is "
               "necessary and cannot be replaced with an equivalent two-spring system.")


def conclusion_uplift_beneficial(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = [f"{building}_elcentro-{c}" for c in ("fixed", "C")]
        if not all(k in r for k in keys):
            continue
        u = {"fixed": r[keys[0]].peaks["u"], "uplift (C)": r[keys[1]].peaks["u"]}
        ev.append(Evidence(f"{reduced_label(building)}, El Centro",
                           f"peak u with uplift / fixed base = "
                           f"{peak_ratio(u['uplift (C)'], u['fixed']):.2f}", u, "in",
                           u["uplift (C)"] < u["fixed"]))
    return Conclusion(6, "Uplift reduces the structural deformation against a fixed base.",
                      tuple(ev), record_note(record))


def conclusion_more_with_c(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = {c: f"{building}_elcentro-{c}" for c in ("fixed", "A", "C")}
        if not all(k in r for k in keys.values()):
            continue
        ratio = {c: peak_ratio(r[keys[c]].peaks["u"], r[keys["fixed"]].peaks["u"]) for c in "AC"}
        ev.append(Evidence(f"{reduced_label(building)}, El Centro",
                           f"peak u over the fixed base's: A {ratio['A']:.2f}, C "
                           f"{ratio['C']:.2f}", ratio, "-", ratio["C"] < ratio["A"]))
    why = ""
    return Conclusion(7, "Uplift is even more beneficial in reducing structural deformation "
                         "with the recommended model (Case C).", tuple(ev),
                      record_note(record), why)


def conclusion_period(r: Mapping, record: Motion | None) -> Conclusion:
    ev = []
    for building in BUILDINGS:
        keys = {c: f"{building}_elcentro-{c}" for c in ("fixed", "C")}
        if not all(k in r for k in keys.values()):
            continue
        period = {c: apparent_period(r[k].time, r[k].u) for c, k in keys.items()}
        scene = load_scene(f"{building}_elcentro")
        story = scene.structure.stories[0]
        nominal = 2.0 * math.pi * math.sqrt(story.weight / scene.units.gravity / story.stiffness)
        ev.append(Evidence(f"{reduced_label(building)}, El Centro",
                           "mean period between upward zero crossings of u: "
                           f"{period['C']:.3f} s with uplift, {period['fixed']:.3f} s fixed "
                           f"(nominal fixed-base period {nominal:g} s)",
                           {"uplift (C)": period["C"], "fixed": period["fixed"]}, "s",
                           period["C"] > period["fixed"]))
    return Conclusion(8, "Uplift elongates the fundamental response period (introduction).",
                      tuple(ev), record_note(record))
