"""The ``{finding}`` role: a number of a findings page, read from a study's committed outputs.

A findings page never types a number that a study computed. It writes, in MyST::

    the pair caps the moment at
    {finding}`two_spring_equivalence:numbers.capacity_ratio_equivalent_vs_winkler;.3f` of the
    bed's

and the build reads ``docs/findings/data/two_spring_equivalence.json`` (written from the
study's output folder by ``docs/findings/update.py``), follows the key path into it and formats
the value. The text is ``STUDY:PATH`` or ``STUDY:PATH;FORMAT``:

- ``PATH`` is a dotted key path into the file's ``summary`` (``numbers.share.best_share``); a
  key with a dot or a space in it is written in brackets and quotes
  (``numbers.capacity_fits["clay FS_v=2"].beta``), and a list index as a number
  (``conclusions.0.verdict``), and the element of a list of records whose field has a value
  as ``[FIELD=VALUE]`` (``numbers.rows[id=K_r].error``); ``[@PATH]`` is the key that the value
  at PATH names (``numbers.picks.theta.median[@numbers.picks.theta.best]``: the median of the
  best bed, whichever it is); a path that starts with ``/`` is taken from the file's top level
  (``/source``).
- ``FORMAT`` is a Python format spec (``.3f``, ``.3g``, ``,d``), with three additions: a spec
  ending in ``%`` prints a fraction as a percentage with a space before the sign
  (``.1%``: 0.1263 -> "12.6 %"), ``%s`` a signed percentage ("+1.7 %"), and ``x`` a ratio with
  a times sign (``.0fx``: 3357.2 -> "3357×").

(``|`` is accepted as the separator too, outside a Markdown table, where it would split the
cell.) A missing file, a missing key or a value the format cannot print is a warning, and so is
a ``{finding}`` left unparsed in a page (a role broken by a table's bars, say), so the strict
build (``-W``) fails: a page never shows a blank where a number was meant to be.
"""

from __future__ import annotations

import json
import math
import re
from functools import lru_cache
from pathlib import Path

from docutils import nodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxRole

logger = logging.getLogger(__name__)

DATA = Path(__file__).resolve().parents[1] / "findings" / "data"
_TOKEN = re.compile(r"""\[\s*(?:"([^"]*)"|'([^']*)'|(-?\d+)|(\w+)\s*=\s*([^\]]*?)|@([^\]]+))\s*\]"""
                    r"""|([^.\[\]]+)""")


class FindingError(LookupError):
    """A reference that names no value of the study's data."""


class Pointer(str):
    """A key given as the path of the value that names it (``[@numbers.picks.theta.best]``)."""


@lru_cache(maxsize=None)
def load(study: str, root: str = str(DATA)) -> dict:
    """The committed data of ``study`` (``findings/data/<study>.json``)."""
    path = Path(root) / f"{study}.json"
    if not path.is_file():
        raise FindingError(f"no findings data for study {study!r}: {path} is missing "
                           "(run docs/findings/update.py)")
    return json.loads(path.read_text(encoding="utf-8"))


def keys(path: str) -> list:
    """The keys of a dotted path: ``a.b["c d"].0`` -> ['a', 'b', 'c d', 0]."""
    out, position = [], 0
    for match in _TOKEN.finditer(path):
        if path[position:match.start()].strip(". "):
            raise FindingError(f"cannot read the key path {path!r} near "
                               f"{path[position:match.start()]!r}")
        quoted, single, index, field, wanted, pointer, bare = match.groups()
        if pointer is not None:  # [@a.b]: the key is the value at path a.b
            out.append(Pointer(pointer.strip()))
        elif field is not None:  # [id=K_r]: the list's element whose "id" is "K_r"
            out.append((field, wanted.strip().strip("'\"")))
        elif bare is not None:
            bare = bare.strip()
            out.append(int(bare) if re.fullmatch(r"-?\d+", bare) else bare)
        elif index is not None:
            out.append(int(index))
        else:
            out.append(quoted if quoted is not None else single)
        position = match.end()
    if not out:
        raise FindingError(f"empty key path {path!r}")
    return out


def lookup(data: dict, path: str):
    """The value at ``path`` in a study's data (its ``summary``, or the top with ``/``)."""
    node = data if path.startswith("/") else data.get("summary", {})
    walked = []
    for key in keys(path.lstrip("/")):
        if isinstance(key, Pointer):
            key = lookup(data, str(key))
            if not isinstance(key, (str, int)):
                raise FindingError(f"[@{key}] names no key")
        walked.append(f"[{key[0]}={key[1]}]" if isinstance(key, tuple) else str(key))
        if isinstance(key, tuple) and isinstance(node, list):
            found = [x for x in node if isinstance(x, dict) and str(x.get(key[0])) == key[1]]
            if not found:
                raise FindingError(f"no element with {key[0]} = {key[1]!r} at "
                                   f"{'.'.join(walked)!r}")
            node = found[0]
        elif isinstance(node, list) and isinstance(key, int) and -len(node) <= key < len(node):
            node = node[key]
        elif isinstance(node, dict) and str(key) in node:
            node = node[str(key)]
        else:
            have = (sorted(node)[:12] if isinstance(node, dict) else
                    f"a list of {len(node)}" if isinstance(node, list) else repr(node))
            raise FindingError(f"no key {'.'.join(walked)!r} (there: {have})")
    return node


def formatted(value, spec: str) -> str:
    """``value`` printed with ``spec`` (see the module's docstring)."""
    if isinstance(value, bool) or value is None:
        if spec:
            raise FindingError(f"{value!r} is not a number (format {spec!r})")
        return {True: "yes", False: "no", None: "none"}[value]
    if isinstance(value, (dict, list)):
        raise FindingError(f"the key names a {type(value).__name__}, not a value")
    if isinstance(value, str):
        if spec:
            raise FindingError(f"{value!r} is text (format {spec!r})")
        return value
    if not math.isfinite(value):
        return "∞" if value > 0 else "−∞" if value < 0 else "NaN"
    try:
        if spec.endswith("%s"):
            text = format(100.0 * value, "+" + spec[:-2] + "f") + " %"
        elif spec.endswith("%"):
            text = format(100.0 * value, spec[:-1] + "f") + " %"
        elif spec.endswith("x") and spec != "x":
            text = format(value, spec[:-1]) + "×"
        else:
            text = format(value, spec)
    except (TypeError, ValueError) as exc:
        raise FindingError(f"cannot format {value!r} with {spec!r}: {exc}") from exc
    return text.replace("-", "−")  # a minus sign, not a hyphen


def resolve(text: str, root: str = str(DATA)) -> str:
    """``STUDY:PATH[;FORMAT]`` -> the printed value."""
    reference, _, spec = text.partition(";") if ";" in text else text.partition("|")
    study, sep, path = reference.partition(":")
    if not sep or not study.strip() or not path.strip():
        raise FindingError(f"expected STUDY:PATH or STUDY:PATH;FORMAT, got {text!r}")
    return formatted(lookup(load(study.strip(), root), path.strip()), spec.strip())


class FindingRole(SphinxRole):
    """``{finding}`STUDY:PATH;FORMAT``` -> the value, as plain text."""

    def run(self):
        study = self.text.partition(":")[0].strip()
        self.env.note_dependency(str(DATA / f"{study}.json"))  # rebuilt when the data change
        try:
            value = resolve(self.text)
        except FindingError as exc:
            logger.warning("finding %r: %s", self.text, exc, location=self.get_location(),
                           type="findings", subtype="missing")
            return [nodes.problematic(self.rawtext, self.rawtext)], []
        node = nodes.inline(value, value, classes=["finding"])
        return [node], []


class FindingSource(SphinxRole):
    """``{finding-source}`STUDY``` -> where the study's data came from, in one line."""

    def run(self):
        self.env.note_dependency(str(DATA / f"{self.text.strip()}.json"))
        try:
            data = load(self.text.strip())
            text = (f"{data['source']}, {'fast' if data.get('fast') else 'full'} build, "
                    f"upliftlab {data.get('upliftlab_version', '?')}, "
                    f"{data.get('created_utc', '?')}")
        except (FindingError, KeyError) as exc:
            logger.warning("finding-source %r: %s", self.text, exc,
                           location=self.get_location(), type="findings", subtype="missing")
            return [nodes.problematic(self.rawtext, self.rawtext)], []
        return [nodes.emphasis(text, text)], []


def unparsed(app, doctree, docname):
    """A ``{finding}`` role that reached the page as text (never parsed) is an error."""
    for node in doctree.findall(nodes.Text):
        if "{finding" in node.astext() and not isinstance(node.parent, nodes.literal):
            logger.warning("a {finding} role was not parsed (inside a table cell, a | splits "
                           "it: use ; before the format): %r", node.astext()[:80],
                           location=node.parent, type="findings", subtype="unparsed")


def setup(app):
    app.connect("doctree-resolved", unparsed)
    app.add_role("finding", FindingRole())
    app.add_role("finding-source", FindingSource())
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
