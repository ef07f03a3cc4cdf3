"""The docs site's sidebar (docs/_ext/sidebar.py): the theme's ``toctree`` call is made with
``collapse=True`` and every other option as the theme asked. Reference: the call furo 2025
makes (``collapse=False, titles_only=True, maxdepth=-1, includehidden=True``), written out
here; the extension must change ``collapse`` alone and leave a page without a ``toctree`` as
it is. (The strict docs build of .ci/run renders the real sidebars.)"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

SIDEBAR = Path(__file__).resolve().parents[1] / "docs" / "_ext" / "sidebar.py"


@pytest.fixture(scope="module")
def sidebar():
    spec = importlib.util.spec_from_file_location("docs_sidebar", SIDEBAR)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_themes_toctree_call_is_collapsed_and_keeps_its_other_options(sidebar):
    calls = []

    def toctree(**options):
        calls.append(options)
        return "<ul></ul>"

    context = {"toctree": toctree}
    sidebar.collapse_sidebar(None, "api/upliftlab", "page.html", context, None)
    themes = {"collapse": False, "titles_only": True, "maxdepth": -1, "includehidden": True}
    assert context["toctree"](**themes) == "<ul></ul>"
    assert calls == [{**themes, "collapse": True}]
    page = {"title": "search"}
    sidebar.collapse_sidebar(None, "search", "search.html", page, None)
    assert page == {"title": "search"}


def test_it_runs_before_the_themes_handler(sidebar):
    # Sphinx calls the handlers of an event in the order of their priority (lower first); a
    # theme's handler has the default, 500
    connected = []

    class App:
        def connect(self, event, handler, priority=500):
            connected.append((event, handler, priority))

    metadata = sidebar.setup(App())
    assert connected == [("html-page-context", sidebar.collapse_sidebar, sidebar.PRIORITY)]
    assert sidebar.PRIORITY < 500 and metadata["parallel_write_safe"]
