"""The paper study's summary, read from its dataset alone: the Markdown (:func:`summarise`) and
the numbers of ``summary.json`` (:func:`key_numbers`: every conclusion with its evidence and
values, and the record)."""

from __future__ import annotations

from ....number_text import number_text
from .dataset import conclusions_of
from .records import Conclusion

__all__ = ["summarise", "key_numbers", "conclusion_numbers"]

#: What an infinite value of a conclusion's evidence means: a decay time of a free vibration
#: whose energy never stays below the fraction within the run (:func:`.reduced.paper.decay_time`).
_UNBOUNDED = "not reached within the run"


def conclusion_numbers(c: Conclusion) -> dict:
    """One conclusion as the numbers of ``summary.json``."""
    return {"number": c.number, "statement": c.statement, "verdict": c.verdict, "note": c.note,
            "why": c.why,
            "evidence": [{"source": e.source, "says": e.says, "supports": e.supports,
                          "unit": e.unit, "values": {k: float(v) for k, v in e.values.items()}}
                         for e in c.evidence]}


def key_numbers(ds) -> dict:
    """The conclusions' numbers and the record's source (None: the record was not found)."""
    return {"conclusions": [conclusion_numbers(c) for c in conclusions_of(ds)],
            "record": ds.attrs.get("record")}


def summarise(ds) -> str:
    """The Markdown: how many conclusions hold, then each with its verdict and evidence."""
    conclusions = conclusions_of(ds)
    lines = ["# The founding study's conclusions, checked", ""]
    verdicts = [c.verdict for c in conclusions]
    lines += [f"{verdicts.count('holds')} of {len(verdicts)} conclusions hold, "
              f"{verdicts.count('holds in part')} hold in part, "
              f"{verdicts.count('does not hold')} do not hold and "
              f"{verdicts.count('not tested')} are not tested.", ""]
    for c in conclusions:
        lines += [f"## {c.number}. {c.statement}", "", f"**Verdict: {c.verdict}.**", ""]
        for e in c.evidence:
            values = ", ".join(f"{k} = {number_text(v, '.4g', e.unit, unbounded=_UNBOUNDED)}"
                               for k, v in e.values.items())
            mark = "supports" if e.supports else "**contradicts**"
            lines.append(f"- {mark} — {e.source}: {e.says} ({values})")
        if c.note:
            lines += ["", f"Note: {c.note}"]
        if c.why:
            lines += ["", f"Where we differ, and why: {c.why}"]
        lines.append("")
    return "\n".join(lines)
