"""Inside the sandbox: execute one notebook with nbclient and a Jupyter kernel, and say what happened, as JSON.

THE PREVIOUS DESIGN, kept only so that ``make bench`` can print its figure beside the current one's
(``grade_class(engine="kernel")``) and ``tests/test_classroom_engines.py`` can check that both give an honest
class the same gradebook. ``make grade`` runs notebooks with :mod:`~course.classroom._cells` in a warm sandbox
(:func:`course.classroom.sandbox.start_warm`).

``python -m course.classroom._runner NOTEBOOK RESULT CELL_TIMEOUT`` is the executor only: the cells it runs,
what it records and the RESULT it writes are :mod:`~course.classroom._cells`' (:func:`~course.classroom._cells.
code_cells`, :class:`~course.classroom._cells.Outcome`). It runs the audit hook of
:data:`course.classroom.sandbox.GUARD` in a first cell, then every code cell with nbgrader's settings (errors
do not stop the run, a cell over its time is interrupted and the next one runs, history in memory).
"""

from __future__ import annotations

import sys

import nbformat
from nbclient import NotebookClient

from course.classroom._cells import Outcome, code_cells
from course.classroom.sandbox import GUARD


def main(path: str, result: str, cell_timeout: float) -> None:
    nb = nbformat.v4.new_notebook(metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                                            "language": "python"}})
    nb.cells = [nbformat.v4.new_code_cell(s) for s in (GUARD, *code_cells(path))]
    outcome = Outcome(result)
    client = NotebookClient(nb, timeout=cell_timeout, interrupt_on_timeout=True, allow_errors=True,
                            kernel_name="python3", startup_timeout=120, record_timing=False,
                            extra_arguments=["--HistoryManager.hist_file=:memory:"],
                            resources={"metadata": {"path": "."}})
    try:
        client.execute()
    except Exception as exc:  # the kernel died, or would not start
        outcome.stopped(f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}")
    for number, cell in enumerate(nb.cells[1:], start=1):
        for o in cell.get("outputs", []):
            if o.get("output_type") != "error":
                continue
            if o.get("ename") == "KeyboardInterrupt":
                outcome.timeout(number)
            else:
                outcome.error(number, str(o.get("ename")), str(o.get("evalue")))
    outcome.finish()


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]))
