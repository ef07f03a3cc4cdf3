"""The report's opening: the three findings the README states, one paragraph each, its numbers
read from the studies' own results (``StudyResult.numbers``, what each study writes to its
``summary.json``), each with the figure that shows it.

1. When does a two-spring foundation stop being equivalent to a Winkler bed? (the two-spring
   study: the bonded errors, the static ratios, the share of uplifting points within 10 %);
2. How well does a Winkler bed match the continuum? (the Winkler map: the best bed, its share
   and speed-up; its figure is Winkler against the continuum's);
3. Which model is the cheapest that is accurate enough? (speed against error: the cheapest run
   within 1 % per scene, how often two springs are the cheapest, the Pareto front).

A finding whose study has no results says so, naming the section, instead of a number.
"""

from __future__ import annotations

import html
from collections.abc import Callable, Mapping, Sequence

from ...number_text import number_text
from ..beds import BEDS
from .figures import figure_html, figure_id, records_of

__all__ = ["findings_html", "FINDINGS"]

#: Each finding: (its question, the study whose numbers say it, the study whose figure shows
#: it, the paragraph's writer).
FINDINGS: tuple[tuple[str, str, str, Callable], ...]


def _pct(value, spec: str = ".0f") -> str:
    """A fraction as a percentage ("12.6 %"); what is missing is said, never printed as nan."""
    value = None if value is None else 100.0 * float(value)
    return number_text(value, spec, "%")


def _code(name: str) -> str:
    """A bed's short code (the registry's), or its name."""
    entry = BEDS.get(name)
    return entry.short if entry is not None and entry.short else name


def _two_springs(n: Mapping) -> str:
    ewing = n["ewing"]
    bonded = ewing["bonded_error"]
    best = {case: max(layouts.values(), key=lambda v: v["all"])["all"]
            for case, layouts in ewing["share"].items()}
    points = sum(ewing["uplifting_points"].values())
    verdict = ("Ewing's conclusion holds: uplift breaks the equivalence"
               + (", even for the elastic Case A." if ewing.get("elastic_holds") else ".")
               if ewing["holds"] else "Ewing's conclusion does not hold on these points.")
    return (f"Two springs at ±b/√3 (or calibrated to the bed's K_v and K_θ) match a converged "
            f"bed of {n['springs']:d} springs to {_pct(bonded['equivalent'], '.2g')} in all "
            "six measures (peak u, θ, edge uplift, permanent settlement, base shear, dissipated "
            f"energy) as long as the bed stays in contact; springs at the edges ±b are off by "
            f"up to {_pct(bonded['edges'])}. Statically the ±b/√3 pair uplifts at "
            f"{number_text(n['onset_ratio_equivalent_vs_winkler'], '.2f')} times the bed's "
            "moment and caps the moment at "
            f"{number_text(n['capacity_ratio_equivalent_vs_winkler'], '.2f')} of it. Once the "
            f"bed uplifts ({points:d} of the study's {n['points']:d} runs) the best pair is "
            "within 10 % in all six measures at "
            + ", ".join(f"{_pct(best[c])} of the points in Case {c}" for c in sorted(best))
            + f". {verdict}")


def _winkler(n: Mapping) -> str:
    share, goal = n["share"], n["goal"]
    code = _code(share["best"])
    by_soil = ""
    if goal.get("calibration") == share["best"] and goal.get("share_by_soil_fs_v"):
        by_soil = (" By soil and FS_v: " + ", ".join(
            f"{where} {_pct(v, '.1f')}" for where, v in goal["share_by_soil_fs_v"].items())
            + ".")
    speed = n.get("speed", {}).get("median", {}).get(share["best"])
    return (f"{len(share['by_calibration']):d} beds calibrated to the plane-strain continuum "
            f"over the Winkler map's {share['points']:,d} points: the best bed, {code}, "
            + (f"{number_text(speed, ',.0f')} times faster than the continuum (median per "
               "point), " if speed is not None else "")
            + f"is within {_pct(share['threshold'])} of the continuum in both peak θ and edge "
            f"uplift at {_pct(share['best_share'], '.1f')} of the points "
            f"({_pct(share['any_share'], '.1f')} with the best bed chosen point by point)."
            + by_soil + " The map's goal (a bed within "
            f"{_pct(share['threshold'])} at more than {_pct(goal['share_needed'])} of the "
            f"points, {number_text(goal['speedup_needed'], ',.0f')} times faster) is "
            + ("met." if goal["met"] else "not met: no calibrated bed is enough."))


def _run_text(run: Mapping) -> str:
    model = {"edges": "two springs at ±b", "equivalent": "two springs at ±b/√3"}.get(
        run["model"], f"a bed of {run['springs']} springs" if run["model"] == "winkler"
        else f"the {run['model']}")
    return (f"{model}, {run['integrator']}, Δt = {number_text(run['dt'], '.3g', 's')}: "
            f"{number_text(1e3 * run['runtime_s'], '.3g', 'ms')}, "
            f"{number_text(run['speedup_vs_reference'], '.3g')} times faster than the "
            "reference")


def _speed(n: Mapping) -> str:
    scenes = n["scenes"]
    cheapest = "; ".join(
        f"{label}: " + (_run_text(s["cheapest"]["u"]["0.01"]) if s["cheapest"]["u"].get("0.01")
                        else "no run within 1 %")
        for label, s in scenes.items())
    pairs = [s["cheapest"][q].get("0.05") for s in scenes.values() for q in s["cheapest"]]
    two = sum(1 for p in pairs if p and p["model"] in ("edges", "equivalent"))
    front = ", ".join(f"{k} {v}" for k, v in n["pareto_points_by_integrator"].items())
    return (f"Measured for every model, integrator and step against a converged reference "
            f"({sum(s['points'] for s in scenes.values()):d} runs, {len(scenes):d} scenes), "
            f"the cheapest run within 1 % in peak u is, per scene, {cheapest}. Two springs "
            f"are the cheapest within 5 % in {two} of {len(pairs)} scene-quantity pairs. The "
            f"Pareto fronts' points by integrator: {front}. Continuum: "
            + str(n["continuum"]).rstrip(".") + ".")


FINDINGS = (
    ("When does a two-spring foundation stop being equivalent to a Winkler bed?",
     "two_spring_equivalence", "two_spring_equivalence", _two_springs),
    ("How well does a Winkler bed match the continuum?", "winkler_map",
     "winkler_vs_continuum", _winkler),
    ("Which model is the cheapest that is accurate enough?", "speed_vs_error",
     "speed_vs_error", _speed),
)


def _figure(section) -> str:
    """The first readable (not dense) figure of ``section`` that answers a whole question
    (a two-spring map of every measure at once), with the id of its copy in the opening."""
    if section is None or section.status != "ok":
        return ""
    records = [r for r in records_of(section.study) if not r.caption.dense and not r.frames]
    wanted = ([r for r in records if r.image.stem.endswith("C_all")]
              or [r for r in records if r.image.stem.endswith("_all")] or records)
    if not wanted:
        return ""
    record = wanted[0]
    own = figure_id(section.name, record)
    return (figure_html(record, ident=f"finding-{own}")
            + f'<p class="meta">The figure in its section: <a href="#{own}">{html.escape(own)}'
            "</a>.</p>")


def findings_html(sections: Sequence) -> str:
    """The opening: one paragraph per finding, with its figure and a link to its section."""
    by_name = {s.name: s for s in sections}
    parts = ['<section id="findings"><h2 id="what-the-studies-found">What the studies found</h2>']
    for k, (question, study, shown, write) in enumerate(FINDINGS, 1):
        section = by_name.get(study)
        head = f"<strong>{k}. {html.escape(question)}</strong> "
        if section is None or section.status != "ok":
            why = "not in this report" if section is None else f"its section {section.status}"
            parts.append(f'<p id="finding-{k}">{head}Not available: the study {study} has no '
                         f"results ({why}).</p>")
            continue
        try:
            text = write(section.study.numbers)
        except (KeyError, TypeError, ValueError) as exc:  # a study that wrote other numbers
            text = f"Not available: the study's results lack {exc!s} (its summary.json)."
        parts.append(f'<p id="finding-{k}">{head}{html.escape(text)} '
                     f'<a href="#{study}">The section.</a></p>')
        parts.append(_figure(by_name.get(shown)))
    return "".join(parts) + "</section>"
