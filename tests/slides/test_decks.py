"""Every chapter's deck builds and works in a real browser (headless Chromium).

The decks are built once per session into _build/test-artifacts/slides/decks
(executed outputs come from build_slides' cache when the code is unchanged),
served over HTTP on 127.0.0.1, and walked slide by slide with the keyboard in
Debian's Chromium driven by Playwright. Every request to another host is
aborted and recorded. Screenshots of a few slides per deck are kept in
_build/test-artifacts/slides/ (not committed).
"""

from __future__ import annotations

import functools
import http.server
import json
import re
import shutil
import tempfile
import threading
from pathlib import Path

import pytest
from tools import build_slides
from tools.slides import reader

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = ROOT / "_build" / "test-artifacts" / "slides"
DECKS = ARTIFACTS / "decks"
CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
SOURCES = build_slides.deck_sources()
IDS = [s.stem for s in SOURCES]

# raw TeX or MyST that must never be visible on a slide
RAW_PATTERNS = {
    "raw $$": re.compile(r"\$\$"),
    "raw \\[": re.compile(r"\\\["),
    "raw \\(": re.compile(r"\\\("),
    "raw \\begin": re.compile(r"\\begin\{"),
    "raw TeX command": re.compile(r"\\[A-Za-z]{2,}"),
    "raw inline math": re.compile(r"(?<![\w$])\$[^$\s][^$\n]*\$"),
    "raw directive": re.compile(r"(```|:::)\{|\{(prf:|exercise|solution|note|warning)"),
    "raw role": re.compile(r"\{[\w:-]+\}`"),
}


@pytest.fixture(scope="session")
def decks():
    """Build every deck once; returns {stem: report or error}."""
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    for old in ARTIFACTS.glob("*.png"):
        old.unlink()
    if DECKS.exists():
        for old in DECKS.glob("*.slides.html"):
            old.unlink()
    status = build_slides.main([str(DECKS), "--jobs", "2"])
    reports = {d["name"]: d for d in json.loads((DECKS / "decks.json").read_text())}
    return status, reports


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_deck_builds(decks, source):
    status, reports = decks
    assert source.stem in reports, f"no deck for {source.name} (build_slides exit status {status})"
    assert "error" not in reports[source.stem], reports[source.stem].get("error")
    html = (DECKS / build_slides.deck_name(source)).read_text(encoding="utf-8")
    assert html.count("<section") >= 2, "a deck has a title slide and at least one more"
    # nothing is fetched from another host by the markup itself
    for m in re.finditer(r"<(?:script|link|img)\b[^>]*\b(?:src|href)=[\"']([^\"']+)", html):
        assert not re.match(r"^(?:https?:)?//", m.group(1)), m.group(0)[:200]
    assert "mermaid" not in html.split("</head>")[0]
    text = source.read_text(encoding="utf-8")
    if '"notes"' in text:
        assert '<aside class="notes">' in html
    if "{exercise}" in text:
        assert "Try it" in html
    assert "{solution" not in html


class Server:
    def __init__(self, directory: Path):
        class Quiet(http.server.SimpleHTTPRequestHandler):
            def log_message(self, *args):
                pass

        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(directory)))
        self.port = self.httpd.server_address[1]
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)
        self.thread.start()

    def close(self):
        self.httpd.shutdown()
        self.httpd.server_close()


@pytest.fixture(scope="session")
def browser(decks):
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: `make browser` installs Debian's chromium")
    from playwright.sync_api import sync_playwright

    server = Server(DECKS)
    profile = tempfile.mkdtemp(prefix="slides-chromium-")
    with sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            profile, executable_path=CHROMIUM, args=FLAGS, headless=True,
            viewport={"width": 1280, "height": 720})
        yield context, server.port
        context.close()
    server.close()
    shutil.rmtree(profile, ignore_errors=True)


_WALKS: dict = {}


def walk(browser, source):
    """Open the deck and press ArrowRight / Space until the last slide; record everything."""
    if source.stem in _WALKS:
        return _WALKS[source.stem]
    context, port = browser
    if not (DECKS / build_slides.deck_name(source)).exists():
        pytest.fail(f"the deck of {source.name} was not built (see test_deck_builds)")
    page = context.new_page()
    host = f"http://127.0.0.1:{port}/"
    external, console_errors = [], []

    def route(r):
        if r.request.url.startswith(host):
            r.continue_()
        else:
            external.append(r.request.url)
            r.abort()

    page.route("**/*", route)
    page.on("request", lambda req: None if req.url.startswith((host, "data:", "blob:")) else external.append(req.url))
    page.on("console", lambda m: console_errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: console_errors.append(f"page error: {e}"))
    page.goto(host + build_slides.deck_name(source) + "?transition=none", wait_until="load")
    # MathJax 3 (reveal.js's math plugin) sets courseMathReady once it has typeset the deck
    page.wait_for_function("window.Reveal && Reveal.isReady && Reveal.isReady() && window.courseMathReady === true",
                           timeout=30000)
    idle = "Reveal.getCurrentSlide().getAttribute('data-fitted') === '1'"
    all_slides = page.evaluate("Reveal.getSlides().map(s => { const i = Reveal.getIndices(s); return [i.h, i.v || 0]; })")
    n_fragments = page.evaluate("document.querySelectorAll('.reveal .slides .fragment').length")
    total = page.evaluate("Reveal.getTotalSlides()")
    visited, problems, overflow, shots = [], [], [], []
    keys = ["ArrowRight", "Space"]
    step = 0
    limit = total + n_fragments + 5
    shot_at = {0, total // 2, total - 1}
    while True:
        page.wait_for_function(idle, timeout=20000)
        idx = page.evaluate("(() => { const i = Reveal.getIndices(); return [i.h, i.v || 0]; })()")
        if idx not in visited:
            visited.append(idx)
            k = len(visited) - 1
            text = page.evaluate("Reveal.getCurrentSlide().innerText")
            for what, pattern in RAW_PATTERNS.items():
                m = pattern.search(text)
                if m:
                    problems.append(f"slide {idx}: {what}: ...{text[max(0, m.start() - 40):m.end() + 40]!r}...")
            ratio = page.evaluate("Reveal.getCurrentSlide().getAttribute('data-overflow')")
            if ratio:
                overflow.append((idx, float(ratio)))
            if k in shot_at or ratio:
                path = ARTIFACTS / f"{source.stem}-{k:02d}.png"
                page.screenshot(path=str(path))
                shots.append(path)
        done = page.evaluate("Reveal.isLastSlide() && !Reveal.availableFragments().next")
        if done or step > limit:
            break
        page.keyboard.press(keys[step % 2])
        step += 1
    counts = page.evaluate("""({
        chtml: document.querySelectorAll('mjx-container.MathJax[jax="CHTML"]').length,
        errors: document.querySelectorAll('mjx-merror').length,
        notesVisible: [...document.querySelectorAll('aside.notes')].some(a => a.offsetParent !== null),
    })""")
    page.close()
    result = dict(all_slides=all_slides, visited=visited, problems=problems, overflow=overflow, shots=shots,
                  external=external, console_errors=console_errors, counts=counts, total=total, steps=step)
    _WALKS[source.stem] = result
    return result


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_every_slide_reached_with_keyboard(browser, source):
    w = walk(browser, source)
    assert len(w["all_slides"]) == w["total"]
    missing = [s for s in w["all_slides"] if s not in w["visited"]]
    assert not missing, f"slides never reached with ArrowRight/Space: {missing}"
    assert w["visited"][-1] == w["all_slides"][-1]


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_math_typeset_and_no_raw_markup(browser, source):
    w = walk(browser, source)
    assert not w["problems"], "\n".join(w["problems"])
    assert w["counts"]["errors"] == 0, "MathJax reported TeX errors"
    if reader.has_math(source.read_text(encoding="utf-8").split("---", 2)[-1]):
        assert w["counts"]["chtml"] > 0, "the chapter has math but no MathJax element is on the slides"
    assert not w["counts"]["notesVisible"], "speaker notes are visible on the slides"


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_no_console_error_and_no_other_host(browser, source):
    w = walk(browser, source)
    assert not w["external"], f"requests to other hosts: {sorted(set(w['external']))}"
    assert not w["console_errors"], w["console_errors"]


@pytest.mark.parametrize("source", SOURCES, ids=IDS)
def test_every_slide_fits(browser, source):
    """After the fit script (display math shrunk, slide zoomed down to 0.6), nothing overflows."""
    w = walk(browser, source)
    assert w["shots"], "screenshots are kept as test artefacts"
    assert not w["overflow"], (
        f"slides taller than the screen even at 60% (split them with slide metadata): {w['overflow']}; "
        f"see {[str(p) for p in w['shots']]}")
