"""Sphinx configuration of the upliftlab docs site.

Build it strict (every warning an error), offline, from the repository's root::

    python -m sphinx -j auto -W --keep-going -b html docs docs/_build/html

Pages are Markdown (myst-parser); the gallery's scripts (``docs/gallery/*.py``) are executed by
sphinx-gallery; the API pages are generated from the docstrings (autodoc, autosummary); the
scene reference is generated from the scene records (``_ext/scene_reference.py``); every number
of a findings page is read from ``findings/data/<study>.json`` (``_ext/findings.py``).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

from upliftlab.version import __version__  # noqa: E402

# ``upliftlab/__main__.py`` runs the command line when it is imported (``python -m upliftlab``),
# and the recursive API listing imports every module: it finds this one imported already, a
# module with the file's docstring and nothing run.
import ast  # noqa: E402
import types  # noqa: E402

import upliftlab  # noqa: E402

_MAIN = Path(upliftlab.__file__).with_name("__main__.py")
sys.modules.setdefault("upliftlab.__main__", types.ModuleType(
    "upliftlab.__main__", ast.get_docstring(ast.parse(_MAIN.read_text(encoding="utf-8")))))

# The API pages are written by this build (autosummary, docs/.gitignore): start them afresh, so
# that the page of a module since moved or removed does not outlive it and fail the strict build.
_API_PAGES = HERE / "api"
if _API_PAGES.is_dir() and all(p.suffix == ".rst" for p in _API_PAGES.iterdir()):
    import shutil

    shutil.rmtree(_API_PAGES)

project = "upliftlab"
author = "the upliftlab developers"
copyright = "2026, the upliftlab developers"  # noqa: A001
release = version = __version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "findings",
    "scene_reference",
    "include_markdown",
    "docstrings",
    "sidebar",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "gallery/README.rst", "findings/data", "**/.ipynb_checkpoints"]
templates_path = ["_templates"]

myst_enable_extensions = ["colon_fence", "deflist", "dollarmath"]
myst_heading_anchors = 3

# The API, from the docstrings: each module one page with the public names it defines (a name
# it re-exports is documented where it is defined, once).
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True,
                           "ignore-module-all": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
#: The packages the API pages cover; each is documented from its own folder (the editable
#: install maps them from the repository's top-level folders).
api_packages = ["upliftlab", "upliftlab.reduced", "upliftlab.continuum", "upliftlab.meshes",
                "upliftlab.comparisons"]

# The gallery: every docs/gallery/*.py is run by the build (a few seconds each; numba's kernels
# are compiled once and cached under ~/.cache/upliftlab).
sphinx_gallery_conf = {
    "examples_dirs": "gallery",
    "gallery_dirs": "auto_gallery",
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"__init__\.py",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "image_scrapers": ("matplotlib",),
    # a cell that ends on a figure (``result.plot()``) shows the figure, not its repr
    "ignore_repr_types": r"matplotlib\.(figure|text|axes)",
    "matplotlib_animations": False,
    "min_reported_time": 1,
}

html_theme = "furo"
html_title = f"upliftlab {release}"
html_static_path = []
html_last_updated_fmt = None
html_show_sourcelink = False

# Offline: no intersphinx, no remote images. A short cross-reference in a docstring that
# names two objects (:mod:`.labelled` is a module of the reduced and of the continuum model)
# links to the first; that ambiguity is not an error of the page.
suppress_warnings = ["ref.python"]
