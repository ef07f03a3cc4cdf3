"""Changing a scene's table before it is validated: merging one of its ``[cases.X]`` tables,
and ``--set`` overrides by dotted TOML key (the command line's way to vary a scene; in code,
:meth:`~upliftlab.scenes.Scene.replace` is typed and re-validating)."""

from __future__ import annotations

import copy
import tomllib

from ..checks import InputError
from ..paths import path_component
from ..units import UNIT_SYSTEMS

__all__ = ["merge_case", "deep_merge", "override_key", "check_case_override", "apply_overrides",
           "parse_value", "apply_override"]


def merge_case(data: dict, case: str | None) -> dict:
    """``data`` without its ``cases`` table, with the table of ``case`` merged in."""
    cases = data.pop("cases", {})
    if isinstance(cases, dict):
        for name in cases:  # a case names its output files: one plain path component
            path_component(name, f"cases.{name}")
    if case is None:
        return data
    path_component(case, "case")
    if not isinstance(cases, dict) or case not in cases:
        valid = ", ".join(map(repr, cases)) if isinstance(cases, dict) and cases else "none"
        raise InputError(f"case = {case!r}: not defined in this scene (cases: {valid})")
    declared = data.get("units")
    deep_merge(data, cases[case], f"cases.{case}")
    _same_units(declared, data.get("units"), f"cases.{case}.units", "a case table")
    return data


def _same_units(declared, new, where: str, changer: str) -> None:
    """Refuse a change of the unit system after the scene's numbers were written: it would
    reinterpret every number of the scene (kip and inch read as newton and metre)."""
    if declared is not None and isinstance(new, str) and new != declared and new in UNIT_SYSTEMS:
        raise InputError(f"{where} = {new!r}: every number of this scene is in {declared!r}; "
                         f"{changer} cannot convert them. Write the values in "
                         f"{new!r} in a scene file of its own")


def deep_merge(base: dict, patch: dict, path: str) -> None:
    """Merge table ``patch`` into ``base`` in place, key by key."""
    if not isinstance(patch, dict):
        raise InputError(f"{path} = {patch!r}: expected a table")
    for key, value in patch.items():
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            deep_merge(base[key], value, f"{path}.{key}")
        else:
            base[key] = copy.deepcopy(value)


def override_key(item: str) -> str:
    """The dotted key of a ``key=value`` override."""
    return item.split("=", 1)[0].strip()


def check_case_override(item: str, case: str | None, cases) -> None:
    """An override of ``cases.X...`` only means something for the case that runs."""
    parts = [p for p in override_key(item).split(".") if p]
    if len(parts) < 3 or parts[1] != case:
        running = f"case {case!r}" if case is not None else "no case (--case is not given)"
        raise InputError(f"--set {item!r}: has no effect: this run uses {running}; "
                         f"override the scene's fields directly (e.g. --set "
                         f"{'.'.join(parts[2:]) or 'foundation.restitution'}=...), or select "
                         f"the case with --case {parts[1] if len(parts) > 1 else 'X'}")
    if not isinstance(cases, dict) or not isinstance(cases.get(case), dict):
        raise InputError(f"--set {item!r}: the scene has no table cases.{case}")


def apply_overrides(data: dict, overrides) -> None:
    """Apply ``overrides`` in order; refuse one that changes the unit system, which would
    reinterpret every number of the scene in other units."""
    declared = data.get("units")
    for item in overrides:
        if override_key(item).split(".")[0] == "cases":
            raise InputError(f"--set {item!r}: has no effect: the scene's case is already "
                             "merged; override the scene's fields directly")
        apply_override(data, item)
    _same_units(declared, data.get("units"), "units", "an override")


def parse_value(text: str):
    """An override's value read as TOML, else the text itself."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text
    except RecursionError:
        raise InputError(f"--set value {text[:20]!r}…: tables or lists nested too deeply to "
                         "read; a scene's field nests at most a few levels") from None


def apply_override(data: dict, item: str) -> None:
    """Apply one ``dotted.key=value`` override in place. The value is read as TOML, else text.

    List entries are addressed by index: ``structure.story.1.stiffness=300``. An empty value
    removes the key: ``foundation.vertical_period=``.
    """
    if "=" not in item:
        raise InputError(f"--set {item!r}: expected KEY=VALUE with a dotted TOML key")
    key, text = item.split("=", 1)
    parts = key.strip().split(".")
    if not key.strip():
        raise InputError(f"--set {item!r}: empty key")
    if not all(part.strip() for part in parts):
        raise InputError(f"--set {item!r}: the key has an empty part ('..', or a '.' at an "
                         "end); a dotted TOML key names each table once: structure.weight=…")
    node = data
    for depth, part in enumerate(parts[:-1]):
        where = ".".join(parts[: depth + 1])
        if isinstance(node, list):
            node = node[list_index(part, node, where)]
        else:
            node = node.setdefault(part, {})
        if not isinstance(node, (dict, list)):
            raise InputError(f"--set {item!r}: {where} is a value, not a table")
    last = parts[-1]
    if isinstance(node, list):
        node[list_index(last, node, key)] = parse_value(text.strip())
    elif not text.strip():
        node.pop(last, None)
    else:
        node[last] = parse_value(text.strip())


def list_index(part: str, node: list, where: str) -> int:
    """``part`` as an index of ``node``: ASCII digits 0-9 only (``str.isdigit`` also takes
    '²', '٣' and '１', which ``int`` refuses or reads as other numbers), within the list."""
    if not (part.isascii() and part.isdigit() and len(part) <= 9) or int(part) >= len(node):
        raise InputError(f"--set {where}: index {part!r} is not in 0..{len(node) - 1} "
                         "(written in the digits 0-9)")
    return int(part)
