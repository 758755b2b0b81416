"""How a verdict is shown: :class:`Feedback`, as text and as a coloured HTML box.

>>> fb = verdict(False, "Check column 2.", mistake="sign_column_2")
>>> fb.exercise_id = "ch02_ex1"
>>> str(fb)
'[ch02_ex1] Not yet: Check column 2.'
>>> bool(fb), fb.kind, fb.mistake
(False, 'wrong', 'sign_column_2')
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass

__all__ = ["Feedback", "agrees", "statement_html", "verdict"]

#: Heading of the text form, by kind.
_HEADS = {"correct": "Correct", "empty": "No answer yet", "invalid": "Cannot grade this"}

#: Border colour, background and heading of the HTML box, by kind (Okabe-Ito colours).
_BOXES = {
    "correct": ("#009E73", "#e6f5f0", "&#10004; Correct"),
    "wrong": ("#D55E00", "#fbece3", "&#10008; Not yet"),
    "empty": ("#0072B2", "#e6f0f8", "&#8230; No answer yet"),
    "invalid": ("#E69F00", "#fdf4e3", "? Cannot grade this"),
}


_DISPLAY = re.compile(r"\$\$(.+?)\$\$", re.S)
_INLINE = re.compile(r"\$(.+?)\$", re.S)
_CODE = re.compile(r"`([^`]+)`")


def statement_html(markdown: str) -> str:
    r"""A statement (Markdown with ``$...$`` math) as HTML for the feedback box: escaped, math in the
    ``\( \)`` and ``\[ \]`` delimiters MathJax reads in an HTML output (in Jupyter, and on the book page,
    whose outputs MathJax only processes inside a ``mathjax_process`` element), code in ``<code>``.

    >>> print(statement_html("Give $x < 1$ in `ans`."))
    Give \(x &lt; 1\) in <code>ans</code>.
    """
    text = html.escape(markdown, quote=False)
    text = _DISPLAY.sub(lambda m: "\\[" + m.group(1) + "\\]", text)
    text = _INLINE.sub(lambda m: "\\(" + m.group(1) + "\\)", text)
    text = _CODE.sub(lambda m: "<code>" + m.group(1) + "</code>", text)
    return text.replace("\n\n", "<br>")


@dataclass
class Feedback:
    """The checker's verdict: ``.correct`` (bool), ``.message`` (str), ``.kind``.

    ``kind`` is one of ``"correct"``, ``"wrong"`` (a gradable but wrong
    answer), ``"empty"`` (no answer yet), ``"invalid"`` (not something the
    checker can grade, such as text), and ``mistake`` names the catalogued
    mistake that was recognised (``None`` if none).

    The catalogue also fills in which variant was graded: ``seed`` (the
    student's seed as text, e.g. their ID), ``title`` and ``statement`` (the
    Markdown statement of that variant, shown folded in the HTML box).
    """

    correct: bool
    message: str
    kind: str = "wrong"
    exercise_id: str = ""
    mistake: str | None = None
    seed: str = ""
    title: str = ""
    statement: str = ""

    def __bool__(self) -> bool:
        return self.correct

    def __str__(self) -> str:
        head = "Correct" if self.correct else _HEADS.get(self.kind, "Not yet")
        tag = f"[{self.exercise_id}] " if self.exercise_id else ""
        return f"{tag}{head}: {self.message}"

    def __repr__(self) -> str:
        return str(self)

    def _repr_html_(self) -> str:
        border, bg, head = _BOXES.get(self.kind, _BOXES["wrong"])
        msg = html.escape(self.message).replace("\n", "<br>")
        ident = html.escape(self.exercise_id)
        variant = ""
        if self.statement:
            who = f" for seed “{html.escape(self.seed)}”" if self.seed else ""
            variant = (f'<details style="margin-top:0.4em"><summary>The exercise you answered{who}</summary>'
                       f'<div class="jacobians-feedback-statement mathjax_process" style="overflow-x:auto">'
                       f'{statement_html(self.statement)}</div></details>')
        return (
            f'<div class="jacobians-feedback jacobians-feedback-{self.kind}" role="status" '
            f'style="border-left:6px solid {border};background:{bg};color:#1a1a1a;'
            f'padding:0.6em 0.9em;margin:0.4em 0;border-radius:4px;font-family:sans-serif">'
            f'<strong>{head}</strong> <span style="color:#555">({ident})</span><br>{msg}{variant}</div>'
        )


def agrees(what: str, singular: str, plural: str) -> str:
    """The verb that agrees with ``what``: ``plural`` for a plural noun phrase ("joint values", "semi-axes"),
    ``singular`` otherwise ("torque vector", "manipulability", "matrix of body screw axes").

    >>> agrees("joint values", "matches", "match"), agrees("error twist", "is", "are")
    ('match', 'is')
    """
    head = what.split(" of ")[0].split()  # "matrix of body screw axes" agrees with "matrix"
    last = head[-1] if head else what
    return plural if last.endswith("s") and not last.endswith(("ss", "is", "us")) else singular


def verdict(ok: bool, message: str, kind: str | None = None, mistake: str | None = None) -> Feedback:
    """A :class:`Feedback` whose kind defaults to ``"correct"`` or ``"wrong"`` from ``ok``."""
    return Feedback(bool(ok), message, kind or ("correct" if ok else "wrong"), mistake=mistake)
