"""Build one reveal.js lecture deck per chapter from the chapter sources.

Usage: python -m tools.build_slides DEST [--only NAME ...] [--jobs N]
                                         [--cache DIR] [--no-book-cache]

For every page listed in ``_toc.yml`` that gets a deck
(``_ext/notebook_pages.py``: a notebook in ``chapters/``; the plain-Markdown
root page and the exercise notebooks in ``exercises/`` have none):

1. read it with jupytext;
2. take its executed outputs from a cache when the code and the library are
   unchanged: first this script's own cache (``_build/.slides_cache``, keyed
   by the code cells, the kernel and the source of ``lib/jacobians``), then
   the book's jupyter-cache (``_build/.jupyter_cache``, filled by
   ``jupyter-book build``); otherwise execute it with nbclient in the
   chapter's folder;
3. convert it with nbconvert's SlidesExporter, the preprocessor
   ``tools/slides/preprocess.py`` (MyST directives as boxes, code hidden unless
   tagged ``slide-show-code``, solutions dropped) and the template
   ``tools/slides/templates/course`` (no CDN: reveal.js and require.js are
   copied from node_modules into ``DEST/vendor`` by
   ``tools/vendor.py``; MathJax 3 runs through reveal.js's ``RevealMath.MathJax3``
   plugin from the book's copy in ``DEST/../_static`` when the decks are built
   into the book, else from its own copy in ``DEST/vendor``);
4. write ``DEST/<name>.slides.html`` and an index page ``DEST/index.html``.

Exit status 1 if any deck failed; the others are still written.
"""

from __future__ import annotations

import argparse
import hashlib
import html
import json
import shutil
import sys
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any, cast

import yaml
from _ext.notebook_pages import has_deck, read
from nbconvert.exporters import SlidesExporter
from nbformat import NotebookNode

from tools import vendor
from tools.slides import reader
from tools.slides.preprocess import MystSlidesPreprocessor

ROOT = Path(__file__).resolve().parent.parent
TEMPLATES = ROOT / "tools" / "slides" / "templates"
DEFAULT_CACHE = ROOT / "_build" / ".slides_cache"
BOOK_CACHE = ROOT / "_build" / ".jupyter_cache"
EXEC_TIMEOUT = 180


# ---------------------------------------------------------------- what to build


def toc_files(root: Path = ROOT) -> list[Path]:
    """Every source listed in _toc.yml, in book order (root page first)."""
    toc = yaml.safe_load((root / "_toc.yml").read_text(encoding="utf-8"))
    found: list[str] = []

    def walk(node: object) -> None:
        if isinstance(node, dict):
            if "file" in node:
                found.append(node["file"])
            for key in ("root",):
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


def deck_name(source: Path) -> str:
    return f"{source.stem}.slides.html"


def all_labels(root: Path = ROOT) -> dict:
    """Label -> shown text over the whole book; a page is also known by its path.

    Chapters are indexed last so that a chapter's stem names the chapter even
    when an exercise notebook has the same file name.
    """
    labels: dict = {}
    decks = set(deck_sources(root))
    for p in sorted((p for p in toc_files(root) if p.suffix == ".md"), key=lambda p: p in decks):
        found = reader.index_labels(p)
        if p.stem in found:
            found[p.relative_to(root).with_suffix("").as_posix()] = found[p.stem]
        labels.update(found)
    return labels


def mathjax_config(root: Path = ROOT) -> dict:
    """The book's MathJax 3 set-up (_config.yml ``mathjax3_config``): the components
    to load, the TeX packages and the macros, given to the decks' MathJax 3 as they are."""
    cfg = yaml.safe_load((root / "_config.yml").read_text(encoding="utf-8"))
    try:
        return dict(cfg["sphinx"]["config"]["mathjax3_config"])
    except (KeyError, TypeError):
        return {}


def mathjax_macros(root: Path = ROOT) -> dict:
    """The book's MathJax 3 macros (_config.yml), given to the decks' MathJax 3 as they are."""
    return dict(mathjax_config(root).get("tex", {}).get("macros", {}))


# ---------------------------------------------------------------- execution


def _lib_hash(root: Path = ROOT) -> str:
    h = hashlib.sha256()
    for p in sorted((root / "lib" / "jacobians").rglob("*.py")):
        h.update(p.relative_to(root).as_posix().encode())
        h.update(p.read_bytes())
    return h.hexdigest()


def _code_hash(nb: NotebookNode) -> str:
    h = hashlib.sha256()
    h.update(json.dumps(nb.metadata.get("kernelspec", {}), sort_keys=True).encode())
    for cell in nb.cells:
        if cell.cell_type == "code":
            h.update(b"\x00" + cell.source.encode())
    return h.hexdigest()


def _from_book_cache(nb: NotebookNode) -> NotebookNode | None:
    """Outputs from the book's jupyter-cache, or None if it has no match."""
    if not (BOOK_CACHE / "global.db").exists():
        return None
    try:
        from jupyter_cache import get_cache

        _, merged = get_cache(str(BOOK_CACHE)).merge_match_into_notebook(nb)
        return cast(NotebookNode, merged)
    except Exception:  # no match, or a cache written by another version
        return None


def executed(source: Path, cache_dir: Path, use_book_cache: bool,
             log: Callable[[str], object]) -> tuple[NotebookNode, str]:
    """The chapter as an executed notebook, and where its outputs came from."""
    import nbformat

    nb = read(source)
    key = hashlib.sha256((_code_hash(nb) + _lib_hash()).encode()).hexdigest()[:20]
    cached = cache_dir / f"{source.stem}-{key}.ipynb"
    if cached.exists():
        return _merge_outputs(nb, nbformat.read(cached, as_version=4)), "slides cache"
    if use_book_cache:
        merged = _from_book_cache(nb)
        if merged is not None:
            return merged, "book cache"
    from nbclient import NotebookClient

    t0 = time.perf_counter()
    client = NotebookClient(
        nb,
        timeout=EXEC_TIMEOUT,
        kernel_name=nb.metadata.get("kernelspec", {}).get("name", "python3"),
        resources={"metadata": {"path": str(source.parent)}},
    )
    client.execute()
    log(f"  executed {source.name} in {time.perf_counter() - t0:.1f} s")
    cache_dir.mkdir(parents=True, exist_ok=True)
    for old in cache_dir.glob(f"{source.stem}-*.ipynb"):
        old.unlink()
    tmp = cached.with_suffix(".tmp")
    nbformat.write(nb, tmp)
    tmp.replace(cached)
    return nb, "executed"


def _merge_outputs(nb: NotebookNode, done: NotebookNode) -> NotebookNode:
    """Copy outputs of the cached executed notebook into the freshly read one.

    Markdown and metadata come from the source (they may have changed without
    changing the code); code cells are matched in order.
    """
    code_done = [c for c in done.cells if c.cell_type == "code"]
    code_new = [c for c in nb.cells if c.cell_type == "code"]
    for new, old in zip(code_new, code_done, strict=False):  # same code: same count
        new.outputs = old.get("outputs", [])
        new.execution_count = old.get("execution_count")
    for key in ("language_info", "widgets"):
        if key in done.metadata:
            nb.metadata[key] = done.metadata[key]
    return nb


# ---------------------------------------------------------------- conversion


def exporter(labels: dict[str, str], source: Path, stem: str, urls: dict[str, str]) -> SlidesExporter:
    from traitlets.config import Config

    c = Config()
    c.SlidesExporter.template_name = "course"
    c.SlidesExporter.extra_template_basedirs = [str(TEMPLATES)]
    c.SlidesExporter.reveal_url_prefix = urls["reveal.js"].removesuffix("/" + vendor.REVEAL.entry)
    c.SlidesExporter.reveal_theme = "white"
    c.SlidesExporter.reveal_transition = "fade"
    c.SlidesExporter.reveal_width = "1280"
    c.SlidesExporter.reveal_height = "720"
    c.SlidesExporter.mathjax_url = urls["mathjax"]
    c.SlidesExporter.require_js_url = urls["requirejs"]
    c.SlidesExporter.exclude_input_prompt = True
    c.SlidesExporter.exclude_output_prompt = True
    c.SlidesExporter.preprocessors = [MystSlidesPreprocessor]
    c.MystSlidesPreprocessor.labels = labels
    c.MystSlidesPreprocessor.source_dir = str(source.parent)
    c.MystSlidesPreprocessor.asset_prefix = f"{stem}_files/"
    ex = SlidesExporter(config=c)
    return ex


def build_deck(source: Path, dest: Path, labels: dict, course: dict, cache_dir: Path, use_book_cache: bool) -> dict:
    """Build one deck; ``course`` holds the template's ``urls`` (:func:`tools.vendor.deck_urls`) and ``macros``."""
    # returns a small report (name, title, seconds, where outputs came from)
    lines: list[str] = []
    t0 = time.perf_counter()
    nb, origin = executed(source, cache_dir, use_book_cache, lines.append)
    t_exec = time.perf_counter() - t0
    ex = exporter(labels, source, source.stem, course["urls"])
    resources = {
        "metadata": {"name": source.stem, "path": str(source.parent)},
        "course": course,
    }
    title = reader.index_labels(source).get(source.stem, source.stem)
    nb.metadata["title"] = title
    body, resources = ex.from_notebook_node(nb, resources=resources)
    out = dest / deck_name(source)
    out.write_text(body, encoding="utf-8")
    for src, name in resources.get("slides", {}).get("images", []):
        target = dest / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, target)
    return {
        "name": source.stem,
        "title": title,
        "file": out.name,
        "origin": origin,
        "exec_seconds": round(t_exec, 2),
        "seconds": round(time.perf_counter() - t0, 2),
        "bytes": out.stat().st_size,
        "warnings": resources.get("slides", {}).get("warnings", []),
        "log": lines,
    }


def _build_one(args: tuple[Path, Path, dict[str, str], dict[str, Any], Path, bool]) -> dict[str, Any]:
    source, dest, labels, course, cache_dir, use_book_cache = args
    try:
        return build_deck(source, dest, labels, course, cache_dir, use_book_cache)
    except Exception as exc:  # report and continue with the other decks
        return {"name": source.stem, "error": f"{type(exc).__name__}: {exc}"}


def write_index(dest: Path, reports: list[dict]) -> None:
    items = "\n".join(
        f'<li><a href="{html.escape(r["file"])}">{html.escape(r["title"])}</a></li>'
        for r in reports
        if "error" not in r
    )
    dest.joinpath("index.html").write_text(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        "<title>Manipulator Jacobians: lecture slides</title>"
        "<style>body{font-family:sans-serif;font-size:22px;max-width:40em;margin:2em auto;color:#111}"
        "a{color:#0b4f8a}</style></head><body>"
        "<h1>Manipulator Jacobians: lecture slides</h1>"
        "<p>One deck per chapter. Keys: arrows or space to move, <kbd>S</kbd> speaker notes, "
        "<kbd>F</kbd> full screen, <kbd>Esc</kbd> overview.</p>"
        f"<ol>\n{items}\n</ol></body></html>\n",
        encoding="utf-8",
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dest", type=Path)
    ap.add_argument("--only", nargs="*", help="chapter stems to build (default: all)")
    ap.add_argument("--jobs", type=int, default=2, help="decks built in parallel (default 2)")
    ap.add_argument("--cache", type=Path, default=DEFAULT_CACHE, help="executed-notebook cache folder")
    ap.add_argument("--no-book-cache", action="store_true", help="do not reuse the book's jupyter-cache")
    ap.add_argument("--root", type=Path, default=ROOT, help="book folder with _toc.yml (default: this repository)")
    args = ap.parse_args(argv)

    t0 = time.perf_counter()
    dest = args.dest.resolve()
    dest.mkdir(parents=True, exist_ok=True)
    urls = vendor.deck_urls(dest)
    root = args.root.resolve()
    sources = deck_sources(root)
    if args.only:
        unknown = set(args.only) - {s.stem for s in sources}
        if unknown:
            known = [s.stem for s in sources]
            print(f"build_slides: no chapter named {sorted(unknown)}; known: {known}", file=sys.stderr)
            return 2
        sources = [s for s in sources if s.stem in args.only]
    labels = all_labels(root)
    course = {"urls": urls, "macros": mathjax_macros(root), "mathjax": mathjax_config(root)}
    jobs = [(s, dest, labels, course, args.cache.resolve(), not args.no_book_cache) for s in sources]
    if args.jobs > 1 and len(jobs) > 1:
        with ProcessPoolExecutor(max_workers=args.jobs) as pool:
            reports = list(pool.map(_build_one, jobs))
    else:
        reports = [_build_one(j) for j in jobs]
    failed = 0
    for r in reports:
        if "error" in r:
            failed += 1
            print(f"FAILED {r['name']}: {r['error']}", file=sys.stderr)
            continue
        for line in r["log"]:
            print(line)
        print(f"{r['file']:<40} {r['bytes'] / 1e6:5.2f} MB  outputs: {r['origin']:<12} {r['seconds']:6.1f} s")
        for w in r["warnings"]:
            print(f"  warning: {w}")
    all_reports = [r for r in reports if "error" not in r]
    write_index(dest, all_reports)
    (dest / "decks.json").write_text(json.dumps(
        [{k: r[k] for k in ("name", "title", "file", "origin", "seconds", "bytes")} for r in all_reports]
        + [{"name": r["name"], "error": r["error"]} for r in reports if "error" in r], indent=1))
    print(f"build_slides: {len(all_reports)} decks in {dest} ({time.perf_counter() - t0:.1f} s), {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
