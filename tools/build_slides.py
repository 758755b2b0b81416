"""Build the lecture decks: the book's sources through Sphinx's ``revealjs`` builder.

Usage: python -m tools.build_slides [DEST] [--book BOOK_HTML] [--no-build]

1. ``jupyter-book build . --builder custom --custom-builder revealjs`` (the
   book's own toolchain and configuration: myst-nb with the book's
   jupyter-cache, so nothing is executed again; ``_ext/decks.py`` turns each
   chapter's resolved doctree into slides) writes ``_build/revealjs``;
2. the chapter decks (``_ext/notebook_pages.has_deck``) are copied into
   ``DEST`` (default ``_build/html/slides``, inside the book) keeping the
   book's layout (``DEST/chapters/<stem>.html``); every ``_static``/``_images``
   file a deck links that the book already has, byte for byte, is linked in
   the book instead of copied (one copy of each file in the site); reveal.js
   is npm's (``node_modules/reveal.js``, pinned in package-lock.json to the
   version sphinx-revealjs bundles, 5.2.1), and only the files a deck loads;
3. ``DEST/index.html`` lists each deck, its PDF (``make slides-pdf``) and its
   chapter; ``DEST/decks.json`` the same for the tests.

Exit status 1 if the Sphinx build failed.
"""

from __future__ import annotations

import argparse
import filecmp
import html
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import yaml
from _ext.notebook_pages import has_deck

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "_build" / "revealjs"
NODE_MODULES = ROOT / "node_modules"
BOOK_HTML = ROOT / "_build" / "html"
PDF_DIR = ROOT / "_build" / "slides-pdf"
#: reveal.js files a deck loads (from npm's reveal.js, the release sphinx-revealjs bundles)
#: (the browser loads the woff fonts; the theme's .eot/.ttf copies and the source map are left out)
REVEAL_KEEP = ("dist/reveal.js", "dist/reveal.css", "dist/theme/white.css", "plugin/notes/notes.js", "LICENSE",
               "dist/theme/fonts/source-sans-pro/source-sans-pro.css", "dist/theme/fonts/source-sans-pro/LICENSE",
               *(f"dist/theme/fonts/source-sans-pro/source-sans-pro-{w}.woff"
                 for w in ("regular", "italic", "semibold", "semibolditalic")))
_URL = re.compile(r"""(?P<up>(?:\.\./)+)(?P<tree>_static|_images)/(?P<path>[^"'?#\s)<>]+)""")


def toc_files(root: Path = ROOT) -> list[Path]:
    """Every source listed in _toc.yml, in book order (root page first)."""
    toc = yaml.safe_load((root / "_toc.yml").read_text(encoding="utf-8"))
    found: list[str] = []

    def walk(node: object) -> None:
        if isinstance(node, dict):
            for key in ("root", "file"):
                if key in node:
                    found.append(node[key])
            for key in ("parts", "chapters", "sections"):
                for child in node.get(key, []) or []:
                    walk(child)

    walk(toc)
    paths = []
    for name in found:
        for ext in (".md", ".ipynb"):
            p = root / (name + ext)
            if p.exists():
                paths.append(p)
                break
    return paths


def deck_sources(root: Path = ROOT) -> list[Path]:
    """The chapter sources that get a deck (``_ext/notebook_pages.py``, as for the book's link)."""
    return [p for p in toc_files(root) if has_deck(p, root)]


def deck_path(source: Path, root: Path = ROOT) -> str:
    """Where a chapter's deck is, relative to the slides folder (the book's layout)."""
    return source.relative_to(root).with_suffix(".html").as_posix()


def run_sphinx(root: Path = ROOT) -> int:
    cmd = [str(Path(sys.executable).parent / "jupyter-book"), "build", str(root), "-W", "-n", "--keep-going",
           "--builder", "custom", "--custom-builder", "revealjs"]
    done = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
    if done.returncode:
        sys.stderr.write(done.stdout[-6000:] + done.stderr[-6000:])
    return done.returncode


def _share(deck_html: str, deck_rel: str, dest: Path, book: Path) -> str:
    """Point links to ``_static``/``_images`` files the book holds identically at the book's copy."""
    depth = deck_rel.count("/")

    def swap(m: re.Match[str]) -> str:
        if len(m.group("up")) // 3 != depth:
            return m.group(0)
        rel = f"{m.group('tree')}/{m.group('path')}"
        ours, theirs = dest / rel, book / rel
        if theirs.is_file() and (not ours.exists() or filecmp.cmp(ours, theirs, shallow=False)):
            return "../" * (depth + 1) + rel
        return m.group(0)

    return _URL.sub(swap, deck_html)


def _title(page: str) -> str:
    m = re.search(r"<h1>(.*?)</h1>", page, re.S)
    return re.sub(r"<[^>]+>", "", m.group(1)).strip() if m else ""


def assemble(dest: Path, book: Path, root: Path = ROOT) -> list[dict[str, str]]:
    shutil.rmtree(dest, ignore_errors=True)
    dest.mkdir(parents=True)
    shutil.copytree(BUILD / "_static", dest / "_static")
    if (BUILD / "_images").is_dir():
        shutil.copytree(BUILD / "_images", dest / "_images")
    decks = []
    for source in deck_sources(root):
        rel = deck_path(source, root)
        page = (BUILD / rel).read_text(encoding="utf-8")
        target = dest / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(_share(page, rel, dest, book) if book.is_dir() else page, encoding="utf-8")
        decks.append({"name": source.stem, "title": _title(page), "file": rel,
                      "chapter": "../" + rel, "pdf": f"pdf/{source.stem}.pdf"})
    # keep only what a deck still links in this folder
    linked: set[str] = set()
    for d in decks:
        page = (dest / d["file"]).read_text(encoding="utf-8")
        for m in _URL.finditer(page):
            if len(m.group("up")) // 3 == d["file"].count("/"):
                linked.add(f"{m.group('tree')}/{m.group('path')}")
    reveal = dest / "_static" / "revealjs"
    for p in sorted(dest.rglob("*"), reverse=True):
        rel = p.relative_to(dest).as_posix()
        if p.is_file() and rel.startswith(("_static/", "_images/")):
            in_reveal = p.is_relative_to(reveal) and p.relative_to(reveal).as_posix() in REVEAL_KEEP
            if rel not in linked and not in_reveal:
                p.unlink()
        elif p.is_dir() and not any(p.iterdir()):
            p.rmdir()
    reveal_from_npm(reveal)
    return decks


def reveal_from_npm(reveal: Path, node_modules: Path = NODE_MODULES) -> None:
    """Put npm's reveal.js files (the ones a deck loads) in place of sphinx-revealjs's bundled copy.

    The front-end files of the site come from npm, pinned in package-lock.json.
    The two copies must be the same release: a sphinx-revealjs whose bundled
    reveal.js differs from the pinned one stops the build, naming the file.
    """
    npm = node_modules / "reveal.js"
    if not (npm / "package.json").is_file():
        raise FileNotFoundError(f"{npm} is missing: run `npm ci` (make does this) first")
    for rel in REVEAL_KEEP:
        src, dst = npm / rel, reveal / rel
        if not src.is_file():
            raise FileNotFoundError(f"npm's reveal.js has no {rel}: package.json pins the wrong release")
        if dst.is_file() and not filecmp.cmp(src, dst, shallow=False):
            version = json.loads((npm / "package.json").read_text(encoding="utf-8"))["version"]
            raise ValueError(f"sphinx-revealjs bundles another reveal.js than npm's {version} ({rel} differs): "
                             "pin in package.json the release sphinx-revealjs bundles")
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, dst)


def write_index(dest: Path, decks: list[dict[str, str]]) -> None:
    """The slides index: each deck, its PDF handout (once `make slides-pdf` has made it) and its chapter."""
    def pdf(d: dict[str, str]) -> str:
        if (dest / d["pdf"]).is_file():
            return f'· <a href="{html.escape(d["pdf"])}">PDF handout</a> '
        return "· PDF handout: <code>make slides-pdf</code> "

    rows = "\n".join(
        f'<li><a href="{html.escape(d["file"])}">{html.escape(d["title"])}</a> {pdf(d)}'
        f'· <a href="{html.escape(d["chapter"])}">chapter in the book</a></li>'
        for d in decks)
    dest.joinpath("index.html").write_text(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
        "<link rel=\"icon\" href=\"data:,\">"
        "<title>Manipulator Jacobians: lecture slides</title>"
        "<style>body{font-family:sans-serif;font-size:20px;max-width:46em;margin:2em auto;padding:0 1em;"
        "color:#111;line-height:1.5}a{color:#0b4f8a}li{margin:.4em 0}</style></head><body>"
        "<h1>Manipulator Jacobians: lecture slides</h1>"
        "<p>One deck per chapter, with a PDF handout of each. Keys: arrows, space or a clicker to move, "
        "<kbd>S</kbd> speaker notes, <kbd>F</kbd> full screen, <kbd>Esc</kbd> overview. "
        "<a href=\"../index.html\">The book</a>.</p>"
        f"<ol>\n{rows}\n</ol></body></html>\n",
        encoding="utf-8",
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dest", type=Path, nargs="?", default=BOOK_HTML / "slides")
    ap.add_argument("--book", type=Path, default=BOOK_HTML, help="the built book whose files the decks share")
    ap.add_argument("--no-build", action="store_true", help="reuse _build/revealjs as it is")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if not args.no_build and run_sphinx():
        print("build_slides: the revealjs build failed", file=sys.stderr)
        return 1
    dest = args.dest.resolve()
    decks = assemble(dest, args.book.resolve())
    pdfs = dest / "pdf"
    if PDF_DIR.is_dir():   # handouts made by `make slides-pdf` travel with the decks
        pdfs.mkdir(exist_ok=True)
        for p in PDF_DIR.glob("*.pdf"):
            shutil.copy2(p, pdfs / p.name)
    write_index(dest, decks)
    (dest / "decks.json").write_text(json.dumps(decks, indent=1))
    size = sum(p.stat().st_size for p in dest.rglob("*") if p.is_file())
    print(f"build_slides: {len(decks)} decks in {os.path.relpath(dest)} ({size / 1e6:.1f} MB, "
          f"{time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
