"""Tests of the checker itself (jacobians.grading): answers of every kind, politeness, no mutation."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from course import exercises
from jacobians import grading
from jacobians.grading import Feedback, Mistake, NumericExercise, compare


def _numeric_exercise(ref, mistakes=()):
    return NumericExercise("t_ex1", "test", "statement", {}, np.asarray(ref, float), list(mistakes))


REF = np.arange(12, dtype=float).reshape(6, 2) + 1.0


# ------------------------------------------------------------------ Feedback

def test_feedback_repr_and_html():
    fb = exercises.check("ch01_ex1", exercises.load("ch01_ex1", seed=0).solution(), seed=0)
    assert fb.correct and fb.kind == "correct" and bool(fb)
    assert str(fb).startswith("[ch01_ex1] Correct:")
    html = fb._repr_html_()
    assert "Correct" in html and "#009E73" in html and "jacobians-feedback-correct" in html
    wrong = exercises.check("ch01_ex1", np.zeros(6), seed=0)
    assert not wrong.correct and "#D55E00" in wrong._repr_html_() and "Not yet" in str(wrong)


def test_feedback_html_escapes_message():
    fb = Feedback(False, "<script>alert(1)</script>", "wrong", "x")
    assert "<script>" not in fb._repr_html_() and "&lt;script&gt;" in fb._repr_html_()


def test_empty_answer_is_polite():
    fb = exercises.check("ch02_ex2", None, seed=0)
    assert fb.kind == "empty" and not fb.correct and "Set `answer`" in fb.message


# ------------------------------------------------------------------ normalisation of answers

@pytest.mark.parametrize("answer", [REF.tolist(), REF, tuple(map(tuple, REF)), sp.Matrix(REF.tolist()),
                                    REF.astype(np.float32), REF.copy(),
                                    [list(col) for col in REF.T.T], [np.array(r) for r in REF],
                                    np.array(REF, dtype=object), REF + 0j])
def test_answer_forms_accepted(answer):
    fb = _numeric_exercise(REF).check(answer)
    assert fb.correct, fb


def test_sympy_numbers_and_rationals_accepted():
    ex = _numeric_exercise([0.5, np.sqrt(2)])
    assert ex.check([sp.Rational(1, 2), sp.sqrt(2)]).correct
    assert ex.check(sp.Matrix([sp.Rational(1, 2), sp.sqrt(2)])).correct


def test_vector_shapes_interchangeable_but_matrix_shapes_are_not():
    ex = _numeric_exercise([1.0, 2.0, 3.0])
    assert ex.check([[1.0], [2.0], [3.0]]).correct and ex.check([[1.0, 2.0, 3.0]]).correct
    fb = _numeric_exercise(REF).check(REF.ravel())
    assert fb.mistake == "wrong_shape" and "(6, 2)" in fb.message


def test_transposed_detected():
    fb = _numeric_exercise(REF).check(REF.T)
    assert fb.mistake == "transposed" and "transpose" in fb.message


def test_wrong_entry_located():
    wrong = REF.copy()
    wrong[3, 1] += 1
    fb = _numeric_exercise(REF).check(wrong)
    assert fb.mistake == "wrong_entry" and "row 4, column 2" in fb.message


def test_column_order_detected():
    fb = _numeric_exercise(REF).check(REF[:, ::-1])
    assert fb.mistake == "column_order"


def test_many_wrong_entries_named_by_column():
    wrong = REF.copy()
    wrong[:, 1] += 3
    fb = _numeric_exercise(REF).check(wrong)
    assert fb.mistake == "wrong_entries" and "column(s) 2" in fb.message and "column(s) 1 are right" in fb.message


def test_catalogued_mistake_wins_over_generic():
    swapped = np.vstack([REF[3:], REF[:3]])
    fb = _numeric_exercise(REF, [Mistake("v_omega_swapped", swapped, "swap message")]).check(swapped)
    assert fb.mistake == "v_omega_swapped" and fb.message == "swap message"


def test_tolerance_accepts_typed_three_decimals():
    ref = np.array([0.123456, -2.718281])
    assert _numeric_exercise(ref).check([0.123, -2.718]).correct
    assert not _numeric_exercise(ref).check([0.133, -2.718]).correct


# ------------------------------------------------------------------ garbage in, feedback out

def _raises(*args):
    raise RuntimeError("boom")


class Weird:
    def __array__(self, *a, **k):
        raise ValueError("no")


GARBAGE = [None, "text", "[[1, 2], [3, 4]]", b"bytes", [[1, 2], [3]], [1, [2, 3]], np.full((6, 2), np.nan),
           np.full((6, 2), np.inf), math.inf, float("nan"), np.zeros(10 ** 6), [0.0] * (10 ** 6), object(), Weird(),
           _raises, lambda *a: None, {"a": 1}, {1, 2}, 1 + 2j, True, [[None, 1]], np.array(["a", "b"]),
           [[[[[[[1]]]]]]], [], np.zeros((0, 2)), sp.Symbol("x"), sp.Matrix([[sp.Symbol("x")]]), Ellipsis, int,
           np.array([1, 2], dtype="datetime64[s]"), [sp.Matrix([1, 2])], range(3), -1e308 * 10]


@pytest.mark.parametrize("exercise_id", ["ch02_ex2", "ch01_ex4", "ch03_ex3", "ch06_ex4", "ch09_ex3"])
@pytest.mark.parametrize("answer", GARBAGE, ids=lambda a: type(a).__name__)
def test_garbage_gets_feedback_not_exception(exercise_id, answer):
    fb = exercises.check(exercise_id, answer, seed=1)
    assert isinstance(fb, Feedback) and not fb.correct
    assert fb.kind in ("wrong", "empty", "invalid") and fb.message and fb.exercise_id == exercise_id


def test_text_is_never_evaluated(monkeypatch):
    calls = []
    real = sp.sympify

    def spy(*a, **k):
        calls.append(a)
        return real(*a, **k)

    monkeypatch.setattr(sp, "sympify", spy)
    for eid in ("ch02_ex3", "ch06_ex1", "ch02_ex2"):
        fb = exercises.check(eid, "Matrix([[0, 0]])", seed=0)
        assert fb.kind == "invalid" and "not text" in fb.message
        fb = exercises.check(eid, [["theta1", "0"]], seed=0)
        assert fb.kind == "invalid"
    assert not any(isinstance(a[0], str) for a in calls)


def test_unknown_exercise_is_feedback_from_check_but_error_from_load():
    fb = exercises.check("ch99_ex9", [1], seed=0)
    assert fb.kind == "invalid" and "Unknown exercise" in fb.message
    with pytest.raises(KeyError):
        exercises.load("ch99_ex9")
    with pytest.raises(TypeError):
        exercises.load("ch01_ex1", seed=3.5)
    with pytest.raises(ValueError):
        exercises.load("ch01_ex1", seed="  ")
    with pytest.raises(ValueError):
        exercises.load("ch01_ex1", seed=-1)


answers = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=5) | st.complex_numbers(),
    lambda children: st.lists(children, max_size=7) | st.tuples(children, children)
    | st.dictionaries(st.text(max_size=2), children, max_size=2),
    max_leaves=40)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(answer=answers, eid=st.sampled_from(["ch02_ex2", "ch05_ex3", "ch09_ex5", "ch09_ex6", "ch06_ex1"]))
def test_fuzz_never_raises(answer, eid):
    before = copy.deepcopy(answer)
    fb = exercises.check(eid, answer, seed=2)
    assert isinstance(fb, Feedback)
    assert repr(answer) == repr(before)  # not mutated


@settings(max_examples=60, deadline=None)
@given(arr=st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=0, max_size=30),
       shape=st.sampled_from([None, (6, 3), (3, 6), (2, 9)]))
def test_fuzz_arrays(arr, shape):
    a = np.array(arr)
    if shape is not None and a.size == 18:
        a = a.reshape(shape)
    copy_a = a.copy()
    fb = exercises.check("ch02_ex2", a, seed=0)
    assert isinstance(fb, Feedback)
    np.testing.assert_array_equal(a, copy_a)


# ------------------------------------------------------------------ no mutation

def test_check_does_not_mutate_arrays_lists_or_function_inputs():
    ex = exercises.load("ch02_ex2", seed=4)
    ans = ex.solution()
    ans_list = ans.tolist()
    snapshot, snapshot_list = ans.copy(), copy.deepcopy(ans_list)
    assert ex.check(ans).correct and ex.check(ans_list).correct
    np.testing.assert_array_equal(ans, snapshot)
    assert ans_list == snapshot_list
    assert ans.flags.writeable


def test_function_that_mutates_its_input_cannot_change_reference():
    ex = exercises.load("ch04_ex3", seed=0)
    ref_fn = ex.solution()

    def vandal(J_s, T_sb):
        out = ref_fn(J_s, T_sb)
        J_s[:] = 0
        T_sb[:] = 0
        return out

    assert ex.check(vandal).correct


# ------------------------------------------------------------------ function answers

def test_function_that_loops_is_stopped():
    def forever(S, theta):
        while True:
            pass

    fb = exercises.check("ch02_ex4", forever, seed=0)
    assert not fb.correct and "did not finish" in fb.message


def test_function_that_raises_is_reported_politely():
    def broken(S, theta):
        return S @ np.ones(99)

    fb = exercises.check("ch02_ex4", broken, seed=0)
    assert not fb.correct and fb.mistake == "raised" and "ValueError" in fb.message


def test_function_that_exits_or_recurses():
    import sys

    def leaves(S, theta):
        sys.exit(1)

    def deep(S, theta):
        return deep(S, theta)

    assert "exit()" in exercises.check("ch02_ex4", leaves).message
    assert "RecursionError" in exercises.check("ch02_ex4", deep).message


def test_function_returning_none_wrong_shape_or_text():
    assert exercises.check("ch02_ex4", lambda S, th: None).mistake == "returned_none"
    assert exercises.check("ch02_ex4", lambda S, th: np.zeros((3, 3))).mistake == "wrong_shape"
    assert exercises.check("ch02_ex4", lambda S, th: "J").mistake == "bad_return"
    assert exercises.check("ch02_ex4", lambda: 1).mistake == "raised"  # wrong signature


def test_function_given_where_numbers_expected_and_vice_versa():
    assert "call your function" in exercises.check("ch02_ex2", lambda: 0, seed=0).message
    assert "wants a function" in exercises.check("ch02_ex4", np.zeros((6, 2)), seed=0).message


# ------------------------------------------------------------------ variants

def test_same_seed_same_numbers_different_seed_different_numbers():
    a, b, c = (exercises.load("ch02_ex2", seed=s) for s in (5, 5, 6))
    assert a.statement == b.statement
    np.testing.assert_array_equal(a.solution(), b.solution())
    different = [exercises.load("ch02_ex2", seed=s).statement for s in range(6)]
    assert len(set(different)) > 3


def test_answer_for_one_variant_is_wrong_for_another():
    ex0, ex1 = exercises.load("ch05_ex1", seed=0), exercises.load("ch05_ex1", seed=1)
    assert not np.allclose(ex0.solution(), ex1.solution())
    assert not exercises.check("ch05_ex1", ex0.solution(), seed=1).correct


def test_statement_renders_as_markdown_with_numbers():
    ex = exercises.load("ch02_ex1", seed=0)
    md = ex._repr_markdown_()
    assert "ch02_ex1" in md and "$" in md
    for v in ex.given["lengths"]:
        assert f"{v:g}" in md


def test_compare_on_nan_reference_is_not_called_correct():
    fb = compare(np.array([np.nan]), np.array([1.0]), [], 1e-3, 1e-3, "x")
    assert not fb.correct


# ------------------------------------------------------------------ the catalogue (exercises by id and seed)

def _toy_catalogue():
    toy = grading.Catalogue()

    @toy.register("ch01_ex10")
    def _ten(rng):
        x = float(rng.integers(1, 100))
        same = grading.Mistake("same_as_reference", 2 * x, "never shown")
        half = grading.Mistake("half", x, "You gave x, not 2x.")
        return grading.numeric_exercise("Double", f"Double {x:g}.", {"x": x}, 2 * x, [same, half, half])

    @toy.register("ch01_ex2")
    def _two(rng):
        return grading.numeric_exercise("Zero", "Give 0.", {}, 0.0, [])

    return toy


def test_catalogue_orders_ids_by_chapter_then_number_and_sets_id_and_seed():
    toy = _toy_catalogue()
    assert toy.ids() == ["ch01_ex2", "ch01_ex10"] and len(toy) == 2 and "ch01_ex2" in toy
    ex = toy.load("ch01_ex10", seed=4)
    assert (ex.id, ex.seed) == ("ch01_ex10", "4")
    assert toy.load("ch01_ex10", seed=4).given == ex.given


def test_catalogue_drops_mistakes_equal_to_the_reference_or_to_an_earlier_mistake():
    ex = _toy_catalogue().load("ch01_ex10", seed=1)
    assert [m.name for m in ex.mistakes] == ["half"]
    assert _toy_catalogue().check("ch01_ex10", ex.given["x"], seed=1).mistake == "half"


def test_catalogue_refuses_a_bad_or_repeated_id_at_registration():
    toy = _toy_catalogue()
    with pytest.raises(ValueError, match="registered twice"):
        toy.register("ch01_ex2")(lambda rng: None)
    with pytest.raises(ValueError, match="ch02_ex1"):
        toy.register("exercise one")
    fb = toy.check("ch01_ex3", 0, seed=0)
    assert fb.kind == "invalid" and "Unknown exercise 'ch01_ex3'" in fb.message


def test_grading_holds_no_exercise_and_the_course_catalogue_holds_every_exercise_of_the_pages():
    import re
    from pathlib import Path

    assert not hasattr(grading, "load") and not hasattr(grading, "check")
    pages = sorted((Path(__file__).resolve().parent.parent / "exercises").glob("[0-9][0-9]_*.md"))
    on_pages = [eid for p in pages for eid in re.findall(r'exercises\.load\("(\w+)", seed=SEED\)', p.read_text())]
    assert on_pages and exercises.exercise_ids() == exercises.CATALOGUE.ids() == on_pages
