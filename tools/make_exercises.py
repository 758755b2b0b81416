"""Write the student exercise notebooks: no solutions, no outputs.

The sources exercises/NN_name.md are the instructor versions (MyST Markdown
notebooks whose solution cells carry the tag ``solution``). Each exercise is,
in order::

    exercises.load("chNN_exK", seed=SEED)     statement, shown in book and notebook
    (book-only Markdown line)                 "in the notebook, your answer goes here"
    answer = None  # your answer here         tag remove-cell: hidden in the book
    (solution-start ... solution cells ...)   tag solution
    exercises.check("chNN_exK", answer, ...)  tag solution: the verdict on the
                                              solution, last cell of the dropdown
    (solution-end)                            tag solution
    exercises.check("chNN_exK", answer, ...)  tag remove-cell: the student's check
    assert _fb.correct                        tags solution, remove-cell: CI only

For each source this script writes DEST/NN_name.ipynb with

* every cell tagged ``solution`` removed (the dropdown's opening and closing
  Markdown cells, the solution code, the verdict on the solution, the
  instructor-only asserts), and every ``book-only`` cell;
* the answer cell and the check cell kept (their ``remove-cell`` tag only
  hides them in the book, and is dropped here), so each exercise reads:
  statement, answer, check;
* no outputs and no execution counts;
* the MyST-only markup a plain Jupyter front end shows as raw text turned into
  plain Markdown: the ``{exercise}`` block becomes a quoted task, ``{doc}`` and
  ``{ref}`` roles become plain text.

Usage: python -m tools.make_exercises DEST   (``make exercises`` uses _build/exercises)
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import jupytext
import nbformat
from _ext.reader_notebooks import configured_course, imported_modules, install_cell

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ROOT / "exercises"
SOLUTION_TAG = "solution"
BOOK_ONLY_TAG = "book-only"  # cells for the web page only (the link to this very notebook)
BOOK_HIDDEN_TAG = "remove-cell"  # the answer and check cells: run but not shown in the book

_EXERCISE = re.compile(r"```\{exercise\}[^\n]*\n((?::[^\n]*\n)*)(.*?)\n```", re.S)
_ROLE = re.compile(r"\{(?:doc|ref|numref|prf:ref)\}`([^`<]*?)(?:\s*<([^>]*)>)?`")
_LABEL = re.compile(r"^\([\w-]+\)=\s*$", re.M)


def _role_text(match: re.Match[str]) -> str:
    text, target = match.group(1).strip(), match.group(2)
    if target:  # {ref}`words <target>`
        return text
    name = Path(text).stem if "/" in text or text.startswith("..") else text
    return f"the chapter *{name.replace('_', ' ')}*" if "/chapters/" in text or text.startswith("../") else name


def _plain_markdown(source: str) -> str:
    source = _EXERCISE.sub(lambda m: "> **Task.** " + m.group(2).strip().replace("\n", "\n> "), source)
    source = _ROLE.sub(_role_text, source)
    source = _LABEL.sub("", source)
    return source.strip("\n")


def student_notebook(path: Path, course: str | None = None) -> nbformat.NotebookNode:
    """The student version of one source notebook.

    Its first code cell installs what the notebook imports when it is missing
    (``_ext/reader_notebooks.py``: the course from ``course``, a pip requirement,
    when given; else the cell says how to install it).
    """
    nb: nbformat.NotebookNode = jupytext.read(path)
    cells = []
    for cell in nb.cells:
        tags = cell.get("metadata", {}).get("tags", [])
        if SOLUTION_TAG in tags or BOOK_ONLY_TAG in tags:
            continue
        if BOOK_HIDDEN_TAG in tags:  # hidden in the book only; a plain tag-free cell for the student
            tags = [t for t in tags if t != BOOK_HIDDEN_TAG]
            if tags:
                cell.metadata["tags"] = tags
            else:
                cell.metadata.pop("tags")
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None
        elif cell.cell_type == "markdown":
            cell.source = _plain_markdown(cell.source)
            if not cell.source.strip():
                continue
        cells.append(cell)
    banner = nbformat.v4.new_markdown_cell(
        "*Student version, generated from `exercises/" + path.name + "` by `make exercises`. "
        "Run the cells from the top; put your answer in each `answer = ...` cell and run the check "
        "cell below it. First put your student ID between the quotes of `SEED = \"student-id\"` in the "
        "first code cell: it picks your own variant of every exercise, and your instructor grades that "
        "variant.*")
    needs = imported_modules(nbformat.v4.new_notebook(cells=cells))  # what the student version imports
    nb.cells = [banner, install_cell(needs, course)] + cells
    nb.metadata.pop("mystnb", None)
    jt = nb.metadata.get("jupytext")
    if isinstance(jt, dict):  # a plain .ipynb: no pairing with the source
        jt.pop("text_representation", None)
        if not jt:
            nb.metadata.pop("jupytext")
    return nb


_LOAD = re.compile(r'exercises\.load\("(\w+)", seed=SEED\)')

#: The set-up line that sets the student's seed; a grader finds it (with ``ast``) to regrade that variant.
SEED_LINE = 'SEED = "student-id"  # your student ID (any text): it picks your variant of every exercise'

_ANSWER = re.compile(r"^answer = None\b", re.M)


def exercise_cells(nb: nbformat.NotebookNode) -> dict[str, list[nbformat.NotebookNode]]:
    """The code cells of each exercise, by id: from its ``exercises.load`` cell to the next one."""
    out: dict[str, list] = {}
    current = None
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        if cell.source.strip().startswith("exercises.summary("):  # the progress cell ends the exercises
            current = None
            continue
        m = _LOAD.search(cell.source)
        if m:
            current = m.group(1)
            assert current not in out, f"exercise {current} is loaded twice"
            out[current] = []
        if current is not None:
            out[current].append(cell)
    return out


def check_student(nb: nbformat.NotebookNode) -> None:
    """Raise AssertionError if a solution or an output slipped through, or an exercise lost its
    answer cell or its check cell (each exercise: load, answer = None, check, in that order)."""
    for cell in nb.cells:
        assert SOLUTION_TAG not in cell.get("metadata", {}).get("tags", []), "a solution cell remains"
        if cell.cell_type == "code":
            assert not cell.get("outputs"), "a code cell has outputs"
            assert cell.get("execution_count") is None, "a code cell has an execution count"
        assert "solution-start" not in cell.source and "solution-end" not in cell.source, "solution markup remains"
    seed_cells = [c for c in nb.cells if c.cell_type == "code" and SEED_LINE in c.source.splitlines()]
    assert len(seed_cells) == 1, f"expected the set-up line {SEED_LINE!r} in exactly one code cell"
    by_id = exercise_cells(nb)
    assert by_id, "no exercise (no exercises.load cell)"
    for eid, cells in by_id.items():
        sources = [c.source.strip() for c in cells]
        assert len(cells) == 3, f"{eid}: expected 3 code cells (load, answer, check), got {len(cells)}: {sources}"
        one_answer = len(re.findall(r"^answer\s*=", sources[1], re.M)) == 1 and _ANSWER.search(sources[1])
        assert one_answer, f"{eid}: no answer cell: {sources[1]!r}"
        assert sources[2] == f'exercises.check("{eid}", answer, seed=SEED)', f"{eid}: no check cell: {sources[2]!r}"


def main(dest: Path) -> int:
    dest.mkdir(parents=True, exist_ok=True)
    paths = sorted(SOURCES.glob("[0-9][0-9]_*.md"))
    if not paths:
        print("make_exercises: no exercise sources found in", SOURCES, file=sys.stderr)
        return 1
    course = configured_course(ROOT)  # repository.url of _config.yml: where the install cell gets the course
    for path in paths:
        nb = student_notebook(path, course=course)
        check_student(nb)
        nbformat.validate(nb)
        nbformat.write(nb, dest / f"{path.stem}.ipynb")
    print(f"make_exercises: wrote {len(paths)} student notebooks to {dest}")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(Path(sys.argv[1])))
