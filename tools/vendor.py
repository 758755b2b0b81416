"""Copy the front-end files the book and the slides need from node_modules.

Nothing in the built pages may load from the internet, so MathJax, require.js,
the Jupyter widgets HTML manager, reveal.js and their fonts are copied from
npm packages (installed by ``npm ci`` from package-lock.json) into

* ``_vendor/``        -> Sphinx's html_static_path, served as ``_static/``;
* ``_build/slides/vendor/`` when called with ``--slides``.

Usage: python tools/vendor.py [--slides DEST]
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
NM = ROOT / "node_modules"


def _copy(src: Path, dst: Path, skip_maps: bool = True) -> None:
    if not src.exists():
        sys.exit(f"vendor: {src} is missing; run `npm ci` (make does this) first")
    if src.is_dir():
        ignore = shutil.ignore_patterns("*.map", "*.md", "sre") if skip_maps else None
        shutil.copytree(src, dst, dirs_exist_ok=True, ignore=ignore)
    else:
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)


def book(dest: Path) -> None:
    """MathJax 3, require.js and the widget manager, for the HTML book."""
    # MathJax 3: only what the pages load (the combined TeX/CHTML component and
    # its woff-v2 fonts), plus what it may fetch later (TeX extensions that
    # autoload, the context menu and its accessibility parts): about 3 MB of the
    # package's 20 MB.
    mj = NM / "mathjax" / "es5"
    shutil.rmtree(dest / "mathjax", ignore_errors=True)  # drop files of an older, fuller copy
    for part in ("tex-mml-chtml.js", "output/chtml/fonts/woff-v2", "input/tex/extensions", "ui", "a11y"):
        _copy(mj / part, dest / "mathjax" / "es5" / part)
    _copy(NM / "requirejs" / "require.js", dest / "require.js")
    _copy(NM / "@jupyter-widgets" / "html-manager" / "dist", dest / "html-manager")


def slides(dest: Path) -> None:
    """reveal.js 4, MathJax 2 (nbconvert's reveal template calls its API), jQuery, require.js, fonts."""
    _copy(NM / "reveal.js" / "dist", dest / "reveal.js" / "dist")
    _copy(NM / "reveal.js" / "plugin", dest / "reveal.js" / "plugin")
    for part in ("MathJax.js", "config", "extensions", "jax", "localization", "fonts/HTML-CSS/TeX/woff"):
        _copy(NM / "mathjax2" / part, dest / "mathjax2" / part)
    _copy(NM / "jquery" / "dist" / "jquery.min.js", dest / "jquery.min.js")
    _copy(NM / "requirejs" / "require.js", dest / "require.js")
    _copy(NM / "font-awesome" / "css", dest / "font-awesome" / "css")
    _copy(NM / "font-awesome" / "fonts", dest / "font-awesome" / "fonts")
    _copy(NM / "@jupyter-widgets" / "html-manager" / "dist", dest / "html-manager")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--slides":
        slides(Path(sys.argv[2]))
    else:
        book(ROOT / "_vendor")
