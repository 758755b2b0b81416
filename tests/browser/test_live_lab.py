"""The live views as anywidgets in a real JupyterLab, headless: Python and the view agree both ways.

Starts ``jupyter lab`` (this venv, a fresh temporary notebook folder and
Jupyter config/runtime folders, a random token, ``expose_app_in_browser`` so
the test can run cells), opens a notebook in Chromium and runs its cells one
by one:

1. ``w = PlanarExplorer("planar_2r", theta=[0.3, 1.2])``, then ``w``: the view
   (the same ``lib/jacobians/widgets/live/planar_explorer/view.js``, its ``./kinematics.js``
   imports inlined as data: URLs) renders in the output, and shows the
   library's Jacobian at θ;
2. a key press on the view's θ₁ slider (view -> Python): a traitlet observer in
   the kernel writes ``w.theta`` and ``w.J`` (the library's) to a file, which
   must hold θ₁ + 0.01 and the Jacobian the view shows;
3. ``w.theta = [-0.7, 0.4]; w.frame = "body"`` (Python -> view): the view redraws
   at those angles with the library's body Jacobian;
4. the resolved-rate view: ``ResolvedRate(...)``, a step key in the view, and
   ``r.step`` in Python agree, and the arm drawn is the library run's;
5. in a second notebook the two 3-D views (``jacobians.widgets.live_spatial``):
   ``ColumnsExplorer`` and ``GimbalLock`` render the library's Jacobians; a
   key on a slider in the view moves ``w.theta`` in the kernel and ``w.J`` (and
   ``Jb``, ``Ja``) follow; ``w.theta = ...`` (and ``g.rep = ...``) from Python
   redraws the view with the library's numbers, including J_a at the lock.

No request leaves 127.0.0.1, no console error from the views.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import sys
import tempfile
from pathlib import Path
from urllib.parse import urlsplit

import numpy as np
import pytest
from labdriver import HALF_ULP, READ_PLANAR, notebook, running_lab
from labdriver import open_notebook as _open
from labdriver import run_cell as _run_cell
from labdriver import wait_file as _wait_file
from live_data import live_data, with_data

import jacobians as jac

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = ROOT / "_build" / "test-artifacts" / "lab"  # screenshots of the 3-D views in JupyterLab (not committed)

CELLS = [
    # 0: set-up, and an observer that writes the Python side's state to a file on every change
    "import json, numpy as np\n"
    "from jacobians.widgets.live import PlanarExplorer, ResolvedRate\n"
    "w = PlanarExplorer('planar_2r', theta=[0.3, 1.2])\n"
    "def dump(change=None):\n"
    "    with open('py_state.json', 'w') as f:\n"
    "        json.dump({'theta': list(map(float, w.theta)), 'frame': w.frame, 'J': w.J.tolist()}, f)\n"
    "w.observe(dump, names=['theta', 'frame'])\n"
    "dump()\n"
    "w",
    # 1: Python -> view
    "w.theta = [-0.7, 0.4]\nw.frame = 'body'",
    # 2: the resolved-rate view
    "r = ResolvedRate('planar_2r', path='circle', method='dls', damping=0.05)\n"
    "def dump_r(change=None):\n"
    "    with open('py_rr.json', 'w') as f:\n"
    "        json.dump({'step': int(r.step), 'theta': r.theta.tolist()}, f)\n"
    "r.observe(dump_r, names=['step'])\n"
    "r",
    # 3: Python -> resolved-rate view
    "r.step = 40",
]

CELLS_3D = [
    # 0: the columns explorer, and an observer writing the kernel's state (theta, J_s, J_b) to a file
    "import json, numpy as np\n"
    "from jacobians.widgets.live_spatial import ColumnsExplorer, GimbalLock\n"
    "c = ColumnsExplorer('spatial_5r', theta=[0.3, -0.5, 0.9, 0.4, 0.3], column=3)\n"
    "def dump_c(change=None):\n"
    "    with open('py_cols.json', 'w') as f:\n"
    "        json.dump({'theta': list(map(float, c.theta)), 'column': int(c.column), 'Js': c.Js.tolist(),\n"
    "                   'Jb': c.Jb.tolist(), 'J': c.J.tolist()}, f)\n"
    "c.observe(dump_c, names=['theta', 'column'])\n"
    "dump_c()\n"
    "c",
    # 1: Python -> columns view
    "c.theta = [-0.2, 0.7, -1.1, 0.5, 1.0]",
    # 2: the gimbal-lock view (theta in rad; the view's sliders in degrees)
    "g = GimbalLock('zyz_wrist', theta=[np.radians(30), np.radians(45), 0.0], rep='zyx')\n"
    "def dump_g(change=None):\n"
    "    with open('py_gimbal.json', 'w') as f:\n"
    "        json.dump({'theta': list(map(float, g.theta)), 'wrist': g.wrist, 'rep': g.rep, 'J': g.J.tolist(),\n"
    "                   'Ja': g.Ja.tolist(), 'B': g.B.tolist()}, f)\n"
    "g.observe(dump_g, names=['theta', 'wrist', 'rep'])\n"
    "dump_g()\n"
    "g",
    # 3: Python -> gimbal view: other angles and ZYZ coordinates
    "g.theta = [0.2, 1.2, -0.4]\ng.rep = 'zyz'",
    # 4: Python -> gimbal view: the ZYX lock (theta2 = 90 degrees), where J_a does not exist
    "g.rep = 'zyx'\ng.theta = [np.radians(30), np.pi / 2, 0.0]",
]

READ_TABLES = with_data("""(() => {
  const rows = (sel) => [...el.querySelectorAll(sel + " tbody tr")].map((tr) => [...tr.querySelectorAll("td")]
    .map((c) => c.textContent));
  return { theta: data.theta, rep: data.rep || null, level: data.level || null,
    Js: rows("table.jl-space"), Jb: rows("table.jl-body"), B: rows("table.jl-B"), J: rows("table.jl-J"),
    Ja: rows("table.jl-Ja") };
})()""")

@pytest.fixture(scope="module")
def lab():
    """This venv's JupyterLab on a temporary folder with the two notebooks: (base URL, token, folder)."""
    work = Path(tempfile.mkdtemp(prefix="live-lab-"))
    (work / "nb").mkdir()
    (work / "nb" / "live.ipynb").write_text(json.dumps(notebook(CELLS)), encoding="utf-8")
    (work / "nb" / "live3d.ipynb").write_text(json.dumps(notebook(CELLS_3D)), encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=f"{ROOT / 'lib'}{os.pathsep}{ROOT}")
    try:
        with running_lab(sys.executable, work / "nb", work, env) as (base, token):
            yield base, token, work / "nb"
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _numbers(rows: list[list[str]]) -> np.ndarray:
    return np.array([[float(c.replace("\u2212", "-")) for c in row] for row in rows])


def test_python_and_the_view_agree_both_ways(lab, browser_context):
    base, token, nb = lab
    page = browser_context.new_page()
    errors: list[str] = []
    requests: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("request", lambda r: requests.append(r.url))
    try:
        _open(page, base, token, "live.ipynb")
        chain = jac.robots.planar_2r()
        # 1. the widget renders from Python's state
        _run_cell(page, 0)
        el = page.wait_for_selector(".jp-OutputArea .jac-live[data-view=planar_explorer]", state="attached", timeout=90_000)
        got = el.evaluate(READ_PLANAR)
        assert np.allclose(got["theta"], [0.3, 1.2]) and got["frame"] == "space"
        assert np.abs(np.array(got["table"]) - jac.space_jacobian(chain, [0.3, 1.2])).max() <= HALF_ULP
        _wait_file(nb / "py_state.json", lambda s: np.allclose(s["theta"], [0.3, 1.2]))
        # 2. view -> Python: a key on the slider of θ1
        slider = el.query_selector("input.jl-theta")
        slider.focus()
        page.keyboard.press("ArrowRight")  # the view sets data-lm-suppress-shortcuts: the key reaches the slider
        page.wait_for_function(with_data("data.theta[0] > 0.305"), arg=el, timeout=10_000)
        state = _wait_file(nb / "py_state.json", lambda s: abs(s["theta"][0] - 0.31) < 1e-9)
        assert state["theta"][1] == pytest.approx(1.2)
        shown = np.array(el.evaluate(READ_PLANAR)["table"])
        assert np.abs(shown - np.array(state["J"])).max() <= HALF_ULP           # the library's w.J is what is shown
        assert np.allclose(state["J"], jac.space_jacobian(chain, [0.31, 1.2]), atol=1e-12)
        # 3. Python -> view
        _run_cell(page, 1)
        page.wait_for_function(with_data("data.frame === 'body' && data.theta[0] === -0.7"),
                               arg=el, timeout=30_000)
        got = el.evaluate(READ_PLANAR)
        assert np.allclose(got["theta"], [-0.7, 0.4])
        assert np.abs(np.array(got["table"]) - jac.body_jacobian(chain, [-0.7, 0.4])).max() <= HALF_ULP
        state = _wait_file(nb / "py_state.json", lambda s: s["frame"] == "body")
        assert np.allclose(state["J"], jac.body_jacobian(chain, [-0.7, 0.4]), atol=1e-12)
        # 4. the resolved-rate view: a key in the view moves Python's step; Python's step moves the view
        _run_cell(page, 2)
        rr = page.wait_for_selector(".jp-OutputArea .jac-live[data-view=resolved_rate]", state="attached", timeout=60_000)
        rr.query_selector("button.jr-fwd").focus()
        page.keyboard.press(".")
        rstate = _wait_file(nb / "py_rr.json", lambda s: s["step"] == 1)
        assert np.allclose(live_data(rr)["theta"], rstate["theta"], atol=1e-9)
        _run_cell(page, 3)
        page.wait_for_function(with_data("data.step === 40"), arg=rr, timeout=30_000)
        rstate = _wait_file(nb / "py_rr.json", lambda s: s["step"] == 40)
        assert np.allclose(live_data(rr)["theta"], rstate["theta"], atol=1e-9)
        host = urlsplit(base).netloc
        assert [u for u in requests if not u.startswith(("data:", "blob:")) and urlsplit(u).netloc != host] == []
        assert [e for e in errors if "jac" in e.lower() or "live" in e.lower() or "kinematics" in e.lower()] == []
    finally:
        page.close()


def _shown_close(rows: list[list[str]], ref, tol: float = HALF_ULP) -> bool:
    shown = _numbers(rows)
    ref = np.asarray(ref, dtype=float)
    return shown.shape == ref.shape and float(np.abs(shown - ref).max()) <= tol


def test_3d_views_python_and_the_view_agree_both_ways(lab, browser_context):
    base, token, nb = lab
    page = browser_context.new_page()
    errors: list[str] = []
    requests: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("request", lambda r: requests.append(r.url))
    try:
        _open(page, base, token, "live3d.ipynb")
        arm = jac.robots.spatial_5r()
        th0 = [0.3, -0.5, 0.9, 0.4, 0.3]
        # columns explorer: renders the library's J_s and J_b from Python's state
        _run_cell(page, 0)
        el = page.wait_for_selector(".jp-OutputArea .jac-live[data-view=columns_explorer]", state="attached", timeout=90_000)
        got = el.evaluate(READ_TABLES)
        assert np.allclose(got["theta"], th0)
        assert _shown_close(got["Js"], jac.space_jacobian(arm, th0)) and _shown_close(got["Jb"], jac.body_jacobian(arm, th0))
        _wait_file(nb / "py_cols.json", lambda s: np.allclose(s["theta"], th0))
        # view -> Python: a key on the slider of theta_4 (0.01 rad a step)
        el.query_selector_all("input.jl-theta")[3].focus()
        page.keyboard.press("ArrowRight")
        page.wait_for_function(with_data("data.theta[3] > 0.405"), arg=el, timeout=10_000)
        state = _wait_file(nb / "py_cols.json", lambda s: abs(s["theta"][3] - 0.41) < 1e-9)
        th1 = [0.3, -0.5, 0.9, 0.41, 0.3]
        assert np.allclose(state["theta"], th1, atol=1e-12)
        assert np.allclose(state["Js"], jac.space_jacobian(arm, th1), atol=1e-12)
        assert np.allclose(state["Jb"], jac.body_jacobian(arm, th1), atol=1e-12) and state["J"] == state["Js"]
        got = el.evaluate(READ_TABLES)
        assert _shown_close(got["Js"], state["Js"]) and _shown_close(got["Jb"], state["Jb"])  # the kernel's w.J is shown
        # theta_4 moved: the columns of J_s after 4 and of J_b before 4 changed
        assert live_data(el)["changedS"] == [5] and live_data(el)["changedB"] == [1, 2, 3]
        # Python -> view
        _run_cell(page, 1)
        th2 = [-0.2, 0.7, -1.1, 0.5, 1.0]
        page.wait_for_function(with_data("data.theta[0] === -0.2"), arg=el, timeout=30_000)
        got = el.evaluate(READ_TABLES)
        assert np.allclose(got["theta"], th2)
        assert _shown_close(got["Js"], jac.space_jacobian(arm, th2)) and _shown_close(got["Jb"], jac.body_jacobian(arm, th2))
        state = _wait_file(nb / "py_cols.json", lambda s: np.allclose(s["theta"], th2))
        assert _shown_close(got["Js"], state["Js"])
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        el.screenshot(path=str(ARTIFACTS / "columns_explorer.png"))

        # gimbal lock: the ZYZ wrist, ZYX coordinates
        wrist = jac.robots.zyz_wrist(0.3)
        _run_cell(page, 2)
        g = page.wait_for_selector(".jp-OutputArea .jac-live[data-view=gimbal_lock]", state="attached", timeout=90_000)
        ga = [math.radians(30), math.radians(45), 0.0]
        got = g.evaluate(READ_TABLES)
        assert np.allclose(got["theta"], ga) and got["rep"] == "zyx"
        assert _shown_close(got["J"], jac.geometric_jacobian(wrist, ga))
        assert _shown_close(got["Ja"], jac.analytic_jacobian(wrist, ga, "zyx"))
        # view -> Python: a key on the slider of theta_2 (0.5 degrees a step)
        g.query_selector_all("input.jl-theta")[1].focus()
        page.keyboard.press("ArrowRight")
        gb = [math.radians(30), math.radians(45.5), 0.0]
        state = _wait_file(nb / "py_gimbal.json", lambda s: abs(s["theta"][1] - gb[1]) < 1e-9)
        assert np.allclose(state["theta"], gb, atol=1e-12)
        assert np.allclose(state["J"], jac.geometric_jacobian(wrist, gb), atol=1e-12)
        assert np.allclose(state["Ja"], jac.analytic_jacobian(wrist, gb, "zyx"), atol=1e-12)
        got = g.evaluate(READ_TABLES)
        assert _shown_close(got["J"], state["J"]) and _shown_close(got["Ja"], state["Ja"])
        assert _shown_close(got["B"], state["B"])
        # Python -> view: other angles, ZYZ coordinates
        _run_cell(page, 3)
        page.wait_for_function(with_data("data.rep === 'zyz' && data.theta[1] === 1.2"),
                               arg=g, timeout=30_000)
        gc = [0.2, 1.2, -0.4]
        got = g.evaluate(READ_TABLES)
        assert _shown_close(got["J"], jac.geometric_jacobian(wrist, gc))
        assert _shown_close(got["Ja"], jac.analytic_jacobian(wrist, gc, "zyz"))
        state = _wait_file(nb / "py_gimbal.json", lambda s: s["rep"] == "zyz" and np.allclose(s["theta"], gc))
        assert _shown_close(got["B"], state["B"])
        # Python -> view: at the ZYX lock J_a does not exist: NaN in the kernel, "—" in the view, J still shown
        _run_cell(page, 4)
        page.wait_for_function(with_data("data.rep === 'zyx' && data.level === 'singular'"), arg=g,
                               timeout=30_000)
        state = _wait_file(nb / "py_gimbal.json", lambda s: s["rep"] == "zyx" and abs(s["theta"][1] - math.pi / 2) < 1e-12)
        assert np.isnan(np.array(state["Ja"], dtype=float)).all()
        got = g.evaluate(READ_TABLES)
        assert all(c == "\u2014" for row in got["Ja"] for c in row) and len(got["Ja"]) == 6
        assert _shown_close(got["J"], state["J"])
        g.screenshot(path=str(ARTIFACTS / "gimbal_lock.png"))
        host = urlsplit(base).netloc
        assert [u for u in requests if not u.startswith(("data:", "blob:")) and urlsplit(u).netloc != host] == []
        assert [e for e in errors if "jac" in e.lower() or "live" in e.lower() or "kinematics" in e.lower()] == []
    finally:
        page.close()
