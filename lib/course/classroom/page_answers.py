"""Answers saved from the book's exercise pages ("Save my answers"), graded beside the notebooks.

The page writes one JSON file per reader, ``answers-<id>.json``::

    {"format": "jacobians-course-answers", "version": 1, "id": "s2401012", "saved": "...",
     "answers": {"ch01_ex1": {"text": "0, 0, 1, ...", "value": {"shape": [6], "data": [0, 0, 1, ...]},
                 "variant": 12}, ...}}

A file is data from a student, so it is read with bounds: at most :data:`MAX_BYTES`, JSON only (no
evaluation of the typed text), an ID of at most 200 characters, at most :data:`MAX_ANSWERS` answers, each a
known exercise id with a value of at most two indices and :data:`~jacobians.grading.answers.MAX_ENTRIES`
finite-or-NaN numbers whose count matches its shape. Nothing the file claims is trusted: no verdict is read,
the variant is the one of the ID (``exercises.load``), and every answer is regraded with the course's checker
(:func:`course.exercises.check` without the session's log: ``Exercise.check``). Each problem gets a row that
says what is wrong; a file never stops the grading of the class.

The grader (:func:`course.classroom.grade.grade_class`) turns the marks into gradebook rows. When the same
student also hands in a notebook, one answer counts per exercise (:func:`course.classroom.grade.one_answer_each`:
the notebook's where it checked the exercise, else the page's); the other is listed, not counted.

>>> sid, marks = read_answers_text(b'{"format": "jacobians-course-answers", "version": 1, "id": "s1", "answers": {}}')
>>> sid, [m.message for m in marks]
('s1', ['holds no answer'])
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, NamedTuple

from jacobians.grading.answers import MAX_ENTRIES

__all__ = ["FORMAT", "MAX_ANSWERS", "MAX_BYTES", "Mark", "find_answer_files", "read_answers_file",
           "read_answers_text"]

#: The ``format`` of a file the page saves.
FORMAT = "jacobians-course-answers"
#: Biggest answers file read, in bytes (51 exercises of 36 numbers need about 40 KB).
MAX_BYTES = 4 << 20
#: Most answers read from one file.
MAX_ANSWERS = 200


class Mark(NamedTuple):
    """One verdict of an answers file: ``exercise`` is ``""`` for a note about the whole file; ``correct`` is
    ``"1"``, ``"0"`` or ``""`` (a note), as in the gradebook."""

    exercise: str
    correct: str
    message: str
    mistake: str = ""


def find_answer_files(root: Path) -> list[Path]:
    """Every ``answers*.json`` under ``root`` (folders starting with a dot skipped)."""
    return sorted(p for p in Path(root).rglob("answers*.json")
                  if p.is_file() and not any(part.startswith(".") for part in p.relative_to(root).parts))


def _value(entry: Any) -> list[Any] | float | None | str:
    """The numbers of one saved answer as a nested list (or a float, or None for no value); a text saying what is
    wrong if they cannot be graded."""
    if not isinstance(entry, dict):
        return "is not an answer record"
    value = entry.get("value")
    if value is None:
        return None
    if not isinstance(value, dict):
        return "has a value that is not {shape, data}"
    shape, data = value.get("shape"), value.get("data")
    if not (isinstance(shape, list) and len(shape) <= 2 and all(isinstance(n, int) and not isinstance(n, bool)
                                                                 and 0 < n <= MAX_ENTRIES for n in shape)):
        return "has a shape that is not a list of at most two positive whole numbers"
    size = math.prod(shape)
    if not isinstance(data, list) or len(data) != size or size > MAX_ENTRIES:
        return f"has {len(data) if isinstance(data, list) else 'no list of'} numbers for the shape {shape}"
    nums: list[float] = []
    for x in data:
        if x is None:  # JSON's stand-in for NaN (JSON.stringify writes NaN as null)
            nums.append(math.nan)
        elif isinstance(x, (int, float)) and not isinstance(x, bool):
            nums.append(float(x))
        else:
            return "has an entry that is not a number"
    if not shape:
        return nums[0]
    if len(shape) == 1:
        return nums
    return [nums[i * shape[1]:(i + 1) * shape[1]] for i in range(shape[0])]


def read_answers_text(raw: bytes) -> tuple[str | None, list[Mark]]:
    """The student ID of one answers file's bytes (None if it has none) and its marks."""
    from course import exercises

    def note(message: str) -> Mark:
        return Mark("", "", message)

    if len(raw) > MAX_BYTES:
        return None, [note(f"is an answers file of {len(raw) >> 10} KB, more than the {MAX_BYTES >> 10} KB one may "
                           "have; not graded")]
    try:
        data = json.loads(raw)
    except (ValueError, RecursionError, UnicodeDecodeError):
        return None, [note("is not an answers file saved by the book's exercise pages (not valid JSON); not graded")]
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        return None, [note(f"is not an answers file saved by the book's exercise pages (no format {FORMAT!r}); "
                           "not graded")]
    sid = data.get("id")
    if not isinstance(sid, str) or not sid.strip() or len(sid) > 200:
        return None, [note("has no student ID (the page saves it when an ID is set); not graded")]
    answers = data.get("answers")
    if not isinstance(answers, dict):
        return sid, [note("has no answers object; not graded")]
    if not answers:
        return sid, [note("holds no answer")]
    if len(answers) > MAX_ANSWERS:
        return sid, [note(f"holds {len(answers)} answers, more than the {MAX_ANSWERS} read; not graded")]
    known = set(exercises.exercise_ids())
    marks: list[Mark] = []
    for eid, entry in answers.items():
        if eid not in known:
            marks.append(note(f"answers an unknown exercise {str(eid)[:40]!r}; that answer is ignored"))
            continue
        value = _value(entry)
        if isinstance(value, str):
            marks.append(Mark(eid, "0", f"The saved answer {value}: it cannot be graded."))
            continue
        fb = exercises.load(eid, seed=sid).check(value)
        marks.append(Mark(eid, "1" if fb.correct else "0", fb.message[:400], fb.mistake or ""))
    return sid, marks


def read_answers_file(path: Path) -> tuple[str | None, list[Mark]]:
    """The student ID and marks of one answers file (see the module docstring); never raises for a bad file."""
    try:
        with open(path, "rb") as f:
            raw = f.read(MAX_BYTES + 1)
    except OSError as exc:
        return None, [Mark("", "", f"could not be read ({exc.strerror}); not graded")]
    try:
        return read_answers_text(raw)
    except Exception as exc:  # a grader bug: say so in the gradebook, keep going
        return None, [Mark("", "", f"the grader failed on this answers file ({type(exc).__name__}); please report it")]
