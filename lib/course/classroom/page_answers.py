"""Answers saved from the book's exercise pages ("Save my answers"), graded beside the notebooks.

The page writes one JSON file per reader, ``answers-<id>.json``::

    {"format": "jacobians-course-answers", "version": 1, "id": "s2401012", "saved": "...",
     "answers": {"ch01_ex1": {"text": "0, 0, 1, ...", "value": {"shape": [6], "data": [0, 0, 1, ...]},
                 "variant": 12}, ...}}

A file is data from a student, so it is read with bounds: at most :data:`MAX_BYTES`, JSON only (no
evaluation of the typed text), an ID of at most 200 characters, at most :data:`MAX_ANSWERS` answers, each a
known exercise id with a value of at most two indices and :data:`~jacobians.grading.answers.MAX_ENTRIES`
finite-or-NaN numbers whose count matches its shape; for a formula (``{"shape", "formulas"}``), each formula is
read from Python's parse tree node by node (numbers, symbols, + - * / **, a few functions: :func:`_formula`),
never evaluated. Nothing the file claims is trusted: no verdict is read,
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

from jacobians.grading import SymbolicExercise
from jacobians.grading.answers import MAX_ENTRIES

__all__ = ["FORMAT", "MAX_ANSWERS", "MAX_BYTES", "Mark", "find_answer_files", "read_answers_file",
           "read_answers_text"]

#: The ``format`` of a file the page saves.
FORMAT = "jacobians-course-answers"
#: Biggest answers file read, in bytes (about 50 exercises of 36 numbers need about 40 KB).
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


#: Longest formula read from an answers file, in characters.
MAX_FORMULA = 2000
#: The functions a saved formula may call (those the page's math.js reads), as sympy names.
_FUNCTIONS = {"sin": "sin", "cos": "cos", "tan": "tan", "asin": "asin", "acos": "acos", "atan": "atan",
              "atan2": "atan2", "sqrt": "sqrt", "exp": "exp", "log": "log", "abs": "Abs"}
#: Largest exponent written in a saved formula (a formula of the course needs squares; 9**9**9 is refused).
_MAX_POWER = 64


def _formula(text: Any, symbols: dict[str, Any]) -> Any:
    """A saved formula (math.js's printing of what the reader typed) as a sympy expression, built node by node from
    Python's own parse tree with only numbers, the exercise's symbols (other names become symbols the checker
    then names as unknown), + - * / **, and the functions of :data:`_FUNCTIONS`; a text saying what is wrong
    otherwise. Nothing is evaluated."""
    import ast

    import sympy as sp
    if not isinstance(text, str) or len(text) > MAX_FORMULA:
        return "has a formula that is not text of at most 2000 characters"
    consts = {"pi": sp.pi, "e": sp.E, "E": sp.E, "NaN": sp.nan, "nan": sp.nan, "Infinity": sp.oo, "inf": sp.oo}
    binary = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
              ast.Div: lambda a, b: a / b}

    def conv(node: ast.AST, depth: int) -> Any:
        if depth > 200:
            raise ValueError("nested too deeply")
        if isinstance(node, ast.Constant) and type(node.value) in (int, float):
            return sp.Integer(node.value) if isinstance(node.value, int) else sp.Float(node.value)
        if isinstance(node, ast.Name):
            if node.id in consts:
                return consts[node.id]
            return symbols[node.id] if node.id in symbols else sp.Symbol(node.id)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            x = conv(node.operand, depth + 1)
            return -x if isinstance(node.op, ast.USub) else x
        if isinstance(node, ast.BinOp) and type(node.op) in binary:
            return binary[type(node.op)](conv(node.left, depth + 1), conv(node.right, depth + 1))
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
            base, power = conv(node.left, depth + 1), conv(node.right, depth + 1)
            if not (power.is_number and power.is_finite and abs(float(power)) <= _MAX_POWER):
                raise ValueError("an exponent that is not a number of at most 64")
            return base ** power
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in _FUNCTIONS
                and not node.keywords and 1 <= len(node.args) <= 2):
            return getattr(sp, _FUNCTIONS[node.func.id])(*(conv(a, depth + 1) for a in node.args))
        raise ValueError(f"{type(node).__name__}")

    try:
        tree = ast.parse(text.replace("^", "**"), mode="eval")
        return conv(tree.body, 0)
    except (SyntaxError, ValueError, TypeError, RecursionError, MemoryError, OverflowError):
        return "has a formula that is not one the page reads"


def _formulas(entry: Any, symbols: dict[str, Any]) -> Any:
    """The formulas of one saved symbolic answer (``{"shape", "formulas"}``) as the notebook would give them: a
    sympy Matrix, a list of expressions or one expression (None for no value); a text saying what is wrong."""
    import sympy as sp
    if not isinstance(entry, dict) or not isinstance(entry.get("value"), dict):
        return None if isinstance(entry, dict) and entry.get("value") is None else "is not an answer record"
    shape, formulas = entry["value"].get("shape"), entry["value"].get("formulas")
    if not (isinstance(shape, list) and len(shape) <= 2 and all(isinstance(n, int) and not isinstance(n, bool)
                                                                 and 0 < n <= 100 for n in shape)):
        return "has a shape that is not a list of at most two whole numbers up to 100"
    size = math.prod(shape)
    if not isinstance(formulas, list) or len(formulas) != size:
        return f"has {len(formulas) if isinstance(formulas, list) else 'no list of'} formulas for the shape {shape}"
    exprs = []
    for f in formulas:
        x = _formula(f, symbols)
        if isinstance(x, str):
            return x
        exprs.append(x)
    if not shape:
        return exprs[0]
    if len(shape) == 1:
        return exprs
    return sp.Matrix(shape[0], shape[1], exprs)


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
        ex = exercises.load(eid, seed=sid)
        value = (_formulas(entry, {str(x): x for x in ex.symbols.values()}) if isinstance(ex, SymbolicExercise)
                 else _value(entry))
        if isinstance(value, str):
            marks.append(Mark(eid, "0", f"The saved answer {value}: it cannot be graded."))
            continue
        fb = ex.check(value)
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
