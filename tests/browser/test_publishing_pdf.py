"""The whole-book PDF of the built site (``tools/book_pdf.py``, run by ``make book``): linked, complete, light.

Reads the built site (no browser): the introduction links the PDF, the PDF has
a bookmark for every page of the table of contents, in order, and it weighs at
most ``MAX_BYTES`` (the figures redrawn for print at about 150 dots per inch).
"""

from __future__ import annotations

import re

import pytest
from tools import book_pdf

#: measured: 403 printed pages in 8.4 MB (page content 3.5 MB, 254 font subsets 1.9 MB, 24 raster images 0.7 MB;
#: 23 MB before the theme's shadows were left out of the print); the limit leaves room for a few more chapters
MAX_BYTES = 12_000_000


@pytest.fixture(scope="module")
def pdf(book_html):
    path = book_html / book_pdf.PDF_NAME
    if not path.is_file():
        pytest.fail(f"{path} is missing: make book prints it (python -m tools.book_pdf)", pytrace=False)
    return path


def test_intro_links_the_pdf(book_html, pdf):
    intro = (book_html / "chapters" / "intro.html").read_text(encoding="utf-8")
    hrefs = re.findall(r'href="([^"]*manipulator-jacobians\.pdf)"', intro)
    assert hrefs, "the introduction does not link the whole-book PDF"
    assert all((book_html / "chapters" / h).resolve() == pdf.resolve() for h in hrefs)


def test_pdf_has_every_page_in_order_and_is_light(book_html, pdf):
    from pypdf import PdfReader

    reader = PdfReader(pdf)
    toc = book_pdf.toc_pages(book_pdf.ROOT / "_toc.yml")
    marks = [(item.title, reader.get_destination_page_number(item)) for item in reader.outline
             if not isinstance(item, list)]
    assert len(marks) == len(toc), f"{len(marks)} bookmarks for {len(toc)} pages of the table of contents"
    starts = [p for _, p in marks]
    assert starts == sorted(starts) and len(set(starts)) == len(starts), "bookmarks out of order"
    assert len(reader.pages) >= 2 * len(toc)
    size = pdf.stat().st_size
    assert size <= MAX_BYTES, f"the PDF weighs {size / 1e6:.1f} MB (limit {MAX_BYTES / 1e6:.0f} MB)"
