"""The verification's tables: ``anchors.csv`` and ``orders.csv``, from its dataset."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ....results import write_csv
from .dataset import orders_of, rows_of
from .records import FAIL, PASS


def write_tables(ds, out: Path) -> list[Path]:
    """``anchors.csv`` and ``orders.csv`` of ``ds`` into ``out``."""
    return [write_rows_csv(rows_of(ds), out / "anchors.csv"),
            write_orders_csv(orders_of(ds), out / "orders.csv")]


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
