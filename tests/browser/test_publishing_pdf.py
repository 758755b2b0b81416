"""The whole-book PDF (``tools/book_pdf.py``, run by ``make book``): linked, complete, light.

After ``make book`` the built PDF is checked: the introduction links it, it has
a bookmark for every page of the table of contents, in order, and it weighs at
most ``MAX_BYTES`` (the figures redrawn for print at about 150 dots per inch).

``make test`` builds the book with ``BOOK_PDF=0`` (printing the whole book is
minutes of Chromium's CPU, for a file that only authors publish). Then this
module prints a sample of the book with the same code into a temporary folder
(the introduction and ``SAMPLE_CHAPTER``, a chapter with math, figures and
live views) and checks the sample in the same way; the introduction's link must
still lead to where ``make book`` writes the PDF.
"""

from __future__ import annotations

import os
import re

import pytest
import yaml
from tools import book_pdf

#: measured: 403 printed pages in 8.4 MB (page content 3.5 MB, 254 font subsets 1.9 MB, 24 raster images 0.7 MB;
#: 23 MB before the theme's shadows were left out of the print); the limit leaves room for a few more chapters
MAX_BYTES = 12_000_000
#: the whole book's limit per printed page (MAX_BYTES over its 403 pages), for the sample: a print with the
#: shadows as page-wide bitmaps (2.7 times the size) or with figures at full size fails it
MAX_BYTES_PER_PAGE = MAX_BYTES / 403
#: did this build print the whole book? (the Makefile's BOOK_PDF, exported to the tests; unset: yes)
BUILT = os.environ.get("BOOK_PDF", "1") != "0"
#: the chapter printed with the introduction when the build printed no PDF
SAMPLE_CHAPTER = "chapters/07_conversions"


@pytest.fixture(scope="module")
def printed(book_html, tmp_path_factory, request):
    """The PDF to check and the table of contents it prints: the built book's, or a sample printed here."""
    if BUILT:
        path = book_html / book_pdf.PDF_NAME
        if not path.is_file():
            pytest.fail(f"{path} is missing: make book prints it (python -m tools.book_pdf); "
                        "a build with BOOK_PDF=0 does not, so test it with BOOK_PDF=0", pytrace=False)
        return path, book_pdf.ROOT / "_toc.yml"
    context = request.getfixturevalue("browser_context")
    folder = tmp_path_factory.mktemp("book-pdf")
    toc = folder / "_toc.yml"
    root = yaml.safe_load((book_pdf.ROOT / "_toc.yml").read_text(encoding="utf-8"))["root"]
    toc.write_text(yaml.safe_dump({"format": "jb-book", "root": root, "chapters": [{"file": SAMPLE_CHAPTER}]}))
    out = folder / book_pdf.PDF_NAME
    book_pdf.build(book_html, toc, out, context=context)
    return out, toc


def test_intro_links_the_pdf(book_html, printed):
    intro = (book_html / "chapters" / "intro.html").read_text(encoding="utf-8")
    hrefs = re.findall(r'href="([^"]*manipulator-jacobians\.pdf)"', intro)
    assert hrefs, "the introduction does not link the whole-book PDF"
    # where make book writes it (tools/book_pdf.py's default output), and the file there when this build printed it
    assert all((book_html / "chapters" / h).resolve() == (book_html / book_pdf.PDF_NAME).resolve() for h in hrefs)
    if BUILT:
        assert all((book_html / "chapters" / h).resolve() == printed[0].resolve() for h in hrefs)


def test_pdf_has_every_page_in_order_and_is_light(printed):
    from pypdf import PdfReader

    pdf, toc_file = printed
    reader = PdfReader(pdf)
    toc = book_pdf.toc_pages(toc_file)
    marks = [(item.title, reader.get_destination_page_number(item)) for item in reader.outline
             if not isinstance(item, list)]
    assert len(marks) == len(toc), f"{len(marks)} bookmarks for {len(toc)} pages of the table of contents"
    starts = [p for _, p in marks]
    assert starts == sorted(starts) and len(set(starts)) == len(starts), "bookmarks out of order"
    assert len(reader.pages) >= 2 * len(toc)
    size = pdf.stat().st_size
    if BUILT:
        assert size <= MAX_BYTES, f"the PDF weighs {size / 1e6:.1f} MB (limit {MAX_BYTES / 1e6:.0f} MB)"
    per_page = size / len(reader.pages)
    assert per_page <= MAX_BYTES_PER_PAGE, (
        f"the PDF weighs {per_page / 1e3:.1f} kB a page (limit {MAX_BYTES_PER_PAGE / 1e3:.1f} kB)")
