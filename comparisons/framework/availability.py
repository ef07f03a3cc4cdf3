"""Whether the continuum's dynamics can run here: the studies that compare against it say so,
and skip those runs, when it cannot be imported (a missing optional dependency)."""

from __future__ import annotations

__all__ = ["continuum_status"]


def continuum_status() -> tuple[bool, str]:
    """(available, why): whether the continuum dynamics module can be imported."""
    try:
        from ...continuum.dynamics import run as dynamics  # noqa: F401
    except Exception as exc:  # noqa: BLE001 — any failure to import means "not available"
        return False, (f"continuum points were not run: upliftlab.continuum.dynamics is not "
                       f"available ({type(exc).__name__}: {exc})")
    return True, "upliftlab.continuum.dynamics is available"
