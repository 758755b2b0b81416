"""The built site as published: from a sub-path, with its sitemap, 404 page, footer and meta tags.

A host such as GitHub Pages serves a project's site under ``/<repository>/``.
The book is served here under ``/course/jacobians/`` (the built folder linked
into a temporary root) and a few pages of each kind are opened in Chromium: no
request may fail, and none may leave the sub-path.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path
from urllib.parse import urlsplit

import bookcheck
import pytest

SUB = "course/jacobians/"
PAGES = ["index.html", "chapters/intro.html", "chapters/02_space_jacobian.html", "chapters/09_using_the_jacobian.html",
         "search.html", "slides/index.html", "slides/chapters/02_space_jacobian.html"]


@pytest.fixture(scope="module")
def sub_url(book_html, tmp_path_factory):
    root = tmp_path_factory.mktemp("host")
    (root / "course").mkdir()
    (root / SUB.rstrip("/")).symlink_to(book_html, target_is_directory=True)
    with bookcheck.BookServer(root) as server:
        yield server.base, server.base + SUB


@pytest.mark.parametrize("path", PAGES)
def test_page_works_from_a_sub_path(path, sub_url, browser_context, book_html):
    if not (book_html / path).exists():
        pytest.fail(f"{path} is missing from the built site", pytrace=False)
    host, base = sub_url
    failed: list[str] = []
    outside: list[str] = []
    page = browser_context.new_page()

    def on_response(resp):
        if resp.status >= 400:
            failed.append(f"{resp.status} {resp.url}")

    def on_request(req):
        if req.url.startswith(host) and not req.url.startswith(base):
            outside.append(req.url)

    page.on("response", on_response)
    page.on("requestfailed", lambda req: failed.append(f"failed {req.url}"))
    page.on("request", on_request)
    try:
        page.goto(base + path, wait_until="networkidle", timeout=60_000)
        landed = page.url
        title = page.title()
    finally:
        page.close()
    assert not failed, f"{path} from /{SUB}: " + "; ".join(failed)
    assert not outside, f"{path} from /{SUB} asked outside the sub-path: " + "; ".join(outside)
    assert landed.startswith(base) and title.strip()
    if path == "index.html":  # the root redirect lands on the first page
        assert landed == base + "chapters/intro.html"


def test_root_index_is_a_titled_page_in_english(book_html):
    text = (book_html / "index.html").read_text(encoding="utf-8")
    assert re.search(r'<html lang="en">', text) and re.search(r"<title>[^<]+</title>", text)


def _base_of_build(book_html: Path) -> str:
    locs = [e.text or "" for e in ET.parse(book_html / "sitemap.xml").getroot().iter() if e.tag.endswith("loc")]
    assert locs, "sitemap.xml lists no page"
    return locs[0][: locs[0].index("chapters/")] if "chapters/" in locs[0] else locs[0]


def test_sitemap_lists_every_page(book_html, book_toc_pages):
    locs = {e.text for e in ET.parse(book_html / "sitemap.xml").getroot().iter() if e.tag.endswith("loc")}
    base = _base_of_build(book_html)
    missing = [p for p in book_toc_pages if base + p not in locs]
    assert not missing, f"sitemap.xml misses {missing}"


def test_404_page_links_under_the_sites_path(book_html):
    text = (book_html / "404.html").read_text(encoding="utf-8")
    prefix = urlsplit(_base_of_build(book_html)).path
    assert "Page not found" in text
    local = [u for u in re.findall(r'(?:href|src)="([^"#?]+)', text) if not re.match(r"[a-z]+:", u)]
    assert local, "404.html links to nothing"
    wrong = [u for u in local if not u.startswith(prefix)]
    assert not wrong, f"404.html links outside {prefix}: {wrong[:5]}"
    missing = [u for u in local if not (book_html / u[len(prefix):]).exists()]
    assert not missing, f"404.html links to files that are not built: {missing[:5]}"


def test_chapters_have_a_description_a_card_and_the_version(book_html, book_toc_pages):
    for path in book_toc_pages:
        text = (book_html / path).read_text(encoding="utf-8")
        assert re.search(r'<meta name="description" content="[^"]{40,}"', text), f"{path}: no meta description"
        assert 'property="og:image" content="' in text, f"{path}: no social card"
        footer = re.search(r'class="book-version">([^<]+)', text)
        assert footer and re.search(r"Version \d+\.\d+\.\d+, built \d{4}-\d\d-\d\d", footer.group(1)), \
            f"{path}: footer has no version and build date"
        assert "computed by the course library" in text, f"{path}: the course's extra_footer is not shown"


@pytest.fixture(scope="module")
def book_toc_pages():
    from conftest import BOOK_TOC
    return bookcheck.pages_from_toc(BOOK_TOC)
