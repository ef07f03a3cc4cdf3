"""The sources a point function's records depend on, derived from what its module imports.

A stored record is stale when the code its numbers come from changed
(:meth:`.store.PointFunction.depends_on`, a digest of sources). Declaring every module of the
study would make a record stale when only its summary or its figures changed. Instead
:func:`point_sources` reads the point function's module and, through its imports (found in its
source, any import anywhere in it, relative ones resolved), the modules of the same package it
reaches: those, the models' sources and the shared layers the study names are what its records
depend on.
"""

from __future__ import annotations

import ast
from collections.abc import Sequence

from ...provenance import MODEL_SOURCES, PACKAGES, package_files

__all__ = ["import_closure", "point_sources", "source_name", "SHARED_LAYERS"]

#: The comparisons' layers below the studies, which a study's point modules build on: their
#: records depend on all of them (a bed, a measure or the store's point format may change them).
SHARED_LAYERS = ("upliftlab.comparisons/framework/", "upliftlab.comparisons/beds/")


def source_name(module: str) -> str | None:
    """The name of ``module``'s source as :func:`upliftlab.provenance.package_files` names it
    (``upliftlab.comparisons/studies/winkler_map/points.py``), or None when it has none."""
    files = package_files()
    for package in sorted(PACKAGES, key=len, reverse=True):
        if module == package or module.startswith(package + "."):
            rest = module[len(package):].lstrip(".").replace(".", "/")
            stem = f"{package}/{rest}" if rest else package
            for name in (f"{stem}.py", f"{stem}/__init__.py"):
                if name in files:
                    return name
            return None
    return None


def _imports(module: str, is_package: bool) -> set[str]:
    """The modules ``module`` imports anywhere in its source (relative imports resolved; for
    ``from X import y`` both X and X.y, since y may be a module)."""
    tree = ast.parse(package_files()[source_name(module)].read_text())
    parts = module.split(".") if is_package else module.split(".")[:-1]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = parts[:len(parts) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            out.add(base)
            out.update(f"{base}.{alias.name}" for alias in node.names)
    return out


def import_closure(module: str, within: str) -> tuple[str, ...]:
    """``module`` and every module whose name starts with ``within`` that it imports, directly
    or through others of them, sorted (package ``__init__`` modules are left out: importing
    them runs the package, which computes nothing a record holds)."""
    seen, todo = set(), [module]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        source = source_name(name)
        if source is None:
            continue
        for target in _imports(name, source.endswith("/__init__.py")):
            if target.startswith(within + ".") and source_name(target) is not None:
                todo.append(target)
    return tuple(sorted(n for n in seen if source_name(n) is not None
                        and not source_name(n).endswith("/__init__.py")))


def point_sources(module: str, within: str,
                  shared: Sequence[str] = SHARED_LAYERS) -> tuple[str, ...]:
    """The sources (as :func:`upliftlab.provenance.code_digest` takes them) the records of a
    point function defined in ``module`` depend on: the models'
    (:data:`upliftlab.provenance.MODEL_SOURCES`), the ``shared`` prefixes (default
    :data:`SHARED_LAYERS`) and the source of every module of package ``within`` (the study's)
    in ``module``'s :func:`import_closure`. Declared as ``point_function(...,
    sources=point_sources(__name__, __package__))`` in the point function's module."""
    own = tuple(source_name(m) for m in import_closure(module, within))
    return tuple(MODEL_SOURCES) + tuple(shared) + own
