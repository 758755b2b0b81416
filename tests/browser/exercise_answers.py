"""Answers to try on an exercise, as the page reads them (text) and as the notebook gives them (a Python value),
for the agreement tests of the page's checker with :func:`course.exercises.check`.

For a variant: the reference (written three ways: a nested list, rows one a line, NumPy's repr), the reference
rounded to the decimals asked, to one and two fewer, to one decimal; every catalogued mistake (exact and
rounded to the decimals asked); the reference moved by 1.5 and 2.5 times the stated margin (the message about
precision); the transpose, a wrong shape (one entry dropped, and one entry only), entries in another order,
the empty box, garbage text, NaN, and a formula with an unknown symbol.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from jacobians.grading import Exercise


def text_of(value: Any, style: int = 0) -> str:
    """The text a reader types for ``value``: ``repr`` of each float (the same double when read back)."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        return repr(float(arr))
    if arr.ndim == 1:
        entries = [repr(float(x)) for x in arr]
        return "[" + ", ".join(entries) + "]" if style != 1 else " ".join(entries)
    rows = [[repr(float(x)) for x in row] for row in arr]
    if style == 1:  # one row a line, spaces between entries
        return "\n".join(" ".join(r) for r in rows)
    if style == 2:  # NumPy's repr
        return "array([" + ",\n       ".join("[" + ", ".join(r) + "]" for r in rows) + "])"
    return "[" + ", ".join("[" + ", ".join(r) + "]" for r in rows) + "]"


def formula_text(value: Any) -> str:
    """The text a reader types for a sympy expression, or a matrix of them (rows in brackets, sympy's printing)."""
    import sympy as sp
    if isinstance(value, sp.MatrixBase):
        return "[" + ",\n ".join("[" + ", ".join(str(e) for e in row) + "]" for row in value.tolist()) + "]"
    if isinstance(value, list):
        return "[" + ", ".join(str(e) for e in value) + "]"
    return str(value)


def symbolic_answers_for(ex: Exercise) -> list[tuple[str, Any]]:
    """(text for the page, value for the notebook: a sympy Matrix, a list of expressions or one expression) pairs
    to try on a symbolic variant: the reference (as printed, expanded, and written with ^ and spaces), every
    catalogued mistake, the transpose, the columns swapped, a wrong shape (a row dropped, one row only, one
    entry), one entry changed, a symbol set to a number (the answer then misses it), numbers only, NaN, a
    formula with an unknown symbol, garbage and an empty box."""
    import sympy as sp
    ref = ex.reference
    syms = {str(s): s for s in ex.symbols.values()}
    out: list[tuple[str, Any]] = []

    def add(value: Any, text: str | None = None) -> None:
        out.append((formula_text(value) if text is None else text, value))

    add(ref)
    expanded = ref.applyfunc(lambda e: sp.expand(sp.expand_trig(e)))
    add(expanded)
    add(ref, formula_text(ref).replace("**", "^").replace("*", " * "))
    add(ref, "Matrix(" + formula_text(ref) + ")")
    for m in ex.mistakes:
        add(m.value)
    add(ref.T)
    add(ref[:, ::-1])
    add(ref[:-1, :])
    add(list(ref[0, :]))
    add(ref[0, 0])
    changed = ref.copy()
    changed[0, 0] = changed[0, 0] + 1
    add(changed)
    changed = ref.copy()
    changed[-1, -1] = changed[-1, -1] + syms["l1"]
    add(changed)
    add(ref.xreplace({syms["l2"]: sp.Integer(1)}))
    add(ref.xreplace({s: sp.Float(0.5 + 0.1 * i) for i, s in enumerate(syms.values())}))
    nan = ref.copy()
    nan[0, 0] = sp.nan
    add(nan, formula_text(nan))
    q = sp.Symbol("q")
    unknown = ref.copy()
    unknown[1, 0] = unknown[1, 0] + q
    add(unknown)
    out.append(("", None))
    out.append(("hello world", "hello world"))
    out.append(("l1*cos(theta1", "l1*cos(theta1"))
    return out


def answers_for(ex: Exercise) -> list[tuple[str, Any]]:
    """(text for the page, value for the notebook) pairs to try on the variant ``ex``."""
    if ex.kind == "symbolic":
        return symbolic_answers_for(ex)
    ref = np.asarray(ex.reference, dtype=float)
    d = ex.decimals if ex.decimals is not None else 3
    out: list[tuple[str, Any]] = []

    def add(value: Any, style: int = 0) -> None:
        arr = np.asarray(value, dtype=float)
        out.append((text_of(arr, style), arr if arr.ndim else float(arr)))

    for style in (0, 1, 2):
        add(ref, style)
    for k in sorted({d, max(d - 1, 0), max(d - 2, 0), 1}, reverse=True):
        add(np.round(ref, k))
    for m in ex.mistakes:
        add(m.value)
        add(np.round(np.asarray(m.value, dtype=float), d))
    if ex.tol is not None:
        for f in (1.5, 2.5, 5.0):
            moved = ref.copy()
            moved.reshape(-1)[0] += f * ex.tol
            add(moved)
    if ref.ndim == 2:
        add(ref.T, 1)
        add(np.round(ref.T, d))
        add(ref[:, ::-1])
    if ref.ndim == 1 and ref.size > 1:
        add(ref[::-1])
        add(np.round(ref[::-1], d))
    if ref.size > 1:
        add(ref.reshape(-1)[:-1])
    else:
        add([float(ref.reshape(-1)[0]), 1.0])
    add(ref.reshape(-1)[:1])
    wrong = ref.copy()
    wrong.reshape(-1)[-1] += 1.0
    add(wrong)
    if ex.kind == "scalar":
        for a in ex.accepted + ex.outside:
            add(a)
            add(np.round(a, 1))
        add(-ref)
    # near the edges of the rules: the margin, NEAR times it, a mistake's margin (entries moved at random)
    rng = np.random.default_rng(sum(ex.seed.encode()) + len(out))
    margin = ex.tol if ex.tol is not None else 0.5 * 10.0 ** (-d)
    for f in (0.99, 1.0, 1.01, 2.99, 3.0, 3.01):
        moved = ref.copy().reshape(-1)
        moved += f * margin * rng.choice([-1.0, 0.0, 1.0], size=moved.size)
        add(moved.reshape(ref.shape))
    for m in ex.mistakes[:3]:
        mv = np.asarray(m.value, dtype=float).copy().reshape(-1)
        mv += 0.99 * margin * rng.choice([-1.0, 1.0], size=mv.size)
        add(mv.reshape(np.shape(m.value)))
    out.append(("", None))
    out.append(("hello world", "hello world"))
    nan = ref.copy()
    nan.reshape(-1)[0] = np.nan
    out.append((text_of(nan), nan if nan.ndim else float("nan")))
    out.append(("theta1 + 1", "theta1 + 1"))
    return out
