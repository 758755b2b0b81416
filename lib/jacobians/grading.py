r"""Self-graded exercises: a checker that names the likely mistake.

Every exercise of the course has an id such as ``"ch02_ex1"``. Load a
randomised variant with :func:`load` (the seed picks the link lengths,
configurations and screw axes) and grade an answer with :func:`check`:

>>> import numpy as np
>>> from jacobians import grading
>>> ex = grading.load("ch01_ex1", seed=3)
>>> sorted(ex.given)
['omega', 'q']
>>> grading.check("ch01_ex1", ex.solution(), seed=3).correct
True
>>> fb = grading.check("ch01_ex1", None, seed=3)
>>> fb.correct, fb.kind
(False, 'empty')
>>> grading.check("ch01_ex1", "0 0 1 0 0 0", seed=3).kind
'invalid'

What the checker promises:

* it never raises at a student, whatever comes (``None``, text, ragged
  lists, NaN, huge arrays, objects of other types, functions that raise or
  loop): it returns a :class:`Feedback`;
* it never evaluates text (a string answer is refused politely, never
  sympified) and never changes the answer it is given (it works on copies);
* a wrong answer is compared with each mistake of the exercise's catalogue,
  computed from the reference for that variant (the body Jacobian given for
  the space one, (v, omega) swapped, transposed, columns in the wrong order,
  the home screw axis instead of the carried one, one column with the wrong
  sign, R missing in the geometric Jacobian, degrees for radians, ...); the
  message says what to look at, not the answer. Otherwise a single wrong
  entry is located by row and column.

Symbolic answers (sympy expressions or matrices in the exercise's symbols)
are compared by simplification and by evaluation at random points; function
answers are run on seeded random inputs against the reference, with a time
guard.
"""

from __future__ import annotations

import copy
import html
import numbers
import signal
import threading
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

__all__ = ["Feedback", "Exercise", "Mistake", "check", "load", "exercise_ids", "SEED_ENV"]

#: Environment variable the notebooks read their seed from.
SEED_ENV = "JACOBIANS_SEED"

#: Largest answer (number of entries) the checker looks at.
MAX_ENTRIES = 10_000

#: Seconds a student's function may run on one test input.
TIME_LIMIT = 2.0


# --------------------------------------------------------------------------- feedback

@dataclass
class Feedback:
    """The checker's verdict: ``.correct`` (bool), ``.message`` (str), ``.kind``.

    ``kind`` is one of ``"correct"``, ``"wrong"`` (a gradable but wrong
    answer), ``"empty"`` (no answer yet), ``"invalid"`` (not something the
    checker can grade, such as text), and ``mistake`` names the catalogued
    mistake that was recognised (``None`` if none).
    """

    correct: bool
    message: str
    kind: str = "wrong"
    exercise_id: str = ""
    mistake: str | None = None

    def __bool__(self) -> bool:
        return self.correct

    def __str__(self) -> str:
        head = "Correct" if self.correct else {"empty": "No answer yet", "invalid": "Cannot grade this"}.get(
            self.kind, "Not yet")
        tag = f"[{self.exercise_id}] " if self.exercise_id else ""
        return f"{tag}{head}: {self.message}"

    def __repr__(self) -> str:
        return str(self)

    def _repr_html_(self) -> str:
        colours = {
            "correct": ("#009E73", "#e6f5f0", "&#10004; Correct"),
            "wrong": ("#D55E00", "#fbece3", "&#10008; Not yet"),
            "empty": ("#0072B2", "#e6f0f8", "&#8230; No answer yet"),
            "invalid": ("#E69F00", "#fdf4e3", "? Cannot grade this"),
        }
        border, bg, head = colours.get(self.kind, colours["wrong"])
        msg = html.escape(self.message).replace("\n", "<br>")
        ident = html.escape(self.exercise_id)
        return (
            f'<div class="jacobians-feedback jacobians-feedback-{self.kind}" role="status" '
            f'style="border-left:6px solid {border};background:{bg};color:#1a1a1a;'
            f'padding:0.6em 0.9em;margin:0.4em 0;border-radius:4px;font-family:sans-serif">'
            f'<strong>{head}</strong> <span style="color:#555">({ident})</span><br>{msg}</div>'
        )


def _fb(ok: bool, message: str, kind: str | None = None, mistake: str | None = None) -> Feedback:
    return Feedback(bool(ok), message, kind or ("correct" if ok else "wrong"), mistake=mistake)


# --------------------------------------------------------------------------- answers -> arrays

class _Refused(Exception):
    """Internal: the answer cannot be graded; carries the polite message."""

    def __init__(self, message: str, kind: str = "invalid"):
        super().__init__(message)
        self.message = message
        self.kind = kind


def _sympy():
    import sympy
    return sympy


def _is_sympy(x) -> bool:
    mod = type(x).__module__ or ""
    return mod.startswith("sympy")


def _a(word: str) -> str:
    return ("an " if word[:1].lower() in "aeiou" else "a ") + word


def _describe(x) -> str:
    if isinstance(x, np.ndarray):
        return f"an array of shape {x.shape}"
    if isinstance(x, (list, tuple)):
        return f"{_a(type(x).__name__)} of length {len(x)}"
    return _a(type(x).__name__)


def _unnest_arrays(x, depth=0):
    """Lists holding numpy arrays (e.g. a list of columns) become plain nested lists (copies)."""
    if depth > 6:
        return x
    if isinstance(x, np.ndarray):
        if x.size > MAX_ENTRIES:
            raise _Refused(f"Your answer has {x.size} entries, far more than this exercise needs.")
        return x.tolist()
    if isinstance(x, (list, tuple)) and len(x) <= MAX_ENTRIES:
        return [_unnest_arrays(e, depth + 1) for e in x]
    return x


def _walk_shape(x, depth=0):
    """Shape of a nested list/tuple, or raise _Refused for ragged or oversized input."""
    if isinstance(x, (list, tuple)):
        if depth > 4:
            raise _Refused("Your answer is nested too deeply: give a number, a vector or a matrix.")
        if len(x) > MAX_ENTRIES:
            raise _Refused(f"Your answer has {len(x)} entries, far more than this exercise needs.")
        if len(x) == 0:
            return (0,)
        shapes = [_walk_shape(e, depth + 1) for e in x]
        if any(s != shapes[0] for s in shapes):
            raise _Refused(
                "Your rows have different lengths (a ragged list): every row of a matrix needs the same "
                "number of entries.")
        return (len(x),) + shapes[0]
    return ()


def _to_number(x, subs=None) -> float:
    """One entry to a float (sympy numbers allowed, sympy symbols substituted by ``subs``)."""
    if isinstance(x, (str, bytes)):
        raise _Refused("Please give a number or a matrix of numbers, not text: the checker does not read "
                       "text (write 0.5, not \"0.5\").")
    if x is None:
        raise _Refused("One entry of your answer is None: fill in every entry.")
    if isinstance(x, bool):
        raise _Refused("One entry of your answer is True/False: give numbers.")
    if isinstance(x, numbers.Complex) and not isinstance(x, numbers.Real):
        if getattr(x, "imag", 0) != 0:
            raise _Refused("Your answer has complex numbers: every entry should be real.")
        x = x.real
    if isinstance(x, (numbers.Real, np.floating, np.integer)):
        return float(x)
    if _is_sympy(x):
        sp = _sympy()
        try:
            expr = sp.sympify(x) if not isinstance(x, sp.Basic) else x  # x is a sympy object, not text
            if subs is not None:
                free = expr.free_symbols
                unknown = sorted(str(s) for s in free if str(s) not in subs)
                if unknown:
                    raise _Refused(
                        f"Your answer uses the symbol(s) {', '.join(unknown)}, which this exercise does not "
                        f"define. Use only: {', '.join(sorted(subs))}.")
                expr = expr.subs({s: subs[str(s)] for s in free})
            elif expr.free_symbols:
                names = ", ".join(sorted(str(s) for s in expr.free_symbols))
                raise _Refused(f"This exercise wants numbers, but your answer still contains the symbol(s) "
                               f"{names}: substitute the given values.")
            val = complex(expr.evalf())
        except _Refused:
            raise
        except Exception:
            raise _Refused("One entry of your answer could not be turned into a number.")
        if abs(val.imag) > 1e-9 * max(1.0, abs(val.real)):
            raise _Refused("Your answer has complex numbers: every entry should be real.")
        return val.real
    raise _Refused(f"One entry of your answer is {_describe(x)}, which is not a number.")


def _as_array(answer, subs=None) -> np.ndarray:
    """A clean float array from whatever came, or raise _Refused. Never mutates ``answer``."""
    if answer is None:
        raise _Refused("Set `answer` to your result and run the check cell again.", "empty")
    if isinstance(answer, (str, bytes)):
        raise _Refused("Please give a number or a matrix (a list of lists or a numpy array), not text: "
                       "the checker never reads text.")
    if callable(answer) and not _is_sympy(answer) and not isinstance(answer, np.ndarray):
        raise _Refused("You gave a function, but this exercise wants a number or a matrix: call your "
                       "function and give its result.")
    if isinstance(answer, dict) or isinstance(answer, (set, frozenset)):
        raise _Refused(f"You gave {_describe(answer)}; this exercise wants a number, a vector or a matrix.")
    if _is_sympy(answer):
        sp = _sympy()
        if isinstance(answer, sp.MatrixBase):
            if answer.rows * answer.cols > MAX_ENTRIES:
                raise _Refused("Your matrix is far larger than this exercise needs.")
            rows = answer.tolist()
            return np.array([[_to_number(e, subs) for e in r] for r in rows], dtype=float)
        return np.asarray(_to_number(answer, subs), dtype=float)
    if isinstance(answer, np.ndarray):
        if answer.size > MAX_ENTRIES:
            raise _Refused(f"Your answer has {answer.size} entries, far more than this exercise needs.")
        if answer.dtype.kind in "biuf":
            if answer.dtype.kind == "b":
                raise _Refused("Your answer is an array of True/False values: give numbers.")
            return np.array(answer, dtype=float)  # a copy
        if answer.dtype.kind == "c":
            if np.any(np.imag(answer) != 0):
                raise _Refused("Your answer has complex numbers: every entry should be real.")
            return np.array(np.real(answer), dtype=float)
        if answer.dtype.kind in "US":
            raise _Refused("Your array holds text: give numbers, not strings.")
        flat = [_to_number(e, subs) for e in answer.ravel().tolist()] if answer.dtype.kind == "O" else None
        if flat is None:
            raise _Refused(f"You gave {_describe(answer)} of an unsupported type: give numbers.")
        return np.array(flat, dtype=float).reshape(answer.shape)
    if isinstance(answer, (list, tuple)):
        answer = _unnest_arrays(answer)
        shape = _walk_shape(answer)
        flat = []

        def rec(x):
            if isinstance(x, (list, tuple)):
                for e in x:
                    rec(e)
            elif _is_sympy(x) and isinstance(x, _sympy().MatrixBase):
                raise _Refused("Your list mixes sympy matrices with other entries: give one matrix.")
            else:
                flat.append(_to_number(x, subs))

        rec(answer)
        if int(np.prod(shape)) > MAX_ENTRIES:
            raise _Refused("Your answer is far larger than this exercise needs.")
        return np.array(flat, dtype=float).reshape(shape)
    if isinstance(answer, (numbers.Number, np.generic)):
        return np.asarray(_to_number(answer, subs), dtype=float)
    # Other array-likes (e.g. a pandas object, a torch tensor): try numpy, carefully.
    if hasattr(answer, "__array__"):
        try:
            arr = np.asarray(answer)
        except Exception:
            raise _Refused(f"You gave {_describe(answer)}, which could not be read as numbers.")
        if isinstance(arr, np.ndarray) and arr.dtype.kind in "biufcO":
            return _as_array(arr, subs)
    raise _Refused(f"You gave {_describe(answer)}; this exercise wants a number, a vector or a matrix "
                   "(a list of lists or a numpy array).")


# --------------------------------------------------------------------------- comparison

def _close(a: np.ndarray, b: np.ndarray, rtol: float, atol: float) -> bool:
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= atol + rtol * np.abs(b)))


@dataclass
class Mistake:
    """A catalogued mistake: its name, the wrong answer it produces, and what to look at."""

    name: str
    value: Any
    message: str


def _ordinal_col(j: int) -> str:
    return f"column {j + 1}"


def _compare(ans: np.ndarray, ref: np.ndarray, mistakes: list[Mistake], rtol: float, atol: float,
             what: str, entry_hint: str = "") -> Feedback:
    """Grade a float array against the reference and the catalogue of mistakes."""
    ref = np.asarray(ref, dtype=float)
    # Vectors: accept (n,), (n, 1) and (1, n) alike.
    if ref.ndim == 1 and ans.size == ref.size and ans.ndim <= 2 and (ans.ndim == 1 or 1 in ans.shape):
        ans = ans.reshape(ref.shape)
    if ref.ndim == 0 and ans.size == 1:
        ans = ans.reshape(())
    if not np.all(np.isfinite(ans)):
        return _fb(False, "Your answer contains NaN or inf: check for a division by zero or an unset entry.",
                   mistake="not_finite")
    if _close(ans, ref, rtol, atol):
        return _fb(True, f"Your {what} matches the reference.")
    for m in mistakes:
        mv = np.asarray(m.value, dtype=float)
        if ref.ndim == 1 and mv.ndim == 1:
            pass
        if mv.shape == ans.shape and _close(ans, mv, rtol, atol):
            return _fb(False, m.message, mistake=m.name)
    if ans.shape != ref.shape:
        if ref.ndim == 2 and ans.shape == ref.shape[::-1] and _close(ans.T, ref, rtol, atol):
            return _fb(False, "Your matrix is the transpose of the right one: rows and columns are swapped.",
                       mistake="transposed")
        return _fb(False, f"Your answer has shape {ans.shape}, but this {what} has shape {ref.shape}"
                   + (" (6 rows (omega, v), one column per joint)." if ref.ndim == 2 and ref.shape[0] == 6 else "."),
                   mistake="wrong_shape")
    if ref.ndim == 2 and ref.shape[0] == ref.shape[1] and _close(ans.T, ref, rtol, atol):
        return _fb(False, "Your matrix is the transpose of the right one: rows and columns are swapped.",
                   mistake="transposed")
    if ref.ndim == 2 and ref.shape[1] > 1:
        # Columns in the wrong order: every column matches some other column.
        perm = []
        for j in range(ref.shape[1]):
            hits = [k for k in range(ref.shape[1]) if _close(ans[:, j], ref[:, k], rtol, atol)]
            perm.append(hits)
        if all(perm) and not all(j in h for j, h in enumerate(perm)):
            return _fb(False, "Every column you gave is a right column, but in the wrong place: check the "
                       "order of the columns (column i belongs to joint i).", mistake="column_order")
    bad = ~(np.abs(ans - ref) <= atol + rtol * np.abs(ref))
    nbad = int(bad.sum())
    if ref.ndim == 0:
        return _fb(False, f"Your value is not right. {entry_hint}".strip(), mistake="wrong_value")
    if nbad == 1:
        idx = tuple(int(i[0]) for i in np.nonzero(bad))
        if ref.ndim == 1:
            where = f"entry {idx[0] + 1} (counting from 1)"
        elif ref.ndim == 2:
            where = f"the entry in row {idx[0] + 1}, column {idx[1] + 1} (counting from 1)"
        else:
            where = "the entry at index " + ", ".join(str(i + 1) for i in idx) + " (counting from 1)"
        return _fb(False, f"Almost: {where} is wrong; every other entry is right. {entry_hint}".strip(),
                   mistake="wrong_entry")
    if ref.ndim == 3:
        blocks = [i for i in range(ref.shape[0]) if bad[i].any()]
        return _fb(False, f"{nbad} entries are wrong, in block(s) {', '.join(str(i + 1) for i in blocks)} "
                   f"(first index, counting from 1). {entry_hint}".strip(), mistake="wrong_entries")
    if ref.ndim == 2:
        cols = [j for j in range(ref.shape[1]) if bad[:, j].any()]
        good = [j for j in range(ref.shape[1]) if j not in cols]
        txt = ", ".join(str(j + 1) for j in cols)
        msg = f"{nbad} entries are wrong, in column(s) {txt}"
        if good:
            msg += f"; column(s) {', '.join(str(j + 1) for j in good)} are right"
        return _fb(False, msg + f". {entry_hint}".rstrip(), mistake="wrong_entries")
    idx = ", ".join(str(i + 1) for i in np.nonzero(bad.ravel())[0])
    return _fb(False, f"Entries {idx} (counting from 1) are wrong. {entry_hint}".strip(), mistake="wrong_entries")


# --------------------------------------------------------------------------- running student code

class _TimeUp(BaseException):
    pass


def _run_guarded(fn: Callable, args: tuple, limit: float = TIME_LIMIT):
    """Call ``fn(*args)``; return (ok, value_or_message). Never raises (but KeyboardInterrupt)."""
    use_alarm = (hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread())
    old = None
    if use_alarm:
        def _handler(signum, frame):
            raise _TimeUp()
        try:
            old = signal.signal(signal.SIGALRM, _handler)
            signal.setitimer(signal.ITIMER_REAL, limit)
        except Exception:  # pragma: no cover - signals unavailable
            use_alarm = False
    try:
        return True, fn(*args)
    except _TimeUp:
        return False, f"your function did not finish within {limit:g} s (an endless loop?)"
    except RecursionError:
        return False, "your function recursed too deeply (RecursionError)"
    except SystemExit:
        return False, "your function called exit()"
    except Exception as exc:  # anything the student's code raises
        text = str(exc).splitlines()[0][:200] if str(exc) else ""
        return False, f"your function raised {type(exc).__name__}" + (f": {text}" if text else "")
    finally:
        if use_alarm:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old if old is not None else signal.SIG_DFL)


def _fmt(x) -> str:
    return np.array2string(np.asarray(x, dtype=float), precision=3, suppress_small=True, separator=", ")


# --------------------------------------------------------------------------- exercises

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
    given: dict
    kind: str
    reference: Any = None
    mistakes: list = field(default_factory=list)
    what: str = "answer"
    hint: str = ""
    rtol: float = 2e-3
    atol: float = 2e-3
    symbols: dict = field(default_factory=dict)
    # function exercises
    make_case: Callable | None = None       # rng -> (args tuple, reference output, mistakes list)
    n_cases: int = 6
    fn_name: str = "your function"
    # predicate exercises
    predicate: Callable | None = None      # float array -> Feedback
    seed: int = 0

    # ------------------------------------------------------------ display
    def _repr_markdown_(self) -> str:
        return f"**{self.title}** (`{self.id}`, variant {self.seed})\n\n{self.statement}"

    def __repr__(self) -> str:
        return f"<Exercise {self.id} seed={self.seed}: {self.title}>"

    def solution(self):
        """The reference answer (instructors): array, sympy Matrix or function."""
        if isinstance(self.reference, np.ndarray):
            return self.reference.copy()
        return self.reference

    # ------------------------------------------------------------ grading
    def check(self, answer) -> Feedback:
        """Grade ``answer``; never raises, never mutates ``answer``."""
        try:
            fb = self._check(answer)
        except _Refused as r:
            fb = Feedback(False, r.message, r.kind)
        except Exception as exc:  # a checker bug must not reach the student as a traceback
            fb = Feedback(False, "The checker could not grade this answer (" + type(exc).__name__ +
                          "). Check that it is a number, a matrix or a function as asked.", "invalid")
        fb.exercise_id = self.id
        return fb

    def _check(self, answer) -> Feedback:
        if answer is None:
            raise _Refused("Set `answer` to your result and run the check cell again.", "empty")
        if self.kind == "function":
            return self._check_function(answer)
        if self.kind == "symbolic":
            return self._check_symbolic(answer)
        arr = _as_array(answer)
        if self.kind == "predicate":
            if not np.all(np.isfinite(arr)):
                return _fb(False, "Your answer contains NaN or inf.", mistake="not_finite")
            return self.predicate(arr)
        return _compare(arr, self.reference, self.mistakes, self.rtol, self.atol, self.what, self.hint)

    def _check_function(self, fn) -> Feedback:
        if isinstance(fn, (str, bytes)):
            raise _Refused("Please give your function itself (its name, without quotes or brackets), not text.")
        if not callable(fn):
            raise _Refused(f"This exercise wants a function (define `{self.fn_name}` and set "
                           f"`answer = {self.fn_name}`), but you gave {_describe(fn)}.")
        rng = np.random.default_rng(self.seed + 1000)
        for case in range(self.n_cases):
            args, ref, mistakes, label = self.make_case(rng)
            ok, out = _run_guarded(fn, copy.deepcopy(args))
            if not ok:
                return _fb(False, f"On test {case + 1} ({label}) {out}.", mistake="raised")
            try:
                arr = _as_array(out)
            except _Refused as r:
                if r.kind == "empty":
                    return _fb(False, f"On test {case + 1} ({label}) your function returned None: "
                               "did you forget `return`?", mistake="returned_none")
                return _fb(False, f"On test {case + 1} ({label}) your function's result could not be graded: "
                           + r.message, mistake="bad_return")
            # Code is compared tightly: the same computation agrees to rounding error.
            fb = _compare(arr, ref, mistakes, 1e-6, 1e-8, self.what, self.hint)
            if not fb.correct:
                fb.message = f"On test {case + 1} ({label}): {fb.message}"
                return fb
        return _fb(True, f"Your function matches the reference on all {self.n_cases} random tests.")

    def _check_symbolic(self, answer) -> Feedback:
        sp = _sympy()
        ref = self.reference
        names = {str(s): s for s in self.symbols.values()}
        # Numeric route first (fast, and it names mistakes): evaluate at random points.
        rng = np.random.default_rng(self.seed + 77)
        for _ in range(3):
            point = {name: float(rng.uniform(0.3, 1.4)) * (float(rng.choice([-1, 1])) if name.startswith("th") else 1.0)
                     for name in names}
            arr = _as_array(answer, subs=point)
            r = _eval_sym(ref, point)
            ms = [Mistake(m.name, _eval_sym(m.value, point), m.message) for m in self.mistakes]
            verdict = _compare(arr, r, ms, 1e-6, 1e-8, self.what, self.hint)
            if not verdict.correct:
                return verdict
        # Exact route: the difference simplifies to zero.
        if _is_sympy(answer) and isinstance(answer, (sp.MatrixBase, sp.Expr)):
            try:
                A = answer if isinstance(answer, sp.MatrixBase) else sp.Matrix([answer])
                sub = {s: names[str(s)] for s in A.free_symbols if str(s) in names}
                diff = (A.xreplace(sub).reshape(*ref.shape) - ref).applyfunc(sp.simplify)
                if all(e == 0 for e in diff):
                    return _fb(True, f"Your {self.what} simplifies to the reference.")
            except Exception:
                pass
        return _fb(True, f"Your {self.what} agrees with the reference at random values of "
                   f"{', '.join(sorted(names))}.")


def _contains_sympy(x) -> bool:
    if isinstance(x, (list, tuple)):
        return any(_contains_sympy(e) for e in x)
    return _is_sympy(x)


def _eval_sym(expr, point: dict) -> np.ndarray:
    sp = _sympy()
    sub = {s: point[str(s)] for s in expr.free_symbols}
    val = expr.xreplace(sub) if sub else expr
    if isinstance(val, sp.MatrixBase):
        return np.array(val.evalf().tolist(), dtype=float)
    return np.asarray(float(val.evalf()))


# --------------------------------------------------------------------------- registry

_REGISTRY: dict[str, Callable[[np.random.Generator], dict]] = {}


def register(exercise_id: str):
    """Decorator used by :mod:`jacobians._exercises` to add an exercise builder."""
    def deco(builder):
        _REGISTRY[exercise_id] = builder
        return builder
    return deco


def _ensure_loaded():
    if not _REGISTRY:
        from . import _exercises  # noqa: F401  (registers every exercise)


def exercise_ids() -> list[str]:
    """All exercise ids, in chapter order."""
    _ensure_loaded()
    return sorted(_REGISTRY, key=lambda s: (s.split("_")[0], int(s.split("ex")[-1])))


def _seed_value(seed) -> int:
    if seed is None:
        return 0
    if isinstance(seed, bool) or not isinstance(seed, (numbers.Integral,)):
        raise TypeError(f"Expected an int seed, got {type(seed).__name__} {seed!r}"[:120])
    if seed < 0:
        raise ValueError(f"Expected a non-negative seed, got {seed}")
    return int(seed)


def load(exercise_id: str, seed: int | None = None) -> Exercise:
    """The variant of ``exercise_id`` for ``seed`` (same seed, same numbers).

    Raises ``KeyError`` for an unknown id and ``TypeError``/``ValueError`` for a
    bad seed: these are the author's inputs, not the student's.
    """
    _ensure_loaded()
    if not isinstance(exercise_id, str):
        raise TypeError(f"Expected an exercise id such as 'ch02_ex1', got {type(exercise_id).__name__}")
    if exercise_id not in _REGISTRY:
        raise KeyError(f"Unknown exercise {exercise_id!r}; known: {', '.join(exercise_ids())}")
    s = _seed_value(seed)
    rng = np.random.default_rng([s, sum(map(ord, exercise_id))])
    ex = _REGISTRY[exercise_id](rng)
    ex.id = exercise_id
    ex.seed = s
    # Drop catalogued mistakes that this variant cannot tell from the reference
    # (e.g. a sign error in a zero column), and duplicates of earlier ones.
    if ex.kind == "numeric":
        ref = np.asarray(ex.reference, dtype=float)
        kept: list[Mistake] = []
        for m in ex.mistakes:
            mv = np.asarray(m.value, dtype=float)
            same = mv.shape == ref.shape and np.allclose(mv, ref, rtol=5 * ex.rtol, atol=5 * ex.atol)
            dup = any(np.asarray(k.value).shape == mv.shape and np.allclose(np.asarray(k.value, dtype=float), mv,
                                                                            rtol=5 * ex.rtol, atol=5 * ex.atol)
                      for k in kept)
            if not same and not dup and np.all(np.isfinite(mv)):
                kept.append(m)
        ex.mistakes = kept
    return ex


def check(exercise_id: str, answer, *, seed: int | None = None) -> Feedback:
    """Grade ``answer`` for the variant ``seed`` of ``exercise_id``; returns a :class:`Feedback`.

    Never raises for any ``answer``. An unknown ``exercise_id`` or a bad seed
    also comes back as feedback (kind ``"invalid"``), so a typo in a notebook
    shows a box, not a traceback.
    """
    try:
        ex = load(exercise_id, seed=seed)
    except Exception as exc:
        return Feedback(False, f"Cannot load this exercise: {exc}", "invalid", exercise_id=str(exercise_id)[:40])
    return ex.check(answer)
