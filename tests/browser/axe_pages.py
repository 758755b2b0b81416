"""axe-core over the built book and its decks: what WCAG 2.1 A and AA rules each page breaks.

axe-core comes from npm (``node_modules/axe-core/axe.min.js``); it is injected
into each page after the page has settled (MathJax has typeset, the live views
have mounted), and runs the rules tagged ``wcag2a``, ``wcag2aa``, ``wcag21a``
and ``wcag21aa``. Each page is loaded once and checked in both colour modes:

* light: the reader's system asks for light (``prefers-color-scheme: light``);
* dark: it asks for dark; the book follows it (the theme's mode is "auto": the
  theme sets ``<html data-theme>`` from the media query and again when it
  changes, which :func:`check_modes` waits for), and so do the live views and the decks
  (``course.css``, the decks' stylesheet: media queries, applied at once).

Before axe-core runs, MathJax's glyph boxes are emptied, once shown to hold nothing any rule could find
(``_HOLLOW_GLYPH_BOXES``): they are half of a chapter's elements, and axe-core's time grows with the element
count (measured, CPU seconds of Chromium and pytest, every page and deck in both modes: 519 before, 411 after,
the planted page's test included; the same results). ``test_axe_pages.py`` plants a fault of each kind the check could miss and finds it.

Used by ``test_axe_pages.py`` (the book's pages) and ``test_axe_decks.py`` (the
decks; two modules, so ``make test-browser`` runs them on its two workers) and
from the command line (``python tests/browser/axe_pages.py [--dark] [page ...]``),
which prints each violation with its nodes.
"""

from __future__ import annotations

import json
import sys
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(HERE))

import bookcheck  # noqa: E402

AXE_JS = ROOT / "node_modules" / "axe-core" / "axe.min.js"
WCAG_TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
EXTRA_PAGES = ["search.html"]  # written by Sphinx, not in the table of contents


def deck_pages(book_html: Path) -> list[str]:
    """The decks' index and every deck (``make book`` builds them into ``slides/``)."""
    slides = book_html / "slides"
    decks = sorted(p.relative_to(book_html).as_posix() for p in slides.rglob("*.html") if p.name != "index.html")
    return ["slides/index.html", *decks] if (slides / "index.html").exists() else decks


def book_pages(book_html: Path, toc: Path) -> list[str]:
    return [*bookcheck.pages_from_toc(toc), *EXTRA_PAGES]


@dataclass
class AxeResult:
    path: str
    mode: str
    violations: list[dict] = field(default_factory=list)
    passes: int = 0
    glyph_boxes_emptied: int = 0

    def lines(self) -> list[str]:
        out = []
        for v in self.violations:
            nodes = v["nodes"]
            where = "; ".join(
                f"{' '.join(n['target']) if isinstance(n['target'][0], str) else n['target']}"
                f" ({(n.get('failureSummary') or '').splitlines()[-1].strip() if n.get('failureSummary') else ''})"
                for n in nodes[:4])
            more = f" and {len(nodes) - 4} more" if len(nodes) > 4 else ""
            out.append(f"{self.path} [{self.mode}] {v['id']} ({v['impact']}), {len(nodes)} nodes: {where}{more}")
        return out


_SETTLE = """async () => {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) { await MathJax.startup.promise; }
  if (window.Reveal && Reveal.isReady && !Reveal.isReady()) {
    await new Promise((ok) => Reveal.on('ready', ok));
  }
  await new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok)));
}"""

_RUN = """async (tags) => {
  const r = await axe.run(document, {runOnly: {type: 'tag', values: tags}, resultTypes: ['violations']});
  return {violations: r.violations.map(v => ({id: v.id, impact: v.impact, help: v.help,
            nodes: v.nodes.map(n => ({target: n.target, html: n.html.slice(0, 200),
                                       failureSummary: n.failureSummary}))})),
          passes: r.passes.length};
}"""


# MathJax draws each formula twice: a box of glyphs for the eye (the SVG output's ``svg``, or the CHTML output's
# ``mjx-math`` (the decks'), aria-hidden; paths, or CSS ``::before`` content: elements but no text) and MathML for assistive
# technology (``mjx-assistive-mml``). On a chapter the glyph boxes are half the page's elements (ch. 6: about
# 10,000 of 20,500), and axe-core's cost grows with the element count, not with the rules asked for (one rule
# takes about as long as all of them). So before axe runs, each glyph box is emptied (kept, with its own size, so
# the layout around it is unchanged), once it is shown that no rule could have found anything inside it:
# it is aria-hidden, has no text, no focusable element, no role or aria-* attribute inside, and its formula has
# its MathML beside it. A box that fails this is reported as a violation (``mathjax-glyph-box``), so that a
# change to how formulas are drawn cannot hide anything from axe-core.
_HOLLOW_GLYPH_BOXES = """() => {
  const FOCUSABLE = 'a[href], area[href], button, input, select, textarea, iframe, object, embed, summary, '
    + '[tabindex], [contenteditable]:not([contenteditable="false"]), audio[controls], video[controls]';
  const bad = [];
  const boxes = Array.from(document.querySelectorAll('mjx-container > mjx-math, mjx-container > svg'));
  const empty = boxes.filter((m) => {
    const why = [];
    if (m.getAttribute('aria-hidden') !== 'true') why.push('not aria-hidden');
    const walker = document.createTreeWalker(m, NodeFilter.SHOW_TEXT);
    for (let t = walker.nextNode(); t; t = walker.nextNode()) {
      if (t.nodeValue.trim()) { why.push('holds text "' + t.nodeValue.trim().slice(0, 40) + '"'); break; }
    }
    if (m.querySelector(FOCUSABLE)) why.push('holds a focusable element');
    for (const e of m.querySelectorAll('*')) {
      if (e.getAttributeNames().some((a) => a === 'role' || a.startsWith('aria-'))) {
        why.push('holds an element with a role or aria-* attribute'); break;
      }
    }
    const mml = m.parentElement.querySelector(':scope > mjx-assistive-mml > math');
    if (!mml && !m.parentElement.hasAttribute('aria-label')) why.push('its formula has no MathML nor label beside it');
    if (why.length) bad.push({target: [m.parentElement.id ? '#' + m.parentElement.id : 'mjx-container'],
                              html: m.parentElement.outerHTML.slice(0, 200), failureSummary: why.join('; ')});
    return !why.length;
  });
  const sizes = empty.map((m) => m.getBoundingClientRect());
  empty.forEach((m, i) => {
    const style = getComputedStyle(m);
    m.style.width = sizes[i].width + 'px';
    m.style.height = sizes[i].height + 'px';
    if (style.display === 'inline') m.style.display = 'inline-block';
    m.replaceChildren();
  });
  return {emptied: empty.length, bad};
}"""

_MODE_APPLIED = """(mode) => {
  const root = document.documentElement;
  return root.dataset.mode !== "auto" || root.dataset.theme === mode;
}"""


def check_modes(context, base: str, path: str, modes: tuple[str, ...] = ("light", "dark"),
                timeout: float = 60_000) -> list[AxeResult]:
    """Load ``path`` once; for each mode, ask for its colours, let the page follow, run axe-core."""
    page = context.new_page()
    out = []
    try:
        page.emulate_media(color_scheme=modes[0])
        page.goto(base + path, wait_until="load", timeout=timeout)
        page.evaluate(_SETTLE)
        page.add_script_tag(path=str(AXE_JS))
        # the theme animates its colours when the mode changes: axe must see the colours of the mode, not a blend
        page.add_style_tag(content="*, *::before, *::after { transition: none !important; animation: none !important; }")
        hollow = page.evaluate(_HOLLOW_GLYPH_BOXES)
        for mode in modes:
            page.emulate_media(color_scheme=mode)
            page.wait_for_function(_MODE_APPLIED, arg=mode, timeout=timeout)
            page.evaluate(_SETTLE)
            got = page.evaluate(_RUN, WCAG_TAGS)
            violations = got["violations"]
            if hollow["bad"]:
                violations = [*violations, {
                    "id": "mathjax-glyph-box", "impact": "serious", "nodes": hollow["bad"],
                    "help": "a MathJax glyph box that assistive technology could reach: axe-core must see inside it"}]
            out.append(AxeResult(path, mode, violations, got["passes"], hollow["emptied"]))
    finally:
        page.close()
    return out


def check(context, base: str, path: str, mode: str) -> AxeResult:
    """Load ``path`` in ``mode`` ("light" or "dark"), run axe-core, return its violations."""
    return check_modes(context, base, path, (mode,))[0]


def main(argv: list[str]) -> int:
    from playwright.sync_api import sync_playwright

    dark = "--dark" in argv
    args = [a for a in argv if not a.startswith("--")]
    html = ROOT / "_build" / "html"
    paths = args or [*book_pages(html, ROOT / "_toc.yml"), *deck_pages(html)]
    total = 0
    with bookcheck.BookServer(html) as server, sync_playwright() as p, bookcheck.opened_browser(p) as context:
        for path in paths:
            for r in check_modes(context, server.base, path, ("dark",) if dark else ("light", "dark")):
                mode = r.mode
                total += len(r.violations)
                for line in r.lines():
                    print(line)
                if not r.violations:
                    print(f"{path} [{mode}] clean ({r.passes} rules pass)")
    print(json.dumps({"violations": total, "pages": len(paths)}))
    return 1 if total else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
