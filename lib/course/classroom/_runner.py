"""Inside the sandbox: execute one notebook with nbclient and say what happened, as JSON.

THE PREVIOUS DESIGN, kept only so that ``make bench`` can print its figure beside the current one's
(``grade_class(engine="kernel")``) and ``tests/test_classroom_engines.py`` can check that both give an honest
class the same gradebook. ``make grade`` runs notebooks with :mod:`~course.classroom._cells` in a warm sandbox
(:func:`course.classroom.sandbox.start_warm`).

``python -m course.classroom._runner NOTEBOOK RESULT CELL_TIMEOUT`` runs the
audit hook of :data:`course.classroom.sandbox.GUARD` first, then every code
cell (nbgrader's settings: errors do not stop the run, a cell over its time is
interrupted and the next one runs, history in memory), and writes RESULT:
``{"errors": [{"cell", "ename", "evalue"}], "timeouts": [cell...], "status", "strays", "left_files"}``
(the last two in a sandbox only: processes still running after the last cell, files left in /tmp and
/dev/shm)
(cells numbered from 1 among the notebook's code cells). The answers are not
here: ``exercises.check`` logs them itself (:mod:`course.exercises._progress`),
so a kernel that dies keeps the checks it made.
"""

from __future__ import annotations

import json
import os
import sys
from typing import Any

import nbformat
from nbclient import NotebookClient

from course.classroom.sandbox import GUARD


def main(path: str, result: str, cell_timeout: float) -> None:
    nb = nbformat.read(path, as_version=4)
    code_cells = [c for c in nb.cells if c.cell_type == "code"]
    nb.cells = [nbformat.v4.new_code_cell(GUARD), *code_cells]
    out: dict[str, Any] = {"errors": [], "timeouts": [], "status": "ok"}
    client = NotebookClient(nb, timeout=cell_timeout, interrupt_on_timeout=True, allow_errors=True,
                            kernel_name="python3", startup_timeout=120, record_timing=False,
                            extra_arguments=["--HistoryManager.hist_file=:memory:"],
                            resources={"metadata": {"path": "."}})
    try:
        client.execute()
    except Exception as exc:  # the kernel died, or would not start
        out["status"] = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"[:300]
    for number, cell in enumerate(nb.cells[1:], start=1):
        for o in cell.get("outputs", []):
            if o.get("output_type") != "error":
                continue
            if o.get("ename") == "KeyboardInterrupt":
                out["timeouts"].append(number)
            else:
                out["errors"].append({"cell": number, "ename": str(o.get("ename"))[:80],
                                      "evalue": str(o.get("evalue"))[:300]})
    if _in_sandbox():
        out["strays"], out["left_files"] = _strays(), _left_files()
    with open(result, "w", encoding="utf-8") as f:
        json.dump(out, f)


def _in_sandbox() -> bool:
    """Whether this runs in make grade's bubblewrap sandbox (its own PID namespace, bwrap as process 1)."""
    try:
        with open("/proc/1/cmdline", "rb") as f:
            return f.read().split(b"\0")[0].endswith(b"bwrap")
    except OSError:
        return False


def _strays() -> list[str]:
    """Processes still running after the last cell, but this one and the sandbox's first (the kernel was shut
    down): what the notebook left behind, each as its command line."""
    out = []
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) not in (1, os.getpid()):
            try:
                with open(f"/proc/{name}/cmdline", "rb") as f:
                    out.append(f.read(200).replace(b"\0", b" ").decode("utf-8", "replace").strip() or "?")
            except OSError:
                continue
    return out[:5]


def _left_files() -> list[str]:
    """Files the notebook left in the sandbox's private /tmp and /dev/shm (they vanish with it)."""
    out = []
    for folder in ("/tmp", "/dev/shm"):
        try:
            out += [f"{folder}/{n}"[:100] for n in sorted(os.listdir(folder))]
        except OSError:
            continue
    return out[:5]


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]))
