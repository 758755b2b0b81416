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


def _seeds(eid):
    """The seeds a check runs on: :data:`SEEDS`; for a code exercise, whose test cases can take seconds to draw
    (the IK loop's search), one seed of each of its variants (what its ``given`` says beside the worked example)
    among the first 12, since the check runs on every test case of the variant anyway."""
    if exercises.load(eid, seed=0).kind != "function":
        return list(SEEDS)
    first = {}
    for seed in range(12):
        given = exercises.load(eid, seed=seed).given
        first.setdefault(repr(sorted((k, v) for k, v in given.items() if not k.startswith("example"))), seed)
    return sorted(first.values())


@pytest.mark.parametrize("eid", sorted(LIBRARY_CHECKS))
def test_reference_agrees_with_the_library(eid):
    seeds = _seeds(eid)
    assert len(seeds) >= 2, (eid, seeds)  # every exercise varies; a code exercise has two variants at least
    for seed in seeds:
        LIBRARY_CHECKS[eid](exercises.load(eid, seed=seed))


def test_every_exercise_registers_a_library_check():
    ids = set(exercises.exercise_ids())
    assert set(LIBRARY_CHECKS) <= ids, sorted(set(LIBRARY_CHECKS) - ids)
    missing = ids - set(LIBRARY_CHECKS)
    assert not missing, f"register a library check (register(..., library=...)) for {sorted(missing)}"


@pytest.mark.parametrize("eid", sorted(LIBRARY_CHECKS))
def test_a_library_check_fails_on_a_wrong_reference(eid):
    """The check compares the reference itself: its first entry moved by 1 % of (1 + its size) (well over every
    check's tolerance, 2e-3 at most) makes it fail. A code exercise's reference function is moved so on every
    call: its check runs it on the variant's data."""
    ex = exercises.load(eid, seed=0)
    if ex.kind == "symbolic":
        ex.reference = ex.reference + _unit(ex.reference.shape)
    elif ex.kind == "function":
        right = ex.reference
        ex.reference = lambda *args: _moved(right(*args))
    else:
        ex.reference = _moved(ex.reference)
    with pytest.raises(AssertionError):
        LIBRARY_CHECKS[eid](ex)


def _moved(value):
    ref = np.array(value, dtype=float)
    ref.flat[0] += 0.01 * (1 + abs(ref.flat[0]))  # (flat: in place whatever the memory order)
    return ref


def _unit(shape):
    import sympy as sp

    m = sp.zeros(*shape)
    m[0, 0] = sp.Rational(1, 100)
    return m
