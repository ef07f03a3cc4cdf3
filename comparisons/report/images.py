"""Images inside the page: a figure's file as a base64 data URI, so that the report is one
self-contained file that opens offline."""

from __future__ import annotations

import base64
from pathlib import Path

__all__ = ["data_uri"]

_TYPES = {".svg": "image/svg+xml", ".png": "image/png"}


def data_uri(path: Path) -> str:
    """``path`` (SVG or PNG) as a base64 data URI."""
    path = Path(path)
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f"data:{_TYPES[path.suffix]};base64,{data}"
