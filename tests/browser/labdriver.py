"""A headless JupyterLab driven from Chromium: start a server, open a notebook, run a cell, read a file it wrote.

Used by tests/browser/test_live_lab.py (this checkout's venv) and tests/install/test_student_install.py (a
student's venv made from the wheel). The server runs with a random token, ``expose_app_in_browser`` (so a page
can run cells through ``window.jupyterapp``), no news and no update check (nothing leaves 127.0.0.1), and its
own config, runtime, data and IPython folders under ``work``.
"""

from __future__ import annotations

import json
import os
import secrets
import socket
import subprocess
import time
import urllib.request
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from live_data import with_data

#: A matrix entry shown with two decimals is within half a unit of the last place of the exact value.
HALF_ULP = 0.005 + 1e-9

#: the planar views' state as the page shows it: angles, frame, and the Jacobian table's numbers
READ_PLANAR = with_data("""{
  theta: data.theta, frame: data.frame,
  table: [...el.querySelectorAll("table.jl-matrix tbody tr")].map(
    (tr) => [...tr.querySelectorAll("td")].map((td) => Number(td.textContent.replace("\\u2212", "-")))),
}""")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def notebook(cells: list[str]) -> dict:
    """An nbformat 4 notebook of code cells (no outputs) on the python3 kernel."""
    return {"cells": [{"cell_type": "code", "execution_count": None, "id": f"c{i}", "metadata": {}, "outputs": [],
                       "source": src} for i, src in enumerate(cells)],
            "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"}},
            "nbformat": 4, "nbformat_minor": 5}


@contextmanager
def running_lab(python: Path | str, notebook_dir: Path, work: Path, env: dict[str, str],
                start_timeout: float = 120) -> Iterator[tuple[str, str]]:
    """``python -m jupyterlab`` serving ``notebook_dir``; yields (base URL, token). The server's log goes to
    ``work/lab.log`` (its tail is in the error if it does not start); it is stopped on exit."""
    port, token = free_port(), secrets.token_hex(16)
    cmd = [str(python), "-m", "jupyterlab", "--no-browser", f"--port={port}", "--ip=127.0.0.1",
           f"--IdentityProvider.token={token}", "--LabApp.expose_app_in_browser=True",
           "--ServerApp.disable_check_xsrf=False", f"--notebook-dir={notebook_dir}", "--LabApp.news_url=",
           "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate", "--ServerApp.open_browser=False"]
    if os.geteuid() == 0:
        cmd.append("--allow-root")
    env = dict(env, JUPYTER_CONFIG_DIR=str(work / "lab-config"), JUPYTER_RUNTIME_DIR=str(work / "lab-runtime"),
               JUPYTER_DATA_DIR=str(work / "lab-data"), IPYTHONDIR=str(work / "lab-ipython"))
    base = f"http://127.0.0.1:{port}"
    with open(work / "lab.log", "wb") as log:
        proc = subprocess.Popen(cmd, cwd=notebook_dir, env=env, stdout=log, stderr=subprocess.STDOUT)
        try:
            deadline = time.time() + start_timeout
            while True:
                try:
                    urllib.request.urlopen(f"{base}/api/status?token={token}", timeout=2).read()
                    break
                except OSError:
                    if proc.poll() is not None or time.time() > deadline:
                        raise AssertionError("jupyter lab did not start:\n"
                                             + (work / "lab.log").read_text(errors="replace")[-3000:]) from None
                    time.sleep(0.5)
            yield base, token
        finally:
            proc.terminate()
            try:
                proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


def open_notebook(page: Any, base: str, token: str, name: str) -> None:
    """Open ``name`` in a workspace of its own (the default one would also restore another test's notebook)
    and wait until its kernel is there."""
    page.set_viewport_size({"width": 1280, "height": 900})
    page.goto(f"{base}/lab/workspaces/{name.split('.')[0]}/tree/{name}?token={token}", wait_until="load")
    page.wait_for_function("(name) => window.jupyterapp && window.jupyterapp.shell.currentWidget"
                           " && window.jupyterapp.shell.currentWidget.sessionContext"
                           " && window.jupyterapp.shell.currentWidget.context.path === name", arg=name, timeout=90_000)
    page.wait_for_function("() => window.jupyterapp.shell.currentWidget.sessionContext.session?.kernel",
                           timeout=90_000)


def run_cell(page: Any, index: int) -> None:
    """Run cell ``index`` of the open notebook (returns when the command is sent, not when the cell ends)."""
    page.evaluate("""async (i) => {
      const app = window.jupyterapp;
      const panel = app.shell.currentWidget;
      await panel.sessionContext.ready;
      panel.content.activeCellIndex = i;
      await app.commands.execute("notebook:run-cell");
    }""", index)


def wait_file(path: Path, check: Callable[[Any], bool], timeout: float = 30.0) -> Any:
    """The JSON a kernel wrote to ``path``, once ``check`` holds for it."""
    deadline = time.time() + timeout
    last = None
    while time.time() < deadline:
        try:
            last = json.loads(path.read_text(encoding="utf-8"))
            if check(last):
                return last
        except (OSError, ValueError):
            pass
        time.sleep(0.2)
    raise AssertionError(f"{path.name} never satisfied the check; last {last}")
