"""Keep the book's execution cache in step with the course library.

Jupyter Book's cache (``_build/.jupyter_cache``) keys each notebook on its own
code cells, not on the ``jacobians`` library the cells import, so after a
change in ``lib/`` (the library and the course content) it would keep serving outputs computed by the old
library. ``make book`` runs this first: it hashes every file of the library
(and ``pyproject.toml``) and, when the hash differs from the one stored beside
the cache, empties the cache so that every page is executed again.

Usage: python -m tools.cache_guard [CACHE_DIR]   (default _build/.jupyter_cache)
"""

from __future__ import annotations

import hashlib
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LIBRARY = ROOT / "lib"
STAMP_NAME = ".library-hash"


def library_hash(library: Path = LIBRARY, extra: tuple[Path, ...] = (ROOT / "pyproject.toml",)) -> str:
    """SHA-256 over the library's files (path and bytes), in a fixed order."""
    h = hashlib.sha256()
    files = sorted(p for p in library.rglob("*") if p.is_file()
                   and not any(part == "__pycache__" or part.endswith(".egg-info") for part in p.parts))
    for path in [*files, *(p for p in extra if p.is_file())]:
        h.update(path.relative_to(library.parent).as_posix().encode() if path.is_relative_to(library.parent)
                 else path.name.encode())
        h.update(b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


def guard(cache: Path, digest: str) -> bool:
    """Empty ``cache`` if it was filled under another library; return True if it was emptied."""
    stamp = cache.parent / (cache.name + STAMP_NAME)
    old = stamp.read_text().strip() if stamp.is_file() else None
    emptied = False
    if old != digest and cache.exists():
        shutil.rmtree(cache)
        emptied = True
    stamp.parent.mkdir(parents=True, exist_ok=True)
    stamp.write_text(digest + "\n")
    return emptied


def main(argv: list[str]) -> int:
    cache = Path(argv[0]) if argv else ROOT / "_build" / ".jupyter_cache"
    if guard(cache, library_hash()):
        print(f"cache_guard: lib/ changed since the last build; emptied {cache} so every page re-executes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
