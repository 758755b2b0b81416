"""The theme's CSS trimmed by PurgeCSS (``_ext/trim_css.py``, ``tools/purge_css.cjs``) on a tiny site: what a page
or a script names stays, with dark mode and the safelisted states; what nothing names goes."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "_ext"))
import trim_css

THEME = """.used-in-page{color:red}
.added-by-script{color:blue}
.never-used{color:green}
html[data-theme=dark] .used-in-page{color:pink}
.dropdown-menu.show{display:block}
.bd-unused-widget{margin:0}
"""


@pytest.mark.skipif(shutil.which("node") is None or not (trim_css.ROOT / "node_modules" / "purgecss").is_dir(),
                    reason="needs Node and npm's purgecss (make setup)")
def test_only_rules_that_a_page_or_a_script_names_stay(tmp_path):
    site = tmp_path / "html"
    (site / "_static" / "styles").mkdir(parents=True)
    (site / "slides").mkdir()
    (site / "index.html").write_text('<html><body><div class="used-in-page">x</div></body></html>')
    # a deck's page names a class the book never uses: the decks load their own copies, so it does not count
    (site / "slides" / "deck.html").write_text('<div class="bd-unused-widget"></div>')
    (site / "_static" / "app.js").write_text('el.classList.add("added-by-script"); root.dataset.theme = "dark";')
    sheet = site / "_static" / "styles" / "pydata-sphinx-theme.css"
    sheet.write_text(THEME + "/*# sourceMappingURL=pydata-sphinx-theme.css.map */\n")
    own = site / "_static" / "course.css"
    own.write_text(".never-used{color:green}")
    report = trim_css.trim(site)
    css = sheet.read_text()
    assert ".used-in-page{" in css and ".added-by-script{" in css
    assert "html[data-theme=dark] .used-in-page" in css and ".dropdown-menu.show" in css
    assert ".never-used" not in css and ".bd-unused-widget" not in css and "sourceMappingURL" not in css
    assert own.read_text() == ".never-used{color:green}"   # the course's own style sheets stay whole
    before, after = report["sizes"]["styles/pydata-sphinx-theme.css"]
    assert before == len(THEME) + len("/*# sourceMappingURL=pydata-sphinx-theme.css.map */\n") and after == len(css)


def test_a_site_without_static_files_is_refused(tmp_path):
    if shutil.which("node") is None:
        pytest.skip("needs Node")
    with pytest.raises(Exception, match="Usage"):
        trim_css.trim(tmp_path)
