r"""Simplifying, testing and evaluating symbolic matrices of sines, cosines and lengths.

:func:`simplify_matrix` gives the textbook form of a Jacobian; :func:`is_zero`
and :func:`is_zero_matrix` decide an identity exactly (what a chapter's hidden
check asserts); :func:`lambdify_matrix` turns a matrix into a fast numpy function.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import sympy as sp
from numpy.typing import ArrayLike, NDArray
from sympy.simplify.fu import TR10i as _TR10i

from ._checks import describe, matrix

__all__ = ["simplify_matrix", "is_zero", "is_zero_matrix", "lambdify_matrix", "MatrixFunction"]


def _is_trig_power(t: sp.Basic) -> bool:
    return bool(t.is_Pow and isinstance(t.base, (sp.sin, sp.cos)) and t.exp.is_Integer and t.exp >= 2)


def _pythagoras(e: sp.Expr, keep: type) -> sp.Expr:
    """Rewrite every power (>= 2) of the trig function other than ``keep`` with sin^2 + cos^2 = 1, and expand."""
    other = sp.cos if keep is sp.sin else sp.sin

    def lower(t: sp.Expr) -> sp.Expr:
        if _is_trig_power(t) and isinstance(t.base, other):
            x = t.base.args[0]
            return other(x) ** (t.exp - 2) * (1 - keep(x) ** 2)
        return t

    for _ in range(8):  # each pass lowers every exponent by 2
        new = sp.expand(e.replace(_is_trig_power, lower))
        if new == e:
            break
        e = new
    return e


def _simplify_entry(e: sp.Expr, cache: dict[sp.Expr, sp.Expr]) -> sp.Expr:
    """Expand, cancel sin^2 + cos^2, then fold c_a c_b - s_a s_b into c_{a+b} (Fu's rule TR10i)."""
    if e in cache:
        return cache[e]
    out = sp.expand(e)
    if out.has(sp.sin, sp.cos):
        if any(_is_trig_power(t) for t in out.atoms(sp.Pow)):
            out = min([out, _pythagoras(out, sp.cos), _pythagoras(out, sp.sin)], key=sp.count_ops)
        out = _TR10i(out)
        if any(_is_trig_power(t) for t in out.atoms(sp.Pow)):
            # folding may have produced new squares of angle sums
            out = _TR10i(min([out, _pythagoras(out, sp.cos), _pythagoras(out, sp.sin)], key=sp.count_ops))
    cache[e] = out
    return out


def tidy(A: sp.Matrix, simplify: bool, cache: dict[sp.Expr, sp.Expr] | None = None) -> sp.Matrix:
    """Expand every entry, and simplify it cheaply if asked (used on partial products)."""
    if not simplify:
        return A.applyfunc(sp.expand)
    memo: dict[sp.Expr, sp.Expr] = {} if cache is None else cache
    return A.applyfunc(lambda e: _simplify_entry(e, memo))


def simplify_matrix(A: object) -> sp.Matrix:
    r"""Simplify every entry of a matrix of sines, cosines and lengths.

    Each entry is expanded; powers of sines and cosines are reduced with
    :math:`\sin^2 + \cos^2 = 1` when that shortens the entry; then Fu's rule
    TR10i folds sums of products into sines and cosines of angle sums
    (:math:`c_1c_2 - s_1s_2 \to c_{12}`, :math:`s_1c_2 + c_1s_2 \to s_{12}`).
    These targeted rules are much faster than ``sympy.trigsimp`` and give the
    textbook forms (planar 3R Jacobians in a fraction of a second, the UR5's in
    a few seconds). Repeated entries are simplified once. Not a general
    simplifier: rational functions are only expanded.

    >>> a, b, l = sp.symbols("a b l")
    >>> simplify_matrix(sp.Matrix([[l*sp.cos(a)*sp.cos(b) - l*sp.sin(a)*sp.sin(b)]]))
    Matrix([[l*cos(a + b)]])
    """
    return tidy(matrix(A, "A"), simplify=True)


def _reduces_to_zero(e: sp.Expr) -> bool:
    """Exact test for rational functions of sines and cosines: True only if e is identically zero.

    Sines and cosines of sums and multiples are expanded; sin x, cos x become
    new symbols s, c; the numerator is reduced modulo s^2 + c^2 - 1 (remainder of
    the division by it, in c). A zero remainder proves e = 0.
    """
    if any(isinstance(f.args[0], sp.Add) or f.args[0].is_Mul for f in e.atoms(sp.sin, sp.cos)):
        e = sp.expand_trig(e)
    angles = sorted({f.args[0] for f in e.atoms(sp.sin, sp.cos)}, key=str)
    rename: dict[sp.Expr, sp.Expr] = {}
    pairs = []
    for k, x in enumerate(angles):
        s_k, c_k = sp.Dummy(f"s{k}"), sp.Dummy(f"c{k}")
        rename[sp.sin(x)], rename[sp.cos(x)] = s_k, c_k
        pairs.append((s_k, c_k))
    num, _ = sp.fraction(sp.together(e.xreplace(rename)))
    num = sp.expand(num)
    for s_k, c_k in pairs:
        if num == 0:
            break
        num = sp.expand(sp.rem(num, c_k**2 + s_k**2 - 1, c_k))
    return bool(num == 0)


def _clearly_not_zero(e: sp.Expr) -> bool:
    """True if e takes a value far from 0 at one of a few points (which proves it is not identically 0).

    The symbols get values in [0.5, 1.5], which meet the usual assumptions (real, positive); if a
    symbol cannot be positive, nothing is tried.
    """
    symbols = sorted(e.free_symbols, key=str)
    if any(x.is_positive is False for x in symbols):
        return False
    rng = np.random.default_rng(0)
    for _ in range(3):
        point = {x: sp.Float(v) for x, v in zip(symbols, rng.uniform(0.5, 1.5, len(symbols)), strict=True)}
        try:
            value = complex(e.xreplace(point).evalf(30))
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if np.isfinite(value) and abs(value) > 1e-9:
            return True
    return False


def is_zero(expr: object) -> bool:
    """True if a sympy expression is identically zero: True only when one of the tests below proves it.

    First the fast polynomial test (sines and cosines as symbols, reduced with
    :math:`s^2 + c^2 = 1`); then, if the value at a few points is clearly not
    zero, False; then ``sympy.simplify``, then a rewrite in complex
    exponentials. False means none of them proved it zero.

    >>> x = sp.Symbol("x")
    >>> is_zero(sp.sin(2 * x) - 2 * sp.sin(x) * sp.cos(x)), is_zero(sp.sin(x) - sp.cos(x))
    (True, False)
    """
    if isinstance(expr, (str, bytes)):
        raise TypeError(f"Expected a sympy expression, got {describe(expr)}")
    e = sp.sympify(expr)
    if not isinstance(e, sp.Expr):
        raise TypeError(f"Expected a sympy expression, got {describe(expr)}")
    if e == 0 or _reduces_to_zero(e):
        return True
    if _clearly_not_zero(e):
        return False
    if sp.simplify(e) == 0:
        return True
    return bool(sp.expand(sp.expand_trig(e).rewrite(sp.exp)) == 0)


def is_zero_matrix(A: object) -> bool:
    """True if every entry of a matrix is identically zero (:func:`is_zero` on each).

    >>> t = sp.Symbol("t")
    >>> is_zero_matrix(sp.Matrix([[sp.cos(t)**2 + sp.sin(t)**2 - 1, 0]]))
    True
    """
    return all(is_zero(e) for e in matrix(A, "A"))


def _flatten_symbols(symbols: object) -> list[sp.Symbol]:
    if isinstance(symbols, (str, bytes)):
        raise TypeError("Expected sympy symbols, got a str (pass sympy.Symbol objects)")
    if isinstance(symbols, sp.Symbol):
        return [symbols]
    if isinstance(symbols, sp.MatrixBase):
        symbols = list(symbols)
    if not isinstance(symbols, (list, tuple)):
        raise TypeError(f"Expected a sequence of sympy symbols, got {describe(symbols)}")
    out: list[sp.Symbol] = []
    for s in symbols:
        if isinstance(s, (list, tuple, sp.MatrixBase)):
            out.extend(_flatten_symbols(s))
        elif isinstance(s, sp.Symbol):
            out.append(s)
        else:
            raise TypeError(f"Expected sympy symbols, got {describe(s)}")
    if len(set(out)) != len(out):
        raise ValueError(f"Expected distinct symbols, got {out}")
    return out


class MatrixFunction:
    """A symbolic matrix compiled to numpy: ``f(x)``, x of shape (..., k), or ``f(x1, ..., xk)``.

    Made by :func:`lambdify_matrix`.
    """

    def __init__(self, shape: tuple[int, int], symbols: tuple[sp.Symbol, ...], funcs: Callable[..., Any]) -> None:
        self._shape = shape
        self._symbols = symbols
        self._funcs = funcs

    @property
    def symbols(self) -> tuple[sp.Symbol, ...]:
        """The symbols, in the order the values come."""
        return self._symbols

    def __call__(self, *args: ArrayLike) -> NDArray[np.float64]:
        k = len(self._symbols)
        if len(args) == 1 and k != 1:
            x = np.asarray(args[0], dtype=float)
            if x.ndim == 0 or x.shape[-1] != k:
                raise ValueError(f"Expected values with shape (..., {k}) for the symbols {self._symbols}, "
                                 f"got shape {x.shape}")
            vals = [x[..., j] for j in range(k)]
        elif len(args) == k:
            vals = [np.asarray(a, dtype=float) for a in args]
        else:
            raise TypeError(f"Expected one array of shape (..., {k}) or {k} values, got {len(args)} arguments")
        shape = np.broadcast_shapes(*[v.shape for v in vals]) if vals else ()
        r, c = self._shape
        out = np.empty(shape + (r * c,))
        for j, e in enumerate(self._funcs(*vals)):
            out[..., j] = e
        return out.reshape(shape + (r, c))


def lambdify_matrix(A: object, symbols: object) -> MatrixFunction:
    r"""A fast numeric function of a symbolic matrix.

    Parameters
    ----------
    A : sympy Matrix, shape (r, c)
    symbols : sequence of sympy symbols (nested sequences are flattened)
        The k symbols, in the order the values will come. Every free symbol
        of A must be among them.

    Returns
    -------
    f : MatrixFunction
        ``f(x)`` with x of shape (..., k) returns an ndarray of shape
        (..., r, c); ``f(x1, ..., xk)`` with k scalars or broadcastable
        arrays also works. With a single symbol (k = 1), ``f(x)`` takes the
        values of that symbol, any shape (...).

    >>> a, b = sp.symbols("a b")
    >>> f = lambdify_matrix(sp.Matrix([[a, a * b]]), [a, b])
    >>> f([2.0, 3.0])
    array([[2., 6.]])
    """
    M = matrix(A, "A")
    syms = _flatten_symbols(symbols)
    missing = M.free_symbols - set(syms)
    if missing:
        raise ValueError(f"The matrix depends on {sorted(map(str, missing))}, which are not in symbols {syms}")
    funcs = sp.lambdify(syms, list(M), modules="numpy", cse=True)
    return MatrixFunction(M.shape, tuple(syms), funcs)
