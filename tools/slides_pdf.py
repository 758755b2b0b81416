"""PDF handouts of the lecture decks: one page per slide, fragments complete, MathJax fonts.

Usage: python -m tools.slides_pdf [DEST] [--site _build/html] [--only STEM ...]

Each deck of ``SITE/slides/decks.json`` (``tools/build_slides.py``) is opened
in Debian's headless Chromium (Playwright, ``/usr/bin/chromium``; no browser
download) at reveal.js's print view (``?print-pdf``), served over HTTP on
127.0.0.1 with the book around it. Once MathJax has typeset every slide (the
page is laid out again after it), Chromium prints it at the slide size,
1280x720 px, one slide a page (``pdfMaxPagesPerSlide: 1``; fragments are shown
complete). ``DEST/<stem>.pdf`` (default ``_build/slides-pdf``); then
``python -m tools.build_slides --no-build`` copies them next to the decks,
where the slides index links them.
"""

from __future__ import annotations

import argparse
import functools
import http.server
import json
import sys
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args: Any) -> None:
        pass


def print_decks(site: Path, dest: Path, only: list[str] | None = None, browser: Any = None) -> list[dict[str, Any]]:
    """Print every deck (or those named in ``only``); ``browser``: a Playwright browser, else Chromium is started."""
    from playwright.sync_api import sync_playwright

    decks = json.loads((site / "slides" / "decks.json").read_text(encoding="utf-8"))
    if only:
        decks = [d for d in decks if d["name"] in only]
    dest.mkdir(parents=True, exist_ok=True)
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_Quiet, directory=str(site)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{httpd.server_address[1]}/slides/"
    try:
        if browser is not None:
            return _print(browser, base, decks, dest)
        with sync_playwright() as p:
            own = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
            done = _print(own, base, decks, dest)
            own.close()
    finally:
        httpd.shutdown()
    return done


def _print(browser: Any, base: str, decks: list[dict[str, Any]], dest: Path) -> list[dict[str, Any]]:
    done = []
    for deck in decks:
        t0 = time.perf_counter()
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        page.goto(base + deck["file"] + "?print-pdf", wait_until="load")
        page.wait_for_selector("html[data-math-done]", timeout=120_000)
        page.wait_for_selector(".pdf-page", state="attached", timeout=60_000)
        page.evaluate("document.fonts.ready")
        page.wait_for_timeout(300)
        slides = page.evaluate("Reveal.getTotalSlides()")
        out = dest / f"{deck['name']}.pdf"
        page.pdf(path=str(out), width="1280px", height="720px", print_background=True, prefer_css_page_size=True)
        page.close()
        done.append({"name": deck["name"], "slides": slides, "file": str(out),
                     "seconds": round(time.perf_counter() - t0, 1)})
    return done


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dest", type=Path, nargs="?", default=ROOT / "_build" / "slides-pdf")
    ap.add_argument("--site", type=Path, default=ROOT / "_build" / "html")
    ap.add_argument("--only", nargs="*")
    args = ap.parse_args(argv)
    if not (args.site / "slides" / "decks.json").is_file():
        print(f"slides_pdf: no decks in {args.site}/slides: run `make book` first", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    done = print_decks(args.site.resolve(), args.dest.resolve(), args.only)
    for d in done:
        print(f"{d['name']:<28} {d['slides']:3d} slides  {d['seconds']:5.1f} s")
    (args.dest / "pdfs.json").write_text(json.dumps(done, indent=1))
    print(f"slides_pdf: {len(done)} PDFs in {args.dest} ({time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
