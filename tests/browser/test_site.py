"""The built site is lean: at most 100 MB, every vendored tree used, one copy of each front-end package.

Reads the built HTML folder (``BOOK_HTML``, default ``_build/html``: the book
with its decks in ``slides/``, as ``make book`` writes it); no browser needed.
The requests pages really make are checked by the other browser tests.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from tools import vendor

# (the math typeset at build time, _ext/math_prerender.py, is most of the chapter and exercise pages' 20 MB: each
# formula draws its glyphs with its own path; 2.7 MB once gzipped as hosts send it)
# (and the slides' SVG figures and the ten lectures add about 2 MB)
# (and the exercise statements typeset at build time, _ext/exercise_checks: 42 exercises x 32 variants, one
# script each; each formula draws its own glyphs (tools/flatten_math_svg.cjs), so 36 MB in all, 7.2 MB gzipped,
# 5 KB gzipped per statement on average; a reader loads one per exercise)
# (and the whole book as one PDF, 8.3 MB, and each lecture's PDF and handout beside the decks', 11.4 MB of
# slides/pdf in all: a reader downloads one when they ask for it)
# The limit is a guard against bloat (a second copy of a package, frames inlined again), far under what static
# hosts take (GitHub Pages: 1 GB); the first-visit budget per page is tests/browser/test_pages.py's.
MAX_BYTES = 100_000_000
#: folders of _static that come from the themes and Sphinx, not from tools/vendor.py
THEME_DIRS = {"scripts", "styles", "vendor", "images"}
#: folders of _static that a course extension writes at build time (the exercise pages' checker and variant
#: banks, _ext/exercise_checks)
BUILT_DIRS = {"exercise-checks"}
COURSE_THEME = Path(__file__).resolve().parents[2] / "_theme"
#: the live views ship inside the package (anywidget layout); _ext/live_views.py copies them to _static/live
COURSE_LIVE = "live"
#: file names by which a front-end package is recognised wherever it is copied, and a
#: text its first kilobyte holds (MathJax has a TeX extension also named require.js)
PACKAGE_FILES = {
    "MathJax": (("tex-mml-chtml.js", "tex-chtml.js", "tex-svg.js", "MathJax.js", "startup.js"), ""),
    "require.js": (("require.js",), "RequireJS"),
    "reveal.js": (("reveal.js", "reveal.esm.js"), "reveal.js"),
    "jupyter widget manager": (("embed-amd.js", "libembed-amd.js"), ""),
    "jQuery": (("jquery.js", "jquery.min.js"), "jQuery"),
    "font-awesome 4": (("font-awesome.min.css", "font-awesome.css"), "Font Awesome"),
}


def _files(folder: Path) -> list[Path]:
    """The site's files, without the .gz/.br copies of its text files (tools/precompress.cjs): those are
    the same files, compressed, for hosts that serve them."""
    return [p for p in folder.rglob("*") if p.is_file() and p.suffix not in (".gz", ".br")]


def _size(folder: Path) -> int:
    return sum(p.stat().st_size for p in _files(folder))


def _pages(site: Path) -> dict[Path, str]:
    """Every HTML page of the site (book pages and decks), outside _static and the decks' vendor folder."""
    return {p: p.read_text(encoding="utf-8", errors="replace") for p in site.rglob("*.html")
            if "_static" not in p.parts}


def _referenced(target: Path, pages: dict[Path, str]) -> list[Path]:
    """Pages whose HTML names ``target`` by its path relative to the page."""
    import os

    found = []
    for page, text in pages.items():
        rel = Path(os.path.relpath(target, page.parent)).as_posix()
        if rel in text:
            found.append(page)
    return found


def test_site_is_at_most_100_mb(book_html, capsys):
    total = _size(book_html)
    folders = sorted(((_size(p), p) for p in [*book_html.iterdir(), *(book_html / "_static").iterdir(),
                                               *(book_html / "slides").glob("*/")] if p.is_dir()), reverse=True)
    lines = [f"site {book_html}: {total / 1e6:.1f} MB (limit {MAX_BYTES / 1e6:.0f} MB); biggest folders:"]
    lines += [f"  {size / 1e6:6.2f} MB  {path.relative_to(book_html)}" for size, path in folders[:12]]
    with capsys.disabled():
        print("\n" + "\n".join(lines))
    assert total <= MAX_BYTES, "\n".join(lines)


def test_every_vendored_tree_is_loaded_by_a_page_or_deck(book_html):
    pages = _pages(book_html)
    decks = [p for p in pages if p.relative_to(book_html).parts[:2] == ("slides", "chapters")]
    assert decks, "no deck in the site: `make book` builds them into slides/"
    static = book_html / "_static"
    for package in vendor.BOOK:
        entry = static / package.folder / package.entry
        assert entry.is_file(), f"{entry} is missing: tools/vendor.py vendors {package.npm}"
        # (the book's pages load MathJax only through _theme/math_menu.js, when a reader asks for its menu)
        menu = static / "math_menu.js"
        by_menu = menu.is_file() and f"{package.folder}/{package.entry}" in menu.read_text(encoding="utf-8") \
            and bool(_referenced(menu, pages))
        assert _referenced(entry, pages) or by_menu, f"no page or deck loads {entry.relative_to(book_html)}"
    ours = {p.folder for p in vendor.BOOK}
    # the course's own front-end trees (_theme/<dir>, the live views): each is loaded by some page
    course_dirs = {p.name for p in COURSE_THEME.iterdir() if p.is_dir()} | {COURSE_LIVE}
    for name in sorted(course_dirs):
        files = sorted((static / name).glob("*.js"))
        assert files, f"{name}/ of the course was not copied into _static"
        assert any(_referenced(f, pages) for f in files), f"no page loads a script of _static/{name}"
    unknown = sorted(p.name for p in static.iterdir() if p.is_dir() and p.name not in ours | THEME_DIRS | course_dirs | BUILT_DIRS)
    assert not unknown, f"trees in _static that tools/vendor.py does not vendor (left by an older build?): {unknown}"
    # the decks vendor nothing of their own but reveal.js, from npm (tools/build_slides.py)
    assert not (book_html / "slides" / "vendor").exists()
    from tools import build_slides

    reveal = book_html / "slides" / "_static" / "revealjs"
    shipped = sorted(p.relative_to(reveal).as_posix() for p in reveal.rglob("*")
                     if p.is_file() and p.suffix not in (".gz", ".br"))  # (the compressed copies hosts serve)
    assert shipped == sorted(build_slides.REVEAL_KEEP)
    for rel in shipped:
        assert (reveal / rel).read_bytes() == (build_slides.NODE_MODULES / "reveal.js" / rel).read_bytes(), rel


def test_one_copy_of_each_front_end_package(book_html):
    copies: dict[str, list[str]] = {package: [] for package in PACKAGE_FILES}
    for path in _files(book_html):
        for package, (names, marker) in PACKAGE_FILES.items():
            if path.name in names and marker in path.read_bytes()[:1024].decode("utf-8", "replace"):
                copies[package].append(path.relative_to(book_html).as_posix())
    for package, found in copies.items():
        # one copy in the book, and one in the deck folder slides/, which stands alone (copied to a USB stick)
        for tree in ([f for f in found if not f.startswith("slides/")], [f for f in found if f.startswith("slides/")]):
            assert len(tree) <= 1, f"{package}: {len(tree)} copies in the site: {tree}"
    assert not copies["jupyter widget manager"], "no page shows a widget: the widget manager is not vendored"
    assert copies["MathJax"] and copies["reveal.js"], copies


def test_chapter_pages_link_exactly_the_decks(book_html):
    decks = {p.name for p in (book_html / "slides" / "chapters").glob("*.html")}
    linked = {}
    for page in (book_html / "chapters").glob("*.html"):
        m = re.search(r'<p class="slides-link">.*?href="([^"]+)"', page.read_text(encoding="utf-8"), re.S)
        if m:
            linked[page.name] = m.group(1)
    for page, href in linked.items():
        assert (book_html / "chapters" / href).resolve().is_file(), f"{page} links {href}, which was not built"
    assert {Path(h).name for h in linked.values()} == decks, "every deck is linked from its chapter"


@pytest.mark.parametrize("package", vendor.BOOK, ids=lambda p: p.npm)
def test_vendored_package_is_in_package_json(package):
    import json

    root = Path(__file__).resolve().parents[2]
    deps = json.loads((root / "package.json").read_text())["dependencies"]
    assert package.npm in deps, f"{package.npm} is vendored but not pinned in package.json"


def test_font_awesome_is_trimmed_to_the_icons_pages_show(book_html):
    """``offline_fixes.trim_font_awesome``: the theme's CSS keeps the rules of the icons the site
    names, the solid webfont their glyphs; every icon a page shows still has both."""
    import offline_fixes as fx
    from fontTools.ttLib import TTFont

    original = fx._theme_file("static", fx.THEME_CSS).read_text(encoding="utf-8")
    trimmed = (book_html / "_static" / fx.THEME_CSS).read_text(encoding="utf-8")

    def rules(css: str) -> dict[str, int]:
        out = {}
        for m in fx._ICON_RULE.finditer(css):
            for sel in m.group(1).rstrip(",").split(","):
                out[sel[1:-len(":before")]] = int(m.group(2), 16)
        return out

    every, kept = rules(original), rules(trimmed)
    assert len(every) > 1500 and 5 <= len(kept) < 100, (len(every), len(kept))
    shown = set()
    for page in _pages(book_html).values():
        shown.update(fx._ICON_NAME.findall(page))
    icons = shown & set(every)
    assert {"fa-magnifying-glass", "fa-bars", "fa-sun", "fa-moon"} <= icons
    assert icons <= set(kept), f"icons pages show whose CSS rule went: {sorted(icons - set(kept))}"
    font = TTFont(book_html / "_static" / fx.SOLID_FONT)
    cmap = font.getBestCmap()
    missing = sorted(name for name in icons if kept[name] not in cmap)
    assert not missing, f"icons whose glyph is not in the trimmed fa-solid font: {missing}"
    assert (book_html / "_static" / fx.SOLID_FONT).stat().st_size < 10_000
