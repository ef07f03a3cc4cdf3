"""Dependencies point one way, with no exemption, and no module imports itself back.

The layers, each importing only those below it (``design.md``):

    core (upliftlab, but its command line) → models (reduced; meshes; continuum, which may use
    meshes) → the studies' framework → beds → studies → report, advise, opensees (none of which
    imports another) → the command line (upliftlab.cli and ``python -m upliftlab``).

Within the studies, one study imports no other study's modules (what two studies share is a bed
or the framework, below them both), and report, advise and opensees import a study only through
its public package (``upliftlab.comparisons.studies.<study>``), never its modules.

Every import statement counts, those inside functions too: an import deferred to call time is
still a dependency. Reference: the source files' syntax trees; the layers as listed here.
"""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FOLDERS = {"upliftlab": "upliftlab", "upliftlab.reduced": "reduced",
           "upliftlab.continuum": "continuum", "upliftlab.meshes": "meshes",
           "upliftlab.comparisons": "comparisons"}

#: Layer of a module: the first prefix it matches (longest first), and the layers' ranks.
LAYERS = (
    ("upliftlab.cli", "cli", 6), ("upliftlab.__main__", "cli", 6),
    ("upliftlab.comparisons.report", "report", 5), ("upliftlab.comparisons.advise", "advise", 5),
    ("upliftlab.comparisons.opensees", "opensees", 5),
    ("upliftlab.comparisons.studies", "studies", 4), ("upliftlab.comparisons.beds", "beds", 3),
    ("upliftlab.comparisons.framework", "framework", 2),
    ("upliftlab.comparisons", "framework", 2),  # the package's face hands the framework on
    ("upliftlab.continuum", "continuum", 1), ("upliftlab.reduced", "reduced", 1),
    ("upliftlab.meshes", "meshes", 1), ("upliftlab", "core", 0),
)
#: Imports between layers of the same rank that are allowed.
SIDEWAYS = {("continuum", "meshes")}


def _layer(module: str) -> tuple[str, int]:
    for prefix, name, rank in LAYERS:
        if module == prefix or module.startswith(prefix + "."):
            return name, rank
    raise AssertionError(module)


def _modules() -> dict[str, Path]:
    """Every module of the package by name (packages by their own name)."""
    out = {}
    for package, folder in FOLDERS.items():
        for path in (ROOT / folder).rglob("*.py"):
            if "__pycache__" in path.parts:
                continue
            parts = list(path.relative_to(ROOT / folder).with_suffix("").parts)
            if package == "upliftlab" and parts[0] in ("reduced", "continuum", "meshes",
                                                        "comparisons"):
                continue
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join([package, *parts])] = path
    return out


MODULES = _modules()


def _imports(name: str, path: Path) -> set[str]:
    """The package's modules that module ``name`` imports, anywhere in its body."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("upliftlab")}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1]
                                + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            if not base.startswith("upliftlab"):
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                found.add(sub if sub in MODULES else base)
    return {m for m in found if m in MODULES and m != name}


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


@pytest.mark.parametrize("layer", sorted({name for _, name, _ in LAYERS}))
def test_imports_point_one_way(layer):
    for module, targets in sorted(GRAPH.items()):
        here, rank = _layer(module)
        if here != layer:
            continue
        for target in targets:
            there, other = _layer(target)
            ok = other < rank or there == here or (here, there) in SIDEWAYS
            assert ok, f"{module} ({here}) imports {target} ({there})"


STUDY_PREFIX = "upliftlab.comparisons.studies."


def _registered_studies() -> tuple[str, ...]:
    """The studies by module name, as the registry lists them (its ``STUDIES`` literal)."""
    tree = ast.parse((ROOT / "comparisons" / "studies" / "registry.py").read_text())
    for node in ast.walk(tree):
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if any(isinstance(t, ast.Name) and t.id == "STUDIES" for t in targets):
                return tuple(ast.literal_eval(node.value))
    raise AssertionError("no STUDIES in comparisons/studies/registry.py")


STUDIES = _registered_studies()


def _study(module: str) -> str | None:
    """The registered study a module belongs to (its package or module), else None."""
    if not module.startswith(STUDY_PREFIX):
        return None
    head = module[len(STUDY_PREFIX):].split(".")[0]
    return head if head in STUDIES else None


@pytest.mark.parametrize("study", STUDIES)
def test_a_study_imports_no_other_study(study):
    for module, targets in sorted(GRAPH.items()):
        if _study(module) != study:
            continue
        for target in targets:
            other = _study(target)
            assert other in (None, study), f"{module} (study {study}) imports {target} ({other})"


@pytest.mark.parametrize("layer", ["report", "advise", "opensees", "cli"])
def test_the_layers_above_import_a_study_only_through_its_package(layer):
    for module, targets in sorted(GRAPH.items()):
        if _layer(module)[0] != layer:
            continue
        for target in targets:
            study = _study(target)
            assert study is None or target == STUDY_PREFIX + study, (
                f"{module} ({layer}) imports {target}, not the package of study {study}")


def test_no_module_imports_itself_back():
    """No import circle: the strongly connected components of the import graph are single
    modules (Tarjan's algorithm)."""
    index, low, stack, on, circles = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in GRAPH[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                circles.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in sorted(GRAPH):
        if v not in index:
            visit(v)
    assert not circles, circles


def test_the_reduced_model_runs_without_scikit_fem():
    """Import and run the reduced model in a fresh interpreter: no skfem, meshio or pyvista."""
    code = ("import sys\n"
            "from upliftlab.scenes import load_scene\n"
            "from upliftlab.reduced import run\n"
            "run(load_scene('short_period_free', overrides=['motion.duration=0.1']))\n"
            "bad = [m for m in ('skfem', 'meshio', 'pyvista') if m in sys.modules]\n"
            "assert not bad, bad\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_every_subpackage_is_installed():
    # Reference: the folders of the checkout. A non-editable install (the README's first
    # command) copies only the packages pyproject.toml lists: a new subpackage left out of the
    # list imports in the editable test install and fails in the installed one.
    import tomllib

    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    found = {name for name, path in MODULES.items() if path.name == "__init__.py"}
    assert found <= listed, f"not installed: {sorted(found - listed)}"


def test_the_package_has_no_path_hack():
    """``upliftlab/__init__.py`` does not add the checkout to its path: the package works as
    installed (editable or not), and nothing else."""
    assert "__path__" not in (ROOT / "upliftlab" / "__init__.py").read_text()


def _top_level_names(tree: ast.Module) -> set[str]:
    """The names a module binds at its top level, in ``if``/``try`` blocks as well."""
    names, body = set(), list(tree.body)
    while body:
        node = body.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names |= {(a.asname or a.name).split(".")[0] for a in node.names}
        elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names |= {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)}
        elif isinstance(node, (ast.If, ast.Try, ast.With)):
            body += [*node.body, *getattr(node, "orelse", []), *getattr(node, "finalbody", []),
                     *[n for h in getattr(node, "handlers", []) for n in h.body]]
    return names


def _declared_public(tree: ast.Module) -> list[str]:
    """The strings of a module's ``__all__`` (assigned or extended at its top level)."""
    out = []
    for node in tree.body:
        targets = (node.targets if isinstance(node, ast.Assign) else
                   [node.target] if isinstance(node, (ast.AugAssign, ast.AnnAssign)) else [])
        if any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets):
            out += [n.value for n in ast.walk(node.value)
                    if isinstance(n, ast.Constant) and isinstance(n.value, str)]
    return out


@pytest.mark.parametrize("module", sorted(MODULES))
def test_every_public_name_is_defined(module):
    """Each name in a module's ``__all__`` is bound in it (or is a submodule of its package):
    a name that is not makes ``from module import *`` fail and the API page name nothing."""
    path = MODULES[module]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    bound = _top_level_names(tree)
    if path.name == "__init__.py":
        bound |= {p.stem for p in path.parent.glob("*.py")} | {
            p.name for p in path.parent.iterdir() if (p / "__init__.py").is_file()}
    undefined = [name for name in _declared_public(tree) if name not in bound]
    if undefined and "__getattr__" in bound:  # a lazy face (PEP 562): ask it
        import importlib

        loaded = importlib.import_module(module)
        undefined = [name for name in undefined if not hasattr(loaded, name)]
    assert not undefined, f"{module}: __all__ names {undefined}, which it does not define"
