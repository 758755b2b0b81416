"""One variant of an exercise, and how it grades an answer of each kind.

Four kinds: ``numeric`` (a number, vector or matrix, compared with a
tolerance), ``symbolic`` (a sympy expression or matrix in the exercise's
symbols, compared at random points and by simplification), ``function`` (a
student's function, run on seeded random test cases, each a :class:`Case`)
and ``predicate`` (a number tested by a rule, for answers that are not unique).

>>> ex = numeric_exercise("Twice", "Give twice 3.", {}, 6.0, [Mistake("sum", 5.0, "That is 2 + 3.")])
>>> ex.check(6).correct, ex.check(5).mistake, ex.check("6").kind
(True, 'sum', 'invalid')
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from .answers import Refused, as_array, describe, is_sympy, sympy
from .compare import Mistake, compare
from .feedback import Feedback, verdict
from .sandbox import run_guarded

__all__ = ["Case", "Exercise", "function_exercise", "numeric_exercise", "predicate_exercise",
           "symbolic_exercise"]


class Case(NamedTuple):
    """One test input of a function exercise: the arguments, the reference output, the catalogue of
    mistakes for this input, and a label saying what the input is."""

    args: tuple[Any, ...]
    reference: Any
    mistakes: list[Mistake]
    label: str


@dataclass
class Exercise:
    """One randomised variant of an exercise.

    Attributes
    ----------
    id : str
    title : str
    statement : str
        Markdown with LaTeX (``$...$``) giving the task and this variant's numbers.
    given : dict
        The numbers (and symbols) a student needs, as numpy arrays / sympy objects.
    kind : {"numeric", "symbolic", "function", "predicate"}
    """

    id: str
    title: str
    statement: str
    given: dict[str, Any]
    kind: str
    reference: Any = None
    mistakes: list[Mistake] = field(default_factory=list)
    what: str = "answer"
    hint: str = ""
    rtol: float = 2e-3
    atol: float = 2e-3
    symbols: dict[str, Any] = field(default_factory=dict)
    # function exercises: rng -> Case
    make_case: Callable[[np.random.Generator], Case] | None = None
    n_cases: int = 6
    fn_name: str = "your function"
    # predicate exercises: float array -> Feedback
    predicate: Callable[[NDArray[np.float64]], Feedback] | None = None
    seed: int = 0

    # ------------------------------------------------------------ display
    def _repr_markdown_(self) -> str:
        return f"**{self.title}** (`{self.id}`, variant {self.seed})\n\n{self.statement}"

    def __repr__(self) -> str:
        return f"<Exercise {self.id} seed={self.seed}: {self.title}>"

    def solution(self) -> Any:
        """The reference answer (instructors): array, sympy Matrix or function."""
        if isinstance(self.reference, np.ndarray):
            return self.reference.copy()
        return self.reference

    # ------------------------------------------------------------ grading
    def check(self, answer: Any) -> Feedback:
        """Grade ``answer``; never raises, never mutates ``answer``."""
        try:
            fb = self._check(answer)
        except Refused as r:
            fb = Feedback(False, r.message, r.kind)
        except Exception as exc:  # a checker bug must not reach the student as a traceback
            fb = Feedback(False, "The checker could not grade this answer (" + type(exc).__name__ +
                          "). Check that it is a number, a matrix or a function as asked.", "invalid")
        fb.exercise_id = self.id
        return fb

    def _check(self, answer: Any) -> Feedback:
        if answer is None:
            raise Refused("Set `answer` to your result and run the check cell again.", "empty")
        if self.kind == "function":
            return self._check_function(answer)
        if self.kind == "symbolic":
            return self._check_symbolic(answer)
        arr = as_array(answer)
        if self.kind == "predicate":
            if not np.all(np.isfinite(arr)):
                return verdict(False, "Your answer contains NaN or inf.", mistake="not_finite")
            if self.predicate is None:
                raise ValueError(f"Exercise {self.id!r} is a predicate exercise without a predicate")
            return self.predicate(arr)
        return compare(arr, self.reference, self.mistakes, self.rtol, self.atol, self.what, self.hint)

    def _check_function(self, fn: Any) -> Feedback:
        if isinstance(fn, (str, bytes)):
            raise Refused("Please give your function itself (its name, without quotes or brackets), not text.")
        if not callable(fn):
            raise Refused(f"This exercise wants a function (define `{self.fn_name}` and set "
                          f"`answer = {self.fn_name}`), but you gave {describe(fn)}.")
        if self.make_case is None:
            raise ValueError(f"Exercise {self.id!r} is a function exercise without test cases")
        rng = np.random.default_rng(self.seed + 1000)
        for case in range(self.n_cases):
            args, ref, mistakes, label = self.make_case(rng)
            ok, out = run_guarded(fn, copy.deepcopy(args))
            if not ok:
                return verdict(False, f"On test {case + 1} ({label}) {out}.", mistake="raised")
            try:
                arr = as_array(out)
            except Refused as r:
                if r.kind == "empty":
                    return verdict(False, f"On test {case + 1} ({label}) your function returned None: "
                                   "did you forget `return`?", mistake="returned_none")
                return verdict(False, f"On test {case + 1} ({label}) your function's result could not be graded: "
                               + r.message, mistake="bad_return")
            # Code is compared tightly: the same computation agrees to rounding error.
            fb = compare(arr, ref, mistakes, 1e-6, 1e-8, self.what, self.hint)
            if not fb.correct:
                fb.message = f"On test {case + 1} ({label}): {fb.message}"
                return fb
        return verdict(True, f"Your function matches the reference on all {self.n_cases} random tests.")

    def _check_symbolic(self, answer: Any) -> Feedback:
        sp = sympy()
        ref = self.reference
        names = {str(s): s for s in self.symbols.values()}
        # Numeric route first (fast, and it names mistakes): evaluate at random points.
        rng = np.random.default_rng(self.seed + 77)
        for _ in range(3):
            point = {name: float(rng.uniform(0.3, 1.4)) * (float(rng.choice([-1, 1])) if name.startswith("th")
                                                           else 1.0)
                     for name in names}
            arr = as_array(answer, subs=point)
            r = _eval_sym(ref, point)
            ms = [Mistake(m.name, _eval_sym(m.value, point), m.message) for m in self.mistakes]
            result = compare(arr, r, ms, 1e-6, 1e-8, self.what, self.hint)
            if not result.correct:
                return result
        # Exact route: the difference simplifies to zero.
        if is_sympy(answer) and isinstance(answer, (sp.MatrixBase, sp.Expr)):
            try:
                A = answer if isinstance(answer, sp.MatrixBase) else sp.Matrix([answer])
                sub = {s: names[str(s)] for s in A.free_symbols if str(s) in names}
                diff = (A.xreplace(sub).reshape(*ref.shape) - ref).applyfunc(sp.simplify)
                if all(e == 0 for e in diff):
                    return verdict(True, f"Your {self.what} simplifies to the reference.")
            except Exception:
                pass
        return verdict(True, f"Your {self.what} agrees with the reference at random values of "
                       f"{', '.join(sorted(names))}.")


def _eval_sym(expr: Any, point: dict[str, float]) -> NDArray[np.float64]:
    sp = sympy()
    sub = {s: point[str(s)] for s in expr.free_symbols}
    val = expr.xreplace(sub) if sub else expr
    if isinstance(val, sp.MatrixBase):
        return np.array(val.evalf().tolist(), dtype=float)
    return np.asarray(float(val.evalf()))


# --------------------------------------------------------------------------- one constructor per kind
# The id and the seed are set by the catalogue that loads the variant.

def numeric_exercise(title: str, statement: str, given: dict[str, Any], reference: Any,
                     mistakes: list[Mistake], *, what: str = "answer", hint: str = "") -> Exercise:
    """A number, vector or matrix, compared with a tolerance of 2e-3 (three typed decimals)."""
    return Exercise("", title, statement, given, "numeric", reference, mistakes, what=what, hint=hint)


def symbolic_exercise(title: str, statement: str, symbols: dict[str, Any], reference: Any,
                      mistakes: list[Mistake], *, what: str = "answer") -> Exercise:
    """A sympy expression or matrix in ``symbols`` (name -> sympy Symbol), which are also the given."""
    return Exercise("", title, statement, {"symbols": symbols}, "symbolic", reference, mistakes,
                    symbols=symbols, what=what)


def function_exercise(title: str, statement: str, *, reference: Callable[..., Any],
                      make_case: Callable[[np.random.Generator], Case], fn_name: str, what: str) -> Exercise:
    """A student's function named ``fn_name``, run on the cases ``make_case`` draws."""
    return Exercise("", title, statement, {}, "function", reference=reference, make_case=make_case,
                    fn_name=fn_name, what=what)


def predicate_exercise(title: str, statement: str, given: dict[str, Any], reference: Any,
                       predicate: Callable[[NDArray[np.float64]], Feedback], *, what: str = "answer") -> Exercise:
    """A number judged by ``predicate`` (answers that are not unique); ``reference`` is one right answer."""
    return Exercise("", title, statement, given, "predicate", reference, [], predicate=predicate, what=what)
