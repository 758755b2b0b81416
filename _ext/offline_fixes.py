"""Fixes for the known browser-console errors of the book's stack.

A local Sphinx extension (``_config.yml``: ``sphinx: local_extensions:
{offline_fixes: _ext}``). Each fix below names the error it removes; the
browser tests in ``tests/browser`` check that a built page shows none of them.

1. ``Identifier 'THEBE_JS_URL' has already been declared`` (a page error on
   every page). Sphinx 7.4 registers an inline script added by an extension
   once with filename ``None`` and once with filename ``''``, so the
   ``<script>`` of sphinx-thebe (and of sphinx-togglebutton) appears twice.
   We drop duplicate scripts, and drop sphinx-thebe's scripts altogether when
   the thebe launch button is off (it is: thebe needs a remote kernel, which
   an offline book cannot have; its script names a CDN URL).
2. ``Got invalid theme mode: . Resetting to auto.`` (console error on a first
   visit): pydata-sphinx-theme writes ``localStorage.mode || default_mode`` and
   ``default_mode`` is empty unless set in ``html_context``. We default it to
   ``"auto"`` (follow the reader's system setting), which is what the theme
   falls back to anyway.
3. ``GET /favicon.ico 404``: browsers ask for a favicon when the page names
   none. We give the book one (``_ext/favicon.svg``) unless the config sets
   ``html_favicon``.
4. ``Cannot read properties of undefined (reading 'Queue')``: the widget HTML
   manager typesets widget labels with the MathJax 2 API
   (``MathJax.Hub.Queue``) but the book runs MathJax 3. On pages with widgets
   we add a shim ``MathJax.Hub.Queue`` that calls MathJax 3's
   ``typesetPromise``.
5. 404s for the widget manager's fonts (``chapters/@jupyter-widgets/
   html-manager/dist/<hash>.woff2``): the manager computes its public path
   from its AMD module id, which require.js resolves against the page's
   folder. A ``require.config`` ``paths`` entry maps that id to the vendored
   copy in ``_static/html-manager``, where the fonts are.
6. Images without alt text: myst-nb renders a matplotlib output as ``<img>``
   whose alt is the file path (``../_images/3f2a...png``), and matplotlib's
   JS animation has an ``<img>`` with no alt at all. We fill in the alt text
   from, in this order: an explicit ``mystnb: image: alt:`` (kept as is), the
   figure caption, the titles the cell's code sets on the figure
   (``set_title``/``suptitle``/``plt.title``), else the section the output
   sits in. Authors who want better alt text set ``mystnb: image: alt:``.
7. Page weight: a page whose notebook saved widget state but shows no
   widget does not load require.js and the 4.3 MB widget manager.
8. Page weight: the theme's ``fontawesome.js`` (1.4 MB, only needed for
   custom icons, which the book has none of) is not loaded; see
   :func:`_drop_fontawesome_js`.
"""

from __future__ import annotations

import ast
import html
import json
import re
from pathlib import Path
from typing import Any

from docutils import nodes

HERE = Path(__file__).resolve().parent

# ---------------------------------------------------------------- scripts
_MATHJAX2_SHIM = r"""
(function () {
  /* offline_fixes: the widget manager calls MathJax.Hub.Queue (MathJax 2);
     the book runs MathJax 3. Forward to typesetPromise once MathJax is up. */
  function queue(cmd) {
    var el = Array.isArray(cmd) ? cmd[2] : undefined;
    dollarsToParens(el);
    var tries = 0;
    (function go() {
      var MJ = window.MathJax;
      if (MJ && MJ.typesetPromise && MJ.startup && MJ.startup.promise) {
        MJ.startup.promise.then(function () {
          return MJ.typesetPromise(el ? [el] : undefined);
        }).catch(function (e) { console.warn("MathJax typeset failed", e); });
      } else if (tries++ < 100) {
        setTimeout(go, 100);
      }
    })();
  }
  function dollarsToParens(el) {
    /* widget descriptions use $...$; the book's MathJax 3 knows only \(...\) */
    if (!el || !document.createTreeWalker) { return; }
    var walker = document.createTreeWalker(el, NodeFilter.SHOW_TEXT), node, nodes = [];
    while ((node = walker.nextNode())) { nodes.push(node); }
    nodes.forEach(function (t) {
      if (t.nodeValue.indexOf("$") >= 0) {
        t.nodeValue = t.nodeValue.replace(/\$([^$]+)\$/g, "\\($1\\)");
      }
    });
  }
  function install() {
    var MJ = window.MathJax;
    if (MJ && !MJ.Hub) { MJ.Hub = {Queue: queue}; }
  }
  install();
  document.addEventListener("DOMContentLoaded", install);
  window.addEventListener("load", install);
})();
"""


def _require_paths_config(html_manager_url: str) -> str:
    # The bundle defines these AMD modules by name; each computes webpack's
    # public path (where its fonts and chunks are) from its own module URI.
    base = html_manager_url.rstrip("/")
    paths = {
        "@jupyter-widgets/html-manager/dist": base,
        "@jupyter-widgets/html-manager": base + "/html-manager",
        "@jupyter-widgets/base": base + "/base",
        "@jupyter-widgets/controls": base + "/controls",
        "@jupyter-widgets/output": base + "/output",
    }
    return (
        "/* offline_fixes: serve the widget manager (and its fonts) from _static */\n"
        f"require.config({{paths: {json.dumps(paths)}}});"
    )


def _script_key(js: Any) -> tuple:
    filename = getattr(js, "filename", js) or ""
    attrs = getattr(js, "attributes", {}) or {}
    return (str(filename), tuple(sorted((k, str(v)) for k, v in attrs.items())))


def _is_thebe(js: Any) -> bool:
    filename = str(getattr(js, "filename", js) or "")
    body = str((getattr(js, "attributes", {}) or {}).get("body", ""))
    return filename.endswith("sphinx-thebe.js") or "THEBE_JS_URL" in body


def _is_widget_asset(js: Any) -> bool:
    filename = str(getattr(js, "filename", js) or "")
    attrs = getattr(js, "attributes", {}) or {}
    return (
        filename.endswith(("require.js", "embed-amd.js"))
        or attrs.get("type") == "application/vnd.jupyter.widget-state+json"
    )


def _thebe_enabled(app) -> bool:
    opts = app.config.html_theme_options or {}
    launch = opts.get("launch_buttons") or {}
    return bool(launch.get("thebe")) or bool(getattr(app.config, "use_thebe", False))


def _fix_page_assets(app, pagename, templatename, context, doctree) -> None:
    scripts = context.get("script_files")
    if isinstance(scripts, list):
        thebe = _thebe_enabled(app)
        seen: set[tuple] = set()
        kept = []
        for js in scripts:
            key = _script_key(js)
            if key in seen or (not thebe and _is_thebe(js)):
                continue
            seen.add(key)
            kept.append(js)
        # widgets: a notebook can carry widget state with no widget shown on the
        # page (a removed cell made one); the 4.3 MB manager then renders nothing.
        body = str(context.get("body", ""))
        if "application/vnd.jupyter.widget-view+json" not in body:
            kept = [js for js in kept if not _is_widget_asset(js)]
        # widgets: shim MathJax 2's API and point require.js at the vendored manager
        names = [str(getattr(js, "filename", "") or "") for js in kept]
        req = next((i for i, n in enumerate(names) if n.endswith("require.js")), None)
        if req is not None and any("html-manager" in n for n in names):
            from sphinx.builders.html._assets import _JavaScript

            prio = kept[req].priority
            url = context["pathto"]("_static/html-manager", 1)
            extra = [
                _JavaScript("", priority=prio, body=_require_paths_config(url)),
                _JavaScript("", priority=prio, body=_MATHJAX2_SHIM),
            ]
            kept[req + 1:req + 1] = extra
        context["script_files"] = kept
    css = context.get("css_files")
    if isinstance(css, list) and not _thebe_enabled(app):
        context["css_files"] = [
            c for c in css if not str(getattr(c, "filename", c) or "").endswith("sphinx-thebe.css")
        ]


# ---------------------------------------------------------------- config
def _drop_fontawesome_js(app, config) -> None:
    """Override pydata-sphinx-theme's ``static/webpack-macros.html`` without its fontawesome.js.

    The theme loads ``_static/scripts/fontawesome.js`` (1.4 MB, every Font
    Awesome icon as JavaScript) on every page "so that users can add custom
    icons". The book adds none; the theme's own icons come from its CSS and
    the woff2 webfont, so the script only adds weight. The override is made
    from the installed theme's file at build time (one line removed), so it
    follows the pinned theme version.
    """
    try:
        import pydata_sphinx_theme
    except ImportError:
        return
    src = Path(pydata_sphinx_theme.__file__).parent / "theme" / "pydata_sphinx_theme" / "static" / "webpack-macros.html"
    if not src.exists():
        return
    text = src.read_text(encoding="utf-8")
    fixed = re.sub(r"[ \t]*<script[^>]*scripts/fontawesome\.js[^>]*></script>\n?", "", text)
    if fixed == text:
        return
    dest = Path(app.doctreedir) / "offline_fixes_templates"
    (dest / "static").mkdir(parents=True, exist_ok=True)
    (dest / "static" / "webpack-macros.html").write_text(fixed, encoding="utf-8")
    config.templates_path = [str(dest)] + list(config.templates_path or [])


def _config_inited(app, config) -> None:
    _drop_fontawesome_js(app, config)
    if not config.html_favicon:
        config.html_favicon = str(HERE / "favicon.svg")
    if config.html_context is None:
        config.html_context = {}
    config.html_context.setdefault("default_mode", "auto")


# ---------------------------------------------------------------- alt text


def titles_from_code(source: str) -> list[str]:
    """String-literal titles a cell sets on its figure, in order.

    Looks for ``ax.set_title("...")``, ``fig.suptitle("...")`` and
    ``plt.title("...")`` with a literal first argument (f-strings keep their
    literal parts). The code is parsed, never run.
    """
    found: list[str] = []
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return found
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or not node.args:
            continue
        func = node.func
        name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
        if name not in ("set_title", "suptitle", "title"):
            continue
        arg = node.args[0]
        text = None
        if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
            text = arg.value
        elif isinstance(arg, ast.JoinedStr):
            text = "".join(
                v.value for v in arg.values if isinstance(v, ast.Constant) and isinstance(v.value, str)
            )
        if text:
            text = re.sub(r"\$([^$]*)\$", r"\1", text)  # drop mathtext dollars
            text = re.sub(r"\\(mathrm|mathcal|mathbf|operatorname)\{([^}]*)\}", r"\2", text)
            text = " ".join(text.replace("\\", "").split())
            if text and text not in found:
                found.append(text)
    return found


def _cell_sources(app, docname: str) -> dict[int, str]:
    """Code of each cell of a notebook page, by cell index (empty if not a notebook)."""
    cache = getattr(app.env, "_offline_fixes_sources", None)
    if cache is None:
        cache = app.env._offline_fixes_sources = {}
    if docname in cache:
        return cache[docname]
    sources: dict[int, str] = {}
    try:
        path = Path(app.env.doc2path(docname))
        text = path.read_text(encoding="utf-8")
        if path.suffix == ".ipynb":
            import nbformat

            nb = nbformat.reads(text, as_version=4)
        else:
            from myst_nb.core.read import read_myst_markdown_notebook

            nb = read_myst_markdown_notebook(text)
        sources = {i: c.get("source", "") for i, c in enumerate(nb.cells) if c.get("cell_type") == "code"}
    except Exception:  # not a notebook, or unreadable: fall back to section titles
        sources = {}
    cache[docname] = sources
    return sources


def _section_title(node: nodes.Node) -> str | None:
    parent = node.parent
    while parent is not None:
        if isinstance(parent, nodes.section):
            for child in parent.children:
                if isinstance(child, nodes.title):
                    return child.astext()
        parent = parent.parent
    return None


def _cell_index(node: nodes.Node) -> int | None:
    parent = node.parent
    while parent is not None:
        if isinstance(parent, nodes.container) and parent.get("nb_element") == "cell_code":
            idx = parent.get("cell_index")
            return int(idx) if idx is not None else None
        parent = parent.parent
    return None


def plain(text: str) -> str:
    """Alt text is read aloud: TeX commands as words, no braces or backslashes.

    >>> plain(r"arm at $\\theta = (0.5, 0.6)$, T_{sb}")
    'arm at theta = (0.5, 0.6), T_sb'
    """
    text = text.replace("$", "")
    text = re.sub(r"\\(mathrm|mathcal|mathbf|operatorname|text)\{([^}]*)\}", r"\2", text)
    text = re.sub(r"\\([a-zA-Z]+)", r"\1", text)
    text = text.replace("{", "").replace("}", "").replace("\\", "")
    return " ".join(text.split())


def _describe(app, docname: str, node: nodes.Node, kind: str) -> str:
    return plain(_describe_raw(app, docname, node, kind))


def _describe_raw(app, docname: str, node: nodes.Node, kind: str) -> str:
    # a figure caption says it best
    parent = node.parent
    while parent is not None:
        if isinstance(parent, nodes.figure):
            for child in parent.children:
                if isinstance(child, nodes.caption) and child.astext().strip():
                    return child.astext().strip()
            break
        parent = parent.parent
    idx = _cell_index(node)
    if idx is not None:
        titles = titles_from_code(_cell_sources(app, docname).get(idx, ""))
        if titles:
            return f"{kind}: " + "; ".join(titles)
    section = _section_title(node) or app.env.titles.get(docname, nodes.title()).astext()
    return f"{kind} in the section “{section}”" if section else kind


_IMG_TAG = re.compile(r"<img\b[^>]*>", re.IGNORECASE)
_HAS_ALT = re.compile(r"\balt\s*=", re.IGNORECASE)


def add_alt_to_html(fragment: str, alt: str) -> str:
    """Give every ``<img>`` of an HTML fragment without an ``alt`` attribute one."""

    def fix(match: re.Match) -> str:
        tag = match.group(0)
        if _HAS_ALT.search(tag):
            return tag
        return tag[:4] + f' alt="{html.escape(alt, quote=True)}"' + tag[4:]

    return _IMG_TAG.sub(fix, fragment)


def _fix_alt_text(app, doctree, docname) -> None:
    for img in list(doctree.findall(nodes.image)):
        alt = (img.get("alt") or "").strip()
        uri = img.get("uri", "")
        if alt and alt != uri and Path(alt).name != Path(uri).name:
            continue
        img["alt"] = _describe(app, docname, img, "Figure")
    for raw in list(doctree.findall(nodes.raw)):
        if "html" not in raw.get("format", "").split():
            continue
        text = raw.astext()
        if "<img" not in text.lower():
            continue
        kind = "Animation" if "_anim_img" in text or "anim-buttons" in text else "Figure"
        fixed = add_alt_to_html(text, _describe(app, docname, raw, kind))
        if fixed != text:
            new = nodes.raw(fixed, fixed, **{k: v for k, v in raw.attributes.items() if k != "ids"})
            new["ids"] = list(raw.get("ids", []))
            raw.replace_self(new)


def setup(app) -> dict[str, Any]:
    app.connect("config-inited", _config_inited)
    app.connect("html-page-context", _fix_page_assets, priority=900)
    app.connect("doctree-resolved", _fix_alt_text)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
