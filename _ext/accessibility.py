"""Sphinx extension: accessible names of the theme's and myst-nb's controls (WCAG 2.1 AA, axe-core).

* The search button of pydata-sphinx-theme 0.17.1 says "Search Ctrl+K" but is
  named "Search" (``aria-label``): WCAG 2.5.3 (label in name) wants the name
  to contain what is shown. ``a11y_templates/search-button-field.html``
  replaces the theme's component (same markup, no ``aria-label``).
* myst-nb 1.4.0 writes each hidden code cell as ``<details>`` whose
  ``<summary aria-label="Toggle hidden content">`` shows "Show code cell
  source": same problem. The summary is written here without the
  ``aria-label``, so its name is the text it shows.

* The decks (sphinx-revealjs 3.2.1, theme ``revealjs-basic``) forbid zooming
  (``maximum-scale=1.0, user-scalable=no``), which WCAG 1.4.4 (resize text)
  does not allow on a phone; their slide number is white on a 40 % black
  veil, 2.8:1 over a white slide. After the deck build, each deck's viewport
  lets the reader zoom, and the slide number sits on a darker veil (7:1).

Each fix checks that the upstream markup it replaces is still there, and fails
the build when it is gone (the fix would then be dead code).
"""

from __future__ import annotations

import re
from html import escape
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx.config import Config
from sphinx.errors import ExtensionError

HERE = Path(__file__).resolve().parent
TEMPLATES = HERE / "a11y_templates"


def _upstream_search_button() -> Path:
    import pydata_sphinx_theme

    return Path(pydata_sphinx_theme.__file__).parent / "theme" / "pydata_sphinx_theme" / "components" \
        / "search-button-field.html"


def use_templates(app: Sphinx, config: Config) -> None:
    upstream = _upstream_search_button()
    if 'aria-label="{{ _(\'Search\') }}"' not in upstream.read_text(encoding="utf-8"):
        raise ExtensionError("accessibility: the theme's search button no longer has aria-label 'Search'; "
                             "check it and drop a11y_templates/search-button-field.html if it is fixed")
    config.templates_path = [str(TEMPLATES), *(config.templates_path or [])]


def visit_hidden_cell(self: Any, node: Any) -> None:
    classes = " ".join(node["classes"])
    self.body.append(f'<details class="admonition hide {classes}">\n')
    self.body.append("<summary>\n")  # named by the prompt it shows, not "Toggle hidden content"
    self.body.append(f'<p class="collapsed admonition-title">{escape(node["prompt_show"])}</p>\n')
    self.body.append(f'<p class="expanded admonition-title">{escape(node["prompt_hide"])}</p>\n')
    self.body.append("</summary>\n")


def replace_hidden_cell_visitor(app: Sphinx) -> None:
    import inspect

    from myst_nb import sphinx_ as nb_sphinx

    if '<summary aria-label="Toggle hidden content">' not in inspect.getsource(nb_sphinx.visit_HideCellInput):
        raise ExtensionError("accessibility: myst-nb's hidden-cell summary changed; check it and drop "
                             "replace_hidden_cell_visitor if its name is now what it shows")
    app.add_node(nb_sphinx.HideCodeCellNode, override=True,
                 html=(visit_hidden_cell, nb_sphinx.depart_HideCellInput))


_NO_ZOOM = re.compile(r'<meta name="viewport" content="[^"]*user-scalable=no[^"]*">')
ZOOMABLE = '<meta name="viewport" content="width=device-width, initial-scale=1.0">'
# white on rgba(0,0,0,.75) over a white slide: the veil is #404040, 10:1 for white text
SLIDE_NUMBER_STYLE = "<style>.reveal .slide-number{background-color:rgba(0,0,0,.75);color:#fff}</style>"


def fix_deck_html(text: str) -> str:
    """A deck page that lets the reader zoom and shows its slide number at >= 4.5:1."""
    text = _NO_ZOOM.sub(ZOOMABLE, text)
    if SLIDE_NUMBER_STYLE not in text:
        text = text.replace("</head>", SLIDE_NUMBER_STYLE + "</head>", 1)
    return text


_WRITTEN: set[str] = set()


def note_deck_page(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any) -> None:
    if app.builder.name == "revealjs":
        _WRITTEN.add(pagename)


def fix_decks(app: Sphinx, exception: Exception | None) -> None:
    """Rewrite the decks written by this build (an incremental build writes only the changed ones)."""
    if exception is not None or app.builder.name != "revealjs":
        return
    pages = [p for p in (Path(app.outdir) / (name + ".html") for name in sorted(_WRITTEN)) if p.exists()]
    _WRITTEN.clear()
    texts = {p: p.read_text(encoding="utf-8") for p in pages}
    if texts and not any(_NO_ZOOM.search(t) for t in texts.values()):
        raise ExtensionError("accessibility: no deck forbids zooming any more (sphinx-revealjs's viewport); "
                             "drop the viewport part of fix_deck_html")
    for page, text in texts.items():
        fixed = fix_deck_html(text)
        if fixed != text:
            page.write_text(fixed, encoding="utf-8")


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("config-inited", use_templates)
    app.connect("builder-inited", replace_hidden_cell_visitor)
    app.connect("html-page-context", note_deck_page)
    app.connect("build-finished", fix_decks)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
