"""The live columns explorer (``lib/jacobians/widgets/live/columns_explorer/view.js``, chapter 4) in Chromium, no kernel.

On the harness page (no book build needed) the view is mounted from the model
``jacobians.widgets.live_spatial`` builds for the book page; on the built chapter 4
page as well. Checked: what the view computes and draws is the library's (200
random configurations of the 5R arm: FK, J_s, J_b, the geometric J, the joint
points, the drawn axes); a slider moved from the keyboard changes the tables to
the library's Jacobians and colours and lists exactly the columns whose numbers
changed (after the joint in J_s, before it in J_b); the watched column colours
the axes by role; the drawing turns by arrow keys and by drag; at 390 px nothing
overflows and text is at least 14 px; no console error, failed or foreign request.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import spatial_views as sv
from live_data import with_data

import jacobians as jac
from jacobians.widgets import live_spatial as spatial

N_CONFIGS = 200
TOL = 1e-12
HALF_ULP = 0.005 + 1e-9
STEP = 0.01

READ_JS = with_data("""{
  theta: data.theta, column: data.column, moved: data.moved, changedS: data.changedS, changedB: data.changedB,
  Js: [...el.querySelectorAll("table.jl-space tbody tr")].map((tr) => [...tr.querySelectorAll("td")].map((c) => c.textContent)),
  Jb: [...el.querySelectorAll("table.jl-body tbody tr")].map((tr) => [...tr.querySelectorAll("td")].map((c) => c.textContent)),
  hotS: [...el.querySelectorAll("table.jl-space thead th.jl-changed")].map((c) => +c.textContent),
  hotB: [...el.querySelectorAll("table.jl-body thead th.jl-changed")].map((c) => +c.textContent),
  hotCellsS: el.querySelectorAll("table.jl-space td.jl-changed").length,
  hotCellsB: el.querySelectorAll("table.jl-body td.jl-changed").length,
  watch: [...el.querySelectorAll("table.jl-space thead th.jl-watch")].map((c) => +c.textContent),
  axisColors: [1, 2, 3, 4, 5].map((i) => getComputedStyle(el.querySelector(`line.jl-axis-${i}`)).stroke),
  changes: el.querySelector(".jl-changes").textContent,
  text: el.innerText, markup: el.innerHTML,
}""")

SET_JS = """([el, i, v]) => {
  const s = el.querySelectorAll("input.jl-theta")[i];
  s.value = String(v);
  s.dispatchEvent(new Event("input", { bubbles: true }));
}"""


@pytest.fixture(scope="module")
def harness(browser_context):
    page, open_view, seen, server = sv.open_harness(browser_context)
    try:
        yield page, open_view, seen, server.base
    finally:
        page.close()
        server.__exit__(None, None, None)


def _axis_points(chain, theta, axis_length):
    """(n, 2, 3): the drawn joint axes, ±axis_length along ω_s,i through joint i's point, from the library."""
    Js = jac.space_jacobian(chain, theta)
    q = chain.joint_positions(theta)[:-1]
    w = Js[:3].T
    return np.stack([q - axis_length * w, q + axis_length * w], axis=1)


def _check_state(el, chain, model) -> dict:
    got = el.evaluate(READ_JS)
    theta = np.array(got["theta"])
    for key, ref in (("Js", jac.space_jacobian(chain, theta)), ("Jb", jac.body_jacobian(chain, theta))):
        shown = np.array([[sv.number(c) for c in row] for row in got[key]])
        assert shown.shape == ref.shape == (6, chain.dof)
        assert np.abs(shown - ref).max() <= HALF_ULP, f"{key}: table {shown} vs library {ref}"
        assert sv.no_negative_zero(got[key])
    cam = el.evaluate(sv.CAMERA_JS)
    drawn = sv.line_ends(el, "line.jl-axis")
    ref = sv.project(_axis_points(chain, theta, model["axis_length"]), cam, model["center"], model["extent"])
    assert np.abs(drawn - ref).max() < sv.SVG_DIGITS
    links = sv.line_ends(el, "line.jl-link")
    P = chain.joint_positions(theta)
    ref_links = sv.project(np.stack([P[:-1], P[1:]], axis=1), cam, model["center"], model["extent"])
    assert np.abs(links - ref_links).max() < sv.SVG_DIGITS
    assert "NaN" not in got["markup"] and "Infinity" not in got["markup"] and "undefined" not in got["text"]
    return got


def test_view_kinematics_match_library_at_200_configurations(harness):
    """The view's own numbers (el.jacLive after model.set) at 200 random configurations, within 1e-12."""
    page, open_view, seen, _ = harness
    model = spatial.columns_model()
    el = open_view("columns_explorer", model)
    chain = jac.robots.spatial_5r()
    rng = np.random.default_rng(2024)
    thetas = rng.uniform(-3.14, 3.14, (N_CONFIGS, chain.dof))
    got = page.evaluate("""([el, thetas]) => thetas.map((th) => {
      window.liveModel.set("theta", th);
      const s = el.jacLive;
      const K = window.K, c = K.makeChain(...["S", "M", "Q"].map((k) => window.liveModel.get(k)));
      return {T: s.T, Js: s.Js, Jb: s.Jb, points: s.points, Jg: K.geometricJacobian(c, th), fk: K.fk(c, th)};
    })""", [el, thetas.tolist()])
    ref = {"T": chain.fk(thetas), "fk": chain.fk(thetas), "Js": jac.space_jacobian(chain, thetas),
           "Jb": jac.body_jacobian(chain, thetas), "Jg": jac.geometric_jacobian(chain, thetas),
           "points": chain.joint_positions(thetas)}
    worst = {}
    for key, R in ref.items():
        G = np.array([g[key] for g in got], dtype=float)
        assert G.shape == R.shape, key
        worst[key] = float((np.abs(G - R).max(axis=(1, 2)) / np.maximum(1.0, np.abs(R).max(axis=(1, 2)))).max())
    print("\ncolumns explorer, 5R, largest difference from the library:",
          ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))
    assert max(worst.values()) <= TOL, worst
    _check_state(el, chain, model)  # and the last configuration is drawn and tabulated as the library says
    assert seen["console"] == []


@pytest.mark.parametrize("joint", [1, 3, 5])
def test_keyboard_slider_changes_the_columns_the_rule_says(harness, joint):
    page, open_view, seen, _ = harness
    model = spatial.columns_model(column=3)
    el = open_view("columns_explorer", model)
    chain = jac.robots.spatial_5r()
    before = _check_state(el, chain, model)
    assert before["changes"].startswith("Move one joint") and before["hotS"] == [] and before["watch"] == [3]
    labels = [lab.inner_text() for lab in el.query_selector_all("label")]
    assert labels[0].startswith("Watch column") and labels[joint].startswith(f"θ{chr(0x2080 + joint)} = ")
    el.query_selector_all("input.jl-theta")[joint - 1].focus()
    page.keyboard.press("ArrowRight")
    after = _check_state(el, chain, model)
    expected = np.array(model["theta"])
    expected[joint - 1] += STEP
    assert np.allclose(after["theta"], expected, atol=1e-9)
    assert f"{np.degrees(expected[joint - 1]):.1f}°" in el.query_selector_all("label")[joint].inner_text()
    # moving θ_k changes the columns of J_s after k and the columns of J_b before k, nothing else
    after_k = list(range(joint + 1, chain.dof + 1))
    before_k = list(range(1, joint))
    assert after["moved"] == [joint]
    assert after["changedS"] == after_k and after["changedB"] == before_k
    assert after["hotS"] == after_k and after["hotB"] == before_k
    assert after["hotCellsS"] == 6 * len(after_k) and after["hotCellsB"] == 6 * len(before_k)
    none = "none"
    assert f"You moved θ{chr(0x2080 + joint)}" in after["changes"]
    assert f"that changed: {', '.join(map(str, after_k)) or none} (after {joint})" in after["changes"]
    assert f": {', '.join(map(str, before_k)) or none} (before {joint})" in after["changes"]
    # the library agrees on which columns moved
    Js0, Js1 = (jac.space_jacobian(chain, t) for t in (np.array(model["theta"]), expected))
    Jb0, Jb1 = (jac.body_jacobian(chain, t) for t in (np.array(model["theta"]), expected))
    assert [i + 1 for i in range(chain.dof) if np.abs(Js1[:, i] - Js0[:, i]).max() > 1e-12] == after_k
    assert [i + 1 for i in range(chain.dof) if np.abs(Jb1[:, i] - Jb0[:, i]).max() > 1e-12] == before_k
    assert seen["console"] == []


def _rgb(hex_colour: str) -> str:
    """A #RRGGBB colour as the browser's computed style writes it."""
    r, g, b = (int(hex_colour[i:i + 2], 16) for i in (1, 3, 5))
    return f"rgb({r}, {g}, {b})"


def test_watched_column_colours_the_axes_by_role(harness):
    page, open_view, seen, _ = harness
    model = spatial.columns_model(column=3)
    el = open_view("columns_explorer", model)
    # the library's orange and sky blue, drawn darker on the view's light ground (palette.js: >= 3:1)
    on_white = {"#E69F00": "#B07800", "#56B4E9": "#3388BB"}
    pal = {k: _rgb(on_white.get(v.upper(), v)) for k, v in model["palette"].items()}
    black = _rgb("#000000")
    got = el.evaluate(READ_JS)
    assert got["axisColors"] == [pal["space"], pal["space"], black, pal["body"], pal["body"]]
    el.query_selector("select.jl-column").select_option("1")
    got = _check_state(el, jac.robots.spatial_5r(), model)
    assert got["column"] == 1 and got["watch"] == [1]
    assert got["axisColors"] == [black] + [pal["body"]] * 4
    assert "axes none (before 1)" in got["text"] and "axes 2, 3, 4, 5 (after 1)" in got["text"]
    page.evaluate(SET_JS, [el, 4, -3.14])  # the joint limit
    _check_state(el, jac.robots.spatial_5r(), model)


def test_turning_the_view_by_keys_and_drag(harness):
    page, open_view, seen, _ = harness
    model = spatial.columns_model()
    el = open_view("columns_explorer", model)
    chain = jac.robots.spatial_5r()
    pts = _axis_points(chain, np.array(model["theta"]), model["axis_length"])
    sv.check_turning(page, el, model["center"], model["extent"], pts, "line.jl-axis")
    # turning does not change the numbers
    _check_state(el, chain, model)
    assert seen["console"] == []


def test_fits_a_phone_with_readable_text(harness):
    page, open_view, seen, _ = harness
    el = open_view("columns_explorer", spatial.columns_model(), width=390)
    fit = el.evaluate(sv.FIT_JS)
    assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["page"] <= 0, fit
    assert fit["small"] == [] and fit["svgSmall"] == [], fit
    assert fit["touch"] == ["svg"], fit  # touch-action none on the drawing only
    assert 300 < fit["width"] <= 390


def test_no_console_error_and_no_foreign_request(harness):
    page, open_view, seen, base = harness
    open_view("columns_explorer", spatial.columns_model())
    assert seen["console"] == [] and seen["failed"] == []
    assert seen["requests"] and sv.foreign(seen["requests"], base) == []


def test_on_the_built_chapter_page(browser_context, book_html):
    """Chapter 4 as built (``make book`` runs before the browser tests)."""
    path = "chapters/04_space_vs_body.html"
    text = (book_html / path).read_text(encoding="utf-8")
    assert 'data-view="columns_explorer"' in text, f"{path} has no columns explorer: rebuild the book"
    import bookcheck

    with bookcheck.BookServer(book_html) as server:
        page = browser_context.new_page()
        errors: list[str] = []
        requests: list[str] = []
        failed: list[str] = []
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("request", lambda r: requests.append(r.url))
        page.on("requestfailed", lambda r: failed.append(r.url))
        try:
            page.set_viewport_size(bookcheck.DESKTOP)
            page.goto(server.base + path, wait_until="load")
            el = page.wait_for_selector(".jac-live[data-view='columns_explorer'][data-ready='1']", state="attached",
                                        timeout=15_000)
            model = json.loads(el.get_attribute("data-model"))
            assert model == spatial.columns_model(theta=model["theta"], column=model["column"])
            chain = jac.robots.spatial_5r()
            _check_state(el, chain, model)
            el.query_selector_all("input.jl-theta")[1].focus()
            page.keyboard.press("ArrowLeft")
            got = _check_state(el, chain, model)
            assert got["theta"][1] == pytest.approx(model["theta"][1] - STEP, abs=1e-9)
            assert got["changedS"] == [3, 4, 5] and got["changedB"] == [1]
            pts = _axis_points(chain, np.array(got["theta"]), model["axis_length"])
            sv.check_turning(page, el, model["center"], model["extent"], pts, "line.jl-axis")
            page.set_viewport_size(bookcheck.PHONE)
            fit = el.evaluate(sv.FIT_JS)
            assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["small"] == [] and fit["svgSmall"] == [], fit
            assert errors == [] and failed == []
            assert sv.foreign(requests, server.base) == []
        finally:
            page.close()
