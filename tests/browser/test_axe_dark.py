"""axe-core (WCAG 2.1 A and AA) finds no violation on any page or deck, dark mode.

Each page of the table of contents, the search page, the decks' index and
every deck is loaded once with the system asking for dark colours; see
axe_pages.py. test_axe_light.py does the same in light mode.
"""

from __future__ import annotations

import axe_pages
import pytest
from conftest import BOOK_HTML, BOOK_TOC

MODE = "dark"
PAGES = [*axe_pages.book_pages(BOOK_HTML, BOOK_TOC), *axe_pages.deck_pages(BOOK_HTML)]


@pytest.mark.parametrize("path", PAGES)
def test_no_axe_violation(path, book_url, browser_context):
    result = axe_pages.check(browser_context, book_url, path, MODE)
    assert not result.violations, "\n".join(result.lines())
