"""axe-core (WCAG 2.1 A and AA) finds no violation on the decks' index or any deck, in light and in dark mode.

Each is loaded once and checked with the system asking for light colours, then for dark ones
(axe_pages.check_modes). test_axe_pages.py does the same for the book's pages.
"""

from __future__ import annotations

import axe_pages
import pytest
from conftest import BOOK_HTML

PAGES = axe_pages.deck_pages(BOOK_HTML)


def test_decks_are_built(book_html):
    assert axe_pages.deck_pages(book_html), "no deck under slides/: `make book` builds them"


@pytest.mark.parametrize("path", PAGES)
def test_no_axe_violation_in_either_mode(path, book_url, browser_context):
    results = axe_pages.check_modes(browser_context, book_url, path)
    assert [r.mode for r in results] == ["light", "dark"]
    assert not [v for r in results for v in r.violations], "\n".join(line for r in results for line in r.lines())
