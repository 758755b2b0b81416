"""make grade reads the answers files saved from the book's exercise pages: the same verdicts as the
notebook's checker, bounded reading, and a row that says what is wrong with a malformed, huge or hostile file."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from course import exercises
from course.classroom.grade import grade_class
from course.classroom.page_answers import MAX_BYTES, find_answer_files, read_answers_file, read_answers_text

SID = "s2401012"


def _saved(answers: dict[str, object], sid: object = SID) -> bytes:
    """A file as the page writes it (page.js: download)."""
    def entry(value: object) -> dict[str, object]:
        arr = np.asarray(value, dtype=float)
        data = [None if np.isnan(x) else float(x) for x in arr.ravel()]
        return {"text": "typed", "value": {"shape": list(arr.shape), "data": data}, "variant": 3,
                "correct": True}  # a claimed verdict, never read
    return json.dumps({"format": "jacobians-course-answers", "version": 1, "id": sid,
                       "answers": {k: entry(v) for k, v in answers.items()}}).encode()


def test_a_saved_file_gets_the_notebooks_verdicts():
    ex1 = exercises.load("ch01_ex1", seed=SID)
    ex2 = exercises.load("ch04_ex1", seed=SID)
    ex3 = exercises.load("ch06_ex4", seed=SID)
    answers = {"ch01_ex1": ex1.solution(), "ch04_ex1": ex2.mistakes[0].value,
               "ch06_ex4": round(float(ex3.solution()), 1), "ch09_ex3": float("nan")}
    sid, marks = read_answers_text(_saved(answers))
    rows = {r.exercise: r for r in marks}
    assert sid == SID
    for eid, value in answers.items():
        fb = exercises.check(eid, value, seed=SID)
        assert (rows[eid].correct, rows[eid].mistake) == ("1" if fb.correct else "0", fb.mistake or ""), eid
        assert rows[eid].message == fb.message[:400]
    assert rows["ch01_ex1"].correct == "1" and rows["ch04_ex1"].correct == "0"


@pytest.mark.parametrize(("raw", "says"), [
    (b"", "not valid JSON"),
    (b"{not json", "not valid JSON"),
    (b"[" * 100_000 + b"]" * 100_000, "not valid JSON"),
    (b'{"format": "something else"}', "no format"),
    (b'{"format": "jacobians-course-answers", "answers": {}}', "no student ID"),
    (b'{"format": "jacobians-course-answers", "id": 7, "answers": {}}', "no student ID"),
    (b'{"format": "jacobians-course-answers", "id": "s1", "answers": []}', "no answers object"),
    (b'{"format": "jacobians-course-answers", "id": "' + b"x" * 300 + b'", "answers": {}}', "no student ID"),
])
def test_malformed_files_get_a_row_that_says_so(raw, says):
    _sid, rows = read_answers_text(raw)
    assert rows and all(r.exercise == "" for r in rows) and says in rows[-1].message


def test_hostile_answers_are_refused_one_by_one():
    bad = {
        "ch01_ex1": {"value": {"shape": [True], "data": [1]}},
        "ch01_ex2": {"value": {"shape": [6, 6], "data": [1.0] * 5}},
        "ch01_ex3": {"value": {"shape": [6], "data": ["__import__('os')"] * 6}},
        "ch02_ex1": {"value": {"shape": [2, 2, 2], "data": [0] * 8}},
        "ch02_ex2": "not a record",
        "ch99_ex1": {"value": {"shape": [], "data": [1]}},
        "ch04_ex1": {"value": {"shape": [10 ** 9], "data": [0]}},
    }
    raw = json.dumps({"format": "jacobians-course-answers", "id": SID, "answers": bad}).encode()
    _sid, rows = read_answers_text(raw)
    graded = {r.exercise: r for r in rows if r.exercise}
    assert set(graded) == set(bad) - {"ch99_ex1"}
    assert all(r.correct == "0" and "cannot be graded" in r.message for r in graded.values())
    assert any("unknown exercise" in r.message for r in rows if not r.exercise)


def test_huge_and_unreadable_files(tmp_path: Path):
    huge = tmp_path / "answers-huge.json"
    huge.write_bytes(b" " * (MAX_BYTES + 10))
    assert "more than" in read_answers_file(huge)[1][0].message
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "answers-a.json").write_bytes(b"{}")
    assert find_answer_files(tmp_path) == [huge]


def test_make_grade_reads_answers_files_beside_notebooks(tmp_path: Path, monkeypatch):
    """grade_class grades an answers file with no notebook in the folder (no student code runs for it)."""
    monkeypatch.setenv("JACOBIANS_GRADE_UNSAFE", "1")
    ex = exercises.load("ch01_ex1", seed=SID)
    (tmp_path / "answers-s2401012.json").write_bytes(_saved({"ch01_ex1": ex.solution()}))
    rows = grade_class(tmp_path, workers=1)
    mine = [r for r in rows if r.exercise == "ch01_ex1"]
    assert len(mine) == 1 and mine[0].correct == "1" and mine[0].student == SID
    assert (tmp_path / "gradebook.csv").is_file()


def test_a_student_with_a_notebook_and_a_page_file_gets_one_answer_counted_per_exercise():
    """The rule of grade.one_answer_each: the notebook's answer counts where the notebook checked the exercise (its
    page answer is listed, not counted, with its verdict); the page's answer counts where the notebook did not
    attempt it or has no such exercise; other students, and IDs written differently, are matched as the gradebook
    matches them (normalised)."""
    from course.classroom.grade import NOT_ATTEMPTED, Row, grades_table, one_answer_each

    nb = [Row("s1", "s1/ch01.ipynb", "ch01_ex1", "S1", "0", "wrong", "sign"),       # notebook wrong, page right
          Row("s1", "s1/ch01.ipynb", "ch01_ex2", "S1", "0", NOT_ATTEMPTED),         # notebook blank, page right
          Row("s1", "s1/ch01.ipynb", "ch01_ex3", "S1", "1", "right"),               # notebook right, page wrong
          Row("s2", "s2/ch01.ipynb", "ch01_ex1", "s2", "1", "right")]
    page = [Row("s1", "answers-s1.json", "ch01_ex1", "s1", "1", "right"),
            Row("s1", "answers-s1.json", "ch01_ex2", "s1", "1", "right"),
            Row("s1", "answers-s1.json", "ch01_ex3", "s1", "0", "wrong", "sign"),
            Row("s1", "answers-s1.json", "ch02_ex1", "s1", "1", "right"),           # no notebook of chapter 2
            Row("s1", "answers-s1.json", "(notebook)", "s1", "", "answers an unknown exercise")]
    rows = one_answer_each(nb, page)
    assert len(rows) == len(nb) + len(page)  # nothing dropped: the answer that does not count is listed
    counted = {(r.notebook, r.exercise): r.correct for r in rows if r.correct in ("0", "1")}
    assert counted == {("s1/ch01.ipynb", "ch01_ex1"): "0", ("s1/ch01.ipynb", "ch01_ex3"): "1",
                       ("answers-s1.json", "ch01_ex2"): "1", ("answers-s1.json", "ch02_ex1"): "1",
                       ("s2/ch01.ipynb", "ch01_ex1"): "1"}
    listed = {(r.notebook, r.exercise): r.message for r in rows if r.correct == "" and r.exercise != "(notebook)"}
    assert "the notebook's answer to ch01_ex1 counts" in listed[("answers-s1.json", "ch01_ex1")]
    assert "this one was right" in listed[("answers-s1.json", "ch01_ex1")]
    assert "this one was wrong" in listed[("answers-s1.json", "ch01_ex3")]
    assert "answers-s1.json" in listed[("s1/ch01.ipynb", "ch01_ex2")]
    worth = {"ch01_ex1": 1.0, "ch01_ex2": 1.0, "ch01_ex3": 1.0, "ch02_ex1": 1.0}
    head, table = grades_table(rows, {}, worth, frozenset())
    assert {r[0]: r[-1] for r in table} == {"s1": "3", "s2": "1"}  # both counting once would have given s1 4


def _saved_formulas(eid: str, shape: list[int], formulas: list[object]) -> bytes:
    """A file with one symbolic answer, as the page writes it (math.js's printing of each typed entry)."""
    return json.dumps({"format": "jacobians-course-answers", "version": 1, "id": SID,
                       "answers": {eid: {"text": "typed", "value": {"shape": shape, "formulas": formulas},
                                         "variant": 0, "correct": True}}}).encode()


def test_saved_formulas_get_the_notebooks_verdicts():
    """A formula answer is rebuilt from Python's parse tree and graded by the checker: the reference, a catalogued
    mistake and an unknown symbol, as math.js prints them (spaces around *, ^ for powers)."""
    ex = exercises.load("ch06_ex1", seed=SID)
    shape = list(ex.reference.shape)

    def printed(matrix):
        return [str(e).replace("**", "^").replace("*", " * ") for e in matrix]

    for value, formulas in [(ex.reference, printed(ex.reference)), (ex.mistakes[0].value, printed(ex.mistakes[0].value)),
                            (None, ["q + " + printed(ex.reference)[0], *printed(ex.reference)[1:]])]:
        (mark,) = read_answers_text(_saved_formulas("ch06_ex1", shape, formulas))[1]
        if value is None:
            assert mark.correct == "0" and "q" in mark.message and "does not define" in mark.message
            continue
        fb = ex.check(value)
        assert (mark.correct, mark.mistake, mark.message) == ("1" if fb.correct else "0", fb.mistake or "", fb.message)


@pytest.mark.parametrize("formula", [
    "__import__('os').system('true')", "().__class__.__bases__[0].__subclasses__()", "l1.__class__",
    "lambda: 1", "[x for x in (1,)]", "9**9**9", "10**(10**10)", "(" * 500 + "1" + ")" * 500, "'text'", "x" * 3000,
    "open('/etc/passwd')", "l1 if l1 else l2", "sin(l1, l2, theta1)", "cos(x=1)", 7, None])
def test_hostile_formulas_are_refused_without_evaluation(formula):
    (mark,) = read_answers_text(_saved_formulas("ch06_ex1", [], [formula]))[1]
    assert mark.correct == "0" and mark.exercise == "ch06_ex1"
    assert "cannot be graded" in mark.message or "does not define" in mark.message or mark.mistake
