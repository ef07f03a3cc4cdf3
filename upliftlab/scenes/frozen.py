"""Read-only tables: a scene's ``data`` (the merged table it came from, which a run's
provenance records) cannot be changed after the scene is made, so the provenance always
describes the scene that ran. Before, ``scene.data["structure"]["weight"] = 1`` changed what a
result's provenance claimed while the run used the scene's fields.

:func:`freeze` copies a parsed TOML table into :class:`FrozenTable` and :class:`FrozenList`
(a ``dict`` and a ``list`` that refuse every change). They read, compare, serialise to JSON and
pickle as a dict and a list; ``copy.deepcopy`` gives back plain, mutable ones, the way a
caller derives a changed table (``data = copy.deepcopy(scene.data)``; ``data[...] = ...``).
"""

from __future__ import annotations

import copy

__all__ = ["FrozenTable", "FrozenList", "freeze", "thaw"]

_WHY = ("a scene's data is read-only (it is what the run's provenance records); change the "
        "scene with Scene.replace or Scene.with_overrides, or edit copy.deepcopy(scene.data)")


def _refuse(self, *args, **kwargs):
    raise TypeError(_WHY)


class FrozenTable(dict):
    """A TOML table that cannot be changed (module docstring)."""

    __slots__ = ()
    __setitem__ = __delitem__ = __ior__ = _refuse
    clear = pop = popitem = setdefault = update = _refuse

    def __deepcopy__(self, memo) -> dict:
        return {k: copy.deepcopy(v, memo) for k, v in self.items()}

    def __copy__(self) -> dict:
        return dict(self)

    def __reduce__(self):
        return freeze, (thaw(self),)


class FrozenList(list):
    """A TOML array that cannot be changed (module docstring)."""

    __slots__ = ()
    __setitem__ = __delitem__ = __iadd__ = __imul__ = _refuse
    append = extend = insert = pop = remove = clear = sort = reverse = _refuse

    def __deepcopy__(self, memo) -> list:
        return [copy.deepcopy(v, memo) for v in self]

    def __copy__(self) -> list:
        return list(self)

    def __reduce__(self):
        return freeze, (thaw(self),)


def freeze(value):
    """A read-only deep copy of a parsed TOML value (tables and arrays at any depth)."""
    if isinstance(value, dict):
        return FrozenTable((k, freeze(v)) for k, v in value.items())
    if isinstance(value, list):
        return FrozenList(freeze(v) for v in value)
    return value


def thaw(value):
    """A plain, mutable deep copy of a (frozen) TOML value."""
    if isinstance(value, dict):
        return {k: thaw(v) for k, v in value.items()}
    if isinstance(value, list):
        return [thaw(v) for v in value]
    return value
