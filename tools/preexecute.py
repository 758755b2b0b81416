"""Run the book's notebooks on every core into myst-nb's execution cache, before Sphinx reads the pages.

Sphinx reads the pages one at a time, and myst-nb executes each notebook page
as it reads it, so a cold ``make book`` executes its notebooks one after the
other on one core (Sphinx's parallel read is no way out: ``sphinx-revealjs``,
loaded in both builds for the decks, is not parallel-read safe). This command
does the execution first, on ``--jobs`` kernels at once, and stores each
executed notebook in the cache exactly as myst-nb does in its ``cache`` mode
(``myst_nb.core.execute.cache``): the notebook read by myst-nb's own reader,
executed by jupyter-cache's ``single_nb_execution`` in the page's folder with
the book's timeout and ``allow_errors``, and stored under the hash of its code
cells. Sphinx then finds every notebook in the cache and executes nothing.

What stays the book's: a notebook whose run fails here is not stored, so
Sphinx executes it again and fails the build with its own message (and the
notebook's traceback); a notebook already in the cache is not run again; the
cache is first emptied if it was filled under another library
(``_ext/library_deps.py``'s guard, the same one the build applies), so a
library change re-executes every notebook, here, in parallel.

Usage: python -m tools.preexecute [--jobs N] [--cache DIR]   (default: every core, _build/.jupyter_cache)
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parent.parent


def _config(root: Path = ROOT) -> dict[str, Any]:
    config: dict[str, Any] = yaml.safe_load((root / "_config.yml").read_text(encoding="utf-8"))
    return config


def book_notebooks(root: Path = ROOT) -> list[Path]:
    """The notebook pages of the table of contents (the book builds only those: ``only_build_toc_files``)."""
    from _ext.notebook_pages import is_notebook

    from tools.build_slides import toc_files

    return [path.resolve() for path in dict.fromkeys(toc_files(root)) if is_notebook(path)]


def _reader(path: Path, extensions: list[str]) -> Any:
    """myst-nb's reader of ``path``, with the book's MyST extensions (as ``myst_nb.sphinx_`` makes it)."""
    from myst_nb.core.config import NbParserConfig
    from myst_nb.core.read import create_nb_reader
    from myst_parser.config.main import MdParserConfig

    text = path.read_text(encoding="utf-8") if path.suffix == ".md" else None
    reader = create_nb_reader(str(path), MdParserConfig(enable_extensions=set(extensions)), NbParserConfig(), text)
    if reader is None:
        raise ValueError(f"{path} is not a notebook")
    return reader, text


def read_notebook(path: Path, extensions: list[str]) -> Any:
    """The notebook of ``path`` as myst-nb reads it (``extensions``: the book's ``myst_enable_extensions``)."""
    reader, text = _reader(path, extensions)
    return reader.read(text if text is not None else path.read_text(encoding="utf-8"))


def _execute(path_str: str, extensions: list[str], timeout: int,
             allow_errors: bool) -> tuple[str, Any, float, str | None]:
    """In a worker process: execute the notebook of ``path_str`` in its folder, as myst-nb's cache mode does."""
    from jupyter_cache.executors.utils import single_nb_execution

    path = Path(path_str)
    nb = read_notebook(path, extensions)
    result = single_nb_execution(nb, cwd=str(path.parent), allow_errors=allow_errors, timeout=timeout,
                                 meta_override=True)
    err = None if result.err is None else f"{result.err.__class__.__name__}"
    return path_str, result.nb, result.time, err


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--root", type=Path, default=ROOT, help="the book's folder (default: this repository)")
    ap.add_argument("--cache", type=Path, default=None, help="default: ROOT/_build/.jupyter_cache")
    args = ap.parse_args(argv)
    root = args.root.resolve()
    cache_path = args.cache or root / "_build" / ".jupyter_cache"

    from _ext import library_deps
    from jupyter_cache import get_cache
    from jupyter_cache.base import CacheBundleIn

    config = _config(root)
    execute = config.get("execute", {})
    if execute.get("execute_notebooks", "cache") != "cache":
        print("preexecute: the book does not execute into the cache (execute_notebooks is not 'cache'): nothing to do")
        return 0
    timeout = int(execute.get("timeout", 30))
    allow_errors = bool(execute.get("allow_errors", False))
    extensions = list(config.get("parse", {}).get("myst_enable_extensions", []))
    # the library as the book's build hashes it (_ext/library_deps.py: course_library_paths)
    sphinx_config = config.get("sphinx", {}).get("config", {}) or {}
    library = sphinx_config.get("course_library_paths", list(library_deps.DEFAULT_PATHS))
    digest = library_deps.library_hash([root / p for p in library], root)
    if library_deps.guard(cache_path, digest):
        print(f"preexecute: the library changed; emptied {cache_path} so every notebook executes again")
    cache = get_cache(str(cache_path))

    todo: list[Path] = []
    for path in book_notebooks(root):
        try:
            cache.match_cache_notebook(read_notebook(path, extensions))
        except KeyError:
            todo.append(path)
    if not todo:
        print("preexecute: every notebook of the book is in the cache")
        return 0
    # the biggest sources first: the long notebooks start early and the short ones fill the gaps
    todo.sort(key=lambda p: -p.stat().st_size)
    start = time.perf_counter()
    print(f"preexecute: {len(todo)} notebooks on {args.jobs} kernels at once", flush=True)
    failed: list[str] = []
    with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = [pool.submit(_execute, str(p), extensions, timeout, allow_errors) for p in todo]
        for fut in as_completed(futures):
            path_str, nb, seconds, err = fut.result()
            name = Path(path_str).relative_to(root).as_posix()
            if err is not None:
                failed.append(name)
                print(f"preexecute: {name} failed ({err}); the book build runs it again and reports the error")
                continue
            record = cache.add_nb_to_project(path_str)
            cache.cache_notebook_bundle(CacheBundleIn(nb, record.uri, data={"execution_seconds": seconds}),
                                        check_validity=False, overwrite=True)
            print(f"preexecute: {name} in {seconds:.1f} s", flush=True)
    print(f"preexecute: {len(todo) - len(failed)} of {len(todo)} notebooks cached in "
          f"{time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
