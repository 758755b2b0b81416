"""A set of exercises by id: how a variant is drawn from a seed, and the never-raising ``check``.

The exercise definitions (course content) live elsewhere, in :mod:`course.exercises`,
which fills a :class:`Catalogue`; this module only knows builders, seeds and ids.

>>> from jacobians.grading import Catalogue, numeric_exercise
>>> toy = Catalogue()
>>> @toy.register("ch01_ex1")
... def _double(rng):
...     x = float(rng.integers(1, 9))
...     return numeric_exercise("Double", f"Give $2 \\\\times {x:g}$.", {"x": x}, 2 * x, [])
>>> ex = toy.load("ch01_ex1", seed="s1234567")
>>> toy.check("ch01_ex1", 2 * ex.given["x"], seed="s1234567").correct
True
>>> ex.seed, toy.load("ch01_ex1", seed=3).seed
('s1234567', '3')
>>> toy.check("ch01_ex1", None, seed=3).kind
'empty'
>>> toy.check("ch99_ex1", 1).kind
'invalid'
"""

from __future__ import annotations

import hashlib
import numbers
from collections.abc import Callable
from typing import Any

import numpy as np

from .exercise import Exercise
from .feedback import Feedback

__all__ = ["Builder", "Catalogue", "exercise_entropy", "seed_value", "stable_hash"]

#: Longest seed (student ID) accepted, in characters.
MAX_SEED_LENGTH = 200

#: A builder draws one variant of an exercise from a seeded generator.
Builder = Callable[[np.random.Generator], Exercise]


def seed_value(seed: object) -> str:
    """A seed checked and written as text: any string (a student ID, stripped of surrounding spaces) or a
    non-negative int (``5`` and ``"5"`` are the same seed); ``None`` is ``"0"``.

    Raises TypeError for other types and ValueError for an empty or overlong string or a negative int.
    """
    if seed is None:
        return "0"
    if isinstance(seed, str):
        text = seed.strip()
        if not text:
            raise ValueError("Expected a seed such as your student ID, got an empty string")
        if len(text) > MAX_SEED_LENGTH:
            raise ValueError(f"Expected a seed of at most {MAX_SEED_LENGTH} characters, got {len(text)}")
        return text
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
        raise TypeError(f"Expected a seed that is a string (your student ID) or an int, got "
                        f"{type(seed).__name__} {seed!r}"[:160])
    if seed < 0:
        raise ValueError(f"Expected a non-negative seed, got {seed}")
    return str(int(seed))


def stable_hash(text: str) -> int:
    """A 64-bit hash of ``text`` that is the same in every process and on every machine (SHA-256;
    Python's own ``hash`` of a string is salted per process)."""
    return int.from_bytes(hashlib.sha256(text.encode("utf-8")).digest()[:8], "big")


def exercise_entropy(seed: object, exercise_id: str) -> tuple[int, int]:
    """The entropy of one exercise's random stream for ``seed``: the stable hashes of the seed and of the
    id, so every exercise draws from its own stream (a :class:`numpy.random.SeedSequence` of both)."""
    return stable_hash("seed:" + seed_value(seed)), stable_hash("exercise:" + exercise_id)


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

    def unregister(self, exercise_id: str) -> None:
        """Remove the builder of ``exercise_id`` (a test's made-up exercise, once the test is done); KeyError if
        there is none."""
        del self._builders[exercise_id]

    def ids(self) -> list[str]:
        """All exercise ids, in chapter order."""
        return sorted(self._builders, key=_order)

    def __contains__(self, exercise_id: object) -> bool:
        return exercise_id in self._builders

    def __len__(self) -> int:
        return len(self._builders)

    def load(self, exercise_id: str, seed: int | str | None = None) -> Exercise:
        """The variant of ``exercise_id`` for ``seed`` (same seed, same numbers).

        Raises ``KeyError`` for an unknown id and ``TypeError``/``ValueError`` for a
        bad seed: these are the author's inputs, not the student's.
        """
        if not isinstance(exercise_id, str):
            raise TypeError(f"Expected an exercise id such as 'ch02_ex1', got {type(exercise_id).__name__}")
        if exercise_id not in self._builders:
            raise KeyError(f"Unknown exercise {exercise_id!r}; known: {', '.join(self.ids())}")
        s = seed_value(seed)
        entropy = exercise_entropy(s, exercise_id)
        rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(list(entropy))))
        ex = self._builders[exercise_id](rng)
        ex.id = exercise_id
        ex.seed = s
        ex.entropy = entropy
        ex.loaded()
        return ex

    def check(self, exercise_id: str, answer: Any, *, seed: int | str | None = None) -> Feedback:
        """Grade ``answer`` for the variant ``seed`` of ``exercise_id``; returns a :class:`Feedback`.

        Never raises for any ``answer``. An unknown ``exercise_id`` or a bad seed
        also comes back as feedback (kind ``"invalid"``), so a typo in a notebook
        shows a box, not a traceback.
        """
        try:
            ex = self.load(exercise_id, seed=seed)
        except Exception as exc:
            return Feedback(False, f"Cannot load this exercise: {exc}", "invalid", exercise_id=str(exercise_id)[:40],
                            seed=str(seed)[:MAX_SEED_LENGTH])
        return ex.check(answer)
