"""PDFs of the lecture decks: one page per slide, and a handout with the speaker notes.

Usage: python -m tools.slides_pdf [SLIDES] [--only STEM ...]

Each deck of ``SLIDES/decks.json`` (``tools/build_slides.py``; default
``_build/html/slides``) is opened from disk (``file://``: the deck folder
holds everything it loads) in Debian's headless Chromium (Playwright,
``/usr/bin/chromium``; no browser download) at reveal.js's print view twice:

* ``?print-pdf``: one page a slide, fragments complete → ``SLIDES/pdf/<stem>.pdf``;
* ``?print-pdf&showNotes=separate-page``: each slide followed by a page of its
  speaker notes → ``SLIDES/pdf/<stem>-notes.pdf`` (the handout).

Live views and animations print as a labelled still without their controls
(``_ext/decks_static/course_decks.css``, ``html.print-pdf``). Pages are
printed once MathJax has typeset every slide, at the slide size, 1280x720 px.
``make book`` runs this through ``tools/build_slides.py``; the slides index
links both PDFs of each deck.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
#: the two prints of a deck: its decks.json key and the query reveal.js reads
PRINTS = (("pdf", "?print-pdf"), ("handout", "?print-pdf&showNotes=separate-page"))


def print_decks(slides: Path, only: list[str] | None = None, browser: Any = None) -> list[dict[str, Any]]:
    """Print every deck (or those named in ``only``) and its handout into ``slides/pdf``."""
    decks = json.loads((slides / "decks.json").read_text(encoding="utf-8"))
    if only:
        decks = [d for d in decks if d["name"] in only]
    (slides / "pdf").mkdir(parents=True, exist_ok=True)
    if browser is not None:
        return _print(browser, slides, decks)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        own = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
        try:
            return _print(own, slides, decks)
        finally:
            own.close()


def _print(browser: Any, slides: Path, decks: list[dict[str, Any]]) -> list[dict[str, Any]]:
    done = []
    for deck in decks:
        t0 = time.perf_counter()
        row: dict[str, Any] = {"name": deck["name"]}
        for key, query in PRINTS:
            page = browser.new_page(viewport={"width": 1280, "height": 720})
            page.goto((slides / deck["file"]).as_uri() + query, wait_until="load")
            page.wait_for_selector("html[data-math-done]", state="attached", timeout=120_000)
            page.wait_for_selector(".pdf-page", state="attached", timeout=60_000)
            page.evaluate("document.fonts.ready")
            page.wait_for_timeout(300)
            row["slides"] = page.evaluate("Reveal.getTotalSlides()")
            out = slides / deck[key]
            page.pdf(path=str(out), width="1280px", height="720px", print_background=True, prefer_css_page_size=True)
            page.close()
            row[key] = str(out)
        row["seconds"] = round(time.perf_counter() - t0, 1)
        done.append(row)
    return done


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("slides", type=Path, nargs="?", default=ROOT / "_build" / "html" / "slides")
    ap.add_argument("--only", nargs="*")
    args = ap.parse_args(argv)
    if not (args.slides / "decks.json").is_file():
        print(f"slides_pdf: no decks in {args.slides}: run `make book` first", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    done = print_decks(args.slides.resolve(), args.only)
    for d in done:
        print(f"{d['name']:<28} {d['slides']:3d} slides  {d['seconds']:5.1f} s")
    print(f"slides_pdf: {len(done)} decks and handouts in {args.slides / 'pdf'} ({time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
