"""The book's "Lecture slides for this chapter" link and the deck list follow one rule."""

from __future__ import annotations

from pathlib import Path

import pytest
import slides_link  # as Sphinx loads it (``_ext`` on the path)
from _ext import notebook_pages
from tools import build_slides

ROOT = Path(__file__).resolve().parents[2]


def test_same_pages_get_a_deck_and_a_link():
    decks = build_slides.deck_sources()
    assert decks and len({p.stem for p in decks}) == len(decks), "deck names are unique"
    assert slides_link.has_deck is not None and slides_link.has_deck.__module__ == "notebook_pages"
    for path in build_slides.toc_files():
        in_folder = path.relative_to(build_slides.ROOT).parts[0] in notebook_pages.DECK_FOLDERS
        assert (path in decks) == (notebook_pages.is_notebook(path) and in_folder), path
        assert (path in decks) == slides_link.has_deck(path, ROOT), path


def test_notebook_rule_is_the_books(tmp_path):
    """myst-nb's test: a jupytext ``myst`` front matter; not merely any front matter."""
    nb = tmp_path / "nb.md"
    nb.write_text("---\njupytext:\n  text_representation:\n    extension: .md\n    format_name: myst\n"
                  "kernelspec:\n  name: python3\n  display_name: Python 3\n---\n# T\n")
    plain = tmp_path / "plain.md"
    plain.write_text("---\ntitle: x\nkernelspec:\n  name: python3\n---\n# T\n")
    assert notebook_pages.is_notebook(nb) is True
    assert notebook_pages.is_notebook(plain) is False
    assert notebook_pages.is_notebook(tmp_path / "missing.md") is False
    assert notebook_pages.read(nb).metadata["kernelspec"]["name"] == "python3"
    with pytest.raises(ValueError, match="not a notebook"):
        notebook_pages.read(plain)
    (tmp_path / "chapters").mkdir()
    chapter = tmp_path / "chapters" / "nb.md"
    chapter.write_text(nb.read_text())
    assert notebook_pages.has_deck(chapter, tmp_path) is True
    assert notebook_pages.has_deck(nb, tmp_path) is False  # not in a deck folder


@pytest.mark.parametrize("docname, href", [
    ("chapters/02_space_jacobian", "../slides/chapters/02_space_jacobian.html"),
    ("index", "slides/index.html"),
    ("a/b/c", "../../slides/a/b/c.html"),
])
def test_href_is_relative_to_the_page(docname, href):
    assert slides_link.slides_href(docname) == href
