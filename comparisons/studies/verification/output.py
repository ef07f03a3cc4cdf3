"""The verification's files (anchors.csv, orders.csv) and its Markdown summary."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from ....provenance import provenance
from ....results import write_csv
from ...framework.protocol import Context
from ...framework.study import StudyResult, write_summary
from .records import FAIL, PASS, SKIP, STUDY, Row, Verification


def write(result: Verification, ctx: Context) -> StudyResult:
    """``anchors.csv``, ``orders.csv`` and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, fast=fast, key=result.key, store=str(store.root),
                      computed_utc=result.computed_utc, reused=result.reused,
                      inputs=dict(result.inputs))
    files = [write_rows_csv(result.rows, out / "anchors.csv"),
             write_orders_csv(result.orders, out / "orders.csv")]
    elapsed = ctx.elapsed()
    numbers = {"passed": result.passed, "failures": result.failures,
               "counts": status_counts(result), "reused": result.reused, "key": result.key,
               "computed_utc": result.computed_utc,
               "compute_seconds": result.compute_seconds,
               "check_seconds": dict(result.check_seconds),
               "rows": [dataclasses.asdict(r) for r in result.rows],
               "orders": [dataclasses.asdict(o) for o in result.orders], "elapsed_s": elapsed}
    text = markdown(result, fast)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def status_counts(result: Verification) -> dict:
    items = [r.status for r in result.rows] + [o.status for o in result.orders]
    return {s: items.count(s) for s in (PASS, FAIL, SKIP)}


def write_rows_csv(rows, path: Path) -> Path:
    nan = math.nan
    return write_csv(path, {
        "row": np.arange(len(rows)),
        "measured": [nan if r.measured is None else r.measured for r in rows],
        "expected": [nan if r.expected is None else r.expected for r in rows],
        "error": [nan if r.error is None else r.error for r in rows],
        "passed": [{PASS: 1, FAIL: 0}.get(r.status, nan) for r in rows]},
        header="verification anchors (row order as in summary.json): " +
        "; ".join(f"{i}={r.id}" for i, r in enumerate(rows)))


def write_orders_csv(orders, path: Path) -> Path:
    nan = math.nan
    return write_csv(path, {
        "row": np.arange(len(orders)),
        "slope": [nan if o.slope is None else o.slope for o in orders],
        "low": [o.low for o in orders], "high": [o.high for o in orders],
        "passed": [{PASS: 1, FAIL: 0}.get(o.status, nan) for o in orders]},
        header="observed orders: " + "; ".join(f"{i}={o.group}/{o.case}/{o.method}"
                                               for i, o in enumerate(orders)))


def fmt(value: float | None, digits: int = 6) -> str:
    """A number for the tables (— for none)."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    return f"{value:.{digits}g}"


def error_text(row: Row) -> str:
    if row.error is None:
        return "—"
    if row.kind == "relative":
        return f"{row.error:+.2e}"
    if row.kind == "absolute":
        return f"{row.error:+.2e} (abs)"
    return f"{row.error:.4g}"


def markdown(result: Verification, fast: bool) -> str:
    """The summary: counts, the anchors table and the orders table."""
    n = status_counts(result)
    lines = [f"# Verification anchors{' (fast)' if fast else ''}", "",
             f"{n[PASS]} pass, {n[FAIL]} fail, {n[SKIP]} skipped. Computed "
             f"{result.computed_utc} in {result.compute_seconds:.1f} s"
             + (" (read from the store: nothing recomputed)." if result.reused else "."), "",
             "Errors are relative (measured/reference − 1) unless marked abs; a bound row "
             "shows the measured value itself." + (" Fast mode skips the costly continuum "
                                                    "levels (rows marked skipped)."
                                                    if fast else ""), "",
             "| group | quantity | reference | measured | expected | error | tolerance | "
             "result |", "|---|---|---|---|---|---|---|---|"]
    for r in result.rows:
        status = r.status if r.status != FAIL else "**FAIL**"
        note = f" — {r.note}" if r.note else ""
        lines.append(f"| {r.group} | {r.quantity}{note} | {r.reference} | {fmt(r.measured)} | "
                     f"{fmt(r.expected)} | {error_text(r)} | {r.tolerance} | {status} |")
    lines += ["", "## Observed convergence orders", "",
              "Slope of log(error) against log(step) by least squares (np.polyfit).", "",
              "| group | case | method | steps | observed order | expected | band | result |",
              "|---|---|---|---|---|---|---|---|"]
    for o in result.orders:
        steps = ", ".join(f"{s:g}" for s in o.steps) or "—"
        status = o.status if o.status != FAIL else "**FAIL**"
        note = f" — {o.note}" if o.note else ""
        lines.append(f"| {o.group} | {o.case} | {o.method} | {steps} | "
                     f"{fmt(o.slope, 3)} | {o.expected} | [{o.low:g}, {o.high:g}] | "
                     f"{status}{note} |")
    if result.failures:
        lines += ["", "## Failures", ""] + [f"- {f}" for f in result.failures]
    return "\n".join(lines) + "\n"
