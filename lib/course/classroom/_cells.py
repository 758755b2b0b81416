"""Inside the sandbox: execute one notebook's code cells with IPython's shell, and say what happened, as JSON.

``main(NOTEBOOK, RESULT, CELL_TIMEOUT)`` runs in a sandboxed process forked from the warm worker
(:mod:`~course.classroom._zygote`): it installs the audit hook of :data:`course.classroom.sandbox.GUARD`,
then runs every code cell in one :class:`IPython.core.interactiveshell.InteractiveShell` (the shell a
Jupyter kernel wraps: the same ``%magics``, ``!commands`` and namespace, without the kernel's process and
messaging). As nbgrader does, an error does not stop the run, and a cell over ``CELL_TIMEOUT`` seconds is
interrupted (``KeyboardInterrupt``, as a kernel's interrupt) and the next one runs. RESULT gets the same
fields as the kernel runner's (:mod:`~course.classroom._runner`):
``{"errors": [{"cell", "ename", "evalue"}], "timeouts": [cell...], "status", "strays", "left_files"}``,
written after every cell, so that a notebook that ends its own process keeps what it did.
"""

from __future__ import annotations

import json
import os
import signal
import sys
from typing import Any

from course.classroom.sandbox import GUARD


class _CellTimeout(KeyboardInterrupt):
    pass


def _alarm(signum: int, frame: Any) -> None:
    raise _CellTimeout()


def main(path: str, result: str, cell_timeout: float) -> None:
    from IPython.core.interactiveshell import InteractiveShell
    from traitlets.config import Config

    with open(path, encoding="utf-8") as f:
        nb = json.load(f)
    cells = ["".join(c["source"]) if isinstance(c.get("source"), list) else str(c.get("source", ""))
             for c in nb.get("cells", []) if isinstance(c, dict) and c.get("cell_type") == "code"]
    out: dict[str, Any] = {"errors": [], "timeouts": [], "status": "ok"}
    config = Config()
    config.HistoryManager.hist_file = ":memory:"  # (as the kernel runner: no history file)
    shell = InteractiveShell.instance(config=config)  # (made before the hook: it copies its profile files)
    exec(compile(GUARD, "<grading sandbox>", "exec"), {})
    signal.signal(signal.SIGALRM, _alarm)
    status = "ok"
    for number, source in enumerate(cells, start=1):
        signal.setitimer(signal.ITIMER_REAL, cell_timeout)
        try:
            run = shell.run_cell(source, store_history=False, silent=False)
            error = run.error_before_exec or run.error_in_exec
        except KeyboardInterrupt as exc:  # the alarm came outside the cell's own code
            error = exc
        except BaseException as exc:  # the shell itself failed
            error, status = exc, f"{type(exc).__name__}: {exc}"[:300]
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        if isinstance(error, KeyboardInterrupt):
            out["timeouts"].append(number)
        elif error is not None:
            out["errors"].append({"cell": number, "ename": type(error).__name__[:80], "evalue": str(error)[:300]})
        _write(result, out)
        if status != "ok":
            out["status"] = status
            break
    if _in_sandbox():
        out["strays"], out["left_files"] = _strays(), _left_files()
    sys.stdout.flush()
    _write(result, out)


def _write(result: str, out: dict[str, Any]) -> None:
    tmp = result + ".part"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(out, f)
    os.replace(tmp, result)


def _in_sandbox() -> bool:
    """Whether this runs in make grade's bubblewrap sandbox (its own PID namespace, bwrap as process 1)."""
    try:
        with open("/proc/1/cmdline", "rb") as f:
            return f.read().split(b"\0")[0].endswith(b"bwrap")
    except OSError:
        return False


def _strays() -> list[str]:
    """Processes still running after the last cell, but the sandbox's own (bwrap's init, process 1, and the
    program that holds the sandbox open, process 2) and this one: what the notebook left, each as its
    command line."""
    out = []
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) not in (1, 2, os.getpid()):
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


if __name__ == "__main__":  # (without isolation, UNSAFE=1: started afresh)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]))
