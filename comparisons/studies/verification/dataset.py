"""The verification as one labelled dataset: the anchors over ``anchor`` (their ids), the
observed orders over ``order`` and the time of each check over ``check``, built from the
store's record (:func:`.workflow.compute_checks`), and the records read back from it."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from ....results import cf_attributes
from .records import FAIL, PASS, SKIP, Order, Row

#: The anchors' text fields and their long names (variables over ``anchor``).
ROW_TEXT = {"group": "model checked (reduced or continuum)", "quantity": "quantity checked",
            "reference": "where the expected value comes from",
            "unit": "unit of measured and expected (\u2013 for a ratio)",
            "kind": "kind of error: relative, absolute or value (a bound)",
            "tolerance": "tolerance of the error", "status": "pass, fail or skipped",
            "note": "note (the message of a check that raised)"}
#: The anchors' numbers (NaN where there is none) and their long names.
ROW_NUMBERS = {"measured": "value computed by the library",
               "expected": "reference value (NaN for a bound)",
               "error": "error, as its kind says"}
#: The orders' fields (variables ``order_<field>`` over ``order``).
ORDER_TEXT = {"group": "model checked", "case": "case whose convergence is measured",
              "method": "integrator or element", "expected": "expected order",
              "status": "pass, fail or skipped", "note": "note"}
ORDER_NUMBERS = {"slope": "observed order: slope of log error against log step",
                 "low": "lower end of the accepted band", "high": "upper end of the band"}


def _text(values) -> np.ndarray:
    return np.array([str(v) for v in values], dtype=str)


def _number(value) -> float:
    return math.nan if value is None else float(value)


def _padded(seqs) -> np.ndarray:
    width = max((len(s) for s in seqs), default=0)
    out = np.full((len(seqs), width), np.nan)
    for i, s in enumerate(seqs):
        out[i, :len(s)] = s
    return out


def verification_dataset(entry: Mapping, attrs: Mapping):
    """The verification's :class:`xarray.Dataset` from the store's ``entry`` ({"rows",
    "orders", "seconds"} of dicts as :func:`dataclasses.asdict` gives them): per ``anchor``
    (the row's id) its text fields and ``measured``, ``expected``, ``error`` (NaN for none;
    units per anchor in ``unit``); per ``order`` the fields as ``order_<field>`` and the fitted
    ``order_steps``/``order_errors`` over (order, level), NaN-padded; ``check_seconds`` (s) per
    ``check`` (by title, sorted). ``attrs`` (fast, reused, key, computed_utc,
    compute_seconds, inputs) are added."""
    import xarray as xr

    rows, orders = list(entry["rows"]), list(entry["orders"])
    seconds = dict(sorted(entry.get("seconds", {}).items()))  # the store may reorder them
    data = {name: ("anchor", _text(r[name] for r in rows), {"long_name": text})
            for name, text in ROW_TEXT.items()}
    data.update({name: ("anchor", np.array([_number(r[name]) for r in rows], dtype=float),
                        {"long_name": text}) for name, text in ROW_NUMBERS.items()})
    data.update({f"order_{name}": ("order", _text(o[name] for o in orders), {"long_name": text})
                 for name, text in ORDER_TEXT.items()})
    data.update({f"order_{name}": ("order", np.array([_number(o[name]) for o in orders],
                                                     dtype=float), {"long_name": text})
                 for name, text in ORDER_NUMBERS.items()})
    data["order_steps"] = (("order", "level"), _padded([o["steps"] for o in orders]),
                           {"long_name": "steps of the fit (\u0394t in s or h in m; NaN pads)"})
    data["order_errors"] = (("order", "level"), _padded([o["errors"] for o in orders]),
                            {"long_name": "errors at the steps (NaN pads)"})
    data["check_seconds"] = ("check", np.array(list(seconds.values()), dtype=float),
                             {"units": "s", "long_name": "wall time of the check"})
    coords = {"anchor": ("anchor", _text(r["id"] for r in rows), {"long_name": "anchor id"}),
              "check": ("check", _text(seconds), {"long_name": "check"})}
    attrs = {"Conventions": "CF-1.10", "title": "verification anchors and observed orders",
             **attrs}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


def _value(x: float) -> float | None:
    x = float(x)
    return None if math.isnan(x) else x


def rows_of(ds) -> tuple[Row, ...]:
    """The anchors of ``ds`` as :class:`Row` records (NaN read as none)."""
    text = {k: [str(v) for v in ds[k].values.tolist()] for k in ROW_TEXT}
    nums = {k: ds[k].values for k in ROW_NUMBERS}
    ids = [str(v) for v in ds.anchor.values.tolist()]
    return tuple(Row(id=ids[i], **{k: v[i] for k, v in text.items()},
                     **{k: _value(v[i]) for k, v in nums.items()}) for i in range(len(ids)))


def orders_of(ds) -> tuple[Order, ...]:
    """The observed orders of ``ds`` as :class:`Order` records (padding dropped)."""
    n = ds.sizes.get("order", 0)
    text = {k: [str(v) for v in ds[f"order_{k}"].values.tolist()] for k in ORDER_TEXT}
    steps, errors = ds.order_steps.values, ds.order_errors.values
    out = []
    for i in range(n):
        kept = ~np.isnan(steps[i])
        out.append(Order(steps=tuple(float(s) for s in steps[i][kept]),
                         errors=tuple(float(e) for e in errors[i][kept]),
                         slope=_value(ds.order_slope.values[i]),
                         low=float(ds.order_low.values[i]), high=float(ds.order_high.values[i]),
                         **{k: v[i] for k, v in text.items()}))
    return tuple(out)


def failures(ds) -> list[str]:
    """One line per failing anchor or order."""
    bad = [f"{r.group}: {r.quantity} ({r.note or r.status})" for r in rows_of(ds)
           if r.status == FAIL]
    bad += [f"{o.group}: order of {o.method} on {o.case} ({o.note or o.status})"
            for o in orders_of(ds) if o.status == FAIL]
    return bad


def status_counts(ds) -> dict:
    """{pass, fail, skipped: how many anchors and orders}."""
    items = ds.status.values.tolist() + ds.order_status.values.tolist()
    return {s: items.count(s) for s in (PASS, FAIL, SKIP)}
