"""make grade's two ways of running a notebook agree, and partial credit for code exercises.

The warm worker (:mod:`course.classroom._zygote`, cells run by IPython's shell in a fork that enters a bubblewrap
sandbox) replaced a Jupyter kernel started afresh in each sandbox (:mod:`course.classroom._runner`, kept for
``make bench``'s comparison). An honest class must get the same gradebook, row for row, both ways; here it
also has a code exercise with partial credit, so that the tests-passed counts are compared too. The class hands in
the made-up chapter ``ch00`` (``tests/fixtures/classroom.py``), not a chapter of the course.
"""

from __future__ import annotations

import numpy as np
import pytest
from tests.fixtures import classroom
from tests.fixtures.classroom import CODE, IDS, PAGE
from tools.bench_grade import BOOK, submission

from course import exercises
from course.classroom import grade
from course.classroom.grade import Row, grades_table, score
from course.classroom.sandbox import Limits, isolation

fixture_chapter = classroom.fixture_chapter  # (the made-up chapter in the catalogue, for this module's tests)
pytestmark = pytest.mark.usefixtures("fixture_chapter")
#: Two of the chapter's exercises: a numeric one and the code one.
NUMERIC = next(eid for eid, kind in classroom.KINDS.items() if kind == "numeric")
CH = CODE.split("_")[0]

#: A function answer right on every other call (the grader calls it once per test, in order): partial credit.
_HALF = '''calls = [0]


def {name}(*args):
    calls[0] += 1
    ref = exercises.load("{code}", seed=SEED).reference(*args)
    return ref if calls[0] % 2 else 0 * np.asarray(ref)


answer = {name}
'''


def test_tests_passed_counts_each_test_as_the_checker_judges_it():
    ex = exercises.load(CODE, seed="s1")
    n = len(ex.cases())
    assert grade.count_passed_tests(ex, ex.reference) == (n, n)
    assert grade.count_passed_tests(ex, lambda *a: np.zeros((6, 6))) == (0, n)
    calls = []

    def wrong_on_the_second(*args):
        calls.append(1)
        out = ex.reference(*args)
        return out + 1.0 if len(calls) == 2 else out

    assert grade.count_passed_tests(ex, wrong_on_the_second) == (n - 1, n)
    calls.clear()
    assert not ex.check(wrong_on_the_second).correct  # (all or nothing without partial credit)


def test_partial_credit_scores_and_the_grades_table():
    rows = [Row("s1", "a.ipynb", CODE, "s1", "0", "wrong", "", "4/6"),
            Row("s1", "a.ipynb", NUMERIC, "s1", "1", "right"),
            Row("s2", "b.ipynb", CODE, "s2", "0", "wrong", "", "4/6"),
            Row("s3", "c.ipynb", CODE, "s3", "0", "wrong", "", "7/6")]  # (impossible: earns nothing)
    worth = {NUMERIC: 1.0, CODE: 3.0}
    head, table = grades_table(rows, {}, worth, partial=frozenset({CODE}))
    assert head == ["student", "name", f"{CH} (of 4)", "total (of 4)"]
    assert table == [["s1", "", "3", "3"], ["s2", "", "2", "2"], ["s3", "", "0", "0"]]
    _, none = grades_table(rows, {}, worth, partial=frozenset())
    assert none == [["s1", "", "1", "1"], ["s2", "", "0", "0"], ["s3", "", "0", "0"]]
    assert score(rows[0], frozenset()) == 0.0


def test_partial_credit_is_only_for_code_exercises(tmp_path):
    bad = tmp_path / "points.toml"
    bad.write_text(f"[points]\n[partial]\n{NUMERIC} = true\n", encoding="utf-8")
    with pytest.raises(ValueError, match="not a code exercise"):
        grade.partial_credit.__wrapped__(bad)
    bad.write_text(f"[partial]\n{CODE} = 1\n", encoding="utf-8")
    with pytest.raises(ValueError, match="true or false"):
        grade.partial_credit.__wrapped__(bad)
    bad.write_text(f"[partial]\n{CODE} = true\n", encoding="utf-8")
    assert grade.partial_credit.__wrapped__(bad) == {CODE}


#: The notebooks graded the previous way too (a Jupyter kernel started in each sandbox costs several CPU seconds):
#: between them they run right answers typed in, a code answer with partial credit, blank answers ("half"), and the
#: book's worked solutions that read the notebook's exercise variables; "right" and "wrong" differ from "partly"
#: only in the answers' values, which the regrade judges the same way after either engine.
KERNEL_ALSO = ("partly.ipynb", "half.ipynb", "book.ipynb")


@pytest.fixture(scope="module")
def both_ways(tmp_path_factory, fixture_chapter):
    if isolation().broken:
        pytest.fail(f"the grading sandbox does not work on a machine that has all it needs: {isolation().reason}")
    if not isolation().ok:
        pytest.skip(f"make grade cannot isolate notebooks here: {isolation().reason}")
    import nbformat

    root = tmp_path_factory.mktemp("engines")
    nbs = {"right.ipynb": submission(PAGE, "s-right", "right"), "wrong.ipynb": submission(PAGE, "s-wrong", "wrong"),
           "half.ipynb": submission(PAGE, "s-half", "half"), "book.ipynb": submission(PAGE, "s-book", BOOK)}
    partly = submission(PAGE, "s-partly", "right")
    cell = next(c for c in partly.cells if c.cell_type == "code" and c.source.startswith("def "))
    cell.source = _HALF.format(name=cell.source.split("(")[0].removeprefix("def "), code=CODE)
    nbs["partly.ipynb"] = partly
    out = {}
    patch = pytest.MonkeyPatch()
    patch.setattr(grade, "partial_credit", lambda path=None: frozenset({CODE}))  # (forked workers inherit)
    try:
        for engine in grade.ENGINES:
            folder = root / engine
            folder.mkdir()
            for name, nb in nbs.items():
                if engine == "warm" or name in KERNEL_ALSO:
                    nbformat.write(nb, folder / name)
            out[engine] = grade.grade_class(folder, workers=2, engine=engine,
                                            limits=Limits(cell_timeout=60, notebook_timeout=200))
    finally:
        patch.undo()
    return out


def test_an_honest_class_gets_the_same_gradebook_both_ways(both_ways):
    warm, kernel = both_ways["warm"], both_ways["kernel"]
    assert [r for r in warm if r.notebook in KERNEL_ALSO] == kernel
    assert {r.notebook for r in kernel} == set(KERNEL_ALSO)
    assert not [r for r in warm + kernel if r.exercise == "(notebook)"], warm
    n = len(IDS)
    # right, book, half (the first half), partly (all but its code exercise)
    assert sum(r.correct == "1" for r in warm) == n + n + n // 2 + n - 1


def test_a_code_exercise_earns_partial_credit_end_to_end(both_ways):
    rows = both_ways["warm"]
    tests = {r.student: r.tests for r in rows if r.exercise == CODE}
    n = len(exercises.load(CODE, seed="s-partly").cases())
    assert tests["s-right"] == f"{n}/{n}" and tests["s-wrong"] == f"0/{n}"
    passed, run = map(int, tests["s-partly"].split("/"))
    assert run == n and 0 < passed < n
    (row,) = [r for r in rows if r.student == "s-partly" and r.exercise == CODE]
    assert row.correct == "0" and f"passed {passed} of the {n} tests" in row.message
