"""A scene's own table, and changing a scene so that its description follows its fields.

:func:`scene_table` writes a :class:`~upliftlab.scenes.Scene` back as the table a scene file
would hold: every field explicit (defaults, and stiffnesses derived from periods), only the
keys that apply (a record's ``name``, not a pulse's ``amplitude``). Validating that table
gives back the same scene, so the table — and the digest computed from it — describe the
fields, not the file the scene was once read from.

:func:`revalidate` runs for every scene made otherwise than by
:func:`~upliftlab.scenes.scene_from_dict` (``dataclasses.replace``, or :meth:`Scene.replace`):
the fields are validated again through their table, with the same checks and messages as a
file; a field that the table cannot hold (it does not apply to this scene) is an error; and
when the fields no longer match the scene's ``data``, ``data`` becomes their table and the
changes are appended to ``overrides`` (``foundation.springs=40``), so that a run's provenance
names them.
"""

from __future__ import annotations

import dataclasses
import json
import math

from ..checks import InputError
from .laws import LAWS, LawRecord
from .table import SCHEMA_VERSION

__all__ = ["scene_table", "revalidate", "replace_fields", "flatten"]

#: The fields of a scene that its table holds (the rest say where it came from).
PHYSICS = ("title", "description", "reference", "units", "structure", "foundation", "motion",
           "analysis", "soil", "continuum")

_MOTION_KEYS = {
    "record": ("name", "scale", "pga"),
    "free": ("velocity", "displacement", "rotation"),
    "sine": ("amplitude", "period", "cycles"),
    "cosine": ("amplitude", "period", "cycles"),
    "ricker": ("amplitude", "period", "delay"),
    "harmonic": ("amplitude", "period"),
}


def _value(value):
    if isinstance(value, tuple):
        return [_value(v) for v in value]
    return value


def _plain(record, keys=None) -> dict:
    """The non-None fields of a record (``keys``: only these, in this order)."""
    names = keys if keys is not None else [f.name for f in dataclasses.fields(record)]
    return {k: _value(getattr(record, k)) for k in names if getattr(record, k) is not None}


def _structure_table(structure) -> dict:
    others = [f.name for f in dataclasses.fields(structure) if f.name != "stories"]
    stories = structure.stories
    if len(stories) == 1 and stories[0].damping_ratio is None:  # an SDOF: one flat table
        story = _plain(stories[0])
        return {**story, **_plain(structure, others)}
    return {"story": [_plain(s) for s in stories], **_plain(structure, others)}


def _foundation_table(foundation) -> dict:
    """The foundation's keys, its law's own keys right after ``law`` (the law's name)."""
    skip = set()
    if foundation.layout != "custom":
        skip |= {"positions", "stiffnesses"}
    else:
        skip.add("stiffness")
    if foundation.layout != "end_stiffened":
        skip |= {"end_stiffness_ratio", "end_length"}
    table = {}
    for name in (f.name for f in dataclasses.fields(foundation) if f.name not in skip):
        if name == "law":
            if not isinstance(foundation.law, LawRecord):
                raise InputError(f"foundation.law = {foundation.law!r}: a law's record is "
                                 "expected (upliftlab.scenes.laws; Scene.replace also takes "
                                 "its name)")
            table["law"] = foundation.law.name
            table.update(foundation.law.table())
        elif getattr(foundation, name) is not None:
            table[name] = _value(getattr(foundation, name))
    return table


def _motion_table(motion) -> dict:
    keys = ["type", *_MOTION_KEYS[motion.type], "duration", "dt"]
    if motion.type == "record":
        keys.remove("pga" if motion.pga is None else "scale")
    return _plain(motion, keys)


#: Fields added after results were kept, left out of the table at the value that means what
#: their absence meant, so that every scene written before them keeps its table and digest
#: (and the results keyed on it stay reachable): (table, field): that value.
NEUTRAL_DEFAULTS = {("soil", "undrained_strength_gradient"): 0.0}


def scene_table(scene) -> dict:
    """The table of ``scene``'s fields, as a scene file would hold it (module docstring);
    a field of :data:`NEUTRAL_DEFAULTS` at its neutral value is left out."""
    table = {"schema": SCHEMA_VERSION, "units": scene.units.name}
    for key in ("title", "description", "reference"):
        if getattr(scene, key):
            table[key] = getattr(scene, key)
    table["structure"] = _structure_table(scene.structure)
    table["foundation"] = _foundation_table(scene.foundation)
    table["motion"] = _motion_table(scene.motion)
    table["analysis"] = _plain(scene.analysis)
    for key in ("soil", "continuum"):
        if getattr(scene, key) is not None:
            table[key] = _plain(getattr(scene, key))
    for (key, name), neutral in NEUTRAL_DEFAULTS.items():
        if key in table and table[key].get(name, neutral) == neutral:
            table[key].pop(name, None)
    return table


def flatten(table: dict, prefix: str = "") -> dict:
    """``{"a": {"b": 1}}`` -> ``{"a.b": 1}``; lists of tables are indexed (``story.0.weight``)."""
    out = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(flatten(value, name + "."))
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for i, item in enumerate(value):
                out.update(flatten(item, f"{name}.{i}."))
        else:
            out[name] = value
    return out


def _toml(value) -> str:
    """A value as TOML text (for the overrides a change is recorded as)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, float) and math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def _normal(value):
    """For comparing a field with its validated value: tuples as lists, ints as floats."""
    if isinstance(value, LawRecord):  # a law is its name and its fields
        return {"name": value.name, **{k: _normal(getattr(value, k)) for k in value.keys()}}
    if dataclasses.is_dataclass(value):
        return {f.name: _normal(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, (tuple, list)):
        return [_normal(v) for v in value]
    if isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    return value


def _first_difference(given, kept, path: str):
    if isinstance(given, dict) and isinstance(kept, dict):
        for key in given:
            found = _first_difference(given[key], kept.get(key), f"{path}.{key}")
            if found:
                return found
        return None
    if isinstance(given, list) and isinstance(kept, list) and len(given) == len(kept):
        for i, (a, b) in enumerate(zip(given, kept)):
            found = _first_difference(a, b, f"{path}.{i}")
            if found:
                return found
        return None
    return None if given == kept else (path, given, kept)


def revalidate(scene, scene_from_dict) -> None:
    """Validate a scene made from fields (module docstring) by ``scene_from_dict``, the
    validation of a scene file; adjust ``data``, ``overrides`` and the fields' types in place
    (the scene is not yet shared)."""
    table = scene_table(scene)
    again = scene_from_dict(table, source=scene.source, case=scene.case, merged=True)
    for name in PHYSICS:
        given, kept = _normal(getattr(scene, name)), _normal(getattr(again, name))
        if given != kept:
            where = _first_difference(given, kept, name) or (name, given, kept)
            path = where[0].replace(".stories.", ".story.")
            raise InputError(f"{path} = {where[1]!r}: does not apply to this scene (its "
                             f"{name} keeps {where[2]!r}); change a scene with fields that "
                             "apply to it")
        object.__setattr__(scene, name, getattr(again, name))
    old = None
    if scene.data:
        try:
            old = scene_table(scene_from_dict(scene.data, source=scene.source, case=scene.case,
                                              merged=True))
        except InputError:
            old = None
    if old == table:
        return
    changes = _changes(old or {}, table)
    object.__setattr__(scene, "data", table)
    object.__setattr__(scene, "overrides", tuple(scene.overrides) + tuple(changes))


def _changes(old: dict, new: dict) -> list[str]:
    """``key=value`` overrides that turn table ``old`` into ``new`` (``key=`` removes)."""
    a, b = flatten(old), flatten(new)
    out = [f"{k}={_toml(v)}" for k, v in b.items() if k not in a or a[k] != v]
    out += [f"{k}=" for k in a if k not in b]
    return out


_TABLES = ("structure", "foundation", "motion", "analysis", "soil", "continuum")


def replace_fields(scene, table: str, fields: dict):
    """:meth:`Scene.replace`: ``scene`` with ``fields`` of record ``table`` changed."""
    if not fields:
        raise InputError(f"Scene.replace({table!r}): no field given")
    parts = table.split(".")
    if parts[0] == "structure" and len(parts) == 3 and parts[1] == "story":
        parts = parts[1:]
    if parts[0] == "story":
        stories = scene.structure.stories
        index = 0 if len(parts) == 1 else parts[1]
        if not str(index).isdigit() or int(index) >= len(stories):
            raise InputError(f"Scene.replace({table!r}): the structure has stories "
                             f"0..{len(stories) - 1}")
        i = int(index)
        story = _replaced(stories[i], fields, f"structure.story.{i}")
        record = dataclasses.replace(scene.structure,
                                     stories=stories[:i] + (story,) + stories[i + 1:])
        return dataclasses.replace(scene, structure=record)
    if len(parts) != 1 or parts[0] not in _TABLES:
        raise InputError(f"Scene.replace({table!r}): valid tables are "
                         f"{', '.join(_TABLES)}, story and story.N")
    current = getattr(scene, table)
    if current is None:
        raise InputError(f"Scene.replace({table!r}): the scene has no [{table}] table")
    return dataclasses.replace(scene, **{table: _replaced(current, fields, table)})


def _replaced(record, fields: dict, path: str):
    names = [f.name for f in dataclasses.fields(record)]
    if path == "foundation":
        return _replaced_foundation(record, fields, names)
    for key in fields:
        if key not in names:
            raise InputError(f"{path}.{key}: not a field of {type(record).__name__} (fields: "
                             f"{', '.join(names)})")
    return dataclasses.replace(record, **fields)


def _replaced_foundation(foundation, fields: dict, names: list[str]):
    """The foundation with ``fields`` changed, its law's keys gathered into its law's record
    as a scene file writes them: ``z50=0.2`` changes the current law's; ``law="qz",
    capacity_multiple=3, z50=0.1`` makes a record of another law (``law`` may be a record)."""
    law = fields.get("law", foundation.law)
    if isinstance(law, str):
        if law not in LAWS:
            raise InputError(f"foundation.law = {law!r}: must be one of {', '.join(LAWS)}")
        law_class = LAWS[law]
        law = foundation.law if law == foundation.law.name else None
    elif isinstance(law, LawRecord):
        law_class = type(law)
    else:
        raise InputError(f"foundation.law = {law!r}: give a law's name or its record "
                         "(upliftlab.scenes.laws)")
    keys = law_class.keys()
    for key in fields:
        if key not in names and key not in keys:
            raise InputError(f"foundation.{key}: not a field of Foundation or of its law "
                             f"{law_class.__name__} (fields: {', '.join(names + list(keys))})")
    own = {k: v for k, v in fields.items() if k in keys}
    try:
        law = law_class(**own) if law is None else dataclasses.replace(law, **own)
    except TypeError as exc:
        raise InputError(f"foundation.law = {law_class.name!r}: {exc}") from None
    rest = {k: v for k, v in fields.items() if k not in keys}
    return dataclasses.replace(foundation, **{**rest, "law": law})
