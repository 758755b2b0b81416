"""The ``.ipynb`` a reader downloads from a chapter page, made from its MyST source; and the install cell.

Every downloaded notebook (a chapter's, and the student notebook of an
exercise page, ``tools/make_exercises.py``) starts with :func:`install_cell`:
a code cell that looks for what the notebook imports and, only when something
is missing (on Colab, Binder, a fresh Python), installs it with pip, at the
versions the course was tested with (``constraints.txt``). Where everything is
installed it does nothing and needs no network. Offline with something
missing, pip fails and the cell stops with an error that says what is missing
and how to install it from a copy of the course.

A chapter's notebook (:func:`reader_notebook`) is the chapter with every cell
(the hidden checks too: they run and assert), no outputs, and the MyST markup
that a plain Jupyter shows as raw text turned into Markdown: theorems,
definitions and warnings become quoted paragraphs with a bold title, roles
become their text, labels and slide blocks go, and a ``{live-view}`` becomes a
code cell that shows the same view as a Jupyter widget
(:mod:`jacobians.widgets.live`).

No Sphinx import: used by ``_ext/notebook_downloads.py`` and by the tools.
"""

from __future__ import annotations

import ast
import json
import re
import sys
import warnings
from collections.abc import Iterable
from pathlib import Path

import jupytext
import nbformat
from nbformat import NotebookNode

ROOT = Path(__file__).resolve().parent.parent
INSTALL_TAG = "course-install"

#: import name -> pip name, for what a page may import that is not in the standard library
PIP_NAMES: dict[str, str] = {
    "numpy": "numpy", "scipy": "scipy", "sympy": "sympy", "matplotlib": "matplotlib", "IPython": "ipython",
    "ipywidgets": "ipywidgets", "anywidget": "anywidget", "modern_robotics": "modern_robotics",
    "pinocchio": "pin", "roboticstoolbox": "roboticstoolbox-python", "spatialmath": "spatialmath-python",
}
#: the course's own packages: installed together, as the distribution ``jacobians`` with these extras
COURSE_PACKAGES = ("jacobians", "course")
COURSE_EXTRAS = "course,widgets"


def _constraints() -> dict[str, str]:
    """Pinned versions of constraints.txt (name lower-cased, ``_`` as ``-``)."""
    out: dict[str, str] = {}
    path = ROOT / "constraints.txt"
    for line in path.read_text(encoding="utf-8").splitlines() if path.is_file() else []:
        m = re.match(r"^([A-Za-z0-9_.-]+)==([^\s;#]+)", line.strip())
        if m:
            out[m.group(1).lower().replace("_", "-")] = m.group(2)
    return out


def imported_modules(nb: NotebookNode) -> list[str]:
    """Top-level modules the notebook's code imports that pip installs (:data:`PIP_NAMES` or the course's)."""
    found: list[str] = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        source = "\n".join(line for line in cell.source.splitlines() if not line.lstrip().startswith(("%", "!")))
        try:
            with warnings.catch_warnings():  # (LaTeX in a plain string: an invalid escape warns, it is not ours)
                warnings.simplefilter("ignore")
                tree = ast.parse(source)
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module] if isinstance(node, ast.ImportFrom) and node.module and not node.level else [])
            for name in names:
                top = name.split(".")[0]
                if (top in PIP_NAMES or top in COURSE_PACKAGES) and top not in found:
                    found.append(top)
    return found


def course_requirement(repository_url: str = "", branch: str = "main", subdirectory: str = "") -> str | None:
    """The pip requirement of the course from its repository, or None when no repository is set."""
    url = repository_url.strip().rstrip("/")
    if not url:
        return None
    if url.endswith(".git"):
        url = url[:-4]
    tail = f"#subdirectory={subdirectory.strip('/')}" if subdirectory.strip("/") else ""
    return f"jacobians[{COURSE_EXTRAS}] @ git+{url}.git@{branch}{tail}"


def book_settings(confdir: Path = ROOT) -> dict[str, dict]:
    """``launch_buttons``, ``repository`` and ``html`` of the book's ``_config.yml`` (empty when absent)."""
    import yaml

    path = Path(confdir) / "_config.yml"
    data = yaml.safe_load(path.read_text(encoding="utf-8")) if path.is_file() else {}
    return {k: dict((data or {}).get(k) or {}) for k in ("launch_buttons", "repository", "html")}


def configured_course(confdir: Path = ROOT) -> str | None:
    """The course's pip requirement from ``repository`` of ``_config.yml``, or None while its url is empty."""
    repo = book_settings(confdir)["repository"]
    return course_requirement(str(repo.get("url") or ""), str(repo.get("branch") or "main"),
                              str(repo.get("path_to_book") or ""))


def install_cell(modules: Iterable[str], course: str | None) -> NotebookNode:
    """The first code cell: install what ``modules`` names when it is missing (see the module docstring)."""
    pins = _constraints()
    third = [m for m in modules if m in PIP_NAMES]
    wanted = {m: (f"{PIP_NAMES[m]}=={pins[PIP_NAMES[m].lower().replace('_', '-')]}"
                  if PIP_NAMES[m].lower().replace("_", "-") in pins else PIP_NAMES[m]) for m in third}
    hint = ('pip install "jacobians[student]" from the course\'s wheel or repository '
            '(see the book\'s "Start here" page), then restart the kernel')
    no_course = f"This notebook needs the course library: {hint}."
    failed = f" (offline?): {hint}."
    lines = [
        "# Set-up for a fresh Python (Colab, Binder, a new venv): installs what this notebook imports, only if",
        "# it is missing. Where the course is installed this cell does nothing and needs no network.",
        "import importlib.util, subprocess, sys",
        f"NEEDS = {json.dumps(wanted)}",
        "missing = [spec for module, spec in NEEDS.items() if importlib.util.find_spec(module) is None]",
    ]
    if course:
        lines.append(f"if importlib.util.find_spec('course') is None:\n    missing.append({course!r})")
    else:
        lines.append("if importlib.util.find_spec('course') is None:\n"
                     f"    raise ModuleNotFoundError({no_course!r})")
    lines += [
        "if missing:",
        "    print('Installing', ', '.join(missing))",
        "    done = subprocess.run([sys.executable, '-m', 'pip', 'install', '--quiet', '--retries', '1', *missing])",
        "    if done.returncode != 0:",
        f"        raise RuntimeError('pip could not install ' + ', '.join(missing) + {failed!r})",
        "    importlib.invalidate_caches()",
    ]
    cell: NotebookNode = nbformat.v4.new_code_cell("\n".join(lines))
    cell.metadata["tags"] = [INSTALL_TAG]
    return cell


# ---------------------------------------------------------------- MyST -> plain Markdown

_FENCE = re.compile(r"^(?P<fence>`{3,}|:{3,})\{(?P<name>[\w:-]+)\}[ \t]*(?P<arg>[^\n]*)\n"
                    r"(?P<body>.*?)^(?P=fence)[ \t]*$\n?", re.S | re.M)
_OPTION = re.compile(r"^:([\w-]+):[ \t]*(.*)$")
_ROLE = re.compile(r"\{(?:doc|ref|numref|prf:ref|eq|term)\}`([^`<]*?)(?:\s*<([^>]*)>)?`")
_MATH_ROLE = re.compile(r"\{math\}`([^`]*)`")
_LABEL = re.compile(r"^\([\w:-]+\)=[ \t]*\n?", re.M)
_DROP = {"slide", "slide-notes", "margin"}
_TITLES = {"prf:definition": "Definition", "prf:theorem": "Theorem", "prf:proposition": "Proposition",
           "prf:lemma": "Lemma", "prf:corollary": "Corollary", "prf:proof": "Proof", "prf:algorithm": "Algorithm",
           "prf:example": "Example", "prf:remark": "Remark", "exercise": "Exercise", "warning": "Warning",
           "note": "Note", "tip": "Tip", "important": "Important", "caution": "Caution", "hint": "Hint",
           "seealso": "See also", "admonition": ""}


_KINDS = {"def": "Definition", "thm": "Theorem", "prop": "Proposition", "lem": "Lemma", "cor": "Corollary",
          "alg": "Algorithm", "ex": "Exercise", "eq": "Equation", "fig": "Figure"}


def _role_text(m: re.Match[str]) -> str:
    """A cross-reference as words: its own text, else a chapter's name or a label read aloud."""
    text, target = m.group(1).strip(), m.group(2)
    if target:
        return text
    if "/" in text or text.startswith(("0", "1")):  # {doc}`../chapters/02_space_jacobian`
        return "the chapter *" + Path(text).stem.lstrip("0123456789_").replace("_", " ") + "*"
    label = re.fullmatch(r"ch(\d\d)-(\w+?)-([\w-]+)", text)
    if label:
        kind = _KINDS.get(label.group(2), "")
        name = label.group(3).replace("-", " ")
        return f"{kind + ' ' if kind else ''}*{name}* (chapter {int(label.group(1))})"
    return "*" + text.replace("-", " ") + "*"


def _split(body: str) -> tuple[dict[str, str], str]:
    options: dict[str, str] = {}
    lines = body.split("\n")
    i = 0
    if lines and lines[0].strip() == "---":  # a YAML options block
        end = lines.index("---", 1) if "---" in lines[1:] else 0
        for line in lines[1:end]:
            k, _, v = line.partition(":")
            options[k.strip()] = v.strip()
        i = end + 1
    while i < len(lines) and _OPTION.match(lines[i]):
        m = _OPTION.match(lines[i])
        assert m is not None
        options[m.group(1)] = m.group(2).strip()
        i += 1
    return options, "\n".join(lines[i:]).strip("\n")


def live_view_code(view: str, options: dict[str, str]) -> str:
    """The notebook code that shows a ``{live-view}`` as the same view in a Jupyter widget (its spec's)."""
    from jacobians.widgets.live import VIEWS

    if view not in VIEWS:
        raise ValueError(f"Expected a live view one of {', '.join(VIEWS)}, got {view!r}")
    spec = VIEWS[view]
    unknown = sorted(set(options) - set(spec.options))
    if unknown:
        raise ValueError(f"Expected options {', '.join(spec.options)} for {view}, got {unknown}")
    args = ", ".join(f"{k}={spec.options[k](text)!r}" for k, text in options.items())
    widget = spec.widget
    return f"from {widget.__module__} import {widget.__name__}\n{widget.__name__}({args})"


def plain_markdown(source: str) -> tuple[str, list[tuple[str, str]]]:
    """MyST Markdown as plain Markdown, and the live views it held (in order): (view, notebook code)."""
    views: list[tuple[str, str]] = []

    def block(m: re.Match[str]) -> str:
        name, arg = m.group("name"), m.group("arg").strip()
        options, body = _split(m.group("body"))
        if name in _DROP:
            return ""
        if name == "live-view":
            # the caption and name are the book's figure around the view, not options of its model
            caption = options.pop("caption", "")
            options.pop("name", None)
            views.append((arg, live_view_code(arg, options)))
            lead = f"*{caption}*\n\n" if caption else ""
            return f"{lead}*A live view ({arg.replace('_', ' ')}): the code cell below shows it.*\n"
        if name == "solution-start":
            return "**Solution.**\n"
        if name == "solution-end":
            return ""
        if name in ("math", "prf:math"):
            return f"$$\n{body}\n$$\n"
        if name in ("figure", "image"):
            return f"*{body.strip()}*\n" if body.strip() else ""
        head = _TITLES.get(name, name.split(":")[-1].replace("-", " ").capitalize())
        title = f"**{head}{' (' + arg + ')' if arg and head else arg if arg else ''}.**"
        inner = plain_markdown(body)
        views.extend(inner[1])
        quoted = "\n".join(("> " + line) if line.strip() else ">" for line in (title + " " + inner[0]).split("\n"))
        return quoted + "\n"

    out = source
    for _ in range(4):  # nested blocks: the outer fence is longer, so each pass takes the innermost first
        new = _FENCE.sub(block, out)
        if new == out:
            break
        out = new
    out = _ROLE.sub(_role_text, out)
    out = _MATH_ROLE.sub(lambda m: f"${m.group(1)}$", out)
    out = _LABEL.sub("", out)
    out = re.sub(r"\n{3,}", "\n\n", out)
    return out.strip("\n"), views


def view_class(view: str) -> str:
    """The name of the widget class that shows a live view in a notebook (its spec's ``widget``)."""
    from jacobians.widgets.live import VIEWS

    return VIEWS[view].widget.__name__ if view in VIEWS else "LiveView"


def displayed_widgets(nb: NotebookNode) -> set[str]:
    """Classes of the widgets the notebook's code already displays (``w = Class(...)`` ... ``w`` last)."""
    shown: set[str] = set()
    for cell in nb.cells:
        lines = [line for line in cell.source.splitlines() if line.strip()] if cell.cell_type == "code" else []
        if lines and re.fullmatch(r"[A-Za-z_]\w*", lines[-1].strip()):
            m = re.search(rf"^{lines[-1].strip()}\s*=\s*(\w+)\(", cell.source, re.M)
            if m:
                shown.add(m.group(1))
    return shown


def reader_notebook(path: Path, course: str | None) -> NotebookNode:
    """A chapter as a notebook for readers: see the module docstring."""
    nb: NotebookNode = jupytext.read(path)
    shown = displayed_widgets(nb)
    cells: list[NotebookNode] = []
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None
            cells.append(cell)
        elif cell.cell_type == "markdown":
            text, views = plain_markdown(cell.source)
            if text.strip():
                cell.source = text
                cells.append(cell)
            cells.extend(nbformat.v4.new_code_cell(code) for view, code in views
                         if view_class(view) not in shown - {"LiveView"})
        else:
            cells.append(cell)
    nb.cells = [install_cell(imported_modules(nb), course), *cells]
    nb.metadata.pop("mystnb", None)
    jt = nb.metadata.get("jupytext")
    if isinstance(jt, dict):  # a plain .ipynb: no pairing with the source
        jt.pop("text_representation", None)
        if not jt:
            nb.metadata.pop("jupytext")
    for i, cell in enumerate(nb.cells):  # stable, valid ids (jupytext leaves some out)
        cell["id"] = f"cell-{i}"
    nbformat.validate(nb)
    return nb


if __name__ == "__main__":  # python _ext/reader_notebooks.py chapters/02_space_jacobian.md out.ipynb
    nbformat.write(reader_notebook(Path(sys.argv[1]), None), sys.argv[2])
