"""Every chapter and exercise page offers its notebook (``.ipynb``) in the download menu; launch buttons.

A local Sphinx extension (``_config.yml``: ``sphinx: local_extensions``).

**Downloads.** For every notebook page in ``chapters/`` and ``exercises/``
(:func:`notebook_pages.is_notebook`), the page's download menu gets an
``.ipynb`` entry (sphinx-book-theme shows one when the page context names
``ipynb_source``), and the build writes that file into ``_sources/``, made
from the page's MyST source (jupytext):

* a chapter: the chapter as a notebook, no outputs, MyST markup turned into
  plain Markdown, live views as widget cells (:mod:`reader_notebooks`);
* an exercise page: the student notebook, without solutions
  (``tools/make_exercises.py``: the same file as ``exercises/student/``).

Both start with the install cell of :mod:`reader_notebooks`, which installs
the course from the repository set in ``_config.yml`` (``repository.url``)
when the course is missing, and otherwise does nothing.

**Launch buttons.** jupyter-book 1.0.4 turns ``launch_buttons:`` and
``repository:`` of ``_config.yml`` into ``html_theme_options``, but the
book's ``sphinx: config: html_theme_options`` replaces that whole dict, so
those settings never reached the theme. :func:`launch_settings` puts them back
from ``_config.yml``; while ``repository.url`` is empty it leaves every launch
button out (a launch button needs a repository to start from).
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path
from typing import Any

import nbformat
from notebook_pages import is_notebook
from reader_notebooks import book_settings, course_requirement, reader_notebook
from sphinx.application import Sphinx
from sphinx.config import Config

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ("chapters", "exercises")
EXERCISES = "exercises"
#: the launch services sphinx-book-theme knows (the keys of launch_buttons that name a URL)
LAUNCH_URLS = ("binderhub_url", "jupyterhub_url", "colab_url", "deepnote_url", "jupyterlite_url")


def theme_launch_options(settings: dict[str, Any]) -> dict[str, Any]:
    """The html_theme_options that carry launch buttons and the repository, as jupyter-book would set them.

    >>> opts = theme_launch_options({"launch_buttons": {"binderhub_url": "https://mybinder.org"}, "repository": {}})
    >>> opts["launch_buttons"], opts["repository_url"]
    ({}, '')
    """
    repo = settings.get("repository", {})
    url = str(repo.get("url") or "").strip()
    launch = dict(settings.get("launch_buttons", {})) if url else {}  # no repository: no launch button
    html = settings.get("html", {})
    return {
        "launch_buttons": launch,
        "repository_url": url,
        "repository_branch": str(repo.get("branch") or "main"),
        "path_to_docs": str(repo.get("path_to_book") or ""),
        "use_repository_button": bool(html.get("use_repository_button")) and bool(url),
        "use_issues_button": bool(html.get("use_issues_button")) and bool(url),
        "use_edit_page_button": bool(html.get("use_edit_page_button")) and bool(url),
    }


def launch_settings(app: Sphinx, config: Config) -> None:
    """Give the theme the launch buttons and repository of _config.yml (see the module docstring)."""
    options = dict(config.html_theme_options or {})
    options.update(theme_launch_options(book_settings(Path(app.confdir))))
    config.html_theme_options = options


def _course(app: Sphinx) -> str | None:
    opts = app.config.html_theme_options or {}
    return course_requirement(str(opts.get("repository_url") or ""), str(opts.get("repository_branch") or "main"),
                              str(opts.get("path_to_docs") or ""))


def _download_pages(app: Sphinx) -> dict[str, Path]:
    """docname -> source path of every page that offers a notebook."""
    out: dict[str, Path] = {}
    for docname in sorted(app.env.found_docs):
        if docname.split("/")[0] not in FOLDERS:
            continue
        path = Path(app.env.doc2path(docname))
        if is_notebook(path):
            out[docname] = path
    return out


def name_the_notebook(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any) -> None:
    """Before the theme builds the download menu (priority 501): this page's notebook is ``_sources/<page>.ipynb``."""
    if app.builder.name != "html" or pagename.split("/")[0] not in FOLDERS:
        return
    if is_notebook(Path(app.env.doc2path(pagename))):
        context["ipynb_source"] = pagename + ".ipynb"


def notebook_for(docname: str, path: Path, course: str | None) -> nbformat.NotebookNode:
    """The notebook a reader downloads from the page ``docname``."""
    if docname.split("/")[0] == EXERCISES:
        if str(ROOT) not in sys.path:
            sys.path.insert(0, str(ROOT))
        make_exercises = importlib.import_module("tools.make_exercises")  # (by name: tools/ is not on mypy's path)
        student: nbformat.NotebookNode = make_exercises.student_notebook(path, course=course)
        return student
    return reader_notebook(path, course)


def write_notebooks(app: Sphinx, exception: Exception | None) -> None:
    """After the build (after the theme, which copies an executed notebook there when a launch button is
    set), write every page's notebook into ``_sources``."""
    if exception is not None or app.builder.name != "html":
        return
    course = _course(app)
    sources = Path(app.outdir) / "_sources"
    for docname, path in _download_pages(app).items():
        dest = sources / f"{docname}.ipynb"
        dest.parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(notebook_for(docname, path, course), dest)


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("config-inited", launch_settings)
    app.connect("html-page-context", name_the_notebook, priority=500)
    app.connect("build-finished", write_notebooks)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
