"""The variant banks of the exercise pages: the hash that picks a variant, the notebook drawing from the bank,
and the size of the largest banks."""

from __future__ import annotations

import json

import numpy as np
import pytest

from course import exercises
from course.exercises._bank import BANK_SIZE, bank, fnv1a32, normalise_id, statements, variant_index, variant_seed
from jacobians.grading.feedback import statement_html


def test_fnv1a_matches_the_published_test_vectors():
    assert fnv1a32("") == 0x811C9DC5
    assert fnv1a32("a") == 0xE40C292C
    assert fnv1a32("foobar") == 0xBF9CF968


def test_ids_that_the_grader_takes_for_one_student_get_one_variant():
    for a, b in [("s123", "  S123 "), ("Jane  Doe", "jane doe"), (5, "5"), ("a\tb", "A B")]:
        assert normalise_id(a) == normalise_id(b)
        assert all(variant_index(e, a) == variant_index(e, b) for e in exercises.exercise_ids())


def test_the_notebook_draws_the_variant_of_the_bank():
    for sid in ("s2401012", "student-id", 7):
        for eid in ("ch01_ex1", "ch06_ex4", "ch12_ex2"):
            k = variant_index(eid, sid)
            mine, banked = exercises.load(eid, seed=sid), exercises.CATALOGUE.load(eid, seed=variant_seed(k))
            assert mine.statement == banked.statement and mine.seed == str(sid)
            assert mine.check(banked.solution()).correct


def test_ids_spread_over_the_bank():
    ks = {variant_index("ch01_ex2", f"s{2400000 + i}") for i in range(400)}
    assert len(ks) == BANK_SIZE


def test_tolerances_are_the_same_double_in_the_page():
    """decide.js writes 10^-k as the literal 1e-k; the checker computes 10.0 ** -k."""
    for k in range(16):
        assert 10.0 ** (-k) == float(f"1e-{k}")


@pytest.mark.parametrize("eid", ["ch03_ex2", "ch07_ex3", "ch03_ex3"])
def test_the_largest_banks_stay_under_100_kb(eid):
    data = bank(eid)
    assert len(data["variants"]) == BANK_SIZE
    assert len(json.dumps(data, separators=(",", ":"), ensure_ascii=False).encode()) < 100_000


def test_the_statements_are_those_of_the_variants():
    """The page shows variant k's statement (typeset at build time from these) for an ID of variant k."""
    texts = statements("ch06_ex1")
    assert len(texts) == BANK_SIZE and len(set(texts)) > 1
    for sid in ("s2401012", "s7"):
        assert texts[variant_index("ch06_ex1", sid)] == statement_html(exercises.load("ch06_ex1", seed=sid).statement)


def test_a_formula_bank_holds_the_checkers_points_and_values():
    """For a symbolic exercise the bank has the three points the checker evaluates at, and the reference's and
    each catalogued mistake's values there (what the page compares a typed formula with)."""
    data = bank("ch02_ex3")
    for k in (0, 5):
        ex = exercises.CATALOGUE.load("ch02_ex3", seed=variant_seed(k))
        v = data["variants"][k]
        assert v["points"] == ex.sample_points() and len(v["points"]) == 3
        assert v["wanted"] == sorted(str(s) for s in ex.reference.free_symbols)
        assert [m[0] for m in v["mistakes"]] == [m.name for m in ex.mistakes]
        for p, ref in zip(v["points"], v["ref"], strict=True):
            at = ex.reference.subs({s: p[str(s)] for s in ex.symbols.values()}).evalf()
            # two double evaluations (numpy's lambdify, sympy's evalf) of sums of a few products of lengths <= 1.4
            # and sines and cosines: each is within a few 1e-16 of the exact value, so 1e-12 separates a wrong point
            np.testing.assert_allclose(ref, np.array(at.tolist(), dtype=float), rtol=0, atol=1e-12)
