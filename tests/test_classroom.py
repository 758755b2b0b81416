"""make grade's machinery on a class of made-up notebooks: right, wrong, half-done, broken JSON, empty,
endless loop, raising, writing outside its scratch folder, tampering with the checker; the gradebook row by row.

The class hands in the made-up chapter ``ch00`` (``tests/fixtures/classroom.py``: two numeric exercises, a symbolic
one and a code one), not a chapter of the course, so that changing the course's exercises changes no test here and
the other way round. The per-cell limit is 20 s: the endless loop is stopped, and the set-up cell finishes on a
loaded machine."""

from __future__ import annotations

import csv
import hashlib
import json
from pathlib import Path

import nbformat
import numpy as np
import pytest
import sympy as sp
from tests.fixtures import classroom
from tests.fixtures.classroom import CODE, IDS
from tests.fixtures.classroom import PAGE as CHAPTER
from tools.bench_grade import string_ids_supported, submission

from course import exercises
from course.classroom import answer_data
from course.classroom.grade import COLUMNS, Row, exercises_of, grade_class, student_id
from course.classroom.report import report_name
from course.classroom.sandbox import Limits

fixture_chapter = classroom.fixture_chapter  # (the made-up chapter in the catalogue, for this module's tests)
pytestmark = pytest.mark.usefixtures("fixture_chapter")

# The chapter the class hands in is the made-up one (CHAPTER, its page; IDS, its exercises in page order); CODE is
# its code exercise (a function returning zeros fails its first test).

#: The exercises a half-done notebook answers (bench_grade's "half": the first half of the page).
HALF = len(IDS) // 2
#: The per-cell limit of the class: it stops the endless loop, and must leave the set-up cell (numpy, sympy,
#: matplotlib and the course imported in a fresh sandbox) time to finish on a loaded shared machine too.
CELL = 20


def _id(k: int) -> str | int:
    return f"student-{k}" if string_ids_supported() else 100 + k


def _need_isolation() -> None:
    """Skip, with the reason, where make grade would refuse to grade (not root, no bubblewrap, no cgroups); fail
    where the machine has all that and the sandbox still does not work."""
    from course.classroom.sandbox import isolation

    if isolation().broken:
        pytest.fail(f"the grading sandbox does not work on a machine that has all it needs: {isolation().reason}")
    if not isolation().ok:
        pytest.skip(f"make grade cannot isolate notebooks here: {isolation().reason}")


def _with_cell(nb: nbformat.NotebookNode, index: int, source: str) -> nbformat.NotebookNode:
    """``nb`` with a code cell ``source`` inserted before its code cell ``index`` (0: the set-up cell), so that it
    becomes code cell ``index + 1`` counting from 1."""
    code = [i for i, c in enumerate(nb.cells) if c.cell_type == "code"]
    nb.cells.insert(code[index], nbformat.v4.new_code_cell(source))
    return nb


@pytest.fixture(scope="module")
def graded(tmp_path_factory: pytest.TempPathFactory, fixture_chapter) -> tuple[Path, list[Row], dict[str, str]]:
    _need_isolation()
    root = tmp_path_factory.mktemp("class") / "submissions"
    (root / "a" / "deep" / "folder").mkdir(parents=True)
    (root / "b").mkdir()
    (root / "reports").mkdir()
    (root / "reports" / "from-last-year.html").write_text("stale", encoding="utf-8")  # replaced by this run's
    write = nbformat.write
    write(submission(CHAPTER, _id(1), "right"), root / "a" / "right.ipynb")
    write(submission(CHAPTER, _id(2), "wrong"), root / "b" / "wrong.ipynb")
    write(submission(CHAPTER, _id(3), "half"), root / "a" / "deep" / "folder" / "half.ipynb")
    (root / "broken.ipynb").write_text('{"cells": [', encoding="utf-8")
    (root / "empty.ipynb").write_text("", encoding="utf-8")
    loop = _with_cell(submission(CHAPTER, _id(4), "right"), 3, "while True:\n    pass")
    write(loop, root / "loop.ipynb")
    raising = _with_cell(submission(CHAPTER, _id(5), "right"), 2, "1 / 0")
    write(raising, root / "raising.ipynb")
    target = root / "b" / "wrong.ipynb"
    outside = _with_cell(submission(CHAPTER, _id(6), "right"), 1,
                         f"try:\n    open({str(target)!r}, 'w').write('gone')\nexcept OSError:\n    pass\n"
                         f"try:\n    import subprocess\n    subprocess.run(['rm', {str(target)!r}])\n"
                         "except OSError:\n    pass\n"
                         f"open({str(root / 'gradebook.csv')!r}, 'w').write('forged')")
    write(outside, root / "outside.ipynb")
    # a student who replaces the checker by one that always says correct, then gives wrong answers: every
    # exercise's check (the method that course.exercises.check calls) is made to accept anything
    cheat = submission(CHAPTER, _id(7), "wrong")
    cheat = _with_cell(cheat, 1, "from jacobians.grading import Exercise, Feedback\n"
                                 "Exercise.check = lambda self, a: Feedback(True, 'fine', 'correct')")
    write(cheat, root / "cheat.ipynb")
    before = {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in root.rglob("*.ipynb")}
    rows = grade_class(root, workers=2, limits=Limits(cell_timeout=CELL, notebook_timeout=200))
    return root, rows, before


def _rows(rows: list[Row], notebook: str) -> list[Row]:
    return [r for r in rows if r.notebook == notebook]


def _exercise_rows(rows: list[Row], notebook: str) -> dict[str, Row]:
    return {r.exercise: r for r in _rows(rows, notebook) if r.exercise != "(notebook)"}


def test_the_gradebook_file_is_the_rows_returned(graded):
    root, rows, _ = graded
    with open(root / "gradebook.csv", newline="", encoding="utf-8") as f:
        table = list(csv.reader(f))
    assert tuple(table[0]) == COLUMNS
    assert [Row(*r) for r in table[1:]] == rows
    assert {r.notebook for r in rows} == {"a/right.ipynb", "b/wrong.ipynb", "a/deep/folder/half.ipynb",
                                          "broken.ipynb", "empty.ipynb", "loop.ipynb", "raising.ipynb",
                                          "outside.ipynb", "cheat.ipynb"}


def test_right_notebook_every_exercise_right_and_no_note(graded):
    _, rows, _ = graded
    assert [r.exercise for r in _rows(rows, "a/right.ipynb")] == IDS
    for r in _rows(rows, "a/right.ipynb"):
        assert (r.student, r.seed, r.correct) == (str(_id(1)), str(_id(1)), "1"), r


def test_wrong_notebook_every_exercise_wrong_with_the_checkers_message(graded):
    _, rows, _ = graded
    got = _exercise_rows(rows, "b/wrong.ipynb")
    assert list(got) == IDS
    for r in got.values():
        assert r.correct == "0" and r.student == str(_id(2)), r
        assert r.message.startswith("wrong: "), r.message
    assert "On test 1 (" in got[CODE].message  # the function (zeros) fails on the first random input


def test_half_done_notebook_first_half_right_rest_not_attempted(graded):
    _, rows, _ = graded
    got = _exercise_rows(rows, "a/deep/folder/half.ipynb")
    assert [got[e].correct for e in IDS] == ["1"] * HALF + ["0"] * (len(IDS) - HALF)
    for eid in IDS[HALF:]:  # answer = None was checked: the checker's "empty" verdict
        assert got[eid].message.startswith("not attempted: "), got[eid]


def test_broken_and_empty_notebooks_get_one_row_each_and_nothing_runs(graded):
    _, rows, _ = graded
    (broken,) = _rows(rows, "broken.ipynb")
    assert (broken.exercise, broken.correct) == ("(notebook)", "")
    assert "not valid JSON (line 1, column 12)" in broken.message and "nothing was run" in broken.message
    (empty,) = _rows(rows, "empty.ipynb")
    assert "empty file" in empty.message


def test_endless_loop_is_stopped_and_the_other_cells_still_count(graded):
    _, rows, _ = graded
    notes = [r.message for r in _rows(rows, "loop.ipynb") if r.exercise == "(notebook)"]
    assert notes == [f"code cell 4 was stopped after {CELL} s (an endless loop?)"]  # (code cells counted from 1)
    assert [r.correct for r in _exercise_rows(rows, "loop.ipynb").values()] == ["1"] * len(IDS)


def test_raising_cell_is_named_and_the_run_goes_on(graded):
    _, rows, _ = graded
    notes = [r.message for r in _rows(rows, "raising.ipynb") if r.exercise == "(notebook)"]
    assert notes == ["code cell 3 raised ZeroDivisionError: division by zero"]
    assert [r.correct for r in _exercise_rows(rows, "raising.ipynb").values()] == ["1"] * len(IDS)


def test_writing_outside_is_refused_reported_and_changes_nothing(graded):
    root, rows, before = graded
    notes = [r.message for r in _rows(rows, "outside.ipynb") if r.exercise == "(notebook)"]
    assert any("refused" in m and "wrong.ipynb" in m for m in notes), notes
    assert any("refused" in m and "gradebook.csv" in m for m in notes), notes
    assert any("refused: starting a program (subprocess.Popen)" in m for m in notes), notes
    after = {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in root.rglob("*.ipynb")}
    assert after == before
    assert not [r for r in rows if r.exercise == "(submissions)"]  # the tree hash saw no change
    assert (root / "gradebook.csv").read_text(encoding="utf-8").startswith("student,notebook")


def test_a_replaced_checker_does_not_change_the_grade(graded):
    _, rows, _ = graded
    got = _exercise_rows(rows, "cheat.ipynb")
    assert [r.correct for r in got.values()] == ["0"] * len(IDS)
    for r in got.values():
        assert "The notebook's own check said correct" in r.message


def test_one_html_report_per_student(graded):
    root, rows, _ = graded
    pages = sorted(p.name for p in (root / "reports").iterdir())
    students = {r.student for r in rows}
    assert pages == sorted(report_name(s) for s in students)
    page = (root / "reports" / report_name(str(_id(1)))).read_text(encoding="utf-8")
    assert f"{len(IDS)} of {len(IDS)} exercises right" in page and CODE in page
    assert "http" not in page.replace('lang="en"', "")  # nothing loaded from the network
    loop = (root / "reports" / report_name(str(_id(4)))).read_text(encoding="utf-8")
    assert f"code cell 4 was stopped after {CELL} s" in loop


# --------------------------------------------------------------------------- reading notebooks, no execution
def test_student_id_is_read_without_running_anything():
    assert student_id(['import os\nSEED = "s123"  # your student ID (any text): it picks your variant']) == "s123"
    assert student_id(["%matplotlib inline\nSEED = 'x'"]) == "x"
    assert student_id(['SEED = int(os.environ.get("JACOBIANS_SEED", "0"))']) == 0
    assert student_id(["SEED = 12"]) == 12
    assert student_id(["SEED = __import__('os').system('echo hi')"]) is None
    assert student_id(["x = 1", "def f(:"]) is None
    first, other = IDS[0], IDS[-1]
    assert exercises_of([f'ex1 = exercises.load("{first}", seed=SEED)', f"exercises.load('{other}')",
                         f'exercises.load("{first}")']) == [first, other]


# --------------------------------------------------------------------------- the codec
@pytest.mark.parametrize("value", [
    None, True, 3, -2.5, float("inf"), 1 + 2j, "text", [1, [2.0, None]], (1, 2), {"a": 1},
    np.arange(6.0).reshape(2, 3), np.array([1, 2], dtype=np.int64), np.array([True, False]),
])
def test_plain_answers_round_trip(value):
    back = answer_data.decode(answer_data.encode(value))
    if isinstance(value, np.ndarray):
        assert back.dtype.kind == value.dtype.kind and np.array_equal(back, value)
    else:
        assert back == value and type(back) is type(value)


def test_sympy_answers_round_trip_with_their_types():
    t1, l1 = sp.symbols("theta1 l1", real=True)
    for value in [sp.Matrix([[0, l1 * sp.sin(t1)], [1, -l1 * sp.cos(t1)]]), sp.ImmutableMatrix([[sp.pi / 2]]),
                  sp.Array([t1, 2 * t1]), sp.sqrt(2) * sp.atan2(t1, l1) + sp.Rational(1, 3), sp.Float(0.125) * t1]:
        back = answer_data.decode(answer_data.encode(value))
        assert type(back) is type(value) and back == value


def test_malformed_data_never_evaluates():
    assert isinstance(answer_data.decode({"t": "sympy", "v": ["F", "__import__", [["Integer", "1"]]]}), answer_data.Opaque)
    assert isinstance(answer_data.decode({"t": "nope"}), answer_data.Opaque)
    assert isinstance(answer_data.decode("not a dict"), answer_data.Opaque)
    assert isinstance(answer_data.decode(answer_data.encode(object())), answer_data.Opaque)


def test_every_reference_answer_survives_the_codec_and_is_accepted_again():
    for eid in exercises.exercise_ids():
        ex = exercises.load(eid, seed=3)
        if ex.kind == "function":
            continue  # graded through the sandbox in the class above
        back = answer_data.decode(json.loads(json.dumps(answer_data.encode(ex.solution()))))
        assert exercises.check(eid, back, seed=3).correct, eid


# --------------------------------------------------------------------------- a student's own progress
def test_progress_summary_counts_right_tried_untouched():
    from course.exercises import _progress

    _progress.reset()
    try:
        one, two, three, *rest = IDS
        chapter = one.split("_")[0]
        exercises.check(one, exercises.load(one, seed=5).solution(), seed=5)
        exercises.check(two, [[1, 2], [3, 4]], seed=5)
        exercises.check(three, None, seed=5)  # "no answer yet" is not an attempt
        s = exercises.summary(chapter)
        assert (s.right, s.tried, s.untouched) == ([one], [two], [three, *rest])
        assert str(s).splitlines()[0] == (f"Your progress in {chapter}: 1 of {len(IDS)} right, 1 tried but not "
                                          f"right yet, {len(IDS) - 2} untouched.")
        assert ", ".join([three, *rest]) in s._repr_html_()
        exercises.check(two, exercises.load(two, seed=5).solution(), seed=5)
        assert exercises.summary(chapter).right == [one, two]
        with pytest.raises(ValueError, match="ch99"):
            exercises.summary("ch99")
    finally:
        _progress.reset()


def test_every_exercise_notebook_ends_with_the_progress_cell():
    from tools.make_exercises import SOURCES, student_notebook

    for path in sorted(SOURCES.glob("[0-9][0-9]_*.md")):
        nb = student_notebook(path)
        last = nb.cells[-1]
        chapter = "ch" + path.name[:2]
        assert last.cell_type == "code" and f'exercises.summary("{chapter}")' in last.source, path.name


# --------------------------------------------------------------------------- the instructor's page
def test_the_teaching_page_counts_the_exercises_of_each_chapter_from_the_catalogue():
    """Each week's row asks the catalogue ({exercise-count}`NN`, _ext/exercise_checks) for its chapter's count,
    whose kinds add up to the chapter's exercises; a chapter without exercises is an error, not a zero."""
    import re

    from _ext.exercise_checks import count_text

    text = (Path(__file__).resolve().parent.parent / "chapters" / "teaching.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| \d+ \| .*?exercises/(\d\d)_\w+` \(\{exercise-count\}`(\d\d)`\) \|$", text, re.M)
    assert [r[0] for r in rows] == [r[1] for r in rows] == [f"{k:02d}" for k in range(1, 13)]
    for chapter, _ in rows:
        ids = [i for i in exercises.exercise_ids() if i.startswith(f"ch{chapter}_")]
        total, kinds = count_text(int(chapter)).split(": ")
        said = {kind: int(n) for n, kind in (part.split() for part in kinds.split(", "))}
        assert int(total) == len(ids) == sum(said.values()) and set(said) <= {"numeric", "symbolic", "code"}
        assert said.get("code", 0) == sum(exercises.load(i, seed=0).kind == "function" for i in ids)
    assert count_text(2).startswith(f"{len([i for i in exercises.exercise_ids() if i.startswith('ch02_')])}: ")
    with pytest.raises(KeyError, match="chapter 99"):
        count_text(99)


# --------------------------------------------------------------------------- a function answer, in the sandbox
_STUDENT_CODE = '''import numpy as np
SCALE = 2.0


def helper(x):
    return SCALE * np.asarray(x, dtype=float)


def my_fn(x):
    return helper(x) + 1


def bad(x):
    return 1 / 0


def slow(x):
    while True:
        pass
'''


@pytest.fixture()
def student_functions(tmp_path):
    _need_isolation()
    import tempfile

    path = tmp_path / "cell.py"
    path.write_text(_STUDENT_CODE, encoding="utf-8")
    ns = {"__name__": "__main__"}
    exec(compile(_STUDENT_CODE, str(path), "exec"), ns)  # as a notebook cell defines them (module __main__)
    parent = Path(tempfile.mkdtemp(prefix="sandbox-test-"))
    parent.chmod(0o711)
    yield ns, parent
    import shutil

    shutil.rmtree(parent, ignore_errors=True)


def test_a_function_answer_is_collected_with_its_helpers_and_runs_in_the_sandbox(student_functions):
    from course.classroom.sandbox import SandboxedFunction, make_scratch
    from jacobians.grading.guard import run_guarded

    ns, parent = student_functions
    data = json.loads(json.dumps(answer_data.encode(ns["my_fn"])))
    code = answer_data.decode(data)
    assert isinstance(code, answer_data.CodeAnswer) and "def helper" in code.helpers[0]
    assert ["import", "numpy", "np"] in code.imports and answer_data.decode(code.constants["SCALE"]) == 2.0
    fn = SandboxedFunction(code, make_scratch(parent), Limits())
    try:
        assert np.array_equal(fn([1, 2]), [3.0, 5.0])
        ok, out = run_guarded(fn, ([1, 2],))
        assert ok and np.array_equal(out, [3.0, 5.0])
    finally:
        fn.close()
    bad = SandboxedFunction(answer_data.decode(answer_data.encode(ns["bad"])), make_scratch(parent), Limits())
    try:
        assert run_guarded(bad, (1,)) == (False, "your function raised ZeroDivisionError: division by zero")
        assert run_guarded(bad, (1,))[0] is False  # the process lives on after an exception
    finally:
        bad.close()
    slow = SandboxedFunction(answer_data.decode(answer_data.encode(ns["slow"])), make_scratch(parent), Limits())
    ok, out = run_guarded(slow, (1,), limit=1.0)
    assert not ok and "did not finish within 1 s" in out
    with pytest.raises(RuntimeError, match="stopped after an earlier failure"):
        slow(1)  # the looping process was killed, never reused


# --------------------------------------------------------------------------- the made-up chapter itself
def test_the_made_up_chapter_is_a_generated_page_whose_solutions_are_right_for_several_ids():
    """Its page is in the generated layout, lists the chapter's exercises in order, its student notebook is what
    students get, and its worked solutions (which the book-style submissions hand in) are right for other IDs; each
    exercise's library check holds. (The course's own pages: tests/test_exercise_solutions_every_variant.py.)"""
    import jupytext
    from tools.make_exercises import check_student, parse_page, render_page, student_notebook

    from course.exercises._registry import LIBRARY_CHECKS

    head, blocks, chapter = parse_page(CHAPTER.read_text(encoding="utf-8"))
    assert render_page(head, blocks, chapter) == CHAPTER.read_text(encoding="utf-8")
    assert [b.eid for b in blocks] == IDS == [e for e in exercises.exercise_ids() if e.startswith(f"ch{chapter:02d}_")]
    check_student(student_notebook(CHAPTER))
    for seed in ("s1", "maria.garcia@uni.example", "0", "1", "2", "3"):
        ns: dict[str, object] = {}
        for cell in jupytext.read(CHAPTER).cells:
            if cell.cell_type == "code":
                exec(cell.source.replace('SEED = "student-id"', f"SEED = {seed!r}"), ns)  # (asserts each verdict)
        for eid in IDS:
            LIBRARY_CHECKS[eid](exercises.load(eid, seed=seed))
