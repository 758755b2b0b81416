r"""Self-graded exercises, the machinery: a checker that names the likely mistake.

This package knows how an answer is read and compared, how a likely mistake
is named and how a verdict is shown. It holds no exercise: the course's
exercises (statements, expected answers, catalogues of mistakes) are defined
in :mod:`course.exercises`, which fills a :class:`Catalogue` and gives the
notebooks ``exercises.load(id, seed=...)`` and ``exercises.check(id, answer, seed=...)``.

>>> import numpy as np
>>> from jacobians import grading
>>> ex = grading.numeric_exercise(
...     "Screw axis", "Give the screw axis.", {}, np.array([0, 0, 1, 0, -1, 0.0]),
...     [grading.Mistake("v_sign", np.array([0, 0, 1, 0, 1, 0.0]), "The linear part has the wrong sign.")])
>>> ex.check([0, 0, 1, 0, -1, 0]).correct
True
>>> fb = ex.check([0, 0, 1, 0, 1, 0])
>>> fb.correct, fb.mistake, fb.message
(False, 'v_sign', 'The linear part has the wrong sign.')
>>> ex.check(None).kind, ex.check("0 0 1 0 -1 0").kind
('empty', 'invalid')

What the checker promises:

* it never raises at a student, whatever comes (``None``, text, ragged
  lists, NaN, huge arrays, objects of other types, functions that raise or
  loop): it returns a :class:`Feedback`;
* it never evaluates text (a string answer is refused politely, never
  sympified) and never changes the answer it is given (it works on copies);
* a numeric exercise states the precision it wants (``decimals``): an
  answer rounded to it is right, and an answer right only to the fewer
  decimals it was given in is asked for more decimals, not called wrong;
* a wrong answer is compared with each mistake of the exercise's catalogue,
  computed from the reference for that variant; the message says what to
  look at, not the answer, and never repeats the student's value. Otherwise
  the wrong entries are located by row and column, with what to check;
* the seed may be any text (a student ID): it is hashed stably, and every
  exercise draws from its own stream (a SeedSequence of the seed's hash and
  the id's hash).

Symbolic answers (sympy expressions or matrices in the exercise's symbols)
are compared by simplification and by evaluation at random points; function
answers are run on seeded random inputs against the reference, with a time
guard.

Modules: :mod:`~jacobians.grading.feedback` (the verdict and its HTML box),
:mod:`~jacobians.grading.answers` (any answer to a float array, or a polite
refusal), :mod:`~jacobians.grading.compare` (reference and mistakes),
:mod:`~jacobians.grading.guard` (running a student's function),
:mod:`~jacobians.grading.exercise` (one variant: a class per kind, one protocol),
:mod:`~jacobians.grading.catalogue` (exercises by id and seed).
"""

from __future__ import annotations

from .answers import MAX_ENTRIES
from .catalogue import Catalogue, exercise_entropy, seed_value, stable_hash
from .compare import Mistake, compare
from .exercise import (
                       Case,
                       Exercise,
                       FunctionExercise,
                       NumericExercise,
                       PredicateExercise,
                       ScalarExercise,
                       SymbolicExercise,
                       function_exercise,
                       numeric_exercise,
                       predicate_exercise,
                       scalar_exercise,
                       symbolic_exercise,
)
from .feedback import Feedback
from .guard import TIME_LIMIT

__all__ = ["MAX_ENTRIES", "TIME_LIMIT", "Case", "Catalogue", "Exercise", "Feedback", "FunctionExercise", "Mistake",
           "NumericExercise", "PredicateExercise", "ScalarExercise", "SymbolicExercise", "compare",
           "exercise_entropy", "function_exercise", "numeric_exercise", "predicate_exercise", "scalar_exercise",
           "seed_value", "stable_hash", "symbolic_exercise"]
