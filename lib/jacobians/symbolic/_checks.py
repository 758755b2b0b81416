"""Input checks shared by the symbolic modules: every entry point refuses strings and says what it expected."""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np
import sympy as sp


def describe(value: object) -> str:
    """A short description of a value for an error message."""
    if isinstance(value, sp.MatrixBase):
        return f"sympy Matrix with shape {value.shape}"
    if isinstance(value, np.ndarray):
        return f"array with shape {value.shape} and dtype {value.dtype}"
    if isinstance(value, (list, tuple)):
        return f"{type(value).__name__} of length {len(value)}"
    return f"{type(value).__name__} {value!r}"[:120]


def scalar(value: object, name: str) -> sp.Expr:
    """A sympy expression from a number or a sympy object; never parses strings."""
    if isinstance(value, (str, bytes)) or value is None or isinstance(value, bool):
        raise TypeError(f"Expected a number or a sympy expression for {name}, got {describe(value)}")
    if isinstance(value, sp.Basic):
        if not isinstance(value, sp.Expr):
            raise TypeError(f"Expected a sympy expression for {name}, got {describe(value)}")
        return value
    if isinstance(value, (numbers.Number, np.generic)):
        if isinstance(value, (complex, np.complexfloating)):
            raise TypeError(f"Expected a real number for {name}, got {value!r}")
        if isinstance(value, (float, np.floating)) and not np.isfinite(value):
            raise ValueError(f"Expected a finite number for {name}, got {value!r}")
        return sp.sympify(value)
    raise TypeError(f"Expected a number or a sympy expression for {name}, got {describe(value)}")


def matrix(value: object, name: str, shape: tuple[int | None, int | None] | None = None) -> sp.Matrix:
    """A mutable sympy Matrix with checked shape (``None`` entries match any size)."""
    if isinstance(value, (str, bytes)) or value is None or isinstance(value, (bool, numbers.Number)):
        raise TypeError(f"Expected a sympy Matrix (or nested list) for {name}, got {describe(value)}")
    if isinstance(value, sp.MatrixBase):
        A = sp.Matrix(value)
    else:
        if isinstance(value, np.ndarray) and value.dtype.kind == "c":
            raise TypeError(f"Expected real entries for {name}, got a complex array")
        try:
            A = sp.Matrix(value)
        except Exception as exc:  # sympy raises several types for ragged input
            raise TypeError(
                f"Expected a sympy Matrix (or nested list) for {name}, got {describe(value)} ({exc})") from None
    for entry in A:
        scalar(entry, f"an entry of {name}")
    if shape is not None:
        ok = all(s is None or s == h for s, h in zip(shape, A.shape, strict=True))
        if not ok:
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
            raise ValueError(f"Expected {name} with shape {want}, got shape {A.shape}")
    return A


def vector(value: object, name: str, length: int) -> sp.Matrix:
    """A column vector of the given length from a list, a row or a column."""
    A = matrix(value, name)
    if A.shape == (1, length):
        A = A.T
    if A.shape != (length, 1):
        raise ValueError(f"Expected {name} with {length} entries (a list, a row or a column), got shape {A.shape}")
    return A


def joint_values(theta: object, n: int, name: str = "theta") -> tuple[sp.Expr, ...]:
    """n joint symbols or values from a sequence (or one bare value when n = 1)."""
    items: list[Any]
    if isinstance(theta, (str, bytes)) or theta is None:
        raise TypeError(f"Expected a sequence of {n} joint symbols or values for {name}, got {describe(theta)}")
    if isinstance(theta, sp.MatrixBase):
        items = list(theta)
    elif isinstance(theta, np.ndarray):
        items = list(np.asarray(theta, dtype=object).ravel())
    elif isinstance(theta, (list, tuple)):
        items = list(theta)
    elif n == 1 and isinstance(theta, (sp.Expr, numbers.Number)):
        items = [theta]
    else:
        raise TypeError(f"Expected a sequence of {n} joint symbols or values for {name}, got {describe(theta)}")
    if len(items) != n:
        raise ValueError(f"Expected {n} joint variables in {name} (one per screw axis), got {len(items)}")
    return tuple(scalar(t, f"{name}[{i}]") for i, t in enumerate(items))


def _not_one(expr: sp.Expr) -> bool:
    """True when a squared norm is a number that is not 1 (to 1e-9); symbolic ones are taken as 1."""
    if expr.free_symbols:
        return False
    try:
        value = complex(expr.evalf())
    except (TypeError, ValueError):  # pragma: no cover - not a number after all
        return False
    return abs(value - 1) > 1e-9


def check_unit_axis(w: sp.Matrix, name: str) -> None:
    """Refuse a numeric rotation axis that is not of unit length (a symbolic one is assumed to be)."""
    nw = sum(e**2 for e in w)
    if _not_one(nw):
        raise ValueError(f"Expected a unit rotation axis for {name}, got |w|^2 = {nw}; "
                         "normalise it and scale theta instead")


def is_revolute(w: sp.Matrix, v: sp.Matrix, name: str) -> bool:
    """True for a revolute/screw axis (|omega| = 1), False for a prismatic one (omega = 0).

    Symbolic entries that sympy cannot decide are taken as a unit axis (the
    caller's responsibility, stated in the docstrings).
    """
    if all(e.is_zero for e in w):
        nv = sum(e**2 for e in v)
        if _not_one(nv):
            raise ValueError(f"Expected {name} with omega = 0 to have a unit linear part, got |v|^2 = {nv}")
        return False
    nw = sum(e**2 for e in w)
    if _not_one(nw):
        raise ValueError(
            f"Expected {name} to have a unit angular part (|omega| = 1) or omega = 0, got |omega|^2 = {nw}; "
            "normalise the axis and scale theta instead"
        )
    return True


def transform(T: object, name: str = "T") -> sp.Matrix:
    """A 4 x 4 sympy matrix whose last row is [0, 0, 0, 1]."""
    A = matrix(T, name, (4, 4))
    bottom = A[3, :]
    if any(sp.simplify(b - e) != 0 for b, e in zip(bottom, (0, 0, 0, 1), strict=True)):
        raise ValueError(f"Expected {name} in SE(3) with last row [0, 0, 0, 1], got last row {list(bottom)}")
    return A


def screw_axes(S: object, name: str = "screw_axes") -> sp.Matrix:
    """A 6 x n sympy matrix of screw axes, one per column, each unit revolute or unit prismatic."""
    A = matrix(S, name)
    if A.rows != 6:
        hint = " (it looks transposed: the axes must be the columns)" if A.cols == 6 else ""
        raise ValueError(f"Expected {name} with shape (6, n), one screw axis per column, got shape {A.shape}{hint}")
    if A.cols == 0:
        raise ValueError(f"Expected {name} with at least one column, got shape {A.shape}")
    for i in range(A.cols):
        is_revolute(A[:3, i], A[3:, i], f"column {i} of {name}")
    return A
