"""Run every student notebook of a folder in THIS Python (the student's install), as a student would.

Run by tests/install/test_student_install.py with the student venv's Python:

    python run_student_notebooks.py NOTEBOOK_DIR SEED OUT.json

Only the standard library and what ``jacobians[student]`` installs (nbformat,
nbclient, ipykernel) are used. Each notebook is executed from the top in a
kernel of this Python, with three changes:

* the set-up line ``SEED = "student-id"`` gets ``SEED``, as a student fills in an ID;
* a first cell records where ``jacobians`` and ``course`` were imported from
  (the test checks that it is the venv's site-packages, not the checkout);
* after every check cell (``exercises.check("id", answer, seed=SEED)``, run on
  the untouched ``answer = None``), a cell asserts that the check returned an
  "empty" verdict without raising, and that the same checker calls the
  exercise's reference answer (``exN.solution()``) correct.

Writes, per notebook: the exercise ids whose check cell ran and showed a
verdict, those whose reference answer was called correct, the seconds taken,
and the error, if a cell raised.
"""

from __future__ import annotations

import json
import os
import re
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

SEED_LINE = re.compile(r'^SEED = "student-id"', re.M)
LOAD = re.compile(r'^(\w+)\s*=\s*exercises\.load\("(\w+)", seed=SEED\)', re.M)
CHECK = re.compile(r'^exercises\.check\("(\w+)", answer, seed=SEED\)$')

WHERE = ("import json as _json, sys as _sys, jacobians as _jac, course as _course\n"
         "print('WHERE ' + _json.dumps({'prefix': _sys.prefix, 'jacobians': _jac.__file__, "
         "'course': _course.__file__}))")


def prepare(nb: nbformat.NotebookNode, seed: str) -> tuple[nbformat.NotebookNode, list[str]]:
    names: dict[str, str] = {}
    cells = [nbformat.v4.new_code_cell(WHERE)]
    checked: list[str] = []
    for cell in nb.cells:
        cells.append(cell)
        if cell.cell_type != "code":
            continue
        cell.source = SEED_LINE.sub(f"SEED = {json.dumps(seed)}", cell.source)
        for m in LOAD.finditer(cell.source):
            names[m.group(2)] = m.group(1)
        m = CHECK.match(cell.source.strip())
        if m:
            eid = m.group(1)
            checked.append(eid)
            cell.metadata["student_check"] = eid
            cells.append(nbformat.v4.new_code_cell(
                f"_student = _  # the verdict the check cell above displayed\n"
                f"assert _student.kind == 'empty' and not _student.correct, _student\n"
                f"_ref = exercises.check({eid!r}, {names[eid]}.solution(), seed=SEED)\n"
                f"assert _ref.correct, _ref.message\n"
                f"print('REFERENCE-CORRECT {eid}')"))
    nb.cells = cells
    return nb, checked


def run(path: Path, seed: str) -> dict:
    nb, checked = prepare(nbformat.read(path, as_version=4), seed)
    out: dict = {"exercises": checked, "shown": [], "reference_correct": [], "where": None, "error": None}
    start = time.perf_counter()
    client = NotebookClient(nb, timeout=180, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    try:
        client.execute()
    except CellExecutionError as exc:
        out["error"] = str(exc)[-2000:]
    except Exception as exc:  # a kernel that died: report it, go on with the next notebook
        out["error"] = f"{type(exc).__name__}: {exc}"[-2000:]
    out["seconds"] = round(time.perf_counter() - start, 1)
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        texts = [o.get("text", "") for o in cell.get("outputs", []) if o.get("output_type") == "stream"]
        for line in "".join(texts).splitlines():
            if line.startswith("WHERE "):
                out["where"] = json.loads(line[len("WHERE "):])
            elif line.startswith("REFERENCE-CORRECT "):
                out["reference_correct"].append(line.split()[1])
        eid = cell.metadata.get("student_check")
        if eid and any(o.get("output_type") == "execute_result" and "text/html" in o.get("data", {})
                       for o in cell.get("outputs", [])):
            out["shown"].append(eid)
    return out


def main(folder: Path, seed: str, dest: Path) -> int:
    paths = sorted(folder.glob("*.ipynb"))
    with ProcessPoolExecutor(max_workers=min(2, os.cpu_count() or 1)) as pool:  # a kernel each, two at a time
        results = dict(zip((p.name for p in paths), pool.map(run, paths, [seed] * len(paths)), strict=True))
    dest.write_text(json.dumps(results, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), sys.argv[2], Path(sys.argv[3])))
