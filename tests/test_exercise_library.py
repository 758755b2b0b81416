"""Each exercise's reference against the library: the check its definition registers
(``register(..., library=...)``, :data:`course.exercises._registry.LIBRARY_CHECKS`), run on several variants;
and a check of the checks (a reference moved off the library's value fails it)."""

from __future__ import annotations

import numpy as np
import pytest

from course import exercises
from course.exercises._registry import LIBRARY_CHECKS

#: Six variants: enough to meet every branch the checks have (ch04_ex4 asks for three kinds of velocity).
SEEDS = range(6)

#: Exercises defined before the library checks moved into the definitions, whose reference is the library's own
#: call (ch10-ch12) or a computation the exercise's other tests check; a new exercise must register a check.
WITHOUT_CHECK = frozenset({
    "ch01_ex1", "ch01_ex2", "ch01_ex3", "ch01_ex4", "ch02_ex4", "ch03_ex4", "ch04_ex2", "ch04_ex3", "ch05_ex3",
    "ch05_ex4", "ch06_ex3", "ch06_ex4", "ch07_ex1", "ch07_ex3", "ch07_ex4", "ch08_ex4", "ch09_ex1", "ch09_ex4",
    "ch09_ex5", "ch09_ex6", "ch10_ex1", "ch10_ex2", "ch10_ex3", "ch10_ex4", "ch11_ex1", "ch11_ex2", "ch11_ex3",
    "ch11_ex4", "ch12_ex1", "ch12_ex2", "ch12_ex3", "ch12_ex4",
})


@pytest.mark.parametrize("eid", sorted(LIBRARY_CHECKS))
def test_reference_agrees_with_the_library(eid):
    for seed in SEEDS:
        LIBRARY_CHECKS[eid](exercises.load(eid, seed=seed))


def test_every_new_exercise_registers_a_library_check():
    ids = set(exercises.exercise_ids())
    assert set(LIBRARY_CHECKS) <= ids
    assert WITHOUT_CHECK <= ids, sorted(WITHOUT_CHECK - ids)
    missing = ids - set(LIBRARY_CHECKS) - WITHOUT_CHECK
    assert not missing, f"register a library check (register(..., library=...)) for {sorted(missing)}"
    assert not WITHOUT_CHECK & set(LIBRARY_CHECKS), "has a check now: drop it from WITHOUT_CHECK"


@pytest.mark.parametrize("eid", sorted(LIBRARY_CHECKS))
def test_a_library_check_fails_on_a_wrong_reference(eid):
    """The check compares the reference itself: one entry moved by 0.01 (well over every check's tolerance, 2e-3
    at most) makes it fail."""
    ex = exercises.load(eid, seed=0)
    if ex.kind == "symbolic":
        ex.reference = ex.reference + _unit(ex.reference.shape)
    else:
        ref = np.array(ex.reference, dtype=float)
        ref.reshape(-1)[0] += 0.01 * (1 + abs(ref.reshape(-1)[0]))
        ex.reference = ref
    with pytest.raises(AssertionError):
        LIBRARY_CHECKS[eid](ex)


def _unit(shape):
    import sympy as sp

    m = sp.zeros(*shape)
    m[0, 0] = sp.Rational(1, 100)
    return m
