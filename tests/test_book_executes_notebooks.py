"""``make book`` runs every notebook cell that nbval would run, and stops on the first error: so ``make test``
needs no separate nbval stage (``make test-notebooks`` stays, to run the notebooks without building the book).

What nbval --nbval-lax checks on the notebooks of ``tools.to_ipynb`` (every MyST notebook of chapters/ and
exercises/) is that every code cell runs without an exception (outputs are compared only in cells tagged
``nbval-check-output``; a cell tagged ``raises-exception`` may raise). The book build does the same when

* every one of those notebooks is a page of the table of contents (``only_build_toc_files``),
* execution is on, with ``allow_errors: false`` and ``nb_execution_raise_on_error: true`` (an exception in
  a cell fails the build), and no notebook or cell is left out of execution (no ``execution_excludepatterns``,
  no cell tagged ``skip-execution``, which myst-nb skips and nbval would run),
* no cell carries an nbval tag, whose meaning the book build does not share.

A page run from the cache (``execute_notebooks: cache``) was run with the same source and the same library
(``_ext/library_deps.py`` empties the cache when ``lib/`` changes); a fresh clone has no cache.
"""

from __future__ import annotations

from pathlib import Path

import yaml
from tools import to_ipynb

ROOT = Path(__file__).resolve().parents[1]


def _toc_files(node) -> set[str]:
    out: set[str] = set()
    if isinstance(node, dict):
        if isinstance(node.get("file"), str):
            out.add(node["file"])
        if isinstance(node.get("root"), str):
            out.add(node["root"])
        for value in node.values():
            out |= _toc_files(value)
    elif isinstance(node, list):
        for value in node:
            out |= _toc_files(value)
    return out


def test_every_notebook_nbval_would_run_is_a_page_the_book_executes():
    toc = _toc_files(yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8")))
    notebooks = {f"{folder}/{path.stem}" for folder, path in to_ipynb.sources(ROOT)}
    assert {"chapters/01_twists", "exercises/01_twists"} <= notebooks, sorted(notebooks)  # both folders are read
    assert notebooks <= toc, f"notebooks the book does not build (nbval would run them): {sorted(notebooks - toc)}"


def test_the_book_build_fails_on_any_cell_error():
    cfg = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    assert cfg.get("only_build_toc_files") is True
    execute = cfg["execute"]
    assert execute["execute_notebooks"] in ("cache", "force", "auto"), execute
    assert execute["allow_errors"] is False and not execute.get("exclude_patterns"), execute
    sphinx = cfg["sphinx"]["config"]
    assert sphinx["nb_execution_raise_on_error"] is True
    assert not sphinx.get("nb_execution_excludepatterns") and sphinx.get("nb_execution_mode") in (None, "cache",
                                                                                                  "force", "auto")
    assert sphinx.get("nb_execution_allow_errors") in (None, False)


def test_no_cell_is_skipped_by_the_book_or_tagged_for_nbval():
    bad = []
    for folder, path in to_ipynb.sources(ROOT):
        nb = to_ipynb.read(path)
        for k, cell in enumerate(nb.cells):
            tags = cell.get("metadata", {}).get("tags", [])
            odd = [t for t in tags if t == "skip-execution" or t.startswith("nbval")]
            if odd or (cell.cell_type == "code" and cell.get("metadata", {}).get("skip_execution")):
                bad.append(f"{folder}/{path.name} cell {k}: {odd or 'skip_execution'}")
    assert bad == []
