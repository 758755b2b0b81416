"""Copy the front-end files the book and the decks load from node_modules.

Nothing in the built pages may load from the internet, so the few npm files
the pages use are copied from ``node_modules`` (installed by ``npm ci`` from
package-lock.json). Only the files a page or a deck loads are copied (the
browser tests list every request, tests/browser/test_site.py checks the sizes
and that every copied tree is used):

* the book (:data:`BOOK`, into ``_vendor/``, Sphinx's ``html_static_path``,
  served as ``_static/``): MathJax 3 only. The live views are the course's
  own ES modules (``lib/jacobians/widgets/live/``, shipped inside the
  package), so there is no widget manager and no require.js;
  ``_ext/offline_fixes.py`` stops the build if a page ever shows a Jupyter
  widget. The book's pages load no MathJax: their math is typeset at build
  time (``_ext/math_prerender.py``, SVG: no font). MathJax is
  loaded when a reader asks for MathJax's menu or explorer
  (``_theme/math_menu.js``) and by the decks.
* the decks vendor nothing: they are a Sphinx build of the same sources
  (``_ext/decks.py``, ``tools/build_slides.py``) that loads reveal.js from
  the copy bundled with sphinx-revealjs, and the book's MathJax and styles
  from the book's ``_static``.

Usage: python -m tools.vendor            (writes _vendor/)
"""

from __future__ import annotations

import shutil
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
NODE_MODULES = ROOT / "node_modules"
BOOK_VENDOR = ROOT / "_vendor"
#: the built book's static folder, where Sphinx copies _vendor
SITE_STATIC = ROOT / "_build" / "html" / "_static"


@dataclass(frozen=True)
class Package:
    """The files of one npm package that pages load, and where they go.

    ``parts`` are files or folders inside ``node_modules/<npm>``; they are
    copied to ``<dest>/<folder>/<part>`` (``folder`` is one name, a tree of
    its own under ``_static`` or ``vendor``). ``entry`` is the file a page
    links, relative to ``<dest>/<folder>``.
    """

    npm: str
    folder: str
    parts: tuple[str, ...]
    entry: str

    def copy(self, dest: Path, node_modules: Path = NODE_MODULES) -> None:
        """Copy the parts into ``dest/<folder>`` (which is emptied first)."""
        target = dest / self.folder
        shutil.rmtree(target, ignore_errors=True)
        for part in self.parts:
            src = node_modules / self.npm / part
            if not src.exists():
                raise FileNotFoundError(f"vendor: {src} is missing; run `npm ci` (make does this) first")
            dst = target / part
            if src.is_dir():
                shutil.copytree(src, dst)
            else:
                dst.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, dst)


#: MathJax 3 from its components, as the decks' ``mathjax3_config.loader.load``
#: (_config.yml) and ``_theme/math_menu.js`` list them: the start-up loader, the
#: core, TeX input with the packages the pages use (others, e.g. \\boldsymbol or
#: \\cancel, autoload from input/tex/extensions), CommonHTML output with its TeX
#: font and woff-v2 files (for the formulas the menu typesets again; the math
#: typeset at build time is SVG and needs no font), the
#: hidden MathML that screen readers read, and, loaded on demand, the menu and
#: the explorer (speech: the speech rule engine with its English rules, and the
#: MathML input that its semantic enrichment reads). Not the
#: combined tex-mml-chtml.js, nor the rules of
#: other languages (3.5 MB).
MATHJAX_COMPONENTS = ("startup", "core", "input/tex-base", "output/chtml", "output/chtml/fonts/tex",
                      "a11y/assistive-mml", "ui/menu", "a11y/explorer", "a11y/semantic-enrich", "a11y/sre",
                      "input/mml")
MATHJAX = Package("mathjax", "mathjax",
                  (*(f"es5/{c}.js" for c in MATHJAX_COMPONENTS),
                   "es5/output/chtml/fonts/woff-v2", "es5/input/tex/extensions",
                   "es5/sre/mathmaps/base.json", "es5/sre/mathmaps/en.json"),
                  "es5/startup.js")
BOOK: tuple[Package, ...] = (MATHJAX,)


def book(dest: Path = BOOK_VENDOR, site_static: Path | None = SITE_STATIC) -> None:
    """Write ``dest`` (``_vendor``) afresh with :data:`BOOK`, and bring a built site in step with it.

    Sphinx copies ``_vendor`` into ``_static`` but never deletes what left it.
    So in an already built site (``site_static``) the trees this folder held
    before and no longer holds are removed, and the trees it holds now are
    replaced by the fresh copies at once: the built pages and decks keep
    loading them whether or not a Sphinx build follows (``make slides``,
    ``make vendor`` run none).
    """
    previous = {p.name for p in dest.iterdir()} if dest.is_dir() else set()
    shutil.rmtree(dest, ignore_errors=True)
    dest.mkdir(parents=True)
    for package in BOOK:
        package.copy(dest)
    if site_static is not None and site_static.is_dir():
        current = {p.folder for p in BOOK}
        for name in previous | current:
            stale = site_static / name
            if stale.is_dir():
                shutil.rmtree(stale)
            elif stale.exists():
                stale.unlink()
        for name in sorted(current):
            shutil.copytree(dest / name, site_static / name)


def main(argv: list[str]) -> int:
    if argv:
        print(f"usage: python -m tools.vendor   (got {argv})", file=sys.stderr)
        return 2
    book()
    print(f"vendor: {', '.join(p.npm for p in BOOK)} -> {BOOK_VENDOR.relative_to(ROOT)}/")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
