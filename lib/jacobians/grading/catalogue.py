"""A set of exercises by id: how a variant is drawn from a seed, and the never-raising ``check``.

The exercise definitions (course content) live elsewhere, in :mod:`course.exercises`,
which fills a :class:`Catalogue`; this module only knows builders, seeds and ids.

>>> from jacobians.grading import Catalogue, numeric_exercise
>>> toy = Catalogue()
>>> @toy.register("ch01_ex1")
... def _double(rng):
...     x = float(rng.integers(1, 9))
...     return numeric_exercise("Double", f"Give $2 \\\\times {x:g}$.", {"x": x}, 2 * x, [])
>>> ex = toy.load("ch01_ex1", seed=3)
>>> toy.check("ch01_ex1", 2 * ex.given["x"], seed=3).correct
True
>>> toy.check("ch01_ex1", None, seed=3).kind
'empty'
>>> toy.check("ch99_ex1", 1).kind
'invalid'
"""

from __future__ import annotations

import numbers
from collections.abc import Callable
from typing import Any

import numpy as np

from .compare import distinct_mistakes
from .exercise import Exercise
from .feedback import Feedback

__all__ = ["SEED_ENV", "Builder", "Catalogue", "seed_value"]

#: Environment variable the notebooks read their seed from.
SEED_ENV = "JACOBIANS_SEED"

#: A builder draws one variant of an exercise from a seeded generator.
Builder = Callable[[np.random.Generator], Exercise]


def seed_value(seed: object) -> int:
    """A seed checked: ``None`` is 0; otherwise a non-negative int (TypeError / ValueError if not)."""
    if seed is None:
        return 0
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
        raise TypeError(f"Expected an int seed, got {type(seed).__name__} {seed!r}"[:120])
    if seed < 0:
        raise ValueError(f"Expected a non-negative seed, got {seed}")
    return int(seed)


def _order(exercise_id: str) -> tuple[str, int]:
    """Sort key of ids such as ``ch02_ex10``: by chapter, then by exercise number."""
    chapter, _, number = exercise_id.partition("_ex")
    return chapter, int(number) if number.isdigit() else 0


class Catalogue:
    """Exercise builders by id; :meth:`load` draws a variant, :meth:`check` grades an answer."""

    def __init__(self) -> None:
        self._builders: dict[str, Builder] = {}

    def register(self, exercise_id: str) -> Callable[[Builder], Builder]:
        """Decorator adding a builder under ``exercise_id`` (ids like ``"ch02_ex1"``, each once)."""
        if "_ex" not in str(exercise_id):
            raise ValueError(f"Expected an exercise id such as 'ch02_ex1', got {exercise_id!r}")

        def deco(builder: Builder) -> Builder:
            if exercise_id in self._builders:
                raise ValueError(f"Exercise {exercise_id!r} is registered twice")
            self._builders[exercise_id] = builder
            return builder
        return deco

    def ids(self) -> list[str]:
        """All exercise ids, in chapter order."""
        return sorted(self._builders, key=_order)

    def __contains__(self, exercise_id: object) -> bool:
        return exercise_id in self._builders

    def __len__(self) -> int:
        return len(self._builders)

    def load(self, exercise_id: str, seed: int | None = None) -> Exercise:
        """The variant of ``exercise_id`` for ``seed`` (same seed, same numbers).

        Raises ``KeyError`` for an unknown id and ``TypeError``/``ValueError`` for a
        bad seed: these are the author's inputs, not the student's.
        """
        if not isinstance(exercise_id, str):
            raise TypeError(f"Expected an exercise id such as 'ch02_ex1', got {type(exercise_id).__name__}")
        if exercise_id not in self._builders:
            raise KeyError(f"Unknown exercise {exercise_id!r}; known: {', '.join(self.ids())}")
        s = seed_value(seed)
        rng = np.random.default_rng([s, sum(map(ord, exercise_id))])
        ex = self._builders[exercise_id](rng)
        ex.id = exercise_id
        ex.seed = s
        if ex.kind == "numeric":
            ex.mistakes = distinct_mistakes(ex.reference, ex.mistakes, ex.rtol, ex.atol)
        return ex

    def check(self, exercise_id: str, answer: Any, *, seed: int | None = None) -> Feedback:
        """Grade ``answer`` for the variant ``seed`` of ``exercise_id``; returns a :class:`Feedback`.

        Never raises for any ``answer``. An unknown ``exercise_id`` or a bad seed
        also comes back as feedback (kind ``"invalid"``), so a typo in a notebook
        shows a box, not a traceback.
        """
        try:
            ex = self.load(exercise_id, seed=seed)
        except Exception as exc:
            return Feedback(False, f"Cannot load this exercise: {exc}", "invalid", exercise_id=str(exercise_id)[:40])
        return ex.check(answer)
