"""Dependencies point one way: core, then the models (reduced, continuum, meshes), then the
comparisons, with the CLI at the edge. The reduced model never imports scikit-fem."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = {"upliftlab": "upliftlab", "reduced": "upliftlab.reduced",
            "continuum": "upliftlab.continuum", "meshes": "upliftlab.meshes",
            "comparisons": "upliftlab.comparisons"}
# what each layer may import from the project (besides itself)
ALLOWED = {
    "upliftlab": {"upliftlab"},
    "upliftlab.reduced": {"upliftlab"},
    "upliftlab.meshes": {"upliftlab"},
    "upliftlab.continuum": {"upliftlab", "upliftlab.meshes"},
    "upliftlab.comparisons": {"upliftlab", "upliftlab.reduced", "upliftlab.continuum",
                              "upliftlab.meshes"},
}


def test_reduced_model_runs_without_scikit_fem():
    """Import and run the reduced model in a fresh interpreter: no skfem, meshio or pyvista."""
    code = ("import sys\n"
            "from upliftlab.scenes import load_scene\n"
            "from upliftlab.reduced import run\n"
            "run(load_scene('short_period_free', overrides=['motion.duration=0.1']))\n"
            "bad = [m for m in ('skfem', 'meshio', 'pyvista') if m in sys.modules]\n"
            "assert not bad, bad\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def _imports(path: Path, package: str) -> set[str]:
    """Project packages that module ``path`` of ``package`` imports (relative imports resolved
    from the module's own package: ``..x`` from a subpackage of the core is ``upliftlab.x``,
    ``...x`` from ``comparisons/opensees/`` also)."""
    tree = ast.parse(path.read_text())
    here = package.split(".") + list(path.relative_to(ROOT).parts[1:-1])
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 0 and node.module:
                name = node.module
            elif node.level <= len(here):
                base = here[:len(here) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
            else:
                continue
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("upliftlab"):
                    found.add(_layer(alias.name))
            continue
        else:
            continue
        if name.startswith("upliftlab"):
            found.add(_layer(name))
    return found


def _layer(module: str) -> str:
    parts = module.split(".")
    if len(parts) > 1 and f"upliftlab.{parts[1]}" in ALLOWED:
        return f"upliftlab.{parts[1]}"
    return "upliftlab"


@pytest.mark.parametrize("folder", list(PACKAGES))
def test_imports_point_one_way(folder):
    package = PACKAGES[folder]
    for path in sorted((ROOT / folder).rglob("*.py")):
        if folder == "upliftlab" and (path.name.startswith("cli") or path.name == "__main__.py"):
            continue  # the CLI (cli.py, cli_*.py) is the edge: it may call every model
        wrong = _imports(path, package) - ALLOWED[package] - {package}
        assert not wrong, f"{path.relative_to(ROOT)} imports {sorted(wrong)}"


def test_every_subpackage_is_installed():
    # Reference: the folders of the checkout. A non-editable install (the README's first
    # command) copies only the packages pyproject.toml lists: a new subpackage left out of the
    # list imports in the editable test install and fails in the installed one (found by
    # .ci/run: reduced/kernels/ was missing).
    import tomllib

    root = Path(__file__).resolve().parents[1]
    config = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    found = set()
    for name, folder in config["package-dir"].items():
        for init in (root / folder).rglob("__init__.py"):
            if "__pycache__" in init.parts:
                continue
            rel = init.parent.relative_to(root / folder).parts
            if name == "upliftlab" and rel and f"upliftlab.{rel[0]}" in config["package-dir"]:
                continue  # a folder mapped on its own
            found.add(".".join((name, *rel)))
    assert found <= listed, f"not installed: {sorted(found - listed)}"
