"""The course's exercises: one definition each (statement's data, expected answer, named mistakes, library check).

Each builder takes a seeded ``numpy.random.Generator`` and returns a
:class:`jacobians.grading.Exercise`; the grading machinery (reading, comparing,
naming mistakes, showing verdicts) is :mod:`jacobians.grading`. The exercise
pages call::

    from course import exercises
    SEED = "student-id"  # your student ID (any text): it picks your variant of every exercise
    ex1 = exercises.load("ch02_ex1", seed=SEED)      # the statement of this variant
    exercises.check("ch02_ex1", answer, seed=SEED)    # the verdict, never an exception

``SEED`` is any text (or a non-negative int; ``5`` and ``"5"`` are one seed).
It picks one of the exercise's :data:`~course.exercises._bank.BANK_SIZE` variants through a stable
hash (FNV-1a of the exercise id and the normalised ID, :func:`~course.exercises._bank.variant_index`), the
same hash the book page computes: the notebook and the page show an ID the same numbers. Each variant
draws from its own random stream (variant ``k`` is the catalogue's variant for the seed ``"variant-k"``).

>>> from course import exercises
>>> exercises.exercise_ids()[:2]  # in chapter order; how many there are is the catalogue's business
['ch01_ex1', 'ch01_ex2']
>>> ex = exercises.load("ch01_ex1", seed="a1234567")
>>> sorted(ex.given)
['omega', 'q']
>>> exercises.check("ch01_ex1", ex.solution(), seed="a1234567").correct
True
>>> fb = exercises.check("ch01_ex1", None, seed="a1234567")
>>> fb.correct, fb.kind
(False, 'empty')
>>> exercises.check("ch01_ex1", "0 0 1 0 0 0", seed=3).kind
'invalid'

Modules: ``ch01`` ... ``ch10`` (the definitions, one module per chapter);
``_registry`` (the catalogue they fill); shared by them: ``_variants`` (random
angles, lengths, chains, poses; test cases of function exercises), ``_kinematics``
(the references' plain-numpy formulas), ``_mistakes`` (mistakes met in many
exercises), ``_latex`` (numbers in statements), ``_symbolic_2r`` (the planar 2R
arm in sympy), ``_checks`` (what the library checks share). ``fixture`` is not the
course's: the made-up chapter ``ch00`` that the grading tests hand in, registered only
when they ask (:func:`fixture.register`, or the variable ``COURSE_FIXTURE_CHAPTER``).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

from jacobians.grading import Exercise, Feedback
from jacobians.grading.catalogue import MAX_SEED_LENGTH, seed_value

from . import ch01, ch02, ch03, ch04, ch05, ch06, ch07, ch08, ch09, ch10, ch11, ch12  # noqa: F401  (importing them registers the exercises)
from ._bank import variant_index, variant_seed
from ._progress import Progress, record
from ._progress import summary as _summary
from ._registry import CATALOGUE
from .fixture import ENV as _FIXTURE_ENV
from .fixture import register as _register_fixture

__all__ = ["CATALOGUE", "check", "exercise_ids", "load", "on_check", "summary"]

if os.environ.get(_FIXTURE_ENV):  # the made-up chapter of make grade's tests, in the processes they grade with
    _register_fixture()

#: Functions called with every Feedback that :func:`check` returns (e.g. a session's progress record).
_LISTENERS: list[Callable[[Feedback], None]] = []


def on_check(listener: Callable[[Feedback], None]) -> Callable[[Feedback], None]:
    """Register ``listener(feedback)`` to be called after every :func:`check` (usable as a decorator).

    The feedback carries ``exercise_id``, ``seed`` (the student's seed as text), ``correct``, ``kind``,
    ``mistake``, ``message``, ``title`` and ``statement``. A listener that raises is ignored: recording
    must never break a student's check.
    """
    if not callable(listener):
        raise TypeError(f"Expected a function of one Feedback, got {type(listener).__name__}")
    if listener not in _LISTENERS:
        _LISTENERS.append(listener)
    return listener


def exercise_ids() -> list[str]:
    """All exercise ids, in chapter order."""
    return CATALOGUE.ids()


def load(exercise_id: str, seed: int | str | None = None) -> Exercise:
    """The variant of ``exercise_id`` for ``seed`` (same seed, same numbers).

    Raises ``KeyError`` for an unknown id and ``TypeError``/``ValueError`` for a
    bad seed: these are the author's inputs, not the student's.
    """
    text = seed_value(seed)
    if not isinstance(exercise_id, str):
        raise TypeError(f"Expected an exercise id such as 'ch02_ex1', got {type(exercise_id).__name__}")
    ex = CATALOGUE.load(exercise_id, seed=variant_seed(variant_index(exercise_id, text)))
    ex.seed = text  # the student's ID, as feedback and progress name it
    return ex


def check(exercise_id: str, answer: Any, *, seed: int | str | None = None) -> Feedback:
    """Grade ``answer`` for the variant ``seed`` of ``exercise_id``; never raises for any ``answer``.

    An unknown ``exercise_id`` or a bad seed also comes back as feedback (kind
    ``"invalid"``), so a typo in a notebook shows a box, not a traceback.
    """
    try:
        ex = load(exercise_id, seed=seed)
    except Exception as exc:
        fb = Feedback(False, f"Cannot load this exercise: {exc}", "invalid", exercise_id=str(exercise_id)[:40],
                      seed=str(seed)[:MAX_SEED_LENGTH])
    else:
        fb = ex.check(answer)
    record(exercise_id, seed, answer, fb)  # the session's progress (and make grade's log)
    for listener in list(_LISTENERS):
        try:
            listener(fb)
        except Exception:  # a recorder's bug must not reach the student
            pass
    return fb


def summary(chapter: str | None = None, seed: int | str | None = None) -> Progress:
    """This session's progress: which exercises (of ``chapter``, e.g. ``"ch02"``) are right, tried, practised or
    untouched, by the last answer to each under the notebook's ID (``seed``, or the ID of the latest check), as
    the grader counts them; checks under the placeholder ID ``"student-id"`` are practice, never right."""
    return _summary(CATALOGUE.ids(), chapter, seed)
