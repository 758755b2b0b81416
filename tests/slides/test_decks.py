"""Every chapter's deck, slide by slide, in a real browser (headless Chromium), as projected at 1280x720.

The decks are the ones ``make book`` writes into ``_build/html/slides`` (built
here by ``tools/build_slides.py`` if missing), served over HTTP on 127.0.0.1
with the book around them (they load the book's MathJax and styles). Each
deck is walked once (:func:`walk`): every slide measured after MathJax has
typeset it, every request and console message recorded, every request to
another host aborted. The tests then check what was measured. Screenshots of
every slide are kept in ``_build/test-artifacts/slides/`` (not committed).
"""

from __future__ import annotations

import base64
import functools
import http.server
import io
import json
import re
import threading
import urllib.parse
from pathlib import Path
from typing import Any

import pytest
from tools import build_slides

ROOT = Path(__file__).resolve().parents[2]
SITE = ROOT / "_build" / "html"
SLIDES = SITE / "slides"
ARTIFACTS = ROOT / "_build" / "test-artifacts" / "slides"
SOURCES = build_slides.deck_sources()
IDS = [s.stem for s in SOURCES]

MIN_FONT_PX = 24
MIN_SCALE = 0.9
MIN_LABEL_PX = 16
MIN_FIGURE_PX = 900
#: one idea a slide: about 40 words (issue #14), math not counted
MAX_WORDS = 45

BANNED = {
    "unresolved label": re.compile(r"\bch\d\d[-_ ](?:fig|ex|def|thm|sec|[a-z]+\b)", re.I),
    "notebook wording": re.compile(r"\b(?:cells?|below)\b", re.I),
    "the notes": re.compile(r"\bthe notes\b", re.I),
    "Python repr": re.compile(r"array\(|\bTrue True\b|\bdtype=|<function |\[\[\s*-?\d"),
    "raw TeX": re.compile(r"\\[A-Za-z]{2,}|\$\$"),
    "raw MyST": re.compile(r"(```|:::)\{|\{[\w:-]+\}`"),
}

MEASURE = """(i) => {
  const slide = Reveal.getCurrentSlide();
  const box = slide.getBoundingClientRect();
  const visible = (el) => { const r = el.getBoundingClientRect();
    return r.width > 0 && r.height > 0 && getComputedStyle(el).visibility !== "hidden" && !el.closest("aside.notes"); };
  const fonts = [...slide.querySelectorAll("p, li, td")].filter(visible)
    .filter(el => el.textContent.trim()).map(el => parseFloat(getComputedStyle(el).fontSize));
  const scale = Reveal.getScale();
  const out = [];
  for (const el of slide.querySelectorAll("*")) {
    if (!visible(el) || el.closest("mjx-assistive-mml")) continue;
    const r = el.getBoundingClientRect();
    if (r.left < box.left - 2 || r.right > box.right + 2 || r.top < box.top - 2 || r.bottom > box.bottom + 2) {
      out.push(el.tagName.toLowerCase() + "." + (el.className || "") + " " + (el.textContent || "").slice(0, 40));
    }
  }
  // a picture's drawn width: its box, less the bands object-fit: contain leaves beside it
  const imgs = [...slide.querySelectorAll("img")].filter(visible).filter(im => !im.closest(".anim-buttons"))
    .map(im => { const r = im.getBoundingClientRect();
      const anim = im.closest("[data-smallest-text-px]");
      return {w: Math.min(r.width, r.height * im.naturalWidth / Math.max(im.naturalHeight, 1)) / scale,
              natural: im.naturalWidth, src: im.currentSrc || im.src,
              textPx: anim ? anim.getAttribute("data-smallest-text-px") : null}; });
  // the words a reader sees: visible text, not math, not the notes, not a live view's controls and readouts
  const words = [];
  const walker = document.createTreeWalker(slide, NodeFilter.SHOW_TEXT);
  for (let t = walker.nextNode(); t; t = walker.nextNode()) {
    const el = t.parentElement;
    if (!el || el.closest("aside.notes, mjx-container, script, style, .jac-live, .live-view") || !el.checkVisibility()) continue;
    words.push(...t.textContent.split(/\\s+/).filter(w => /[A-Za-z0-9]/.test(w)));
  }
  const notes = slide.querySelector("aside.notes");
  const clone = slide.cloneNode(true);
  clone.querySelectorAll("aside.notes, mjx-assistive-mml, script, style").forEach(n => n.remove());
  return {index: i, scale, fonts, overflow: out.slice(0, 5), imgs, words: words.length,
          heading: (slide.querySelector("h1, h2") || {textContent: ""}).textContent.trim(),
          notes: notes ? notes.textContent.trim() : "",
          title: slide.classList.contains("title-slide") || i === 0,
          text: clone.textContent.replace(/\\s+/g, " ").trim(),
          animations: slide.querySelectorAll(".animation, .jac-live[data-story]").length};
}"""


@pytest.fixture(scope="session")
def server():
    if not (SLIDES / "decks.json").is_file():
        assert build_slides.main([]) == 0, "tools/build_slides.py failed"
    handler = functools.partial(_Quiet, directory=str(SITE))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    httpd.shutdown()


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args: Any) -> None:
        pass


_WALKS: dict[str, dict[str, Any]] = {}


def walk(browser: Any, server: str, source: Path) -> dict[str, Any]:
    """Open the deck at 1280x720, measure every slide, drive its animations from the keyboard."""
    if source.stem in _WALKS:
        return _WALKS[source.stem]
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    page = browser.new_page(viewport={"width": 1280, "height": 720})
    problems: list[str] = []
    page.on("console", lambda m: problems.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    page.on("requestfailed", lambda r: problems.append(f"failed request {r.url}"))
    page.on("response", lambda r: problems.append(f"HTTP {r.status} {r.url}") if r.status >= 400 else None)

    def route(r: Any) -> None:
        if r.request.url.startswith(server) or r.request.url.startswith("data:"):
            r.continue_()
        else:
            problems.append(f"request to another host: {r.request.url}")
            r.abort()

    page.route("**/*", route)
    page.goto(server + "slides/" + build_slides.deck_path(source), wait_until="load")
    page.wait_for_selector("html[data-math-done]", timeout=60_000)
    page.wait_for_timeout(300)
    total = page.evaluate("Reveal.getTotalSlides()")
    slides = []
    for i in range(total):
        page.evaluate(f"Reveal.slide({i}, 0, 99)")   # every fragment shown: the slide at its fullest
        page.wait_for_timeout(120)
        slides.append(page.evaluate(MEASURE, i))
        page.screenshot(path=str(ARTIFACTS / f"{source.stem}-{i:02d}.png"))
    # animations: reached with the keyboard, they run; the arrow keys still move on
    anims = []
    page.evaluate("Reveal.slide(0)")
    page.locator("body").click(position={"x": 5, "y": 5})
    for i in range(1, total):
        page.keyboard.press("ArrowRight")
        page.wait_for_timeout(100)
        while page.evaluate("Reveal.getIndices().h") < i:
            page.keyboard.press("ArrowRight")
            page.wait_for_timeout(60)
        if slides[i]["animations"]:
            src = ("() => [...Reveal.getCurrentSlide().querySelectorAll('.animation img')].map(im => im.src.length + ':' + im.src.slice(-40))"
                   ".concat([...Reveal.getCurrentSlide().querySelectorAll('.jac-live[data-story]')].map(el => el.dataset.frame))")
            before = page.evaluate(src)
            page.wait_for_timeout(900)
            anims.append((i, before != page.evaluate(src)))
    page.close()
    _WALKS[source.stem] = {"slides": slides, "problems": problems, "animations": anims, "total": total}
    return _WALKS[source.stem]


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_deck_is_built_and_listed(server, source):
    decks = {d["name"]: d for d in json.loads((SLIDES / "decks.json").read_text())}
    assert source.stem in decks
    html = (SLIDES / build_slides.deck_path(source)).read_text(encoding="utf-8")
    for m in re.finditer(r"<(?:script|link|img)\b[^>]*\b(?:src|href)=[\"']([^\"']+)", html):
        assert not re.match(r"^(?:https?:)?//", m.group(1)), m.group(0)[:200]
    index = (SLIDES / "index.html").read_text(encoding="utf-8")
    for href in (decks[source.stem]["file"], decks[source.stem]["chapter"]):
        assert f'href="{href}"' in index
    # the handout is linked once `make slides-pdf` has made it, and never linked missing
    assert (f'href="{decks[source.stem]["pdf"]}"' in index) == (SLIDES / decks[source.stem]["pdf"]).is_file()
    chapter = (SLIDES / decks[source.stem]["chapter"]).resolve()
    assert chapter.is_file()
    # slide text and speaker notes are the deck's: not on the book's page
    assert "Key point:" in html and "Key point:" not in chapter.read_text(encoding="utf-8")


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_slides_are_legible_and_inside(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    bad = []
    for s in w["slides"]:
        if s["scale"] < MIN_SCALE:
            bad.append(f"slide {s['index']}: scale {s['scale']:.2f}")
        if s["fonts"] and min(s["fonts"]) < MIN_FONT_PX:
            bad.append(f"slide {s['index']}: body text at {min(s['fonts']):.1f} px")
        if s["overflow"]:
            bad.append(f"slide {s['index']}: outside the slide: {s['overflow']}")
        if not s["heading"]:
            bad.append(f"slide {s['index']}: no heading")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_no_raw_labels_wording_or_printouts(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    bad = [f"slide {s['index']}: {what}: {m.group(0)!r} in {s['text'][max(0, m.start() - 40):m.end() + 40]!r}"
           for s in w["slides"] for what, rx in BANNED.items() for m in [rx.search(s["text"])] if m]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_no_console_error_or_failed_request(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    assert not w["problems"], "\n".join(w["problems"])


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_animations_run_when_reached_by_keyboard(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    stuck = [i for i, moved in w["animations"] if not moved]
    assert not stuck, f"animations on slides {stuck} did not advance after the key press"


def smallest_text_px(im: dict[str, Any]) -> float | None:
    """The smallest text of a picture, in its own pixels, as the chapter drew it.

    ``course.chapter.start_page`` writes it into every figure's PNG
    (``course.chapter.TEXT_SIZE_KEY``); ``jacobians.plotting.animation_html``
    onto the player (``data-smallest-text-px``). None: a picture with no text.
    """
    from PIL import Image

    from course.chapter import TEXT_SIZE_KEY

    value = im["textPx"]
    if value is None:
        src = im["src"]
        if src.startswith("data:"):
            data = base64.b64decode(src.split(",", 1)[1])
        else:
            path = SITE / urllib.parse.unquote(urllib.parse.urlsplit(src).path).lstrip("/")
            data = path.read_bytes()
        value = Image.open(io.BytesIO(data)).text.get(TEXT_SIZE_KEY)
        assert value is not None, f"{src[:80]}: a picture without its text size (drawn without start_page?)"
    return None if value == "none" else float(value)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_figures_are_wide_with_large_labels(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    bad = []
    for s in w["slides"]:
        for im in s["imgs"]:
            text = smallest_text_px(im)
            labels = (text or 0.0) * im["w"] / max(im["natural"], 1)
            if im["w"] < MIN_FIGURE_PX or (text is not None and labels < MIN_LABEL_PX):
                bad.append(f"slide {s['index']}: figure {im['w']:.0f} px wide, smallest text {labels:.1f} px")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_one_idea_a_slide_at_most_45_words(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    long = [f"slide {s['index']} ({s['heading']}): {s['words']} words" for s in w["slides"] if s["words"] > MAX_WORDS]
    assert not long, "\n".join(long)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_every_content_slide_has_notes_with_minutes(deck_browser, server, source):
    w = walk(deck_browser, server, source)
    missing = [s["index"] for s in w["slides"] if not s["title"] and not re.search(r"About \d+", s["notes"])]
    assert not missing, f"content slides without speaker notes (key point, question, minutes): {missing}"
    # each note: the key point, a question to put to the class, and text a speaker can read out
    bad = []
    for s in w["slides"]:
        if s["title"]:
            continue
        if not re.search(r"Key point", s["notes"]):
            bad.append(f"slide {s['index']}: no key point in {s['notes'][:80]!r}")
        if "?" not in s["notes"] and "Ask:" not in s["notes"]:
            bad.append(f"slide {s['index']}: no question for the class in {s['notes'][:80]!r}")
        for what, rx in BANNED.items():
            m = rx.search(s["notes"])
            if m:
                bad.append(f"slide {s['index']} notes: {what}: {m.group(0)!r} in "
                           f"{s['notes'][max(0, m.start() - 40):m.end() + 40]!r}")
    assert not bad, "\n".join(bad)


def test_index_loads_without_a_failed_request_and_every_link_resolves(deck_browser, server):
    page = deck_browser.new_page()
    bad: list[str] = []
    page.on("requestfailed", lambda r: bad.append(f"failed {r.url}"))
    page.on("response", lambda r: bad.append(f"HTTP {r.status} {r.url}") if r.status >= 400 else None)
    page.goto(server + "slides/index.html", wait_until="load")
    page.wait_for_timeout(300)
    hrefs = page.evaluate("[...document.querySelectorAll('a')].map(a => a.getAttribute('href'))")
    page.close()
    assert not bad, bad
    decks = json.loads((SLIDES / "decks.json").read_text())
    assert len(hrefs) >= 2 * len(decks) + 1
    for href in hrefs:
        assert (SLIDES / href).resolve().is_file(), f"the index links {href}, which is not there"
