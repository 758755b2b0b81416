"""The live planar explorer (``_theme/live/planar_explorer.js``) in Chromium, no kernel.

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
import live_views
import numpy as np
import pytest

import jacobians as jac

ROOT = Path(__file__).resolve().parents[2]
STEP = 0.01
HALF_ULP = 0.005 + 1e-9  # the table shows 2 decimals

READ_JS = """(el) => ({
  theta: JSON.parse(el.dataset.theta), frame: el.dataset.frame, level: el.dataset.level,
  table: [...el.querySelectorAll("table.jl-matrix tbody tr")].map(
    (tr) => [...tr.querySelectorAll("td")].map((td) => td.textContent)),
  link: el.querySelector("polyline.jl-link").getAttribute("points"),
  ellipse: ["cx", "cy", "rx", "ry", "transform"].map((k) => el.querySelector("ellipse.jl-ellipse").getAttribute(k)),
  banner: el.querySelector(".jl-banner").hidden ? null : el.querySelector(".jl-banner").textContent,
  text: el.innerText, markup: el.innerHTML,
})"""

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

        def open_view(robot: str, theta: list[float], frame: str, width: int = 1280):
            page.set_viewport_size({"width": width, "height": 900})
            page.goto(server.base + "tests/browser/live_view_harness.html", wait_until="load")
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            page.evaluate("([v, m]) => window.mountView(v, m)",
                          ["planar_explorer", live_views.planar_model(robot, theta, frame)])
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
    for frame in ("body", "geometric", "space"):
        el.query_selector("select.jl-frame").select_option(frame)
        got = _check_state(el, robot)
        assert got["frame"] == frame and f"{frame} Jacobian" in got["text"]


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
    for frame in ("space", "geometric"):
        el.query_selector("select.jl-frame").select_option(frame)
        _check_state(el, "planar_2r")
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


def check_built_page(context, root: Path, path: str) -> dict:
    """The live view on a built page (``path`` under ``root``): renders, keyboard, frame, phone width, offline."""
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
            el = page.wait_for_selector(".jac-live[data-ready='1']", state="attached", timeout=15_000)
            model = json.loads(el.get_attribute("data-model"))
            theta0 = list(model["theta"])
            _check_state(el, "planar_2r")
            el.query_selector("input.jl-theta").focus()
            page.keyboard.press("ArrowRight")
            got = _check_state(el, "planar_2r")
            assert got["theta"][0] == pytest.approx(theta0[0] + STEP, abs=1e-9)
            el.query_selector("select.jl-frame").select_option("body")
            assert _check_state(el, "planar_2r")["frame"] == "body"
            page.set_viewport_size(bookcheck.PHONE)
            fit = el.evaluate(FIT_JS)
            assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["small"] == [], fit
            assert errors == []
            host = urlsplit(server.base).netloc
            assert [u for u in requests if not u.startswith("data:") and urlsplit(u).netloc != host] == []
            return {"fit": fit, "requests": len(requests)}
        finally:
            page.close()


def test_on_the_built_chapter_page(browser_context, book_html):
    """The built book (``make book`` runs before the browser tests; BOOK_HTML may point elsewhere)."""
    built = book_html / "chapters" / "02_space_jacobian.html"
    assert 'class="jac-live"' in built.read_text(encoding="utf-8"), (
        f"{built} has no live view, but chapters/02_space_jacobian.md mounts one: rebuild the book")
    check_built_page(browser_context, book_html, "chapters/02_space_jacobian.html")
