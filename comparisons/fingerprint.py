"""The code a stored result depends on, as one digest: a stored point is reused only with it.

A store's key names the study, the point function and its parameters (:mod:`.store`); the
package version alone does not say which code computed a record (it stayed 0.1.0 while the
continuum changed many times), so a store resumed after an update could mix records of the old
code with the new. :func:`code_fingerprint` closes that gap: the SHA-256 of

* the syntax tree of every module of the ``upliftlab`` package that the point function's
  module imports, directly or through others (the import closure, function-level imports
  included), with docstrings removed: comments, docstrings and layout do not count, a changed
  statement or constant does;
* the scene files shipped with the package, when the closure loads scenes by name;
* the versions of the libraries that compute the numbers (numpy, scipy, numba, scikit-fem).

Importing a name from a package counts its ``__init__``; a package that is only passed
through on the way to a submodule does not (its ``__init__`` re-exports, it computes nothing).
The closure is found from the source, before anything runs, so the key is known before the
point is computed.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import importlib.util
from importlib import metadata
from pathlib import Path

__all__ = ["code_fingerprint", "closure_digest", "import_closure", "LIBRARIES"]

#: The distributions whose versions are part of every fingerprint.
LIBRARIES = ("numpy", "scipy", "numba", "scikit-fem")
_SCENES = "upliftlab.scenes"
_SCENE_FILES = "upliftlab.scene_files"


def _spec(name: str):
    try:
        return importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return None


def _within(name: str, root: str) -> bool:
    return name == root or name.startswith(root + ".")


def _is_package(name: str) -> bool:
    spec = _spec(name)
    return spec is not None and spec.submodule_search_locations is not None


def _type_checking(node: ast.AST) -> bool:
    """True for ``if TYPE_CHECKING:`` (or ``typing.TYPE_CHECKING``): imports for annotations
    only, never run."""
    test = getattr(node, "test", None)
    return isinstance(node, ast.If) and (
        (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
        or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"))


def _nodes(tree: ast.AST):
    """Every node of ``tree`` outside ``if TYPE_CHECKING:`` blocks."""
    todo = [tree]
    while todo:
        node = todo.pop()
        yield node
        todo.extend(child for child in ast.iter_child_nodes(node) if not _type_checking(child))


def _imports(name: str, tree: ast.AST, root: str) -> set[str]:
    """The modules of package ``root`` that module ``name`` imports (anywhere in its body,
    annotations-only imports under ``if TYPE_CHECKING:`` aside)."""
    package = name if _is_package(name) else name.rpartition(".")[0]
    found = set()
    for node in _nodes(tree):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if _within(a.name, root))
        elif isinstance(node, ast.ImportFrom):
            base = importlib.util.resolve_name("." * node.level + (node.module or ""), package) \
                if node.level else node.module
            if not base or not _within(base, root):
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                found.add(sub if alias.name != "*" and _spec(sub) is not None else base)
    return found


def _source(name: str) -> tuple[Path, ast.AST]:
    spec = _spec(name)
    if spec is None or not spec.origin or not spec.origin.endswith(".py"):
        raise ImportError(f"module {name!r}: no Python source to fingerprint")
    path = Path(spec.origin)
    return path, ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


def import_closure(module: str, root: str | None = None) -> dict[str, Path]:
    """Module name → source file of ``module`` and every module of package ``root`` (default:
    the package ``module`` belongs to) it imports, directly or through others."""
    root = root or module.split(".", 1)[0]
    todo, seen = [module], {}
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        path, tree = _source(name)
        seen[name] = path
        todo.extend(sorted(_imports(name, tree, root) - seen.keys()))
    return seen


def _without_docstrings(tree: ast.AST) -> ast.AST:
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                node.body = body[1:] or [ast.Pass()]
    return tree


def _library_versions() -> list[str]:
    out = []
    for name in LIBRARIES:
        try:
            out.append(f"{name}=={metadata.version(name)}")
        except metadata.PackageNotFoundError:
            out.append(f"{name} absent")
    return out


def closure_digest(module: str) -> str:
    """SHA-256 (hex) of the code that a function of ``module`` computes with (module
    docstring), read from the source files now."""
    digest = hashlib.sha256()
    closure = import_closure(module)
    for name in sorted(closure):
        _, tree = _source(name)
        digest.update(f"module {name}\n".encode())
        digest.update(ast.dump(_without_docstrings(tree), include_attributes=False).encode())
    if _SCENES in closure:
        spec = _spec(_SCENE_FILES)
        for folder in (spec.submodule_search_locations if spec else ()):
            for path in sorted(Path(folder).glob("*.toml")):
                digest.update(f"scene {path.name}\n".encode())
                digest.update(path.read_bytes())
    for line in _library_versions():
        digest.update(f"library {line}\n".encode())
    return digest.hexdigest()


@functools.lru_cache(maxsize=None)
def code_fingerprint(module: str) -> str:
    """:func:`closure_digest` of ``module``, computed once per module and process (the code of
    a running process does not change)."""
    return closure_digest(module)
