"""_ext/library_deps.py: a library change reaches the built pages; no change executes nothing.

A scratch book (the book's execution settings, the extension, one notebook page
that prints a value of a scratch library, one plain page) is built four times
with ``jupyter-book build``: first build; library value changed (the page shows
the new value); value restored and the notebooks pre-run by tools/preexecute.py
(the old value again, executed by the pre-run, none by the build); no change at
all (Sphinx reads nothing and no notebook is executed).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
JB = Path(sys.executable).parent / "jupyter-book"

CONFIG = """\
title: scratch
only_build_toc_files: true
exclude_patterns: [_build, scratchlib]
execute:
  execute_notebooks: cache
  timeout: 120
  allow_errors: false
sphinx:
  local_extensions:
    library_deps: _ext
  config:
    course_library_paths: [scratchlib]
    nb_execution_raise_on_error: true
"""
TOC = "format: jb-book\nroot: index\nchapters:\n  - file: page\n"
INDEX = "# Scratch\n\nA plain page: it does not use the library.\n"
PAGE = """\
---
jupytext:
  text_representation:
    extension: .md
    format_name: myst
    format_version: 0.13
kernelspec:
  display_name: Python 3
  language: python
  name: python3
---

# A page that prints a library value

```{code-cell} ipython3
import scratchvalue
print(f"library value = {scratchvalue.VALUE}")
```
"""


def _book(tmp_path: Path) -> Path:
    book = tmp_path / "book"
    (book / "_ext").mkdir(parents=True)
    for name in ("library_deps.py", "notebook_pages.py"):
        shutil.copy2(ROOT / "_ext" / name, book / "_ext" / name)
    (book / "_config.yml").write_text(CONFIG)
    (book / "_toc.yml").write_text(TOC)
    (book / "index.md").write_text(INDEX)
    (book / "page.md").write_text(PAGE)
    (book / "scratchlib").mkdir()
    (book / "scratchlib" / "scratchvalue.py").write_text("VALUE = 1111.25\n")
    return book


def _build(book: Path) -> str:
    env = dict(os.environ, PYTHONPATH=str(book / "scratchlib"))   # the kernel imports the scratch library
    done = subprocess.run([str(JB), "build", str(book), "-W", "-n", "--keep-going"], cwd=book, env=env,
                          capture_output=True, text=True, timeout=600)
    log = done.stdout + done.stderr
    assert done.returncode == 0, log[-4000:]
    return log


def _shown(book: Path) -> str:
    html = (book / "_build" / "html" / "page.html").read_text(encoding="utf-8")
    m = re.search(r"library value = ([0-9.]+)", html)
    assert m, "the page shows no library value"
    return m.group(1)


def _executed(log: str) -> int:
    return len(re.findall(r"Executing notebook", log))


def test_a_new_library_file_changes_the_hash_and_caches_are_stamped(tmp_path):
    sys.path.insert(0, str(ROOT / "_ext"))
    try:
        import library_deps
    finally:
        sys.path.remove(str(ROOT / "_ext"))
    lib = tmp_path / "lib"
    lib.mkdir()
    (lib / "a.py").write_text("A = 1\n")
    before = library_deps.library_hash([lib], tmp_path)
    (lib / "b.py").write_text("")
    assert library_deps.library_hash([lib], tmp_path) != before
    (lib / "__pycache__").mkdir()
    (lib / "__pycache__" / "a.cpython-311.pyc").write_bytes(b"\0")   # byte code is not the library
    assert library_deps.library_hash([lib], tmp_path) == library_deps.library_hash([lib / "a.py", lib / "b.py"],
                                                                                   tmp_path)


def test_which_pages_use_the_library(tmp_path):
    sys.path.insert(0, str(ROOT / "_ext"))
    try:
        import library_deps
    finally:
        sys.path.remove(str(ROOT / "_ext"))
    plain = tmp_path / "plain.md"
    plain.write_text("# Plain\n\nNo code, no live view.\n")
    live = tmp_path / "live.md"
    live.write_text("# Live\n\n```{live-view} planar_explorer\n:robot: planar_2r\n```\n")
    notebook = tmp_path / "nb.md"
    notebook.write_text(PAGE)
    assert not library_deps.uses_library(plain)
    assert library_deps.uses_library(live)
    assert library_deps.uses_library(notebook)
    assert library_deps.uses_library(ROOT / "chapters" / "02_space_jacobian.md")


def _preexecute(book: Path) -> str:
    env = dict(os.environ, PYTHONPATH=str(book / "scratchlib"))
    done = subprocess.run([sys.executable, "-m", "tools.preexecute", "--root", str(book), "--jobs", "2"], cwd=ROOT,
                          env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, (done.stdout + done.stderr)[-4000:]
    return done.stdout


@pytest.mark.skipif(not JB.exists(), reason="jupyter-book is not installed in this environment")
def test_library_change_reaches_the_page_with_or_without_the_prerun_and_no_change_executes_nothing(tmp_path):
    """One scratch book, built four times and pre-run (tools/preexecute.py, make book's first step) twice:
    a library change alone makes Sphinx execute the page again and show the new value; the pre-run stores each
    notebook under the key the build looks up, so the build then executes nothing and shows the value; with
    no change at all the build reads nothing and executes nothing."""
    book = _book(tmp_path)
    lib = book / "scratchlib" / "scratchvalue.py"

    log = _build(book)                            # no pre-run: Sphinx executes the page
    assert _shown(book) == "1111.25" and _executed(log) == 1, log[-3000:]

    lib.write_text("VALUE = 2222.5\n")           # the library changes, the page's source does not
    log = _build(book)
    assert "library_deps: the library changed; 1 pages that use it are read again" in log, log[-3000:]
    assert _executed(log) == 1, log[-3000:]
    assert _shown(book) == "2222.5"

    lib.write_text("VALUE = 1111.25\n")          # restored, and pre-run: the build finds the page in the cache
    out = _preexecute(book)
    assert "the library changed" in out and "preexecute: 1 of 1 notebooks cached" in out, out
    log = _build(book)
    assert "library_deps: the library changed; 1 pages that use it are read again" in log, log[-3000:]
    assert _executed(log) == 0 and "Using cached notebook" in log, log[-3000:]
    assert _shown(book) == "1111.25"
    assert "every notebook of the book is in the cache" in _preexecute(book)

    log = _build(book)                            # nothing changed: nothing read, nothing executed
    assert re.search(r"updating environment: .*0 added, 0 changed, 0 removed", log), log[-3000:]
    assert _executed(log) == 0 and "library_deps" not in log, log[-3000:]
    assert _shown(book) == "1111.25"
