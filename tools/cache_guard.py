"""Keep the book's execution cache in step with the course library (by hand).

Jupyter Book's cache (``_build/.jupyter_cache``) keys each notebook on its own
code cells, not on the ``jacobians`` library the cells import. The book's
Sphinx extension ``_ext/library_deps.py`` handles this in every build: it
hashes the library's files (``lib/`` and ``pyproject.toml``), empties the cache
when the hash differs from the one stamped beside it, and marks every page
that uses the library outdated so that Sphinx reads and executes it again.
This command does the first half only (empty a cache filled under another
library); the hash and the guard are the extension's.

Usage: python -m tools.cache_guard [CACHE_DIR]   (default _build/.jupyter_cache)
"""

from __future__ import annotations

import sys
from pathlib import Path

from _ext import library_deps

ROOT = Path(__file__).resolve().parent.parent
LIBRARY = ROOT / "lib"
STAMP_NAME = library_deps.STAMP_SUFFIX


def library_hash(library: Path = LIBRARY, extra: tuple[Path, ...] = (ROOT / "pyproject.toml",)) -> str:
    """SHA-256 over the library's files (path and bytes), in a fixed order: as the book's build computes it."""
    return library_deps.library_hash([library, *extra], library.parent)


def guard(cache: Path, digest: str) -> bool:
    """Empty ``cache`` if it was filled under another library; return True if it was emptied."""
    return library_deps.guard(cache, digest)


def main(argv: list[str]) -> int:
    cache = Path(argv[0]) if argv else ROOT / "_build" / ".jupyter_cache"
    if guard(cache, library_hash()):
        print(f"cache_guard: lib/ changed since the last build; emptied {cache} so every page re-executes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
