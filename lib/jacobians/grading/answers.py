"""How an answer is read: whatever a student gives becomes a clean float array, or a polite refusal.

The reader never evaluates text, never changes the answer it is given (it works
on copies) and never lets anything but :class:`Refused` out.

>>> as_array([[1, 2], [3, 4]]).shape
(2, 2)
>>> try:
...     as_array("0 0 1")
... except Refused as r:
...     print(r.kind)
invalid
"""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["MAX_ENTRIES", "Refused", "as_array", "describe", "is_sympy"]

#: Largest answer (number of entries) the checker looks at.
MAX_ENTRIES = 10_000


class Refused(Exception):
    """The answer cannot be graded; carries the polite message and the kind (``invalid`` or ``empty``)."""

    def __init__(self, message: str, kind: str = "invalid") -> None:
        super().__init__(message)
        self.message = message
        self.kind = kind


def sympy() -> Any:
    """The sympy module, imported on first use (numeric answers never need it)."""
    import sympy as sp
    return sp


def is_sympy(x: object) -> bool:
    """Whether ``x`` is a sympy object (told by its type's module, without importing sympy)."""
    mod = type(x).__module__ or ""
    return mod.startswith("sympy")


def _a(word: str) -> str:
    return ("an " if word[:1].lower() in "aeiou" else "a ") + word


def describe(x: object) -> str:
    """A short description of what came, for messages: ``"a dict"``, ``"an array of shape (2,)"``."""
    if isinstance(x, np.ndarray):
        return f"an array of shape {x.shape}"
    if isinstance(x, (list, tuple)):
        return f"{_a(type(x).__name__)} of length {len(x)}"
    return _a(type(x).__name__)


def _unnest_arrays(x: Any, depth: int = 0) -> Any:
    """Lists holding numpy arrays (e.g. a list of columns) become plain nested lists (copies)."""
    if depth > 6:
        return x
    if isinstance(x, np.ndarray):
        if x.size > MAX_ENTRIES:
            raise Refused(f"Your answer has {x.size} entries, far more than this exercise needs.")
        return x.tolist()
    if isinstance(x, (list, tuple)) and len(x) <= MAX_ENTRIES:
        return [_unnest_arrays(e, depth + 1) for e in x]
    return x


def _walk_shape(x: Any, depth: int = 0) -> tuple[int, ...]:
    """Shape of a nested list/tuple, or raise Refused for ragged or oversized input."""
    if isinstance(x, (list, tuple)):
        if depth > 4:
            raise Refused("Your answer is nested too deeply: give a number, a vector or a matrix.")
        if len(x) > MAX_ENTRIES:
            raise Refused(f"Your answer has {len(x)} entries, far more than this exercise needs.")
        if len(x) == 0:
            return (0,)
        shapes = [_walk_shape(e, depth + 1) for e in x]
        if any(s != shapes[0] for s in shapes):
            raise Refused(
                "Your rows have different lengths (a ragged list): every row of a matrix needs the same "
                "number of entries.")
        return (len(x), *shapes[0])
    return ()


def _sympy_number(x: Any, subs: dict[str, float] | None) -> float:
    sp = sympy()
    try:
        expr = sp.sympify(x) if not isinstance(x, sp.Basic) else x  # x is a sympy object, not text
        if subs is not None:
            free = expr.free_symbols
            unknown = sorted(str(s) for s in free if str(s) not in subs)
            if unknown:
                raise Refused(
                    f"Your answer uses the symbol(s) {', '.join(unknown)}, which this exercise does not "
                    f"define. Use only: {', '.join(sorted(subs))}.")
            expr = expr.xreplace({s: sp.Float(subs[str(s)]) for s in free})
        elif expr.free_symbols:
            names = ", ".join(sorted(str(s) for s in expr.free_symbols))
            raise Refused(f"This exercise wants numbers, but your answer still contains the symbol(s) "
                          f"{names}: substitute the given values.")
        val = complex(expr.evalf())
    except Refused:
        raise
    except Exception:
        raise Refused("One entry of your answer could not be turned into a number.") from None
    if abs(val.imag) > 1e-9 * max(1.0, abs(val.real)):
        raise Refused("Your answer has complex numbers: every entry should be real.")
    return val.real


def to_number(x: Any, subs: dict[str, float] | None = None) -> float:
    """One entry to a float (sympy numbers allowed, sympy symbols substituted by ``subs``)."""
    if isinstance(x, (str, bytes)):
        raise Refused("Please give a number or a matrix of numbers, not text: the checker does not read "
                      "text (write 0.5, not \"0.5\").")
    if x is None:
        raise Refused("One entry of your answer is None: fill in every entry.")
    if isinstance(x, bool):
        raise Refused("One entry of your answer is True/False: give numbers.")
    if isinstance(x, numbers.Complex) and not isinstance(x, numbers.Real):
        if getattr(x, "imag", 0) != 0:
            raise Refused("Your answer has complex numbers: every entry should be real.")
        x = x.real
    if isinstance(x, (numbers.Real, np.floating, np.integer)):
        return float(x)
    if is_sympy(x):
        return _sympy_number(x, subs)
    raise Refused(f"One entry of your answer is {describe(x)}, which is not a number.")


def _from_ndarray(answer: NDArray[Any], subs: dict[str, float] | None) -> NDArray[np.float64]:
    if answer.size > MAX_ENTRIES:
        raise Refused(f"Your answer has {answer.size} entries, far more than this exercise needs.")
    kind = answer.dtype.kind
    if kind == "b":
        raise Refused("Your answer is an array of True/False values: give numbers.")
    if kind in "iuf":
        return np.array(answer, dtype=float)  # a copy
    if kind == "c":
        if np.any(np.imag(answer) != 0):
            raise Refused("Your answer has complex numbers: every entry should be real.")
        return np.array(np.real(answer), dtype=float)
    if kind in "US":
        raise Refused("Your array holds text: give numbers, not strings.")
    if kind != "O":
        raise Refused(f"You gave {describe(answer)} of an unsupported type: give numbers.")
    flat = [to_number(e, subs) for e in answer.ravel().tolist()]
    return np.array(flat, dtype=float).reshape(answer.shape)


def _from_nested(answer: list[Any] | tuple[Any, ...], subs: dict[str, float] | None) -> NDArray[np.float64]:
    nested = _unnest_arrays(answer)
    shape = _walk_shape(nested)
    flat: list[float] = []

    def rec(x: Any) -> None:
        if isinstance(x, (list, tuple)):
            for e in x:
                rec(e)
        elif is_sympy(x) and isinstance(x, sympy().MatrixBase):
            raise Refused("Your list mixes sympy matrices with other entries: give one matrix.")
        else:
            flat.append(to_number(x, subs))

    rec(nested)
    if int(np.prod(shape)) > MAX_ENTRIES:
        raise Refused("Your answer is far larger than this exercise needs.")
    return np.array(flat, dtype=float).reshape(shape)


def as_array(answer: Any, subs: dict[str, float] | None = None) -> NDArray[np.float64]:
    """A clean float array from whatever came, or raise :class:`Refused`. Never mutates ``answer``.

    ``subs`` maps symbol names to values for symbolic answers; without it a
    symbol in the answer is refused.
    """
    if answer is None:
        raise Refused("Set `answer` to your result and run the check cell again.", "empty")
    if isinstance(answer, (str, bytes)):
        raise Refused("Please give a number or a matrix (a list of lists or a numpy array), not text: "
                      "the checker never reads text.")
    if callable(answer) and not is_sympy(answer) and not isinstance(answer, np.ndarray):
        raise Refused("You gave a function, but this exercise wants a number or a matrix: call your "
                      "function and give its result.")
    if isinstance(answer, (dict, set, frozenset)):
        raise Refused(f"You gave {describe(answer)}; this exercise wants a number, a vector or a matrix.")
    if is_sympy(answer):
        sp = sympy()
        if isinstance(answer, sp.MatrixBase):
            if answer.rows * answer.cols > MAX_ENTRIES:
                raise Refused("Your matrix is far larger than this exercise needs.")
            return np.array([[to_number(e, subs) for e in r] for r in answer.tolist()], dtype=float)
        return np.asarray(to_number(answer, subs), dtype=float)
    if isinstance(answer, np.ndarray):
        return _from_ndarray(answer, subs)
    if isinstance(answer, (list, tuple)):
        return _from_nested(answer, subs)
    if isinstance(answer, (numbers.Number, np.generic)):
        return np.asarray(to_number(answer, subs), dtype=float)
    # Other array-likes (e.g. a pandas object, a torch tensor): try numpy, carefully.
    if hasattr(answer, "__array__"):
        try:
            arr = np.asarray(answer)
        except Exception:
            raise Refused(f"You gave {describe(answer)}, which could not be read as numbers.") from None
        if arr.dtype.kind in "biufcO":
            return as_array(arr, subs)
    raise Refused(f"You gave {describe(answer)}; this exercise wants a number, a vector or a matrix "
                  "(a list of lists or a numpy array).")
