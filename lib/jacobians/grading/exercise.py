"""One variant of an exercise, and how it grades an answer of each kind.

Five kinds, one class each, all graded through :meth:`Exercise.check`: ``numeric``
(a number, vector or matrix, compared to the precision the statement asks for), ``scalar`` (one number, one of several
right values, within a stated range), ``symbolic`` (a sympy expression or matrix in the exercise's
symbols, compared at random points and by simplification), ``function`` (a
student's function, run on seeded random test cases, each a :class:`Case`)
and ``predicate`` (a number tested by a rule, for answers that are not unique).

>>> ex = numeric_exercise("Twice", "Give twice 3.", {}, 6.0, [Mistake("sum", 5.0, "That is 2 + 3.")])
>>> ex.check(6).correct, ex.check(5).mistake, ex.check("6").kind
(True, 'sum', 'invalid')
"""

from __future__ import annotations

import copy
import functools
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar, NamedTuple

import numpy as np
from numpy.typing import NDArray

from .answers import Refused, as_array, describe, is_sympy, sympy
from .compare import Mistake, compare, distinct_mistakes, given_decimals, precision_message
from .feedback import Feedback, agrees, verdict
from .guard import run_guarded
from .rounding import Method, Rule, derive_rule, direct_rule, rule_sentence

__all__ = ["Case", "Exercise", "FunctionExercise", "Interval", "NumericExercise", "PredicateExercise", "ScalarExercise",
           "SymbolicExercise", "function_exercise", "numeric_exercise", "predicate_exercise", "scalar_exercise",
           "symbolic_exercise"]

#: Decimals a numeric answer is asked for unless the exercise says otherwise.
DECIMALS = 3


class Interval(NamedTuple):
    """An open range ``(low, high)`` a scalar answer must lie in, and how the statement writes it."""

    low: float
    high: float
    text: str


def precision_sentence(decimals: int, scalar: bool) -> str:
    """What the statement says about precision."""
    return rule_sentence(direct_rule(decimals), scalar)


#: The test cases of function exercises already drawn in this process, by (id, entropy): at most 64.
_CASES: dict[tuple[str, tuple[int, int]], list[Case]] = {}


class Case(NamedTuple):
    """One test input of a function exercise: the arguments, the reference output, the catalogue of
    mistakes for this input, and a label saying what the input is."""

    args: tuple[Any, ...]
    reference: Any
    mistakes: list[Mistake]
    label: str


@dataclass
class Exercise:
    """One randomised variant of an exercise: what every kind has. Each kind is a subclass
    (:class:`NumericExercise`, :class:`ScalarExercise`, :class:`SymbolicExercise`, :class:`FunctionExercise`,
    :class:`PredicateExercise`) that names itself in ``kind`` and grades an answer in :meth:`_grade`.

    Attributes
    ----------
    id : str
    title : str
    statement : str
        Markdown with LaTeX (``$...$``) giving the task and this variant's numbers.
    given : dict
        The numbers (and symbols) a student needs, as numpy arrays / sympy objects.
    reference : object
        The right answer (array, sympy object, or the reference function).
    mistakes : list of Mistake
        The catalogue of likely mistakes, each with its value for this variant and its message.
    seed : str
        The seed as text (a student ID, or an int written out).
    entropy : tuple of int
        The stable hashes of the seed and the id that seeded this variant's stream.
    kind : str
        The kind's name (class attribute): "numeric", "scalar", "symbolic", "function" or "predicate".
    """

    kind: ClassVar[str] = ""

    id: str
    title: str
    statement: str
    given: dict[str, Any]
    reference: Any = None
    mistakes: list[Mistake] = field(default_factory=list)
    what: str = "answer"
    hint: str = ""
    seed: str = "0"
    entropy: tuple[int, int] = (0, 0)

    # ------------------------------------------------------------ display
    def _repr_markdown_(self) -> str:
        return f"**{self.title}** (`{self.id}`, your variant for seed `{self.seed}`)\n\n{self.statement}"

    def __repr__(self) -> str:
        return f"<Exercise {self.id} seed={self.seed!r}: {self.title}>"

    def _rng(self, salt: int) -> np.random.Generator:
        """A generator of this variant's own (test cases, evaluation points), from its entropy."""
        return np.random.Generator(np.random.PCG64(np.random.SeedSequence([*self.entropy, salt])))

    def solution(self) -> Any:
        """The reference answer (instructors): array, sympy Matrix or function."""
        if isinstance(self.reference, np.ndarray):
            return self.reference.copy()
        return self.reference

    def loaded(self) -> None:
        """Called by the catalogue once the id and the seed are set (a kind may settle its catalogue here)."""

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
        fb.seed = self.seed
        fb.title = self.title
        fb.statement = self.statement
        return fb

    def _check(self, answer: Any) -> Feedback:
        if answer is None:
            raise Refused("Set `answer` to your result and run the check cell again.", "empty")
        return self._grade(answer)

    def _grade(self, answer: Any) -> Feedback:
        """The verdict on an answer that is not None (may raise :class:`Refused`); each kind defines it."""
        raise NotImplementedError(f"{type(self).__name__} does not grade answers: use one of the kinds")


@dataclass(repr=False)
class NumericExercise(Exercise):
    """A number, vector or matrix, compared entry by entry with the reference to the precision the statement
    asks for.

    Attributes
    ----------
    decimals : int or None
        The precision the statement asks for.
    tol : float or None
        The accepted tolerance the statement prints: an answer within ``tol`` of the reference, entry by entry,
        is right. It is derived from the exercise's ``method`` (see :mod:`jacobians.grading.rounding`).
    carry : int or None
        The decimals the statement asks the student to carry through the steps.
    method : callable or None
        The intended computation, with every written-down intermediate passed through ``r`` (``method(r)``).
    """

    kind: ClassVar[str] = "numeric"

    rtol: float = 2e-3
    atol: float = 2e-3
    decimals: int | None = None
    tol: float | None = None
    carry: int | None = None
    method: Method | None = None

    def loaded(self) -> None:
        """Drop the catalogued mistakes the stated rule cannot tell from the reference (or from each other)."""
        self.mistakes = distinct_mistakes(self.reference, self.mistakes, self.rtol, self.atol, self.decimals,
                                          self.tol)

    def _grade(self, answer: Any) -> Feedback:
        return compare(as_array(answer), self.reference, self.mistakes, self.rtol, self.atol, self.what, self.hint,
                       decimals=self.decimals, tol=self.tol,
                       carry=self.carry if self.method is not None else None)


@dataclass(repr=False)
class ScalarExercise(Exercise):
    """One number with possibly several right values (``accepted``) inside a stated range (``interval``); a
    right value outside it (``outside``) is told to be right but for a multiple of 2π."""

    kind: ClassVar[str] = "scalar"
    #: A scalar answer is right within half a unit of the last decimal asked: no printed tolerance.
    tol: ClassVar[None] = None

    accepted: list[float] = field(default_factory=list)
    outside: list[float] = field(default_factory=list)
    interval: Interval | None = None
    decimals: int | None = None

    def _grade(self, answer: Any) -> Feedback:
        arr = as_array(answer)
        d = self.decimals if self.decimals is not None else DECIMALS
        if arr.size != 1:
            return verdict(False, f"Give one number (the {self.what}); you gave {arr.size} values.",
                           mistake="wrong_shape")
        x = float(arr.ravel()[0])
        if not np.isfinite(x):
            return verdict(False, "Your answer is NaN or inf: check for a division by zero.", mistake="not_finite")
        tol = 0.5 * 10.0 ** (-d) * (1 + 1e-6)
        k = given_decimals(np.asarray(x), d)
        coarse = 0.5 * 10.0 ** (-k) * (1 + 1e-6) if k is not None else tol

        def near(values: list[float], within: float) -> bool:
            return any(abs(x - v) <= within for v in values)

        if near(self.accepted, tol):
            verb = agrees(self.what, "is", "are")
            return verdict(True, f"Your {self.what} {verb} right (to the {d} decimals asked).")
        for m in self.mistakes:
            if near([float(m.value)], max(tol, coarse if k is not None and k > 0 else tol)):
                return verdict(False, m.message, mistake=m.name)
        if self.interval is not None and not self.interval.low < x < self.interval.high:
            msg = f"The statement asks for a value in {self.interval.text}, and yours lies outside that range."
            if near(self.outside, max(tol, coarse)):
                msg += (f" It does give the same configuration as the {self.what} asked for: add or subtract "
                        "a multiple of 2π to bring it into the range.")
                return verdict(False, msg, mistake="outside_range")
            return verdict(False, msg + " " + (self.hint or ""), mistake="outside_range")
        if k is not None and k > 0 and near(self.accepted, coarse):
            return verdict(False, precision_message(self.what, k, d), mistake="too_few_decimals")
        verb = agrees(self.what, "is", "are")
        return verdict(False, f"Your {self.what} {verb} not right. {self.hint}".strip(), mistake="wrong_value")



@dataclass(repr=False)
class FunctionExercise(Exercise):
    """A student's function, run on seeded random test cases (each a :class:`Case`) against the reference.

    Attributes
    ----------
    make_case : callable
        ``rng -> Case``: one random test case.
    n_cases : int
        How many random cases are run.
    fn_name : str
        The name the statement asks the function to have.
    more_cases, on_timeout, adapt
        More test cases after the random ones (e.g. the edge cases a statement promises), a mistake to name when
        the function runs out of time, and an adapter of the function's result (the value to compare, or a
        verdict).
    """

    kind: ClassVar[str] = "function"

    make_case: Callable[[np.random.Generator], Case] | None = None
    n_cases: int = 6
    fn_name: str = "your function"
    more_cases: Callable[[np.random.Generator], list[Case]] | None = None
    on_timeout: Mistake | None = None
    adapt: Callable[[Any, tuple[Any, ...], Any], Any] | None = None

    def _grade(self, fn: Any) -> Feedback:
        if isinstance(fn, (str, bytes)):
            raise Refused("Please give your function itself (its name, without quotes or brackets), not text.")
        if not callable(fn):
            raise Refused(f"This exercise wants a function (define `{self.fn_name}` and set "
                          f"`answer = {self.fn_name}`), but you gave {describe(fn)}.")
        if self.make_case is None:
            raise ValueError(f"Exercise {self.id!r} is a function exercise without test cases")
        cases = self.cases()
        # A wrong result that several catalogued mistakes produce on one test names none of them there; the
        # tests after it may tell them apart (the names left are those that fit every test some of them fit).
        # A test no catalogued mistake explains is passed over in that search; if no test names one mistake,
        # the first wrong test is reported.
        first: Feedback | None = None
        where = ""
        candidates: set[str] | None = None
        for case, (args, ref, mistakes, label) in enumerate(cases):
            arr = self._result(fn, case, args, ref, label)
            if isinstance(arr, Feedback):
                return arr
            # Code is compared tightly: the same computation agrees to rounding error.
            fb = compare(arr, ref, mistakes, 1e-6, 1e-8, self.what, self.hint)
            if fb.correct:
                continue
            fb.message = f"On test {case + 1} ({label}): {fb.message}"
            if first is None:
                first, where = fb, f"On test {case + 1} ({label})"
            names = {m.name for m in mistakes if _matches(arr, m.value)}
            if not names:
                continue
            candidates = names if candidates is None else (candidates & names or names)
            if len(candidates) == 1:
                name = next(iter(candidates))
                msg = next(m.message for m in mistakes if m.name == name)
                return verdict(False, f"On test {case + 1} ({label}): {msg}", mistake=name)
        if first is None:
            return verdict(True, f"Your function matches the reference on all {len(cases)} tests.")
        if candidates:
            known = {m.name: m.message for c in cases for m in c.mistakes}
            options = " Or: ".join(known[n] for n in sorted(candidates))
            return verdict(False, f"{where} your result differs from the reference. On every test it fails, it is "
                           f"what more than one mistake gives, so either of these: {options}",
                           mistake="ambiguous")
        return first

    def _result(self, fn: Any, case: int, args: tuple[Any, ...], ref: Any, label: str
                ) -> NDArray[np.float64] | Feedback:
        """The function's result on test ``case`` (on a copy of its arguments) as the array compared, or the
        verdict that ends the grading there (it raised, ran out of time, returned nothing gradable, or the
        adapter decided)."""
        ok, out = run_guarded(fn, copy.deepcopy(args))
        if not ok:
            if out.startswith("your function did not finish") and self.on_timeout is not None:
                return verdict(False, f"On test {case + 1} ({label}) {out}. {self.on_timeout.message}",
                               mistake=self.on_timeout.name)
            return verdict(False, f"On test {case + 1} ({label}) {out}.", mistake="raised")
        if self.adapt is not None:
            adapted = self.adapt(out, args, ref)
            if isinstance(adapted, Feedback):
                adapted.message = f"On test {case + 1} ({label}): {adapted.message}"
                return adapted
            out = adapted
        try:
            return as_array(out)
        except Refused as r:
            if r.kind == "empty":
                return verdict(False, f"On test {case + 1} ({label}) your function returned None: "
                               "did you forget `return`?", mistake="returned_none")
            return verdict(False, f"On test {case + 1} ({label}) your function's result could not be graded: "
                           + r.message, mistake="bad_return")

    def cases(self) -> list[Case]:
        """The test cases of a function exercise, in the order they are run: ``n_cases`` drawn by
        ``make_case``, then those of ``more_cases`` (each from this variant's own stream). They depend on the
        exercise and the seed only, so they are drawn once per process (:data:`_CASES`); the checker passes
        copies of their arguments to the student's function."""
        if self.make_case is None:
            return []
        key = (self.id, self.entropy)
        if key in _CASES and self.id:
            return _CASES[key]
        rng = self._rng(1000)
        out = [self.make_case(rng) for _ in range(self.n_cases)]
        if self.more_cases is not None:
            out += self.more_cases(self._rng(2000))
        if self.id:
            if len(_CASES) >= 64:
                _CASES.pop(next(iter(_CASES)))
            _CASES[key] = out
        return out



@dataclass(repr=False)
class SymbolicExercise(Exercise):
    """A sympy expression or matrix in ``symbols`` (name -> sympy Symbol), compared at random points."""

    kind: ClassVar[str] = "symbolic"

    symbols: dict[str, Any] = field(default_factory=dict)

    def _grade(self, answer: Any) -> Feedback:
        ref = self.reference
        names = {str(s): s for s in self.symbols.values()}
        answer = _sympy_array_as_matrix(answer, ref)
        free = _free_symbol_names(answer)
        wanted = sorted(str(s) for s in ref.free_symbols)
        numbers_only = verdict(False, "Your answer holds numbers only, but this exercise asks for a formula in "
                               f"{', '.join(wanted)}: define the symbols with sympy.symbols and build your matrix "
                               "from them (no values substituted).", mistake="numbers_for_symbols")
        catalogued = {m.name for m in self.mistakes}
        # Evaluated at random points (it names mistakes); the book page decides the same way, at the same
        # points (course.exercises._bank), so the verdict never rests on what sympy can simplify.
        for point in self.sample_points():
            arr = as_array(answer, subs=point)
            r = _eval_sym(ref, point)
            ms = [Mistake(m.name, _eval_sym(m.value, point), m.message) for m in self.mistakes]
            result = compare(arr, r, ms, 1e-6, 1e-8, self.what, self.hint)
            if wanted and not free and (result.correct or result.mistake not in catalogued):
                return numbers_only
            if not result.correct:
                missing = [w for w in wanted if w not in free]
                if result.mistake in ("wrong_entry", "wrong_entries", "wrong_value") and missing:
                    result.message += (f" Your answer does not depend on {', '.join(missing)}, but the "
                                       f"{self.what} does.")
                return result
        verb = agrees(self.what, "agrees", "agree")
        return verdict(True, f"Your {self.what} {verb} with the reference at random values of "
                       f"{', '.join(sorted(names))}.")

    def sample_points(self) -> list[dict[str, float]]:
        """The three points (symbol name -> value) a symbolic answer is compared at, drawn from the variant's own
        stream: each value in [0.3, 1.4], joint angles (names starting with "th") of either sign."""
        names = list(dict.fromkeys(str(s) for s in self.symbols.values()))
        rng = self._rng(77)
        return [{name: float(rng.uniform(0.3, 1.4)) * (float(rng.choice([-1, 1])) if name.startswith("th") else 1.0)
                 for name in names} for _ in range(3)]




@dataclass(repr=False)
class PredicateExercise(Exercise):
    """A number judged by ``predicate`` (float array -> Feedback), for answers that are not unique."""

    kind: ClassVar[str] = "predicate"

    predicate: Callable[[NDArray[np.float64]], Feedback] | None = None

    def _grade(self, answer: Any) -> Feedback:
        arr = as_array(answer)
        if not np.all(np.isfinite(arr)):
            return verdict(False, "Your answer contains NaN or inf.", mistake="not_finite")
        if self.predicate is None:
            raise ValueError(f"Exercise {self.id!r} is a predicate exercise without a predicate")
        return self.predicate(arr)


def _matches(arr: NDArray[np.float64], value: Any) -> bool:
    """Whether a function's result is a catalogued mistake's value, to the tolerance code is graded to."""
    v = np.asarray(value, dtype=float)
    a = arr.reshape(v.shape) if arr.size == v.size and v.ndim == 1 else arr
    return a.shape == v.shape and bool(np.all(np.abs(a - v) <= 1e-8 + 1e-6 * np.abs(v)))


def _sympy_array_as_matrix(answer: Any, ref: Any) -> Any:
    """A sympy ``Array`` of two indices becomes a Matrix (accepted like one); of another shape it is refused
    with a message naming it. Anything else is returned unchanged (ImmutableMatrix is already a matrix)."""
    if not is_sympy(answer):
        return answer
    sp = sympy()
    if isinstance(answer, sp.NDimArray):
        shape = tuple(answer.shape)
        if len(shape) == 2:
            return sp.Matrix(answer.tolist())
        want = "x".join(str(n) for n in ref.shape)
        raise Refused(f"You gave a sympy Array of shape {shape}; this exercise wants a {want} matrix. Give "
                      f"sympy.Matrix(...) with {ref.shape[0]} rows of {ref.shape[1]} entries (or an Array of "
                      f"shape {tuple(ref.shape)}).")
    return answer


def _free_symbol_names(answer: Any) -> set[str]:
    """Names of the sympy symbols anywhere in the answer (a sympy object or nested lists of them)."""
    out: set[str] = set()

    def rec(x: Any, depth: int) -> None:
        if depth > 5:
            return
        if is_sympy(x) and hasattr(x, "free_symbols"):
            try:
                out.update(str(s) for s in x.free_symbols)
            except Exception:
                pass
        elif isinstance(x, (list, tuple)) and len(x) <= 1000:
            for e in x:
                rec(e, depth + 1)
        elif isinstance(x, np.ndarray) and x.dtype.kind == "O" and x.size <= 1000:
            for e in x.ravel().tolist():
                rec(e, depth + 1)

    rec(answer, 0)
    return out


@functools.lru_cache(maxsize=512)
def _compiled(expr: Any) -> tuple[tuple[str, ...], Callable[..., Any]]:
    """The names of the free symbols of a (hashable) sympy expression or matrix, and a numpy function of them."""
    sp = sympy()
    syms = sorted(expr.free_symbols, key=str)
    return tuple(str(x) for x in syms), sp.lambdify(syms, expr, modules="numpy")


def _eval_sym(expr: Any, point: dict[str, float]) -> NDArray[np.float64]:
    """A reference or mistake (the course's own sympy objects) at a point, compiled once with lambdify."""
    sp = sympy()
    key = sp.ImmutableMatrix(expr) if isinstance(expr, sp.MatrixBase) else expr
    names, fn = _compiled(key)
    val = np.asarray(fn(*[point[n] for n in names]), dtype=float)
    if isinstance(expr, sp.MatrixBase):
        return val.reshape(expr.shape)
    return val


# --------------------------------------------------------------------------- one constructor per kind
# The id and the seed are set by the catalogue that loads the variant.

def _with_precision(statement: str, decimals: int, scalar: bool) -> str:
    return statement.rstrip() + " " + precision_sentence(decimals, scalar)


def numeric_exercise(title: str, statement: str, given: dict[str, Any], reference: Any,
                     mistakes: list[Mistake], *, what: str = "answer", hint: str = "",
                     decimals: int = DECIMALS, method: Method | None = None) -> NumericExercise:
    """A number, vector or matrix, asked to ``decimals`` decimals; the statement gets a sentence saying what is
    accepted. ``method(r)`` is the intended computation (every intermediate a student writes down passed
    through ``r``): the accepted tolerance is derived from how rounding those intermediates propagates
    (:func:`~jacobians.grading.rounding.derive_rule`). Without it, the answer is taken to be a formula of
    the exact data, and the tolerance is half a unit of the last decimal asked.

    Raises ValueError if the method does not give the reference (it must be the reference's computation)."""
    scalar = np.ndim(reference) == 0
    rule: Rule = direct_rule(decimals)
    if method is not None:
        out = np.asarray(method(lambda x: x), dtype=float)
        ref = np.asarray(reference, dtype=float)
        if out.shape != ref.shape or not np.allclose(out, ref, rtol=1e-9, atol=1e-9):
            raise ValueError(f"Expected the method of {title!r} to give the reference, got {out} for {ref}")
        rule = derive_rule(method, decimals)
    st = statement.rstrip() + " " + rule_sentence(rule, scalar)
    return NumericExercise("", title, st, given, reference, mistakes, what=what, hint=hint, decimals=decimals,
                           tol=rule.tol, carry=rule.carry, method=method)


def scalar_exercise(title: str, statement: str, given: dict[str, Any], accepted: list[float],
                    mistakes: list[Mistake], *, interval: Interval | None = None, outside: list[float] | None = None,
                    what: str = "answer", hint: str = "", decimals: int = DECIMALS) -> ScalarExercise:
    """One number with possibly several right values (``accepted``, all inside ``interval``). A value outside
    the interval is told so (and, if it is in ``outside``, that it is right but for a multiple of 2π)."""
    if interval is not None and not all(interval.low < a < interval.high for a in accepted):
        raise ValueError(f"Expected every accepted value inside {interval.text}, got {accepted}")
    return ScalarExercise("", title, _with_precision(statement, decimals, True), given, float(accepted[0]),
                          mistakes, what=what, hint=hint, decimals=decimals, accepted=[float(a) for a in accepted],
                          outside=[float(o) for o in (outside or [])], interval=interval)


def symbolic_exercise(title: str, statement: str, symbols: dict[str, Any], reference: Any,
                      mistakes: list[Mistake], *, what: str = "answer") -> SymbolicExercise:
    """A sympy expression or matrix in ``symbols`` (name -> sympy Symbol), which are also the given."""
    return SymbolicExercise("", title, statement, {"symbols": symbols}, reference, mistakes, symbols=symbols,
                            what=what)


def function_exercise(title: str, statement: str, *, reference: Callable[..., Any],
                      make_case: Callable[[np.random.Generator], Case], fn_name: str, what: str,
                      more_cases: Callable[[np.random.Generator], list[Case]] | None = None,
                      on_timeout: Mistake | None = None,
                      adapt: Callable[[Any, tuple[Any, ...], Any], Any] | None = None) -> FunctionExercise:
    """A student's function named ``fn_name``, run on the cases ``make_case`` draws, then on ``more_cases``.
    ``on_timeout`` names the mistake of a function that runs out of time; ``adapt(result, args, reference)``
    turns a result in another accepted form into the value compared (or returns a verdict)."""
    return FunctionExercise("", title, statement, {}, reference=reference, make_case=make_case,
                            fn_name=fn_name, what=what, more_cases=more_cases, on_timeout=on_timeout, adapt=adapt)


def predicate_exercise(title: str, statement: str, given: dict[str, Any], reference: Any,
                       predicate: Callable[[NDArray[np.float64]], Feedback], *,
                       what: str = "answer") -> PredicateExercise:
    """A number judged by ``predicate`` (answers that are not unique); ``reference`` is one right answer."""
    return PredicateExercise("", title, statement, given, reference, [], predicate=predicate, what=what)
