"""The paper's conclusions as labelled data: the study's :class:`xarray.Dataset`, and the
records read back from it.

Three dimensions, because a conclusion has several pieces of evidence and a piece of evidence
several values:

- ``conclusion``: the conclusion's number in the paper (1–8), with its ``statement``,
  ``verdict``, ``note`` and ``why``;
- ``evidence``: every piece of evidence in order, with the ``conclusion`` it belongs to (by
  number), its ``source``, what it ``says``, the ``unit`` of its values and whether it
  ``supports`` the conclusion;
- ``value``: every value that decides a piece of evidence, with the ``evidence`` it belongs to
  (by index), its ``value_name`` and the ``value_number``, in the evidence's ``unit``.

``ds.where(ds.verdict == "holds", drop=True)`` selects the conclusions that hold;
:func:`conclusions_of` gives the records back (the summary is written from them), exactly.
"""

from __future__ import annotations

import numpy as np

from .records import Conclusion, Evidence

__all__ = ["conclusions_dataset", "conclusions_of"]


def _text(values) -> np.ndarray:
    return np.array([str(v) for v in values], dtype=object)


def conclusions_dataset(conclusions, record: str | None):
    """``conclusions`` (:class:`~.records.Conclusion`, in order) as the study's dataset;
    ``record``: the source of the El Centro record the runs used (None: not found)."""
    import xarray as xr

    evidence = [(c.number, e) for c in conclusions for e in c.evidence]
    values = [(i, name, float(v)) for i, (_, e) in enumerate(evidence)
              for name, v in e.values.items()]
    one = {"units": "1"}
    data = {
        "statement": ("conclusion", _text(c.statement for c in conclusions),
                      {"long_name": "the paper's conclusion"}),
        "verdict": ("conclusion", _text(c.verdict for c in conclusions),
                    {"long_name": "holds, holds in part, does not hold or not tested"}),
        "note": ("conclusion", _text(c.note for c in conclusions),
                 {"long_name": "why a conclusion is not tested (empty: it is)"}),
        "why": ("conclusion", _text(c.why for c in conclusions),
                {"long_name": "where our results differ from the paper, and why"}),
        "evidence_conclusion": ("evidence", np.array([n for n, _ in evidence], np.int64),
                                {**one, "long_name": "number of the conclusion it is for"}),
        "source": ("evidence", _text(e.source for _, e in evidence),
                   {"long_name": "model and scene of the evidence"}),
        "says": ("evidence", _text(e.says for _, e in evidence),
                 {"long_name": "what the evidence says"}),
        "unit": ("evidence", _text(e.unit for _, e in evidence),
                 {"long_name": "unit of the evidence's values"}),
        "supports": ("evidence", np.array([e.supports for _, e in evidence], bool),
                     {"long_name": "the evidence supports the conclusion"}),
        "value_evidence": ("value", np.array([i for i, _, _ in values], np.int64),
                           {**one, "long_name": "index of the evidence the value decides"}),
        "value_name": ("value", _text(n for _, n, _ in values),
                       {"long_name": "what the value is"}),
        "value_number": ("value", np.array([v for _, _, v in values], float),
                         {"long_name": "the value, in its evidence's unit"}),
    }
    coords = {
        "conclusion": ("conclusion", np.array([c.number for c in conclusions], np.int64),
                       {**one, "long_name": "number of the conclusion in the paper"}),
        "evidence": ("evidence", np.arange(len(evidence), dtype=np.int64),
                     {**one, "long_name": "index of the evidence"}),
        "value": ("value", np.arange(len(values), dtype=np.int64),
                  {**one, "long_name": "index of the value"}),
    }
    attrs = {"title": "The founding study's conclusions, checked (upliftlab)"}
    if record is not None:
        attrs["record"] = record
    return xr.Dataset(data, coords=coords, attrs=attrs)


def conclusions_of(ds) -> tuple[Conclusion, ...]:
    """The conclusions the dataset holds, as the records it was made from (the verdict is
    the records' own, decided again from the evidence)."""
    owner = ds["value_evidence"].values
    names, numbers = ds["value_name"].values, ds["value_number"].values
    evidence: dict[int, list[Evidence]] = {}
    for i, n in enumerate(ds["evidence_conclusion"].values):
        mine = owner == i
        evidence.setdefault(int(n), []).append(Evidence(
            str(ds["source"].values[i]), str(ds["says"].values[i]),
            {str(k): float(v) for k, v in zip(names[mine], numbers[mine])},
            str(ds["unit"].values[i]), bool(ds["supports"].values[i])))
    return tuple(
        Conclusion(int(n), str(ds["statement"].values[j]), tuple(evidence.get(int(n), ())),
                   str(ds["note"].values[j]), str(ds["why"].values[j]))
        for j, n in enumerate(ds["conclusion"].values))
