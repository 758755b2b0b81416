"""Which source files are notebooks, and which pages get a lecture deck: the one rule.

A file is a notebook when the book reads it as one: myst-nb's own test
(:func:`myst_nb.core.read.create_nb_reader`), i.e. an ``.ipynb`` or a MyST
Markdown file whose front matter names jupytext's ``myst`` format. A notebook
page in one of :data:`DECK_FOLDERS` gets a reveal.js deck (tools/build_slides.py)
and a link to it on its page (``slides_link.py``); exercise notebooks and the
plain-Markdown root page get none.

Used by the Sphinx extensions of this folder (Sphinx puts ``_ext`` on
``sys.path``) and by the tools (``from _ext.notebook_pages import ...``, with
the repository root on the path: ``python -m tools.<name>``). No Sphinx import.

Both ``tools/`` and ``_ext/`` read a MyST notebook with :func:`read`
(jupytext, as JupyterLab and the slide builder do).
"""

from __future__ import annotations

from pathlib import Path

import jupytext
from myst_nb.core.config import NbParserConfig
from myst_nb.core.read import create_nb_reader
from myst_parser.config.main import MdParserConfig
from nbformat import NotebookNode

#: only notebook pages in these folders are lectures (exercises/ holds student notebooks)
DECK_FOLDERS: tuple[str, ...] = ("chapters",)


def is_notebook(path: Path) -> bool:
    """True if the book reads ``path`` as a notebook (myst-nb's rule).

    >>> is_notebook(Path(__file__))
    False
    """
    path = Path(path)
    if not path.is_file():
        return False
    text = path.read_text(encoding="utf-8") if path.suffix == ".md" else None
    return create_nb_reader(str(path), MdParserConfig(), NbParserConfig(), text) is not None


def in_deck_folder(relative: str | Path) -> bool:
    """True if a path relative to the book root (or a docname) is in a deck folder."""
    parts = Path(relative).parts
    return bool(parts) and parts[0] in DECK_FOLDERS


def has_deck(path: Path, root: Path) -> bool:
    """True if the page of ``path`` (inside the book folder ``root``) gets a lecture deck."""
    path = Path(path)
    return in_deck_folder(path.resolve().relative_to(Path(root).resolve())) and is_notebook(path)


def read(path: Path) -> NotebookNode:
    """The notebook of a source file (MyST Markdown or .ipynb), read by jupytext."""
    if not is_notebook(path):
        raise ValueError(f"{path} is not a notebook: expected an .ipynb or a MyST Markdown file "
                         "with a jupytext front matter (format_name: myst)")
    notebook: NotebookNode = jupytext.read(path)
    return notebook
