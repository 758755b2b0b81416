"""Every chapter's deck, slide by slide, in a real browser (headless Chromium), as projected at 1280x720.

The decks are the ones ``make book`` writes into ``_build/html/slides`` (built
here by ``tools/build_slides.py`` if missing), copied alone into a temp folder
and opened from disk (``file://``), as from a USB stick: everything they load
must be inside ``slides/``. Each deck is walked once (:func:`walk`): every
slide measured after MathJax has typeset it, at 1280x720 and again at
1024x768 (a 4:3 projector), every request and console message recorded,
every request to a web host aborted. The tests then check what was measured.
Screenshots of every slide are kept in ``_build/test-artifacts/slides/`` (not
committed).
"""

from __future__ import annotations

import base64
import html
import io
import json
import os
import re
import urllib.parse
from pathlib import Path
from typing import Any

import pytest
from live_data import DATA_JS
from tools import build_slides

ROOT = Path(__file__).resolve().parents[2]
SITE = ROOT / "_build" / "html"
SLIDES = SITE / "slides"
ARTIFACTS = ROOT / "_build" / "test-artifacts" / "slides"
#: BOOK_SHOTS=0 (make test): no screenshot of each slide; they are for a person to look at, no test reads them
SHOTS = os.environ.get("BOOK_SHOTS", "1") != "0"
SOURCES = build_slides.deck_sources()
IDS = [s.stem for s in SOURCES]

MIN_FONT_PX = 24
MIN_SCALE = 0.9
MIN_FIGURE_PX = 900
#: one idea a slide: about 40 words, math not counted
MAX_WORDS = 45

BANNED = {
    "unresolved label": re.compile(r"\bch\d\d[-_ ](?:fig|ex|def|thm|sec|[a-z]+\b)", re.I),
    "notebook wording": re.compile(r"\b(?:cells?|below)\b", re.I),
    "the notes": re.compile(r"\bthe notes\b", re.I),
    "Python repr": re.compile(r"array\(|\bTrue True\b|\bdtype=|<function |\[\[\s*-?\d"),
    "raw TeX": re.compile(r"\\[A-Za-z]{2,}|\$\$"),
    "raw MyST": re.compile(r"(```|:::)\{|\{[\w:-]+\}`"),
}

#: what every slide must show, measured at each size: statement boxes with their content inside, display
#: formulas without a sentence's punctuation at their end, no overlap between text, controls and reveal's
#: own buttons, and something besides the heading in the slide's first view (before any fragment)
CONTENT = """(i) => {
  const slide = Reveal.getCurrentSlide();
  const shown = (el) => el.checkVisibility({ opacityProperty: true, visibilityProperty: true })
    && el.getClientRects().length > 0;
  const rect = (el) => el.getBoundingClientRect();
  const inside = (a, b) => a.left >= b.left - 2 && a.right <= b.right + 2 && a.top >= b.top - 2 && a.bottom <= b.bottom + 2;
  // statement boxes (sphinx-proof's div.proof): text or a formula besides the title, and every formula inside
  const boxes = [];
  for (const box of slide.querySelectorAll("div.proof")) {
    if (!shown(box)) continue;
    const clone = box.cloneNode(true);
    clone.querySelectorAll(".admonition-title, mjx-assistive-mml").forEach((n) => n.remove());
    const body = clone.textContent.trim() || clone.querySelector("mjx-container");
    const title = (box.querySelector(".admonition-title") || box).textContent.trim().slice(0, 40);
    if (!body) boxes.push(title + ": only a title");
    for (const m of box.querySelectorAll("mjx-container")) if (!inside(rect(m), rect(box))) boxes.push(title + ": formula outside");
  }
  // display formulas, from MathJax's own record of their TeX
  const punct = [];
  const items = (window.MathJax && MathJax.startup && MathJax.startup.document)
    ? MathJax.startup.document.getMathItemsWithin(slide) : [];
  for (const it of items) if (it.display && !(it.typesetRoot && it.typesetRoot.closest("aside.notes")) && /(^|[^\\\\])[,;:]\\s*(\\\\end\\{[^}]*\\}\\s*)*$/.test(it.math.trim())) punct.push(it.math.trim().slice(-40));
  // overlaps: lines of text (their text's own boxes), controls and reveal's own buttons
  const parts = [];
  const walker = document.createTreeWalker(slide, NodeFilter.SHOW_TEXT);
  for (let t = walker.nextNode(); t; t = walker.nextNode()) {
    const el = t.parentElement;
    if (!el || !t.textContent.trim() || el.closest("aside.notes, mjx-container, script, style, svg, button, select, option, .anim-state, .jl-sr, .sr-only")) continue;  // .jl-sr, .sr-only: screen-reader text, clipped to nothing
    if (!shown(el)) continue;
    const range = document.createRange(); range.selectNodeContents(t);
    for (const r of range.getClientRects()) if (r.width > 1 && r.height > 1) parts.push({ r, el, what: "text " + t.textContent.trim().slice(0, 24) });
  }
  for (const m of slide.querySelectorAll("mjx-container")) if (shown(m) && !m.closest("aside.notes")) parts.push({ r: rect(m), el: m, what: "math" });
  for (const c of slide.querySelectorAll("button, input, select, a.book-link")) if (shown(c)) parts.push({ r: rect(c), el: c, what: c.tagName.toLowerCase() + " " + (c.textContent || c.className).trim().slice(0, 20) });
  for (const c of document.querySelectorAll(".reveal > .controls button, .reveal > .slide-number")) {
    if (c.checkVisibility({ opacityProperty: true, visibilityProperty: true }) && parseFloat(getComputedStyle(c).opacity || "1") > 0.05
        && !c.disabled && !c.closest("[aria-hidden=true]")) parts.push({ r: rect(c), el: c, what: "deck " + (c.className || "") });
  }
  const overlaps = [];
  for (let a = 0; a < parts.length; a++) for (let b = a + 1; b < parts.length; b++) {
    const p = parts[a], q = parts[b];
    if (p.el === q.el || p.el.contains(q.el) || q.el.contains(p.el)) continue;
    const w = Math.min(p.r.right, q.r.right) - Math.max(p.r.left, q.r.left);
    const h = Math.min(p.r.bottom, q.r.bottom) - Math.max(p.r.top, q.r.top);
    // lines of text may touch (a superscript reaches into the line above): a collision covers a good part of both
    const minW = Math.min(p.r.width, q.r.width), minH = Math.min(p.r.height, q.r.height);
    if (w > 2 && h > 2 && w > 0.25 * minW && h > 0.4 * minH) overlaps.push(p.what + " / " + q.what);
  }
  // the labels a live view draws (its SVG text: a 3-D view's numbers, frame names, axis letters; a chart's ticks),
  // one drawing at a time, by the same rule (not a story's: it plays on its own while the slide is measured)
  for (const drawing of slide.querySelectorAll(".jac-live:not([data-story]) svg")) {
    const labels = [...drawing.querySelectorAll("text")].filter((t) => t.textContent.trim() && shown(t))
      .map((t) => ({ r: rect(t), what: "view label " + t.textContent.trim().slice(0, 12) }));
    for (let a = 0; a < labels.length; a++) for (let b = a + 1; b < labels.length; b++) {
      const p = labels[a].r, q = labels[b].r;
      const w = Math.min(p.right, q.right) - Math.max(p.left, q.left);
      const h = Math.min(p.bottom, q.bottom) - Math.max(p.top, q.top);
      if (w > 2 && h > 2 && w > 0.25 * Math.min(p.width, q.width) && h > 0.4 * Math.min(p.height, q.height))
        overlaps.push(labels[a].what + " / " + labels[b].what);
    }
  }
  // figures as drawn on the screen: their drawn width (less object-fit's bands) against their own size, and
  // the smallest text of a live view (HTML text: its font size times reveal's scale; SVG text: its font size
  // times the SVG's scale on the screen)
  const figs = [...slide.querySelectorAll("img")].filter((im) => shown(im) && !im.closest(".anim-buttons, aside.notes"))
    .map((im) => { const r = rect(im);
      const anim = im.closest("[data-smallest-text-px]");
      return { drawn: Math.min(r.width, r.height * im.naturalWidth / Math.max(im.naturalHeight, 1)),
               natural: im.naturalWidth, src: im.currentSrc || im.src,
               textPx: anim ? anim.getAttribute("data-smallest-text-px") : null,
               textProblems: anim ? anim.getAttribute("data-text-problems") : null,
               figure: (im.closest("figure[id]") || { id: "" }).id }; });
  let viewText = null;
  for (const view of slide.querySelectorAll(".jac-live")) {
    const walker2 = document.createTreeWalker(view, NodeFilter.SHOW_TEXT);
    for (let t = walker2.nextNode(); t; t = walker2.nextNode()) {
      const el = t.parentElement;
      if (!el || !t.textContent.trim() || el.closest(".jl-sr, .sr-only, .jl-static, option") || !shown(el)) continue;
      let px;
      if (el instanceof SVGElement) { const m = el.getScreenCTM(); px = parseFloat(getComputedStyle(el).fontSize) * (m ? Math.hypot(m.a, m.b) : 1); }
      else px = parseFloat(getComputedStyle(el).fontSize) * Reveal.getScale();
      if (viewText === null || px < viewText.px) viewText = { px, what: t.textContent.trim().slice(0, 24) };
    }
  }
  return { index: i, boxes, punct, overlaps: overlaps.slice(0, 4), figs, viewText };
}"""

#: the slide as it first appears (no fragment shown yet): something besides its heading is on it
FIRST_VIEW = """() => {
  const slide = Reveal.getCurrentSlide();
  const shown = (el) => el.checkVisibility({ opacityProperty: true, visibilityProperty: true })
    && el.getClientRects().length > 0;
  return [...slide.querySelectorAll("img, svg, mjx-container, p, li, td, div.proof, .jac-live, pre")]
    .filter((el) => !el.closest("aside.notes, h1, h2") && shown(el)
      && (el.textContent.trim() || el.tagName === "IMG" || el.tagName === "svg")).length;
}"""

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
  // the words a reader sees: visible text, not math, not the notes, not a live view's controls and readouts,
  // not the slide's small link to the book
  const words = [];
  const walker = document.createTreeWalker(slide, NodeFilter.SHOW_TEXT);
  for (let t = walker.nextNode(); t; t = walker.nextNode()) {
    const el = t.parentElement;
    if (!el || el.closest("aside.notes, mjx-container, script, style, .jac-live, .live-view, a.book-link") || !el.checkVisibility()) continue;
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
          animations: slide.querySelectorAll(".animation, .jac-live[data-story]").length,
          // what a slide shows besides words: a picture, a display formula, a statement, a table, a view
          material: [...slide.querySelectorAll("img, svg, mjx-container[display=true], div.proof, table, .jac-live")]
            .filter((el) => !el.closest("aside.notes, .anim-buttons") && !(el.parentElement && el.parentElement.closest("mjx-container"))).length,
          summary: /^(summary|recap)\\b/i.test((slide.querySelector("h1, h2") || {textContent: ""}).textContent.replace(/^[\\d.\\s]+/, "").trim())};
}"""


_WALKS: dict[str, dict[str, Any]] = {}


SIZES = ((1280, 720), (1024, 768))


def walk(browser: Any, usb: Path, source: Path) -> dict[str, Any]:
    """Open the deck from disk at 1280x720, measure every slide, drive its animations from the keyboard;
    then at 1024x768, what every slide must show."""
    if source.stem in _WALKS:
        return _WALKS[source.stem]
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    page = browser.new_page(viewport={"width": 1280, "height": 720})
    problems: list[str] = []
    page.on("console", lambda m: problems.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    page.on("requestfailed", lambda r: problems.append(f"failed request {r.url}"))
    page.on("response", lambda r: problems.append(f"HTTP {r.status} {r.url}") if r.status >= 400 else None)

    def route(r: Any) -> None:
        problems.append(f"request to a web host: {r.request.url}")
        r.abort()

    page.route(re.compile(r"^(?:https?|wss?)://"), route)
    page.on("request", lambda r: None if r.url.startswith(("file:", "data:", "blob:")) else problems.append(
        f"request outside the deck folder: {r.url}"))
    page.goto((usb / build_slides.deck_path(source)).as_uri(), wait_until="load")
    page.wait_for_selector("html[data-math-done]", timeout=60_000)
    page.wait_for_timeout(300)
    total = page.evaluate("Reveal.getTotalSlides()")
    slides, content, first = [], [], []
    for i in range(total):
        page.evaluate(f"Reveal.slide({i}, 0, -1)")   # as it first appears
        page.wait_for_timeout(60)
        first.append(page.evaluate(FIRST_VIEW))
        page.evaluate(f"Reveal.slide({i}, 0, 99)")   # every fragment shown: the slide at its fullest
        page.wait_for_timeout(120)
        slides.append(page.evaluate(MEASURE, i))
        content.append(page.evaluate(CONTENT, i))
        if SHOTS:
            page.screenshot(path=str(ARTIFACTS / f"{source.stem}-{i:02d}.png"))
    stuck_live = page.evaluate("[...document.querySelectorAll('.jac-live[data-view]')]"
                               ".filter((el) => el.dataset.ready !== '1').map((el) => el.id)")
    if stuck_live:
        problems.append(f"live views that did not start: {stuck_live}")
    untypeset = page.evaluate("[...document.querySelectorAll('.reveal .slides div.math')]"
                              ".filter((el) => !el.querySelector('mjx-container')).length")
    if untypeset:
        problems.append(f"{untypeset} display formulas not typeset")
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
                   ".concat([...Reveal.getCurrentSlide().querySelectorAll('.jac-live[data-story]')].map(el => " + DATA_JS + "(el).step))")
            before = page.evaluate(src)
            page.wait_for_timeout(900)
            anims.append((i, before != page.evaluate(src)))
    # a 4:3 projector: what every slide must show, again
    page.set_viewport_size({"width": 1024, "height": 768})
    page.wait_for_timeout(200)
    for i in range(total):
        page.evaluate(f"Reveal.slide({i}, 0, -1)")
        page.wait_for_timeout(40)
        first.append(page.evaluate(FIRST_VIEW))
        page.evaluate(f"Reveal.slide({i}, 0, 99)")
        page.wait_for_timeout(80)
        content.append(page.evaluate(CONTENT, i))
        if SHOTS and i % 4 == 0:
            page.screenshot(path=str(ARTIFACTS / f"{source.stem}-{i:02d}-1024.png"))
    page.close()
    _WALKS[source.stem] = {"slides": slides, "problems": problems, "animations": anims, "total": total,
                           "content": content, "first": first}
    return _WALKS[source.stem]


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_deck_is_built_and_listed(usb, source):
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


def test_title_slides_carry_course_lecturer_and_date(usb):
    """Every deck's and lecture's title slide names the course, the lecturer and the date or term: the
    settings of ``_config.yml`` (``decks_course``, ``decks_lecturer``, ``decks_date``), the environment,
    else the book's title and author and the month and year of the build (``decks.title_date``)."""
    import yaml

    book = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    conf = book["sphinx"]["config"]
    course = conf.get("decks_course") or os.environ.get("COURSE_TITLE") or book["title"]
    lecturer = conf.get("decks_lecturer") or os.environ.get("COURSE_LECTURER") or book["author"]
    date = (conf.get("decks_date") or os.environ.get("COURSE_DATE") or "").strip()
    when = re.escape(html.escape(date)) if date else r"(?:January|February|March|April|May|June|July|August|" \
        r"September|October|November|December) \d{4}"
    pages = [d["file"] for d in json.loads((usb / "decks.json").read_text())]
    pages += [lec["file"] for lec in json.loads((usb / "lectures.json").read_text())]
    bad = []
    for rel in pages:
        page = (usb / rel).read_text(encoding="utf-8")
        # the title slide: the first, before any slide's heading (the writer drops its section's class)
        title = re.search(r'<p class="deck-course">(.*?)</p>\s*<p class="deck-lecturer">(.*?)</p>', page, re.S)
        if title is None or ("<h2" in page and title.start() > page.index("<h2")):
            bad.append(f"{rel}: no course, lecturer and date on the title slide")
            continue
        if title.group(1) != html.escape(course):
            bad.append(f"{rel}: the course is {title.group(1)!r}, not {course!r}")
        if not re.fullmatch(rf"{re.escape(html.escape(lecturer))} \u00b7 {when}", title.group(2)):
            bad.append(f"{rel}: lecturer and date {title.group(2)!r}, not {lecturer!r} and {when!r}")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_slides_are_legible_and_inside(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
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
def test_no_raw_labels_wording_or_printouts(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
    bad = [f"slide {s['index']}: {what}: {m.group(0)!r} in {s['text'][max(0, m.start() - 40):m.end() + 40]!r}"
           for s in w["slides"] for what, rx in BANNED.items() for m in [rx.search(s["text"])] if m]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_no_console_error_or_failed_request(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
    assert not w["problems"], "\n".join(w["problems"])


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_animations_run_when_reached_by_keyboard(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
    stuck = [i for i, moved in w["animations"] if not moved]
    assert not stuck, f"animations on slides {stuck} did not advance after the key press"


def _picture_bytes(src: str) -> bytes:
    if src.startswith("data:"):
        return base64.b64decode(src.split(",", 1)[1])
    return Path(urllib.parse.unquote(urllib.parse.urlsplit(src).path)).read_bytes()


def figure_text(im: dict[str, Any]) -> tuple[str, float | None, float, str]:
    """A picture's kind ("svg" or "raster"), its smallest text in its own units (None: no text), its own
    width in those units, and the texts that overlap in it ("" if none, or not measurable).

    A chapter's figure on a slide is an SVG drawn for the slides (``course.chapter.slide_svg``): its root
    carries its smallest text and its overlapping texts (``course.chapter.SVG_TEXT_ATTR``,
    ``SVG_OVERLAP_ATTR``), in the units of its viewBox. A raster picture carries its smallest text in px:
    a chapter's PNG in a text key (``course.chapter.TEXT_SIZE_KEY``, written by ``start_page``), an
    animation on its player (``data-smallest-text-px``, ``jacobians.plotting.animation_html``).
    """
    from PIL import Image

    from course.chapter import SVG_OVERLAP_ATTR, SVG_TEXT_ATTR, TEXT_SIZE_KEY

    data = _picture_bytes(im["src"])
    if data.lstrip()[:5] in (b"<?xml", b"<svg ") or b"<svg" in data[:400]:
        head = re.search(rb"<svg\b[^>]*>", data)
        assert head is not None, f"{im['src'][:80]}: an SVG without its root"
        attrs = dict(re.findall(rb'([\w:-]+)="([^"]*)"', head.group(0)))
        text = attrs.get(SVG_TEXT_ATTR.encode())
        assert text is not None, f"{im['src'][:80]}: an SVG without its text size (drawn by course.chapter.slide_svg?)"
        width = float(attrs[b"viewBox"].split()[2])
        value = None if text == b"none" else float(text)
        return "svg", value, width, attrs.get(SVG_OVERLAP_ATTR.encode(), b"").decode()
    value = im["textPx"]
    if value is None:
        value = Image.open(io.BytesIO(data)).text.get(TEXT_SIZE_KEY)
        assert value is not None, f"{im['src'][:80]}: a picture without its text size (drawn without start_page?)"
    return "raster", None if value == "none" else float(value), float(im["natural"]), ""


#: the smallest figure text on the screen, as drawn: the back row reads 24 px on a 1280x720 projector and
#: 20 px on a 1024x768 one
MIN_FIGURE_TEXT_PX = {(1280, 720): 24.0, (1024, 768): 20.0}
#: a raster picture has at least this many of its pixels per pixel it is drawn at on a 1280x720 screen
RASTER_DENSITY = 2.0


def _figure_problems(w: dict[str, Any], animations: bool) -> list[str]:
    """What fails the projection rules among a deck's figures (``animations``: its animations' frames, else
    every other picture), measured at both sizes."""
    bad = []
    for k, c in enumerate(w["content"]):
        size = SIZES[k // w["total"]]
        where = f"{size[0]}x{size[1]} slide {c['index'] + 1}"
        for im in c["figs"]:
            if (im["textPx"] is not None) != animations:
                continue
            kind, text, own, overlaps = figure_text(im)
            scale = im["drawn"] / max(own, 1.0)
            if text is not None and text * scale < MIN_FIGURE_TEXT_PX[size]:
                bad.append(f"{where}: {kind} figure's smallest text {text * scale:.1f} px on the screen "
                           f"(needs {MIN_FIGURE_TEXT_PX[size]:.0f}): {im['src'][-50:]}")
            if kind == "raster" and size == SIZES[0] and im["textPx"] is None and im["natural"] < RASTER_DENSITY * im["drawn"]:
                bad.append(f"{where}: raster figure of {im['natural']} px drawn {im['drawn']:.0f} px wide "
                           f"(needs {RASTER_DENSITY:g}x): {im['src'][-50:]}")
            if overlaps:
                bad.append(f"{where}: texts overlap in the figure: {overlaps}")
            # an animation's frames drawn for the slides were checked frame by frame as they were drawn
            # (jacobians.plotting.animation.frame_text_problems): the same at every size, said once
            if animations and size == SIZES[0]:
                problems = im.get("textProblems")
                if problems is None:
                    bad.append(f"{where}: animation {im.get('figure') or '(no figure id)'}: its frames' text was "
                               "not checked (drawn without course.chapter.start_page?)")
                elif problems:
                    bad.append(f"{where}: animation {im.get('figure') or '(no figure id)'}: in its slide frames, "
                               f"{problems}")
    for s in w["slides"]:
        for im in s["imgs"]:
            if (im["textPx"] is not None) == animations and im["w"] < MIN_FIGURE_PX:
                bad.append(f"slide {s['index'] + 1}: figure {im['w']:.0f} px of the canvas wide (needs {MIN_FIGURE_PX})")
    return bad


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_figures_are_drawn_for_projection(deck_browser, usb, source):
    """Every figure on every slide, at 1280x720 and 1024x768, as drawn: SVG, or a raster of twice the
    drawn pixels; its smallest text 24 px and 20 px on the screen; no two of its texts overlapping; and
    wide (900 px of the canvas at least)."""
    bad = _figure_problems(walk(deck_browser, usb, source), animations=False)
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_animations_text_at_projection_size(deck_browser, usb, source):
    """An animation's frames, as drawn at 1280x720 and 1024x768: smallest text 24 px and 20 px, wide, and in
    no frame two texts overlapping or a text cut off at the edge. (Not
    held to twice the drawn pixels: a player embeds 60-160 PNG frames, and twice their size is four times
    the deck's weight.)"""
    bad = _figure_problems(walk(deck_browser, usb, source), animations=True)
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_live_view_text_at_projection_size(deck_browser, usb, source):
    """A live view's smallest text on the screen: 24 px at 1280x720, 20 px at 1024x768."""
    w = walk(deck_browser, usb, source)
    bad = []
    for k, c in enumerate(w["content"]):
        size = SIZES[k // w["total"]]
        if c["viewText"] is not None and c["viewText"]["px"] < MIN_FIGURE_TEXT_PX[size]:
            bad.append(f"{size[0]}x{size[1]} slide {c['index'] + 1}: live view text {c['viewText']['px']:.1f} px: "
                       f"{c['viewText']['what']!r}")
    assert not bad, "\n".join(bad)


#: a slide of words alone with fewer words than this is a heading and a sentence (``_ext/decks.py``
#: merges such a slide into a neighbour, or the chapter gives it content of its own)
THIN_WORDS = 30


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_no_slide_is_a_heading_and_a_sentence(deck_browser, usb, source):
    """Every slide but the title and the summary shows a picture, a formula, a statement, a table or a
    view, or a full idea in words (:data:`THIN_WORDS` or more)."""
    w = walk(deck_browser, usb, source)
    thin = [f"slide {s['index'] + 1} ({s['heading'][:50]}): {s['words']} words and nothing else"
            for s in w["slides"] if not s["title"] and not s["summary"] and not s["material"]
            and s["words"] < THIN_WORDS]
    assert not thin, "\n".join(thin)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_one_idea_a_slide_at_most_45_words(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
    long = [f"slide {s['index']} ({s['heading']}): {s['words']} words" for s in w["slides"] if s["words"] > MAX_WORDS]
    assert not long, "\n".join(long)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_every_content_slide_has_notes_with_minutes(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
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


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_every_slide_shows_its_content_at_both_sizes(deck_browser, usb, source):
    """No empty statement box, no formula outside its box or ending in , ; : and nothing overlapping,
    at 1280x720 and 1024x768."""
    w = walk(deck_browser, usb, source)
    bad = []
    for k, c in enumerate(w["content"]):
        size = "x".join(map(str, SIZES[k // w["total"]]))
        bad += [f"{size} slide {c['index'] + 1}: statement box {b}" for b in c["boxes"]]
        bad += [f"{size} slide {c['index'] + 1}: display formula ends in punctuation: ...{m!r}" for m in c["punct"]]
        bad += [f"{size} slide {c['index'] + 1}: overlap {o}" for o in c["overlaps"]]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_the_first_view_of_every_slide_is_not_blank(deck_browser, usb, source):
    w = walk(deck_browser, usb, source)
    blank = sorted({k % w["total"] + 1 for k, n in enumerate(w["first"]) if n == 0})
    assert not blank, f"slides (1-based) that open on their heading alone: {blank}"


def test_decks_standalone_folder_links_nothing_outside_but_the_book(usb):
    """Every file a deck links (script, style, image) is inside the copied folder; only links to the book leave it."""
    bad = []
    for deck in json.loads((usb / "decks.json").read_text()):
        page = usb / deck["file"]
        html = page.read_text(encoding="utf-8")
        for m in re.finditer(r"<(script|link|img)\b[^>]*?\b(?:src|href)=[\"']([^\"'#?]+)", html):
            target = (page.parent / urllib.parse.unquote(m.group(2))).resolve()
            if not target.is_relative_to(usb) or not target.is_file():
                bad.append(f"{deck['file']}: <{m.group(1)}> {m.group(2)}")
        if "type=\"module\"" in html:
            bad.append(f"{deck['file']}: a module script (blocked over file://)")
    assert not bad, "\n".join(bad[:20])


def test_cross_references_resolve_and_open_the_book_in_a_new_tab():
    """Every link on a slide to the book names a page of the site and an id on it, and opens a new tab;
    each content slide links its section of the book."""
    from lxml import html as lxml_html  # libxml2's HTML parser: the book's pages are megabytes of SVG math

    pages: dict[Path, set[str]] = {}

    def ids(path: Path) -> set[str]:
        if path not in pages:
            pages[path] = {str(i) for i in lxml_html.parse(str(path)).xpath("//@id")}
        return pages[path]

    bad = []
    for deck in json.loads((SLIDES / "decks.json").read_text()):
        page = SLIDES / deck["file"]
        book_links = 0
        for a in (dict(e.attrib) for e in lxml_html.parse(str(page)).xpath("//a[@href]")):
            href = str(a["href"])
            if href.startswith(("#", "http:", "https:", "mailto:")):
                continue
            path, _, frag = href.partition("#")
            target = (page.parent / urllib.parse.unquote(path)).resolve()
            if not target.is_file():
                bad.append(f"{deck['file']}: {href}: no such page")
            elif frag and frag not in ids(target):
                bad.append(f"{deck['file']}: {href}: no id {frag!r} on that page")
            if target.is_relative_to(SITE) and not target.is_relative_to(SLIDES):
                book_links += 1
                if a.get("target") != "_blank":
                    bad.append(f"{deck['file']}: {href} opens in the presenting tab")
        slides = page.read_text(encoding="utf-8").count('class="book-link"')
        if slides < 3:
            bad.append(f"{deck['file']}: {slides} slides link their section of the book")
    assert not bad, "\n".join(bad[:30])


def test_index_loads_without_a_failed_request_and_every_link_resolves(deck_browser):
    page = deck_browser.new_page()
    bad: list[str] = []
    page.on("requestfailed", lambda r: bad.append(f"failed {r.url}"))
    page.goto((SLIDES / "index.html").as_uri(), wait_until="load")
    page.wait_for_timeout(300)
    hrefs = page.evaluate("[...document.querySelectorAll('a')].map(a => a.getAttribute('href'))")
    text = page.evaluate("document.body.innerText")
    page.close()
    assert not bad, bad
    decks = json.loads((SLIDES / "decks.json").read_text())
    assert len(hrefs) >= 2 * len(decks) + 1
    for href in hrefs:
        assert (SLIDES / href).resolve().is_file(), f"the index links {href}, which is not there"
    # each lecture with its minutes, the sum of its speaker notes' minutes
    for d in decks:
        assert int(d["minutes"]) > 0 and f"{d['minutes']} min" in text, d


def test_lectures_last_45_to_55_minutes_and_cover_every_slide(usb):
    """The lectures (``decks_lectures`` in ``_config.yml``): 45 to 55 minutes each by their speaker notes,
    each ending on a summary slide, and together every content slide of every deck once, in order."""
    lectures = json.loads((usb / "lectures.json").read_text())
    decks = {d["name"]: d for d in json.loads((usb / "decks.json").read_text())}
    low, high = build_slides.LECTURE_MINUTES
    bad = []
    taken: dict[str, list[str]] = {name: [] for name in decks}
    for lec in lectures:
        page = (usb / lec["file"]).read_text(encoding="utf-8")
        _, slides, _ = build_slides.split_slides(page)
        minutes = sum(build_slides._slide_minutes(s) for s in slides)
        if not low <= round(minutes) <= high or round(minutes) != lec["minutes"]:
            bad.append(f"lecture {lec['number']}: {minutes:g} min by its notes (listed {lec['minutes']})")
        if not build_slides._is_summary_slide(slides[-1]):
            bad.append(f"lecture {lec['number']} ends on {build_slides._heading(slides[-1])!r}, not a summary")
        unprefixed = re.sub(r'(<section\b[^>]*\bid=")[\w-]+?--', r"\1", page)
        for part in lec["parts"]:
            deck_page = (usb / decks[part["deck"]]["file"]).read_text(encoding="utf-8")
            deck_slides = build_slides.split_slides(deck_page)[1]
            chosen = [deck_slides[k] for k in build_slides._select(deck_slides, part["from"], part["to"])]
            taken[part["deck"]].extend(chosen)
            missing = [build_slides._heading(s) for s in chosen if s not in unprefixed]
            if missing:
                bad.append(f"lecture {lec['number']}: slides of {part['deck']} not in it: {missing[:3]}")
    for name, d in decks.items():
        content = build_slides.split_slides((usb / d["file"]).read_text(encoding="utf-8"))[1][1:]
        if taken[name] != content:
            bad.append(f"{name}: {len(content)} content slides, the lectures take {len(taken[name])} "
                       "(each once, in order, is wanted)")
    assert not bad, "\n".join(bad)


def test_lectures_open_from_the_copy(deck_browser, usb):
    """Each lecture opens from the copied folder: every slide counted, math typeset, no error, no request
    outside the folder."""
    lectures = json.loads((usb / "lectures.json").read_text())
    page = deck_browser.new_page(viewport={"width": 1280, "height": 720})
    problems: list[str] = []
    page.on("console", lambda m: problems.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    page.on("requestfailed", lambda r: problems.append(f"failed request {r.url}"))
    page.on("request", lambda r: None if r.url.startswith(("file:", "data:", "blob:")) else problems.append(
        f"request outside the deck folder: {r.url}"))
    for lec in lectures:
        page.goto((usb / lec["file"]).as_uri(), wait_until="load")
        page.wait_for_selector("html[data-math-done]", timeout=60_000)
        total = page.evaluate("Reveal.getTotalSlides()")
        raw = page.evaluate("[...document.querySelectorAll('.reveal .slides div.math')]"
                            ".filter((el) => !el.querySelector('mjx-container')).length")
        if total != lec["slides"]:
            problems.append(f"lecture {lec['number']}: {total} slides, {lec['slides']} built")
        if raw:
            problems.append(f"lecture {lec['number']}: {raw} display formulas not typeset")
    page.close()
    assert not problems, "\n".join(problems)
