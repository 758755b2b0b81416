"""The whole-book PDF (``tools/book_pdf.py``, written by ``make book``): every page in order, math typeset.

Read with pypdf, no browser: its bookmarks are the pages of the table of
contents in their order (titles as the built pages have them), each bookmark
points after the one before, the text has no TeX left over, and formulas
came out as math symbols (Greek letters and the dotted theta of a joint rate,
which only typeset math produces from the TeX sources), and the intro page
links the PDF.
"""

from __future__ import annotations

import re

import pytest
from tools.book_pdf import PDF_NAME, toc_pages


@pytest.fixture(scope="module")
def pdf(book_html):
    path = book_html / PDF_NAME
    if not path.is_file():
        pytest.fail(f"{path} is missing: `make book` prints it (tools/book_pdf.py)", pytrace=False)
    from pypdf import PdfReader

    return PdfReader(str(path))


def _title(html: str) -> str:
    m = re.search(r"<title>([^<]*)</title>", html)
    assert m, "a page without <title>"
    import html as h

    return h.unescape(m.group(1)).split("—")[0].split(" | ")[0].strip()


def test_pdf_has_every_page_in_order(pdf, book_html):
    from conftest import BOOK_TOC

    expected = [_title((book_html / p).read_text(encoding="utf-8")) for p in toc_pages(BOOK_TOC)]
    marks = [(o.title, pdf.get_destination_page_number(o)) for o in pdf.outline if not isinstance(o, list)]
    assert [t for t, _ in marks] == expected
    starts = [n for _, n in marks]
    assert starts == sorted(starts) and len(set(starts)) == len(starts), starts
    assert len(pdf.pages) > len(expected)


def test_pdf_math_is_typeset(pdf):
    from conftest import BOOK_TOC

    pages = toc_pages(BOOK_TOC)
    start = pages.index("chapters/02_space_jacobian.html")
    first = [pdf.get_destination_page_number(o) for o in pdf.outline if not isinstance(o, list)][start]
    text = "\n".join(pdf.pages[i].extract_text() or "" for i in range(first, min(first + 6, len(pdf.pages))))
    assert "Jacobian" in text
    for raw in (r"\(", r"\[", r"\theta", r"\dot", r"\begin{"):
        assert raw not in text, f"raw TeX {raw!r} in the PDF's text of chapter 2"
    assert "θ" in text, "no typeset theta in chapter 2's first pages"


def test_intro_links_the_pdf(book_html):
    intro = (book_html / "chapters" / "intro.html").read_text(encoding="utf-8")
    assert f'href="../{PDF_NAME}"' in intro
