"""_ext/offline_fixes.py: each handler fixes its problem, and fails loudly once the problem is gone."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import Any

import alt_text
import offline_fixes as fx
import pytest
from docutils import nodes
from docutils.frontend import get_default_settings
from docutils.parsers.rst import Parser
from docutils.utils import new_document

ROOT = Path(__file__).resolve().parents[1]


def js(filename: str | None, **attributes: Any) -> SimpleNamespace:
    """Stands for a Sphinx script entry (filename, attributes); the handlers only read these two."""
    return SimpleNamespace(filename=filename, attributes=attributes, priority=500)


def app(tmp_path: Path, **config: Any) -> SimpleNamespace:
    cfg = SimpleNamespace(html_theme_options={}, html_context=None, html_favicon=None, templates_path=[])
    for key, value in config.items():
        setattr(cfg, key, value)
    return SimpleNamespace(config=cfg, doctreedir=str(tmp_path / "doctrees"), outdir=str(tmp_path / "html"),
                           builder=SimpleNamespace(format="html", name="html"), parallel=1,
                           env=SimpleNamespace(found_docs={"a", "b"}))


@pytest.fixture(autouse=True)
def fresh_tally():
    fx._reset_tally(None)  # type: ignore[arg-type]
    yield
    fx._reset_tally(None)  # type: ignore[arg-type]


def test_duplicate_inline_scripts_are_dropped(tmp_path):
    body = "var THEBE_JS_URL = 1"
    ctx = {"script_files": [js(None, body=body), js("", body=body), js("a.js"), js("a.js")]}
    fx.drop_duplicate_scripts(app(tmp_path), "a", "page.html", ctx, None)
    assert [(s.filename, s.attributes) for s in ctx["script_files"]] == [(None, {"body": body}), ("a.js", {})]
    assert fx._TALLY["drop_duplicate_scripts"] == 1


def test_thebe_assets_dropped_only_when_thebe_is_off(tmp_path):
    def ctx():
        return {"script_files": [js("_static/sphinx-thebe.js"), js(None, body="const THEBE_JS_URL = 'x'"),
                                 js("keep.js")],
                "css_files": [js("_static/sphinx-thebe.css"), js("keep.css")]}

    off = ctx()
    fx.drop_thebe_assets(app(tmp_path), "a", "page.html", off, None)
    assert [s.filename for s in off["script_files"]] == ["keep.js"]
    assert [c.filename for c in off["css_files"]] == ["keep.css"]
    on = ctx()
    fx.drop_thebe_assets(app(tmp_path, html_theme_options={"launch_buttons": {"thebe": True}}), "a", "p", on, None)
    assert len(on["script_files"]) == 3 and len(on["css_files"]) == 2
    assert fx._TALLY["drop_thebe_assets"] == 1


def test_widget_assets_dropped_without_a_widget_and_a_widget_stops_the_build(tmp_path):
    scripts = [js("require.js"), js("html-manager/embed-amd.js"), js(None, type=fx.WIDGET_STATE, body="{}"),
               js("keep.js")]
    ctx = {"script_files": list(scripts), "body": "<p>an animation</p>"}
    fx.drop_unused_widget_assets(app(tmp_path), "a", "page.html", ctx, None)
    assert [s.filename for s in ctx["script_files"]] == ["keep.js"]
    assert fx._TALLY["drop_unused_widget_assets"] == 1
    shown = {"script_files": list(scripts), "body": f'<script type="{fx.WIDGET_VIEW}">{{}}</script>'}
    with pytest.raises(fx.ExtensionError, match="page 'b' shows a live Jupyter widget"):
        fx.drop_unused_widget_assets(app(tmp_path), "b", "page.html", shown, None)


def test_full_build_where_a_page_fix_changed_nothing_fails(tmp_path):
    a = app(tmp_path)
    for page in ("a", "b", "genindex"):
        fx._count_page(a, page, "page.html", {}, None)
    assert fx._TALLY["pages"] == 2  # genindex is not a document
    for handler in ("drop_duplicate_scripts", "drop_thebe_assets", "fill_alt_text"):
        fx._TALLY[handler] += 1
    with pytest.raises(fx.ProblemGone, match="drop_unused_widget_assets: changed none of the 2 pages"):
        fx.check_tally(a, None)
    fx._TALLY["drop_unused_widget_assets"] += 1
    fx.check_tally(a, None)  # every fix had work: no error


def test_incremental_build_skips_the_tally_check(tmp_path):
    a = app(tmp_path)
    fx._count_page(a, "a", "page.html", {}, None)  # one page of two written
    fx.check_tally(a, None)
    fx._count_page(a, "b", "page.html", {}, None)
    fx.check_tally(a, RuntimeError("the build failed"))  # a failed build reports its own error


def test_theme_mode_defaults_to_auto_and_an_explicit_one_is_kept(tmp_path):
    a = app(tmp_path)
    fx.default_theme_mode(a, a.config)  # type: ignore[arg-type]
    assert a.config.html_context == {"default_mode": "auto"}
    b = app(tmp_path, html_context={"default_mode": "dark"})
    fx.default_theme_mode(b, b.config)  # type: ignore[arg-type]
    assert b.config.html_context == {"default_mode": "dark"}


def test_theme_mode_fails_when_the_theme_no_longer_reads_it(tmp_path, monkeypatch):
    (tmp_path / "layout.html").write_text('<script>mode = localStorage.getItem("mode") || "auto";</script>')
    monkeypatch.setattr(fx, "_theme_file", lambda *parts: tmp_path.joinpath(*parts))
    a = app(tmp_path)
    with pytest.raises(fx.ProblemGone, match="default_theme_mode"):
        fx.default_theme_mode(a, a.config)  # type: ignore[arg-type]


def test_favicon_is_given_unless_one_is_set(tmp_path):
    a = app(tmp_path)
    fx.default_favicon(a, a.config)  # type: ignore[arg-type]
    assert Path(a.config.html_favicon) == ROOT / "_ext" / "favicon.svg" and Path(a.config.html_favicon).is_file()
    with pytest.raises(fx.ProblemGone, match="html_favicon is already set"):
        fx.default_favicon(a, a.config)  # type: ignore[arg-type]


def test_fontawesome_js_is_removed_from_the_theme_macros(tmp_path):
    a = app(tmp_path, templates_path=["_templates"])
    fx.drop_fontawesome_js(a, a.config)  # type: ignore[arg-type]
    override = Path(a.config.templates_path[0]) / "static" / "webpack-macros.html"
    assert a.config.templates_path[1:] == ["_templates"]
    text = override.read_text()
    assert "fontawesome.js" not in text and "pydata-sphinx-theme.js" in text


def test_fontawesome_js_fix_fails_when_the_theme_no_longer_loads_it(tmp_path, monkeypatch):
    (tmp_path / "static").mkdir()
    (tmp_path / "static" / "webpack-macros.html").write_text('<script src="scripts/bootstrap.js"></script>\n')
    monkeypatch.setattr(fx, "_theme_file", lambda *parts: tmp_path.joinpath(*parts))
    a = app(tmp_path)
    with pytest.raises(fx.ProblemGone, match="does not load scripts/fontawesome.js"):
        fx.drop_fontawesome_js(a, a.config)  # type: ignore[arg-type]


def test_search_scripts_leave_every_page_but_the_search_page(tmp_path):
    a = app(tmp_path, templates_path=["_templates"])
    fx.search_scripts_on_search_page_only(a, a.config)  # type: ignore[arg-type]
    root = Path(a.config.templates_path[0])
    assert a.config.templates_path[1:] == ["_templates"]
    text = (root / "pydata_sphinx_theme" / "layout.html").read_text()
    original = fx._theme_file("layout.html").read_text()
    for name in ("searchtools.js", "language_data.js", "searchindex.js"):
        assert name in original and name not in text
    # only those three lines went
    assert len(original.splitlines()) - len(text.splitlines()) == 3
    fx.search_scripts_on_search_page_only(a, a.config)  # type: ignore[arg-type]
    assert a.config.templates_path.count(str(root)) == 1


def test_search_scripts_fix_fails_with_search_as_you_type_or_a_changed_theme(tmp_path, monkeypatch):
    a = app(tmp_path, html_theme_options={"search_as_you_type": True})
    with pytest.raises(fx.ProblemGone, match="search_as_you_type is on"):
        fx.search_scripts_on_search_page_only(a, a.config)  # type: ignore[arg-type]
    (tmp_path / "layout.html").write_text("{% block extrahead %}{% endblock %}\n")
    monkeypatch.setattr(fx, "_theme_file", lambda *parts: tmp_path.joinpath(*parts))
    b = app(tmp_path)
    with pytest.raises(fx.ProblemGone, match="no longer loads searchtools.js"):
        fx.search_scripts_on_search_page_only(b, b.config)  # type: ignore[arg-type]


def test_plain_math_search_script_only_on_the_search_page(tmp_path):
    scripts = [js("_static/a.js"), js("_static/search_plain_math.js"), js("_static/b.js")]
    page: dict[str, Any] = {"script_files": list(scripts)}
    fx.plain_math_search_on_search_page_only(app(tmp_path), "chapters/x", "page.html", page, None)  # type: ignore[arg-type]
    assert [j.filename for j in page["script_files"]] == ["_static/a.js", "_static/b.js"]
    search: dict[str, Any] = {"script_files": list(scripts)}
    fx.plain_math_search_on_search_page_only(app(tmp_path), "search", "search.html", search, None)  # type: ignore[arg-type]
    assert search["script_files"] == scripts


def test_unloaded_theme_files_are_removed_and_loaded_ones_kept(tmp_path):
    static = tmp_path / "html" / "_static"
    files = ["scripts/bootstrap.js", "scripts/bootstrap.js.map", "styles/theme.css.map", "scripts/fontawesome.js",
             "scripts/fontawesome.js.map",
             "vendor/fontawesome/webfonts/fa-solid-900.woff2", "vendor/fontawesome/webfonts/fa-solid-900.ttf",
             "locales/de/LC_MESSAGES/booktheme.mo", "mathjax/es5/startup.js"]
    for name in files:
        (static / name).parent.mkdir(parents=True, exist_ok=True)
        (static / name).write_text("x")
    fx.remove_unloaded_theme_files(app(tmp_path), None)
    left = sorted(p.relative_to(static).as_posix() for p in static.rglob("*") if p.is_file())
    assert left == ["mathjax/es5/startup.js", "scripts/bootstrap.js",
                    "vendor/fontawesome/webfonts/fa-solid-900.woff2"]
    with pytest.raises(fx.ProblemGone, match="remove_unloaded_theme_files"):
        fx.remove_unloaded_theme_files(app(tmp_path), None)  # a second time: nothing left to remove
    decks = app(tmp_path)
    decks.builder.name = "revealjs"   # the decks' build (_ext/decks.py) is not the book's: left alone
    fx.remove_unloaded_theme_files(decks, None)
    fx.check_tally(decks, None)


def _doctree(rst: str) -> nodes.document:
    settings = get_default_settings(Parser)
    settings.report_level = 5
    doc = new_document("test", settings)
    Parser().parse(rst, doc)
    return doc


def test_alt_text_from_caption_section_or_kept(tmp_path):
    doc = _doctree("Arms\n====\n\n.. figure:: plot.png\n\n   The arm at rest\n\n.. image:: ../_images/3f2a.png\n"
                   "   :alt: ../_images/3f2a.png\n\n.. image:: b.png\n   :alt: A drawing\n")
    raw = nodes.raw("", '<div class="anim-buttons"></div><img id="_anim_img1" src="data:,">', format="html")
    doc.children[0].append(raw)
    changed = alt_text.describe_image(doc, tmp_path / "missing.md", nodes.title(text="Page"))
    alts = [img["alt"] for img in doc.findall(nodes.image)]
    assert alts == ["The arm at rest", "Figure in the section “Arms”", "A drawing"]
    html = next(iter(doc.findall(nodes.raw))).astext()
    assert 'alt="Animation in the section “Arms”"' in html
    assert changed == 3


def test_fill_alt_text_counts_pages_it_changed(tmp_path):
    doc = _doctree("Arms\n====\n\n.. image:: x.png\n")
    a = app(tmp_path)
    a.env = SimpleNamespace(found_docs={"p"}, titles={}, doc2path=lambda name: str(tmp_path / f"{name}.md"))
    fx.fill_alt_text(a, doc, "p")  # type: ignore[arg-type]
    assert next(iter(doc.findall(nodes.image)))["alt"] == "Figure in the section “Arms”"
    assert fx._TALLY["fill_alt_text"] == 1


def test_alt_text_uses_titles_set_by_the_cell_code(tmp_path):
    src = tmp_path / "nb.md"
    src.write_text("---\njupytext:\n  text_representation:\n    extension: .md\n    format_name: myst\n"
                   "kernelspec:\n  name: python3\n  display_name: Python 3\n---\n# T\n\n"
                   "```{code-cell} ipython3\nax.set_title(r\"Columns of $J_s$\")\n```\n")
    doc = _doctree("T\n=\n")
    cell = nodes.container(nb_element="cell_code", cell_index=1)
    cell += nodes.image(uri="../_images/a.png", alt="../_images/a.png")
    doc.children[0].append(cell)
    alt_text.describe_image(doc, src, None)
    assert next(iter(doc.findall(nodes.image)))["alt"] == "Figure: Columns of J_s"


def test_the_extension_registers_every_handler():
    events: list[tuple[str, str]] = []
    fake = SimpleNamespace(connect=lambda event, fn, priority=500: events.append((event, fn.__name__)))
    meta = fx.setup(fake)  # type: ignore[arg-type]
    handlers = {name for _, name in events}
    assert {"drop_duplicate_scripts", "drop_thebe_assets", "drop_unused_widget_assets", "default_theme_mode",
            "default_favicon", "drop_fontawesome_js", "remove_unloaded_theme_files", "fill_alt_text",
            "check_tally", "search_scripts_on_search_page_only", "plain_math_search_on_search_page_only"} <= handlers
    assert set(fx._PER_PAGE) <= handlers
    assert meta["parallel_read_safe"] is True
