"""Copy the front-end files the book and the decks load from node_modules.

Nothing in the built pages may load from the internet, so the few npm files
the pages use are copied from ``node_modules`` (installed by ``npm ci`` from
package-lock.json). Only the files a page or a deck loads are copied (the
browser tests list every request, tests/browser/test_site.py checks the sizes
and that every copied tree is used):

* the book (:data:`BOOK`, into ``_vendor/``, Sphinx's ``html_static_path``,
  served as ``_static/``): MathJax 3 only. No page shows a live widget (the
  chapters show animations), so there is no widget manager and no require.js;
  ``_ext/offline_fixes.py`` stops the build if a page ever shows one.
* the decks (:data:`DECKS`, into ``<slides>/vendor/``): reveal.js with its notes
  and math plugins, and require.js, which loads them. (No jQuery: nothing in a
  deck uses it. No font-awesome: the course's animations draw their buttons
  with plain characters.) A deck built inside the book
  (``_build/html/slides``) uses the book's MathJax from ``../_static``; a deck
  built elsewhere gets its own copy (:func:`deck_urls`).

Usage: python -m tools.vendor            (writes _vendor/)
"""

from __future__ import annotations

import os
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


#: MathJax 3 from its components, as the book's ``mathjax3_config.loader.load``
#: (_config.yml) lists them: the start-up loader, the core, TeX input with the
#: packages the pages use (others, e.g. \\boldsymbol or \\cancel, autoload from
#: input/tex/extensions), CommonHTML output with its TeX font and woff-v2 files,
#: and the hidden MathML that screen readers read. Not the combined
#: tex-mml-chtml.js: its menu and MathML input are 0.4 MB no page uses.
MATHJAX_COMPONENTS = ("startup", "core", "input/tex-base", "output/chtml", "output/chtml/fonts/tex",
                      "a11y/assistive-mml")
MATHJAX = Package("mathjax", "mathjax",
                  (*(f"es5/{c}.js" for c in MATHJAX_COMPONENTS),
                   "es5/output/chtml/fonts/woff-v2", "es5/input/tex/extensions"),
                  "es5/startup.js")
REVEAL = Package("reveal.js", "reveal.js",
                 ("dist/reveal.js", "dist/reveal.css", "dist/theme/white.css",
                  "dist/theme/fonts/source-sans-pro/source-sans-pro.css",
                  *(f"dist/theme/fonts/source-sans-pro/source-sans-pro-{w}.woff"
                    for w in ("regular", "italic", "semibold", "semibolditalic")),
                  "plugin/notes/notes.js", "plugin/math/math.js"),
                 "dist/reveal.js")
REQUIREJS = Package("requirejs", "requirejs", ("require.js",), "require.js")

BOOK: tuple[Package, ...] = (MATHJAX,)
DECKS: tuple[Package, ...] = (REVEAL, REQUIREJS)
DECK_VENDOR = "vendor"


def book(dest: Path = BOOK_VENDOR, site_static: Path | None = SITE_STATIC) -> None:
    """Write ``dest`` (``_vendor``) afresh with :data:`BOOK`.

    Sphinx copies ``_vendor`` into ``_static`` but never deletes what left it,
    so the trees this folder held before (and holds now) are also removed from
    ``site_static``; the next build copies the current ones.
    """
    previous = {p.name for p in dest.iterdir()} if dest.is_dir() else set()
    shutil.rmtree(dest, ignore_errors=True)
    dest.mkdir(parents=True)
    for package in BOOK:
        package.copy(dest)
    if site_static is not None and site_static.is_dir():
        for name in previous | {p.folder for p in BOOK}:
            stale = site_static / name
            if stale.is_dir():
                shutil.rmtree(stale)
            elif stale.exists():
                stale.unlink()


def deck_urls(slides_dir: Path, book_static: Path | None = None) -> dict[str, str]:
    """Copy what the decks in ``slides_dir`` load; return the URL of each entry file.

    Keys are the npm names. A package of :data:`BOOK` already in
    ``book_static`` (default: ``slides_dir/../_static``, the book the decks sit
    in) is linked there instead of copied, so the site holds one copy.
    """
    book_static = book_static if book_static is not None else slides_dir.parent / "_static"
    vendor = slides_dir / DECK_VENDOR
    shutil.rmtree(vendor, ignore_errors=True)
    vendor.mkdir(parents=True)
    urls: dict[str, str] = {}
    for package in (*DECKS, *BOOK):
        shared = package in BOOK and (book_static / package.folder / package.entry).is_file()
        if shared:
            base = Path(os.path.relpath(book_static / package.folder, slides_dir)).as_posix()
        else:
            package.copy(vendor)
            base = f"{DECK_VENDOR}/{package.folder}"
        urls[package.npm] = f"{base}/{package.entry}"
    return urls


def main(argv: list[str]) -> int:
    if argv:
        print(f"usage: python -m tools.vendor   (got {argv})", file=sys.stderr)
        return 2
    book()
    print(f"vendor: {', '.join(p.npm for p in BOOK)} -> {BOOK_VENDOR.relative_to(ROOT)}/")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
