"""Fixes for known problems of the book's stack, one small handler per problem.

A local Sphinx extension (``_config.yml``: ``sphinx: local_extensions:
{offline_fixes: _ext}``). Each handler's docstring names the problem and the
package version it was seen in; the browser tests in ``tests/browser`` check
that a built page shows none of the problems, tests/test_offline_fixes.py
tests each handler.

Each handler also fails the build loudly (:class:`ProblemGone`, a Sphinx
``ExtensionError``) when the problem it fixes has gone away upstream, so that a
fix never outlives its problem:

* fixes of the configuration check the upstream file they work around;
* fixes applied page by page count the pages they changed; a full build (every
  page written) in which one of them changed nothing fails at the end
  (incremental builds, which write a few pages, skip this check).

Handlers (see each one's docstring): :func:`drop_duplicate_scripts`,
:func:`drop_thebe_assets`, :func:`drop_unused_widget_assets`,
:func:`default_theme_mode`, :func:`default_favicon`,
:func:`drop_fontawesome_js`, :func:`remove_unloaded_theme_files`,
:func:`fill_alt_text`.
"""

from __future__ import annotations

import re
import shutil
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

# (titles_from_code, plain and add_alt_to_html are re-exported for tests/browser)
from alt_text import add_alt_to_html, describe_image, plain, titles_from_code
from docutils import nodes
from sphinx.application import Sphinx
from sphinx.config import Config
from sphinx.errors import ExtensionError

__all__ = ["ProblemGone", "add_alt_to_html", "plain", "setup", "titles_from_code"]

HERE = Path(__file__).resolve().parent
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"


class ProblemGone(ExtensionError):
    """A fix of this extension found nothing to fix: the upstream problem is gone."""

    def __init__(self, handler: str, what: str) -> None:
        super().__init__(f"offline_fixes.{handler}: {what}. The upstream problem it fixes seems gone: "
                         f"check, then delete the handler (and its test) from _ext/offline_fixes.py.")


# ---------------------------------------------------------------- page tallies

#: pages written in this build, and pages each per-page handler changed
_TALLY: Counter[str] = Counter()
_PER_PAGE = ("drop_duplicate_scripts", "drop_thebe_assets", "drop_unused_widget_assets", "fill_alt_text")


def _reset_tally(app: Sphinx) -> None:
    _TALLY.clear()


def _count_page(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any) -> None:
    if pagename in app.env.found_docs:  # not genindex, search, ... (written by every build)
        _TALLY["pages"] += 1


def check_tally(app: Sphinx, exception: Exception | None) -> None:
    """After a full build, fail for each per-page handler that changed no page."""
    full = app.parallel <= 1 and _TALLY["pages"] >= len(app.env.found_docs) > 0
    if exception is not None or not full or app.builder.name != "html":  # the book, not the decks
        return
    for handler in _PER_PAGE:
        if _TALLY[handler] == 0:
            raise ProblemGone(handler, f"changed none of the {_TALLY['pages']} pages of a full build")


# ---------------------------------------------------------------- scripts and styles


def _filename(asset: Any) -> str:
    return str(getattr(asset, "filename", asset) or "")


def _attributes(asset: Any) -> dict[str, Any]:
    return dict(getattr(asset, "attributes", {}) or {})


def drop_duplicate_scripts(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any],
                           doctree: Any) -> None:
    """Each inline script of an extension appears twice on every page (Sphinx 7.4.7).

    Sphinx registers an inline script added with ``app.add_js_file(None,
    body=...)`` once with filename ``None`` and once with ``''``, so the
    page runs it twice: ``Identifier 'THEBE_JS_URL' has already been declared``
    (sphinx-thebe 0.3.1, sphinx-togglebutton 0.4.5). The second copy is dropped.
    """
    scripts = context.get("script_files")
    if not isinstance(scripts, list):
        return
    seen: set[tuple[str, tuple[tuple[str, str], ...]]] = set()
    kept = []
    for js in scripts:
        key = (_filename(js), tuple(sorted((k, str(v)) for k, v in _attributes(js).items())))
        if key not in seen:
            seen.add(key)
            kept.append(js)
    if len(kept) < len(scripts):
        _TALLY["drop_duplicate_scripts"] += 1
        context["script_files"] = kept


def _thebe_enabled(config: Config) -> bool:
    launch = (config.html_theme_options or {}).get("launch_buttons") or {}
    return bool(launch.get("thebe")) or bool(getattr(config, "use_thebe", False))


def drop_thebe_assets(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any],
                      doctree: Any) -> None:
    """sphinx-thebe 0.3.1 loads its script and style sheet on every page, even with thebe off.

    Thebe needs a remote kernel, which an offline book cannot have (its
    launch button is off in _config.yml), and its script names a CDN URL. With
    thebe off, the page loads neither.
    """
    if _thebe_enabled(app.config):
        return
    scripts, css = context.get("script_files"), context.get("css_files")
    changed = False
    if isinstance(scripts, list):
        kept = [js for js in scripts if not (_filename(js).endswith("sphinx-thebe.js")
                                            or "THEBE_JS_URL" in str(_attributes(js).get("body", "")))]
        changed |= len(kept) < len(scripts)
        context["script_files"] = kept
    if isinstance(css, list):
        kept_css = [c for c in css if not _filename(c).endswith("sphinx-thebe.css")]
        changed |= len(kept_css) < len(css)
        context["css_files"] = kept_css
    if changed:
        _TALLY["drop_thebe_assets"] += 1


def _is_widget_asset(js: Any) -> bool:
    return (_filename(js).endswith(("require.js", "embed-amd.js"))
            or _attributes(js).get("type") == WIDGET_STATE)


def drop_unused_widget_assets(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any],
                              doctree: Any) -> None:
    """myst-nb 1.4.0 loads the widget manager on a page whose notebook saved widget state.

    It adds require.js, the 4.3 MB widget manager (``nb_ipywidgets_js``) and the
    saved state whenever the notebook's metadata holds widget state, even when
    no widget is shown (a hidden cell made one). The book shows no live widget
    (the chapters show animations) and vendors no widget manager
    (tools/vendor.py), so these are dropped; a page that does show a widget
    stops the build, since it could not work offline.
    """
    scripts = context.get("script_files")
    if not isinstance(scripts, list):
        return
    if WIDGET_VIEW in str(context.get("body", "")):
        raise ExtensionError(
            f"offline_fixes: page {pagename!r} shows a live Jupyter widget, which the book cannot run: it "
            "vendors no widget manager (tools/vendor.py). Show an animation instead, or tag the cell remove-cell.")
    kept = [js for js in scripts if not _is_widget_asset(js)]
    if len(kept) < len(scripts):
        _TALLY["drop_unused_widget_assets"] += 1
        context["script_files"] = kept


# ---------------------------------------------------------------- configuration


def _theme_file(*parts: str) -> Path:
    import pydata_sphinx_theme

    return Path(pydata_sphinx_theme.__file__).parent.joinpath("theme", "pydata_sphinx_theme", *parts)


def default_theme_mode(app: Sphinx, config: Config) -> None:
    """``Got invalid theme mode: . Resetting to auto.`` on a first visit (pydata-sphinx-theme 0.17.1).

    The theme's layout sets ``localStorage.getItem("mode") || "{{ default_mode }}"``
    and ``default_mode`` is empty unless ``html_context`` sets it. It is set to
    ``"auto"`` (follow the reader's system setting), what the theme falls back to.
    """
    layout = _theme_file("layout.html").read_text(encoding="utf-8")
    if '|| "{{ default_mode }}"' not in layout:
        raise ProblemGone("default_theme_mode", "the theme's layout.html no longer reads default_mode")
    context: dict[str, object] = dict(config.html_context or {})
    context.setdefault("default_mode", "auto")
    config.html_context = context


def default_favicon(app: Sphinx, config: Config) -> None:
    """``GET /favicon.ico 404``: jupyter-book 1.0.4 names no favicon, so browsers ask for one.

    The book gets ``_ext/favicon.svg``.
    """
    if config.html_favicon:
        raise ProblemGone("default_favicon", f"html_favicon is already set ({config.html_favicon!r})")
    config.html_favicon = str(HERE / "favicon.svg")


_FONTAWESOME_TAG = re.compile(r"[ \t]*<script[^>]*scripts/fontawesome\.js[^>]*></script>\n?")


def drop_fontawesome_js(app: Sphinx, config: Config) -> None:
    """pydata-sphinx-theme 0.17.1 loads ``fontawesome.js`` (1.4 MB) on every page.

    The script holds every Font Awesome icon as JavaScript "so that users can
    add custom icons"; the book adds none, and the theme's own icons come from
    its CSS and webfont. The theme's ``static/webpack-macros.html`` is
    overridden by a copy without that line, made from the installed theme at
    build time (so it follows the pinned version).
    """
    src = _theme_file("static", "webpack-macros.html")
    text = src.read_text(encoding="utf-8") if src.is_file() else ""
    fixed = _FONTAWESOME_TAG.sub("", text)
    if fixed == text:
        raise ProblemGone("drop_fontawesome_js", f"{src} does not load scripts/fontawesome.js")
    dest = Path(app.doctreedir) / "offline_fixes_templates"
    (dest / "static").mkdir(parents=True, exist_ok=True)
    (dest / "static" / "webpack-macros.html").write_text(fixed, encoding="utf-8")
    config.templates_path = [str(dest), *(config.templates_path or [])]


_SEARCH_TAGS = re.compile(r"[ \t]*<script src=\"\{\{ pathto\('(?:_static/searchtools\.js|_static/language_data\.js|"
                          r"searchindex\.js)', 1\) \| e \}\}\"></script>\n?")


def search_scripts_on_search_page_only(app: Sphinx, config: Config) -> None:
    """pydata-sphinx-theme 0.17.1 loads the search index (80 KB) and Sphinx's search tools on every page.

    Its layout loads them everywhere for its search-as-you-type box, which the
    book leaves off (``search_as_you_type`` is false): the search field sends
    the reader to ``search.html``, which loads them itself. The theme's
    ``layout.html`` is overridden by a copy without those three tags, made from
    the installed theme at build time. (If the book ever turns on search as you
    type, this stops the build instead of breaking the box.)
    """
    options = (config.html_theme_options or {})
    if str(options.get("search_as_you_type", False)).lower() == "true":
        raise ProblemGone("search_scripts_on_search_page_only", "search_as_you_type is on: every page needs the index")
    src = _theme_file("layout.html")
    text = src.read_text(encoding="utf-8") if src.is_file() else ""
    fixed, n = _SEARCH_TAGS.subn("", text)
    if n != 3:
        raise ProblemGone("search_scripts_on_search_page_only",
                          f"{src} no longer loads searchtools.js, language_data.js and searchindex.js on every page")
    dest = Path(app.doctreedir) / "offline_fixes_templates" / "pydata_sphinx_theme"
    dest.mkdir(parents=True, exist_ok=True)
    (dest / "layout.html").write_text(fixed, encoding="utf-8")
    root = str(dest.parent)
    if root not in (config.templates_path or []):
        config.templates_path = [root, *(config.templates_path or [])]


def plain_math_search_on_search_page_only(app: Sphinx, pagename: str, templatename: str,
                                          context: dict[str, Any], doctree: Any) -> None:
    """``_theme/search_plain_math.js`` acts on the search page only; other pages do not load it."""
    if pagename == "search":
        return
    scripts = context.get("script_files") or []
    context["script_files"] = [js for js in scripts if not _filename(js).endswith("search_plain_math.js")]


#: files of the themes' static folders that no page loads (paths under _static; globs)
UNLOADED_THEME_FILES: Sequence[str] = (
    "scripts/*.map", "styles/*.map",             # source maps, for the theme's developers
    "scripts/fontawesome.js*",                   # no longer loaded (drop_fontawesome_js)
    "vendor/fontawesome/webfonts/*.ttf",         # every browser that runs the theme reads the woff2
    "locales",                                   # the theme's translations, read at build time
)


def remove_unloaded_theme_files(app: Sphinx, exception: Exception | None) -> None:
    """pydata-sphinx-theme 0.17.1 and sphinx-book-theme 1.3.0 copy 5 MB into ``_static`` that no page loads.

    Source maps (3.4 MB), ``fontawesome.js`` (1.5 MB, see
    :func:`drop_fontawesome_js`), TrueType copies of the woff2 webfonts and the
    translation catalogues are removed from the built ``_static`` (they are
    copied again, and removed again, by every build). The browser tests see
    every request a page makes; none goes to these files.
    """
    if exception is not None or app.builder.name != "html":  # (not the decks' revealjs build)
        return
    static = Path(app.outdir) / "_static"
    found = list(dict.fromkeys(p for pattern in UNLOADED_THEME_FILES for p in static.glob(pattern)))
    if not found:
        raise ProblemGone("remove_unloaded_theme_files", f"none of {list(UNLOADED_THEME_FILES)} is in {static}")
    for path in found:
        if not path.exists():  # inside a folder removed just before
            continue
        if path.is_dir():
            shutil.rmtree(path)
        else:
            path.unlink()


_ICON_RULE = re.compile(r'((?:\.fa-[a-z0-9-]+:before,?)+)\{content:"\\([0-9a-f]+)"\}')
_ICON_NAME = re.compile(r"fa-[a-z0-9-]+")
_TRIMMED = "/* offline_fixes.trim_font_awesome: icon rules of unused icons removed */"
THEME_CSS = "styles/pydata-sphinx-theme.css"
SOLID_FONT = "vendor/fontawesome/webfonts/fa-solid-900.woff2"


def trim_font_awesome(app: Sphinx, exception: Exception | None) -> None:
    """pydata-sphinx-theme 0.17.1 ships all 1834 Font Awesome icon rules (85 KB of its CSS) and the
    whole solid webfont (153 KB), which every page downloads; the book shows about a dozen icons.

    The icons are found by name (``fa-bars``, ...) in every built page and in
    every script of ``_static`` (a script may add an icon); the theme's CSS keeps
    the rules of those icons only, and ``fa-solid-900.woff2`` keeps their glyphs
    only (fontTools, written as woff2). The browser tests check that each icon
    on a page still draws its glyph.
    """
    if exception is not None or app.builder.name != "html":  # (not the decks' revealjs build)
        return
    out = Path(app.outdir)
    css_path, font_path = out / "_static" / THEME_CSS, out / "_static" / SOLID_FONT
    if not css_path.is_file() or not font_path.is_file():
        raise ProblemGone("trim_font_awesome", f"{css_path} or {font_path} is not in the build")
    css = css_path.read_text(encoding="utf-8")
    if _TRIMMED in css:  # Sphinx kept the copy trimmed by an earlier build
        return
    used: set[str] = set()
    for path in [*out.rglob("*.html"), *(out / "_static").rglob("*.js")]:
        used.update(_ICON_NAME.findall(path.read_text(encoding="utf-8", errors="replace")))
    codepoints: set[int] = set()

    def keep(m: re.Match[str]) -> str:
        names = {sel[1:-len(":before")] for sel in m.group(1).rstrip(",").split(",")}
        if names & used:
            codepoints.add(int(m.group(2), 16))
            return m.group(0)
        return ""

    trimmed, n = _ICON_RULE.subn(keep, css)
    if n < 100 or not codepoints:
        raise ProblemGone("trim_font_awesome", f"{css_path.name} holds {n} icon rules, {len(codepoints)} of them used")
    css_path.write_text(trimmed + "\n" + _TRIMMED + "\n", encoding="utf-8")

    from fontTools import subset  # type: ignore[import-untyped]  # (matplotlib needs it; woff2 needs brotli)

    options = subset.Options()
    options.flavor = "woff2"
    options.layout_features = ["*"]
    font = subset.load_font(str(font_path), options)
    subsetter = subset.Subsetter(options)
    subsetter.populate(unicodes=sorted(codepoints))
    subsetter.subset(font)
    subset.save_font(font, str(font_path), options)


# ---------------------------------------------------------------- alt text


def fill_alt_text(app: Sphinx, doctree: nodes.document, docname: str) -> None:
    """Images without real alt text (myst-nb 1.4.0, matplotlib 3.10's HTML animation).

    myst-nb renders a matplotlib output as ``<img>`` whose alt is the file path
    (``../_images/3f2a...png``), and matplotlib's JS animation has an ``<img>``
    with no alt at all. They get a description (:mod:`alt_text`): an explicit
    ``mystnb: image: alt:`` is kept as is; else the figure caption, the titles
    the cell's code sets, or the section the output sits in.
    """
    if describe_image(doctree, Path(app.env.doc2path(docname)), app.env.titles.get(docname)):
        _TALLY["fill_alt_text"] += 1


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("config-inited", default_theme_mode)
    app.connect("config-inited", default_favicon)
    app.connect("config-inited", drop_fontawesome_js)
    app.connect("config-inited", search_scripts_on_search_page_only)
    app.connect("builder-inited", _reset_tally)
    app.connect("html-page-context", _count_page, priority=900)
    app.connect("html-page-context", drop_duplicate_scripts, priority=900)
    app.connect("html-page-context", drop_thebe_assets, priority=901)
    app.connect("html-page-context", drop_unused_widget_assets, priority=902)
    app.connect("html-page-context", plain_math_search_on_search_page_only, priority=903)
    app.connect("doctree-resolved", fill_alt_text)
    app.connect("build-finished", remove_unloaded_theme_files)
    app.connect("build-finished", trim_font_awesome)
    app.connect("build-finished", check_tally, priority=900)
    return {"version": "2.0", "parallel_read_safe": True, "parallel_write_safe": True}
