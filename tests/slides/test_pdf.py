"""`make slides-pdf`: one PDF page per slide, at the slide's shape, no blank page (tools/slides_pdf.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from tools import build_slides, slides_pdf

ROOT = Path(__file__).resolve().parents[2]
SITE = ROOT / "_build" / "html"
OUT = ROOT / "_build" / "test-artifacts" / "slides-pdf"
SOURCES = build_slides.deck_sources()


@pytest.fixture(scope="session")
def pdfs(deck_browser):
    if not (SITE / "slides" / "decks.json").is_file():
        assert build_slides.main([]) == 0
    return {d["name"]: d for d in slides_pdf.print_decks(SITE, OUT, browser=deck_browser)}


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_one_page_per_slide_none_blank(pdfs, source):
    import pypdf

    done = pdfs[source.stem]
    reader = pypdf.PdfReader(done["file"])
    assert len(reader.pages) == done["slides"], f"{len(reader.pages)} pages for {done['slides']} slides"
    for i, page in enumerate(reader.pages):
        box = page.mediabox
        assert abs(float(box.width) / float(box.height) - 16 / 9) < 0.01, f"page {i + 1} is not 16:9"
        text = (page.extract_text() or "").strip()
        xobjects = page["/Resources"].get("/XObject") or {}
        assert len(text) > 3 or len(xobjects) > 0, f"page {i + 1} is blank"


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_math_is_printed_in_mathjax_fonts(pdfs, source):
    """A deck with math prints it in MathJax's own web fonts (MathJax_...), not in the browser's fallback fonts."""
    import pypdf

    html = (SITE / "slides" / build_slides.deck_path(source)).read_text(encoding="utf-8")
    if 'class="math' not in html:
        pytest.skip("no math in this deck")
    fonts: set[str] = set()
    for page in pypdf.PdfReader(pdfs[source.stem]["file"]).pages:
        for ref in (page["/Resources"].get("/Font") or {}).values():
            font = ref.get_object()
            described = font.get("/FontDescriptor")   # Chromium embeds web fonts as Type 3, named there
            fonts.add(str(font.get("/BaseFont") or (described.get_object().get("/FontName") if described else "")))
    assert any("MathJax_" in f for f in fonts), sorted(fonts)
