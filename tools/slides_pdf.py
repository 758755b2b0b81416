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

A print is kept in ``_build/.slides_pdf_cache`` under a key made of everything it depends on: the deck's
HTML, every other file of ``SLIDES`` it can load (reveal.js, MathJax, CSS, figures, the live views' bundle),
the print query, this file and Chromium's version. The next run (``make slides`` after ``make book``, or
``make slides-pdf``) copies a print whose key it finds instead of printing it again, so a deck is printed
only when something it shows changed. ``--force`` prints every deck asked for.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
#: the two prints of a deck: its decks.json key and the query reveal.js reads
PRINTS = (("pdf", "?print-pdf"), ("handout", "?print-pdf&showNotes=separate-page"))
#: what each page of a print is, in order: "s" a slide (reveal.js's ``.pdf-page``), "n" the page of speaker
#: notes reveal.js puts after its slide (``showNotes=separate-page``)
PAGE_KINDS = """() => [...document.querySelectorAll(
  '.reveal .slides > .pdf-page, .reveal .slides > .speaker-notes-pdf')].map(
  (el) => el.classList.contains('pdf-page') ? 's' : 'n')"""
#: earlier prints, by key (see the module's docstring); ``make clean`` empties it with the rest of _build
CACHE = ROOT / "_build" / ".slides_pdf_cache"


def _chromium_version() -> str:
    try:
        return subprocess.run([CHROMIUM, "--version"], capture_output=True, text=True, timeout=60).stdout.strip()
    except OSError:
        return "no chromium"


def print_keys(slides: Path, decks: list[dict[str, Any]]) -> dict[tuple[str, str], str]:
    """The cache key of each (deck, print): a hash of what the print depends on (the deck's own page, and
    every file of the folder a deck may load: not the pages of the decks and lectures, nor the listings)."""
    shared = hashlib.sha256()
    shared.update(Path(__file__).read_bytes())
    shared.update(_chromium_version().encode())
    for path in sorted(slides.rglob("*")):
        rel = path.relative_to(slides).as_posix()
        if path.is_file() and not rel.startswith("pdf/") and not rel.endswith((".html", ".json")):
            shared.update(f"\0{rel}\0".encode())
            shared.update(path.read_bytes())
    keys = {}
    for deck in decks:
        html = (slides / deck["file"]).read_bytes()
        for key, query in PRINTS:
            keys[(deck["name"], key)] = hashlib.sha256(
                shared.digest() + deck["file"].encode() + query.encode() + html).hexdigest()
    return keys


def print_decks(slides: Path, only: list[str] | None = None, browser: Any = None,
                force: bool = False, decks: list[dict[str, Any]] | None = None) -> list[dict[str, Any]]:
    """Print every deck of ``slides/decks.json`` (or of ``decks``; those named in ``only``) and its handout
    into ``slides/pdf``; a print whose key is in :data:`CACHE` is copied from there unless ``force``.

    Each row gives the deck's number of slides and, for each print, what each page is (:data:`PAGE_KINDS`):
    ``"s"`` a slide, ``"n"`` the speaker notes of the slide before it."""
    if decks is None:
        decks = json.loads((slides / "decks.json").read_text(encoding="utf-8"))
    if only:
        decks = [d for d in decks if d["name"] in only]
    (slides / "pdf").mkdir(parents=True, exist_ok=True)
    keys = print_keys(slides, decks)
    done: list[dict[str, Any]] = []
    todo: list[dict[str, Any]] = []
    for deck in decks:
        row = _from_cache(slides, deck, keys) if not force else None
        (done if row else todo).append(row or deck)
    if not todo:
        return done
    if browser is not None:
        return done + _store(_print(browser, slides, todo), keys)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        own = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
        try:
            return done + _store(_print(own, slides, todo), keys)
        finally:
            own.close()


def _from_cache(slides: Path, deck: dict[str, Any], keys: dict[tuple[str, str], str]) -> dict[str, Any] | None:
    """The row of a deck whose two prints are both in the cache (copied into ``slides/pdf``), or None."""
    cached = [CACHE / f"{keys[(deck['name'], key)]}.pdf" for key, _ in PRINTS]
    meta = CACHE / f"{keys[(deck['name'], 'pdf')]}.json"
    if not (meta.is_file() and all(c.is_file() for c in cached)):
        return None
    stored = json.loads(meta.read_text())
    row: dict[str, Any] = {"name": deck["name"], "slides": stored["slides"], "pages": stored["pages"],
                           "seconds": 0.0, "cached": True}
    for (key, _), src in zip(PRINTS, cached, strict=True):
        shutil.copy2(src, slides / deck[key])
        row[key] = str(slides / deck[key])
    return row


def _store(rows: list[dict[str, Any]], keys: dict[tuple[str, str], str]) -> list[dict[str, Any]]:
    CACHE.mkdir(parents=True, exist_ok=True)
    for row in rows:
        for key, _ in PRINTS:
            shutil.copy2(row[key], CACHE / f"{keys[(row['name'], key)]}.pdf")
        (CACHE / f"{keys[(row['name'], 'pdf')]}.json").write_text(
            json.dumps({"slides": row["slides"], "pages": row["pages"]}))
    return rows


def _print(browser: Any, slides: Path, decks: list[dict[str, Any]]) -> list[dict[str, Any]]:
    done = []
    for deck in decks:
        t0 = time.perf_counter()
        row: dict[str, Any] = {"name": deck["name"], "pages": {}}
        for key, query in PRINTS:
            page = browser.new_page(viewport={"width": 1280, "height": 720})
            page.goto((slides / deck["file"]).as_uri() + query, wait_until="load", timeout=120_000)
            page.wait_for_selector("html[data-math-done]", state="attached", timeout=120_000)
            page.wait_for_selector(".pdf-page", state="attached", timeout=60_000)
            page.evaluate("document.fonts.ready")
            page.wait_for_timeout(300)
            row["slides"] = page.evaluate("Reveal.getTotalSlides()")
            row["pages"][key] = page.evaluate(PAGE_KINDS)
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
    ap.add_argument("--force", action="store_true", help="print again even what the cache holds")
    args = ap.parse_args(argv)
    if not (args.slides / "decks.json").is_file():
        print(f"slides_pdf: no decks in {args.slides}: run `make book` first", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    done = print_decks(args.slides.resolve(), args.only, force=args.force)
    for d in done:
        print(f"{d['name']:<28} {d['slides']:3d} slides  " + ("(unchanged: from the cache)" if d.get("cached")
                                                              else f"{d['seconds']:5.1f} s"))
    print(f"slides_pdf: {len(done)} decks and handouts in {args.slides / 'pdf'} ({time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
