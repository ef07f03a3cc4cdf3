"""The ``scene-reference`` directive: the scene's fields, generated from its records.

Nothing of it is typed by hand. The directive starts from :class:`upliftlab.scenes.Scene` and
walks every frozen dataclass its fields hold (through ``X | None``, ``tuple[X, ...]``, unions,
and the subclasses of a base class that is not itself a dataclass, e.g. one record per
foundation law), recursively, then adds any other dataclass defined in the modules of
:mod:`upliftlab.scenes`. For each record it prints its docstring and a table of its fields:

- the field's **type** and **default** (the reader's default, where the reader of its TOML
  table gives one: ``required`` when it must be given; else the dataclass's);
- its **unit and valid range**: from the check its reader applies to the TOML key of the same
  name: a physical kind of :mod:`upliftlab.bounds` (unit in the scene's system, range in SI),
  ``in_range``, ``choice`` (the values), ``bounded_integer``, or the field's own
  attribute docstring;
- its **description**: its attribute docstring (``#:`` or a string after it) when it has one,
  else the sentences of the record's docstring that name it in double back-quotes.

The readers are found by reading the source of the record's module (``ast``): a function whose
return annotation or whose body builds the record, and the helpers it calls. Keys a reader
reads that are no field of the record (``period`` for ``stiffness``) are listed below its table.
A record whose readers cannot be found still gets its fields, types and defaults.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib
import inspect
import math
import pkgutil
import re
import sys
import types
import typing
from functools import lru_cache

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

ROOT_RECORD = "upliftlab.scenes.Scene"
SCENE_PACKAGE = "upliftlab.scenes"


# ---------------------------------------------------------------------------------------------
# Which records
# ---------------------------------------------------------------------------------------------

def _import(path: str):
    module, _, name = path.rpartition(".")
    return getattr(importlib.import_module(module), name)


def _members_of(hint) -> list[type]:
    """The classes a type hint names: through Optional, unions, tuples, lists and dicts."""
    if isinstance(hint, type) and not typing.get_args(hint):
        return [hint]
    found = []
    for arg in typing.get_args(hint):
        if arg is not Ellipsis and arg is not type(None):
            found += _members_of(arg)
    return found


def _hints(cls) -> dict:
    try:
        return typing.get_type_hints(cls)
    except Exception:  # an unresolvable annotation: fall back to the raw ones
        return {f.name: f.type for f in dataclasses.fields(cls)}


def _subclasses(cls) -> list[type]:
    out = []
    for sub in cls.__subclasses__():
        out += [sub, *_subclasses(sub)]
    return out


def records() -> list[type]:
    """Every record of a scene, in the order a reader meets them (depth first from Scene),
    then the scene modules' other dataclasses."""
    order: list[type] = []

    def visit(cls):
        if cls in order or not cls.__module__.startswith("upliftlab"):
            return
        if dataclasses.is_dataclass(cls):
            order.append(cls)
            for hint in _hints(cls).values():
                for member in _members_of(hint):
                    visit(member)
        for sub in _subclasses(cls):  # one record per law under a common base, say
            visit(sub)

    visit(_import(ROOT_RECORD))
    package = importlib.import_module(SCENE_PACKAGE)
    for info in pkgutil.iter_modules(package.__path__, SCENE_PACKAGE + "."):
        module = importlib.import_module(info.name)
        for _, obj in inspect.getmembers(module, inspect.isclass):
            if obj.__module__ == module.__name__ and dataclasses.is_dataclass(obj):
                visit(obj)
    return order


# ---------------------------------------------------------------------------------------------
# What the readers check
# ---------------------------------------------------------------------------------------------

@dataclasses.dataclass
class KeyRule:
    """What a reader does with one TOML key."""

    key: str
    rule: str = ""
    default: str | None = None  # None: none given to the reader


@lru_cache(maxsize=None)
def _module_tree(modname: str):
    module = sys.modules[modname]
    try:
        source = inspect.getsource(module)
    except (OSError, TypeError):
        return None, {}
    tree = ast.parse(source)
    functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    return tree, functions


def _module_assigns(modname: str) -> dict:
    """Module-level ``NAME = expression`` (a shared check: ``MULTIPLE = in_range(...)``)."""
    tree, _ = _module_tree(modname)
    if tree is None:
        return {}
    return {t.id: n.value for n in tree.body if isinstance(n, ast.Assign)
            for t in n.targets if isinstance(t, ast.Name)}


def _methods(cls) -> list[ast.FunctionDef]:
    """The record's own methods that read it: ``read`` and its kin (a classmethod that
    returns ``cls(...)``)."""
    tree, _ = _module_tree(cls.__module__)
    if tree is None:
        return []
    body = next((n.body for n in tree.body
                 if isinstance(n, ast.ClassDef) and n.name == cls.__name__), [])
    return [f for f in body if isinstance(f, ast.FunctionDef)
            and (f.name.startswith("read") or _builds(f, cls.__name__)
                 or _builds(f, "cls"))]


def _builds(function: ast.FunctionDef, name: str) -> bool:
    """Whether ``function`` returns a ``name`` (annotation) or calls ``name(...)``."""
    returns = ast.unparse(function.returns) if function.returns else ""
    if re.search(rf"\b{name}\b", returns):
        return True
    return any(isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == name
               for n in ast.walk(function))


def _calls(function: ast.FunctionDef, functions: dict) -> list[str]:
    return [n.func.id for n in ast.walk(function) if isinstance(n, ast.Call)
            and isinstance(n.func, ast.Name) and n.func.id in functions]


def reader_functions(cls) -> list[ast.FunctionDef]:
    """The functions of the record's module that read it: those that build it, and the helpers
    they call that build no other record."""
    _, functions = _module_tree(cls.__module__)
    module = sys.modules[cls.__module__]
    others = {n for n, obj in vars(module).items() if dataclasses.is_dataclass(obj)
              and isinstance(obj, type) and obj is not cls}
    own = [f for f in functions.values() if _builds(f, cls.__name__)] + _methods(cls)
    seen = {f.name for f in own}
    queue = list(own)
    while queue:
        for name in _calls(queue.pop(), functions):
            helper = functions[name]
            if name not in seen and not any(_builds(helper, o) for o in others):
                seen.add(name)
                own.append(helper)
                queue.append(helper)
    return own


class Expression(str):
    """Source text of a value the reader computes (a default that depends on other keys)."""


def _evaluate(node, module) -> object:
    try:
        return eval(compile(ast.Expression(node), "<scene_reference>", "eval"),  # noqa: S307
                    vars(module))
    except Exception:
        return Expression(ast.unparse(node))


def _number(value) -> str:
    if isinstance(value, float):
        if math.isinf(value):
            return "∞" if value > 0 else "−∞"
        return f"{value:g}".replace("-", "−")
    return str(value)


def _kind_rule(kind: str) -> str:
    from upliftlab import bounds

    k = bounds.KINDS.get(kind)
    if k is None:
        return f"kind {kind}"
    unit = k.template.format(F="force", L="length").replace("*", "·")
    left = "(" if k.low_open else "["
    return f"{unit}; {left}{_number(k.low)}, {_number(k.high)}] {k.si} ({kind})"


def _rules_in(node, module, functions: dict, depth: int = 0,
              local: dict | None = None) -> list[str]:
    """The constraints a check expression applies, following calls into its module and the
    reader's own variables (``step = bounds.checker("step", units)``)."""
    local = local or {}
    rules: list[str] = []
    for call in (n for n in ast.walk(node) if isinstance(n, ast.Call)):
        name = ast.unparse(call.func)
        args = [_evaluate(a, module) for a in call.args]
        kw = {k.arg: _evaluate(k.value, module) for k in call.keywords}
        if name in ("bounds.checker", "bounds.check") and args:
            kind = args[0] if name == "bounds.checker" else (args[2] if len(args) > 2 else "")
            if isinstance(kind, str):
                rules.append(_kind_rule(kind))
        elif name.endswith("in_range") and len(args) >= 2:
            lo, hi = (args[0], args[1]) if name == "in_range" else (args[-2], args[-1])
            left = "(" if kw.get("low_open") else "["
            right = ")" if kw.get("high_open") else "]"
            rules.append(f"{left}{_number(lo)}, {_number(hi)}{right}")
        elif name in ("choice", "checks.one_of") and args:
            values = args[0] if name == "choice" else args[-1]
            if isinstance(values, (tuple, list)):
                rules.append("one of " + ", ".join(f"``{v}``" for v in values))
        elif name == "bounded_integer" and len(args) == 2:
            rules.append(f"integer in [{_number(args[0])}, {_number(args[1])}]")
        elif name == "checks.integer_at_least" and args:
            rules.append(f"integer ≥ {_number(args[-1])}")
        elif name == "checks.positive":
            rules.append("> 0")
        elif depth < 2 and isinstance(call.func, ast.Name) and call.func.id in functions:
            rules += _rules_in(functions[call.func.id], module, functions, depth + 1)
    if isinstance(node, ast.Attribute) and ast.unparse(node) == "checks.boolean":
        rules.append("true or false")
    if isinstance(node, ast.Name):
        if node.id in local and depth < 3:
            rules += _rules_in(local[node.id], module, functions, depth + 1)
        elif node.id == "numbers":
            rules.append("a list of numbers")
        elif node.id == "string":
            rules.append("text")
        elif node.id in functions and depth < 2:
            rules += _rules_in(functions[node.id], module, functions, depth + 1)
    return list(dict.fromkeys(rules))


def key_rules(cls) -> dict[str, KeyRule]:
    """TOML key -> what the record's readers do with it (``table.get(KEY, CHECK, DEFAULT)``)."""
    module = sys.modules[cls.__module__]
    _, functions = _module_tree(cls.__module__)
    found: dict[str, KeyRule] = {}
    for function in reader_functions(cls):
        local = {**_module_assigns(cls.__module__),
                 **{t.id: n.value for n in ast.walk(function) if isinstance(n, ast.Assign)
                    for t in n.targets if isinstance(t, ast.Name)}}
        for call in (n for n in ast.walk(function) if isinstance(n, ast.Call)):
            if not (isinstance(call.func, ast.Attribute) and call.func.attr == "get"
                    and call.args and isinstance(call.args[0], ast.Constant)
                    and isinstance(call.args[0].value, str)):
                continue
            key = call.args[0].value
            rule = "; ".join(_rules_in(call.args[1], module, functions, local=local)) if len(
                call.args) > 1 else ""
            default = None
            if len(call.args) > 2:
                value = _evaluate(call.args[2], module)
                default = "required" if type(value).__name__ == "object" else _literal(value)
            old = found.get(key)
            if old is None:
                found[key] = KeyRule(key, rule, default)
            else:  # read in two places (say, per law): keep what each adds
                if rule and rule not in old.rule:
                    old.rule = f"{old.rule}; {rule}" if old.rule else rule
                old.default = old.default if old.default is not None else default
    return found


# ---------------------------------------------------------------------------------------------
# What the docstrings say
# ---------------------------------------------------------------------------------------------

def _literal(value) -> str:
    if isinstance(value, Expression):
        return f"computed: ``{value}``"
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'``"{value}"``' if value else '``""``'
    if isinstance(value, (int, float)):
        return _number(value)
    if isinstance(value, tuple) and not value:
        return "empty"
    return f"``{value!r}``"


def _type_name(hint) -> str:
    text = hint if isinstance(hint, str) else inspect.formatannotation(hint)
    text = re.sub(r"\b(?:upliftlab\.[\w.]*\.)?(\w+)", r"\1", text)
    return text.replace("NoneType", "None")


def sentences(text: str) -> list[str]:
    """The sentences of a docstring, split outside back-quotes and parentheses."""
    text = " ".join(inspect.cleandoc(text or "").split())
    out, start, depth, quoted = [], 0, 0, False
    i = 0
    while i < len(text):
        if text.startswith("``", i):
            quoted = not quoted
            i += 2
            continue
        c = text[i]
        if not quoted:
            depth += c == "("
            depth -= c == ")" and depth > 0
            if c in ".;" and depth == 0 and (i + 1 == len(text) or text[i + 1] == " "):
                if c == "." and re.search(r"(?:\be\.g|\bi\.e|\betc|\bcf|\bvs|\beq|\bFig)$",
                                          text[start:i]):
                    i += 1
                    continue
                out.append(text[start:i + 1].strip())
                start = i + 1
        i += 1
    if text[start:].strip():
        out.append(text[start:].strip())
    return out


def describe(cls, name: str, attr_docs: dict) -> str:
    """What the record's docstrings say of field ``name``."""
    own = attr_docs.get((cls.__qualname__, name))
    if own:
        return " ".join(" ".join(own).split())
    said = [s for s in sentences(cls.__doc__ or "")
            if re.search(rf"``{re.escape(name)}``", s)]
    return " ".join(said)


def _attr_docs(cls) -> dict:
    from sphinx.pycode import ModuleAnalyzer

    try:
        return ModuleAnalyzer.for_module(cls.__module__).find_attr_docs()
    except Exception:
        return {}


# ---------------------------------------------------------------------------------------------
# The directive
# ---------------------------------------------------------------------------------------------

def _cell(text: str) -> str:
    return " ".join(str(text).split()) or "—"


def _section_name(cls, parents: dict) -> str:
    """The TOML table a record is read from, when a reader names it: ``Table(data, "soil")``."""
    names = []
    for function in reader_functions(cls):
        for call in (n for n in ast.walk(function) if isinstance(n, ast.Call)):
            if (isinstance(call.func, ast.Name) and call.func.id == "Table"
                    and len(call.args) > 1):
                arg = call.args[1]
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
                    names.append(f"[{arg.value}]" if arg.value else "top-level")
                elif isinstance(arg, ast.JoinedStr):
                    text = "".join(v.value if isinstance(v, ast.Constant) else "N"
                                   for v in arg.values)
                    names.append(f"[[{text.rsplit('.', 1)[0]}]]")
    return ", ".join(dict.fromkeys(names)) or parents.get(cls, "")


def record_rst(cls, parents: dict) -> list[str]:
    """The reST of one record: a section, its docstring, its fields' table."""
    title = f"{cls.__name__}"
    where = _section_name(cls, parents)
    lines = [title, "-" * len(title), ""]
    if where:
        table = "top level" if where == "top-level" else f"``{where}`` table"
        lines += [f"Read from the scene's {table} "
                  f"(:class:`{cls.__module__}.{cls.__qualname__}`).", ""]
    else:
        lines += [f":class:`{cls.__module__}.{cls.__qualname__}`", ""]
    doc = inspect.cleandoc(cls.__doc__ or "")
    if doc and not doc.startswith(f"{cls.__name__}("):
        lines += [*doc.splitlines(), ""]
    hints, attr_docs = _hints(cls), _attr_docs(cls)
    rules = key_rules(cls)
    lines += [".. list-table::", "   :header-rows: 1", "   :widths: 14 12 10 24 40", "",
              "   * - field", "     - type", "     - default", "     - unit and valid range",
              "     - description"]
    for f in dataclasses.fields(cls):
        if not f.init:
            continue
        rule = rules.get(f.name, KeyRule(f.name))
        if f.default is not dataclasses.MISSING:
            fallback = _literal(f.default)
        elif f.default_factory is not dataclasses.MISSING:
            fallback = _literal(f.default_factory())
        else:
            fallback = "required"
        default = rule.default if rule.default is not None else fallback
        lines += [f"   * - ``{f.name}``", f"     - ``{_type_name(hints.get(f.name, f.type))}``",
                  f"     - {_cell(default)}", f"     - {_cell(rule.rule)}",
                  f"     - {_cell(describe(cls, f.name, attr_docs))}"]
    names = {f.name for f in dataclasses.fields(cls)}
    extra = [r for key, r in rules.items() if key not in names]
    if extra:
        lines += ["", "Also read from the table (turned into the fields above):", ""]
        for r in extra:
            bits = [b for b in (r.rule, f"default {r.default}" if r.default else "") if b]
            lines.append(f"- ``{r.key}``" + (f": {'; '.join(bits)}" if bits else ""))
    return lines + [""]


class SceneReference(SphinxDirective):
    """``.. scene-reference::`` -> a section per record of a scene."""

    has_content = False

    def run(self):
        parents: dict = {}
        lines: list[str] = []
        found = records()
        for cls in found:  # a record held by another is read from its holder's table
            where = _section_name(cls, parents)
            for name, hint in _hints(cls).items():
                for member in _members_of(hint):
                    subs = [member, *_subclasses(member)]
                    for sub in subs:
                        if sub in found and where and sub not in parents:
                            parents[sub] = where
        for cls in found:
            self.env.note_dependency(inspect.getsourcefile(cls) or "")
            try:
                lines += record_rst(cls, parents)
            except Exception as exc:  # a record the generator cannot read: say so, fail -W
                logger.warning("scene-reference: %s: %s", cls.__qualname__, exc,
                               location=self.get_location())
        node = nodes.section()
        node.document = self.state.document
        self.state.nested_parse(StringList(lines, source="scene-reference"), 0, node,
                                match_titles=True)
        return node.children


def setup(app):
    app.add_directive("scene-reference", SceneReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
