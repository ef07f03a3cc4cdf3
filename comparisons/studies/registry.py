"""The studies of the report, in the report's order, by module name under
``upliftlab.comparisons``. Each module defines ``DEFINITION``, a :class:`.protocol.Study`.

Modules are imported when asked for (:func:`definition`), one at a time, so that a study that
does not exist yet or fails to import leaves only its own section without results.
"""

from __future__ import annotations

import importlib

from ..framework.protocol import Study

__all__ = ["STUDIES", "definition"]

STUDIES: tuple[str, ...] = ("verification", "two_spring_equivalence", "winkler_vs_continuum",
                            "winkler_map", "speed_vs_error", "fixed_vs_uplift", "paper",
                            "uplift_zone")


def definition(module: str) -> Study:
    """The :class:`.protocol.Study` of ``upliftlab.comparisons.<module>``. Raises
    ModuleNotFoundError when the module does not exist, TypeError when it defines no study."""
    found = getattr(importlib.import_module(f"{__package__}.{module}"), "DEFINITION", None)
    if not isinstance(found, Study):
        raise TypeError(f"{__package__}.{module} defines no DEFINITION (a protocol.Study)")
    return found
