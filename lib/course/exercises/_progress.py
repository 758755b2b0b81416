"""A student's own progress: every ``exercises.check`` of this session, and the summary of them.

:func:`record` is called by ``exercises.check`` after each verdict; it never raises
(a failure to record must not hide the verdict from the student).
:func:`summary` tells which exercises of a chapter are right, which were tried
and which are untouched; the last cell of every exercise notebook shows it.

The summary follows the grader's rule: the *last* answer to each exercise
counts (a right answer followed by a wrong one is not right), and only the
answers checked under the notebook's ID count: the ID of the latest check
of the session, unless ``seed`` names it. Checks under the placeholder ID of
the notebooks (:data:`PLACEHOLDER_SEEDS`, ``"student-id"``) are practice: an
exercise checked only under it is listed as practice, never as right.

When the notebook runs inside ``make grade`` (the environment variable
:data:`LOG_ENV` names a file), each check is also appended to that file as one
JSON line holding the answer in the safe form of :mod:`course.classroom.answer_data`;
the grader regrades those answers itself, so the verdict this session saw is
never trusted.

>>> from course.exercises import _progress
>>> _progress.reset()
>>> class FB:  # the two attributes of a Feedback that are kept
...     correct, kind = False, "wrong"
>>> _progress.record("ch01_ex1", "s1", [1, 2], FB())
>>> FB.correct, FB.kind = True, "correct"
>>> _progress.record("ch01_ex2", "s1", [1, 2], FB())
>>> s = _progress.summary(["ch01_ex1", "ch01_ex2", "ch01_ex3", "ch02_ex1"], chapter="ch01")
>>> s.right, s.tried, s.untouched
(['ch01_ex2'], ['ch01_ex1'], ['ch01_ex3'])
>>> print(s)
Your progress in ch01: 1 of 3 right, 1 tried but not right yet, 1 untouched.
  right:      ch01_ex2
  not yet:    ch01_ex1
  untouched:  ch01_ex3
(The last answer to each exercise under the ID s1 counts, as in grading.)
>>> FB.correct, FB.kind = False, "wrong"
>>> _progress.record("ch01_ex2", "s1", [9, 9], FB())  # a wrong answer after the right one: the last counts
>>> _progress.summary(["ch01_ex1", "ch01_ex2"]).right
[]
>>> _progress.reset()
"""

from __future__ import annotations

import html
import json
import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

__all__ = ["LOG_ENV", "PLACEHOLDER_SEEDS", "Attempt", "Progress", "attempts", "record", "reset", "summary"]

#: Environment variable naming the file that receives one JSON line per check (set by ``make grade``).
LOG_ENV = "JACOBIANS_PROGRESS_LOG"

#: The IDs the notebooks and the book's solutions run under until a student puts their own: checks under them
#: are practice (the variant is not the student's).
PLACEHOLDER_SEEDS = frozenset({"student-id"})


def _seed_text(seed: object) -> str:
    """A seed as the catalogue writes it (``5`` and ``"5"`` alike, spaces stripped, ``None`` as ``"0"``)."""
    if seed is None:
        return "0"
    return seed.strip() if isinstance(seed, str) else str(seed)


@dataclass(frozen=True)
class Attempt:
    """One call of ``exercises.check``: the exercise, the seed, and the verdict's ``correct`` and ``kind``."""

    exercise_id: str
    seed: object
    correct: bool
    kind: str


_SESSION: list[Attempt] = []


def record(exercise_id: object, seed: object, answer: Any, feedback: Any) -> None:
    """Keep one check of this session (and, under ``make grade``, log the answer). Never raises."""
    try:
        attempt = Attempt(str(exercise_id)[:60], seed if isinstance(seed, (int, str)) else repr(seed)[:60],
                          bool(getattr(feedback, "correct", False)), str(getattr(feedback, "kind", "wrong")))
        _SESSION.append(attempt)
        path = os.environ.get(LOG_ENV)
        if path:
            from course.classroom.answer_data import encode  # only under make grade: students never pay for it
            line = json.dumps({"exercise": attempt.exercise_id, "seed": attempt.seed, "correct": attempt.correct,
                               "kind": attempt.kind, "answer": encode(answer)})
            with open(path, "a", encoding="utf-8") as f:
                f.write(line + "\n")
    except Exception:  # pragma: no cover - recording must never hide a verdict
        pass


def attempts() -> list[Attempt]:
    """The checks of this session, oldest first."""
    return list(_SESSION)


def reset() -> None:
    """Forget this session's checks (tests; a student may also call it to start over)."""
    _SESSION.clear()


@dataclass
class Progress:
    """Which exercises are right, which were tried but are not right yet (by the last answer under ``seed``),
    which were only practised under the placeholder ID, which are untouched."""

    chapter: str
    right: list[str] = field(default_factory=list)
    tried: list[str] = field(default_factory=list)
    untouched: list[str] = field(default_factory=list)
    practice: list[str] = field(default_factory=list)
    seed: str = ""

    def _lines(self) -> list[tuple[str, list[str]]]:
        return [("right", self.right), ("not yet", self.tried), ("practice", self.practice),
                ("untouched", self.untouched)]

    def __str__(self) -> str:
        total = len(self.right) + len(self.tried) + len(self.practice) + len(self.untouched)
        where = f" in {self.chapter}" if self.chapter else ""
        if self.seed in PLACEHOLDER_SEEDS:
            head = (f"Your checks{where} ran under the placeholder ID \"{self.seed}\": they are practice, not your "
                    f"variants, and not graded ({len(self.practice)} of {total} practised). Put your student ID in "
                    "SEED (first code cell) and run the notebook again.")
        else:
            head = (f"Your progress{where}: {len(self.right)} of {total} right, {len(self.tried)} tried but not "
                    f"right yet, {len(self.untouched)} untouched.")
            if self.practice:
                head = head[:-1] + f", {len(self.practice)} practised under the placeholder ID only."
        body = [f"  {name + ':':<11} {', '.join(ids)}" for name, ids in self._lines() if ids]
        if self.seed and self.seed not in PLACEHOLDER_SEEDS:
            body.append(f"(The last answer to each exercise under the ID {self.seed} counts, as in grading.)")
        return "\n".join([head, *body])

    def __repr__(self) -> str:
        return str(self)

    def _repr_html_(self) -> str:
        colours = {"right": "#009E73", "not yet": "#D55E00", "practice": "#E69F00", "untouched": "#0072B2"}
        rows = "".join(
            f'<tr><th style="text-align:left;padding:0.2em 0.8em 0.2em 0;color:{colours[name]}">{name}</th>'
            f'<td style="padding:0.2em 0">{html.escape(", ".join(ids)) if ids else "none"}</td></tr>'
            for name, ids in self._lines() if ids or name != "practice")
        head = html.escape(str(self).splitlines()[0])
        return (f'<div class="jacobians-progress" role="status" style="border-left:6px solid #56B4E9;'
                f'background:#eef7fc;color:#1a1a1a;padding:0.6em 0.9em;margin:0.4em 0;border-radius:4px;'
                f'font-family:sans-serif"><strong>{head}</strong><table style="margin-top:0.3em">{rows}'
                f'</table></div>')


def summary(ids: Iterable[str], chapter: str | None = None, seed: object = None) -> Progress:
    """The progress over ``ids`` (those of ``chapter``, e.g. ``"ch02"``, if given), from this session's checks.

    Only checks with an answer (not ``None``) under the notebook's ID count: ``seed`` if given, else the ID
    of the session's latest such check. An exercise is *right* if its last such check was correct, *tried* if
    it has such checks and the last was not correct, *practice* if it was checked only under a placeholder ID
    (:data:`PLACEHOLDER_SEEDS`), *untouched* otherwise. Under a placeholder ID itself, every exercise checked
    is practice.
    """
    if chapter is not None and not isinstance(chapter, str):
        raise TypeError(f"Expected a chapter such as 'ch02', got {type(chapter).__name__}")
    wanted = [i for i in ids if chapter is None or i.startswith(chapter + "_")]
    if chapter is not None and not wanted:
        raise ValueError(f"Expected a chapter such as 'ch02', got {chapter!r}: it has no exercises")
    answered = [a for a in _SESSION if a.kind != "empty"]
    own = _seed_text(seed) if seed is not None else (_seed_text(answered[-1].seed) if answered else "")
    last: dict[str, Attempt] = {}
    practised: set[str] = set()
    for a in answered:
        text = _seed_text(a.seed)
        if text in PLACEHOLDER_SEEDS:
            practised.add(a.exercise_id)
        if text == own and own not in PLACEHOLDER_SEEDS:
            last[a.exercise_id] = a
    out = Progress(chapter or "", seed=own)
    for i in wanted:
        if i in last:
            (out.right if last[i].correct else out.tried).append(i)
        else:
            (out.practice if i in practised else out.untouched).append(i)
    return out
