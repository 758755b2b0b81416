"""Grading throughput (``make bench``), and the class of made-up students the tests grade.

:func:`submission` writes one student notebook as a student would hand it in:
the student notebook of ``tools.make_exercises`` with the set-up cell's
``SEED`` set to the student's ID and each answer cell filled in one way
(``right``: the reference values typed in as literals, or a function of the
notebook that calls the variant's reference function; ``wrong``: off by one or a function returning
zeros; ``half``: the first half right, the rest untouched; ``blank``: nothing).

``python -m tools.bench_grade [N] [N_OLD]`` grades N (default 200) such notebooks,
every chapter and all four ways, with isolation on, and the first N_OLD (default 40) of them the previous
way (a Jupyter kernel per sandbox), in the same run; it prints both figures and their ratio.

Beside the notebooks per second (wall clock, which other work on the machine slows down), it prints the CPU
seconds the grading spends per notebook: the CPU time of the grader and every process it starts (its pool
workers, their warm workers, the sandboxes and what runs in them), from a cpuacct cgroup the bench puts itself
in (:class:`CpuMeter`). That figure does not depend on the load: c cores grade at most c / (CPU seconds per
notebook) notebooks per second, so 2 notebooks/s on 2 cores needs at most 1 CPU second per notebook.
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import nbformat
import numpy as np

from tools.make_exercises import SOURCES, exercise_cells, student_notebook

WAYS = ("right", "wrong", "half", "blank")
#: A way that only the tests use: each answer cell holds the book's worked solution, as the book writes it
#: (reading the variant from the notebook's ``exN.given``, calling helpers of its own).
BOOK = "book"
_SEED_LINE = re.compile(r"^SEED\s*=.*$", re.M)


def string_ids_supported() -> bool:
    """Whether ``exercises.load`` takes a string seed (a student ID) in this tree, not only an int."""
    from course import exercises

    seed: Any = "s1"  # any text: a student ID
    try:
        exercises.load("ch01_ex1", seed=seed)
    except (TypeError, ValueError):
        return False
    return True


def _literal(value: Any) -> str:
    import sympy as sp

    if isinstance(value, sp.MatrixBase | sp.Basic):
        return f"sp.sympify({sp.srepr(value)!r})"
    return f"np.array({np.asarray(value, dtype=float).tolist()!r})"


def answer_source(exercise_id: str, seed: str | int, way: str) -> str:
    """The source of a filled answer cell for ``exercise_id`` (``way``: ``right`` or ``wrong``)."""
    from course import exercises
    from jacobians.grading import FunctionExercise, SymbolicExercise

    seed_arg: Any = seed
    ex = exercises.load(exercise_id, seed=seed_arg)
    if isinstance(ex, FunctionExercise):  # a function of the notebook that calls the variant's reference when run
        body = (f"return exercises.load({exercise_id!r}, seed=SEED).reference(*args)" if way == "right"
                else "return np.zeros((6, 6))")
        return f"def {ex.fn_name}(*args):\n    {body}\n\n\nanswer = {ex.fn_name}\n"
    ref = ex.solution()
    if way == "wrong":
        if isinstance(ex, SymbolicExercise):
            ref = 2 * ref
        else:
            ref = np.asarray(ref, dtype=float) + 1.0
    return f"answer = {_literal(ref)}\n"


def page(chapter: str | Path) -> Path:
    """The source page of ``chapter``: an exercise page's name (``"02_space_jacobian"``), or a page's path (the
    tests' made-up chapter, ``tests/fixtures/00_fixture.md``)."""
    return chapter if isinstance(chapter, Path) else SOURCES / f"{chapter}.md"


def submission(chapter: str | Path, student: str | int, way: str) -> nbformat.NotebookNode:
    """The notebook ``chapter`` (e.g. ``"02_space_jacobian"``, or a page's path, see :func:`page`) handed in by
    ``student``, answered ``way``."""
    if way not in (*WAYS, BOOK):
        raise ValueError(f"Expected a way in {(*WAYS, BOOK)}, got {way!r}")
    nb = student_notebook(page(chapter))
    solutions = book_solutions(chapter) if way == BOOK else {}
    for cell in nb.cells:
        if cell.cell_type == "code" and _SEED_LINE.search(cell.source):
            cell.source = _SEED_LINE.sub(f"SEED = {student!r}  # your student ID", cell.source, count=1)
            break
    else:
        raise ValueError(f"{chapter}: no SEED line in the set-up cell")
    by_id = exercise_cells(nb)
    for k, (eid, cells) in enumerate(by_id.items()):
        this = way
        if way == "half":
            this = "right" if k < len(by_id) // 2 else "blank"
        if this == BOOK:
            cells[1].source = solutions[eid]
        elif this != "blank":
            cells[1].source = answer_source(eid, student, this)
    return nb


def book_solutions(chapter: str | Path) -> dict[str, str]:
    """The worked solution of each exercise of ``chapter``: its solution cells that do not call the checker."""
    import jupytext

    from tools.make_exercises import SOLUTION_TAG

    nb = jupytext.read(page(chapter))
    out: dict[str, list[str]] = {}
    current = None
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        m = re.search(r"""exercises\.load\(\s*["'](ch\d\d_ex\d+)["']""", cell.source)
        if m:
            current = m.group(1)
        tags = cell.get("metadata", {}).get("tags", [])
        if current and SOLUTION_TAG in tags and "exercises.check(" not in cell.source:
            out.setdefault(current, []).append(cell.source)
    return {eid: "\n\n".join(srcs) + "\n" for eid, srcs in out.items()}


def make_class(folder: Path, n: int, chapters: list[str] | None = None) -> list[Path]:
    """``n`` submissions under ``folder/<student>/``, cycling through the chapters and the ways."""
    chapters = chapters or sorted(p.stem for p in SOURCES.glob("[0-9][0-9]_*.md"))
    ids: list[str | int] = [f"s{k:04d}" if string_ids_supported() else 1000 + k for k in range(n)]
    out = []
    for k, sid in enumerate(ids):
        chapter, way = chapters[k % len(chapters)], WAYS[k % len(WAYS)]
        path = folder / str(sid) / f"{chapter}.ipynb"
        path.parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(submission(chapter, sid, way), path)
        out.append(path)
    return out


class CpuMeter:
    """CPU seconds used by this process and all its descendants while the meter is open.

    As root with a writable cgroup v1 ``cpuacct`` hierarchy, the process moves itself into a cgroup of its own
    (its children inherit it; the sandboxes move only into memory, pids and freezer cgroups, so they stay), and
    ``cpuacct.usage`` counts every process of the tree, waited for or not. Otherwise it falls back to
    ``getrusage``: this process and the children it waited for (a descendant whose parent did not wait for it,
    such as a pool worker's warm worker killed with its parent, is missed), a lower bound; ``exact`` says
    which."""

    ROOT = Path("/sys/fs/cgroup/cpuacct")

    def __init__(self) -> None:
        self.group: Path | None = None
        self.home: Path | None = None
        self.exact = False
        try:
            line = next(ln for ln in Path("/proc/self/cgroup").read_text().splitlines()
                        if "cpuacct" in ln.split(":")[1].split(","))
            self.home = self.ROOT / line.split(":", 2)[2].lstrip("/")
            group = self.ROOT / f"jacobians-bench-{os.getpid()}"
            group.mkdir()
            (group / "cgroup.procs").write_text(str(os.getpid()))
            self.group, self.exact = group, True
        except (OSError, StopIteration, IndexError):
            self.group = None

    def seconds(self) -> float:
        if self.group is not None:
            return int((self.group / "cpuacct.usage").read_text()) / 1e9
        import resource

        me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
        return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime

    def close(self) -> None:
        """Move back to where this process was, and remove the cgroup once its last process has ended."""
        if self.group is None or self.home is None:
            return
        (self.home / "cgroup.procs").write_text(str(os.getpid()))
        for _ in range(500):
            try:
                self.group.rmdir()
                break
            except OSError:
                time.sleep(0.02)
        self.group = None


def main(n: int = 200, n_old: int = 40) -> None:
    """Grade ``n`` notebooks the current way (a warm worker forking into a bubblewrap sandbox per notebook),
    and the first ``n_old`` of them the previous way (a fresh interpreter, nbclient and a Jupyter kernel in each
    sandbox), in the same run; print both figures, the CPU seconds per notebook of each, and their ratios."""
    cores = os.cpu_count() or 1
    figures: dict[str, float] = {}
    cpu: dict[str, float] = {}
    meter = CpuMeter()
    try:
        _grade_both(n, n_old, cores, figures, cpu, meter)
    finally:
        meter.close()
    how = ("cpuacct cgroup: the grader and every process it started" if meter.exact else
           "getrusage: the grader and the children it waited for, a lower bound")
    for engine, per in cpu.items():
        print(f"grading, {engine} engine: {per:.2f} CPU seconds per notebook ({how}); at most "
              f"{cores / per:.2f} notebooks/s on {cores} cores, however quiet the machine", flush=True)
    if len(figures) == 2:
        print(f"grading: the current design grades {figures['warm'] / figures['kernel']:.1f} times as many notebooks "
              "per second as the previous one (same run, same machine load), and spends "
              f"{cpu['kernel'] / cpu['warm']:.1f} times less CPU per notebook")


def _grade_both(n: int, n_old: int, cores: int, figures: dict[str, float], cpu: dict[str, float],
                meter: CpuMeter) -> None:
    from course.classroom.grade import grade_class

    with tempfile.TemporaryDirectory(prefix="bench-grade-") as tmp:
        folder = Path(tmp) / "submissions"
        made = make_class(folder, n)
        old = Path(tmp) / "old"
        for path in made[:n_old]:  # the same mix of chapters and ways
            (old / path.parent.name).mkdir(parents=True, exist_ok=True)
            (old / path.parent.name / path.name).write_bytes(path.read_bytes())
        for engine, where, count in (("kernel", old, n_old), ("warm", folder, n)):
            if count == 0:
                continue
            load = os.getloadavg()[0]
            c0, t0 = meter.seconds(), time.perf_counter()
            rows = grade_class(where, workers=cores, engine=engine)
            dt = time.perf_counter() - t0
            time.sleep(0.5)  # (the pool's warm workers end with their parents: let them finish being counted)
            cpu[engine] = (meter.seconds() - c0) / count
            right = sum(r.correct == "1" for r in rows)
            notes = [r for r in rows if r.exercise == "(notebook)"]
            figures[engine] = count / dt
            label = {"kernel": "previous design (fresh Python + nbclient + Jupyter kernel per sandbox)",
                     "warm": "current design (warm worker forked into a bubblewrap sandbox per notebook)"}[engine]
            print(f"grading, {label}: {count} notebooks on {cores} cores in {dt:.1f} s: {count / dt:.2f} notebooks/s, "
                  f"{count / dt / cores:.2f} per core (load average at start {load:.1f}; {right} answers right, "
                  f"{len(notes)} notes on notebooks)", flush=True)


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
