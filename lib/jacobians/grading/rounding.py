r"""The rule for numbers: how far from the exact value a right answer worked by hand may land.

A student who works an exercise by hand rounds what they write down: the
sines and cosines, the entries of a Jacobian, a determinant. Each rounding
moves the final answer a little. The checker accepts exactly the answers
that such right hand-work can give, and says so in the statement.

The exercise supplies its *method*: the intended computation written as a
function ``method(r)`` that passes every intermediate result it would write
down through ``r`` (``x = r(np.sin(th))``) and returns the answer. Then

* the *rounding bound* is first order: rounding intermediate ``x_i`` to ``c``
  decimals moves it by at most ``h = 0.5 * 10**-c``, so the answer moves by at
  most ``sum_i |d answer / d x_i| * h``; the derivatives are finite
  differences of the method itself (each intermediate entry nudged in turn);
* the final answer is rounded to the ``d`` decimals asked, which adds
  ``0.5 * 10**-d``;
* the accepted tolerance is that sum, taken over the entries (the largest),
  with :data:`HEADROOM` (10 %) added for the second-order terms (of size
  ``h**2`` times the curvature, about ``h`` = 0.0005 times smaller than the
  first-order ones unless a step divides by a number near zero), rounded *up*
  to two significant digits (what the statement prints);
  ``tests/test_exercise_rule.py`` rounds every step of every exercise's method
  over many variants and checks the hand answer lands inside.

If carrying ``d`` decimals through the steps would allow too much (both more
than :data:`MAX_UNITS` units of the last decimal asked and more than
:data:`MAX_RELATIVE` of the answer's size), the variant asks the student to
carry one more decimal, up to ``d + 3``: the statement says how many.

Why this and not a relative tolerance (WeBWorK's 0.1 %, PrairieLearn's 1 %)?
A relative rule is blind to the conditioning of the method: an entry that is
the small difference of large rounded numbers (an entry near 0 of a Jacobian, a
Newton step) moves by far more than 1 % of itself, while a well-conditioned
entry needs less. The bound above is exactly what the method can produce,
so right hand-work is accepted and little else is.

>>> import numpy as np
>>> def method(r):  # the area of a 1.2 x 0.7 rectangle turned by 30 degrees: rounding cos 30 matters
...     c = r(np.cos(np.pi / 6))
...     return 1.2 * 0.7 * c
>>> rule = derive_rule(method, 3)
>>> rule.tol, rule.carry
(0.0011, 3)
>>> bool(abs(hand_answer(method, 3, 3) - method(lambda x: x)) <= rule.tol)
True
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["HEADROOM", "MAX_RELATIVE", "MAX_UNITS", "Method", "Rule", "derive_rule", "direct_rule", "hand_answer",
           "nice_ceil", "rule_sentence"]

#: The method of an exercise: its computation, with every written-down intermediate passed through ``r``.
Method = Callable[[Callable[[Any], Any]], Any]

#: Most units of the last decimal asked that rounding the steps may cost before the variant asks for one more
#: carried decimal (5 units of the third decimal: ±0.005).
MAX_UNITS = 5.0

#: Largest share of the answer's size (its largest entry) the tolerance may reach before the variant asks for
#: one more carried decimal.
MAX_RELATIVE = 0.01

#: Share added to the first-order bound for the second-order terms of the rounding errors.
HEADROOM = 0.10

#: Finite-difference step for the derivatives of the answer with respect to the intermediates.
_FD_STEP = 1e-6


@dataclass(frozen=True)
class Rule:
    """The accepted tolerance of one variant: ``tol`` (absolute, per entry, as printed), the decimals asked
    (``decimals``) and the decimals to carry through the steps (``carry``); ``bound`` is the first-order bound
    before rounding up."""

    tol: float
    decimals: int
    carry: int
    bound: float


class _Recorder:
    """The ``r`` a method calls: records the intermediates, nudges one entry, or rounds them all."""

    def __init__(self, mode: str = "identity", index: int = -1, step: float = 0.0, carry: int = 0) -> None:
        self.mode, self.index, self.step, self.carry = mode, index, step, carry
        self.count = 0

    def __call__(self, x: Any) -> Any:
        arr = np.array(x, dtype=float)
        start = self.count
        self.count += arr.size
        if self.mode == "round":
            arr = np.round(arr, self.carry)
        elif self.mode == "nudge" and start <= self.index < self.count:
            arr.flat[self.index - start] += self.step
        return float(arr) if arr.ndim == 0 else arr


def _run(method: Method, r: _Recorder) -> NDArray[np.float64]:
    return np.asarray(method(r), dtype=float)


def nice_ceil(x: float) -> float:
    """``x`` (``> 0``) rounded up to two significant digits: ``nice_ceil(0.01124) == 0.012``."""
    if not x > 0 or not math.isfinite(x):
        raise ValueError(f"Expected a positive finite tolerance, got {x}")
    unit = 10.0 ** (math.floor(math.log10(x)) - 1)
    return round(math.ceil(x / unit * (1 - 1e-12)) * unit, 12)


def sensitivity(method: Method) -> NDArray[np.float64]:
    """``sum_i |d answer / d x_i|`` per entry of the answer, over every intermediate entry ``x_i``."""
    rec = _Recorder()
    f0 = _run(method, rec)
    total = np.zeros_like(f0)
    for k in range(rec.count):
        fk = _run(method, _Recorder("nudge", k, _FD_STEP))
        total += np.abs(fk - f0) / _FD_STEP
    return total


def direct_rule(decimals: int) -> Rule:
    """The rule of an answer with no rounded intermediate step (a formula of exact data): half a unit of
    the last decimal asked."""
    h = 0.5 * 10.0 ** (-decimals)
    return Rule(h, decimals, decimals, h)


def derive_rule(method: Method, decimals: int) -> Rule:
    """The accepted tolerance of a method whose intermediates are rounded to ``carry`` decimals, with the
    smallest ``carry`` in ``decimals .. decimals + 3`` whose tolerance stays within :data:`MAX_UNITS` units
    of the last decimal or within :data:`MAX_RELATIVE` of the answer's size (the largest tried otherwise)."""
    grad = sensitivity(method)
    size = float(np.max(np.abs(_run(method, _Recorder())))) if grad.size else 0.0
    rule = direct_rule(decimals)
    for carry in range(decimals, decimals + 4):
        bound = float(np.max(0.5 * 10.0 ** (-decimals) + grad * 0.5 * 10.0 ** (-carry))) if grad.size else 0.0
        rule = Rule(nice_ceil(bound * (1 + HEADROOM)), decimals, carry, bound)
        if rule.tol <= MAX_UNITS * 10.0 ** (-decimals) or rule.tol <= MAX_RELATIVE * size:
            break
    return rule


def hand_answer(method: Method, carry: int, decimals: int) -> NDArray[np.float64]:
    """The method worked by hand: every intermediate rounded to ``carry`` decimals, the answer to ``decimals``."""
    return np.round(_run(method, _Recorder("round", carry=carry)), decimals)


def _fmt(x: float) -> str:
    return f"{x:.10f}".rstrip("0").rstrip(".")


def rule_sentence(rule: Rule, scalar: bool) -> str:
    """What the statement says about precision, in words a student understands."""
    what, one = ("your value", "A value") if scalar else ("every entry", "An entry")
    d = rule.decimals
    if rule.tol <= 0.5 * 10.0 ** (-d) * (1 + 1e-9):
        return (f"Give {what} to {d} decimals (or more); {one.lower()} within ±{_fmt(rule.tol)} of the exact "
                "value is accepted.")
    return (f"Give {what} to {d} decimals (or more), carrying at least {rule.carry} decimals through every step: "
            f"{one.lower()} within ±{_fmt(rule.tol)} of the exact value is accepted, which covers rounding each "
            f"intermediate result to {rule.carry} decimals.")
