"""The book's math is typeset at build time; MathJax's menu and explorer load only when a reader asks.

One chapter page is opened once; every request it makes must go to the local
server (the book works offline). Checked on it, in turn:

* before any action: every formula of the page is typeset (an
  ``mjx-container`` of MathJax's SVG output with its hidden MathML,
  ``mjx-assistive-mml``, for screen readers), its SVG draws its glyphs with
  a path or two (flattened at build time: no ``<use>``, no glyph cache), and
  the page requested no MathJax script nor font;
* the reader tabs to a formula: MathJax with its menu and explorer is loaded
  from ``_static/mathjax`` (no other address), and the formula is typeset
  again from its TeX;
* the explorer: Enter starts it and an arrow key makes it speak a part of the
  formula (its live region gets text);
* the menu: a right-click opens MathJax's menu; "Show Math As" lists the TeX
  commands, and the formula's TeX source in MathJax is the page's TeX
  (what "Copy to Clipboard > TeX Commands" copies);
* zoom: a double-click on another formula shows it enlarged.
"""

from __future__ import annotations

import pytest

PAGE = "chapters/02_space_jacobian.html"


@pytest.fixture(scope="module")
def math_page(book_url, browser_context, book_html):
    if not (book_html / PAGE).exists():
        pytest.fail(f"{PAGE} is missing from the built site", pytrace=False)
    page = browser_context.new_page()
    requests: list[str] = []
    foreign: list[str] = []

    def on_request(req):
        if req.url.startswith(book_url):
            requests.append(req.url[len(book_url):])
        elif not req.url.startswith(("data:", "blob:")):
            foreign.append(req.url)

    page.on("request", on_request)
    failed: list[str] = []
    page.on("response", lambda resp: resp.status >= 400 and failed.append(f"{resp.status} {resp.url}"))
    page.on("requestfailed", lambda req: failed.append(f"failed {req.url}"))
    page.goto(book_url + PAGE, wait_until="domcontentloaded", timeout=120_000)
    page.wait_for_function("() => document.readyState === 'complete' && document.fonts.status === 'loaded'",
                           timeout=120_000)
    yield page, requests, foreign, failed
    page.close()


def test_math_is_typeset_in_the_page_without_mathjax(math_page):
    page, requests, foreign, failed = math_page
    counts = page.evaluate("""() => {
      const boxes = Array.from(document.querySelectorAll('span.math, div.math'));
      return {boxes: boxes.length, tex: boxes.filter(b => b.dataset.tex).length,
              typeset: boxes.filter(b => b.querySelector(':scope > mjx-container[jax="SVG"]')).length,
              mathml: boxes.filter(b => b.querySelector('mjx-assistive-mml > math')).length,
              focusable: boxes.filter(b => b.closest('a, button, summary, label')
                                           || b.querySelector(':scope > mjx-container[tabindex="0"]')).length,
              mathjax: !!window.MathJax,
              // a formula's glyphs are drawn by its own paths, not copied from a glyph cache
              paths: document.querySelectorAll('mjx-container svg path').length,
              drawn: boxes.filter(b => b.querySelector('mjx-container svg path')).length,
              uses: document.querySelectorAll('mjx-container use, #MJX-SVG-global-cache').length,
              svgElements: document.querySelectorAll('mjx-container svg *').length};
    }""")
    assert counts["boxes"] > 20, counts
    assert counts["tex"] == counts["typeset"] == counts["mathml"] == counts["focusable"] == counts["boxes"], counts
    assert not counts["mathjax"], "the page loaded MathJax before anyone asked for its menu"
    assert not [r for r in requests if r.endswith(".js") and "/mathjax/" in r], requests
    # the SVG output draws with paths: no MathJax font is needed until a reader asks for the menu
    assert not [r for r in requests if "/mathjax/" in r], requests
    assert counts["drawn"] == counts["boxes"] and counts["uses"] == 0, counts
    # flattened: MathJax wrote about 20 elements per formula of this page (a <g> per MathML node, a <use> per glyph)
    assert counts["svgElements"] <= 3 * counts["boxes"], counts
    assert not foreign and not failed, foreign + failed


def test_focus_loads_the_menu_and_explorer_offline(math_page):
    page, requests, foreign, failed = math_page
    page.evaluate("() => document.querySelector('p span.math > mjx-container').scrollIntoView()")
    first = page.locator("p span.math > mjx-container").first
    tex = first.evaluate("c => c.parentElement.dataset.tex")
    first.focus()
    page.wait_for_function("() => document.querySelector('[data-math-live=\"1\"]')", timeout=60_000)
    loaded = [r for r in requests if "/mathjax/" in r and r.endswith(".js")]
    for part in ("es5/startup.js", "es5/ui/menu.js", "es5/a11y/explorer.js"):
        assert any(r.endswith(part) for r in loaded), f"{part} not loaded on focus: {loaded}"
    item = page.evaluate("""() => {
      const box = document.querySelector('[data-math-live="1"]');
      const it = Array.from(MathJax.startup.document.math).find(m => box.contains(m.typesetRoot));
      return it && {math: it.math, focused: document.activeElement === it.typesetRoot};
    }""")
    assert item and item["math"] == tex, item
    assert item["focused"], "the formula typeset again did not get the focus back"
    assert not foreign and not failed, foreign + failed


def test_explorer_speaks_and_menu_offers_tex(math_page):
    page, _requests, foreign, failed = math_page
    box = page.locator('[data-math-live="1"] > mjx-container')
    box.focus()
    box.press("Enter")   # the explorer starts on Enter, then the arrow keys walk the formula
    box.press("ArrowDown")
    page.wait_for_function("""() => Array.from(document.querySelectorAll('.MJX_LiveRegion'))
                                .some(r => r.textContent.trim().length > 0)""", timeout=30_000)
    box.click(button="right")
    menu = page.locator(".CtxtMenu_Menu").first
    menu.wait_for(state="visible", timeout=10_000)
    text = menu.inner_text()
    for entry in ("Show Math As", "Copy to Clipboard", "Math Settings"):
        assert entry in text, f"the math menu has no {entry!r}: {text!r}"
    menu.get_by_text("Show Math As").hover()
    sub = page.locator(".CtxtMenu_Menu").nth(1)
    sub.wait_for(state="visible", timeout=10_000)
    assert "TeX Commands" in sub.inner_text()
    page.keyboard.press("Escape")
    page.keyboard.press("Escape")
    assert not foreign and not failed, foreign + failed


def test_double_click_zooms_a_formula(math_page):
    page, _requests, foreign, failed = math_page
    other = page.locator("div.math:not([data-math-live]) > mjx-container").first
    other.scroll_into_view_if_needed()
    other.dblclick()
    zoom = page.locator(".CtxtMenu_Info").filter(has=page.locator("mjx-container")).first
    zoom.wait_for(state="visible", timeout=60_000)
    assert not foreign and not failed, foreign + failed
