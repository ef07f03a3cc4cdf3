"""The verification's Markdown summary and key numbers, read from its dataset alone."""

from __future__ import annotations

import dataclasses
import math

from .dataset import failures, orders_of, rows_of, status_counts
from .records import FAIL, PASS, SKIP, Row


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


def key_numbers(ds) -> dict:
    """The numbers of ``summary.json``: passed, failures, counts, whether reused, the key, when
    and how long it was computed (s), each check's time (s), the rows and the orders."""
    a = ds.attrs
    numbers = {"passed": not failures(ds), "failures": failures(ds),
               "counts": status_counts(ds), "reused": bool(a["reused"]), "key": a["key"],
               "computed_utc": a["computed_utc"],
               "compute_seconds": float(a["compute_seconds"]),
               "check_seconds": dict(zip(ds.check.values.tolist(),
                                         ds.check_seconds.values.tolist())),
               "rows": [dataclasses.asdict(r) for r in rows_of(ds)],
               "orders": [dataclasses.asdict(o) for o in orders_of(ds)]}
    if "elapsed_s" in a:
        numbers["elapsed_s"] = float(a["elapsed_s"])
    return numbers


def summarise(ds) -> str:
    """The summary: counts, the anchors table and the orders table."""
    fast, a = bool(ds.attrs["fast"]), ds.attrs
    n, bad = status_counts(ds), failures(ds)
    lines = [f"# Verification anchors{' (fast)' if fast else ''}", "",
             f"{n[PASS]} pass, {n[FAIL]} fail, {n[SKIP]} skipped. Computed "
             f"{a['computed_utc']} in {float(a['compute_seconds']):.1f} s"
             + (" (read from the store: nothing recomputed)." if a["reused"] else "."), "",
             "Errors are relative (measured/reference − 1) unless marked abs; a bound row "
             "shows the measured value itself." + (" Fast mode skips the costly continuum "
                                                    "levels (rows marked skipped)."
                                                    if fast else ""), "",
             "| group | quantity | reference | measured | expected | error | tolerance | "
             "result |", "|---|---|---|---|---|---|---|---|"]
    for r in rows_of(ds):
        status = r.status if r.status != FAIL else "**FAIL**"
        note = f" — {r.note}" if r.note else ""
        lines.append(f"| {r.group} | {r.quantity}{note} | {r.reference} | {fmt(r.measured)} | "
                     f"{fmt(r.expected)} | {error_text(r)} | {r.tolerance} | {status} |")
    lines += ["", "## Observed convergence orders", "",
              "Slope of log(error) against log(step) by least squares (np.polyfit).", "",
              "| group | case | method | steps | observed order | expected | band | result |",
              "|---|---|---|---|---|---|---|---|"]
    for o in orders_of(ds):
        steps = ", ".join(f"{s:g}" for s in o.steps) or "—"
        status = o.status if o.status != FAIL else "**FAIL**"
        note = f" — {o.note}" if o.note else ""
        lines.append(f"| {o.group} | {o.case} | {o.method} | {steps} | "
                     f"{fmt(o.slope, 3)} | {o.expected} | [{o.low:g}, {o.high:g}] | "
                     f"{status}{note} |")
    if bad:
        lines += ["", "## Failures", ""] + [f"- {f}" for f in bad]
    return "\n".join(lines) + "\n"
