"""Sphinx extension: a "Lecture slides for this chapter" link on each chapter page.

`make slides` (tools/build_slides.py) builds one reveal.js deck per page of
_toc.yml that is a MyST Markdown notebook (a jupytext header with a
kernelspec), named ``<stem>.slides.html``. This extension puts, right under
the page title of each such page, a link to ``slides/<stem>.slides.html``
relative to the root of the built HTML, so the link works when the decks are
built into ``_build/html/slides/`` (see the Makefile's book target) and the
HTML folder is deployed as is.

The rule deciding which pages get a deck is the same as in
tools/build_slides.py (``is_notebook``); tests/slides/test_slides_link.py
checks that the two agree.
"""

from __future__ import annotations

import posixpath
from pathlib import Path

from docutils import nodes

LINK_TEXT = "Lecture slides for this chapter"
#: only pages in these folders are lectures (same as tools/build_slides.py)
DECK_FOLDERS = ("chapters",)
SLIDES_DIR = "slides"


def is_notebook(path: Path) -> bool:
    """True for a MyST Markdown notebook (jupytext header with a kernelspec)."""
    if path.suffix != ".md" or not path.is_file():
        return False
    head = path.read_text(encoding="utf-8")[:600]
    return head.startswith("---") and "jupytext:" in head and "kernelspec:" in head


def slides_href(docname: str) -> str:
    """Link from the page of ``docname`` to its deck, relative to the page."""
    stem = posixpath.basename(docname)
    depth = docname.count("/")
    return "../" * depth + f"{SLIDES_DIR}/{stem}.slides.html"


def add_link(app, doctree) -> None:
    env = app.env
    docname = env.docname
    if docname == app.config.root_doc or docname.split("/", 1)[0] not in DECK_FOLDERS:
        return
    source = Path(env.doc2path(docname))
    if not is_notebook(source):
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


def setup(app):
    app.connect("doctree-read", add_link)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
