"""``make grade SUBMISSIONS=<dir>``: find every student notebook, run each sandboxed, regrade, write the gradebook.

For each ``*.ipynb`` under the folder (any layout; folders starting with ``.``
are skipped):

1. read it as JSON (never executing anything in the grader); take the student
   ID from the set-up cell's ``SEED = "..."`` line with :mod:`ast`, and the
   exercises from its ``exercises.load("chNN_exK", ...)`` cells;
2. copy it into a scratch folder and execute it there in a bubblewrap sandbox of its own
   (:mod:`~course.classroom.sandbox`: a uid, namespaces and a cgroup of its own), its cells run by IPython's
   shell in a fork of a warm worker (:mod:`~course.classroom._zygote`) that enters the sandbox, with a time
   limit per cell and per notebook; every ``exercises.check`` logs its answer as data
   (:mod:`~course.classroom.answer_data`);
3. regrade the last answer to each exercise here, with the course's reference
   for the student's ID (a function answer is called in a sandboxed process);
   the verdict the notebook showed is never used, only compared;
4. write ``gradebook.csv`` (student, notebook, exercise, seed, correct,
   message) and ``reports/<student>.html``.

A notebook that cannot be read, is empty, raises, runs over its time or tries
to write outside its scratch folder gets rows saying so (exercise
``(notebook)``) and the run goes on. The submissions are hashed before and
after; a change is reported as a row. Notebooks are graded in a process pool.
"""

from __future__ import annotations

import ast
import contextlib
import csv
import hashlib
import io
import json
import os
import re
import signal
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import astuple, dataclass, replace
from functools import cache
from pathlib import Path
from typing import Any

from .page_answers import find_answer_files, read_answers_file  # answers saved from the exercise pages
from .sandbox import (
    EVENTS,
    Limits,
    SandboxedFunction,
    isolation,
    kill_tree,
    limits_hit,
    make_scratch,
    remove_scratch,
    sandbox_home,
    scratch_owner,
    start,
    start_warm,
    stop_warm,
    unsafe_allowed,
)

__all__ = ["COLUMNS", "NOTEBOOK", "Row", "exercises_of", "grade_class", "grade_notebook", "main", "student_id"]

#: The columns of gradebook.csv (``tests``: for a code exercise with partial credit, tests passed/tests run).
COLUMNS = ("student", "notebook", "exercise", "seed", "correct", "message", "mistake", "tests")
#: The ``exercise`` of a row about the whole notebook (it could not be read, a cell raised, ...).
NOTEBOOK = "(notebook)"
#: The ``exercise`` of a row about the roster (an ID not on it, a student on it without a notebook).
ROSTER = "(roster)"
#: Start of every message when the class was graded without isolation (``UNSAFE=1``).
UNSAFE_NOTE = "[UNSAFE: graded without isolation] "
#: Most bytes of a notebook's answer log read, and longest line decoded (an answer of 200 000 numbers fits).
MAX_LOG = 64 << 20
MAX_LOG_LINE = 8 << 20
#: CPU seconds the grader may spend regrading one answer (decoding it and running the course's checker);
#: a second line behind the bounds of :mod:`~course.classroom.answer_data`.
CHECK_CPU = 60.0
#: Biggest notebook read, in bytes.
MAX_BYTES = 50 << 20

_LOAD = re.compile(r"""exercises\.load\(\s*["'](ch\d\d_ex\d+)["']""")
_LOG = "checks.jsonl"


class Refused(RuntimeError):
    """Isolation is impossible here and ``UNSAFE=1`` was not given: nothing was graded."""


@dataclass(frozen=True)
class Row:
    """One line of the gradebook. ``correct`` is ``"1"``, ``"0"`` or ``""`` (a row about the notebook);
    ``mistake`` the name of the catalogued mistake the checker recognised in a wrong answer, if any; ``tests``
    the tests of a code exercise its function passed, as ``"passed/run"`` (only for the exercises given
    partial credit in ``points.toml``)."""

    student: str
    notebook: str
    exercise: str
    seed: str
    correct: str
    message: str
    mistake: str = ""
    tests: str = ""


# --------------------------------------------------------------------------- reading a notebook (no execution)
def _code_sources(nb: Any) -> list[str]:
    cells = nb.get("cells") if isinstance(nb, dict) else None
    if not isinstance(cells, list):
        raise ValueError("it has no list of cells")
    out = []
    for c in cells:
        if isinstance(c, dict) and c.get("cell_type") == "code":
            src = c.get("source", "")
            src = "".join(src) if isinstance(src, list) else src
            if not isinstance(src, str):
                raise ValueError("a cell's source is not text")
            out.append(src)
    return out


def _parse(src: str) -> ast.Module | None:
    """The cell as Python, IPython's ``%magic`` and ``!shell`` lines blanked; None if it is not Python."""
    lines = ["" if ln.lstrip().startswith(("%", "!")) else ln for ln in src.splitlines()]
    try:
        return ast.parse("\n".join(lines))
    except (SyntaxError, ValueError):
        return None


def student_id(sources: Iterable[str]) -> str | int | None:
    """The student ID a notebook sets: the value of the first top-level ``SEED = ...`` assignment.

    Accepted forms (read with :mod:`ast`, never evaluated): ``SEED = "text"``,
    ``SEED = 12``, and ``SEED = int(os.environ.get("JACOBIANS_SEED", "12"))``
    (the default given there). Anything else gives None.

    >>> student_id(['import os', 'SEED = "s1234567"  # your student ID'])
    's1234567'
    >>> student_id(['SEED = int(os.environ.get("JACOBIANS_SEED", "7"))'])
    7
    >>> student_id(['SEED = input()']) is None
    True
    """
    for src in sources:
        tree = _parse(src)
        if tree is None:
            continue
        for node in tree.body:
            if not (isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "SEED"
                                                          for t in node.targets)):
                continue
            value = node.value
            if isinstance(value, ast.Constant) and isinstance(value.value, (str, int)) \
                    and not isinstance(value.value, bool):
                return value.value
            if (isinstance(value, ast.Call) and isinstance(value.func, ast.Name) and value.func.id == "int"
                    and len(value.args) == 1 and isinstance(value.args[0], ast.Call)
                    and len(value.args[0].args) == 2 and isinstance(value.args[0].args[1], ast.Constant)):
                default = value.args[0].args[1].value
                try:
                    return int(default) if isinstance(default, (str, int)) else None
                except ValueError:
                    return None
            return None
    return None


#: IDs that students leave from the template (after :func:`normalise_id`).
PLACEHOLDERS = frozenset({"student-id", "your-id", "your id", "id", ""})


def normalise_id(sid: str | int) -> str:
    """The gradebook's form of a student ID: surrounding whitespace removed, inner runs of whitespace made one
    space, letters lower-cased (``casefold``). The variant is still the one of the ID as the notebook wrote it.

    >>> normalise_id("  S2401012 "), normalise_id("s2401012"), normalise_id(7)
    ('s2401012', 's2401012', '7')
    """
    return " ".join(str(sid).split()).casefold()


def is_placeholder(sid: str | int) -> bool:
    """Whether ``sid`` is the template's placeholder (e.g. ``"student-id"``), not a student's ID."""
    return normalise_id(sid) in PLACEHOLDERS


def student_key(sid: str | int, notebook: str) -> str:
    """The gradebook's ``student`` of a notebook: the normalised ID, or for a placeholder ID a name of its
    own made from the notebook's path (two students who both left ``"student-id"`` are never merged).

    >>> student_key("student-id", "a/ch02.ipynb")
    '(placeholder ID student-id) a/ch02.ipynb'
    """
    if is_placeholder(sid):
        return f"(placeholder ID {normalise_id(sid) or 'empty'}) {notebook}"
    return normalise_id(sid)


def exercises_of(sources: Iterable[str]) -> list[str]:
    """The exercise ids a notebook loads, in order of first appearance."""
    seen: list[str] = []
    for src in sources:
        for eid in _LOAD.findall(src):
            if eid not in seen:
                seen.append(eid)
    return seen


def _calls_solution(sources: Iterable[str]) -> bool:
    for src in sources:
        tree = _parse(src)
        if tree is not None and any(isinstance(n, ast.Attribute) and n.attr == "solution" for n in ast.walk(tree)):
            return True
    return False


# --------------------------------------------------------------------------- one notebook
def grade_notebook(path: Path, root: Path, limits: Limits, scratch_parent: Path) -> list[Row]:
    """The gradebook rows of one notebook (see the module docstring). Never raises for a bad notebook."""
    rel = str(path.relative_to(root))

    def note(message: str, student: str = "", seed: str = "") -> Row:
        return Row(student, rel, NOTEBOOK, seed, "", message)

    try:
        raw = path.read_bytes()
    except OSError as exc:
        return [note(f"could not be read ({exc.strerror}); nothing was run")]
    if len(raw) > MAX_BYTES:
        return [note(f"is {len(raw) >> 20} MB, more than the {MAX_BYTES >> 20} MB a notebook may have; "
                     "nothing was run")]
    if not raw.strip():
        return [note("is an empty file; nothing was run")]
    try:
        nb = json.loads(raw)
        sources = _code_sources(nb)
    except (ValueError, RecursionError) as exc:
        where = f" (line {exc.lineno}, column {exc.colno})" if isinstance(exc, json.JSONDecodeError) else ""
        return [note(f"is not a valid notebook: not valid JSON{where}; nothing was run"
                     if isinstance(exc, json.JSONDecodeError) else f"is not a valid notebook: {exc}; nothing was run")]
    if not any(s.strip() for s in sources):
        return [note("is empty: it has no code; nothing was run")]
    sid = student_id(sources)
    if sid is None:
        return [note('has no student ID: the set-up cell must set SEED = "your ID" (a plain string); '
                     "nothing was run")]
    student, seed = student_key(sid, rel), str(sid)
    wanted = exercises_of(sources)
    rows: list[Row] = []
    if is_placeholder(sid):
        rows.append(note(f'keeps the placeholder ID {str(sid)!r} in SEED = "..." (the student did not put their '
                         "own ID there): graded for that ID and listed on its own, never merged with others",
                         student, seed))
    if not wanted:
        rows.append(note("loads no exercise (no exercises.load cell)", student, seed))
    if _calls_solution(sources):
        rows.append(note("calls .solution() somewhere: that is the reference answer, not the student's work",
                         student, seed))
    scratch = make_scratch(scratch_parent)
    try:
        rows += _run_and_regrade(path, raw, nb, sid, wanted, scratch, limits, rel)
    finally:
        remove_scratch(scratch)
    try:
        if hashlib.sha256(path.read_bytes()).digest() != hashlib.sha256(raw).digest():
            rows.append(note("the submitted file changed while it was graded", student, seed))
    except OSError:
        rows.append(note("the submitted file disappeared while it was graded", student, seed))
    return rows


def _run_and_regrade(path: Path, raw: bytes, nb: Any, sid: str | int, wanted: list[str], scratch: Path,
                     limits: Limits, rel: str) -> list[Row]:
    student, seed = student_key(sid, rel), str(sid)
    rows: list[Row] = []

    def note(message: str) -> None:
        rows.append(Row(student, rel, "(notebook)", seed, "", message))

    code_cells: list[dict[str, Any]] = [
        {"cell_type": "code", "source": s, "metadata": {}, "outputs": [], "execution_count": None}
        for s in _code_sources(nb)]
    clean = {"nbformat": 4, "nbformat_minor": 5, "metadata": {"kernelspec": {"name": "python3",
             "display_name": "Python 3", "language": "python"}}, "cells": code_cells}
    (scratch / "submission.ipynb").write_text(json.dumps(clean), encoding="utf-8")
    uid = scratch_owner(scratch)
    if uid is not None:
        os.chown(scratch / "submission.ipynb", uid, uid)
    log = scratch / _LOG
    env = {"JACOBIANS_PROGRESS_LOG": sandbox_home(scratch) + "/" + _LOG}
    if isinstance(sid, int):
        env["JACOBIANS_SEED"] = str(sid)  # the set-up cell of older notebooks reads it
    if _ENGINE["name"] == "kernel":  # the previous design, kept for make bench's comparison only
        proc: Any = start([sys.executable, "-P", "-m", "course.classroom._runner", "submission.ipynb",
                           "result.json", str(limits.cell_timeout)], scratch, limits,
                          cpu_seconds=limits.notebook_timeout, env=env)
    else:
        proc = start_warm("cells", ["submission.ipynb", "result.json", str(limits.cell_timeout)], scratch, limits,
                          cpu_seconds=limits.notebook_timeout, env=env)
    t0 = time.monotonic()
    try:
        proc.wait(timeout=limits.notebook_timeout)
        finished = True
    except Exception:
        finished = False
    hit = limits_hit(proc)
    kill_tree(proc)  # every process of the sandbox, however it was started
    if "memory" in hit:
        note(f"used all the memory a notebook may use ({limits.memory >> 20} MB); a process was stopped")
    if "processes" in hit:
        note(f"tried to run more than {limits.processes} processes and threads at once; it was not allowed to")
    if not finished:
        note(f"did not finish within {limits.notebook_timeout:g} s and was stopped; the checks made before "
             "count")
    result = _read_json(scratch / "result.json")
    if finished and result is None:
        note("could not be executed (the runner stopped after "
             f"{time.monotonic() - t0:.0f} s without a result; is the notebook a Python 3 notebook?)")
    if isinstance(result, dict):
        for n in result.get("timeouts", [])[:5]:
            note(f"code cell {n} was stopped after {limits.cell_timeout:g} s (an endless loop?)")
        for e in result.get("errors", [])[:5]:
            if str(e.get("evalue", "")).startswith("[grading sandbox]"):
                continue  # said once below, from the event log
            note(f"code cell {e.get('cell')} raised {e.get('ename')}: {e.get('evalue')}"[:400])
        if result.get("status", "ok") != "ok":
            note(f"the kernel stopped: {result.get('status')}"[:400])
        strays = [str(x)[:100] for x in result.get("strays", [])][:5]
        if strays:
            note(f"left {len(strays)} process(es) running after its last cell ({'; '.join(strays)}); they were "
                 "killed with its sandbox"[:400])
        left = [str(x)[:100] for x in result.get("left_files", [])][:5]
        if left:
            note(f"wrote files outside its folder ({', '.join(left)}); they were in the sandbox's own memory and "
                 "are gone"[:400])
    events = _read_lines(scratch / EVENTS, 5)
    for ev in events:
        note("tried something outside its scratch folder, which was refused: " + ev.removeprefix(
            "[grading sandbox] ")[:300])
    checks = _last_checks(log, set(wanted))
    from course import exercises  # the course's own reference (imported once per worker)

    for eid in wanted:
        entry = checks.get(eid)
        if entry is None:
            rows.append(Row(student, rel, eid, seed, "0", NOT_ATTEMPTED))
            continue
        correct, message, mistake, tests = _regrade(exercises, eid, entry, sid, scratch, limits)
        rows.append(Row(student, rel, eid, seed, correct, message, mistake, tests))
    return rows


def _read_json(path: Path) -> Any:
    try:
        if path.stat().st_size > 1 << 20:
            return None
        return json.loads(path.read_bytes())
    except (OSError, ValueError):
        return None


def _read_lines(path: Path, most: int) -> list[str]:
    try:
        with open(path, "rb") as f:
            text = f.read(1 << 16).decode("utf-8", "replace")
    except OSError:
        return []
    out: list[str] = []
    for ln in text.splitlines():
        if ln.strip() and ln not in out:
            out.append(ln.strip())
    return out[:most]


def _last_checks(log: Path, wanted: set[str]) -> dict[str, dict[str, Any]]:
    """The last logged check of each wanted exercise (the log is the student's data: read with limits:
    :data:`MAX_LOG` bytes in all, lines of at most :data:`MAX_LOG_LINE` bytes)."""
    out: dict[str, dict[str, Any]] = {}
    try:
        with open(log, "rb") as f:
            data = f.read(MAX_LOG)
    except OSError:
        return out
    for line in data.splitlines():
        if len(line) > MAX_LOG_LINE:
            continue
        try:
            entry = json.loads(line)
        except (ValueError, RecursionError):
            continue
        if isinstance(entry, dict) and entry.get("exercise") in wanted and isinstance(entry.get("answer"), dict):
            out[entry["exercise"]] = entry
    return out


def _regrade(exercises: Any, eid: str, entry: dict[str, Any], sid: str | int, scratch: Path,
             limits: Limits) -> tuple[str, str, str, str]:
    from .answer_data import CodeAnswer, Opaque, decode

    extra = ""
    proxy = None
    tests = ""
    try:
        with _cpu_limit(CHECK_CPU):
            answer = decode(entry["answer"])
            if isinstance(answer, Opaque):
                what = ("is too large to grade (a number of more than 4096 bits or an exponent above 64); it "
                        "was not decoded" if answer.type_name == "too large" else
                        f"could not be collected as data (an object of type {answer.type_name})")
                return "0", f"invalid: the answer {what}", "", ""
            if isinstance(answer, CodeAnswer):
                if answer.library:
                    extra += (f" (The answer is the library function {'.'.join(answer.library)}, not the "
                              "notebook's code.)")
                proxy = SandboxedFunction(answer, scratch, limits, seed=sid, warm=_ENGINE["name"] == "warm")
                answer = proxy
            fb = exercises.check(eid, answer, seed=sid)
            if proxy is not None and eid in partial_credit():
                ex = exercises.load(eid, seed=sid)
                if fb.correct:
                    passed, run = len(ex.cases()), len(ex.cases())
                else:
                    def fresh() -> SandboxedFunction:
                        return SandboxedFunction(proxy.answer, scratch, limits, seed=sid,
                                                 warm=_ENGINE["name"] == "warm")
                    passed, run = count_passed_tests(ex, proxy, fresh)
                tests = f"{passed}/{run}"
                extra += (f" (Partial credit: your function passed {passed} of the {run} tests, so it earns "
                          f"{passed}/{run} of the exercise's points.)" if not fb.correct else "")
    except _OverTime:
        return "0", f"not graded: checking this answer took more than {CHECK_CPU:g} s of the grader's time", "", ""
    finally:
        if proxy is not None:
            proxy.close()
    if entry.get("correct") is True and not fb.correct:
        extra += " (The notebook's own check said correct; the course's reference does not accept this answer.)"
    if entry.get("seed") != sid:
        extra += f" (Checked in the notebook with seed {str(entry.get('seed'))[:40]!r}; graded for the ID's variant.)"
    kind = "" if fb.correct else "not attempted: " if fb.kind == "empty" else f"{fb.kind}: "
    return (("1" if fb.correct else "0"), (kind + str(fb.message) + extra).replace("\n", " "),
            str(fb.mistake or "")[:80], tests)


def count_passed_tests(ex: Any, fn: Any, fresh: Callable[[], Any] | None = None) -> tuple[int, int]:
    """How many of the test cases of the code exercise ``ex`` the function ``fn`` passes, and how many were
    run. Each test is judged by the exercise's own checker on that test alone (an exercise whose test list is
    that one test), so a test passes here exactly when the checker would accept it. A function whose
    sandbox stopped (it ran over its time, or crashed) is started again with ``fresh()`` for the next test."""
    import copy

    cases = ex.cases()
    passed = 0
    for case in cases:
        one = copy.copy(ex)
        one.cases = lambda case=case: [case]
        passed += bool(one.check(fn).correct)
        if fresh is not None and getattr(fn, "_proc", True) is None:  # the sandbox was stopped: a new one
            fn.close()
            fn = fresh()
    if fresh is not None:
        fn.close()
    return passed, len(cases)


class _OverTime(Exception):
    pass


@contextlib.contextmanager
def _cpu_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`_OverTime` in the block once this process has spent ``seconds`` of CPU in it (the
    profiling timer, SIGPROF: the checker's own guard uses the real-time one). Main thread only."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def over(signum: int, frame: Any) -> None:
        raise _OverTime()

    old = signal.signal(signal.SIGPROF, over)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, old)


# --------------------------------------------------------------------------- a class
def find_notebooks(root: Path) -> list[Path]:
    """Every ``.ipynb`` under ``root``, skipping folders whose name starts with a dot."""
    return sorted(p for p in root.rglob("*.ipynb")
                  if p.is_file() and not any(part.startswith(".") for part in p.relative_to(root).parts[:-1]))


def _tree_digest(root: Path, skip: set[Path]) -> dict[str, str]:
    out = {}
    for p in sorted(root.rglob("*")):
        if p.is_file() and not any(p == s or s in p.parents for s in skip):
            out[str(p.relative_to(root))] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


#: How notebooks run (:func:`grade_class`'s ``engine``), set in each grading process.
ENGINES = ("warm", "kernel")
_ENGINE = {"name": "warm"}


#: The kinds of submission :func:`grade_class` grades: for each, a function listing them under the submissions
#: folder and one grading one (``(path, root, limits, scratch_parent) -> rows``; it must never raise for bad
#: input, and must run student code only through :mod:`~course.classroom.sandbox`). A new kind (a reader's saved
#: answers, say) is one more entry here, and a way for :func:`_quick_key` to read its student (``STUDENT=``).
KINDS: dict[str, tuple[Callable[[Path], list[Path]], Callable[[Path, Path, Limits, Path], list[Row]]]] = {}


def _worker(args: tuple[str, str, Limits, str, str, str]) -> list[Row]:
    path, root, limits, scratch_parent, engine, kind = args
    _ENGINE["name"] = engine
    try:
        return KINDS[kind][1](Path(path), Path(root), limits, Path(scratch_parent))
    except Exception as exc:  # a grader bug: say so in the gradebook, keep going
        return [Row("", str(Path(path).relative_to(root)), NOTEBOOK, "", "",
                    f"the grader failed on this notebook ({type(exc).__name__}: {exc}); please report it"[:400])]


def grade_class(root: Path, *, workers: int | None = None, limits: Limits | None = None,
                roster: Path | None = None, student: str | None = None, engine: str = "warm") -> list[Row]:
    """Grade every notebook under ``root``; write ``gradebook.csv`` and ``reports/``; return the rows.

    With ``student``, only the notebooks whose ID is that student's (after :func:`normalise_id`) are graded
    again, and their rows replace that student's rows of the existing ``gradebook.csv`` (which must exist);
    the other rows are kept as they are, the roster rows and every file made from the gradebook are redone.

    Duplicates (two notebooks of one chapter by one student, IDs compared after :func:`normalise_id`): the
    latest file (modification time, then path) counts, the others get one row saying so. With a ``roster``
    (:func:`read_roster`), IDs not on it and students on it without a notebook get a row each."""
    from .report import class_page, write_reports

    if engine not in ENGINES:
        raise ValueError(f"Expected an engine in {ENGINES}, got {engine!r}")
    root = Path(root).resolve()
    if not root.is_dir():
        raise ValueError(f"Expected a folder of submissions, got {str(root)!r}")
    limits = limits or Limits()
    how = isolation()  # (probed once here, before the worker processes are forked: they inherit the answer)
    if not how.ok and not unsafe_allowed():
        raise Refused(f"make grade refuses to grade: {how.reason}. Without isolation one student's code could "
                      "read or change another's work and grade. To grade anyway, at your own risk: UNSAFE=1")
    gradebook, reports = root / "gradebook.csv", root / "reports"
    skip = {gradebook, reports, root / GRADES, root / CLASS_PAGE, root / EXPORTS}
    before = _tree_digest(root, skip)
    found = [(kind, p) for kind, (finder, _) in KINDS.items() for p in finder(root)]
    paths = [p for _, p in found]
    kind_of = {p: kind for kind, p in found}
    kept: list[Row] = []
    if student is not None:
        if not gradebook.exists():
            raise ValueError(f"there is no {gradebook} to regrade {student!r} into: grade the class first")
        key = normalise_id(student)
        paths = [p for p in paths if _quick_key(p, root) == key]
        mine = {str(p.relative_to(root)) for p in paths}
        kept = [r for r in read_gradebook(gradebook) if r.student != key and r.notebook not in mine
                and r.exercise not in (ROSTER, "(submissions)")]
    mtimes = {str(p.relative_to(root)): p.stat().st_mtime_ns for p in paths}
    names = read_roster(Path(roster)) if roster else None
    workers = max(1, min(workers or os.cpu_count() or 1, len(paths) or 1))
    with tempfile.TemporaryDirectory(prefix="jacobians-grade-") as tmp:
        Path(tmp).chmod(0o711)  # the sandbox user may enter its own scratch folder, and list nothing
        jobs = [(str(p), str(root), limits, tmp, engine, kind_of[p]) for p in paths]
        if workers == 1:
            try:
                results = [_worker(j) for j in jobs]
            finally:
                stop_warm()
        else:
            with ProcessPoolExecutor(max_workers=workers) as pool:
                results = list(pool.map(_worker, jobs))
    rows = [r for rs in _supersede(results, mtimes) for r in rs]
    if not how.ok:
        rows = [replace(r, message=UNSAFE_NOTE + r.message) for r in rows]
    page_rows: list[Row] = []
    for f in find_answer_files(root):  # answers saved from the book's exercise pages (page_answers.py)
        sid, marks = read_answers_file(f)
        who, rel = student_key(sid, str(f.relative_to(root))) if sid else "", str(f.relative_to(root))
        if student is None or who == normalise_id(student):
            page_rows += [Row(who, rel, m.exercise or NOTEBOOK, sid or "", m.correct, m.message, m.mistake)
                          for m in marks]
    rows = one_answer_each(kept + rows, page_rows)
    if names is not None:
        rows += _roster_rows(rows, names)
    after = _tree_digest(root, skip)
    for name in sorted(set(before) | set(after)):
        if before.get(name) != after.get(name):
            what = "appeared" if name not in before else "disappeared" if name not in after else "changed"
            rows.append(Row("", name, "(submissions)", "", "", f"this file {what} while the class was graded"))
    _write_csv(gradebook, rows)
    write_grades(root / GRADES, rows, names or {})
    write_exports(root / EXPORTS, rows, names or {}, roster_emails(Path(roster)) if roster else {})
    write_reports(reports, rows)
    (root / CLASS_PAGE).write_text(class_page(rows), encoding="utf-8")
    return rows


#: The message of a notebook's row for an exercise no check of the notebook ran (see :func:`_run_and_regrade`).
NOT_ATTEMPTED = "not attempted: no check of this exercise ran"


def one_answer_each(notebook_rows: list[Row], page_rows: list[Row]) -> list[Row]:
    """The gradebook rows when a student hands in notebooks and answers files from the exercise pages: one answer
    counts for each (student, exercise), the other is listed.

    The rule: a notebook's answer counts for every exercise its notebook checked (the notebook is the assignment,
    its code ran in the sandbox, and a code exercise can only be answered there); the page's answer to that
    exercise becomes a note (correct left empty) that says it was not counted, with its verdict. For an exercise
    the student's notebook did not attempt (its row says "not attempted"), or that no notebook of theirs loads,
    the page's answer counts, and the notebook's "not attempted" row becomes the note. Students are matched by
    :func:`normalise_id` (through their rows' ``student``); a placeholder ID is never matched with anyone.

    >>> nb = [Row("s1", "ch01.ipynb", "ch01_ex1", "s1", "0", "wrong"),
    ...       Row("s1", "ch01.ipynb", "ch01_ex2", "s1", "0", NOT_ATTEMPTED)]
    >>> page = [Row("s1", "answers-s1.json", "ch01_ex1", "s1", "1", "right"),
    ...         Row("s1", "answers-s1.json", "ch01_ex2", "s1", "1", "right")]
    >>> for r in one_answer_each(nb, page):
    ...     print(r.notebook, r.exercise, repr(r.correct))
    ch01.ipynb ch01_ex1 '0'
    ch01.ipynb ch01_ex2 ''
    answers-s1.json ch01_ex1 ''
    answers-s1.json ch01_ex2 '1'
    """
    def answered(r: Row) -> bool:
        return bool(r.student) and r.correct in ("0", "1") and r.exercise not in (NOTEBOOK, ROSTER)

    in_notebook = {(r.student, r.exercise) for r in notebook_rows if answered(r) and r.message != NOT_ATTEMPTED}
    on_page = {(r.student, r.exercise): r.notebook for r in page_rows if answered(r)}
    out: list[Row] = []
    for r in notebook_rows:
        key = (r.student, r.exercise)
        if answered(r) and r.message == NOT_ATTEMPTED and key in on_page and key not in in_notebook:
            r = replace(r, correct="", message=f"not attempted in this notebook; the answer saved from the "
                        f"exercise page ({on_page[key]}) counts instead")
        out.append(r)
    for r in page_rows:
        if answered(r) and (r.student, r.exercise) in in_notebook:
            was = "right" if r.correct == "1" else "wrong"
            r = replace(r, correct="", message=f"not counted: the notebook's answer to {r.exercise} counts, not the "
                        f"exercise page's (this one was {was}: {r.message})"[:400])
        out.append(r)
    return out


def _quick_key(path: Path, root: Path) -> str | None:
    """The gradebook's student of a notebook, read without running it (None if it has no readable ID)."""
    try:
        raw = path.read_bytes()
        sid = student_id(_code_sources(json.loads(raw))) if len(raw) <= MAX_BYTES else None
    except (OSError, ValueError, RecursionError):
        return None
    return None if sid is None else student_key(sid, str(path.relative_to(root)))


def _chapters(rows: list[Row]) -> tuple[str, ...]:
    return tuple(sorted({r.exercise.split("_")[0] for r in rows if r.correct in ("0", "1")}))


def _supersede(results: list[list[Row]], mtimes: dict[str, int]) -> list[list[Row]]:
    """Keep the latest notebook of each (student, chapters); an earlier one becomes one row saying so."""
    groups: dict[tuple[str, tuple[str, ...]], list[int]] = {}
    for k, rs in enumerate(results):
        student = next((r.student for r in rs if r.student), "")
        chapters = _chapters(rs)
        if student and chapters:
            groups.setdefault((student, chapters), []).append(k)
    out = list(results)
    for (student, chapters), members in groups.items():
        if len(members) < 2:
            continue
        members.sort(key=lambda k: (mtimes.get(results[k][0].notebook, 0), results[k][0].notebook))
        latest = results[members[-1]][0].notebook
        earlier = [results[k][0].notebook for k in members[:-1]]
        seed = results[members[-1]][0].seed
        for k in members[:-1]:
            rs = results[k]
            graded = [r for r in rs if r.correct in ("0", "1")]
            out[k] = [Row(student, rs[0].notebook, NOTEBOOK, rs[0].seed, "",
                          f"is an earlier submission of {', '.join(chapters)} by the same student: {latest} is "
                          f"later and counts, this one does not (it had {sum(r.correct == '1' for r in graded)} "
                          f"of {len(graded)} right)")]
        out[members[-1]] = [*results[members[-1]], Row(
            student, latest, NOTEBOOK, seed, "",
            f"counts for {', '.join(chapters)}; earlier submissions not counted: {', '.join(earlier)}")]
    return out


def read_roster(path: Path) -> dict[str, str]:
    """A roster CSV as ``{normalised ID: name}``.

    The ID is the column headed ``id``, ``student``, ``student_id``, ``student id``, ``sis user id``,
    ``username`` or ``login`` (any case), else the first column; the name is the column headed ``name``,
    ``full name`` or ``student name``, else the second column, else empty. A first row that names no such
    column is data.
    """
    with open(path, newline="", encoding="utf-8-sig") as f:
        table = [row for row in csv.reader(f) if any(c.strip() for c in row)]
    if not table:
        raise ValueError(f"the roster {path} is empty")
    head = [c.strip().casefold() for c in table[0]]
    ids = [k for k, c in enumerate(head) if c in ("id", "student", "student_id", "student id", "sis user id",
                                                  "username", "login")]
    names = [k for k, c in enumerate(head) if c in ("name", "full name", "student name")]
    if ids or names:
        table = table[1:]
    mails = {k for k, c in enumerate(head) if c in ("email", "email address", "e-mail")}
    i = ids[0] if ids else 0
    n = names[0] if names else next((k for k in (1, 0) if k != i and k not in mails), -1)
    out: dict[str, str] = {}
    for row in table:
        if i < len(row) and row[i].strip():
            out[normalise_id(row[i])] = row[n].strip() if 0 <= n < len(row) and n != i else ""
    return out


def roster_emails(path: Path) -> dict[str, str]:
    """``{normalised ID: email}`` from the roster's column headed ``email``, ``email address`` or ``e-mail``
    (any case; empty if it has none). Gradescope's roster needs them."""
    with open(path, newline="", encoding="utf-8-sig") as f:
        table = [row for row in csv.reader(f) if any(c.strip() for c in row)]
    if not table:
        return {}
    head = [c.strip().casefold() for c in table[0]]
    mails = [k for k, c in enumerate(head) if c in ("email", "email address", "e-mail")]
    ids = [k for k, c in enumerate(head) if c in ("id", "student", "student_id", "student id", "sis user id",
                                                  "username", "login")]
    if not mails:
        return {}
    i, m = (ids[0] if ids else 0), mails[0]
    return {normalise_id(row[i]): row[m].strip() for row in table[1:]
            if i < len(row) and m < len(row) and row[i].strip() and row[m].strip()}


def _roster_rows(rows: list[Row], names: dict[str, str]) -> list[Row]:
    seen = {r.student for r in rows if r.student}
    out = [Row(s, "", ROSTER, "", "", "this ID is not on the roster (a typo in SEED, or a student who is not "
                                     "enrolled?)") for s in sorted(seen) if s not in names and
           not s.startswith("(placeholder")]
    out += [Row(s, "", ROSTER, "", "", f"{names[s] or 'this student'} is on the roster, but no notebook with this "
                                       "ID was found") for s in sorted(names) if s not in seen]
    return out


#: File names, in the submissions folder, of the table of grades and of the class page.
GRADES = "grades.csv"
CLASS_PAGE = "class.html"
#: The course file of points per exercise (:func:`points`).
POINTS_FILE = Path(__file__).with_name("points.toml")


def points(path: Path = POINTS_FILE) -> dict[str, float]:
    """Points of every exercise of the course: 1, or what the ``[points]`` table of ``path`` says.

    >>> p = points()
    >>> len(p) > 40 and all(v >= 0 for v in p.values())
    True
    """
    import tomllib

    from course import exercises

    out = {eid: 1.0 for eid in exercises.exercise_ids()}
    with open(path, "rb") as f:
        table = tomllib.load(f).get("points", {})
    for eid, value in table.items():
        if eid not in out:
            raise ValueError(f"{path}: {eid!r} is not an exercise of the course")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0:
            raise ValueError(f"{path}: the points of {eid} must be a number >= 0, got {value!r}")
        out[eid] = float(value)
    return out


@cache
def partial_credit(path: Path = POINTS_FILE) -> frozenset[str]:
    """The code exercises that earn partial credit: the keys set to ``true`` in the ``[partial]`` table of
    ``path`` (points times tests passed over tests run; every other exercise is all or nothing).

    >>> isinstance(partial_credit(), frozenset)
    True
    """
    import tomllib

    from course import exercises

    with open(path, "rb") as f:
        table = tomllib.load(f).get("partial", {})
    out = set()
    for eid, value in table.items():
        if eid not in exercises.exercise_ids():
            raise ValueError(f"{path}: {eid!r} in [partial] is not an exercise of the course")
        if not isinstance(value, bool):
            raise ValueError(f"{path}: [partial] {eid} must be true or false, got {value!r}")
        if value and exercises.load(eid, seed=0).kind != "function":
            raise ValueError(f"{path}: {eid} is not a code exercise; only code exercises (tests passed over tests "
                             "run) can earn partial credit")
        if value:
            out.add(eid)
    return frozenset(out)


def score(row: Row, partial: frozenset[str]) -> float:
    """The share of an exercise's points a gradebook row earns: 1 if right, else tests passed over tests run
    for a code exercise with partial credit, else 0.

    >>> score(Row("s", "n", "ch02_ex4", "s", "0", "", "", "7/9"), frozenset({"ch02_ex4"}))
    0.7777777777777778
    """
    if row.correct == "1":
        return 1.0
    if row.exercise in partial and row.tests.count("/") == 1:
        passed, run = row.tests.split("/")
        if passed.isdigit() and run.isdigit() and 0 < int(run) and int(passed) <= int(run):
            return int(passed) / int(run)
    return 0.0


def _number(x: float) -> str:
    return f"{round(x, 2):g}"


def grades_table(rows: list[Row], names: dict[str, str], worth: dict[str, float] | None = None,
                 partial: frozenset[str] | None = None) -> tuple[list[str], list[list[str]]]:
    """``grades.csv`` as a header and rows: one row per student (``student``, ``name``, the points of each
    chapter, ``total``); the header gives each column's maximum. A student's exercise counts once, from the
    rows that count (an earlier copy of a later submission has none), with its :func:`score` (partial credit
    for the code exercises of ``partial``, by default those of :func:`partial_credit`); points are rounded to
    two decimals."""
    worth = worth or points()
    partial = partial_credit() if partial is None else partial
    chapters = sorted({eid.split("_")[0] for eid in worth})
    earned: dict[str, dict[str, float]] = {}
    for r in rows:
        if r.student and r.exercise not in (NOTEBOOK, ROSTER, "(submissions)"):
            mine = earned.setdefault(r.student, {})
            if r.exercise in worth:
                mine[r.exercise] = max(mine.get(r.exercise, 0.0), worth[r.exercise] * score(r, partial))
    for sid in names:
        earned.setdefault(sid, {})
    top = {c: sum(v for e, v in worth.items() if e.startswith(c + "_")) for c in chapters}
    head = ["student", "name", *(f"{c} (of {_number(top[c])})" for c in chapters),
            f"total (of {_number(sum(top.values()))})"]
    table = []
    for sid in sorted(earned):
        got = {c: sum(v for e, v in earned[sid].items() if e.startswith(c + "_")) for c in chapters}
        table.append([sid, names.get(sid, ""), *(_number(got[c]) for c in chapters), _number(sum(got.values()))])
    return head, table


def write_grades(path: Path, rows: list[Row], names: dict[str, str]) -> None:
    """Write :func:`grades_table` to ``path`` (every field made :func:`spreadsheet_safe`)."""
    head, table = grades_table(rows, names)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    for line in (head, *table):
        w.writerow([spreadsheet_safe(v) for v in line])
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(buf.getvalue(), encoding="utf-8")
    os.replace(tmp, path)


#: Folder, in the submissions folder, of the exports for learning platforms (:func:`write_exports`).
EXPORTS = "exports"


def exports(rows: list[Row], names: dict[str, str], worth: dict[str, float] | None = None,
            emails: dict[str, str] | None = None) -> dict[str, list[list[str]]]:
    """The chapter grades as each platform's CSV import expects them (one table per file name).

    Every file is UTF-8 CSV with a header row, fields quoted where they hold a comma, a double quote or a line
    break (doubled inside, RFC 4180), as the platforms' import pages ask.

    * ``canvas.csv``: Canvas's gradebook import ("How do I import grades in the Gradebook?", Instructure's
      Canvas Instructor Guide; the same columns in Ohio State's guide "Import a CSV File to Carmen Grades",
      teaching.resources.osu.edu/toolsets/carmencanvas/guides/calculating-final-grades/import-csv-file-carmen-grades):
      the columns ``Student``, ``ID``, ``SIS User ID``, ``SIS Login ID``, ``Section`` (the student is found
      by any one of name, Canvas ID or SIS User ID: here the SIS User ID is the student ID), then one column
      per assignment, ``Jacobians chNN`` (a name the course does not have yet becomes a new assignment),
      and a second row ``Points Possible`` with each assignment's maximum, as Canvas's own export writes it.
    * ``moodle.csv``: Moodle's "Import grades from CSV" (docs.moodle.org/en/Grade_import): a header row; in
      the import form the instructor maps the column ``ID number`` to the user field "ID number" (or
      ``Email address`` to "Email address") and each ``Jacobians chNN`` column to a grade item (or a new
      one). The course total is Moodle's to compute, so it is not exported.
    * ``gradescope_roster.csv``: Gradescope's roster upload ("Adding Students and Staff", Gradescope Help
      Center, help.gradescope.com/article/w59nl02vyt-instructor-course-add-members): a header on every
      column, the full name in one column (``Name``), a unique ``Email`` per student (required: students
      without one in the roster are left out), and ``SID``. Gradescope documents no CSV import of scores, so
    * ``gradescope.csv`` holds the scores in the layout of Gradescope's own grade export (``Name``, ``SID``,
      ``Email``, one column per assignment, ``Total Score``), for the instructor's records or a script.

    Placeholder IDs (no student to give the grade to) are left out.
    """
    emails = emails or {}
    head, table = grades_table(rows, names, worth)
    chapters = [h.split(" ")[0] for h in head[2:-1]]
    tops = [h.split("(of ")[1].rstrip(")") for h in head[2:]]
    real = [t for t in table if not t[0].startswith("(placeholder")]
    canvas = [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", *(f"Jacobians {c}" for c in chapters)],
              ["    Points Possible", "", "", "", "", *tops[:-1]]]
    canvas += [[t[1] or t[0], "", t[0], "", "", *t[2:-1]] for t in real]
    moodle = [["ID number", "Full name", "Email address", *(f"Jacobians {c}" for c in chapters)]]
    moodle += [[t[0], t[1], emails.get(t[0], ""), *t[2:-1]] for t in real]
    roster = [["Name", "Email", "SID"]]
    roster += [[t[1] or t[0], emails[t[0]], t[0]] for t in real if emails.get(t[0])]
    gradescope = [["Name", "SID", "Email", *chapters, "Total Score"]]
    gradescope += [[t[1], t[0], emails.get(t[0], ""), *t[2:]] for t in real]
    return {"canvas.csv": canvas, "moodle.csv": moodle, "gradescope_roster.csv": roster, "gradescope.csv": gradescope}


def write_exports(folder: Path, rows: list[Row], names: dict[str, str], emails: dict[str, str] | None = None,
                  worth: dict[str, float] | None = None) -> None:
    """Write :func:`exports` into ``folder`` (every field made :func:`spreadsheet_safe`)."""
    folder.mkdir(exist_ok=True)
    for name, table in exports(rows, names, worth, emails).items():
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\r\n")  # (RFC 4180's line break)
        for line in table:
            w.writerow([spreadsheet_safe(v) for v in line])
        (folder / name).write_text(buf.getvalue(), encoding="utf-8", newline="")


def spreadsheet_safe(text: str) -> str:
    """``text`` as a CSV field that no spreadsheet runs as a formula: a leading ``= + - @``, tab or carriage
    return (and a leading quote, so that it can be undone) gets a ``'`` in front (OWASP's rule).

    >>> spreadsheet_safe("=2+3"), spreadsheet_safe("s1"), spreadsheet_safe("'x")
    ("'=2+3", 's1', "''x")
    """
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r", "'") else text


def _unsafe_back(text: str) -> str:
    return text[1:] if text.startswith("'") else text


def _write_csv(path: Path, rows: list[Row]) -> None:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for r in rows:
        w.writerow([spreadsheet_safe(str(v)) for v in astuple(r)])
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(buf.getvalue(), encoding="utf-8")
    os.replace(tmp, path)


def read_gradebook(path: Path) -> list[Row]:
    """The rows of a gradebook.csv."""
    with open(path, newline="", encoding="utf-8") as f:
        r = csv.reader(f)
        head = next(r)
        if tuple(head) not in (COLUMNS, COLUMNS[:-1]):  # (a gradebook written before the tests column)
            raise ValueError(f"Expected the columns {COLUMNS}, got {head}")
        return [Row(*(_unsafe_back(v) for v in row)) for row in r]


KINDS["notebook"] = (find_notebooks, grade_notebook)


def main(argv: list[str] | None = None) -> int:
    """``python -m course.classroom.grade DIR [--workers N] [--cell-timeout S] [--notebook-timeout S]``."""
    import argparse

    p = argparse.ArgumentParser(prog="make grade", description="Grade every student notebook under DIR.")
    p.add_argument("submissions", type=Path)
    p.add_argument("--workers", type=int, default=None, help="processes (default: one per core)")
    p.add_argument("--cell-timeout", type=float, default=Limits.cell_timeout)
    p.add_argument("--notebook-timeout", type=float, default=Limits.notebook_timeout)
    p.add_argument("--roster", type=Path, default=None, help="CSV of the class: ID (and name) per row")
    p.add_argument("--student", default=None, help="regrade only this student into the existing gradebook")
    a = p.parse_args(argv)
    if not a.submissions.is_dir():
        print(f"make grade: {a.submissions} is not a folder (give SUBMISSIONS=<dir>)", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    how = isolation()
    if not how.ok and unsafe_allowed():
        print(f"make grade: WARNING: grading WITHOUT isolation ({how.reason}); every row says so", file=sys.stderr)
    try:
        rows = grade_class(a.submissions, workers=a.workers, roster=a.roster, student=a.student,
                           limits=Limits(cell_timeout=a.cell_timeout, notebook_timeout=a.notebook_timeout))
    except Refused as exc:
        print(exc, file=sys.stderr)
        return 3
    except ValueError as exc:  # no gradebook to regrade into, a bad roster or points file
        print(f"make grade: {exc}", file=sys.stderr)
        return 2
    n = len({r.notebook for r in rows if r.exercise != "(submissions)"})
    right = sum(r.correct == "1" for r in rows)
    graded = sum(r.correct in ("0", "1") for r in rows)
    notes = sum(r.exercise == NOTEBOOK for r in rows)
    print(f"make grade: {n} notebooks in {time.perf_counter() - t0:.1f} s; {right} of {graded} answers right; "
          f"{notes} notes on notebooks; wrote {a.submissions / 'gradebook.csv'} and {a.submissions / 'reports'}/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
