"""_ext/live_views.py: the model the {live-view} directive writes, and its errors on bad options."""

from __future__ import annotations

import html
import json
import re

import live_views
import numpy as np
import pytest

import jacobians as jac


@pytest.mark.parametrize("robot,n", [("planar_2r", 2), ("planar_3r", 3)])
def test_planar_model_is_the_library_chain(robot, n):
    chain = getattr(jac.robots, robot)()
    m = live_views.planar_model(robot, [0.3, -1.2, 2.0][:n], "body")
    assert np.array_equal(m["S"], chain.screw_axes) and np.array_equal(m["M"], chain.home)
    assert np.array_equal(m["Q"], chain.axis_points())
    assert m["theta"] == [0.3, -1.2, 2.0][:n] and m["frame"] == "body"
    assert m["reach"] == pytest.approx(float(n)) and m["sing_tol"] == pytest.approx(0.08 * n)
    assert m["vel_scale"] == 0.35
    json.dumps(m, allow_nan=False)  # plain JSON, no NaN


def test_default_theta_is_the_matplotlib_explorers():
    assert live_views.planar_model("planar_3r")["theta"] == [0.5, 1.2, -0.8]
    assert live_views.planar_model("planar_2r")["theta"] == [0.5, 1.2]


@pytest.mark.parametrize("args,message", [
    (("ur5", None, "space"), "Expected robot one of planar_2r, planar_3r or a planar SerialChain, got 'ur5'"),
    (("planar_2r", None, "jacobian"), "Expected frame one of space, body, geometric, analytic, got 'jacobian'"),
    (("planar_2r", [0.1], "space"), "Expected theta with 2 angles (rad) for planar_2r, got 1"),
    (("planar_2r", [0.1, float("nan")], "space"), "Expected theta as finite angles within ±3.14 rad"),
    (("planar_2r", [0.1, 4.0], "space"), "Expected theta as finite angles within ±3.14 rad, got [4.0]"),
])
def test_bad_options_say_what_was_expected(args, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        live_views.planar_model(*args)


def test_angles_option():
    assert live_views._angles("0.3 1.2") == [0.3, 1.2] and live_views._angles("0.3, -1") == [0.3, -1.0]
    with pytest.raises(ValueError, match="Expected :theta: as angles in rad"):
        live_views._angles("0.3 ninety")


@pytest.mark.parametrize("depth,prefix", [(0, "./_static/live"), (1, "../_static/live"), (2, "../../_static/live")])
def test_host_html_paths_follow_the_page_depth(depth, prefix):
    model = live_views.planar_model("planar_2r", [0.0, 1.2])
    out = live_views.host_html("planar_explorer", model, depth, "jac-live-x-0")
    assert f'from "{prefix}/host.js"' in out and f'from "{prefix}/planar_explorer/view.js"' in out
    assert 'id="jac-live-x-0"' in out and 'getElementById("jac-live-x-0")' in out
    data = re.search(r'data-model="([^"]*)"', out)
    assert data is not None and json.loads(html.unescape(data.group(1))) == model
    assert "http" not in out  # nothing from another host
    with pytest.raises(ValueError, match=r"Expected a live view one of columns_explorer, .*planar_explorer, .*got 'gimbal'"):
        live_views.host_html("gimbal", model, 0, "x")


def test_planar_model_force_and_sweep():
    m = live_views.planar_model("planar_3r", [0.1, 0.2, 0.3], "analytic", sweep=1)
    assert m["force_scale"] == pytest.approx(0.9) and m["force_clip"] == pytest.approx(3.75) and m["sweep"] == 1
    with pytest.raises(ValueError, match=re.escape("Expected sweep as a joint index 0..2 (the joint Play turns), got 3")):
        live_views.planar_model("planar_3r", None, "space", sweep=3)


def test_resolved_rate_model_and_directive_options():
    m = live_views.model_for("resolved_rate", {"robot": "planar_3r", "path": "circle", "method": "dls",
                                               "damping": "0.05"})
    chain = jac.robots.planar_3r()
    assert np.array_equal(m["S"], chain.screw_axes) and m["reach"] == pytest.approx(3.0)
    assert (m["path"], m["method"], m["damping"], m["step"], m["drawn"]) == ("circle", "dls", 0.05, 0, None)
    assert (m["n_steps"], m["duration"], m["gain"]) == (160, 4.0, 2.0)  # the run of widgets.live.planar_path
    for options, message in [({"path": "spiral"}, "Expected path one of circle, to full reach, close past the base"),
                             ({"method": "newton"}, "Expected method 'pinv' or 'dls', got 'newton'"),
                             ({"damping": "0"}, "Expected damping λ in [0.001, 1] m, got 0.0"),
                             ({"damping": "lots"}, "Expected a number, got 'lots'"),
                             ({"frame": "body"}, "do not all apply to resolved_rate")]:
        with pytest.raises(ValueError, match=re.escape(message)):
            live_views.model_for("resolved_rate", options)
    with pytest.raises(ValueError, match=re.escape("Expected a whole number, got '1.5'")):
        live_views.model_for("planar_explorer", {"sweep": "1.5"})


def test_module_source_inlines_relative_imports_recursively():
    import base64

    from jacobians.widgets.live import module_source

    src = module_source("planar_explorer")
    assert not re.search(r"""from\s*["']\.\.?/""", src)  # a blob: URL module cannot resolve ../kinematics.js
    urls = re.findall(r'from "data:text/javascript;base64,([A-Za-z0-9+/=]+)"', src)
    inner = [base64.b64decode(u).decode("utf-8") for u in urls]
    kin = next(t for t in inner if "export function makeChain" in t)
    assert not re.search(r"""from\s*["']\./""", kin) and 'from "data:text/javascript;base64,' in kin  # linalg.js
    assert "export default { render }" in src
    with pytest.raises(ValueError, match="Expected a view module in"):
        module_source("gimbal_lock_nope")
    with pytest.raises(ValueError, match="Expected a view name"):
        module_source("../kinematics")


def test_live_view_widget_state_and_library_values():
    from jacobians.widgets.live import LiveView, PlanarExplorer, ResolvedRate

    w = PlanarExplorer("planar_3r", theta=[0.1, 0.2, 0.3], frame="analytic")
    assert w.J.shape == (3, 3) and np.allclose(w.J[2], 1)
    w.theta = [0.4, -0.2, 1.0]
    w.frame = "body"
    assert np.allclose(w.J, jac.body_jacobian(jac.robots.planar_3r(), [0.4, -0.2, 1.0]))
    r = ResolvedRate("planar_2r", path="circle", method="dls", damping=0.05)
    r.step = 10
    assert np.allclose(r.theta, r.run.thetas[10])
    g = LiveView("planar_explorer", live_views.planar_model("planar_2r"))
    assert g.frame == "space" and g.view == "planar_explorer"
    with pytest.raises(TypeError, match="either a model or options"):
        LiveView("planar_explorer", live_views.planar_model("planar_2r"), robot="planar_2r")
    with pytest.raises(ValueError, match="no builder in MODELS"):
        LiveView("columns_explorer_nope")


def test_every_live_view_is_a_numbered_figure_the_text_refers_to():
    """Each {live-view} of the chapters has a :caption: and a :name:, and its chapter cites the name."""
    from pathlib import Path

    chapters = sorted((Path(__file__).resolve().parents[1] / "chapters").glob("*.md"))
    seen = 0
    for path in chapters:
        text = path.read_text(encoding="utf-8")
        for block in re.findall(r"```\{live-view\}[^\n]*\n((?::[a-z_]+:[^\n]*\n)*)", text):
            seen += 1
            opts = dict(re.findall(r":([a-z_]+): *([^\n]*)", block))
            assert opts.get("caption", "").strip(), f"{path.name}: a live view without :caption:"
            name = opts.get("name", "").strip()
            assert name, f"{path.name}: a live view without :name:"
            assert f"{{numref}}`{name}`" in text, f"{path.name}: the text never refers to {name}"
    assert seen >= 8
