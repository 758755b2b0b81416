"""Pages that use the course library are read (and executed) again when the library changes.

Sphinx decides what to read again from each page's own source, and myst-nb's
execution cache keys a notebook on its own code cells: neither knows that a
chapter's numbers come from ``lib/``. This extension closes that gap:

* it hashes every file of the library (``course_library_paths``, relative to
  the book's folder; default ``lib`` and ``pyproject.toml``): path and bytes,
  in a fixed order, so an edited, added or removed file changes the hash;
* the execution cache is emptied when the hash differs from the one stamped
  beside it (``<cache>.library-hash``), so no notebook is served outputs
  computed by another library (:func:`guard`, also ``python -m tools.cache_guard``);
* on ``env-get-outdated`` every page that uses the library (a notebook, which
  imports it, or a page with a ``{live-view}``, whose model the library
  computes at build time) is marked outdated when the hash differs from the
  one stored in the build environment, so Sphinx reads it again and myst-nb
  executes it again.

A build with no change to the library or the pages reads and executes nothing.
"""

from __future__ import annotations

import hashlib
import importlib
import re
import shutil
from pathlib import Path
from typing import Any

STAMP_SUFFIX = ".library-hash"
DEFAULT_PATHS = ("lib", "pyproject.toml")
#: a Markdown page that is no notebook uses the library if it mounts a live view
_LIVE_VIEW = re.compile(r"^\s*(```+|:::+)\s*\{live-view\}", re.M)
_SKIP_PARTS = ("__pycache__", ".pytest_cache", ".mypy_cache", ".ruff_cache")


def _files(path: Path) -> list[Path]:
    if path.is_file():
        return [path]
    if not path.is_dir():
        return []
    return sorted(p for p in path.rglob("*") if p.is_file()
                  and not any(part in _SKIP_PARTS or part.endswith(".egg-info") for part in p.parts))


def library_hash(paths: list[Path] | tuple[Path, ...], root: Path) -> str:
    """SHA-256 over the files under ``paths`` (name relative to ``root``, and bytes), in a fixed order."""
    h = hashlib.sha256()
    for path in paths:
        for f in _files(path):
            name = f.relative_to(root).as_posix() if f.is_relative_to(root) else f.name
            h.update(name.encode())
            h.update(b"\0")
            h.update(f.read_bytes())
            h.update(b"\0")
    return h.hexdigest()


def guard(cache: Path, digest: str) -> bool:
    """Empty ``cache`` if it was filled under another library; return True if it was emptied.

    A cache with no stamp is of unknown origin and is emptied too.
    """
    stamp = cache.parent / (cache.name + STAMP_SUFFIX)
    old = stamp.read_text().strip() if stamp.is_file() else None
    emptied = False
    if old != digest and cache.exists():
        shutil.rmtree(cache)
        emptied = True
    stamp.parent.mkdir(parents=True, exist_ok=True)
    stamp.write_text(digest + "\n")
    return emptied


def uses_library(source: Path) -> bool:
    """True for a page whose output depends on the library (a notebook, or a page with a live view)."""
    # notebook_pages: the one rule for what is a notebook. Sphinx (and pytest's pythonpath) put _ext on sys.path;
    # imported by name so that the tools, which import this module as _ext.library_deps, need not.
    is_notebook = importlib.import_module("notebook_pages").is_notebook

    try:
        return is_notebook(source) or bool(_LIVE_VIEW.search(source.read_text(encoding="utf-8")))
    except (OSError, UnicodeDecodeError):
        return True  # unreadable here: read it again rather than keep a stale page


def _outdated(app: Any, env: Any, added: set[str], changed: set[str], removed: set[str]) -> list[str]:
    from sphinx.util import logging

    logger = logging.getLogger(__name__)
    root = Path(app.confdir)
    digest = library_hash([root / p for p in app.config.course_library_paths], root)
    cache_path = getattr(getattr(env, "mystnb_config", None), "execution_cache_path", None)
    if cache_path and guard(Path(cache_path), digest):
        logger.info(f"library_deps: the library changed; emptied {cache_path} so every notebook executes again")
    old = getattr(env, "course_library_hash", None)
    env.course_library_hash = digest
    if old is None or old == digest:
        return []   # a fresh environment reads every page anyway; an unchanged library: nothing to add
    pages = sorted(d for d in env.found_docs - added - changed - removed if uses_library(Path(env.doc2path(d))))
    logger.info(f"library_deps: the library changed; {len(pages)} pages that use it are read again")
    return pages


def setup(app: Any) -> dict[str, Any]:
    app.add_config_value("course_library_paths", list(DEFAULT_PATHS), "env")
    app.connect("env-get-outdated", _outdated)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True, "env_version": 1}
