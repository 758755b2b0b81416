"""axe-core (WCAG 2.1 A and AA) finds no violation on any page of the book, in light and in dark mode.

Each page of the table of contents and the search page is loaded once and checked with the system asking
for light colours, then for dark ones (axe_pages.check_modes). test_axe_decks.py does the same for the decks.
"""

from __future__ import annotations

import axe_pages
import pytest
from conftest import BOOK_HTML, BOOK_TOC

PAGES = axe_pages.book_pages(BOOK_HTML, BOOK_TOC)


@pytest.mark.parametrize("path", PAGES)
def test_no_axe_violation_in_either_mode(path, book_url, browser_context):
    results = axe_pages.check_modes(browser_context, book_url, path)
    assert [r.mode for r in results] == ["light", "dark"]
    assert not [v for r in results for v in r.violations], "\n".join(line for r in results for line in r.lines())
