"""The sidebar's navigation: the site's sections, with only the reader's own branch open.

The theme (furo) writes the whole table of contents into every page's sidebar: its call
``toctree(collapse=False, maxdepth=-1, titles_only=True, includehidden=True)``. The API has one
page per module, some 340 of them, so every page carried all of them, and building those
sidebars (copy the site's tree, write it as HTML, parse it back) was most of the build's time:
work of the order of pages². Here each page's ``toctree`` is that same call with
``collapse=True``: the top-level sections, and below them only the entries on the way to the
page itself and its own children, which is what a reader moves by. The theme's own handler then
builds its sidebar from it; nothing of the theme is replaced.
"""

from __future__ import annotations

import functools

#: Before the theme's own ``html-page-context`` handler (Sphinx's default priority, 500), so
#: that the theme finds the collapsed ``toctree`` when it builds the sidebar.
PRIORITY = 400


def collapsed(toctree):
    """``toctree`` (the page context's function) that always collapses the branches the page is
    not on, whatever its caller asks for ``collapse``."""

    @functools.wraps(toctree)
    def call(**options):
        return toctree(**{**options, "collapse": True})

    return call


def collapse_sidebar(app, pagename, templatename, context, doctree):
    if "toctree" in context:
        context["toctree"] = collapsed(context["toctree"])


def setup(app):
    app.connect("html-page-context", collapse_sidebar, priority=PRIORITY)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
