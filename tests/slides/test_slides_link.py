"""The book's "Lecture slides for this chapter" link and the deck list agree."""

from __future__ import annotations

import pytest

import build_slides
import slides_link


def test_same_pages_get_a_deck_and_a_link():
    decks = build_slides.deck_sources()
    assert decks and len({p.stem for p in decks}) == len(decks), "deck names are unique"
    assert slides_link.DECK_FOLDERS == build_slides.DECK_FOLDERS
    for path in build_slides.toc_files():
        assert slides_link.is_notebook(path) == build_slides.is_notebook(path), path
        in_folder = path.relative_to(build_slides.ROOT).parts[0] in slides_link.DECK_FOLDERS
        assert (path in decks) == (slides_link.is_notebook(path) and in_folder), path


@pytest.mark.parametrize("docname, href", [
    ("chapters/02_space_jacobian", "../slides/02_space_jacobian.slides.html"),
    ("index", "slides/index.slides.html"),
    ("a/b/c", "../../slides/c.slides.html"),
])
def test_href_is_relative_to_the_page(docname, href):
    assert slides_link.slides_href(docname) == href
