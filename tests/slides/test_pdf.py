"""The decks on paper (``tools/slides_pdf.py``, run by ``make book``): one PDF page per slide, at the
slide's shape, no blank page, no player or control, math in MathJax's fonts; a handout with the notes.

Which decks: every deck, unless the Makefile's ``SLIDES_PDF`` (exported to the tests) names some (``make test``
builds the book with one deck's PDFs: printing them all is minutes of Chromium's CPU, for files that only
authors publish); then those decks and the lectures made of them alone, the other decks' tests skipped as not
printed in this run. ``SLIDES_PDF=0`` (no deck printed by the build): :data:`SAMPLE_DECK`, printed here.
A deck whose PDFs the build did not print is printed here."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pytest
from tools import build_slides, slides_pdf

ROOT = Path(__file__).resolve().parents[2]
SLIDES = ROOT / "_build" / "html" / "slides"
SOURCES = build_slides.deck_sources()
#: what a player or a live view's controls print as (matplotlib's animation buttons are Font Awesome
#: glyphs with these titles; a live view's buttons and sliders carry these words)
CONTROL_WORDS = re.compile(r"\b(?:Play|Pause|Reset view|Draw a path|step \d+ of \d+)\b")
#: the deck checked when the build printed none (math, figures, animations and live views; lecture 4 alone)
SAMPLE_DECK = "05_geometric_jacobian"
_ASKED = os.environ.get("SLIDES_PDF", "1").split()
#: the decks whose PDFs are checked (None: every deck)
CHECKED: set[str] | None = None if _ASKED in ([], ["1"]) else {SAMPLE_DECK} if _ASKED == ["0"] else set(_ASKED)


def _checked(name: str) -> None:
    if CHECKED is not None and name not in CHECKED:
        pytest.skip(f"not printed in this run (SLIDES_PDF={os.environ.get('SLIDES_PDF')}: {' '.join(sorted(CHECKED))})")


@pytest.fixture(scope="session")
def decks(deck_browser) -> dict[str, dict[str, str]]:
    if not (SLIDES / "decks.json").is_file():
        assert build_slides.main(build_slides.pdf_args(os.environ.get("SLIDES_PDF"))) == 0
    listed = {d["name"]: d for d in json.loads((SLIDES / "decks.json").read_text())}
    unknown = sorted((CHECKED or set()) - set(listed))
    assert not unknown, f"SLIDES_PDF names no deck: {unknown}"
    missing = [n for n, d in listed.items() if (CHECKED is None or n in CHECKED) and (
        "slides" not in d or not (SLIDES / d["pdf"]).is_file() or not (SLIDES / d["handout"]).is_file())]
    if missing:   # a site built with --no-pdf: print what is missing
        for row in slides_pdf.print_decks(SLIDES, missing, browser=deck_browser):
            listed[row["name"]]["slides"] = str(row["slides"])
    return listed


def _slides_in(deck: dict[str, str]) -> int:
    """The slides reveal.js counted when the deck was printed (tools/build_slides.py keeps it in decks.json)."""
    return int(deck["slides"])


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_one_page_per_slide_none_blank_no_control(decks, source):
    import pypdf

    _checked(source.stem)

    deck = decks[source.stem]
    reader = pypdf.PdfReader(SLIDES / deck["pdf"])
    assert len(reader.pages) == _slides_in(deck), f"{len(reader.pages)} pages for {_slides_in(deck)} slides"
    for i, page in enumerate(reader.pages):
        box = page.mediabox
        assert abs(float(box.width) / float(box.height) - 16 / 9) < 0.01, f"page {i + 1} is not 16:9"
        text = (page.extract_text() or "").strip()
        xobjects = page["/Resources"].get("/XObject") or {}
        assert len(text) > 3 or len(xobjects) > 0, f"page {i + 1} is blank"
        m = CONTROL_WORDS.search(text)
        assert m is None, f"page {i + 1} prints a control: {m.group(0)!r}"


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_the_handout_has_the_speaker_notes(decks, source):
    import pypdf

    _checked(source.stem)

    deck = decks[source.stem]
    reader = pypdf.PdfReader(SLIDES / deck["handout"])
    text = "\n".join(p.extract_text() or "" for p in reader.pages)
    assert len(reader.pages) > _slides_in(deck), "the handout has no page of notes"
    assert "Key point" in text and "min." in text


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_math_is_printed_in_mathjax_fonts(decks, source):
    """A deck with math prints it in MathJax's own web fonts (MathJax_...), not in the browser's fallback fonts."""
    import pypdf

    _checked(source.stem)
    html = (SLIDES / build_slides.deck_path(source)).read_text(encoding="utf-8")
    if 'class="math' not in html:
        pytest.skip("no math in this deck")
    fonts: set[str] = set()
    for page in pypdf.PdfReader(SLIDES / decks[source.stem]["pdf"]).pages:
        for ref in (page["/Resources"].get("/Font") or {}).values():
            font = ref.get_object()
            described = font.get("/FontDescriptor")   # Chromium embeds web fonts as Type 3, named there
            fonts.add(str(font.get("/BaseFont") or (described.get_object().get("/FontName") if described else "")))
    assert any("MathJax_" in f for f in fonts), sorted(fonts)


def _lectures() -> list[dict]:
    path = SLIDES / "lectures.json"
    return json.loads(path.read_text()) if path.is_file() else []


def test_every_lecture_has_its_pdf_and_handout_linked_from_the_index(decks, deck_browser):
    """Each lecture's PDF is its slides in order, a page each (its own title first, its summary last, every
    other page the slide of its deck at that place: the page's text holds the slide's heading), and its
    handout adds the speaker notes; the slides index links both."""
    import pypdf

    every = _lectures()
    # with SLIDES_PDF naming decks: the lectures made of them alone (a lecture's PDF is made of its decks' pages)
    lectures = [lec for lec in every if CHECKED is None or all(not d or d in CHECKED for d, _, _ in lec["sources"])]
    assert lectures, f"no lecture is made of the decks printed in this run alone ({sorted(CHECKED or [])})"
    if not all((SLIDES / lec[k]).is_file() for lec in lectures for k in ("pdf", "handout")):   # --no-pdf
        printed = {row["name"]: row for row in slides_pdf.print_decks(
            SLIDES, only=None if CHECKED is None else sorted(CHECKED), browser=deck_browser)}
        build_slides.lecture_pdfs(SLIDES, lectures, printed, browser=deck_browser)
        build_slides.write_index(SLIDES, json.loads((SLIDES / "decks.json").read_text()), every)
    index = (SLIDES / "index.html").read_text(encoding="utf-8")
    words = re.compile(r"[A-Za-z]{4,}")
    TEX = r"\\\(.*?\\\)|\\\[.*?\\\]|\$[^$]*\$|\\[A-Za-z]+"  # inline and display math, TeX commands
    bad = []
    for lec in lectures:
        _, slides, _ = build_slides.split_slides((SLIDES / lec["file"]).read_text(encoding="utf-8"))
        pages = [(p.extract_text() or "") for p in pypdf.PdfReader(SLIDES / lec["pdf"]).pages]
        if len(pages) != lec["slides"] or len(slides) != lec["slides"]:
            bad.append(f"lecture {lec['number']}: {len(pages)} pages, {len(slides)} slides, {lec['slides']} listed")
            continue
        if f"Lecture {lec['number']}" not in pages[0]:
            bad.append(f"lecture {lec['number']}: page 1 is not its title slide: {pages[0][:60]!r}")
        for k, (slide, text) in enumerate(zip(slides, pages, strict=True)):
            # the heading's words, its math left out (TeX source such as \mathcal or \theta is drawn as glyphs)
            plain = re.sub(TEX, " ", build_slides._heading(slide), flags=re.S)
            heading = words.findall(plain)
            flat = re.sub(r"\s+", "", text)
            if heading and not all(w in flat for w in heading[:3]):
                bad.append(f"lecture {lec['number']} page {k + 1}: {heading[:3]} not in {text[:60]!r}")
        handout = pypdf.PdfReader(SLIDES / lec["handout"])
        notes = "\n".join(p.extract_text() or "" for p in handout.pages)
        if len(handout.pages) <= lec["slides"] or "Key point" not in notes or "min." not in notes:
            bad.append(f"lecture {lec['number']}: the handout has no pages of notes")
        for key in ("pdf", "handout"):
            if f'href="{lec[key]}"' not in index:
                bad.append(f"lecture {lec['number']}: the index does not link {lec[key]}")
    assert lectures and not bad, "\n".join(bad)
