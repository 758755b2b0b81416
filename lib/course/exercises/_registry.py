"""The catalogue of the course's exercises, which the chapter modules fill."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from jacobians.grading import Case, Catalogue, Exercise, function_exercise

__all__ = ["CATALOGUE", "register", "register_code"]

#: Every exercise of the course, by id.
CATALOGUE = Catalogue()

#: Decorator adding a builder ``rng -> Exercise`` under an id.
register = CATALOGUE.register


def register_code(exercise_id: str, title: str, statement: str, *, reference: Callable[..., Any],
                  make_case: Callable[[np.random.Generator], Case], fn_name: str, what: str) -> None:
    """Add a function exercise: the student writes ``fn_name``, tested on the cases ``make_case`` draws."""
    def build(rng: np.random.Generator) -> Exercise:
        return function_exercise(title, statement, reference=reference, make_case=make_case, fn_name=fn_name,
                                 what=what)
    register(exercise_id)(build)
