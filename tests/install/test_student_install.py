"""A student's install, made as a student makes it, and used as a student uses it.

1. A wheel is built from the checkout (a copy of ``pyproject.toml`` and ``lib/``:
   nothing of the checkout is importable afterwards).
2. A fresh venv (only Python and pip) gets the one documented command,
   ``pip install "<wheel>[student]"`` (with ``-c constraints.txt``: the tested
   versions, which the pip cache holds). Timed; the venv is measured (bytes of
   its files and disk blocks used) against the 500 MB budget, its packages
   counted, and none may come from the test stack.
3. Every student notebook (``python -m tools.make_exercises``) runs in that
   venv's kernel, from a folder outside the checkout: every check cell shows a
   verdict, and the same checker calls every exercise's reference answer correct.
4. ``jupyter lab`` of that venv, driven by Chromium, mounts a live view from the
   installed wheel (its JavaScript read from the wheel's
   ``jacobians/widgets/live``), and the view and the kernel agree both ways.
5. A second fresh venv gets the bare wheel: numpy and nothing else; the library
   works, and ``import course`` says which extra it needs.

The closing note (conftest.py) prints the time, the size and the package count.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import jacobians as jac

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
BUDGET_BYTES = 500 * 10**6  # the student venv, in bytes of its files (see test_the_student_venv_fits_the_budget)
SEED = "s1234567"

#: what [student] must bring (distribution names, normalised)
NEEDED = {"jacobians", "numpy", "sympy", "matplotlib", "ipython", "ipywidgets", "anywidget", "jupyterlab",
          "ipykernel", "jupytext"}
#: what it must not: the test stack, the static checks, the book build, the reference libraries
FORBIDDEN = {"pytest", "pytest-cov", "pytest-xdist", "coverage", "hypothesis", "nbval", "playwright", "mypy", "ruff",
             "jupyter-book", "sphinx", "myst-nb", "pin", "roboticstoolbox-python", "spatialmath-python",
             "modern-robotics", "scipy"}


def _clean_env(**extra: str) -> dict[str, str]:
    """The environment of a student's shell: nothing that points Python at the checkout or another venv."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}
    env.update(extra)
    return env


def _run(cmd: list[str], **kw) -> subprocess.CompletedProcess:
    out = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if out.returncode != 0:
        raise AssertionError(f"{' '.join(map(str, cmd))} failed ({out.returncode}):\n{out.stdout[-3000:]}\n"
                             f"{out.stderr[-3000:]}")
    return out


def _norm(name: str) -> str:
    return name.lower().replace("_", "-").replace(".", "-")


def _venv(path: Path) -> Path:
    _run([sys.executable, "-m", "venv", str(path)])  # venv uses the base interpreter, not this venv's
    return path / "bin" / "python"


def _site_packages(python: Path) -> Path:
    out = _run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], env=_clean_env())
    return Path(out.stdout.strip())


def _packages(python: Path) -> dict[str, str]:
    out = _run([str(python), "-m", "pip", "list", "--format=json", "--disable-pip-version-check"], env=_clean_env())
    return {_norm(p["name"]): p["version"] for p in json.loads(out.stdout)}


def _size(folder: Path) -> tuple[int, int, int]:
    """Bytes of the files, bytes of disk blocks they use, number of files (symlinks not followed)."""
    size = blocks = n = 0
    for dirpath, _dirs, files in os.walk(folder):
        for f in files:
            st = os.lstat(os.path.join(dirpath, f))
            size += st.st_size
            blocks += st.st_blocks * 512
            n += 1
    return size, blocks, n


@pytest.fixture(scope="module")
def work(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("student-install")


@pytest.fixture(scope="module")
def wheel(work) -> Path:
    """A wheel of the checkout, built from a copy (the build writes build/ and *.egg-info where it runs)."""
    src = work / "src"
    src.mkdir()
    shutil.copy2(ROOT / "pyproject.toml", src / "pyproject.toml")
    shutil.copytree(ROOT / "lib", src / "lib", ignore=shutil.ignore_patterns("__pycache__", "*.egg-info", "*.pyc"))
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(work / "dist"),
          str(src)], env=_clean_env())
    (built,) = (work / "dist").glob("jacobians-*.whl")
    return built


@pytest.fixture(scope="module")
def numpy_only(work, wheel):
    """A second venv with the bare wheel, installed in the background while the student venv is made."""
    python = _venv(work / "bare")
    proc = subprocess.Popen([str(python), "-m", "pip", "install", "-q", "--disable-pip-version-check", str(wheel),
                             "-c", str(ROOT / "constraints.txt")], env=_clean_env(), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    return python, proc


@pytest.fixture(scope="module")
def student(work, wheel, numpy_only, note) -> Path:
    """The student's venv: ``python -m venv``, then the one documented pip command. Returns its Python."""
    venv = work / "venv"
    python = _venv(venv)
    start = time.perf_counter()
    _run([str(python), "-m", "pip", "install", "-q", "--disable-pip-version-check", f"{wheel}[student]",
          "-c", str(ROOT / "constraints.txt")], env=_clean_env())
    seconds = time.perf_counter() - start
    size, blocks, files = _size(venv)
    packages = _packages(python)
    note["install command"] = f'pip install "{wheel.name}[student]" -c constraints.txt (in a fresh venv)'
    note["install time"] = f"{seconds:.0f} s (pip, from the pip cache; 2 cores shared with the other jobs)"
    note["venv size"] = (f"{size / 1e6:.0f} MB in {files} files (budget {BUDGET_BYTES / 1e6:.0f} MB); "
                         f"{blocks / 1e6:.0f} MB of disk blocks on this file system")
    note["packages"] = f"{len(packages)} distributions (pip list, pip and setuptools included)"
    return python


def test_student_install_brings_the_course_and_nothing_of_the_test_stack(student):
    packages = _packages(student)
    assert NEEDED <= set(packages), f"missing from [student]: {sorted(NEEDED - set(packages))}"
    assert not FORBIDDEN & set(packages), f"[student] pulled in {sorted(FORBIDDEN & set(packages))}"


def test_the_student_venv_fits_the_budget(student):
    """The budget counts the bytes of the venv's files (what the install writes, the bytecode pip compiles
    included); the disk blocks they occupy depend on the file system's block size and are printed too."""
    size, _blocks, _files = _size(student.parent.parent)
    assert size <= BUDGET_BYTES, f"the student venv holds {size / 1e6:.0f} MB, over the {BUDGET_BYTES / 1e6:.0f} MB budget"


def test_the_course_is_imported_from_the_wheel_with_its_live_views(student, work):
    code = ("import json, jacobians, course\nfrom jacobians.widgets.live import live_dir\n"
            "from course import exercises\n"
            "print(json.dumps({'jacobians': jacobians.__file__, 'course': course.__file__, 'live': str(live_dir()),"
            " 'n': len(exercises.exercise_ids())}))")
    elsewhere = work / "elsewhere"
    elsewhere.mkdir(exist_ok=True)
    got = json.loads(_run([str(student), "-c", code], cwd=elsewhere, env=_clean_env()).stdout)
    site = _site_packages(student)
    for key in ("jacobians", "course", "live"):
        assert Path(got[key]).is_relative_to(site), (key, got[key])
    def modules(live: Path) -> set[str]:  # the views' ES modules and deck styles, in their folders
        return {p.relative_to(live).as_posix() for p in live.rglob("*") if p.suffix in (".js", ".css")}

    shipped = modules(Path(got["live"]))
    in_checkout = modules(ROOT / "lib" / "jacobians" / "widgets" / "live")
    assert shipped == in_checkout and {"kinematics.js", "planar_explorer/view.js", "story/deck.css"} <= shipped
    assert got["n"] == len(__import__("course.exercises", fromlist=["x"]).exercise_ids())


def test_every_student_notebook_runs_every_check(student, work, note):
    notebooks = work / "notebooks"
    _run([sys.executable, "-m", "tools.make_exercises", str(notebooks)], cwd=ROOT)
    sources = sorted((ROOT / "exercises").glob("[0-9][0-9]_*.md"))
    assert len(list(notebooks.glob("*.ipynb"))) == len(sources) == 12
    out = work / "notebook_results.json"
    start = time.perf_counter()
    _run([str(student), str(HERE / "run_student_notebooks.py"), str(notebooks), SEED, str(out)], cwd=notebooks,
         env=_clean_env(JUPYTER_PATH=str(work / "jupyter-data"), JUPYTER_DATA_DIR=str(work / "jupyter-data"),
                        JUPYTER_CONFIG_DIR=str(work / "jupyter-config"), IPYTHONDIR=str(work / "ipython")))
    results = json.loads(out.read_text(encoding="utf-8"))
    site = _site_packages(student)
    from course import exercises

    every = set(exercises.exercise_ids())
    seen: set[str] = set()
    for name, r in results.items():
        assert r["error"] is None, f"{name}: {r['error']}"
        assert Path(r["where"]["jacobians"]).is_relative_to(site), (name, r["where"])
        assert Path(r["where"]["course"]).is_relative_to(site), (name, r["where"])
        assert r["exercises"], f"{name}: no check cell"
        assert r["shown"] == r["exercises"], f"{name}: check cells without a verdict: {set(r['exercises']) - set(r['shown'])}"
        assert r["reference_correct"] == r["exercises"], name
        seen |= set(r["exercises"])
    assert seen == every, f"exercises with no check cell in any student notebook: {sorted(every - seen)}"
    note["student notebooks"] = (f"{len(results)} notebooks, {len(seen)} check cells run (and each reference answer "
                                 f"checked correct) in {time.perf_counter() - start:.0f} s")


def test_a_live_view_mounts_in_jupyterlab_from_the_wheel(student, work, browser_context, note):
    import labdriver as lab  # tests/browser: how a headless JupyterLab is driven

    nbdir = work / "lab"
    nbdir.mkdir()
    cells = [
        "import json, jacobians\n"
        "from jacobians.widgets.live import PlanarExplorer, live_dir\n"
        "w = PlanarExplorer('planar_2r', theta=[0.3, 1.2])\n"
        "def dump(change=None):\n"
        "    with open('py_state.json', 'w') as f:\n"
        "        json.dump({'theta': list(map(float, w.theta)), 'J': w.J.tolist(), 'lib': jacobians.__file__,\n"
        "                   'live': str(live_dir())}, f)\n"
        "w.observe(dump, names=['theta', 'frame'])\n"
        "dump()\n"
        "w",
        "w.theta = [-0.7, 0.4]",
    ]
    (nbdir / "live.ipynb").write_text(json.dumps(lab.notebook(cells)), encoding="utf-8")
    start = time.perf_counter()
    with lab.running_lab(student, nbdir, work, _clean_env()) as (base, token):
        page = browser_context.new_page()
        try:
            errors: list[str] = []
            page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
            lab.open_notebook(page, base, token, "live.ipynb")
            chain = jac.robots.planar_2r()
            lab.run_cell(page, 0)
            el = page.wait_for_selector(".jp-OutputArea .jac-live[data-view=planar_explorer]", state="attached", timeout=120_000)
            got = el.evaluate(lab.READ_PLANAR)
            assert np.allclose(got["theta"], [0.3, 1.2])
            assert np.abs(np.array(got["table"]) - jac.space_jacobian(chain, [0.3, 1.2])).max() <= lab.HALF_ULP
            state = lab.wait_file(nbdir / "py_state.json", lambda s: np.allclose(s["theta"], [0.3, 1.2]))
            site = _site_packages(student)
            assert Path(state["lib"]).is_relative_to(site) and Path(state["live"]).is_relative_to(site), state
            # the view responds: a key on the θ1 slider reaches the kernel, which computes J there
            el.query_selector("input.jl-theta").focus()
            page.keyboard.press("ArrowRight")
            state = lab.wait_file(nbdir / "py_state.json", lambda s: abs(s["theta"][0] - 0.31) < 1e-9)
            assert np.allclose(state["J"], jac.space_jacobian(chain, [0.31, 1.2]), atol=1e-12)
            # and the kernel moves the view
            lab.run_cell(page, 1)
            page.wait_for_function(lab.with_data("data.theta[0] === -0.7"), arg=el, timeout=30_000)
            got = el.evaluate(lab.READ_PLANAR)
            assert np.abs(np.array(got["table"]) - jac.space_jacobian(chain, [-0.7, 0.4])).max() <= lab.HALF_ULP
            assert [e for e in errors if "jac" in e.lower() or "live" in e.lower() or "kinematics" in e.lower()] == []
            note["JupyterLab"] = (f"a live view mounted from the wheel, answered a key and a kernel assignment "
                                  f"({time.perf_counter() - start:.0f} s with the server's start)")
        finally:
            page.close()


def test_the_numeric_library_installs_alone_with_numpy_only(numpy_only, work):
    python, proc = numpy_only
    output, _ = proc.communicate(timeout=900)
    assert proc.returncode == 0, output
    assert set(_packages(python)) - {"pip", "setuptools"} == {"jacobians", "numpy"}
    code = ("import json, jacobians as jac\n"
            "J = jac.space_jacobian(jac.robots.planar_2r(), [0.3, 0.4])\n"
            "try:\n    import course\n    err = None\nexcept ImportError as e:\n    err = str(e)\n"
            "print(json.dumps({'J': J.tolist(), 'err': err}))")
    elsewhere = work / "elsewhere"
    elsewhere.mkdir(exist_ok=True)
    got = json.loads(_run([str(python), "-c", code], cwd=elsewhere, env=_clean_env()).stdout)
    # the same code and numpy in both processes; 1e-15 is about 2 ulps of the largest entry (|J| <= reach = 2 m)
    assert np.allclose(got["J"], jac.space_jacobian(jac.robots.planar_2r(), [0.3, 0.4]), rtol=0, atol=1e-15)
    assert got["err"] is not None and 'jacobians[course]' in got["err"] and "sympy" in got["err"], got["err"]
