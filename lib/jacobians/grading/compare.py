"""How an answer is compared, and how a likely mistake is named.

:func:`compare` grades a float array against the reference and a catalogue of
:class:`Mistake` s (wrong answers computed from the same variant, each with the
message that says what to look at). If none matches, the generic mistakes are
tried: wrong shape, transposed, columns in the wrong order, rows in the wrong order, the entries of a vector in
the wrong order, one wrong entry (located by row and column), several wrong entries (named by column).

>>> ref = np.array([[1.0, 2.0], [3.0, 4.0]])
>>> compare(ref.T, ref, [], 1e-6, 1e-8, "matrix").mistake
'transposed'
>>> compare(np.array([[1.0, 2.0], [3.0, 5.0]]), ref, [], 1e-6, 1e-8, "matrix").message[:63]
'Almost: the entry in row 2, column 2 (counting from 1) is wrong'
>>> compare(np.array([1.23, 2.0]), np.array([1.23456, 2.0]), [], 0, 0, "vector", decimals=3).mistake
'too_few_decimals'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .feedback import Feedback, agrees, verdict

__all__ = ["NEAR", "Mistake", "compare", "distinct_mistakes", "given_decimals", "near_message", "precision_message",
           "tolerance"]


@dataclass
class Mistake:
    """A catalogued mistake: its name, the wrong answer it produces, and what to look at."""

    name: str
    value: Any
    message: str


def _close_tol(a: NDArray[np.float64], b: NDArray[np.float64], tol: Any) -> bool:
    tol = np.asarray(tol, dtype=float)
    return a.shape == b.shape and tol.shape in ((), b.shape) and bool(np.all(np.abs(a - b) <= tol))


_TRANSPOSED = "Your matrix is the transpose of the right one: rows and columns are swapped."


def _shape_feedback(ans: NDArray[np.float64], ref: NDArray[np.float64], tol: NDArray[np.float64],
                    what: str) -> Feedback | None:
    """Wrong shape, transposed, entries, columns or rows in the wrong order; None if none of these."""
    if ans.shape != ref.shape:
        if ref.ndim == 2 and ans.shape == ref.shape[::-1] and _close_tol(ans.T, ref, tol):
            return verdict(False, _TRANSPOSED, mistake="transposed")
        if ref.ndim == 3 and ans.shape == (ref.shape[0], *ref.shape[:0:-1]) and _close_tol(
                np.swapaxes(ans, 1, 2), ref, tol):
            return verdict(False, "Each matrix of your stack is the transpose of the right one: rows and columns "
                           "are swapped.", mistake="transposed")
        jacobian = ref.ndim == 2 and ref.shape[0] == 6 and "Jacobian" in what
        layout = (" (6 rows (ω, v), one column per joint)." if jacobian
                  else ": check how many rows and columns the statement asks for.")
        return verdict(False, f"Your answer has shape {ans.shape}, but this {what} has shape {ref.shape}" + layout,
                       mistake="wrong_shape")
    if ref.ndim == 3:
        return _blocks_feedback(ans, ref, tol, what)
    if ref.ndim == 1 and ref.size > 1:
        # Entries in the wrong order: the sorted answer matches the sorted reference, the answer does not.
        order = np.argsort(ref)
        if _close_tol(np.sort(ans), ref[order], tol[order] if tol.ndim else tol):
            return verdict(False, "Every value you gave is right, but they are in the wrong order: check the order "
                           "the statement asks for (entry i belongs to joint i, or the order it names, such as "
                           "largest first).", mistake="wrong_order")
    if ref.ndim == 2 and ref.shape[0] == ref.shape[1] and _close_tol(ans.T, ref, tol):
        return verdict(False, _TRANSPOSED, mistake="transposed")
    if ref.ndim == 2 and ref.shape[1] > 1:
        # Columns in the wrong order: every column matches some other column.
        perm = [[k for k in range(ref.shape[1]) if _close_tol(ans[:, j], ref[:, k], tol[:, k] if tol.ndim else tol)]
                for j in range(ref.shape[1])]
        if all(perm) and not all(j in h for j, h in enumerate(perm)):
            return verdict(False, "Every column you gave is a right column, but in the wrong place: check the "
                           "order of the columns (column i belongs to joint i).", mistake="column_order")
    if ref.ndim == 2 and ref.shape[0] > 1:
        # Rows in the wrong order: every row matches some other row (a twist's halves swapped, (v, ω) for (ω, v)).
        perm = [[k for k in range(ref.shape[0]) if _close_tol(ans[i], ref[k], tol[k] if tol.ndim else tol)]
                for i in range(ref.shape[0])]
        if all(perm) and not all(i in h for i, h in enumerate(perm)):
            return verdict(False, "Every row you gave is a right row, but in the wrong place: check the order of "
                           "the rows" + (" (ω in rows 1-3, then v in rows 4-6)." if ref.shape[0] == 6 else "."),
                           mistake="row_order")
    return None


_ORDER = ("transposed", "column_order", "row_order")


def _blocks_feedback(ans: NDArray[np.float64], ref: NDArray[np.float64], tol: NDArray[np.float64],
                     what: str) -> Feedback | None:
    """For a stack of matrices (one per link, say; same shape as the reference): the blocks in the wrong order,
    or every wrong block in the same wrong order (transposed, columns or rows); None if neither."""
    n = ref.shape[0]
    right = [_close_tol(ans[b], ref[b], tol[b]) for b in range(n)]
    if all(right):
        return None
    perm = [[k for k in range(n) if _close_tol(ans[b], ref[k], tol[k])] for b in range(n)]
    if all(perm) and not all(b in h for b, h in enumerate(perm)):
        return verdict(False, "Every matrix you gave is a right one, but in the wrong place: check the order of the "
                       "blocks (the first index, counting from 1, is the link or joint the statement names).",
                       mistake="block_order")
    named = [_shape_feedback(ans[b], ref[b], tol[b], what) for b in range(n) if not right[b]]
    names = {fb.mistake if fb is not None else None for fb in named}
    if len(names) == 1 and (name := names.pop()) in _ORDER:
        wrong = ", ".join(str(b + 1) for b in range(n) if not right[b])
        first = next(fb for fb in named if fb is not None)
        return verdict(False, f"In block(s) {wrong} (first index, counting from 1): {first.message}", mistake=name)
    return None


def _rows_text(bad_rows: list[int]) -> str:
    """Which half of a twist column the wrong rows are in (rows 1-3 angular, 4-6 linear)."""
    ang = any(r < 3 for r in bad_rows)
    lin = any(r >= 3 for r in bad_rows)
    if ang and lin:
        return "in both the angular rows 1-3 and the linear rows 4-6"
    return "in the angular rows 1-3 (ω)" if ang else "in the linear rows 4-6 (v)"


def _entries_feedback(ans: NDArray[np.float64], ref: NDArray[np.float64], tol: NDArray[np.float64],
                      what: str, entry_hint: str) -> Feedback:
    """Which entries are wrong, for an answer of the right shape, with what to check."""
    bad = ~(np.abs(ans - ref) <= tol)
    nbad = int(bad.sum())
    twist_rows = ref.ndim >= 1 and ref.shape[0] == 6
    if ref.ndim == 0:
        side = "too large" if ans > ref else "too small"
        hint = entry_hint or f"Redo the computation step by step and check each quantity that enters your {what}."
        return verdict(False, f"Your {what} {agrees(what, 'is', 'are')} {side}. {hint}", mistake="wrong_value")
    if not entry_hint:
        entry_hint = "Check the wrong entries' joint, frame and sign against the definition."
    if nbad == 1:
        idx = tuple(int(i[0]) for i in np.nonzero(bad))
        if ref.ndim == 1:
            where = f"entry {idx[0] + 1} (counting from 1)"
        elif ref.ndim == 2:
            where = f"the entry in row {idx[0] + 1}, column {idx[1] + 1} (counting from 1)"
        else:
            where = "the entry at index " + ", ".join(str(i + 1) for i in idx) + " (counting from 1)"
        return verdict(False, f"Almost: {where} is wrong; every other entry is right. {entry_hint}",
                       mistake="wrong_entry")
    if ref.ndim == 3:
        blocks = [i for i in range(ref.shape[0]) if bad[i].any()]
        return verdict(False, f"{nbad} entries are wrong, in block(s) {', '.join(str(i + 1) for i in blocks)} "
                       f"(first index, counting from 1). {entry_hint}", mistake="wrong_entries")
    if ref.ndim == 2:
        cols = [j for j in range(ref.shape[1]) if bad[:, j].any()]
        good = [j for j in range(ref.shape[1]) if j not in cols]
        msg = f"{nbad} entries are wrong, in column(s) {', '.join(str(j + 1) for j in cols)}"
        if twist_rows:
            msg += " " + _rows_text([int(r) for r in np.nonzero(bad.any(axis=1))[0]])
        if good:
            msg += f"; column(s) {', '.join(str(j + 1) for j in good)} are right"
        return verdict(False, msg + f". {entry_hint}", mistake="wrong_entries")
    rows = [int(i) for i in np.nonzero(bad.ravel())[0]]
    idx_txt = ", ".join(str(i + 1) for i in rows)
    extra = f", {_rows_text(rows)}" if twist_rows else ""
    return verdict(False, f"Entries {idx_txt} (counting from 1) are wrong{extra}. {entry_hint}",
                   mistake="wrong_entries")


def given_decimals(ans: NDArray[np.float64], most: int) -> int | None:
    """The number of decimals the answer was given to, if fewer than ``most`` (None: ``most`` or more).

    An answer whose every entry is a multiple of 10^-k was rounded to k decimals.
    """
    for k in range(most):
        scaled = ans * 10.0 ** k
        if np.all(np.abs(scaled - np.round(scaled)) <= 1e-6 * np.maximum(1.0, np.abs(scaled))):
            return k
    return None


def tolerance(ref: NDArray[np.float64], decimals: int | None, rtol: float, atol: float) -> NDArray[np.float64]:
    """Entry-wise tolerance: half a unit of the ``decimals``-th decimal (an answer rounded to that many
    decimals is right), or ``atol + rtol |ref|`` without a stated precision."""
    if decimals is None:
        return atol + rtol * np.abs(ref)
    return 0.5 * 10.0 ** (-decimals) * (1 + 1e-6) + 1e-5 * np.abs(ref)


def _stated(tol: float, ref: NDArray[np.float64]) -> NDArray[np.float64]:
    """The stated tolerance as an entry-wise array, with room for the binary noise of the comparison."""
    return np.full(np.shape(ref), tol * (1 + 1e-9) + 1e-12 * (1 + np.max(np.abs(ref), initial=0.0)))


def _within(a: NDArray[np.float64], b: NDArray[np.float64], tol: NDArray[np.float64] | float) -> bool:
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= tol))


def precision_message(what: str, given: int, asked: int) -> str:
    """The message for an answer right to the decimals it was given in, but fewer than asked."""
    dec = "decimal" if given == 1 else "decimals"
    verb = agrees(what, "agrees", "agree")
    return (f"Your {what} {verb} with the reference to the {given} {dec} you gave, but this exercise "
            f"asks for {asked} decimals: give more decimals (keep the digits your computation gives, or round "
            f"to {asked}).")


def near_message(what: str, tol: float, worst: float, carry: int | None) -> str:
    """The message for an answer just outside the accepted tolerance: about precision, never the method."""
    steps = f"rounding every step to {carry} decimals" if carry is not None else "rounding the answer"
    verb = agrees(what, "is", "are")
    return (f"Close: your {what} {verb} off by up to {worst:.2g}, a little more than the ±{tol:g} that {steps} "
            "can give. Your method looks right; carry more decimals through the steps (keep 4 or 5, or let Python "
            "keep them all) and round only the final answer.")


#: How many tolerances from the reference an answer may be and still get the message about precision
#: (farther, it is wrong; a catalogued mistake that near is not told apart, see :func:`distinct_mistakes`).
NEAR = 3.0


def compare(ans: NDArray[np.float64], ref: Any, mistakes: list[Mistake], rtol: float, atol: float,
            what: str, entry_hint: str = "", decimals: int | None = None, tol: float | None = None,
            carry: int | None = None) -> Feedback:
    """Grade a float array against the reference and the catalogue of mistakes.

    With ``decimals`` (the precision the statement asks for), an answer within
    half a unit of that decimal is right, and an answer given to fewer
    decimals that agrees with the reference to the decimals it has is told to
    give more decimals. With ``tol`` (the exercise's stated rule, see :mod:`~jacobians.grading.rounding`) an
    answer within ``tol`` of the reference (entry by entry) is right, one within ``tol`` of a catalogued mistake
    is named as that mistake, and one within :data:`NEAR` times ``tol`` is told to carry more decimals
    (``carry`` is the number of decimals the statement asks to carry). Without them, ``rtol`` and ``atol``
    decide (code and symbolic answers, compared tightly). Vectors are accepted as ``(n,)``,
    ``(n, 1)`` or ``(1, n)`` alike; a catalogued mistake wins over the generic
    ones; NaN or inf is never right.
    """
    ref = np.asarray(ref, dtype=float)
    if ref.ndim == 1 and ans.size == ref.size and ans.ndim <= 2 and (ans.ndim == 1 or 1 in ans.shape):
        ans = ans.reshape(ref.shape)
    if ref.ndim == 0 and ans.size == 1:
        ans = ans.reshape(())
    if not np.all(np.isfinite(ans)):
        return verdict(False, "Your answer contains NaN or inf: check for a division by zero or an unset entry.",
                       mistake="not_finite")
    stated = tol
    tolv = tolerance(ref, decimals, rtol, atol) if stated is None else _stated(stated, ref)
    if _within(ans, ref, tolv):
        return verdict(True, f"Your {what} {agrees(what, 'matches', 'match')} the reference" +
                       (f" (within ±{stated:g})." if stated is not None else "."))
    values = [(m, np.asarray(m.value, dtype=float)) for m in mistakes]
    for m, mv in values:  # a catalogued mistake, to the precision asked
        mtol = tolerance(mv, decimals, rtol, atol) if stated is None else _stated(stated, mv)
        if mv.shape == ans.shape and _within(ans, mv, mtol):
            return verdict(False, m.message, mistake=m.name)
    k = given_decimals(ans, decimals) if decimals is not None and ans.shape == ref.shape else None
    if k is not None and decimals is not None and (k > 0 or np.any(ans != 0)):
        half = 0.5 * 10.0 ** (-k) * (1 + 1e-6)
        if _within(ans, ref, half + 1e-5 * np.abs(ref)):  # right to the decimals given, too few of them
            return verdict(False, precision_message(what, k, decimals), mistake="too_few_decimals")
        for m, mv in values:  # a catalogued mistake, to the decimals given
            if mv.shape == ans.shape and _within(ans, mv, half + 1e-5 * np.abs(mv)):
                return verdict(False, m.message, mistake=m.name)
    if stated is not None and ans.shape == ref.shape and _within(ans, ref, NEAR * tolv):
        worst = float(np.max(np.abs(ans - ref)))
        return verdict(False, near_message(what, stated, worst, carry), mistake="imprecise")
    by_shape = _shape_feedback(ans, ref, tolv, what)  # (a Feedback is falsy when wrong: test for None)
    return by_shape if by_shape is not None else _entries_feedback(ans, ref, tolv, what, entry_hint)


def distinct_mistakes(reference: Any, mistakes: list[Mistake], rtol: float, atol: float,
                      decimals: int | None = None, tol: float | None = None) -> list[Mistake]:
    """The mistakes a variant can tell apart: not equal to the reference (e.g. a sign error in a zero
    column), not equal to an earlier mistake, and finite. "Equal" is within a few tolerances (those of
    ``decimals`` if given, or :data:`NEAR` times the stated ``tol``), so an answer within the rule never matches
    two of them, and an answer that gets the message about precision is never a catalogued mistake."""
    ref = np.asarray(reference, dtype=float)
    kept: list[Mistake] = []

    def near(a: NDArray[np.float64], b: NDArray[np.float64]) -> bool:
        if a.shape != b.shape:
            return False
        if tol is not None:
            return bool(np.all(np.abs(a - b) <= (NEAR + 1) * tol))
        if decimals is None:
            return bool(np.allclose(a, b, rtol=5 * rtol, atol=5 * atol))
        return bool(np.all(np.abs(a - b) <= 3 * tolerance(b, decimals, rtol, atol)))

    for m in mistakes:
        mv = np.asarray(m.value, dtype=float)
        same = near(mv, ref)
        dup = any(near(np.asarray(k.value, dtype=float), mv) for k in kept)
        if not same and not dup and np.all(np.isfinite(mv)):
            kept.append(m)
    return kept
