"""axe-core (WCAG 2.1 A and AA) finds no violation on any page of the book, in light and in dark mode.

Each page of the table of contents and the search page is loaded once and checked with the system asking
for light colours, then for dark ones (axe_pages.check_modes). test_axe_decks.py does the same for the decks.
"""

from __future__ import annotations

import axe_pages
import pytest
from conftest import BOOK_HTML, BOOK_TOC

PAGES = axe_pages.book_pages(BOOK_HTML, BOOK_TOC)


@pytest.mark.parametrize("path", PAGES)
def test_no_axe_violation_in_either_mode(path, book_url, browser_context):
    results = axe_pages.check_modes(browser_context, book_url, path)
    assert [r.mode for r in results] == ["light", "dark"]
    assert not [v for r in results for v in r.violations], "\n".join(line for r in results for line in r.lines())


# ---------------------------------------------------------------- what the check still catches
# A page with a planted fault of each kind that the way the check is run could hide: faint text in light mode
# only, faint text in dark mode only, an image without alt text that only dark mode shows, a formula drawn as
# MathJax does (its glyph box is emptied before axe-core runs) and glyph boxes that must not be emptied.
_PLANTED = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>Planted faults</title>
<style>
  body {{ background: #fff; color: #000; }}
  .dark-only {{ display: none; }}
  @media (prefers-color-scheme: light) {{ .light-faint {{ color: #ddd; }} }}
  @media (prefers-color-scheme: dark) {{
    body {{ background: #111; color: #eee; }}
    .dark-faint {{ color: #222; }}
    .dark-only {{ display: block; }}
  }}
  mjx-container, mjx-math, mjx-mi, mjx-c {{ display: inline-block; }}
  mjx-assistive-mml {{ position: absolute; clip: rect(1px, 1px, 1px, 1px); }}
</style></head>
<body><main><h1>Planted faults</h1>
{body}
<p>A formula: <mjx-container class="MathJax" jax="CHTML"><mjx-math aria-hidden="true"><mjx-mi><mjx-c
  class="mjx-c1D465"></mjx-c></mjx-mi></mjx-math><mjx-assistive-mml><math><mi>x</mi></math></mjx-assistive-mml>
  </mjx-container>.</p>
{glyph}
</main></body></html>
"""
_FAULTS = """<p class="light-faint" id="light-faint">Faint in light mode only.</p>
<p class="dark-faint" id="dark-faint">Faint in dark mode only.</p>
<div class="dark-only"><img id="dark-img" src="data:image/gif;base64,R0lGODlhAQABAAAAACw="></div>"""
_BAD_GLYPHS = """<p id="focusable"><mjx-container class="MathJax"><mjx-math aria-hidden="true"><a href="#x">x</a></mjx-math>
<mjx-assistive-mml><math><mi>x</mi></math></mjx-assistive-mml></mjx-container></p>
<p><mjx-container class="MathJax"><mjx-math><mjx-c></mjx-c></mjx-math>
<mjx-assistive-mml><math><mi>y</mi></math></mjx-assistive-mml></mjx-container></p>"""


def _nodes(result: axe_pages.AxeResult, rule: str) -> list[str]:
    return [" ".join(map(str, n["target"])) for v in result.violations if v["id"] == rule for n in v["nodes"]]


def test_check_catches_faults_of_one_mode_and_keeps_math_glyphs_honest(tmp_path, browser_context):
    import bookcheck

    (tmp_path / "clean.html").write_text(_PLANTED.format(body="<p>Plain text.</p>", glyph=""), encoding="utf-8")
    (tmp_path / "faults.html").write_text(_PLANTED.format(body=_FAULTS, glyph=""), encoding="utf-8")
    (tmp_path / "glyphs.html").write_text(_PLANTED.format(body="", glyph=_BAD_GLYPHS), encoding="utf-8")
    with bookcheck.BookServer(tmp_path) as server:
        clean = axe_pages.check_modes(browser_context, server.base, "clean.html")
        light, dark = axe_pages.check_modes(browser_context, server.base, "faults.html")
        glyphs = axe_pages.check_modes(browser_context, server.base, "glyphs.html")
    # the control: nothing to find, and the formula's glyph box was emptied before axe-core ran
    assert [r.violations for r in clean] == [[], []], "\n".join(line for r in clean for line in r.lines())
    assert [r.glyph_boxes_emptied for r in clean] == [1, 1]
    # light-only and dark-only faults, each found in its mode only
    assert _nodes(light, "color-contrast") == ["#light-faint"], light.lines()
    assert _nodes(dark, "color-contrast") == ["#dark-faint"], dark.lines()
    assert _nodes(light, "image-alt") == [] and _nodes(dark, "image-alt") == ["#dark-img"], (light.lines(), dark.lines())
    # glyph boxes that a reader's assistive technology could reach are not emptied: they are reported
    for r in glyphs:
        why = [n["failureSummary"] for v in r.violations if v["id"] == "mathjax-glyph-box" for n in v["nodes"]]
        assert len(why) == 2 and "focusable" in why[0] and "not aria-hidden" in why[1], r.lines()
        assert r.glyph_boxes_emptied == 1  # only the well-formed formula
