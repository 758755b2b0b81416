"""The course's exercises: 39 definitions (statements' data, expected answers, named mistakes).

Each builder takes a seeded ``numpy.random.Generator`` and returns a
:class:`jacobians.grading.Exercise`; the grading machinery (reading, comparing,
naming mistakes, showing verdicts) is :mod:`jacobians.grading`. The exercise
pages call::

    from course import exercises
    ex1 = exercises.load("ch02_ex1", seed=SEED)      # the statement of this variant
    exercises.check("ch02_ex1", answer, seed=SEED)    # the verdict, never an exception

>>> from course import exercises
>>> len(exercises.exercise_ids())
39
>>> ex = exercises.load("ch01_ex1", seed=3)
>>> sorted(ex.given)
['omega', 'q']
>>> exercises.check("ch01_ex1", ex.solution(), seed=3).correct
True
>>> fb = exercises.check("ch01_ex1", None, seed=3)
>>> fb.correct, fb.kind
(False, 'empty')
>>> exercises.check("ch01_ex1", "0 0 1 0 0 0", seed=3).kind
'invalid'

Modules: ``ch01`` ... ``ch09`` (the definitions, one module per chapter);
``_registry`` (the catalogue they fill); shared by them: ``_variants`` (random
angles, lengths, chains, poses; test cases of function exercises), ``_kinematics``
(the references' plain-numpy formulas), ``_mistakes`` (mistakes met in many
exercises), ``_latex`` (numbers in statements), ``_symbolic_2r`` (the planar 2R
arm in sympy).
"""

from __future__ import annotations

from typing import Any

from jacobians.grading import SEED_ENV, Exercise, Feedback

from . import ch01, ch02, ch03, ch04, ch05, ch06, ch07, ch08, ch09  # noqa: F401  (importing them registers the exercises)
from ._progress import Progress, record
from ._progress import summary as _summary
from ._registry import CATALOGUE

__all__ = ["CATALOGUE", "SEED_ENV", "check", "exercise_ids", "load", "summary"]


def exercise_ids() -> list[str]:
    """All exercise ids, in chapter order."""
    return CATALOGUE.ids()


def load(exercise_id: str, seed: int | None = None) -> Exercise:
    """The variant of ``exercise_id`` for ``seed`` (same seed, same numbers).

    Raises ``KeyError`` for an unknown id and ``TypeError``/``ValueError`` for a
    bad seed: these are the author's inputs, not the student's.
    """
    return CATALOGUE.load(exercise_id, seed=seed)


def check(exercise_id: str, answer: Any, *, seed: int | None = None) -> Feedback:
    """Grade ``answer`` for the variant ``seed`` of ``exercise_id``; never raises for any ``answer``.

    An unknown ``exercise_id`` or a bad seed also comes back as feedback (kind
    ``"invalid"``), so a typo in a notebook shows a box, not a traceback.
    """
    feedback = CATALOGUE.check(exercise_id, answer, seed=seed)
    record(exercise_id, seed, answer, feedback)  # the session's progress (and make grade's log)
    return feedback


def summary(chapter: str | None = None) -> Progress:
    """This session's progress: which exercises (of ``chapter``, e.g. ``"ch02"``) are right, tried, untouched."""
    return _summary(CATALOGUE.ids(), chapter)
