"""The exercise pages link to their student notebooks; the link itself never reaches the student version."""

from pathlib import Path

import jupytext

ROOT = Path(__file__).resolve().parent.parent


def _tool():
    from tools import make_exercises
    return make_exercises


def test_every_exercise_page_links_its_student_notebook_and_the_link_is_book_only():
    tool = _tool()
    sources = sorted((ROOT / "exercises").glob("[0-9][0-9]_*.md"))
    assert len(sources) == 12
    for path in sources:
        nb = jupytext.read(path)
        link_cells = [c for c in nb.cells if f'href="student/{path.stem}.ipynb"' in c.source]
        assert len(link_cells) == 1, path.name
        assert "book-only" in link_cells[0].metadata.get("tags", [])
        student = tool.student_notebook(path)
        assert not any("student/" + path.stem in c.source for c in student.cells)


def test_every_exercise_has_a_book_only_line_saying_where_the_answer_goes_and_the_student_version_drops_it():
    tool = _tool()
    for path in sorted((ROOT / "exercises").glob("[0-9][0-9]_*.md")):
        nb = jupytext.read(path)
        n_exercises = sum("exercises.load(" in c.source for c in nb.cells if c.cell_type == "code")
        lines = [c for c in nb.cells if c.cell_type == "markdown" and "In the student notebook" in c.source]
        assert len(lines) == n_exercises >= 4, path.name
        assert all(c.metadata.get("tags") == ["book-only"] for c in lines), path.name
        student = tool.student_notebook(path)
        assert not any("In the student notebook" in c.source for c in student.cells), path.name
        # every answer cell and check cell reaches the student, without the book's remove-cell tag
        kept = [c for c in student.cells if c.cell_type == "code" and ("answer = None" in c.source
                                                                       or "exercises.check(" in c.source)]
        assert len(kept) == 2 * n_exercises, path.name
        assert not any("remove-cell" in c.metadata.get("tags", []) for c in student.cells), path.name
