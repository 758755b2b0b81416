"""Sphinx extension: a "Lecture slides for this chapter" link on each chapter page.

`make slides` (tools/build_slides.py) builds one reveal.js deck per page of
_toc.yml that :func:`notebook_pages.has_deck` accepts, at the page's own path
under ``slides/`` (``slides/chapters/<stem>.html``). This extension puts, right
under the page title of each such page, a link to it relative to the page, so
the link works when the decks are built into
``_build/html/slides/`` (see the Makefile's book target) and the HTML folder
is deployed as is. Both sides call the same rule (``_ext/notebook_pages.py``);
tests/browser/test_site.py checks that the built links and decks agree.
"""

from __future__ import annotations

import posixpath
from pathlib import Path
from typing import Any

from docutils import nodes
from notebook_pages import has_deck
from sphinx.application import Sphinx

LINK_TEXT = "Lecture slides for this chapter"
SLIDES_DIR = "slides"


def slides_href(docname: str) -> str:
    """Link from the page of ``docname`` to its deck, relative to the page."""
    depth = docname.count("/")
    return "../" * depth + posixpath.join(SLIDES_DIR, docname + ".html")


def add_link(app: Sphinx, doctree: nodes.document) -> None:
    env = app.env
    docname = env.docname
    if docname == app.config.root_doc or not has_deck(Path(env.doc2path(docname)), Path(app.srcdir)):
        return
    section = next(iter(doctree.findall(nodes.section)), None)
    if section is None:
        return
    ref = nodes.reference("", "", internal=False, refuri=slides_href(docname))
    ref += nodes.Text(LINK_TEXT)
    para = nodes.paragraph("", "", classes=["slides-link"])
    para += nodes.Text("\N{BLACK RIGHT-POINTING TRIANGLE} ")
    para += ref
    index = 1 if section.children and isinstance(section.children[0], nodes.title) else 0
    section.insert(index, para)


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("doctree-read", add_link)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
