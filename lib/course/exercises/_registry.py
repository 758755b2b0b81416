"""The catalogue of the course's exercises, which the chapter modules fill."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from jacobians.grading import Case, Catalogue, Exercise, Mistake, function_exercise
from jacobians.grading.catalogue import Builder

from ._hints import HINTS

__all__ = ["CATALOGUE", "LIBRARY_CHECKS", "CodeVariant", "LibraryCheck", "register", "register_code"]

#: Every exercise of the course, by id.
CATALOGUE = Catalogue()

#: A cross-check of one variant's reference against the library (``jacobians``), computed another way than the
#: definition computes it: it raises AssertionError when the two disagree.
LibraryCheck = Callable[[Exercise], None]

#: The library check of each exercise that has one, by id (``tests/test_exercise_library.py`` runs them all).
LIBRARY_CHECKS: dict[str, LibraryCheck] = {}


def register(exercise_id: str, *, library: LibraryCheck | None = None) -> Callable[[Builder], Builder]:
    """Decorator adding a builder ``rng -> Exercise`` under an id, with its ``library`` check (see
    :data:`LibraryCheck`); an exercise without a hint of its own gets the one of
    :data:`~course.exercises._hints.HINTS` (what to check when no catalogued mistake matches)."""
    if library is not None:
        LIBRARY_CHECKS[exercise_id] = library

    def deco(builder: Builder) -> Builder:
        def build(rng: np.random.Generator) -> Exercise:
            ex = builder(rng)
            if not ex.hint:
                ex.hint = HINTS.get(exercise_id, "")
            return ex
        build.__doc__ = builder.__doc__
        CATALOGUE.register(exercise_id)(build)
        return builder
    return deco


class CodeVariant(NamedTuple):
    """One variant of a function exercise: its statement, reference, test cases, the function's name,
    what it returns, and the facts of the variant (its ``given``); optionally the test cases after the random
    ones, the mistake of a function that runs out of time, an adapter of the result (see
    :func:`jacobians.grading.function_exercise`), an example drawn per seed, added to the statement, and the
    number of random cases (6 if None)."""

    statement: str
    reference: Callable[..., Any]
    make_case: Callable[[np.random.Generator], Case]
    fn_name: str
    what: str
    given: dict[str, Any]
    more_cases: Callable[[np.random.Generator], list[Case]] | None = None
    on_timeout: Mistake | None = None
    adapt: Callable[[Any, tuple[Any, ...], Any], Any] | None = None
    example: Callable[[np.random.Generator], tuple[str, dict[str, Any]]] | None = None
    n_cases: int | None = None


def register_code(exercise_id: str, title: str, variants: list[CodeVariant], *,
                  library: LibraryCheck | None = None) -> None:
    """Add a function exercise: the seed picks one of ``variants``; the student writes its ``fn_name``,
    tested on the cases its ``make_case`` draws (from the variant's own stream); ``library`` as for
    :func:`register`."""
    if library is not None:
        LIBRARY_CHECKS[exercise_id] = library
    def build(rng: np.random.Generator) -> Exercise:
        v = variants[int(rng.integers(len(variants)))]
        statement, given = v.statement, dict(v.given)
        if v.example is not None:
            text, facts = v.example(rng)
            statement, given = statement + "\n\n" + text, {**given, **facts}
        ex = function_exercise(title, statement, reference=v.reference, make_case=v.make_case, fn_name=v.fn_name,
                               what=v.what, more_cases=v.more_cases, on_timeout=v.on_timeout, adapt=v.adapt)
        ex.given = given
        ex.hint = HINTS.get(exercise_id, "")
        if v.n_cases is not None:
            ex.n_cases = v.n_cases
        return ex
    CATALOGUE.register(exercise_id)(build)
