"""The book's formulas look the same flattened (``tools/flatten_math_svg.cjs``) as MathJax drew them.

The build draws each formula with one ``<path>`` (or one per colour) where MathJax's SVG output has a ``<g>`` per
MathML node and a glyph per ``<path>`` or ``<use>``. Here, formulas of the built book are typeset both ways (the
flattener's command line: MathJax's own SVG, then the same flattened), drawn in Chromium side by side in cells of
one size at the same place, and compared pixel by pixel.

Which formulas: the book's distinct formulas (their TeX, from the built chapters and exercise pages) that MathJax
draws with the most elements (the deepest transforms: fractions in matrices, scripts of scripts), every one in
which the flattener keeps an element as it was or that it leaves whole, and ``EXTRA``: what an author may write
and the book does not yet (colours, a ``\\cancel`` line, a box, a link, a character the fonts lack, stretched
arrows and braces, an equation number).

The bound on a pixel's change (grey levels of 255), derived:

* Where two shapes overlap (a root's sign and its bar, a delimiter's pieces), one path is antialiased once, where
  two were blended: with coverages a and b of the pixel, blending gives a + b - ab, and one path gives a coverage
  u with max(a, b) <= u <= min(1, a + b). So |u - (a + b - ab)| <= max(min(a, b)(1 - max(a, b)), ab or
  (1 - a)(1 - b)) <= 1/4.
* A shape's edge moves by at most one font unit (1/1000 em: tests/js/math_flatten.test.mjs checks every point of
  a formula against its exact place). With exact coverage that changes a pixel by at most FONT_PX/1000 (0.024);
  a rasterizer that samples coverage (Skia's supersampling: 4 sub-scanlines a pixel) can see an edge cross one
  sample, a change of at most 1/4. So at most 1/4.

Together: at most half a pixel's coverage, 255/2. A glyph put in the wrong place, scaled or flipped wrongly, or a
hole cut where two shapes overlap changes whole pixels inside the glyph's stems (2 px and more at FONT_PX): 255
(the cells are black on white).

MathJax's zero-width stroke (``stroke-width="0"`` with ``stroke="currentColor"``, which Chromium still draws as a
hairline on a transformed path) is turned off on both sides for the comparison; the flattened paths keep it, so
that the page looks as before.
"""

from __future__ import annotations

import html
import io
import json
import re
import subprocess
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
FONT_PX = 24
BOUND = 255 * (0.25 + 0.25)
#: the formulas with the most SVG elements in MathJax's output that are compared (with every unusual one)
LARGEST = 160
CELL_W, CELL_H, COLUMNS = 880, 150, 2
PER_SHOT = 40
EXTRA = [r"\textcolor{red}{a} + b \textcolor{blue}{\frac{c}{d}} e {\color{green} f}", r"\cancel{x} + \bcancel{y}", r"\boxed{J_s(\theta)}",
         r"\bbox[yellow,5px]{\dot\theta}", r"\href{#top}{\omega}", r"\text{é, ü: } x", r"\sqrt[3]{x^2 + y_1}",
         r"\overbrace{a + b}^{n} \underbrace{c}_{m}", r"\xrightarrow[under]{\text{over}} \Longleftrightarrow",
         r"\left(\frac{\partial f}{\partial \theta}\right)^{\!2} \Bigg| \,", r"x = 1 \tag{7}",
         r"\enclose{circle}{x} \enclose{roundedbox}{y}"]

pytestmark = pytest.mark.browser


def _book_formulas(book_html: Path) -> list[tuple[str, bool]]:
    found: set[tuple[str, bool]] = set()
    for page in [*book_html.glob("chapters/*.html"), *book_html.glob("exercises/*.html")]:
        text = page.read_text(encoding="utf-8")
        for m in re.finditer(r'<(span|div) class="[^"]*\bmath\b[^"]*"[^>]*? data-tex="([^"]*)"', text):
            found.add((html.unescape(m.group(2)), m.group(1) == "div"))
    return sorted(found)


@pytest.fixture(scope="module")
def drawn(book_html, tmp_path_factory):
    formulas = _book_formulas(book_html)
    if len(formulas) < 500:
        pytest.fail(f"only {len(formulas)} formulas found in the built book's pages", pytrace=False)
    formulas += [(t, display) for t in EXTRA for display in (False, True)]
    macros = _macros()
    tmp = tmp_path_factory.mktemp("flatten")
    (tmp / "in.json").write_text(json.dumps({"tex": [list(f) for f in formulas], "macros": macros}),
                                 encoding="utf-8")
    subprocess.run(["node", str(ROOT / "tools" / "flatten_math_svg.cjs"), str(tmp / "in.json"),
                    str(tmp / "out.json")], check=True, cwd=ROOT, timeout=600)
    return formulas, json.loads((tmp / "out.json").read_text(encoding="utf-8"))


def _macros() -> dict:
    """The book's TeX macros (``_config.yml``: the configuration the build typesets with)."""
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    return config["sphinx"]["config"]["mathjax3_config"]["tex"]["macros"]


def _unusual(f: dict) -> bool:
    return f["after"] is None or "<g" in f["flat"].split("<mjx-assistive-mml")[0]


def test_flattening_draws_fewer_elements(drawn):
    formulas, out = drawn
    rows = out["formulas"][:-2 * len(EXTRA)]  # (the book's own)
    assert len(rows) + 2 * len(EXTRA) == len(formulas)
    flat = [r for r in rows if r["after"] is not None]
    before, after = sum(r["before"] for r in flat), sum(r["after"] for r in flat)
    # every formula the flattener takes becomes at most as many elements, and the book's as a whole a tenth
    assert all(r["after"] <= r["before"] for r in flat)
    assert after * 10 <= before, (before, after)
    # only a table of equation numbers (laid out by the browser's width) leaves a formula whole
    assert all(r["after"] is not None or 'data-labels="true"' in r["mathjax"] for r in rows), \
        [r["tex"] for r in rows if r["after"] is None][:20]


def test_flattened_formulas_look_the_same(drawn, browser_context):
    from PIL import Image, ImageChops

    _formulas, out = drawn
    rows = out["formulas"]
    extra = rows[-2 * len(EXTRA):]
    rows = rows[:-2 * len(EXTRA)]
    unusual = extra + [r for r in rows if _unusual(r)]
    largest = sorted((r for r in rows if not _unusual(r)), key=lambda r: -r["before"])[:LARGEST]
    chosen = unusual + largest
    assert any(r["after"] is None for r in unusual) and any(r["after"] is not None for r in unusual), \
        "EXTRA no longer has a formula the flattener leaves whole, or one with a kept element: add one"
    page = browser_context.new_page()
    page.set_viewport_size({"width": CELL_W * COLUMNS, "height": 900})
    try:
        page.set_content(
            "<!doctype html><html><head><style>"
            f"body{{margin:0;background:#fff;color:#000;font-size:{FONT_PX}px}}"
            f"#grid{{display:grid;grid-template-columns:repeat({COLUMNS},{CELL_W}px);grid-auto-rows:{CELL_H}px}}"
            ".cell{overflow:hidden;padding:8px;box-sizing:border-box}"
            "mjx-container{margin:0 !important}"
            # MathJax's zero-width stroke, off on both sides (see the module's docstring); a <line> keeps its own
            "mjx-container svg g, mjx-container svg path, mjx-container svg rect{stroke:none !important}"
            f"</style><style>{out['css']}</style></head><body><div id=grid></div></body></html>")
        worst: list[tuple[float, str]] = []
        for start in range(0, len(chosen), PER_SHOT):
            part = chosen[start:start + PER_SHOT]
            shots = []
            for side in ("mathjax", "flat"):
                page.evaluate("cells => document.getElementById('grid').innerHTML = cells.map("
                              "c => '<div class=cell>' + c + '</div>').join('')", [r[side] for r in part])
                shots.append(Image.open(io.BytesIO(page.locator("#grid").screenshot())).convert("L"))
            a, b = shots
            assert a.size == b.size
            for k, r in enumerate(part):
                x, y = (k % COLUMNS) * CELL_W, (k // COLUMNS) * CELL_H
                box = (x, y, x + CELL_W, y + CELL_H)
                ca, cb = a.crop(box), b.crop(box)
                assert ca.getextrema()[0] < 128, f"nothing drawn for {r['tex']!r}"
                worst.append((ImageChops.difference(ca, cb).getextrema()[1], r["tex"]))
        bad = sorted(((d, t) for d, t in worst if d > BOUND), reverse=True)
        assert not bad, f"{len(bad)} of {len(worst)} formulas change by more than {BOUND:.0f}/255: {bad[:10]}"
        assert len(worst) == len(chosen)
    finally:
        page.close()
