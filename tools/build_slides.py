"""Build the lecture decks: the book's sources through Sphinx's ``revealjs`` builder.

Usage: python -m tools.build_slides [DEST] [--no-build] [--no-pdf]

1. ``jupyter-book build . --builder custom --custom-builder revealjs`` (the
   book's own toolchain and configuration: myst-nb with the book's
   jupyter-cache, so nothing is executed again; ``_ext/decks.py`` turns each
   chapter's resolved doctree into slides) writes ``_build/revealjs``;
2. the chapter decks (``_ext/notebook_pages.has_deck``) are copied into
   ``DEST`` (default ``_build/html/slides``, inside the book) keeping the
   book's layout (``DEST/chapters/<stem>.html``), with every file they load,
   one copy each (:func:`assemble`): the folder stands alone, so a copy of it
   on a USB stick works over ``file://``. reveal.js and its search, zoom and
   notes plugins, the slide menu (reveal.js-menu) and the chalkboard
   (reveal.js-plugins) come from npm (package-lock.json); the live views are
   one classic script bundled by esbuild (:func:`bundle_live`);
3. every deck is printed to a PDF and a handout with the speaker notes
   (``tools/slides_pdf.py``, into ``DEST/pdf``; ``--no-pdf`` skips it);
4. ``DEST/index.html`` lists each lecture with its minutes (the sum of its
   speaker notes' minutes), its PDFs and its chapter; ``DEST/decks.json`` the
   same for the tests.

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

from tools import vendor

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "_build" / "revealjs"
NODE_MODULES = ROOT / "node_modules"
BOOK_HTML = ROOT / "_build" / "html"
#: reveal.js files a deck loads (from npm's reveal.js, the release sphinx-revealjs bundles)
#: (the browser loads the woff fonts; the theme's .eot/.ttf copies and the source map are left out)
REVEAL_KEEP = ("dist/reveal.js", "dist/reveal.css", "dist/theme/white.css", "plugin/notes/notes.js", "LICENSE",
               "plugin/search/search.js", "plugin/zoom/zoom.js",
               "dist/theme/fonts/source-sans-pro/source-sans-pro.css", "dist/theme/fonts/source-sans-pro/LICENSE",
               *(f"dist/theme/fonts/source-sans-pro/source-sans-pro-{w}.woff"
                 for w in ("regular", "italic", "semibold", "semibolditalic")))
#: the presenter's plugins from npm beyond reveal.js's own (search, zoom, notes): npm package -> the files a
#: deck loads, copied to ``_static/plugins/<folder>/`` (the browser loads the woff2 fonts only)
PLUGINS = {
    "reveal.js-menu": ("menu", ("menu.js", "menu.css", "LICENSE", "font-awesome/LICENSE.txt",
                                "font-awesome/css/all.css", *(f"font-awesome/webfonts/fa-{w}.woff2" for w in (
                                    "solid-900", "regular-400", "brands-400")))),
    "reveal.js-plugins": ("chalkboard", ("chalkboard/plugin.js", "chalkboard/style.css", "LICENSE",
                                         *(f"chalkboard/img/{n}" for n in (
                                             "blackboard.png", "whiteboard.png", "sponge.png",
                                             *(f"boardmarker-{c}.png" for c in ("black", "blue", "green", "orange",
                                                                                "purple", "red", "yellow")),
                                             *(f"chalk-{c}.png" for c in ("white", "blue", "green", "orange", "purple",
                                                                          "red", "yellow")))))),
}
#: the live views' bundle entry (esbuild): the views' ES modules of lib/jacobians/widgets/static/live
LIVE_ENTRY = ROOT / "_ext" / "decks_live" / "entry.js"
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


def _title(page: str) -> str:
    m = re.search(r"<h1>(.*?)</h1>", page, re.S)
    return re.sub(r"<[^>]+>", "", m.group(1)).strip() if m else ""


def assemble(dest: Path, root: Path = ROOT) -> list[dict[str, str]]:
    """The deck folder, standing alone: every file a deck loads is inside ``dest``, one copy each.

    A copy of ``dest`` alone (a USB stick) works over ``file://``: reveal.js,
    MathJax (the whole tree: it loads its components and fonts itself), the
    figures, the CSS and the live views (one classic script, :func:`bundle_live`)
    are all under ``dest/_static`` and ``dest/_images``. Links to the book's
    pages stay relative (``../../chapters/...``): they work inside the site.
    """
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
        target.write_text(page, encoding="utf-8")
        decks.append({"name": source.stem, "title": _title(page), "file": rel,
                      "chapter": "../" + rel, "pdf": f"pdf/{source.stem}.pdf",
                      "handout": f"pdf/{source.stem}-notes.pdf", "minutes": str(deck_minutes(page))})
    # keep only what a deck links; then reveal.js, MathJax, the plugins and the live views' bundle go in
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
    # MathJax as the book has it (tools/vendor.py: the components the book's configuration loads, their
    # fonts and TeX extensions: it loads them itself at run time, so the whole tree)
    vendor.MATHJAX.copy(dest / "_static")
    plugins_from_npm(dest / "_static" / "plugins")
    bundle_live(dest / "_static" / "live" / "jac-live.js")
    return decks


def plugins_from_npm(dest: Path, node_modules: Path = NODE_MODULES) -> None:
    """Copy the presenter's plugins (:data:`PLUGINS`) from npm (pinned in package-lock.json) into ``dest``."""
    for package, (folder, files) in PLUGINS.items():
        for rel in files:
            src = node_modules / package / rel
            if not src.is_file():
                raise FileNotFoundError(f"{src} is missing: run `npm ci` (make does this) first")
            dst = dest / folder / (rel.split("/", 1)[1] if rel.startswith(folder + "/") else rel)
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src, dst)


def bundle_live(out: Path, node_modules: Path = NODE_MODULES) -> None:
    """The live views as one classic script (an IIFE), bundled by npm's esbuild from the views' ES modules.

    The book's pages import the modules (``_static/live/*.js``); a deck opened
    from disk cannot (browsers block module scripts over ``file://``), so the
    decks load this bundle of the same modules (``_ext/decks_live/entry.js``).
    """
    esbuild = node_modules / ".bin" / "esbuild"
    if not esbuild.is_file():
        raise FileNotFoundError(f"{esbuild} is missing: run `npm ci` (make does this) first")
    out.parent.mkdir(parents=True, exist_ok=True)
    done = subprocess.run([str(esbuild), str(LIVE_ENTRY), "--bundle", "--format=iife", "--target=es2020",
                           "--minify", "--legal-comments=none", "--log-level=warning", f"--outfile={out}"],
                          cwd=ROOT, capture_output=True, text=True)
    if done.returncode:
        raise RuntimeError(f"esbuild failed to bundle the live views:\n{done.stderr}")


_MINUTES = re.compile(r'<p class="minutes">About (\d+(?:\.\d+)?) min\.</p>')


def deck_minutes(page: str) -> int:
    """A deck's length in minutes: the sum of its speaker notes' minutes (``{slide-notes}`` ``:minutes:``)."""
    return round(sum(float(m) for m in _MINUTES.findall(page)))


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
    """The slides index: each lecture with its minutes, its PDF and handout (when printed) and its chapter."""
    def paper(d: dict[str, str]) -> str:
        links = [f'<a href="{html.escape(d[k])}">{label}</a>'
                 for k, label in (("pdf", "PDF"), ("handout", "handout with notes")) if (dest / d[k]).is_file()]
        return " · ".join(links) if links else "PDFs: <code>make book</code>"

    rows = "\n".join(
        f'<li><a href="{html.escape(d["file"])}">{html.escape(d["title"])}</a> '
        f'<span class="minutes">({d["minutes"]} min)</span> · {paper(d)} '
        f'· <a href="{html.escape(d["chapter"])}">chapter in the book</a></li>'
        for d in decks)
    total = sum(int(d["minutes"]) for d in decks)
    dest.joinpath("index.html").write_text(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
        "<link rel=\"icon\" href=\"data:,\">"
        "<title>Manipulator Jacobians: lecture slides</title>"
        "<style>body{font-family:sans-serif;font-size:20px;max-width:50em;margin:2em auto;padding:0 1em;"
        "color:#111;line-height:1.5}a{color:#0b4f8a}li{margin:.4em 0}.minutes{color:#444}</style></head><body>"
        "<h1>Manipulator Jacobians: lecture slides</h1>"
        f"<p>One lecture per chapter, {len(decks)} in all ({total} min by the speaker notes' timings), each with "
        "a PDF (a page a slide) and a handout with the speaker notes. This folder stands alone: copy it to a "
        "USB stick and open a deck from there, no network needed.</p>"
        "<p>Keys: <kbd>PageDown</kbd>/<kbd>Space</kbd>/<kbd>N</kbd> or a clicker to go on, "
        "<kbd>PageUp</kbd>/<kbd>P</kbd> back (always the deck's, also after touching a slider; the arrow "
        "keys move a slider only for a second after it was touched), <kbd>S</kbd> speaker notes, "
        "<kbd>T</kbd> pacing timer, <kbd>M</kbd> slide menu, <kbd>W</kbd> chalkboard, <kbd>C</kbd> pen, "
        "<kbd>B</kbd> black screen, <kbd>F</kbd> full screen, <kbd>Esc</kbd> overview, "
        "<kbd>Ctrl</kbd>+<kbd>Shift</kbd>+<kbd>F</kbd> search, <kbd>Alt</kbd>+click zoom. "
        "<a href=\"../index.html\">The book</a>.</p>"
        f"<ol>\n{rows}\n</ol></body></html>\n",
        encoding="utf-8",
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dest", type=Path, nargs="?", default=BOOK_HTML / "slides")
    ap.add_argument("--no-build", action="store_true", help="reuse _build/revealjs as it is")
    ap.add_argument("--no-pdf", action="store_true", help="do not print the PDFs and handouts (tools/slides_pdf.py)")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if not args.no_build and run_sphinx():
        print("build_slides: the revealjs build failed", file=sys.stderr)
        return 1
    dest = args.dest.resolve()
    decks = assemble(dest)
    (dest / "decks.json").write_text(json.dumps(decks, indent=1))
    if not args.no_pdf:
        from tools import slides_pdf

        t1 = time.perf_counter()
        printed = {row["name"]: row["slides"] for row in slides_pdf.print_decks(dest)}
        for d in decks:   # the number of slides reveal.js counted: the PDF's number of pages
            d["slides"] = str(printed[d["name"]])
        (dest / "decks.json").write_text(json.dumps(decks, indent=1))
        print(f"build_slides: {2 * len(decks)} PDFs (decks and handouts) in {time.perf_counter() - t1:.1f} s")
    write_index(dest, decks)
    size = sum(p.stat().st_size for p in dest.rglob("*") if p.is_file())
    print(f"build_slides: {len(decks)} decks in {os.path.relpath(dest)} ({size / 1e6:.1f} MB, "
          f"{time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
