"""Convert every MyST Markdown notebook of the course to .ipynb for nbval.

nbval reads .ipynb only, and the sources are MyST Markdown with a jupytext
header. Usage: python tools/to_ipynb.py DEST  (writes DEST/<folder>__<name>.ipynb)
"""

from __future__ import annotations

import sys
from pathlib import Path

import jupytext

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ("chapters", "exercises")


def sources():
    for folder in FOLDERS:
        for path in sorted((ROOT / folder).glob("*.md")):
            head = path.read_text(encoding="utf-8")[:400]
            if "jupytext:" in head and "kernelspec:" in head:
                yield folder, path


def main(dest: Path) -> int:
    dest.mkdir(parents=True, exist_ok=True)
    count = 0
    for folder, path in sources():
        nb = jupytext.read(path)
        jupytext.write(nb, dest / f"{folder}__{path.stem}.ipynb")
        count += 1
    print(f"to_ipynb: wrote {count} notebooks to {dest}")
    if count == 0:
        print("to_ipynb: no notebooks found", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
