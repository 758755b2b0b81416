"""The build-time typesetting of fragments (the exercise statements of each variant) and of outputs marked
``mathjax_process``: the same MathJax document as the page; every formula draws its own glyphs (no glyph cache)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "_ext"))

import math_prerender  # noqa: E402


def test_fragments_and_processed_outputs_are_typeset(tmp_path: Path):
    page = tmp_path / "page.html"
    page.write_text('<html><head></head><body><span class="math notranslate nohighlight">\\(x\\)</span>'
                    '<div class="jacobians-feedback-statement mathjax_process">Turn about \\(\\hat\\omega &lt; 1\\)'
                    '</div></body></html>', encoding="utf-8")
    src = tmp_path / "src.json"
    src.write_text(json.dumps(["Give \\(\\theta_2 = 1\\) and \\[\\begin{bmatrix}1 & 0\\end{bmatrix}\\]<br>now",
                               "No math"]), encoding="utf-8")
    out = tmp_path / "st" / "ex"
    spec = {str(page): [{"src": str(src), "out": str(out), "key": "ex"}]}
    for _ in range(2):  # typeset twice: a page typeset before is typeset again from its TeX
        (report,) = math_prerender.typeset(tmp_path, [page], {}, spec)
        assert report["math"] == 4
    html = page.read_text(encoding="utf-8")
    assert "\\(" not in html and 'data-tex="\\hat\\omega &lt; 1"' in html and html.count("<mjx-container") == 2
    # no glyph cache in the page: a fragment, shown later by a script, draws its glyphs itself
    assert "MJX-SVG-global-cache" not in html and "<use" not in html
    first = (out / "0.js").read_text(encoding="utf-8")
    assert first.startswith('(window.__courseStatements=window.__courseStatements||{})["ex/0"]=')
    shown = json.loads(first.split("=", 2)[2].rstrip(";\n").replace("<\\/", "</"))
    assert shown.count("<mjx-container") == 2 and 'data-tex="\\theta_2 = 1"' in shown and "\\(" not in shown
    assert "<use" not in shown and "xlink:href" not in shown and shown.count("<path") == 2  # (one per formula)
    assert '<div class="math notranslate nohighlight" data-tex="\\begin{bmatrix}1 &amp; 0\\end{bmatrix}">' in shown
    assert (out / "1.js").read_text(encoding="utf-8").endswith('="No math";\n')
