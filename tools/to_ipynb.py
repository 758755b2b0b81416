"""Convert every MyST Markdown notebook of the course to .ipynb for nbval.

nbval reads .ipynb only, and the sources are MyST Markdown with a jupytext
header. Usage: python -m tools.to_ipynb DEST  (writes DEST/<folder>__<name>.ipynb)
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import jupytext
from _ext.notebook_pages import is_notebook, read

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ("chapters", "exercises")


def sources(root: Path = ROOT) -> Iterator[tuple[str, Path]]:
    """(folder, path) of every notebook in :data:`FOLDERS`, in name order."""
    for folder in FOLDERS:
        for path in sorted((root / folder).glob("*.md")):
            if is_notebook(path):
                yield folder, path


def main(dest: Path) -> int:
    dest.mkdir(parents=True, exist_ok=True)
    count = 0
    for folder, path in sources():
        jupytext.write(read(path), dest / f"{folder}__{path.stem}.ipynb")
        count += 1
    print(f"to_ipynb: wrote {count} notebooks to {dest}")
    if count == 0:
        print("to_ipynb: no notebooks found", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
