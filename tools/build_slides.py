"""Build the lecture decks: the book's sources through Sphinx's ``revealjs`` builder.

Usage: python -m tools.build_slides [DEST] [--no-build] [--no-pdf | --pdf-only DECK ...]

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
3. the lectures (``decks_lectures`` in ``_config.yml``: the decks cut and
   joined into lectures of 45-55 minutes, :func:`assemble_lectures`) into
   ``DEST/lectures/``, ``DEST/lectures.json`` for the tests;
4. every deck is printed to a PDF and a handout with the speaker notes
   (``tools/slides_pdf.py``, into ``DEST/pdf``; ``--no-pdf`` skips it,
   ``--pdf-only DECK ...`` prints only these decks), and each lecture's PDF and
   handout are put together from its decks' pages (:func:`lecture_pdfs`: only
   a lecture's own title and summary are printed; with ``--pdf-only``, only the
   lectures made of the printed decks alone);
5. ``DEST/index.html`` lists each lecture with its minutes (the sum of its
   speaker notes' minutes), PDFs and parts, then each chapter's deck with its
   minutes, PDFs and chapter; ``DEST/decks.json`` the same for the tests.

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
import tempfile
import time
from pathlib import Path
from typing import Any

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
#: the live views' bundle entry (esbuild): it mounts the views of jacobians.widgets.live.VIEWS
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


def live_views_module() -> str:
    """The ES module ``jac-live-views`` of the decks' bundle: every registered view's module and deck style.

    It imports ``<view>/deck.css`` and ``<view>/view.js`` of each spec of :data:`jacobians.widgets.live.VIEWS`
    and exports ``VIEWS`` (name -> module), so a view added as a folder is in the decks with no other edit.
    """
    from jacobians.widgets.live import VIEWS

    lines = []
    for name, spec in VIEWS.items():
        lines.append(f"import {json.dumps(spec.deck_css.as_posix())};")
        lines.append(f"import {name} from {json.dumps(spec.module.as_posix())};")
    lines.append(f"export const VIEWS = {{ {', '.join(VIEWS)} }};")
    return "\n".join(lines) + "\n"


def bundle_live(out: Path, node_modules: Path = NODE_MODULES) -> None:
    """The live views as one classic script (an IIFE) and one style sheet, bundled by npm's esbuild.

    The book's pages import the modules (``_static/live/<view>/view.js``); a deck opened
    from disk cannot (browsers block module scripts over ``file://``), so the
    decks load this bundle of the same modules (``_ext/decks_live/entry.js``), and
    ``jac-live.css`` beside it: every view's ``deck.css`` (:func:`live_views_module`).
    """
    esbuild = node_modules / ".bin" / "esbuild"
    if not esbuild.is_file():
        raise FileNotFoundError(f"{esbuild} is missing: run `npm ci` (make does this) first")
    out.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        views = Path(tmp) / "jac-live-views.js"
        views.write_text(live_views_module(), encoding="utf-8")
        done = subprocess.run([str(esbuild), str(LIVE_ENTRY), "--bundle", "--format=iife", "--target=es2020",
                               f"--alias:jac-live-views={views}", "--minify", "--legal-comments=none",
                               "--log-level=warning", f"--outfile={out}"],
                              cwd=ROOT, capture_output=True, text=True)
    if done.returncode:
        raise RuntimeError(f"esbuild failed to bundle the live views:\n{done.stderr}")
    if not out.with_suffix(".css").is_file():
        raise RuntimeError(f"esbuild wrote no {out.with_suffix('.css').name}: the views' deck.css are missing")


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


# ---------------------------------------------------------------- lectures

#: a part of a lecture: a chapter's deck, whole (``01_twists``) or from a section up to another one
#: (``06_analytic_jacobian:6.4-``, ``03_body_jacobian:-3.3.1``: FROM included, TO not; numbers as the book's)
_PART = re.compile(r"^(?P<deck>[\w-]+)(?::(?P<start>[\d.]*)-(?P<stop>[\d.]*))?$")
#: a lecture's length by its speaker notes, in minutes
LECTURE_MINUTES = (45, 55)
LECTURES = "lectures"
_NUMBER = re.compile(r'<h[12][^>]*>\s*<span class="section-number">([\d.]+?)\.?\s*</span>')
_SLIDES_DIV = '<div class="slides" role="main">'


def lecture_plan(root: Path = ROOT) -> list[list[str]]:
    """The lectures (``_config.yml``, ``sphinx: config: decks_lectures``): each a list of parts."""
    config = yaml.safe_load((root / "_config.yml").read_text(encoding="utf-8"))
    plan = ((config.get("sphinx") or {}).get("config") or {}).get("decks_lectures") or []
    if not isinstance(plan, list) or not all(isinstance(lec, list) and lec and all(
            isinstance(part, str) and _PART.match(part) for part in lec) for lec in plan):
        raise ValueError("decks_lectures in _config.yml: expected a list of lectures, each a list of parts "
                         f"such as '01_twists' or '06_analytic_jacobian:6.4-', got {plan!r}")
    return plan


def split_slides(page: str) -> tuple[str, list[str], str]:
    """A deck's page as its head, its slides (each reveal.js's outer ``<section>``) and its tail."""
    start = page.index(_SLIDES_DIV) + len(_SLIDES_DIV)
    slides, depth, begin = [], 0, start
    for m in re.finditer(r"<section\b|</section>", page[start:]):
        at = start + m.start()
        if m.group(0) == "</section>":
            depth -= 1
            if depth == 0:
                slides.append(page[begin:at + len("</section>")].strip())
        else:
            if depth == 0:
                begin = at
            depth += 1
    end = page.index("</div>", page.index(slides[-1]) + len(slides[-1]))
    return page[:start], slides, page[end:]


def _heading(slide: str) -> str:
    m = re.search(r"<h[12][^>]*>(.*?)</h[12]>", slide, re.S)
    return re.sub(r"<[^>]+>", "", m.group(1)).strip() if m else ""


def _is_summary_slide(slide: str) -> bool:
    return bool(re.match(r"^[\d.\s]*(summary|recap)\b", _heading(slide), re.I))


def _slide_minutes(slide: str) -> float:
    return sum(float(m) for m in _MINUTES.findall(slide))


def _select(slides: list[str], start: str, stop: str) -> list[int]:
    """The content slides of a deck (not its title slide) from section ``start`` up to section ``stop``: their
    places in ``slides``."""
    def within(number: str, section: str) -> bool:
        return number == section or number.startswith(section + ".")

    out, number, on = [], "", not start
    for k, slide in enumerate(slides[1:], start=1):
        m = _NUMBER.search(slide)
        number = m.group(1) if m else number
        if start and within(number, start):
            on = True
        if stop and within(number, stop):
            break
        if on:
            out.append(k)
    return out


def _summary_of_part(slides: list[str]) -> str:
    """A summary slide for a lecture that ends inside a chapter: the statements its slides set up."""
    names = []
    for slide in slides:
        for m in re.finditer(r'<p class="admonition-title">(.*?)</p>', slide, re.S):
            names.append(m.group(1).strip())
    names = list(dict.fromkeys(names))[:5]
    items = names or [html.escape(_heading(s)) for s in slides if _heading(s)][:5]
    lead = "This lecture set up:" if names else "This lecture covered:"
    lis = "".join(f"<li><p>{n}</p></li>" for n in dict.fromkeys(items))
    return ('<section >\n<section id="lecture-summary" >\n<h2>Summary</h2>\n'
            f"<p>{lead}</p>\n<ul>{lis}</ul>\n"
            '<aside class="notes">\n<p class="minutes">About 2 min.</p>\n'
            "<p>Key point: the statements above are where the next lecture picks up; the book has each in "
            "full, with its proof and its check by code.</p>\n"
            "<p>Ask: which of these would you use first in the exercises, and why?</p>\n</aside>\n"
            "</section>\n</section>")


def assemble_lectures(dest: Path, decks: list[dict[str, str]], root: Path = ROOT) -> list[dict[str, Any]]:
    """The lectures of :func:`lecture_plan` as decks of their own (``dest/lectures/lecture-NN.html``).

    A lecture is its chapters' slides in order, cut at sections where the plan
    says so: a title slide (the course, lecturer and date, and the plan in its
    notes), the slides of each part (a chapter's title slide only where the
    chapter starts after another part), and a summary slide at its end (the
    chapter's own, or one of the statements of a part that ends inside a
    chapter). Its files sit beside the chapters' decks, at the same depth, so
    it loads the same files. Every content slide of every deck is in exactly
    one lecture (``tests/slides``).

    Each lecture's ``sources`` say where each of its slides comes from, for its
    PDFs (:func:`lecture_pdfs`): ``[deck, place in the deck, notes kept]``, or
    ``["", 0, true]`` for a slide of the lecture's own (its title, a summary
    it adds).
    """
    by_name = {d["name"]: d for d in decks}
    out_dir = dest / LECTURES
    out_dir.mkdir(parents=True, exist_ok=True)
    lectures = []
    for number, parts in enumerate(lecture_plan(root), start=1):
        body: list[str] = []
        sources: list[list[Any]] = [["", 0, True]]   # the title slide: the lecture's own
        covered = []
        head = tail = title_slide = ""
        titles = []
        for k, part in enumerate(parts):
            m = _PART.match(part)
            assert m is not None
            name = m.group("deck")
            if name not in by_name:
                raise ValueError(f"decks_lectures: lecture {number} names {name!r}, which has no deck "
                                 f"(decks: {', '.join(by_name)})")
            page = (dest / by_name[name]["file"]).read_text(encoding="utf-8")
            h, slides, t = split_slides(page)
            if not head:
                head, tail, title_slide = h, t, slides[0]
            chosen = _select(slides, m.group("start") or "", m.group("stop") or "")
            if not chosen:
                raise ValueError(f"decks_lectures: {part!r} selects no slide of {name}")
            if k > 0:   # a chapter that starts inside the lecture opens with its own title slide
                body.append(re.sub(r'<aside class="notes">.*?</aside>', "", slides[0], flags=re.S))
                sources.append([name, 0, False])
            # ids unique within the lecture (two chapters may both have a section "summary")
            body.extend(re.sub(r'(<section\b[^>]*\bid=")', rf"\g<1>{name}--", slides[i]) for i in chosen)
            sources.extend([name, i, True] for i in chosen)
            covered.append({"deck": name, "from": m.group("start") or "", "to": m.group("stop") or "",
                            "slides": len(chosen)})
            titles.append(_heading(slides[0]))
        if not _is_summary_slide(body[-1]):
            body.append(_summary_of_part([s for s in body if 'class="title-slide"' not in s]))
            sources.append(["", 0, True])
        minutes = round(sum(_slide_minutes(s) for s in body))
        names = "; ".join(dict.fromkeys(titles))
        plan = "; ".join(dict.fromkeys(_heading(s) for s in body if _heading(s)))
        h1 = f'<h1>Lecture {number}</h1>\n<p class="lecture-topics">{html.escape(names)}</p>'
        notes = (f'<aside class="notes">\n<p>This lecture: about {minutes} min by the slides\' notes, '
                 f"{len(body) + 1} slides.</p>\n<p>Plan: {html.escape(plan)}.</p>\n</aside>")
        title = re.sub(r"<h1>.*?</h1>", lambda _m, r=h1: r, title_slide, count=1, flags=re.S)  # type: ignore[misc]
        title = re.sub(r'<aside class="notes">.*?</aside>', lambda _m, r=notes: r, title,  # type: ignore[misc]
                       count=1, flags=re.S)
        head_title = f"<title>Lecture {number}: {html.escape(names)}</title>"
        page = (re.sub(r"<title>.*?</title>", lambda _m, r=head_title: r, head, count=1, flags=re.S)  # type: ignore[misc]
                + "\n" + title + "\n" + "\n".join(body) + "\n" + tail)
        rel = f"{LECTURES}/lecture-{number:02d}.html"
        (dest / rel).write_text(page, encoding="utf-8")
        lectures.append({"number": number, "name": f"lecture-{number:02d}", "file": rel, "title": names,
                         "minutes": minutes, "parts": covered, "slides": len(body) + 1,
                         "pdf": f"pdf/lecture-{number:02d}.pdf", "handout": f"pdf/lecture-{number:02d}-notes.pdf",
                         "sources": sources})
    return lectures


def lecture_pdfs(dest: Path, lectures: list[dict[str, Any]], printed: dict[str, dict[str, Any]],
                 browser: Any = None) -> float:
    """Each lecture's PDF and handout (``dest/pdf/lecture-NN.pdf``, ``-notes.pdf``), put together from the
    pages of its decks' prints (``printed``: :func:`tools.slides_pdf.print_decks`'s rows, by deck), so no
    slide is printed twice. Only the lecture's own slides (its title, and a summary it adds) are printed, as
    a small deck of their own beside the lecture (removed afterwards). Returns the seconds spent printing."""
    from pypdf import PdfReader, PdfWriter

    from tools import slides_pdf

    own_decks: list[dict[str, str]] = []
    for lec in lectures:
        head, slides, tail = split_slides((dest / lec["file"]).read_text(encoding="utf-8"))
        own_slides = [slide for slide, (deck, _, _) in zip(slides, lec["sources"], strict=True) if not deck]
        own_file = f"{LECTURES}/.{lec['name']}-own.html"
        (dest / own_file).write_text(head + "\n" + "\n".join(own_slides) + "\n" + tail, encoding="utf-8")
        own_decks.append({"name": f"{lec['name']}-own", "file": own_file, "pdf": f"pdf/.{lec['name']}-own.pdf",
                          "handout": f"pdf/.{lec['name']}-own-notes.pdf"})
    t0 = time.perf_counter()
    try:
        rows = {row["name"]: row for row in slides_pdf.print_decks(dest, browser=browser, decks=own_decks)}
    finally:
        for d in own_decks:
            (dest / d["file"]).unlink()
    seconds = time.perf_counter() - t0

    def pages_of(kinds: list[str]) -> list[list[int]]:
        """The pages of each slide of a print: its slide page, then its notes page if it has one."""
        out: list[list[int]] = []
        for page, kind in enumerate(kinds):
            if kind == "s":
                out.append([page])
            else:
                out[-1].append(page)
        return out

    readers: dict[str, PdfReader] = {}

    def reader(path: Path) -> PdfReader:
        if str(path) not in readers:
            readers[str(path)] = PdfReader(path)
        return readers[str(path)]

    for lec, own in zip(lectures, own_decks, strict=True):
        for key in ("pdf", "handout"):
            writer = PdfWriter()
            next_own = 0
            for deck, place, notes in lec["sources"]:
                if deck:
                    row, path = printed[deck], dest / "pdf" / Path(printed[deck][key]).name
                else:
                    row, path, place = rows[own["name"]], dest / own[key], next_own
                    next_own += 1
                pages = pages_of(row["pages"][key])[place]
                for page in pages if notes else pages[:1]:
                    writer.add_page(reader(path).pages[page])
            with open(dest / lec[key], "wb") as fh:
                writer.write(fh)
        for key in ("pdf", "handout"):
            (dest / own[key]).unlink()
    return seconds


def write_index(dest: Path, decks: list[dict[str, str]], lectures: list[dict[str, Any]] | None = None) -> None:
    """The slides index: each lecture with its minutes and the chapters it covers; then each chapter's deck
    with its minutes, its PDF and handout (when printed) and its chapter in the book."""
    def paper(d: dict[str, Any]) -> str:
        links = [f'<a href="{html.escape(d[k])}">{label}</a>'
                 for k, label in (("pdf", "PDF"), ("handout", "handout with notes")) if (dest / d[k]).is_file()]
        return " · ".join(links) if links else "PDFs: <code>make book</code>"

    by_name = {d["name"]: d for d in decks}

    def part(p: dict[str, Any]) -> str:
        d = by_name[p["deck"]]
        span = ("" if not (p["from"] or p["to"]) else
                f" (sections {p['from'] or 'start'} to {'before ' + p['to'] if p['to'] else 'end'})")
        return f'<a href="{html.escape(d["file"])}">{html.escape(d["title"])}</a>{span}'

    lecture_rows = "\n".join(
        f'<li><a href="{html.escape(lec["file"])}">Lecture {lec["number"]}</a> '
        f'<span class="minutes">({lec["minutes"]} min)</span> · {paper(lec)}: '
        + "; ".join(part(p) for p in lec["parts"]) + "</li>"
        for lec in lectures or [])
    rows = "\n".join(
        f'<li><a href="{html.escape(d["file"])}">{html.escape(d["title"])}</a> '
        f'<span class="minutes">({d["minutes"]} min)</span> · {paper(d)} '
        f'· <a href="{html.escape(d["chapter"])}">chapter in the book</a></li>'
        for d in decks)
    total = sum(int(d["minutes"]) for d in decks)
    lecture_block = (
        f"<h2>Lectures</h2><p>{len(lectures or [])} lectures of {LECTURE_MINUTES[0]} to {LECTURE_MINUTES[1]} "
        "minutes by the speaker notes' timings, the chapters' slides in order (set in <code>_config.yml</code>, "
        f"<code>decks_lectures</code>); each ends with a summary.</p><ol>\n{lecture_rows}\n</ol>"
        if lectures else "")
    dest.joinpath("index.html").write_text(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
        "<link rel=\"icon\" href=\"data:,\">"
        "<title>Manipulator Jacobians: lecture slides</title>"
        "<style>body{font-family:sans-serif;font-size:20px;max-width:50em;margin:2em auto;padding:0 1em;"
        "color:#111;line-height:1.5}a{color:#0b4f8a}li{margin:.4em 0}.minutes{color:#444}</style></head><body>"
        "<h1>Manipulator Jacobians: lecture slides</h1>"
        "<p>This folder stands alone: copy it to a USB stick and open a deck from there, no network needed.</p>"
        "<p>Keys: <kbd>PageDown</kbd>/<kbd>Space</kbd>/<kbd>N</kbd> or a clicker to go on, "
        "<kbd>PageUp</kbd>/<kbd>P</kbd> back (always the deck's, also after touching a slider; the arrow "
        "keys move a slider only for a second after it was touched), <kbd>S</kbd> speaker notes, "
        "<kbd>T</kbd> pacing timer, <kbd>M</kbd> slide menu, <kbd>W</kbd> chalkboard, <kbd>C</kbd> pen, "
        "<kbd>B</kbd> black screen, <kbd>F</kbd> full screen, <kbd>Esc</kbd> overview, "
        "<kbd>Ctrl</kbd>+<kbd>Shift</kbd>+<kbd>F</kbd> search, <kbd>Alt</kbd>+click zoom. "
        "<a href=\"../index.html\">The book</a>.</p>"
        + lecture_block +
        f"<h2>By chapter</h2><p>One deck a chapter, {len(decks)} in all ({total} min by the speaker notes' "
        "timings), each with a PDF (a page a slide) and a handout with the speaker notes.</p>"
        f"<ol>\n{rows}\n</ol></body></html>\n",
        encoding="utf-8",
    )


def pdf_args(slides_pdf: str | None) -> list[str]:
    """The arguments for the PDFs the Makefile's ``SLIDES_PDF`` asks for: ``1`` or unset every deck's, ``0``
    none, else the decks it names (as the Makefile's ``SLIDES_PDF_ARGS``)."""
    asked = (slides_pdf or "1").split()
    return [] if asked == ["1"] else ["--no-pdf"] if asked == ["0"] else ["--pdf-only", *asked]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dest", type=Path, nargs="?", default=BOOK_HTML / "slides")
    ap.add_argument("--no-build", action="store_true", help="reuse _build/revealjs as it is")
    ap.add_argument("--no-pdf", action="store_true", help="do not print the PDFs and handouts (tools/slides_pdf.py)")
    ap.add_argument("--pdf-only", nargs="+", metavar="DECK", default=None,
                    help="print only these decks (by name, e.g. 05_geometric_jacobian) and the lectures made of them")
    args = ap.parse_args(argv)
    if args.no_pdf and args.pdf_only:
        ap.error("--no-pdf and --pdf-only exclude each other")
    t0 = time.perf_counter()
    if not args.no_build and run_sphinx():
        print("build_slides: the revealjs build failed", file=sys.stderr)
        return 1
    dest = args.dest.resolve()
    decks = assemble(dest)
    (dest / "decks.json").write_text(json.dumps(decks, indent=1))
    lectures = assemble_lectures(dest, decks)
    if args.pdf_only:
        unknown = sorted(set(args.pdf_only) - {d["name"] for d in decks})
        if unknown:
            print(f"build_slides: --pdf-only names no deck: {', '.join(unknown)} "
                  f"(decks: {', '.join(d['name'] for d in decks)})", file=sys.stderr)
            return 2
    if not args.no_pdf:
        from tools import slides_pdf

        t1 = time.perf_counter()
        printed = {row["name"]: row for row in slides_pdf.print_decks(dest, only=args.pdf_only)}
        for d in decks:   # the number of slides reveal.js counted: the PDF's number of pages
            if d["name"] in printed:
                d["slides"] = str(printed[d["name"]]["slides"])
        (dest / "decks.json").write_text(json.dumps(decks, indent=1))
        print(f"build_slides: {2 * len(printed)} PDFs (decks and handouts) in {time.perf_counter() - t1:.1f} s")
        # a lecture's PDFs are made of its decks' pages: only the lectures whose decks were all printed
        whole = [lec for lec in lectures if all(not deck or deck in printed for deck, _, _ in lec["sources"])]
        own = lecture_pdfs(dest, whole, printed)
        print(f"build_slides: {2 * len(whole)} PDFs of the lectures, from the decks' pages "
              f"(their own slides printed in {own:.1f} s)")
    (dest / "lectures.json").write_text(json.dumps(lectures, indent=1))
    write_index(dest, decks, lectures)
    size = sum(p.stat().st_size for p in dest.rglob("*") if p.is_file())
    print(f"build_slides: {len(decks)} decks in {os.path.relpath(dest)} ({size / 1e6:.1f} MB, "
          f"{time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
