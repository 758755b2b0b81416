"""Sphinx extension: the book's math typeset at build time, so that no page waits for MathJax.

On a slow phone, MathJax in the page (0.8 MB of script, then the typesetting on
a slow CPU) showed the formulas 15-25 s after the text. Here the pages written
by an HTML build go through ``tools/prerender_math.cjs`` (MathJax 3.2.2 in
Node, npm ``mathjax-full``) at the end of the build: each formula becomes
MathJax's SVG output, with the hidden MathML screen readers read, and the page
no longer loads MathJax. SVG rather than CommonHTML: the glyphs are paths, so a
page downloads no font (the CommonHTML output needed up to a dozen, and the
first screen waited for them). Each formula is flattened to one ``<path>`` (or
one per colour; ``tools/flatten_math_svg.cjs``), where MathJax writes a ``<g>``
per MathML node and a ``<use>`` per glyph: the slow phone's first screen
waited on the browser's work on those elements. The paths are filled with the
text's colour (dark mode). Sizes are in em, as the CommonHTML output's were.

Each formula keeps its TeX in ``data-tex``: ``_theme/math_menu.js`` loads
MathJax with its menu and explorer (speech, zoom, copy as TeX) only when a
reader asks for them (focus on a formula, or a right-click), and typesets that
formula again from its TeX.

Fragments: another extension may leave, in ``app.course_math_fragments``, HTML typeset with a page but shown
later by its scripts (``{pagename: [{"src": <JSON list of HTML strings>, "out": <folder>, "key": <name>}]}``;
the exercise pages' statements, ``_ext/exercise_checks``). Each string k is typeset with the page's own MathJax
document and written to ``<out>/<k>.js`` as
``window.__courseStatements["<key>/<k>"] = "<html>"``.

Only the book (the ``html`` builder): the decks (``revealjs``) keep MathJax in
the page. A TeX error stops the build with the page and the formula.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx.errors import ExtensionError
from sphinx.util import logging

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "prerender_math.cjs"
logger = logging.getLogger(__name__)
_WRITTEN: set[str] = set()


def note_page(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any) -> None:
    if app.builder.name == "html":
        _WRITTEN.add(pagename)


def macros(config: Any) -> dict[str, Any]:
    """The TeX macros of the book's MathJax configuration (``mathjax3_config.tex.macros``)."""
    return dict(((config.mathjax3_config or {}).get("tex") or {}).get("macros") or {})


def prerender(app: Sphinx, exception: Exception | None) -> None:
    if exception is not None or app.builder.name != "html":
        return
    out = Path(app.outdir)
    wanted: dict[str, list[dict[str, str]]] = getattr(app, "course_math_fragments", {}) or {}
    fragments = {str(out / app.builder.get_target_uri(name)): f for name, f in wanted.items()}
    def has_math(p: Path) -> bool:
        return str(p) in fragments or 'math notranslate nohighlight' in p.read_text(encoding="utf-8")
    pages = [str(p) for p in (out / app.builder.get_target_uri(name) for name in sorted(_WRITTEN | set(wanted)))
             if p.suffix == ".html" and p.is_file() and has_math(p)]
    _WRITTEN.clear()
    if not pages:
        return
    start = time.monotonic()
    counts = typeset(out / "_static", pages, macros(app.config), {p: fragments[p] for p in pages if p in fragments})
    logger.info(f"math_prerender: {sum(c['math'] for c in counts)} formulas on {len(counts)} pages typeset "
                f"in {time.monotonic() - start:.1f} s")


def typeset(static: Path, pages: list[str] | list[Path], tex_macros: dict[str, Any],
            fragments: dict[str, list[dict[str, str]]] | None = None) -> list[dict[str, Any]]:
    """Typeset the math of ``pages`` in place (``static``: the site's ``_static``, where the fonts are), and the
    ``fragments`` of each page (keyed by the page's path as given; see the module's docstring).

    Returns one ``{"page", "math", "css"}`` per page (formulas typeset, fragments' included; bytes of CSS added).
    """
    node = shutil.which("node")
    if node is None:
        raise ExtensionError("math_prerender: Node.js is needed to typeset the math at build time (apt install nodejs)")
    if not (ROOT / "node_modules" / "mathjax-full").is_dir():
        raise ExtensionError("math_prerender: node_modules/mathjax-full is missing: run `npm ci` (make setup does it)")
    if not pages:
        return []
    # One Node process per core, each typesetting its share of the pages (each page and its fragments are
    # written by one process only); shares balanced by the pages' bytes, the biggest first.
    shares: list[list[str]] = [[] for _ in range(max(1, min(os.cpu_count() or 1, len(pages))))]
    loads = [0] * len(shares)
    for page in sorted(map(str, pages), key=lambda p: -Path(p).stat().st_size):
        k = loads.index(min(loads))
        shares[k].append(page)
        loads[k] += Path(page).stat().st_size
    fragments = fragments or {}
    with tempfile.TemporaryDirectory() as tmp:
        procs = []
        for k, share in enumerate(shares):
            args = [node, str(SCRIPT), str(static), json.dumps(tex_macros), *share]
            mine = {p: f for p, f in fragments.items() if p in share}
            if mine:
                spec = Path(tmp) / f"fragments-{k}.json"
                spec.write_text(json.dumps(mine), encoding="utf-8")
                args[2:2] = ["--fragments", str(spec)]
            procs.append(subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT))
        runs = [(proc, *proc.communicate()) for proc in procs]
    for proc, _out, err in runs:
        if proc.returncode != 0:
            raise ExtensionError(f"math_prerender: {err.strip()[-4000:]}")
    by_page = {c["page"]: c for _p, out, _e in runs for c in (json.loads(line) for line in out.splitlines()
                                                                if line.startswith("{"))}
    return [by_page[p] for p in map(str, pages) if p in by_page] + [c for p, c in by_page.items()
                                                                    if p not in set(map(str, pages))]


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("html-page-context", note_page)
    # after the other build-finished handlers that rewrite pages (their priority is 500 or less)
    app.connect("build-finished", prerender, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
