"""The book's chrome, as a reader meets it: one search box, readable search results, no placeholder links."""

from __future__ import annotations

import re
import unicodedata
from urllib.parse import urlsplit

import pytest

RAW_TEX = re.compile(r"\\[A-Za-z]+|\\[()\[\]]|\$\$")


def _open(context, url: str, width: int = 1280):
    page = context.new_page()
    page.set_viewport_size({"width": width, "height": 900})
    host = urlsplit(url).hostname
    page.route("**/*", lambda r: r.continue_() if urlsplit(r.request.url).hostname in (host, None)
               else r.abort("blockedbyclient"))
    page.goto(url, wait_until="load")
    page.wait_for_timeout(1500)  # the theme shows its JS-only controls after load
    return page


def _visible_search_fields(page) -> int:
    return page.evaluate(
        """() => [...document.querySelectorAll('button.search-button-field, form.bd-search input[type=search]')]
              .filter(e => { const r = e.getBoundingClientRect(); const s = getComputedStyle(e);
                             return r.width > 0 && r.height > 0 && s.visibility !== 'hidden'
                                    && !e.closest('dialog'); }).length"""
    )


def test_one_search_box_on_a_chapter_page(book_url, browser_context):
    page = _open(browser_context, f"{book_url}chapters/01_twists.html")
    n = _visible_search_fields(page)
    page.close()
    assert n == 1, f"a chapter page at 1280 px shows {n} search boxes, expected exactly 1 (the sidebar's)"


def test_search_page_shows_only_its_own_box_and_the_sidebar(book_url, browser_context):
    page = _open(browser_context, f"{book_url}search.html")
    n = _visible_search_fields(page)
    page.close()
    assert n == 2, f"the search page shows {n} search fields, expected 2 (its own form and the sidebar's button)"


def test_search_page_field_keeps_its_icon_clear_of_the_text(book_url, browser_context):
    """The magnifying glass of the search page's field sits left of where typed text starts."""
    page = _open(browser_context, f"{book_url}search.html?q=adjoint")
    icon_right, text_left = page.evaluate(
        """() => { const f = [...document.querySelectorAll('form.bd-search')]
                     .find(f => f.querySelector('input').getBoundingClientRect().width > 0);
                   const i = f.querySelector('i').getBoundingClientRect(), inp = f.querySelector('input');
                   return [i.right, inp.getBoundingClientRect().left + parseFloat(getComputedStyle(inp).paddingLeft)]; }""")
    page.close()
    assert icon_right <= text_left, f"the icon ends at x={icon_right:.0f}, the typed text starts at x={text_left:.0f}"


@pytest.mark.parametrize("query", ["torque", "adjoint", "jacobian"])
def test_search_summaries_show_no_raw_tex(book_url, browser_context, query):
    page = _open(browser_context, f"{book_url}search.html?q={query}")
    page.wait_for_function(
        "() => document.querySelectorAll('#search-results ul.search li p.context').length > 2"
        " || /did not match/i.test((document.querySelector('#search-results') || {}).textContent || '')",
        timeout=20_000,
    )
    page.wait_for_timeout(1500)  # the remaining summaries arrive one by one
    summaries = page.evaluate(
        "() => [...document.querySelectorAll('#search-results ul.search li p.context')].map(p => p.textContent)"
    )
    page.close()
    assert len(summaries) >= 3, f"searching {query!r} gave {len(summaries)} summaries"
    bad = [(s[:90], RAW_TEX.findall(s)[:3]) for s in summaries if RAW_TEX.search(s)]
    assert not bad, f"search summaries for {query!r} show raw TeX: {bad}"


def test_plain_tex_reading(book_url, browser_context):
    """The converter the search page uses turns formulas into plain words."""
    page = _open(browser_context, f"{book_url}search.html")
    cases = {
        r"\tau = J^T\mathcal F": "τ = J^T F",
        r"\dot x = J_a(\theta)\,\dot\theta": "ẋ = J_a(θ) θ̇",
        r"[\mathrm{Ad}_{T_{bs}}] J_s": "[Ad_T_bs] J_s",
        r"\begin{bmatrix} 1 & 0 \\ 0 & 1 \end{bmatrix}": "[matrix]",
    }
    got = {tex: unicodedata.normalize("NFC", page.evaluate("t => window.jacobiansPlainTex(t)", tex))
           for tex in cases}
    page.close()
    assert got == {tex: unicodedata.normalize("NFC", want) for tex, want in cases.items()}


def test_no_placeholder_repository_url(book_html):
    hits = [p.relative_to(book_html).as_posix() for p in book_html.rglob("*.html")
            if "example.invalid" in p.read_text(encoding="utf-8", errors="replace")]
    assert not hits, f"pages link a placeholder repository URL: {hits[:5]}"
