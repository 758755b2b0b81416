"""The book's "Lecture slides for this chapter" link and the deck list agree."""

from __future__ import annotations

import pytest

import build_slides
import slides_link


def test_same_pages_get_a_deck_and_a_link():
    for path in build_slides.toc_files():
        assert slides_link.is_notebook(path) == build_slides.is_notebook(path), path
    assert len(build_slides.deck_sources()) >= 1


@pytest.mark.parametrize("docname, href", [
    ("chapters/02_space_jacobian", "../slides/02_space_jacobian.slides.html"),
    ("index", "slides/index.slides.html"),
    ("a/b/c", "../../slides/c.slides.html"),
])
def test_href_is_relative_to_the_page(docname, href):
    assert slides_link.slides_href(docname) == href
