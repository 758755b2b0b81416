"""Inside the sandbox: execute one notebook's code cells and say what happened, as JSON.

One implementation of running a notebook's cells for both of make grade's engines: what a run reads (the
notebook's code cells, :func:`code_cells`), what it records and how (:class:`Outcome`: errors, interrupted
cells, the status, then what the notebook left behind) and where it writes it. Only the executor differs:

* ``main(NOTEBOOK, RESULT, CELL_TIMEOUT)``, the current design, runs in a sandboxed process forked from the
  warm worker (:mod:`~course.classroom._zygote`): it installs the audit hook of
  :data:`course.classroom.sandbox.GUARD`, then runs every code cell in one
  :class:`IPython.core.interactiveshell.InteractiveShell` (the shell a Jupyter kernel wraps: the same
  ``%magics``, ``!commands`` and namespace, without the kernel's process and messaging);
* :mod:`~course.classroom._runner`, the previous design kept for ``make bench``'s comparison, hands the same
  cells to nbclient and a Jupyter kernel, and records its outputs here.

As nbgrader does, an error does not stop the run, and a cell over ``CELL_TIMEOUT`` seconds is interrupted
(``KeyboardInterrupt``, as a kernel's interrupt) and the next one runs. RESULT gets
``{"errors": [{"cell", "ename", "evalue"}], "timeouts": [cell...], "status", "strays", "left_files"}``
(cells numbered from 1 among the notebook's code cells; the last two in a sandbox only: processes still running
after the last cell, files left in /tmp and /dev/shm). The shell writes it after every cell, so that a notebook
that ends its own process keeps what it did. The answers are not here: ``exercises.check`` logs them itself
(:mod:`course.exercises._progress`).
"""

from __future__ import annotations

import json
import os
import signal
import sys
from typing import Any

from course.classroom.sandbox import GUARD


def code_cells(path: str) -> list[str]:
    """The source of every code cell of the notebook at ``path``, in order."""
    with open(path, encoding="utf-8") as f:
        nb = json.load(f)
    return ["".join(c["source"]) if isinstance(c.get("source"), list) else str(c.get("source", ""))
            for c in nb.get("cells", []) if isinstance(c, dict) and c.get("cell_type") == "code"]


class Outcome:
    """What one run of a notebook's cells did, written to ``result`` as JSON (see the module docstring)."""

    def __init__(self, result: str) -> None:
        self.result = result
        self.out: dict[str, Any] = {"errors": [], "timeouts": [], "status": "ok"}

    def timeout(self, cell: int) -> None:
        self.out["timeouts"].append(cell)

    def error(self, cell: int, ename: str, evalue: str) -> None:
        self.out["errors"].append({"cell": cell, "ename": str(ename)[:80], "evalue": str(evalue)[:300]})

    def stopped(self, status: str) -> None:
        """The executor itself failed (the shell, or the kernel died or would not start)."""
        self.out["status"] = status[:300]

    def write(self) -> None:
        tmp = self.result + ".part"
        with open(tmp, "w", encoding="utf-8") as f:
            json.dump(self.out, f)
        os.replace(tmp, self.result)

    def finish(self) -> None:
        """Add what the notebook left behind (in a sandbox), and write the result."""
        if _in_sandbox():
            self.out["strays"], self.out["left_files"] = _strays(), _left_files()
        self.write()


class _CellTimeout(KeyboardInterrupt):
    pass


def _alarm(signum: int, frame: Any) -> None:
    raise _CellTimeout()


def main(path: str, result: str, cell_timeout: float) -> None:
    from IPython.core.interactiveshell import InteractiveShell
    from traitlets.config import Config

    cells = code_cells(path)
    outcome = Outcome(result)
    config = Config()
    config.HistoryManager.hist_file = ":memory:"  # (no history file, as the kernel's --HistoryManager setting)
    shell = InteractiveShell.instance(config=config)  # (made before the hook: it copies its profile files)
    exec(compile(GUARD, "<grading sandbox>", "exec"), {})
    signal.signal(signal.SIGALRM, _alarm)
    for number, source in enumerate(cells, start=1):
        status = "ok"
        signal.setitimer(signal.ITIMER_REAL, cell_timeout)
        try:
            run = shell.run_cell(source, store_history=False, silent=False)
            error = run.error_before_exec or run.error_in_exec
        except KeyboardInterrupt as exc:  # the alarm came outside the cell's own code
            error = exc
        except BaseException as exc:  # the shell itself failed
            error, status = exc, f"{type(exc).__name__}: {exc}"
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        if isinstance(error, KeyboardInterrupt):
            outcome.timeout(number)
        elif error is not None:
            outcome.error(number, type(error).__name__, str(error))
        outcome.write()
        if status != "ok":
            outcome.stopped(status)
            break
    sys.stdout.flush()
    outcome.finish()


def _in_sandbox() -> bool:
    """Whether this runs in make grade's bubblewrap sandbox (its own PID namespace, bwrap as process 1)."""
    try:
        with open("/proc/1/cmdline", "rb") as f:
            return f.read().split(b"\0")[0].endswith(b"bwrap")
    except OSError:
        return False


def _strays() -> list[str]:
    """Processes still running after the last cell, but the sandbox's own (bwrap's init, process 1, and its
    first program, process 2: the placeholder that holds a warm sandbox open, or the kernel runner) and this
    one: what the notebook left (a kernel runner has shut its kernel down by then), each as its command line."""
    out = []
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) not in (1, 2, os.getpid()):
            try:
                with open(f"/proc/{name}/cmdline", "rb") as f:
                    out.append(f.read(200).replace(b"\0", b" ").decode("utf-8", "replace").strip() or "?")
            except OSError:
                continue
    return out[:5]


def _mount_points() -> set[str]:
    """The entries of /tmp that the sandbox itself made: the folders on the way to a Python or a checkout that
    lives under /tmp (bound there read-only, sandbox.py's _needed), not written by the notebook."""
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # holds course/
    out = set()
    for folder in (sys.base_prefix, sys.prefix, here):
        for path in (os.path.realpath(folder), os.path.abspath(folder)):
            if path.startswith("/tmp/"):
                out.add("/tmp/" + path[len("/tmp/"):].split("/", 1)[0])
    return out


def _left_files() -> list[str]:
    """Files the notebook left in the sandbox's private /tmp and /dev/shm (they vanish with it)."""
    out = []
    ours = _mount_points()
    for folder in ("/tmp", "/dev/shm"):
        try:
            out += [f"{folder}/{n}"[:100] for n in sorted(os.listdir(folder)) if f"{folder}/{n}" not in ours]
        except OSError:
            continue
    return out[:5]


if __name__ == "__main__":  # (without isolation, UNSAFE=1: started afresh)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]))
