"""The live planar explorer (``lib/jacobians/widgets/live/planar_explorer/view.js``) in Chromium, no kernel.

On a harness page served from the repository (no book build needed), the view
is mounted from the model that ``_ext/live_views.py`` writes for the book page;
on the built chapter 2 page too, when ``_build/html`` has it. Keyboard input
moves the arm, and the table shows the library's Jacobian at the new angles;
the frame select switches the table; θ₂ = 0 brings the singularity banner and
no NaN; at 390 px nothing overflows; no console error, no foreign request.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from urllib.parse import urlsplit

import bookcheck
import fp_bounds
import live_views
import numpy as np
import pytest
import story_views
from live_data import with_data

import jacobians as jac
from jacobians.plotting import arm_reach

ROOT = Path(__file__).resolve().parents[2]
STEP = 0.01
HALF_ULP = 0.005 + 1e-9  # the table shows 2 decimals

READ_JS = with_data("""{
  theta: data.theta, frame: data.frame, level: data.level, playing: data.playing,
  table: [...el.querySelectorAll("table.jl-matrix tbody tr")].map(
    (tr) => [...tr.querySelectorAll("td")].map((td) => td.textContent)),
  link: el.querySelector("polyline.jl-link").getAttribute("points"),
  ellipse: ["cx", "cy", "rx", "ry", "transform"].map((k) => el.querySelector("ellipse.jl-ellipse").getAttribute(k)),
  force: ["cx", "cy", "rx", "ry", "transform"].map((k) => el.querySelector("ellipse.jl-force").getAttribute(k)),
  clip: el.querySelector("polyline.jl-force-clip").getAttribute("visibility"),
  banner: el.querySelector(".jl-banner").hidden ? null : el.querySelector(".jl-banner").textContent,
  text: el.innerText, markup: el.innerHTML,
}""")

SET_JS = """([el, i, v]) => {
  const s = el.querySelectorAll("input.jl-theta")[i];
  s.value = String(v);
  s.dispatchEvent(new Event("input", { bubbles: true }));
}"""

FIT_JS = """(el) => {
  const box = el.getBoundingClientRect();
  const out = [];
  for (const e of el.querySelectorAll("*")) {
    const r = e.getBoundingClientRect();
    if (r.width && (r.right > box.right + 0.5 || r.left < box.left - 0.5)) out.push(e.tagName + "." + e.className);
  }
  const small = [...el.querySelectorAll("label, output, td, th, caption, p, li, option, select, sub")]
    .filter((e) => e.textContent.trim() && parseFloat(getComputedStyle(e).fontSize) < 14)
    .map((e) => e.tagName + ": " + parseFloat(getComputedStyle(e).fontSize));
  return { overflow: out, small, scroll: el.scrollWidth - el.clientWidth, width: box.width,
           page: document.documentElement.scrollWidth - document.documentElement.clientWidth };
}"""


def _number(cell: str) -> float:
    return float(cell.replace("\u2212", "-"))


def _check_state(el, robot: str) -> dict:
    got = el.evaluate(READ_JS)
    chain = live_views.ROBOTS[robot]()
    theta = np.array(got["theta"])
    if got["frame"] == "analytic":  # the planar arm's (x, y, φ): rows ẋ, ẏ and the ZYX yaw rate of the library's
        J = jac.analytic_jacobian(chain, theta, "zyx")[[3, 4, 0]]
    else:
        J = jac.jacobian(chain, theta, got["frame"])
    shown = np.array([[_number(c) for c in row] for row in got["table"]])
    assert shown.shape == J.shape
    assert np.abs(shown - J).max() <= HALF_ULP, f"table {shown} vs library {J}"
    assert not any(re.fullmatch(r"[-\u2212]0\.00", c) for row in got["table"] for c in row)
    pts = np.array([[float(v) for v in p.split(",")] for p in got["link"].split()])
    assert np.allclose(pts, chain.joint_positions(theta)[:, :2], atol=1e-9)  # the drawn arm
    # the velocity ellipse of J_v at the tool: semi-axes 0.35 σ_i, major axis along U[:, 0] (up to sign)
    sigma, U = jac.analysis.velocity_ellipsoid(jac.geometric_jacobian(chain, theta)[3:5])
    cx, cy, rx, ry = (float(v) for v in got["ellipse"][:4])
    angle = float(re.fullmatch(r"rotate\((\S+) \S+ \S+\)", got["ellipse"][4]).group(1))
    assert np.allclose([cx, cy], pts[-1], atol=1e-9)
    assert rx == pytest.approx(0.35 * sigma[0], abs=1e-9) and ry == pytest.approx(max(0.35 * sigma[1], 1e-4 * chain.dof), abs=1e-9)  # reach = n m
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    assert abs(c * U[1, 0] - s * U[0, 0]) < 1e-9  # parallel
    # the force ellipse: semi-axes 1/σ_i × 0.1 reach², clipped at 1.25 reach (a dotted line then), same directions
    f_axes, _ = jac.analysis.force_ellipsoid(jac.geometric_jacobian(chain, theta)[3:5])
    reach = float(chain.dof)
    drawn = np.minimum(f_axes * 0.1 * reach**2, 1.25 * reach)
    fx, fy, frx, fry = (float(v) for v in got["force"][:4])
    assert np.allclose([fx, fy], pts[-1], atol=1e-9)
    assert frx == pytest.approx(max(drawn[0], 1e-4 * reach), abs=1e-9) and fry == pytest.approx(max(drawn[1], 1e-4 * reach), abs=1e-9)
    assert (got["clip"] == "visible") == bool((f_axes * 0.1 * reach**2 > 1.25 * reach).any())
    assert "NaN" not in got["text"] and "NaN" not in got["markup"] and "Infinity" not in got["markup"]
    return got


@pytest.fixture(scope="module")
def harness(browser_context):
    with bookcheck.BookServer(ROOT) as server:
        page = browser_context.new_page()
        seen: dict[str, list[str]] = {"console": [], "requests": []}
        page.on("console", lambda m: seen["console"].append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: seen["console"].append(str(e)))
        page.on("request", lambda r: seen["requests"].append(r.url))

        def open_view(robot: str, theta: list[float] | None, frame: str | None, width: int = 1280,
                      view: str = "planar_explorer", model: dict | None = None):
            page.set_viewport_size({"width": width, "height": 900})
            page.goto(server.base + "tests/browser/live_view_harness.html", wait_until="load")
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            page.evaluate("([v, m]) => window.mountView(v, m)",
                          [view, model if model is not None else live_views.planar_model(robot, theta, frame)])
            return page.wait_for_selector("#host[data-ready='1']", state="attached", timeout=10_000)

        yield page, open_view, seen, server.base
        page.close()


@pytest.mark.parametrize("robot,theta", [("planar_2r", [0.3, 1.2]), ("planar_3r", [0.5, 1.2, -0.8])])
def test_keyboard_moves_the_arm_and_the_table_is_the_library_jacobian(harness, robot, theta):
    page, open_view, seen, _ = harness
    el = open_view(robot, theta, "space")
    assert el.query_selector("svg") is not None
    before = _check_state(el, robot)
    assert np.allclose(before["theta"], theta, atol=1e-12) and before["frame"] == "space"
    labels = [lab.inner_text() for lab in el.query_selector_all("label")]
    assert labels[0].startswith("θ₁ = ") and f"{np.degrees(theta[0]):.1f}°" in labels[0]
    el.query_selector_all("input.jl-theta")[0].focus()
    page.keyboard.press("ArrowRight")
    after = _check_state(el, robot)
    assert after["theta"][0] == pytest.approx(theta[0] + STEP, abs=1e-9)
    assert np.allclose(after["theta"][1:], theta[1:])
    assert f"{np.degrees(after['theta'][0]):.1f}°" in el.query_selector("label").inner_text()
    assert after["table"] != before["table"] and after["link"] != before["link"]
    for frame in ("body", "geometric", "analytic", "space"):
        el.query_selector("select.jl-frame").select_option(frame)
        got = _check_state(el, robot)
        assert got["frame"] == frame and f"{frame} Jacobian" in got["text"]
        assert len(got["table"]) == (3 if frame == "analytic" else 6)


NEW_ELEMENTS_JS = """(el) => {
  // every element the view holds once drawn; then the frame switched through all four and back, and θ moved:
  // the elements it holds then that it did not make in build
  const made = new Set(el.querySelectorAll("*"));
  const select = el.querySelector("select.jl-frame");
  const slider = el.querySelector("input.jl-theta");
  for (const f of ["analytic", "body", "geometric", "analytic", "space"]) {
    select.value = f;
    select.dispatchEvent(new Event("change", { bubbles: true }));
    slider.value = String(Number(slider.value) + 0.1);
    slider.dispatchEvent(new Event("input", { bubbles: true }));
  }
  return [...el.querySelectorAll("*")].filter((e) => !made.has(e)).map((e) => e.outerHTML.slice(0, 80));
}"""


def test_update_creates_no_element(harness):
    """build makes every element once; switching the Jacobian (twist rows ↔ analytic rows) only swaps them."""
    _, open_view, _, _ = harness
    el = open_view("planar_3r", [0.5, 1.2, -0.8], "space")
    assert el.evaluate(NEW_ELEMENTS_JS) == []
    assert el.evaluate("(el) => el.dataset.frame") == "space"


def test_singularity_banner_and_no_nan(harness):
    page, open_view, seen, _ = harness
    el = open_view("planar_2r", [0.3, 1.2], "body")
    assert _check_state(el, "planar_2r")["banner"] is None
    page.evaluate(SET_JS, [el, 1, 0])
    got = _check_state(el, "planar_2r")
    assert got["theta"] == [0.3, 0.0] and got["level"] == "singular"
    assert got["banner"] is not None and got["banner"].startswith("Singular")
    assert "σmin(Jv) = 0.000 m" in got["text"]
    page.evaluate(SET_JS, [el, 1, 0.1])  # σ_min = L1 L2 |sin θ2| / ... ≈ 0.07 m < 0.16 m: near
    got = _check_state(el, "planar_2r")
    assert got["level"] == "warning" and got["banner"].startswith("Near a singularity")
    for frame in ("space", "geometric", "analytic"):
        el.query_selector("select.jl-frame").select_option(frame)
        _check_state(el, "planar_2r")
    page.evaluate(SET_JS, [el, 1, 0])
    assert _check_state(el, "planar_2r")["clip"] == "visible"  # infinite force semi-axis: clipped, marked
    assert "infinite along the dotted line" in el.inner_text()
    page.evaluate(SET_JS, [el, 0, -3.14])  # the joint limit
    _check_state(el, "planar_2r")


SCREEN_JS = """([el, x, y]) => {
  const m = el.querySelector("svg").getScreenCTM();
  const p = new DOMPoint(x, -y).matrixTransform(m);
  return [p.x, p.y];
}"""


@pytest.mark.parametrize("robot,theta", [("planar_2r", [0.3, 1.2]), ("planar_3r", [0.5, 1.2, -0.8])])
def test_dragging_the_tool_moves_it_to_the_pointer(harness, robot, theta):
    page, open_view, seen, _ = harness
    el = open_view(robot, theta, "geometric")
    box = el.query_selector("circle.jl-handle").bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    chain = live_views.ROBOTS[robot]()
    start = chain.fk(np.array(theta))[:2, 3]
    target = np.array([1.2, 1.0])
    for k in range(1, 6):  # along the straight line from the tool to the target, in 5 moves
        page.mouse.move(*page.evaluate(SCREEN_JS, [el, *(start + (target - start) * k / 5)]))
    page.mouse.up()
    got = _check_state(el, robot)  # the table is the library's Jacobian at the new angles
    reached = chain.fk(np.array(got["theta"]))[:2, 3]
    assert np.linalg.norm(reached - target) < 0.015, (reached, target)  # a pixel is about 0.011 m here
    assert not np.allclose(got["theta"], theta)
    # beyond the reach: DLS stretches the arm towards the pointer, near or at the singularity, never NaN
    box = el.query_selector("circle.jl-handle").bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(*page.evaluate(SCREEN_JS, [el, 1.25 * chain.dof, 0.0]))  # inside the drawing
    page.mouse.up()
    far = _check_state(el, robot)
    assert far["level"] in ("warning", "singular") and far["banner"] is not None, far["theta"]
    assert chain.fk(np.array(far["theta"]))[0, 3] > 0.97 * chain.dof  # stretched along x (reach n m)
    assert seen["console"] == []


@pytest.mark.parametrize("robot", ["planar_2r", "planar_3r"])
def test_fits_a_phone_with_readable_text(harness, robot):
    page, open_view, seen, _ = harness
    el = open_view(robot, [0.3, 1.2, 0.4][: live_views.ROBOTS[robot]().dof], "space", width=390)
    fit = el.evaluate(FIT_JS)
    assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["page"] <= 0, fit
    assert fit["small"] == [], fit
    assert 300 < fit["width"] <= 390


def test_no_console_error_and_no_foreign_request(harness):
    page, open_view, seen, base = harness
    open_view("planar_3r", [0.1, 0.2, 0.3], "geometric")
    assert seen["console"] == []
    assert seen["requests"], "no request recorded"
    host = urlsplit(base).netloc
    foreign = [u for u in seen["requests"] if not u.startswith("data:") and urlsplit(u).netloc != host]
    assert foreign == []


def test_dragging_a_joint_turns_the_joint_before_it(harness):
    page, open_view, seen, _ = harness
    el = open_view("planar_3r", [0.5, 1.2, -0.8], "geometric")
    chain = live_views.ROBOTS["planar_3r"]()
    th0 = np.array([0.5, 1.2, -0.8])
    pts = chain.joint_positions(th0)[:, :2]
    # joint 3 (index 2) turns about joint 2 to point at the pointer: θ2 changes alone
    knob = el.query_selector_all("circle.jl-joint-handle")[1]
    box = knob.bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    angle = np.arctan2(*(pts[2] - pts[1])[::-1]) + 0.6
    target = pts[1] + 1.0 * np.array([np.cos(angle), np.sin(angle)])
    page.mouse.move(*page.evaluate(SCREEN_JS, [el, *target]))
    page.mouse.up()
    got = _check_state(el, "planar_3r")
    assert got["theta"][0] == pytest.approx(0.5) and got["theta"][2] == pytest.approx(-0.8)
    assert got["theta"][1] == pytest.approx(1.2 + 0.6, abs=0.02)  # within a pixel's angle at this distance
    assert seen["console"] == []


def test_play_sweeps_the_chosen_joint_through_the_singularity(harness):
    page, open_view, seen, _ = harness
    el = open_view("planar_3r", [0.5, -0.3, 0.0], "geometric")
    el.query_selector("select.jl-sweep").select_option("1")
    el.query_selector("button.jl-play").focus()
    page.keyboard.press("Enter")  # a button: Enter and Space work
    page.wait_for_function(with_data("data.theta[1] > 0.05"), arg=el, timeout=30_000)
    page.keyboard.press("Space")
    assert el.query_selector("button.jl-play").get_attribute("aria-pressed") == "false"
    got = _check_state(el, "planar_3r")
    assert got["theta"][0] == 0.5 and got["theta"][2] == 0.0 and got["theta"][1] > 0.05
    # the sweep is on the sliders' 0.01 grid and passed θ2 = 0 exactly, where the arm is singular
    assert abs(got["theta"][1] * 100 - round(got["theta"][1] * 100)) < 1e-6
    # every level the view writes on the way, each change recorded as it is made (a poll could miss the one
    # frame at θ2 = 0 on a busy machine)
    page.evaluate("""(el) => { el.__levels = [];
      new MutationObserver((records) => { for (const r of records) el.__levels.push(r.oldValue); })
        .observe(el, {attributes: true, attributeFilter: ["data-level"], attributeOldValue: true}); }""", el)
    page.evaluate(SET_JS, [el, 1, -0.02])
    el.query_selector("button.jl-play").click()
    page.wait_for_function(with_data("data.theta[1] > 0.05"), arg=el, timeout=30_000)
    el.query_selector("button.jl-play").click()
    levels = page.evaluate("(el) => [...el.__levels, el.getAttribute('data-level')]", el)
    assert "singular" in levels, f"the sweep from θ2 = -0.02 to above 0.05 never showed 'singular': {levels}"
    assert seen["console"] == []


RR_READ = with_data("""{
  step: data.step, theta: data.theta, level: data.level, playing: data.playing,
  link: el.querySelector("polyline.jl-link").getAttribute("points"),
  desired: el.querySelector("polyline.jr-desired").getAttribute("points"),
  actual: el.querySelector("polyline.jr-actual").getAttribute("points"),
  rates: [...el.querySelectorAll("polyline.jr-rate")].map((p) => p.getAttribute("points")),
  text: el.innerText, markup: el.innerHTML,
}""")


def _rr_check(el, model: dict) -> dict:
    """The resolved-rate view shows the library's run (ResolvedRate.run) at its step."""
    from jacobians.widgets.live import ResolvedRate

    got = el.evaluate(RR_READ)
    chain = live_views.ROBOTS["planar_2r"]()
    w = ResolvedRate(chain, "circle" if model["path"] == "drawn" else model["path"], model["method"], model["damping"])
    w.drawn, w.path = model.get("drawn"), model["path"]
    k = got["step"]
    # The view's run is the module's (el.jacLive.sim). Two whole runs (the module's and the library's) are not
    # compared: through a near-singularity they drift apart by more than any fixed tolerance on another machine.
    # Instead each shown step is the library's step from the view's previous θ, within the bound of that step's
    # conditioning (fp_bounds.compare_step), and what is drawn is the library's kinematics of the shown θ.
    sim = el.evaluate("(el) => el.jacLive.sim")
    run = sim["run"]
    assert got["theta"] == run["thetas"][k]
    thetas = np.asarray(run["thetas"], dtype=float)
    _, x, vel = w.target()
    assert fp_bounds.scaled_err(sim["xd"], x) <= fp_bounds.TOL     # the path: well-conditioned
    if vel is None:                                                # a drawn path: the library's forward differences
        vel = np.zeros_like(np.asarray(sim["xd"], dtype=float))
        vel[:-1] = np.diff(np.asarray(sim["xd"], dtype=float), axis=0) / (sim["t"][1] - sim["t"][0])
    reach = float(arm_reach(chain))
    for j in range(k + 1):
        step = fp_bounds.Step(chain, thetas[j], sim["xd"][j], vel[j], sim["t"][1] - sim["t"][0], model["method"],
                              model["damping"], float(w.gain))
        diffs = fp_bounds.compare_step(step, reach, run["rates"][j], run["positions"][j], run["sigmaMin"][j],
                                       thetas[j], thetas[j + 1] if j < k else None)
        for key, (e, allowed) in diffs.items():
            assert e <= allowed, f"step {j}: {key} differs from the library's step by {e:.1e}, allowed {allowed:.1e}"
    pts = np.array([[float(v) for v in p.split(",")] for p in got["link"].split()])
    assert np.allclose(pts, chain.joint_positions(thetas[k])[:, :2], atol=1e-9)   # SVG digits
    des = np.array([[float(v) for v in p.split(",")] for p in got["desired"].split()])
    assert np.allclose(des, x, atol=1e-9)
    act = np.array([[float(v) for v in p.split(",")] for p in got["actual"].split()])
    assert np.allclose(act, chain.fk(thetas[: k + 1])[:, :2, 3], atol=1e-9)
    assert all(len(r.split()) == k + 1 for r in got["rates"])  # the rates are plotted as the run goes
    smin = float(run["sigmaMin"][k])
    assert f"(Jv) = {smin:.3f} m" in got["text"]
    assert "NaN" not in got["markup"] and "Infinity" not in got["markup"]
    return got


def _rr_model(**kw) -> dict:
    return live_views.resolved_rate_model("planar_2r", **kw)


def test_resolved_rate_keys_step_and_play_and_the_run_is_the_librarys(harness):
    page, open_view, seen, _ = harness
    model = _rr_model(path="close past the base", method="pinv")
    el = open_view(None, None, None, view="resolved_rate", model=model)
    assert _rr_check(el, model)["step"] == 0
    el.query_selector("button.jr-fwd").focus()
    for key in (".", "ArrowRight", "ArrowRight"):
        page.keyboard.press(key)
    assert _rr_check(el, model)["step"] == 3
    page.keyboard.press(",")
    assert _rr_check(el, model)["step"] == 2
    el.query_selector("input.jr-step").focus()
    page.keyboard.press("End")  # a slider: Home/End/arrows
    got = _rr_check(el, model)
    assert got["step"] == 159
    page.keyboard.press("p")  # play from the start again
    page.wait_for_function(with_data("data.step > 3 && data.step < 159"), arg=el,
                           timeout=10_000)
    page.keyboard.press("p")
    _rr_check(el, model)
    # the run near the base: the pseudo-inverse's peak rate leaves the plot; step to the closest pass
    page.evaluate("(el) => { const s = el.querySelector('input.jr-step'); s.value = '80';"
                  " s.dispatchEvent(new Event('input', {bubbles: true})); }", el)
    got = _rr_check(el, model)
    assert got["level"] in ("warning", "singular")
    assert "Near a singularity" in got["text"] or "At a singularity" in got["text"]
    # to full reach with the pseudo-inverse: the arm ends stretched (singular), no NaN, no throw
    el.query_selector("select.jr-path").select_option("to full reach")
    model["path"] = "to full reach"
    el.query_selector("input.jr-step").focus()
    page.keyboard.press("End")
    got = _rr_check(el, model)
    assert got["step"] == 159 and got["level"] in ("warning", "singular")  # near the stretched arm
    assert seen["console"] == []


def test_resolved_rate_method_damping_and_path_change_the_run(harness):
    page, open_view, seen, _ = harness
    model = _rr_model(path="close past the base", method="pinv")
    el = open_view(None, None, None, view="resolved_rate", model=model)
    el.query_selector("select.jr-method").select_option("dls")
    model["method"] = "dls"
    assert el.query_selector("input.jr-damping").is_enabled()
    _rr_check(el, model)
    el.query_selector("input.jr-damping").focus()
    page.keyboard.press("ArrowLeft")  # log10 λ: -1 -> -1.1
    model["damping"] = round(10 ** -1.1, 4)
    assert f"{model['damping']:.3f} m" in el.inner_text()
    page.evaluate("(el) => { const s = el.querySelector('input.jr-step'); s.value = '100';"
                  " s.dispatchEvent(new Event('input', {bubbles: true})); }", el)
    _rr_check(el, model)
    for path in ("circle", "to full reach"):
        el.query_selector("select.jr-path").select_option(path)
        model["path"] = path
        assert _rr_check(el, model)["step"] == 0
    assert seen["console"] == []


def test_resolved_rate_follows_a_drawn_path(harness):
    page, open_view, seen, _ = harness
    model = _rr_model(path="circle", method="dls", damping=0.05)
    el = open_view(None, None, None, view="resolved_rate", model=model)
    el.query_selector("button.jr-draw").click()
    stroke = [(0.5 + 0.6 * np.cos(a), 0.8 + 0.4 * np.sin(a)) for a in np.linspace(0, 3, 25)]
    page.mouse.move(*page.evaluate(SCREEN_JS, [el, *stroke[0]]))
    page.mouse.down()
    for p in stroke[1:]:
        page.mouse.move(*page.evaluate(SCREEN_JS, [el, *p]))
    page.mouse.up()
    drawn = page.evaluate("(el) => el.jacLive && el.jacLive.sim && el.jacLive.sim.xd.length", el)
    assert drawn == 160
    model["path"] = "drawn"
    assert el.query_selector("select.jr-path").input_value() == "drawn"
    # the view resampled what it recorded; the library, given the same points, runs the same motion
    page.evaluate("(el) => { const s = el.querySelector('input.jr-step'); s.value = '120';"
                  " s.dispatchEvent(new Event('input', {bubbles: true})); }", el)
    got = el.evaluate(RR_READ)
    recorded = page.evaluate("(el) => el.jacLive.drawn", el)
    model["drawn"] = recorded
    _rr_check(el, model)
    assert got["step"] == 120
    start = np.array(recorded[0])
    assert np.linalg.norm(start - np.array(stroke[0])) < 0.02  # a pixel is about 0.005 m here
    assert seen["console"] == []


def test_resolved_rate_path_drawn_with_the_keyboard(harness):
    """Draw a path without a pointer: the button gives the picture the focus and a pen at the tool; arrow keys
    move it 0.05 reach (Shift 0.01), Enter places a point, Backspace takes one back, the button uses the path."""
    page, open_view, seen, _ = harness
    model = _rr_model(path="circle", method="dls", damping=0.05)
    el = open_view(None, None, None, view="resolved_rate", model=model)
    tool = page.evaluate("(el) => el.jacLive.sim.run.positions[0]", el)
    el.query_selector("button.jr-draw").focus()
    page.keyboard.press("Enter")
    assert page.evaluate("(el) => document.activeElement === el.querySelector('svg')", el)
    assert "Enter adds a point" in el.query_selector("svg").get_attribute("aria-label")
    reach = 2.0  # planar_2r
    h, fine = 0.05 * reach, 0.01 * reach
    keys = ["Enter", "ArrowUp", "ArrowUp", "ArrowUp", "Enter", "ArrowLeft", "ArrowLeft", "Shift+ArrowLeft", "Enter",
            "ArrowDown", "Enter", "Backspace"]
    for key in keys:
        page.keyboard.press(key)
    assert int(el.evaluate("(el) => el.jacLive.step")) == 0  # the arrows moved the pen, not the run
    start = np.round(np.array(tool), 2)
    want = [start, start + [0, 3 * h], start + [-2 * h - fine, 3 * h]]
    el.query_selector("button.jr-draw").focus()
    page.keyboard.press("Enter")  # use the path
    recorded = np.array(page.evaluate("(el) => el.jacLive.drawn", el))
    assert np.allclose(recorded, want, atol=1e-4), recorded  # the view keeps 4 decimals
    assert el.query_selector("select.jr-path").input_value() == "drawn"
    model.update(path="drawn", drawn=recorded.tolist())
    page.evaluate("(el) => { const s = el.querySelector('input.jr-step'); s.value = '60';"
                  " s.dispatchEvent(new Event('input', {bubbles: true})); }", el)
    _rr_check(el, model)  # the run along the keyed path is the library's
    assert el.query_selector("svg").get_attribute("tabindex") is None  # the pad leaves the tab order
    assert seen["console"] == []


def test_resolved_rate_fits_a_phone(harness):
    page, open_view, seen, _ = harness
    el = open_view(None, None, None, view="resolved_rate", model=_rr_model(), width=390)
    fit = el.evaluate(FIT_JS)
    assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["page"] <= 0, fit
    assert fit["small"] == [], fit
    small_svg = el.evaluate("""(el) => [...el.querySelectorAll("svg text")].filter(
        (t) => t.getBoundingClientRect().height && parseFloat(getComputedStyle(t).fontSize)
               * el.querySelector("svg.jr-rates").getScreenCTM().a < 13.5).length""")
    assert small_svg == 0


def check_built_page(context, root: Path, path: str) -> dict:
    """Every live view on a built page (``path`` under ``root``): renders, keyboard, library numbers, phone, offline."""
    with bookcheck.BookServer(root) as server:
        page = context.new_page()
        errors: list[str] = []
        requests: list[str] = []
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("request", lambda r: requests.append(r.url))
        try:
            page.set_viewport_size(bookcheck.DESKTOP)
            page.goto(server.base + path, wait_until="load")
            page.wait_for_selector(".jac-live[data-ready='1']", state="attached", timeout=15_000)
            views = page.query_selector_all(".jac-live[data-ready='1']")
            assert views, f"{path}: no live view rendered"
            for el in views:
                model = json.loads(el.get_attribute("data-model"))
                if el.get_attribute("data-view") == "story":  # chapters 1, 3, 7: the replay (story_views.py)
                    story_views.check_view(el, model)
                    el.query_selector("input.js-time").focus()
                    page.keyboard.press("ArrowRight")
                    assert story_views.check_view(el, model)["frame"] == 1
                    continue
                robot = {2: "planar_2r", 3: "planar_3r"}[len(model["S"][0])]
                if el.get_attribute("data-view") == "planar_explorer":
                    theta0 = list(model["theta"])
                    _check_state(el, robot)
                    el.query_selector("input.jl-theta").focus()
                    page.keyboard.press("ArrowRight")
                    got = _check_state(el, robot)
                    assert got["theta"][0] == pytest.approx(theta0[0] + STEP, abs=1e-9)
                    el.query_selector("select.jl-frame").select_option("body")
                    assert _check_state(el, robot)["frame"] == "body"
                else:
                    _rr_check(el, model)
                    el.query_selector("button.jr-fwd").focus()
                    page.keyboard.press("ArrowRight")
                    assert _rr_check(el, model)["step"] == 1
            page.set_viewport_size(bookcheck.PHONE)
            for el in views:
                fit = el.evaluate(FIT_JS)
                assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["small"] == [], fit
            assert errors == []
            host = urlsplit(server.base).netloc
            assert [u for u in requests if not u.startswith("data:") and urlsplit(u).netloc != host] == []
            return {"views": len(views), "requests": len(requests)}
        finally:
            page.close()


@pytest.mark.parametrize("chapter,view", [("02_space_jacobian", "planar_explorer"),
                                          ("05_geometric_jacobian", "planar_explorer"),
                                          ("09_using_the_jacobian", "resolved_rate"),
                                          ("01_twists", "story"), ("03_body_jacobian", "story"),
                                          ("07_conversions", "story")])
def test_on_the_built_chapter_page(browser_context, book_html, chapter, view):
    """The built book (``make book`` runs before the browser tests; BOOK_HTML may point elsewhere)."""
    built = book_html / "chapters" / f"{chapter}.html"
    assert f'data-view="{view}"' in built.read_text(encoding="utf-8"), (
        f"{built} has no {view} live view, but chapters/{chapter}.md mounts one: rebuild the book")
    assert check_built_page(browser_context, book_html, f"chapters/{chapter}.html")["views"] >= 1


def test_touch_drag_moves_the_tool(harness):
    """A finger on the dashed ring (real touch events through the DevTools protocol): the tool follows it."""
    page, open_view, seen, _ = harness
    el = open_view("planar_2r", [0.3, 1.2], "space")
    cdp = page.context.new_cdp_session(page)
    try:
        cdp.send("Emulation.setTouchEmulationEnabled", {"enabled": True, "maxTouchPoints": 1})
        box = el.query_selector("circle.jl-handle").bounding_box()
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        chain = live_views.ROBOTS["planar_2r"]()
        start = chain.fk(np.array([0.3, 1.2]))[:2, 3]
        target = np.array([0.9, 1.1])
        cdp.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": x, "y": y}]})
        for k in range(1, 6):
            px, py = page.evaluate(SCREEN_JS, [el, *(start + (target - start) * k / 5)])
            cdp.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": px, "y": py}]})
            page.evaluate("() => new Promise((r) => requestAnimationFrame(() => r()))")  # moves are sent per frame
        cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
        got = _check_state(el, "planar_2r")
        assert np.linalg.norm(chain.fk(np.array(got["theta"]))[:2, 3] - target) < 0.015, got["theta"]
        assert el.evaluate("(el) => getComputedStyle(el.querySelector('circle.jl-handle')).touchAction") == "none"
    finally:
        cdp.send("Emulation.setTouchEmulationEnabled", {"enabled": False})
        cdp.detach()
    assert seen["console"] == []
