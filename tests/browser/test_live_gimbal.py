"""The live gimbal-lock view (``lib/jacobians/widgets/live/gimbal_lock/view.js``, chapter 6) in Chromium, no kernel.

On the harness page (no book build needed) the view is mounted from the model
``jacobians.widgets.live_spatial`` builds for the book page; on the built chapter 6
page as well. Checked: at 200 random configurations of each wrist (ZYZ, ZYX) in
each coordinate choice (ZYX, ZYZ) the view's φ, B(φ), det B, J, J_a, σ_min of
J's angular rows and the norms are the library's within 1e-12, and its lock
flag is the library's NaN; a slider moved from the keyboard changes the tables,
the status and the drawn axes to the library's values; at the lock (θ₂ = 90°
on the ZYZ wrist, ZYX coordinates) the banner says so, J_a shows "—" and
nothing is NaN; near it J_a is large and the banner warns; at θ₂ = 0 the wrist's
own singularity is named; the drawing turns by keys and drag; phone width;
no console error, failed or foreign request.
"""

from __future__ import annotations

import json
import math

import fp_bounds
import numpy as np
import pytest
import spatial_views as sv
from live_data import live_data, with_data

import jacobians as jac
from jacobians import representations as reps
from jacobians.widgets import live_spatial as spatial

N_CONFIGS = 200
TOL = 1e-12
HALF_ULP = 0.005 + 1e-9
STEP_DEG = 0.5

READ_JS = with_data("""(() => {
  const rows = (sel) => [...el.querySelectorAll(sel + " tbody tr")].map((tr) => [...tr.querySelectorAll("td")]
    .map((c) => c.textContent));
  const b = el.querySelector(".jl-banner");
  return { theta: data.theta, wrist: data.wrist, rep: data.rep, level: data.level,
    B: rows("table.jl-B"), J: rows("table.jl-J"), Ja: rows("table.jl-Ja"),
    caption: el.querySelector("table.jl-Ja caption").textContent,
    banner: b.hidden ? null : b.textContent, status: el.querySelector(".jl-status").innerText,
    text: el.innerText, markup: el.innerHTML };
})()""")

SET_JS = """([el, i, v]) => {
  const s = el.querySelectorAll("input.jl-theta")[i];
  s.value = String(v);
  s.dispatchEvent(new Event("input", { bubbles: true }));
}"""

WRISTS = {"zyz_wrist": lambda: jac.robots.zyz_wrist(spatial.WRIST_TOOL),
          "zyx_wrist": lambda: jac.robots.zyx_wrist(spatial.WRIST_TOOL)}


@pytest.fixture(scope="module")
def harness(browser_context):
    page, open_view, seen, server = sv.open_harness(browser_context)
    try:
        yield page, open_view, seen, server.base
    finally:
        page.close()
        server.__exit__(None, None, None)


def _library(chain, theta, rep):
    theta = np.asarray(theta, dtype=float)
    T = chain.fk(theta)
    phi = jac.pose_coordinates(T, rep)[..., :3]
    B = reps.rate_to_angular_velocity(phi, rep)
    J = jac.geometric_jacobian(chain, theta)
    with np.errstate(invalid="ignore"):
        Ja = jac.analytic_jacobian(chain, theta, rep, on_singularity="nan")
    smin = np.linalg.svd(J[..., :3, :], compute_uv=False)[..., -1]
    return {"T": T, "phi": phi, "B": B, "detB": np.linalg.det(B), "J": J, "Ja": Ja, "sigmaMin": smin,
            "margin": reps.representation_singularity_margin(phi, rep), "normJ": np.linalg.norm(J, axis=(-2, -1))}


def _axis_points(chain, theta):
    """(3, 2, 3): the drawn joint axes, ±0.95 tool along each axis through the wrist centre."""
    w = jac.geometric_jacobian(chain, theta)[:3].T
    L = 0.95 * spatial.WRIST_TOOL
    return np.stack([-L * w, L * w], axis=1)


def _fixed1(x: float) -> str:
    """As the view prints a number with 1 decimal: no "−0.0", a true minus sign."""
    text = f"{x:.1f}"
    return "0.0" if text == "-0.0" else text.replace("-", "\u2212")


def _check_state(el, model) -> dict:
    got = el.evaluate(READ_JS)
    chain = WRISTS[got["wrist"]]()
    theta = np.array(got["theta"])
    ref = _library(chain, theta, got["rep"])
    for key in ("B", "J"):
        shown = np.array([[sv.number(c) for c in row] for row in got[key]])
        assert shown.shape == ref[key].shape and np.abs(shown - ref[key]).max() <= HALF_ULP, (key, shown, ref[key])
        assert sv.no_negative_zero(got[key])
    locked = bool(np.isnan(ref["Ja"]).any())
    if locked:
        assert all(c == "—" for row in got["Ja"] for c in row)
        assert "undefined" in got["caption"] and got["level"] == "singular"
        assert got["banner"] is not None and got["banner"].startswith("Gimbal lock")
    else:
        shown = np.array([[sv.number(c) for c in row] for row in got["Ja"]])
        scale = np.maximum(1.0, np.abs(ref["Ja"]))  # large entries are shown with 3 significant digits
        assert np.all(np.abs(shown - ref["Ja"]) <= np.where(np.abs(ref["Ja"]) < 1e4, HALF_ULP, 0.005 * scale))
    deg = ", ".join(_fixed1(math.degrees(v)) + "°" for v in ref["phi"])
    assert f"φ ({got['rep'].upper()}) = ({deg})" in got["status"]
    assert f"= {abs(ref['detB']):.4f}" in got["status"].replace("\u2212", "") or abs(ref["detB"]) < 5e-5
    assert f"rows = {ref['sigmaMin']:.3f}" in got["status"]
    cam = el.evaluate(sv.CAMERA_JS)
    drawn = sv.line_ends(el, "line.jl-axis")
    assert np.abs(drawn - sv.project(_axis_points(chain, theta), cam, [0, 0, 0], 1.55 * spatial.WRIST_TOOL)).max() \
        < sv.SVG_DIGITS
    assert "NaN" not in got["markup"] and "Infinity" not in got["markup"]
    return got


@pytest.mark.parametrize("wrist", ["zyz_wrist", "zyx_wrist"])
@pytest.mark.parametrize("rep", ["zyx", "zyz"])
def test_view_numbers_match_library_at_200_configurations(harness, wrist, rep):
    page, open_view, seen, _ = harness
    model = spatial.gimbal_model(wrist, rep=rep)
    el = open_view("gimbal_lock", model)
    chain = WRISTS[wrist]()
    rng = np.random.default_rng(sum(map(ord, wrist + rep)))
    thetas = rng.uniform(-np.pi, np.pi, (N_CONFIGS, 3))
    got = page.evaluate("""([el, thetas]) => thetas.map((th) => {
      window.liveModel.set("theta", th);
      const s = el.jacLive;
      return {T: s.T, phi: s.phi, B: s.B, detB: s.detB, J: s.J, Ja: s.Ja, sigmaMin: s.sigmaMin, margin: s.margin,
              singular: s.singular, normJ: s.normJ, normA: s.normA, level: s.level};
    })""", [el, thetas.tolist()])
    ref = _library(chain, thetas, rep)
    # Well-conditioned numbers (T, J, det B, σ_min, margin, |J|) at TOL; the first and third angles, B(φ) (built
    # from them) and J_a are ill-conditioned near the lock, by 1/h with h = cos φ₂ (ZYX) or sin φ₂ (ZYZ), the
    # norm of the two entries of R each angle is an atan2 of: bounds derived in fp_bounds (angle_bound,
    # analytic_bound), computed at each configuration.
    R = ref["T"][:, :3, :3]
    h = np.hypot(R[:, 0, 0], R[:, 1, 0]) if rep == "zyx" else np.hypot(R[:, 2, 0], R[:, 2, 1])
    worst: dict[str, float] = {}
    over: list[str] = []
    compared = 0

    def note(key: str, err: float, allowed: float = TOL) -> None:
        worst[key] = max(worst.get(key, 0.0), err)
        if not err <= allowed:
            over.append(f"{key} at θ={thetas[k].tolist()}: {err:.1e} > {allowed:.1e}")

    for k, g in enumerate(got):
        lib_singular = bool(np.isnan(ref["Ja"][k]).any())
        assert g["singular"] is lib_singular, (thetas[k], g["margin"])
        for key in ("T", "B", "J", "detB", "sigmaMin", "margin", "normJ"):
            r = np.asarray(ref[key][k])
            err = float(np.max(np.abs(np.asarray(g[key]) - r)) / max(1.0, float(np.max(np.abs(r)))))
            note(key, err, fp_bounds.angle_bound(float(h[k])) if key == "B" else TOL)
        d = (np.asarray(g["phi"]) - ref["phi"][k] + np.pi) % (2 * np.pi) - np.pi
        if h[k] < 1e-13 or h[k] > 1e-11:   # around the lock threshold (1e-12) the sides may take different branches
            note("phi", float(np.abs(d).max()), TOL if h[k] < 1e-13 else fp_bounds.angle_bound(float(h[k])))
        if lib_singular:
            assert g["Ja"] is None and g["normA"] is None and g["level"] == "singular"
        else:
            compared += 1
            r = ref["Ja"][k]
            allowed = fp_bounds.analytic_bound(float(h[k]), float(np.abs(ref["J"][k]).max()))
            note("Ja", float(np.abs(np.asarray(g["Ja"]) - r).max() / max(1.0, np.abs(r).max())), allowed)
            note("normA", abs(g["normA"] - np.linalg.norm(r)) / max(1.0, np.linalg.norm(r)), allowed)
    assert compared > 0.95 * N_CONFIGS
    print(f"\ngimbal view, {wrist}, {rep}: largest difference from the library: "
          + ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))
    assert not over, over[:10]
    _check_state(el, model)
    assert seen["console"] == []


def test_keyboard_slider_moves_the_wrist_and_numbers(harness):
    page, open_view, seen, _ = harness
    model = spatial.gimbal_model()
    el = open_view("gimbal_lock", model)
    before = _check_state(el, model)
    assert before["banner"] is None and before["level"] == "ok"
    labels = [lab.inner_text() for lab in el.query_selector_all("label")]
    assert labels[0].startswith("Wrist:") and labels[1].startswith("Coordinates φ:")
    assert labels[3].startswith("θ₂ = 60.0°")
    el.query_selector_all("input.jl-theta")[1].focus()
    for _ in range(4):
        page.keyboard.press("ArrowRight")
    after = _check_state(el, model)
    assert after["theta"][1] == pytest.approx(math.radians(62.0), abs=1e-12)
    assert "θ₂ = 62.0°" in el.query_selector_all("label")[3].inner_text()
    assert after["B"] != before["B"] and after["Ja"] != before["Ja"]
    el.query_selector("select.jl-rep").select_option("zyz")
    got = _check_state(el, model)
    assert got["rep"] == "zyz" and "ZYZ" in got["caption"]
    el.query_selector("select.jl-wrist").select_option("zyx_wrist")
    assert _check_state(el, model)["wrist"] == "zyx_wrist"
    assert seen["console"] == []


def test_lock_near_lock_and_the_wrists_own_singularity(harness):
    page, open_view, seen, _ = harness
    model = spatial.gimbal_model(theta=[math.radians(30.0), math.radians(60.0), 0.0], rep="zyx")
    el = open_view("gimbal_lock", model)
    page.evaluate(SET_JS, [el, 1, 90])  # the ZYX lock of the ZYZ wrist; the wrist is at its best
    got = _check_state(el, model)
    assert got["level"] == "singular" and "Jₐ does not exist" in got["banner"]
    assert "wrist itself" not in got["banner"] and "rows = 1.000" in got["status"]
    assert "‖J" in got["status"] and "undefined" in got["status"]
    page.evaluate(SET_JS, [el, 1, 89])  # near it: J_a large, a warning
    got = _check_state(el, model)
    Ja = _library(WRISTS["zyz_wrist"](), got["theta"], "zyx")["Ja"]
    assert got["level"] == "warning" and got["banner"].startswith("Near gimbal lock") and np.abs(Ja).max() > 50
    page.evaluate(SET_JS, [el, 1, 0])  # the wrist's own singularity; ZYX angles fine
    got = _check_state(el, model)
    assert got["level"] == "wrist" and "The wrist itself is singular" in got["banner"]
    assert "Gimbal lock" not in got["banner"]
    el.query_selector("select.jl-rep").select_option("zyz")  # ZYZ coordinates lock there too
    got = _check_state(el, model)
    assert got["level"] == "singular" and "Gimbal lock" in got["banner"] and "wrist itself is singular" in got["banner"]
    for v in (-180, 180):  # the joint limits
        page.evaluate(SET_JS, [el, 0, v])
        page.evaluate(SET_JS, [el, 2, v])
        _check_state(el, model)
    assert seen["console"] == []


def _chart(el):
    """The three curves read back: θ2 (rad) and the value (log scale undone) of each point, and the cursor's θ2."""
    got = el.evaluate("""(el) => ({curves: ["a", "j", "d"].map((k) => el.querySelector(`polyline.jl-curve-${k}`)
      .getAttribute("points").split(" ").map((p) => p.split(",").map(Number))),
      cursor: +el.querySelector("line.jl-cursor").getAttribute("x1")})""")
    w, h, left, right, top, bottom, lo, hi = 400, 190, 52, 24, 12, 46, -2, 3  # gimbal_lock.js CHART
    out = []
    for c in got["curves"]:
        a = np.array(c, dtype=float)
        th2 = np.radians((a[:, 0] - left) / (w - left - right) * 360.0 - 180.0)
        value = 10 ** (lo + (h - bottom - a[:, 1]) / (h - top - bottom) * (hi - lo))
        out.append((th2, value))
    return out, np.radians((got["cursor"] - left) / (w - left - right) * 360.0 - 180.0)


@pytest.mark.parametrize("wrist,rep,theta", [("zyz_wrist", "zyx", [0.5, 1.0, 0.0]), ("zyz_wrist", "zyx", [-2.0, 0.3, 0.7]),
                                             ("zyx_wrist", "zyz", [1.0, -0.4, -1.2]), ("zyz_wrist", "zyz", [2.5, 2.0, 0.3])])
def test_chart_is_the_library_along_theta2(harness, wrist, rep, theta):
    """The curves drawn: ‖J_a‖, ‖J‖ and |det B| along θ2 (θ1, θ3 fixed), read back from the SVG, are the library's."""
    page, open_view, seen, _ = harness
    model = spatial.gimbal_model(wrist, rep=rep)
    el = open_view("gimbal_lock", model)
    for th1 in (theta[0], theta[0] + 2.0):  # θ1 alone moved: the chart is kept, and still the library's
        th = [th1, *theta[1:]]
        page.evaluate("([th]) => window.liveModel.set('theta', th)", [th])
        (tA, vA), (tJ, vJ), (tD, vD) = _chart(el)[0]
        cursor = _chart(el)[1]
        assert len(tA) == 121 and np.allclose(tA, np.linspace(-np.pi, np.pi, 121), atol=1e-3)  # 0.05 SVG unit
        assert cursor == pytest.approx(th[1], abs=1e-3)
        grid = np.column_stack([np.full(121, th1), np.linspace(-np.pi, np.pi, 121), np.full(121, theta[2])])
        ref = _library(WRISTS[wrist](), grid, rep)
        with np.errstate(invalid="ignore"):
            norm_a = np.linalg.norm(ref["Ja"], axis=(-2, -1))
        for drawn, lib in ((vA, norm_a), (vJ, ref["normJ"]), (vD, ref["margin"])):
            shown = np.isfinite(lib) & (lib > 10 ** -2.4) & (lib < 10 ** 3.4)  # inside the chart, not clipped
            assert shown.sum() > 60
            assert np.abs(np.log10(drawn[shown]) - np.log10(lib[shown])).max() < 0.004  # 0.1 SVG unit = 0.004 decade
        assert np.all(vA[~np.isfinite(norm_a)] > 10 ** 3.4)  # at the lock: off the top, not NaN
    assert seen["console"] == []


def test_turning_the_view_by_keys_and_drag(harness):
    page, open_view, seen, _ = harness
    model = spatial.gimbal_model()
    el = open_view("gimbal_lock", model)
    pts = _axis_points(WRISTS["zyz_wrist"](), np.array(model["theta"]))
    sv.check_turning(page, el, [0, 0, 0], 1.55 * spatial.WRIST_TOOL, pts, "line.jl-axis")
    _check_state(el, model)
    assert seen["console"] == []


def test_fits_a_phone_with_readable_text(harness):
    page, open_view, seen, _ = harness
    el = open_view("gimbal_lock", spatial.gimbal_model(), width=390)
    fit = el.evaluate(sv.FIT_JS)
    assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["page"] <= 0, fit
    assert fit["small"] == [] and fit["svgSmall"] == [], fit
    assert fit["touch"] == ["svg"], fit
    assert 300 < fit["width"] <= 390


def test_no_console_error_and_no_foreign_request(harness):
    page, open_view, seen, base = harness
    open_view("gimbal_lock", spatial.gimbal_model())
    assert seen["console"] == [] and seen["failed"] == []
    assert seen["requests"] and sv.foreign(seen["requests"], base) == []


def test_on_the_built_chapter_page(browser_context, book_html):
    """Chapter 6 as built (``make book`` runs before the browser tests)."""
    import bookcheck

    path = "chapters/06_analytic_jacobian.html"
    text = (book_html / path).read_text(encoding="utf-8")
    assert 'data-view="gimbal_lock"' in text, f"{path} has no gimbal-lock view: rebuild the book"
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
            el = page.wait_for_selector(".jac-live[data-view='gimbal_lock'][data-ready='1']", state="attached",
                                        timeout=15_000)
            model = json.loads(el.get_attribute("data-model"))
            assert model == spatial.gimbal_model(model["wrist"], model["theta"], model["rep"])
            _check_state(el, model)
            el.query_selector_all("input.jl-theta")[1].focus()
            page.keyboard.press("ArrowRight")
            got = _check_state(el, model)
            assert got["theta"][1] == pytest.approx(model["theta"][1] + math.radians(STEP_DEG), abs=1e-9)
            page.evaluate(SET_JS, [el, 1, 90])
            assert _check_state(el, model)["level"] == "singular"
            pts = _axis_points(WRISTS[got["wrist"]](), np.array(live_data(el)["theta"]))
            sv.check_turning(page, el, [0, 0, 0], 1.55 * spatial.WRIST_TOOL, pts, "line.jl-axis")
            page.set_viewport_size(bookcheck.PHONE)
            fit = el.evaluate(sv.FIT_JS)
            assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["small"] == [] and fit["svgSmall"] == [], fit
            assert errors == [] and failed == []
            assert sv.foreign(requests, server.base) == []
        finally:
            page.close()
