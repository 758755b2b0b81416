"""Sphinx extension: the theme's style sheets trimmed to what the book's pages use (PurgeCSS).

The pages linked about 460 KB of CSS (the pydata and book themes, sphinx-design, myst-nb, Sphinx's
``basic.css``), most of it rules for components the book never shows; on a slow phone every byte of it
is fetched and parsed before the first paint. At the end of each HTML build (after every handler that
rewrites pages: ``math_prerender`` and ``lazy_frames``), ``tools/purge_css.cjs`` (npm ``purgecss``)
rewrites those files in place with only the rules whose selectors name something in a page or in a
script of ``_static`` (scripts add classes at run time), plus a safelist for what no file spells out
whole (dark mode, MathJax's menu, Bootstrap's states). Sphinx copies the full files again on every
build, and the trim reads every page on disk, so an incremental build is trimmed as a full one.

Only the book (the ``html`` builder); the decks load their own copies. ``tests/browser`` (axe in both
colour modes, contrast, the pages' checks) run on the trimmed site.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx.errors import ExtensionError
from sphinx.util import logging

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "purge_css.cjs"
logger = logging.getLogger(__name__)


def trim(site: Path) -> dict[str, Any]:
    """Trim the site's third-party CSS in place; returns what ``tools/purge_css.cjs`` reports (bytes of each
    file before and after)."""
    node = shutil.which("node")
    if node is None:
        raise ExtensionError("trim_css: Node.js is needed to trim the CSS (apt install nodejs)")
    if not (ROOT / "node_modules" / "purgecss").is_dir():
        raise ExtensionError("trim_css: node_modules/purgecss is missing: run `npm ci` (make setup does it)")
    run = subprocess.run([node, str(SCRIPT), str(site)], capture_output=True, text=True, cwd=ROOT, check=False)
    if run.returncode != 0:
        raise ExtensionError(f"trim_css: {run.stderr.strip()[-4000:]}")
    report: dict[str, Any] = json.loads(run.stdout.strip().splitlines()[-1])
    return report


def finished(app: Sphinx, exception: Exception | None) -> None:
    if exception is not None or app.builder.name != "html":
        return
    report = trim(Path(app.outdir))
    before = sum(b for b, _ in report["sizes"].values())
    after = sum(a for _, a in report["sizes"].values())
    logger.info(f"trim_css: {len(report['sizes'])} style sheets from {before / 1000:.0f} KB to "
                f"{after / 1000:.0f} KB (what {report['pages']} pages and {report['scripts']} scripts use)")


def setup(app: Sphinx) -> dict[str, Any]:
    # after math_prerender (900) and every other build-finished handler that rewrites pages
    app.connect("build-finished", finished, priority=950)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
