"""Every ``make`` target run after ``make book`` leaves a working site: no page or deck links a missing file.

Runs ``make slides``, ``make exercises``, ``make vendor`` and ``make slides-pdf``
(it prints every deck in Chromium, about 80 s, or the decks ``SLIDES_PDF`` names, as in ``make test``;
``SITE_TARGETS_PDF=0`` leaves it out) in sequence on
the built book (``make book`` first; this test never builds the book) and,
before the first and after each, crawls the site: every ``href`` and ``src``
of every HTML file under ``_build/html`` (book pages, decks, the slides index),
and every file a stylesheet there names with ``url(...)``, must be a file of
the site. A local file crawl, no browser: a 404 here is a 404 in a browser.

Run by ``make test-targets`` (part of ``make test``, after the browser and
deck tests, because it rewrites the site they read). The site is read once after each target (:func:`crawl`):
what pages and stylesheets load, and where links lead.
"""

from __future__ import annotations

import os
import re
import subprocess
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[2]
SITE = Path(os.environ.get("BOOK_HTML", ROOT / "_build" / "html")).resolve()
TARGETS = ["slides", "exercises", "vendor"] + ([] if os.environ.get("SITE_TARGETS_PDF") == "0" else ["slides-pdf"])
_CSS_URL = re.compile(r"""url\(\s*(['"]?)([^'")]+)\1\s*\)""")
#: <link rel=...> kinds a browser fetches (rel="next", "prev", "search", "index" it does not)
_FETCHED_RELS = {"stylesheet", "icon", "shortcut", "apple-touch-icon", "preload", "modulepreload", "prefetch", "manifest"}
#: an @font-face rule; of its src declarations only the last counts, and the browser loads one url of its list
_FONT_FACE = re.compile(r"@font-face\s*\{([^}]*)\}")
_SRC = re.compile(r"\bsrc\s*:\s*([^;}]+)")


class _Links(HTMLParser):
    """The links of a page: what it loads (``src``, ``srcset``, a stylesheet's or icon's ``<link href>``) and
    where it leads (``<a href>``, ``<link rel="next">`` and the like)."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.loads: list[str] = []
        self.anchors: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        rel = set((dict(attrs).get("rel") or "").lower().split())
        fetched = tag == "link" and bool(rel & _FETCHED_RELS)   # <link rel="next"> is a hint, never fetched
        for name, value in attrs:
            if not value:
                continue
            if name == "src" or (name == "href" and fetched):
                self.loads.append(value)
            elif name == "href":
                self.anchors.append(value)
            elif name == "srcset":
                self.loads.extend(part.strip().split()[0] for part in value.split(",") if part.strip())


def _local(link: str) -> str | None:
    """The path part of a link to a file of this site, or None (another host, a fragment, data:, mailto:...)."""
    parts = urlsplit(link)
    if parts.scheme or parts.netloc or link.startswith(("#", "//")):
        return None
    return unquote(parts.path) or None


def _exists(site: Path, base: Path, link: str) -> bool:
    path = _local(link)
    if path is None:
        return True
    target = (site / path.lstrip("/")) if path.startswith("/") else (base / path)
    return (target / "index.html").is_file() if target.is_dir() else target.is_file()


def _pages(site: Path) -> list[Path]:
    """The HTML pages (book pages, decks, indexes); not the theme's Jinja snippets that Sphinx copies to _static."""
    return sorted(p for p in site.rglob("*.html") if "_static" not in p.relative_to(site).parts)


def missing_files(site: Path, anchors: bool = True) -> list[str]:
    """Every (file, link) of the site whose target is missing.

    Loaded files: every ``src``/``srcset``/``<link href>`` of every page, and
    every ``url(...)`` of every stylesheet, except that in an ``@font-face``
    rule only its last ``src`` counts and one existing file of its list is
    enough (the browser loads the first format it supports). With ``anchors``, also every ``<a href>`` (a click that
    would 404).
    """
    loads, links = crawl(site)
    return loads + links if anchors else loads


def crawl(site: Path) -> tuple[list[str], list[str]]:
    """The site read once: (missing files that pages and stylesheets load, missing targets of ``<a href>``)."""
    missing = []
    dead = []
    for page in _pages(site):
        parser = _Links()
        parser.feed(page.read_text(encoding="utf-8", errors="replace"))
        for link in parser.loads:
            if not _exists(site, page.parent, link):
                missing.append(f"{page.relative_to(site)} -> {link}")
        for link in parser.anchors:
            if not _exists(site, page.parent, link):
                dead.append(f"{page.relative_to(site)} -> {link}")
    for sheet in sorted(site.rglob("*.css")):
        text = sheet.read_text(encoding="utf-8", errors="replace")
        for face in _FONT_FACE.finditer(text):
            srcs = _SRC.findall(face.group(1))
            urls = [m.group(2) for m in _CSS_URL.finditer(srcs[-1])] if srcs else []
            if urls and not any(_exists(site, sheet.parent, u) for u in urls):
                missing.append(f"{sheet.relative_to(site)} -> none of {urls}")
        for m in _CSS_URL.finditer(_FONT_FACE.sub("", text)):
            if not _exists(site, sheet.parent, m.group(2)):
                missing.append(f"{sheet.relative_to(site)} -> {m.group(2)}")
    return missing, dead


def test_crawler_finds_a_missing_file(tmp_path):
    """The crawl itself: missing scripts, images, stylesheet assets and link targets are reported; good links not."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "_static").mkdir()
    (tmp_path / "_static" / "ok.js").write_text("")
    (tmp_path / "_static" / "f.woff2").write_text("")
    (tmp_path / "_static" / "macros.html").write_text("<a href=\"{{ pathto('x') }}\">")   # a theme template
    (tmp_path / "_static" / "s.css").write_text(
        "a { background: url('gone.png') } b { background: url(ok.js) }"
        "@font-face { src: url(f.eot); src: url(f.woff2) format('woff2'), url(f.ttf) format('truetype'); }"
        "@font-face { src: url(g.woff2) format('woff2'), url(g.woff) format('woff') }")
    (tmp_path / "sub" / "page.html").write_text(
        '<a href="#x">x</a><a href="https://example.org/">e</a><img src="data:image/png;base64,AA">'
        '<script src="../_static/ok.js?v=1"></script><script src="../_static/mathjax/es5/startup.js"></script>'
        '<a href="../index.html#top">home</a><a href="..">root</a><a href="../exercises/none.html">gone</a>'
        '<link rel="stylesheet" href="../_static/none.css"><link rel="next" href="next.html">')
    (tmp_path / "index.html").write_text('<img srcset="sub/none.png 2x, _static/ok.js 1x">')
    assert sorted(missing_files(tmp_path)) == sorted([
        "_static/s.css -> gone.png",
        "_static/s.css -> none of ['g.woff2', 'g.woff']",
        "index.html -> sub/none.png",
        "sub/page.html -> ../_static/mathjax/es5/startup.js",
        "sub/page.html -> ../exercises/none.html",
        "sub/page.html -> ../_static/none.css",
        "sub/page.html -> next.html",
    ])
    loads = missing_files(tmp_path, anchors=False)
    assert "sub/page.html -> ../_static/none.css" in loads
    assert "sub/page.html -> ../exercises/none.html" not in loads and "sub/page.html -> next.html" not in loads


def test_every_target_after_the_book_leaves_a_working_site():
    """No file any page or deck loads is missing, after the book and after each target; no link breaks."""
    if not (SITE / "index.html").is_file():
        pytest.fail(f"No built book at {SITE}: run `make book` first (this test does not build it).", pytrace=False)
    loads, links = crawl(SITE)
    assert not loads, f"the built book already loads {len(loads)} missing files: {loads[:10]}"
    assert (SITE / "_static" / "mathjax" / "es5" / "startup.js").is_file()
    # Links that already lead nowhere after `make book` are the builders' to fix (listed, then not held against
    # the targets); what a target must not do is break one more.
    before = set(links)
    if before:
        print(f"\nafter make book, {len(before)} links lead to a missing page: " + "; ".join(sorted(before)))
    for target in TARGETS:
        done = subprocess.run(["make", "--no-print-directory", target], cwd=ROOT, capture_output=True, text=True)
        assert done.returncode == 0, f"make {target} failed:\n{(done.stdout + done.stderr)[-3000:]}"
        loads, links = crawl(SITE)
        assert not loads, f"after `make {target}`, pages and decks load {len(loads)} missing files: {loads[:10]}"
        broken = sorted(set(links) - before)
        assert not broken, f"after `make {target}`, {len(broken)} more links lead nowhere: {broken[:10]}"
