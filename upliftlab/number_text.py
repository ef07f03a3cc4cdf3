"""A number as text, for the summaries and the report: a value that is not a finite number is
never printed as one ("Δt = nan s", "B = inf"); the text says what is missing instead."""

from __future__ import annotations

import math

__all__ = ["number_text"]


def number_text(value: float | None, spec: str = ".4g", unit: str = "", *,
                missing: str = "not measured", unbounded: str = "unbounded") -> str:
    """``value`` formatted by ``spec`` with `` unit`` after it; ``missing`` for None or NaN
    and ``unbounded`` (its sign in front when negative) for an infinity, without the unit."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return missing
    value = float(value)
    if math.isnan(value):
        return missing
    if math.isinf(value):
        return unbounded if value > 0 else f"−{unbounded}"
    return f"{value:{spec}}" + (f" {unit}" if unit else "")
