"""The macro-element in the advisor's continuum ladder (issue 36 §4): its calibration read and
checked before any run, and why it is left out without one.

The ``macro`` bed is the element fitted to the continuum's statics of the scene's soil
(``upliftlab calibrate SCENE`` makes it, minutes to an hour); the advisor does not fit it, it
takes the user's ``calibration.json`` (``--macro-calibration``), builds the element under the
scene's structure with the ladder's own K_v and K_r (the finest mesh's, as every bed), and
certifies it against the continuum's runs like any bed. Without one, the ladder says how to make
it.
"""

from __future__ import annotations

import math

from ...checks import InputError
from ...paths import NO_SUCH_FILE, REGULAR_FILE, file_kind
from ...scenes import Scene

__all__ = ["MACRO_NEEDS", "read_macro_calibration"]

#: Why the ``macro`` bed is not built without a calibration (the advice's line for it).
MACRO_NEEDS = ("the macro-element is fitted to the continuum's statics of the scene's soil at "
               "several FS_v (minutes to an hour): make it once with `upliftlab calibrate "
               "SCENE`, then pass --macro-calibration OUT/calibration.json")


def read_macro_calibration(path, scene: Scene) -> dict:
    """The law of a ``calibration.json`` written by ``upliftlab calibrate`` (its ``law``: a
    :class:`~upliftlab.reduced.laws.macro.MacroElement`'s fields), refused in one line where
    the file cannot be read, is not such a record, or was made for another footing width."""
    import json
    from pathlib import Path

    from ...reduced.laws.macro import MacroElement

    where = f"--macro-calibration = {str(path)!r}"
    kind = file_kind(path, where)  # examined before it is opened: a named pipe would block
    if kind not in (REGULAR_FILE, NO_SUCH_FILE):  # a missing file is refused below
        raise InputError(f"{where}: {kind}, not a regular file; valid: the calibration.json "
                         "written by `upliftlab calibrate SCENE`")
    try:
        record = json.loads(Path(path).read_text())
        law = MacroElement(**{k: float(v) for k, v in record["law"].items()})
    except (OSError, ValueError, TypeError, KeyError, AttributeError) as exc:
        raise InputError(f"{where}: not a calibration written by `upliftlab calibrate` "
                         f"({type(exc).__name__}: {exc}); valid: its calibration.json") from None
    if not math.isclose(law.width, scene.foundation.width, rel_tol=1e-9):
        raise InputError(f"{where}: made for a footing {law.width:g} wide, the scene's is "
                         f"{scene.foundation.width:g}; valid: a calibration of this footing "
                         "(`upliftlab calibrate SCENE`)")
    return {"law": {k: float(v) for k, v in record["law"].items()},
            "scene": str(record.get("scene", "")), "path": str(path)}
