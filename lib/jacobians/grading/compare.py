"""How an answer is compared, and how a likely mistake is named.

:func:`compare` grades a float array against the reference and a catalogue of
:class:`Mistake` s (wrong answers computed from the same variant, each with the
message that says what to look at). If none matches, the generic mistakes are
tried: wrong shape, transposed, columns in the wrong order, one wrong entry
(located by row and column), several wrong entries (named by column).

>>> ref = np.array([[1.0, 2.0], [3.0, 4.0]])
>>> compare(ref.T, ref, [], 1e-6, 1e-8, "matrix").mistake
'transposed'
>>> compare(np.array([[1.0, 2.0], [3.0, 5.0]]), ref, [], 1e-6, 1e-8, "matrix").message
'Almost: the entry in row 2, column 2 (counting from 1) is wrong; every other entry is right.'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .feedback import Feedback, verdict

__all__ = ["Mistake", "compare", "distinct_mistakes"]


@dataclass
class Mistake:
    """A catalogued mistake: its name, the wrong answer it produces, and what to look at."""

    name: str
    value: Any
    message: str


def _close(a: NDArray[np.float64], b: NDArray[np.float64], rtol: float, atol: float) -> bool:
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= atol + rtol * np.abs(b)))


_TRANSPOSED = "Your matrix is the transpose of the right one: rows and columns are swapped."


def _shape_feedback(ans: NDArray[np.float64], ref: NDArray[np.float64], rtol: float, atol: float,
                    what: str) -> Feedback | None:
    """Wrong shape, transposed or columns in the wrong order; None if none of these."""
    if ans.shape != ref.shape:
        if ref.ndim == 2 and ans.shape == ref.shape[::-1] and _close(ans.T, ref, rtol, atol):
            return verdict(False, _TRANSPOSED, mistake="transposed")
        layout = " (6 rows (omega, v), one column per joint)." if ref.ndim == 2 and ref.shape[0] == 6 else "."
        return verdict(False, f"Your answer has shape {ans.shape}, but this {what} has shape {ref.shape}" + layout,
                       mistake="wrong_shape")
    if ref.ndim == 2 and ref.shape[0] == ref.shape[1] and _close(ans.T, ref, rtol, atol):
        return verdict(False, _TRANSPOSED, mistake="transposed")
    if ref.ndim == 2 and ref.shape[1] > 1:
        # Columns in the wrong order: every column matches some other column.
        perm = [[k for k in range(ref.shape[1]) if _close(ans[:, j], ref[:, k], rtol, atol)]
                for j in range(ref.shape[1])]
        if all(perm) and not all(j in h for j, h in enumerate(perm)):
            return verdict(False, "Every column you gave is a right column, but in the wrong place: check the "
                           "order of the columns (column i belongs to joint i).", mistake="column_order")
    return None


def _entries_feedback(ans: NDArray[np.float64], ref: NDArray[np.float64], rtol: float, atol: float,
                      entry_hint: str) -> Feedback:
    """Which entries are wrong, for an answer of the right shape."""
    bad = ~(np.abs(ans - ref) <= atol + rtol * np.abs(ref))
    nbad = int(bad.sum())
    if ref.ndim == 0:
        return verdict(False, f"Your value is not right. {entry_hint}".strip(), mistake="wrong_value")
    if nbad == 1:
        idx = tuple(int(i[0]) for i in np.nonzero(bad))
        if ref.ndim == 1:
            where = f"entry {idx[0] + 1} (counting from 1)"
        elif ref.ndim == 2:
            where = f"the entry in row {idx[0] + 1}, column {idx[1] + 1} (counting from 1)"
        else:
            where = "the entry at index " + ", ".join(str(i + 1) for i in idx) + " (counting from 1)"
        return verdict(False, f"Almost: {where} is wrong; every other entry is right. {entry_hint}".strip(),
                       mistake="wrong_entry")
    if ref.ndim == 3:
        blocks = [i for i in range(ref.shape[0]) if bad[i].any()]
        return verdict(False, f"{nbad} entries are wrong, in block(s) {', '.join(str(i + 1) for i in blocks)} "
                       f"(first index, counting from 1). {entry_hint}".strip(), mistake="wrong_entries")
    if ref.ndim == 2:
        cols = [j for j in range(ref.shape[1]) if bad[:, j].any()]
        good = [j for j in range(ref.shape[1]) if j not in cols]
        msg = f"{nbad} entries are wrong, in column(s) {', '.join(str(j + 1) for j in cols)}"
        if good:
            msg += f"; column(s) {', '.join(str(j + 1) for j in good)} are right"
        return verdict(False, msg + f". {entry_hint}".rstrip(), mistake="wrong_entries")
    idx_txt = ", ".join(str(i + 1) for i in np.nonzero(bad.ravel())[0])
    return verdict(False, f"Entries {idx_txt} (counting from 1) are wrong. {entry_hint}".strip(),
                   mistake="wrong_entries")


def compare(ans: NDArray[np.float64], ref: Any, mistakes: list[Mistake], rtol: float, atol: float,
            what: str, entry_hint: str = "") -> Feedback:
    """Grade a float array against the reference and the catalogue of mistakes.

    Vectors are accepted as ``(n,)``, ``(n, 1)`` or ``(1, n)`` alike; a
    catalogued mistake wins over the generic ones; NaN or inf is never right.
    """
    ref = np.asarray(ref, dtype=float)
    if ref.ndim == 1 and ans.size == ref.size and ans.ndim <= 2 and (ans.ndim == 1 or 1 in ans.shape):
        ans = ans.reshape(ref.shape)
    if ref.ndim == 0 and ans.size == 1:
        ans = ans.reshape(())
    if not np.all(np.isfinite(ans)):
        return verdict(False, "Your answer contains NaN or inf: check for a division by zero or an unset entry.",
                       mistake="not_finite")
    if _close(ans, ref, rtol, atol):
        return verdict(True, f"Your {what} matches the reference.")
    for m in mistakes:
        mv = np.asarray(m.value, dtype=float)
        if mv.shape == ans.shape and _close(ans, mv, rtol, atol):
            return verdict(False, m.message, mistake=m.name)
    by_shape = _shape_feedback(ans, ref, rtol, atol, what)  # (a Feedback is falsy when wrong: test for None)
    return by_shape if by_shape is not None else _entries_feedback(ans, ref, rtol, atol, entry_hint)


def distinct_mistakes(reference: Any, mistakes: list[Mistake], rtol: float, atol: float) -> list[Mistake]:
    """The mistakes a variant can tell apart: not equal to the reference (e.g. a sign error in a zero
    column), not equal to an earlier mistake, and finite."""
    ref = np.asarray(reference, dtype=float)
    kept: list[Mistake] = []
    for m in mistakes:
        mv = np.asarray(m.value, dtype=float)
        same = mv.shape == ref.shape and np.allclose(mv, ref, rtol=5 * rtol, atol=5 * atol)
        dup = any(np.asarray(k.value).shape == mv.shape
                  and np.allclose(np.asarray(k.value, dtype=float), mv, rtol=5 * rtol, atol=5 * atol)
                  for k in kept)
        if not same and not dup and np.all(np.isfinite(mv)):
            kept.append(m)
    return kept
