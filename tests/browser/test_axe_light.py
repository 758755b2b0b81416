"""axe-core (WCAG 2.1 A and AA) finds no violation on any page or deck, light mode.

Each page of the table of contents, the search page, the decks' index and
every deck is loaded once with the system asking for light colours; see
axe_pages.py. test_axe_dark.py does the same in dark mode.
"""

from __future__ import annotations

import axe_pages
import pytest
from conftest import BOOK_HTML, BOOK_TOC

MODE = "light"
PAGES = [*axe_pages.book_pages(BOOK_HTML, BOOK_TOC), *axe_pages.deck_pages(BOOK_HTML)]


def test_decks_are_built(book_html):
    assert axe_pages.deck_pages(book_html), "no deck under slides/: `make book` builds them"


@pytest.mark.parametrize("path", PAGES)
def test_no_axe_violation(path, book_url, browser_context):
    result = axe_pages.check(browser_context, book_url, path, MODE)
    assert not result.violations, "\n".join(result.lines())
