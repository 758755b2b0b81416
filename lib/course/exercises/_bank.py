"""Variant banks: which variant a student ID gets, and the data the book page checks answers with.

Every exercise has :data:`BANK_SIZE` variants, numbered 0 ... BANK_SIZE - 1. Variant ``k`` is the catalogue's
variant for the seed text ``"variant-k"`` (:func:`variant_seed`). A student ID picks its variant with
:func:`variant_index`: FNV-1a (32 bits) over the UTF-8 bytes of ``exercise_id + "\\n" + normalise_id(ID)``,
modulo the bank size. The book page's script computes the same hash (``_ext/exercise_checks/checker.js``), so
the notebook (:func:`course.exercises.load`) and the page show the same numbers for an ID.

:func:`bank` writes what the page needs to check one exercise, computed by the library at build time: per variant
the reference, the tolerance rule (stated margin, decimals asked, decimals carried), every catalogued mistake's
answer and message, and the hint. :func:`statements` gives each variant's statement as HTML with its math in
``\\( \\)`` and ``\\[ \\]``; the book build typesets them with the pages' MathJax (``tools/prerender_math.cjs``)
into one small script per variant, so the page loads only the statement of the reader's variant and no MathJax.
The page only reads the answer and compares it the way :func:`jacobians.grading.compare.compare` does
(``checker.js`` mirrors it; the browser tests check that the two agree answer by answer).

>>> variant_index("ch01_ex1", "  S2401012 ") == variant_index("ch01_ex1", "s2401012")
True
>>> fnv1a32("a")  # the published FNV-1a test vector
3826002220
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from jacobians.grading import Exercise, NumericExercise, ScalarExercise, SymbolicExercise
from jacobians.grading.catalogue import seed_value
from jacobians.grading.exercise import _eval_sym
from jacobians.grading.feedback import statement_html

from ._registry import CATALOGUE

__all__ = ["BANK_SIZE", "PAGE_KINDS", "bank", "fnv1a32", "normalise_id", "statements", "variant_index",
           "variant_seed"]

#: Variants per exercise: 32 keeps the largest bank (a 6 x 5 Jacobian with eight mistakes) near 80 KB, under the
#: 100 KB a page may load for one exercise (64 would take it to 160 KB).
BANK_SIZE = 32

#: The kinds the page checks itself (the others, code, are checked in the notebook).
PAGE_KINDS = ("numeric", "scalar", "symbolic")

#: Whitespace as JavaScript's ``\s`` reads it (ECMAScript WhiteSpace and LineTerminator), so that both sides
#: collapse the same characters.
_SPACE = re.compile("[\t\n\v\f\r \u00a0\u1680\u2000-\u200a\u2028\u2029\u202f\u205f\u3000\ufeff]+")


def normalise_id(seed: object) -> str:
    """A student ID as the variant hash reads it: the seed's text (:func:`~jacobians.grading.catalogue.seed_value`:
    ``5`` and ``"5"`` are one ID), runs of white space as one space, no space at the ends, lower case.

    >>> normalise_id("  Ab\\t 12 "), normalise_id(7)
    ('ab 12', '7')
    """
    return _SPACE.sub(" ", seed_value(seed)).strip(" ").lower()


def fnv1a32(text: str) -> int:
    """The 32-bit FNV-1a hash of the UTF-8 bytes of ``text`` (offset basis 2166136261, prime 16777619)."""
    h = 2166136261
    for b in text.encode("utf-8"):
        h = ((h ^ b) * 16777619) & 0xFFFFFFFF
    return h


def variant_index(exercise_id: str, seed: object) -> int:
    """The number of the variant (0 ... BANK_SIZE - 1) that ``seed`` (a student ID) gets of ``exercise_id``."""
    return fnv1a32(f"{exercise_id}\n{normalise_id(seed)}") % BANK_SIZE


def variant_seed(k: int) -> str:
    """The catalogue seed of variant ``k`` of every exercise."""
    return f"variant-{k}"


def _num(x: Any) -> Any:
    """A float array as nested lists of floats (JSON writes the shortest text that reads back to the same
    double); NaN and inf are not expected in a reference."""
    arr = np.asarray(x, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"Expected finite numbers in a bank, got {arr}")
    return arr.tolist()


def _variant(ex: Exercise, messages: dict[str, int]) -> dict[str, Any]:
    """One variant's data; messages (long, repeated) are numbered in ``messages``."""
    def msg(text: str) -> int:
        return messages.setdefault(text, len(messages))

    if isinstance(ex, SymbolicExercise):
        # the page evaluates the typed formula at the points the checker uses (Exercise.sample_points) and compares
        # with the reference's and each mistake's values there, as SymbolicExercise._grade does
        points = ex.sample_points()
        return {
            "symbols": sorted(points[0]),
            "wanted": sorted(str(s) for s in ex.reference.free_symbols),
            "points": points,
            "ref": [_num(_eval_sym(ex.reference, p)) for p in points],
            "mistakes": [[m.name, [_num(_eval_sym(m.value, p)) for p in points], msg(m.message)] for m in ex.mistakes],
            "hint": msg(ex.hint or ""),
            "what": ex.what,
        }
    ref = np.asarray(ex.reference, dtype=float)
    if ref.ndim > 2:
        raise ValueError(f"{ex.id}: the page reads numbers, vectors and matrices, not a reference of shape "
                         f"{ref.shape}")
    out: dict[str, Any] = {
        "ref": _num(ref),
        "mistakes": [[m.name, _num(m.value), msg(m.message)] for m in ex.mistakes],
        "hint": msg(ex.hint or ""),
        "what": ex.what,  # a variant may ask for another quantity (a body twist or a geometric velocity)
    }
    if isinstance(ex, NumericExercise):
        out.update(tol=ex.tol, decimals=ex.decimals, carry=ex.carry if ex.method is not None else None)
    elif isinstance(ex, ScalarExercise):
        iv = ex.interval
        out.update(decimals=ex.decimals, accepted=[float(a) for a in ex.accepted],
                   outside=[float(o) for o in ex.outside],
                   interval=None if iv is None else [float(iv.low), float(iv.high), iv.text])
    return out


def bank(exercise_id: str) -> dict[str, Any]:
    """The page's checking data of ``exercise_id`` (JSON-ready): kind, title, what is asked, and for a kind the
    page checks (:data:`PAGE_KINDS`), every variant's data (statements apart: :func:`statements`)."""
    messages: dict[str, int] = {}
    variants = []
    first = CATALOGUE.load(exercise_id, seed=variant_seed(0))
    for k in range(BANK_SIZE):
        ex = first if k == 0 else CATALOGUE.load(exercise_id, seed=variant_seed(k))
        if ex.kind != first.kind:
            raise ValueError(f"{exercise_id}: variants of different kinds ({first.kind}, {ex.kind})")
        if ex.kind in PAGE_KINDS:
            variants.append(_variant(ex, messages))
        else:
            variants.append({})
    return {"id": exercise_id, "kind": first.kind, "title": first.title, "what": first.what, "size": BANK_SIZE,
            "messages": [m for m, _ in sorted(messages.items(), key=lambda kv: kv[1])], "variants": variants}



def statements(exercise_id: str) -> list[str]:
    """The statement of every variant of ``exercise_id`` (variant k at index k), as the notebook's feedback box
    shows it (:func:`~jacobians.grading.feedback.statement_html`: escaped HTML, math in ``\\( \\)`` and
    ``\\[ \\]``)."""
    return [statement_html(CATALOGUE.load(exercise_id, seed=variant_seed(k)).statement) for k in range(BANK_SIZE)]
